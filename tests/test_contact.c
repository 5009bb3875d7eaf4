/* test_contact.c - normal contact solvers: agreement between methods and backends, and the
 * complementarity conditions of the solution (contact.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "contact/contact.h"
#include "kernels/kernel.h"
#include "test_util.h"

/* Solver tier: a solve stopped at residual 1e-13 (gap scale) reproduces the exact LCP solution to
 * about cond(K_CC)*1e-13; 1e-8 of p_max is the required agreement (issue: CG vs active set). */
#define TIGHT 1e-13
#define TOL_METHODS 1e-8
/* Backends differ by ~1e-15 per operator application; iterating keeps the same active sets, so
 * the two solutions agree to a few hundred eps relative. */
#define TOL_BACKENDS 1e-11
/* KKT check tier: the stopping rule guarantees residual <= tolerance; recomputed with an
 * independent K p (direct sum: differs from the solver's FFT operator by round-off, ~1e-15 of
 * max|K p|) and a recomputed multiplier delta (the mean gap over the contact cells, which can
 * differ from the solver's by up to tol s), the measure stays within a few tol: 10 tol. */
#define KKT_SLACK 10.0
/* Bounds: the solvers clip p to [p_lub, p_cap], exact at the lower bound and one rounding at the
 * cap (p = p_lub + q): a few eps of p_max; 1e-12 leaves a wide margin. */
#define BOUND_SLACK 1e-12

typedef struct {
    const char *name;
    int nx, ny;
    double rough;   /* rms of the sinusoidal roughness relative to the smooth interference */
    double lub;     /* lubricant pressure / mean nominal pressure */
    double cap;     /* pressure cap / Hertz p0 (0: none) */
    int approach;   /* approach control instead of force control */
} scene_t;

static const scene_t scenes[] = {
    {"smooth", 20, 20, 0.0, 0.0, 0.0, 0},
    {"rough", 24, 24, 0.3, 0.0, 0.0, 0},
    {"rough_lub", 24, 24, 0.3, 0.3, 0.0, 0},
    {"rough_cap", 24, 24, 0.3, 0.0, 1.1, 0},
    {"rough_lub_cap", 24, 24, 0.3, 0.3, 1.1, 0},
    {"rough_approach", 24, 20, 0.3, 0.0, 0.0, 1},
    {"rough_approach_cap", 21, 24, 0.3, 0.1, 1.1, 1},
};
#define NSCENES (int)(sizeof scenes / sizeof scenes[0])

static const double E_STAR = 115.4e9, R = 0.01;

/* A sphere of radius R plus a deterministic sum of sinusoids (a few random phases). */
static mc_grid make_topo(const scene_t *sc, double *h, double *W, double *p0)
{
    mc_grid g = {sc->nx, sc->ny, 2e-6, 2.2e-6, 0, 0};
    const double a = 0.35 * sc->nx * g.dx; /* Hertz radius: contact covers most of the grid */
    const double delta = a * a / R;
    double ph[8];
    test_random_field(ph, 8, 42);
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            double z = 0;
            for (int k = 0; k < 4; k++)
                z += sin(2 * M_PI * (k + 2) * x / (g.nx * g.dx) + 3 * ph[2 * k]) *
                     cos(2 * M_PI * (k + 3) * y / (g.ny * g.dy) + 3 * ph[2 * k + 1]);
            h[(size_t)j * g.nx + i] = (x * x + y * y) / (2 * R) - sc->rough * delta * z / 2;
        }
    *W = 4.0 * E_STAR * a * a * a / (3.0 * R);
    *p0 = 3.0 * *W / (2.0 * M_PI * a * a);
    return g;
}

typedef struct {
    double *p, *u, *gap;
    mc_contact_summary sum;
    int rc;
} solution;

/* K p by the direct O(N^2) sum of Love's rectangle (kernels/kernel.h) over a free (non-periodic)
 * grid: u_i = sum_j p_j uz(x_i - x_j, y_i - y_j; dx/2, dy/2) / E*. Shares nothing with the
 * operator module but the kernel formula: no tables of its own, no convolution, no FFT, so a
 * wrong operator (scale, offset, padding, crop) or a solver that reports a stale or rescaled
 * displacement cannot agree with it. The influence depends on the offset only: one table of
 * (2 nx - 1)(2 ny - 1) values. */
