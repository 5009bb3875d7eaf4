/* bodies.c - the surfaces of the two bodies (bodies.h; docs/theory.md §4.11). */
#include "pipeline/bodies.h"

#include <string.h>

#include "core/alloc.h"
#include "surface/roughness.h"
#include "surface/surface.h"

static const char *const section_name[2] = {"roughness", "roughness2"};

int mc_bodies_topography(const mc_scene *sc, mc_results *res, double *topo, const char **section,
                         mc_error *err)
{
    const mc_grid *g = &sc->grid;
    if (section)
        *section = section_name[0];
    if (sc->roughness2.type == MC_ROUGH_NONE)
        return mc_surface_topography(g, &sc->geometry, &sc->roughness, topo, err);
    const size_t n = mc_grid_cells(g);
    for (int k = 0; k < 2; k++)
        if (!res->body_initial[k] && !(res->body_initial[k] = mc_zeros(n)))
            return mc_fail(err, MC_ERR_NOMEM, "out of memory for the %d x %d heights of body %d",
                           g->nx, g->ny, k + 1);
    int which = 0;
    int rc = mc_surface_two_bodies(g, &sc->roughness, &sc->roughness2, res->body_initial[0],
                                   res->body_initial[1], &res->body_file[0], &res->body_file[1],
                                   &which, err);
    if (rc != MC_OK) {
        if (section)
            *section = section_name[which == 2];
        return rc;
    }
    res->two_bodies = 1;
    /* the gap's roughness is the sum of the outward heights of the two bodies (§4.11) */
    mc_surface_shape(g, &sc->geometry, topo);
    for (size_t i = 0; i < n; i++)
        topo[i] -= res->body_initial[0][i] + res->body_initial[1][i];
    return MC_OK;
}

void mc_bodies_options(const mc_scene *sc, const mc_roughness_spec *spec, int runin,
                       mc_roughness_options *opt)
{
    mc_roughness_options_default(opt);
    opt->cutoff = spec->cutoff;
    if (runin)
        opt->filter = spec->cutoff > 0;
    opt->periodic_x = sc->grid.periodic_x;
    opt->periodic_y = sc->grid.periodic_y;
}

/* ISO parameters of body k's heights z. */
static int parameters(const mc_scene *sc, int runin, int k, const double *z,
                      mc_roughness_params *out, const char **section, mc_error *err)
{
    const mc_grid *g = &sc->grid;
    mc_roughness_options opt;
    mc_bodies_options(sc, k ? &sc->roughness2 : &sc->roughness, runin, &opt);
    int rc = mc_roughness_compute(z, NULL, g->nx, g->ny, g->dx, g->dy, &opt, out, err);
    if (rc != MC_OK) {
        if (section)
            *section = section_name[k];
        if (err)
            mc_error_prefix(err, "the roughness of body %d: ", k + 1);
    }
    return rc;
}

int mc_bodies_initial_parameters(const mc_scene *sc, int runin, mc_results *res,
                                 const char **section, mc_error *err)
{
    int rc = MC_OK;
    for (int k = 0; rc == MC_OK && res->two_bodies && k < 2; k++)
        rc = parameters(sc, runin, k, res->body_initial[k], &res->body_roughness_initial[k],
                        section, err);
    return rc;
}

int mc_bodies_final(const mc_scene *sc, int runin, const double *u_r, mc_results *res,
                    const char **section, mc_error *err)
{
    if (!res->two_bodies)
        return MC_OK;
    const size_t n = mc_grid_cells(&sc->grid);
    const int plastic = sc->plasticity.enabled && u_r != NULL;
    res->body_dents[0] = plastic;
    res->body_dents[1] = plastic && sc->plasticity.criterion == MC_CRITERION_VON_MISES &&
                         sc->plasticity.both;
    int rc = MC_OK;
    for (int k = 0; rc == MC_OK && k < 2; k++) {
        if (!res->body_final[k] && !(res->body_final[k] = mc_zeros(n)))
            return mc_fail(err, MC_ERR_NOMEM, "out of memory for the final surface of body %d",
                           k + 1);
        const double *z0 = res->body_initial[k];
        double *z = res->body_final[k];
        /* the body's own residual dent lowers its surface (u_r > 0 into the body, §1.2) */
        for (size_t i = 0; i < n; i++)
            z[i] = res->body_dents[k] ? z0[i] - u_r[i] : z0[i];
        rc = parameters(sc, runin, k, z, &res->body_roughness_final[k], section, err);
    }
    res->body_has_final = rc == MC_OK;
    return rc;
}
