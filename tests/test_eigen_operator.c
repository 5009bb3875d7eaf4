/* test_eigen_operator.c - the eigenstrain operators (src/plastic/eigen_op.h): direct vs fft on
 * odd and even windows, dx != dy and several nz; the impulse response against the kernel
 * functions of kernels/eigen.h summed by hand (S1 + S2 from mc_eigen_stress12, S3 from
 * mc_rect_stress_p over p3); the finite-patch limits of a uniform layer (dossier
 * theory.md §8.1) and the laterally constrained layer's stress; the vanishing surface
 * traction (S3 cancels p3, §2.3); the reciprocity cross-check u_z = Boussinesq displacement of p3
 * (§2.3), converging at second order in the mesh; bad input and allocation failures. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/threads.h"
#include "kernels/eigen.h"
#include "kernels/kernel.h"
#include "operator/operator.h"
#include "plastic/eigen_op.h"
#include "eigen_testkit.h"
#include "test_util.h"

/* ---- tolerances ------------------------------------------------------------------------------ */

/* Backends: the same tables summed directly or through FFTs (lateral and, for the stress, the
 * depth transforms): round-off of O(N) terms relative to the largest output; the issue asks for
 * <= 1e-10, measured ~1e-15. */
#define TOL_BACKENDS 1e-10
/* Impulse response vs the kernel functions: the tables hold the same corner sums, except that
 * negative offsets come from parity and S2 from S1 of a translated cuboid (the mirror's corner
 * sums evaluated separately, not combined first as mc_eigen_stress12 does): round-off of corner
 * terms of size O(10) relative to the largest output, the self cell's O(1) (measured 1e-15). */
#define TOL_IMPULSE 1e-12
/* D's corner terms do not decay while D falls like (h/d)^3 (eigen.h: relative error ~ eps
 * (d/h)^3, measured 1e-12 at d = 10 h); per value, with d the farthest surface cell and h the
 * smallest side of the cuboid, times a margin of 64 (measured 3e-12 at d/h = 18). */
#define TOL_IMPULSE_D(d_over_h) (64.0 * DBL_EPSILON * pow(d_over_h, 3))
/* The 21-table storage relies on S[c][i] = (w_i / w_c) S[i][c] (major symmetry of C:Gamma:C);
 * the kernel evaluates the two sides from different corner terms of size O(1-10): absolute
 * round-off per unit 2G (eigen.h: ~3e-16 for S; measured <= 1e-16). */
#define TOL_SYMMETRY 1e-14

static const double NU = 0.3;
static const double E_MOD = 210e9;                      /* Pa */
#define G_MOD (E_MOD / (2.0 * (1.0 + NU)))             /* shear modulus, Pa */

/* ---- helpers ----------------------------------------------------------------------------- */

typedef struct {
    int gx, gy;          /* surface grid */
    double dx, dy;
    int i0, j0, wx, wy;  /* window */
    int nz;
    double dz;
    int line;            /* periodic along y with gy = 1: a line contact (bars along y) */
} vol_case;

/* Odd and even windows, dx != dy, windows inside larger grids (not centred), nz = 1, 3, 5; and
 * line contacts (periodic y, ny = 1) with odd and even nx, a window inside the grid, nz 1..5. */
static const vol_case cases[] = {
    {6, 6, 1e-6, 1e-6, 0, 0, 6, 6, 1, 0.5e-6, 0},
    {9, 7, 1.0e-6, 1.3e-6, 0, 0, 9, 7, 3, 0.8e-6, 0},
    {11, 10, 0.7e-6, 1.0e-6, 2, 1, 5, 8, 5, 0.6e-6, 0},
    {8, 9, 1.2e-6, 0.9e-6, 3, 4, 4, 5, 3, 1.1e-6, 0},
    {12, 5, 1e-6, 2e-6, 1, 0, 7, 5, 1, 0.3e-6, 0},
    {1, 1, 1e-6, 1e-6, 0, 0, 1, 1, 3, 1e-6, 0},
    {9, 1, 1.0e-6, 1.3e-6, 0, 0, 9, 1, 3, 0.8e-6, 1},
    {16, 1, 0.7e-6, 1.0e-6, 3, 0, 8, 1, 5, 0.6e-6, 1},
    {13, 1, 1.2e-6, 0.9e-6, 2, 0, 7, 1, 1, 1.1e-6, 1},
    {10, 1, 1e-6, 2e-6, 0, 0, 10, 1, 4, 0.3e-6, 1},
    {1, 1, 1e-6, 1e-6, 0, 0, 1, 1, 2, 1e-6, 1},
};
#define N_CASES ((int)(sizeof cases / sizeof cases[0]))

static mc_grid case_grid(const vol_case *c)
{
    mc_grid g = {c->gx, c->gy, c->dx, c->dy, 0, c->line};
    return g;
}

