/* test_runin.c - the running-in driver (pipeline/runin.h) and its case keys: the [runin] lists
 * and rules; an elastic material runs in nothing (run-down and run-up identical to the bit); an
 * elastic-plastic one smooths its surface only on the run-down; the hysteresis measure; the
 * checkpoint file; an interrupted run resumed gives the uninterrupted run's results bit for bit;
 * and a resume is refused without a checkpoint or from another case. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ctype.h>
#include <stddef.h>

#include "case/case.h"
#include "contact/contact.h"
#include "core/alloc.h"
#include "core/threads.h"
#include "io/npy.h"
#include "kernels/kernel.h"
#include "operator/operator.h"
#include "io/npy.h"
#include "pipeline/checkpoint.h"
#include "pipeline/memguard.h"
#include "pipeline/output.h"
#include "pipeline/pipeline.h"
#include "pipeline/runin.h"
#include "plastic/hardening.h"
#include "plastic/loop.h"
#include "surface/roughness.h"
#include "surface/surface.h"
#include "test_util.h"

#define RPM (2.0 * M_PI / 60.0) /* rad/s per rpm */

/* The twin-disc patch of the paper's rig (dossier plastic-lubrication §4.4) on a small grid: a
 * ground-like surface (correlation along y three times that along x), 1086 N on R1 = R2 = 40 mm
 * discs 10 mm wide (p_H = 447 MPa), Pan-Hamrock film. At 1000 rpm the film is thick enough for
 * a mixed regime on this patch, at 200 rpm the solids carry almost everything. */
static const char *BASE =
    "[mesh]\nnx = 32\nny = 16\ndx = 0.8 um\n%s"
    "[roughness]\ntype = gaussian\nrq = 0.3 um\ncorrelation_x = 4 um\ncorrelation_y = 12 um\n"
    "seed = %d\n"
    "[load]\nforce = 1086 N\nlubricant_pressure = auto\n"
    "[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\nrpm = 1000 rpm\n"
    "radius1 = 40 mm\nradius2 = 40 mm\nwidth = 10 mm\nmu_solid = 0.12\nmu_fluid = 0.03\n"
    "[solver]\nthreads = 1\n"
    "[runin]\nspeeds = 1000, 500, 200 rpm\n%s";

/* Swift hardening of AISI 52100 (dossier §9 point 1), both discs alike, 5 layers of 0.4 um. */
static const char *PLASTIC = "[plasticity]\nhardening = swift\nswift_B = 1280 MPa\nswift_C = 4\n"
                             "swift_n = 0.095\nbodies = both\nload_steps = 1\ndz = 0.4 um\n"
                             "depth = 2 um\nplastic_tolerance = 1e-5\n";

static void scene(mc_scene *s, const char *mesh, int seed, const char *extra, int nset,
                  const char *const *set)
{
    char text[4096];
    snprintf(text, sizeof text, BASE, mesh, seed, extra);
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(text, "r.ini", "", nset, set, s, &err) == MC_OK, "%s",
                  err.msg);
}

/* The message of a case text that must be refused. */
static const char *refused(const char *text)
{
    static mc_error err;
    static mc_scene s;
    memset(&err, 0, sizeof err);
    ck_assert_int_eq(mc_case_parse_text(text, "b.ini", "", 0, NULL, &s, &err), MC_ERR_INPUT);
    return err.msg;
}

/* ---- keys and rules ------------------------------------------------------------------------- */

/* A list takes the unit written after its last number for the bare numbers before it; an item
 * with its own unit keeps it. Values compare exactly with the single-quantity parser. */
START_TEST(list_units)
{
    mc_scene s;
    scene(&s, "", 1, "forces = 1086 N, 2 kN\n", 0, NULL);
    ck_assert_int_eq(s.runin.nspeeds, 3);
    ck_assert_double_eq(s.runin.speeds[0], 1000 * RPM);
    ck_assert_double_eq(s.runin.speeds[1], 500 * RPM);
    ck_assert_double_eq(s.runin.speeds[2], 200 * RPM);
    ck_assert_double_eq(s.lubrication.rpm, s.runin.speeds[0]); /* "1000 rpm" parsed alike */
    ck_assert_int_eq(s.runin.nforces, 2);
    ck_assert_double_eq(s.runin.forces[1], 2000.0);
    const char *set[] = {"runin.speeds=1000 rpm, 60, 5 rad/s"};
    scene(&s, "", 1, "", 1, set);
    ck_assert_double_eq(s.runin.speeds[1], 60.0); /* bare: the last item's unit */
    ck_assert_double_eq(s.runin.speeds[2], 5.0);
    ck_assert_int_eq(s.runin.deflection, MC_DEFLECTION_REMOVE);
}
END_TEST

/* Bad [runin] input names the file, the line and the key, and says what is accepted. */
typedef struct {
    const char *runin;       /* the [runin] section's keys */
    const char *lubrication; /* replaces "rpm = 1000 rpm" of [lubrication] */
    const char *want[3];
} bad_row;

static const bad_row bad_rows[] = {
    {"speeds = 200, 500, 1000 rpm\n", "rpm = 1000 rpm\n",
     {"b.ini:20:", "[runin] speeds = 200, 500, 1000 rpm", "must be less than item 1"}},
    {"speeds = 1000, 1000 rpm\n", "rpm = 1000 rpm\n", {"b.ini:20:", "strictly decreasing", NULL}},
    {"speeds = 1000, 0 rpm\n", "rpm = 1000 rpm\n", {"item 2 (0 rpm)", "rotation speed > 0", NULL}},
    {"speeds = 1000, , 200 rpm\n", "rpm = 1000 rpm\n", {"item 2 is empty", NULL, NULL}},
    {"speeds = 1000, 2 N\n", "rpm = 1000 rpm\n", {"unit 'N' is a force", NULL, NULL}},
    {"speeds = 1000, 500 rpm\nforces = 2000 N\n", "rpm = 1000 rpm\n",
     {"b.ini:21:", "[runin] forces: the first force (2000 N) must be [load] force", NULL}},
    {"speeds = 1000, 500 rpm\n", "rpm = 500 rpm\n",
     {"[runin] speeds: the first speed (1000 rpm) must be [lubrication] rpm", NULL, NULL}},
    {"speeds = 1000, 500 rpm\n", "speed = 4 m/s\n", {"[lubrication] gives rpm", NULL, NULL}},
    {"", "rpm = 1000 rpm\n", {"[runin] speeds is required", NULL, NULL}},
};

START_TEST(bad_input)
{
    const bad_row *b = &bad_rows[_i];
    char text[2048];
    snprintf(text, sizeof text,
             "[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = gaussian\nrq = 0.3 um\n"
             "correlation_x = 4 um\n[load]\nforce = 1086 N\nlubricant_pressure = auto\n"
             "[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\n%sradius1 = 40 mm\n"
             "radius2 = 40 mm\nwidth = 10 mm\n[runin]\n%s",
             b->lubrication, b->runin);
    const char *msg = refused(text);
    for (int k = 0; k < 3 && b->want[k]; k++)
        ck_assert_msg(strstr(msg, b->want[k]), "row %d: '%s' lacks '%s'", _i, msg, b->want[k]);
}
END_TEST

/* Cross-section rules: the volume equilibrium at every step, a film from the speeds, the stress
 * stage and a pressure cap are not combined with a running-in. */
