/* test_eigen_bar.c - the bar limit (plane strain) of the eigenstrain kernels and the strip limit of
 * Love's pressure stresses (kernels/eigen.h mc_eigen_*_bar, kernels/kernel.h mc_strip_stress_p;
 * docs/theory.md §8.5) against their independently tested cuboid and rectangle counterparts
 * evaluated at a large y half-length L: the difference must shrink at the rate of the missing
 * tail (stress of a cuboid ~ 1/y^3 beyond L: O(L^-2); surface displacement and Love's stresses
 * ~ 1/y^2: O(L^-1)), which a wrong limit (an error d independent of L) cannot do once d exceeds
 * a tenth of the tail; and the bar's surface displacement against the 2-D reciprocity with
 * Flamant's line load. Lengths in units of the cell (hx = 1/2). */
#include <float.h>
#include <math.h>

#include "kernels/eigen.h"
#include "kernels/kernel.h"
#include "test_util.h"

static const double NU = 0.3;

/* Field points (x, z) relative to the bar: inside, above, beside, below, far; none on a face
 * plane's edge line. */
static const double PTS[][2] = {{0.0, 0.5},  {1.0, 0.5}, {2.5, 1.3}, {-3.0, 0.2},
                                {0.3, 2.7},  {5.0, 4.0}, {0.2, 0.9}, {-0.7, 0.0}};
#define NPTS ((int)(sizeof PTS / sizeof PTS[0]))
/* the bar's cross-section: |x'| <= 1/2, Z1 <= z' <= Z2 (buried), and a top-layer bar (z' from 0) */
#define HX 0.5
#define Z1 0.4
#define Z2 1.1

/* Rates: the relative difference d(L) = |cuboid(L) - bar| / |bar|max at L and 10 L must fall by
 * the tail's factor within RATE_SLACK (the next term of the expansion is (h/L) times smaller:
 * at L >= 1000 cells a few per cent at most), and be at most TOL_* at the larger L (bounds on
 * the tails of these points; measured maxima: stress 1.2e-6 at L = 1e4, displacement 3.7e-5 at
 * 1e5, Love 7.1e-5 at b = 1e5).
 * The cuboid formulas' round-off grows with their largest corner terms, ~ L ln L for D (eigen.h):
 * eps 1e6 = 2e-10 at L = 1e5, far below the differences checked. */
#define RATE_SLACK 0.1
#define L_STRESS 1e3
#define L_DISP 1e4
#define TOL_STRESS 1e-5
#define TOL_DISP 1e-4
#define TOL_LOVE 1e-4

static double maxabs66(double S[6][6])
{
    double m = 0.0;
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            m = test_worst(m, fabs(S[i][c]));
    return m;
}

static double diff66(double A[6][6], double B[6][6])
{
    double m = 0.0;
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            m = test_worst(m, fabs(A[i][c] - B[i][c]));
    return m;
}

static double diff6(const double *a, const double *b)
{
    double m = 0.0;
    for (int c = 0; c < 6; c++)
        m = test_worst(m, fabs(a[c] - b[c]));
    return m;
}

static double maxabs6(const double *a)
{
    double m = 0.0;
    for (int c = 0; c < 6; c++)
        m = test_worst(m, fabs(a[c]));
    return m;
}

/* d(L) / d(10 L) within RATE_SLACK of 10^order, and d(10 L) <= tol */
static void check_rate(const char *what, int p, double d1, double d2, int order, double tol)
{
    const double want = pow(10.0, order), ratio = d1 / d2;
    ck_assert_msg(fabs(ratio / want - 1.0) <= RATE_SLACK,
                  "%s point %d: d(L)/d(10L) = %.4g (d = %.3g, %.3g), want %g", what, p, ratio, d1,
                  d2, want);
    ck_assert_msg(d2 <= tol, "%s point %d: relative difference %.3g at 10 L > %.2g", what, p, d2,
                  tol);
}

START_TEST(test_bar_stress_limit)
{
    const double x = PTS[_i][0], z = PTS[_i][1];
    double B[6][6], B1[6][6], C[6][6];
    /* S1 + S2 of a buried bar, S1 alone (any z) */
    mc_eigen_stress12_bar(x, z, HX, Z1, Z2, NU, B);
    mc_eigen_stress1_bar(x, z - 0.6, HX, Z1, Z2, NU, B1);
    double d[2], d1[2];
    for (int n = 0; n < 2; n++) {
        const double L = L_STRESS * pow(10.0, n);
        mc_eigen_stress12(x, 0.0, z, HX, L, Z1, Z2, NU, C);
        d[n] = diff66(C, B) / maxabs66(B);
        mc_eigen_stress1(x, 0.0, z - 0.6, HX, L, Z1, Z2, NU, C);
        d1[n] = diff66(C, B1) / maxabs66(B1);
    }
    check_rate("S12", _i, d[0], d[1], 2, TOL_STRESS);
    check_rate("S1", _i, d1[0], d1[1], 2, TOL_STRESS);
}
END_TEST