static mc_eigen_volume case_volume(const vol_case *c)
{
    mc_eigen_volume v = {c->i0, c->j0, c->wx, c->wy, c->nz, c->dz, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    return v;
}

static size_t vol_cells(const mc_eigen_volume *v) { return (size_t)v->nx * v->ny * v->nz; }





/* ---- direct vs fft ------------------------------------------------------------------------- */

START_TEST(test_disp_backends)
{
    const vol_case *vc = &cases[_i];
    const mc_grid g = case_grid(vc);
    const mc_eigen_volume v = case_volume(vc);
    const size_t n = vol_cells(&v), ns = mc_grid_cells(&g);
    double *eps[6], *blk = eig_fields(n, eps);
    test_random_field(blk, 6 * n, 11 + (unsigned)_i);
    double *ud = malloc(ns * sizeof *ud), *uf = malloc(ns * sizeof *uf);
    mc_eigen_disp *od = eig_disp_op(&g, &v, NU, MC_BACKEND_DIRECT), *of = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_disp_apply(od, (const double *const *)eps, ud);
    mc_eigen_disp_apply(of, (const double *const *)eps, uf);
    const double e = test_rel_maxdiff(uf, ud, ns);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "disp case %d: fft vs direct %.3g\n", _i, e);
    ck_assert_msg(e <= TOL_BACKENDS, "case %d: fft vs direct %.3g", _i, e);
    ck_assert(eig_max_abs(ud, ns) > 0.0);
    mc_eigen_disp_destroy(&od);
    mc_eigen_disp_destroy(&of);
    free(ud);
    free(uf);
    free(blk);
}
END_TEST

START_TEST(test_stress_backends)
{
    const vol_case *vc = &cases[_i];
    const mc_grid g = case_grid(vc);
    mc_eigen_volume v = case_volume(vc);
    if (_i % 2) /* the default evaluation, averaged near the source, on every other case */
        v.stress_points = MC_EIG_CELL_AVERAGE;
    const size_t n = vol_cells(&v), nw = (size_t)v.nx * v.ny;
    double *eps[6], *sd[6], *sf[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sd), *b3 = eig_fields(n, sf);
    test_random_field(b1, 6 * n, 29 + (unsigned)_i);
    mc_eigen_stress *od = eig_stress_op(&g, &v, NU, MC_BACKEND_DIRECT);
    mc_eigen_stress *of = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_stress_apply(od, (const double *const *)eps, G_MOD, sd);
    mc_eigen_stress_apply(of, (const double *const *)eps, G_MOD, sf);
    const double e = test_rel_maxdiff(b3, b2, 6 * n);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "stress case %d: fft vs direct %.3g\n", _i, e);
    ck_assert_msg(e <= TOL_BACKENDS, "case %d: stress fft vs direct %.3g", _i, e);
    double *pd = malloc(nw * sizeof *pd), *pf = malloc(nw * sizeof *pf);
    mc_eigen_stress_p3(od, pd);
    mc_eigen_stress_p3(of, pf);
    const double ep = test_rel_maxdiff(pf, pd, nw);
    ck_assert_msg(ep <= TOL_BACKENDS, "case %d: p3 fft vs direct %.3g", _i, ep);
    ck_assert(eig_max_abs(b2, 6 * n) > 0.0 && eig_max_abs(pd, nw) > 0.0);
    mc_eigen_stress_destroy(&od);
    mc_eigen_stress_destroy(&of);
    free(pd);
    free(pf);
    free(b1);
    free(b2);
    free(b3);
}
END_TEST

/* ---- impulse responses against the kernel functions ---------------------------------------- */

/* One unit eigenstrain column c in the cuboid (is, js, ks) of case 2; u_z at every surface cell
 * equals mc_eigen_surface_uz of that cuboid seen from the cell. */
START_TEST(test_disp_impulse)
{
    const vol_case *vc = &cases[2];
    const mc_grid g = case_grid(vc);
    const mc_eigen_volume v = case_volume(vc);
    const int is = 1, js = 5, ks = 3, c = _i;
    const size_t n = vol_cells(&v), ns = mc_grid_cells(&g);
    double *eps[6], *blk = eig_fields(n, eps);
    eps[c][((size_t)ks * v.ny + js) * v.nx + is] = 1.0;
    double *u = malloc(ns * sizeof *u), *ref = malloc(ns * sizeof *ref);
    mc_eigen_disp *op = eig_disp_op(&g, &v, NU, MC_BACKEND_DIRECT);
    mc_eigen_disp_apply(op, (const double *const *)eps, u);
    const double xs = mc_grid_x(&g, v.i0 + is), ys = mc_grid_y(&g, v.j0 + js);
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            const double bx = xs - mc_grid_x(&g, i), by = ys - mc_grid_y(&g, j);
            double D[6];
            mc_eigen_surface_uz(bx - 0.5 * g.dx, bx + 0.5 * g.dx, by - 0.5 * g.dy,
                                by + 0.5 * g.dy, ks * v.dz, (ks + 1) * v.dz, NU, D);
            ref[(size_t)j * g.nx + i] = D[c];
        }
    const double e = test_rel_maxdiff(u, ref, ns);
    const double far = hypot(hypot(fmax(xs - mc_grid_x(&g, 0), mc_grid_x(&g, g.nx - 1) - xs),
                                   fmax(ys - mc_grid_y(&g, 0), mc_grid_y(&g, g.ny - 1) - ys)),
                             (ks + 1) * v.dz);
    const double tol = TOL_IMPULSE_D(far / fmin(fmin(g.dx, g.dy), v.dz));
    ck_assert_msg(e <= tol, "column %d: impulse vs mc_eigen_surface_uz %.3g (tol %.3g)", c, e,
                  tol);
    mc_eigen_disp_destroy(&op);
    free(u);
    free(ref);
    free(blk);
}
END_TEST