START_TEST(rules)
{
    const char *mesh = "";
    char text[4096];
    static const struct {
        const char *set[2], *want;
    } rows[] = {
        {{"load.lubricant_pressure=0", "lubrication.enabled=no"},
         "[runin] needs [load] lubricant_pressure = auto"},
        {{"stress.enabled=yes", NULL}, "[stress] cannot be combined with [runin]"},
        {{"plasticity.criterion=pressure_cap", NULL},
         "[runin] needs [plasticity] criterion = von_mises"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        snprintf(text, sizeof text, BASE, mesh, 1, "");
        if (strstr(rows[k].set[0], "plasticity"))
            strncat(text, "[plasticity]\nhardness = 3 GPa\n", sizeof text - strlen(text) - 1);
        mc_scene s;
        mc_error err = {0};
        ck_assert_int_eq(mc_case_parse_text(text, "r.ini", "", rows[k].set[1] ? 2 : 1,
                                            rows[k].set, &s, &err),
                         MC_ERR_INPUT);
        ck_assert_msg(strstr(err.msg, rows[k].want), "%s: %s", rows[k].set[0], err.msg);
    }
}
END_TEST

/* [runin] friction_in_yield refused where it has no effect, naming the key: without
 * [plasticity], in pure rolling (no sliding direction), and beside [plasticity] friction, which
 * it replaces. */
START_TEST(friction_rules)
{
    static const struct {
        const char *plastic, *set[3], *want;
    } rows[] = {
        {"", {"runin.friction_in_yield=yes", "lubrication.rpm2=1100 rpm", NULL},
         "[runin] friction_in_yield = yes has no effect without [plasticity]"},
        {"[plasticity]\nyield_stress = 1 GPa\n", {"runin.friction_in_yield=yes", NULL, NULL},
         "[runin] friction_in_yield = yes has no effect in pure rolling"},
        {"[plasticity]\nyield_stress = 1 GPa\n",
         {"runin.friction_in_yield=yes", "lubrication.rpm2=1000 rpm", NULL},
         "[runin] friction_in_yield = yes has no effect in pure rolling"},
        {"[plasticity]\nyield_stress = 1 GPa\nfriction = 0.1\n",
         {"runin.friction_in_yield=yes", "lubrication.rpm2=1100 rpm", NULL},
         "[plasticity] friction has no effect with [runin] friction_in_yield = yes"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        char text[4096];
        snprintf(text, sizeof text, BASE, "", 1, rows[k].plastic);
        int nset = 0;
        while (nset < 3 && rows[k].set[nset])
            nset++;
        mc_scene s;
        mc_error err = {0};
        ck_assert_int_eq(mc_case_parse_text(text, "r.ini", "", nset, rows[k].set, &s, &err),
                         MC_ERR_INPUT);
        ck_assert_msg(strstr(err.msg, rows[k].want), "row %zu: %s", k, err.msg);
    }
    mc_scene s; /* accepted: plastic, rolling-sliding */
    const char *ok[] = {"runin.friction_in_yield=yes", "lubrication.rpm2=900 rpm"};
    scene(&s, "", 1, PLASTIC, 2, ok);
    ck_assert_int_eq(s.runin.friction_in_yield, 1);
}
END_TEST

/* ---- the hysteresis measure -------------------------------------------------------------------- */

/* Trapezoids over log10 of the speed: speeds 1000, 100, 10 (one decade each), mu down 0.05, 0.08,
 * 0.10 and up 0.04, 0.06, 0.10: (0.01 + 0.02)/2 + (0.02 + 0)/2 = 0.025 mu decades. */
START_TEST(hysteresis_measure)
{
    mc_runin_row rows[6];
    memset(rows, 0, sizeof rows);
    const double speed[3] = {1000, 100, 10}, down[3] = {0.05, 0.08, 0.10}, up[3] = {0.04, 0.06, 0.10};
    for (int k = 0; k < 3; k++) {
        rows[k].speed = speed[k];
        rows[k].mu = down[k];
        rows[5 - k].speed = speed[k];
        rows[5 - k].mu = up[k];
        rows[5 - k].up = 1;
    }
    mc_runin_summary r = {.nforces = 1, .nspeeds = 3, .nsteps = 6, .done = 6, .rows = rows};
    /* 4 operations on values of 0.1: a few ulps */
    ck_assert_double_eq_tol(mc_runin_hysteresis(&r, 0), 0.025, TOL_TIGHT);
    r.done = 5; /* the run-up is incomplete */
    ck_assert(isnan(mc_runin_hysteresis(&r, 0)));
}
END_TEST

/* ---- the loop's carried state ------------------------------------------------------------------ */

/* mc_plastic_run from an earlier state (eps_p0, peq0): reloading to 0.6 of the load that made
 * the state yields nothing (the residual stress and the hardening of the first run hold it), so
 * the state and the residual displacement come back bit for bit; the same 0.6 load on virgin
 * material yields less than the first run did (so the first check can fail). A rigid sphere
 * (R = 15 mm) on an elastic-perfectly plastic half-space (Y = 1 GPa) at 4 P_c (P_c = 91.96 N,
 * the Kogut-Etsion geometry of docs/theory.md §9.3). */
START_TEST(loop_carries_state)
{
    /* one thread: the DC-FFT of the residual displacement sums its per-thread partial spectra
     * over a dynamic schedule (plastic/eigen_disp_op.c), so with more threads its last bits vary
     * from call to call */
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    mc_grid g = {.nx = 16, .ny = 16, .dx = 40e-6, .dy = 40e-6};
    const size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *p = mc_zeros(n), *u = mc_zeros(n), *gap = mc_zeros(n);
    mc_shape_spec sphere = {.shape = MC_SHAPE_SPHERE, .radius = 15e-3};
    mc_surface_shape(&g, &sphere, h);
    mc_error err = {0};
    const double estar = mc_combined_modulus(210e9, 0.3, 0, 0, 1);
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_operator_plan_love(&g, estar, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options o = {.method = MC_METHOD_CG, .tolerance = 1e-10, .max_iterations = 5000};
    ck_assert_int_eq(mc_contact_create(K, &o, &s, &err), MC_OK);
    mc_hardening law;
    ck_assert_int_eq(mc_hardening_perfect(1e9, &law, &err), MC_OK);
    mc_plastic_problem pb = {.h = h, .load = 4 * 91.96, .load_steps = 2, .E = 210e9, .nu = 0.3,
                             .law = &law, .volume = mc_eigen_volume_full(&g, 6, 40e-6),
                             .backend = MC_BACKEND_FFT, .relaxation = 0.7, .tol_outer = 1e-3,
                             .max_outer = 30, .tol_plastic = 1e-4, .max_plastic = 100};
    mc_plastic_result a, b, c;
    mc_contact_summary cs;
    ck_assert_msg(mc_plastic_run(&g, K, s, &pb, p, u, gap, &cs, &a, &err) == MC_OK, "%s",
                  err.msg);
    const size_t nv = (size_t)a.nvol;
    double peq_a = 0;
    for (size_t v = 0; v < nv; v++)
        peq_a = test_worst(peq_a, a.peq[v]);
    ck_assert(peq_a > 0);
    mc_plastic_problem again = pb;
    again.load = 0.6 * pb.load;
    again.load_steps = 1;
    again.eps_p0 = a.eps_p;
    again.peq0 = a.peq;
    ck_assert_msg(mc_plastic_run(&g, K, s, &again, p, u, gap, &cs, &b, &err) == MC_OK, "%s",
                  err.msg);
    ck_assert(memcmp(b.eps_p, a.eps_p, 6 * nv * sizeof(double)) == 0);
    ck_assert(memcmp(b.peq, a.peq, nv * sizeof(double)) == 0);
    ck_assert(memcmp(b.u_r, a.u_r, n * sizeof(double)) == 0);
    /* the same state lent in place (loop.h: state_eps_p, state_peq, state_sig_r, work_sig_e, as
     * the running-in passes it): the same bits, the totals in the lent arrays, which the result
     * does not free; the lent residual and elastic stress arrays start as garbage (never read
     * before they are written) */
    {
        double *e = mc_malloc(6 * nv * sizeof *e), *q = mc_malloc(nv * sizeof *q);
        double *sr = mc_malloc(6 * nv * sizeof *sr), *se = mc_malloc(6 * nv * sizeof *se);
        double *pb_ = mc_malloc(n * sizeof *pb_); /* run b's pressure (the dent shapes it) */
        ck_assert(e && q && sr && se && pb_);
        memcpy(pb_, p, n * sizeof *pb_);
        memcpy(e, a.eps_p, 6 * nv * sizeof *e);
        memcpy(q, a.peq, nv * sizeof *q);
        for (size_t i = 0; i < 6 * nv; i++)
            sr[i] = se[i] = 1e300;
        mc_plastic_problem lent = again;
        lent.eps_p0 = lent.peq0 = NULL;
        lent.state_eps_p = e;
        lent.state_peq = q;
        lent.state_sig_r = sr;
        lent.work_sig_e = se;
        mc_plastic_result l;
        ck_assert_msg(mc_plastic_run(&g, K, s, &lent, p, u, gap, &cs, &l, &err) == MC_OK, "%s",
                      err.msg);
        ck_assert(l.eps_p == e && l.peq == q && l.sig_r == sr && l.lent == 3);
        ck_assert(memcmp(e, b.eps_p, 6 * nv * sizeof(double)) == 0);
        ck_assert(memcmp(q, b.peq, nv * sizeof(double)) == 0);
        ck_assert(memcmp(sr, b.sig_r, 6 * nv * sizeof(double)) == 0);
        ck_assert(memcmp(l.u_r, b.u_r, n * sizeof(double)) == 0);
        ck_assert(memcmp(l.residual_vm, b.residual_vm, nv * sizeof(double)) == 0);
        ck_assert(memcmp(p, pb_, n * sizeof(double)) == 0);
        mc_plastic_result_free(&l); /* leaves the lent arrays */
        ck_assert(l.eps_p == NULL && e[0] == b.eps_p[0]);
        /* lent with eps_p0 too, or only half of the state: refused */
        lent.eps_p0 = a.eps_p;
        ck_assert_int_eq(mc_plastic_run(&g, K, s, &lent, p, u, gap, &cs, &l, &err), MC_ERR_INPUT);
        mc_plastic_result_free(&l);
        lent.eps_p0 = NULL;
        lent.state_peq = NULL;
        ck_assert_int_eq(mc_plastic_run(&g, K, s, &lent, p, u, gap, &cs, &l, &err), MC_ERR_INPUT);
        mc_plastic_result_free(&l);
        mc_free(e);
        mc_free(q);
        mc_free(sr);
        mc_free(se);
        mc_free(pb_);
    }
    again.eps_p0 = again.peq0 = NULL;
    ck_assert_msg(mc_plastic_run(&g, K, s, &again, p, u, gap, &cs, &c, &err) == MC_OK, "%s",
                  err.msg);
    double peq_c = 0;
    for (size_t v = 0; v < nv; v++)
        peq_c = test_worst(peq_c, c.peq[v]);
    ck_assert_msg(peq_c < peq_a, "virgin at 0.6 load: %g, at the full load %g", peq_c, peq_a);
    mc_plastic_result_free(&a);
    mc_plastic_result_free(&b);
    mc_plastic_result_free(&c);
    mc_hardening_free(&law);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
    mc_free(p);
    mc_free(u);
    mc_free(gap);
    mc_threads_end(&scope);
}
END_TEST

/* ---- runs ------------------------------------------------------------------------------------ */

/* Rows k of the run-down and 2m - 1 - k of the run-up are the same speed. */
static void assert_no_hysteresis(const mc_results *r)
{
    const mc_runin_summary *ri = &r->runin;
    const int m = ri->nspeeds;
    ck_assert_int_eq(ri->done, ri->nsteps);
    for (int f = 0; f < ri->nforces; f++) {
        for (int k = 0; k < m; k++) {
            const mc_runin_row *d = &ri->rows[2 * m * f + k], *u = &ri->rows[2 * m * f + 2 * m - 1 - k];
            ck_assert(!d->up && u->up && d->speed == u->speed && !d->plastic);
            /* identical solves from identical states: identical bits */
            ck_assert_double_eq(d->mu, u->mu);
            ck_assert_double_eq(d->p_lub, u->p_lub);
            ck_assert_double_eq(d->psi_load, u->psi_load);
            ck_assert_double_eq(d->pocket_height, u->pocket_height);
            ck_assert_double_eq(d->ra, ri->rows[0].ra);
        }
        ck_assert_double_eq(ri->hysteresis[f], 0.0);
    }
}

/* An elastic material (no [plasticity]) runs in nothing: down and up identical to the bit, the
 * hysteresis exactly zero, the surface unchanged. Periodic, so that the run is quick. The speeds
 * span the regimes on this patch (full film at 1000 rpm, mixed at 600 and 500, dry at 200): the
 * check is not the trivial one of equal full-film rows. */
START_TEST(elastic_material)
{
    mc_scene s;
    const char *set[] = {"runin.speeds=1000, 600, 500, 200 rpm"};
    scene(&s, "periodic_x = yes\nperiodic_y = yes\n", 3, "", 1, set);
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_runin_run(&s, NULL, &r, &err) == MC_OK, "%s", err.msg);
    assert_no_hysteresis(&r);
    int mixed = 0;
    for (int k = 0; k < r.runin.done; k++)
        mixed += r.runin.rows[k].regime == 1;
    ck_assert_msg(mixed > 0, "no step in the mixed regime");
    ck_assert(!r.plastic.enabled && !r.residual_displacement);
    for (size_t i = 0; i < mc_grid_cells(&r.grid); i++)
        ck_assert_double_eq(r.surface_final[i], r.surface_initial[i]);
    mc_results_free(&r);
}
END_TEST

/* A material that never yields (Y = 100 GPa) on a free grid takes the elastic path of every
 * run-down step, with the same result. */
START_TEST(never_yields)
{
    mc_scene s;
    scene(&s, "", 2, "[plasticity]\nyield_stress = 100 GPa\nbodies = both\ndepth = 2 um\n", 0,
          NULL);
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_runin_run(&s, NULL, &r, &err) == MC_OK, "%s", err.msg);
    assert_no_hysteresis(&r);
    ck_assert(r.plastic.enabled && r.plastic.peq_max == 0.0 && r.plastic.residual_max == 0.0);
    mc_results_free(&r);
}
END_TEST

/* The shared run of the elastic-plastic tests (computed once). */
static mc_results plastic_run;
static int plastic_done;

static const mc_results *plastic_reference(void)
{
    if (!plastic_done) {
        mc_scene s;
        scene(&s, "", 2, PLASTIC, 0, NULL);
        mc_error err = {0};
        ck_assert_msg(mc_runin_run(&s, NULL, &plastic_run, &err) == MC_OK, "%s", err.msg);
        plastic_done = 1;
    }
    return &plastic_run;
}

/* Running-in: the surface is smoothed only where something yields, on the run-down; Ra falls
 * there and stays on the run-up. The outputs are consistent: mu is the mix of psi, the final
 * surface is the initial one lowered by the residual displacement of both bodies. */
START_TEST(running_in)
{
    const mc_results *r = plastic_reference();
    const mc_runin_summary *ri = &r->runin;
    const int m = ri->nspeeds;
    int plastic = 0;
    for (int k = 0; k < m; k++) {
        const mc_runin_row *w = &ri->rows[k], *prev = k ? &ri->rows[k - 1] : NULL;
        plastic += w->plastic;
        ck_assert(w->converged && !w->up);
        if (prev && !w->plastic) /* nothing yielded: the surface is the one before */
            ck_assert_double_eq(w->ra, prev->ra);
        if (prev)
            ck_assert_msg(w->ra <= prev->ra, "Ra rose from %g to %g at step %d", prev->ra, w->ra,
                          k + 1);
        /* mu = psi mu_solid + (1 - psi) mu_fluid (psi = psi_load, the default): 3 operations */
        ck_assert_double_eq_tol(w->mu, w->psi_load * 0.12 + (1 - w->psi_load) * 0.03, TOL_TIGHT);
    }
    ck_assert_msg(plastic > 0, "no run-down step yielded");
    ck_assert_msg(ri->rows[m - 1].ra < r->roughness_initial.Ra, "Ra %g did not fall below %g",
                  ri->rows[m - 1].ra, r->roughness_initial.Ra);
    for (int k = m; k < 2 * m; k++) { /* the run-up is elastic: the surface stays */
        ck_assert(ri->rows[k].up && !ri->rows[k].plastic);
        ck_assert_double_eq(ri->rows[k].ra, ri->rows[m - 1].ra);
        ck_assert_double_eq(ri->rows[k].residual_max, ri->rows[m - 1].residual_max);
    }
    ck_assert_double_eq(r->roughness_final.Ra, ri->rows[2 * m - 1].ra);
    const size_t n = mc_grid_cells(&r->grid);
    double umax = 0;
    for (size_t i = 0; i < n; i++) {
        ck_assert_double_eq(r->surface_final[i],
                            -(r->topography[i] + 2.0 * r->residual_displacement[i]));
        ck_assert_double_eq(r->surface_initial[i], -r->topography[i]);
        umax = test_worst(umax, r->residual_displacement[i]);
    }
    ck_assert_double_eq(umax, r->plastic.residual_max);
    ck_assert(r->plastic.peq_max > 0 && isfinite(ri->hysteresis[0]));
}
END_TEST

/* The plastic memory guard of the running-in (pipeline/memguard.h): once its volume is planned
 * (here 32 x 16 x 5 layers of 0.4 um: depth and dz set), a limit one byte below the estimate
 * refuses the run before the volume arrays are allocated, naming the running-in and the volume;
 * the limit at the estimate itself lets it run (the estimate is what the guard compares). The
 * pre-run guard (mc_memory_check) passes at both limits: the refusal is the plastic guard's. */
START_TEST(plastic_guard)
{
    mc_scene s;
    const char *set[] = {"runin.speeds=200 rpm", "lubrication.rpm=200 rpm"};
    scene(&s, "", 2, PLASTIC, 2, set);
    mc_eigen_volume v = mc_eigen_volume_full(&s.grid, 5, 0.4e-6);
    v.stress_points = s.plasticity.stress_points;
    v.kernel = s.plasticity.kernel;
    const double pre = mc_memory_estimate(&s), need = pre + mc_memory_estimate_runin(&s, &s.grid, &v);
    ck_assert(need > pre + 5 * 32 * 16 * 280.0); /* at least the loop's dense arrays */
    char lim[64];
    snprintf(lim, sizeof lim, "%.0f", floor(need) - 1);
    setenv("MC_MEMORY_LIMIT", lim, 1);
    mc_results r;
    mc_error err = {0};
    int rc = mc_runin_run(&s, NULL, &r, &err);
    ck_assert_int_eq(rc, MC_ERR_NOMEM);
    ck_assert_msg(strstr(err.msg, "the running-in needs about") &&
                      strstr(err.msg, "plastic volume 32 x 16 x 5 cells"),
                  "%s", err.msg);
    mc_results_free(&r);
    snprintf(lim, sizeof lim, "%.0f", ceil(need));
    setenv("MC_MEMORY_LIMIT", lim, 1);
    rc = mc_runin_run(&s, NULL, &r, &err);
    unsetenv("MC_MEMORY_LIMIT");
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
    ck_assert(r.runin.rows[0].plastic && r.plastic.volume_cells == 5 * 32 * 16);
    mc_results_free(&r);
}
END_TEST

/* A single elastic-plastic run with the lubricant volume equilibrium (no [runin]): the loop
 * solves every contact with the current p_lub; the returned state meets the equilibrium on its
 * own gap, the load splits, and something yielded. 800 rpm is mixed on this patch. */
START_TEST(lubricated_plastic_stage)
{
    mc_scene s;
    const char *set[] = {"runin.enabled=no", "lubrication.rpm=800 rpm"};
    scene(&s, "", 2, PLASTIC, 2, set);
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    const mc_stage_lube_summary *l = &r.lube;
    ck_assert(r.plastic.enabled && r.plastic.converged && r.plastic.residual_max > 0);
    ck_assert_str_eq(l->regime, "mixed");
    const size_t n = mc_grid_cells(&r.grid);
    const double dA = mc_grid_cell_area(&r.grid), a_nom = dA * (double)n;
    double v = 0, f_solid = 0, a_c = 0;
    for (size_t i = 0; i < n; i++) {
        v += dA * r.gap[i];
        if (r.pressure[i] > l->p_lub) {
            f_solid += dA * r.pressure[i];
            a_c += dA;
        }
    }
    /* the root tolerance 1e-6 plus the contact tolerance's share (1e-8 x the gap scale) */
    ck_assert_msg(fabs(v - l->h_ehd * a_nom) <= 2e-6 * l->h_ehd * a_nom, "V = %g, V* = %g", v,
                  l->h_ehd * a_nom);
    /* the load splits between the solids and the fluid, to the contact tolerance (1e-8) */
    ck_assert_msg(fabs(f_solid + l->p_lub * (a_nom - a_c) - l->patch_load) <=
                      1e-6 * l->patch_load,
                  "F = %g of %g", f_solid + l->p_lub * (a_nom - a_c), l->patch_load);
    ck_assert(l->p_lub > 0 && l->p_lub < l->nominal_pressure);
    mc_results_free(&r);
}
END_TEST

/* ---- what shows running-in: the ISO columns, the material-ratio curves, the figures --------- */

/* The lines of a file written by a run (at most max; each malloc'ed, newline removed). */
static int read_lines(const char *dir, const char *name, char **lines, int max)
{
    char path[700], buf[8192];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    int n = 0;
    while (n < max && fgets(buf, sizeof buf, f)) {
        buf[strcspn(buf, "\n")] = '\0';
        lines[n] = strdup(buf);
        ck_assert(lines[n] != NULL);
        n++;
    }
    ck_assert_msg(!fgets(buf, sizeof buf, f), "%s has more than %d lines", path, max);
    fclose(f);
    return n;
}

/* 0-based column of name in a CSV header line (-1: none). */
static int csv_col(const char *header, const char *name)
{
    const size_t len = strlen(name);
    int col = 0;
    for (const char *p = header;; col++) {
        const char *q = strchr(p, ',');
        size_t l = q ? (size_t)(q - p) : strlen(p);
        if (l == len && strncmp(p, name, len) == 0)
            return col;
        if (!q)
            return -1;
        p = q + 1;
    }
}

/* Field col of a CSV line as a number (the test fails when it is not one). */
static double csv_num(const char *line, int col)
{
    const char *p = line;
    for (int c = 0; c < col; c++) {
        p = strchr(p, ',');
        ck_assert_msg(p != NULL, "no column %d in '%s'", col, line);
        p++;
    }
    char *end;
    double v = strtod(p, &end);
    ck_assert_msg(end != p && (*end == ',' || *end == '\0'), "column %d of '%s' is no number",
                  col, line);
    return v;
}

/* Does text hold name as a word (no letter, digit or '_' on either side)? */
static int has_word(const char *text, const char *name)
{
    const size_t len = strlen(name);
    for (const char *p = strstr(text, name); p; p = strstr(p + 1, name)) {
        int before = p > text && (isalnum((unsigned char)p[-1]) || p[-1] == '_');
        int after = isalnum((unsigned char)p[len]) || p[len] == '_';
        if (!before && !after)
            return 1;
    }
    return 0;
}

/* The roughness columns of runin.csv, the parameter of mc_roughness_params each holds and the
 * field of the row (results.h) it comes from. */
static const struct {
    const char *name;
    size_t param, row;
} iso_cols[] = {
#define ISO(n, f) {#n, offsetof(mc_roughness_params, n), offsetof(mc_runin_row, f)}
    ISO(Ra, ra),   ISO(Rq, rq),   ISO(Rz, rz),   ISO(Sa, sa),   ISO(Sq, sq),     ISO(Rpk, rpk),
    ISO(Rk, rk),   ISO(Rvk, rvk), ISO(Mr1, mr1), ISO(Mr2, mr2), ISO(Sp, sp),     ISO(Spk, spk),
    ISO(Sk, sk),   ISO(Svk, svk), ISO(Smr1, smr1), ISO(Smr2, smr2),
#undef ISO
};
#define N_ISO ((int)(sizeof iso_cols / sizeof iso_cols[0]))

static double field_at(const void *base, size_t off)
{
    double v;
    memcpy(&v, (const char *)base + off, sizeof v);
    return v;
}

/* The Mr (%) at which a non-increasing sampled curve (Mr_k = 100 k / (n - 1)) falls to level:
 * below it (strict) or to it (at), linear between the samples. */
static double crossing(const double *mr, const double *h, int n, double level, int strict)
{
    for (int k = 0; k < n; k++)
        if (strict ? h[k] < level : h[k] <= level) {
            if (k == 0)
                return mr[0];
            double t = (h[k - 1] - level) / (h[k - 1] - h[k]);
            return mr[k - 1] + t * (mr[k] - mr[k - 1]);
        }
    return mr[n - 1];
}

/* runin.csv's roughness columns read back equal the roughness module's parameters recomputed
 * here from the written surface_initial.npy (rows before the first yielding step) and
 * surface_final.npy (rows from the last yielding step on), and the driver's rows in between;
 * material_ratio.csv holds the areal curves of the two files: non-increasing, from Sp down to
 * -Sv, crossing its equivalent straight line's ends at Smr1 and Smr2 of the csv; docs/outputs.md
 * names the columns; runin.gp draws its five figures (where gnuplot is installed). */
START_TEST(iso_columns)
{
    const mc_results *r = plastic_reference();
    const mc_runin_summary *ri = &r->runin;
    mc_scene s;
    scene(&s, "", 2, PLASTIC, 0, NULL);
    char dir[700];
    snprintf(dir, sizeof dir, "%s/out", test_tmpdir());
    mc_error err = {0};
    ck_assert_msg(mc_output_write(dir, &s, r, &err) == MC_OK, "%s", err.msg);
    /* the parameters of the written surfaces, with the options the driver documents: those of
     * roughness.initial (no [roughness] cutoff: rows levelled, not filtered) */
    mc_roughness_options o;
    mc_roughness_options_default(&o);
    o.cutoff = s.roughness.cutoff;
    o.filter = s.roughness.cutoff > 0;
    o.periodic_x = s.grid.periodic_x;
    o.periodic_y = s.grid.periodic_y;
    const char *files[2] = {"surface_initial.npy", "surface_final.npy"};
    mc_roughness_params p[2];
    double *z[2];
    int nx = 0, ny = 0;
    for (int k = 0; k < 2; k++) {
        char path[800];
        snprintf(path, sizeof path, "%s/%s", dir, files[k]);
        ck_assert_msg(mc_npy_read(path, &z[k], &ny, &nx, &err) == MC_OK, "%s", err.msg);
        ck_assert(nx == s.grid.nx && ny == s.grid.ny);
        ck_assert_msg(mc_roughness_compute(z[k], NULL, nx, ny, s.grid.dx, s.grid.dy, &o, &p[k],
                                           &err) == MC_OK,
                      "%s", err.msg);
        /* Sp from its definition: the highest point above the mean plane */
        double mean = 0, hi = -INFINITY;
        for (int i = 0; i < nx * ny; i++)
            mean += z[k][i];
        mean /= nx * ny;
        for (int i = 0; i < nx * ny; i++)
            hi = test_worst(hi, z[k][i] - mean);
        ck_assert_double_eq_tol(p[k].Sp, hi, TOL_ROUNDOFF * p[k].Sq);
    }
    ck_assert_msg(p[1].Sp < p[0].Sp && p[1].Spk < p[0].Spk, "the peaks did not fall: Sp %g -> %g",
                  p[0].Sp, p[1].Sp);
    char *lines[64];
    int nl = read_lines(dir, "runin.csv", lines, 64);
    ck_assert_int_eq(nl, ri->done + 1);
    int first_plastic = -1, last_plastic = -1;
    for (int k = 0; k < ri->done; k++)
        if (ri->rows[k].plastic) {
            first_plastic = first_plastic < 0 ? k : first_plastic;
            last_plastic = k;
        }
    ck_assert(first_plastic > 0); /* at least one row of each surface */
    int ncols = 1;
    for (const char *c = lines[0]; (c = strchr(c, ',')); c++)
        ncols++;
    for (int k = 0; k < ri->done; k++) {
        int n = 1;
        for (const char *c = lines[k + 1]; (c = strchr(c, ',')); c++)
            n++;
        ck_assert_int_eq(n, ncols);
        const mc_roughness_params *want = k < first_plastic   ? &p[0]
                                          : k >= last_plastic ? &p[1]
                                                              : NULL;
        for (int c = 0; c < N_ISO; c++) {
            int col = csv_col(lines[0], iso_cols[c].name);
            ck_assert_msg(col >= 0, "runin.csv has no column %s", iso_cols[c].name);
            double v = csv_num(lines[k + 1], col);
            /* %.17g reads back to the bit; the recomputation is the same function on the same
             * heights (the .npy holds them to the bit): equality */
            double ref = want ? field_at(want, iso_cols[c].param)
                              : field_at(&ri->rows[k], iso_cols[c].row);
            ck_assert_msg(v == ref, "row %d %s: csv %.17g, recomputed %.17g", k + 1,
                          iso_cols[c].name, v, ref);
        }
    }
    /* material_ratio.csv */
    char *mr_lines[1100];
    int nm = read_lines(dir, "material_ratio.csv", mr_lines, 1100);
    ck_assert_int_ge(nm, 3);
    const int npts = nm - 1;
    double *mr = malloc(sizeof(double) * 5 * (size_t)npts);
    ck_assert(mr != NULL);
    const char *mcols[5] = {"Mr", "initial", "final", "line_initial", "line_final"};
    for (int c = 0; c < 5; c++) {
        int col = csv_col(mr_lines[0], mcols[c]);
        ck_assert_msg(col >= 0, "material_ratio.csv has no column %s", mcols[c]);
        for (int k = 0; k < npts; k++)
            mr[c * npts + k] = csv_num(mr_lines[k + 1], col);
    }
    const char *smr1 = "Smr1", *smr2 = "Smr2";
    for (int k = 0; k < 2; k++) {
        const double *h = mr + (1 + k) * npts, *line = mr + (3 + k) * npts;
        const char *row = lines[k ? ri->done : 1]; /* the first row: the initial surface */
        for (int i = 0; i < npts; i++) {
            ck_assert_double_eq_tol(mr[i], 100.0 * i / (npts - 1), TOL_TIGHT * 100);
            if (i)
                ck_assert_msg(h[i] <= h[i - 1], "%s: the curve rises at Mr = %g %%", mcols[1 + k],
                              mr[i]);
        }
        ck_assert_double_eq(h[0], p[k].Sp);
        ck_assert_double_eq(h[npts - 1], -p[k].Sv);
        /* the equivalent straight line: its drop over 0 .. 100 % is Sk (round-off of the
         * line's evaluation, a few ulp of heights of 1e-7 m) */
        const double sk = csv_num(row, csv_col(lines[0], "Sk"));
        ck_assert_double_eq_tol(line[0] - line[npts - 1], sk, TOL_ROUNDOFF * sk);
        /* where the curve crosses the line's ends: Smr1 (heights above c0) and Smr2 (at or
         * above c100). The n heights sit at Mr = 100 (j + 1/2) / n, so the crossing of the
         * piecewise-linear curve lies within 50 / n % of the share, and the sampling of the file
         * (step 100 / (npts - 1)) adds at most one step. */
        const double tol = 50.0 / (nx * ny) + 100.0 / (npts - 1);
        const double c1 = crossing(mr, h, npts, line[0], 0);
        const double c2 = crossing(mr, h, npts, line[npts - 1], 1);
        const double want1 = csv_num(row, csv_col(lines[0], smr1));
        const double want2 = csv_num(row, csv_col(lines[0], smr2));
        if (getenv("MC_TEST_VERBOSE"))
            printf("material ratio %s: crossings %.3f %% (Smr1 %.3f %%), %.3f %% (Smr2 %.3f %%), "
                   "tolerance %.3f %%\n", mcols[1 + k], c1, want1, c2, want2, tol);
        ck_assert_msg(fabs(c1 - want1) <= tol, "%s: the curve crosses c0 at %g %%, Smr1 %g %%",
                      mcols[1 + k], c1, want1);
        ck_assert_msg(fabs(c2 - want2) <= tol, "%s: the curve crosses c100 at %g %%, Smr2 %g %%",
                      mcols[1 + k], c2, want2);
    }
    /* docs/outputs.md (generated from the output table, test_output checks that) names every
     * roughness column of runin.csv */
    FILE *f = fopen("docs/outputs.md", "r");
    ck_assert_msg(f != NULL, "cannot open docs/outputs.md (run the tests from the repository root)");
    char doc[8192];
    int found = 0;
    while (fgets(doc, sizeof doc, f))
        if (strncmp(doc, "| `runin.csv` |", 15) == 0) {
            found = 1;
            break;
        }
    fclose(f);
    ck_assert_msg(found, "docs/outputs.md has no row of runin.csv");
    for (int c = 0; c < N_ISO; c++)
        ck_assert_msg(has_word(doc, iso_cols[c].name), "docs/outputs.md: runin.csv lacks %s",
                      iso_cols[c].name);
    ck_assert(has_word(doc, "Rpk") && !has_word(doc, "Rp")); /* has_word tells words apart */
    /* the figures, where gnuplot is there to draw them */
    if (system("command -v gnuplot > /dev/null 2>&1") == 0) {
        char cmd[900];
        snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot runin.gp > gnuplot.log 2>&1", dir);
        ck_assert_msg(system(cmd) == 0, "gnuplot runin.gp failed (%s/gnuplot.log)", dir);
        const char *png[] = {"runin_ra.png", "runin_psi.png", "runin_mu.png", "runin_mr.png",
                             "runin_surface.png"};
        for (size_t k = 0; k < sizeof png / sizeof png[0]; k++) {
            char path[800];
            struct stat sb;
            snprintf(path, sizeof path, "%s/%s", dir, png[k]);
            ck_assert_msg(stat(path, &sb) == 0 && sb.st_size > 1000, "no figure %s", path);
        }
        char *log[4];
        int nlog = read_lines(dir, "gnuplot.log", log, 4);
        ck_assert_msg(nlog == 0, "gnuplot said: %s", nlog ? log[0] : "");
    }
    for (int k = 0; k < nl; k++)
        free(lines[k]);
    for (int k = 0; k < nm; k++)
        free(mr_lines[k]);
    free(mr);
    mc_free(z[0]);
    mc_free(z[1]);
}
END_TEST

/* ---- checkpoints and resume ----------------------------------------------------------------- */

typedef struct {
    int steps;     /* progress calls seen */
    int polls;     /* stop polls since the last step */
    int stop_step; /* stop once this many steps are done ... */
    int stop_poll; /* ... and this many polls have been made since (0: at once) */
} stopper;

static void count_step(void *ctx, const mc_runin_progress *p)
{
    stopper *s = ctx;
    s->steps = p->step;
    s->polls = 0;
}

static int stop_now(void *ctx)
{
    stopper *s = ctx;
    return s->steps >= s->stop_step && ++s->polls > s->stop_poll;
}

static void assert_same_rows(const mc_results *a, const mc_results *b)
{
    ck_assert_int_eq(a->runin.done, b->runin.done);
    for (int k = 0; k < a->runin.done; k++) {
        mc_runin_row x = a->runin.rows[k], y = b->runin.rows[k];
        x.seconds = y.seconds = 0; /* the one column that may differ */
        ck_assert_msg(memcmp(&x, &y, sizeof x) == 0, "row %d differs", k + 1);
    }
    const size_t n = mc_grid_cells(&a->grid);
    ck_assert(memcmp(a->pressure, b->pressure, n * sizeof(double)) == 0);
    ck_assert(memcmp(a->gap, b->gap, n * sizeof(double)) == 0);
    ck_assert(memcmp(a->surface_final, b->surface_final, n * sizeof(double)) == 0);
    ck_assert_int_eq(a->plastic.nz, b->plastic.nz);
    ck_assert(memcmp(a->plastic_strain, b->plastic_strain,
                     n * (size_t)a->plastic.nz * sizeof(double)) == 0);
    ck_assert(memcmp(a->residual_von_mises, b->residual_von_mises,
                     n * (size_t)a->plastic.nz * sizeof(double)) == 0);
    ck_assert_int_eq(a->plastic.steps_done, b->plastic.steps_done);
    ck_assert(memcmp(a->plastic.steps, b->plastic.steps,
                     (size_t)a->plastic.steps_done * sizeof *a->plastic.steps) == 0);
    for (int f = 0; f < a->runin.nforces; f++)
        ck_assert_double_eq(a->runin.hysteresis[f], b->runin.hysteresis[f]);
}

/* Stopped between steps (before any yielding, and between two elastic-plastic steps: the second
 * needs the plastic strain, hardening and residual stress of the first from the checkpoint), and
 * inside an elastic-plastic step: resumed, the run ends with the uninterrupted run's rows and
 * fields, bit for bit. */
START_TEST(resume_identical)
{
    const mc_results *ref = plastic_reference();
    /* the first plastic step: stop inside it (after its first outer iteration) */
    int first_plastic = -1, last_plastic = -1;
    for (int k = 0; k < ref->runin.done; k++)
        if (ref->runin.rows[k].plastic) {
            first_plastic = first_plastic < 0 ? k : first_plastic;
            last_plastic = k;
        }
    ck_assert(first_plastic >= 0 && first_plastic + 1 < ref->runin.done &&
              ref->runin.rows[first_plastic + 1].plastic && last_plastic + 1 < ref->runin.done);
    /* the last stop resumes after every plastic step: the residual stress comes from the file */
    const struct {
        int step, poll;
    } stops[] = {{1, 0}, {first_plastic, 1}, {first_plastic + 1, 0}, {last_plastic + 1, 0}};
    for (size_t t = 0; t < sizeof stops / sizeof stops[0]; t++) {
        char dir[512];
        snprintf(dir, sizeof dir, "%s/ck", test_tmpdir());
        mc_scene s;
        scene(&s, "", 2, PLASTIC, 0, NULL);
        stopper st = {.stop_step = stops[t].step, .stop_poll = stops[t].poll};
        mc_runin_options opt = {.checkpoint_dir = dir,
                                .progress = count_step,
                                .progress_ctx = &st,
                                .stop = stop_now,
                                .stop_ctx = &st};
        mc_results r;
        mc_error err = {0};
        ck_assert_int_eq(mc_runin_run(&s, &opt, &r, &err), MC_ERR_INTERRUPTED);
        ck_assert_int_eq(r.runin.done, stops[t].step);
        mc_results_free(&r);
        ck_assert(mc_checkpoint_exists(dir));
        mc_runin_options again = {.checkpoint_dir = dir, .resume = 1};
        ck_assert_msg(mc_runin_run(&s, &again, &r, &err) == MC_OK, "%s", err.msg);
        ck_assert_int_eq(r.runin.resumed_from, stops[t].step);
        assert_same_rows(ref, &r);
        mc_results_free(&r);
        /* a finished run's checkpoint resumes to the same results too */
        ck_assert_msg(mc_runin_run(&s, &again, &r, &err) == MC_OK, "%s", err.msg);
        assert_same_rows(ref, &r);
        mc_results_free(&r);
        mc_checkpoint_remove(dir);
        ck_assert(!mc_checkpoint_exists(dir));
    }
}
END_TEST

/* Resume is refused without a checkpoint, from another case (another seed, or a --set value),
 * and from a torn file; the refusal leaves the checkpoint where it is. */
START_TEST(resume_refused)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s/ck", test_tmpdir());
    mc_scene s;
    scene(&s, "periodic_x = yes\nperiodic_y = yes\n", 2, "", 0, NULL);
    mc_runin_options again = {.checkpoint_dir = dir, .resume = 1};
    mc_results r;
    mc_error err = {0};
    ck_assert_int_eq(mc_runin_run(&s, &again, &r, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "no checkpoint to resume"), "%s", err.msg);
    mc_results_free(&r);
    stopper st = {.stop_step = 2};
    mc_runin_options opt = {.checkpoint_dir = dir,
                            .progress = count_step,
                            .progress_ctx = &st,
                            .stop = stop_now,
                            .stop_ctx = &st};
    ck_assert_int_eq(mc_runin_run(&s, &opt, &r, &err), MC_ERR_INTERRUPTED);
    mc_results_free(&r);
    mc_scene other;
    scene(&other, "periodic_x = yes\nperiodic_y = yes\n", 3, "", 0, NULL);
    ck_assert_int_eq(mc_runin_run(&other, &again, &r, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "belongs to another case"), "%s", err.msg);
    mc_results_free(&r);
    const char *set[] = {"lubrication.mu_solid=0.13"};
    scene(&other, "periodic_x = yes\nperiodic_y = yes\n", 2, "", 1, set);
    ck_assert_int_eq(mc_runin_run(&other, &again, &r, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "belongs to another case"), "%s", err.msg);
    mc_results_free(&r);
    ck_assert(mc_checkpoint_exists(dir));
    /* the same case from another path, or into another output directory, is the same case */
    mc_scene same = s;
    snprintf(same.path, sizeof same.path, "elsewhere/r.ini");
    snprintf(same.output.dir, sizeof same.output.dir, "other_out");
    ck_assert_msg(mc_runin_run(&same, &again, &r, &err) == MC_OK, "%s", err.msg);
    mc_results_free(&r);
    /* a flipped byte in the middle of the file */
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, MC_CHECKPOINT_FILE);
    FILE *f = fopen(path, "r+b");
    ck_assert(f != NULL);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, size / 2, SEEK_SET);
    int c = fgetc(f);
    fseek(f, size / 2, SEEK_SET);
    fputc(c ^ 0x10, f);
    fclose(f);
    ck_assert_int_eq(mc_runin_run(&s, &again, &r, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "checksum differs"), "%s", err.msg);
    mc_results_free(&r);
}
END_TEST

