/* stage_lube.c - the lubrication stage (stage_lube.h). */
#include "pipeline/stage_lube.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "lube/film.h"
#include "lube/friction.h"
#include "lube/volume.h"
#include "reference/hertz.h"

static const double RAD_S_PER_RPM = 6.283185307179586476925286766559 / 60.0;

int mc_stage_lube_macro(const mc_scene *sc, const mc_grid *g, mc_stage_lube_summary *lube, mc_error *err)
{
    const double estar = mc_scene_estar(sc);
    const double a_nom = mc_grid_cell_area(g) * (double)mc_grid_cells(g);
    memset(lube, 0, sizeof *lube);
    lube->enabled = 1;
    lube->macro_load = sc->load.value;
    lube->film = sc->lubrication.film == MC_FILM_EHL ? "ehl" : "given";
    lube->formula = "";
    lube->psi_kind = mc_psi_name(sc->lubrication.psi);
    lube->whole = mc_lube_is_whole(sc);
    lube->crowned = sc->geometry.shape == MC_SHAPE_ELLIPSOID;
    double rx = sc->lubrication.macro_radius;
    if (lube->whole) /* the scene checked that it equals macro_radius or R1 R2 / (R1 + R2) */
        rx = lube->crowned ? sc->geometry.radius_x : sc->geometry.radius;
    if (!(rx > 0) && sc->lubrication.radius1 > 0 && sc->lubrication.radius2 > 0) {
        int rc = mc_film_reduced_radius(sc->lubrication.radius1, sc->lubrication.radius2, &rx, err);
        if (rc != MC_OK)
            return rc;
    }
    if (lube->crowned) { /* the elliptical Hertz contact of F_N */
        mc_hertz_ellipse he;
        int rc = mc_hertz_ellipse_from_load(rx, sc->geometry.radius_y, estar, sc->load.value, &he,
                                            err);
        if (rc != MC_OK)
            return rc;
        lube->macro_radius = rx;
        lube->hertz_half_width = he.ax;
        lube->hertz_half_length = he.ay;
        lube->hertz_pressure = he.p0;
    } else if (rx > 0 && sc->lubrication.width > 0) {
        lube->macro_radius = rx;
        lube->load_per_length = sc->load.value / sc->lubrication.width;
        int rc = mc_film_hertz_line(lube->load_per_length, rx, estar, &lube->hertz_half_width,
                                    &lube->hertz_pressure, err);
        if (rc != MC_OK)
            return rc;
    }
    if (lube->whole) {
        /* the whole contact: the strip carries w' per length along y; the nominal area is the
         * Hertz band, which must lie inside the grid with a margin for the rough edge */
        const double half = 0.5 * g->nx * g->dx, b = lube->hertz_half_width;
        const double halfy = 0.5 * g->ny * g->dy, a = lube->hertz_half_length;
        if (lube->crowned && !(MC_WHOLE_BAND_MARGIN * a <= halfy))
            return mc_fail(err, MC_ERR_INPUT,
                           "[mesh] the grid spans |y| <= %.6g um, too short for the whole crowned "
                           "contact at F_N = %.6g N: its Hertz ellipse reaches a = %.6g um",
                           halfy * 1e6, sc->load.value, a * 1e6);
        if (!(MC_WHOLE_BAND_MARGIN * b <= half))
            return mc_fail(err, MC_ERR_INPUT,
                           "[mesh] the grid spans |x| <= %.6g um, too narrow for the whole "
                           "contact at F_N = %.6g N: the Hertz band |x| <= b = %.6g um plus %.0f %% "
                           "needs nx >= %.0f at dx = %.6g um",
                           half * 1e6, sc->load.value, b * 1e6,
                           (MC_WHOLE_BAND_MARGIN - 1.0) * 100.0,
                           ceil(2.0 * MC_WHOLE_BAND_MARGIN * b / g->dx), g->dx * 1e6);
        size_t nband = 0;
        for (int j = 0; j < g->ny; j++)
            for (int i = 0; i < g->nx; i++)
                nband += mc_stage_lube_nominal_shape(lube, mc_grid_x(g, i), mc_grid_y(g, j), 0) > 0;
        lube->nominal_area = (double)nband * mc_grid_cell_area(g);
        /* the strip carries w' per length; the crowned contact the whole F_N */
        lube->patch_load = lube->crowned ? sc->load.value : lube->load_per_length * g->ny * g->dy;
        lube->nominal_pressure = lube->patch_load / lube->nominal_area;
        lube->profile = sc->lubrication.profile == MC_PROFILE_HERTZ ? "hertz" : "uniform";
    } else {
        /* with a macro radius the patch is the centre of the macro contact, loaded with p_H */
        lube->patch_load = lube->hertz_pressure > 0 ? lube->hertz_pressure * a_nom
                                                    : sc->load.value;
        lube->nominal_area = a_nom;
        lube->nominal_pressure = lube->patch_load / a_nom;
    }
    if (sc->lubrication.film == MC_FILM_GIVEN) {
        lube->h_ehd = sc->lubrication.film_thickness;
        return MC_OK;
    }
    mc_film_kinematics k;
    int rc;
    if (sc->lubrication.rpm > 0) {
        double n1 = sc->lubrication.rpm / RAD_S_PER_RPM;
        double n2 = sc->lubrication.rpm2 > 0 ? sc->lubrication.rpm2 / RAD_S_PER_RPM
                                             : n1 * sc->lubrication.radius1 /
                                                   sc->lubrication.radius2; /* equal speeds */
        rc = mc_film_kinematics_rpm(n1, sc->lubrication.radius1, n2, sc->lubrication.radius2, &k,
                                    err);
    } else
        rc = mc_film_kinematics_speeds(sc->lubrication.speed, sc->lubrication.speed, &k, err);
    if (rc != MC_OK)
        return rc;
    lube->entrainment = k.u;
    lube->srr = k.srr;
    mc_film_formula f = sc->lubrication.formula;
    lube->formula = mc_film_formula_name(f);
    mc_film_input in = {.eta0 = sc->lubrication.viscosity,
                        .alpha = sc->lubrication.pressure_viscosity,
                        .u = k.u,
                        .eprime = 2.0 * estar,
                        .rx = rx,
                        /* line formulas take w', point formulas F_N with a circular contact */
                        .load = mc_film_formula_is_point(f) ? sc->load.value
                                                            : lube->load_per_length,
                        /* the crowned contact's ellipticity, else the circle's */
                        .k = mc_film_ellipticity(lube->crowned ? sc->geometry.radius_y /
                                                                     sc->geometry.radius_x
                                                               : 1.0)};
    rc = mc_film_thickness(f, &in, &lube->h_ehd, err);
    if (rc != MC_OK)
        mc_error_prefix(err, "[lubrication] film = ehl: ");
    return rc;
}

