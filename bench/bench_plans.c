/* bench_plans.c - [solver] plans (issue 13 item 5): what FFTW_MEASURE costs when planning and
 * gains per application, and what planning from stored wisdom costs, for the Love operator and
 * a whole Hertz solve (operator, solver, solve: the preconditioner and box plans included) at
 * 256² and 1024²; and that the default (estimate) gives the same bits after scopes that measured.
 * A measurement: no target. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "contact/contact.h"
#include "core/alloc.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"

#define PL_RADIUS 10e-3                  /* sphere radius, m */
#define PL_ESTAR (210e9 / (2 * (1 - 0.09))) /* steel on steel (E 210 GPa, nu 0.3), Pa */
#define PL_FORCE 100.0                   /* N: Hertz a = 186.6 um */
#define PL_A 186.6e-6                    /* contact radius, m: the grid's side is 3a */

typedef struct {
    double plan, apply, create, solve; /* s: operator planning, one application (median),
                                          solver creation, the solve */
} plan_cost;

typedef struct {
    mc_operator *op;
    const double *in;
    double *out;
} apply_arg;

static void do_apply(void *a)
{
    apply_arg *x = a;
    mc_operator_apply(x->op, x->in, x->out);
}

/* One Hertz case on an N x N grid under the rigor in force: the costs in *c, the pressure in p
 * (N*N, may be NULL). MC_OK or the failing call's status. */
static int hertz_costs(int N, int reps, plan_cost *c, double *p_out)
{
    const double dx = 3 * PL_A / N;
    const mc_grid g = {N, N, dx, dx, 0, 0};
    const size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *p = mc_zeros(n), *u = mc_zeros(n);
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    mc_error err = {0};
    int rc = MC_ERR_NOMEM;
    if (!h || !p || !u)
        goto out;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            const double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            h[(size_t)j * N + i] = (x * x + y * y) / (2 * PL_RADIUS);
        }
    double t0 = mc_clock();
    if ((rc = mc_operator_plan_love(&g, PL_ESTAR, MC_BACKEND_FFT, &K, &err)))
        goto out;
    c->plan = mc_clock() - t0;
    apply_arg a = {K, h, u};
    c->apply = mc_bench_time(do_apply, &a, reps);
    const mc_contact_options opt = {MC_METHOD_CG, 1e-8, 2000, PL_ESTAR, 0};
    t0 = mc_clock();
    if ((rc = mc_contact_create(K, &opt, &s, &err)))
        goto out;
    c->create = mc_clock() - t0;
    const mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                                     .load = PL_FORCE};
    mc_contact_summary sum;
    t0 = mc_clock();
    rc = mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err);
    c->solve = mc_clock() - t0;
    if (p_out)
        memcpy(p_out, p, n * sizeof *p);
out:
    if (rc != MC_OK)
        fprintf(stderr, "bench plans: %s\n", err.msg);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
    mc_free(p);
    mc_free(u);
    return rc;
}

/* hertz_costs inside a plans scope of rigor r (wisdom file w for MC_PLANS_WISDOM). */
static int scoped(mc_plan_rigor r, const char *w, int N, int reps, plan_cost *c)
{
    mc_fft_plans_scope sc;
    mc_error err = {0};
    int rc = mc_fft_plans_begin(r, w, &sc, &err);
    if (rc != MC_OK) {
        fprintf(stderr, "bench plans: %s\n", err.msg);
        return rc;
    }
    rc = hertz_costs(N, reps, c, NULL);
    if (mc_fft_plans_end(&sc, &err) != MC_OK) {
        fprintf(stderr, "bench plans: %s\n", err.msg);
        rc = rc ? rc : MC_ERR_ENV;
    }
    return rc;
}