/* The file itself: a round trip keeps every value; a truncated file is refused. */
START_TEST(checkpoint_round_trip)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s/ck", test_tmpdir());
    enum { NX = 5, NY = 3, NZ = 2, NV = NX * NY * NZ };
    double eps[6 * NV], peq[NV], sig[6 * NV], ur[NX * NY];
    test_random_field(eps, 6 * NV, 1);
    test_random_field(peq, NV, 2);
    test_random_field(sig, 6 * NV, 3);
    test_random_field(ur, NX * NY, 4);
    mc_runin_row rows[2];
    memset(rows, 0, sizeof rows);
    rows[1].mu = 0.07;
    rows[1].up = 1;
    mc_plastic_step rec;
    memset(&rec, 0, sizeof rec);
    rec.peq_max = 0.25;
    mc_checkpoint w = {.case_hash = 0x0123456789abcdefull, .nx = NX, .ny = NY, .nz = NZ,
                       .nvol = NV, .nsteps = 8, .done = 2, .seconds = 3.5, .rows = rows,
                       .eps_p = eps, .peq = peq, .sig_r = sig, .u_r = ur, .nrec = 1,
                       .records = &rec};
    mc_error err = {0};
    ck_assert_msg(mc_checkpoint_write(dir, &w, &err) == MC_OK, "%s", err.msg);
    mc_checkpoint c;
    ck_assert_msg(mc_checkpoint_read(dir, &c, &err) == MC_OK, "%s", err.msg);
    ck_assert(c.case_hash == w.case_hash && c.nx == NX && c.ny == NY && c.nz == NZ &&
              c.nvol == NV && c.nsteps == 8 && c.done == 2 && c.seconds == 3.5 && c.nrec == 1);
    ck_assert(memcmp(c.rows, rows, sizeof rows) == 0);
    ck_assert(memcmp(c.eps_p, eps, sizeof eps) == 0 && memcmp(c.peq, peq, sizeof peq) == 0 &&
              memcmp(c.sig_r, sig, sizeof sig) == 0 && memcmp(c.u_r, ur, sizeof ur) == 0);
    ck_assert_double_eq(c.records[0].peq_max, 0.25);
    mc_checkpoint_free(&c);
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, MC_CHECKPOINT_FILE);
    ck_assert_int_eq(truncate(path, 100), 0);
    ck_assert_int_eq(mc_checkpoint_read(dir, &c, &err), MC_ERR_INPUT);
    mc_checkpoint_free(&c);
    mc_checkpoint_remove(dir);
    struct stat sb;
    ck_assert(stat(dir, &sb) != 0); /* the directory went with its file */
}
END_TEST

