/* test_eigen_kernels.c - influence functions of a cuboid of uniform eigenstrain (src/kernels/
 * eigen.h) against the dossier's compact value and layer limits (theory.md §8.1),
 * brute-force quadrature of the Boussinesq stresses (D) and of the Kelvin Green's function (S1),
 * the defining properties of the mirror solution (traction-free shear, equilibrium, jump
 * conditions, interior dilatation; §2.3), and the reciprocity between the two: the surface u_z
 * of the image method equals the Betti-reciprocity D. Lengths in units of the box. */
#include <float.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

#include "kernels/eigen.h"
#include "kernels/kernel.h"
#include "test_util.h"

/* ---- tolerances ------------------------------------------------------------------------------ */

/* Dossier §2.2 prints the compact value to 6 decimals: half a unit in the last place, plus the
 * same again for the dossier's own rounding of a value already rounded once. */
#define TOL_COMPACT 1e-6
/* Round-off tier for O(1) boxes at O(1) distance: the corner sums combine O(10) corner terms of
 * size O(1-10) (logs, atans), a few hundred operations in all. */
#define TOL_ROUND (256.0 * DBL_EPSILON)
/* Tensor Gauss-Legendre (n points per axis on split^3 sub-boxes) of integrands analytic in a
 * neighbourhood of the box: per axis the error decays like rho^(-2n), rho = 1 + d/h +
 * sqrt((1 + d/h)^2 - 1) for a singularity at distance d from a sub-box of half-width h. Boussinesq
 * boxes: d >= 0.2, h <= 0.15 (split 6), rho >= 4.4, n = 24: 1e-31. Kelvin points: d >= 0.55,
 * h <= 0.25 (split 2), rho >= 6, n = 16: 1e-25. The bound is set by round-off: ~10^5-10^6
 * terms summed (sqrt(N) eps ~ 1e-13 relative), plus TOL_ROUND absolute for the closed forms'
 * own (corner terms of size O(1) for unit boxes; measured 8e-16). */
#define N_GL_D 24
#define GL_SPLIT_D 6
#define N_GL_K 16
#define GL_SPLIT_K 2
#define TOL_GAUSS 1e-13
/* Tiny far box (side h at distance d): the midpoint rule's error is (h^2/24) sum_k d^2 f/dx_k^2,
 * and for the 1/rho^2 Boussinesq field |d^2 f/dx_k^2| <= 20 |f|max / d^2; bound:
 * (h/d)^2 * 20 * 3 / 24 = 2.5e-5 (measured 8e-6). */
#define TINY_H 1e-2
#define TINY_D 2.0
#define TOL_TINY ((TINY_H / TINY_D) * (TINY_H / TINY_D) * 2.5)
/* Wide thin layer (half-width W >> depth d, thickness t): the missing far field beyond the
 * inscribed disc of radius W of the in-plane nucleus, sum of sigma^B_xx + sigma^B_yy ~
 * -(2 + 2 nu) z/(2 pi rho^3), integrates to 2 (1 + nu) t (d + t)/W; the z-z part decays as
 * z^3/rho^5 (negligible) and the cos 2 theta parts cancel on the square. */
#define LAYER_W 2000.0
#define LAYER_D 1.0
#define LAYER_T 0.5
/* Finite differences: 4th-order central stencil with step FD_H at points >= 0.1 from any face:
 * truncation (h/0.1)^4 * O(10) = 1e-7 relative to |S|/0.1, round-off eps |S| / h = 1e-12. */
#define FD_H 1e-3
#define TOL_FD 1e-7
/* X moved by EDGE_DX across the line of a top-face edge: D is continuous there, with a
 * derivative O(ln(1/EDGE_DX)) (the corner terms are x ln|x|): change <= 1e-13 * 30 < 1e-11. */
#define EDGE_DX 1e-13
#define TOL_EDGE 1e-11
/* Jump conditions across a face, probed at +-JUMP_DZ: the smooth part changes by O(JUMP_DZ |grad
 * S|) with |grad S| <= 10 here (points 0.2 from every edge). */
#define JUMP_DZ 1e-9
#define TOL_JUMP 1e-7

/* ---- helpers --------------------------------------------------------------------------------- */

static const double NU = 0.3;

/* component order xx, yy, zz, xy, yz, xz as axis pairs */
static const int CI[6] = {0, 1, 2, 0, 1, 0};
static const int CJ[6] = {0, 1, 2, 1, 2, 2};
static const int PC[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};

/* number of x (axis 0) or y (axis 1) indices of component c: parity under that reflection */
static int axis_count(int c, int axis)
{
    return (CI[c] == axis) + (CJ[c] == axis);
}

static double maxabs6x6(double S[6][6])
{
    double m = 0.0;
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            m = test_worst(m, fabs(S[i][c]));
    return m;
}

/* Composite tensor Gauss-Legendre of a 6-vector integrand over a box. */
typedef void (*vec_fn)(const double xi[3], void *par, double f[], int nf);

