/* test_baselines.c - the regression gate of the verification harness (verify/harness.h,
 * verify/baseline.h): a drift beyond a check's regression tolerance fails the check and names
 * the check, the blessed and the new value; --bless restores a passing state and prints the
 * diff; a blessed check that disappears fails; a bless is refused while a check fails against
 * its reference; the tiers are the documented ones.
 *
 * The harness is front-end code (it is linked into the executable, not into the library the
 * tests link), so this file compiles it in: verify/harness.c and verify/baseline.c are included
 * below, and the registry they need (vf_suites) is this file's toy suite. */
#include <check.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_util.h"

#include "baseline.c"
#include "harness.c"

/* ---- a toy suite whose numbers the tests set ------------------------------------------------ */

static double g_value = 1.0;  /* the measured value of check "value_a" */
static double g_iters = 12;   /* an iteration count (information row) */
static double g_resid = 5e-9; /* a stopping residual (tolerance 2e-8): noise */
static int g_extra = 0;       /* 1: record one more check, "extra" */
static double g_errs[3] = {1e-9, 2e-9, 3e-9}; /* errors accumulated into check "worst_c" */

static int toy_run(vf_ctx *ctx, int fast)
{
    (void)fast;
    /* physics tolerance 10 % around 1: the gate must catch drifts far inside it */
    vf_check(ctx, "value_a", "a value with a reference", "one", 1.0, g_value, 0.1, VF_REL);
    vf_check(ctx, "error_b", "an error that must stay small", "zero", 0, 1e-9, 1e-6, VF_MAX);
    vf_info(ctx, "solver_iterations", "iterations of a solve", "regression only", NAN, g_iters);
    vf_check(ctx, "solve_residual", "where a solve stopped", "<= 2 tol", 0, g_resid, 2e-8, VF_MAX);
    if (g_extra)
        vf_check(ctx, "extra", "a check added later", "one", 1.0, 1.0, 0.1, VF_REL);
    /* the suites' accumulation of a worst error over many values */
    double worst = 0;
    for (int k = 0; k < 3; k++)
        worst = vf_worst(worst, g_errs[k]);
    vf_check(ctx, "worst_c", "worst of three errors", "zero", 0, worst, 1e-6, VF_MAX);
    return 0;
}

static const vf_suite toy = {.name = "toy", .title = "toy suite of the gate test", .run = toy_run};

const vf_suite *vf_suites(int *count)
{
    *count = 1;
    return &toy;
}

/* the toy's residual is noise (the tier by pattern, as suites.c gives the stability suite's) */
const char *vf_suite_tiers(const char *suite)
{
    return !strcmp(suite, "toy") ? "*_residual=noise" : NULL;
}

/* ---- helpers ------------------------------------------------------------------------------ */

typedef struct {
    char root[256], reports[512], bl[512], out[512];
} dirs_t;

static void make_dirs(dirs_t *d)
{
    snprintf(d->root, sizeof d->root, "%s", test_tmpdir());
    snprintf(d->reports, sizeof d->reports, "%s/reports", d->root);
    snprintf(d->bl, sizeof d->bl, "%s/baselines", d->root);
    snprintf(d->out, sizeof d->out, "%s/stdout.txt", d->root);
    ck_assert_int_eq(mkdir(d->bl, 0777), 0);
    g_value = 1.0;
    g_iters = 12;
    g_resid = 5e-9;
    g_extra = 0;
    g_errs[0] = 1e-9;
    g_errs[1] = 2e-9;
    g_errs[2] = 3e-9;
}

/* Run the toy suite (fast variant) with stdout captured into d->out; returns the failures. */
static int run_toy(const dirs_t *d, const char *baselines, int bless)
{
    vf_options opt = {.reports_dir = d->reports, .baselines = baselines, .fast = 1,
                      .bless = bless};
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    FILE *f = fopen(d->out, "w");
    ck_assert_ptr_nonnull(f);
    dup2(fileno(f), STDOUT_FILENO);
    int failures = vf_run_opts(&opt, 0, NULL);
    fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    fclose(f);
    return failures;
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "cannot read %s", path);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Copy the baseline file of dir into a new directory <root>/<name> with the value of check id
 * replaced by value (NAN: id removed; add != NULL: an entry add with value 1 appended). */
