/* test_plastic_material.c - hardening laws and the J2 radial return against closed-form material
 * paths (uniaxial stress, pure shear), return-mapping identities, refinement and input checks.
 * Physics: theory.md §7.1-§7.3; table pl_material_laws.csv. */
#include <check.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "plastic/hardening.h"
#include "plastic/return_map.h"
#include "test_util.h"

/* Closed-form paths: sums over <= 200 steps of rounded increments and a mixed-control solve to a
 * few eps; the worst-case bound 200 eps = 4e-14, so 1e-12 has a 25x margin. */
#define TOL_PATH 1e-12
/* Identities of one return (consistency, normality, tr deps_p = 0, |deps_p| = dp), per unit of
 * the largest stress component: the solve stops at 4 eps q_tr and each identity adds a few
 * roundings of O(|sigma|) terms; 64 eps covers both. */
#define TOL_RETURN (64.0 * DBL_EPSILON)
/* The dossier prints sigma_y in whole MPa: the exact value is within half a unit. */
#define TOL_SWIFT_MPA 0.5
/* Central differences of sigma_y with step 1e-4 (p + eps0): truncation (h/(p+eps0))^2 ~ 1e-8 of
 * H times an O(1) factor, round-off eps sigma/(h H) ~ 1e-10; 1e-6 leaves room for both. */
#define TOL_FD 1e-6
#define E_MOD 210e9 /* AISI 52100-like steel (theory.md §7.2) */
#define NU 0.3
#define MPA 1e6

enum { LAW_PERFECT, LAW_LINEAR, LAW_SWIFT, LAW_TABLE, N_LAWS };
static const double TAB_E[4] = {0, 1e-4, 1e-3, 1e-2}; /* Swift values as a table (theory.md §7.2) */
static const double TAB_S[4] = {1460 * MPA, 1990 * MPA, 2468 * MPA, 3071 * MPA};

static void make_law(int which, mc_hardening *h)
{
    mc_error e;
    int rc = which == LAW_PERFECT  ? mc_hardening_perfect(1000 * MPA, h, &e)
             : which == LAW_LINEAR ? mc_hardening_linear(1500 * MPA, 20e9, h, &e)
             : which == LAW_SWIFT  ? mc_hardening_swift(1280 * MPA, 4, 0.095, h, &e)
                                   : mc_hardening_table(TAB_E, TAB_S, 4, h, &e);
    ck_assert_msg(rc == MC_OK, "%s", e.msg);
}

static double shear_mod(double E, double nu) { return E / (2 * (1 + nu)); }

/* von Mises from the deviator, written independently of kernels/invariants.c. */
static double vm_dev(const double s[6], double dev[6])
{
    double m = (s[0] + s[1] + s[2]) / 3, ss = 0;
    for (int i = 0; i < 6; i++) {
        dev[i] = i < 3 ? s[i] - m : s[i];
        ss += (i < 3 ? 1 : 2) * dev[i] * dev[i];
    }
    return sqrt(1.5 * ss);
}

static double max_abs(const double s[6])
{
    double m = 0;
    for (int i = 0; i < 6; i++)
        m = test_worst(m, fabs(s[i]));
    return m;
}

/* ---- uniaxial stress under mixed control: axial strain imposed, sigma_yy = sigma_zz = 0 ---- */
typedef struct {
    const double *sig;
    double p, a, E, nu;
    const mc_hardening *h;
    double b, out[6], deps_p[6], dp; /* lateral strain increment and the step's result */
} uni_step;

static double lateral_stress(double b, void *par)
{
    uni_step *u = par;
    double deps[6] = {u->a, b, b, 0, 0, 0};
    u->b = b;
    mc_error e;
    int rc = mc_j2_strain_step(u->sig, u->p, deps, u->E, u->nu, u->h, u->out, u->deps_p, &u->dp,
                               &e);
    ck_assert_msg(rc == MC_OK, "%s", e.msg);
    return u->out[1];
}

/* Brent's method (GSL) on the lateral strain increment b in [-a, 0], which brackets the root for
 * a > 0 (b = -a compresses, b = 0 stretches laterally); converged to a width of 4 eps. */
static void uniaxial_step(uni_step *u)
{
    gsl_function F = {lateral_stress, u};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    ck_assert(s && gsl_root_fsolver_set(s, &F, -u->a, 0.0) == GSL_SUCCESS);
    for (int it = 0; it < 200; it++) {
        gsl_root_fsolver_iterate(s);
        double lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(lo, hi, 0, 4 * DBL_EPSILON) == GSL_SUCCESS)
            break;
    }
    lateral_stress(gsl_root_fsolver_root(s), u); /* leave the state of the root in u */
    gsl_root_fsolver_free(s);
}

