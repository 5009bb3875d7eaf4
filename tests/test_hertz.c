/* test_hertz.c - analytic reference solutions (hertz.c) against the dossier's reference tables,
 * quadrature of the elementary solutions, equilibrium, boundary conditions and known maxima.
 * Physics: theory.md §6.1-§6.4; tables: tests/data/physics/hertz_*.csv. */
#include <check.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "core/error.h"
#include "core/grid.h"
#include "reference/hertz.h"
#include "kernels/invariants.h"
#include "kernels/kernel.h"
#include "test_util.h"

#define NU 0.3 /* Poisson ratio of every reference table */

/* ---- tolerances ----------------------------------------------------------------------------- */
/* Tables printed with 13 significant digits (hertz_point_field_ref.csv): half a unit in the last
 * place of values up to 1.3, plus round-off of our evaluation. */
#define TOL_FIELD_TABLE 1e-12
/* Tables printed to 6 decimals (hertz_*_axis.csv): half a unit in the last place. */
#define TOL_6DEC (5e-7 + 1e-12)
/* Maxima printed to 5 decimals: half a unit in the last place plus the 1e-7 search tolerance. */
#define TOL_5DEC (5e-6 + 1e-7)
/* Two closed forms of the same field (Huber vs Hamilton, series vs direct near the axis, surface
 * formula vs field at z = 0): measured <= 2e-15 p0 against 50-digit mpmath for depth <= 10a. */
#define TOL_FORMS 1e-14
/* Adaptive quadrature (GSL, requested 1e-12 relative) against closed forms. */
#define TOL_QUAD 1e-10
/* Equilibrium by central differences with step H_FD (lengths / a or b): truncation
 * H_FD^2/6 |sigma'''| <= 2e-8 for |sigma'''| <= 1e3 (near a contact edge sigma''' ~ d^-5/2: 1e3
 * at d = 0.07; near a Flamant load ~ r^-4: 1e3 at r = 0.2), plus eps |sigma| / H_FD = 2e-11. A
 * wrong term in any component leaves an O(0.1) residual. */
#define H_FD 1e-5
#define TOL_EQUIL 1e-7
/* Maximum von Mises vs the friction tables: those are maxima over scan grids (0.0025-0.005 a),
 * printed to 5 decimals, so the true maximum exceeds them by up to the grid deficit
 * |f''| (h/2)^2 / 2 ~ 2.5e-5 (|f''| <= 8) plus 5e-6 rounding. */
#define TOL_VM_TABLE 3e-5
/* Location of a flat maximum from a grid of 0.005: a value flat to 5e-6 moves it ~3e-3. */
#define TOL_VM_WHERE 1e-2
/* At the trailing contact edge (point contact, mu >= 0.4) von Mises has a square-root cusp,
 * vm(-a) - vm(-a + d) ~ 0.26 sqrt(d/a), so a grid of 0.005 a under-reads the true maximum by up to
 * ~0.02; the table value must lie between the cusp value and that much below. */
#define TOL_VM_CUSP 2e-2
/* Table locations printed with 4 decimals: +-5e-5 a. */
#define TABLE_X_HALF_ULP 5e-5
/* Brent brackets a cusp maximum to its 1e-10 interval tolerance; 1e-6 a is a safe bound. */
#define TOL_CUSP_WHERE 1e-6
/* Surface sr at rho = 1 - 1e-12: the inside formula differs from the edge value by terms in
 * sqrt(1 - rho^2) = 1.4e-6. */
#define TOL_NEAR_EDGE 1e-5
/* A strip of half-width a seen from r = 500 (385 a) acts as a line load 2a p up to relative
 * corrections O((a/r)^2) = 7e-6. */
#define TOL_FAR_STRIP 1e-4

/* ---- helpers --------------------------------------------------------------------------------- */

static void setup(void) { mc_gsl_quiet(); }

static const char *const comp_name[6] = {"xx", "yy", "zz", "xy", "yz", "xz"}; /* kernel.h order */

static int col_of(char header[][32], int ncols, const char *name)
{
    for (int c = 0; c < ncols; c++)
        if (strcmp(header[c], name) == 0)
            return c;
    ck_abort_msg("column %s not found", name);
    return -1;
}

/* Rotate the cylindrical Huber stresses at azimuth (cx, cy) = (cos, sin) to Cartesian. */
static void cyl_to_cart(double sr, double st, double sz, double trz, double cx, double cy,
                        double s[6])
{
    s[MC_SXX] = sr * cx * cx + st * cy * cy;
    s[MC_SYY] = sr * cy * cy + st * cx * cx;
    s[MC_SZZ] = sz;
    s[MC_SXY] = (sr - st) * cx * cy;
    s[MC_SXZ] = trz * cx;
    s[MC_SYZ] = trz * cy;
}

static void huber_cart(double x, double y, double z, double nu, double s[6])
{
    double r = hypot(x, y), sr, st, sz, trz;
    mc_hertz_huber(r, z, nu, &sr, &st, &sz, &trz);
    double cx = r > 0 ? x / r : 1.0, cy = r > 0 ? y / r : 0.0;
    cyl_to_cart(sr, st, sz, trz, cx, cy, s);
}

static double maxabs_diff6(const double a[6], const double b[6])
{
    double m = 0.0;
    for (int c = 0; c < 6; c++)
        m = test_worst(m, fabs(a[c] - b[c]));
    return m;
}

/* 1-D maximisation by Brent's method (gsl_min on -f) in [lo, hi] from a guess with
 * f(guess) > f(lo), f(hi). Returns the location; *fmax the value. */
typedef double (*fun1)(double, void *);
typedef struct {
    fun1 f;
    void *par;
} neg1_par;
static double neg1(double x, void *p)
{
    neg1_par *q = p;
    return -q->f(x, q->par);
}
static double brent_max(fun1 f, void *par, double lo, double guess, double hi, double *fmax)
{
    neg1_par q = {f, par};
    gsl_function F = {neg1, &q};
    gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    ck_assert(m != NULL);
    ck_assert_int_eq(gsl_min_fminimizer_set(m, &F, guess, lo, hi), GSL_SUCCESS);
    for (int it = 0; it < 200; it++) {
        gsl_min_fminimizer_iterate(m);
        if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m),
                                  1e-10, 0.0) == GSL_SUCCESS)
            break;
    }
    double x = gsl_min_fminimizer_x_minimum(m);
    *fmax = f(x, par);
    gsl_min_fminimizer_free(m);
    return x;
}

/* 2-D maximisation (Nelder-Mead) of f(x, z) over z >= 0 from (x0, z0). */
typedef double (*fun2)(double, double, void *);
typedef struct {
    fun2 f;
    void *par;
} neg2_par;
static double neg2(const gsl_vector *v, void *p)
{
    neg2_par *q = p;
    double z = gsl_vector_get(v, 1);
    return z < 0.0 ? 1.0 : -q->f(gsl_vector_get(v, 0), z, q->par);
}
static double simplex_max(fun2 f, void *par, double *x, double *z)
{
    neg2_par q = {f, par};
    gsl_multimin_function F = {neg2, 2, &q};
    gsl_multimin_fminimizer *m =
        gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 2);
    gsl_vector *v = gsl_vector_alloc(2), *step = gsl_vector_alloc(2);
    ck_assert(m && v && step);
    gsl_vector_set(v, 0, *x);
    gsl_vector_set(v, 1, *z);
    gsl_vector_set_all(step, 0.003);
    ck_assert_int_eq(gsl_multimin_fminimizer_set(m, &F, v, step), GSL_SUCCESS);
    for (int it = 0; it < 2000; it++) {
        gsl_multimin_fminimizer_iterate(m);
        if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(m), 1e-10) == GSL_SUCCESS)
            break;
    }
    *x = gsl_vector_get(m->x, 0);
    *z = gsl_vector_get(m->x, 1);
    double fm = -m->fval;
    gsl_multimin_fminimizer_free(m);
    gsl_vector_free(v);
    gsl_vector_free(step);
    return fm;
}

