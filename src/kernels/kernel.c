/* kernel.c - influence functions of the elastic half-space (see kernel.h). */
#include "kernels/kernel.h"

#include <math.h>

const char *mc_component_name(int c)
{
    static const char *names[MC_NSTRESS] = {"xx", "yy", "zz", "xy", "yz", "xz"};
    return c >= 0 && c < MC_NSTRESS ? names[c] : "?";
}

double mc_combined_modulus(double E1, double nu1, double E2, double nu2, int rigid2)
{
    double c = (1.0 - nu1 * nu1) / E1;
    if (!rigid2)
        c += (1.0 - nu2 * nu2) / E2;
    return 1.0 / c;
}

/* X asinh(Y/|X|) + Y asinh(X/|Y|): the asinh form stays accurate where the log form cancels
 * (theory.md §2.2); each term is 0 when its prefactor is 0 (its limit). */
double mc_love_corner(double X, double Y)
{
    double f = 0.0;
    if (X != 0.0)
        f += X * asinh(Y / fabs(X));
    if (Y != 0.0)
        f += Y * asinh(X / fabs(Y));
    return f;
}

double mc_love_uz(double x, double y, double a, double b)
{
    double s = mc_love_corner(x + a, y + b) - mc_love_corner(x + a, y - b) -
               mc_love_corner(x - a, y + b) + mc_love_corner(x - a, y - b);
    return s / M_PI;
}

double mc_point_uz(double r) { return 1.0 / (M_PI * r); }

/* ---- subsurface stress under uniform rectangular loads (theory.md §5.3-§5.5) --------------- */

#define INV_2PI (0.5 / M_PI)

/* Corner function of the uniform pressure, 1/2pi included. One sqrt, one log and two atan2 serve
 * all six components: T(Y,X) = theta - T(X,Y), since atan(Y/X) + atan(X/Y) = sign(XY) pi/2 and
 * atan(zY/(X rho)) + atan(zX/(Y rho)) = atan(z rho/(XY)). */
static inline void corner_p(double X, double Y, double z, double nu, double f[MC_NSTRESS])
{
    const double X2 = X * X, Y2 = Y * Y, z2 = z * z;
    const double R2 = X2 + Y2;
    const double rho = sqrt(R2 + z2);
    const double m = 1.0 - 2.0 * nu;
    if (rho == 0.0) { /* the corner itself at z = 0: only ln(rho) of txy diverges */
        for (int c = 0; c < MC_NSTRESS; c++)
            f[c] = 0.0;
        f[MC_SXY] = m > 0.0 ? HUGE_VAL : 0.0;
        return;
    }
    const double XY = X * Y;
    const double inv_rho = 1.0 / rho;
    const double rmz = R2 / (rho + z); /* rho - z without cancellation */
    const double th = atan2(XY, z * rho);
    const double T = atan2(XY * rmz, X2 * rho + z * Y2);
    const double Tyx = th - T;
    /* z/((X^2+z^2) rho), := 0 at X = z = 0 where every term using it carries a factor z */
    const double xz2 = X2 + z2, yz2 = Y2 + z2;
    const double gx = xz2 > 0.0 ? z * inv_rho / xz2 : 0.0;
    const double gy = yz2 > 0.0 ? z * inv_rho / yz2 : 0.0;
    const double ax = gx * XY, ay = gy * XY;
    f[MC_SXX] = INV_2PI * (-2.0 * nu * th + ax - m * T);
    f[MC_SYY] = INV_2PI * (-2.0 * nu * th + ay - m * Tyx);
    f[MC_SZZ] = -INV_2PI * (th + ax + ay);
    f[MC_SXY] = -INV_2PI * (m * log(rho + z) + z * inv_rho);
    f[MC_SYZ] = INV_2PI * gy * z * X;
    f[MC_SXZ] = INV_2PI * gx * z * Y;
}

/* ln(U + rho) with V2 = rho^2 - U^2: for U < 0 use U + rho = V2/(rho - U), free of cancellation.
 * -inf only on the singular half-line V2 = 0, U < 0. */
static inline double log_sum(double U, double V2, double rho)
{
    return U >= 0.0 ? log(U + rho) : log(V2 / (rho - U));
}

/* Corner function of the uniform traction q_x, 1/2pi included. One sqrt, two logs and one atan2
 * serve all six components. */