/* Run n steps to axial strain eps_max; check sigma = sigma_y(p), eps = sigma/E + p, the lateral
 * strain -nu sigma/E - p/2 and eps_p = diag(p, -p/2, -p/2) (theory.md §7.3 validation). Returns
 * the number of plastic steps. */
static int uniaxial_path(const mc_hardening *h, double E, double nu, double eps_max, int n)
{
    double sig[6] = {0}, ep[6] = {0}, p = 0, ex = 0, ey = 0;
    int plastic = 0;
    for (int k = 0; k < n; k++) {
        uni_step u = {sig, p, eps_max / n, E, nu, h, 0, {0}, {0}, 0};
        uniaxial_step(&u);
        ck_assert(fabs(u.out[1]) <= TOL_PATH * fabs(u.out[0]) && u.out[2] == u.out[1]);
        ex += u.a;
        ey += u.b;
        p += u.dp;
        for (int i = 0; i < 6; i++) {
            ep[i] += u.deps_p[i];
            sig[i] = u.out[i];
        }
        double sx = sig[0], tol = TOL_PATH * sx;
        if (u.dp > 0) {
            plastic++;
            ck_assert_msg(fabs(sx - mc_hardening_sigma_y(h, p)) <= tol, "step %d: %.17g vs %.17g",
                          k, sx, mc_hardening_sigma_y(h, p));
        }
        ck_assert_msg(fabs(ex - (sx / E + p)) <= TOL_PATH * ex, "step %d: eps %.17g vs %.17g", k,
                      ex, sx / E + p);
        ck_assert(fabs(ep[0] - p) <= TOL_PATH * ex && fabs(ep[1] + p / 2) <= TOL_PATH * ex);
        ck_assert(fabs(ep[2] - ep[1]) <= TOL_PATH * ex);
        ck_assert(fabs(ey - (-nu * sx / E - p / 2)) <= TOL_PATH * ex);
    }
    return plastic;
}

START_TEST(test_uniaxial)
{
    mc_hardening h;
    make_law(_i, &h);
    /* 100 steps to 2 % strain: yield at about 0.5-0.7 %, so most steps are plastic. */
    int plastic = uniaxial_path(&h, E_MOD, NU, 0.02, 100);
    ck_assert_int_ge(plastic, 60);
    mc_hardening_free(&h);
}
END_TEST

/* Tangent modulus: after yield the uniaxial slope d sigma / d eps is Et, 1/Et = 1/E + 1/H. */
START_TEST(test_linear_tangent)
{
    double H, Et = 15e9;
    mc_error e;
    ck_assert_int_eq(mc_hardening_linear_from_tangent(E_MOD, Et, &H, &e), MC_OK);
    mc_hardening h;
    ck_assert_int_eq(mc_hardening_linear(1500 * MPA, H, &h, &e), MC_OK);
    /* from a state on the yield surface at 2000 MPa, 1 % more axial strain (stays plastic) */
    double s0[6] = {2000 * MPA, 0, 0, 0, 0, 0}, p0 = (2000 - 1500) * MPA / H;
    uni_step u = {s0, p0, 0.01, E_MOD, NU, &h, 0, {0}, {0}, 0};
    uniaxial_step(&u);
    double slope = (u.out[0] - s0[0]) / u.a;
    ck_assert_msg(fabs(slope - Et) <= TOL_PATH * Et, "slope %.17g vs Et %.17g", slope, Et);
}
END_TEST

/* Pure shear: tau = sigma_y / sqrt 3 and gamma = tau/G + sqrt(3) p; normal stresses stay 0. */
START_TEST(test_pure_shear)
{
    mc_hardening h;
    make_law(_i, &h);
    double G = shear_mod(E_MOD, NU), sig[6] = {0}, p = 0, gamma = 0, dp, dep[6];
    int n = 100, plastic = 0;
    mc_error e;
    for (int k = 0; k < n; k++) {
        double g = 0.03 / n / 2, deps[6] = {0, 0, 0, g, 0, 0}; /* tensor eps_xy; gamma = 2 g */
        ck_assert_int_eq(mc_j2_strain_step(sig, p, deps, E_MOD, NU, &h, sig, dep, &dp, &e), MC_OK);
        p += dp;
        gamma += 2 * g;
        double tau = sig[3];
        if (dp > 0) {
            plastic++;
            ck_assert(fabs(tau - mc_hardening_sigma_y(&h, p) / sqrt(3.0)) <= TOL_PATH * tau);
        }
        ck_assert(fabs(gamma - (tau / G + sqrt(3.0) * p)) <= TOL_PATH * gamma);
        ck_assert(sig[0] == 0 && sig[1] == 0 && sig[2] == 0 && sig[4] == 0 && sig[5] == 0);
    }
    ck_assert_int_ge(plastic, 60);
    mc_hardening_free(&h);
}
END_TEST

