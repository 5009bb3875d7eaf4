/* test_stress.c - subsurface stress (src/stress/stress.c, stress_table.c, stress_sym.c,
 * src/pipeline/stage_stress.c): kernel tables against a plain per-entry evaluation of the rectangle
 * functions, the convergence of the periodic tails, the exact strip, direct vs fft, surface limits,
 * impulse response, linearity, Hertz point and line contact against the closed forms of hertz.h,
 * the speed-ups against the plain paths (quadrant tables, symmetric transforms, sparse sums over
 * the loaded cells and their cost model, windows, depths from the contact), and the pipeline
 * stage. Sections refer to docs/theory.md. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "reference/hertz.h"
#include "kernels/invariants.h"
#include "kernels/kernel.h"
#include "operator/operator.h"
#include "case/scene.h"
#include "stress/stress.h"
#include "stress/traction.h"
#include "pipeline/stage_stress.h"
#include "test_util.h"

/* ---- tolerances ------------------------------------------------------------------------------ */

/* Tables vs the plain evaluation: the same sums in another order. Entries are differences of O(10)
 * corner values, so the round-off relative to the largest entry grows like eps (z/d)^2 once the
 * depth spreads the kernel (theory.md §5.5): TOL_TABLE up to TABLE_Z0 cells deep, then scaled
 * by (z/(TABLE_Z0 d))^2 (measured 3.6e-12 at 12 cells). */
#define TOL_TABLE 1e-12
#define TABLE_Z0 4.0
/* The periodic tail (stress.h): the automatic M is chosen so that the table change from M to 2M
 * is <= 5e-10 of the largest entry of the load's six tables (stress_table.c); 2x margin. */
#define TOL_TAIL 1e-9
/* The exact strip (n = 1) against the plane-strain closed form: the far edge of the strip at
 * 1e12 periods leaves O(d/F) ~ 1e-12 in the in-plane stresses; the rest is round-off. */
#define TOL_STRIP 1e-11
/* Direct vs fft, surface limits, impulse response, linearity: round-off of O(N) sums and FFTs. */
#define TOL_BACKEND TOL_ROUNDOFF
/* Hertz point, axis stresses on an odd grid (a cell on the axis), |error|/p0 <= C (dx/a)^2:
 * O(dx^2) pixelation of the cell-centre sampled pressure; C from the measured 3.8e-4 p0 at
 * a/dx = 20 (sigma_zz, z = a) with 30% margin. */
#define HERTZ_AXIS_C 0.2
/* Hertz point von Mises, max over the plane z = 0.48 a on even grids (as in theory.md §5.7, whose
 * table gives 1.6e-3, 3.7e-4, 1.1e-4 p0 for a/dx = 10, 20, 40, mu = 0.3; measured here 1.64e-3,
 * 3.65e-4, 1.05e-4): the dossier's two-digit values + 25%. */
#define HERTZ_VM_MARGIN 1.25
/* Halving dx: an O(dx^2) error drops ~4x; accept >= 3 (pixelation of the edge varies). */
#define RATIO_DX2 3.0
/* Hertz line, cell-averaged pressure (piecewise-constant loads: the kernels are exact, the error
 * is p - its cell average, O(dx^2)): |error|/p0 <= C (dx/b)^2; measured 2.3e-4 at b/dx = 20. */
#define HERTZ_LINE_C 0.12
/* Hertz line, cell-centre samples: the sqrt edge of p makes the sampling error O(dx^1.5)
 * (measured ratio 2.9 per halving): accept >= 2.5. */
#define RATIO_DX15 2.5
/* Point vs patch kernel at depth: they differ by the pixel's second moments, O((d/z)^2)
 * (theory.md §5.6): relative table difference <= POINT_PATCH_C (d/z)^2, d = max(dx, dy), and ~4x
 * per doubling of z; measured constant 0.35 (p) ... 0.50 (q_y) at dx/dy = 0.83. */
#define POINT_PATCH_C 0.6
/* Uniform load on the whole grid: sigma_zz under the centre within this of the rectangle's closed
 * form is round-off; and the closed form itself is -p to O((z/A)^3). */
#define UNIFORM_Z_OVER_A 0.05
/* A table entry and its mirror image (the parity's sign) come from different corners: each is a
 * difference of four corner values of size <= ~1 (the test grids have cells of ~1 m: logs of a
 * few, angles <= pi/2, over 2 pi), so they agree to a few eps absolutely (measured <= 6.7e-16 =
 * 3 eps, to z = 12 cells); 64 eps. The relative difference grows like (z/d)^2 as the entries
 * shrink, which is why it is held absolutely. */
#define TOL_MIRROR (64 * DBL_EPSILON)

#define NU 0.3

/* ---- helpers --------------------------------------------------------------------------------- */

typedef void (*rect_fn)(double, double, double, double, double, double, double *);
typedef void (*point_fn)(double, double, double, double, double *);
static const rect_fn rect_fns[3] = {mc_rect_stress_p, mc_rect_stress_qx, mc_rect_stress_qy};
static const point_fn point_fns[3] = {mc_point_stress_p, mc_point_stress_qx, mc_point_stress_qy};
static const int load_bits[3] = {MC_TRACTION_P, MC_TRACTION_QX, MC_TRACTION_QY};

static double **vols(int ncomp, size_t n)
{
    double **v = malloc(sizeof *v * (size_t)ncomp);
    ck_assert(v != NULL);
    for (int c = 0; c < ncomp; c++) {
        v[c] = calloc(n, sizeof(double));
        ck_assert(v[c] != NULL);
    }
    return v;
}

static void vols_free(double **v, int ncomp)
{
    for (int c = 0; c < ncomp; c++)
        free(v[c]);
    free(v);
}

/* max over the six components of max|a - b|, and of max|b| */
static double rel_diff6(double *const a[6], double *const b[6], size_t n)
{
    double md = 0.0, mb = 0.0;
    for (int c = 0; c < MC_NSTRESS; c++)
        for (size_t i = 0; i < n; i++) {
            md = test_worst(md, fabs(a[c][i] - b[c][i]));
            mb = test_worst(mb, fabs(b[c][i]));
        }
    return mb > 0.0 ? md / mb : md;
}

/* Table sizes as the fft engine would choose (a free axis: 2n - 1 rounded up; test both the
 * minimal and a padded length via pad). */
static void table_dims(const mc_grid *g, int pad, int *tx, int *ty)
{
    *tx = g->periodic_x ? g->nx : 2 * g->nx - 1 + pad;
    *ty = g->periodic_y ? g->ny : 2 * g->ny - 1 + pad;
}

/* ---- the plain reference of a table entry ------------------------------------------------------
 * Written from the formula of stress_table.c's header, independently of its lattice and streaming:
 * along an axis, a list of rectangles (centre shift, half-width, weight, image?) whose product over
 * x and y, evaluated with the rectangle functions of kernel.h, is the entry. */

#define STRIP_STEP_DIV 8 /* the strip stencil's step max(1, n/8), as in stress_table.c */
#define MAX_IVALS 64

typedef struct {
    double shift, half, w;
    int image;
} ival;

static int axis_ivals(int n, double d, int periodic, int M, double far, ival *out)
{
    int c = 0;
    if (!periodic) {
        out[c++] = (ival){0.0, 0.5 * d, 1.0, 1};
        return c;
    }
    const double L = n * d, w = 1.0 / n;
    out[c++] = (ival){0.0, far, w, 0};
    if (M < 0)
        return c;
    for (int k = -M; k <= M; k++)
        out[c++] = (ival){k * L, 0.5 * d, 1.0, 1};
    const int s = n / STRIP_STEP_DIV > 1 ? n / STRIP_STEP_DIV : 1;
    const double nn = (double)n * n, r2 = 1.0 / ((double)s * s);
    const double e2 = (1.0 - nn) / 24.0 * r2;
    const double c4 = (1.0 / 120.0 - nn / 36.0 + 7.0 * nn * nn / 360.0) / 16.0;
    const double e4 = c4 * r2 * r2 - e2 / 12.0;
    const double d2[5] = {0, 1, -2, 1, 0}, d4[5] = {1, -4, 6, -4, 1};
    const double H = (M + 0.5) * L;
    for (int j = 0; j < 5; j++)
        out[c++] = (ival){0.0, H + (j - 2) * s * d, -w * ((j == 2) + e2 * d2[j] + e4 * d4[j]), 0};
    return c;
}

/* The six reference tables of load li at depth z, in the wrap layout, with the means of a fully
 * periodic grid set as stress.h states. */
static void ref_tables(const mc_grid *g, int tx, int ty, mc_stress_kernel kernel, int li,
                       double z, int Mx, int My, double *const k[6])
{
    const double far = MC_STRESS_FAR_EDGE * fmax(g->nx * g->dx, g->ny * g->dy);
    ival ix[MAX_IVALS], iy[MAX_IVALS];
    const int nix = axis_ivals(g->nx, g->dx, g->periodic_x, Mx, far, ix);
    const int niy = axis_ivals(g->ny, g->dy, g->periodic_y, My, far, iy);
    for (int jt = 0; jt < ty; jt++) {
        int uy, oy = mc_table_offset(jt, g->ny, ty, &uy);
        for (int it = 0; it < tx; it++) {
            int ux, ox = mc_table_offset(it, g->nx, tx, &ux);
            double acc[MC_NSTRESS] = {0}, s[MC_NSTRESS];
            for (int a = 0; a < nix && ux && uy; a++)
                for (int b = 0; b < niy; b++) {
                    const double x = ox * g->dx - ix[a].shift, y = oy * g->dy - iy[b].shift;
                    if (kernel == MC_STRESS_POINT && ix[a].image && iy[b].image) {
                        point_fns[li](x, y, z, NU, s);
                        for (int c = 0; c < MC_NSTRESS; c++)
                            s[c] *= g->dx * g->dy;
                    } else {
                        rect_fns[li](x, y, z, ix[a].half, iy[b].half, NU, s);
                    }
                    for (int c = 0; c < MC_NSTRESS; c++)
                        acc[c] += ix[a].w * iy[b].w * s[c];
                }
            for (int c = 0; c < MC_NSTRESS; c++)
                k[c][(size_t)jt * tx + it] = acc[c];
        }
    }
    /* with a periodic axis the tables are made exactly even or odd (stress_table.c: the image
     * sum's truncation is not symmetric at the offset n/2): the mirror entries averaged, with the
     * kernel's parities (kernel.h; bit 0 odd in x, bit 1 odd in y; p, q_x, q_y by rows), written
     * here apart from the module's table */
    static const int odd[3][MC_NSTRESS] = {{0, 0, 0, 3, 2, 1}, {1, 1, 1, 2, 3, 0}, {2, 2, 2, 1, 0, 3}};
    for (int c = 0; c < MC_NSTRESS && (g->periodic_x || g->periodic_y); c++) {
        const double sx = (odd[li][c] & 1) ? -1.0 : 1.0, sy = (odd[li][c] & 2) ? -1.0 : 1.0;
        double *m = mc_zeros((size_t)tx * ty);
        ck_assert(m);
        for (int jt = 0; jt < ty; jt++)
            for (int it = 0; it < tx; it++) {
                const int jm = (ty - jt) % ty, im = (tx - it) % tx;
                m[(size_t)jt * tx + it] =
                    0.25 * (k[c][(size_t)jt * tx + it] + sx * k[c][(size_t)jt * tx + im] +
                            sy * k[c][(size_t)jm * tx + it] + sx * sy * k[c][(size_t)jm * tx + im]);
            }
        memcpy(k[c], m, (size_t)tx * ty * sizeof *m);
        mc_free(m);
    }
    if (g->periodic_x && g->periodic_y) {
        const size_t n = (size_t)tx * ty;
        for (int c = 0; c < MC_NSTRESS; c++) {
            double m = 0.0;
            for (size_t i = 0; i < n; i++)
                m += k[c][i];
            const int eq = (li == 0 && c == MC_SZZ) || (li == 1 && c == MC_SXZ) ||
                           (li == 2 && c == MC_SYZ);
            const double shift = (eq ? -1.0 / (double)n : 0.0) - m / (double)n;
            for (size_t i = 0; i < n; i++)
                k[c][i] += shift;
        }
    }
}

/* ---- tables against the plain reference ------------------------------------------------------ */

typedef struct {
    int nx, ny;
    double dx, dy;
    int px, py;
    int pad;
} grid_case;