static void gauss_box(const double lo[3], const double hi[3], int split, int n_gl, vec_fn fn,
                      void *par, double *out, int nf)
{
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc((size_t)n_gl);
    ck_assert_ptr_nonnull(t);
    for (int q = 0; q < nf; q++)
        out[q] = 0.0;
    double f[36];
    for (int bz = 0; bz < split; bz++)
        for (int by = 0; by < split; by++)
            for (int bx = 0; bx < split; bx++) {
                const int b[3] = {bx, by, bz};
                double a0[3], a1[3];
                for (int d = 0; d < 3; d++) {
                    const double h = (hi[d] - lo[d]) / split;
                    a0[d] = lo[d] + b[d] * h;
                    a1[d] = a0[d] + h;
                }
                for (int k = 0; k < n_gl; k++) {
                    double zk, wk;
                    gsl_integration_glfixed_point(a0[2], a1[2], (size_t)k, &zk, &wk, t);
                    for (int j = 0; j < n_gl; j++) {
                        double yj, wj;
                        gsl_integration_glfixed_point(a0[1], a1[1], (size_t)j, &yj, &wj, t);
                        for (int i = 0; i < n_gl; i++) {
                            double xi_, wi;
                            gsl_integration_glfixed_point(a0[0], a1[0], (size_t)i, &xi_, &wi, t);
                            const double p[3] = {xi_, yj, zk};
                            fn(p, par, f, nf);
                            const double w = wi * wj * wk;
                            for (int q = 0; q < nf; q++)
                                out[q] += w * f[q];
                        }
                    }
                }
            }
    gsl_integration_glfixed_table_free(t);
}

/* Boussinesq stresses at xi of a unit force at the origin (observation point X = 0). */
static void boussinesq_fn(const double xi[3], void *par, double f[], int nf)
{
    (void)par;
    (void)nf;
    mc_point_stress_p(xi[0], xi[1], xi[2], NU, f);
}

/* D[c] from D_ij = integral sigma^B_ij: doubled shear entries (eigen.h column convention). */
static void brute_D(const double lo[3], const double hi[3], double D[6])
{
    gauss_box(lo, hi, GL_SPLIT_D, N_GL_D, boussinesq_fn, NULL, D, 6);
    for (int c = 3; c < 6; c++)
        D[c] *= 2.0;
}

/* ---- D: surface displacement (theory.md §8.1) -------------------------------------------------- */

START_TEST(test_D_compact_value)
{
    double D[6];
    mc_eigen_surface_uz(-0.5, 0.5, -0.5, 0.5, 0.0, 0.5, NU, D);
    ck_assert_double_eq_tol(D[0], -0.175903, TOL_COMPACT);
    ck_assert_double_eq_tol(D[1], -0.175903, TOL_COMPACT);
    ck_assert_double_eq_tol(D[2], -0.450465, TOL_COMPACT);
    for (int c = 3; c < 6; c++)
        ck_assert_double_le_tol(fabs(D[c]), 0.0, TOL_ROUND);
}
END_TEST

/* Boxes (relative to X) whose closure avoids X, so that the tensor rule sees smooth integrands
 * (boxes with X in their top face: the compact value above and the reciprocity test below). */
static const double D_BOXES[][6] = {
    {0.3, 1.3, -0.4, 0.6, 0.0, 0.7},    /* touches the surface */
    {-0.6, 0.4, -0.3, 0.5, 0.2, 0.9},   /* above X, buried */
    {-1.7, -0.2, 0.25, 1.1, 0.05, 0.4}, /* thin, near the surface */
    {0.4, 0.9, -2.0, -1.2, 1.0, 2.5},   /* deep and off to a side */
};

START_TEST(test_D_brute_force)
{
    const double *b = D_BOXES[_i];
    const double lo[3] = {b[0], b[2], b[4]}, hi[3] = {b[1], b[3], b[5]};
    double D[6], R[6];
    mc_eigen_surface_uz(b[0], b[1], b[2], b[3], b[4], b[5], NU, D);
    brute_D(lo, hi, R);
    double scale = 0.0;
    for (int c = 0; c < 6; c++)
        scale = test_worst(scale, fabs(R[c]));
    for (int c = 0; c < 6; c++)
        ck_assert_msg(fabs(D[c] - R[c]) <= TOL_GAUSS * scale + TOL_ROUND,
                      "box %d comp %d: closed form %.15g, quadrature %.15g", _i, c, D[c], R[c]);
}
END_TEST

START_TEST(test_D_tiny_far_box)
{
    const double c[3] = {1.2, -0.9, 1.1}; /* |c| ~ TINY_D */
    const double h = 0.5 * TINY_H;
    double D[6], s[6];
    mc_eigen_surface_uz(c[0] - h, c[0] + h, c[1] - h, c[1] + h, c[2] - h, c[2] + h, NU, D);
    mc_point_stress_p(c[0], c[1], c[2], NU, s);
    const double V = TINY_H * TINY_H * TINY_H;
    double scale = 0.0;
    for (int k = 0; k < 6; k++)
        scale = test_worst(scale, fabs(s[k]) * V);
    for (int k = 0; k < 6; k++) {
        const double ref = (k < 3 ? 1.0 : 2.0) * V * s[k];
        ck_assert_msg(fabs(D[k] - ref) <= TOL_TINY * scale, "comp %d: %.10g vs %.10g", k, D[k],
                      ref);
    }
}
END_TEST