/* Identities every plastic return must satisfy, whatever the law (theory.md §7.1, §7.3). */
static void check_return(const mc_hardening *h, double G, const double st[6], double pn,
                         const double so[6], const double dep[6], double dp)
{
    double dt[6], dn[6], qt = vm_dev(st, dt), qn = vm_dev(so, dn), sc = max_abs(st);
    double tol = TOL_RETURN * sc, tr = dep[0] + dep[1] + dep[2], ee = 0;
    ck_assert(dp > 0);
    ck_assert_msg(fabs(qn - mc_hardening_sigma_y(h, pn + dp)) <= tol, "f = %g Pa",
                  qn - mc_hardening_sigma_y(h, pn + dp));
    ck_assert(fabs(tr) <= TOL_RETURN * sc / G);
    ck_assert(fabs(qn - (qt - 3 * G * dp)) <= tol); /* radial: q shrinks by 3 G dp */
    for (int i = 0; i < 6; i++) {
        ee += (i < 3 ? 1 : 2) * dep[i] * dep[i];
        ck_assert(fabs(st[i] - so[i] - 2 * G * dep[i]) <= tol);
        ck_assert(fabs(dn[i] * qt - dt[i] * qn) <= tol * qt); /* s parallel to s_trial */
    }
    ck_assert(fabs((so[0] + so[1] + so[2]) - (st[0] + st[1] + st[2])) <= tol);
    ck_assert(fabs(sqrt(2.0 / 3.0 * ee) - dp) <= TOL_RETURN * sc / G);
}

START_TEST(test_random_returns)
{
    mc_hardening h;
    make_law(_i, &h);
    double G = shear_mod(E_MOD, NU), r[7 * 400];
    test_random_field(r, 7 * 400, 1234 + (unsigned long long)_i);
    mc_error e;
    int plastic = 0;
    for (int k = 0; k < 400; k++) {
        double st[6], so[6], dep[6], dp, pn = 0.01 * fabs(r[7 * k + 6]); /* p_n in [0, 1 %] */
        for (int i = 0; i < 6; i++) /* up to 6 GPa, a hydrostatic part up to 3x the deviator */
            st[i] = 3000 * MPA * (r[7 * k + i] + (i < 3 ? 1.0 : 0.0));
        ck_assert_int_eq(mc_return_map(st, pn, &h, G, so, dep, &dp, &e), MC_OK);
        if (dp > 0) {
            plastic++;
            check_return(&h, G, st, pn, so, dep, dp);
        } else {
            double d[6];
            ck_assert(vm_dev(st, d) <= mc_hardening_sigma_y(&h, pn));
            ck_assert(memcmp(st, so, sizeof st) == 0 && max_abs(dep) == 0);
        }
    }
    ck_assert_int_ge(plastic, 100);
    mc_hardening_free(&h);
}
END_TEST

/* Newton (table and Swift paths) against closed forms: a two-row table that is the linear law,
 * and a Swift law with n = 0 that is perfectly plastic. */
START_TEST(test_newton_vs_closed_form)
{
    double Y0 = 1500 * MPA, H = 20e9, G = shear_mod(E_MOD, NU), r[600];
    double te[2] = {0, 0.5}, ts[2] = {Y0, Y0 + H * 0.5};
    mc_hardening lin, tab, per, sw0;
    mc_error e;
    ck_assert(!mc_hardening_linear(Y0, H, &lin, &e) && !mc_hardening_table(te, ts, 2, &tab, &e));
    ck_assert(!mc_hardening_perfect(Y0, &per, &e) && !mc_hardening_swift(Y0, 4, 0, &sw0, &e));
    test_random_field(r, 600, 99);
    int plastic = 0;
    for (int k = 0; k < 100; k++) {
        double st[6], o1[6], o2[6], d1[6], d2[6], dp1, dp2, pn = 0.005 * fabs(r[6 * k]);
        for (int i = 0; i < 6; i++)
            st[i] = 4000 * MPA * r[6 * k + i];
        const mc_hardening *pair[2][2] = {{&lin, &tab}, {&per, &sw0}};
        for (int j = 0; j < 2; j++) {
            ck_assert(!mc_return_map(st, pn, pair[j][0], G, o1, d1, &dp1, &e));
            ck_assert(!mc_return_map(st, pn, pair[j][1], G, o2, d2, &dp2, &e));
            double dvm[6], q = vm_dev(st, dvm), sy = mc_hardening_sigma_y(pair[j][0], pn);
            double Hj = j == 0 ? H : 0, closed = q > sy ? (q - sy) / (3 * G + Hj) : 0;
            plastic += q > sy;
            /* dp is a difference q - sigma_y over 3G + H: 8 eps relative to q / 3G. */
            ck_assert(fabs(dp1 - closed) <= 8 * DBL_EPSILON * q / (3 * G));
            ck_assert(fabs(dp2 - closed) <= TOL_RETURN * q / (3 * G));
            for (int i = 0; i < 6; i++)
                ck_assert(fabs(o1[i] - o2[i]) <= TOL_RETURN * max_abs(st));
        }
    }
    ck_assert_int_ge(plastic, 100);
    mc_hardening_free(&tab);
}
END_TEST