/* odd and even sizes, nx != ny, dx != dy, every periodicity combination, padded free axes */
static const grid_case table_grids[] = {
    {5, 4, 1.0, 1.3, 0, 0, 0}, {6, 7, 1.3, 1.0, 0, 0, 3}, {5, 4, 1.0, 1.3, 0, 1, 0},
    {7, 9, 0.8, 1.1, 0, 1, 2}, {6, 3, 1.0, 1.3, 1, 0, 1}, {4, 5, 1.0, 0.7, 1, 1, 0},
    {5, 3, 1.2, 1.0, 1, 1, 0}, {7, 1, 1.0, 0.5, 0, 1, 0}, {1, 6, 0.9, 1.0, 1, 0, 0},
    {6, 20, 1.0, 1.1, 0, 1, 0},
};
#define N_TABLE_GRIDS ((int)(sizeof table_grids / sizeof table_grids[0]))
static const double table_depths[] = {0.0, 0.3, 2.5, 12.0}; /* in units of dx */
#define N_TABLE_DEPTHS 4

static mc_grid grid_of(const grid_case *c)
{
    mc_grid g = {c->nx, c->ny, c->dx, c->dy, c->px, c->py};
    return g;
}

static void check_tables(const grid_case *gc, mc_stress_kernel kernel)
{
    const mc_grid g = grid_of(gc);
    int tx, ty;
    table_dims(&g, gc->pad, &tx, &ty);
    mc_error err;
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, kernel, NU, 0, &tb, &err), MC_OK);
    const size_t n = (size_t)tx * ty;
    double **k = vols(6, n), **r = vols(6, n);
    for (int iz = 0; iz < N_TABLE_DEPTHS; iz++) {
        const double z = table_depths[iz] * g.dx;
        if (kernel == MC_STRESS_POINT && z == 0.0)
            continue;
        for (int li = 0; li < 3; li++) {
            ck_assert_int_eq(mc_stress_tables_build(tb, load_bits[li], z, k, &err), MC_OK);
            ref_tables(&g, tx, ty, kernel, li, z, mc_stress_tables_images(tb, 0, z),
                       mc_stress_tables_images(tb, 1, z), r);
            const double e = rel_diff6(k, r, n);
            const double zc = z / fmin(g.dx, g.dy) / TABLE_Z0, tol = TOL_TABLE * fmax(1.0, zc * zc);
            ck_assert_msg(e <= tol,
                          "grid %dx%d periodic %d%d kernel %d load %d z=%g: tables vs plain "
                          "evaluation %.3g > %.3g",
                          g.nx, g.ny, g.periodic_x, g.periodic_y, (int)kernel, li, z, e, tol);
        }
    }
    vols_free(k, 6);
    vols_free(r, 6);
    mc_stress_tables_destroy(&tb);
    ck_assert_ptr_null(tb);
}

START_TEST(test_tables_patch) { check_tables(&table_grids[_i], MC_STRESS_PATCH); }
END_TEST

START_TEST(test_tables_point) { check_tables(&table_grids[_i], MC_STRESS_POINT); }
END_TEST

/* The free-axis patch table is the rectangle function itself at every offset, and zero in the
 * padding; odd kernels keep their sign at field minus source (theory.md §3.1). */
START_TEST(test_table_free_is_rectangle)
{
    const mc_grid g = {6, 5, 1.0, 1.4, 0, 0};
    const int tx = 14, ty = 12; /* padded beyond 2n - 1 */
    mc_error err;
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, MC_STRESS_PATCH, NU, 0, &tb, &err),
                     MC_OK);
    double **k = vols(6, (size_t)tx * ty);
    const double z = 0.7;
    for (int li = 0; li < 3; li++) {
        ck_assert_int_eq(mc_stress_tables_build(tb, load_bits[li], z, k, &err), MC_OK);
        double md = 0.0, mb = 0.0;
        for (int jt = 0; jt < ty; jt++)
            for (int it = 0; it < tx; it++) {
                int ux, uy, ox = mc_table_offset(it, g.nx, tx, &ux),
                            oy = mc_table_offset(jt, g.ny, ty, &uy);
                double s[MC_NSTRESS] = {0};
                if (ux && uy)
                    rect_fns[li](ox * g.dx, oy * g.dy, z, 0.5 * g.dx, 0.5 * g.dy, NU, s);
                for (int c = 0; c < MC_NSTRESS; c++) {
                    const double v = k[c][(size_t)jt * tx + it];
                    if (!(ux && uy))
                        ck_assert_msg(v == 0.0, "padding slot (%d,%d) holds %g", it, jt, v);
                    md = test_worst(md, fabs(v - s[c]));
                    mb = test_worst(mb, fabs(s[c]));
                }
            }
        ck_assert_msg(md <= TOL_TABLE * mb, "load %d: %.3g", li, md / mb);
    }
    vols_free(k, 6);
    mc_stress_tables_destroy(&tb);
}
END_TEST

/* ---- the periodic tail ---------------------------------------------------------------------- */

typedef struct {
    int nx, ny, px, py;
    double zl; /* depth in periods of the periodic axis (the shorter one) */
} tail_case;

static const tail_case tail_cases[] = {
    {6, 5, 0, 1, 0.0}, {6, 5, 0, 1, 0.15}, {6, 5, 0, 1, 1.0}, {6, 5, 0, 1, 3.0},
    {6, 2, 0, 1, 0.3}, {6, 3, 0, 1, 2.0},  {9, 4, 1, 0, 0.5}, {4, 3, 1, 1, 0.0},
    {4, 3, 1, 1, 0.6}, {5, 4, 1, 1, 2.5},
};
#define N_TAIL ((int)(sizeof tail_cases / sizeof tail_cases[0]))

/* The automatic images M against 2M: the table change is the truncation error of the strips. */
START_TEST(test_tail_convergence)
{
    const tail_case *tc = &tail_cases[_i];
    const mc_grid g = {tc->nx, tc->ny, 1.0, 1.3, tc->px, tc->py};
    const double L = fmin(tc->px ? g.nx * g.dx : INFINITY, tc->py ? g.ny * g.dy : INFINITY);
    const double z = tc->zl * L;
    int tx, ty;
    table_dims(&g, 0, &tx, &ty);
    mc_error err;
    mc_stress_tables *a = NULL, *b = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, MC_STRESS_PATCH, NU, 0, &a, &err), MC_OK);
    const int m = (int)fmax(mc_stress_tables_images(a, 0, z), mc_stress_tables_images(a, 1, z));
    ck_assert_int_ge(m, 2);
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, MC_STRESS_PATCH, NU, 2 * m, &b, &err),
                     MC_OK);
    const size_t n = (size_t)tx * ty;
    double **ka = vols(6, n), **kb = vols(6, n);
    for (int li = 0; li < 3; li++) {
        ck_assert_int_eq(mc_stress_tables_build(a, load_bits[li], z, ka, &err), MC_OK);
        ck_assert_int_eq(mc_stress_tables_build(b, load_bits[li], z, kb, &err), MC_OK);
        const double e = rel_diff6(ka, kb, n);
        ck_assert_msg(e <= TOL_TAIL, "grid %dx%d periodic %d%d z/L=%g load %d: M=%d vs %d: %.3g",
                      g.nx, g.ny, g.periodic_x, g.periodic_y, tc->zl, li, m, 2 * m, e);
    }
    vols_free(ka, 6);
    vols_free(kb, 6);
    mc_stress_tables_destroy(&a);
    mc_stress_tables_destroy(&b);
}
END_TEST

/* The images rule: free axes 0; a single-cell period and depths >= MC_STRESS_SMEAR_DEPTH periods
 * smear the whole sum; M grows with depth. */
START_TEST(test_images_rule)
{
    const mc_grid g = {8, 1, 1.0, 1.0, 1, 1};
    mc_error err;
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, 8, 1, MC_STRESS_PATCH, NU, 0, &tb, &err), MC_OK);
    ck_assert_int_eq(mc_stress_tables_images(tb, 1, 0.0), -1);
    ck_assert_int_ge(mc_stress_tables_images(tb, 0, 0.0), 2);
    ck_assert_int_gt(mc_stress_tables_images(tb, 0, 8.0), mc_stress_tables_images(tb, 0, 0.0));
    ck_assert_int_eq(mc_stress_tables_images(tb, 0, MC_STRESS_SMEAR_DEPTH * 8.0), -1);
    mc_stress_tables_destroy(&tb);
    const mc_grid f = {8, 3, 1.0, 1.0, 0, 0};
    ck_assert_int_eq(mc_stress_tables_create(&f, 15, 5, MC_STRESS_PATCH, NU, 0, &tb, &err), MC_OK);
    ck_assert_int_eq(mc_stress_tables_images(tb, 0, 1.0), 0);
    ck_assert_int_eq(mc_stress_tables_images(tb, 1, 1.0), 0);
    mc_stress_tables_destroy(&tb);
}
END_TEST

/* ny = 1, periodic in y: the images tile the y axis, so the table is the plane-strain strip of
 * width dx (mc_flamant_strip_uniform, with sigma_yy = nu (sigma_xx + sigma_zz), no xy, yz). */
START_TEST(test_strip_exact)
{
    const mc_grid g = {9, 1, 1.0, 0.4, 0, 1};
    const int tx = 17, ty = 1;
    mc_error err;
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, MC_STRESS_PATCH, NU, 0, &tb, &err), MC_OK);
    double **k = vols(6, (size_t)tx);
    const double zs[] = {0.0, 0.05, 0.5, 3.0, 40.0};
    for (int iz = 0; iz < 5; iz++) {
        ck_assert_int_eq(mc_stress_tables_build(tb, MC_TRACTION_P, zs[iz], k, &err), MC_OK);
        double md = 0.0, mb = 0.0;
        for (int it = 0; it < tx; it++) {
            int used, ox = mc_table_offset(it, g.nx, tx, &used);
            double s[MC_NSTRESS];
            mc_flamant_strip_uniform(ox * g.dx, zs[iz], 0.5 * g.dx, NU, s);
            for (int c = 0; c < MC_NSTRESS; c++) {
                md = test_worst(md, fabs(k[c][it] - s[c]));
                mb = test_worst(mb, fabs(s[c]));
            }
        }
        ck_assert_msg(md <= TOL_STRIP * mb, "z=%g: strip error %.3g", zs[iz], md / mb);
    }
    vols_free(k, 6);
    mc_stress_tables_destroy(&tb);
}
END_TEST

/* Fully periodic: the mean of each table is its equilibrium value (zz, xz, yz) or 0 (in-plane). */
START_TEST(test_periodic_means)
{
    const mc_grid g = {6, 5, 1.0, 1.2, 1, 1};
    mc_error err;
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, 6, 5, MC_STRESS_PATCH, NU, 0, &tb, &err), MC_OK);
    double **k = vols(6, 30);
    for (int li = 0; li < 3; li++) {
        ck_assert_int_eq(mc_stress_tables_build(tb, load_bits[li], 1.7, k, &err), MC_OK);
        for (int c = 0; c < MC_NSTRESS; c++) {
            double m = 0.0;
            for (int i = 0; i < 30; i++)
                m += k[c][i];
            const int eq = (li == 0 && c == MC_SZZ) || (li == 1 && c == MC_SXZ) ||
                           (li == 2 && c == MC_SYZ);
            ck_assert_msg(fabs(m - (eq ? -1.0 : 0.0)) <= TOL_ROUNDOFF, "load %d %s: sum %.17g",
                          li, mc_component_name(c), m);
        }
    }
    vols_free(k, 6);
    mc_stress_tables_destroy(&tb);
}
END_TEST

/* Tables do not depend on the thread count: each table row sums its contributions in one order. */
START_TEST(test_tables_threads)
{
    const mc_grid g = {9, 7, 1.0, 1.3, 1, 1};
    mc_error err;
    double **k[2];
    for (int t = 0; t < 2; t++) {
        mc_threads_scope scope;
        mc_threads_begin(t == 0 ? 1 : 3, &scope);
        mc_stress_tables *tb = NULL;
        ck_assert_int_eq(mc_stress_tables_create(&g, 9, 7, MC_STRESS_PATCH, NU, 0, &tb, &err),
                         MC_OK);
        k[t] = vols(6, 63);
        ck_assert_int_eq(mc_stress_tables_build(tb, MC_TRACTION_QX, 0.4, k[t], &err), MC_OK);
        mc_stress_tables_destroy(&tb);
        mc_threads_end(&scope);
    }
    for (int c = 0; c < MC_NSTRESS; c++)
        ck_assert(memcmp(k[0][c], k[1][c], 63 * sizeof(double)) == 0);
    vols_free(k[0], 6);
    vols_free(k[1], 6);
}
END_TEST

