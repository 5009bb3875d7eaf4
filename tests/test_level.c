/* test_level.c - form removal, in-painting, cropping and resampling (level.c, level_fill.c). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface/level.h"
#include "test_util.h"

/* The fill's conjugate gradients stop at a relative residual of 1e-12; the error that leaves
 * is at most the condition number (~ (hole diameter)^2 ~ 1e3 here) times that. */
#define TOL_FILL_SOLVE 1e-8

static double cx(int i, int nx, double dx) { return (i + 0.5 - 0.5 * nx) * dx; }

/* c0 + c1 x + c2 y + c3 x^2 + c4 x y + c5 y^2 at the cell centres, the terms of `kind`. */
static void poly(double *z, int nx, int ny, double dx, double dy, const double c[6], int kind)
{
    static const int nt[] = {0, 1, 3, 6};
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double x = cx(i, nx, dx), y = cx(j, ny, dy);
            double phi[6] = {1, x, y, x * x, x * y, y * y}, s = 0;
            for (int a = 0; a < nt[kind]; a++)
                s += c[a] * phi[a];
            z[j * nx + i] = s;
        }
}

static const double COEF[6] = {3e-6, 2e-3, -1.5e-3, 40.0, -25.0, 60.0}; /* m, m/m, 1/m */

START_TEST(test_detrend_exact)
{
    const int kind = _i, nx = 37, ny = 23;
    const double dx = 1e-6, dy = 2.5e-6;
    double *z = malloc(sizeof(double) * nx * ny);
    unsigned char *v = malloc((size_t)nx * ny);
    poly(z, nx, ny, dx, dy, COEF, kind);
    double zmax = 0;
    for (int k = 0; k < nx * ny; k++) {
        zmax = test_worst(zmax, fabs(z[k]));
        v[k] = (k % 13) != 5; /* some missing points, NaN there */
        if (!v[k])
            z[k] = NAN;
    }
    double c[6];
    mc_error err = {0};
    ck_assert_int_eq(mc_level_detrend(z, v, nx, ny, dx, dy, (mc_detrend_kind)kind, c, &err), 0);
    double rmax = 0;
    for (int k = 0; k < nx * ny; k++) {
        if (v[k])
            rmax = test_worst(rmax, fabs(z[k]));
        else
            ck_assert(isnan(z[k])); /* invalid points untouched */
    }
    printf("detrend kind %d: residual %.2e of the removed %.2e m\n", kind, rmax, zmax);
    ck_assert_double_le(rmax, TOL_ROUNDOFF * zmax);
    /* each coefficient against its value, scaled by the height its term reaches on the map */
    const double hx = nx * dx / 2, hy = ny * dy / 2;
    const double reach[6] = {1, hx, hy, hx * hx, hx * hy, hy * hy};
    static const int nt[] = {0, 1, 3, 6};
    for (int a = 0; a < 6; a++) {
        double want = a < nt[kind] ? COEF[a] : 0.0;
        ck_assert_double_le(fabs(c[a] - want) * reach[a], TOL_ROUNDOFF * zmax);
    }
    free(z);
    free(v);
}
END_TEST

START_TEST(test_detrend_least_squares)
{
    /* the residual of a least-squares fit is orthogonal to every fitted term */
    const int nx = 50, ny = 31;
    const double dx = 2e-6, dy = 1e-6;
    double *z = malloc(sizeof(double) * nx * ny), *q = malloc(sizeof(double) * nx * ny);
    test_random_field(z, (size_t)nx * ny, 3);
    poly(q, nx, ny, dx, dy, COEF, 3);
    for (int kind = 1; kind <= 3; kind++) {
        double *r = malloc(sizeof(double) * nx * ny);
        for (int k = 0; k < nx * ny; k++)
            r[k] = 1e-6 * z[k] + q[k];
        mc_error err = {0};
        ck_assert_int_eq(mc_level_detrend(r, NULL, nx, ny, dx, dy, kind, NULL, &err), 0);
        static const int nt[] = {0, 1, 3, 6};
        for (int a = 0; a < nt[kind]; a++) {
            double dotp = 0, mag = 0;
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++) {
                    double u = cx(i, nx, 1) / (nx / 2.0), w = cx(j, ny, 1) / (ny / 2.0);
                    double phi[6] = {1, u, w, u * u, u * w, w * w};
                    dotp += r[j * nx + i] * phi[a];
                    mag += fabs(r[j * nx + i] * phi[a]);
                }
            ck_assert_double_le(fabs(dotp), TOL_ROUNDOFF * mag);
        }
        free(r);
    }
    free(z);
    free(q);
}
END_TEST