/* ---- Hertz point contact: relations ---------------------------------------------------------- */

/* (R [m], E* [Pa], P [N]): steel ball, a soft case, a micro-asperity */
static const double point_cases[][3] = {
    {10e-3, 115.38e9, 50.0}, {0.5, 2e6, 3.0}, {2e-6, 230e9, 1e-4}};

static double point_p_r(double r, void *par)
{
    const mc_hertz_point *h = par;
    return 2.0 * M_PI * r * mc_hertz_point_pressure(h, r);
}

START_TEST(test_point_relations)
{
    const double *c = point_cases[_i];
    double R = c[0], E = c[1], P = c[2];
    mc_hertz_point h;
    mc_error err;
    ck_assert_int_eq(mc_hertz_point_from_load(R, E, P, &h, &err), MC_OK);
    /* the cube-root forms of theory.md §6.1, evaluated independently */
    ck_assert(fabs(h.p0 / cbrt(6.0 * P * E * E / (M_PI * M_PI * M_PI * R * R)) - 1.0) <= TOL_TIGHT);
    ck_assert(fabs(h.delta / cbrt(9.0 * P * P / (16.0 * R * E * E)) - 1.0) <= TOL_TIGHT);
    ck_assert(fabs(h.delta / (h.a * h.a / R) - 1.0) <= TOL_TIGHT);
    ck_assert(fabs(h.p0 / (3.0 * P / (2.0 * M_PI * h.a * h.a)) - 1.0) <= TOL_TIGHT);
    /* load balance: 2 pi int p r dr = P */
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_function F = {point_p_r, &h};
    double load, abserr;
    ck_assert_int_eq(gsl_integration_qags(&F, 0.0, h.a, 0.0, 1e-13, 1000, w, &load, &abserr),
                     GSL_SUCCESS);
    gsl_integration_workspace_free(w);
    ck_assert_msg(fabs(load / P - 1.0) <= TOL_QUAD, "load %.17g vs %.17g", load, P);
    /* the approach is the centre displacement (rigid sphere: gap = r^2/2R - delta + u_z = 0),
     * and u_z(0) - u_z(r) = r^2/(2R) inside the contact */
    ck_assert(fabs(mc_hertz_point_uz(&h, 0.0) / h.delta - 1.0) <= TOL_TIGHT);
    for (int k = 1; k <= 10; k++) {
        double r = 0.1 * k * h.a;
        double d = mc_hertz_point_uz(&h, 0.0) - mc_hertz_point_uz(&h, r);
        ck_assert_msg(fabs(d - r * r / (2.0 * R)) <= TOL_TIGHT * h.delta, "r/a=%g: %.17g vs %.17g",
                      r / h.a, d, r * r / (2.0 * R));
    }
    /* approach control inverts load control */
    mc_hertz_point g;
    ck_assert_int_eq(mc_hertz_point_from_approach(R, E, h.delta, &g, &err), MC_OK);
    ck_assert(fabs(g.load / P - 1.0) <= TOL_TIGHT);
    ck_assert(fabs(g.a / h.a - 1.0) <= TOL_TIGHT);
    ck_assert(fabs(g.p0 / h.p0 - 1.0) <= TOL_TIGHT);
    ck_assert(g.R == R && g.Estar == E && g.delta == h.delta);
    /* pressure: p0 at the centre, 0 at and beyond the edge, p0 sqrt(1 - r^2/a^2) between */
    ck_assert(mc_hertz_point_pressure(&h, 0.0) == h.p0);
    ck_assert(mc_hertz_point_pressure(&h, h.a) == 0.0);
    ck_assert(mc_hertz_point_pressure(&h, -2.0 * h.a) == 0.0);
    ck_assert(fabs(mc_hertz_point_pressure(&h, 0.6 * h.a) / h.p0 - 0.8) <= TOL_TIGHT);
}
END_TEST