/* ---- the operator --------------------------------------------------------------------------- */

/* Stresses of loads p, qx, qy (NULL allowed) on grid g at the depths, backend b. */
static double **stress_run(const mc_grid *g, mc_stress_kernel kernel, const double *depths, int nz,
                           mc_backend b, const double *p, const double *qx, const double *qy)
{
    const mc_stress_options opt = {kernel, NU, nz, depths, b,
                                   (p ? MC_TRACTION_P : 0) | (qx ? MC_TRACTION_QX : 0) |
                                       (qy ? MC_TRACTION_QY : 0), 0};
    mc_error err;
    mc_stress_plan *plan = NULL;
    int rc = mc_stress_create(g, &opt, &plan, &err);
    ck_assert_msg(rc == MC_OK, "create: %s", err.msg);
    double **s = vols(6, mc_grid_cells(g) * (size_t)nz);
    rc = mc_stress_field(plan, p, qx, qy, s, &err);
    ck_assert_msg(rc == MC_OK, "field: %s", err.msg);
    mc_stress_destroy(&plan);
    ck_assert_ptr_null(plan);
    return s;
}

static double *random_load(const mc_grid *g, unsigned long long seed)
{
    double *f = malloc(sizeof *f * mc_grid_cells(g));
    ck_assert(f != NULL);
    test_random_field(f, mc_grid_cells(g), seed);
    return f;
}

static const grid_case backend_grids[] = {
    {7, 6, 1.0, 1.3, 0, 0, 0}, {8, 5, 1.2, 0.9, 0, 1, 0}, {6, 9, 1.0, 1.1, 1, 0, 0},
    {9, 8, 0.8, 1.0, 1, 1, 0}, {11, 1, 1.0, 0.3, 0, 1, 0},
};
#define N_BACKEND_GRIDS ((int)(sizeof backend_grids / sizeof backend_grids[0]))

/* direct vs fft on random p, qx, qy; patch (z = 0 included) and point kernels */
START_TEST(test_direct_vs_fft)
{
    const grid_case *gc = &backend_grids[_i / 2];
    const mc_stress_kernel kernel = _i % 2 ? MC_STRESS_POINT : MC_STRESS_PATCH;
    const mc_grid g = grid_of(gc);
    const double patch_z[] = {0.0, 0.4, 3.0}, point_z[] = {0.2, 0.4, 3.0};
    const double *z = kernel == MC_STRESS_PATCH ? patch_z : point_z;
    double *p = random_load(&g, 11), *qx = random_load(&g, 12), *qy = random_load(&g, 13);
    double **a = stress_run(&g, kernel, z, 3, MC_BACKEND_DIRECT, p, qx, qy);
    double **b = stress_run(&g, kernel, z, 3, MC_BACKEND_FFT, p, qx, qy);
    const double e = rel_diff6(b, a, mc_grid_cells(&g) * 3);
    ck_assert_msg(e <= TOL_BACKEND, "grid %dx%d periodic %d%d kernel %d: fft vs direct %.3g", g.nx,
                  g.ny, g.periodic_x, g.periodic_y, (int)kernel, e);
    vols_free(a, 6);
    vols_free(b, 6);
    free(p);
    free(qx);
    free(qy);
}
END_TEST

/* Patch kernel at z = 0: the traction of every cell is its own load (theory.md §1, §5.5):
 * sigma_zz = -p, sigma_xz = -q_x, sigma_yz = -q_y, for random loads. */
START_TEST(test_surface_traction)
{
    const grid_case *gc = &backend_grids[_i];
    const mc_grid g = grid_of(gc);
    const size_t n = mc_grid_cells(&g);
    double *p = random_load(&g, 21), *qx = random_load(&g, 22), *qy = random_load(&g, 23);
    const double z0 = 0.0;
    double **s = stress_run(&g, MC_STRESS_PATCH, &z0, 1, MC_BACKEND_FFT, p, qx, qy);
    for (size_t i = 0; i < n; i++) {
        ck_assert_msg(fabs(s[MC_SZZ][i] + p[i]) <= TOL_BACKEND, "cell %zu: szz %g, p %g", i,
                      s[MC_SZZ][i], p[i]);
        ck_assert_msg(fabs(s[MC_SXZ][i] + qx[i]) <= TOL_BACKEND, "cell %zu: sxz %g, qx %g", i,
                      s[MC_SXZ][i], qx[i]);
        ck_assert_msg(fabs(s[MC_SYZ][i] + qy[i]) <= TOL_BACKEND, "cell %zu: syz %g, qy %g", i,
                      s[MC_SYZ][i], qy[i]);
    }
    vols_free(s, 6);
    free(p);
    free(qx);
    free(qy);
}
END_TEST

/* A unit load on one cell returns the rectangle functions at the offsets field minus source: the
 * orientation of the odd kernels (theory.md §3.1). */
START_TEST(test_impulse_response)
{
    const int li = _i;
    const mc_grid g = {9, 7, 1.0, 1.3, 0, 0};
    const size_t n = mc_grid_cells(&g);
    const int i0 = 2, j0 = 5; /* off-centre, so that both signs of the offsets occur */
    double *f = calloc(n, sizeof *f);
    ck_assert(f != NULL);
    f[(size_t)j0 * g.nx + i0] = 1.0;
    const double z = 0.6;
    double **s = stress_run(&g, MC_STRESS_PATCH, &z, 1, MC_BACKEND_FFT, li == 0 ? f : NULL,
                            li == 1 ? f : NULL, li == 2 ? f : NULL);
    double md = 0.0, mb = 0.0;
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            double r[MC_NSTRESS];
            rect_fns[li]((i - i0) * g.dx, (j - j0) * g.dy, z, 0.5 * g.dx, 0.5 * g.dy, NU, r);
            for (int c = 0; c < MC_NSTRESS; c++) {
                md = test_worst(md, fabs(s[c][(size_t)j * g.nx + i] - r[c]));
                mb = test_worst(mb, fabs(r[c]));
            }
        }
    ck_assert_msg(md <= TOL_BACKEND * mb, "load %d: impulse response vs rectangle %.3g", li,
                  md / mb);
    vols_free(s, 6);
    free(f);
}
END_TEST

/* sigma(alpha p + beta qx + gamma qy) = alpha sigma(p) + beta sigma(qx) + gamma sigma(qy) */
START_TEST(test_linearity)
{
    const mc_grid g = {8, 7, 1.0, 1.2, 1, 0};
    const size_t n = mc_grid_cells(&g);
    const double z[] = {0.0, 1.1};
    const double al = 0.7, be = -1.9, ga = 2.3;
    double *p = random_load(&g, 31), *qx = random_load(&g, 32), *qy = random_load(&g, 33);
    double **all = stress_run(&g, MC_STRESS_PATCH, z, 2, MC_BACKEND_FFT, p, qx, qy);
    double **sp = stress_run(&g, MC_STRESS_PATCH, z, 2, MC_BACKEND_FFT, p, NULL, NULL);
    double **sx = stress_run(&g, MC_STRESS_PATCH, z, 2, MC_BACKEND_FFT, NULL, qx, NULL);
    double **sy = stress_run(&g, MC_STRESS_PATCH, z, 2, MC_BACKEND_FFT, NULL, NULL, qy);
    double **scaled = vols(6, 2 * n), **sum = vols(6, 2 * n);
    for (size_t i = 0; i < n; i++) {
        p[i] *= al;
        qx[i] *= be;
        qy[i] *= ga;
    }
    double **ss = stress_run(&g, MC_STRESS_PATCH, z, 2, MC_BACKEND_FFT, p, qx, qy);
    for (int c = 0; c < MC_NSTRESS; c++)
        for (size_t i = 0; i < 2 * n; i++) {
            sum[c][i] = sp[c][i] + sx[c][i] + sy[c][i];
            scaled[c][i] = al * sp[c][i] + be * sx[c][i] + ga * sy[c][i];
        }
    ck_assert_double_le(rel_diff6(all, sum, 2 * n), TOL_BACKEND);
    ck_assert_double_le(rel_diff6(ss, scaled, 2 * n), TOL_BACKEND);
    double **v[] = {all, sp, sx, sy, ss, scaled, sum};
    for (int k = 0; k < 7; k++)
        vols_free(v[k], 6);
    free(p);
    free(qx);
    free(qy);
}
END_TEST

/* mc_stress_layer equals the matching layer of mc_stress_field. */
START_TEST(test_layer_matches_field)
{
    const mc_grid g = {7, 6, 1.0, 1.3, 0, 1};
    const size_t n = mc_grid_cells(&g);
    const double z[] = {0.0, 0.5, 2.0};
    double *p = random_load(&g, 41), *qx = random_load(&g, 42);
    double **all = stress_run(&g, MC_STRESS_PATCH, z, 3, MC_BACKEND_FFT, p, qx, NULL);
    const mc_stress_options opt = {MC_STRESS_PATCH, NU, 3, z, MC_BACKEND_FFT,
                                   MC_TRACTION_P | MC_TRACTION_QX | MC_TRACTION_QY, 0};
    mc_error err;
    mc_stress_plan *plan = NULL;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_OK);
    double **one = vols(6, n);
    for (int k = 0; k < 3; k++) {
        ck_assert_int_eq(mc_stress_layer(plan, k, p, qx, NULL, one, &err), MC_OK);
        for (int c = 0; c < MC_NSTRESS; c++)
            ck_assert(memcmp(one[c], all[c] + (size_t)k * n, n * sizeof(double)) == 0);
    }
    mc_stress_timing t;
    mc_stress_timing_get(plan, &t);
    ck_assert_int_eq(t.layers, 3);
    ck_assert(t.tables > 0.0 && t.apply > 0.0);
    mc_stress_destroy(&plan);
    vols_free(all, 6);
    vols_free(one, 6);
    free(p);
    free(qx);
}
END_TEST

/* A uniform pressure on the whole (free) grid is one rectangle: sigma under its centre equals the
 * closed form, and sigma_zz -> -p just below the surface. */
START_TEST(test_uniform_patch)
{
    const mc_grid g = {41, 31, 1.0, 1.4, 0, 0};
    const size_t n = mc_grid_cells(&g);
    double *p = malloc(sizeof *p * n);
    ck_assert(p != NULL);
    for (size_t i = 0; i < n; i++)
        p[i] = 1.0;
    const double A = 0.5 * g.nx * g.dx, B = 0.5 * g.ny * g.dy;
    const double z[] = {0.0, 1.0, UNIFORM_Z_OVER_A * A, 0.5 * A};
    double **s = stress_run(&g, MC_STRESS_PATCH, z, 4, MC_BACKEND_FFT, p, NULL, NULL);
    const size_t ic = (size_t)(g.ny / 2) * g.nx + (size_t)(g.nx / 2); /* the centre cell */
    for (int k = 0; k < 4; k++) {
        double r[MC_NSTRESS];
        mc_rect_stress_p(0.0, 0.0, z[k], A, B, NU, r);
        for (int c = 0; c < MC_NSTRESS; c++)
            ck_assert_msg(fabs(s[c][(size_t)k * n + ic] - r[c]) <= TOL_BACKEND,
                          "z=%g %s: %.17g vs %.17g", z[k], mc_component_name(c),
                          s[c][(size_t)k * n + ic], r[c]);
    }
    /* just below: the rectangle's sigma_zz differs from -p by ~(z/A)^3 */
    const double szz = s[MC_SZZ][2 * n + ic];
    ck_assert_double_le(fabs(szz + 1.0), pow(UNIFORM_Z_OVER_A, 3.0));
    ck_assert_double_eq_tol(s[MC_SZZ][ic], -1.0, TOL_BACKEND);
    vols_free(s, 6);
    free(p);
}
END_TEST

/* ---- Hertz point contact (theory.md §6.1, §6.2, §5.7) ------------------------------------------- */

/* Grid of cells dx = a/r around the contact (a = 1), |x|, |y| <= ~1.5 a; odd n puts a cell
 * centre on the axis, even n puts a corner there (the dossier's grids). */