/* Tension then shear, fully strain driven, n1 + n2 steps; returns the final stress. */
static void tension_shear(const mc_hardening *h, int n1, int n2, double sig[6], double *p,
                          double ep[6], int check)
{
    double ey = mc_hardening_initial(h) / E_MOD, G = shear_mod(E_MOD, NU), dep[6], dp;
    mc_error e;
    memset(sig, 0, 6 * sizeof(double));
    memset(ep, 0, 6 * sizeof(double));
    *p = 0;
    for (int k = 0; k < n1 + n2; k++) {
        double deps[6] = {0};
        if (k < n1)
            deps[0] = 2.0 * ey / n1;
        else
            deps[3] = 3.0 * ey / n2;
        double st[6], pn = *p;
        for (int i = 0; i < 6; i++)
            st[i] = sig[i];
        ck_assert_int_eq(mc_j2_strain_step(st, pn, deps, E_MOD, NU, h, sig, dep, &dp, &e), MC_OK);
        *p += dp;
        for (int i = 0; i < 6; i++)
            ep[i] += dep[i];
        if (check && dp > 0) { /* trial stress rebuilt from the step's definition */
            double trial[6], lam = 2 * G * NU / (1 - 2 * NU), tr = deps[0] + deps[1] + deps[2];
            for (int i = 0; i < 6; i++)
                trial[i] = st[i] + 2 * G * deps[i] + (i < 3 ? lam * tr : 0);
            check_return(h, G, trial, pn, sig, dep, dp);
        }
    }
}

START_TEST(test_nonproportional)
{
    mc_hardening h;
    make_law(_i, &h);
    double sig[6], p, ep[6], d[6];
    tension_shear(&h, 20, 20, sig, &p, ep, 1);
    double f = vm_dev(sig, d) - mc_hardening_sigma_y(&h, p);
    ck_assert_msg(p > 0 && fabs(f) <= TOL_RETURN * max_abs(sig), "f = %g Pa", f);
    ck_assert(fabs(ep[0] + ep[1] + ep[2]) <= TOL_RETURN * p);
    mc_hardening_free(&h);
}
END_TEST

/* Backward Euler is first order on a non-proportional path: the shear leg in 10 sub-steps must
 * be at least 2x closer to a 10^4-sub-step reference than in one step (first order predicts
 * about 10x; the factor 2 allows for the pre-asymptotic regime). Dossier: 6-18 % vs 1-3 %. */
START_TEST(test_substeps)
{
    mc_hardening h;
    make_law(_i, &h);
    double ref[6], s1[6], s10[6], ep[6], p, d1 = 0, d10 = 0, nr;
    tension_shear(&h, 20, 10000, ref, &p, ep, 0);
    tension_shear(&h, 20, 1, s1, &p, ep, 0);
    tension_shear(&h, 20, 10, s10, &p, ep, 0);
    nr = max_abs(ref);
    for (int i = 0; i < 6; i++) {
        d1 = test_worst(d1, fabs(s1[i] - ref[i]) / nr);
        d10 = test_worst(d10, fabs(s10[i] - ref[i]) / nr);
    }
    ck_assert_msg(d10 < 0.5 * d1, "law %d: 1 step %.3g, 10 steps %.3g", _i, d1, d10);
    mc_hardening_free(&h);
}
END_TEST

/* Swift law of theory.md §7.2 (B = 1280 MPa, C = 4, n = 0.095), values printed there. */
START_TEST(test_swift_values)
{
    mc_hardening h;
    make_law(LAW_SWIFT, &h);
    const double p[4] = {0, 1e-4, 1e-3, 1e-2}, ref[4] = {1460, 1990, 2468, 3071};
    for (int k = 0; k < 4; k++)
        ck_assert_msg(fabs(mc_hardening_sigma_y(&h, p[k]) / MPA - ref[k]) <= TOL_SWIFT_MPA,
                      "sigma_y(%g) = %.3f MPa", p[k], mc_hardening_sigma_y(&h, p[k]) / MPA);
    ck_assert(mc_hardening_initial(&h) == mc_hardening_sigma_y(&h, 0));
    ck_assert(isnan(mc_hardening_sigma_y(&h, -1e-9)) && isnan(mc_hardening_slope(&h, NAN)));
}
END_TEST