/* One unit column c in one cuboid; the stress at every cuboid centre equals
 * 2G [mc_eigen_stress12 + sum over window cells s of mc_rect_stress_p(x - s) p3(s) / 2G],
 * p3(s) / 2G = mc_eigen_surface_szz12 at s: S1 + S2 + S3 summed by hand. */
START_TEST(test_stress_impulse)
{
    const vol_case *vc = &cases[2];
    const mc_grid g = case_grid(vc);
    const mc_eigen_volume v = case_volume(vc);
    const int is = 3, js = 2, ks = 1, c = _i;
    const size_t n = vol_cells(&v), nw = (size_t)v.nx * v.ny;
    const double hx = 0.5 * g.dx, hy = 0.5 * g.dy;
    double *eps[6], *sig[6], *ref[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sig), *b3 = eig_fields(n, ref);
    eps[c][((size_t)ks * v.ny + js) * v.nx + is] = 1.0;
    mc_eigen_stress *op = eig_stress_op(&g, &v, NU, MC_BACKEND_DIRECT);
    mc_eigen_stress_apply(op, (const double *const *)eps, G_MOD, sig);
    /* p3 / 2G of the cuboid on the window, and its check against the operator's p3 */
    double *p3 = malloc(nw * sizeof *p3), *p3op = malloc(nw * sizeof *p3op);
    for (int j = 0; j < v.ny; j++)
        for (int i = 0; i < v.nx; i++) {
            double s[6];
            mc_eigen_surface_szz12((i - is) * g.dx, (j - js) * g.dy, hx, hy, ks * v.dz,
                                   (ks + 1) * v.dz, NU, s);
            p3[(size_t)j * v.nx + i] = s[c];
            p3op[(size_t)j * v.nx + i] = 0.0;
        }
    mc_eigen_stress_p3(op, p3op);
    for (size_t q = 0; q < nw; q++)
        p3op[q] /= 2.0 * G_MOD;
    const double ep = test_rel_maxdiff(p3op, p3, nw);
    ck_assert_msg(ep <= TOL_IMPULSE, "column %d: p3 vs mc_eigen_surface_szz12 %.3g", c, ep);
    for (int k = 0; k < v.nz; k++)
        for (int j = 0; j < v.ny; j++)
            for (int i = 0; i < v.nx; i++) {
                const double z = (k + 0.5) * v.dz;
                double S[6][6];
                mc_eigen_stress12((i - is) * g.dx, (j - js) * g.dy, z, hx, hy, ks * v.dz,
                                  (ks + 1) * v.dz, NU, S);
                double s3[6] = {0.0};
                for (int jj = 0; jj < v.ny; jj++)
                    for (int ii = 0; ii < v.nx; ii++) {
                        double s[6];
                        mc_rect_stress_p((i - ii) * g.dx, (j - jj) * g.dy, z, hx, hy, NU, s);
                        for (int o = 0; o < 6; o++)
                            s3[o] += s[o] * p3[(size_t)jj * v.nx + ii];
                    }
                for (int o = 0; o < 6; o++)
                    ref[o][((size_t)k * v.ny + j) * v.nx + i] = 2.0 * G_MOD * (S[o][c] + s3[o]);
            }
    const double e = test_rel_maxdiff(b2, b3, 6 * n);
    ck_assert_msg(e <= TOL_IMPULSE, "column %d: impulse vs S1+S2+S3 by hand %.3g", c, e);
    mc_eigen_stress_destroy(&op);
    free(p3);
    free(p3op);
    free(b1);
    free(b2);
    free(b3);
}
END_TEST

/* The major symmetry the 21-table storage relies on, at points inside, beside, above and below
 * a non-cubic cuboid. */
START_TEST(test_kernel_symmetry)
{
    static const double pts[][3] = {{0.0, 0.0, 0.4},  {0.3, -0.2, 0.1}, {1.3, 2.0, 3.5},
                                    {-2.0, 1.0, -1.5}, {3.0, -4.0, 7.5}, {0.0, 1.0, 2.5}};
    const double w[6] = {1, 1, 1, 2, 2, 2};
    for (size_t p = 0; p < sizeof pts / sizeof pts[0]; p++) {
        double S[6][6], d = 0.0;
        mc_eigen_stress1(pts[p][0], pts[p][1], pts[p][2], 0.5, 0.35, 0.0, 0.8, NU, S);
        for (int i = 0; i < 6; i++)
            for (int c = 0; c < 6; c++)
                d = test_worst(d, fabs(S[c][i] - w[i] / w[c] * S[i][c]));
        ck_assert_msg(d <= TOL_SYMMETRY, "point %zu: asymmetry %.3g", p, d);
    }
}
END_TEST