static mc_grid hertz_grid(int r, int odd)
{
    const int n = 2 * (int)ceil(1.5 * r) + (odd ? 1 : 0);
    mc_grid g = {n, n, 1.0 / r, 1.0 / r, 0, 0};
    return g;
}

static double *hertz_pressure(const mc_grid *g)
{
    double *p = malloc(sizeof *p * mc_grid_cells(g));
    ck_assert(p != NULL);
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            const double x = mc_grid_x(g, i), y = mc_grid_y(g, j), r2 = x * x + y * y;
            p[(size_t)j * g->nx + i] = r2 < 1.0 ? sqrt(1.0 - r2) : 0.0;
        }
    return p;
}

/* axis stresses against mc_hertz_point_axis, odd grids a/dx = 20, 40 */
START_TEST(test_hertz_point_axis)
{
    const double z[] = {0.2, 0.48, 1.0};
    double err[2][3][3]; /* [grid][depth][xx, yy, zz] */
    for (int gi = 0; gi < 2; gi++) {
        const int r = 20 << gi;
        const mc_grid g = hertz_grid(r, 1);
        const size_t n = mc_grid_cells(&g), ic = (size_t)(g.ny / 2) * g.nx + (size_t)(g.nx / 2);
        ck_assert_double_eq(mc_grid_x(&g, g.nx / 2), 0.0);
        double *p = hertz_pressure(&g);
        double **s = stress_run(&g, MC_STRESS_PATCH, z, 3, MC_BACKEND_FFT, p, NULL, NULL);
        const double tol = HERTZ_AXIS_C / ((double)r * r);
        for (int k = 0; k < 3; k++) {
            double sr, sz;
            mc_hertz_point_axis(z[k], NU, &sr, &sz);
            const double ref[3] = {sr, sr, sz};
            for (int c = 0; c < 3; c++) {
                err[gi][k][c] = fabs(s[c][(size_t)k * n + ic] - ref[c]);
                ck_assert_msg(err[gi][k][c] <= tol, "a/dx=%d z=%g %s: error %.3g p0 > %.3g", r,
                              z[k], mc_component_name(c), err[gi][k][c], tol);
            }
        }
        vols_free(s, 6);
        free(p);
    }
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < 3; c++)
            ck_assert_msg(err[0][k][c] >= RATIO_DX2 * err[1][k][c],
                          "z=%g %s: error %.3g -> %.3g does not fall as dx^2", z[k],
                          mc_component_name(c), err[0][k][c], err[1][k][c]);
}
END_TEST

/* von Mises over the plane z = 0.48 a with sliding friction mu = 0.3 (and without) against
 * Hamilton (mc_hertz_point_sliding), even grids a/dx = 10, 20, 40 as theory.md §5.7. */
static double hertz_vm_error(int r, double mu)
{
    const mc_grid g = hertz_grid(r, 0);
    const size_t n = mc_grid_cells(&g);
    const double z = 0.48;
    double *p = hertz_pressure(&g), *q = malloc(sizeof *q * n);
    ck_assert(q != NULL);
    for (size_t i = 0; i < n; i++)
        q[i] = mu * p[i];
    double **s = stress_run(&g, MC_STRESS_PATCH, &z, 1, MC_BACKEND_FFT, p, mu > 0 ? q : NULL, NULL);
    double e = 0.0;
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            double ref[MC_NSTRESS], t[MC_NSTRESS];
            mc_hertz_point_sliding(mc_grid_x(&g, i), mc_grid_y(&g, j), z, NU, mu, ref);
            for (int c = 0; c < MC_NSTRESS; c++)
                t[c] = s[c][(size_t)j * g.nx + i];
            e = test_worst(e, fabs(mc_von_mises(t) - mc_von_mises(ref)));
        }
    vols_free(s, 6);
    free(p);
    free(q);
    return e;
}

START_TEST(test_hertz_point_vm)
{
    const double dossier[3] = {1.6e-3, 3.7e-4, 1.1e-4}; /* theory.md §5.7, mu = 0.3, z = 0.48 a */
    double e[3], e0[3];
    for (int gi = 0; gi < 3; gi++) {
        e[gi] = hertz_vm_error(10 << gi, 0.3);
        e0[gi] = hertz_vm_error(10 << gi, 0.0);
        ck_assert_msg(e[gi] <= HERTZ_VM_MARGIN * dossier[gi], "a/dx=%d: vM error %.3g p0", 10 << gi,
                      e[gi]);
        ck_assert_msg(e0[gi] <= HERTZ_VM_MARGIN * dossier[gi], "a/dx=%d, mu=0: vM error %.3g p0",
                      10 << gi, e0[gi]);
    }
    for (int gi = 0; gi < 2; gi++) {
        ck_assert_msg(e[gi] >= RATIO_DX2 * e[gi + 1], "vM error %.3g -> %.3g", e[gi], e[gi + 1]);
        ck_assert_msg(e0[gi] >= RATIO_DX2 * e0[gi + 1], "vM error %.3g -> %.3g", e0[gi],
                      e0[gi + 1]);
    }
}
END_TEST

/* ---- Hertz line contact: ny = 1, periodic in y (theory.md §6.3) ----------------------------- */

/* cell average of sqrt(1 - x^2) over [x - h, x + h] */
static double sqrt_avg(double x, double h)
{
    const double lo = fmax(x - h, -1.0), hi = fmin(x + h, 1.0);
    if (hi <= lo)
        return 0.0;
    const double F1 = 0.5 * (hi * sqrt(1.0 - hi * hi) + asin(hi));
    const double F0 = 0.5 * (lo * sqrt(1.0 - lo * lo) + asin(lo));
    return (F1 - F0) / (2.0 * h);
}

/* max error on the axis (sigma_xx, yy, zz vs McEwen) at three depths, b = 1, dx = b/r */
static double hertz_line_error(int r, int averaged)
{
    const mc_grid g = {2 * (int)ceil(1.5 * r) + 1, 1, 1.0 / r, 0.37 / r, 0, 1};
    double *p = malloc(sizeof *p * (size_t)g.nx);
    ck_assert(p != NULL);
    for (int i = 0; i < g.nx; i++) {
        const double x = mc_grid_x(&g, i);
        p[i] = averaged ? sqrt_avg(x, 0.5 * g.dx) : (fabs(x) < 1.0 ? sqrt(1.0 - x * x) : 0.0);
    }
    const double z[] = {0.3, 0.786, 1.5};
    double **s = stress_run(&g, MC_STRESS_PATCH, z, 3, MC_BACKEND_FFT, p, NULL, NULL);
    const int ic = g.nx / 2;
    double e = 0.0;
    for (int k = 0; k < 3; k++) {
        double ref[MC_NSTRESS];
        mc_mcewen_normal(0.0, z[k], NU, ref);
        for (int c = 0; c < 3; c++)
            e = test_worst(e, fabs(s[c][(size_t)k * g.nx + ic] - ref[c]));
    }
    vols_free(s, 6);
    free(p);
    return e;
}

START_TEST(test_hertz_line)
{
    double ea[2], es[2];
    for (int gi = 0; gi < 2; gi++) {
        const int r = 20 << gi;
        ea[gi] = hertz_line_error(r, 1);
        es[gi] = hertz_line_error(r, 0);
        ck_assert_msg(ea[gi] <= HERTZ_LINE_C / ((double)r * r), "b/dx=%d: axis error %.3g p0", r,
                      ea[gi]);
    }
    ck_assert_msg(ea[0] >= RATIO_DX2 * ea[1], "cell averages: %.3g -> %.3g", ea[0], ea[1]);
    ck_assert_msg(es[0] >= RATIO_DX15 * es[1], "centre samples: %.3g -> %.3g", es[0], es[1]);
}
END_TEST

/* ---- point kernel --------------------------------------------------------------------------- */

/* Point and patch tables differ by the pixel's second moments: O((d/z)^2) relative. */
START_TEST(test_point_approaches_patch)
{
    const mc_grid g = {12, 10, 1.0, 1.2, 0, 0};
    int tx, ty;
    table_dims(&g, 0, &tx, &ty);
    mc_error err;
    mc_stress_tables *pa = NULL, *pt = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, MC_STRESS_PATCH, NU, 0, &pa, &err), MC_OK);
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, MC_STRESS_POINT, NU, 0, &pt, &err), MC_OK);
    const size_t n = (size_t)tx * ty;
    double **ka = vols(6, n), **kt = vols(6, n);
    for (int li = 0; li < 3; li++) {
        double prev = 0.0;
        for (int iz = 0; iz < 3; iz++) {
            const double z = 2.0 * (1 << iz) * g.dy; /* 2, 4, 8 cells */
            ck_assert_int_eq(mc_stress_tables_build(pa, load_bits[li], z, ka, &err), MC_OK);
            ck_assert_int_eq(mc_stress_tables_build(pt, load_bits[li], z, kt, &err), MC_OK);
            const double e = rel_diff6(kt, ka, n);
            const double bound = POINT_PATCH_C * pow(fmax(g.dx, g.dy) / z, 2.0);
            ck_assert_msg(e <= bound, "load %d z=%g: point vs patch %.3g > %.3g", li, z, e, bound);
            if (iz > 0)
                ck_assert_msg(prev >= RATIO_DX2 * e, "load %d: %.3g -> %.3g", li, prev, e);
            prev = e;
        }
    }
    vols_free(ka, 6);
    vols_free(kt, 6);
    mc_stress_tables_destroy(&pa);
    mc_stress_tables_destroy(&pt);
}
END_TEST

/* ---- errors and failure paths --------------------------------------------------------------- */

START_TEST(test_bad_input)
{
    const mc_grid g = {6, 5, 1.0, 1.0, 0, 0};
    const double z[] = {0.0, 1.0}, zneg = -1.0;
    mc_error err;
    mc_stress_plan *plan = NULL;
    mc_stress_options opt = {MC_STRESS_POINT, NU, 2, z, MC_BACKEND_FFT, MC_TRACTION_P, 0};
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_ERR_INPUT); /* point at z = 0 */
    ck_assert_ptr_null(plan);
    opt.kernel = MC_STRESS_PATCH;
    opt.loads = 0;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_ERR_INPUT);
    opt.loads = MC_TRACTION_P;
    opt.nu = 0.7;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_ERR_INPUT);
    opt.nu = NU;
    opt.depths = &zneg;
    opt.nlayers = 1;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_ERR_INPUT);
    opt.depths = z;
    opt.nlayers = 0;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_ERR_INPUT);
    opt.nlayers = 2;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_OK);
    double *f = calloc(30, sizeof *f);
    double **s = vols(6, 60);
    ck_assert_int_eq(mc_stress_field(plan, f, f, NULL, s, &err), MC_ERR_INPUT); /* qx unannounced */
    ck_assert_int_eq(mc_stress_layer(plan, 2, f, NULL, NULL, s, &err), MC_ERR_INPUT);
    s[0][0] = 1.0;
    ck_assert_int_eq(mc_stress_field(plan, NULL, NULL, NULL, s, &err), MC_OK); /* no load: zero */
    ck_assert_double_eq(s[0][0], 0.0);
    mc_stress_destroy(&plan);
    mc_stress_destroy(&plan); /* NULL-safe */
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, 10, 9, MC_STRESS_PATCH, NU, 0, &tb, &err),
                     MC_ERR_INPUT); /* 10 < 2 nx - 1 */
    ck_assert_int_eq(mc_stress_tables_create(&g, 11, 9, MC_STRESS_PATCH, NU, 0, &tb, &err), MC_OK);
    ck_assert_int_eq(mc_stress_tables_build(tb, MC_TRACTION_P | MC_TRACTION_QX, 1.0, s, &err),
                     MC_ERR_INPUT);
    ck_assert_int_eq(mc_stress_tables_build(tb, MC_TRACTION_P, NAN, s, &err), MC_ERR_INPUT);
    mc_stress_tables_destroy(&tb);
    vols_free(s, 6);
    free(f);
}
END_TEST