static void direct_Kp(const mc_grid *g, const double *p, double *u)
{
    const int nx = g->nx, ny = g->ny, tx = 2 * nx - 1;
    ck_assert(!g->periodic_x && !g->periodic_y); /* no images summed here */
    double *t = mc_zeros((size_t)tx * (2 * ny - 1));
    ck_assert_ptr_nonnull(t);
    for (int dj = -(ny - 1); dj <= ny - 1; dj++)
        for (int di = -(nx - 1); di <= nx - 1; di++)
            t[(size_t)(dj + ny - 1) * tx + (di + nx - 1)] =
                mc_love_uz(di * g->dx, dj * g->dy, 0.5 * g->dx, 0.5 * g->dy) / E_STAR;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double acc = 0;
            for (int l = 0; l < ny; l++)
                for (int k = 0; k < nx; k++)
                    acc += t[(size_t)(j - l + ny - 1) * tx + (i - k + nx - 1)] *
                           p[(size_t)l * nx + k];
            u[(size_t)j * nx + i] = acc;
        }
    mc_free(t);
}

/* The conditions of contact.h checked on the pressure alone: K p and K p_lub from direct_Kp, the
 * gap g = h + K p - delta rebuilt from them, delta the given approach (approach control) or, under
 * force control, the mean of h + K p over the cells strictly between the bounds (where g must
 * vanish: the multiplier of the load), compared with the summary's approach. The gap scale s is
 * the stopping rule's (delta - min h~, h~ = h + K p_lub, with its floors). Then: bounds,
 * g >= 0 where p = p_lub, g = 0 between the bounds, g <= 0 at the cap (each within KKT_SLACK tol
 * s), the load (force control), and the solver's u and gap outputs against the recomputed ones. */
static void kkt_check(const scene_t *sc, const mc_grid *g, const double *h,
                      const mc_contact_problem *prob, double tol, const solution *out)
{
    const size_t n = mc_grid_cells(g);
    const double lo = prob->p_lub, cap = prob->p_cap, A = mc_grid_cell_area(g);
    double *Kp = mc_zeros(n), *ht = mc_zeros(n), *plub = mc_zeros(n);
    ck_assert(Kp && ht && plub);
    direct_Kp(g, out->p, Kp);
    for (size_t i = 0; i < n; i++)
        plub[i] = lo;
    direct_Kp(g, plub, ht);
    for (size_t i = 0; i < n; i++)
        ht[i] += h[i]; /* h~ = h + K p_lub */

    double delta = prob->approach, dsum = 0;
    size_t ninner = 0;
    for (size_t i = 0; i < n; i++)
        if (out->p[i] > lo && out->p[i] < cap) {
            dsum += h[i] + Kp[i];
            ninner++;
        }
    if (prob->control == MC_CONTROL_FORCE)
        delta = ninner ? dsum / (double)ninner : out->sum.approach;
    double hmin = INFINITY, hmax = -INFINITY, umax = 0;
    for (size_t i = 0; i < n; i++) {
        hmin = fmin(hmin, ht[i]);
        hmax = test_worst(hmax, ht[i]);
        umax = test_worst(umax, fabs(Kp[i]));
    }
    double sg = delta - hmin, fl = fmax(1e-6 * (hmax - hmin), 1e-12 * fmax(fabs(hmin), fabs(hmax)));
    if (!(sg > fl))
        sg = fl;
    const double slack = KKT_SLACK * tol * sg;
    ck_assert_msg(fabs(out->sum.approach - delta) <= slack, "%s: approach %.17g, recomputed %.17g",
                  sc->name, out->sum.approach, delta);

    double sum = 0, pmax = 0;
    for (size_t i = 0; i < n; i++)
        pmax = test_worst(pmax, out->p[i]);
    for (size_t i = 0; i < n; i++) {
        double p = out->p[i], gp = h[i] + Kp[i] - delta;
        ck_assert_msg(p >= lo - BOUND_SLACK * pmax && p <= cap + BOUND_SLACK * pmax,
                      "%s: p out of bounds", sc->name);
        if (p <= lo)
            ck_assert_msg(gp >= -slack, "%s: penetration %g (of s) at a free cell", sc->name,
                          gp / sg);
        else if (p >= cap)
            ck_assert_msg(gp <= slack, "%s: open capped cell, gap %g (of s)", sc->name, gp / sg);
        else
            ck_assert_msg(fabs(gp) <= slack, "%s: gap %g (of s) in contact", sc->name, gp / sg);
        /* the solver's outputs against the recomputed displacement and gap */
        ck_assert_msg(fabs(out->u[i] - Kp[i]) <= TOL_ROUNDOFF * umax,
                      "%s: displacement output %g, direct K p %g", sc->name, out->u[i], Kp[i]);
        ck_assert_msg(fabs(out->gap[i] - gp) <= slack, "%s: gap output %g, recomputed %g",
                      sc->name, out->gap[i], gp);
        sum += p;
    }
    if (prob->control == MC_CONTROL_FORCE)
        ck_assert_msg(fabs(A * sum - prob->load) <= KKT_SLACK * tol * prob->load,
                      "%s: load %g vs %g", sc->name, A * sum, prob->load);
    mc_free(Kp);
    mc_free(ht);
    mc_free(plub);
}

