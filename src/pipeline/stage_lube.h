/* stage_lube.h - the lubrication stage: the scene's [lubrication] turned into the macro contact,
 * the EHL film thickness and the lubricant volume equilibrium of the patch (lube/), and the
 * friction mix. docs/theory.md §10-§12.
 */
#ifndef MC_STAGE_LUBE_H
#define MC_STAGE_LUBE_H

#include "case/scene.h"
#include "contact/contact.h"
#include "core/error.h"
#include "lube/volume.h"
#include "operator/operator.h"
#include "pipeline/results.h"

/* The macro contact and film of the scene (no contact solve): h_EHD, entrainment, w', R_x,
 * p_H, b and the patch's load (p_H A_nom with a macro radius, else the scene's force) into
 * res->lube. MC_OK or MC_ERR_INPUT (a film formula input out of its range). */
int mc_stage_lube_macro(const mc_scene *sc, const mc_grid *g, mc_stage_lube_summary *lube, mc_error *err);

/* Whether the scene is a whole contact (theory.md §11.4): the grid carries the macro geometry,
 * a cylinder on a strip (the line contact) or an ellipsoid on a free grid (the crowned one). */
static inline int mc_lube_is_whole(const mc_scene *sc)
{
    return sc->geometry.shape == MC_SHAPE_CYLINDER || sc->geometry.shape == MC_SHAPE_ELLIPSOID;
}

/* The whole contact's Hertz band must lie within the grid with this factor of margin on b. */
#define MC_WHOLE_BAND_MARGIN 1.1

/* The lubricant pressure profile w of the whole contact (lube/volume.h, theory.md §11.4) into
 * res->lube_profile (allocated on first use), from the macro contact in res->lube
 * (mc_stage_lube_macro): uniform 1 on the Hertz band |x| <= b, or (hertz) sqrt(1 - (x/b)^2) scaled to
 * mean 1 over the band's cells; 0 outside. For a patch (res->lube.whole = 0) nothing is done
 * and res->lube_profile stays NULL. MC_OK or MC_ERR_NOMEM. */
int mc_stage_lube_profile(const mc_scene *sc, mc_results *res, mc_error *err);

/* The nominal area's shape at (x, y): for the line contact |x| <= b, for the crowned one the
 * ellipse (x/b)^2 + (y/a)^2 <= 1 (lube: the macro contact of mc_stage_lube_macro); 1 inside (or with
 * hertz the smooth contact's sqrt(1 - r^2)), 0 outside. */
double mc_stage_lube_nominal_shape(const mc_stage_lube_summary *lube, double x, double y, int hertz);

/* Solve the patch: the lubricant pressure from the volume equilibrium (lube/volume.h) with the
 * contact solver s over K (h_extra, e.g. a residual displacement, may be NULL; p_start a warm
 * start or NULL), the fields into res (pressure, displacement, gap), res->contact and
 * res->lube (ratios, pocket height, mu). MC_OK, MC_NOT_CONVERGED (fields still filled) or an
 * error. */
int mc_stage_lube(const mc_scene *sc, mc_operator *K, mc_contact_solver *s, const double *h_extra,
                  const double *p_start, mc_results *res, mc_error *err);
/* mc_stage_lube that also gives the equilibrium's own figures (root, slope, volumes) in *vr:
 * the seed of a later contact step of the same problem (mc_stage_lube_contact below). */
int mc_stage_lube_seed(const mc_scene *sc, mc_operator *K, mc_contact_solver *s,
                       const double *h_extra, const double *p_start, mc_results *res,
                       mc_volume_result *vr, mc_error *err);

/* The outcome of an equilibrium vr whose state is in res (pressure, gap): res->contact and the
 * lubrication figures of res->lube (p_lub, regime, volumes, solves, the load and area ratios,
 * the pocket height and mu). res->lube must hold the macro contact (mc_stage_lube_macro) already.
 * MC_OK or MC_ERR_INPUT (a ratio out of range: psi above 1 beyond the contact tolerance). */
int mc_stage_lube_outcome(const mc_scene *sc, const mc_volume_result *vr, mc_results *res,
                    mc_error *err);

/* The contact step of the elastic-plastic loop as a lubricant volume equilibrium: set
 * solver, K, h_target (h_EHD, m) and tolerance (relative on V; <= 0: the default), then pass
 * mc_stage_lube_contact_step with a pointer to this as the loop's contact (plastic/loop.h). Each call
 * solves the equilibrium of the loop's problem (h, h_extra, its load, its warm start; from the
 * second call on, the last root and the last slope found as the guess of lube/volume.h) and keeps
 * the figures of the last one in `last`. An inexact call (the joint iteration, theory.md §9.8)
 * under the load of the call before makes one secant step of the root instead, one contact solve
 * at p_lub - (V - V*) / slope from the last state, and says in *settled whether that state meets
 * the tolerance. A seed (seeded 1, `last` the equilibrium of the same problem without plastic
 * strain, whose pressure the caller's p array still holds) is the guess and the warm start of the
 * first call: the running-in step solved it just before its plastic loop. */
typedef struct {
    mc_contact_solver *solver;
    mc_operator *K;
    double h_target, tolerance;
    const double *weight;  /* the whole contact's profile (res->lube_profile), NULL: a patch */
    mc_volume_result last; /* of the last call (or the seed) */
    int seeded;            /* 1: `last` is the seed (see above) */
    double slope;          /* the last positive dV/dp_lub found, m^3/Pa (0: none yet) */
    double load;           /* the load of the last call, N */
    int calls, solves;     /* equilibria solved (or secant steps made), contact solves in all */
} mc_stage_lube_contact;

int mc_stage_lube_contact_step(void *ctx, const mc_contact_problem *cp, int inexact, double *p,
                               double *u, double *gap, mc_contact_summary *sum, double *p_lub,
                               int *settled, mc_error *err);

#endif
