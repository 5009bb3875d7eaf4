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

/* A stage begins: stage is "contact" (the input files are read and the memory guard has passed;
 * the operator and the contact solve follow) or "stress". For progress output. */
typedef void (*mc_stage_fn)(void *ctx, const char *stage);

/* mc_pipeline_run, calling stage (when not NULL) as each stage of a single solve begins (not for
 * a running-in, which reports its own steps: pipeline/runin.h). */
int mc_pipeline_run_staged(const mc_scene *scene, mc_stage_fn stage, void *ctx, mc_results *res,
                           mc_error *err);

/* A scene the run's MPI processes (core/dist.h) can compute together: with ranks > 1 [solver]
 * plans other than estimate are refused (every process must make the same plans); the
 * elastic-plastic stage and the running-in run replicated (their volume whole on every rank,
 * their contact solves distributed). MC_OK or MC_ERR_INPUT naming the case file, line and key.
 * mc_pipeline_run_staged checks it with the run's ranks. */
int mc_pipeline_check_ranks(const mc_scene *scene, int ranks, mc_error *err);

/* Seconds on a monotonic clock (for timings in the library and front ends). */
double mc_clock(void);

#endif
