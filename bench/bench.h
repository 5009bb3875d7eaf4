/* bench.h - the benchmark report (`microcontact bench`, `make bench`): run time against error
 * and against the bare FFTW cost of the same size, all measured in one run, as ratios. It runs
 * through the verification harness, so its targets are checks and its tables a report. */
#ifndef MC_BENCH_H
#define MC_BENCH_H

#include <stddef.h>

#include "harness.h"

extern const vf_suite mc_bench_suite;

/* Sections (bench_*.c), each adding its tables, CSV and figures to the report. */
int mc_bench_operator(vf_ctx *ctx, int quick);
int mc_bench_hertz(vf_ctx *ctx, int quick);
int mc_bench_rough(vf_ctx *ctx, int quick);
int mc_bench_stress(vf_ctx *ctx, int quick);
int mc_bench_threads(vf_ctx *ctx, int quick);
int mc_bench_memory(vf_ctx *ctx, int quick);
int mc_bench_skips(vf_ctx *ctx, int quick);
int mc_bench_plastic(vf_ctx *ctx, int quick);
int mc_bench_whole(vf_ctx *ctx, int quick);
int mc_bench_growth(vf_ctx *ctx, int quick);
int mc_bench_runin(vf_ctx *ctx, int quick);
int mc_bench_plans(vf_ctx *ctx, int quick);
int mc_bench_mpi(vf_ctx *ctx, int quick);

/* Run only the sections named in names (comma-separated, e.g. "plastic" or "operator,hertz";
 * NULL or "" = all); the string must outlive the run. 0, or -1 for an unknown name. */
int mc_bench_select(const char *names);
/* The section names, comma-separated in report order (for usage messages). */
const char *mc_bench_section_names(void);

/* The default running-in scene's path (cases/default.ini beside the executable's bin/, else in
 * the current directory) into path: 0, or 1 when not readable. */
int mc_bench_default_case(char *path, size_t len);
/* Wall time (s) of the run-down step of the default running-in scene with one force (1086 N) and
 * one speed (e.g. "350 rpm") on an nx x ny grid of its 0.8 um cells, extra more --set overrides
 * separated by spaces (each "section.key=value" without spaces) or NULL; *plastic (may be NULL) =
 * the step ran the plastic loop. NAN on failure. */
double mc_bench_runin_step(int nx, int ny, const char *speed, const char *extra, int *plastic);
/* The same step with its counts (issue 20 item 3): wall time of the step, process CPU time from
 * the start of the run to the end of the step (all threads; set-up and the operators' creation
 * included), and the elastic-plastic loop's outer iterations, sweeps, residual stress
 * applications, volume equilibria (one per outer iteration) and contact solves of the step.
 * threads > 0: the run's thread count ([solver] threads), else the default. 0, or -1 on
 * failure. */
typedef struct {
    double wall_s, cpu_s;
    int plastic, outer, sweeps, applies, equilibria, solves;
    int local_sweeps;  /* near-field sweeps between the applications (theory §9.7) */
    int nz;            /* layers of the plastic volume, read back from the run's results */
} mc_bench_step;
int mc_bench_runin_step_counts(int nx, int ny, const char *speed, const char *extra, int threads,
                               mc_bench_step *out);
/* Process CPU time (all threads), s. */
double mc_bench_cpu(void);

/* The Hertz point case of issue 13 (steel on steel, R = 10 mm, F = 100 N, a square of side 3a on
 * N x N cells, no [solver] section: a new user's defaults) written to path: 0, or 1. */
int mc_bench_hertz_case(const char *path, int N);
/* Run argv (argv[0] a path) as a child, stdout and stderr to /dev/null: wall time fork to exit,
 * s; NAN when it did not exit with 0. */
double mc_bench_run_child(const char *const argv[]);
/* The same with the child's stdout into the file out (NULL: /dev/null, as above); argv[0] is
 * searched in PATH when it has no slash (mpirun). */
double mc_bench_run_child_to(const char *const argv[], const char *out);
/* A number "key": value of a run's summary.json (the first occurrence); NAN if absent. */
double mc_bench_json_number(const char *path, const char *key);
/* rm -rf dir (a temporary directory of the bench). */
void mc_bench_remove_tree(const char *dir);

/* One bare FFTW r2c + c2r pair for the timers (the FFT reference every ratio is read against):
 * the two plans (fftw_plan) executed in turn. */
typedef struct {
    void *f, *b; /* fftw_plan forward (r2c) and backward (c2r) */
} mc_bench_pair;
void mc_bench_pair_run(void *arg); /* fftw_execute(f), fftw_execute(b) of an mc_bench_pair */
/* Bare FFTW: one r2c and one c2r of tx x ty on the run's threads, median wall time of reps after
 * a warm-up, s (NAN without memory); flags FFTW_ESTIMATE (what the operators use) or
 * FFTW_MEASURE (for the cost of that choice: *plan_s, when not NULL, gets the planning time). */
double mc_bench_pair_time(int tx, int ty, int reps, unsigned flags, double *plan_s);

/* One application of the eigenstrain operators for the timers (plastic/eigen_op.h): eigenstrain
 * components e[6] in, stresses sg[6] (shear modulus 80 GPa) or the surface displacement uz out. */
typedef struct mc_eigen_stress mc_eigen_stress;
typedef struct mc_eigen_disp mc_eigen_disp;
typedef struct {
    mc_eigen_stress *s;
    mc_eigen_disp *d;
    const double *e[6];
    double *sg[6], *uz;
} mc_bench_eig;
void mc_bench_eig_stress(void *arg); /* mc_eigen_stress_apply on an mc_bench_eig */
void mc_bench_eig_disp(void *arg);   /* mc_eigen_disp_apply on an mc_bench_eig */

/* Median wall time (s) of reps calls of fn(arg) after one warm-up call. */
double mc_bench_time(void (*fn)(void *), void *arg, int reps);

#endif