/* ---- uniform layers: the finite-patch limits (theory.md §8.1) and the constrained layer ------- */

/* Wide thin surface layer (thickness t, half-width W): at the centre u_z / t tends to the finite
 * patch limits -eps_zz, -(1+2nu) for (1,1,0), +(1-2nu) for (1,1,-2), -2(1+nu) for eps I, 0 for
 * eps_xz. The missing far field beyond the inscribed disc of the in-plane nucleus integrates to
 * 2(1+nu) t (d + t) / W per unit in-plane eigenstrain (test_eigen_kernels.c; d = 0 here), the zz
 * nucleus (z^3/rho^5) to (2 pi / 3) t^4 / W^3.
 * Loop index 1: the same on a line grid (periodic y, ny = 1), a strip |x| <= W infinite along y.
 * Betti with Flamant's line load (sigma_xx, sigma_zz = -(2/pi) x^2 z, z^3 / rho^4, sigma_yy =
 * nu (sigma_xx + sigma_zz)) gives the same limits (int sigma_xx = int sigma_zz = -t, int sigma_yy
 * = -2 nu t over the thin strip), the missing tails |x| > W now (2/pi)(1 + nu) t / W in-plane and
 * O((t/W)^3) for zz: within the same bounds. */
#define LAYER_CELLS 127 /* odd: the centre cell is the patch centre (xz: 0 by symmetry) */
#define LAYER_T 0.1 /* in cells */
#define TOL_LAYER_INPLANE(t, w) (2.0 * (1.0 + NU) * (t) / (w))
#define TOL_LAYER_ZZ(t, w) (2.0 * M_PI / 3.0 * pow((t) / (w), 3))

START_TEST(test_disp_uniform_layer)
{
    static const double e6[5][6] = {{0, 0, 1, 0, 0, 0}, {1, 1, 0, 0, 0, 0}, {1, 1, -2, 0, 0, 0},
                                    {1, 1, 1, 0, 0, 0}, {0, 0, 0, 0, 0, 1}};
    const double limit[5] = {-1.0, -(1.0 + 2.0 * NU), 1.0 - 2.0 * NU, -2.0 * (1.0 + NU), 0.0};
    const double dx = 1e-6, t = LAYER_T * dx, w = 0.5 * LAYER_CELLS * dx;
    const mc_grid g = {LAYER_CELLS, _i ? 1 : LAYER_CELLS, dx, dx, 0, _i};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, 1, t);
    const size_t mid = (size_t)(g.ny / 2) * g.nx + g.nx / 2;
    const size_t n = mc_grid_cells(&g);
    double *eps[6], *blk = eig_fields(n, eps), *u = malloc(n * sizeof *u);
    mc_eigen_disp *op = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT); /* = direct: test_disp_backends */
    for (int q = 0; q < 5; q++) {
        for (int c = 0; c < 6; c++)
            for (size_t s = 0; s < n; s++)
                eps[c][s] = e6[q][c];
        mc_eigen_disp_apply(op, (const double *const *)eps, u);
        const double uc = u[mid] / t;
        const double inplane = 0.5 * (fabs(e6[q][0]) + fabs(e6[q][1]));
        const double tol = inplane * TOL_LAYER_INPLANE(t, w) + TOL_LAYER_ZZ(t, w);
        ck_assert_msg(fabs(uc - limit[q]) <= tol,
                      "%s case %d: u_z/t = %.6f, limit %.6f, tol %.2g", _i ? "line" : "patch", q,
                      uc, limit[q], tol);
    }
    mc_eigen_disp_destroy(&op);
    free(u);
    free(blk);
}
END_TEST

/* A wide buried layer of in-plane eigenstrain (1,1,0) e, laterally constrained far from its rim:
 * inside sigma_xx = sigma_yy = -2G (1+nu)/(1-nu) e, sigma_zz = shear = 0, and no stress above or
 * below it. The rim line forces f = |sigma| t at distance W from the centre leave stresses of
 * order f / W there: bound 2 (t / W) |sigma| (measured 1.2 (t / W) |sigma|, halving with W).
 * Loop index 1: a strip |x| <= W on a line grid (periodic y, ny = 1); its two rim lines leave
 * stresses of the same order f / W (measured 1.28 (t / W) |sigma|). */
#define SLAB_CELLS 96
#define SLAB_T 0.05
#define TOL_SLAB(t, w) (2.0 * (t) / (w))