/* Wide thin layer: u_z per thickness for the dossier's eigenstrain patterns. */
START_TEST(test_D_wide_layer)
{
    double D[6];
    mc_eigen_surface_uz(-LAYER_W, LAYER_W, -LAYER_W, LAYER_W, LAYER_D, LAYER_D + LAYER_T, NU, D);
    const double tol = 2.0 * (1.0 + NU) * LAYER_T * (LAYER_D + LAYER_T) / LAYER_W;
    const double t = LAYER_T;
    ck_assert_double_eq_tol(D[2], -t, tol);                                   /* eps_zz */
    ck_assert_double_eq_tol(D[0] + D[1] + D[2], -2.0 * (1.0 + NU) * t, tol);  /* isotropic */
    ck_assert_double_eq_tol(D[0] + D[1], -(1.0 + 2.0 * NU) * t, tol);         /* (1,1,0) */
    ck_assert_double_eq_tol(D[0] + D[1] - 2.0 * D[2], (1.0 - 2.0 * NU) * t, tol); /* (1,1,-2) */
    ck_assert_double_le_tol(fabs(D[5]), 0.0, tol);                           /* eps_xz */
    ck_assert_double_le_tol(fabs(D[4]), 0.0, tol);
    ck_assert_double_le_tol(fabs(D[3]), 0.0, tol);
}
END_TEST

/* Reflecting the box about X in x (or y) multiplies D[c] by (-1)^(number of x (y) indices). */
START_TEST(test_D_parity)
{
    const double b[6] = {0.3, 1.7, -0.45, 0.85, 0.0, 0.6};
    double D[6], Dx[6], Dy[6], Dt[6];
    mc_eigen_surface_uz(b[0], b[1], b[2], b[3], b[4], b[5], NU, D);
    mc_eigen_surface_uz(-b[1], -b[0], b[2], b[3], b[4], b[5], NU, Dx);
    mc_eigen_surface_uz(b[0], b[1], -b[3], -b[2], b[4], b[5], NU, Dy);
    /* transposing x <-> y swaps xx <-> yy and yz <-> xz */
    mc_eigen_surface_uz(b[2], b[3], b[0], b[1], b[4], b[5], NU, Dt);
    static const int swap[6] = {1, 0, 2, 3, 5, 4};
    for (int c = 0; c < 6; c++) {
        const double sx = axis_count(c, 0) & 1 ? -1.0 : 1.0;
        const double sy = axis_count(c, 1) & 1 ? -1.0 : 1.0;
        ck_assert_double_eq_tol(Dx[c], sx * D[c], TOL_ROUND);
        ck_assert_double_eq_tol(Dy[c], sy * D[c], TOL_ROUND);
        ck_assert_double_eq_tol(Dt[swap[c]], D[c], TOL_ROUND);
        ck_assert(fabs(D[c]) > TOL_ROUND); /* the box is generic: nothing vanishes */
    }
}
END_TEST

/* X on the line of a top-face edge (corner terms with x = z = 0, y < 0) and above a vertical edge
 * of a buried box: finite, and continuous with X moved slightly off the line either way. */
START_TEST(test_D_edge_lines)
{
    static const double boxes[2][6] = {{0.0, 1.0, -1.5, -0.5, 0.0, 0.5},
                                       {0.0, 1.0, 0.0, 1.0, 0.2, 0.5}};
    for (int b = 0; b < 2; b++) {
        const double *x = boxes[b];
        double D[6], Dp[6], Dm[6];
        mc_eigen_surface_uz(x[0], x[1], x[2], x[3], x[4], x[5], NU, D);
        mc_eigen_surface_uz(x[0] + EDGE_DX, x[1] + EDGE_DX, x[2] + EDGE_DX, x[3] + EDGE_DX, x[4],
                            x[5], NU, Dp);
        mc_eigen_surface_uz(x[0] - EDGE_DX, x[1] - EDGE_DX, x[2] - EDGE_DX, x[3] - EDGE_DX, x[4],
                            x[5], NU, Dm);
        for (int c = 0; c < 6; c++) {
            ck_assert(isfinite(D[c]));
            ck_assert_double_eq_tol(Dp[c], D[c], TOL_EDGE);
            ck_assert_double_eq_tol(Dm[c], D[c], TOL_EDGE);
        }
    }
}
END_TEST

/* ---- S1: Kelvin quadrature (Mura 1987: u_i,l = -integral G_ij,kl(x - x') sigma*_jk dV') --- */

typedef struct {
    double x[3];
} kelvin_par;

/* 2G = 1 units: sigma*_jk = C:E of the unit column E, c_K = 1/(16 pi G (1-nu)). The 36 values
 * f[6 c + o] are the strain components o (tensor) for the column c. */