static inline void corner_qx(double X, double Y, double z, double nu, double f[MC_NSTRESS])
{
    const double X2 = X * X, Y2 = Y * Y, z2 = z * z;
    const double rho = sqrt(X2 + Y2 + z2);
    const double m = 1.0 - 2.0 * nu;
    if (rho == 0.0) { /* the corner itself at z = 0: ln(Y + rho) and ln(X + rho) diverge */
        for (int c = 0; c < MC_NSTRESS; c++)
            f[c] = 0.0;
        f[MC_SXX] = -HUGE_VAL;
        f[MC_SYY] = nu > 0.0 ? -HUGE_VAL : (nu < 0.0 ? HUGE_VAL : 0.0);
        f[MC_SXY] = -HUGE_VAL;
        return;
    }
    const double inv_rho = 1.0 / rho;
    const double inv_rz = 1.0 / (rho + z);
    const double xz2 = X2 + z2;
    const double lY = log_sum(Y, xz2, rho);
    const double lX = log_sum(X, Y2 + z2, rho);
    /* X^2, z^2 and X z over rho (Y + rho); for Y < 0, 1/(Y + rho) = (rho - Y)/(X^2 + z^2). On the
     * line X = z = 0, Y < 0 the ratios take their z = 0 limits 2, 0, 0. */
    double tX2, tz2, tXz;
    if (Y >= 0.0) {
        const double iY = inv_rho / (Y + rho);
        tX2 = X2 * iY;
        tz2 = z2 * iY;
        tXz = X * z * iY;
    } else if (xz2 > 0.0) {
        const double iY = inv_rho * (rho - Y) / xz2;
        tX2 = X2 * iY;
        tz2 = z2 * iY;
        tXz = X * z * iY;
    } else {
        tX2 = 2.0;
        tz2 = 0.0;
        tXz = 0.0;
    }
    const double gx = xz2 > 0.0 ? z / xz2 : 0.0; /* its terms carry a factor z: 0 at X = z = 0 */
    const double th = atan2(X * Y, z * rho);
    f[MC_SXX] = INV_2PI * (2.0 * lY - 2.0 * nu * tX2 +
                           m * gx * Y * (X2 - z * rho) * inv_rho * inv_rz);
    f[MC_SYY] = INV_2PI * (2.0 * nu * lY - Y * inv_rho + m * Y * inv_rz);
    f[MC_SZZ] = -INV_2PI * tz2;
    f[MC_SXY] = INV_2PI * (lX - X * inv_rho + m * X * inv_rz);
    f[MC_SYZ] = -INV_2PI * z * inv_rho;
    f[MC_SXZ] = -INV_2PI * (th + tXz);
}

/* Swap rule (theory.md §5.4): reflecting x <-> y turns a +x traction into a +y traction; the
 * components follow the reflection (xx <-> yy, xz <-> yz, zz and xy unchanged). */
static inline void swap_xy(const double g[MC_NSTRESS], double f[MC_NSTRESS])
{
    f[MC_SXX] = g[MC_SYY];
    f[MC_SYY] = g[MC_SXX];
    f[MC_SZZ] = g[MC_SZZ];
    f[MC_SXY] = g[MC_SXY];
    f[MC_SYZ] = g[MC_SXZ];
    f[MC_SXZ] = g[MC_SYZ];
}

void mc_rect_corner_p(double X, double Y, double z, double nu, double f[6])
{
    corner_p(X, Y, z, nu, f);
}

void mc_rect_corner_qx(double X, double Y, double z, double nu, double f[6])
{
    corner_qx(X, Y, z, nu, f);
}

void mc_rect_corner_qy(double X, double Y, double z, double nu, double f[6])
{
    double g[MC_NSTRESS];
    corner_qx(Y, X, z, nu, g);
    swap_xy(g, f);
}

/* s = S[f] = f(x+a,y+b) - f(x+a,y-b) - f(x-a,y+b) + f(x-a,y-b) */
static inline void corner_sum(const double pp[MC_NSTRESS], const double pm[MC_NSTRESS],
                              const double mp[MC_NSTRESS], const double mm[MC_NSTRESS],
                              double s[MC_NSTRESS])
{
    for (int c = 0; c < MC_NSTRESS; c++)
        s[c] = (pp[c] - pm[c]) - (mp[c] - mm[c]);
}

void mc_rect_stress_p(double x, double y, double z, double a, double b, double nu, double s[6])
{
    double pp[MC_NSTRESS], pm[MC_NSTRESS], mp[MC_NSTRESS], mm[MC_NSTRESS];
    corner_p(x + a, y + b, z, nu, pp);
    corner_p(x + a, y - b, z, nu, pm);
    corner_p(x - a, y + b, z, nu, mp);
    corner_p(x - a, y - b, z, nu, mm);
    corner_sum(pp, pm, mp, mm, s);
}

void mc_rect_stress_qx(double x, double y, double z, double a, double b, double nu, double s[6])
{
    double pp[MC_NSTRESS], pm[MC_NSTRESS], mp[MC_NSTRESS], mm[MC_NSTRESS];
    corner_qx(x + a, y + b, z, nu, pp);
    corner_qx(x + a, y - b, z, nu, pm);
    corner_qx(x - a, y + b, z, nu, mp);
    corner_qx(x - a, y - b, z, nu, mm);
    corner_sum(pp, pm, mp, mm, s);
}

void mc_rect_stress_qy(double x, double y, double z, double a, double b, double nu, double s[6])
{
    double g[MC_NSTRESS];
    mc_rect_stress_qx(y, x, z, b, a, nu, g);
    swap_xy(g, s);
}