START_TEST(test_detrend_degenerate_and_errors)
{
    /* one row: no y terms to fit; x terms removed exactly, y coefficients 0 */
    const int nx = 40;
    const double dx = 1e-6;
    double z[40], c[6];
    const double cc[6] = {1e-6, 1e-3, 7e-3, 50.0, 9.0, 8.0};
    for (int i = 0; i < nx; i++) {
        double x = cx(i, nx, dx);
        z[i] = cc[0] + cc[1] * x + cc[3] * x * x;
    }
    mc_error err = {0};
    ck_assert_int_eq(mc_level_detrend(z, NULL, nx, 1, dx, dx, MC_DETREND_QUADRATIC, c, &err), 0);
    for (int i = 0; i < nx; i++)
        ck_assert_double_le(fabs(z[i]), TOL_ROUNDOFF * 1e-6);
    ck_assert(c[2] == 0 && c[4] == 0 && c[5] == 0);
    ck_assert_double_eq_tol(c[1], cc[1], 1e-9 * cc[1]);
    /* errors */
    unsigned char v[40] = {0};
    ck_assert_int_eq(mc_level_detrend(z, v, nx, 1, dx, dx, MC_DETREND_PLANE, c, &err),
                     MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "no valid point"));
    z[3] = NAN;
    ck_assert_int_eq(mc_level_detrend(z, NULL, nx, 1, dx, dx, MC_DETREND_MEAN, c, &err),
                     MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "(3, 0)"));
    ck_assert_int_eq(mc_level_detrend(z, NULL, nx, 1, dx, dx, (mc_detrend_kind)7, c, &err),
                     MC_ERR_INPUT);
    ck_assert_int_eq(mc_level_detrend(z, NULL, nx, 1, dx, dx, MC_DETREND_NONE, c, &err), 0);
}
END_TEST

/* ---- fill -------------------------------------------------------------------------------- */

/* Holes: an interior disc, an isolated point, a separate rectangle, one touching the edge. */
static int holes(unsigned char *v, int nx, int ny, int r, int edge)
{
    int m = 0, ci = r + 12, cj = r + 10;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int in = (i - ci) * (i - ci) + (j - cj) * (j - cj) <= r * r;
            in |= i > 2 * r + 30 && i < nx - 2 && j > 1 && j < ny - 2 && /* scattered points */
                  (i * 7 + j * 3) % 11 == 0;
            in |= i == 45 && j == 10;
            in |= i >= 40 && i < 50 && j >= 25 && j < 29;
            in |= edge && i < 4 && j >= 5 && j < 12;
            v[j * nx + i] = !in;
            m += in;
        }
    return m;
}

