/* test_plastic_loop.c - the inexact inner solves of the elastic-plastic loop (plastic/loop.h,
 * docs/theory.md §9.4): the loop with inexact plastic fixed points converges to the state of the
 * loop that solves every fixed point to tol_plastic (within the outer tolerance), with fewer
 * sweeps; an outer iteration is never accepted on a loosely solved fixed point; and operators
 * built once (mc_plastic_ops) and lent to several runs give the bits of a run that builds its
 * own, and are refused by a problem they were not made for. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "core/threads.h"
#include "kernels/kernel.h"
#include "lube/volume.h"
#include "operator/operator.h"
#include "pipeline/stage_lube.h"
#include "plastic/hardening.h"
#include "plastic/loop.h"
#include "stress/stress.h"
#include "surface/surface.h"
#include "test_util.h"

/* Kogut-Etsion's sphere (R = 15 mm, E = 210 GPa, nu = 0.3, elastic-perfectly plastic Y = 1 GPa,
 * P_c = 91.96 N; docs/theory.md §9.3) on a rigid flat at 4 P_c in two load steps, 16 x 16 cells
 * of 40 um with 6 layers: small enough for a unit test, plastic enough (a_c ~ 165 um: the
 * plastic zone spans a few cells and layers) that the fixed point takes tens of sweeps. */
typedef struct {
    mc_grid g;
    double *h, *p, *u, *gap;
    mc_operator *K;
    mc_contact_solver *s;
    mc_hardening law;
    mc_plastic_problem pb;
} sphere;

/* The sphere on n x n cells of dx with nz layers of dx. */
static void sphere_init_size(sphere *t, int n_side, double dx, int nz)
{
    memset(t, 0, sizeof *t);
    t->g = (mc_grid){.nx = n_side, .ny = n_side, .dx = dx, .dy = dx};
    const size_t n = mc_grid_cells(&t->g);
    t->h = mc_zeros(n);
    t->p = mc_zeros(n);
    t->u = mc_zeros(n);
    t->gap = mc_zeros(n);
    ck_assert(t->h && t->p && t->u && t->gap);
    mc_shape_spec shape = {.shape = MC_SHAPE_SPHERE, .radius = 15e-3};
    mc_surface_shape(&t->g, &shape, t->h);
    mc_error err = {0};
    const double estar = mc_combined_modulus(210e9, 0.3, 0, 0, 1);
    ck_assert_int_eq(mc_operator_plan_love(&t->g, estar, MC_BACKEND_FFT, &t->K, &err), MC_OK);
    mc_contact_options o = {.method = MC_METHOD_CG, .tolerance = 1e-10, .max_iterations = 5000};
    ck_assert_int_eq(mc_contact_create(t->K, &o, &t->s, &err), MC_OK);
    ck_assert_int_eq(mc_hardening_perfect(1e9, &t->law, &err), MC_OK);
    t->pb = (mc_plastic_problem){.h = t->h, .load = 4 * 91.96, .load_steps = 2, .E = 210e9,
                                 .nu = 0.3, .law = &t->law,
                                 .volume = mc_eigen_volume_full(&t->g, nz, dx),
                                 .backend = MC_BACKEND_FFT, .relaxation = 0.7, .tol_outer = 1e-3,
                                 .max_outer = 30, .tol_plastic = 1e-4, .max_plastic = 200};
}

static void sphere_init(sphere *t) { sphere_init_size(t, 16, 40e-6, 6); }

static void sphere_free(sphere *t)
{
    mc_hardening_free(&t->law);
    mc_contact_destroy(&t->s);
    mc_operator_destroy(&t->K);
    mc_free(t->h);
    mc_free(t->p);
    mc_free(t->u);
    mc_free(t->gap);
}

/* Run the loop on the sphere with problem pb, asserting MC_OK (the error's message if not). */
static void sphere_run(sphere *t, const mc_plastic_problem *pb, mc_contact_summary *cs,
                       mc_plastic_result *r)
{
    mc_error err = {0};
    ck_assert_msg(mc_plastic_run(&t->g, t->K, t->s, pb, t->p, t->u, t->gap, cs, r, &err) == MC_OK,
                  "%s", err.msg);
}

static int sweeps(const mc_plastic_result *r)
{
    int n = 0;
    for (int k = 0; k < r->steps_done; k++)
        n += r->steps[k].plastic_iterations;
    return n;
}

static double maxabs(const double *a, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = test_worst(m, fabs(a[i]));
    return m;
}

/* max |a - b| / max |b| */
static double rel_diff(const double *a, const double *b, size_t n)
{
    double d = 0;
    for (size_t i = 0; i < n; i++)
        d = test_worst(d, fabs(a[i] - b[i]));
    const double s = maxabs(b, n);
    return s > 0 ? d / s : d;
}

/* How far the state of result a (pressure pa) lies from that of b (pressure pb): rel_diff of the
 * residual displacement, the equivalent plastic strain, the plastic strain and the pressure. */
typedef struct {
    double u, peq, eps, p;
} apart;

static apart states_apart(const mc_plastic_result *a, const double *pa, const mc_plastic_result *b,
                          const double *pb, size_t n)
{
    const size_t nv = (size_t)b->nvol;
    return (apart){rel_diff(a->u_r, b->u_r, n), rel_diff(a->peq, b->peq, nv),
                   rel_diff(a->eps_p, b->eps_p, 6 * nv), rel_diff(pa, pb, n)};
}

static int within(apart d, double tol) { return d.u <= tol && d.peq <= tol && d.eps <= tol && d.p <= tol; }

