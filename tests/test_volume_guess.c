/* test_volume_guess.c - the lubricant volume equilibrium started from a guess of the root
 * (lube/volume.h p_lub_guess, slope_guess; used by the elastic-plastic loop's contact steps):
 * the same regime and a root within the tolerance of the cold start's, in fewer contact solves
 * when the guess is the last root of a slightly changed problem; a far guess and a guess in a
 * dry problem end where the cold start does. */
#include <math.h>
#include <string.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "lube/volume.h"
#include "test_util.h"

/* A rough flat (Sq 0.3 um, smoothed random heights) of 32 x 32 cells of 0.8 um, free edges,
 * steel on steel, under 1 GPa nominal. */
static const double E_STAR = 115.4e9, SQ = 0.3e-6, P_NOM = 1e9, DX = 0.8e-6;
#define N 32
/* contact solves to 1e-11 (gap scale): V exact far below the root's tolerance */
#define CT 1e-11
#define ROOT_TOL MC_VOLUME_TOL_DEFAULT
/* Two roots each within ROOT_TOL V* of V*, V increasing with slope ~ s near the root: they are
 * within 2 ROOT_TOL V* / s; the slope varies over that interval by far less than a factor 2. */
#define ROOT_AGREE (4.0 * ROOT_TOL)

typedef struct {
    mc_grid g;
    size_t n;
    double *h, *bump;
    double load;
    mc_operator *K;
    mc_contact_solver *s;
} patch;

static void make_patch(patch *pt)
{
    pt->g = (mc_grid){N, N, DX, DX, 0, 0};
    pt->n = mc_grid_cells(&pt->g);
    pt->h = mc_zeros(pt->n);
    pt->bump = mc_zeros(pt->n);
    ck_assert(pt->h && pt->bump);
    test_smooth_rough_gap(pt->h, N, SQ, 20261124ULL);
    /* a residual dent of up to 5 nm under the highest asperities: the change between two outer
     * iterations of the elastic-plastic loop */
    double hmin = INFINITY;
    for (size_t i = 0; i < pt->n; i++)
        hmin = fmin(hmin, pt->h[i]);
    for (size_t i = 0; i < pt->n; i++)
        pt->bump[i] = 5e-9 * exp(-(pt->h[i] - hmin) / (0.2 * SQ));
    pt->load = P_NOM * (double)pt->n * DX * DX;
    mc_error err = {0};
    ck_assert_msg(mc_operator_plan_love(&pt->g, E_STAR, MC_BACKEND_FFT, &pt->K, &err) == MC_OK,
                  "%s", err.msg);
    mc_contact_options opt = {.method = MC_METHOD_CG, .tolerance = CT, .max_iterations = 20000};
    ck_assert_msg(mc_contact_create(pt->K, &opt, &pt->s, &err) == MC_OK, "%s", err.msg);
}

static void free_patch(patch *pt)
{
    mc_contact_destroy(&pt->s);
    mc_operator_destroy(&pt->K);
    mc_free(pt->h);
    mc_free(pt->bump);
}

/* Solve prob into r (fields in scratch). */
static void solve(patch *pt, const mc_volume_problem *prob, mc_volume_result *r)
{
    double *p = mc_zeros(pt->n), *gap = mc_zeros(pt->n);
    ck_assert(p && gap);
    mc_error err = {0};
    ck_assert_msg(mc_volume_equilibrium(pt->s, pt->K, prob, p, NULL, gap, r, &err) == MC_OK, "%s",
                  err.msg);
    ck_assert(r->converged);
    mc_free(p);
    mc_free(gap);
}

START_TEST(guess_mixed)
{
    patch pt;
    make_patch(&pt);
    /* a film between V(0) and V(p_nominal): the mixed regime */
    mc_volume_problem prob = {.h = pt.h, .load = pt.load, .h_target = 0, .tolerance = ROOT_TOL};
    mc_volume_result first;
    solve(&pt, &prob, &first); /* V* = 0: dry, gives V(0) */
    const double a_nom = (double)pt.n * DX * DX;
    prob.h_target = 0.5 * (first.v_dry + first.v_onset) / a_nom;
    solve(&pt, &prob, &first);
    ck_assert_int_eq(first.regime, MC_REGIME_MIXED);
    ck_assert(first.slope > 0);
    /* the changed problem, cold and from the first root */
    prob.h_extra = pt.bump;
    mc_volume_result cold, warm, far;
    solve(&pt, &prob, &cold);
    mc_volume_problem guessed = prob;
    guessed.p_lub_guess = first.p_lub;
    guessed.slope_guess = first.slope;
    solve(&pt, &guessed, &warm);
    ck_assert_int_eq(cold.regime, MC_REGIME_MIXED);
    ck_assert_int_eq(warm.regime, MC_REGIME_MIXED);
    ck_assert(warm.rel_error <= ROOT_TOL);
    const double dp = fabs(warm.p_lub - cold.p_lub) * cold.slope / cold.v_target;
    ck_assert_msg(dp <= ROOT_AGREE, "roots %.9g and %.9g Pa: %g V*", cold.p_lub, warm.p_lub, dp);
    ck_assert_msg(warm.solves < cold.solves, "%d solves from the guess, %d cold", warm.solves,
                  cold.solves);
    /* a guess far below the root, with a slope ten times too steep: small steps, doubled */
    guessed.p_lub_guess = 0.02 * cold.p_lub;
    guessed.slope_guess = 10 * first.slope;
    solve(&pt, &guessed, &far);
    ck_assert_int_eq(far.regime, MC_REGIME_MIXED);
    const double dfar = fabs(far.p_lub - cold.p_lub) * cold.slope / cold.v_target;
    ck_assert_msg(dfar <= ROOT_AGREE, "far guess: roots %.9g and %.9g Pa", cold.p_lub, far.p_lub);
    free_patch(&pt);
}
END_TEST