START_TEST(test_input_errors)
{
    mc_hertz_point h;
    mc_hertz_line l;
    mc_error err;
    const double bad[] = {0.0, -1.0, NAN, INFINITY};
    for (int k = 0; k < 4; k++) {
        mc_error_clear(&err);
        ck_assert_int_eq(mc_hertz_point_from_load(bad[k], 1e9, 1.0, &h, &err), MC_ERR_INPUT);
        ck_assert_int_eq(err.code, MC_ERR_INPUT);
        ck_assert(strstr(err.msg, "R > 0") != NULL);
        ck_assert_int_eq(mc_hertz_point_from_load(1.0, bad[k], 1.0, &h, &err), MC_ERR_INPUT);
        ck_assert_int_eq(mc_hertz_point_from_load(1.0, 1e9, bad[k], &h, &err), MC_ERR_INPUT);
        ck_assert_int_eq(mc_hertz_point_from_approach(1.0, 1e9, bad[k], &h, &err), MC_ERR_INPUT);
        ck_assert_int_eq(mc_hertz_line_from_load(1.0, 1e9, bad[k], &l, &err), MC_ERR_INPUT);
        ck_assert_int_eq(mc_hertz_line_from_load(bad[k], 1e9, 1.0, &l, &err), MC_ERR_INPUT);
    }
    ck_assert_int_eq(mc_hertz_point_from_load(1.0, 1e9, 1.0, NULL, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_hertz_line_from_load(1.0, 1e9, 1.0, NULL, NULL), MC_ERR_INPUT);
}
END_TEST

/* ---- point contact: surface displacement by quadrature of Boussinesq ------------------------ */
/* u_z(x) = 1/(pi E*) int p(s)/|x - s| dA. In polar coordinates (t, psi) centred on the field point
 * at distance rho from the centre (lengths / a), 1/|x-s| cancels the Jacobian and
 * 1 - |s|^2 = (t - t1)(t2 - t), t12 = rho cos psi -+ sqrt(1 - rho^2 sin^2 psi), so
 * u_z = p0 a/(pi E*) * 2 int_0^psimax dpsi int_max(0,t1)^t2 sqrt((t-t1)(t2-t)) dt. */
typedef struct {
    double rho, t1, t2;
    gsl_integration_workspace *win;
} uz_par;

static double uz_inner(double t, void *p)
{
    const uz_par *q = p;
    return sqrt(fmax(0.0, (t - q->t1) * (q->t2 - t)));
}

static double uz_outer(double psi, void *p)
{
    uz_par *q = p;
    double sn = q->rho * sin(psi);
    double w = sqrt(fmax(0.0, 1.0 - sn * sn));
    q->t1 = q->rho * cos(psi) - w;
    q->t2 = q->rho * cos(psi) + w;
    double lo = fmax(0.0, q->t1);
    if (q->t2 <= lo)
        return 0.0;
    gsl_function F = {uz_inner, q};
    double v, e;
    ck_assert_int_eq(gsl_integration_qags(&F, lo, q->t2, 1e-15, 1e-13, 1000, q->win, &v, &e),
                     GSL_SUCCESS);
    return v;
}

/* inside, at and around the edge, both sides of the series hand-over at rho = 2, far out */
static const double uz_rho[] = {0.0, 0.3, 0.7, 0.999, 1.0, 1.001, 1.5, 1.999, 2.0, 3.0, 10.0, 50.0};

START_TEST(test_point_uz_quadrature)
{
    mc_hertz_point h;
    ck_assert_int_eq(mc_hertz_point_from_load(10e-3, 115.38e9, 50.0, &h, NULL), MC_OK);
    uz_par q = {uz_rho[_i], 0, 0, gsl_integration_workspace_alloc(1000)};
    gsl_integration_workspace *wout = gsl_integration_workspace_alloc(1000);
    double psimax = q.rho <= 1.0 ? M_PI : asin(1.0 / q.rho);
    gsl_function F = {uz_outer, &q};
    double I, e;
    ck_assert_int_eq(gsl_integration_qags(&F, 0.0, psimax, 1e-14, 1e-12, 1000, wout, &I, &e),
                     GSL_SUCCESS);
    double uq = h.p0 * h.a * 2.0 * I / (M_PI * h.Estar);
    double uf = mc_hertz_point_uz(&h, q.rho * h.a);
    ck_assert_msg(fabs(uf / uq - 1.0) <= TOL_QUAD, "rho=%g: formula %.17g quadrature %.17g", q.rho,
                  uf, uq);
    gsl_integration_workspace_free(wout);
    gsl_integration_workspace_free(q.win);
}
END_TEST

/* Far field: u_z 2 E* / (p0 a) = 4s/3 + 2s^3/15 + 3s^5/70 + O(s^7), s = a/r (series of the outside
 * formula; the leading term is the point load P/(pi E* r)). The naive formula loses ~eps rho^2. */
START_TEST(test_point_uz_far_field)
{
    mc_hertz_point h;
    ck_assert_int_eq(mc_hertz_point_from_load(10e-3, 115.38e9, 50.0, &h, NULL), MC_OK);
    const double rhos[] = {1e3, 1e4, 1e5, 1e8}; /* s^7 term below 1e-21 */
    for (int k = 0; k < 4; k++) {
        double s = 1.0 / rhos[k];
        double f = 4.0 * s / 3.0 + 2.0 * s * s * s / 15.0 + 3.0 * pow(s, 5) / 70.0;
        double u = mc_hertz_point_uz(&h, rhos[k] * h.a) * 2.0 * h.Estar / (h.p0 * h.a);
        ck_assert_msg(fabs(u / f - 1.0) <= TOL_TIGHT, "rho=%g: %.17g vs %.17g", rhos[k], u, f);
    }
    /* the two branches meet at r = a, with the same slope */
    double a = h.a, d = 1e-7 * a;
    ck_assert(fabs(mc_hertz_point_uz(&h, a * (1 + 1e-15)) / mc_hertz_point_uz(&h, a) - 1.0) <=
              TOL_TIGHT);
    double sl_in = (mc_hertz_point_uz(&h, a) - mc_hertz_point_uz(&h, a - d)) / d;
    double sl_out = (mc_hertz_point_uz(&h, a + d) - mc_hertz_point_uz(&h, a)) / d;
    /* outside, u_z has a (r-a)^(3/2) term: the one-sided slope over d deviates by
     * (8/3) sqrt(2 d/a)/pi = 1.2 sqrt(d/a); round-off eps a/d is far smaller */
    ck_assert_msg(fabs(sl_out / sl_in - 1.0) <= 2.0 * sqrt(d / a), "slopes %.12g %.12g", sl_in,
                  sl_out);
}
END_TEST

/* ---- point contact: tables ------------------------------------------------------------------- */

START_TEST(test_point_axis_table)
{
    double *d;
    int cols;
    char hd[8][32];
    int rows = test_read_csv("hertz_point_axis.csv", &d, &cols, hd, 8);
    ck_assert_int_ge(rows, 20);
    int cz = col_of(hd, cols, "z_over_a"), cr = col_of(hd, cols, "sigma_r"),
        czz = col_of(hd, cols, "sigma_z"), ct = col_of(hd, cols, "tau1"),
        cv = col_of(hd, cols, "von_mises");
    for (int i = 0; i < rows; i++) {
        const double *row = d + i * cols;
        double z = row[cz], sr, sz;
        mc_hertz_point_axis(z, NU, &sr, &sz);
        double s[6] = {sr, sr, sz, 0, 0, 0};
        ck_assert_msg(fabs(sr - row[cr]) <= TOL_6DEC, "z=%g sr %.9f vs %.9f", z, sr, row[cr]);
        ck_assert_msg(fabs(sz - row[czz]) <= TOL_6DEC, "z=%g sz %.9f vs %.9f", z, sz, row[czz]);
        ck_assert(fabs(0.5 * fabs(sz - sr) - row[ct]) <= TOL_6DEC);
        ck_assert(fabs(mc_tresca(s) - row[ct]) <= TOL_6DEC);
        ck_assert(fabs(mc_von_mises(s) - row[cv]) <= TOL_6DEC);
        /* Huber at r = 0 (its own limit form) and Hamilton at r = 0 give the same axis */
        double h[6], hm[6];
        huber_cart(0.0, 0.0, z, NU, h);
        mc_hertz_hamilton_normal(0.0, 0.0, z, NU, hm);
        ck_assert_msg(maxabs_diff6(h, s) <= TOL_FORMS, "z=%g Huber axis off by %g", z,
                      maxabs_diff6(h, s));
        ck_assert(maxabs_diff6(hm, s) <= TOL_FORMS);
    }
    free(d);
}
END_TEST

START_TEST(test_point_field_table)
{
    double *d;
    int cols;
    char hd[16][32];
    int rows = test_read_csv("hertz_point_field_ref.csv", &d, &cols, hd, 16);
    ck_assert_int_ge(rows, 13);
    static const char *nn[6] = {"sxx_n", "syy_n", "szz_n", "sxy_n", "syz_n", "sxz_n"};
    static const char *tn[6] = {"sxx_t", "syy_t", "szz_t", "sxy_t", "syz_t", "sxz_t"};
    int cx = col_of(hd, cols, "x"), cy = col_of(hd, cols, "y"), cz = col_of(hd, cols, "z");
    int huber_checked = 0;
    for (int i = 0; i < rows; i++) {
        const double *row = d + i * cols;
        double x = row[cx], y = row[cy], z = row[cz], sn[6], st[6];
        mc_hertz_hamilton_normal(x, y, z, NU, sn);
        mc_hertz_hamilton_tangential(x, y, z, NU, st);
        for (int c = 0; c < 6; c++) { /* nn[] / tn[] are in kernel.h component order */
            double rn = row[col_of(hd, cols, nn[c])], rt = row[col_of(hd, cols, tn[c])];
            ck_assert_msg(fabs(sn[c] - rn) <= TOL_FIELD_TABLE,
                          "(%g,%g,%g) normal %s: %.15g vs %.15g", x, y, z, comp_name[c], sn[c], rn);
            ck_assert_msg(fabs(st[c] - rt) <= TOL_FIELD_TABLE,
                          "(%g,%g,%g) tangential %s: %.15g vs %.15g", x, y, z, comp_name[c], st[c],
                          rt);
        }
        if (x * x + y * y > 0.0) { /* Huber (cylindrical, minus sign in stheta) off the axis */
            double hb[6];
            huber_cart(x, y, z, NU, hb);
            ck_assert_msg(maxabs_diff6(hb, sn) <= TOL_FORMS, "(%g,%g,%g) Huber vs Hamilton %g", x,
                          y, z, maxabs_diff6(hb, sn));
            huber_checked++;
        }
    }
    ck_assert_int_ge(huber_checked, 10);
    free(d);
}
END_TEST

/* Mutation guard for the dossier's boxed warning: with a PLUS in front of the second term of
 * stheta the axis value at the surface would be (6nu-1)/2 instead of -(1+2nu)/2. */
START_TEST(test_huber_sign)
{
    double sr, st, sz, trz;
    mc_hertz_huber(0.0, 0.0, NU, &sr, &st, &sz, &trz);
    ck_assert(fabs(st + (1.0 + 2.0 * NU) / 2.0) <= TOL_FORMS);
    ck_assert(fabs(sr - st) <= TOL_FORMS && fabs(sz + 1.0) <= TOL_FORMS && trz == 0.0);
}
END_TEST

/* ---- point contact: near the axis ------------------------------------------------------------ */
/* Hamilton's 1/r^2, 1/r^4 brackets are evaluated by series near the axis. Checks: (a) continuity
 * to the axis limit, |s(r) - s(0)| <= L r with a gradient bound L = 3 (the direct formulas miss
 * this by 1e5 at r = 1e-7); (b) Huber (cancellation-free) against Hamilton normal; (c) the series
 * and the direct form agree where one hands over to the other. */
#define GRAD_BOUND 3.0
static const double near_z[] = {0.0, 1e-3, 0.1, 0.48, 1.0, 3.0, 10.0};

START_TEST(test_point_near_axis)
{
    double z = near_z[_i];
    double s0n[6], s0t[6];
    mc_hertz_hamilton_normal(0.0, 0.0, z, NU, s0n);
    mc_hertz_hamilton_tangential(0.0, 0.0, z, NU, s0t);
    const double ang[] = {0.0, 0.7, M_PI / 2, 2.5, -1.2};
    for (int k = 1; k <= 12; k++) {
        double r = pow(10.0, -k);
        for (int j = 0; j < 5; j++) {
            double x = r * cos(ang[j]), y = r * sin(ang[j]), sn[6], st[6], hb[6];
            mc_hertz_hamilton_normal(x, y, z, NU, sn);
            mc_hertz_hamilton_tangential(x, y, z, NU, st);
            huber_cart(x, y, z, NU, hb);
            ck_assert_msg(maxabs_diff6(sn, s0n) <= GRAD_BOUND * r + TOL_FORMS,
                          "normal z=%g r=%g: %g from the axis", z, r, maxabs_diff6(sn, s0n));
            ck_assert_msg(maxabs_diff6(st, s0t) <= GRAD_BOUND * r + TOL_FORMS,
                          "tangential z=%g r=%g: %g from the axis", z, r, maxabs_diff6(st, s0t));
            ck_assert_msg(maxabs_diff6(sn, hb) <= TOL_FORMS, "z=%g r=%g Huber vs Hamilton %g", z, r,
                          maxabs_diff6(sn, hb));
        }
    }
    /* hand-over radius r_s = sqrt((1+z^2)/16) (hertz.c NEAR_AXIS_T): evaluate one ulp either side
     */
    double rs = sqrt((1.0 + z * z) / 16.0);
    for (int j = 0; j < 5; j++) {
        double ri = nextafter(rs, 0.0) * (1.0 - 4 * DBL_EPSILON), ro = rs * (1.0 + 4 * DBL_EPSILON);
        double a[6], b[6];
        mc_hertz_hamilton_normal(ri * cos(ang[j]), ri * sin(ang[j]), z, NU, a);
        mc_hertz_hamilton_normal(ro * cos(ang[j]), ro * sin(ang[j]), z, NU, b);
        ck_assert_msg(maxabs_diff6(a, b) <= TOL_FORMS, "normal hand-over z=%g: %g", z,
                      maxabs_diff6(a, b));
        mc_hertz_hamilton_tangential(ri * cos(ang[j]), ri * sin(ang[j]), z, NU, a);
        mc_hertz_hamilton_tangential(ro * cos(ang[j]), ro * sin(ang[j]), z, NU, b);
        ck_assert_msg(maxabs_diff6(a, b) <= TOL_FORMS, "tangential hand-over z=%g: %g", z,
                      maxabs_diff6(a, b));
    }
}
END_TEST

/* ---- point contact: equilibrium and boundary conditions ------------------------------------- */

typedef void (*field3)(double, double, double, double, double[6]);

static double div_residual3(field3 f, double x, double y, double z)
{
    double p[6], m[6], dx[6], dy[6], dz[6];
    f(x + H_FD, y, z, NU, p);
    f(x - H_FD, y, z, NU, m);
    for (int c = 0; c < 6; c++)
        dx[c] = (p[c] - m[c]) / (2 * H_FD);
    f(x, y + H_FD, z, NU, p);
    f(x, y - H_FD, z, NU, m);
    for (int c = 0; c < 6; c++)
        dy[c] = (p[c] - m[c]) / (2 * H_FD);
    f(x, y, z + H_FD, NU, p);
    f(x, y, z - H_FD, NU, m);
    for (int c = 0; c < 6; c++)
        dz[c] = (p[c] - m[c]) / (2 * H_FD);
    double r1 = dx[MC_SXX] + dy[MC_SXY] + dz[MC_SXZ];
    double r2 = dx[MC_SXY] + dy[MC_SYY] + dz[MC_SYZ];
    double r3 = dx[MC_SXZ] + dy[MC_SYZ] + dz[MC_SZZ];
    return fmax(fabs(r1), fmax(fabs(r2), fabs(r3)));
}

static const double equil_pts[][3] = {
    {0.3, 0.2, 0.1},   {0.8, -0.5, 0.3}, {1.2, 0.4, 0.2},    {0.5, 0.5, 0.6},     {-0.7, 0.1, 0.15},
    {2.0, -1.0, 1.0},  {0.0, 0.7, 0.4},  {0.01, 0.005, 0.3}, {1e-3, -2e-3, 0.48}, {0.2, 0.1, 0.05},
    {-0.1, 0.15, 1.0}, {0.0, 0.2, 2.0},  {1.5, 0.0, 0.3}};

START_TEST(test_point_equilibrium)
{
    const double *p = equil_pts[_i];
    double rn = div_residual3(mc_hertz_hamilton_normal, p[0], p[1], p[2]);
    double rt = div_residual3(mc_hertz_hamilton_tangential, p[0], p[1], p[2]);
    ck_assert_msg(rn <= TOL_EQUIL, "normal div sigma = %g at (%g,%g,%g)", rn, p[0], p[1], p[2]);
    ck_assert_msg(rt <= TOL_EQUIL, "tangential div sigma = %g at (%g,%g,%g)", rt, p[0], p[1], p[2]);
}
END_TEST

/* Surface tractions (t = sigma . (-e_z)): szz = -p, sxz = -q, syz = 0; free outside. */
START_TEST(test_point_surface_tractions)
{
    for (int i = -30; i <= 30; i++)
        for (int j = -5; j <= 5; j++) {
            double x = 0.05 * i + 0.013, y = 0.1 * j + 0.007, r2 = x * x + y * y;
            double p = r2 < 1.0 ? sqrt(1.0 - r2) : 0.0, sn[6], st[6];
            mc_hertz_hamilton_normal(x, y, 0.0, NU, sn);
            mc_hertz_hamilton_tangential(x, y, 0.0, NU, st);
            ck_assert_msg(fabs(sn[MC_SZZ] + p) <= TOL_FORMS, "(%g,%g) szz %g vs -p %g", x, y,
                          sn[MC_SZZ], -p);
            ck_assert(fabs(sn[MC_SXZ]) <= TOL_FORMS && fabs(sn[MC_SYZ]) <= TOL_FORMS);
            ck_assert_msg(fabs(st[MC_SXZ] + p) <= TOL_FORMS, "(%g,%g) sxz %g vs -q %g", x, y,
                          st[MC_SXZ], -p);
            ck_assert(fabs(st[MC_SZZ]) <= TOL_FORMS && fabs(st[MC_SYZ]) <= TOL_FORMS);
        }
}
END_TEST

/* Surface formulas (theory.md §6.1) against the full fields at z = 0 on the x axis (sr = sxx,
 * stheta = syy there), and the edge values. */
START_TEST(test_point_surface)
{
    for (int k = 0; k <= 250; k++) {
        double rho = 0.01 * k + 1e-3;
        double sr, st, sz, s[6], hb[6];
        mc_hertz_point_surface(rho, NU, &sr, &st, &sz);
        mc_hertz_hamilton_normal(rho, 0.0, 0.0, NU, s);
        huber_cart(rho, 0.0, 0.0, NU, hb);
        ck_assert_msg(fabs(sr - s[MC_SXX]) <= TOL_FORMS && fabs(st - s[MC_SYY]) <= TOL_FORMS &&
                          fabs(sz - s[MC_SZZ]) <= TOL_FORMS,
                      "rho=%g: surface (%g %g %g) vs Hamilton (%g %g %g)", rho, sr, st, sz,
                      s[MC_SXX], s[MC_SYY], s[MC_SZZ]);
        ck_assert(maxabs_diff6(s, hb) <= TOL_FORMS);
    }
    double sr, st, sz;
    mc_hertz_point_surface(0.0, NU, &sr, &st, &sz);
    ck_assert(fabs(sr + (1.0 + 2.0 * NU) / 2.0) <= TOL_TIGHT && fabs(st - sr) <= TOL_TIGHT);
    ck_assert(fabs(sz + 1.0) <= TOL_TIGHT);
    /* maximum tension (1-2nu)/3 at the edge, from both sides */
    mc_hertz_point_surface(1.0, NU, &sr, &st, &sz);
    ck_assert(fabs(sr - (1.0 - 2.0 * NU) / 3.0) <= TOL_TIGHT && sz == 0.0);
    mc_hertz_point_surface(1.0 - 1e-12, NU, &sr, &st, &sz);
    ck_assert(fabs(sr - (1.0 - 2.0 * NU) / 3.0) <= TOL_NEAR_EDGE);
    /* the edge point itself (Hamilton's S = 0) returns the surface limit */
    double s[6];
    mc_hertz_hamilton_normal(1.0, 0.0, 0.0, NU, s);
    ck_assert(fabs(s[MC_SXX] - (1.0 - 2.0 * NU) / 3.0) <= TOL_TIGHT && s[MC_SZZ] == 0.0);
    ck_assert(isfinite(s[MC_SXZ]) && isfinite(s[MC_SYY]));
}
END_TEST

/* ---- point contact: maxima ----------------------------------------------------------------- */

static double point_axis_tau1(double z, void *par)
{
    (void)par;
    double sr, sz;
    mc_hertz_point_axis(z, NU, &sr, &sz);
    return 0.5 * fabs(sz - sr);
}

static double point_axis_vm(double z, void *par)
{
    (void)par;
    double s[6];
    mc_hertz_hamilton_normal(0.0, 0.0, z, NU, s);
    return mc_von_mises(s);
}

START_TEST(test_point_maxima)
{
    double f, z = brent_max(point_axis_tau1, NULL, 0.1, 0.5, 1.5, &f);
    ck_assert_msg(fabs(f - 0.31002) <= TOL_5DEC, "tau1 max %.7f", f);
    ck_assert_msg(fabs(z - 0.48086) <= TOL_5DEC, "tau1 max at z=%.7f", z);
    z = brent_max(point_axis_vm, NULL, 0.1, 0.5, 1.5, &f);
    ck_assert_msg(fabs(f - 0.62004) <= TOL_5DEC, "vm max %.7f", f);
    ck_assert_msg(fabs(z - 0.48086) <= TOL_5DEC, "vm max at z=%.7f", z);
}
END_TEST

/* ---- maximum von Mises with friction in the plane y = 0 ------------------------------------- */

typedef struct {
    int line; /* 0: point contact (Hamilton), 1: line contact (McEwen) */
    double mu;
} vm_par;

static double vm_xz(double x, double z, void *p)
{
    const vm_par *q = p;
    double s[6];
    if (q->line)
        mc_hertz_line_sliding(x, z, NU, q->mu, s);
    else
        mc_hertz_point_sliding(x, 0.0, z, NU, q->mu, s);
    return mc_von_mises(s);
}

static double vm_surface(double x, void *p) { return vm_xz(x, 0.0, p); }

/* Scan x in [-1.5, 1.5], z in [0, 1.2] with step 0.01, then refine the best subsurface point
 * (Nelder-Mead) and the best surface point (Brent along z = 0); the larger wins. */
static double vm_max_plane(vm_par *q, double *xm, double *zm)
{
    const double h = 0.01;
    double best_in = -1, xi = 0, zi = 0, best_s = -1, xs = 0;
    for (int i = 0; i <= 300; i++)
        for (int j = 0; j <= 120; j++) {
            double x = -1.5 + h * i, z = h * j, v = vm_xz(x, z, q);
            if (j == 0 && v > best_s) {
                best_s = v;
                xs = x;
            } else if (j > 0 && v > best_in) {
                best_in = v;
                xi = x;
                zi = z;
            }
        }
    double vin = simplex_max(vm_xz, q, &xi, &zi);
    double vs;
    xs = brent_max(vm_surface, q, xs - h, xs, xs + h, &vs);
    if (vs >= vin) {
        *xm = xs;
        *zm = 0.0;
        return vs;
    }
    *xm = xi;
    *zm = zi;
    return vin;
}

static void check_vm_table_row(const char *file, int line, int row, int ncols_expected)
{
    double *d;
    int cols;
    char hd[8][32];
    int rows = test_read_csv(file, &d, &cols, hd, 8);
    ck_assert_int_eq(cols, ncols_expected);
    ck_assert_int_lt(row, rows);
    const double *r = d + row * cols;
    double mu = r[col_of(hd, cols, "mu")], vt = r[col_of(hd, cols, "vm_max")];
    double xt = r[col_of(hd, cols, line ? "x_over_b" : "x_over_a")];
    double zt = r[col_of(hd, cols, line ? "z_over_b" : "z_over_a")];
    free(d);
    vm_par q = {line, mu};
    double x, z, v = vm_max_plane(&q, &x, &z);
    if (!line && zt == 0.0 && fabs(xt) > 0.99) {
        /* trailing-edge cusp: the supremum sits exactly at x = -a on the surface */
        ck_assert_msg(z == 0.0 && fabs(x + 1.0) <= TOL_CUSP_WHERE, "mu=%g: max at (%g, %g)", mu, x,
                      z);
        ck_assert_msg(v >= vt - TOL_5DEC && v <= vt + TOL_VM_CUSP, "mu=%g: edge %.6f vs table %.5f",
                      mu, v, vt);
        /* and the table value is our field at its printed (rounded) location */
        double lo = vm_surface(xt - TABLE_X_HALF_ULP, &q),
               hi = vm_surface(xt + TABLE_X_HALF_ULP, &q);
        ck_assert_msg(vt >= fmin(lo, hi) - TOL_5DEC && vt <= fmax(lo, hi) + TOL_5DEC,
                      "mu=%g: table %.5f not within [%.6f, %.6f] at x=%g", mu, vt, fmin(lo, hi),
                      fmax(lo, hi), xt);
        return;
    }
    ck_assert_msg(fabs(v - vt) <= TOL_VM_TABLE, "mu=%g: vm max %.7f vs table %.5f", mu, v, vt);
    ck_assert_msg(fabs(x - xt) <= TOL_VM_WHERE && fabs(z - zt) <= TOL_VM_WHERE,
                  "mu=%g: at (%.5f, %.5f) vs table (%.4f, %.4f)", mu, x, z, xt, zt);
    ck_assert((zt == 0.0) == (z == 0.0)); /* surface vs subsurface maximum as in the table */
}

START_TEST(test_point_vm_vs_mu) { check_vm_table_row("hertz_point_vm_vs_mu.csv", 0, _i, 5); }
END_TEST

START_TEST(test_line_vm_vs_mu) { check_vm_table_row("hertz_line_vm_vs_mu.csv", 1, _i, 4); }
END_TEST

/* ---- sliding = normal + mu tangential -------------------------------------------------------- */

START_TEST(test_sliding_superposition)
{
    const double mu = 0.37;
    for (int k = 0; k < 13; k++) {
        const double *p = equil_pts[k];
        double a[6], n[6], t[6];
        mc_hertz_point_sliding(p[0], p[1], p[2], NU, mu, a);
        mc_hertz_hamilton_normal(p[0], p[1], p[2], NU, n);
        mc_hertz_hamilton_tangential(p[0], p[1], p[2], NU, t);
        for (int c = 0; c < 6; c++)
            ck_assert(fabs(a[c] - (n[c] + mu * t[c])) <= TOL_TIGHT);
        mc_hertz_line_sliding(p[0], p[2], NU, mu, a);
        mc_mcewen_normal(p[0], p[2], NU, n);
        mc_mcewen_tangential(p[0], p[2], NU, t);
        for (int c = 0; c < 6; c++)
            ck_assert(fabs(a[c] - (n[c] + mu * t[c])) <= TOL_TIGHT);
    }
}
END_TEST

/* ---- line contact: relations ----------------------------------------------------------------- */

static double line_p(double x, void *par) { return mc_hertz_line_pressure(par, x); }

static const double pv_x[] = {-0.9, -0.5, 0.1, 0.3, 0.7, 0.95};

/* du_z/dx = -(2/(pi E*)) PV int p(s)/(x - s) ds = -x/R inside the contact (theory.md §6.3):
 * the condition that fixes b and p0. gsl_integration_qawc gives PV int f(s)/(s - c) ds. */
START_TEST(test_line_relations)
{
    double R = 20e-3, E = 115.38e9, P = 5e5; /* 500 N/mm */
    mc_hertz_line h;
    ck_assert_int_eq(mc_hertz_line_from_load(R, E, P, &h, NULL), MC_OK);
    ck_assert(fabs(h.p0 / sqrt(P * E / (M_PI * R)) - 1.0) <= TOL_TIGHT);
    ck_assert(fabs(h.p0 / (2.0 * P / (M_PI * h.b)) - 1.0) <= TOL_TIGHT);
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_function F = {line_p, &h};
    double v, e;
    ck_assert_int_eq(gsl_integration_qags(&F, -h.b, h.b, 0.0, 1e-13, 1000, w, &v, &e), GSL_SUCCESS);
    ck_assert_msg(fabs(v / P - 1.0) <= TOL_QUAD, "load %.17g vs %.17g", v, P);
    for (int k = 0; k < 6; k++) {
        double x = pv_x[k] * h.b;
        ck_assert_int_eq(gsl_integration_qawc(&F, -h.b, h.b, x, 0.0, 1e-12, 1000, w, &v, &e),
                         GSL_SUCCESS);
        double dudx = -2.0 / (M_PI * E) * (-v);
        ck_assert_msg(fabs(dudx / (-x / R) - 1.0) <= TOL_QUAD, "x/b=%g: du/dx %.17g vs %.17g",
                      pv_x[k], dudx, -x / R);
    }
    gsl_integration_workspace_free(w);
    ck_assert(mc_hertz_line_pressure(&h, 0.0) == h.p0 && mc_hertz_line_pressure(&h, h.b) == 0.0);
    ck_assert(fabs(mc_hertz_line_pressure(&h, -0.6 * h.b) / h.p0 - 0.8) <= TOL_TIGHT);
}
END_TEST

START_TEST(test_line_axis_table)
{
    double *d;
    int cols;
    char hd[8][32];
    int rows = test_read_csv("hertz_line_axis.csv", &d, &cols, hd, 8);
    ck_assert_int_ge(rows, 20);
    int cz = col_of(hd, cols, "z_over_b"), cx = col_of(hd, cols, "sigma_x"),
        cy = col_of(hd, cols, "sigma_y"), czz = col_of(hd, cols, "sigma_z"),
        ct = col_of(hd, cols, "tau1"), cv = col_of(hd, cols, "von_mises");
    for (int i = 0; i < rows; i++) {
        const double *row = d + i * cols;
        double z = row[cz], s[6];
        mc_mcewen_normal(0.0, z, NU, s);
        ck_assert_msg(fabs(s[MC_SXX] - row[cx]) <= TOL_6DEC, "z=%g sx %.9f vs %.9f", z, s[MC_SXX],
                      row[cx]);
        ck_assert(fabs(s[MC_SYY] - row[cy]) <= TOL_6DEC);
        ck_assert(fabs(s[MC_SZZ] - row[czz]) <= TOL_6DEC);
        ck_assert(fabs(0.5 * fabs(s[MC_SZZ] - s[MC_SXX]) - row[ct]) <= TOL_6DEC);
        ck_assert(fabs(mc_von_mises(s) - row[cv]) <= TOL_6DEC);
        ck_assert(s[MC_SXZ] == 0.0 && s[MC_SXY] == 0.0 && s[MC_SYZ] == 0.0);
    }
    free(d);
}
END_TEST

static double line_axis_tau1(double z, void *par)
{
    (void)par;
    double s[6];
    mc_mcewen_normal(0.0, z, NU, s);
    return 0.5 * fabs(s[MC_SZZ] - s[MC_SXX]);
}

static double line_axis_vm(double z, void *par)
{
    (void)par;
    double s[6];
    mc_mcewen_normal(0.0, z, NU, s);
    return mc_von_mises(s);
}

static double line_abs_txz(double x, double z, void *par)
{
    (void)par;
    double s[6];
    mc_mcewen_normal(x, z, NU, s);
    return fabs(s[MC_SXZ]);
}

START_TEST(test_line_maxima)
{
    double f, z = brent_max(line_axis_tau1, NULL, 0.2, 0.8, 1.5, &f);
    ck_assert_msg(fabs(f - 0.30028) <= TOL_5DEC, "tau1 max %.7f", f);
    ck_assert_msg(fabs(z - 0.78615) <= TOL_5DEC, "tau1 max at %.7f", z);
    z = brent_max(line_axis_vm, NULL, 0.2, 0.7, 1.5, &f);
    ck_assert_msg(fabs(f - 0.55752) <= TOL_5DEC, "vm max %.7f", f);
    ck_assert_msg(fabs(z - 0.70429) <= TOL_5DEC, "vm max at %.7f", z);
    /* |txz| = 1/4 exactly at (+-sqrt(3)/2, 1/2): m = sqrt(3)/2, n = 1/2 there */
    for (int sg = -1; sg <= 1; sg += 2) {
        double x = 0.8 * sg, zz = 0.45;
        f = simplex_max(line_abs_txz, NULL, &x, &zz);
        ck_assert_msg(fabs(f - 0.25) <= TOL_5DEC, "|txz| max %.9f", f);
        ck_assert_msg(fabs(x - sg * sqrt(3.0) / 2.0) <= TOL_5DEC && fabs(zz - 0.5) <= TOL_5DEC,
                      "|txz| max at (%.7f, %.7f)", x, zz);
    }
    double s[6];
    mc_mcewen_normal(sqrt(3.0) / 2.0, 0.5, NU, s);
    ck_assert(fabs(s[MC_SXZ] + 0.25) <= TOL_TIGHT); /* negative ahead of the centre (x > 0) */
}
END_TEST

/* ---- line contact: surface limits ------------------------------------------------------------ */

START_TEST(test_mcewen_surface)
{
    for (int k = -300; k <= 300; k++) {
        double x = 0.01 * k + 1e-4, n[6], t[6];
        mc_mcewen_normal(x, 0.0, NU, n);
        mc_mcewen_tangential(x, 0.0, NU, t);
        if (fabs(x) < 1.0) {
            double p = sqrt(1.0 - x * x);
            ck_assert_msg(fabs(n[MC_SXX] + p) <= TOL_TIGHT && fabs(n[MC_SZZ] + p) <= TOL_TIGHT,
                          "x=%g normal sxx %g szz %g vs %g", x, n[MC_SXX], n[MC_SZZ], -p);
            ck_assert(fabs(n[MC_SXZ]) <= TOL_TIGHT);
            ck_assert_msg(fabs(t[MC_SXX] + 2.0 * x) <= TOL_TIGHT, "x=%g tangential sxx %g", x,
                          t[MC_SXX]);
            ck_assert(fabs(t[MC_SXZ] + p) <= TOL_TIGHT && fabs(t[MC_SZZ]) <= TOL_TIGHT);
        } else {
            double sg = x > 0 ? 1.0 : -1.0;
            ck_assert(fabs(n[MC_SXX]) <= TOL_TIGHT && fabs(n[MC_SZZ]) <= TOL_TIGHT &&
                      fabs(n[MC_SXZ]) <= TOL_TIGHT);
            /* outside: sxx = -2 (x - sign(x) sqrt(x^2 - 1)) (Johnson 1985 ch. 7) */
            ck_assert(fabs(t[MC_SXX] + 2.0 * (x - sg * sqrt(x * x - 1.0))) <= TOL_TIGHT);
            ck_assert(fabs(t[MC_SXZ]) <= TOL_TIGHT && fabs(t[MC_SZZ]) <= TOL_TIGHT);
        }
        ck_assert(fabs(n[MC_SYY] - NU * (n[MC_SXX] + n[MC_SZZ])) <= TOL_TIGHT);
        ck_assert(fabs(t[MC_SYY] - NU * (t[MC_SXX] + t[MC_SZZ])) <= TOL_TIGHT);
    }
    /* the edge itself returns the continuous surface limit */
    double n[6], t[6];
    mc_mcewen_normal(1.0, 0.0, NU, n);
    mc_mcewen_tangential(-1.0, 0.0, NU, t);
    ck_assert(n[MC_SXX] == 0.0 && n[MC_SZZ] == 0.0 && fabs(t[MC_SXX] - 2.0) <= TOL_TIGHT);
}
END_TEST

/* ---- line contact: McEwen and the strip against quadrature of Flamant ---------------------- */

typedef struct {
    double x, z;
    int comp, tangential;
} flam_par;

static double flamant_at(double s, void *p)
{
    const flam_par *q = p;
    double f[6];
    if (q->tangential)
        mc_flamant_tangential(q->x - s, q->z, NU, f);
    else
        mc_flamant_normal(q->x - s, q->z, NU, f);
    return f[q->comp];
}

static const double line_pts[][2] = {{0.0, 0.3}, {0.5, 0.2},  {0.95, 0.05}, {-0.7, 0.6},
                                     {1.5, 0.4}, {-2.0, 1.0}, {0.3, 2.0},   {0.05, 0.01}};

/* McEwen = int sqrt(1 - s^2) Flamant(x - s, z) ds: GSL's QAWS with the algebraic weight
 * (1+s)^(1/2) (1-s)^(1/2) integrates the square-root edges exactly. */
START_TEST(test_mcewen_vs_flamant)
{
    const double *p = line_pts[_i];
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_integration_qaws_table *tb = gsl_integration_qaws_table_alloc(0.5, 0.5, 0, 0);
    for (int tang = 0; tang <= 1; tang++) {
        double ref[6], s[6];
        for (int c = 0; c < 6; c++) {
            if (c == MC_SXY || c == MC_SYZ) {
                ref[c] = 0.0;
                continue;
            }
            flam_par q = {p[0], p[1], c, tang};
            gsl_function F = {flamant_at, &q};
            double e;
            ck_assert_int_eq(
                gsl_integration_qaws(&F, -1.0, 1.0, tb, 1e-14, 1e-12, 1000, w, &ref[c], &e),
                GSL_SUCCESS);
        }
        if (tang)
            mc_mcewen_tangential(p[0], p[1], NU, s);
        else
            mc_mcewen_normal(p[0], p[1], NU, s);
        ck_assert_msg(maxabs_diff6(s, ref) <= TOL_QUAD, "(%g,%g) %s: McEwen vs quadrature %g", p[0],
                      p[1], tang ? "tangential" : "normal", maxabs_diff6(s, ref));
    }
    gsl_integration_qaws_table_free(tb);
    gsl_integration_workspace_free(w);
}
END_TEST

#define STRIP_A 1.3 /* half-width, same length unit as x, z */

START_TEST(test_strip_vs_flamant)
{
    const double *p = line_pts[_i];
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    double ref[6] = {0}, s[6];
    for (int c = 0; c < 6; c++) {
        if (c == MC_SXY || c == MC_SYZ)
            continue;
        flam_par q = {p[0], p[1], c, 0};
        gsl_function F = {flamant_at, &q};
        double e;
        double pts[3] = {-STRIP_A, p[0], STRIP_A}; /* the kernel peaks under the field point */
        int np = fabs(p[0]) < STRIP_A ? 3 : 0;
        if (np)
            ck_assert_int_eq(gsl_integration_qagp(&F, pts, 3, 1e-14, 1e-12, 1000, w, &ref[c], &e),
                             GSL_SUCCESS);
        else
            ck_assert_int_eq(
                gsl_integration_qags(&F, -STRIP_A, STRIP_A, 1e-14, 1e-12, 1000, w, &ref[c], &e),
                GSL_SUCCESS);
    }
    mc_flamant_strip_uniform(p[0], p[1], STRIP_A, NU, s);
    ck_assert_msg(maxabs_diff6(s, ref) <= TOL_QUAD, "(%g,%g): strip vs quadrature %g", p[0], p[1],
                  maxabs_diff6(s, ref));
    gsl_integration_workspace_free(w);
}
END_TEST

START_TEST(test_strip_surface)
{
    double s[6];
    for (int k = -40; k <= 40; k++) {
        double x = 0.05 * k + 1e-3;
        mc_flamant_strip_uniform(x, 0.0, STRIP_A, NU, s);
        double expect = fabs(x) < STRIP_A ? -1.0 : 0.0;
        ck_assert(fabs(s[MC_SXX] - expect) <= TOL_TIGHT && fabs(s[MC_SZZ] - expect) <= TOL_TIGHT);
        ck_assert(fabs(s[MC_SXZ]) <= TOL_TIGHT);
    }
    mc_flamant_strip_uniform(STRIP_A, 0.0, STRIP_A, NU, s); /* edge: mean of the one-sided values */
    ck_assert(fabs(s[MC_SZZ] + 0.5) <= TOL_TIGHT);
    /* far away the strip acts as a Flamant line load of 2a */
    double f[6];
    mc_flamant_strip_uniform(300.0, 400.0, STRIP_A, NU, s);
    mc_flamant_normal(300.0, 400.0, NU, f);
    for (int c = 0; c < 6; c++)
        ck_assert(fabs(s[c] - 2.0 * STRIP_A * f[c]) <=
                  TOL_FAR_STRIP * fabs(2.0 * STRIP_A * f[MC_SZZ]));
}
END_TEST

/* ---- Flamant: resultants and equilibrium ---------------------------------------------------- */

typedef struct {
    int kind; /* 0 normal, 1 tangential, 2 anti-plane */
    int comp;
    double z;
} res_par;

static double flamant_line(double x, void *p)
{
    const res_par *q = p;
    double s[6];
    if (q->kind == 0)
        mc_flamant_normal(x, q->z, NU, s);
    else if (q->kind == 1)
        mc_flamant_tangential(x, q->z, NU, s);
    else
        mc_flamant_antiplane(x, q->z, s);
    return s[q->comp];
}

/* On any plane z = const the tractions balance the unit line load: int szz dx = -1 (normal),
 * int sxz dx = -1 (tangential), int syz dx = -1 (anti-plane); the other two resultants vanish. */
START_TEST(test_flamant_resultants)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    const double zs[] = {0.1, 1.0, 7.0};
    for (int k = 0; k < 3; k++)
        for (int kind = 0; kind < 3; kind++) {
            int comps[3] = {MC_SZZ, MC_SXZ, MC_SYZ};
            for (int j = 0; j < 3; j++) {
                res_par q = {kind, comps[j], zs[k]};
                gsl_function F = {flamant_line, &q};
                double pts[3] = {-1.0, 0.0, 1.0}, v, vl, vr, e;
                /* split at 0 where the kernel peaks; tails by qagi */
                ck_assert_int_eq(gsl_integration_qagp(&F, pts, 3, 1e-14, 1e-12, 1000, w, &v, &e),
                                 GSL_SUCCESS);
                ck_assert_int_eq(gsl_integration_qagil(&F, -1.0, 1e-14, 1e-12, 1000, w, &vl, &e),
                                 GSL_SUCCESS);
                ck_assert_int_eq(gsl_integration_qagiu(&F, 1.0, 1e-14, 1e-12, 1000, w, &vr, &e),
                                 GSL_SUCCESS);
                double total = v + vl + vr, expect = (kind == j) ? -1.0 : 0.0;
                ck_assert_msg(fabs(total - expect) <= TOL_QUAD, "kind %d comp %d z=%g: %.15g", kind,
                              comps[j], zs[k], total);
            }
        }
    gsl_integration_workspace_free(w);
}
END_TEST