/* Both states are fixed points of the outer map to within its stopping rule: the last change of
 * u_r was at most tol_outer max|u_r| with the relaxed update (omega = 0.7). With the outer map
 * contracting by rho per iteration, a state is within tol_outer rho / (1 - rho) of the fixed
 * point; the loop's 5-20 iterations per step (dossier §2.1) put rho at 0.5-0.8, i.e. within
 * 4 tol_outer each, 8 tol_outer apart; 10 tol_outer leaves a little room. The plastic strain and
 * the pressure follow u_r with factors of order one (the same outer tolerance bounds them in the
 * loop's own contract). */
#define STATE_TOL_FACTOR 10.0

/* The inexact loop and the tight one, with the adaptive under-relaxation of the fixed point and
 * with Anderson mixing: converged, every accepted fixed point within tol_plastic, the same state
 * within the outer tolerance, and fewer sweeps. */
START_TEST(inexact_matches_tight)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    double *p_tight = mc_zeros(n);
    ck_assert(p_tight);
    for (int aa = 0; aa <= 4; aa += 4) {
        mc_plastic_problem pb = t.pb;
        pb.anderson = aa;
        pb.iteration = MC_PLASTIC_NESTED; /* the inexact scheme of the nested iteration */
        mc_plastic_result tight, loose;
        mc_contact_summary cs;
        pb.tight_inner = 1;
        sphere_run(&t, &pb, &cs, &tight);
        memcpy(p_tight, t.p, n * sizeof *p_tight);
        pb.tight_inner = 0;
        sphere_run(&t, &pb, &cs, &loose);
        ck_assert(tight.converged && loose.converged);
        ck_assert_msg(tight.inner_change <= pb.tol_plastic && loose.inner_change <= pb.tol_plastic,
                      "accepted fixed points: %g, %g > tol_plastic %g", tight.inner_change,
                      loose.inner_change, pb.tol_plastic);
        const size_t nv = (size_t)tight.nvol;
        ck_assert(maxabs(tight.peq, nv) > 0); /* it did yield */
        const double tol = STATE_TOL_FACTOR * pb.tol_outer;
        const apart d = states_apart(&loose, t.p, &tight, p_tight, n);
        ck_assert_msg(within(d, tol), "anderson %d: u_r %g, peq %g, eps_p %g, p %g apart "
                      "(tolerance %g)", aa, d.u, d.peq, d.eps, d.p, tol);
        const int st = sweeps(&tight), sl = sweeps(&loose);
        ck_assert_msg(sl < st, "anderson %d: %d sweeps inexact, %d tight", aa, sl, st);
        mc_plastic_result_free(&tight);
        mc_plastic_result_free(&loose);
    }
    mc_free(p_tight);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* The warm start of theory §9.6 against the cold one (every increment from a zero increment),
 * with the adaptive under-relaxation and with Anderson mixing, on the sphere in 4 load steps of
 * 1 P_c: both converged, the same state within the outer tolerance (the argument of
 * STATE_TOL_FACTOR: two states that each meet the stopping rule), and fewer sweeps warm. The
 * per-step counts add up: one contact solve per outer iteration (dry), at most one residual
 * stress application per sweep, and the steps' contact solves are the run's. */
START_TEST(warm_matches_cold)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    double *p_cold = mc_zeros(n);
    ck_assert(p_cold);
    for (int aa = 0; aa <= 4; aa += 4) {
        mc_plastic_problem pb = t.pb;
        pb.anderson = aa;
        pb.load_steps = 4;
        pb.iteration = MC_PLASTIC_NESTED; /* its sweeps fall with the warm start; the joint
                                             iteration's do not (joint_matches_nested) */
        mc_plastic_result cold, warm;
        mc_contact_summary cs;
        pb.cold_start = 1;
        sphere_run(&t, &pb, &cs, &cold);
        memcpy(p_cold, t.p, n * sizeof *p_cold);
        pb.cold_start = 0;
        sphere_run(&t, &pb, &cs, &warm);
        ck_assert(cold.converged && warm.converged);
        const size_t nv = (size_t)cold.nvol;
        ck_assert(maxabs(cold.peq, nv) > 0);
        const double tol = STATE_TOL_FACTOR * pb.tol_outer;
        const apart d = states_apart(&warm, t.p, &cold, p_cold, n);
        ck_assert_msg(within(d, tol), "anderson %d: u_r %g, peq %g, eps_p %g, p %g apart "
                      "(tolerance %g)", aa, d.u, d.peq, d.eps, d.p, tol);
        /* the warm start seeds the volume (its compact store of the yielding cells), not only
         * u_r: after the first step that yields (the sphere yields from its second step), none
         * cold */
        long seeded = 0;
        for (int k = 0; k < warm.steps_done; k++) {
            ck_assert_int_eq(cold.steps[k].warm_cells, 0);
            ck_assert(warm.steps[k].warm_cells >= 0 && warm.steps[k].warm_cells <= (long)nv);
            ck_assert(k > 0 || warm.steps[k].warm_cells == 0);
            seeded += warm.steps[k].warm_cells;
        }
        ck_assert_msg(seeded > 0, "anderson %d: the warm start seeded no volume cell", aa);
        const int sc = sweeps(&cold), sw = sweeps(&warm);
        ck_assert_msg(sw < sc, "anderson %d: %d sweeps warm, %d cold", aa, sw, sc);
        const mc_plastic_result *rs[2] = {&cold, &warm};
        for (int m = 0; m < 2; m++) {
            int solves = 0;
            for (int k = 0; k < rs[m]->steps_done; k++) {
                const mc_plastic_step *st = &rs[m]->steps[k];
                ck_assert_int_eq(st->contact_solves, st->outer_iterations);
                ck_assert(st->stress_applies <= st->plastic_iterations);
                solves += st->contact_solves;
            }
            ck_assert_int_eq(solves, rs[m]->contact_solves);
        }
        if (getenv("MC_TEST_VERBOSE"))
            fprintf(stderr, "warm start, anderson %d: %d -> %d sweeps, u_r %.2e, peq %.2e apart\n",
                    aa, sc, sw, d.u, d.peq);
        mc_plastic_result_free(&cold);
        mc_plastic_result_free(&warm);
    }
    mc_free(p_cold);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* The joint iteration (theory §9.8) against the nested one solved tight (every fixed point to
 * tol_plastic), in one load step and in four (the warm start and the committed state of the
 * steps before: a joint iteration that counted the committed plastic strain twice at its
 * acceptance was 0.2 apart in u_r after two steps and passed in one): the same state within
 * STATE_TOL_FACTOR tol_outer (two states that each meet the stopping rules), every accepted
 * image within tol_plastic, fewer residual stress applications, one contact solve, one sweep
 * and one outer iteration per evaluation, no fallback. Then (one step) with max_outer two
 * evaluations short: the nested iteration goes on from its state (joint_fallback) and converges
 * to the same state. */