/* A checkpoint whose fields are not finite (a run gone wrong, or a file altered with its checksum
 * recomputed) is refused at read time, naming the checkpoint and the field (issue 23, class 6). */
START_TEST(checkpoint_nonfinite)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s/ckn%d", test_tmpdir(), _i);
    enum { NX = 4, NY = 2, NZ = 2, NV = NX * NY * NZ };
    double eps[6 * NV] = {0}, peq[NV] = {0}, sig[6 * NV] = {0}, ur[NX * NY] = {0};
    mc_runin_row rows[1];
    memset(rows, 0, sizeof rows);
    mc_checkpoint w = {.case_hash = 1, .nx = NX, .ny = NY, .nz = NZ, .nvol = NV, .nsteps = 4,
                       .done = 1, .seconds = 1.0, .rows = rows, .eps_p = eps, .peq = peq,
                       .sig_r = sig, .u_r = ur};
    static const char *const names[] = {"plastic strain", "accumulated plastic strain",
                                        "residual stress", "residual displacement",
                                        "elapsed seconds"};
    double *bad[] = {&eps[7], &peq[3], &sig[6 * NV - 1], &ur[5], &w.seconds};
    *bad[_i] = _i % 2 ? INFINITY : NAN;
    mc_error err = {0};
    ck_assert_msg(mc_checkpoint_write(dir, &w, &err) == MC_OK, "%s", err.msg);
    mc_checkpoint c;
    ck_assert_int_eq(mc_checkpoint_read(dir, &c, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, MC_CHECKPOINT_FILE) && strstr(err.msg, names[_i]) &&
                      strstr(err.msg, "not finite"),
                  "%s", err.msg);
    mc_checkpoint_free(&c);
    mc_checkpoint_remove(dir);
}
END_TEST

