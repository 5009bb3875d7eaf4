/* eigen_disp.c - surface normal displacement of a cuboid of uniform eigenstrain (see eigen.h).
 *
 * Betti reciprocity (Jacq et al. 2002; theory.md §8.1): u_z(X) = integral of
 * sigma^B : eps* over the cuboid, sigma^B the Boussinesq field of a unit normal force at X. The
 * volume integrals J_ij = integral du_i/dx_j dV of the Boussinesq displacements
 *   u_x = c0 [x z/r^3 - (1-2nu) x/(r (r+z))],  u_z = c0 [z^2/r^3 + 2 (1-nu)/r],  c0 = 1/(4 pi G)
 * are corner sums of double antiderivatives F_i^(j) (d^2 F_i^(j)/dx_k dx_l = u_i, {k,l,j} =
 * {x,y,z}); terms depending on fewer than three corner coordinates cancel and are dropped.
 */
#include "kernels/eigen.h"

#include <math.h>

/* ln(u + r) with v2 = r^2 - u^2 >= 0; for u < 0 the form v2/(r - u) avoids the cancellation. */
static inline double log_plus(double u, double v2, double r)
{
    return u >= 0.0 ? log(u + r) : log(v2 / (r - u));
}

/* a * L for a log L that may be -inf where a = 0: the limit a ln|a| -> 0. */
static inline double mul0(double a, double L)
{
    return a != 0.0 ? a * L : 0.0;
}

/* a atan(m/(a r)), 0 at a = 0 (its limit). atan, not atan2: the function is even in a. */
static inline double xatan(double a, double m, double r)
{
    return a != 0.0 ? a * atan(m / (a * r)) : 0.0;
}

/* The nine corner functions over c0 at the corner offset (x, y, z), z >= 0, r > 0:
 * F[3*i + j] = F_i^(j) / c0, i the displacement and j the derivative direction. L_x (L_y) is
 * -inf where y = z = 0 (x = z = 0) and x < 0 (y < 0); it only appears multiplied by a
 * coordinate that is 0 there, so the products take their limit 0 (mul0): X may lie on the line
 * of a top-face edge. */
static void corner_F(double x, double y, double z, double nu, double F[9])
{
    const double x2 = x * x, y2 = y * y, z2 = z * z;
    const double r = sqrt(x2 + y2 + z2);
    const double m = 1.0 - 2.0 * nu;
    const double n2 = 2.0 * (1.0 - nu);
    const double Lx = log_plus(x, y2 + z2, r);
    const double Ly = log_plus(y, x2 + z2, r);
    const double Lz = log(z + r);
    /* T(a,b) = atan(b/a) - atan(b z/(a r)) as one atan2 with a non-negative denominator and
     * r - z = (x^2 + y^2)/(r + z); no singularity at a = 0 (theory.md §8.1). */
    const double rmz = (x2 + y2) / (r + z);
    const double Txy = atan2(x * y * rmz, x2 * r + y2 * z);
    const double Tyx = atan2(x * y * rmz, y2 * r + x2 * z);
    /* z A, A = atan2(x y, z r): only ever needed times z, 0 on the surface. */
    const double zA = z > 0.0 ? z * atan2(x * y, z * r) : 0.0;
    const double xLy = mul0(x, Ly), yLx = mul0(y, Lx), zLy = mul0(z, Ly), zLx = mul0(z, Lx);
    const double Fxy = -r - m * (z * Lz - r);
    F[0] = -xLy - m * (z * Txy - xLy);
    F[1] = Fxy;
    F[2] = -zLy - m * (y * Lz + zLy + x * Txy);
    F[3] = Fxy; /* F_y^(x): F_x^(y) with x and y swapped, which is symmetric */
    F[4] = -yLx - m * (z * Tyx - yLx);
    F[5] = -zLx - m * (x * Lz + zLx + y * Tyx);
    F[6] = y * Lz + x * Txy + n2 * (y * Lz + zLy - xatan(x, y * z, r));
    F[7] = x * Lz + y * Tyx + n2 * (x * Lz + zLx - xatan(y, x * z, r));
    F[8] = zA + n2 * (xLy + yLx - zA);
}