START_TEST(joint_matches_nested)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    double *p_ref = mc_zeros(n);
    ck_assert(p_ref);
    for (int steps = 1; steps <= 4; steps += 3) {
        mc_plastic_problem pb = t.pb;
        pb.anderson = 4;
        pb.load_steps = steps;
        mc_plastic_result ref, joint, fb;
        mc_contact_summary cs;
        mc_error err = {0};
        pb.iteration = MC_PLASTIC_NESTED;
        pb.tight_inner = 1;
        sphere_run(&t, &pb, &cs, &ref);
        memcpy(p_ref, t.p, n * sizeof *p_ref);
        pb.iteration = MC_PLASTIC_JOINT;
        pb.tight_inner = 0;
        sphere_run(&t, &pb, &cs, &joint);
        ck_assert(ref.converged && joint.converged);
        ck_assert_msg(joint.inner_change <= pb.tol_plastic, "accepted at %g > tol_plastic %g",
                      joint.inner_change, pb.tol_plastic);
        const size_t nv = (size_t)ref.nvol;
        ck_assert(maxabs(ref.peq, nv) > 0);
        const double tol = STATE_TOL_FACTOR * pb.tol_outer;
        const apart d = states_apart(&joint, t.p, &ref, p_ref, n);
        int applies_ref = 0, applies = 0, evals = 0;
        for (int k = 0; k < ref.steps_done; k++)
            applies_ref += ref.steps[k].stress_applies;
        for (int k = 0; k < joint.steps_done; k++) {
            const mc_plastic_step *st = &joint.steps[k];
            ck_assert_int_eq(st->joint_fallback, 0);
            ck_assert_int_eq(st->joint_evaluations, st->outer_iterations);
            ck_assert_int_eq(st->joint_evaluations, st->plastic_iterations);
            ck_assert_int_eq(st->joint_evaluations, st->contact_solves);
            ck_assert(st->stress_applies <= st->plastic_iterations);
            applies += st->stress_applies;
            evals += st->joint_evaluations;
        }
        if (getenv("MC_TEST_VERBOSE"))
            fprintf(stderr, "joint, %d steps: %d evaluations, applies %d (nested tight %d); u_r "
                            "%.2e, peq %.2e, eps_p %.2e, p %.2e apart\n",
                    steps, evals, applies, applies_ref, d.u, d.peq, d.eps, d.p);
        ck_assert_msg(within(d, tol), "%d steps: u_r %g, peq %g, eps_p %g, p %g apart "
                      "(tolerance %g)", steps, d.u, d.peq, d.eps, d.p, tol);
        ck_assert_msg(applies < applies_ref, "%d steps: %d applications joint, %d nested",
                      steps, applies, applies_ref);
        /* two evaluations too few for the joint iteration (one step): the nested one finishes
         * from its state */
        pb.max_outer = steps == 1 ? evals - 2 : pb.max_outer;
        ck_assert(pb.max_outer >= 2);
        ck_assert_msg(mc_plastic_run(&t.g, t.K, t.s, &pb, t.p, t.u, t.gap, &cs, &fb, &err) ==
                          MC_OK, "max_outer %d: %s", pb.max_outer, err.msg);
        int fallbacks = 0;
        for (int k = 0; k < fb.steps_done; k++)
            fallbacks += fb.steps[k].joint_fallback;
        ck_assert_msg(fallbacks == (steps == 1), "max_outer %d: %d fallbacks", pb.max_outer,
                      fallbacks);
        const double fu = rel_diff(fb.u_r, ref.u_r, n), fe = rel_diff(fb.eps_p, ref.eps_p, 6 * nv);
        ck_assert_msg(fb.converged && fu <= tol && fe <= tol,
                      "after a fallback: u_r %g, eps_p %g apart", fu, fe);
        mc_plastic_result_free(&ref);
        mc_plastic_result_free(&joint);
        mc_plastic_result_free(&fb);
    }
    mc_free(p_ref);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* The contract under a loose outer tolerance and a very tight plastic one: the outer change
 * meets tol_outer long before the inexact fixed points reach tol_plastic, yet the step is
 * accepted only on a fixed point within tol_plastic. */
START_TEST(accepts_only_tight)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    mc_plastic_problem pb = t.pb;
    pb.tol_outer = 0.02;
    pb.tol_plastic = 1e-9;
    pb.max_plastic = 1000;
    mc_plastic_result r;
    mc_contact_summary cs;
    sphere_run(&t, &pb, &cs, &r);
    ck_assert(r.converged);
    ck_assert_msg(r.inner_change <= pb.tol_plastic, "accepted on a fixed point at %g > %g",
                  r.inner_change, pb.tol_plastic);
    mc_plastic_result_free(&r);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* Operators lent to two runs in a row give each the bits of the run that builds its own (one
 * thread: the residual displacement's partial spectra are summed over a dynamic schedule,
 * plastic/eigen_disp_op.c); operators of another nu, volume or friction are refused. */