START_TEST(test_fill_harmonic)
{
    /* a discrete-harmonic field (5-point Laplacian 0) is restored to solver accuracy in holes
     * enclosed by valid points; the small case is solved directly (<= 256 unknowns), the large
     * one (a disc of radius 40, ~5000 points in all) by the multigrid-preconditioned CG */
    const int big = _i, nx = big ? 160 : 60, ny = big ? 110 : 40;
    double *z = malloc(sizeof(double) * nx * ny), *f = malloc(sizeof(double) * nx * ny);
    unsigned char *v = malloc((size_t)nx * ny);
    int m = holes(v, nx, ny, big ? 40 : 6, 0), filled = -1;
    double fmaxv = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            f[j * nx + i] = 1e-6 * (0.3 + 0.02 * i - 0.01 * j + 1e-3 * (i * i - j * j));
            fmaxv = test_worst(fmaxv, fabs(f[j * nx + i]));
            z[j * nx + i] = v[j * nx + i] ? f[j * nx + i] : NAN;
        }
    mc_error err = {0};
    ck_assert_int_eq(mc_level_fill_missing(z, v, nx, ny, &filled, &err), 0);
    ck_assert_int_eq(filled, m);
    double e = 0;
    for (int k = 0; k < nx * ny; k++)
        e = test_worst(e, fabs(z[k] - f[k]));
    printf("fill, harmonic field: max error %.2e of %.2e m (%d points)\n", e, fmaxv, m);
    ck_assert_double_le(e, TOL_FILL_SOLVE * fmaxv);
    free(z);
    free(f);
    free(v);
}
END_TEST

START_TEST(test_fill_smooth)
{
    /* e = fill - f solves Lap_h e = -Lap_h f in a hole, e = 0 on its rim; with
     * psi = M (R'^2 - rho^2)/4 (Lap_h rho^2 = 4 exactly) the discrete maximum principle gives
     * |e| <= M R'^2 / 4, M = max |Lap_h f|, R' = R + 1 the rim's radius. Edge holes see the
     * zero-flux condition instead: only bounded by the valid range there. */
    const int nx = 64, ny = 48, R = 7;
    double *z = malloc(sizeof(double) * nx * ny), *f = malloc(sizeof(double) * nx * ny);
    unsigned char *v = malloc((size_t)nx * ny);
    holes(v, nx, ny, R, 1);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            f[j * nx + i] = 1e-6 * sin(i / 7.0) * cos(j / 5.0);
            z[j * nx + i] = v[j * nx + i] ? f[j * nx + i] : NAN;
        }
    double M = 0, e = 0, lo = INFINITY, hi = -INFINITY;
    for (int j = 1; j < ny - 1; j++)
        for (int i = 1; i < nx - 1; i++) {
            int k = j * nx + i;
            if (!v[k])
                M = test_worst(M, fabs(f[k - 1] + f[k + 1] + f[k - nx] + f[k + nx] - 4 * f[k]));
            else {
                lo = fmin(lo, f[k]);
                hi = test_worst(hi, f[k]);
            }
        }
    mc_error err = {0};
    ck_assert_int_eq(mc_level_fill_missing(z, v, nx, ny, NULL, &err), 0);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int k = j * nx + i;
            ck_assert(isfinite(z[k]));
            if (i < 4 && j >= 5 && j < 12) { /* the edge hole */
                ck_assert(z[k] >= lo - 1e-12 && z[k] <= hi + 1e-12);
                continue;
            }
            e = test_worst(e, fabs(z[k] - f[k]));
        }
    double bound = M * (R + 1) * (R + 1) / 4;
    printf("fill, smooth field: max error %.3e m, maximum-principle bound %.3e m\n", e, bound);
    ck_assert_double_le(e, bound);
    free(z);
    free(f);
    free(v);
}
END_TEST