/* Every allocation of create may fail: MC_ERR_NOMEM, nothing leaks (ASan), *out stays NULL. */
START_TEST(test_create_nomem)
{
    /* a periodic axis: the engine of operator.h; free axes: the symmetric engine */
    const mc_grid g = {6, 5, 1.0, 1.0, _i == 0, 0};
    const double z[] = {0.0, 1.0};
    const mc_stress_options opt = {MC_STRESS_PATCH, NU, 2, z, MC_BACKEND_FFT,
                                   MC_TRACTION_P | MC_TRACTION_QY, 0};
    mc_error err;
    int failures = 0;
    for (long k = 1;; k++) {
        mc_stress_plan *plan = NULL;
        const long before = mc_alloc_injected();
        mc_alloc_fail_at(k);
        const int rc = mc_stress_create(&g, &opt, &plan, &err);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == before) { /* k is past the last allocation */
            ck_assert_int_eq(rc, MC_OK);
            mc_stress_destroy(&plan);
            break;
        }
        ck_assert_int_eq(rc, MC_ERR_NOMEM);
        ck_assert_ptr_null(plan);
        failures++;
    }
    ck_assert_int_ge(failures, 5);
}
END_TEST

/* The friction traction of solid contact (stress/traction.h, theory.md §19.7): the excess over
 * the cell's own lubricant pressure. A shape of ones is the uniform p_lub to the bit; where the
 * whole contact's profile is 0 (outside the band) every cell with p > 0 carries f p, and inside
 * the band the excess over p_lub w. Exact arithmetic on these values: tolerance 0. */
START_TEST(test_traction_shape)
{
    const double p[5] = {0.0, 50.0, 150.0, 250.0, 400.0};
    const double ones[5] = {1, 1, 1, 1, 1}, band[5] = {0, 0, 2.0, 2.0, 1.0};
    const double f = -0.25, p_lub = 100.0;
    double q0[5], q1[5], q2[5];
    mc_traction_friction(p, p_lub, NULL, f, 5, q0);
    mc_traction_friction(p, p_lub, ones, f, 5, q1);
    mc_traction_friction(p, p_lub, band, f, 5, q2);
    const double want0[5] = {0, 0, f * 50.0, f * 150.0, f * 300.0};
    const double want2[5] = {0, f * 50.0, 0, f * 50.0, f * 300.0};
    for (int i = 0; i < 5; i++) {
        ck_assert_double_eq(q0[i], want0[i]);
        ck_assert_double_eq(q1[i], q0[i]);
        ck_assert_double_eq(q2[i], want2[i]);
    }
}
END_TEST

/* ---- the pipeline stage ------------------------------------------------------------------- */

static void stage_scene(mc_scene *sc, int r, double mu)
{
    mc_scene_defaults(sc);
    sc->grid = hertz_grid(r, 0);
    sc->stress.enabled = 1;
    sc->stress.spacing = MC_SPACING_LIST;
    sc->stress.ndepths = 3;
    sc->stress.depths[0] = 0.0;
    sc->stress.depths[1] = 0.48;
    sc->stress.depths[2] = 1.0;
    sc->stress.friction = mu;
}

static double max_of(const double *v, size_t n)
{
    double m = v[0];
    for (size_t i = 1; i < n; i++)
        m = test_worst(m, v[i]);
    return m;
}

/* the summary's rule (stress.h): the first index within MC_STRESS_TIE of the maximum */
static size_t first_max(const double *v, size_t n)
{
    const double m = max_of(v, n);
    size_t i = 0;
    while (v[i] < m - MC_STRESS_TIE * fabs(m))
        i++;
    return i;
}

/* The stage reproduces the operator's field, the invariants and a summary at the Hertz maximum
 * (theory.md §6.1: 0.62004 p0 at z = 0.48 a on the axis, mu = 0; 4.2 table: 0.6598 p0 at
 * x = 0.32 a, z = 0.43 a, mu = 0.3, here sampled on the layers given). */
START_TEST(test_stage)
{
    const double mu = _i ? 0.3 : 0.0;
    mc_scene sc;
    stage_scene(&sc, 20, mu);
    mc_results res;
    memset(&res, 0, sizeof res);
    res.grid = sc.grid;
    res.pressure = mc_zeros(mc_grid_cells(&sc.grid));
    double *p = hertz_pressure(&sc.grid);
    memcpy(res.pressure, p, sizeof *p * mc_grid_cells(&sc.grid));
    mc_error err;
    for (int run = 0; run < 2; run++) /* the second run replaces the first's arrays */
        ck_assert_msg(mc_stage_stress(&sc, &res, &err) == MC_OK, "%s", err.msg);
    const size_t n = mc_grid_cells(&sc.grid), nv = 3 * n;
    ck_assert_int_eq(res.nlayers, 3);
    ck_assert_double_eq(res.depths[1], 0.48);
    double *q = malloc(sizeof *q * n);
    for (size_t i = 0; i < n; i++)
        q[i] = mu * p[i];
    double **s = stress_run(&sc.grid, MC_STRESS_PATCH, sc.stress.depths, 3, MC_BACKEND_FFT, p,
                            mu > 0 ? q : NULL, NULL);
    for (int c = 0; c < MC_NSTRESS; c++)
        ck_assert(memcmp(s[c], res.stress[c], nv * sizeof(double)) == 0);
    for (size_t i = 0; i < nv; i++) {
        const double t[MC_NSTRESS] = {s[0][i], s[1][i], s[2][i], s[3][i], s[4][i], s[5][i]};
        ck_assert_double_eq(res.von_mises[i], mc_von_mises(t));
        ck_assert_double_eq(res.hydrostatic[i], mc_hydrostatic(t));
        ck_assert_double_le(fabs(res.tresca[i] - mc_tresca(t)), TOL_TIGHT);
    }
    /* the summary: the first cells in volume order within MC_STRESS_TIE of the maxima, at their
     * cell centres and layer depths */
    const mc_stage_stress_summary *ss = &res.stress_summary;
    const size_t iv = first_max(res.von_mises, nv), it = first_max(res.tresca, nv);
    const size_t at[2] = {iv, it};
    const double *got[2] = {ss->vm_max_at, ss->tresca_max_at};
    for (int m = 0; m < 2; m++) {
        const size_t r = at[m] % n;
        ck_assert_double_eq(got[m][0], mc_grid_x(&sc.grid, (int)(r % (size_t)sc.grid.nx)));
        ck_assert_double_eq(got[m][1], mc_grid_y(&sc.grid, (int)(r / (size_t)sc.grid.nx)));
        ck_assert_double_eq(got[m][2], sc.stress.depths[at[m] / n]);
    }
    ck_assert_double_eq(ss->vm_max, max_of(res.von_mises, nv));
    ck_assert_double_eq(ss->hydro_at_vm_max, res.hydrostatic[iv]);
    ck_assert_double_eq(ss->tresca_max, max_of(res.tresca, nv));
    /* and the physics of the maximum: Hamilton at that point, to the a/dx = 20 accuracy */
    double ref[MC_NSTRESS];
    mc_hertz_point_sliding(ss->vm_max_at[0], ss->vm_max_at[1], ss->vm_max_at[2], NU, mu, ref);
    ck_assert_double_le(fabs(ss->vm_max - mc_von_mises(ref)), HERTZ_VM_MARGIN * 3.7e-4);
    ck_assert_double_eq(ss->vm_max_at[2], 0.48);
    if (mu == 0.0)
        ck_assert_double_le(hypot(ss->vm_max_at[0], ss->vm_max_at[1]), sc.grid.dx);
    else
        ck_assert(ss->vm_max_at[0] > 0.0); /* the maximum moves ahead (theory.md §6.2) */
    ck_assert_int_eq(ss->layers, 3);
    ck_assert_double_eq(ss->depth_min, 0.0);
    ck_assert_double_eq(ss->depth_max, 1.0);
    ck_assert_str_eq(ss->kernel, "patch");
    ck_assert_double_eq(ss->friction, mu);
    vols_free(s, 6);
    free(p);
    free(q);
    mc_results_free(&res);
}
END_TEST

/* A failing stage leaves the results' stress members as they were, and leaks nothing. */
START_TEST(test_stage_nomem)
{
    mc_scene sc;
    stage_scene(&sc, 4, 0.2);
    if (_i == 1) { /* a small contact on a large grid: windows, depths from the contact patch */
        sc.grid.nx = sc.grid.ny = 96;
        sc.stress.spacing = MC_SPACING_LINEAR;
        sc.stress.depth_max = MC_STRESS_DEPTH_AUTO;
        sc.stress.layers = 4;
    }
    mc_results res;
    memset(&res, 0, sizeof res);
    res.grid = sc.grid;
    res.pressure = hertz_pressure(&sc.grid);
    mc_error err;
    int failures = 0;
    for (long k = 1;; k++) {
        const long before = mc_alloc_injected();
        mc_alloc_fail_at(k);
        const int rc = mc_stage_stress(&sc, &res, &err);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == before) {
            ck_assert_int_eq(rc, MC_OK);
            ck_assert_ptr_nonnull(res.von_mises);
            break;
        }
        ck_assert_int_eq(rc, MC_ERR_NOMEM);
        ck_assert_ptr_null(res.von_mises);
        ck_assert_ptr_null(res.stress[0]);
        ck_assert_int_eq(res.nlayers, 0);
        failures++;
    }
    ck_assert_int_ge(failures, 10);
    ck_assert_int_eq(res.stress_layout.windowed, _i == 1);
    ck_assert_int_eq(res.stress_layout.depth_auto, _i == 1);
    free(res.pressure);
    res.pressure = NULL;
    mc_results_free(&res);
}
END_TEST

START_TEST(test_stage_bad)
{
    mc_scene sc;
    stage_scene(&sc, 4, 0.0);
    mc_results res;
    memset(&res, 0, sizeof res);
    res.grid = sc.grid;
    mc_error err;
    ck_assert_int_eq(mc_stage_stress(&sc, &res, &err), MC_ERR_INPUT); /* no pressure */
    res.pressure = hertz_pressure(&sc.grid);
    sc.stress.ndepths = 0;
    ck_assert_int_eq(mc_stage_stress(&sc, &res, &err), MC_ERR_INPUT);
    sc.stress.ndepths = 2;
    sc.stress.kernel = MC_STRESS_POINT; /* depth 0 */
    ck_assert_int_eq(mc_stage_stress(&sc, &res, &err), MC_ERR_INPUT);
    ck_assert_ptr_null(res.von_mises);
    free(res.pressure);
}
END_TEST

/* ---- the speed-ups: quadrant tables, symmetric transforms, sparse sums (stress.h) -------------- */

/* Free grids for the symmetric engine: odd and even sizes, nx != ny, dx != dy, a single row or
 * column, 2 x 2, and sizes whose 7-smooth half period m exceeds n (11 -> 12, 13 -> 14). */
static const grid_case sym_grids[] = {
    {7, 6, 1.0, 1.3, 0, 0, 0}, {11, 13, 1.2, 0.9, 0, 0, 0}, {1, 9, 1.0, 0.7, 0, 0, 0},
    {8, 1, 0.8, 1.0, 0, 0, 0}, {2, 2, 1.0, 1.0, 0, 0, 0},   {16, 5, 1.0, 1.1, 0, 0, 0},
};
#define N_SYM_GRIDS ((int)(sizeof sym_grids / sizeof sym_grids[0]))

/* per component c: max |a_c - b_c| <= tol max |b_c| (a component may be much smaller than the
 * others: each one is held to round-off of its own size) */
static void check_each_component(double *const a[6], double *const b[6], size_t n, double tol,
                                 const char *what)
{
    for (int c = 0; c < MC_NSTRESS; c++) {
        double md = 0.0, mb = 0.0;
        for (size_t i = 0; i < n; i++) {
            md = test_worst(md, fabs(a[c][i] - b[c][i]));
            mb = test_worst(mb, fabs(b[c][i]));
        }
        ck_assert_msg(md <= tol * mb, "%s, %s: %.3g relative", what, mc_component_name(c),
                      mb > 0 ? md / mb : md);
    }
}

/* Stresses as stress_run, with the speed-ups of tune; the plan's timing in *t (if not NULL). */
static double **stress_run_tuned(const mc_grid *g, mc_stress_kernel kernel, const double *depths,
                                 int nz, mc_backend b, const mc_stress_tuning *tune,
                                 const double *p, const double *qx, const double *qy,
                                 mc_stress_timing *t)
{
    const mc_stress_options opt = {kernel, NU, nz, depths, b,
                                   (p ? MC_TRACTION_P : 0) | (qx ? MC_TRACTION_QX : 0) |
                                       (qy ? MC_TRACTION_QY : 0), 0};
    mc_error err;
    mc_stress_plan *plan = NULL;
    int rc = mc_stress_create_tuned(g, &opt, tune, &plan, &err);
    ck_assert_msg(rc == MC_OK, "create: %s", err.msg);
    double **s = vols(6, mc_grid_cells(g) * (size_t)nz);
    rc = mc_stress_field(plan, p, qx, qy, s, &err);
    ck_assert_msg(rc == MC_OK, "field: %s", err.msg);
    if (t)
        mc_stress_timing_get(plan, t);
    mc_stress_destroy(&plan);
    return s;
}