START_TEST(shared_operators)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    mc_plastic_problem pb = t.pb;
    pb.anderson = 4;
    mc_plastic_ops ops;
    mc_error err = {0};
    ck_assert_msg(mc_plastic_ops_create(&t.g, &pb.volume, pb.nu, pb.backend, 0, &ops, &err) ==
                      MC_OK, "%s", err.msg);
    mc_plastic_result r[3];
    mc_contact_summary cs;
    double *p[3];
    for (int k = 0; k < 3; k++) {
        pb.ops = k < 2 ? &ops : NULL; /* lent twice, then built by the run */
        sphere_run(&t, &pb, &cs, &r[k]);
        ck_assert(p[k] = mc_malloc(n * sizeof *p[k]));
        memcpy(p[k], t.p, n * sizeof *p[k]);
    }
    const size_t nv = (size_t)r[0].nvol;
    for (int k = 0; k < 2; k++) {
        ck_assert(memcmp(r[k].eps_p, r[2].eps_p, 6 * nv * sizeof(double)) == 0);
        ck_assert(memcmp(r[k].peq, r[2].peq, nv * sizeof(double)) == 0);
        ck_assert(memcmp(r[k].u_r, r[2].u_r, n * sizeof(double)) == 0);
        ck_assert(memcmp(r[k].sig_r, r[2].sig_r, 6 * nv * sizeof(double)) == 0);
        ck_assert(memcmp(p[k], p[2], n * sizeof(double)) == 0);
    }
    for (int k = 0; k < 3; k++) {
        mc_plastic_result_free(&r[k]);
        mc_free(p[k]);
    }
    /* another problem: nu, the volume's depth, friction */
    pb.ops = &ops;
    mc_plastic_problem other[3] = {pb, pb, pb};
    other[0].nu = 0.25;
    other[1].volume.dz *= 2;
    other[2].friction = 0.1;
    for (int k = 0; k < 3; k++) {
        mc_plastic_result bad;
        ck_assert_int_eq(mc_plastic_run(&t.g, t.K, t.s, &other[k], t.p, t.u, t.gap, &cs, &bad,
                                        &err),
                         MC_ERR_INPUT);
        mc_plastic_result_free(&bad);
    }
    mc_plastic_ops_destroy(&ops);
    mc_plastic_ops_destroy(&ops); /* zeroed: a second destroy is harmless */
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* Every field of a stopped run finite (theory §9.5: the results are the last iterate's). */
static void assert_finite_result(const mc_plastic_result *r, const sphere *t)
{
    const size_t n = mc_grid_cells(&t->g), nv = (size_t)r->nvol;
    for (size_t i = 0; i < n; i++)
        ck_assert(isfinite(r->u_r[i]) && isfinite(t->p[i]) && isfinite(t->u[i]) &&
                  isfinite(t->gap[i]));
    for (size_t i = 0; i < nv; i++)
        ck_assert(isfinite(r->peq[i]) && isfinite(r->residual_vm[i]));
    for (size_t i = 0; i < 6 * nv; i++)
        ck_assert(isfinite(r->eps_p[i]) && isfinite(r->sig_r[i]));
}

static int total_sweeps(const mc_plastic_result *r) { return sweeps(r); }

/* A run that cannot converge ends in the load step where it failed, with MC_NOT_CONVERGED, the
 * reason, the step and its last iterate, and within the counts of theory §9.5: max_outer = 2
 * (the cap), max_plastic = 1 (a fixed point that stalls at its cap). */
START_TEST(stops_at_caps)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const struct {
        int max_outer, max_plastic;
        mc_plastic_stop why;
    } cases[] = {{2, 200, MC_PLASTIC_STOP_OUTER_CAP}, {30, 1, MC_PLASTIC_STOP_INNER_STALL}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        mc_plastic_problem pb = t.pb;
        pb.max_outer = cases[c].max_outer;
        pb.max_plastic = cases[c].max_plastic;
        mc_plastic_result r;
        mc_contact_summary cs;
        mc_error err = {0};
        ck_assert_int_eq(mc_plastic_run(&t.g, t.K, t.s, &pb, t.p, t.u, t.gap, &cs, &r, &err),
                         MC_NOT_CONVERGED);
        ck_assert_msg(r.stop == cases[c].why, "case %zu: stop %d, not %d (%s)", c, (int)r.stop,
                      (int)cases[c].why, err.msg);
        ck_assert(!r.converged && r.stop_step == 1 && r.steps_done == 1 && !r.steps[0].converged);
        ck_assert_msg(strstr(err.msg, "load step 1 of 2") &&
                          strstr(err.msg, mc_plastic_stop_text(r.stop)),
                      "message: %s", err.msg);
        ck_assert(r.steps[0].outer_iterations <= pb.max_outer);
        ck_assert(total_sweeps(&r) <= pb.max_outer * pb.max_plastic);
        ck_assert(maxabs(r.peq, (size_t)r.nvol) > 0); /* the last iterate, not a blank */
        assert_finite_result(&r, &t);
        mc_plastic_result_free(&r);
    }
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* step (a) of the loop that fails on its third call (a contact or lubricant root that did not
 * converge) */
typedef struct {
    mc_contact_solver *s;
    int calls;
} failing_contact;

static int contact_fails_third(void *ctx, const mc_contact_problem *cp, int inexact, double *p,
                               double *u, double *gap, mc_contact_summary *sum, double *p_lub,
                               int *settled, mc_error *err)
{
    failing_contact *f = ctx;
    (void)inexact;
    *settled = 1;
    *p_lub = cp->p_lub;
    int rc = mc_contact_solve(f->s, cp, p, u, gap, sum, err);
    if (rc == MC_OK && ++f->calls == 3)
        rc = mc_fail(err, MC_NOT_CONVERGED, "test: contact not converged");
    return rc;
}

/* The lubricant volume equilibrium as the loop's contact step (pipeline/stage_lube.h), passing the
 * loop's inexact flag on, or (exact) always asking for the settled root. */
typedef struct {
    mc_stage_lube_contact lc;
    int exact;
} lube_contact;

static int lube_contact_step(void *ctx, const mc_contact_problem *cp, int inexact, double *p,
                             double *u, double *gap, mc_contact_summary *sum, double *p_lub,
                             int *settled, mc_error *err)
{
    lube_contact *w = ctx;
    return mc_stage_lube_contact_step(&w->lc, cp, inexact && !w->exact, p, u, gap, sum, p_lub,
                                      settled, err);
}

/* The joint iteration over a lubricant volume equilibrium (theory.md §9.8): one secant step of
 * the root per evaluation (inexact contact steps) reaches the state of full roots in every
 * evaluation, within STATE_TOL_FACTOR tol_outer, in fewer contact solves, and its accepted state
 * meets the root's tolerance (the acceptance waits for a settled equilibrium). The sphere under a
 * film between the dry and the onset volumes, in two load steps (the second step's first root
 * from the first step's: another load, so a full root). */
START_TEST(joint_inexact_lubricant)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    const double a_nom = (double)n * t.g.dx * t.g.dy;
    mc_volume_problem vp = {.h = t.h, .load = t.pb.load, .h_target = 0};
    mc_volume_result vr;
    mc_error err = {0};
    ck_assert_msg(mc_volume_equilibrium(t.s, t.K, &vp, t.p, NULL, t.gap, &vr, &err) == MC_OK, "%s",
                  err.msg);
    const double h_target = (vr.v_dry + 0.3 * (vr.v_onset - vr.v_dry)) / a_nom;
    double *p_ref = mc_zeros(n);
    ck_assert(p_ref);
    mc_plastic_result res[2];
    lube_contact w[2];
    for (int v = 0; v < 2; v++) {
        w[v] = (lube_contact){.lc = {.solver = t.s, .K = t.K, .h_target = h_target,
                                     .tolerance = MC_VOLUME_TOL_DEFAULT},
                              .exact = v == 0};
        mc_plastic_problem pb = t.pb;
        pb.anderson = 4;
        pb.iteration = MC_PLASTIC_JOINT;
        pb.contact = lube_contact_step;
        pb.contact_ctx = &w[v];
        mc_contact_summary cs;
        sphere_run(&t, &pb, &cs, &res[v]);
        ck_assert(res[v].converged && res[v].p_lub > 0);
        for (int k = 0; k < res[v].steps_done; k++)
            ck_assert_int_eq(res[v].steps[k].joint_fallback, 0);
        /* the accepted state's own equilibrium: its pocket volume within the root's tolerance */
        double vol = 0;
        for (size_t i = 0; i < n; i++)
            vol += t.gap[i] * t.g.dx * t.g.dy;
        ck_assert_msg(fabs(vol - h_target * a_nom) <= MC_VOLUME_TOL_DEFAULT * h_target * a_nom,
                      "%s: V = %.9g, V* = %.9g", v ? "inexact" : "exact", vol, h_target * a_nom);
        if (v == 0)
            memcpy(p_ref, t.p, n * sizeof *p_ref);
    }
    const size_t nv = (size_t)res[0].nvol;
    ck_assert(maxabs(res[0].peq, nv) > 0);
    const double tol = STATE_TOL_FACTOR * t.pb.tol_outer;
    const double du = rel_diff(res[1].u_r, res[0].u_r, n);
    const double deps = rel_diff(res[1].eps_p, res[0].eps_p, 6 * nv);
    const double dp = rel_diff(t.p, p_ref, n);
    const double dplub = fabs(res[1].p_lub - res[0].p_lub) / res[0].p_lub;
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "lubricated joint: %d contact solves exact, %d inexact; u_r %.2e, eps_p "
                        "%.2e, p %.2e, p_lub %.2e apart\n",
                w[0].lc.solves, w[1].lc.solves, du, deps, dp, dplub);
    ck_assert_msg(du <= tol && deps <= tol && dp <= tol && dplub <= tol,
                  "u_r %g, eps_p %g, p %g, p_lub %g apart (tolerance %g)", du, deps, dp, dplub, tol);
    ck_assert_msg(w[1].lc.solves < w[0].lc.solves, "%d contact solves inexact, %d exact",
                  w[1].lc.solves, w[0].lc.solves);
    for (int v = 0; v < 2; v++)
        mc_plastic_result_free(&res[v]);
    mc_free(p_ref);
    sphere_free(&t);
}
END_TEST

