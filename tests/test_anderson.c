/* test_anderson.c - Anderson mixing (plastic/anderson.h) in its rows mode, the one a distributed
 * joint iteration uses (theory.md §8.4): on one process its dot products are the per-row sums of
 * this process's rows, added row by row; the mixing must be that of the whole-field mode (its
 * sums over the active cells) to round-off, touch no cell outside its rows, and refuse a shape
 * that does not fit. Under mpirun the sums over the ranks are checked by tests/mpi/mpi_eigen.c;
 * here they run under the sanitizers too. */
#include <check.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "plastic/anderson.h"
#include "test_util.h"

#define NB 3 /* blocks (layers) */
#define NY 5 /* rows per block */
#define NX 7 /* cells per row */
#define NC (NB * NY * NX)
#define W 2 /* values per cell */

/* Rows mode against the whole-field mode: the same mixing but for the order of the dot products'
 * sums, whose round-off the least-squares system amplifies as the differences of the residuals
 * shrink near the fixed point (9e-15 measured over 14 steps of the map below; 3e-12 with a map
 * that did not contract). A row or a component left out of the sums is off by 1e-3 or more. */
#define TOL_ORDER 1e-12

/* A linear contraction (factor at most 0.9) coupled only along a row: g(x)_q(v) = b_q(v) +
 * 0.35 x_q(v) + 0.25 x_q'(v) + 0.15 (x_q(v - 1) + x_q(v + 1)) (neighbours in the row; q' the other component): its rows are
 * independent problems, so a field restricted to some rows is the same problem there. b is zero
 * on a third of the cells (they stay out of the active set). */
static void image(const double *x, double *g)
{
    for (int q = 0; q < W; q++)
        for (int v = 0; v < NC; v++) {
            const int i = v % NX;
            const double b = (v % 3) ? 0.1 * (1 + q) + 0.01 * (v % 11) : 0.0;
            double s = b + 0.35 * x[q * NC + v] + 0.25 * x[(1 - q) * NC + v];
            if (i > 0)
                s += 0.15 * x[q * NC + v - 1];
            if (i < NX - 1)
                s += 0.15 * x[q * NC + v + 1];
            g[q * NC + v] = s;
        }
}

static double residual(const double *x)
{
    double g[W * NC], r = 0.0;
    image(x, g);
    for (int k = 0; k < W * NC; k++)
        r = test_worst(r, fabs(g[k] - x[k]));
    return r;
}

/* Steps of the accelerator a from x (in place); the image is taken whole each time. */
static void steps(mc_anderson *a, double *x, int n)
{
    double g[W * NC];
    mc_error err;
    for (int k = 0; k < n; k++) {
        image(x, g);
        ck_assert_int_eq(mc_anderson_step(a, x, g, &err), MC_OK);
    }
}

/* The cells of a dense field whose values are not zero, as a sparse list (stride W + 1: the
 * loop's lists carry one more value per cell, which the accelerator must skip). */
static long to_list(const double *f, long *cell, double *val)
{
    long n = 0;
    for (int v = 0; v < NC; v++) {
        int nz = 0;
        for (int q = 0; q < W; q++)
            nz |= f[q * NC + v] != 0.0;
        if (!nz)
            continue;
        cell[n] = v;
        for (int q = 0; q < W; q++)
            val[(W + 1) * n + q] = f[q * NC + v];
        val[(W + 1) * n + W] = -1.0; /* (not a component) */
        n++;
    }
    return n;
}

/* The sparse step (the plastic loop's, theory.md §9.9) gives the bits of the dense step, step by
 * step from a start with a few non-zero cells, and its iterate is zero off its active cells. */
START_TEST(sparse_as_dense)
{
    mc_anderson *dense = NULL, *sparse = NULL;
    mc_error err;
    ck_assert_int_eq(mc_anderson_create(NC, W, 4, &dense, &err), MC_OK);
    ck_assert_int_eq(mc_anderson_create(NC, W, 4, &sparse, &err), MC_OK);
    double xd[W * NC] = {0}, xs[W * NC] = {0}, g[W * NC];
    xd[17] = xs[17] = 0.3; /* a warm start on two cells */
    xd[NC + 40] = xs[NC + 40] = -0.2;
    long xc[NC], gc[NC];
    double xv[(W + 1) * NC], gv[(W + 1) * NC];
    for (int k = 0; k < 12; k++) {
        image(xd, g);
        ck_assert_int_eq(mc_anderson_step(dense, xd, g, &err), MC_OK);
        image(xs, g);
        const long nx = to_list(xs, xc, xv), ng = to_list(g, gc, gv);
        long n;
        const long *cells;
        const double *vals;
        ck_assert_int_eq(mc_anderson_step_sparse(sparse, nx, xc, xv, ng, gc, gv, W + 1, &n,
                                                 &cells, &vals, &err),
                         MC_OK);
        memset(xs, 0, sizeof xs);
        for (long e = 0; e < n; e++)
            for (int q = 0; q < W; q++)
                xs[q * NC + cells[e]] = vals[W * e + q];
        ck_assert_int_eq(n, mc_anderson_active(dense));
        ck_assert_msg(memcmp(xs, xd, sizeof xs) == 0, "step %d: the iterates differ", k);
    }
    ck_assert_msg(residual(xd) < 1e-3 * residual((double[W * NC]){0}), "residual %g",
                  residual(xd));
    ck_assert_int_eq(mc_anderson_step_sparse(sparse, 0, xc, xv, 0, gc, gv, W - 1, &(long){0},
                                             &(const long *){NULL}, &(const double *){NULL}, &err),
                     MC_ERR_INPUT);
    mc_anderson_destroy(&dense);
    mc_anderson_destroy(&sparse);
}
END_TEST