static void edited_copy(const dirs_t *d, const char *name, const char *id, double value,
                        const char *add, char *out, size_t len)
{
    snprintf(out, len, "%s/%s", d->root, name);
    ck_assert_int_eq(mkdir(out, 0777), 0);
    char src[600], dst[600], msg[256];
    vf_baseline_path(src, sizeof src, d->bl, "toy", 1);
    vf_baseline_path(dst, sizeof dst, out, "toy", 1);
    vf_baseline b;
    ck_assert_int_eq(vf_baseline_load(src, &b, msg, sizeof msg), 0);
    vf_blessed *e = vf_baseline_find(&b, id, -1);
    ck_assert_ptr_nonnull(e);
    e->value = value;
    if (add)
        ck_assert_ptr_nonnull(vf_baseline_add(&b, add, 1.0, 0.0, 0.0, VF_TIER_EXACT));
    ck_assert_int_eq(vf_baseline_save(dst, &b, msg, sizeof msg), 0);
    vf_baseline_free(&b);
}

/* Mark the baseline in dir as blessed on another configuration (another thread count), so that
 * the tol_other tolerances apply to this process. */
static void other_configuration(const char *dir)
{
    char path[600], msg[256];
    vf_baseline_path(path, sizeof path, dir, "toy", 1);
    vf_baseline b;
    ck_assert_int_eq(vf_baseline_load(path, &b, msg, sizeof msg), 0);
    b.config.threads += 1000;
    ck_assert_int_eq(vf_baseline_save(path, &b, msg, sizeof msg), 0);
    vf_baseline_free(&b);
}

static double blessed_value(const char *dir, const char *id)
{
    char path[600], msg[256];
    vf_baseline_path(path, sizeof path, dir, "toy", 1);
    vf_baseline b;
    ck_assert_int_eq(vf_baseline_load(path, &b, msg, sizeof msg), 0);
    vf_blessed *e = vf_baseline_find(&b, id, -1);
    ck_assert_ptr_nonnull(e);
    double v = e->value;
    vf_baseline_free(&b);
    return v;
}

/* ---- tests -------------------------------------------------------------------------------- */

/* Bless, then change one blessed value in a copy of the baseline by 1e-6 relative (a thousand
 * times the plan tier's 1e-9, a hundred-thousandth of the check's physics tolerance): the gate
 * fails that check alone, and the message names the check, the blessed and the new value. */
START_TEST(test_drift_fails_naming_check)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 0); /* the blessed baseline passes */
    const double blessed = 1.0 + 1e-6;
    char copy[600];
    edited_copy(&d, "copy", "value_a", blessed, NULL, copy, sizeof copy);
    ck_assert_int_eq(run_toy(&d, copy, 0), 1);
    const char *out = slurp(d.out);
    char want[256];
    snprintf(want, sizeof want, "FAIL toy.value_a:");
    ck_assert_msg(strstr(out, want), "no FAIL line for value_a in:\n%s", out);
    snprintf(want, sizeof want, "regression: blessed %.15g, new %.15g", blessed, 1.0);
    ck_assert_msg(strstr(out, want), "message does not name blessed and new value:\n%s", out);
    ck_assert_msg(strstr(out, "PASS toy.error_b:"), "the other check must pass:\n%s", out);
    /* the report names it too, and result.json counts it */
    char path[700];
    snprintf(path, sizeof path, "%s/toy/report.md", d.reports);
    const char *rep = slurp(path);
    ck_assert_msg(strstr(rep, "| value_a |") && strstr(rep, "**FAIL**"), "report:\n%s", rep);
    snprintf(path, sizeof path, "%s/toy/result.json", d.reports);
    json_t *r = json_load_file(path, 0, NULL);
    ck_assert_ptr_nonnull(r);
    ck_assert_int_eq(json_integer_value(json_object_get(json_object_get(r, "regression"),
                                                        "drifted")),
                     1);
    ck_assert_int_eq(json_integer_value(json_object_get(r, "failed")), 1);
    json_decref(r);
    /* 1e-6 is beyond the wider tolerance of another configuration (1e-9 relative) too */
    other_configuration(copy);
    ck_assert_int_eq(run_toy(&d, copy, 0), 1);
    ck_assert_msg(strstr(slurp(d.out), "FAIL toy.value_a:"), "%s", slurp(d.out));
}
END_TEST

