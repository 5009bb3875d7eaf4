/* kernel.h - influence functions of the elastic half-space: pure math, no state, no allocation.
 *
 * Conventions (theory.md §1): z >= 0 is the depth into the body; p > 0 is
 * compressive pressure; tractions q_x, q_y act on the body in +x, +y; u_z > 0 is into the body;
 * stresses are tension positive. Offsets (x, y) are FIELD minus SOURCE: odd kernels change sign
 * with the opposite order (theory.md §3.1). A rectangle has half-sides a (along x), b (along y).
 */
#ifndef MC_KERNEL_H
#define MC_KERNEL_H

/* Stress component order used everywhere in microcontact (output files follow it too). */
enum { MC_SXX = 0, MC_SYY, MC_SZZ, MC_SXY, MC_SYZ, MC_SXZ, MC_NSTRESS };

/* Short names "xx", "yy", "zz", "xy", "yz", "xz" for component c. */
const char *mc_component_name(int c);

/* ---- elastic constants ------------------------------------------------------------------ */

/* Combined (contact) modulus E* of two bodies, Pa: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2; a rigid
 * body 2 contributes nothing. Johnson (1985) ch. 4. Inputs must be valid (E > 0, -1 < nu <= 0.5). */
double mc_combined_modulus(double E1, double nu1, double E2, double nu2, int rigid2);

/* ---- normal surface displacement -------------------------------------------------------- */

/* Love (1929): u_z * E* / p at surface offset (x, y) from the centre of a rectangle 2a x 2b under
 * uniform pressure p, i.e. S[F]/pi with F(X,Y) = X asinh(Y/|X|) + Y asinh(X/|Y|) (theory.md §2.2,
 * the robust asinh form). Units: m. Even in x and y. Finite everywhere (also on edges/corners). */
double mc_love_uz(double x, double y, double a, double b);

/* Corner function F(X, Y) of mc_love_uz, m (F(0,0) = 0); S[F]/pi = u_z E* / p. Odd in X and Y. */
double mc_love_corner(double X, double Y);

/* Boussinesq point force: u_z * E* / P at distance r > 0 = 1/(pi r), m^-1 (theory.md §2.1). */
double mc_point_uz(double r);

/* ---- subsurface stress under uniform loads on a rectangle (theory.md §5.3-§5.5) ---------- */

/* Six stresses s[MC_NSTRESS] (Pa per Pa of load, order MC_SXX..MC_SXZ) at the offset (x, y, z), m,
 * z >= 0, from the centre of the rectangle |xi| <= a, |eta| <= b (half-sides a, b > 0, m) under a
 * unit uniform load: normal pressure (p, theory.md §5.3), traction in +x (qx, 3.4) or in +y (qy,
 * the swap rule of 3.4). Poisson ratio nu in (-1, 0.5]. Exact closed forms, s = S[f] of the corner
 * functions below. At z = 0 inside the patch szz = -1 (p), sxz = -1 (qx), syz = -1 (qy).
 * Parities in (x, y): p: xx, yy, zz even/even, xy odd/odd, xz odd/even, yz even/odd; qx: xx, yy,
 * zz odd/even, xy even/odd, xz even/even, yz odd/odd; qy: qx with x and y exchanged.
 * z = 0 is allowed away from the rectangle's edge lines (cell centres of a cell-centred grid);
 * on an edge or corner at z = 0 some components are singular (inf or NaN, theory.md §5.5). */
void mc_rect_stress_p(double x, double y, double z, double a, double b, double nu, double s[6]);
void mc_rect_stress_qx(double x, double y, double z, double a, double b, double nu, double s[6]);
void mc_rect_stress_qy(double x, double y, double z, double a, double b, double nu, double s[6]);

/* The strip limit b -> infinity of mc_rect_stress_p at y = 0: the plane-strain stresses at (x, z)
 * under a unit uniform pressure on the strip |xi| <= a, uniform along y (Johnson 1985 §2.7;
 * docs/theory.md §8.5). s = g(x + a) - g(x - a) with th = atan2(X, z), rho^2 = X^2 + z^2:
 *   g_xx = (-th + z X / rho^2) / pi,  g_zz = -(th + z X / rho^2) / pi,  g_yy = -2 nu th / pi,
 *   g_xz = z^2 / (pi rho^2),  g_xy = g_yz = 0  (so s_yy = nu (s_xx + s_zz): plane strain).
 * Same conventions and validity as mc_rect_stress_p (z = 0 on an edge line x = +-a excluded). */
void mc_strip_stress_p(double x, double z, double a, double nu, double s[6]);

/* Corner (bracket) functions f[MC_NSTRESS] at the corner offset (X, Y, z), m, with the 1/2pi
 * folded in: the rectangle stresses are s = S[f] = f(x+a,y+b) - f(x+a,y-b) - f(x-a,y+b)
 * + f(x-a,y-b). Lets a table builder evaluate f once per lattice corner ((k-1/2)dx, (l-1/2)dy)
 * and difference (theory.md §5.5). Dimensionless; parts depending on X only or Y only are
 * arbitrary (they cancel in S), so only S[f] is physical.
 * Finite for z > 0 everywhere. At z = 0: finite whenever X != 0 and Y != 0 (all of the corner
 * lattice); p also on the lines X = 0 or Y = 0 except X = Y = 0, where its xy term is +inf
 * (ln rho). qx is -inf (a log) on the half-lines X = 0, Y < 0 (xx, yy) and Y = 0, X < 0 (xy), and
 * qy likewise with X and Y exchanged: these are the singular edge lines of the load, which no
 * single form of f can avoid (the stress itself is logarithmic there). */
void mc_rect_corner_p(double X, double Y, double z, double nu, double f[6]);
void mc_rect_corner_qx(double X, double Y, double z, double nu, double f[6]);
void mc_rect_corner_qy(double X, double Y, double z, double nu, double f[6]);

/* ---- point forces (theory.md §5.1, §5.2) -------------------------------------------------- */

/* Six stresses s[MC_NSTRESS] (Pa per N) at (x, y, z), m, z >= 0 with x^2+y^2+z^2 > 0, under a unit
 * point force at the origin: normal compressive (Boussinesq, theory.md §5.1, with the factor 2 in
 * txy), tangential in +x (Cerruti, 3.2) or in +y (Cerruti rotated by 90 degrees, 3.2). Written in
 * forms that stay finite on the axis x = y = 0, z > 0. */
void mc_point_stress_p(double x, double y, double z, double nu, double s[6]);
void mc_point_stress_qx(double x, double y, double z, double nu, double s[6]);
void mc_point_stress_qy(double x, double y, double z, double nu, double s[6]);

#endif