START_TEST(test_stress_uniform_layer)
{
    const double dx = 1e-6, t = SLAB_T * dx, w = 0.5 * SLAB_CELLS * dx;
    const int nz = 4, kl = 1;
    const mc_grid g = {SLAB_CELLS, _i ? 1 : SLAB_CELLS, dx, dx, 0, _i};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, nz, t);
    const size_t nw = mc_grid_cells(&g), n = nw * nz;
    double *eps[6], *sig[6], *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sig);
    for (size_t s = 0; s < nw; s++)
        eps[0][kl * nw + s] = eps[1][kl * nw + s] = 1.0;
    mc_eigen_stress *op = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT); /* = direct: test_stress_backends */
    mc_eigen_stress_apply(op, (const double *const *)eps, G_MOD, sig);
    const double ref = -2.0 * G_MOD * (1.0 + NU) / (1.0 - NU), tol = TOL_SLAB(t, w) * fabs(ref);
    const size_t mid = (size_t)(g.ny / 2) * g.nx + g.nx / 2;
    for (int k = 0; k < nz; k++)
        for (int c = 0; c < 6; c++) {
            const double want = (k == kl && c < 2) ? ref : 0.0, got = sig[c][k * nw + mid];
            ck_assert_msg(fabs(got - want) <= tol, "%s layer %d %s: %.6g Pa, want %.6g, tol %.2g",
                          _i ? "line" : "patch", k, mc_component_name(c), got, want, tol);
            if (getenv("MC_TEST_VERBOSE"))
                fprintf(stderr, "%s layer %d %s: error %.3g (t/W) |sigma|\n", _i ? "line" : "patch",
                        k, mc_component_name(c), fabs(got - want) / (t / w) / fabs(ref));
        }
    mc_eigen_stress_destroy(&op);
    free(b1);
    free(b2);
}
END_TEST

/* ---- S3 cancels the surface traction (theory.md §8.2) ---------------------------------------- */

/* A block of eigenstrain at depth [2, 3] cells under a 12 x 12 window, seen from the top layer of
 * two volumes (dz = 1/2 and 1/4 cell: the same block): with zero shear traction, equilibrium
 * gives d sigma_zz/dz = 0 at a traction-free surface, so sigma_zz = O(z^2) at the top layer's
 * centre z = dz/2: a few per cent of p3 at dz = 1/4 ((z / depth)^2 ~ 0.004 times O(1)), and at
 * least 3 times smaller than at dz = 1/2 (4 asymptotically; measured 5.3 and 0.6 %). Without S3
 * the top layer would carry sigma_zz ~ p3. */
#define TRACTION_MAX 0.02
#define TRACTION_RATE 3.0

static double top_traction(double dz, double *p3max)
{
    const int w = 12, nz = (int)lround(4.0 / dz);
    const double e6[6] = {0.7, -0.3, -0.4, 0.25, -0.15, 0.35};
    const mc_grid g = {w, w, 1e-6, 1e-6, 0, 0};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, nz, dz * 1e-6);
    const size_t nw = mc_grid_cells(&g), n = nw * nz;
    double *eps[6], *sig[6], *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sig);
    for (int k = 0; k < nz; k++) {
        const double zc = (k + 0.5) * dz;
        if (zc < 2.0 || zc > 3.0)
            continue;
        for (int j = 4; j < 8; j++)
            for (int i = 4; i < 8; i++)
                for (int c = 0; c < 6; c++)
                    eps[c][k * nw + (size_t)j * w + i] = e6[c] * (1.0 + 0.1 * i - 0.05 * j);
    }
    mc_eigen_stress *op = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_stress_apply(op, (const double *const *)eps, G_MOD, sig);
    double *p3 = malloc(nw * sizeof *p3);
    mc_eigen_stress_p3(op, p3);
    *p3max = eig_max_abs(p3, nw);
    const double top = eig_max_abs(sig[MC_SZZ], nw); /* layer 0 */
    mc_eigen_stress_destroy(&op);
    free(p3);
    free(b1);
    free(b2);
    return top;
}

START_TEST(test_surface_traction)
{
    double p_coarse, p_fine;
    const double coarse = top_traction(0.5, &p_coarse), fine = top_traction(0.25, &p_fine);
    ck_assert(p_fine > 0.0 && p_coarse > 0.0);
    ck_assert_msg(fine <= TRACTION_MAX * p_fine, "top-layer sigma_zz %.3g of p3 %.3g", fine,
                  p_fine);
    ck_assert_msg(coarse >= TRACTION_RATE * fine, "sigma_zz(dz/2) does not fall like z^2: %.3g, "
                  "%.3g", coarse, fine);
}
END_TEST

/* ---- reciprocity: u_z = Boussinesq displacement of p3 (theory.md §8.2) ----------------------- */

/* A smooth blob of plastic (trace-free) eigenstrain (Gaussian, width 1.5 cells of h = 1, centred
 * 8 deep) under a 128 x 128 surface; the Love operator of operator.h with the one-body modulus
 * E/(1-nu^2) applied to the cell-centre samples of p3 is a midpoint rule, second order in h for a
 * smooth p3, while p3 outside the window is missing (p3 ~ r^-3: a floor of a few 1e-3 here).
 * Bounds: at h = 1 the error is <= RECIP_MAX of max |u_z|, and at least RECIP_RATE times smaller
 * than at h = 2 (4 for second order; measured 1.43 % and 0.48 %, ratio 3.0). */