/* --bless on the drifted copy rewrites that value (printing the diff) and the next run passes. */
START_TEST(test_bless_restores_passing_state)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    char copy[600];
    edited_copy(&d, "copy", "value_a", 1.0 + 1e-6, NULL, copy, sizeof copy);
    ck_assert_int_eq(run_toy(&d, copy, 0), 1);
    ck_assert_int_eq(run_toy(&d, copy, 1), 0);
    const char *out = slurp(d.out);
    char want[256];
    snprintf(want, sizeof want, "value_a: %.15g -> %.15g", 1.0 + 1e-6, 1.0);
    ck_assert_msg(strstr(out, want), "bless does not print the diff line '%s':\n%s", want, out);
    ck_assert_msg(strstr(out, "1 values beyond their tolerance"), "bless summary:\n%s", out);
    ck_assert_double_eq(blessed_value(copy, "value_a"), 1.0);
    ck_assert_int_eq(run_toy(&d, copy, 0), 0);
    /* blessing an unchanged state changes nothing */
    ck_assert_int_eq(run_toy(&d, copy, 1), 0);
    ck_assert_msg(strstr(slurp(d.out), "no change"), "%s", slurp(d.out));
}
END_TEST

/* A blessed check that the run no longer produces fails, named; a new check is reported as not
 * blessed (not a failure) until a bless adds it. */
START_TEST(test_missing_and_new_checks)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    char copy[600];
    edited_copy(&d, "copy", "value_a", 1.0, "gone_check", copy, sizeof copy);
    ck_assert_int_eq(run_toy(&d, copy, 0), 1);
    ck_assert_msg(strstr(slurp(d.out), "FAIL toy.gone_check: blessed check not produced"), "%s",
                  slurp(d.out));
    g_extra = 1;
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 0);
    ck_assert_msg(strstr(slurp(d.out), "1 not blessed"), "%s", slurp(d.out));
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    ck_assert_msg(strstr(slurp(d.out), "+ extra = 1"), "%s", slurp(d.out));
    ck_assert_double_eq(blessed_value(d.bl, "extra"), 1.0);
}
END_TEST

/* A bless is refused (a failure, file unchanged) while a check fails against its reference. */
START_TEST(test_bless_refused_on_physics_failure)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    g_value = 1.5; /* 50 % off: beyond the 10 % physics tolerance */
    ck_assert_int_ge(run_toy(&d, d.bl, 1), 1);
    ck_assert_msg(strstr(slurp(d.out), "bless toy: refused"), "%s", slurp(d.out));
    ck_assert_double_eq(blessed_value(d.bl, "value_a"), 1.0);
}
END_TEST

/* Iteration counts: exact on the blessing configuration; on another, one more iteration passes
 * and two fail. */
START_TEST(test_iteration_tier)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    char path[600], msg[256];
    vf_baseline_path(path, sizeof path, d.bl, "toy", 1);
    vf_baseline b;
    ck_assert_int_eq(vf_baseline_load(path, &b, msg, sizeof msg), 0);
    ck_assert_int_eq(vf_baseline_find(&b, "solver_iterations", -1)->tier, VF_TIER_ITER);
    ck_assert_int_eq(vf_baseline_find(&b, "value_a", -1)->tier, VF_TIER_PLAN);
    vf_baseline_free(&b);
    g_iters = 13;
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 1);
    ck_assert_msg(strstr(slurp(d.out), "FAIL toy.solver_iterations:"), "%s", slurp(d.out));
    other_configuration(d.bl);
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 0);
    g_iters = 14;
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 1);
    ck_assert_msg(strstr(slurp(d.out), "FAIL toy.solver_iterations:"), "%s", slurp(d.out));
}
END_TEST

/* A residual (tier noise by the registry's pattern): round-off on the blessing configuration; on
 * another it may move by half its physics tolerance (where a solve stops is noise there), and a
 * jump beyond that fails. */
START_TEST(test_noise_tier_by_pattern)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    char path[600], msg[256];
    vf_baseline_path(path, sizeof path, d.bl, "toy", 1);
    vf_baseline b;
    ck_assert_int_eq(vf_baseline_load(path, &b, msg, sizeof msg), 0);
    ck_assert_int_eq(vf_baseline_find(&b, "solve_residual", -1)->tier, VF_TIER_NOISE);
    vf_baseline_free(&b);
    g_resid = 5e-9 + 0.4 * 2e-8; /* 0.4 of the physics tolerance */
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 1);
    other_configuration(d.bl);
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 0);
    g_resid = 5e-9 + 0.6 * 2e-8; /* 0.6: beyond half */
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 1);
    ck_assert_msg(strstr(slurp(d.out), "FAIL toy.solve_residual:"), "%s", slurp(d.out));
}
END_TEST