typedef void (*field2)(double, double, double, double[6]);
static void flamant_antiplane2(double x, double z, double nu, double s[6])
{
    (void)nu;
    mc_flamant_antiplane(x, z, s);
}
static void strip2(double x, double z, double nu, double s[6])
{
    mc_flamant_strip_uniform(x, z, STRIP_A, nu, s);
}

/* plane problems: d/dx sxx + d/dz sxz = 0, d/dx sxz + d/dz szz = 0, d/dx sxy + d/dz syz = 0 */
static double div_residual2(field2 f, double x, double z)
{
    double p[6], m[6], dx[6], dz[6];
    f(x + H_FD, z, NU, p);
    f(x - H_FD, z, NU, m);
    for (int c = 0; c < 6; c++)
        dx[c] = (p[c] - m[c]) / (2 * H_FD);
    f(x, z + H_FD, NU, p);
    f(x, z - H_FD, NU, m);
    for (int c = 0; c < 6; c++)
        dz[c] = (p[c] - m[c]) / (2 * H_FD);
    double r1 = dx[MC_SXX] + dz[MC_SXZ], r2 = dx[MC_SXZ] + dz[MC_SZZ], r3 = dx[MC_SXY] + dz[MC_SYZ];
    return fmax(fabs(r1), fmax(fabs(r2), fabs(r3)));
}

