/* volume.h - the lubricant volume equilibrium: the lubricant pressure p_lub at which the pocket
 * volume of the loaded rough gap equals the volume the hydrodynamics conveys into the contact
 * (Mevissen et al. 2025; theory.md §11.1).
 *
 * On the grid (n cells of area dA, nominal area A_nom = n dA) under the nominal load F_N (force
 * control; p_nominal = F_N / A_nom), each p_lub defines a contact problem (contact.h) with the
 * lower bound p >= p_lub, whose gap g gives the pocket volume
 *     V(p_lub) = dA sum_i g_i,
 * and the equilibrium is the scalar equation
 *     V(p_lub) = V*,   V* = h_EHD A_nom   (h_EHD from film.h, or given).
 * V is continuous and strictly increasing on [0, p_nominal] (more fluid pressure unloads the
 * solids and the gap opens); at p_lub = p_nominal the fluid carries the whole load and the solid
 * contact vanishes ("onset": q = p - p_lub = 0, the gap touching at its lowest point). Regimes:
 *   dry       V* <= V(0):               p_lub = 0 (the solids carry everything, psi_load = 1);
 *   mixed     V(0) < V* < V(p_nominal): the root, by Brent's method (Brent 1973, "zeroin":
 *             inverse quadratic / secant steps inside the bracket, bisection as the safeguard);
 *   full_film V* >= V(p_nominal):      p_lub = p_nominal, no solid contact (psi = 0); the surfaces
 *             separate beyond onset by the uniform lift (V* - V(p_nominal)) / A_nom, so V = V*.
 * Each evaluation inside (0, p_nominal) is one contact solve, warm-started from the pressure of
 * the previous one; the onset state is computed directly (one operator application, no solve):
 * p = p_nominal, gap = h~ - min h~, h~ = h + h_extra + K p_nominal (exactly what the contact
 * solver returns when the lubricant carries the load), so p_lub = p_nominal is the full-film
 * state without round-off doubt on the solid load F_N - p_lub A_nom.
 *
 * Periodic grids. Periodic in x and y the Love table is mean-free (operator.h: K 1 = 0), so the
 * uniform lubricant pressure does not deform the surface and sum_i (K q)_i = 0: V = A_nom
 * (mean h~ - delta) depends on the approach delta alone. It is still well defined and strictly
 * increasing in p_lub (the approach falls as the solids unload), so nothing changes for the root;
 * only the absolute displacement level is arbitrary there, and V does not depend on it. With a
 * free axis K 1 is not uniform (the patch edges deflect less) and the lubricant's own
 * deformation enters V.
 *
 * Accuracy. |V - V*| <= tolerance V* is tested on V from the solver's gap, whose error is about
 * the contact tolerance times the gap scale per cell (contact.h): choose the contact tolerance at
 * least 100 times smaller than this one (1e-8 or less for the default 1e-6).
 */
#ifndef MC_LUBE_VOLUME_H
#define MC_LUBE_VOLUME_H

#include "contact/contact.h"
#include "core/error.h"
#include "operator/operator.h"

#define MC_VOLUME_TOL_DEFAULT 1e-6 /* relative on V */
#define MC_VOLUME_MAX_SOLVES 60    /* contact solves per equilibrium, the first at p_lub = 0 included */

typedef enum { MC_REGIME_DRY = 0, MC_REGIME_MIXED = 1, MC_REGIME_FULL_FILM = 2 } mc_lube_regime;

const char *mc_lube_regime_name(mc_lube_regime r); /* "dry" | "mixed" | "full_film" */