/* The parities of mc_stress_parity are those kernel.h states (theory.md §5.3, §5.4), checked on
 * the rectangle functions themselves at a generic point. */
START_TEST(test_parity_table)
{
    const double x = 0.37, y = 0.61, z = 0.29, a = 0.5, b = 0.4;
    for (int li = 0; li < 3; li++) {
        double s[MC_NSTRESS], sx[MC_NSTRESS], sy[MC_NSTRESS];
        rect_fns[li](x, y, z, a, b, NU, s);
        rect_fns[li](-x, y, z, a, b, NU, sx);
        rect_fns[li](x, -y, z, a, b, NU, sy);
        for (int c = 0; c < MC_NSTRESS; c++) {
            const int par = mc_stress_parity(load_bits[li], c);
            const double ex = (par & 1) ? -1.0 : 1.0, ey = (par & 2) ? -1.0 : 1.0;
            ck_assert_msg(fabs(s[c]) > TOL_TIGHT, "load %d %s vanishes at the test point", li,
                          mc_component_name(c));
            ck_assert_double_le(fabs(sx[c] - ex * s[c]), TOL_TIGHT * fabs(s[c]));
            ck_assert_double_le(fabs(sy[c] - ey * s[c]), TOL_TIGHT * fabs(s[c]));
        }
    }
    ck_assert_int_eq(mc_stress_parity(MC_TRACTION_P | MC_TRACTION_QX, 0), -1);
    ck_assert_int_eq(mc_stress_parity(MC_TRACTION_P, 6), -1);
}
END_TEST

/* The quadrant is the full table's entries at offsets >= 0, bit for bit (the same differences in
 * the same order), zero beyond the grid's offsets; the full table's other quadrants are its
 * mirror images with the parities' signs (to round-off: they come from other corners). */
static void check_quadrant(const grid_case *gc, mc_stress_kernel kernel)
{
    const mc_grid g = grid_of(gc);
    int tx, ty;
    table_dims(&g, 2, &tx, &ty);
    const int qx = g.nx + 2, qy = g.ny + 1; /* slots beyond the offsets of the grid */
    mc_error err;
    mc_stress_tables *tb = NULL;
    ck_assert_int_eq(mc_stress_tables_create(&g, tx, ty, kernel, NU, 0, &tb, &err), MC_OK);
    double **k = vols(6, (size_t)tx * ty), **q = vols(6, (size_t)qx * qy);
    for (int iz = 0; iz < N_TABLE_DEPTHS; iz++) {
        const double z = table_depths[iz] * g.dx;
        if (kernel == MC_STRESS_POINT && z == 0.0)
            continue;
        for (int li = 0; li < 3; li++) {
            ck_assert_int_eq(mc_stress_tables_build(tb, load_bits[li], z, k, &err), MC_OK);
            ck_assert_int_eq(
                mc_stress_tables_quadrant(tb, load_bits[li], z, qx, qy, q, &err), MC_OK);
            for (int c = 0; c < MC_NSTRESS; c++) {
                const int par = mc_stress_parity(load_bits[li], c);
                double mk = 0.0;
                for (size_t t = 0; t < (size_t)tx * ty; t++)
                    mk = test_worst(mk, fabs(k[c][t]));
                for (int j = 0; j < qy; j++)
                    for (int i = 0; i < qx; i++) {
                        const double v = q[c][(size_t)j * qx + i];
                        if (i >= g.nx || j >= g.ny) {
                            ck_assert_msg(v == 0.0, "slot (%d,%d) beyond the grid holds %g", i, j,
                                          v);
                            continue;
                        }
                        const double ref = k[c][(size_t)j * tx + i];
                        ck_assert_msg(v == ref, "grid %dx%d load %d %s z=%g (%d,%d): %.17g vs %.17g",
                                      g.nx, g.ny, li, mc_component_name(c), z, i, j, v, ref);
                        /* the mirror images: offsets (-i, j), (i, -j), (-i, -j) */
                        const int im = i ? tx - i : 0, jm = j ? ty - j : 0;
                        const double sx = (par & 1) ? -1.0 : 1.0, sy = (par & 2) ? -1.0 : 1.0;
                        const double mirror[3] = {k[c][(size_t)j * tx + im] - sx * v,
                                                  k[c][(size_t)jm * tx + i] - sy * v,
                                                  k[c][(size_t)jm * tx + im] - sx * sy * v};
                        for (int m = 0; m < 3; m++)
                            ck_assert_msg(fabs(mirror[m]) <= TOL_MIRROR,
                                          "load %d %s (%d,%d) mirror %d: %.3g (largest entry "
                                          "%.3g)",
                                          li, mc_component_name(c), i, j, m, mirror[m], mk);
                    }
            }
        }
    }
    vols_free(k, 6);
    vols_free(q, 6);
    mc_stress_tables_destroy(&tb);
}

START_TEST(test_quadrant_patch) { check_quadrant(&sym_grids[_i], MC_STRESS_PATCH); }
END_TEST

START_TEST(test_quadrant_point) { check_quadrant(&sym_grids[_i], MC_STRESS_POINT); }
END_TEST

/* The symmetric engine (quadrant tables, DCT-I/DST-I spectra, products from the quadrant) against
 * the r2c engine of operator.h on the same loads: round-off, for every component of every load
 * alone and of all three together, patch and point kernels. */
START_TEST(test_symmetric_vs_r2c)
{
    const grid_case *gc = &sym_grids[_i / 2];
    const mc_stress_kernel kernel = _i % 2 ? MC_STRESS_POINT : MC_STRESS_PATCH;
    const mc_grid g = grid_of(gc);
    const double patch_z[] = {0.0, 0.4, 3.0}, point_z[] = {0.2, 0.4, 3.0};
    const double *z = kernel == MC_STRESS_PATCH ? patch_z : point_z;
    const size_t nv = mc_grid_cells(&g) * 3;
    double *f[3] = {random_load(&g, 51), random_load(&g, 52), random_load(&g, 53)};
    const mc_stress_tuning sym = {MC_STRESS_ON, MC_STRESS_OFF, MC_STRESS_AUTO};
    const mc_stress_tuning r2c = {MC_STRESS_OFF, MC_STRESS_OFF, MC_STRESS_AUTO};
    for (int which = 0; which < 4; which++) { /* p, qx, qy alone; all three */
        const double *l[3];
        for (int li = 0; li < 3; li++)
            l[li] = which == 3 || which == li ? f[li] : NULL;
        mc_stress_timing ta, tb;
        double **a = stress_run_tuned(&g, kernel, z, 3, MC_BACKEND_FFT, &sym, l[0], l[1], l[2],
                                      &ta);
        double **b = stress_run_tuned(&g, kernel, z, 3, MC_BACKEND_FFT, &r2c, l[0], l[1], l[2],
                                      &tb);
        ck_assert_int_eq(ta.symmetric, 1);
        ck_assert_int_eq(tb.symmetric, 0);
        char what[96];
        snprintf(what, sizeof what, "grid %dx%d kernel %d loads %d", g.nx, g.ny, (int)kernel,
                 which);
        check_each_component(a, b, nv, TOL_BACKEND, what);
        vols_free(a, 6);
        vols_free(b, 6);
    }
    for (int li = 0; li < 3; li++)
        free(f[li]);
}
END_TEST

/* A load on a few cells only (the rest exactly 0). */
static double *sparse_load(const mc_grid *g, int ncells, unsigned long long seed)
{
    const size_t n = mc_grid_cells(g);
    double *f = calloc(n, sizeof *f), v[64];
    ck_assert(f != NULL && ncells <= 32);
    test_random_field(v, 2 * (size_t)ncells, seed);
    for (int k = 0; k < ncells; k++) {
        const size_t at = (size_t)((0.5 * (v[2 * k] + 1.0)) * (double)n) % n;
        f[at] = 1.0 + v[2 * k + 1];
    }
    return f;
}

/* The sparse sum over the loaded cells against the transforms, on both engines and the direct
 * backend, free and periodic grids: round-off. */
START_TEST(test_sparse_vs_fft)
{
    const grid_case *gc = &backend_grids[_i / 2];
    const mc_backend back = _i % 2 ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = grid_of(gc);
    const double z[] = {0.0, 0.6, 2.5};
    const size_t nv = mc_grid_cells(&g) * 3;
    double *p = sparse_load(&g, 4, 61), *qx = sparse_load(&g, 3, 62), *qy = sparse_load(&g, 1, 63);
    const mc_stress_tuning on = {MC_STRESS_AUTO, MC_STRESS_ON, MC_STRESS_AUTO};
    const mc_stress_tuning off = {MC_STRESS_AUTO, MC_STRESS_OFF, MC_STRESS_AUTO};
    mc_stress_timing ta, tb;
    double **a = stress_run_tuned(&g, MC_STRESS_PATCH, z, 3, back, &on, p, qx, qy, &ta);
    double **b = stress_run_tuned(&g, MC_STRESS_PATCH, z, 3, back, &off, p, qx, qy, &tb);
    ck_assert_int_eq(ta.sparse_layers, 3);
    ck_assert_int_eq(tb.sparse_layers, 0);
    char what[96];
    snprintf(what, sizeof what, "grid %dx%d periodic %d%d backend %d", g.nx, g.ny, g.periodic_x,
             g.periodic_y, (int)back);
    check_each_component(a, b, nv, TOL_BACKEND, what);
    vols_free(a, 6);
    vols_free(b, 6);
    free(p);
    free(qx);
    free(qy);
}
END_TEST

/* The cost model picks the sparse sum for one loaded cell and the transforms for a Hertz contact
 * that fills the grid; the choice follows mc_stress_cost. */
START_TEST(test_cost_model)
{
    const mc_grid g = hertz_grid(20, 0); /* 60 x 60, the contact a third of it */
    const size_t n = mc_grid_cells(&g);
    const double z[] = {0.1, 0.5, 1.0};
    double *one = calloc(n, sizeof *one), *p = hertz_pressure(&g);
    ck_assert(one != NULL);
    one[n / 2 + 7] = 1.0;
    long loaded = 0;
    for (size_t i = 0; i < n; i++)
        loaded += p[i] != 0.0;
    mc_stress_timing t1, th;
    double **a = stress_run_tuned(&g, MC_STRESS_PATCH, z, 3, MC_BACKEND_FFT, NULL, one, NULL,
                                  NULL, &t1);
    double **b = stress_run_tuned(&g, MC_STRESS_PATCH, z, 3, MC_BACKEND_FFT, NULL, p, NULL, NULL,
                                  &th);
    ck_assert_int_eq(t1.sparse_layers, 3);
    ck_assert_int_eq(th.sparse_layers, 0);
    const mc_stress_options opt = {MC_STRESS_PATCH, NU, 3, z, MC_BACKEND_FFT, MC_TRACTION_P, 0};
    mc_error err;
    mc_stress_plan *plan = NULL;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_OK);
    double full1, sparse1, fullh, sparseh;
    mc_stress_cost(plan, 1, 1, &full1, &sparse1);
    mc_stress_cost(plan, loaded, 1, &fullh, &sparseh);
    ck_assert(sparse1 < full1 && sparseh > fullh);
    ck_assert(full1 == fullh && full1 > 0.0);
    mc_stress_destroy(&plan);
    vols_free(a, 6);
    vols_free(b, 6);
    free(one);
    free(p);
}
END_TEST

/* The kernel spectra kept by a repeated plan (stress.h `repeated`): a second and third field
 * from the kept spectra, with other loads, are the bits of a plan that rebuilds them, on free
 * axes (the symmetric engine) and on a periodic grid; with friction (two loads, two cache
 * slots). */
