/* kernel.c - influence functions of the elastic half-space (see kernel.h). */
#include "kernel.h"

#include <math.h>

const char *mc_stress_name(int c)
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
 * (elastic.md 1.2); each term is 0 when its prefactor is 0 (its limit). */
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
