/* hertz.h - analytic reference solutions of elastic half-space contact: Hertz point and line
 * contact (surface quantities and full subsurface stress fields, frictionless and sliding), the
 * uniform strip load and the Flamant line loads. Pure math: no state, no allocation, no output.
 * Used alike by the unit tests, the verification suites and the benchmarks.
 *
 * Conventions (theory.md §1): z >= 0 is the depth into the body; pressure
 * is compressive positive; tractions act on the body in +x; stresses are tension positive; u_z > 0
 * is into the body. E* is the combined modulus, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2; R the reduced
 * radius, 1/R = 1/R1 + 1/R2.
 *
 * Units, one convention per function:
 *   - the mc_hertz_point / mc_hertz_line structs and their pressure / displacement functions: SI
 *     (m, N, N/m, Pa);
 *   - the field functions: NORMALISED. Point contact: lengths / a, stresses / p0 (normal load)
 *     or / q0 (tangential load). Line contact: lengths / b, stresses / p0 or / q0. The strip and
 *     Flamant functions are scale-free (see each).
 * Stress arrays s[6] use the component order of kernel.h: xx, yy, zz, xy, yz, xz (MC_SXX...).
 * Plane-strain (line) fields fill all six: syy = nu (sxx + szz), sxy = syz = 0 (except the
 * anti-plane Flamant load).
 */
#ifndef MC_HERTZ_H
#define MC_HERTZ_H

#include "core/error.h"

/* ---- Hertz point contact (sphere on flat), SI; Johnson (1985) ch. 4; theory.md §6.1 -------- */

typedef struct {
    double R;     /* reduced radius, m */
    double Estar; /* combined modulus E*, Pa */
    double load;  /* normal load P, N */
    double a;     /* contact radius, m: a^3 = 3 P R / (4 E*) */
    double p0;    /* maximum pressure, Pa: p0 = 3 P / (2 pi a^2) */
    double delta; /* rigid approach, m: delta = a^2 / R */
} mc_hertz_point;

/* Load control: fill *h from R > 0, E* > 0, P > 0 (all finite). MC_ERR_INPUT otherwise. */
int mc_hertz_point_from_load(double R, double Estar, double P, mc_hertz_point *h, mc_error *err);

/* Approach control: fill *h from R > 0, E* > 0, delta > 0: a = sqrt(R delta),
 * P = 4 E* a^3 / (3 R). Inverts mc_hertz_point_from_load. MC_ERR_INPUT on bad input. */
int mc_hertz_point_from_approach(double R, double Estar, double delta, mc_hertz_point *h,
                                 mc_error *err);

/* Pressure p(r) = p0 sqrt(1 - r^2/a^2) for |r| < a, 0 outside; Pa, r in m. */
double mc_hertz_point_pressure(const mc_hertz_point *h, double r);

/* Combined normal surface displacement of both bodies (into the bodies), m, at radius r (m) under
 * the Hertz pressure (Johnson 1985 ch. 3, Hertz pressure on a circle; the outside branch, docs/theory.md
 * §6.1, is checked against quadrature of the Boussinesq solution in tests/test_hertz.c):
 *   |r| <= a: u_z = pi p0 (2a^2 - r^2) / (4 a E*)      (so u_z(0) = delta, u_z(0)-u_z(r) = r^2/2R)
 *   |r| >  a: u_z = p0 / (2 a E*) [ (2a^2 - r^2) asin(a/r) + a sqrt(r^2 - a^2) ]
 * The two branches meet continuously (with continuous slope) at r = a. For r >= 2a the outside
 * branch is summed as 2 asin(s) - [asin(s) - s sqrt(1-s^2)]/s^2 (series, s = a/r): the printed
 * form gets the far field 2 p0 a^2/(3 E* r) = P/(pi E* r) as a difference of O(r) terms. */
double mc_hertz_point_uz(const mc_hertz_point *h, double r);

/* ---- Hertz point contact: stress fields, NORMALISED (lengths / a, stresses / p0) ------------ */

/* Stresses on the axis r = 0 at depth zeta = z/a >= 0 (theory.md §6.1):
 *   sz = -1/(1+zeta^2),  sr = stheta = -(1+nu)[1 - zeta atan(1/zeta)] + 1/(2(1+zeta^2)). */