/* H = d sigma_y / dp against central differences, inside table segments. */
START_TEST(test_slope_fd)
{
    mc_hardening h;
    make_law(_i, &h);
    const double p[4] = {3e-5, 5e-4, 4e-3, 7e-3};
    for (int k = 0; k < 4; k++) {
        double d = 1e-4 * (p[k] + 4e-6), H = mc_hardening_slope(&h, p[k]);
        double up = mc_hardening_sigma_y(&h, p[k] + d), dn = mc_hardening_sigma_y(&h, p[k] - d);
        double fd = (up - dn) / (2 * d);
        ck_assert_msg(fabs(fd - H) <= TOL_FD * H, "law %d p %g: %g vs %g", _i, p[k], H, fd);
    }
    mc_hardening_free(&h);
}
END_TEST

/* Table: exact at rows, linear between, constant (slope 0) outside; right-hand slope at rows. */
START_TEST(test_table_interp)
{
    mc_hardening h, one, off;
    mc_error e;
    make_law(LAW_TABLE, &h);
    for (int k = 0; k < 4; k++) {
        ck_assert(mc_hardening_sigma_y(&h, TAB_E[k]) == TAB_S[k]);
        if (k == 3)
            break;
        double sl = (TAB_S[k + 1] - TAB_S[k]) / (TAB_E[k + 1] - TAB_E[k]);
        double mid = mc_hardening_sigma_y(&h, 0.5 * (TAB_E[k] + TAB_E[k + 1]));
        ck_assert(fabs(mid - 0.5 * (TAB_S[k] + TAB_S[k + 1])) <= TOL_TIGHT * TAB_S[k + 1]);
        ck_assert(fabs(mc_hardening_slope(&h, TAB_E[k]) - sl) <= TOL_TIGHT * sl);
    }
    ck_assert(mc_hardening_sigma_y(&h, 1.0) == TAB_S[3] && mc_hardening_slope(&h, 1.0) == 0);
    double e1[1] = {0}, s1[1] = {900 * MPA}, e2[2] = {1e-3, 2e-3}, s2[2] = {1e9, 2e9};
    ck_assert(!mc_hardening_table(e1, s1, 1, &one, &e) && !mc_hardening_table(e2, s2, 2, &off, &e));
    ck_assert(mc_hardening_sigma_y(&one, 0.3) == s1[0] && mc_hardening_slope(&one, 0.3) == 0);
    ck_assert(mc_hardening_initial(&off) == s2[0] && mc_hardening_slope(&off, 0) == 0);
    mc_hardening_free(&h);
    mc_hardening_free(&one);
    mc_hardening_free(&off);
    mc_hardening_free(&off); /* twice is harmless */
}
END_TEST

static int read_text(const char *text, mc_hardening *h, mc_error *e, char *path)
{
    snprintf(path, 512, "%s/hard.csv", test_tmpdir());
    FILE *f = fopen(path, "w");
    ck_assert(f && fputs(text, f) >= 0 && fclose(f) == 0);
    return mc_hardening_table_read(path, MPA, h, e);
}

START_TEST(test_table_read)
{
    mc_hardening h;
    mc_error e;
    char path[512], want[600];
    ck_assert_int_eq(read_text("# 52100\neps_p, sigma_y_MPa\n\n0, 1460\n 1e-4 ,1990 # c\n"
                               "1e-3,2468\r\n0.01, 3071", &h, &e, path), MC_OK);
    ck_assert(h.n_rows == 4 && h.kind == MC_HARDENING_TABLE);
    for (int k = 0; k < 4; k++)
        ck_assert(h.eps_p[k] == TAB_E[k] && h.sigma_y[k] == TAB_S[k]);
    mc_hardening_free(&h);
    const char *bad[5][2] = {{"eps,sig\n0,1000\n1e-3,900\n", ":3:"}, {"0,1000\n0,1100\n", ":2:"},
                             {"0,1000\n1e-3,x\n", ":2:"}, {"0,1000,5\n", ":1:"}, {"# none\n", ":"}};
    for (int k = 0; k < 5; k++) {
        ck_assert_int_eq(read_text(bad[k][0], &h, &e, path), MC_ERR_INPUT);
        snprintf(want, sizeof want, "%s%s", path, bad[k][1]);
        ck_assert_msg(strstr(e.msg, want) != NULL, "message '%s' lacks '%s'", e.msg, want);
    }
    ck_assert_int_eq(mc_hardening_table_read("/nonexistent/h.csv", MPA, &h, &e), MC_ERR_IO);
}
END_TEST