START_TEST(test_repeated_cache)
{
    const mc_grid g = {24, 19, 1e-6, 1.2e-6, 0, _i};
    const double z[3] = {0.3e-6, 1.1e-6, 2.5e-6};
    const size_t n = mc_grid_cells(&g), nv = 3 * n;
    mc_stress_options opt = {MC_STRESS_PATCH, NU, 3, z, MC_BACKEND_FFT,
                             MC_TRACTION_P | MC_TRACTION_QX, 1};
    mc_stress_plan *kept = NULL, *plain = NULL;
    mc_error err;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &kept, &err), MC_OK);
    opt.repeated = 0;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plain, &err), MC_OK);
    double *p = calloc(n, sizeof *p), *q = calloc(n, sizeof *q);
    double *a = calloc(6 * nv, sizeof *a), *b = calloc(6 * nv, sizeof *b);
    double *sa[6], *sb[6];
    for (int c = 0; c < 6; c++) {
        sa[c] = a + c * nv;
        sb[c] = b + c * nv;
    }
    for (int pass = 0; pass < 3; pass++) {
        for (size_t i = 0; i < n; i++) { /* a different dense load each pass */
            p[i] = 1e9 * (0.5 + 0.5 * sin(0.37 * (double)i + pass));
            q[i] = pass == 1 ? 0.0 : 0.1 * p[i] * cos(0.11 * (double)i);
        }
        ck_assert_int_eq(mc_stress_field(kept, p, pass == 1 ? NULL : q, NULL, sa, &err), MC_OK);
        ck_assert_int_eq(mc_stress_field(plain, p, pass == 1 ? NULL : q, NULL, sb, &err), MC_OK);
        ck_assert_msg(memcmp(a, b, 6 * nv * sizeof *a) == 0, "pass %d: kept spectra differ",
                      pass);
    }
    mc_stress_destroy(&kept);
    mc_stress_destroy(&plain);
    free(p);
    free(q);
    free(a);
    free(b);
}
END_TEST

/* mc_stress_field_layers hands over each layer in order with the bits of mc_stress_field's (the
 * running-in's yield check streams the layers through it, pipeline/runin.c); a visitor's non-zero
 * return stops the sweep there. */
typedef struct {
    const double *whole; /* mc_stress_field's volume: component c of layer k at c nv + k n */
    size_t n, nv;
    int stop_after;      /* the visitor stops the sweep after this layer (-1: never) */
    int next, differ;
} layer_seen;

static int see_layer(void *ctx, int k, double *const s[6])
{
    layer_seen *ls = ctx;
    if (k != ls->next++)
        ls->differ++;
    for (int c = 0; c < 6; c++)
        ls->differ += memcmp(s[c], ls->whole + (size_t)c * ls->nv + (size_t)k * ls->n,
                             ls->n * sizeof *s[c]) != 0;
    return k == ls->stop_after ? 7 : MC_OK;
}

START_TEST(test_field_layers)
{
    const mc_grid g = {21, 17, 1e-6, 1.1e-6, 0, _i};
    const double z[3] = {0.4e-6, 1.3e-6, 3.0e-6};
    const size_t n = mc_grid_cells(&g), nv = 3 * n;
    mc_stress_options opt = {MC_STRESS_PATCH, NU, 3, z, MC_BACKEND_FFT,
                             MC_TRACTION_P | MC_TRACTION_QX, 1};
    mc_stress_plan *plan = NULL;
    mc_error err;
    ck_assert_int_eq(mc_stress_create(&g, &opt, &plan, &err), MC_OK);
    double *p = calloc(n, sizeof *p), *q = calloc(n, sizeof *q);
    double *a = calloc(6 * nv, sizeof *a), *l = calloc(6 * n, sizeof *l), *sa[6], *sl[6];
    for (int c = 0; c < 6; c++) {
        sa[c] = a + c * nv;
        sl[c] = l + c * n;
    }
    for (size_t i = 0; i < n; i++) {
        p[i] = 1e9 * (0.5 + 0.5 * sin(0.29 * (double)i));
        q[i] = 0.2 * p[i] * cos(0.13 * (double)i);
    }
    ck_assert_int_eq(mc_stress_field(plan, p, q, NULL, sa, &err), MC_OK);
    layer_seen ls = {a, n, nv, -1, 0, 0};
    ck_assert_int_eq(mc_stress_field_layers(plan, p, q, NULL, sl, see_layer, &ls, &err), MC_OK);
    ck_assert_msg(ls.next == 3 && ls.differ == 0, "%d layers seen, %d differ", ls.next, ls.differ);
    layer_seen stop = {a, n, nv, 1, 0, 0}; /* the visitor stops the sweep after layer 1 */
    ck_assert_int_eq(mc_stress_field_layers(plan, p, q, NULL, sl, see_layer, &stop, &err), 7);
    ck_assert_int_eq(stop.next, 2);
    mc_stress_destroy(&plan);
    free(p);
    free(q);
    free(a);
    free(l);
}
END_TEST

/* Bad switches are refused. */
START_TEST(test_tuning_bad)
{
    const mc_grid g = {6, 5, 1.0, 1.0, 0, 0};
    const double z = 1.0;
    const mc_stress_options opt = {MC_STRESS_PATCH, NU, 1, &z, MC_BACKEND_FFT, MC_TRACTION_P, 0};
    const mc_stress_tuning bad = {MC_STRESS_AUTO, (mc_stress_switch)7, MC_STRESS_AUTO};
    mc_error err;
    mc_stress_plan *plan = NULL;
    ck_assert_int_eq(mc_stress_create_tuned(&g, &opt, &bad, &plan, &err), MC_ERR_INPUT);
    ck_assert_ptr_null(plan);
}
END_TEST

/* ---- the stage's skips: windows and depths from the contact ----------------------------------- */

/* A Hertz pressure (a = 1) of radius a on a grid of n x n cells of a/r, centre (cx, cy) in cells
 * from the grid's centre; p is added to (max with) the given field. */
static void add_hertz(const mc_grid *g, double cx, double cy, double a, double *p)
{
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            const double x = mc_grid_x(g, i) - cx * g->dx, y = mc_grid_y(g, j) - cy * g->dy;
            const double r2 = (x * x + y * y) / (a * a);
            if (r2 < 1.0)
                p[(size_t)j * g->nx + i] = fmax(p[(size_t)j * g->nx + i], sqrt(1.0 - r2));
        }
}

/* A stage run on a prescribed pressure (no contact solve: the loaded cells are the patches). */
static void run_stage(const mc_scene *sc, const double *p, const mc_stress_tuning *tune,
                      mc_results *res)
{
    memset(res, 0, sizeof *res);
    res->grid = sc->grid;
    res->pressure = mc_zeros(mc_grid_cells(&sc->grid));
    ck_assert(res->pressure != NULL);
    memcpy(res->pressure, p, sizeof *p * mc_grid_cells(&sc->grid));
    mc_error err;
    ck_assert_msg(mc_stage_stress_tuned(sc, res, tune, &err) == MC_OK, "%s", err.msg);
}

typedef struct {
    double cx, cy; /* centre of the contact, cells from the grid's centre */
    double mu;
} window_case;

static const window_case window_cases[] = {{3.0, -2.0, 0.0}, {3.0, -2.0, 0.3}, {-70.0, 60.0, 0.3}};

/* A small Hertz contact (a = 6 cells) on a grid 33 a wide: each layer's window holds the full
 * computation to round-off, the cells outside hold 0 and the full computation there is below
 * MC_STRESS_WINDOW_FRACTION of the layer's largest von Mises stress; the summary is the same. */
START_TEST(test_window)
{
    const window_case *wc = &window_cases[_i];
    mc_scene sc;
    mc_scene_defaults(&sc);
    sc.grid = (mc_grid){200, 192, 1.0 / 6, 1.0 / 6, 0, 0};
    sc.stress.enabled = 1;
    sc.stress.spacing = MC_SPACING_LIST;
    const double zs[] = {0.0, 0.05, 0.2, 0.48, 1.0, 2.0, 3.0};
    sc.stress.ndepths = 7;
    memcpy(sc.stress.depths, zs, sizeof zs);
    sc.stress.friction = wc->mu;
    const size_t n = mc_grid_cells(&sc.grid);
    double *p = calloc(n, sizeof *p);
    ck_assert(p != NULL);
    add_hertz(&sc.grid, wc->cx, wc->cy, 1.0, p); /* off-centre; near a corner: clipped windows */
    mc_results win, full;
    const mc_stress_tuning off = {MC_STRESS_AUTO, MC_STRESS_AUTO, MC_STRESS_OFF};
    run_stage(&sc, p, NULL, &win);
    run_stage(&sc, p, &off, &full);
    const mc_stage_stress_layout *lay = &win.stress_layout;
    ck_assert_int_eq(lay->windowed, 1);
    ck_assert_int_ge(lay->nwindows, 2);
    ck_assert_int_eq(full.stress_layout.windowed, 0);
    ck_assert_int_eq(lay->window[0].k0, 0);
    ck_assert_int_eq(lay->window[lay->nwindows - 1].k1, 6);
    double worst_vm = 0.0, worst_c = 0.0;
    for (int w = 0; w < lay->nwindows; w++) {
        const mc_stage_stress_window *wn = &lay->window[w];
        if (w > 0)
            ck_assert_int_eq(wn->k0, lay->window[w - 1].k1 + 1);
        for (int k = wn->k0; k <= wn->k1; k++) {
            const size_t at = (size_t)k * n;
            double smax = 0.0, vmax = 0.0;
            for (size_t i = 0; i < n; i++) {
                vmax = test_worst(vmax, full.von_mises[at + i]);
                for (int c = 0; c < MC_NSTRESS; c++)
                    smax = test_worst(smax, fabs(full.stress[c][at + i]));
            }
            for (int j = 0; j < sc.grid.ny; j++)
                for (int i = 0; i < sc.grid.nx; i++) {
                    const size_t q = at + (size_t)j * sc.grid.nx + i;
                    const int inside = i >= wn->i0 && i <= wn->i1 && j >= wn->j0 && j <= wn->j1;
                    double cmax = 0.0;
                    for (int c = 0; c < MC_NSTRESS; c++) {
                        const double d = fabs(win.stress[c][q] - full.stress[c][q]);
                        if (inside)
                            ck_assert_msg(d <= TOL_ROUNDOFF * smax,
                                          "layer %d cell (%d,%d) %s: %.3g relative", k, i, j,
                                          mc_component_name(c), d / smax);
                        else
                            ck_assert_msg(win.stress[c][q] == 0.0, "outside holds %g",
                                          win.stress[c][q]);
                        cmax = test_worst(cmax, fabs(full.stress[c][q]));
                    }
                    if (!inside) {
                        worst_vm = test_worst(worst_vm, full.von_mises[q] / vmax);
                        worst_c = test_worst(worst_c, cmax / vmax);
                    }
                }
        }
    }
    ck_assert_msg(worst_vm <= MC_STRESS_WINDOW_FRACTION, "von Mises left out: %.3g", worst_vm);
    ck_assert_msg(worst_c <= MC_STRESS_WINDOW_FRACTION, "components left out: %.3g", worst_c);
    ck_assert(worst_vm > 0.0); /* the window did leave something out */
    const mc_stage_stress_summary *a = &win.stress_summary, *b = &full.stress_summary;
    for (int d = 0; d < 3; d++) {
        ck_assert_double_eq(a->vm_max_at[d], b->vm_max_at[d]);
        ck_assert_double_eq(a->tresca_max_at[d], b->tresca_max_at[d]);
    }
    ck_assert_double_le(fabs(a->vm_max - b->vm_max), TOL_ROUNDOFF * b->vm_max);
    ck_assert_double_le(fabs(a->tresca_max - b->tresca_max), TOL_ROUNDOFF * b->tresca_max);
    ck_assert_double_le(fabs(a->hydro_at_vm_max - b->hydro_at_vm_max), TOL_ROUNDOFF * b->vm_max);
    mc_results_free(&win);
    mc_results_free(&full);
    free(p);
}
END_TEST

/* No window where the load is not compact: a lubricant pressure on every cell, a contact that
 * fills the grid, or a periodic axis; [stress] window = full turns it off. */