START_TEST(test_line_equilibrium)
{
    const double *p = line_pts[_i];
    field2 fs[6] = {mc_mcewen_normal,      mc_mcewen_tangential, mc_flamant_normal,
                    mc_flamant_tangential, flamant_antiplane2,   strip2};
    const char *names[6] = {"McEwen normal",      "McEwen tangential",  "Flamant normal",
                            "Flamant tangential", "Flamant anti-plane", "strip"};
    for (int k = 0; k < 6; k++) {
        if (k >= 2 && k <= 4 && p[1] < 0.1)
            continue; /* Flamant: 1/r^2 grows too steep for H_FD near the load point */
        double r = div_residual2(fs[k], p[0], p[1]);
        ck_assert_msg(r <= TOL_EQUIL, "%s: div sigma = %g at (%g, %g)", names[k], r, p[0], p[1]);
    }
}
END_TEST



/* The elliptical Hertz contact: the circle at equal radii; against an independent numerical
 * solve (the FFT contact solver on a smooth ellipsoid, Rx = 2 mm, Ry = 8 mm) and against Hamrock
 * & Brewe's fit k = 1.0339 (Ry/Rx)^0.636 of the axis ratio (their stated accuracy ~3 %). */
START_TEST(test_ellipse)
{
    mc_error err = {0};
    mc_hertz_ellipse h;
    mc_hertz_point c;
    const double es = 115.4e9, P = 5.0;
    ck_assert_int_eq(mc_hertz_ellipse_from_load(3e-3, 3e-3, es, P, &h, &err), MC_OK);
    ck_assert_int_eq(mc_hertz_point_from_load(3e-3, es, P, &c, &err), MC_OK);
    ck_assert_double_eq_tol(h.ax, c.a, 1e-15 * c.a);
    ck_assert_double_eq_tol(h.p0, c.p0, 1e-14 * c.p0);
    ck_assert_double_eq_tol(h.delta, c.a * c.a / 3e-3, 1e-12 * h.delta);
    /* continuity near the circle: ratio 1.01 within its own first-order change */
    ck_assert_int_eq(mc_hertz_ellipse_from_load(3e-3, 3.03e-3, es, P, &h, &err), MC_OK);
    ck_assert_double_le(fabs(h.ay / h.ax - 1.0), 0.01);
    ck_assert_double_le(fabs(h.p0 / c.p0 - 1.0), 0.01);
    /* the numerical solve */
    ck_assert_int_eq(mc_hertz_ellipse_from_load(2e-3, 8e-3, es, P, &h, &err), MC_OK);
    ck_assert_double_gt(h.ay, h.ax);
    const double k_hb = 1.0339 * pow(4.0, 0.636);
    ck_assert_double_le(fabs(h.ay / h.ax / k_hb - 1.0), 0.02);
    const double dx = h.ax / 16.0;
    const int nx = 64, ny = (int)ceil(4.0 * h.ay / dx) + 1;
    mc_grid g = {nx, ny, dx, dx, 0, 0};
    const size_t n = (size_t)nx * (size_t)ny;
    double *hh = calloc(n, sizeof *hh), *p = calloc(n, sizeof *p), *gap = calloc(n, sizeof *gap);
    ck_assert(hh && p && gap);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            hh[(size_t)j * nx + i] = x * x / (2 * h.Rx) + y * y / (2 * h.Ry);
        }
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_operator_plan_love(&g, es, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {MC_METHOD_CG, 1e-10, 5000, 0, 0};
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    mc_contact_problem prob = {.h = hh, .p_cap = INFINITY, .control = MC_CONTROL_FORCE, .load = P};
    mc_contact_summary sum;
    ck_assert_int_eq(mc_contact_solve(s, &prob, p, NULL, gap, &sum, &err), MC_OK);
    /* the extents: the last loaded cell along each axis through the centre, within one cell */
    double xmax = 0, ymax = 0, pmax = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            if (p[(size_t)j * nx + i] > 0) {
                xmax = test_worst(xmax, fabs(mc_grid_x(&g, i)));
                ymax = test_worst(ymax, fabs(mc_grid_y(&g, j)));
                pmax = test_worst(pmax, p[(size_t)j * nx + i]);
            }
    if (getenv("MC_TEST_VERBOSE"))
        printf("ellipse: p_max/p0 %.5f, x extent/ax %.4f, y extent/ay %.4f, approach/delta %.5f\n",
               pmax / h.p0, xmax / h.ax, ymax / h.ay, sum.approach / h.delta);
    ck_assert_double_le(fabs(pmax / h.p0 - 1.0), 0.01); /* 16 cells per short semi-axis */
    ck_assert_double_le(fabs(xmax - h.ax), dx);
    ck_assert_double_le(fabs(ymax - h.ay), dx);
    ck_assert_double_le(fabs(sum.approach / h.delta - 1.0), 0.01);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    free(hh);
    free(p);
    free(gap);
}
END_TEST