#define EXPECT_INPUT(call, needle)                                                              \
    do {                                                                                        \
        ck_assert_int_eq((call), MC_ERR_INPUT);                                                 \
        ck_assert_msg(strstr(e.msg, needle) != NULL, "'%s' lacks '%s'", e.msg, needle);         \
        ck_assert(memcmp(&h, &keep, sizeof h) == 0); /* untouched on failure */                 \
    } while (0)

START_TEST(test_validation)
{
    mc_hardening h, keep;
    mc_error e;
    double H, te[3] = {0, 1e-3, 2e-3}, ts[3] = {1e9, 2e9, 1.5e9}, te2[2] = {0, 0};
    double ts2[2] = {1e9, NAN}, te3[1] = {-1e-3}, ts3[1] = {0};
    memset(&h, 0x5a, sizeof h);
    keep = h;
    EXPECT_INPUT(mc_hardening_perfect(-1e9, &h, &e), "yield stress Y0");
    EXPECT_INPUT(mc_hardening_perfect(NAN, &h, &e), "yield stress Y0");
    EXPECT_INPUT(mc_hardening_linear(-1e9, 1e9, &h, &e), "yield stress Y0");
    EXPECT_INPUT(mc_hardening_linear(1e9, -1, &h, &e), "plastic modulus H");
    EXPECT_INPUT(mc_hardening_linear(1e9, INFINITY, &h, &e), "plastic modulus H");
    EXPECT_INPUT(mc_hardening_linear_from_tangent(E_MOD, E_MOD, &H, &e), "0 <= Et < E");
    EXPECT_INPUT(mc_hardening_linear_from_tangent(E_MOD, -1, &H, &e), "0 <= Et < E");
    EXPECT_INPUT(mc_hardening_linear_from_tangent(E_MOD, NAN, &H, &e), "0 <= Et < E");
    EXPECT_INPUT(mc_hardening_linear_from_tangent(0, 0, &H, &e), "Young's modulus E");
    EXPECT_INPUT(mc_hardening_swift(-1, 4, 0.1, &h, &e), "B =");
    EXPECT_INPUT(mc_hardening_swift(1e9, 0, 0.1, &h, &e), "C =");
    EXPECT_INPUT(mc_hardening_swift(1e9, 4, 1, &h, &e), "0 <= n < 1");
    EXPECT_INPUT(mc_hardening_swift(1e9, 4, NAN, &h, &e), "0 <= n < 1");
    EXPECT_INPUT(mc_hardening_table(te, ts, 3, &h, &e), "row 3: yield stress");
    EXPECT_INPUT(mc_hardening_table(te2, ts, 2, &h, &e), "row 2: plastic strain");
    EXPECT_INPUT(mc_hardening_table(te, ts2, 2, &h, &e), "row 2: eps_p = 0.001, sigma_y = nan");
    EXPECT_INPUT(mc_hardening_table(te3, ts, 1, &h, &e), "row 1: plastic strain");
    EXPECT_INPUT(mc_hardening_table(te, ts3, 1, &h, &e), "row 1: yield stress");
    EXPECT_INPUT(mc_hardening_table(te, ts, 0, &h, &e), "at least one row");
    ck_assert(mc_hardening_linear_from_tangent(E_MOD, 0, &H, &e) == MC_OK && H == 0);
    h = (mc_hardening){.kind = (mc_hardening_kind)7};
    ck_assert_int_eq(mc_hardening_validate(&h, &e), MC_ERR_INPUT);
}
END_TEST

START_TEST(test_return_errors)
{
    mc_hardening h;
    make_law(LAW_LINEAR, &h);
    double st[6] = {2e9, 0, 0, 0, 0, 0}, o[6], d[6], dp, G = shear_mod(E_MOD, NU), de[6] = {0};
    mc_error e;
    ck_assert_int_eq(mc_return_map(st, -1e-3, &h, G, o, d, &dp, &e), MC_ERR_INPUT);
    ck_assert_int_eq(mc_return_map(st, 0, &h, 0, o, d, &dp, &e), MC_ERR_INPUT);
    ck_assert_int_eq(mc_return_map(st, 0, NULL, G, o, d, &dp, &e), MC_ERR_INPUT);
    ck_assert_int_eq(mc_return_map(st, INFINITY, &h, G, o, d, &dp, &e), MC_ERR_NUMERIC);
    ck_assert_int_eq(mc_j2_strain_step(st, 0, de, 0, NU, &h, o, d, &dp, &e), MC_ERR_INPUT);
    ck_assert_int_eq(mc_j2_strain_step(st, 0, de, E_MOD, 0.5, &h, o, d, &dp, &e), MC_ERR_INPUT);
    de[4] = NAN;
    ck_assert_int_eq(mc_j2_strain_step(st, 0, de, E_MOD, NU, &h, o, d, &dp, &e), MC_ERR_NUMERIC);
    st[3] = NAN;
    ck_assert_int_eq(mc_return_map(st, 0, &h, G, o, d, &dp, &e), MC_ERR_NUMERIC);
    mc_hardening bad = {.kind = MC_HARDENING_PERFECT, .yield_stress = NAN}; /* hand-filled */
    st[3] = 0;
    ck_assert_int_eq(mc_return_map(st, 0, &bad, G, o, d, &dp, &e), MC_ERR_INPUT);
}
END_TEST