typedef struct {
    const double *h;       /* initial gap at zero approach (ny*nx), m; required */
    const double *h_extra; /* added to h (e.g. residual plastic displacement), m; NULL = none */
    double load;           /* nominal load F_N, N, > 0 (force control) */
    double h_target;       /* h_EHD, m, >= 0: V* = h_target A_nom */
    double tolerance;      /* relative on V; <= 0: MC_VOLUME_TOL_DEFAULT; else in (0, 0.1] */
    int max_solves;        /* contact solves allowed; <= 0: MC_VOLUME_MAX_SOLVES */
    const double *p_start; /* warm start of the first solve (e.g. the previous step), or NULL */
    /* a guess of the root (e.g. the last equilibrium of a slowly changing problem: the contact
     * solves of the elastic-plastic loop) with the slope dV/dp_lub there (the last result's
     * slope): when 0 < p_lub_guess < p_nominal and slope_guess > 0, V is evaluated at the guess
     * first and the root bracketed outward from it by secant steps (V(0) only when a step reaches
     * 0); otherwise (or when that finds no bracket) the cold start from V(0). Same regimes and
     * tolerance either way. Pa and m^3/Pa; 0 = none. */
    double p_lub_guess, slope_guess;
    /* 1: the guess alone - one contact solve at p_lub_guess (which must lie in (0, p_nominal)),
     * its state returned whether or not |V - V*| <= tolerance V*; res->converged says which,
     * res->rel_error by how much. The elastic-plastic loop's joint iteration makes the root one
     * secant step per evaluation this way and tests the tolerance at its acceptance (theory.md
     * §9.8). 0: the root as above. */
    int one_solve;
    /* The lubricant pressure profile w (ny*nx, >= 0, finite; NULL = 1 everywhere, the patch):
     * the lubricant pressure of cell i is p_lub w_i, the nominal area is the cells with
     * w_i > 0 (A_nom = dA |{w > 0}|) and V sums the gap over them alone. The whole contact of a
     * macro geometry (theory.md §11.4) sets w = 1 on the Hertz band |x| <= b and 0 outside (or
     * a Hertz-shaped profile): the macro gap outside the band is not lubricant of the contact.
     * p_nominal = F_N / (dA sum w) is the p_lub at which the fluid carries the whole load. */
    const double *weight;
} mc_volume_problem;

typedef struct {
    mc_lube_regime regime;
    double p_lub;         /* lubricant pressure, Pa (0 dry, p_nominal full film) */
    double p_nominal;     /* F_N / A_nom (F_N / (dA sum w) with a profile), Pa */
    double a_nom;         /* the nominal area, m^2 (n dA, or the cells with w > 0) */
    double v_target;      /* V* = h_target A_nom, m^3 */
    double volume;        /* V of the returned gap, m^3 (= V* in full film) */
    double rel_error;     /* mixed: |V - V*| / V* of the returned state; dry, full film: 0 */
    double v_dry;         /* V(0), m^3 (0 when not evaluated: full film found first) */
    double v_onset;       /* V(p_nominal), the pocket volume as solid contact vanishes, m^3 */
    double separation;    /* full film: uniform lift beyond onset, m; else 0 */
    int solves;           /* contact solves done */
    long iterations;      /* contact solver iterations, summed over the solves */
    int converged;        /* 1: the returned state meets the tolerance (always in dry/full film) */
    double slope;         /* dV/dp_lub from the last two contact solves, m^3/Pa (0: fewer) */
    mc_contact_summary contact; /* of the returned state; full film: filled here, solver
                                   "full-film", no iterations */
} mc_volume_result;

/* Solve the volume equilibrium with solver s, planned over operator K (both caller-owned, not
 * modified beyond the solver's workspaces; s must be planned over K, force control, any method
 * and backend). Outputs (n = grid cells each, caller-owned): p (Pa) and gap (m) of the returned
 * state, u (= K p, m) optionally (NULL). res receives the regime, p_lub and the figures above.
 * Returns MC_OK; MC_NOT_CONVERGED when the cap on solves is hit or the bracket shrank to
 * round-off before |V - V*| <= tolerance V*, or when a contact solve did not converge (outputs
 * then hold the last solve, res->converged = 0); MC_ERR_INPUT (bad problem); or the contact
 * solver's error codes (contact.h); MC_ERR_NOMEM. */
int mc_volume_equilibrium(mc_contact_solver *s, mc_operator *K, const mc_volume_problem *prob,
                          double *p, double *u, double *gap, mc_volume_result *res,
                          mc_error *err);

#endif
