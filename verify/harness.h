/* harness.h - verification suites: a manifest of checks per suite, each with a stable id, the
 * quantity, its cited reference, the expected and measured values, the tolerance and PASS/FAIL.
 *
 * A suite is a function that computes, calls vf_check() for every comparison, writes its data as
 * CSV and its figures via gnuplot; the harness turns the recorded rows into
 * <reports>/<suite>/report.md and prints one PASS/FAIL line per check (INFO per information
 * row, which is shown but not counted as a check). The suites are a front
 * end (like the CLI): they may print; the library may not.
 */
#ifndef MC_VERIFY_HARNESS_H
#define MC_VERIFY_HARNESS_H

#include <stdio.h>

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

/* Record one check; returns 1 on PASS. id must be unique within the suite. A check must be
 * able to fail: a tolerance that is not finite (INFINITY, NaN) makes the check FAIL, with a
 * note to record the value with vf_info instead. */
int vf_check(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured, double tol, vf_kind kind);

/* Record an information row: a measured value (and, if not NaN, the value it is read against,
 * e.g. a target that binds only elsewhere) shown in the checks table with the result "info".
 * It has no tolerance, never fails and is not counted among the checks. id shares the check
 * ids' name space. */
void vf_info(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured);

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

/* Run one suite (also one that is not in the registry, e.g. the benchmark) into
 * reports_dir/<suite>/; returns its number of failed checks, or -1 if it could not start. */
int vf_run_suite(const vf_suite *suite, const char *reports_dir, int fast);

/* Run the named suites (all when n == 0) writing into reports_dir/<suite>/. Returns the number
 * of failed checks (plus suites that could not run). */
int vf_run(const char *reports_dir, int nnames, char **names, int fast, int list_only);

#endif