/* Every allocation of the table constructor and reader may fail: clean NOMEM, no leak (ASan). */
START_TEST(test_nomem)
{
    mc_hardening h;
    mc_error e;
    char path[512];
    int rc = MC_ERR_NOMEM;
    for (long k = 1; rc == MC_ERR_NOMEM; k++) {
        mc_alloc_fail_at(k);
        rc = mc_hardening_table(TAB_E, TAB_S, 4, &h, &e);
        if (rc == MC_OK)
            mc_hardening_free(&h);
    }
    ck_assert_int_eq(rc, MC_OK);
    rc = MC_ERR_NOMEM;
    for (long k = 1; rc == MC_ERR_NOMEM && k < 20; k++) {
        mc_alloc_fail_at(0);
        read_text("0, 1000\n1e-3, 1100\n", &h, &e, path); /* file first, then inject */
        mc_hardening_free(&h);
        mc_alloc_fail_at(k);
        rc = mc_hardening_table_read(path, MPA, &h, &e);
    }
    mc_alloc_fail_at(0);
    ck_assert_int_eq(rc, MC_OK);
    mc_hardening_free(&h);
}
END_TEST

/* A table with alternating steep (1e13 Pa) and flat segments: kinks everywhere; the safeguarded
 * Newton must still converge and satisfy every identity. */
START_TEST(test_kinked_table)
{
    double te[41], ts[41], r[7 * 300], G = shear_mod(E_MOD, NU);
    for (int k = 0; k <= 40; k++) {
        te[k] = 1e-4 * k;
        ts[k] = k == 0 ? 1e9 : ts[k - 1] + (k % 2 ? 1e13 * 1e-4 : 0);
    }
    mc_hardening h;
    mc_error e;
    ck_assert(!mc_hardening_table(te, ts, 41, &h, &e));
    test_random_field(r, 7 * 300, 7);
    for (int k = 0; k < 300; k++) {
        double st[6], so[6], dep[6], dp, pn = 4e-3 * fabs(r[7 * k + 6]);
        for (int i = 0; i < 6; i++)
            st[i] = 2e10 * r[7 * k + i];
        ck_assert_msg(!mc_return_map(st, pn, &h, G, so, dep, &dp, &e), "%s", e.msg);
        if (dp > 0)
            check_return(&h, G, st, pn, so, dep, dp);
    }
    mc_hardening_free(&h);
}
END_TEST

/* "B=1280 MPa" -> 1.28e9 Pa, "n=0.095" -> 0.095 (pl_material_laws.csv parameter cells). */
static double cell_value(const char *c)
{
    const char *q = strchr(c, '=');
    char *end;
    double v = strtod(q ? q + 1 : c, &end);
    while (*end == ' ')
        end++;
    return v * (!strncmp(end, "GPa", 3) ? 1e9 : !strncmp(end, "MPa", 3) ? MPA : 1.0);
}

/* Rows of pl_material_laws.csv: the law built from its parameters has the tabulated initial yield
 * (printed to 0.1 MPa: half a unit = 0.05 MPa) and passes the uniaxial path with its E, nu. */
START_TEST(test_material_table)
{
    char path[1024], line[1024];
    snprintf(path, sizeof path, "%s/pl_material_laws.csv", test_physics_dir());
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    int rows = 0;
    ck_assert(fgets(line, sizeof line, f) != NULL); /* header */
    while (fgets(line, sizeof line, f)) {
        char *c[10], *rest = line;
        int n = 0;
        while (n < 10 && (c[n] = strsep(&rest, ",")) != NULL)
            n++;
        ck_assert_int_eq(n, 10);
        mc_hardening h;
        mc_error e;
        double E = atof(c[2]) * 1e9, nu = atof(c[3]), y0 = atof(c[7]) * MPA;
        double a = cell_value(c[4]), b = cell_value(c[5]), cc = cell_value(c[6]);
        int rc = !strncmp(c[1], "swift", 5)    ? mc_hardening_swift(a, b, cc, &h, &e)
                 : !strncmp(c[1], "linear", 6) ? mc_hardening_linear(a, b, &h, &e)
                                               : mc_hardening_perfect(a, &h, &e);
        ck_assert_msg(rc == MC_OK, "%s: %s", c[0], e.msg);
        ck_assert_msg(fabs(mc_hardening_initial(&h) - y0) <= 0.05 * MPA, "%s: %.4f MPa", c[0],
                      mc_hardening_initial(&h) / MPA);
        ck_assert_int_ge(uniaxial_path(&h, E, nu, 0.02, 50), 30);
        mc_hardening_free(&h);
        rows++;
    }
    fclose(f);
    ck_assert_int_eq(rows, 3);
}
END_TEST