#define RECIP_MAX 0.01
#define RECIP_RATE 2.5

static double reciprocity_error(double h)
{
    const double L = 128.0, zc = 8.0, sg = 1.5, unit = 1e-6;
    const int w = (int)lround(L / h), nz = (int)lround((zc + 3.0 * sg) / h);
    const double e6[6] = {1.0, 0.6, -1.6, 0.3, 0.2, -0.25};
    const mc_grid g = {w, w, h * unit, h * unit, 0, 0};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, nz, h * unit);
    const size_t nw = mc_grid_cells(&g), n = nw * nz;
    double *eps[6], *sig[6], *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sig);
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < w; j++)
            for (int i = 0; i < w; i++) {
                const double x = mc_grid_x(&g, i) / unit, y = mc_grid_y(&g, j) / unit;
                const double z = (k + 0.5) * h - zc;
                const double b = exp(-(x * x + y * y + z * z) / (2.0 * sg * sg));
                for (int c = 0; c < 6; c++)
                    eps[c][k * nw + (size_t)j * w + i] = e6[c] * b;
            }
    mc_eigen_stress *os = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_disp *od = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_operator *love;
    mc_error err;
    ck_assert_int_eq(mc_operator_plan_love(&g, E_MOD / (1.0 - NU * NU), MC_BACKEND_FFT, &love,
                                           &err), MC_OK);
    double *p3 = malloc(nw * sizeof *p3), *u1 = malloc(nw * sizeof *u1);
    double *u2 = malloc(nw * sizeof *u2);
    mc_eigen_stress_apply(os, (const double *const *)eps, G_MOD, sig);
    mc_eigen_stress_p3(os, p3);
    mc_operator_apply(love, p3, u2);
    mc_eigen_disp_apply(od, (const double *const *)eps, u1);
    const double e = test_rel_maxdiff(u2, u1, nw);
    mc_eigen_stress_destroy(&os);
    mc_eigen_disp_destroy(&od);
    mc_operator_destroy(&love);
    free(p3);
    free(u1);
    free(u2);
    free(b1);
    free(b2);
    return e;
}

START_TEST(test_reciprocity)
{
    const double coarse = reciprocity_error(2.0), fine = reciprocity_error(1.0);
    ck_assert_msg(fine <= RECIP_MAX, "u_z vs Boussinesq of p3: %.3g", fine);
    ck_assert_msg(coarse >= RECIP_RATE * fine, "no convergence: %.3g then %.3g", coarse, fine);
}
END_TEST

/* ---- threads, bad input, allocation failures --------------------------------------------- */

START_TEST(test_threads)
{
    const vol_case *vc = &cases[2];
    const mc_grid g = case_grid(vc);
    const mc_eigen_volume v = case_volume(vc);
    const size_t n = vol_cells(&v), ns = mc_grid_cells(&g);
    double *eps[6], *s1[6], *s2[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, s1), *b3 = eig_fields(n, s2);
    double *u1 = malloc(ns * sizeof *u1), *u2 = malloc(ns * sizeof *u2);
    test_random_field(b1, 6 * n, 5);
    for (int r = 0; r < 2; r++) {
        mc_threads_scope scope;
        mc_threads_begin(r + 1, &scope);
        mc_eigen_stress *os = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
        mc_eigen_disp *od = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
        mc_eigen_stress_apply(os, (const double *const *)eps, G_MOD, r ? s2 : s1);
        mc_eigen_disp_apply(od, (const double *const *)eps, r ? u2 : u1);
        mc_eigen_stress_destroy(&os);
        mc_eigen_disp_destroy(&od);
        mc_threads_end(&scope);
    }
    ck_assert(test_rel_maxdiff(b3, b2, 6 * n) <= TOL_BACKENDS);
    ck_assert(test_rel_maxdiff(u2, u1, ns) <= TOL_BACKENDS);
    free(b1);
    free(b2);
    free(b3);
    free(u1);
    free(u2);
}
END_TEST

/* ---- the line grid against long free grids ------------------------------------------------- */

/* A y-uniform random eigenstrain under a window of a line grid (periodic y, ny = 1) against the
 * same field on free grids of NY_SHORT and NY_LONG rows (odd; the window spans all rows): the
 * centre row converges to the line result as the row count N grows. The rows beyond N dy / 2 are
 * missing: the displacement and Love's stresses of p3 decay like 1/y^2 (first order, error
 * ~ 1/N), the cuboid stresses like 1/y^3: first order overall, a factor 4 from NY_SHORT to
 * NY_LONG asymptotically. Measured (relative to the largest value) from 129 to 517 rows:
 * displacement 6.1e-4 -> 1.8e-4 (3.45 x), stress 2.6e-4 -> 6.9e-5 (3.78 x); with fewer rows a
 * second-order term of the other sign still competes (33 -> 132 rows: 1.8 x). Checked: the error
 * falls by at least LONG_RATE_MIN and is at most LONG_TOL at NY_LONG rows. Loop index: 0
 * displacement, 1 stress (and p3). fft backend (= direct: test_*_backends). */