void mc_hertz_point_axis(double zeta, double nu, double *sr, double *sz);

/* Surface stresses (z = 0) at rho = r/a >= 0 (theory.md §6.1): radial, hoop and normal.
 * rho < 1: sr = (1-2nu)/3 (1/rho^2)[1-(1-rho^2)^(3/2)] - sqrt(1-rho^2),
 *          st = -(1-2nu)/3 (1/rho^2)[1-(1-rho^2)^(3/2)] - 2 nu sqrt(1-rho^2), sz = -sqrt(1-rho^2);
 * rho >= 1: sr = -st = (1-2nu)/(3 rho^2), sz = 0. Evaluated without cancellation at rho -> 0. */
void mc_hertz_point_surface(double rho, double nu, double *sr, double *st, double *sz);

/* Huber (1904) full field in cylindrical coordinates at (r, z), r >= 0, z >= 0: sr, stheta, sz,
 * trz (theory.md §6.2, with the MINUS sign in front of the second term of stheta). u is the root
 * of r^2/(1+u) + z^2/u = 1; the (1/r^2)(1 - (z/sqrt u)^3) term is evaluated in a form exact at
 * r = 0 (limit 3/(2(1+z^2))), so the function is smooth across the axis and valid at z = 0.
 * At the contact edge z = 0, r = 1 the surface limit is returned. */
void mc_hertz_huber(double r, double z, double nu, double *sr, double *st, double *sz, double *trz);

/* Hamilton (1983) Cartesian field under the Hertz pressure p0 sqrt(1 - r^2) (stresses / p0) at
 * (x, y, z), z >= 0 (theory.md §6.2). The axis r = 0 uses the stated limits. Hamilton's brackets
 * divided by r^2 (normal) and r^4 (tangential) cancel near the axis (as eps/r^2, eps/r^3); for
 * r^2 < (1 + z^2)/16 they are evaluated as power series in r^2 instead, so the field is smooth up
 * to the axis. Absolute accuracy (against 50-digit arithmetic): <= 2e-15 for z <= 10, growing as
 * ~eps z^2 deeper (2e-14 at z = 30), where the field itself is O(1/z^2). At the contact edge
 * (z = 0, r = 1), where Hamilton's S vanishes, the (continuous) surface limit is returned. */
void mc_hertz_hamilton_normal(double x, double y, double z, double nu, double s[6]);

/* Hamilton (1983) Cartesian field under the sliding traction q0 sqrt(1 - r^2) acting on the body
 * in +x (stresses / q0) at (x, y, z), z >= 0 (theory.md §6.2); axis, accuracy and edge as above. */
void mc_hertz_hamilton_tangential(double x, double y, double z, double nu, double s[6]);

/* Sliding Hertz contact: pressure p plus traction q = mu p in +x, stresses / p0:
 * s = normal + mu * tangential (Hamilton 1983). */
void mc_hertz_point_sliding(double x, double y, double z, double nu, double mu, double s[6]);

/* ---- Hertz elliptical contact (ellipsoid on flat), SI; Johnson (1985) §4.2 ----------------- */

typedef struct {
    double Rx, Ry; /* principal radii of the gap h = x^2/(2 Rx) + y^2/(2 Ry), m */
    double Estar;  /* combined modulus E*, Pa */
    double load;   /* normal load P, N */
    double ax, ay; /* semi-axes of the contact ellipse along x and y, m (the longer one lies
                      along the larger radius) */
    double e;      /* eccentricity sqrt(1 - (short/long)^2) */
    double p0;     /* maximum pressure 3 P / (2 pi ax ay), Pa */
    double delta;  /* rigid approach p0 short K(e) / E*, m */
} mc_hertz_ellipse;

/* Fill *h from Rx, Ry, E*, P > 0 (finite). With A = 1/(2 R_long), B = 1/(2 R_short) the
 * eccentricity solves B/A = [E(e)/(1 - e^2) - K(e)] / [K(e) - E(e)] (bisection; K, E complete
 * elliptic integrals of modulus e), then long^3 = 3 P R_long (K - E)/(pi E* e^2),
 * short = long sqrt(1 - e^2) (Johnson 1985 eqs. 4.36-4.39). A ratio within 1e-8 of 1 is the
 * circle of mc_hertz_point_from_load (radius sqrt(Rx Ry)). MC_ERR_INPUT otherwise. */