/* Fast and full variants have separate baseline files. */
START_TEST(test_variant_files)
{
    char path[256];
    ck_assert_int_eq(vf_baseline_path(path, sizeof path, "bl", "hertz_point", 1), 0);
    ck_assert_str_eq(path, "bl/hertz_point.fast.json");
    ck_assert_int_eq(vf_baseline_path(path, sizeof path, "bl", "hertz_point", 0), 0);
    ck_assert_str_eq(path, "bl/hertz_point.json");
    volatile size_t small = 8; /* too short for the path: refused, not truncated */
    ck_assert_int_eq(vf_baseline_path(path, small, "bl", "hertz_point", 0), -1);
}
END_TEST

/* The tiers as documented in baseline.c: on the blessing configuration everything but exact is
 * round-off (1e-12 relative + 1e-6 of the physics tolerance of an error row) and iter is exact;
 * on another, plan is 1e-9 relative (+1e-3), noise 1e-6 relative (+0.5), iter 1, round-off
 * unchanged; none is not gated; and the automatic choice. Tolerances compared with TOL_TIGHT:
 * they are closed forms. */
START_TEST(test_tiers)
{
    const double same = 2e-12 + 1e-9; /* v = 2, err = 1e-3 */
    for (int t = VF_TIER_ROUNDOFF; t <= VF_TIER_NOISE; t++)
        ck_assert(fabs(vf_tier_tol((vf_tier)t, 2.0, 1e-3, 0) - same) <= TOL_TIGHT * same);
    ck_assert_double_eq(vf_tier_tol(VF_TIER_EXACT, 5, 1, 0), 0);
    ck_assert_double_eq(vf_tier_tol(VF_TIER_EXACT, 5, 1, 1), 0);
    ck_assert_double_eq(vf_tier_tol(VF_TIER_ITER, 5, 1, 0), 0);
    ck_assert_double_eq(vf_tier_tol(VF_TIER_ITER, 5, 1, 1), 1);
    ck_assert(fabs(vf_tier_tol(VF_TIER_ROUNDOFF, 2.0, 1e-3, 1) - same) <= TOL_TIGHT * same);
    ck_assert(fabs(vf_tier_tol(VF_TIER_PLAN, 2.0, 1e-3, 1) - (2e-9 + 1e-6)) <= TOL_TIGHT * 1e-6);
    ck_assert(fabs(vf_tier_tol(VF_TIER_NOISE, 2.0, 1e-3, 1) - (2e-6 + 5e-4)) <= TOL_TIGHT * 1e-3);
    ck_assert(isnan(vf_tier_tol(VF_TIER_NONE, 2.0, 1e-3, 1)));
    ck_assert_int_eq(vf_tier_auto("count", 0, 1), VF_TIER_EXACT);
    ck_assert_int_eq(vf_tier_auto("cg_iterations", 12, 1), VF_TIER_ITER);
    ck_assert_int_eq(vf_tier_auto("sphere.converged", 1, 1), VF_TIER_EXACT);
    ck_assert_int_eq(vf_tier_auto("iter_limit.fft.cg.finite", 0, 1), VF_TIER_EXACT);
    ck_assert_int_eq(vf_tier_auto("load", 1e5, 0), VF_TIER_PLAN); /* relative: never a count */
    ck_assert_int_eq(vf_tier_auto("half_width", 13.5, 1), VF_TIER_PLAN);
    ck_assert_int_eq(vf_tier_auto("pressure", 3e9, 1), VF_TIER_PLAN); /* beyond 2^31 */
    vf_blessed e = {.value = 1.0};
    ck_assert(vf_blessed_ok(&e, 0.5, 1.4));
    ck_assert(!vf_blessed_ok(&e, 0.5, 1.6));
    ck_assert(!vf_blessed_ok(&e, 0.5, NAN));
    ck_assert(vf_blessed_ok(&e, NAN, 1e9)); /* not gated */
    e.value = NAN;
    ck_assert(vf_blessed_ok(&e, 0.5, INFINITY));
}
END_TEST

/* The gate cannot be skipped: a suite run against a baselines directory that has no file for it
 * fails (check "baseline", naming the file and how to bless it); the explicit bless creates the
 * file, and then the suite passes. */
START_TEST(test_missing_baseline_fails)
{
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_ge(run_toy(&d, d.bl, 0), 1);
    const char *out = slurp(d.out);
    ck_assert_msg(strstr(out, "FAIL toy.baseline:"), "no FAIL line for the missing file:\n%s", out);
    ck_assert_msg(strstr(out, "toy.fast.json"), "the message names no file:\n%s", out);
    char path[600];
    vf_baseline_path(path, sizeof path, d.bl, "toy", 1);
    ck_assert_int_ne(access(path, F_OK), 0); /* a plain run creates nothing */
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    ck_assert_int_eq(access(path, F_OK), 0);
    ck_assert_msg(strstr(slurp(d.out), "created"), "%s", slurp(d.out));
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 0);
    /* without a gate (no baselines directory, --no-baselines) nothing is required */
    ck_assert_int_eq(run_toy(&d, NULL, 0), 0);
}
END_TEST