#define NY_SHORT 129
#define NY_LONG 517
#define LONG_RATE_MIN 3.0
#define LONG_TOL 5e-4

static double long_error(int what, int ny, const double *eps_line, const mc_grid *gl,
                         const mc_eigen_volume *vl)
{
    const int nx = gl->nx, wx = vl->nx, nz = vl->nz;
    const mc_grid g = {nx, ny, gl->dx, gl->dy, 0, 0};
    const mc_eigen_volume v = {vl->i0, 0, wx, ny, nz, vl->dz, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    const size_t n = (size_t)wx * ny * nz, nl = (size_t)wx * nz;
    double *eps[6], *blk = eig_fields(n, eps), *el[6];
    for (int c = 0; c < 6; c++) {
        el[c] = (double *)eps_line + (size_t)c * nl;
        for (int k = 0; k < nz; k++)
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < wx; i++)
                    eps[c][((size_t)k * ny + j) * wx + i] = el[c][(size_t)k * wx + i];
    }
    double err = 0.0, ref = 0.0;
    const int jc = ny / 2;
    if (what == 0) {
        double *u = malloc((size_t)nx * ny * sizeof *u), *ul = malloc((size_t)nx * sizeof *ul);
        mc_eigen_disp *op = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT), *ol = eig_disp_op(gl, vl, NU, MC_BACKEND_FFT);
        mc_eigen_disp_apply(op, (const double *const *)eps, u);
        mc_eigen_disp_apply(ol, (const double *const *)el, ul);
        for (int i = 0; i < nx; i++) {
            err = test_worst(err, fabs(u[(size_t)jc * nx + i] - ul[i]));
            ref = test_worst(ref, fabs(ul[i]));
        }
        mc_eigen_disp_destroy(&op);
        mc_eigen_disp_destroy(&ol);
        free(u);
        free(ul);
    } else {
        double *sig[6], *sl[6], *b2 = eig_fields(n, sig), *b3 = eig_fields(nl, sl);
        mc_eigen_stress *op = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
        mc_eigen_stress *ol = eig_stress_op(gl, vl, NU, MC_BACKEND_FFT);
        mc_eigen_stress_apply(op, (const double *const *)eps, G_MOD, sig);
        mc_eigen_stress_apply(ol, (const double *const *)el, G_MOD, sl);
        for (int c = 0; c < 6; c++)
            for (int k = 0; k < nz; k++)
                for (int i = 0; i < wx; i++) {
                    const double a = sig[c][((size_t)k * ny + jc) * wx + i];
                    const double b = sl[c][(size_t)k * wx + i];
                    err = test_worst(err, fabs(a - b));
                    ref = test_worst(ref, fabs(b));
                }
        mc_eigen_stress_destroy(&op);
        mc_eigen_stress_destroy(&ol);
        free(b2);
        free(b3);
    }
    free(blk);
    return err / ref;
}

START_TEST(test_line_vs_long_grid)
{
    const mc_grid gl = {11, 1, 1e-6, 1.2e-6, 0, 1};
    const mc_eigen_volume vl = {2, 0, 7, 1, 3, 0.7e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    const size_t nl = (size_t)vl.nx * vl.nz;
    double *eps[6], *blk = eig_fields(nl, eps);
    test_random_field(blk, 6 * nl, 71);
    const double e1 = long_error(_i, NY_SHORT, blk, &gl, &vl);
    const double e2 = long_error(_i, NY_LONG, blk, &gl, &vl);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "%s: line vs %d rows %.3g, %d rows %.3g (ratio %.2f)\n",
                _i ? "stress" : "disp", NY_SHORT, e1, NY_LONG, e2, e1 / e2);
    ck_assert_msg(e1 / e2 >= LONG_RATE_MIN && e2 <= LONG_TOL,
                  "%s: line vs %d rows %.3g, %d rows %.3g", _i ? "stress" : "displacement",
                  NY_SHORT, e1, NY_LONG, e2);
    free(blk);
}
END_TEST