Suite *suite_hertz(void);
Suite *suite_hertz(void)
{
    Suite *s = suite_create("hertz");
    TCase *tc = tcase_create("point");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_point_relations, 0, 3);
    tcase_add_test(tc, test_input_errors);
    tcase_add_test(tc, test_ellipse);
    tcase_add_loop_test(tc, test_point_uz_quadrature, 0, (int)(sizeof uz_rho / sizeof uz_rho[0]));
    tcase_add_test(tc, test_point_uz_far_field);
    tcase_add_test(tc, test_point_axis_table);
    tcase_add_test(tc, test_point_field_table);
    tcase_add_test(tc, test_huber_sign);
    tcase_add_loop_test(tc, test_point_near_axis, 0, (int)(sizeof near_z / sizeof near_z[0]));
    tcase_add_loop_test(tc, test_point_equilibrium, 0,
                        (int)(sizeof equil_pts / sizeof equil_pts[0]));
    tcase_add_test(tc, test_point_surface_tractions);
    tcase_add_test(tc, test_point_surface);
    tcase_add_test(tc, test_point_maxima);
    tcase_add_loop_test(tc, test_point_vm_vs_mu, 0, 7);
    tcase_add_test(tc, test_sliding_superposition);
    suite_add_tcase(s, tc);

    TCase *tl = tcase_create("line");
    tcase_add_checked_fixture(tl, setup, NULL);
    tcase_set_timeout(tl, 120);
    tcase_add_test(tl, test_line_relations);
    tcase_add_test(tl, test_line_axis_table);
    tcase_add_test(tl, test_line_maxima);
    tcase_add_loop_test(tl, test_line_vm_vs_mu, 0, 8);
    tcase_add_test(tl, test_mcewen_surface);
    tcase_add_loop_test(tl, test_mcewen_vs_flamant, 0, (int)(sizeof line_pts / sizeof line_pts[0]));
    tcase_add_loop_test(tl, test_strip_vs_flamant, 0, (int)(sizeof line_pts / sizeof line_pts[0]));
    tcase_add_test(tl, test_strip_surface);
    tcase_add_test(tl, test_flamant_resultants);
    tcase_add_loop_test(tl, test_line_equilibrium, 0, (int)(sizeof line_pts / sizeof line_pts[0]));
    suite_add_tcase(s, tl);
    return s;
}