START_TEST(test_bar_disp_limit)
{
    const double x = PTS[_i][0], z1 = PTS[_i][1], z2 = z1 + 0.7;
    double B[6], C[6], Bt[6], Ct[6];
    mc_eigen_surface_uz_bar(x - HX, x + HX, z1, z2, NU, B);
    mc_eigen_surface_uz_bar(x - HX, x + HX, 0.0, z2, NU, Bt); /* a top-layer bar */
    double d[2], dt[2];
    for (int n = 0; n < 2; n++) {
        const double L = L_DISP * pow(10.0, n);
        mc_eigen_surface_uz(x - HX, x + HX, -L, L, z1, z2, NU, C);
        d[n] = diff6(C, B) / maxabs6(B);
        mc_eigen_surface_uz(x - HX, x + HX, -L, L, 0.0, z2, NU, Ct);
        dt[n] = diff6(Ct, Bt) / maxabs6(Bt);
    }
    check_rate("D", _i, d[0], d[1], 1, TOL_DISP);
    check_rate("D top", _i, dt[0], dt[1], 1, TOL_DISP);
    /* the columns odd in y vanish exactly */
    ck_assert(B[3] == 0.0 && B[4] == 0.0);
}
END_TEST

START_TEST(test_bar_p3_and_strip_limit)
{
    const double x = PTS[_i][0], z = fabs(PTS[_i][1]) + 0.05;
    double b[6], c[6], d[2], dl[2];
    mc_eigen_surface_szz12_bar(x, HX, 0.0, Z2, NU, b); /* a top-layer bar seen from z = 0 */
    double sb[6], sc[6];
    mc_strip_stress_p(x, z, HX, NU, sb);
    for (int n = 0; n < 2; n++) {
        const double L = L_STRESS * pow(10.0, n);
        mc_eigen_surface_szz12(x, 0.0, HX, L, 0.0, Z2, NU, c);
        d[n] = diff6(c, b) / maxabs6(b);
        mc_rect_stress_p(x, 0.0, z, HX, 10.0 * L, NU, sc);
        dl[n] = diff6(sc, sb) / maxabs6(sb);
    }
    check_rate("p3", _i, d[0], d[1], 2, TOL_STRESS);
    check_rate("strip", _i, dl[0], dl[1], 1, TOL_LOVE);
    /* plane strain: sigma_yy = nu (sigma_xx + sigma_zz) under a surface load */
    ck_assert_double_eq_tol(sb[MC_SYY], NU * (sb[MC_SXX] + sb[MC_SZZ]), 64 * DBL_EPSILON);
}
END_TEST

/* An independent closed form of the bar's surface displacement: reciprocity with the Flamant line
 * load directly in 2-D (docs/theory.md §8.5; Johnson 1985 ch. 2):
 *   D_ij = -(2/pi) sum over corners s_x s_z G_ij(x_c - X, z_c), s = +1 at upper bounds,
 *   G_xx = (z/2) atan(x/z), G_zz = (x/2) ln(x^2 + z^2) + (z/2) atan(x/z), G_xz = (x/2) atan(z/x),
 *   D_yy = nu (D_xx + D_zz) (plane strain), column xz = 2 D_xz.
 * The two forms share no code (the bar limit comes from the 3-D corner functions): round-off of
 * O(1) corner terms (measured 3e-16). */
#define TOL_FLAMANT (64.0 * DBL_EPSILON)

static void flamant_G(double x, double z, double g[3])
{
    g[0] = 0.5 * z * atan2(x, z);
    g[1] = (x != 0.0 ? 0.5 * x * log(x * x + z * z) : 0.0) + 0.5 * z * atan2(x, z);
    g[2] = x != 0.0 ? 0.5 * x * atan(z / x) : 0.0;
}

START_TEST(test_bar_disp_flamant)
{
    const double x = PTS[_i][0], z1 = PTS[_i][1], z2 = z1 + 0.7;
    const double xs[2] = {x - HX, x + HX}, zs[2] = {z1, z2};
    double B[6], d[3] = {0.0, 0.0, 0.0};
    mc_eigen_surface_uz_bar(xs[0], xs[1], z1, z2, NU, B);
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
            double g[3];
            flamant_G(xs[i], zs[k], g);
            const double sgn = (i ? 1.0 : -1.0) * (k ? 1.0 : -1.0);
            for (int q = 0; q < 3; q++)
                d[q] += -2.0 / M_PI * sgn * g[q];
        }
    const double want[6] = {d[0], NU * (d[0] + d[1]), d[1], 0.0, 0.0, 2.0 * d[2]};
    for (int c = 0; c < 6; c++)
        ck_assert_msg(fabs(B[c] - want[c]) <= TOL_FLAMANT, "point %d column %d: bar %.15g, "
                      "Flamant %.15g", _i, c, B[c], want[c]);
}
END_TEST

Suite *suite_eigen_bar(void);
Suite *suite_eigen_bar(void)
{
    Suite *s = suite_create("eigen_bar");
    TCase *t = tcase_create("limits");
    tcase_add_loop_test(t, test_bar_stress_limit, 0, NPTS);
    tcase_add_loop_test(t, test_bar_disp_limit, 0, NPTS);
    tcase_add_loop_test(t, test_bar_disp_flamant, 0, NPTS);
    tcase_add_loop_test(t, test_bar_p3_and_strip_limit, 0, NPTS);
    suite_add_tcase(s, t);
    return s;
}