void mc_eigen_surface_uz(double x1, double x2, double y1, double y2, double z1, double z2,
                         double nu, double D[6])
{
    const double xs[2] = {x1, x2}, ys[2] = {y1, y2}, zs[2] = {z1, z2};
    double J[9] = {0.0};
    /* corner sign: +1 at the upper bound of each axis, product over the three axes */
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                const double s = ((i + j + k) & 1) ? 1.0 : -1.0; /* (-1)^(number of lower) */
                double F[9];
                corner_F(xs[i], ys[j], zs[k], nu, F);
                for (int q = 0; q < 9; q++)
                    J[q] += s * F[q];
            }
    /* D_ij = lambda delta_ij tr J + G (J_ij + J_ji) with J = c0 Jhat: lambda c0 = nu/((1-2nu) 2pi),
     * G c0 = 1/(4pi). Shear entries doubled (both tensor components, eigen.h). */
    const double g = 0.25 / M_PI;
    const double l = 2.0 * nu / (1.0 - 2.0 * nu) * g * (J[0] + J[4] + J[8]);
    D[0] = l + 2.0 * g * J[0];
    D[1] = l + 2.0 * g * J[4];
    D[2] = l + 2.0 * g * J[8];
    D[3] = 2.0 * g * (J[1] + J[3]);
    D[4] = 2.0 * g * (J[5] + J[7]);
    D[5] = 2.0 * g * (J[2] + J[6]);
}

/* The bar limit (docs/theory.md §8.5): F(x, +L, z) - F(x, -L, z) of the y corners as L -> infinity,
 * over c0, up to parts of x alone or z alone (they cancel in the corner sum over x and z). With
 * th = atan2(x, z) (z >= 0), lr = ln(x^2 + z^2), m = 1 - 2nu, n2 = 2 (1 - nu):
 *   F_x^(x) = x lr - m (2 z th + x lr)      F_x^(z) = (1 + m) z lr - 2 m x th
 *   F_z^(x) = 2 x th - n2 (z lr + 2 x atan(z/x))      F_z^(z) = 2 z th - n2 (x lr + 2 z th)
 * and the y entries 0. */
static void corner_F_bar(double x, double z, double nu, double F[9])
{
    const double m = 1.0 - 2.0 * nu;
    const double n2 = 2.0 * (1.0 - nu);
    const double lr = log(x * x + z * z);
    const double th = atan2(x, z);
    const double xlr = mul0(x, lr), zlr = mul0(z, lr);
    for (int q = 0; q < 9; q++)
        F[q] = 0.0;
    F[0] = xlr - m * (2.0 * z * th + xlr);
    F[2] = (1.0 + m) * zlr - 2.0 * m * x * th;
    F[6] = 2.0 * x * th - n2 * (zlr + 2.0 * xatan(x, z, 1.0));
    F[8] = 2.0 * z * th - n2 * (xlr + 2.0 * z * th);
}

void mc_eigen_surface_uz_bar(double x1, double x2, double z1, double z2, double nu, double D[6])
{
    const double xs[2] = {x1, x2}, zs[2] = {z1, z2};
    double J[9] = {0.0};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 2; i++) {
            const double s = ((i + k) & 1) ? -1.0 : 1.0; /* (-1)^(number of lower) */
            double F[9];
            corner_F_bar(xs[i], zs[k], nu, F);
            for (int q = 0; q < 9; q++)
                J[q] += s * F[q];
        }
    const double g = 0.25 / M_PI;
    const double l = 2.0 * nu / (1.0 - 2.0 * nu) * g * (J[0] + J[4] + J[8]);
    D[0] = l + 2.0 * g * J[0];
    D[1] = l + 2.0 * g * J[4];
    D[2] = l + 2.0 * g * J[8];
    D[3] = 2.0 * g * (J[1] + J[3]);
    D[4] = 2.0 * g * (J[5] + J[7]);
    D[5] = 2.0 * g * (J[2] + J[6]);
}