static void kelvin_fn(const double xi[3], void *par, double f[], int nf)
{
    (void)nf;
    const kelvin_par *kp = par;
    const double a[3] = {kp->x[0] - xi[0], kp->x[1] - xi[1], kp->x[2] - xi[2]};
    const double r2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    const double r = sqrt(r2);
    const double i3 = 1.0 / (r2 * r), i5 = i3 / r2, i7 = i5 / r2;
    const double cK = 1.0 / (8.0 * M_PI * (1.0 - NU));
    double G4[3][3][3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++) {
                    const double dij = i == j, dik = i == k, dil = i == l, djk = j == k,
                                 djl = j == l, dkl = k == l;
                    double v = (3.0 - 4.0 * NU) * dij * (3.0 * a[k] * a[l] * i5 - dkl * i3);
                    v += (dik * djl + dil * djk) * i3;
                    v -= 3.0 * (dik * a[j] * a[l] + djk * a[i] * a[l] + dil * a[j] * a[k] +
                                djl * a[i] * a[k] + dkl * a[i] * a[j]) * i5;
                    v += 15.0 * a[i] * a[j] * a[k] * a[l] * i7;
                    G4[i][j][k][l] = cK * v;
                }
    const double lam = NU / (1.0 - 2.0 * NU);
    for (int c = 0; c < 6; c++) {
        double E[3][3] = {{0}};
        E[CI[c]][CJ[c]] = E[CJ[c]][CI[c]] = 1.0;
        const double tr = E[0][0] + E[1][1] + E[2][2];
        double sg[3][3];
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                sg[j][k] = lam * tr * (j == k) + E[j][k];
        double g[3][3]; /* u_i,l */
        for (int i = 0; i < 3; i++)
            for (int l = 0; l < 3; l++) {
                double v = 0.0;
                for (int j = 0; j < 3; j++)
                    for (int k = 0; k < 3; k++)
                        v -= G4[i][j][k][l] * sg[j][k];
                g[i][l] = v;
            }
        for (int o = 0; o < 6; o++)
            f[6 * c + o] = 0.5 * (g[CI[o]][CJ[o]] + g[CJ[o]][CI[o]]);
    }
}

/* Exterior points: S1 from the corner sums equals C:(quadrature strain) / 2G. */
static const double K_POINTS[][3] = {
    {1.3, 0.4, 0.9}, {-0.2, 0.1, -0.35}, {0.1, -0.95, 0.45}, {-1.0, 0.8, 1.4}};

START_TEST(test_S1_kelvin_quadrature)
{
    const double hx = 0.5, hy = 0.4, z1 = 0.2, z2 = 0.6;
    kelvin_par kp = {{K_POINTS[_i][0], K_POINTS[_i][1], K_POINTS[_i][2]}};
    const double lo[3] = {-hx, -hy, z1}, hi[3] = {hx, hy, z2};
    double e[36], S[6][6];
    gauss_box(lo, hi, GL_SPLIT_K, N_GL_K, kelvin_fn, &kp, e, 36);
    mc_eigen_stress1(kp.x[0], kp.x[1], kp.x[2], hx, hy, z1, z2, NU, S);
    const double lam = NU / (1.0 - 2.0 * NU);
    const double scale = maxabs6x6(S);
    for (int c = 0; c < 6; c++) {
        const double tr = e[6 * c] + e[6 * c + 1] + e[6 * c + 2];
        for (int o = 0; o < 6; o++) {
            const double ref = e[6 * c + o] + (o < 3 ? lam * tr : 0.0);
            ck_assert_msg(fabs(S[o][c] - ref) <= TOL_GAUSS * scale + TOL_ROUND,
                          "point %d S[%d][%d] = %.15g, quadrature %.15g", _i, o, c, S[o][c], ref);
        }
    }
}
END_TEST

/* Interior dilatation of an isotropic eigenstrain: eps_kk = (1+nu)/(1-nu) (Mura 1987), in an
 * infinite space and also with the mirror term (harmonic in z > 0 for this load). */
START_TEST(test_S_interior_dilatation)
{
    const double pts[][3] = {{0.1, 0.2, 0.4}, {-0.45, 0.3, 0.21}, {0.0, -0.49, 0.69}};
    const double hx = 0.5, hy = 0.5, z1 = 0.2, z2 = 0.7;
    for (int p = 0; p < 3; p++)
        for (int mirror = 0; mirror < 2; mirror++) {
            double S[6][6];
            if (mirror)
                mc_eigen_stress12(pts[p][0], pts[p][1], pts[p][2], hx, hy, z1, z2, NU, S);
            else
                mc_eigen_stress1(pts[p][0], pts[p][1], pts[p][2], hx, hy, z1, z2, NU, S);
            double sk = 0.0; /* sigma_kk / 2G for eps* = I */
            for (int i = 0; i < 3; i++)
                for (int c = 0; c < 3; c++)
                    sk += S[i][c];
            /* sigma_kk / 2G = (1+nu)/(1-2nu) (eps_kk - 3) */
            const double ekk = sk * (1.0 - 2.0 * NU) / (1.0 + NU) + 3.0;
            ck_assert_double_eq_tol(ekk, (1.0 + NU) / (1.0 - NU), TOL_ROUND);
        }
}
END_TEST

/* ---- S1 + S2 --------------------------------------------------------------------------------- */

