/* runin.h - the running-in driver: the friction hysteresis of a speed run-down with
 * elastic-plastic smoothing and an elastic run-up on the smoothed surface (Mevissen et al. 2025,
 * Figs. 4-1 to 4-3; docs/theory.md §19, with §9, §11, §12).
 *
 * The scene is a rough flat patch standing for the centre of the twin-disc line contact
 * ([lubrication] with radius1, radius2, width; [load] lubricant_pressure = auto), and it is the
 * first step: [load] force is the first force, [lubrication] rpm the first speed (disc 2 keeps
 * the ratio rpm2 / rpm, or runs at equal surface speed). For each force
 * F_N of [runin] forces, in order, and the speeds n_1 > ... > n_m of [runin] speeds:
 *   run-down  n_1 ... n_m: the macro contact at (F_N, n_k) gives h_EHD and the patch load
 *             p_H A_nom (stage_lube.h); the lubricant volume equilibrium on the current surface
 *             gives p_lub and the pressure; where the stresses of that pressure, with the
 *             residual stress the earlier steps left, exceed the yield stress of the hardened
 *             material, the elastic-plastic loop runs (plastic/loop.h: load steps of [plasticity],
 *             the volume equilibrium at every contact solve, warm-started) and the plastic strain,
 *             hardening and residual displacement are carried to the next step;
 *   run-up    n_m ... n_1: the same equilibrium, elastic, on the run-in surface;
 * and the next force starts from the surface the run-up ended on. Every step is a row of
 * runin.csv: h_EHD, p_lub, psi, the pocket height and mu of the loaded state, and the roughness
 * of the surface after the step (surface/roughness.h with the options of roughness.initial): Ra,
 * Rq, Rz, Sa, Sq and what shows running-in, the peaks: the ISO 13565-2 family Rpk, Rk, Rvk, Mr1,
 * Mr2 (mean over the rows) and Sp with the areal Spk, Sk, Svk, Smr1, Smr2 (ISO 25178-2). Without [plasticity] the material is elastic: nothing runs in and every step
 * of a run-up repeats its run-down step exactly (bit for bit: the same solves from the same cold
 * start; a step never starts from the one before).
 *
 * Surface. The composite surface is z = -(h0 + f u_r), h0 the initial topography (flat shape:
 * minus the roughness heights), u_r the residual displacement of body 1 and f = 2 with
 * [plasticity] bodies = both (body 2 deforms alike), else 1.
 *
 * Nominal deflection. On a grid with free axes the patch alone, loaded with its nominal pressure
 * p_nom = F / A_nom, bends into a bowl K p_nom (about p_nom L / E* deep: 0.3 um at the centre of
 * a 100 um patch at 447 MPa, as deep as the roughness) that in the disc contact belongs to the
 * macro contact, whose deformed surfaces conform. nominal_deflection = remove (the default)
 * solves every step on h0 - K p_nom, so only the deviation from the nominal pressure deforms
 * the patch (what a periodic patch does by itself: there K 1 = 0); keep leaves the bowl in.
 *
 * Hysteresis. Per force, the signed area between the run-down and run-up mu curves over the
 * decades of speed, H = integral of (mu_down - mu_up) d log10 n (trapezoids over the speeds):
 * positive when the run-up, on the smoother surface, has less solid friction.
 *
 * Checkpoints and resume. With opt->checkpoint_dir the state after every completed step (the
 * rows, plastic strain, hardening, residual stress and displacement: pipeline/checkpoint.h) is
 * written there atomically. opt->resume continues from it; a step is a deterministic function
 * of that state (steps start cold), so a resumed run gives the results of an uninterrupted one
 * (same machine, same threads: identical bits; only the timings differ). The checkpoint carries
 * mc_runin_case_hash of the scene: another case (or other --set values) is refused.
 *
 * Outputs into res (pipeline/results.h): res->runin (rows, hysteresis), surface_initial and
 * surface_final, roughness_initial and roughness_final, the fields of the last step (pressure,
 * gap, displacement; topography = h0, topography_final = h0 + f u_r), contact and lube of the
 * last step, and with [plasticity] the plastic fields (residual displacement, plastic strain,
 * residual von Mises) with one plastic step record per run-down step.
 */
#ifndef MC_RUNIN_H
#define MC_RUNIN_H

#include <stdint.h>

#include "case/scene.h"
#include "core/error.h"
#include "pipeline/results.h"

typedef struct {
    int step, nsteps;         /* the step just done (1-based) of the run's nsteps */
    const mc_runin_row *row;  /* its row */
    double elapsed;           /* seconds since this session started */
    double eta;               /* estimated seconds left (from this session's mean step) */
} mc_runin_progress;

typedef struct {
    const char *checkpoint_dir; /* NULL: no checkpoints */
    int resume;                 /* 1: continue from the checkpoint in checkpoint_dir */
    void (*progress)(void *ctx, const mc_runin_progress *p); /* after every step; may be NULL */
    void *progress_ctx;
    int (*stop)(void *ctx);     /* polled often; non-zero abandons the step in progress */
    void *stop_ctx;
} mc_runin_options;

/* Run the running-in of sc ([runin] enabled) into res (zeroed first; free with
 * mc_results_free in every case). opt may be NULL (no checkpoints, no progress).
 * Returns MC_OK; MC_NOT_CONVERGED (a solve of some step did not converge: all steps are still
 * done and reported, the row says which); MC_ERR_INTERRUPTED (stop asked: res holds the
 * res->runin.done steps completed, whose state is the last checkpoint); MC_ERR_INPUT (bad scene;
 * resume without a checkpoint, or from another case or grid: the message says which); errors of
 * the stages (MC_ERR_NOMEM, MC_ERR_NUMERIC, MC_ERR_ENV for a checkpoint that cannot be written). */
int mc_runin_run(const mc_scene *sc, const mc_runin_options *opt, mc_results *res,
                 mc_error *err);

/* Identity of a case for checkpoints: FNV-1a 64 over the scene (without its path and output
 * directory, which do not change the run) and the initial topography h0 (n cells). */
uint64_t mc_runin_case_hash(const mc_scene *sc, const double *h0, size_t n);

/* The hysteresis of force index f over res->runin's rows (see above); NAN while its run-up is
 * incomplete. */
double mc_runin_hysteresis(const mc_runin_summary *r, int f);

#endif