/* ---- friction in the yield check ([runin] friction_in_yield) ------------------------------ */

/* The PLASTIC scene, rolling-sliding (disc 2 10 % faster than disc 1), with extra --set values. */
static void run_sliding(int nset, const char *const *set, mc_results *r)
{
    const char *all[8] = {"lubrication.rpm2=1100 rpm"};
    for (int k = 0; k < nset; k++)
        all[k + 1] = set[k];
    mc_scene s;
    scene(&s, "", 2, PLASTIC, nset + 1, all);
    mc_error err = {0};
    ck_assert_msg(mc_runin_run(&s, NULL, r, &err) == MC_OK, "%s", err.msg);
}

static int plastic_steps(const mc_results *r)
{
    int n = 0;
    for (int k = 0; k < r->runin.done; k++)
        n += r->runin.rows[k].plastic;
    return n;
}

/* mu = 0 (mu_solid = mu_fluid = 0): the option changes nothing, to the bit. */
START_TEST(friction_zero_identical)
{
    const char *off[] = {"lubrication.mu_solid=0", "lubrication.mu_fluid=0"};
    const char *on[] = {"lubrication.mu_solid=0", "lubrication.mu_fluid=0",
                        "runin.friction_in_yield=yes"};
    mc_results a, b;
    run_sliding(2, off, &a);
    run_sliding(3, on, &b);
    ck_assert_int_gt(plastic_steps(&a), 0);
    assert_same_rows(&a, &b);
    mc_results_free(&a);
    mc_results_free(&b);
}
END_TEST