/* One solve at the guess (one_solve, the joint iteration's secant steps, theory.md §9.8): exactly
 * one contact solve, the state at the guess whether or not it meets the tolerance (converged says
 * which), and secant steps p - (V - V*) / s of one solve each from the last root of the unchanged
 * problem reach the cold root of the changed one within ROOT_AGREE in a few steps; a guess outside
 * (0, p_nominal) is refused. */
START_TEST(one_solve_steps)
{
    patch pt;
    make_patch(&pt);
    mc_volume_problem prob = {.h = pt.h, .load = pt.load, .h_target = 0, .tolerance = ROOT_TOL};
    mc_volume_result first, cold;
    solve(&pt, &prob, &first);
    const double a_nom = (double)pt.n * DX * DX;
    prob.h_target = 0.5 * (first.v_dry + first.v_onset) / a_nom;
    solve(&pt, &prob, &first);
    ck_assert_int_eq(first.regime, MC_REGIME_MIXED);
    prob.h_extra = pt.bump;
    solve(&pt, &prob, &cold);
    double *p = mc_zeros(pt.n), *gap = mc_zeros(pt.n);
    ck_assert(p && gap);
    mc_volume_problem one = prob;
    one.one_solve = 1;
    one.p_lub_guess = first.p_lub;
    one.slope_guess = first.slope;
    mc_error err = {0};
    int settled_at = 0;
    mc_volume_result r = {0};
    for (int k = 1; k <= 6 && !settled_at; k++) {
        ck_assert_msg(mc_volume_equilibrium(pt.s, pt.K, &one, p, NULL, gap, &r, &err) == MC_OK,
                      "%s", err.msg);
        ck_assert_int_eq(r.solves, 1);
        ck_assert(r.p_lub == one.p_lub_guess);
        ck_assert_int_eq(r.regime, MC_REGIME_MIXED);
        double v = 0;
        for (size_t i = 0; i < pt.n; i++)
            v += gap[i] * DX * DX;
        ck_assert(fabs(r.rel_error - fabs(v - r.v_target) / r.v_target) <= 1e-12);
        ck_assert_int_eq(r.converged, r.rel_error <= ROOT_TOL);
        if (r.converged)
            settled_at = k;
        one.p_lub_guess = r.p_lub - (r.volume - r.v_target) / first.slope;
        one.p_start = p;
    }
    ck_assert_msg(settled_at >= 2 && settled_at <= 4, "settled after %d one-solve steps",
                  settled_at);
    const double dp = fabs(r.p_lub - cold.p_lub) * cold.slope / cold.v_target;
    ck_assert_msg(dp <= ROOT_AGREE, "roots %.9g and %.9g Pa: %g V*", cold.p_lub, r.p_lub, dp);
    one.p_lub_guess = 1.5 * r.p_nominal;
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &one, p, NULL, gap, &r, &err),
                     MC_ERR_INPUT);
    one.p_lub_guess = 0.0;
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &one, p, NULL, gap, &r, &err),
                     MC_ERR_INPUT);
    mc_free(p);
    mc_free(gap);
    free_patch(&pt);
}
END_TEST

/* A film below V(0): dry from the cold start, and from a guess in the middle of the range. */
START_TEST(guess_dry)
{
    patch pt;
    make_patch(&pt);
    mc_volume_problem prob = {.h = pt.h, .load = pt.load, .h_target = 0, .tolerance = ROOT_TOL};
    mc_volume_result probe, cold, warm;
    solve(&pt, &prob, &probe);
    const double a_nom = (double)pt.n * DX * DX;
    prob.h_target = 0.9 * probe.v_dry / a_nom;
    solve(&pt, &prob, &cold);
    ck_assert_int_eq(cold.regime, MC_REGIME_DRY);
    prob.p_lub_guess = 0.5 * P_NOM;
    prob.slope_guess = (probe.v_onset - probe.v_dry) / P_NOM; /* the mean slope */
    solve(&pt, &prob, &warm);
    ck_assert_int_eq(warm.regime, MC_REGIME_DRY);
    ck_assert(warm.p_lub == 0.0);
    free_patch(&pt);
}
END_TEST

Suite *suite_volume_guess(void);
Suite *suite_volume_guess(void)
{
    Suite *s = suite_create("volume_guess");
    TCase *t = tcase_create("guess");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, guess_mixed);
    tcase_add_test(t, guess_dry);
    tcase_add_test(t, one_solve_steps);
    suite_add_tcase(s, t);
    return s;
}