/* A NaN anywhere fails the check that holds it: one NaN among the accumulated errors (vf_worst,
 * where fmax would drop it and pass), a NaN reference, a NaN measured value. */
START_TEST(test_nan_fails_its_check)
{
    ck_assert(isnan(vf_worst(0, NAN)));
    ck_assert(isnan(vf_worst(NAN, 1)));
    ck_assert(isnan(vf_least(INFINITY, NAN)));
    ck_assert(isnan(vf_least(NAN, -1)));
    ck_assert_double_eq(vf_worst(1, 2), 2);
    ck_assert_double_eq(vf_worst(2, 1), 2);
    ck_assert_double_eq(vf_least(1, 2), 1);
    ck_assert_double_eq(vf_worst(-INFINITY, -3), -3);
    dirs_t d;
    make_dirs(&d);
    ck_assert_int_eq(run_toy(&d, d.bl, 1), 0);
    g_errs[1] = NAN; /* the middle one: neither the first nor the last value of the sweep */
    ck_assert_int_eq(run_toy(&d, d.bl, 0), 1);
    ck_assert_msg(strstr(slurp(d.out), "FAIL toy.worst_c:"), "%s", slurp(d.out));
    /* a blessed NaN would match a NaN on the gate, but the physics check still fails */
    ck_assert_int_ge(run_toy(&d, d.bl, 1), 1);
    ck_assert_msg(strstr(slurp(d.out), "bless toy: refused"), "%s", slurp(d.out));
    vf_options opt = {.reports_dir = d.reports};
    vf_ctx *ctx = calloc(1, sizeof *ctx);
    ck_assert_ptr_nonnull(ctx);
    ctx->suite = &toy;
    ctx->opt = &opt;
    /* the FAIL lines go to a file, not to the test log (tools/mutate.sh reads FAIL lines there) */
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    FILE *f = fopen(d.out, "w");
    ck_assert_ptr_nonnull(f);
    dup2(fileno(f), STDOUT_FILENO);
    ck_assert_int_eq(vf_check(ctx, "nan_ref", "NaN reference", "-", NAN, 1.0, 0.1, VF_REL), 0);
    ck_assert_int_eq(vf_check(ctx, "nan_ref_abs", "NaN reference", "-", NAN, 1.0, 0.1, VF_ABS), 0);
    ck_assert_int_eq(vf_check(ctx, "nan_value", "NaN value", "-", 0, NAN, 0.1, VF_MAX), 0);
    ck_assert_int_eq(vf_check(ctx, "nan_tol", "NaN tolerance", "-", 0, 0, NAN, VF_MAX), 0);
    ck_assert_int_eq(vf_check(ctx, "finite", "a passing row", "-", 1, 1.0, 0.1, VF_REL), 1);
    fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    fclose(f);
    ck_assert_int_eq(ctx->nfail, 4);
    free(ctx->rows);
    free(ctx);
}
END_TEST

/* The configuration: this process against itself, another thread count, another FFTW. */
START_TEST(test_configuration)
{
    vf_config a, b;
    vf_config_current(&a);
    b = a;
    ck_assert(a.threads >= 1);
    ck_assert(vf_config_same(&a, &b));
    b.threads++;
    ck_assert(!vf_config_same(&a, &b));
    b = a;
    b.fftw[0] ^= 1;
    ck_assert(!vf_config_same(&a, &b));
}
END_TEST

Suite *suite_baselines(void);
Suite *suite_baselines(void)
{
    Suite *s = suite_create("baselines");
    TCase *tc = tcase_create("gate");
    tcase_add_test(tc, test_drift_fails_naming_check);
    tcase_add_test(tc, test_bless_restores_passing_state);
    tcase_add_test(tc, test_missing_and_new_checks);
    tcase_add_test(tc, test_bless_refused_on_physics_failure);
    tcase_add_test(tc, test_iteration_tier);
    tcase_add_test(tc, test_noise_tier_by_pattern);
    tcase_add_test(tc, test_variant_files);
    tcase_add_test(tc, test_tiers);
    tcase_add_test(tc, test_configuration);
    tcase_add_test(tc, test_missing_baseline_fails);
    tcase_add_test(tc, test_nan_fails_its_check);
    suite_add_tcase(s, tc);
    return s;
}