/* The law table: every law has a name, help and a reference, its name maps back to it, and its
 * constructor from the case's parameters builds a valid law of that kind (iterates the table). */
START_TEST(test_law_table)
{
    char path[512];
    mc_hardening h;
    mc_error e;
    snprintf(path, sizeof path, "%s/hard_table.csv", test_tmpdir());
    FILE *f = fopen(path, "w");
    ck_assert(f && fputs("0, 1460\n1e-3, 2468\n", f) >= 0 && fclose(f) == 0);
    const mc_hardening_params par = {.E = 210e9, .yield_stress = 1.5e9, .tangent_modulus = 1e10,
                                     .swift_B = 1280e6, .swift_C = 4, .swift_n = 0.095,
                                     .table = path, .table_unit = MPA};
    ck_assert_int_ge(mc_hardening_count(), 1);
    for (int k = 0; k < mc_hardening_count(); k++) {
        mc_hardening_kind kind = (mc_hardening_kind)k, back;
        const char *name = mc_hardening_name(kind);
        ck_assert_ptr_nonnull(name);
        ck_assert_ptr_nonnull(mc_hardening_help(kind));
        ck_assert_ptr_nonnull(mc_hardening_reference(kind));
        ck_assert_int_eq(mc_hardening_from_name(name, &back, &e), MC_OK);
        ck_assert_int_eq(back, kind);
        ck_assert_int_eq(mc_hardening_build(kind, &par, &h, &e), MC_OK);
        ck_assert_int_eq(h.kind, kind);
        ck_assert_int_eq(mc_hardening_validate(&h, &e), MC_OK);
        double y0 = mc_hardening_initial(&h);
        ck_assert_msg(y0 > 1e9 && y0 < 2e9, "%s: sigma_y(0) = %g Pa", name, y0);
        mc_hardening_free(&h);
    }
    ck_assert_ptr_null(mc_hardening_name((mc_hardening_kind)mc_hardening_count()));
    ck_assert_int_eq(mc_hardening_build((mc_hardening_kind)mc_hardening_count(), &par, &h, &e),
                     MC_ERR_INPUT);
    mc_hardening_kind back;
    ck_assert_int_eq(mc_hardening_from_name("voce", &back, &e), MC_ERR_INPUT);
    for (int k = 0; k < mc_hardening_count(); k++)
        ck_assert_msg(strstr(e.msg, mc_hardening_name((mc_hardening_kind)k)), "%s", e.msg);
}
END_TEST

Suite *suite_plastic_material(void);
Suite *suite_plastic_material(void)
{
    Suite *s = suite_create("plastic_material");
    TCase *tl = tcase_create("laws");
    tcase_add_test(tl, test_swift_values);
    tcase_add_loop_test(tl, test_slope_fd, LAW_LINEAR, N_LAWS);
    tcase_add_test(tl, test_table_interp);
    tcase_add_test(tl, test_table_read);
    tcase_add_test(tl, test_validation);
    tcase_add_test(tl, test_nomem);
    tcase_add_test(tl, test_material_table);
    tcase_add_test(tl, test_law_table);
    suite_add_tcase(s, tl);
    TCase *tr = tcase_create("return_map");
    tcase_set_timeout(tr, 60);
    tcase_add_loop_test(tr, test_uniaxial, 0, N_LAWS);
    tcase_add_test(tr, test_linear_tangent);
    tcase_add_loop_test(tr, test_pure_shear, 0, N_LAWS);
    tcase_add_loop_test(tr, test_random_returns, 0, N_LAWS);
    tcase_add_test(tr, test_newton_vs_closed_form);
    tcase_add_loop_test(tr, test_nonproportional, 0, N_LAWS);
    tcase_add_loop_test(tr, test_substeps, 0, N_LAWS);
    tcase_add_test(tr, test_return_errors);
    tcase_add_test(tr, test_kinked_table);
    suite_add_tcase(s, tr);
    return s;
}