/* sigma_xz = sigma_yz = 0 on z = 0, and szz12 equals the zz row there; cell-centred points and a
 * top-layer cuboid (z1 = 0), plus a buried one. */
START_TEST(test_S12_free_surface_shear)
{
    const double z1s[2] = {0.0, 0.3};
    for (int b = 0; b < 2; b++)
        for (int j = -3; j <= 3; j++)
            for (int i = -3; i <= 3; i++) {
                const double x = i + 0.0, y = 0.75 * j; /* faces at +-0.5, +-0.375 */
                double S[6][6], s[6];
                mc_eigen_stress12(x, y, 0.0, 0.5, 0.375, z1s[b], z1s[b] + 1.0, NU, S);
                mc_eigen_surface_szz12(x, y, 0.5, 0.375, z1s[b], z1s[b] + 1.0, NU, s);
                const double scale = fmax(maxabs6x6(S), 1.0);
                for (int c = 0; c < 6; c++) {
                    ck_assert_double_le_tol(fabs(S[4][c]), 0.0, TOL_ROUND * scale);
                    ck_assert_double_le_tol(fabs(S[5][c]), 0.0, TOL_ROUND * scale);
                    ck_assert_double_eq_tol(s[c], S[2][c], TOL_ROUND * scale);
                }
            }
}
END_TEST

/* d/dx_j of S[.][.] by the 4th-order central stencil */
static void fd_grad(double x, double y, double z, int axis, double hx, double hy, double z1,
                    double z2, double G[6][6])
{
    static const double w[4] = {1.0 / 12.0, -8.0 / 12.0, 8.0 / 12.0, -1.0 / 12.0};
    static const double off[4] = {-2.0, -1.0, 1.0, 2.0};
    for (int o = 0; o < 6; o++)
        for (int c = 0; c < 6; c++)
            G[o][c] = 0.0;
    for (int m = 0; m < 4; m++) {
        double p[3] = {x, y, z};
        p[axis] += off[m] * FD_H;
        double S[6][6];
        mc_eigen_stress12(p[0], p[1], p[2], hx, hy, z1, z2, NU, S);
        for (int o = 0; o < 6; o++)
            for (int c = 0; c < 6; c++)
                G[o][c] += w[m] * S[o][c] / FD_H;
    }
}

/* Equilibrium sigma_ij,j = 0 inside (uniform eigenstrain: C:eps* is constant) and outside. */
START_TEST(test_S12_equilibrium)
{
    const double pts[][3] = {{0.1, -0.15, 0.45}, {0.3, 0.2, 0.3},  {0.9, 0.4, 0.5},
                             {-0.2, 1.1, 1.3},   {0.05, 0.1, 0.1}, {-1.2, -0.7, 0.2}};
    const double hx = 0.5, hy = 0.4, z1 = 0.2, z2 = 0.8;
    for (int p = 0; p < 6; p++) {
        double G[3][6][6];
        for (int a = 0; a < 3; a++)
            fd_grad(pts[p][0], pts[p][1], pts[p][2], a, hx, hy, z1, z2, G[a]);
        double scale = 0.0;
        for (int a = 0; a < 3; a++)
            scale = test_worst(scale, maxabs6x6(G[a]));
        for (int c = 0; c < 6; c++)
            for (int i = 0; i < 3; i++) {
                double div = 0.0;
                for (int j = 0; j < 3; j++)
                    div += G[j][PC[i][j]][c];
                ck_assert_msg(fabs(div) <= TOL_FD * scale, "point %d col %d row %d: div %.3g",
                              p, c, i, div);
            }
    }
}
END_TEST

/* Jump of S across a face with normal e_m (inside minus outside): displacement continuity and
 * traction continuity give [eps] = sym(l (x) n) with l_i = 2 E_im (i != m) and
 * l_m = (nu tr E + (1 - 2nu) E_mm)/(1 - nu);
 * [sigma]/2G = lam ([eps_kk] - tr E) delta + [eps] - E. */