START_TEST(test_fill_edge_cases)
{
    double z[12] = {0};
    unsigned char v[12] = {0};
    int filled = -1;
    mc_error err = {0};
    ck_assert_int_eq(mc_level_fill_missing(z, v, 4, 3, &filled, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "all 12 points"));
    ck_assert_int_eq(mc_level_fill_missing(z, NULL, 4, 3, &filled, &err), 0);
    ck_assert_int_eq(filled, 0);
    /* one valid point: everything takes its value */
    v[7] = 1;
    z[7] = 2.5e-6;
    ck_assert_int_eq(mc_level_fill_missing(z, v, 4, 3, &filled, &err), 0);
    ck_assert_int_eq(filled, 11);
    for (int k = 0; k < 12; k++)
        ck_assert_double_eq_tol(z[k], 2.5e-6, TOL_ROUNDOFF * 2.5e-6);
    /* the mask helper */
    double w[4] = {1, NAN, INFINITY, 2};
    unsigned char m[4] = {1, 1, 1, 0};
    ck_assert_int_eq(mc_level_mask_nonfinite(w, m, 4), 3);
    ck_assert(m[0] == 1 && m[1] == 0 && m[2] == 0 && m[3] == 0);
}
END_TEST

/* ---- crop and resample ------------------------------------------------------------------- */

START_TEST(test_crop)
{
    const mc_level_grid g = {100, 50, 1e-6, 2e-6, 1e-3, -5e-5};
    mc_level_grid s;
    int i0, j0;
    mc_error err = {0};
    /* aligned with samples */
    ck_assert_int_eq(mc_level_crop(&g, g.x0 + 10 * g.dx, g.y0 + 4 * g.dy, 20 * g.dx, 6 * g.dy,
                                   &s, &i0, &j0, &err), 0);
    ck_assert(i0 == 10 && j0 == 4 && s.nx == 20 && s.ny == 6);
    ck_assert_double_eq_tol(s.x0, g.x0 + 10 * g.dx, TOL_ROUNDOFF * g.dx);
    /* aligned with cell edges */
    ck_assert_int_eq(mc_level_crop(&g, g.x0 + 9.5 * g.dx, g.y0 + 3.5 * g.dy, 20 * g.dx,
                                   6 * g.dy, &s, &i0, &j0, &err), 0);
    ck_assert(i0 == 10 && j0 == 4 && s.nx == 20 && s.ny == 6);
    /* the whole extent */
    ck_assert_int_eq(mc_level_crop(&g, g.x0 - g.dx / 2, g.y0 - g.dy / 2, 100 * g.dx, 50 * g.dy,
                                   &s, &i0, &j0, &err), 0);
    ck_assert(i0 == 0 && j0 == 0 && s.nx == 100 && s.ny == 50);
    /* outside: names the region and the grid extent */
    ck_assert_int_eq(mc_level_crop(&g, g.x0 + 90 * g.dx, g.y0, 20 * g.dx, 6 * g.dy, &s, &i0,
                                   &j0, &err), MC_ERR_INPUT);
    printf("crop error: %s\n", err.msg);
    ck_assert_ptr_nonnull(strstr(err.msg, "region x [0.00109, 0.00111] m"));
    ck_assert_ptr_nonnull(strstr(err.msg, "grid extent x [0.0009995, 0.0010995] m"));
    /* inside but between samples; no width */
    ck_assert_int_eq(mc_level_crop(&g, g.x0 + 10.2 * g.dx, g.y0, 0.5 * g.dx, 6 * g.dy, &s, &i0,
                                   &j0, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "holds no sample"));
    ck_assert_int_eq(mc_level_crop(&g, g.x0, g.y0, 0, 6 * g.dy, &s, &i0, &j0, &err),
                     MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "empty"));
    /* the block copy */
    double src[12], dst[4];
    unsigned char sv[12], dv[4];
    for (int k = 0; k < 12; k++) {
        src[k] = k;
        sv[k] = k % 2;
    }
    mc_level_copy_block(src, sv, 4, 1, 1, 2, 2, dst, dv); /* rows 1-2, columns 1-2 of 4 x 3 */
    ck_assert(dst[0] == 5 && dst[1] == 6 && dst[2] == 9 && dst[3] == 10);
    ck_assert(dv[0] == 1 && dv[1] == 0 && dv[2] == 1 && dv[3] == 0);
}
END_TEST