static void solve(const scene_t *sc, mc_contact_method m, mc_backend b, double tol, solution *out)
{
    double *h = mc_zeros((size_t)sc->nx * sc->ny);
    double W, p0;
    mc_grid g = make_topo(sc, h, &W, &p0);
    size_t n = mc_grid_cells(&g);
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, b, &K, &err), MC_OK);
    mc_contact_options opt = {m, tol, 20000, 0, 0};
    mc_contact_solver *s = NULL;
    ck_assert_msg(mc_contact_create(K, &opt, &s, &err) == MC_OK, "%s", err.msg);
    double pm = W / (n * mc_grid_cell_area(&g));
    mc_contact_problem prob = {.h = h,
                               .p_lub = sc->lub * pm,
                               .p_cap = sc->cap > 0 ? sc->cap * p0 : INFINITY,
                               .control = sc->approach ? MC_CONTROL_APPROACH : MC_CONTROL_FORCE,
                               .load = W,
                               .approach = 0.6 * (0.35 * sc->nx * g.dx) * (0.35 * sc->nx * g.dx) / R};
    out->p = mc_zeros(n);
    out->u = mc_zeros(n);
    out->gap = mc_zeros(n);
    out->rc = mc_contact_solve(s, &prob, out->p, out->u, out->gap, &out->sum, &err);
    ck_assert_msg(out->rc == MC_OK, "%s %s/%s: %s", sc->name, mc_contact_method_name(m),
                  mc_backend_name(b), err.msg);
    kkt_check(sc, &g, h, &prob, tol, out);
    ck_assert(out->sum.converged);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
}

/* Index of the cell whose centre is nearest to (x, y). */
static size_t vu_center(const mc_grid *g, double x, double y)
{
    int i = (int)floor(x / g->dx + 0.5 * g->nx), j = (int)floor(y / g->dy + 0.5 * g->ny);
    return (size_t)j * g->nx + i;
}

static void release(solution *s)
{
    mc_free(s->p);
    mc_free(s->u);
    mc_free(s->gap);
}

static double max_abs_diff(const double *a, const double *b, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = test_worst(m, fabs(a[i] - b[i]));
    return m;
}

START_TEST(cg_matches_active_set)
{
    const scene_t *sc = &scenes[_i];
    solution a, b;
    solve(sc, MC_METHOD_CG, MC_BACKEND_FFT, TIGHT, &a);
    solve(sc, MC_METHOD_ACTIVE_SET, MC_BACKEND_FFT, TIGHT, &b);
    size_t n = (size_t)sc->nx * sc->ny;
    double d = max_abs_diff(a.p, b.p, n) / b.sum.p_max;
    ck_assert_msg(d <= TOL_METHODS, "%s: cg vs active-set %.3e of p_max", sc->name, d);
    ck_assert_msg(fabs(a.sum.approach - b.sum.approach) <= TOL_METHODS * fabs(b.sum.approach) + 1e-18,
                  "%s: approach %g vs %g", sc->name, a.sum.approach, b.sum.approach);
    release(&a);
    release(&b);
}
END_TEST

START_TEST(pk_matches_active_set)
{
    const scene_t *sc = &scenes[_i];
    solution a, b;
    solve(sc, MC_METHOD_PK, MC_BACKEND_FFT, TIGHT, &a);
    solve(sc, MC_METHOD_ACTIVE_SET, MC_BACKEND_DIRECT, TIGHT, &b);
    size_t n = (size_t)sc->nx * sc->ny;
    double d = max_abs_diff(a.p, b.p, n) / b.sum.p_max;
    ck_assert_msg(d <= TOL_METHODS, "%s: pk vs active-set %.3e of p_max", sc->name, d);
    release(&a);
    release(&b);
}
END_TEST