static void expected_jump(int m, double J[6][6])
{
    const double lam = NU / (1.0 - 2.0 * NU);
    for (int c = 0; c < 6; c++) {
        double E[3][3] = {{0}};
        E[CI[c]][CJ[c]] = E[CJ[c]][CI[c]] = 1.0;
        const double tr = E[0][0] + E[1][1] + E[2][2];
        double l[3];
        for (int i = 0; i < 3; i++)
            l[i] = 2.0 * E[i][m];
        l[m] = (NU * tr + (1.0 - 2.0 * NU) * E[m][m]) / (1.0 - NU);
        double de[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                de[i][j] = 0.5 * (l[i] * (j == m) + l[j] * (i == m));
        const double dtr = de[0][0] + de[1][1] + de[2][2];
        for (int o = 0; o < 6; o++)
            J[o][c] = de[CI[o]][CJ[o]] - E[CI[o]][CJ[o]] + (o < 3 ? lam * (dtr - tr) : 0.0);
    }
}

START_TEST(test_S12_face_jumps)
{
    const double hx = 0.5, hy = 0.4, z1 = 0.2, z2 = 0.8;
    /* a point on each face family: bottom (z = z2, normal z), top (z = z1), side x = -hx */
    const double pts[][3] = {{0.1, -0.15, z2}, {-0.2, 0.1, z1}, {-hx, 0.1, 0.5}};
    const int axis[3] = {2, 2, 0};
    const int lower[3] = {0, 1, 1}; /* the face belongs to the cuboid when it is a lower face */
    for (int p = 0; p < 3; p++) {
        double Sin[6][6], Sout[6][6], Sface[6][6], J[6][6];
        double pi_[3] = {pts[p][0], pts[p][1], pts[p][2]};
        double po[3] = {pts[p][0], pts[p][1], pts[p][2]};
        const double dir = lower[p] ? 1.0 : -1.0; /* into the cuboid */
        pi_[axis[p]] += dir * JUMP_DZ;
        po[axis[p]] -= dir * JUMP_DZ;
        mc_eigen_stress12(pi_[0], pi_[1], pi_[2], hx, hy, z1, z2, NU, Sin);
        mc_eigen_stress12(po[0], po[1], po[2], hx, hy, z1, z2, NU, Sout);
        mc_eigen_stress12(pts[p][0], pts[p][1], pts[p][2], hx, hy, z1, z2, NU, Sface);
        expected_jump(axis[p], J);
        for (int o = 0; o < 6; o++)
            for (int c = 0; c < 6; c++) {
                ck_assert_msg(fabs(Sin[o][c] - Sout[o][c] - J[o][c]) <= TOL_JUMP,
                              "face %d S[%d][%d]: jump %.12g, expected %.12g", p, o, c,
                              Sin[o][c] - Sout[o][c], J[o][c]);
                /* the face point takes the value of its side (eigen.h) */
                const double side = lower[p] ? Sin[o][c] : Sout[o][c];
                ck_assert_double_eq_tol(Sface[o][c], side, TOL_JUMP);
            }
    }
    /* the traction rows really are continuous and the others really jump */
    double J[6][6];
    expected_jump(2, J);
    ck_assert_double_eq_tol(J[5][5], 0.0, TOL_ROUND);
    ck_assert_double_eq_tol(J[2][2], 0.0, TOL_ROUND);
    ck_assert_double_eq_tol(J[0][0], -1.0 / (1.0 - NU), TOL_ROUND);
}
END_TEST

/* Reflection of the field point about the cuboid's centre line in x (y) multiplies S[o][c] by
 * (-1)^(x (y) indices of o and c); transposing x <-> y permutes rows and columns. */
START_TEST(test_S12_parity)
{
    const double p[3] = {0.7, -0.35, 0.45}, hx = 0.5, hy = 0.3, z1 = 0.0, z2 = 0.6;
    double S[6][6], Sx[6][6], Sy[6][6], St[6][6];
    mc_eigen_stress12(p[0], p[1], p[2], hx, hy, z1, z2, NU, S);
    mc_eigen_stress12(-p[0], p[1], p[2], hx, hy, z1, z2, NU, Sx);
    mc_eigen_stress12(p[0], -p[1], p[2], hx, hy, z1, z2, NU, Sy);
    mc_eigen_stress12(p[1], p[0], p[2], hy, hx, z1, z2, NU, St);
    static const int swap[6] = {1, 0, 2, 3, 5, 4};
    const double scale = maxabs6x6(S);
    for (int o = 0; o < 6; o++)
        for (int c = 0; c < 6; c++) {
            const double sx = (axis_count(o, 0) + axis_count(c, 0)) & 1 ? -1.0 : 1.0;
            const double sy = (axis_count(o, 1) + axis_count(c, 1)) & 1 ? -1.0 : 1.0;
            ck_assert_double_eq_tol(Sx[o][c], sx * S[o][c], TOL_ROUND * scale);
            ck_assert_double_eq_tol(Sy[o][c], sy * S[o][c], TOL_ROUND * scale);
            ck_assert_double_eq_tol(St[swap[o]][swap[c]], S[o][c], TOL_ROUND * scale);
        }
}
END_TEST

/* ---- reciprocity: image-method u_z (theory.md §8.2, term S3) equals D (§2.2) ------------------ */

/* u_z(X) = (1 - nu^2)/(pi E) integral p3 / r dA with p3 = 2G s . eps*, E = 2G (1 + nu):
 * u_z = (1 - nu)/pi integral s dr dtheta in polar coordinates about X (the 1/r cancels).
 * p3 is analytic between the lines of the cuboid's vertical faces, where it is log-singular or
 * jumps (top-layer cuboid) or sharply peaked (buried); rays through its corners make the angular
 * integrand singular likewise. So both integrals are split at those points and each piece is done
 * by tanh-sinh quadrature (Takahasi & Mori 1974), whose nodes crowd double-exponentially towards
 * the ends: step halving until two levels agree to the asked accuracy, all six columns at once.
 * Along a ray s = a3/r^3 + a4/r^4 + ... (multipole expansion of a finite source); beyond RECIP_RT
 * the corner sums' absolute round-off (~1e-15) would swamp s, so the tail is taken from the two
 * leading terms fitted at RECIP_RT and 2 RECIP_RT: its error is O(a5/RECIP_RT^4) ~ 1e-13. */
#define RECIP_RT 1000.0
/* Absolute accuracy asked of the quadrature and accepted for u_z (D is 0.01-0.2 here). */
#define RECIP_ACC 1e-10
#define TS_TMAX 3.2      /* t range of the tanh-sinh rule: weights < 1e-20 beyond */
#define TS_MAXLEVEL 8    /* finest step 2^-8 */
#define TS_GAP 1e-15     /* nodes closer than this (relative) to an end are skipped: O(1e-13) */

typedef void (*vec1_fn)(double t, void *par, double out[6]);

/* Integral of f over [a, b] to absolute accuracy tol (difference of successive levels). */
static void ts_integrate(vec1_fn f, void *par, double a, double b, double tol, double out[6])
{
    const double half = 0.5 * (b - a);
    const double gap = TS_GAP * fmax(1.0, fmax(fabs(a), fabs(b)));
    double sum[6] = {0.0}, prev[6] = {0.0};
    for (int level = 0; level <= TS_MAXLEVEL; level++) {
        const double h = ldexp(1.0, -level);
        /* level 0 takes every node j h, later levels only the new (odd) ones */
        const int nmax = (int)(TS_TMAX / h);
        for (int j = -nmax; j <= nmax; j++) {
            if (level > 0 && (j & 1) == 0)
                continue;
            const double t = j * h;
            const double sh = M_PI_2 * sinh(t);
            const double ch = cosh(sh);
            const double w = half * M_PI_2 * cosh(t) / (ch * ch);
            /* distance to the nearer end without cancellation: (b - a)/(1 + exp(2 |sh|)) */
            const double d = (b - a) / (1.0 + exp(2.0 * fabs(sh)));
            if (d < gap)
                continue;
            const double x = t < 0.0 ? a + d : b - d;
            double v[6];
            f(x, par, v);
            for (int c = 0; c < 6; c++)
                sum[c] += w * v[c];
        }
        double err = 0.0, cur[6];
        for (int c = 0; c < 6; c++) {
            cur[c] = sum[c] * h;
            err = test_worst(err, fabs(cur[c] - prev[c]));
            prev[c] = cur[c];
        }
        if (level >= 3 && err <= tol)
            break;
    }
    for (int c = 0; c < 6; c++)
        out[c] = prev[c];
}

/* Sum of ts_integrate over the pieces between the sorted breakpoints pts[0..n-1]. */
static void ts_pieces(vec1_fn f, void *par, const double *pts, int n, double tol, double out[6])
{
    for (int c = 0; c < 6; c++)
        out[c] = 0.0;
    for (int k = 0; k + 1 < n; k++) {
        if (pts[k + 1] <= pts[k])
            continue;
        double v[6];
        ts_integrate(f, par, pts[k], pts[k + 1], tol / (n - 1), v);
        for (int c = 0; c < 6; c++)
            out[c] += v[c];
    }
}

typedef struct {
    double cx, cy, hx, hy, z1, z2; /* box centre relative to X, half-widths, depths */
    double c, s;                   /* direction of the current ray */
    double tol;                    /* accuracy of a ray integral */
} recip_par;

static void recip_s(double r, void *vp, double out[6])
{
    const recip_par *p = vp;
    mc_eigen_surface_szz12(r * p->c - p->cx, r * p->s - p->cy, p->hx, p->hy, p->z1, p->z2, NU,
                           out);
}


static int cmp_double(const void *a, const void *b)
{
    const double u = *(const double *)a, v = *(const double *)b;
    return (u > v) - (u < v);
}

/* Radial integral along the ray theta, breakpoints where the ray crosses the lines of the
 * cuboid's vertical faces, plus the fitted tail. */
static void recip_theta(double th, void *vp, double out[6])
{
    recip_par *p = vp;
    p->c = cos(th);
    p->s = sin(th);
    double pts[6];
    int n = 0;
    pts[n++] = 0.0;
    const double lines[4] = {p->cx - p->hx, p->cx + p->hx, p->cy - p->hy, p->cy + p->hy};
    for (int k = 0; k < 4; k++) {
        const double d = k < 2 ? p->c : p->s;
        if (d != 0.0) {
            const double r = lines[k] / d;
            if (r > 0.0 && r < RECIP_RT)
                pts[n++] = r;
        }
    }
    pts[n++] = RECIP_RT;
    qsort(pts, (size_t)n, sizeof pts[0], cmp_double);
    ts_pieces(recip_s, p, pts, n, p->tol, out);
    const double R = RECIP_RT;
    double f1[6], f2[6];
    recip_s(R, p, f1);
    recip_s(2.0 * R, p, f2);
    for (int c = 0; c < 6; c++) {
        const double g1 = f1[c] * R * R * R, g2 = f2[c] * 8.0 * R * R * R; /* r^3 s = a3 + a4/r */
        const double a4 = 2.0 * R * (g1 - g2), a3 = g1 - a4 / R;
        out[c] += a3 / (2.0 * R * R) + a4 / (3.0 * R * R * R);
    }
}

/* box centre (cx, cy) relative to X, half-widths, depth range */
static const double R_BOXES[][6] = {
    {0.3, -0.2, 0.5, 0.4, 0.25, 0.9}, /* buried, above X */
    {1.1, 0.6, 0.5, 0.5, 0.1, 0.6},   /* buried, to a side */
    {0.8, -0.3, 0.5, 0.5, 0.0, 0.5},  /* top layer, to a side */
    {0.2, 0.1, 0.5, 0.5, 0.0, 0.5},   /* top layer, X under its top face */
};

START_TEST(test_reciprocity)
{
    const double *b = R_BOXES[_i];
    const double acc = RECIP_ACC;
    double D[6];
    mc_eigen_surface_uz(b[0] - b[2], b[0] + b[2], b[1] - b[3], b[1] + b[3], b[4], b[5], NU, D);
    /* rays to acc/(4 pi) (their error integrates to acc/2 over 2 pi), the angle to acc/4, and
     * u_z = (1 - nu)/pi times that */
    recip_par p = {b[0], b[1], b[2], b[3], b[4], b[5], 1.0, 0.0, 0.25 * acc / (2.0 * M_PI)};
    /* the outer integrand has kinks where a ray grazes a corner of the cuboid */
    double th[6];
    int n = 0;
    th[n++] = 0.0;
    for (int k = 0; k < 4; k++) {
        double a = atan2(b[1] + (k & 2 ? b[3] : -b[3]), b[0] + (k & 1 ? b[2] : -b[2]));
        th[n++] = a < 0.0 ? a + 2.0 * M_PI : a;
    }
    th[n++] = 2.0 * M_PI;
    qsort(th, (size_t)n, sizeof th[0], cmp_double);
    double v[6];
    ts_pieces(recip_theta, &p, th, n, 0.25 * acc, v);
    for (int c = 0; c < 6; c++) {
        const double uz = (1.0 - NU) / M_PI * v[c];
        ck_assert_msg(fabs(uz - D[c]) <= acc,
                      "box %d col %d: image method %.15g, reciprocity %.15g", _i, c, uz, D[c]);
    }
}
END_TEST

/* ---- the cell-centred lattice ---------------------------------------------------------------- */

/* Every kernel is finite on the lattice the operators use: field points at cell centres, faces at
 * half-cell offsets, top layer z1 = 0, surface z = 0 (dx != dy, dz). */
START_TEST(test_lattice_finite)
{
    const double dx = 1.0, dy = 0.7, dz = 0.45;
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++)
            for (int j = -4; j <= 4; j++)
                for (int i = -4; i <= 4; i++) {
                    const double x = i * dx, y = j * dy;
                    const double z1 = k * dz, z2 = z1 + dz;
                    double D[6], s[6], S[6][6];
                    mc_eigen_surface_uz(x - 0.5 * dx, x + 0.5 * dx, y - 0.5 * dy, y + 0.5 * dy, z1,
                                        z2, NU, D);
                    mc_eigen_surface_szz12(x, y, 0.5 * dx, 0.5 * dy, z1, z2, NU, s);
                    mc_eigen_stress12(x, y, (l + 0.5) * dz, 0.5 * dx, 0.5 * dy, z1, z2, NU, S);
                    for (int c = 0; c < 6; c++) {
                        ck_assert(isfinite(D[c]) && isfinite(s[c]));
                        for (int o = 0; o < 6; o++)
                            ck_assert(isfinite(S[o][c]));
                    }
                }
}
END_TEST