static double bilin(double x, double y) { return 1e-6 + 2e-3 * x - 3e-3 * y + 40.0 * x * y; }

START_TEST(test_resample_linear)
{
    const mc_level_grid gs = {30, 20, 1e-6, 1.5e-6, -14.5e-6, 2e-6};
    double *src = malloc(sizeof(double) * 600);
    for (int j = 0; j < gs.ny; j++)
        for (int i = 0; i < gs.nx; i++)
            src[j * gs.nx + i] = bilin(gs.x0 + i * gs.dx, gs.y0 + j * gs.dy);
    /* a bilinear field is reproduced exactly: finer grid over the whole cell extent (half a
     * source cell beyond the outer samples), a coarser one, a shifted one */
    const mc_level_grid gd[3] = {
        {90, 60, gs.dx / 3, gs.dy / 3, gs.x0 - gs.dx / 3, gs.y0 - gs.dy / 3},
        {10, 7, 3 * gs.dx, 3 * gs.dy, gs.x0, gs.y0},
        {17, 11, 1.3e-6, 2.1e-6, gs.x0 + 0.37e-6, gs.y0 + 1.1e-6}};
    mc_error err = {0};
    for (int c = 0; c < 3; c++) {
        double *dst = malloc(sizeof(double) * gd[c].nx * gd[c].ny), e = 0, fm = 0;
        ck_assert_msg(mc_level_resample_linear(src, &gs, dst, &gd[c], &err) == 0, "%s",
                      err.msg);
        for (int j = 0; j < gd[c].ny; j++)
            for (int i = 0; i < gd[c].nx; i++) {
                double f = bilin(gd[c].x0 + i * gd[c].dx, gd[c].y0 + j * gd[c].dy);
                e = test_worst(e, fabs(dst[j * gd[c].nx + i] - f));
                fm = test_worst(fm, fabs(f));
            }
        printf("resample %d: max error %.2e of %.2e m\n", c, e, fm);
        ck_assert_double_le(e, TOL_ROUNDOFF * fm);
        free(dst);
    }
    /* beyond the source: names both extents */
    mc_level_grid far = {20, 10, 2e-6, 2e-6, gs.x0, gs.y0};
    double out[200];
    ck_assert_int_eq(mc_level_resample_linear(src, &gs, out, &far, &err), MC_ERR_INPUT);
    printf("resample error: %s\n", err.msg);
    ck_assert_ptr_nonnull(strstr(err.msg, "destination samples x [-1.45e-05, 2.35e-05] m"));
    ck_assert_ptr_nonnull(strstr(err.msg, "source extent x [-1.5e-05, 1.5e-05] m"));
    /* a source of one row is constant along y within its cell */
    const mc_level_grid g1 = {30, 1, 1e-6, 1e-6, 0, 0}, d1 = {5, 3, 2e-6, 0.4e-6, 3e-6, -0.4e-6};
    ck_assert_int_eq(mc_level_resample_linear(src, &g1, out, &d1, &err), 0);
    for (int k = 0; k < 15; k++)
        ck_assert_double_eq_tol(out[k], src[3 + 2 * (k % 5)], TOL_ROUNDOFF * 1e-6);
    free(src);
}
END_TEST

Suite *suite_level(void);
Suite *suite_level(void)
{
    Suite *s = suite_create("level");
    TCase *tc = tcase_create("core");
    tcase_add_loop_test(tc, test_detrend_exact, 1, 4);
    tcase_add_test(tc, test_detrend_least_squares);
    tcase_add_test(tc, test_detrend_degenerate_and_errors);
    tcase_add_loop_test(tc, test_fill_harmonic, 0, 2);
    tcase_add_test(tc, test_fill_smooth);
    tcase_add_test(tc, test_fill_edge_cases);
    tcase_add_test(tc, test_crop);
    tcase_add_test(tc, test_resample_linear);
    suite_add_tcase(s, tc);
    return s;
}
