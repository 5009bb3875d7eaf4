/* test_plans.c - planner rigor of the repeated transforms and stored FFTW wisdom ([solver] plans,
 * operator.h "planner rigor and stored wisdom"): the default (estimate) gives the same bits on
 * every run, also after a scope that measured; measure gives the estimate results to round-off;
 * a wisdom file is written at the end of its scope, read at the next start and makes planning
 * faster; a file that is not wisdom, or wisdom without a file, is refused. */
#include <check.h>
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "core/threads.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "test_util.h"

static const double ESTAR = 1.15e11; /* steel on steel, Pa */

/* Measured plans run other FFT algorithms than the estimate ones: the same transform up to
 * round-off, eps log2(N) ~ 1e-14 relative for these sizes; the contact solve stops on its own
 * tolerance 1e-10, and its iterates differ by round-off only, so 1e-9 of the pressure's scale
 * bounds both with room. */
#define TOL_PLANS_APPLY 1e-12
#define TOL_PLANS_SOLVE 1e-9
/* Planning from wisdom read back must be clearly faster than measuring: measuring runs every
 * candidate algorithm (here ~10-100x the estimate planning); 2x leaves room for a busy machine. */
#define WISDOM_SPEEDUP_MIN 2.0

/* u = K f on grid g with the Love operator planned under the rigor in force; the seconds the
 * planning took in *plan_s (if not NULL). */
static void love_apply(const mc_grid *g, const double *f, double *u, double *plan_s)
{
    mc_error err = {0};
    mc_operator *op = NULL;
    const double t0 = mc_clock();
    ck_assert_msg(mc_operator_plan_love(g, ESTAR, MC_BACKEND_FFT, &op, &err) == MC_OK, "%s",
                  err.msg);
    if (plan_s)
        *plan_s = mc_clock() - t0;
    mc_operator_apply(op, f, u);
    mc_operator_destroy(&op);
}

/* A Hertz-like contact (paraboloid gap, force control, cg with the coarse start, box solve and
 * preconditioner: every repeated transform of the contact path) on an n x n grid. */
static void hertz_solve(int n, double *p)
{
    const double dx = 2e-6, R = 5e-3;
    const mc_grid g = {n, n, dx, dx, 0, 0};
    double *h = mc_zeros((size_t)n * n);
    ck_assert_ptr_nonnull(h);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const double x = (i - 0.5 * (n - 1)) * dx, y = (j - 0.5 * (n - 1)) * dx;
            h[(size_t)j * n + i] = (x * x + y * y) / (2 * R);
        }
    mc_error err = {0};
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    ck_assert_msg(mc_operator_plan_love(&g, ESTAR, MC_BACKEND_FFT, &K, &err) == MC_OK, "%s",
                  err.msg);
    const mc_contact_options opt = {MC_METHOD_CG, 1e-10, 2000, ESTAR, 0};
    ck_assert_msg(mc_contact_create(K, &opt, &s, &err) == MC_OK, "%s", err.msg);
    const mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                                     .load = 0.05};
    mc_contact_summary sum;
    ck_assert_msg(mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err) == MC_OK, "%s", err.msg);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
}

/* A padded-size r2c plan under the rigor in force, as FFTW describes it (caller frees). */
static char *plan_text(int tx, int ty)
{
    double *r = fftw_alloc_real((size_t)tx * ty);
    fftw_complex *c = fftw_alloc_complex((size_t)ty * (tx / 2 + 1));
    ck_assert(mc_fftw_prepare(NULL) == MC_OK);
    fftw_plan pl = fftw_plan_dft_r2c_2d(ty, tx, r, c, mc_fft_plan_flags());
    ck_assert_ptr_nonnull(pl);
    char *text = fftw_sprint_plan(pl);
    fftw_destroy_plan(pl);
    fftw_free(r);
    fftw_free(c);
    return text;
}

/* The default: estimate twice gives the same plan and the same bits; a measuring scope gives the
 * same results to round-off, and after its end estimate gives the first bits and plan again. */
