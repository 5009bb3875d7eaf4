/* harness.h - verification suites: a manifest of checks per suite, each with a stable id, the
 * quantity, its cited reference, the expected and measured values, the tolerance and PASS/FAIL.
 *
 * A suite is a function that computes, calls vf_check() for every comparison, writes its data as
 * CSV and its figures via gnuplot; the harness turns the recorded rows into
 * <reports>/<suite>/report.md (and result.json, which the gallery reads: verify/gallery.h) and
 * prints one PASS/FAIL line per check (INFO per information row, which is shown but not counted
 * as a check). The suites are a front end (like the CLI): they may print; the library may not.
 *
 * Regression gate (verify/baseline.h): when a run is given a baselines directory, every row
 * (checks and information rows) is also compared with its blessed value in
 * <baselines>/<suite>[.fast].json; a drift beyond the row's regression tolerance fails the row
 * and the message names the check, the blessed and the new value. A blessed id that the run does
 * not produce fails too. A suite without a baseline file fails (check id "baseline"): the gate
 * cannot be skipped by deleting a file; blessing (vf_options.bless, `make bless`) is the explicit
 * act that creates or rewrites the file from the run and prints the diff.
 *
 * NaN: a check fails when its measured value, its reference (VF_REL, VF_ABS) or its tolerance is
 * NaN. Suites accumulate the worst error of many values with vf_worst (vf_least for a minimum),
 * never with fmax/fmin, which drop a NaN argument and so would hide it from the check.
 */
#ifndef MC_VERIFY_HARNESS_H
#define MC_VERIFY_HARNESS_H

#include <stdio.h>

#include "baseline.h"

typedef struct vf_ctx vf_ctx;

typedef enum {
    VF_REL, /* |measured - expected| / |expected| <= tol */
    VF_ABS, /* |measured - expected| <= tol (in the unit of the quantity) */
    VF_MAX  /* measured <= tol (expected is informative, e.g. an error that must stay small) */
} vf_kind;

typedef struct {
    const char *name;  /* directory and command-line name, e.g. "hertz_point" */
    const char *title; /* one line for the report heading */
    /* Run the suite; fast = the reduced variant for `make check`. Returns 0, or non-zero when
     * the suite could not run at all (a failed check is not a crash: it is recorded). */
    int (*run)(vf_ctx *ctx, int fast);
    const char *regenerate; /* command that regenerates the report (NULL: microcontact verify) */
} vf_suite;

/* All suites, in report order. */
const vf_suite *vf_suites(int *count);

/* Regression tiers by check id of the suite named (NULL: none), kept beside the registry
 * (suites.c): space-separated PATTERN=TIER pairs, PATTERN a shell glob on the id (fnmatch),
 * TIER a name of baseline.h ("noise", "iter", "roundoff", "none", ...), e.g.
 * "*.kkt=noise *_iterations=iter". The first matching pattern gives the tier of a row that does
 * not declare one with vf_regress. */
const char *vf_suite_tiers(const char *suite);

/* Record one check; returns 1 on PASS. id must be unique within the suite. A check must be
 * able to fail: a tolerance that is not finite (INFINITY, NaN) makes the check FAIL, with a
 * note to record the value with vf_info instead. */
int vf_check(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured, double tol, vf_kind kind);

/* The larger of worst and v, NaN when either is NaN: `worst = vf_worst(worst, err)` carries a
 * NaN anywhere in an accumulation to the check that holds it (fmax(worst, NaN) returns worst). */
double vf_worst(double worst, double v);

/* The smaller of least and v, NaN when either is NaN (fmin drops a NaN the same way). */
double vf_least(double least, double v);

/* Record an information row: a measured value (and, if not NaN, the value it is read against,
 * e.g. a target that binds only elsewhere) shown in the checks table with the result "info".
 * It has no tolerance, never fails and is not counted among the checks. id shares the check
 * ids' name space. */
void vf_info(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured);

/* Declare the regression tier of the row id recorded last (call after vf_check / vf_info):
 * e.g. VF_TIER_ITER for an iteration count, VF_TIER_ROUNDOFF for a closed form, VF_TIER_NONE for
 * a run time. It sets the regression tolerance when the row is blessed; rows that declare none
 * get vf_tier_auto's choice (or keep the tolerance already in the baseline file). */
void vf_regress(vf_ctx *ctx, const char *id, vf_tier tier);

/* A free paragraph of Markdown for the report (printf-style). */
void vf_text(vf_ctx *ctx, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Path of a file inside the suite's report directory (static buffer rotated over 8 calls). */
const char *vf_path(vf_ctx *ctx, const char *file);

/* Open a file of the report directory for writing (written to a temporary name; closed and
 * renamed by vf_close). */
FILE *vf_open(vf_ctx *ctx, const char *file);
int vf_close(vf_ctx *ctx, FILE *f);

/* Write gnuplot commands (terminal and output are set by the harness) to <png>.gp and run
 * gnuplot in the report directory to produce <png>; the figure is linked from the report. A
 * missing gnuplot is noted in the report, not a failure. */
int vf_plot(vf_ctx *ctx, const char *png, const char *caption, const char *script);

/* Whether the run is the reduced (fast) variant. */
int vf_fast(const vf_ctx *ctx);

/* Note an error that stopped part of the suite (recorded as a failed check). */
void vf_fail(vf_ctx *ctx, const char *id, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

typedef struct {
    const char *reports_dir; /* each suite writes <reports_dir>/<suite>/ */
    const char *baselines;   /* directory of the baseline files; NULL: no regression gate */
    int fast;                /* the fast variant (baselines <suite>.fast.json) */
    int bless;               /* rewrite the baselines from this run (needs baselines); refused,
                              * as a failure, for a suite with a failing check */
} vf_options;

/* Run one suite (also one that is not in the registry, e.g. the benchmark) into
 * reports_dir/<suite>/, without a regression gate; returns its number of failed checks, or -1 if
 * it could not start. */
int vf_run_suite(const vf_suite *suite, const char *reports_dir, int fast);

/* The same with options (gate, bless). Returns the failed checks (physics or regression), or -1
 * if the suite could not start (its report directory, or a malformed baseline file). */
int vf_run_suite_opts(const vf_suite *suite, const vf_options *opt);

/* Run the named suites (all when n == 0) writing into reports_dir/<suite>/. Returns the number
 * of failed checks (plus suites that could not run), or -1 for an unknown suite name. */
int vf_run(const char *reports_dir, int nnames, char **names, int fast, int list_only);
int vf_run_opts(const vf_options *opt, int nnames, char **names);

#endif