START_TEST(rows_whole_field_as_whole_mode)
{
    mc_anderson *aw = NULL, *ar = NULL;
    mc_error err;
    ck_assert_int_eq(mc_anderson_create(NC, W, 4, &aw, &err), MC_OK);
    ck_assert_int_eq(mc_anderson_create(NC, W, 4, &ar, &err), MC_OK);
    ck_assert_int_eq(mc_anderson_rows(ar, NB, NY, NX, 0, NY), 1);
    double xw[W * NC] = {0}, xr[W * NC] = {0}, xp[W * NC] = {0}, gp[W * NC];
    double worst = 0.0;
    for (int k = 0; k < 14; k++) {
        steps(aw, xw, 1);
        steps(ar, xr, 1);
        worst = test_worst(worst, test_rel_maxdiff(xr, xw, W * NC));
    }
    /* the same mixing but for the order of the dot products' sums */
    ck_assert_msg(worst <= TOL_ORDER, "rows mode against whole mode: %g", worst);
    /* and it accelerates: the plain iteration is far from the fixed point after as many steps */
    for (int k = 0; k < 14; k++) {
        image(xp, gp);
        memcpy(xp, gp, sizeof xp);
    }
    const double rr = residual(xr), rp = residual(xp);
    ck_assert_msg(rr < 1e-2 * rp, "residual %g mixed, %g plain", rr, rp); /* 8.5e-5, 3.0e-2 */
    mc_anderson_destroy(&aw);
    mc_anderson_destroy(&ar);
}
END_TEST

START_TEST(rows_keep_to_their_rows)
{
    /* rows 1 and 2 of every block: the other rows of x are never written (a sentinel stays), and
     * the rows kept mix as the whole-field mode does on a field that holds those rows alone */
    const int r0 = 1, nr = 2;
    mc_anderson *ar = NULL, *aw = NULL;
    mc_error err;
    ck_assert_int_eq(mc_anderson_create(NC, W, 3, &ar, &err), MC_OK);
    ck_assert_int_eq(mc_anderson_create(NC, W, 3, &aw, &err), MC_OK);
    ck_assert_int_eq(mc_anderson_rows(ar, NB, NY, NX, r0, nr), 1);
    double xr[W * NC], xw[W * NC] = {0}, g[W * NC];
    for (int k = 0; k < W * NC; k++)
        xr[k] = 7.0;
    for (int q = 0; q < W; q++)
        for (int v = 0; v < NC; v++) {
            const int j = (v / NX) % NY;
            if (j >= r0 && j < r0 + nr)
                xr[q * NC + v] = 0.0;
        }
    double worst = 0.0;
    for (int k = 0; k < 10; k++) {
        image(xr, g);
        ck_assert_int_eq(mc_anderson_step(ar, xr, g, &err), MC_OK);
        image(xw, g); /* the whole-field run: the other rows held at zero */
        for (int q = 0; q < W; q++)
            for (int v = 0; v < NC; v++) {
                const int j = (v / NX) % NY;
                if (j < r0 || j >= r0 + nr)
                    g[q * NC + v] = 0.0;
            }
        ck_assert_int_eq(mc_anderson_step(aw, xw, g, &err), MC_OK);
        for (int q = 0; q < W; q++)
            for (int v = 0; v < NC; v++) {
                const int j = (v / NX) % NY;
                const double a = xr[q * NC + v], b = xw[q * NC + v];
                if (j < r0 || j >= r0 + nr)
                    ck_assert_msg(a == 7.0, "step %d: cell %d of row %d written (%g)", k, v, j, a);
                else
                    worst = test_worst(worst, fabs(a - b) / fmax(fabs(b), 1e-300));
            }
    }
    ck_assert_msg(worst <= TOL_ORDER, "the rows kept against the whole-field mode: %g", worst);
    mc_anderson_destroy(&ar);
    mc_anderson_destroy(&aw);
}
END_TEST

START_TEST(rows_shape_checked)
{
    mc_anderson *a = NULL;
    mc_error err;
    ck_assert_int_eq(mc_anderson_create(NC, W, 2, &a, &err), MC_OK);
    ck_assert_int_eq(mc_anderson_rows(a, NB, NY, NX + 1, 0, NY), 0); /* not the field's cells */
    ck_assert_int_eq(mc_anderson_rows(a, NB, NY, NX, 3, 3), 0);      /* past the last row */
    ck_assert_int_eq(mc_anderson_rows(a, NB, NY, NX, -1, 2), 0);
    ck_assert_int_eq(mc_anderson_rows(a, NB, NY, NX, 0, 0), 1);      /* a rank without rows */
    double x[W * NC] = {0}, g[W * NC];
    image(x, g);
    ck_assert_int_eq(mc_anderson_step(a, x, g, &err), MC_OK);
    for (int k = 0; k < W * NC; k++) /* no rows: nothing written */
        ck_assert(x[k] == 0.0);
    ck_assert_int_eq(mc_anderson_rows(a, 0, 0, 0, 0, -1), 1); /* the whole field again */
    steps(a, x, 1);
    ck_assert(x[W * NC - 2] != 0.0);
    mc_anderson_destroy(&a);
}
END_TEST

Suite *suite_anderson(void);
Suite *suite_anderson(void)
{
    Suite *s = suite_create("anderson");
    TCase *t = tcase_create("rows");
    tcase_add_test(t, rows_whole_field_as_whole_mode);
    tcase_add_test(t, sparse_as_dense);
    tcase_add_test(t, rows_keep_to_their_rows);
    tcase_add_test(t, rows_shape_checked);
    suite_add_tcase(s, t);
    return s;
}