int mc_hertz_ellipse_from_load(double Rx, double Ry, double Estar, double P, mc_hertz_ellipse *h,
                               mc_error *err);

/* ---- Hertz line contact (cylinder on flat, plane strain), SI; Johnson (1985) ch. 4 ---------- */

typedef struct {
    double R;     /* reduced radius, m */
    double Estar; /* combined modulus E*, Pa */
    double load;  /* load per unit length P', N/m */
    double b;     /* contact half-width, m: b^2 = 4 P' R / (pi E*) */
    double p0;    /* maximum pressure, Pa: p0 = 2 P' / (pi b) */
} mc_hertz_line;

/* Fill *h from R > 0, E* > 0, P' > 0 (finite); MC_ERR_INPUT otherwise. The approach of a line
 * contact depends on the whole cylinders, not on the half-space, so none is given here. */
int mc_hertz_line_from_load(double R, double Estar, double load, mc_hertz_line *h, mc_error *err);

/* Pressure p(x) = p0 sqrt(1 - x^2/b^2) for |x| < b, 0 outside; Pa, x in m. */
double mc_hertz_line_pressure(const mc_hertz_line *h, double x);

/* ---- Hertz line contact: stress fields, NORMALISED (lengths / b, stresses / p0 or q0) ------- */

/* McEwen (1949) field under the pressure p0 sqrt(1 - x^2) at (x, z), z >= 0 (theory.md §6.3),
 * plane strain. At the contact edge (z = 0, |x| = 1) the (continuous) surface limit is returned. */
void mc_mcewen_normal(double x, double z, double nu, double s[6]);

/* Field under the traction q0 sqrt(1 - x^2) on the body in +x (Smith & Liu 1953 form of
 * McEwen's solution, theory.md §6.3), plane strain; on the surface inside the contact
 * sxx = -2x, sxz = -sqrt(1 - x^2). */
void mc_mcewen_tangential(double x, double z, double nu, double s[6]);

/* Sliding line contact: pressure p plus traction q = mu p in +x, stresses / p0. */
void mc_hertz_line_sliding(double x, double z, double nu, double mu, double s[6]);

/* ---- plane-strain line loads (Johnson 1985 ch. 2; theory.md §6.4) --------------------------- */

/* Uniform pressure p on the strip -a <= x <= a (plane strain), stresses / p at (x, z), z >= 0;
 * x, z, a in one length unit. With theta_pm = atan2(x +- a, z) (angles of the strip edges seen
 * from the field point, measured from the depth axis; Johnson 1985 ch. 2):
 *   sxx = -(1/pi)[(t+ - t-) - (sin 2t+ - sin 2t-)/2]
 *   szz = -(1/pi)[(t+ - t-) + (sin 2t+ - sin 2t-)/2]
 *   sxz = (1/(2 pi)) (cos 2t+ - cos 2t-),   syy = nu (sxx + szz).
 * On the surface inside the strip sxx = szz = -1; exactly at an edge (z = 0, |x| = a) the mean of
 * the two one-sided values is returned. */
void mc_flamant_strip_uniform(double x, double z, double a, double nu, double s[6]);

/* Flamant: concentrated line loads at the surface point x = 0, per unit load per unit length
 * (stress * length / (N/m), i.e. 1/m in SI; any consistent unit), at (x, z) with x^2 + z^2 > 0.
 * normal (compressive) P':  sxx = -(2/pi) x^2 z/r^4, szz = -(2/pi) z^3/r^4, sxz = -(2/pi) x z^2/r^4
 * tangential Q' (+x):       sxx = -(2/pi) x^3/r^4,   szz = -(2/pi) x z^2/r^4, sxz = -(2/pi) x^2
 * z/r^4 both with syy = nu (sxx + szz); anti-plane T' (+y): syz = -(1/pi) z/r^2, sxy = -(1/pi)
 * x/r^2, all normal stresses 0. */
void mc_flamant_normal(double x, double z, double nu, double s[6]);
void mc_flamant_tangential(double x, double z, double nu, double s[6]);
void mc_flamant_antiplane(double x, double z, double s[6]);

#endif
