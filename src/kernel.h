/* kernel.h - influence functions of the elastic half-space: pure math, no state, no allocation.
 *
 * Conventions (shared/physics/elastic.md section 0): z >= 0 is the depth into the body; p > 0 is
 * compressive pressure; tractions q_x, q_y act on the body in +x, +y; u_z > 0 is into the body;
 * stresses are tension positive. Offsets (x, y) are FIELD minus SOURCE: odd kernels change sign
 * with the opposite order (elastic.md 5.1). A rectangle has half-sides a (along x), b (along y).
 */
#ifndef MC_KERNEL_H
#define MC_KERNEL_H

/* Stress component order used everywhere in microcontact (output files follow it too). */
enum { MC_SXX = 0, MC_SYY, MC_SZZ, MC_SXY, MC_SYZ, MC_SXZ, MC_NSTRESS };

/* Short names "xx", "yy", "zz", "xy", "yz", "xz" for component c. */
const char *mc_stress_name(int c);

/* ---- elastic constants ------------------------------------------------------------------ */

/* Combined (contact) modulus E* of two bodies, Pa: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2; a rigid
 * body 2 contributes nothing. Johnson (1985) ch. 4. Inputs must be valid (E > 0, -1 < nu <= 0.5). */
double mc_combined_modulus(double E1, double nu1, double E2, double nu2, int rigid2);

/* ---- normal surface displacement -------------------------------------------------------- */

/* Love (1929): u_z * E* / p at surface offset (x, y) from the centre of a rectangle 2a x 2b under
 * uniform pressure p, i.e. S[F]/pi with F(X,Y) = X asinh(Y/|X|) + Y asinh(X/|Y|) (elastic.md 1.2,
 * the robust asinh form). Units: m. Even in x and y. Finite everywhere (also on edges/corners). */
double mc_love_uz(double x, double y, double a, double b);

/* Corner function F(X, Y) of mc_love_uz (F(0,0) = 0); S[F] over the four corners gives pi*u_z*E*/p. */
double mc_love_corner(double X, double Y);

/* Boussinesq point force: u_z * E* / P at distance r > 0 = 1/(pi r), m^-1 (elastic.md 1.1). */
double mc_point_uz(double r);

/* ---- subsurface stress under uniform loads on a rectangle (elastic.md 3.3, 3.4) ---------- */

/* Six stresses s[MC_NSTRESS] (Pa per Pa of load) at (x, y, z), z >= 0, under a unit uniform load on
 * the rectangle |xi| <= a, |eta| <= b: normal pressure (p), traction in +x (qx) or in +y (qy).
 * Exact closed forms; at z = 0 inside the patch szz -> -1 (p) and sxz -> -1 (qx). Do not evaluate
 * exactly on an edge or corner at z = 0 (singular lines, elastic.md 3.5). */
void mc_rect_stress_p(double x, double y, double z, double a, double b, double nu, double s[6]);
void mc_rect_stress_qx(double x, double y, double z, double a, double b, double nu, double s[6]);
void mc_rect_stress_qy(double x, double y, double z, double a, double b, double nu, double s[6]);

/* Corner (bracket) functions for the corner-lattice trick: with S[f] = f(x+a,y+b) - f(x+a,y-b)
 * - f(x-a,y+b) + f(x-a,y-b), the rectangle stresses are s = S[f] (the 1/2pi factor is included in
 * f). Lets a table builder evaluate f once per lattice corner and difference (elastic.md 3.5). */
void mc_rect_corner_p(double X, double Y, double z, double nu, double f[6]);
void mc_rect_corner_qx(double X, double Y, double z, double nu, double f[6]);
void mc_rect_corner_qy(double X, double Y, double z, double nu, double f[6]);

/* ---- point forces (elastic.md 3.1, 3.2) -------------------------------------------------- */

/* Six stresses (Pa per N) at (x, y, z), z > 0 (or r > 0 at z = 0), under a unit point force at the
 * origin: normal compressive (Boussinesq), tangential in +x or +y (Cerruti). */
void mc_point_stress_p(double x, double y, double z, double nu, double s[6]);
void mc_point_stress_qx(double x, double y, double z, double nu, double s[6]);
void mc_point_stress_qy(double x, double y, double z, double nu, double s[6]);

#endif