/* The elastic stresses folded into the residual stress operator (theory §8.9; the operators of a
 * volume under the whole grid): the sphere with a friction traction q_x = 0.3 p, through the
 * joint iteration (one apply of both fields per evaluation) and the nested one (sigma_e from the
 * operator with eps = 0), against the same runs with operators built without the folding (the
 * separate elastic plan). The fields agree to round-off carried through the iteration (bound
 * 1e-9 of the largest value; the sweep counts must match, so that a round-off cannot flip a
 * stopping decision unseen). */
START_TEST(folded_matches_separate)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    mc_plastic_problem pb = t.pb;
    pb.anderson = 4;
    pb.friction = 0.3;
    mc_error err = {0};
    mc_plastic_ops folded, separate;
    ck_assert_msg(mc_plastic_ops_create(&t.g, &pb.volume, pb.nu, pb.backend, 1, &folded, &err) ==
                      MC_OK, "%s", err.msg);
    ck_assert_int_eq(mc_eigen_stress_loads_of(folded.resid), MC_TRACTION_P | MC_TRACTION_QX);
    /* the same operators, the residual stress one without the loads */
    separate = folded;
    separate.group = NULL;
    separate.near = NULL;
    separate.elastic = NULL;
    separate.resid = NULL;
    separate.disp = NULL;
    double depths[6];
    for (int k = 0; k < pb.volume.nz; k++)
        depths[k] = mc_eigen_layer_depth(&pb.volume, k);
    mc_stress_options so = {.kernel = MC_STRESS_PATCH, .nu = pb.nu, .nlayers = pb.volume.nz,
                            .depths = depths, .backend = pb.backend,
                            .loads = MC_TRACTION_P | MC_TRACTION_QX, .repeated = 1};
    ck_assert(mc_stress_create(&t.g, &so, &separate.elastic, &err) == MC_OK);
    ck_assert(mc_eigen_disp_create(&t.g, &pb.volume, pb.nu, pb.backend, &separate.disp, &err) ==
              MC_OK);
    ck_assert(mc_eigen_stress_create(&t.g, &pb.volume, pb.nu, pb.backend, &separate.resid, &err) ==
              MC_OK);
    static const mc_plastic_iteration its[2] = {MC_PLASTIC_JOINT, MC_PLASTIC_NESTED};
    for (int i = 0; i < 2; i++) {
        mc_plastic_result r[2];
        double *p[2];
        mc_contact_summary cs;
        for (int v = 0; v < 2; v++) {
            pb.iteration = its[i];
            pb.ops = v == 0 ? &folded : &separate;
            sphere_run(&t, &pb, &cs, &r[v]);
            ck_assert(r[v].converged);
            ck_assert(p[v] = mc_malloc(n * sizeof *p[v]));
            memcpy(p[v], t.p, n * sizeof *p[v]);
        }
        const size_t nv = (size_t)r[0].nvol;
        ck_assert(maxabs(r[0].peq, nv) > 0);
        const double deps = rel_diff(r[0].eps_p, r[1].eps_p, 6 * nv);
        const double du = rel_diff(r[0].u_r, r[1].u_r, n), dp = rel_diff(p[0], p[1], n);
        const double dsig = rel_diff(r[0].sig_r, r[1].sig_r, 6 * nv);
        if (getenv("MC_TEST_VERBOSE"))
            fprintf(stderr, "folded vs separate (%s): eps_p %.2e, u_r %.2e, p %.2e, sig_r %.2e; "
                            "sweeps %d / %d\n",
                    i ? "nested" : "joint", deps, du, dp, dsig, sweeps(&r[0]), sweeps(&r[1]));
        /* round-off through the iteration: measured 6e-15 (joint) and 2e-14 (nested) */
        const double tol = 1e-9;
        ck_assert_int_eq(sweeps(&r[0]), sweeps(&r[1]));
        ck_assert_msg(deps <= tol && du <= tol && dp <= tol && dsig <= tol,
                      "%s: eps_p %g, u_r %g, p %g, sig_r %g apart (tolerance %g)",
                      i ? "nested" : "joint", deps, du, dp, dsig, tol);
        for (int v = 0; v < 2; v++) {
            mc_plastic_result_free(&r[v]);
            mc_free(p[v]);
        }
    }
    mc_plastic_ops_destroy(&separate);
    mc_plastic_ops_destroy(&folded);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* The sparse increment of the joint iteration (theory §9.9; the spectral kernel) against the
 * same iteration on dense arrays (dense_increment): the same bits in every result and count,
 * with friction (the loads' q_x), warm starts over three load steps, and a fallback to the
 * nested iteration (max_outer two evaluations short of the joint iteration's first step: the
 * sparse state goes to the dense arrays). */
START_TEST(sparse_matches_dense)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    for (int fb = 0; fb < 2; fb++) {
        mc_plastic_problem pb = t.pb;
        pb.anderson = 4;
        pb.friction = 0.3;
        pb.load_steps = 3;
        pb.volume.kernel = MC_EIG_KERNEL_SPECTRAL;
        if (fb)
            pb.max_outer = 3;
        mc_plastic_result r[2];
        double *p[2];
        mc_contact_summary cs;
        for (int v = 0; v < 2; v++) {
            pb.dense_increment = v;
            mc_error err = {0};
            const int rc = mc_plastic_run(&t.g, t.K, t.s, &pb, t.p, t.u, t.gap, &cs, &r[v], &err);
            ck_assert_msg(rc == MC_OK || (fb && rc == MC_NOT_CONVERGED), "%s", err.msg);
            ck_assert_int_eq(r[v].sparse_increment, !v);
            ck_assert(p[v] = mc_malloc(n * sizeof *p[v]));
            memcpy(p[v], t.p, n * sizeof *p[v]);
        }
        const size_t nv = (size_t)r[0].nvol;
        ck_assert(maxabs(r[0].peq, nv) > 0);
        int fallbacks = 0;
        ck_assert_int_eq(r[0].steps_done, r[1].steps_done);
        for (int k = 0; k < r[0].steps_done; k++) {
            const mc_plastic_step *a = &r[0].steps[k], *b = &r[1].steps[k];
            ck_assert_int_eq(a->joint_evaluations, b->joint_evaluations);
            ck_assert_int_eq(a->plastic_iterations, b->plastic_iterations);
            ck_assert_int_eq(a->stress_applies, b->stress_applies);
            ck_assert_int_eq(a->warm_cells, b->warm_cells);
            ck_assert_int_eq(a->joint_fallback, b->joint_fallback);
            fallbacks += a->joint_fallback;
        }
        ck_assert_msg(fb ? fallbacks > 0 : fallbacks == 0, "%d fallbacks", fallbacks);
        ck_assert(r[0].converged == r[1].converged);
        ck_assert(memcmp(r[0].eps_p, r[1].eps_p, 6 * nv * sizeof(double)) == 0);
        ck_assert(memcmp(r[0].peq, r[1].peq, nv * sizeof(double)) == 0);
        ck_assert(memcmp(r[0].sig_r, r[1].sig_r, 6 * nv * sizeof(double)) == 0);
        ck_assert(memcmp(r[0].residual_vm, r[1].residual_vm, nv * sizeof(double)) == 0);
        ck_assert(memcmp(r[0].u_r, r[1].u_r, n * sizeof(double)) == 0);
        ck_assert(memcmp(p[0], p[1], n * sizeof(double)) == 0);
        if (getenv("MC_TEST_VERBOSE"))
            fprintf(stderr, "sparse vs dense increment (%s): the same bits, %d sweeps, peq max "
                            "%.3e\n",
                    fb ? "with fallbacks" : "joint", sweeps(&r[0]), maxabs(r[0].peq, nv));
        for (int v = 0; v < 2; v++) {
            mc_plastic_result_free(&r[v]);
            mc_free(p[v]);
        }
    }
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* A contact that does not converge ends the run with its iterate (the residual fields of the
 * state before it included), not with blank fields. */
START_TEST(stops_on_contact)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    failing_contact f = {.s = t.s};
    mc_plastic_problem pb = t.pb;
    pb.contact = contact_fails_third;
    pb.contact_ctx = &f;
    mc_plastic_result r;
    mc_contact_summary cs;
    mc_error err = {0};
    ck_assert_int_eq(mc_plastic_run(&t.g, t.K, t.s, &pb, t.p, t.u, t.gap, &cs, &r, &err),
                     MC_NOT_CONVERGED);
    ck_assert_msg(r.stop == MC_PLASTIC_STOP_CONTACT && r.stop_step == 1 && !r.converged, "%s",
                  err.msg);
    ck_assert(maxabs(r.residual_vm, (size_t)r.nvol) > 0); /* unloaded: the residual stress */
    assert_finite_result(&r, &t);
    mc_plastic_result_free(&r);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* A load no material point can carry (Y = 20 MPa at 4 P_c of Y = 1 GPa, one step): the increments
 * blow up and split; the step ends in bounded work (its sweep budget over all the split
 * increments) with a finite last iterate, where the loop before issue 20 spent up to 63
 * increments of max_outer x max_plastic sweeps and returned no results. */
START_TEST(overload_ends_bounded)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    mc_hardening_free(&t.law);
    mc_error err = {0};
    ck_assert_int_eq(mc_hardening_perfect(20e6, &t.law, &err), MC_OK);
    mc_plastic_problem pb = t.pb;
    pb.load_steps = 1;
    pb.max_outer = 10;
    pb.max_plastic = 50;
    mc_plastic_result r;
    mc_contact_summary cs;
    ck_assert_int_eq(mc_plastic_run(&t.g, t.K, t.s, &pb, t.p, t.u, t.gap, &cs, &r, &err),
                     MC_NOT_CONVERGED);
    ck_assert_msg(r.stop != MC_PLASTIC_RUN_CONVERGED && r.stop_step == 1 && !r.converged, "%s",
                  err.msg);
    ck_assert_msg(total_sweeps(&r) <= pb.max_outer * pb.max_plastic, "%d sweeps",
                  total_sweeps(&r));
    assert_finite_result(&r, &t);
    mc_plastic_result_free(&r);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* Round-off of a symmetric run: the contact, the fixed points and the FFTs are mirror-symmetric
 * in exact arithmetic; their round-off breaks the symmetry by ~1e-13 of the largest value, and a
 * window misplaced by one column breaks it by O(1). */
#define MIRROR_TOL 1e-9

/* A window smaller than the grid (its elastic stresses taken layer by layer from the whole grid
 * and cut to the window) under a centred sphere: the accumulated plastic strain is mirror-
 * symmetric in x and y within the window. */
START_TEST(window_is_symmetric)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    mc_plastic_problem pb = t.pb;
    pb.load_steps = 1;
    pb.volume = (mc_eigen_volume){2, 3, 12, 10, 6, 40e-6, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID};
    mc_plastic_result r;
    mc_contact_summary cs;
    mc_error err = {0};
    ck_assert_int_eq(mc_plastic_run(&t.g, t.K, t.s, &pb, t.p, t.u, t.gap, &cs, &r, &err), MC_OK);
    const int nx = pb.volume.nx, ny = pb.volume.ny;
    const double top = maxabs(r.peq, (size_t)r.nvol);
    ck_assert(top > 0);
    double dev = 0;
    for (int k = 0; k < pb.volume.nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                const double v = r.peq[((size_t)k * ny + j) * nx + i];
                dev = test_worst(dev, fabs(v - r.peq[((size_t)k * ny + j) * nx + (nx - 1 - i)]));
                dev = test_worst(dev, fabs(v - r.peq[((size_t)k * ny + (ny - 1 - j)) * nx + i]));
            }
    if (getenv("MC_TEST_VERBOSE"))
        printf("window symmetry: %.3g of the largest plastic strain %.3g\n", dev / top, top);
    ck_assert_msg(dev <= MIRROR_TOL * top, "asymmetry %g of %g", dev, top);
    mc_plastic_result_free(&r);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* The local-global fixed point (near_reach > 0, theory §9.7) against one residual stress
 * application per sweep, on a rough sphere (the sphere of sphere_init with a deterministic
 * random roughness of +-0.5 um on every cell: several contact spots, each its own plastic zone),
 * both with tight tolerances (tol_outer 1e-7, tol_plastic 1e-9, every fixed point tight): the
 * two states are fixed points of the same maps within those rules, so they agree to
 * STATE_TOL_FACTOR tol_outer = 1e-6 (the argument of STATE_TOL_FACTOR). The near field alone
 * (no global correction after the first sweep) would settle a different fixed point, off by the
 * far field's share of the residual stress (percent level): that is what this test catches.
 * And the local-global run applies the residual stress operator fewer times. */
START_TEST(local_global_matches_global)
{
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    sphere t;
    sphere_init(&t);
    const size_t n = mc_grid_cells(&t.g);
    unsigned long long r = 12345;
    for (size_t i = 0; i < n; i++) { /* LCG (Knuth's MMIX constants): +-0.5 um */
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        t.h[i] += 0.5e-6 * (2.0 * (double)(r >> 11) / 9007199254740992.0 - 1.0);
    }
    double *p_ref = mc_zeros(n);
    ck_assert(p_ref);
    mc_plastic_problem pb = t.pb;
    pb.tol_outer = 1e-7;
    pb.tol_plastic = 1e-9;
    pb.max_outer = 200;
    pb.max_plastic = 2000;
    pb.tight_inner = 1;
    mc_plastic_result ref, lg;
    mc_contact_summary cs;
    sphere_run(&t, &pb, &cs, &ref);
    memcpy(p_ref, t.p, n * sizeof *p_ref);
    pb.near_reach = 1;
    sphere_run(&t, &pb, &cs, &lg);
    ck_assert(ref.converged && lg.converged);
    const size_t nv = (size_t)ref.nvol;
    ck_assert(maxabs(ref.peq, nv) > 0);
    const double tol = STATE_TOL_FACTOR * pb.tol_outer;
    const apart d = states_apart(&lg, t.p, &ref, p_ref, n);
    int a_ref = 0, a_lg = 0, local = 0;
    for (int k = 0; k < ref.steps_done; k++)
        a_ref += ref.steps[k].stress_applies;
    for (int k = 0; k < lg.steps_done; k++)
        a_lg += lg.steps[k].stress_applies, local += lg.steps[k].local_sweeps;
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "local-global: applies %d -> %d (%d near-field sweeps); u_r %.2e, peq "
                        "%.2e, eps_p %.2e, p %.2e apart\n", a_ref, a_lg, local, d.u, d.peq, d.eps,
                d.p);
    ck_assert_msg(within(d, tol), "u_r %g, peq %g, eps_p %g, p %g apart (tolerance %g)", d.u,
                  d.peq, d.eps, d.p, tol);
    ck_assert_msg(a_lg < a_ref && local > 0, "applies %d local-global, %d global; %d local",
                  a_lg, a_ref, local);
    mc_plastic_result_free(&ref);
    mc_plastic_result_free(&lg);
    mc_free(p_ref);
    sphere_free(&t);
    mc_threads_end(&scope);
}
END_TEST