START_TEST(estimate_deterministic_after_measure)
{
    ck_assert_int_eq(mc_fft_plan_rigor(), MC_PLANS_ESTIMATE);
    ck_assert_uint_eq(mc_fft_plan_flags(), FFTW_ESTIMATE);
    const mc_grid free_g = {96, 80, 1e-6, 1.2e-6, 0, 0}, per_g = {96, 80, 1e-6, 1.2e-6, 1, 1};
    const mc_grid *grids[2] = {&free_g, &per_g}; /* pruned and plain 2-D transforms */
    const size_t n = mc_grid_cells(&free_g), ns = 100 * 100;
    double *f = mc_zeros(n), *u0[2], *u1 = mc_zeros(n), *um = mc_zeros(n);
    double *p0 = mc_zeros(ns), *p1 = mc_zeros(ns), *pm = mc_zeros(ns);
    test_random_field(f, n, 13);
    for (int k = 0; k < 2; k++) {
        u0[k] = mc_zeros(n);
        love_apply(grids[k], f, u0[k], NULL);
        love_apply(grids[k], f, u1, NULL);
        ck_assert_msg(!memcmp(u0[k], u1, n * sizeof *u1), "grid %d: estimate twice differs", k);
    }
    hertz_solve(100, p0);
    hertz_solve(100, p1);
    ck_assert_msg(!memcmp(p0, p1, ns * sizeof *p0), "contact: estimate twice differs");
    char *plan0 = plan_text(192, 160);

    mc_error err = {0};
    mc_fft_plans_scope sc;
    ck_assert_int_eq(mc_fft_plans_begin(MC_PLANS_MEASURE, NULL, &sc, &err), MC_OK);
    ck_assert_uint_eq(mc_fft_plan_flags(), FFTW_MEASURE);
    for (int k = 0; k < 2; k++) {
        love_apply(grids[k], f, um, NULL);
        const double d = test_rel_maxdiff(um, u0[k], n);
        ck_assert_msg(d <= TOL_PLANS_APPLY, "grid %d: measure vs estimate %.3g", k, d);
    }
    hertz_solve(100, pm);
    const double dp = test_rel_maxdiff(pm, p0, ns);
    ck_assert_msg(dp <= TOL_PLANS_SOLVE, "contact: measure vs estimate %.3g", dp);
    char *planm = plan_text(192, 160);
    ck_assert_int_eq(mc_fft_plans_end(&sc, &err), MC_OK);
    ck_assert_int_eq(mc_fft_plan_rigor(), MC_PLANS_ESTIMATE);

    /* estimate again: the plan and the bits of before the scope */
    char *plan1 = plan_text(192, 160);
    ck_assert_msg(!strcmp(plan0, plan1), "estimate plan changed after measuring:\n%s\n%s", plan0,
                  plan1);
    for (int k = 0; k < 2; k++) {
        love_apply(grids[k], f, u1, NULL);
        ck_assert_msg(!memcmp(u0[k], u1, n * sizeof *u1), "grid %d: estimate after measure "
                      "differs (%.3g)", k, test_rel_maxdiff(u1, u0[k], n));
    }
    hertz_solve(100, p1);
    ck_assert_msg(!memcmp(p0, p1, ns * sizeof *p0), "contact: estimate after measure differs "
                  "(%.3g)", test_rel_maxdiff(p1, p0, ns));
    /* information: whether measuring chose another plan here (it need not) */
    if (!strcmp(plan0, planm))
        fprintf(stderr, "test_plans: measure chose the estimate plan for 192 x 160\n");
    fftw_free(plan0);
    fftw_free(plan1);
    fftw_free(planm);
    for (int k = 0; k < 2; k++)
        mc_free(u0[k]);
    mc_free(f);
    mc_free(u1);
    mc_free(um);
    mc_free(p0);
    mc_free(p1);
    mc_free(pm);
}
END_TEST

/* Wisdom: the first scope measures and writes the file (atomically: no temporary left), the
 * second reads it and plans faster; results equal the estimate ones to round-off. */
