/* topo_run.h - run the contact (and, when the scene asks for it, the elastic-plastic stage) on a
 * topography given as an array, for suites whose surfaces are analytic functions sampled on each
 * mesh (mesh_convergence, yield_criterion) rather than a [roughness] spec or a file.
 *
 * It does what the pipeline's contact path does (pipeline.c: the Love operator of the scene's
 * grid, a contact solver planned over it, then mc_stage_plastic or a plain force-controlled
 * solve) with the scene's thread count scoped to the call; the scene's [geometry] and
 * [roughness] are ignored (the topography replaces them). A front-end helper: it may print
 * nothing either, errors go to err.
 */
#ifndef MC_VERIFY_TOPO_RUN_H
#define MC_VERIFY_TOPO_RUN_H

#include "case/scene.h"
#include "pipeline/results.h"

/* Run sc (load kind force) on the initial gap topo (ny*nx, m, copied) into res (zeroed first;
 * free with mc_results_free even on failure). When p_elastic is not NULL it receives (ny*nx, Pa)
 * the elastic contact pressure at the full load (no plasticity, no cap), solved first with the
 * same solver; when sc->plasticity.enabled the stage of pipeline/stage_plastic.h follows,
 * otherwise res holds that elastic solution. res->timing.total_s is the wall time of the call.
 * Returns MC_OK, MC_NOT_CONVERGED (results filled) or an error status. */
int vt_run_topography(const mc_scene *sc, const double *topo, mc_results *res, double *p_elastic,
                      mc_error *err);

/* The elastic stress of a piecewise-constant pressure p (grid g, Pa) at the point (x, y) (m,
 * relative to the grid centre as mc_grid_x/_y) and the depths z[0..nz-1] (> 0, m), by direct
 * summation of the closed-form kernels over the loaded cells: kernel MC_STRESS_PATCH (uniform
 * pressure on each cell, Love) or MC_STRESS_POINT (a force p dx dy at each cell centre,
 * Boussinesq). s[k*6 + c] in the component order of kernel.h, Pa, tension positive. */
void vt_stress_at(const mc_grid *g, const double *p, double nu, int point_kernel, double x,
                  double y, const double *z, int nz, double *s);

/* Connected contact patches of the cells with p > 0 (4-neighbour connectivity) on grid g; -1
 * when out of memory. */
int vt_count_patches(const mc_grid *g, const double *p);

#endif