/* A whole run gives the same bits on 1, 2 and 3 threads (docs/architecture.md "Threads"): the
 * sphere on 32 x 32 cells of 20 um with 12 layers, where both eigenstrain operators run threaded
 * (6 nz (2n)^2 >= MC_THREADS_MIN_CELLS) and so do the sweeps; everything built inside each
 * thread count's scope. The displacement operator's sum blocks (mc_eig_sum_blocks) and the
 * blocked sums of core/psum.h make it so; per-thread partial sums of u_z made 1 and 2 threads
 * differ. */
START_TEST(same_bits_on_any_thread_count)
{
    ck_assert(6L * 12 * 64 * 64 >= MC_THREADS_MIN_CELLS);
    double *ref[4] = {NULL};
    size_t len[4] = {0};
    int sweeps_ref = -1;
    for (int nt = 1; nt <= 3; nt++) {
        mc_threads_scope scope;
        mc_threads_begin(nt, &scope);
        sphere t;
        sphere_init_size(&t, 32, 20e-6, 12);
        t.pb.load_steps = 1;
        mc_plastic_result r;
        mc_contact_summary cs;
        sphere_run(&t, &t.pb, &cs, &r);
        ck_assert(r.converged);
        const size_t n = mc_grid_cells(&t.g), nv = (size_t)r.nvol;
        ck_assert(maxabs(r.peq, nv) > 0);
        const double *out[4] = {r.eps_p, r.peq, r.u_r, t.p};
        const size_t sz[4] = {6 * nv, nv, n, n};
        for (int a = 0; a < 4; a++) {
            if (nt == 1) {
                ref[a] = malloc(sz[a] * sizeof *ref[a]);
                ck_assert(ref[a]);
                memcpy(ref[a], out[a], sz[a] * sizeof *ref[a]);
                len[a] = sz[a];
            } else {
                ck_assert_uint_eq(sz[a], len[a]);
                ck_assert_msg(memcmp(ref[a], out[a], sz[a] * sizeof *ref[a]) == 0,
                              "%d threads: array %d differs by %.3g", nt, a,
                              rel_diff(out[a], ref[a], sz[a]));
            }
        }
        if (nt == 1)
            sweeps_ref = sweeps(&r);
        else
            ck_assert_int_eq(sweeps(&r), sweeps_ref);
        mc_plastic_result_free(&r);
        sphere_free(&t);
        mc_threads_end(&scope);
    }
    for (int a = 0; a < 4; a++)
        free(ref[a]);
}
END_TEST

Suite *suite_plastic_loop(void);
Suite *suite_plastic_loop(void)
{
    Suite *s = suite_create("plastic_loop");
    TCase *t = tcase_create("inexact");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, inexact_matches_tight);
    tcase_add_test(t, accepts_only_tight);
    tcase_add_test(t, warm_matches_cold);
    tcase_add_test(t, joint_matches_nested);
    tcase_add_test(t, shared_operators);
    tcase_add_test(t, stops_at_caps);
    tcase_add_test(t, stops_on_contact);
    tcase_add_test(t, joint_inexact_lubricant);
    tcase_add_test(t, folded_matches_separate);
    tcase_add_test(t, sparse_matches_dense);
    tcase_add_test(t, overload_ends_bounded);
    tcase_add_test(t, window_is_symmetric);
    tcase_add_test(t, local_global_matches_global);
    tcase_add_test(t, same_bits_on_any_thread_count);
    suite_add_tcase(s, t);
    return s;
}
