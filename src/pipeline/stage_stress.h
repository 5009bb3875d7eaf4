/* stage_stress.h - the stress stage of the pipeline: the scene's [stress] section evaluated under
 * a contact result (depths, windows, the automatic depth, the summary maxima). The numerics are in
 * stress/stress.h; this file decides what to compute for a scene.
 */
#ifndef MC_STAGE_STRESS_H
#define MC_STAGE_STRESS_H

#include "case/scene.h"
#include "core/error.h"
#include "pipeline/results.h"
#include "stress/stress.h"

/* The window of [stress] window = auto (the stage's first skip), on grids with free axes (along a
 * periodic axis the load repeats, and beyond a period acts as a line load whose stress decays like
 * 1/r, not 1/r^2: no window). The load's non-zero cells have the bounding box B; layer z is
 * computed only on B widened on every side by
 *     m(z) = max(MC_STRESS_WINDOW_MIN cells, MC_STRESS_WINDOW_CR R + MC_STRESS_WINDOW_CZ z),
 * R = half the longer side of B (m), rounded up to whole cells per axis and clipped to the grid:
 * the stress plan (stress.h) of that sub-grid, exact inside it because the load lies in it.
 * The other cells of the layer hold 0. Why R and not only z: outside a load the in-plane surface
 * stress decays only like (1 - 2 nu) P / (2 pi r^2), so near the surface the margin must grow with
 * the load, and with depth the stress spreads over ~z. Measured on Hertz contacts (nu = 0.3,
 * a/dx = 6, 8 and 16, friction 0 and 0.3, depths 0 ... 3a, grids 24a to 60a wide, each layer on
 * its own window): the largest von Mises stress left out is <= 1.74 % of that layer's largest
 * (at the surface without friction; <= 1.26 % with friction 0.3, <= 0.6 % at 0.2a ... 1.5a
 * without), the largest stress component left out <= 1.23 % of it; MC_STRESS_WINDOW_FRACTION is
 * the bound the tests hold it to. The margin's constants: the surface fraction falls like
 * ~1.04 / (1 + CR)^2 (the 1/r^2 law), CZ keeps the deep layers below it. Layers are grouped (at most MC_STRESS_MAX_WINDOWS groups, a new group when
 * the window's area would grow by more than half) and each group runs on its deepest layer's
 * window, so a group is planned once. The windows are listed in mc_results.stress_layout and
 * summary.json. The window is skipped (the whole grid computed) when it would cover the grid. */
#define MC_STRESS_WINDOW_CR 7.0
#define MC_STRESS_WINDOW_CZ 2.5
#define MC_STRESS_WINDOW_MIN 4
#define MC_STRESS_WINDOW_FRACTION 0.02

/* depth_max = auto (the default of the stage's depths): MC_STRESS_DEPTH_RADII times the radius R
 * of the largest contact patch, layers from depth_min with [stress] layers and spacing. Patches are
 * the 4-connected groups of cells (connected across periodic edges too) with p > threshold: the
 * solid contact (p above the lubricant pressure) of a solved contact, the loaded cells (p > 0) of
 * a prescribed pressure. R = sqrt(A / pi) of a patch of area A; a patch closed around a periodic
 * axis (a band, as a line contact) has R = A / (2 L), its mean half-width across the period L
 * (closed around both: A / (2 max(Lx, Ly))). A Hertz contact gives R = a to the pixelation: 3a
 * holds the von Mises maximum (0.48a) and its decay to ~17 % of it (theory.md §6.1). With no
 * contact cell the loaded cells count; with no load at all R is one cell. */
#define MC_STRESS_DEPTH_RADII 3.0

typedef struct {
    int patches;   /* connected patches */
    double radius; /* R of the largest (largest R), m; 0 if there is no patch */
    long cells;    /* cells above the threshold */
} mc_stage_stress_patches;

/* Label the patches of p (ny*nx) above threshold on grid g (see MC_STRESS_DEPTH_RADII). Allocates
 * its work arrays (4 ints per cell) for the call. MC_OK, MC_ERR_LIMIT (more than INT_MAX cells) or
 * MC_ERR_NOMEM. */
int mc_stage_stress_find_patches(const mc_grid *g, const double *p, double threshold,
                           mc_stage_stress_patches *out, mc_error *err);

/* Stresses of the scene's [stress] section under the contact result: depths from mc_scene_depths,
 * or from the contact when depth_max is auto (MC_STRESS_DEPTH_RADII; MC_ERR_INPUT if that depth
 * does not exceed depth_min); loads p = res->pressure and, when friction > 0, the traction
 * q_x = friction * p on the lower body (body 1, z >= 0) in +x: the counter body slides in +x
 * relative to it (theory.md §1); Poisson ratio of body 1 (the stresses are body 1's; for body 2
 * mirror the problem); kernel from the scene; backend scene->solver.backend; the grid of res (that of
 * the pressure); window from [stress] window (MC_STRESS_WINDOW_CR: cells outside a layer's window
 * hold 0). Fills res->nlayers, depths, stress[6], von_mises, hydrostatic, tresca (invariants.h),
 * stress_layout (windows, depth rule) and stress_summary: the maxima of von Mises and Tresca with
 * their cell-centre (x, y, z), the first cell in volume order within a relative
 * MC_STRESS_TIE of the maximum (so round-off cannot move the location between equal cells of a
 * symmetric problem, e.g. with and without the window), and the hydrostatic stress at the von
 * Mises maximum. Stress members already present in res are replaced. On failure res's stress
 * members are unchanged. Does not set res->timing.stress_s (the caller times the stage). MC_OK,
 * MC_ERR_INPUT (bad stress settings, no pressure field), MC_ERR_NOMEM, or what mc_stress_create
 * returns. */
int mc_stage_stress(const mc_scene *sc, mc_results *res, mc_error *err);

/* mc_stage_stress with the speed-ups of tune (NULL: all automatic; tune->window overrides the
 * scene's window key unless AUTO), for benchmarks and comparisons. */
int mc_stage_stress_tuned(const mc_scene *sc, mc_results *res, const mc_stress_tuning *tune,
                          mc_error *err);

/* Relative tie tolerance of the summary's maxima: far above the round-off of a layer (~1e-15 of
 * its largest stress), far below any physical difference between cells. */
#define MC_STRESS_TIE 1e-11

#endif