START_TEST(cg_backends_agree)
{
    const scene_t *sc = &scenes[_i];
    solution a, b;
    solve(sc, MC_METHOD_CG, MC_BACKEND_FFT, TIGHT, &a);
    solve(sc, MC_METHOD_CG, MC_BACKEND_DIRECT, TIGHT, &b);
    size_t n = (size_t)sc->nx * sc->ny;
    double d = max_abs_diff(a.p, b.p, n) / b.sum.p_max;
    ck_assert_msg(d <= TOL_BACKENDS, "%s: fft vs direct %.3e of p_max", sc->name, d);
    release(&a);
    release(&b);
}
END_TEST

START_TEST(default_tolerance_kkt)
{
    const scene_t *sc = &scenes[_i];
    solution a;
    solve(sc, MC_METHOD_CG, MC_BACKEND_FFT, 1e-8, &a); /* KKT asserted inside solve() */
    ck_assert(a.sum.residual <= 1e-8);
    release(&a);
}
END_TEST

START_TEST(active_set_refuses_large_grid)
{
    mc_grid g = {128, 64, 1e-6, 1e-6, 0, 0};
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {MC_METHOD_ACTIVE_SET, 1e-8, 100, 0, 0};
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_ERR_LIMIT);
    ck_assert_ptr_null(s);
    ck_assert_msg(strstr(err.msg, "4096") && strstr(err.msg, "cg"), "%s", err.msg);
    mc_operator_destroy(&K);
}
END_TEST

START_TEST(lubricant_carries_everything)
{
    /* lubricant pressure times area above the load: no solid contact, reported, not iterated */
    const scene_t sc = {"lub_only", 16, 16, 0.0, 0.0, 0.0, 0};
    double *h = mc_zeros(256), W, p0;
    mc_grid g = make_topo(&sc, h, &W, &p0);
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {MC_METHOD_CG, 1e-8, 100, 0, 0};
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    double plub = 2.0 * W / (256 * mc_grid_cell_area(&g));
    mc_contact_problem prob = {.h = h, .p_lub = plub, .p_cap = INFINITY,
                               .control = MC_CONTROL_FORCE, .load = W};
    double *p = mc_zeros(256);
    mc_contact_summary sum;
    ck_assert_int_eq(mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err), MC_OK);
    ck_assert_int_eq(sum.iterations, 0);
    ck_assert(sum.solid_load == 0 && sum.area == 0);
    for (int i = 0; i < 256; i++)
        ck_assert(p[i] == plub);
    mc_free(p);
    mc_free(h);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
}
END_TEST

START_TEST(not_converged_is_reported)
{
    const scene_t *sc = &scenes[1];
    double *h = mc_zeros(24 * 24), W, p0;
    mc_grid g = make_topo(sc, h, &W, &p0);
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {MC_METHOD_PK, 1e-12, 2, 0, 0};
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE, .load = W};
    double *p = mc_zeros(24 * 24);
    mc_contact_summary sum;
    ck_assert_int_eq(mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err), MC_NOT_CONVERGED);
    ck_assert(!sum.converged && sum.iterations == 2 && sum.residual > 1e-12);
    ck_assert_msg(strstr(err.msg, "did not converge"), "%s", err.msg);
    for (int i = 0; i < 24 * 24; i++)
        ck_assert(isfinite(p[i]));
    mc_free(p);
    mc_free(h);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
}
END_TEST

/* The nested (coarse-grid) start changes where cg starts, not what it converges to: both starts
 * give the same pressure to the solver tier, and the nested one needs fewer fine iterations. */