double mc_stage_lube_nominal_shape(const mc_stage_lube_summary *lube, double x, double y, int hertz)
{
    const double tx = x / lube->hertz_half_width;
    const double ty = lube->crowned ? y / lube->hertz_half_length : 0.0;
    const double r2 = tx * tx + ty * ty;
    if (!(r2 <= 1.0))
        return 0.0;
    return hertz ? sqrt(1.0 - r2) : 1.0;
}

int mc_stage_lube_profile(const mc_scene *sc, mc_results *res, mc_error *err)
{
    if (!res->lube.whole)
        return MC_OK;
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    if (!res->lube_profile && !(res->lube_profile = mc_malloc(n * sizeof *res->lube_profile)))
        return mc_fail(err, MC_ERR_NOMEM, "lubrication: out of memory for the profile");
    const int hertz = sc->lubrication.profile == MC_PROFILE_HERTZ;
    double sum = 0;
    long nband = 0;
    double *w = res->lube_profile;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            double *wi = &w[(size_t)j * g->nx + i];
            *wi = mc_stage_lube_nominal_shape(&res->lube, mc_grid_x(g, i), mc_grid_y(g, j), hertz);
            sum += *wi;
            nband += *wi > 0;
        }
    if (!(sum > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "lubrication: the Hertz contact (b = %.6g um) holds no cell centre of the "
                       "grid (dx = %.6g um)",
                       res->lube.hertz_half_width * 1e6, g->dx * 1e6);
    for (size_t i = 0; i < n; i++) /* mean 1 over the nominal area: p_lub is its mean */
        w[i] *= (double)nband / sum;
    return MC_OK;
}

int mc_stage_lube(const mc_scene *sc, mc_operator *K, mc_contact_solver *s, const double *h_extra,
                  const double *p_start, mc_results *res, mc_error *err)
{
    mc_volume_result vr;
    return mc_stage_lube_seed(sc, K, s, h_extra, p_start, res, &vr, err);
}