/* A step with the option is the plastic stage with that step's mu as [plasticity] friction: with
 * mu_solid = mu_fluid = 0.125 every step's mu is 0.125 exactly (psi 0.125 + (1 - psi) 0.125: a
 * power of two scales the sum psi + (1 - psi), which rounds to 1), so the run must equal the one
 * with [plasticity] friction = 0.125 to the bit; and the traction must act (the run without it
 * ends on another surface). */
START_TEST(friction_step_mu)
{
    const char *on[] = {"lubrication.mu_solid=0.125", "lubrication.mu_fluid=0.125",
                        "runin.friction_in_yield=yes"};
    const char *stage[] = {"lubrication.mu_solid=0.125", "lubrication.mu_fluid=0.125",
                           "plasticity.friction=0.125"};
    const char *none[] = {"lubrication.mu_solid=0.125", "lubrication.mu_fluid=0.125"};
    mc_results a, b, c;
    run_sliding(3, on, &a);
    run_sliding(3, stage, &b);
    run_sliding(2, none, &c);
    ck_assert_int_gt(plastic_steps(&a), 0);
    for (int k = 0; k < a.runin.done; k++)
        ck_assert_double_eq(a.runin.rows[k].mu, 0.125);
    assert_same_rows(&a, &b);
    const size_t n = mc_grid_cells(&a.grid);
    double d = 0;
    for (size_t i = 0; i < n; i++)
        d = test_worst(d, fabs(a.residual_displacement[i] - c.residual_displacement[i]));
    ck_assert_msg(d > 1e-3 * a.plastic.residual_max, "the traction changed u_r by only %g of %g",
                  d, a.plastic.residual_max);
    mc_results_free(&a);
    mc_results_free(&b);
    mc_results_free(&c);
}
END_TEST

