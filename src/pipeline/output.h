/* output.h - the output contract (README.md, Outputs): summary.json, .npy fields, .csv profiles and
 * VTK files, written atomically into an output directory that one run holds at a time.
 *
 * Files are first written into a staging directory inside DIR (DIR/.staging-XXXXXX) and renamed
 * into DIR only when all of them succeeded: a failed or interrupted run leaves no half-written
 * result and no partial set. Contract files of an earlier run that this run does not produce
 * (von_mises.npy after a run without stress, field.vti without vtk, ...) are removed, so DIR
 * never mixes two runs; other files in DIR are left alone. The old summary.json is removed first
 * and the new one renamed last, so a summary.json in DIR always describes the files beside it.
 *
 * DIR and its missing parents are created only when results are committed (and removed again,
 * while empty, if the commit fails): a run that fails before leaves no directory behind.
 *
 * One run per output directory at a time (pipeline/outdir.h): a run holds an exclusive flock on
 * DIR - from mc_output_open when DIR exists then, else from the commit - until mc_output_close or
 * its end. A second run refuses at once with MC_ERR_ENV naming DIR and the holder's pid; it does
 * not wait. Commits into one directory are therefore serial and the committed set is always one
 * run's. Staging areas left by a killed run (SIGKILL) are removed by the next run's commit.
 *
 * Interruption: mc_output_interrupt (from a signal watcher) makes a commit in progress stop at
 * the next file, remove its staging area and the directories it created, and return
 * MC_ERR_INTERRUPTED with DIR as it was. The final renames are not interrupted (they take
 * microseconds): a commit that reached them completes.
 */
#ifndef MC_OUTPUT_H
#define MC_OUTPUT_H

#include "core/error.h"
#include "pipeline/outdir.h"
#include "pipeline/results.h"
#include "case/scene.h"

/* Start a run's use of DIR, before any computation, so a bad output directory fails fast:
 * initialises *out, checks that DIR can be created and written without creating anything
 * (mc_outdir_open: every existing prefix a directory, a dangling symbolic link named as such, the
 * deepest existing one writable) and, when DIR exists, takes its lock.
 * MC_OK; MC_ERR_INPUT (empty or too long path); MC_ERR_ENV (not a directory, not writable, in
 * use by another run: the message names DIR, the reason and the holder's pid). *out needs
 * mc_output_close in every case. */
int mc_output_open(mc_outdir *out, const char *dir, mc_error *err);

/* Commit the results into the directory of out (see mc_output_write for the files): creates DIR
 * if needed and locks it (unless out holds it), removes stale staging areas, stages, renames.
 * Returns what mc_output_write returns, plus MC_ERR_INTERRUPTED (see above); on any failure DIR
 * is as it was and the directories this call created are removed. */
int mc_output_commit(mc_outdir *out, const mc_scene *scene, const mc_results *res, mc_error *err);

/* The output table (output.c): file i's name ("summary.json", "pressure.npy", ...) and one line
 * of what it holds; NULL when i is out of range. Iterate i = 0 .. mc_output_file_count() - 1. */
int mc_output_file_count(void);
const char *mc_output_file_name(int i);
const char *mc_output_file_help(int i);
/* 1 when a commit of res (from scene) writes file i, else 0. */
int mc_output_file_written(int i, const mc_scene *scene, const mc_results *res);
/* The names of the files a commit of res writes, in table order, joined by sep ("a, b"). */
void mc_output_files_joined(const mc_scene *scene, const mc_results *res, const char *sep,
                            char *buf, size_t len);
/* docs/outputs.md: the output table as Markdown (mc_malloc'd; mc_free), NULL without memory. */
char *mc_output_reference_markdown(void);

/* Release the lock (idempotent). */
void mc_output_close(mc_outdir *out);

/* Ask commits in progress in this process to stop (on = 1) or clear the request (on = 0).
 * Thread-safe and async-signal-safe (atomics only); a request stays until cleared, and a commit
 * started after it stops before creating anything. Returns 1 when a commit is in progress (it
 * will return MC_ERR_INTERRUPTED, or MC_OK if it already reached its final renames), 0 when none
 * is (nothing of this process is being written: it may end at once). */
int mc_output_interrupt(int on);

/* A computation that checkpoints as it goes (the running-in, pipeline/runin.h) holds the output
 * while it runs (on = 1; on = 0 releases): mc_output_interrupt then reports work in progress, so
 * that a signal asks it to stop - it polls mc_output_stop_requested - instead of ending the
 * process at once. Thread-safe (atomics). */
void mc_output_hold(int on);