int mc_stage_lube_seed(const mc_scene *sc, mc_operator *K, mc_contact_solver *s,
                       const double *h_extra, const double *p_start, mc_results *res,
                       mc_volume_result *out, mc_error *err)
{
    mc_stage_lube_summary *lube = &res->lube;
    int rc = mc_stage_lube_macro(sc, &res->grid, lube, err);
    if (rc == MC_OK)
        rc = mc_stage_lube_profile(sc, res, err);
    if (rc != MC_OK)
        return rc;
    mc_volume_problem prob = {.weight = res->lube_profile,
                              .h = res->topography,
                              .h_extra = h_extra,
                              .load = lube->patch_load,
                              .h_target = lube->h_ehd,
                              .tolerance = sc->lubrication.tolerance,
                              .p_start = p_start};
    mc_volume_result vr;
    rc = mc_volume_equilibrium(s, K, &prob, res->pressure, res->displacement, res->gap, &vr, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    *out = vr;
    mc_error oerr = {0};
    int orc = mc_stage_lube_outcome(sc, &vr, res, &oerr);
    if (orc != MC_OK) {
        *err = oerr;
        return orc;
    }
    return rc;
}

int mc_stage_lube_outcome(const mc_scene *sc, const mc_volume_result *vr, mc_results *res,
                    mc_error *err)
{
    mc_stage_lube_summary *lube = &res->lube;
    res->contact = vr->contact;
    lube->p_lub = vr->p_lub;
    lube->regime = mc_lube_regime_name(vr->regime);
    lube->volume = vr->volume;
    lube->v_target = vr->v_target;
    lube->rel_error = vr->rel_error;
    lube->solves = vr->solves;
    lube->converged = vr->converged;
    const size_t n = mc_grid_cells(&res->grid);
    mc_lube_split split;
    mc_error serr = {0};
    int src = mc_lube_split_weighted(res->pressure, res->gap,
                                     lube->whole ? res->lube_profile : NULL, n,
                                     mc_grid_cell_area(&res->grid), vr->p_lub, lube->patch_load,
                                     &split, &serr);
    /* psi_load = F_solid / F_N reaches 1 + round-off in the dry regime (the load is met to the
     * contact tolerance): clamp what is within that, refuse anything beyond */
    double psi = mc_lube_split_psi(&split, sc->lubrication.psi);
    if (psi > 1.0 && psi <= 1.0 + 1e3 * sc->solver.tolerance)
        psi = 1.0;
    if (src == MC_OK)
        src = mc_friction_mu(psi,
                             sc->lubrication.mu_solid, sc->lubrication.mu_fluid, &lube->mu, &serr);
    if (src != MC_OK) {
        if (err)
            *err = serr;
        return src;
    }
    lube->psi_load = fmin(split.psi_load, 1.0);
    lube->psi_area = split.psi_area;
    lube->pocket_height = split.pocket_height;
    return MC_OK;
}

int mc_stage_lube_contact_step(void *ctx, const mc_contact_problem *cp, int inexact, double *p,
                               double *u, double *gap, mc_contact_summary *sum, double *p_lub,
                               int *settled, mc_error *err)
{
    mc_stage_lube_contact *lc = ctx;
    mc_volume_problem prob = {.h = cp->h,
                              .h_extra = cp->h_extra,
                              .load = cp->load,
                              .h_target = lc->h_target,
                              .tolerance = lc->tolerance,
                              .weight = lc->weight,
                              .p_start = cp->p_start};
    const int first = lc->calls == 0;
    if (lc->seeded && first) {
        lc->load = cp->load;
        if (lc->last.slope > 0)
            lc->slope = lc->last.slope;
        if (!prob.p_start)
            prob.p_start = p; /* the seed's pressure (stage_lube.h) */
    }
    const int have = (!first || lc->seeded) && lc->last.regime == MC_REGIME_MIXED;
    if (have && lc->slope > 0) { /* the last root as the guess, or one secant step from it */
        prob.p_lub_guess = lc->last.p_lub;
        prob.slope_guess = lc->slope;
        const double next = lc->last.p_lub - (lc->last.volume - lc->last.v_target) / lc->slope;
        if (inexact && !first && cp->load == lc->load && next > 0 && next < lc->last.p_nominal &&
            isfinite(next)) {
            prob.p_lub_guess = next;
            prob.one_solve = 1;
        }
    }
    int rc = mc_volume_equilibrium(lc->solver, lc->K, &prob, p, u, gap, &lc->last, err);
    if (lc->last.slope > 0)
        lc->slope = lc->last.slope;
    lc->load = cp->load;
    lc->calls++;
    lc->solves += lc->last.solves;
    *sum = lc->last.contact;
    *p_lub = lc->last.p_lub;
    *settled = lc->last.converged;
    return rc;
}
