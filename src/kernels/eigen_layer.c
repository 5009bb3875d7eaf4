/* eigen_layer.c - the layer limit of the cuboid kernels (see eigen.h): a laterally unbounded
 * layer of uniform eigenstrain, the Fourier mode k = 0 of a doubly periodic field, in closed form
 * (docs/theory.md §8.6).
 *
 * Laterally uniform, the fields depend on z alone: the in-plane total strains vanish, and
 * equilibrium with a traction-free surface (or decay at infinity) leaves sigma_zz = sigma_xz =
 * sigma_yz = 0 everywhere. Inside the layer the elastic strain is then e_xx = -eps*_xx,
 * e_yy = -eps*_yy, e_xy = -eps*_xy and sigma_zz = 0 fixes e_zz, so
 *   sigma_xx = -2G [eps*_xx + nu/(1-nu) (eps*_xx + eps*_yy)],   sigma_yy likewise,
 *   sigma_xy = -2G eps*_xy,   outside the layer all stresses 0 (no mirror, no surface term),
 * and the surface moves by the integral of -eps_zz = -[eps*_zz + nu/(1-nu)(eps*_xx + eps*_yy)].
 */
#include "kernels/eigen.h"

#include <string.h>

void mc_eigen_stress1_layer(double z, double z1, double z2, double nu, double S[6][6])
{
    memset(S, 0, 36 * sizeof S[0][0]);
    if (!(z >= z1 && z < z2)) /* the half-open layer, as the cuboid's faces (eigen.h) */
        return;
    const double a = nu / (1.0 - nu);
    S[0][0] = S[1][1] = -(1.0 + a); /* rows xx, yy per their own column */
    S[0][1] = S[1][0] = -a;
    S[3][3] = -1.0; /* column xy carries eps*_xy = eps*_yx = 1 */
}

void mc_eigen_surface_uz_layer(double z1, double z2, double nu, double D[6])
{
    const double t = z2 - z1, a = nu / (1.0 - nu);
    D[0] = D[1] = -a * t;
    D[2] = -t;
    D[3] = D[4] = D[5] = 0.0;
}