START_TEST(test_bad_input)
{
    mc_error err;
    mc_eigen_disp *od = NULL;
    mc_eigen_stress *os = NULL;
    const mc_grid g = {8, 6, 1e-6, 1e-6, 0, 0};
    const mc_eigen_volume ok = {1, 1, 4, 3, 2, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    mc_eigen_volume v = ok;
    /* periodic axes (tests/test_eigen_periodic.c): a volume that does not span the period of a
     * periodic axis, and x periodic alone, are refused */
    const mc_grid gp = {8, 6, 1e-6, 1e-6, 0, 1}, gx = {8, 1, 1e-6, 1e-6, 1, 0};
    const mc_grid gxy = {8, 1, 1e-6, 1e-6, 1, 1};
    ck_assert_int_eq(mc_eigen_disp_create(&gp, &v, NU, MC_BACKEND_FFT, &od, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "whole period"));
    ck_assert_int_eq(mc_eigen_stress_create(&gp, &v, NU, MC_BACKEND_DIRECT, &os, &err),
                     MC_ERR_INPUT);
    const mc_eigen_volume v1 = {1, 0, 4, 1, 2, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    ck_assert_int_eq(mc_eigen_disp_create(&gx, &v1, NU, MC_BACKEND_FFT, &od, &err), MC_ERR_LIMIT);
    ck_assert_ptr_nonnull(strstr(err.msg, "periodic along x alone"));
    ck_assert_int_eq(mc_eigen_stress_create(&gxy, &v1, NU, MC_BACKEND_FFT, &os, &err),
                     MC_ERR_INPUT);
    const mc_eigen_volume bad[] = {
        {5, 1, 4, 3, 2, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID},  /* window beyond x */
        {1, 4, 4, 3, 2, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID},  /* beyond y */
        {-1, 1, 4, 3, 2, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID}, /* negative origin */
        {1, 1, 0, 3, 2, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID},  /* empty */
        {1, 1, 4, 3, 0, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID},  /* no layer */
        {1, 1, 4, 3, 2, 0.0, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID},   /* zero thickness */
        {1, 1, 4, 3, 2, NAN, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID},
    };
    for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
        v = bad[q];
        ck_assert_int_eq(mc_eigen_disp_create(&g, &v, NU, MC_BACKEND_FFT, &od, &err),
                         MC_ERR_INPUT);
        ck_assert_int_eq(mc_eigen_stress_create(&g, &v, NU, MC_BACKEND_FFT, &os, &err),
                         MC_ERR_INPUT);
    }
    v = ok;
    ck_assert_int_eq(mc_eigen_disp_create(&g, &v, 0.5, MC_BACKEND_FFT, &od, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_eigen_stress_create(&g, &v, -1.0, MC_BACKEND_FFT, &os, &err),
                     MC_ERR_INPUT);
    ck_assert_int_eq(mc_eigen_stress_create(&g, &v, NU, (mc_backend)7, &os, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_eigen_stress_create(&g, NULL, NU, MC_BACKEND_FFT, &os, &err),
                     MC_ERR_INPUT);
    ck_assert_ptr_null(od);
    ck_assert_ptr_null(os);
}
END_TEST

START_TEST(test_alloc_failure)
{
    const mc_grid g = {7, 6, 1e-6, 1.2e-6, 0, 0};
    const mc_eigen_volume v = {1, 1, 5, 4, 2, 0.8e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    const mc_backend b = (_i & 1) ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    int done = 0;
    for (long k = 1; k < 200 && !done; k++) {
        mc_error err;
        mc_eigen_disp *od = NULL;
        mc_eigen_stress *os = NULL;
        const long before = mc_alloc_injected();
        mc_alloc_fail_at(k);
        const int rc = _i < 2 ? mc_eigen_disp_create(&g, &v, NU, b, &od, &err)
                              : mc_eigen_stress_create(&g, &v, NU, b, &os, &err);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() > before) {
            ck_assert_int_eq(rc, MC_ERR_NOMEM);
            ck_assert_ptr_null(od);
            ck_assert_ptr_null(os);
        } else {
            ck_assert_int_eq(rc, MC_OK);
            mc_eigen_disp_destroy(&od);
            mc_eigen_stress_destroy(&os);
            done = 1;
        }
    }
    ck_assert_msg(done, "create never succeeded");
}
END_TEST

Suite *suite_eigen_operator(void);
Suite *suite_eigen_operator(void)
{
    Suite *s = suite_create("eigen_operator");
    TCase *tc = tcase_create("backends");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_disp_backends, 0, N_CASES);
    tcase_add_loop_test(tc, test_stress_backends, 0, N_CASES);
    tcase_add_loop_test(tc, test_disp_impulse, 0, 6);
    tcase_add_loop_test(tc, test_stress_impulse, 0, 6);
    tcase_add_test(tc, test_kernel_symmetry);
    tcase_add_test(tc, test_threads);
    tcase_add_test(tc, test_bad_input);
    tcase_add_loop_test(tc, test_alloc_failure, 0, 4);
    suite_add_tcase(s, tc);

    tc = tcase_create("physics");
    tcase_set_timeout(tc, 300);
    tcase_add_loop_test(tc, test_disp_uniform_layer, 0, 2);
    tcase_add_loop_test(tc, test_stress_uniform_layer, 0, 2);
    tcase_add_loop_test(tc, test_line_vs_long_grid, 0, 2);
    tcase_add_test(tc, test_surface_traction);
    tcase_add_test(tc, test_reciprocity);
    suite_add_tcase(s, tc);
    return s;
}