/* The traction follows the sliding. Disc 2 faster (+x) on surface z, against disc 1 faster (-x)
 * on the x-mirrored surface: the second run is the mirror image of the first (the problem is;
 * the grid's cell centres are symmetric), up to round-off. The same surface with the two
 * directions differs by the traction's effect, which bounds the mirror error from above: a sign
 * that did not follow the sliding would make the mirror error as large as that effect. */
START_TEST(friction_sign)
{
    mc_scene s0;
    scene(&s0, "", 2, "", 0, NULL);
    const int nx = s0.grid.nx, ny = s0.grid.ny;
    const size_t n = mc_grid_cells(&s0.grid);
    double *z = mc_zeros(n), *zm = mc_zeros(n);
    mc_error err = {0};
    ck_assert(z && zm);
    ck_assert_msg(mc_surface_topography(&s0.grid, &s0.geometry, &s0.roughness, z, &err) == MC_OK,
                  "%s", err.msg);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            zm[(size_t)j * nx + i] = -z[(size_t)j * nx + (nx - 1 - i)];
    for (size_t i = 0; i < n; i++)
        z[i] = -z[i]; /* heights: a flat shape, h0 = -z */
    char fz[512], fm[512];
    snprintf(fz, sizeof fz, "%s/z.npy", test_tmpdir());
    snprintf(fm, sizeof fm, "%s/zm.npy", test_tmpdir());
    const size_t shape[2] = {(size_t)ny, (size_t)nx};
    ck_assert(mc_npy_write(fz, z, 2, shape, &err) == MC_OK);
    ck_assert(mc_npy_write(fm, zm, 2, shape, &err) == MC_OK);
    static const char *const TEXT =
        "[mesh]\nnx = %d\nny = %d\ndx = 0.8 um\n"
        "[roughness]\ntype = file\nfile = %s\nunits = m\ndetrend = none\n"
        "[load]\nforce = 1086 N\nlubricant_pressure = auto\n"
        "[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\nrpm = %s rpm\n"
        "rpm2 = %s rpm\nradius1 = 40 mm\nradius2 = 40 mm\nwidth = 10 mm\nmu_solid = 0.12\n"
        "mu_fluid = 0.03\n[solver]\nthreads = 1\n"
        "[runin]\nspeeds = %s rpm\nfriction_in_yield = yes\n%s";
    const struct {
        const char *file, *rpm, *rpm2, *speeds;
    } runs[3] = {{fz, "1000", "1100", "1000, 500, 200"},  /* disc 2 faster: +x */
                 {fz, "1100", "1000", "1100, 550, 220"},  /* disc 1 faster: -x, same u */
                 {fm, "1100", "1000", "1100, 550, 220"}}; /* the same, mirrored surface */
    mc_results r[3];
    for (int k = 0; k < 3; k++) {
        char text[4096];
        snprintf(text, sizeof text, TEXT, nx, ny, runs[k].file, runs[k].rpm, runs[k].rpm2,
                 runs[k].speeds, PLASTIC);
        mc_scene s;
        ck_assert_msg(mc_case_parse_text(text, "r.ini", "", 0, NULL, &s, &err) == MC_OK, "%s",
                      err.msg);
        ck_assert_msg(mc_runin_run(&s, NULL, &r[k], &err) == MC_OK, "%s", err.msg);
        ck_assert_int_gt(plastic_steps(&r[k]), 0);
    }
    double d_dir = 0, d_mirror = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const size_t a = (size_t)j * nx + i, m = (size_t)j * nx + (nx - 1 - i);
            d_dir = test_worst(d_dir, fabs(r[0].residual_displacement[a] -
                                     r[1].residual_displacement[a]));
            d_mirror = test_worst(d_mirror, fabs(r[0].residual_displacement[a] -
                                           r[2].residual_displacement[m]));
        }
    if (getenv("MC_TEST_VERBOSE"))
        printf("friction_sign: max |u_r(+x) - u_r(-x)| %.3e m, mirror error %.3e m (u_r max "
               "%.3e m)\n",
               d_dir, d_mirror, r[0].plastic.residual_max);
    /* MIRROR_TOL: the mirrored run differs only by the round-off of the mirrored sums and of the
     * speeds' unit conversions, carried through solves to 1e-8 and a plastic fixed point to
     * 1e-5 relative, i.e. far below the traction's own effect; 1e-3 of that effect */
    const double MIRROR_TOL = 1e-3;
    ck_assert_msg(d_dir > 1e-3 * r[0].plastic.residual_max, "the direction has no effect: %g",
                  d_dir);
    ck_assert_msg(d_mirror <= MIRROR_TOL * d_dir, "mirror error %g against the direction's %g",
                  d_mirror, d_dir);
    for (int k = 0; k < 3; k++)
        mc_results_free(&r[k]);
    mc_free(z);
    mc_free(zm);
}
END_TEST