int mc_bench_plans(vf_ctx *ctx, int quick)
{
    static const int sizes[] = {256, 1024};
    const int nsizes = quick ? 1 : 2;
    char dir[] = "/tmp/mc_bench_plans_XXXXXX", wisdom[64];
    if (!mkdtemp(dir))
        return 1;
    snprintf(wisdom, sizeof wisdom, "%s/wisdom.fftw", dir);
    vf_text(ctx, "## Stored FFTW wisdom ([solver] plans)\n\n"
                 "The Hertz point case (steel, %.0f N, side 3a) planned and solved with each "
                 "rigor of [solver] plans: estimate (the default: no trial runs, the same plan "
                 "and bits on every run), measure (FFTW times candidate algorithms while "
                 "planning), and wisdom read from the file an earlier run wrote (that first run "
                 "measures and stores). Operator planning: the Love operator's table, spectrum "
                 "and transforms; one application: median of repeated calls; solver creation "
                 "and solve include the preconditioner's and the box's plans, made with the same "
                 "rigor. Times in s, the run's default threads; one run per row (planning "
                 "happens once).\n\n"
                 "| N | rigor | operator planning | one application | solver creation | solve | "
                 "plan + create + solve |\n|---|---|---|---|---|---|---|\n",
            PL_FORCE);
    FILE *f = vf_open(ctx, "plans.csv");
    if (f)
        fprintf(f, "N,rigor,plan_s,apply_s,create_s,solve_s\n");
    int deterministic = 1, failed = 0;
    for (int k = 0; k < nsizes; k++) {
        const int N = sizes[k], reps = N >= 1024 ? 9 : 31;
        const size_t n = (size_t)N * N;
        double *p_ref = mc_zeros(n), *p_again = mc_zeros(n);
        plan_cost est, mea, wis, first;
        remove(wisdom);
        int rc = hertz_costs(N, reps, &est, p_ref);
        rc = rc ? rc : scoped(MC_PLANS_MEASURE, NULL, N, reps, &mea);
        rc = rc ? rc : scoped(MC_PLANS_WISDOM, wisdom, N, reps, &first); /* measures, stores */
        rc = rc ? rc : scoped(MC_PLANS_WISDOM, wisdom, N, reps, &wis);   /* reads */
        /* estimate again after the scopes that measured: the same bits */
        rc = rc ? rc : hertz_costs(N, reps, &first, p_again);
        if (rc != MC_OK || !p_ref || !p_again) {
            failed = 1;
            mc_free(p_ref);
            mc_free(p_again);
            break;
        }
        deterministic &= !memcmp(p_ref, p_again, n * sizeof *p_ref);
        const plan_cost *rows[] = {&est, &mea, &wis};
        const char *names[] = {"estimate", "measure", "wisdom (read)"};
        for (int q = 0; q < 3; q++) {
            const plan_cost *x = rows[q];
            vf_text(ctx, "| %d² | %s | %.4f | %.5f | %.4f | %.4f | %.4f |\n", N, names[q], x->plan,
                    x->apply, x->create, x->solve, x->plan + x->create + x->solve);
            if (f)
                fprintf(f, "%d,%s,%.6g,%.6g,%.6g,%.6g\n", N, names[q], x->plan, x->apply,
                        x->create, x->solve);
        }
        char id[64], q[200];
        snprintf(id, sizeof id, "plans_apply_gain_%d", N);
        snprintf(q, sizeof q, "%d²: one operator application, 1 - measured / estimate", N);
        vf_info(ctx, id, q, "fraction of the estimate plan's time saved per apply", NAN,
                1 - mea.apply / est.apply);
        vf_regress(ctx, id, VF_TIER_NONE);
        snprintf(id, sizeof id, "plans_measure_cost_%d_s", N);
        snprintf(q, sizeof q, "%d²: planning cost of measure over estimate (operator + solver, s)",
                 N);
        vf_info(ctx, id, q, "once per run; once per size with plans = wisdom", NAN,
                mea.plan + mea.create - est.plan - est.create);
        vf_regress(ctx, id, VF_TIER_NONE);
        snprintf(id, sizeof id, "plans_wisdom_ratio_%d", N);
        snprintf(q, sizeof q, "%d²: plan + create + solve, wisdom read / estimate", N);
        vf_info(ctx, id, q, "< 1: stored wisdom pays", NAN,
                (wis.plan + wis.create + wis.solve) / (est.plan + est.create + est.solve));
        vf_regress(ctx, id, VF_TIER_NONE);
        mc_free(p_ref);
        mc_free(p_again);
    }
    if (f)
        vf_close(ctx, f);
    vf_text(ctx, "\nThe pipeline applies [solver] plans for the duration of a run "
                 "(mc_fft_plans_begin / mc_fft_plans_end, operator.h): the repeated transforms "
                 "(the operator's and stress engine's padded FFTs, the preconditioner's, the "
                 "stress quadrant r2r, the eigenstrain operators') follow it; one-shot ones "
                 "(kernel spectra, table set-up) stay FFTW_ESTIMATE. A scope that measured "
                 "forgets its wisdom at its end, so later estimate plans of the process are the "
                 "default's again (row below).\n\n");
    vf_check(ctx, "plans_default_deterministic",
             "estimate solves before and after scopes that measured: bitwise equal pressure "
             "(1 = yes)",
             "the default stays deterministic (issue 13)", 1, failed ? NAN : deterministic, 0,
             VF_ABS);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        vf_text(ctx, "(could not remove %s)\n", dir);
    return failed;
}