START_TEST(nested_start_same_answer)
{
    const int N = 129;
    mc_grid g = {N, 2 * N - 20, 1.5e-6, 1.2e-6, 0, 0};
    size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *p1 = mc_zeros(n), *p2 = mc_zeros(n), ph[8];
    test_random_field(ph, 8, 7);
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            h[(size_t)j * g.nx + i] = (x * x + y * y) / (2 * R) +
                                      2e-8 * sin(9e4 * x + 3 * ph[0]) * cos(7e4 * y + 3 * ph[1]);
        }
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_summary s1, s2;
    int it[2];
    for (int k = 0; k < 2; k++) {
        mc_contact_options opt = {MC_METHOD_CG, TIGHT, 5000, k ? E_STAR : 0, 1};
        mc_contact_solver *s = NULL;
        ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
        mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                                   .load = 0.5};
        ck_assert_int_eq(mc_contact_solve(s, &prob, k ? p2 : p1, NULL, NULL, k ? &s2 : &s1, &err),
                         MC_OK);
        it[k] = (k ? s2 : s1).iterations;
        if (k)
            ck_assert_msg(mc_contact_last_coarse_applies(s) > 0, "no coarse solve happened");
        mc_contact_destroy(&s);
    }
    double d = max_abs_diff(p1, p2, n) / s1.p_max;
    ck_assert_msg(d <= TOL_METHODS, "nested vs uniform start differ by %.3e of p_max", d);
    ck_assert_msg(it[1] < it[0], "nested start took %d fine iterations, uniform %d", it[1], it[0]);
    mc_free(h);
    mc_free(p1);
    mc_free(p2);
    mc_operator_destroy(&K);
}
END_TEST

/* The restriction to the contact's bounding box changes the cost, not the answer: a small contact
 * on a large grid solved with and without the box agrees to the solver tier, and the box (not the
 * whole grid) is what the iterations ran on. A warm start that covers too little makes the full
 * operator find penetration outside the box, which must widen it. */
START_TEST(box_restriction_same_answer)
{
    const int N = 200;
    mc_grid g = {N, N - 10, 2e-6, 2e-6, 0, 0};
    size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *p[2] = {mc_zeros(n), mc_zeros(n)}, *start = mc_zeros(n);
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            double x = mc_grid_x(&g, i) - 20e-6, y = mc_grid_y(&g, j) + 10e-6;
            h[(size_t)j * g.nx + i] = (x * x + y * y) / (2 * R);
        }
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_summary sum[2];
    for (int k = 0; k < 2; k++) {
        mc_contact_options opt = {MC_METHOD_CG, TIGHT, 5000, E_STAR, k == 0};
        mc_contact_solver *s = NULL;
        ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
        mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                                   .load = 0.05};
        ck_assert_msg(mc_contact_solve(s, &prob, p[k], NULL, NULL, &sum[k], &err) == MC_OK, "%s",
                      err.msg);
        if (k == 1) {
            ck_assert_msg(mc_contact_last_box_cells(s) > 0 &&
                              mc_contact_last_box_cells(s) < (long)(MC_BOX_FRACTION * n),
                          "box of %ld cells", mc_contact_last_box_cells(s));
            /* a warm start on a single cell: the box must grow until nothing penetrates */
            for (size_t i = 0; i < n; i++)
                start[i] = i == vu_center(&g, 20e-6, -10e-6) ? 1e9 : 0.0;
            prob.p_start = start;
            mc_contact_summary s3;
            double *p3 = mc_zeros(n);
            ck_assert_int_eq(mc_contact_solve(s, &prob, p3, NULL, NULL, &s3, &err), MC_OK);
            ck_assert(max_abs_diff(p3, p[0], n) / sum[0].p_max <= TOL_METHODS);
            mc_free(p3);
        }
        mc_contact_destroy(&s);
    }
    double d = max_abs_diff(p[0], p[1], n) / sum[0].p_max;
    ck_assert_msg(d <= TOL_METHODS, "box vs full differ by %.3e of p_max", d);
    ck_assert(fabs(sum[0].approach - sum[1].approach) <= TOL_METHODS * sum[0].approach);
    mc_free(h);
    mc_free(p[0]);
    mc_free(p[1]);
    mc_free(start);
    mc_operator_destroy(&K);
}
END_TEST

/* A datum far from the contact (1 m under micrometre deformations) must not cost accuracy: the
 * solvers work relative to the lowest point. Same pressure, approach shifted by the datum. */
/* h - 1 m rounds each height by up to 1.1e-16 m, 2e-9 of the 6e-8 m interference; the pressure
 * moves by that times the contact's conditioning (measured 1.1e-8 of p_max). */
