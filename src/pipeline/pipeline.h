/* pipeline.h - runs the stages a scene needs: surface -> contact -> (stress), with timings.
 *
 * Stages a scene does not ask for are skipped (no stress stage without [stress]); a prescribed
 * pressure (pressure_file) replaces the contact solve. Results are complete even when the
 * contact solver did not converge (the status is MC_NOT_CONVERGED then; outputs are still
 * written and say converged: false).
 */
#ifndef MC_PIPELINE_H
#define MC_PIPELINE_H

#include "core/error.h"
#include "pipeline/results.h"
#include "case/scene.h"

/* Run scene into res (zeroed first; free with mc_results_free even on failure).
 * Returns MC_OK, MC_NOT_CONVERGED, or an error status with err filled. */
int mc_pipeline_run(const mc_scene *scene, mc_results *res, mc_error *err);

/* Seconds on a monotonic clock (for timings in the library and front ends). */
double mc_clock(void);

#endif