/* The strip corner function g(X) of mc_strip_stress_p (kernel.h), 1/pi included. */
static void corner_strip(double X, double z, double nu, double g[MC_NSTRESS])
{
    const double r2 = X * X + z * z;
    const double th = atan2(X, z);
    const double zx = r2 > 0.0 ? z * X / r2 : 0.0, zz = r2 > 0.0 ? z * z / r2 : 0.0;
    g[MC_SXX] = (-th + zx) / M_PI;
    g[MC_SYY] = -2.0 * nu * th / M_PI;
    g[MC_SZZ] = -(th + zx) / M_PI;
    g[MC_SXY] = 0.0;
    g[MC_SYZ] = 0.0;
    g[MC_SXZ] = zz / M_PI;
}

void mc_strip_stress_p(double x, double z, double a, double nu, double s[6])
{
    double gp[MC_NSTRESS], gm[MC_NSTRESS];
    corner_strip(x + a, z, nu, gp);
    corner_strip(x - a, z, nu, gm);
    for (int c = 0; c < MC_NSTRESS; c++)
        s[c] = gp[c] - gm[c];
}

/* ---- point forces (theory.md §5.1, §5.2) --------------------------------------------------- */

/* Boussinesq, per unit force. The (1 - 2nu) brackets are rewritten with 1 - z/rho =
 * r^2/(rho (rho + z)) so that they stay finite on the axis r = 0:
 *   (1 - z/rho)(x^2-y^2)/r^4 + z y^2/(rho^3 r^2) = (x^2-y^2+z^2 + z y^2/(rho+z))/(rho^3 (rho+z))
 *   2(1 - z/rho) x y/r^4 - x y z/(rho^3 r^2)    = x y (2 rho + z)/(rho^3 (rho+z)^2)
 * (the second keeps the factor 2 of theory.md §5.1). */
void mc_point_stress_p(double x, double y, double z, double nu, double s[6])
{
    const double x2 = x * x, y2 = y * y, z2 = z * z;
    const double rho = sqrt(x2 + y2 + z2);
    const double q = rho + z;
    const double m = 1.0 - 2.0 * nu;
    const double i3 = 1.0 / (rho * rho * rho);
    const double i5 = i3 / (rho * rho);
    const double iq = 1.0 / q;
    s[MC_SXX] = INV_2PI * (m * (x2 - y2 + z2 + z * y2 * iq) * i3 * iq - 3.0 * z * x2 * i5);
    s[MC_SYY] = INV_2PI * (m * (y2 - x2 + z2 + z * x2 * iq) * i3 * iq - 3.0 * z * y2 * i5);
    s[MC_SZZ] = -3.0 * INV_2PI * z2 * z * i5;
    s[MC_SXY] = INV_2PI * x * y * (m * (2.0 * rho + z) * i3 * iq * iq - 3.0 * z * i5);
    s[MC_SYZ] = -3.0 * INV_2PI * y * z2 * i5;
    s[MC_SXZ] = -3.0 * INV_2PI * x * z2 * i5;
}

void mc_point_stress_qx(double x, double y, double z, double nu, double s[6])
{
    const double x2 = x * x, y2 = y * y, z2 = z * z;
    const double rho = sqrt(x2 + y2 + z2);
    const double q = rho + z;
    const double m = 1.0 - 2.0 * nu;
    const double ir = 1.0 / rho;
    const double i3 = ir * ir * ir;
    const double i5 = i3 * ir * ir;
    const double iq = 1.0 / q;
    const double iq2 = iq * iq;
    /* shared pieces of the (1 - 2nu) brackets: 1/(rho^3 q^2) + 2/(rho^2 q^3) */
    const double w = i3 * iq2 + 2.0 * ir * ir * iq2 * iq;
    s[MC_SXX] = INV_2PI * x * (-3.0 * x2 * i5 + m * (i3 - 3.0 * ir * iq2 + x2 * w));
    s[MC_SYY] = INV_2PI * x * (-3.0 * y2 * i5 + m * (i3 - ir * iq2 + y2 * w));
    s[MC_SZZ] = -3.0 * INV_2PI * x * z2 * i5;
    s[MC_SXY] = INV_2PI * y * (-3.0 * x2 * i5 + m * (-ir * iq2 + x2 * w));
    s[MC_SYZ] = -3.0 * INV_2PI * x * y * z * i5;
    s[MC_SXZ] = -3.0 * INV_2PI * x2 * z * i5;
}

/* Rotation (theory.md §5.2): in the frame x' = y, y' = -x the +y force points along +x'. */
void mc_point_stress_qy(double x, double y, double z, double nu, double s[6])
{
    double g[MC_NSTRESS];
    mc_point_stress_qx(y, -x, z, nu, g);
    s[MC_SXX] = g[MC_SYY];
    s[MC_SYY] = g[MC_SXX];
    s[MC_SZZ] = g[MC_SZZ];
    s[MC_SXY] = -g[MC_SXY];
    s[MC_SYZ] = g[MC_SXZ];
    s[MC_SXZ] = -g[MC_SYZ];
}