Suite *suite_eigen_kernels(void);
Suite *suite_eigen_kernels(void)
{
    Suite *s = suite_create("eigen_kernels");
    TCase *d = tcase_create("surface_uz");
    tcase_add_test(d, test_D_compact_value);
    tcase_add_loop_test(d, test_D_brute_force, 0, (int)(sizeof D_BOXES / sizeof D_BOXES[0]));
    tcase_add_test(d, test_D_tiny_far_box);
    tcase_add_test(d, test_D_wide_layer);
    tcase_add_test(d, test_D_parity);
    tcase_add_test(d, test_D_edge_lines);
    tcase_set_timeout(d, 60);
    suite_add_tcase(s, d);
    TCase *t = tcase_create("stress");
    tcase_add_loop_test(t, test_S1_kelvin_quadrature, 0,
                        (int)(sizeof K_POINTS / sizeof K_POINTS[0]));
    tcase_add_test(t, test_S_interior_dilatation);
    tcase_add_test(t, test_S12_free_surface_shear);
    tcase_add_test(t, test_S12_equilibrium);
    tcase_add_test(t, test_S12_face_jumps);
    tcase_add_test(t, test_S12_parity);
    tcase_set_timeout(t, 60);
    suite_add_tcase(s, t);
    TCase *r = tcase_create("reciprocity");
    tcase_add_loop_test(r, test_reciprocity, 0, (int)(sizeof R_BOXES / sizeof R_BOXES[0]));
    tcase_add_test(r, test_lattice_finite);
    tcase_set_timeout(r, 120);
    suite_add_tcase(s, r);
    return s;
}