/* Computed once, before the tests of the case fork (unchecked fixture): they share it. */
static void setup(void) { (void)plastic_reference(); }

static void teardown(void)
{
    if (plastic_done)
        mc_results_free(&plastic_run);
    plastic_done = 0;
}

Suite *suite_runin(void);
Suite *suite_runin(void)
{
    Suite *s = suite_create("runin");
    TCase *t = tcase_create("keys");
    tcase_add_test(t, list_units);
    tcase_add_loop_test(t, bad_input, 0, (int)(sizeof bad_rows / sizeof bad_rows[0]));
    tcase_add_test(t, rules);
    tcase_add_test(t, friction_rules);
    tcase_add_test(t, hysteresis_measure);
    tcase_add_test(t, checkpoint_round_trip);
    tcase_add_loop_test(t, checkpoint_nonfinite, 0, 5);
    suite_add_tcase(s, t);
    t = tcase_create("runs");
    tcase_set_timeout(t, 600);
    tcase_add_unchecked_fixture(t, setup, teardown);
    tcase_add_test(t, loop_carries_state);
    tcase_add_test(t, elastic_material);
    tcase_add_test(t, never_yields);
    tcase_add_test(t, running_in);
    tcase_add_test(t, plastic_guard);
    tcase_add_test(t, iso_columns);
    tcase_add_test(t, lubricated_plastic_stage);
    tcase_add_test(t, resume_identical);
    tcase_add_test(t, resume_refused);
    tcase_add_test(t, friction_zero_identical);
    tcase_add_test(t, friction_step_mu);
    tcase_add_test(t, friction_sign);
    suite_add_tcase(s, t);
    return s;
}