START_TEST(test_window_not_applied)
{
    mc_scene sc;
    mc_scene_defaults(&sc);
    sc.grid = (mc_grid){96, 96, 1.0 / 8, 1.0 / 8, 0, 0};
    sc.stress.enabled = 1;
    sc.stress.spacing = MC_SPACING_LIST;
    sc.stress.ndepths = 2;
    sc.stress.depths[0] = 0.1;
    sc.stress.depths[1] = 1.0;
    const size_t n = mc_grid_cells(&sc.grid);
    double *p = calloc(n, sizeof *p);
    ck_assert(p != NULL);
    add_hertz(&sc.grid, 0.0, 0.0, 1.0, p);
    mc_results res;
    run_stage(&sc, p, NULL, &res); /* 96 cells = 12 a: a 16 a window does not fit */
    ck_assert_int_eq(res.stress_layout.windowed, 0);
    mc_results_free(&res);
    sc.grid.nx = sc.grid.ny = 200;
    double *q = calloc(mc_grid_cells(&sc.grid), sizeof *q);
    ck_assert(q != NULL);
    add_hertz(&sc.grid, 0.0, 0.0, 1.0, q);
    run_stage(&sc, q, NULL, &res);
    ck_assert_int_eq(res.stress_layout.windowed, 1);
    mc_results_free(&res);
    sc.stress.window = MC_STRESS_WINDOW_FULL;
    run_stage(&sc, q, NULL, &res);
    ck_assert_int_eq(res.stress_layout.windowed, 0);
    mc_results_free(&res);
    sc.stress.window = MC_STRESS_WINDOW_AUTO;
    sc.grid.periodic_y = 1; /* the load repeats along y: a line load, no window */
    run_stage(&sc, q, NULL, &res);
    ck_assert_int_eq(res.stress_layout.windowed, 0);
    mc_results_free(&res);
    sc.grid.periodic_y = 0;
    for (size_t i = 0; i < mc_grid_cells(&sc.grid); i++)
        q[i] = test_worst(q[i], 0.02); /* a lubricant film */
    run_stage(&sc, q, NULL, &res);
    ck_assert_int_eq(res.stress_layout.windowed, 0);
    ck_assert_int_eq(res.stress_layout.loaded_cells, (long)mc_grid_cells(&sc.grid));
    mc_results_free(&res);
    free(p);
    free(q);
}
END_TEST

/* depth_max = auto on a Hertz contact: one patch of radius a (to the pixelation), depth_max = 3 R
 * and the von Mises maximum (0.48 a, theory.md §6.1) inside the range, at the layer nearest to
 * it. Solved contact (patches above the lubricant pressure) and prescribed pressure alike. */
START_TEST(test_depth_auto_hertz)
{
    const int r = 16;
    mc_scene sc;
    mc_scene_defaults(&sc);
    sc.grid = hertz_grid(r, 1);
    sc.stress.enabled = 1;
    sc.stress.layers = 32;
    const size_t n = mc_grid_cells(&sc.grid);
    double *p = hertz_pressure(&sc.grid);
    const double p_lub = 0.01;
    if (_i == 1) { /* a solved contact in a lubricant film */
        sc.load.lubricant_pressure = p_lub;
        for (size_t i = 0; i < n; i++)
            p[i] = test_worst(p[i], p_lub);
    }
    mc_results res;
    memset(&res, 0, sizeof res);
    res.grid = sc.grid;
    res.pressure = p;
    res.contact.solved = _i == 1;
    mc_error err;
    ck_assert_msg(mc_stage_stress(&sc, &res, &err) == MC_OK, "%s", err.msg);
    const mc_stage_stress_layout *lay = &res.stress_layout;
    long cells = 0;
    for (size_t i = 0; i < n; i++)
        cells += p[i] > (_i == 1 ? p_lub : 0.0);
    const double R = sqrt((double)cells * sc.grid.dx * sc.grid.dy / M_PI);
    ck_assert_int_eq(lay->depth_auto, 1);
    ck_assert_int_eq(lay->patches, 1);
    ck_assert_double_le(fabs(lay->patch_radius - R), TOL_TIGHT);
    ck_assert_double_le(fabs(lay->patch_radius - 1.0), sc.grid.dx); /* a, to the pixelation */
    ck_assert_int_eq(res.nlayers, 32);
    ck_assert_double_eq(res.depths[31], MC_STRESS_DEPTH_RADII * lay->patch_radius);
    const double dz = res.depths[1] - res.depths[0], zmax = res.stress_summary.vm_max_at[2];
    ck_assert_double_le(fabs(zmax - 0.48), 0.5 * dz + 0.02);
    ck_assert(zmax > res.depths[0] && zmax < res.depths[31]);
    mc_results_free(&res);
}
END_TEST

/* An independent count of the patches: union-find over right and up neighbours (wrapping along
 * periodic axes), areas by root. Returns the number; *largest the largest area in cells. */
static int find_root(int *parent, int a)
{
    while (parent[a] != a)
        a = parent[a] = parent[parent[a]];
    return a;
}

static int count_patches(const mc_grid *g, const double *p, double thr, long *largest)
{
    const int n = (int)mc_grid_cells(g);
    int *parent = malloc(sizeof *parent * (size_t)n);
    long *size = calloc((size_t)n, sizeof *size);
    ck_assert(parent && size);
    for (int c = 0; c < n; c++)
        parent[c] = c;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            const int c = j * g->nx + i;
            if (!(p[c] > thr))
                continue;
            const int right = i + 1 < g->nx ? c + 1 : (g->periodic_x ? j * g->nx : -1);
            const int up = j + 1 < g->ny ? c + g->nx : (g->periodic_y ? i : -1);
            const int nb[2] = {right, up};
            for (int k = 0; k < 2; k++)
                if (nb[k] >= 0 && p[nb[k]] > thr)
                    parent[find_root(parent, nb[k])] = find_root(parent, c);
        }
    int count = 0;
    *largest = 0;
    for (int c = 0; c < n; c++)
        if (p[c] > thr) {
            const int r = find_root(parent, c);
            count += size[r]++ == 0;
            *largest = size[r] > *largest ? size[r] : *largest;
        }
    free(parent);
    free(size);
    return count;
}

/* A rough contact: many asperity contacts of random sizes and places (two of them touching
 * across the periodic edge), some merged into one patch. The labelling agrees with an independent
 * union-find, the radius is that of the largest patch, and the stage's depth_max is 3 R. A band
 * around a periodic axis counts by its mean half-width. */
START_TEST(test_depth_auto_rough)
{
    mc_scene sc;
    mc_scene_defaults(&sc);
    sc.grid = (mc_grid){128, 96, 0.05, 0.06, 0, 1};
    sc.stress.enabled = 1;
    sc.stress.layers = 6;
    sc.stress.window = MC_STRESS_WINDOW_FULL;
    const size_t n = mc_grid_cells(&sc.grid);
    double *p = calloc(n, sizeof *p), v[3 * 24];
    ck_assert(p != NULL);
    test_random_field(v, 3 * 24, 71);
    for (int k = 0; k < 24; k++) /* radii 0.1 ... 0.5: 2 ... 10 cells */
        add_hertz(&sc.grid, 60.0 * v[3 * k], 44.0 * v[3 * k + 1], 0.3 + 0.2 * v[3 * k + 2], p);
    add_hertz(&sc.grid, 10.0, -48.0, 0.35, p); /* across the periodic edge y = -Ly/2 */
    mc_stage_stress_patches pt;
    mc_error err;
    ck_assert_int_eq(mc_stage_stress_find_patches(&sc.grid, p, 0.0, &pt, &err), MC_OK);
    long largest;
    const int count = count_patches(&sc.grid, p, 0.0, &largest);
    ck_assert_int_ge(count, 5); /* several patches */
    ck_assert_int_eq(pt.patches, count);
    const double R = sqrt((double)largest * sc.grid.dx * sc.grid.dy / M_PI);
    ck_assert_double_le(fabs(pt.radius - R), TOL_TIGHT * R);
    mc_results res;
    run_stage(&sc, p, NULL, &res);
    ck_assert_int_eq(res.stress_layout.patches, count);
    ck_assert_double_eq(res.depths[5], MC_STRESS_DEPTH_RADII * pt.radius);
    mc_results_free(&res);
    /* a band across the periodic y axis: mean half-width */
    memset(p, 0, sizeof *p * n);
    for (int j = 0; j < sc.grid.ny; j++)
        for (int i = 60; i < 60 + 5 + (j % 3); i++)
            p[(size_t)j * sc.grid.nx + i] = 1.0;
    ck_assert_int_eq(mc_stage_stress_find_patches(&sc.grid, p, 0.0, &pt, &err), MC_OK);
    ck_assert_int_eq(pt.patches, 1);
    ck_assert_double_le(fabs(pt.radius - 0.5 * 6.0 * sc.grid.dx), TOL_TIGHT);
    free(p);
}
END_TEST

/* depth_max = auto that does not exceed depth_min is an input error, naming the keys. */
START_TEST(test_depth_auto_bad)
{
    mc_scene sc;
    mc_scene_defaults(&sc);
    sc.grid = hertz_grid(4, 0);
    sc.stress.enabled = 1;
    sc.stress.depth_min = 5.0; /* beyond 3a */
    mc_results res;
    memset(&res, 0, sizeof res);
    res.grid = sc.grid;
    res.pressure = hertz_pressure(&sc.grid);
    mc_error err;
    ck_assert_int_eq(mc_stage_stress(&sc, &res, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "depth_max = auto") && strstr(err.msg, "depth_min"), "%s",
                  err.msg);
    ck_assert_ptr_null(res.von_mises);
    mc_results_free(&res);
}
END_TEST

Suite *suite_stress(void);
Suite *suite_stress(void)
{
    Suite *s = suite_create("stress");

    TCase *tc = tcase_create("tables");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_tables_patch, 0, N_TABLE_GRIDS);
    tcase_add_loop_test(tc, test_tables_point, 0, N_TABLE_GRIDS);
    tcase_add_test(tc, test_table_free_is_rectangle);
    tcase_add_loop_test(tc, test_tail_convergence, 0, N_TAIL);
    tcase_add_test(tc, test_images_rule);
    tcase_add_test(tc, test_strip_exact);
    tcase_add_test(tc, test_periodic_means);
    tcase_add_test(tc, test_tables_threads);
    tcase_add_test(tc, test_point_approaches_patch);
    suite_add_tcase(s, tc);

    tc = tcase_create("operator");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_direct_vs_fft, 0, 2 * N_BACKEND_GRIDS);
    tcase_add_loop_test(tc, test_surface_traction, 0, N_BACKEND_GRIDS);
    tcase_add_loop_test(tc, test_impulse_response, 0, 3);
    tcase_add_test(tc, test_linearity);
    tcase_add_test(tc, test_layer_matches_field);
    tcase_add_test(tc, test_uniform_patch);
    tcase_add_test(tc, test_bad_input);
    tcase_add_loop_test(tc, test_create_nomem, 0, 2);
    tcase_add_test(tc, test_traction_shape);
    suite_add_tcase(s, tc);

    tc = tcase_create("speed-ups");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_parity_table);
    tcase_add_loop_test(tc, test_quadrant_patch, 0, N_SYM_GRIDS);
    tcase_add_loop_test(tc, test_quadrant_point, 0, N_SYM_GRIDS);
    tcase_add_loop_test(tc, test_symmetric_vs_r2c, 0, 2 * N_SYM_GRIDS);
    tcase_add_loop_test(tc, test_sparse_vs_fft, 0, 2 * N_BACKEND_GRIDS);
    tcase_add_test(tc, test_cost_model);
    tcase_add_test(tc, test_tuning_bad);
    suite_add_tcase(s, tc);

    tc = tcase_create("skips");
    tcase_set_timeout(tc, 300);
    tcase_add_loop_test(tc, test_window, 0, 3);
    tcase_add_test(tc, test_window_not_applied);
    tcase_add_loop_test(tc, test_depth_auto_hertz, 0, 2);
    tcase_add_test(tc, test_depth_auto_rough);
    tcase_add_test(tc, test_depth_auto_bad);
    suite_add_tcase(s, tc);

    tc = tcase_create("hertz");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_hertz_point_axis);
    tcase_add_test(tc, test_hertz_point_vm);
    tcase_add_test(tc, test_hertz_line);
    suite_add_tcase(s, tc);

    tc = tcase_create("stage");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_stage, 0, 2);
    tcase_add_loop_test(tc, test_stage_nomem, 0, 2);
    tcase_add_test(tc, test_stage_bad);
    tcase_add_loop_test(tc, test_repeated_cache, 0, 2);
    tcase_add_loop_test(tc, test_field_layers, 0, 2);
    suite_add_tcase(s, tc);
    return s;
}