/* 1 once mc_output_interrupt(1) was called (and not cleared). */
int mc_output_stop_requested(void);

/* mc_output_open + mc_output_close: the checks alone (nothing is created, no lock is kept). */
int mc_output_prepare(const char *dir, mc_error *err);

/* mc_output_open + mc_output_commit + mc_output_close. Write every file the results call for
 * into dir:
 *  always     summary.json, pressure.npy, gap.npy, displacement.npy, topography.npy (ny x nx,
 *             .npy 1.0 float64), profile_x.csv ("x,pressure,gap,displacement": row j of the
 *             maximum pressure, x at cell centres);
 *  res->nlayers > 0 (stress was run)
 *             von_mises.npy, hydrostatic.npy, stress_xx.npy ... stress_xz.npy (layers x ny x nx),
 *             depths.csv ("layer,z"), axis.csv ("z,sxx,syy,szz,sxy,syz,sxz,von_mises,
 *             hydrostatic,tresca" under the cell of maximum pressure);
 *  res->plastic.enabled (elastic-plastic stage or running-in)
 *             residual_displacement.npy, topography_final.npy, plastic_strain.npy,
 *             residual_von_mises.npy (nz x ny x nx), plastic.csv (one row per load step; for a
 *             running-in one per run-down step that yielded: its last load step);
 *  res->runin.enabled (running-in, pipeline/runin.h)
 *             runin.csv (one row per step: force,phase,speed,h_ehd,p_lub,psi_load,psi_area,
 *             pocket_height,mu,Ra,Rq,Rz,Sa,Sq,residual_max,converged,seconds, then step,rpm,
 *             entrainment_speed,regime,plastic,contact_solves,volume_roots,root_error; SI but
 *             rpm), runin.gp (gnuplot: runin_ra.png, runin_psi.png, runin_mu.png, the paper's
 *             Figs. 4-1 to 4-3), surface_initial.npy, surface_final.npy (composite heights, m);
 *  res->two_bodies ([roughness2], pipeline/bodies.h)
 *             surface_initial_body1.npy, surface_initial_body2.npy (each body's outward heights,
 *             m), and with a final surface (res->body_has_final: elastic-plastic stage, running-in)
 *             surface_final_body1.npy, surface_final_body2.npy (minus each body's own dent);
 *  scene->output.x3p
 *             topography.x3p, and beside each of topography_final.npy, surface_initial.npy,
 *             surface_final.npy and the body surfaces that is written its .x3p (io/surface_file.h mc_x3p_write: the same
 *             heights bit for bit, the grid's spacings, offsets at the centre of cell (0, 0));
 *  scene->output.vtk
 *             field.vti (ImageData, the four surface fields as CellData) and, with stress,
 *             stress.vtr (RectilinearGrid: x, y at cell centres, z = -depth increasing; the six
 *             stresses, von_mises, hydrostatic, tresca as PointData); raw appended
 *             little-endian Float64, header_type UInt64.
 * Ties for the maximum pressure (e.g. all zero) go to the cell nearest the grid centre. Numbers
 * in CSV and JSON carry 17 significant digits (exact round trip); JSON infinities and NaN are
 * null.
 * summary.json: format, format_version, case (scene->path), mesh, geometry, materials (E, nu,
 * rigid, estar), load (kind, value or pressure_file, lubricant_pressure, pressure_cap), roughness
 * (type; seed = res->roughness_seed, a string if above INT64_MAX; the type's parameters),
 * contact (the mc_contact_summary, plus the solver tolerance and max_iterations of the scene),
 * stress (the mc_stage_stress_summary, when stress was run), timing (total_s, setup_s, contact_s,
 * stress_s), with a running-in runin (forces, speeds, hysteresis per force, steps, roots),
 * roughness.final where the results hold a final surface (running-in, elastic-plastic), with
 * [roughness2] roughness.body1 and roughness.body2 (section, inputs, initial and final ISO
 * parameters, dents, residual_max, plastic_strain), and files (every file written, summary.json
 * last).
 * Returns MC_OK; MC_ERR_ENV (DIR cannot be created or locked, a write failed - disk full,
 * file too large -, a result file name in DIR is taken by a directory: DIR unchanged);
 * MC_ERR_NOMEM (DIR unchanged); MC_ERR_INPUT (empty path, invalid grid); MC_ERR_INTERNAL
 * (results lack a field the contract needs). Only a failing rename after the commit started
 * (practically impossible within one directory) leaves DIR without summary.json. */
int mc_output_write(const char *dir, const mc_scene *scene, const mc_results *res, mc_error *err);

#endif
