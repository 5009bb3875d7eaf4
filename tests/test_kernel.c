/* test_kernel.c - influence functions (src/kernel.c) against the dossier's reference table
 * (tests/data/physics/rect_kernels_ref.csv), adaptive 2-D quadrature of the point-force solutions,
 * closed-form limits, and the defining properties of the point forms (equilibrium, traction-free
 * surface, force resultants). Sections and equations refer to docs/theory.md. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "kernels/kernel.h"
#include "test_util.h"

/* ---- tolerances ------------------------------------------------------------------------------ */

/* Round-off tier: the corner sums obtain far-field values as differences of O(1) corner terms, so
 * the relative error grows like eps (r/a)^2 (theory.md §2.2, §5.5); 64 eps covers the few dozen
 * operations per corner and the 16-digit table. */
#define TOL_FAR_EPS (64.0 * DBL_EPSILON)
/* Adaptive quadrature tier: QUAD_EPSREL is the relative accuracy asked of GSL's qags (the nested
 * inner integrals 10x tighter); agreement is accepted to 100x that, because the error estimate is
 * not a bound and the inner integrals feed round-off noise into the outer integrand. */
#define QUAD_EPSREL 1e-12
#define TOL_QUAD (100.0 * QUAD_EPSREL)
/* Discretisation tier: the far-field point-load approximation of theory.md §2.2 at r = 20 dx;
 * beyond the quadrupole term the next one is O((a/r)^4) with a coefficient below 1. */
#define FAR_FIELD_R_OVER_DX 20.0
#define TOL_FAR_FIELD 1.6e-4
/* Surface limit (theory.md §5.5): kernels at z = 1e-9 a differ from z = 0 by < 3e-9. */
#define CONT_Z_OVER_A 1e-9
#define TOL_CONTINUITY 3e-9
/* Finite differences: 4th-order central stencil at h = 1e-3 rho: truncation ~ (h/rho)^4 times
 * O(10) derivative ratios, round-off ~ eps rho/h; both far below this. */
#define FD_H_OVER_RHO 1e-3
#define TOL_FD 1e-9
/* Near-surface traction of the point forms: sigma_iz is O(z/r) relative (theory.md §5.1, §5.2). */
#define NEAR_SURFACE_Z_OVER_R 1e-6
#define TOL_NEAR_SURFACE (10.0 * NEAR_SURFACE_Z_OVER_R)

#define QUAD_LIMIT 1000

/* ---- the reference table --------------------------------------------------------------------- */

#define REF_TABLE "rect_kernels_ref.csv"
#define REF_MAX_COLS 40
#define N_REF_ROWS 12 /* rows of the table; checked, so a grown table cannot go half-tested */

typedef struct {
    double a, b, E, nu; /* from the table's comment line */
    double *data;
    int rows, cols;
    char head[REF_MAX_COLS][32];
} ref_table;

/* Value of "key=" in the comment line, e.g. "a=0.5e-6 m". */
static double header_value(const char *line, const char *key)
{
    const char *p = strstr(line, key);
    ck_assert_msg(p != NULL, "%s: no '%s' in the header comment", REF_TABLE, key);
    char *end;
    double v = strtod(p + strlen(key), &end);
    ck_assert_msg(end != p + strlen(key), "%s: bad value for '%s'", REF_TABLE, key);
    return v;
}

static void ref_load(ref_table *t)
{
    char path[1024], line[4096];
    snprintf(path, sizeof path, "%s/%s", test_physics_dir(), REF_TABLE);
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    ck_assert(fgets(line, sizeof line, f) != NULL && line[0] == '#');
    fclose(f);
    t->a = header_value(line, " a=");
    t->b = header_value(line, " b=");
    t->E = header_value(line, " E=");
    t->nu = header_value(line, " nu=");
    t->rows = test_read_csv(REF_TABLE, &t->data, &t->cols, t->head, REF_MAX_COLS);
    ck_assert_int_gt(t->rows, 0);
}

static int ref_col(const ref_table *t, const char *name)
{
    for (int c = 0; c < t->cols; c++)
        if (strcmp(t->head[c], name) == 0)
            return c;
    ck_abort_msg("%s: no column %s", REF_TABLE, name);
    return -1;
}

static double ref_at(const ref_table *t, int row, const char *name)
{
    return t->data[(size_t)row * (size_t)t->cols + (size_t)ref_col(t, name)];
}

/* ---- helpers --------------------------------------------------------------------------------- */

typedef void (*stress_fn)(double x, double y, double z, double a, double b, double nu,
                          double s[6]);
typedef void (*point_fn)(double x, double y, double z, double nu, double s[6]);
typedef void (*corner_fn)(double X, double Y, double z, double nu, double f[6]);

static const char *const load_name[3] = {"p", "qx", "qy"};
static const stress_fn rect_fn[3] = {mc_rect_stress_p, mc_rect_stress_qx, mc_rect_stress_qy};
static const point_fn point_fn_of[3] = {mc_point_stress_p, mc_point_stress_qx, mc_point_stress_qy};
static const corner_fn corner_fn_of[3] = {mc_rect_corner_p, mc_rect_corner_qx, mc_rect_corner_qy};

static double max_abs6(const double s[6])
{
    double m = 0.0;
    for (int c = 0; c < MC_NSTRESS; c++)
        if (fabs(s[c]) > m)
            m = fabs(s[c]);
    return m;
}

/* Half-sides used away from the table: a != b so that x/y mix-ups show. */
#define HA 0.5e-6
#define HB 0.4e-6
#define NU 0.3

/* ---- nested adaptive quadrature over a rectangle --------------------------------------------- */

typedef double (*integrand2)(double xi, double eta, void *ctx);