START_TEST(wisdom_written_and_reused)
{
    const mc_grid g = {200, 180, 1e-6, 1e-6, 0, 0};
    const size_t n = mc_grid_cells(&g);
    double *f = mc_zeros(n), *ref = mc_zeros(n), *u = mc_zeros(n);
    test_random_field(f, n, 21);
    love_apply(&g, f, ref, NULL);
    char dir[512], path[600];
    snprintf(dir, sizeof dir, "%s/plans", test_tmpdir());
    snprintf(path, sizeof path, "%s/wisdom.fftw", dir);
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", dir, dir);
    ck_assert_int_eq(system(cmd), 0);
    double plan_s[2];
    for (int pass = 0; pass < 2; pass++) { /* pass 0 measures and writes, pass 1 reads */
        mc_error err = {0};
        mc_fft_plans_scope sc;
        ck_assert_int_eq(mc_fft_plans_begin(MC_PLANS_WISDOM, path, &sc, &err), MC_OK);
        ck_assert_uint_eq(mc_fft_plan_flags(), FFTW_MEASURE);
        love_apply(&g, f, u, &plan_s[pass]);
        const double d = test_rel_maxdiff(u, ref, n);
        ck_assert_msg(d <= TOL_PLANS_APPLY, "pass %d: wisdom vs estimate %.3g", pass, d);
        ck_assert_int_eq(mc_fft_plans_end(&sc, &err), MC_OK);
        ck_assert_int_eq(mc_fft_plan_rigor(), MC_PLANS_ESTIMATE);
        FILE *w = fopen(path, "r");
        ck_assert_msg(w != NULL, "pass %d: no wisdom written", pass);
        char head[32] = {0};
        ck_assert(fgets(head, sizeof head, w) != NULL);
        fclose(w);
        ck_assert_msg(strncmp(head, "(fftw-3", 7) == 0, "not FFTW wisdom: %s", head);
        snprintf(cmd, sizeof cmd, "test $(ls -A '%s' | wc -l) -eq 1", dir);
        ck_assert_msg(system(cmd) == 0, "pass %d: a temporary file was left beside the wisdom",
                      pass);
    }
    fprintf(stderr, "test_plans: planning 200 x 180 with measure %.4f s, from wisdom %.4f s\n",
            plan_s[0], plan_s[1]);
    ck_assert_msg(plan_s[1] * WISDOM_SPEEDUP_MIN <= plan_s[0],
                  "planning from wisdom %.4f s, measuring %.4f s", plan_s[1], plan_s[0]);
    /* the estimate default again, after the scopes */
    love_apply(&g, f, u, NULL);
    ck_assert_msg(!memcmp(u, ref, n * sizeof *u), "estimate after wisdom differs");
    mc_free(f);
    mc_free(ref);
    mc_free(u);
}
END_TEST

/* Refusals: wisdom without a file; a file that is not wisdom (named, left as it was, the rigor
 * unchanged, nothing imported); an unknown rigor. */
START_TEST(wisdom_refusals)
{
    mc_error err = {0};
    mc_fft_plans_scope sc;
    ck_assert_int_eq(mc_fft_plans_begin(MC_PLANS_WISDOM, NULL, &sc, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_fft_plans_begin(MC_PLANS_WISDOM, "", &sc, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "wisdom_file"));
    ck_assert_int_eq(mc_fft_plans_begin((mc_plan_rigor)7, NULL, &sc, &err), MC_ERR_INPUT);
    char path[600];
    snprintf(path, sizeof path, "%s/not_wisdom.txt", test_tmpdir());
    FILE *w = fopen(path, "w");
    ck_assert_ptr_nonnull(w);
    fputs("1 2 3\n", w);
    fclose(w);
    ck_assert_int_eq(mc_fft_plans_begin(MC_PLANS_WISDOM, path, &sc, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, path) && strstr(err.msg, "not FFTW wisdom"), "%s", err.msg);
    ck_assert_int_eq(mc_fft_plan_rigor(), MC_PLANS_ESTIMATE);
    w = fopen(path, "r");
    char line[16] = {0};
    ck_assert(fgets(line, sizeof line, w) != NULL);
    fclose(w);
    ck_assert_str_eq(line, "1 2 3\n");
}
END_TEST

Suite *suite_plans(void);
Suite *suite_plans(void)
{
    Suite *s = suite_create("plans");
    TCase *tc = tcase_create("plans");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, estimate_deterministic_after_measure);
    tcase_add_test(tc, wisdom_written_and_reused);
    tcase_add_test(tc, wisdom_refusals);
    suite_add_tcase(s, tc);
    return s;
}