#define DATUM_TOL 1e-7
START_TEST(large_datum)
{
    const scene_t *sc = &scenes[1];
    double *h = mc_zeros(24 * 24), *h1 = mc_zeros(24 * 24), W, p0;
    mc_grid g = make_topo(sc, h, &W, &p0);
    for (int i = 0; i < 24 * 24; i++)
        h1[i] = h[i] - 1.0;
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    double *p[2] = {mc_zeros(24 * 24), mc_zeros(24 * 24)};
    mc_contact_summary sum[2];
    for (int m = 0; m < 2; m++) {
        mc_contact_options opt = {m ? MC_METHOD_PK : MC_METHOD_CG, 1e-12, 5000, 0, 0};
        mc_contact_solver *s = NULL;
        ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
        for (int k = 0; k < 2; k++) {
            mc_contact_problem prob = {.h = k ? h1 : h, .p_cap = INFINITY,
                                       .control = MC_CONTROL_FORCE, .load = W};
            ck_assert_msg(mc_contact_solve(s, &prob, p[k], NULL, NULL, &sum[k], &err) == MC_OK,
                          "%s", err.msg);
        }
        double d = max_abs_diff(p[0], p[1], 24 * 24) / sum[0].p_max;
        ck_assert_msg(d <= DATUM_TOL, "method %d: %.3e", m, d);
        ck_assert(fabs(sum[1].approach + 1.0 - sum[0].approach) <= 1e-15 * 4);
        mc_contact_destroy(&s);
    }
    mc_free(p[0]);
    mc_free(p[1]);
    mc_free(h);
    mc_free(h1);
    mc_operator_destroy(&K);
}
END_TEST

/* Review findings: a nested capped solve that stops short reports the state it stopped in (its
 * approach and a non-zero residual), and a per-cell cap reaches the coarse-grid start as a
 * coarse array (not the fine one read at coarse indices). */
START_TEST(capped_stops_short_honestly)
{
    const int N = 64;
    mc_grid g = {N, N, 2e-6, 2e-6, 0, 0};
    size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *p = mc_zeros(n), *gap = mc_zeros(n), *u = mc_zeros(n);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            h[(size_t)j * N + i] = (x * x + y * y) / (2 * R);
        }
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {MC_METHOD_CG, 1e-10, 3, 0, 0};
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    mc_contact_problem prob = {.h = h, .p_cap = 1.0e9, .control = MC_CONTROL_FORCE, .load = 0.05};
    mc_contact_summary sum;
    ck_assert_int_eq(mc_contact_solve(s, &prob, p, u, gap, &sum, &err), MC_NOT_CONVERGED);
    ck_assert(!sum.converged && sum.residual > opt.tolerance);
    ck_assert(sum.approach > 0);
    for (size_t i = 0; i < n; i++)
        ck_assert(fabs(gap[i] - (h[i] + u[i] - sum.approach)) <= 1e-12 * sum.approach);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
    mc_free(p);
    mc_free(gap);
    mc_free(u);
}
END_TEST

START_TEST(per_cell_cap_on_coarse_start)
{
    const int N = 128;
    mc_grid g = {N, N, 1e-6, 1e-6, 0, 0};
    size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *p = mc_zeros(n), *cap = mc_zeros(n);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            h[(size_t)j * N + i] = (x * x + y * y) / (2 * R);
            cap[(size_t)j * N + i] = j < N / 4 ? 1.0 : INFINITY; /* far from the contact */
        }
    mc_operator *K = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {MC_METHOD_CG, 1e-8, 2000, E_STAR, 0};
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .p_upper = cap,
                               .control = MC_CONTROL_FORCE, .load = 0.05};
    mc_contact_summary sum;
    ck_assert_msg(mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err) == MC_OK, "%s", err.msg);
    ck_assert(mc_contact_last_coarse_applies(s) > 0);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
    mc_free(p);
    mc_free(cap);
}
END_TEST

Suite *suite_contact(void);
Suite *suite_contact(void)
{
    Suite *s = suite_create("contact");
    TCase *t = tcase_create("methods");
    tcase_set_timeout(t, 300);
    tcase_add_loop_test(t, cg_matches_active_set, 0, NSCENES);
    tcase_add_loop_test(t, pk_matches_active_set, 0, NSCENES);
    tcase_add_loop_test(t, cg_backends_agree, 0, NSCENES);
    tcase_add_loop_test(t, default_tolerance_kkt, 0, NSCENES);
    suite_add_tcase(s, t);
    TCase *e = tcase_create("edges");
    tcase_add_test(e, active_set_refuses_large_grid);
    tcase_add_test(e, lubricant_carries_everything);
    tcase_add_test(e, not_converged_is_reported);
    tcase_add_test(e, nested_start_same_answer);
    tcase_add_test(e, box_restriction_same_answer);
    tcase_add_test(e, large_datum);
    tcase_add_test(e, capped_stops_short_honestly);
    tcase_add_test(e, per_cell_cap_on_coarse_start);
    suite_add_tcase(s, e);
    return s;
}