typedef struct {
    integrand2 f;
    void *ctx;
    double xi, eta0, eta1, epsabs, epsrel;
    gsl_integration_workspace *win;
    int status; /* first failing GSL status of an inner integral */
} quad2;

static double quad2_inner(double eta, void *p)
{
    quad2 *q = p;
    return q->f(q->xi, eta, q->ctx);
}

static double quad2_outer(double xi, void *p)
{
    quad2 *q = p;
    q->xi = xi;
    gsl_function F = {quad2_inner, q};
    double r, e;
    int st = gsl_integration_qags(&F, q->eta0, q->eta1, q->epsabs, q->epsrel, QUAD_LIMIT, q->win,
                                  &r, &e);
    if (st && !q->status)
        q->status = st;
    return r;
}

/* Integral of f over [-a,a] x [-b,b], split at (xs, ys) (clamped to the rectangle) so that a
 * singularity or peak at the field point sits at a corner of every piece. */
static double quad2_rect(integrand2 f, void *ctx, double a, double b, double xs, double ys,
                         double epsabs, double epsrel)
{
    double xc = fmin(fmax(xs, -a), a), yc = fmin(fmax(ys, -b), b);
    double xe[3] = {-a, xc, a}, ye[3] = {-b, yc, b};
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(QUAD_LIMIT);
    gsl_integration_workspace *wi = gsl_integration_workspace_alloc(QUAD_LIMIT);
    ck_assert(wo != NULL && wi != NULL);
    double sum = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            if (xe[i + 1] <= xe[i] || ye[j + 1] <= ye[j])
                continue;
            quad2 q = {.f = f, .ctx = ctx, .eta0 = ye[j], .eta1 = ye[j + 1],
                       .epsabs = 0.1 * epsabs / (xe[i + 1] - xe[i]), .epsrel = 0.1 * epsrel,
                       .win = wi, .status = 0};
            gsl_function F = {quad2_outer, &q};
            double r, e;
            int st = gsl_integration_qags(&F, xe[i], xe[i + 1], 0.25 * epsabs, epsrel, QUAD_LIMIT,
                                          wo, &r, &e);
            ck_assert_msg(st == GSL_SUCCESS, "outer quadrature: %s", gsl_strerror(st));
            ck_assert_msg(q.status == GSL_SUCCESS, "inner quadrature: %s", gsl_strerror(q.status));
            sum += r;
        }
    gsl_integration_workspace_free(wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* ---- 1. mc_love_uz against the reference table ----------------------------------------------- */

START_TEST(test_love_uz_table)
{
    ref_table t;
    ref_load(&t);
    const double Estar = t.E / (1.0 - t.nu * t.nu); /* single body, as the table states */
    int checked = 0;
    for (int r = 0; r < t.rows; r++) {
        if (ref_at(&t, r, "z") != 0.0)
            continue; /* displacements are surface values only */
        double x = ref_at(&t, r, "x"), y = ref_at(&t, r, "y");
        double want = ref_at(&t, r, "uz_p");
        double got = mc_love_uz(x, y, t.a, t.b) / Estar;
        double rr = hypot(x, y) / fmin(t.a, t.b);
        double tol = TOL_FAR_EPS * (1.0 + rr * rr);
        ck_assert_msg(fabs(got - want) <= tol * fabs(want), "row %d: uz %.16e want %.16e", r, got,
                      want);
        checked++;
    }
    ck_assert_int_ge(checked, 3);
    ck_assert_int_eq(t.rows, N_REF_ROWS);
    free(t.data);
}
END_TEST

/* ---- 2. mc_love_uz against quadrature of the point solution ---------------------------------- */

typedef struct {
    double x, y;
} love_ctx;

static double love_integrand(double xi, double eta, void *p)
{
    const love_ctx *c = p;
    return mc_point_uz(hypot(c->x - xi, c->y - eta));
}

/* inside, near an edge, on both kinds of edge, at corners, outside, far away (in units of a, b) */
static const double love_pts[][2] = {
    {0.0, 0.0}, {0.3, -0.6}, {0.95, 0.2}, {1.0, 0.5}, {-0.4, -1.0},
    {1.0, 1.0}, {-1.0, 1.0}, {1.5, 0.3}, {-2.0, 3.0}, {30.0, -20.0},
};

START_TEST(test_love_uz_quadrature)
{
    mc_gsl_quiet();
    love_ctx c = {love_pts[_i][0] * HA, love_pts[_i][1] * HB};
    double want = quad2_rect(love_integrand, &c, HA, HB, c.x, c.y, 0.0, QUAD_EPSREL);
    double got = mc_love_uz(c.x, c.y, HA, HB);
    ck_assert_msg(fabs(got - want) <= TOL_QUAD * fabs(want), "(%g a, %g b): %.16e vs %.16e",
                  love_pts[_i][0], love_pts[_i][1], got, want);
}
END_TEST

/* ---- 3. closed-form values and properties of mc_love_uz, mc_combined_modulus ----------------- */

START_TEST(test_love_square_centre)
{
    const double c = 2.0 * HA; /* side of the square */
    double want = 4.0 * log(1.0 + sqrt(2.0)) / M_PI * c;
    double got = mc_love_uz(0.0, 0.0, HA, HA);
    ck_assert_msg(fabs(got - want) <= TOL_TIGHT * want, "%.16e vs %.16e", got, want);
}
END_TEST

START_TEST(test_love_even)
{
    double x = love_pts[_i][0] * HA, y = love_pts[_i][1] * HB;
    double u = mc_love_uz(x, y, HA, HB);
    ck_assert(u > 0.0);
    ck_assert(fabs(mc_love_uz(-x, y, HA, HB) - u) <= TOL_TIGHT * u);
    ck_assert(fabs(mc_love_uz(x, -y, HA, HB) - u) <= TOL_TIGHT * u);
    ck_assert(fabs(mc_love_uz(-x, -y, HA, HB) - u) <= TOL_TIGHT * u);
}
END_TEST

/* At r = 20 dx the point-load approximation A/(pi r) holds to 1.6e-4 (theory.md §2.2), and the
 * error is the quadrupole term (1/2)[(a^2/3) d_xx + (b^2/3) d_yy](1/r) / (1/r) up to O((a/r)^4). */
START_TEST(test_love_far_field)
{
    static const double angles[] = {0.0, 0.3, M_PI / 4.0, 1.2, M_PI / 2.0, 2.5};
    const double dx = 2.0 * HA, A = 4.0 * HA * HB;
    const double r = FAR_FIELD_R_OVER_DX * dx;
    for (size_t k = 0; k < sizeof angles / sizeof angles[0]; k++) {
        double x = r * cos(angles[k]), y = r * sin(angles[k]);
        double u = mc_love_uz(x, y, HA, HB), u0 = A * mc_point_uz(r);
        double err = u / u0 - 1.0;
        double quad = 0.5 * (HA * HA / 3.0 * (3.0 * x * x - r * r) +
                             HB * HB / 3.0 * (3.0 * y * y - r * r)) / (r * r * r * r);
        double hexa = pow(fmax(HA, HB) / r, 4.0);
        ck_assert_msg(fabs(err) <= TOL_FAR_FIELD, "angle %g: rel. error %.3e", angles[k], err);
        ck_assert_msg(fabs(err - quad) <= hexa, "angle %g: %.6e vs quadrupole %.6e", angles[k],
                      err, quad);
    }
}
END_TEST

START_TEST(test_combined_modulus)
{
    const double E = 210e9, nu = 0.3, E2 = 115e9, nu2 = 0.34;
    double same = mc_combined_modulus(E, nu, E, nu, 0);
    double rigid = mc_combined_modulus(E, nu, E2, nu2, 1);
    double mixed = mc_combined_modulus(E, nu, E2, nu2, 0);
    double want_mixed = 1.0 / ((1.0 - nu * nu) / E + (1.0 - nu2 * nu2) / E2);
    ck_assert(fabs(same - E / (2.0 * (1.0 - nu * nu))) <= TOL_TIGHT * same);
    ck_assert(fabs(rigid - E / (1.0 - nu * nu)) <= TOL_TIGHT * rigid);
    ck_assert(fabs(mixed - want_mixed) <= TOL_TIGHT * mixed);
    ck_assert(fabs(mc_combined_modulus(E2, nu2, E, nu, 0) - mixed) <= TOL_TIGHT * mixed);
}
END_TEST

/* ---- 4. all 18 stress kernels against the reference table ------------------------------------ */

START_TEST(test_rect_stress_table)
{
    ref_table t;
    ref_load(&t);
    ck_assert_int_gt(t.rows, _i);
    const int r = _i;
    double x = ref_at(&t, r, "x"), y = ref_at(&t, r, "y"), z = ref_at(&t, r, "z");
    double rr = sqrt(x * x + y * y + z * z) / fmin(t.a, t.b);
    double tol = TOL_FAR_EPS * (1.0 + rr * rr);
    for (int L = 0; L < 3; L++) {
        double s[MC_NSTRESS], want[MC_NSTRESS];
        rect_fn[L](x, y, z, t.a, t.b, t.nu, s);
        for (int c = 0; c < MC_NSTRESS; c++) {
            char col[32];
            snprintf(col, sizeof col, "s%s_%s", mc_component_name(c), load_name[L]);
            want[c] = ref_at(&t, r, col);
        }
        double scale = max_abs6(want);
        for (int c = 0; c < MC_NSTRESS; c++)
            ck_assert_msg(fabs(s[c] - want[c]) <= tol * scale,
                          "row %d (%g,%g,%g) %s s%s: %.16e want %.16e (tol %.1e)", r, x, y, z,
                          load_name[L], mc_component_name(c), s[c], want[c], tol * scale);
    }
    free(t.data);
}
END_TEST

/* ---- 5. rectangle stresses against quadrature of the point-force stresses -------------------- */

typedef struct {
    point_fn f;
    int c;
    double x, y, z;
} stress_ctx;

static double stress_integrand(double xi, double eta, void *p)
{
    const stress_ctx *k = p;
    double s[MC_NSTRESS];
    k->f(k->x - xi, k->y - eta, k->z, NU, s);
    return s[k->c];
}

/* (x/a, y/b, z/a): inside, shallow inside, on an edge, beyond a corner, outside, far, deep; then
 * far along -y and -x within the patch's strip, on and just below the surface, where ln(Y + rho)
 * and ln(X + rho) need their cancellation-free forms (theory.md §5.5) */
static const double quad_pts[][3] = {
    {0.3, 0.2, 0.1}, {-0.4, 0.5, 0.02}, {1.0, 0.3, 0.2}, {1.05, -1.1, 0.3},
    {-3.0, 2.0, 0.7}, {10.0, -6.0, 2.0}, {0.0, 0.0, 3.0},
    {0.0, -200.0, 0.0}, {-150.0, 0.4, 0.0}, {-0.2, -150.0, 0.01},
};
#define N_QUAD_PTS ((int)(sizeof quad_pts / sizeof quad_pts[0]))

START_TEST(test_rect_stress_quadrature)
{
    mc_gsl_quiet();
    const int L = _i % 3, k = _i / 3;
    const double x = quad_pts[k][0] * HA, y = quad_pts[k][1] * HB, z = quad_pts[k][2] * HA;
    double s[MC_NSTRESS];
    rect_fn[L](x, y, z, HA, HB, NU, s);
    const double scale = max_abs6(s);
    const double rr = sqrt(x * x + y * y + z * z) / fmin(HA, HB);
    const double tol = TOL_QUAD + TOL_FAR_EPS * (1.0 + rr * rr);
    for (int c = 0; c < MC_NSTRESS; c++) {
        stress_ctx ctx = {point_fn_of[L], c, x, y, z};
        double want = quad2_rect(stress_integrand, &ctx, HA, HB, x, y, QUAD_EPSREL * scale,
                                 QUAD_EPSREL);
        ck_assert_msg(fabs(s[c] - want) <= tol * scale,
                      "%s at (%g a, %g b, %g a) s%s: %.16e vs quadrature %.16e", load_name[L],
                      quad_pts[k][0], quad_pts[k][1], quad_pts[k][2], mc_component_name(c), s[c],
                      want);
    }
}
END_TEST

/* ---- 6. surface limits and the z -> 0 continuity --------------------------------------------- */

/* points inside the patch at z = 0 (units of a, b), away from its edges */
static const double inside_pts[][2] = {{0.0, 0.0}, {0.3, -0.5}, {-0.7, 0.6}, {0.9, 0.9}};
#define N_INSIDE ((int)(sizeof inside_pts / sizeof inside_pts[0]))

START_TEST(test_surface_limits)
{
    const double x = inside_pts[_i][0] * HA, y = inside_pts[_i][1] * HB;
    double p[MC_NSTRESS], qx[MC_NSTRESS], qy[MC_NSTRESS];
    mc_rect_stress_p(x, y, 0.0, HA, HB, NU, p);
    mc_rect_stress_qx(x, y, 0.0, HA, HB, NU, qx);
    mc_rect_stress_qy(x, y, 0.0, HA, HB, NU, qy);
    /* the surface carries the load: t = sigma . (-e_z) equals the applied traction */
    ck_assert(fabs(p[MC_SZZ] + 1.0) <= TOL_TIGHT);
    ck_assert(fabs(p[MC_SXZ]) <= TOL_TIGHT && fabs(p[MC_SYZ]) <= TOL_TIGHT);
    ck_assert(fabs(qx[MC_SXZ] + 1.0) <= TOL_TIGHT);
    ck_assert(fabs(qx[MC_SZZ]) <= TOL_TIGHT && fabs(qx[MC_SYZ]) <= TOL_TIGHT);
    ck_assert(fabs(qy[MC_SYZ] + 1.0) <= TOL_TIGHT);
    ck_assert(fabs(qy[MC_SZZ]) <= TOL_TIGHT && fabs(qy[MC_SXZ]) <= TOL_TIGHT);
    /* at z = 0, S[T(X,Y) + T(Y,X)] = S[theta] = 2 pi inside, so sxx + syy = -(1 + 2 nu) anywhere
     * inside (theory.md §5.5, own-cell values) */
    ck_assert_msg(fabs(p[MC_SXX] + p[MC_SYY] + (1.0 + 2.0 * NU)) <= TOL_TIGHT, "sxx+syy = %.16e",
                  p[MC_SXX] + p[MC_SYY]);
}
END_TEST

START_TEST(test_square_centre_stress)
{
    static const double nus[] = {0.0, 0.25, 0.3, 0.5};
    const double nu = nus[_i];
    double s[MC_NSTRESS];
    mc_rect_stress_p(0.0, 0.0, 0.0, HA, HA, nu, s);
    const double want = -(1.0 + 2.0 * nu) / 2.0;
    ck_assert_msg(fabs(s[MC_SXX] - want) <= TOL_TIGHT, "nu %g: sxx %.16e", nu, s[MC_SXX]);
    ck_assert_msg(fabs(s[MC_SYY] - want) <= TOL_TIGHT, "nu %g: syy %.16e", nu, s[MC_SYY]);
    ck_assert(fabs(s[MC_SZZ] + 1.0) <= TOL_TIGHT);
    ck_assert(fabs(s[MC_SXY]) <= TOL_TIGHT);
}
END_TEST

/* Cell-centred offsets (k dx, l dy), k, l in -2..2: the own cell and its neighbours. */
START_TEST(test_surface_continuity)
{
    const int k = _i % 5 - 2, l = _i / 5 - 2;
    const double x = 2.0 * HA * k, y = 2.0 * HB * l, z = CONT_Z_OVER_A * HA;
    for (int L = 0; L < 3; L++) {
        double s0[MC_NSTRESS], s1[MC_NSTRESS];
        rect_fn[L](x, y, 0.0, HA, HB, NU, s0);
        rect_fn[L](x, y, z, HA, HB, NU, s1);
        for (int c = 0; c < MC_NSTRESS; c++) {
            ck_assert_msg(isfinite(s0[c]), "%s s%s not finite at cell (%d,%d)", load_name[L],
                          mc_component_name(c), k, l);
            ck_assert_msg(fabs(s1[c] - s0[c]) <= TOL_CONTINUITY,
                          "%s s%s at cell (%d,%d): z=0 %.16e, z=1e-9a %.16e", load_name[L],
                          mc_component_name(c), k, l, s0[c], s1[c]);
        }
    }
}
END_TEST

/* The corner functions on the z = 0 corner lattice ((k-1/2) dx, (l-1/2) dy) are all finite, the
 * pressure's also on the lines X = 0 or Y = 0 (except X = Y = 0), and all are finite for z > 0,
 * including X = Y = 0 (kernel.h). */
START_TEST(test_corner_finite)
{
    for (int k = -4; k <= 4; k++)
        for (int l = -4; l <= 4; l++) {
            double X = (k - 0.5) * 2.0 * HA, Y = (l - 0.5) * 2.0 * HB, f[MC_NSTRESS];
            for (int L = 0; L < 3; L++)
                for (int zi = 0; zi < 2; zi++) {
                    corner_fn_of[L](X, Y, zi * 0.3 * HA, NU, f);
                    for (int c = 0; c < MC_NSTRESS; c++)
                        ck_assert_msg(isfinite(f[c]), "%s corner (%d,%d) z%d s%s", load_name[L],
                                      k, l, zi, mc_component_name(c));
                }
            double Xs = k * HA, Ys = l * HB; /* lattice including the lines X = 0, Y = 0 */
            for (int L = 0; L < 3; L++) {
                corner_fn_of[L](Xs, Ys, 0.2 * HA, NU, f);
                for (int c = 0; c < MC_NSTRESS; c++)
                    ck_assert(isfinite(f[c]));
            }
            if (k == 0 && l == 0)
                continue;
            mc_rect_corner_p(Xs, Ys, 0.0, NU, f);
            for (int c = 0; c < MC_NSTRESS; c++)
                ck_assert_msg(isfinite(f[c]), "p corner (%g,%g,0) s%s", Xs, Ys,
                              mc_component_name(c));
        }
    /* the documented singular half-lines of the tractions at z = 0 give -inf, never NaN */
    double f[MC_NSTRESS];
    mc_rect_corner_qx(0.0, -HB, 0.0, NU, f);
    ck_assert(isinf(f[MC_SXX]) && f[MC_SXX] < 0.0 && isinf(f[MC_SYY]) && f[MC_SYY] < 0.0);
    ck_assert(isfinite(f[MC_SZZ]) && isfinite(f[MC_SXY]) && isfinite(f[MC_SYZ]) &&
              isfinite(f[MC_SXZ]));
    mc_rect_corner_qx(-HA, 0.0, 0.0, NU, f);
    ck_assert(isinf(f[MC_SXY]) && f[MC_SXY] < 0.0);
    mc_rect_corner_qy(-HA, 0.0, 0.0, NU, f);
    ck_assert(isinf(f[MC_SYY]) && f[MC_SYY] < 0.0 && isinf(f[MC_SXX]) && f[MC_SXX] < 0.0);
}
END_TEST

/* ---- 7. the point forms ---------------------------------------------------------------------- */

/* points (x, y, z), arbitrary length unit: all octants of x, y, on the axis, near the surface */
static const double pt_pts[][3] = {
    {0.3, 0.4, 0.5}, {-1.2, 0.7, 0.3}, {0.8, -0.2, 1.5}, {-0.5, -0.9, 0.05},
    {0.0, 0.0, 0.7}, {2.0, 0.0, 0.4}, {0.0, -1.0, 0.2},
};
#define N_PT_PTS ((int)(sizeof pt_pts / sizeof pt_pts[0]))

/* d/dx_dir of all six components by the 4th-order central stencil */
static void fd_derivative(point_fn f, const double x0[3], int dir, double h, double d[6])
{
    static const double w[4] = {1.0, -8.0, 8.0, -1.0}, off[4] = {-2.0, -1.0, 1.0, 2.0};
    for (int c = 0; c < MC_NSTRESS; c++)
        d[c] = 0.0;
    for (int k = 0; k < 4; k++) {
        double x[3] = {x0[0], x0[1], x0[2]}, s[MC_NSTRESS];
        x[dir] += off[k] * h;
        f(x[0], x[1], x[2], NU, s);
        for (int c = 0; c < MC_NSTRESS; c++)
            d[c] += w[k] * s[c] / (12.0 * h);
    }
}

START_TEST(test_point_equilibrium)
{
    const int L = _i % 3, k = _i / 3;
    const double *x = pt_pts[k];
    const double rho = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    const double h = FD_H_OVER_RHO * rho;
    double dx[MC_NSTRESS], dy[MC_NSTRESS], dz[MC_NSTRESS];
    fd_derivative(point_fn_of[L], x, 0, h, dx);
    fd_derivative(point_fn_of[L], x, 1, h, dy);
    fd_derivative(point_fn_of[L], x, 2, h, dz);
    const double scale = 1.0 / (2.0 * M_PI * rho * rho * rho); /* |s|/rho, s ~ 1/(2 pi rho^2) */
    double div[3] = {dx[MC_SXX] + dy[MC_SXY] + dz[MC_SXZ], dx[MC_SXY] + dy[MC_SYY] + dz[MC_SYZ],
                     dx[MC_SXZ] + dy[MC_SYZ] + dz[MC_SZZ]};
    for (int i = 0; i < 3; i++)
        ck_assert_msg(fabs(div[i]) <= TOL_FD * scale,
                      "%s at (%g,%g,%g): (div s)_%d = %.3e / (2 pi rho^3)", load_name[L], x[0],
                      x[1], x[2], i, div[i] / scale);
}
END_TEST

/* The surface z = 0 is free of traction away from the load, and sigma_iz = O(z/r) just below. */
START_TEST(test_point_traction_free)
{
    static const double ang[] = {0.0, 0.7, 1.9, 3.3, 4.4, 5.9};
    for (int L = 0; L < 3; L++)
        for (size_t k = 0; k < sizeof ang / sizeof ang[0]; k++) {
            const double r = 0.5 + k, x = r * cos(ang[k]), y = r * sin(ang[k]);
            double s0[MC_NSTRESS], s1[MC_NSTRESS];
            point_fn_of[L](x, y, 0.0, NU, s0);
            point_fn_of[L](x, y, NEAR_SURFACE_Z_OVER_R * r, NU, s1);
            double m0 = max_abs6(s0), m1 = max_abs6(s1);
            ck_assert(m0 > 0.0);
            const int iz[3] = {MC_SZZ, MC_SXZ, MC_SYZ};
            for (int c = 0; c < 3; c++) {
                ck_assert_msg(fabs(s0[iz[c]]) <= TOL_TIGHT * m0, "%s s%s at z=0", load_name[L],
                              mc_component_name(iz[c]));
                ck_assert_msg(fabs(s1[iz[c]]) <= TOL_NEAR_SURFACE * m1, "%s s%s near z=0",
                              load_name[L], mc_component_name(iz[c]));
            }
        }
}
END_TEST

/* Force resultants over the plane z = 0.7: int s_iz dA = -F_i (tension positive, t = s.(-e_z)). */
typedef struct {
    point_fn f;
    int c;
    double z, r;
    gsl_integration_workspace *w;
    int status;
} plane_ctx;

static double plane_phi(double phi, void *p)
{
    const plane_ctx *k = p;
    double s[MC_NSTRESS];
    k->f(k->r * cos(phi), k->r * sin(phi), k->z, NU, s);
    return s[k->c];
}

static double plane_r(double r, void *p)
{
    plane_ctx *k = p;
    k->r = r;
    gsl_function F = {plane_phi, k};
    double v, e;
    int st = gsl_integration_qag(&F, 0.0, 2.0 * M_PI, 0.1 * QUAD_EPSREL / (r * r + k->z * k->z),
                                 0.1 * QUAD_EPSREL, QUAD_LIMIT, GSL_INTEG_GAUSS61, k->w, &v, &e);
    if (st && !k->status)
        k->status = st;
    return r * v;
}

START_TEST(test_point_resultant)
{
    mc_gsl_quiet();
    const int L = _i / 3, j = _i % 3; /* force direction L (p = z, qx = x, qy = y), face comp j */
    const int comp[3] = {MC_SZZ, MC_SXZ, MC_SYZ};
    const int own[3] = {0, 1, 2}; /* p pairs with szz, qx with sxz, qy with syz */
    gsl_integration_workspace *wr = gsl_integration_workspace_alloc(QUAD_LIMIT);
    gsl_integration_workspace *wp = gsl_integration_workspace_alloc(QUAD_LIMIT);
    ck_assert(wr != NULL && wp != NULL);
    plane_ctx k = {point_fn_of[L], comp[j], 0.7, 0.0, wp, 0};
    gsl_function F = {plane_r, &k};
    double v, e;
    int st = gsl_integration_qagiu(&F, 0.0, QUAD_EPSREL, QUAD_EPSREL, QUAD_LIMIT, wr, &v, &e);
    ck_assert_msg(st == GSL_SUCCESS, "quadrature: %s", gsl_strerror(st));
    ck_assert_msg(k.status == GSL_SUCCESS, "inner quadrature: %s", gsl_strerror(k.status));
    const double want = own[L] == j ? -1.0 : 0.0;
    ck_assert_msg(fabs(v - want) <= TOL_QUAD, "%s: int s%s dA = %.12f, want %g", load_name[L],
                  mc_component_name(comp[j]), v, want);
    gsl_integration_workspace_free(wp);
    gsl_integration_workspace_free(wr);
}
END_TEST

/* The robust forms in kernel.c against theory.md §5.1 and §5.2 as printed (off the axis). */
START_TEST(test_point_literal)
{
    const double x = pt_pts[_i][0], y = pt_pts[_i][1], z = pt_pts[_i][2], nu = NU;
    const double r2 = x * x + y * y, rho = sqrt(r2 + z * z), q = rho + z, m = 1.0 - 2.0 * nu;
    const double k = 1.0 / (2.0 * M_PI), r5 = pow(rho, 5), r3 = pow(rho, 3);
    if (r2 == 0.0)
        return; /* the printed Boussinesq brackets are 0/0 on the axis */
    double b[MC_NSTRESS], c[MC_NSTRESS], s[MC_NSTRESS];
    b[MC_SXX] = k * (m * ((1 - z / rho) * (x * x - y * y) / (r2 * r2) + z * y * y / (r3 * r2)) -
                     3 * z * x * x / r5);
    b[MC_SYY] = k * (m * ((1 - z / rho) * (y * y - x * x) / (r2 * r2) + z * x * x / (r3 * r2)) -
                     3 * z * y * y / r5);
    b[MC_SZZ] = -3 * k * z * z * z / r5;
    b[MC_SXY] = k * (m * (2 * (1 - z / rho) * x * y / (r2 * r2) - x * y * z / (r3 * r2)) -
                     3 * x * y * z / r5);
    b[MC_SXZ] = -3 * k * x * z * z / r5;
    b[MC_SYZ] = -3 * k * y * z * z / r5;
    c[MC_SXX] = k * (-3 * x * x * x / r5 + m * (x / r3 - 3 * x / (rho * q * q) +
                                                 x * x * x / (r3 * q * q) +
                                                 2 * x * x * x / (rho * rho * q * q * q)));
    c[MC_SYY] = k * (-3 * x * y * y / r5 + m * (x / r3 - x / (rho * q * q) +
                                                 x * y * y / (r3 * q * q) +
                                                 2 * x * y * y / (rho * rho * q * q * q)));
    c[MC_SZZ] = -3 * k * x * z * z / r5;
    c[MC_SXY] = k * (-3 * x * x * y / r5 + m * (-y / (rho * q * q) + x * x * y / (r3 * q * q) +
                                                 2 * x * x * y / (rho * rho * q * q * q)));
    c[MC_SXZ] = -3 * k * x * x * z / r5;
    c[MC_SYZ] = -3 * k * x * y * z / r5;
    mc_point_stress_p(x, y, z, nu, s);
    double mb = max_abs6(b), mcx = max_abs6(c);
    for (int i = 0; i < MC_NSTRESS; i++)
        ck_assert_msg(fabs(s[i] - b[i]) <= TOL_ROUNDOFF * mb, "Boussinesq s%s %.16e vs %.16e",
                      mc_component_name(i), s[i], b[i]);
    mc_point_stress_qx(x, y, z, nu, s);
    for (int i = 0; i < MC_NSTRESS; i++)
        ck_assert_msg(fabs(s[i] - c[i]) <= TOL_ROUNDOFF * mcx, "Cerruti s%s %.16e vs %.16e",
                      mc_component_name(i), s[i], c[i]);
}
END_TEST

/* Boussinesq on the axis, where the printed Cartesian brackets are 0/0: the cylindrical form of
 * theory.md §5.1 with (1 - z/rho)/r^2 -> 1/(2 z^2) gives
 * sigma_r = sigma_theta = (1-2nu)/(4 pi z^2), and szz = -3/(2 pi z^2). */
START_TEST(test_point_axis)
{
    const double z = 0.7;
    double s[MC_NSTRESS];
    mc_point_stress_p(0.0, 0.0, z, NU, s);
    const double sr = (1.0 - 2.0 * NU) / (4.0 * M_PI * z * z);
    const double szz = -3.0 / (2.0 * M_PI * z * z);
    ck_assert(fabs(s[MC_SXX] - sr) <= TOL_TIGHT * fabs(sr));
    ck_assert(fabs(s[MC_SYY] - sr) <= TOL_TIGHT * fabs(sr));
    ck_assert(fabs(s[MC_SZZ] - szz) <= TOL_TIGHT * fabs(szz));
    ck_assert(s[MC_SXY] == 0.0 && s[MC_SXZ] == 0.0 && s[MC_SYZ] == 0.0);
}
END_TEST

/* A +y force is the +x force reflected in the plane x = y (components xx <-> yy, xz <-> yz). */
START_TEST(test_point_qy_reflection)
{
    const double x = pt_pts[_i][0], y = pt_pts[_i][1], z = pt_pts[_i][2];
    double g[MC_NSTRESS], s[MC_NSTRESS];
    mc_point_stress_qy(x, y, z, NU, s);
    mc_point_stress_qx(y, x, z, NU, g);
    const double want[MC_NSTRESS] = {[MC_SXX] = g[MC_SYY], [MC_SYY] = g[MC_SXX],
                                     [MC_SZZ] = g[MC_SZZ], [MC_SXY] = g[MC_SXY],
                                     [MC_SYZ] = g[MC_SXZ], [MC_SXZ] = g[MC_SYZ]};
    const double m = max_abs6(want);
    for (int c = 0; c < MC_NSTRESS; c++)
        ck_assert_msg(fabs(s[c] - want[c]) <= TOL_TIGHT * m, "s%s", mc_component_name(c));
}
END_TEST

/* ---- 8. swap rule vs rotation, corner sums, parities ----------------------------------------- */

/* (x/a, y/b, z/a), including z = 0 at cell centres of a cell-centred grid */
static const double sym_pts[][3] = {
    {0.3, 0.2, 0.1}, {1.0, 0.3, 0.2}, {-3.0, 2.0, 0.7}, {10.0, -6.0, 2.0},
    {0.0, 0.0, 0.0}, {2.0, -4.0, 0.0}, {-0.4, 0.5, 0.0}, {0.7, -1.3, 0.05},
};
#define N_SYM_PTS ((int)(sizeof sym_pts / sizeof sym_pts[0]))

/* Rotating the frame by 90 degrees (x' = y, y' = -x) maps a +y traction on a 2a x 2b rectangle to
 * a +x' traction on a 2b x 2a rectangle; rotate the stresses back (theory.md §5.2). The swap rule
 * used by mc_rect_stress_qy is a reflection, so this is an independent check. */
START_TEST(test_qy_rotation)
{
    const double x = sym_pts[_i][0] * HA, y = sym_pts[_i][1] * HB, z = sym_pts[_i][2] * HA;
    double s[MC_NSTRESS], g[MC_NSTRESS];
    mc_rect_stress_qy(x, y, z, HA, HB, NU, s);
    mc_rect_stress_qx(y, -x, z, HB, HA, NU, g);
    const double want[MC_NSTRESS] = {[MC_SXX] = g[MC_SYY], [MC_SYY] = g[MC_SXX],
                                     [MC_SZZ] = g[MC_SZZ], [MC_SXY] = -g[MC_SXY],
                                     [MC_SYZ] = g[MC_SXZ], [MC_SXZ] = -g[MC_SYZ]};
    const double m = max_abs6(want);
    for (int c = 0; c < MC_NSTRESS; c++)
        ck_assert_msg(fabs(s[c] - want[c]) <= TOL_ROUNDOFF * m, "s%s: %.16e vs %.16e",
                      mc_component_name(c), s[c], want[c]);
}
END_TEST

START_TEST(test_corner_sum)
{
    const double x = sym_pts[_i][0] * HA, y = sym_pts[_i][1] * HB, z = sym_pts[_i][2] * HA;
    for (int L = 0; L < 3; L++) {
        double s[MC_NSTRESS], pp[6], pm[6], mp[6], mm[6];
        rect_fn[L](x, y, z, HA, HB, NU, s);
        corner_fn_of[L](x + HA, y + HB, z, NU, pp);
        corner_fn_of[L](x + HA, y - HB, z, NU, pm);
        corner_fn_of[L](x - HA, y + HB, z, NU, mp);
        corner_fn_of[L](x - HA, y - HB, z, NU, mm);
        const double m = max_abs6(s);
        for (int c = 0; c < MC_NSTRESS; c++) {
            double S = pp[c] - pm[c] - mp[c] + mm[c];
            ck_assert_msg(fabs(S - s[c]) <= TOL_ROUNDOFF * m, "%s s%s: S[f] %.16e rect %.16e",
                          load_name[L], mc_component_name(c), S, s[c]);
        }
    }
}
END_TEST

/* parity[load][component] = (sign under x -> -x, sign under y -> -y), theory.md §5.3, §5.4 */
static const int parity[3][MC_NSTRESS][2] = {
    /* p */ {[MC_SXX] = {1, 1}, [MC_SYY] = {1, 1}, [MC_SZZ] = {1, 1}, [MC_SXY] = {-1, -1},
             [MC_SYZ] = {1, -1}, [MC_SXZ] = {-1, 1}},
    /* qx */ {[MC_SXX] = {-1, 1}, [MC_SYY] = {-1, 1}, [MC_SZZ] = {-1, 1}, [MC_SXY] = {1, -1},
              [MC_SYZ] = {-1, -1}, [MC_SXZ] = {1, 1}},
    /* qy: qx with x <-> y and xz <-> yz */
    {[MC_SXX] = {1, -1}, [MC_SYY] = {1, -1}, [MC_SZZ] = {1, -1}, [MC_SXY] = {-1, 1},
     [MC_SYZ] = {1, 1}, [MC_SXZ] = {-1, -1}},
};

START_TEST(test_parity)
{
    const double x = sym_pts[_i][0] * HA, y = sym_pts[_i][1] * HB, z = sym_pts[_i][2] * HA;
    for (int L = 0; L < 3; L++) {
        double s[MC_NSTRESS], sx[MC_NSTRESS], sy[MC_NSTRESS];
        rect_fn[L](x, y, z, HA, HB, NU, s);
        rect_fn[L](-x, y, z, HA, HB, NU, sx);
        rect_fn[L](x, -y, z, HA, HB, NU, sy);
        double m = max_abs6(s);
        /* the point-force parities are the same (a point is a vanishing rectangle) */
        double t[MC_NSTRESS], tx[MC_NSTRESS], ty[MC_NSTRESS];
        const double zp = z > 0.0 ? z : 0.1 * HA;
        point_fn_of[L](x, y, zp, NU, t);
        point_fn_of[L](-x, y, zp, NU, tx);
        point_fn_of[L](x, -y, zp, NU, ty);
        double mt = max_abs6(t);
        for (int c = 0; c < MC_NSTRESS; c++) {
            ck_assert_msg(fabs(sx[c] - parity[L][c][0] * s[c]) <= TOL_ROUNDOFF * m,
                          "%s s%s x-parity", load_name[L], mc_component_name(c));
            ck_assert_msg(fabs(sy[c] - parity[L][c][1] * s[c]) <= TOL_ROUNDOFF * m,
                          "%s s%s y-parity", load_name[L], mc_component_name(c));
            ck_assert_msg(fabs(tx[c] - parity[L][c][0] * t[c]) <= TOL_TIGHT * mt,
                          "point %s s%s x-parity", load_name[L], mc_component_name(c));
            ck_assert_msg(fabs(ty[c] - parity[L][c][1] * t[c]) <= TOL_TIGHT * mt,
                          "point %s s%s y-parity", load_name[L], mc_component_name(c));
        }
    }
}
END_TEST

START_TEST(test_stress_names)
{
    static const char *want[MC_NSTRESS] = {"xx", "yy", "zz", "xy", "yz", "xz"};
    for (int c = 0; c < MC_NSTRESS; c++)
        ck_assert_str_eq(mc_component_name(c), want[c]);
    ck_assert_str_eq(mc_component_name(MC_NSTRESS), "?");
}
END_TEST

/* ---- suite ---------------------------------------------------------------------------------- */

#define QUAD_TIMEOUT 300

Suite *suite_kernel(void);
Suite *suite_kernel(void)
{
    Suite *s = suite_create("kernel");
    int n_love = (int)(sizeof love_pts / sizeof love_pts[0]);

    TCase *tc = tcase_create("love_uz");
    tcase_set_timeout(tc, QUAD_TIMEOUT);
    tcase_add_test(tc, test_love_uz_table);
    tcase_add_loop_test(tc, test_love_uz_quadrature, 0, n_love);
    tcase_add_test(tc, test_love_square_centre);
    tcase_add_loop_test(tc, test_love_even, 0, n_love);
    tcase_add_test(tc, test_love_far_field);
    tcase_add_test(tc, test_combined_modulus);
    suite_add_tcase(s, tc);

    tc = tcase_create("rect_stress");
    tcase_set_timeout(tc, QUAD_TIMEOUT);
    tcase_add_loop_test(tc, test_rect_stress_table, 0, N_REF_ROWS);
    tcase_add_loop_test(tc, test_rect_stress_quadrature, 0, 3 * N_QUAD_PTS);
    suite_add_tcase(s, tc);

    tc = tcase_create("surface");
    tcase_add_loop_test(tc, test_surface_limits, 0, N_INSIDE);
    tcase_add_loop_test(tc, test_square_centre_stress, 0, 4);
    tcase_add_loop_test(tc, test_surface_continuity, 0, 25);
    tcase_add_test(tc, test_corner_finite);
    suite_add_tcase(s, tc);

    tc = tcase_create("point");
    tcase_set_timeout(tc, QUAD_TIMEOUT);
    tcase_add_loop_test(tc, test_point_equilibrium, 0, 3 * N_PT_PTS);
    tcase_add_test(tc, test_point_traction_free);
    tcase_add_loop_test(tc, test_point_resultant, 0, 9);
    tcase_add_loop_test(tc, test_point_literal, 0, N_PT_PTS);
    tcase_add_test(tc, test_point_axis);
    tcase_add_loop_test(tc, test_point_qy_reflection, 0, N_PT_PTS);
    suite_add_tcase(s, tc);

    tc = tcase_create("symmetry");
    tcase_add_loop_test(tc, test_qy_rotation, 0, N_SYM_PTS);
    tcase_add_loop_test(tc, test_corner_sum, 0, N_SYM_PTS);
    tcase_add_loop_test(tc, test_parity, 0, N_SYM_PTS);
    tcase_add_test(tc, test_stress_names);
    suite_add_tcase(s, tc);
    return s;
}
