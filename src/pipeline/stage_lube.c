/* stage_lube.c - the lubrication stage (stage_lube.h). */
#include "pipeline/stage_lube.h"

#include <math.h>
#include <string.h>

#include "lube/film.h"
#include "lube/friction.h"
#include "lube/volume.h"

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
    double rx = sc->lubrication.macro_radius;
    if (!(rx > 0) && sc->lubrication.radius1 > 0 && sc->lubrication.radius2 > 0) {
        int rc = mc_film_reduced_radius(sc->lubrication.radius1, sc->lubrication.radius2, &rx, err);
        if (rc != MC_OK)
            return rc;
    }
    if (rx > 0 && sc->lubrication.width > 0) {
        lube->macro_radius = rx;
        lube->load_per_length = sc->load.value / sc->lubrication.width;
        int rc = mc_film_hertz_line(lube->load_per_length, rx, estar, &lube->hertz_half_width,
                                    &lube->hertz_pressure, err);
        if (rc != MC_OK)
            return rc;
    }
    /* with a macro radius the patch is the centre of the macro contact, loaded with p_H */
    lube->patch_load = lube->hertz_pressure > 0 ? lube->hertz_pressure * a_nom : sc->load.value;
    lube->nominal_pressure = lube->patch_load / a_nom;
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
                        .k = mc_film_ellipticity(1.0)};
    rc = mc_film_thickness(f, &in, &lube->h_ehd, err);
    if (rc != MC_OK)
        mc_error_prefix(err, "[lubrication] film = ehl: ");
    return rc;
}

int mc_stage_lube(const mc_scene *sc, mc_operator *K, mc_contact_solver *s, const double *h_extra,
                  const double *p_start, mc_results *res, mc_error *err)
{
    mc_stage_lube_summary *lube = &res->lube;
    int rc = mc_stage_lube_macro(sc, &res->grid, lube, err);
    if (rc != MC_OK)
        return rc;
    mc_volume_problem prob = {.h = res->topography,
                              .h_extra = h_extra,
                              .load = lube->patch_load,
                              .h_target = lube->h_ehd,
                              .tolerance = sc->lubrication.tolerance,
                              .p_start = p_start};
    mc_volume_result vr;
    rc = mc_volume_equilibrium(s, K, &prob, res->pressure, res->displacement, res->gap, &vr, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
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
    int src = mc_lube_split_of(res->pressure, res->gap, n, mc_grid_cell_area(&res->grid),
                               vr->p_lub, lube->patch_load, &split, &serr);
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

int mc_stage_lube_contact_step(void *ctx, const mc_contact_problem *cp, double *p, double *u,
                         double *gap, mc_contact_summary *sum, double *p_lub, mc_error *err)
{
    mc_stage_lube_contact *lc = ctx;
    mc_volume_problem prob = {.h = cp->h,
                              .h_extra = cp->h_extra,
                              .load = cp->load,
                              .h_target = lc->h_target,
                              .tolerance = lc->tolerance,
                              .p_start = cp->p_start};
    if (lc->calls > 0 && lc->last.regime == MC_REGIME_MIXED) { /* the last root as the guess */
        prob.p_lub_guess = lc->last.p_lub;
        prob.slope_guess = lc->last.slope;
    }
    int rc = mc_volume_equilibrium(lc->solver, lc->K, &prob, p, u, gap, &lc->last, err);
    lc->calls++;
    lc->solves += lc->last.solves;
    *sum = lc->last.contact;
    *p_lub = lc->last.p_lub;
    return rc;
}
