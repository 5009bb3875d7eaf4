/* eigen_stress.c - stress of a cuboid of uniform eigenstrain: infinite space (S1) and the mirror
 * cuboid (S2) of the half-space solution (see eigen.h).
 *
 * Infinite space (Chiu 1977; Mura 1987; theory.md §8.2):
 *   eps_ij = K [ psi_,klij eps*_kl - 2 nu eps*_mm phi_,ij
 *                - 2 (1-nu)(eps*_ik phi_,kj + eps*_jk phi_,ki) ],
 *   K = 1/(8 pi (1-nu)),  phi = integral 1/|x-x'| dx',  psi = integral |x-x'| dx'  over the cuboid,
 *   sigma/(2G) = nu/(1-2nu) delta_ij (eps_kk - chi eps*_kk) + eps_ij - chi eps*_ij.
 * Each derivative of phi, psi is a corner sum sum s1 s2 s3 H(a), a = x - x'_corner, s_k = +1 at the
 * LOWER bound of axis k, with d^3 H / da1 da2 da3 = the derivative of 1/r or r.
 */
#include "kernels/eigen.h"

#include <math.h>

/* The 15 distinct fourth derivatives of psi, named by how often each axis appears (n0 n1 n2). */
enum {
    P400, P040, P004, /* psi_,pppp */
    P310, P301, P130, P031, P103, P013, /* psi_,pppq: p thrice, q once */
    P220, P202, P022, /* psi_,ppqq */
    P211, P121, P112, /* psi_,ppqs */
    NP4
};
/* Second derivatives of phi in the stress order xx, yy, zz, xy, yz, xz. */
enum { F11, F22, F33, F12, F23, F13, NF2 };
#define NH (NP4 + NF2)

/* atan(num/den), den = a_p r >= 0 up to the sign of a_p; a_p = 0 (of either sign) is taken as +0,
 * which puts a field point on a face plane on the side the chi rule of eigen.h assigns it to.
 * atan, not atan2: atan2 is off by pi for a_p < 0 (theory.md §8.2 pitfall). */
static inline double atan_p(double num, double den)
{
    if (den == 0.0)
        return num > 0.0 ? M_PI_2 : (num < 0.0 ? -M_PI_2 : 0.0);
    return atan(num / den);
}

/* num/den with the value 0 whenever num = 0: the terms guarded this way vanish on the lines where
 * their denominator does (the limit along the face). */
static inline double ratio0(double num, double den)
{
    return num != 0.0 ? num / den : 0.0;
}

/* Corner functions H at the corner offset a (not all zero): h[0..NP4) for psi, h[NP4..) for phi.
 * With (p, q, s) a permutation of the axes (theory.md §8.2 table):
 *   phi_,pp  -atan(a_q a_s/(a_p r))         phi_,pq  ln(a_s + r)
 *   psi_,pppp -2 atan(a_q a_s/(a_p r)) + a_p a_q a_s (r^2 + a_p^2)/(r (a_p^2+a_q^2)(a_p^2+a_s^2))
 *   psi_,pppq ln(a_s + r) + a_p^2/(r (r + a_s))      psi_,ppqq a_p a_q/(r (r + a_s))
 *   psi_,ppqs a_p/r */
static void corner_H(const double a[3], double h[NH])
{
    const double a2[3] = {a[0] * a[0], a[1] * a[1], a[2] * a[2]};
    const double r2 = a2[0] + a2[1] + a2[2];
    const double r = sqrt(r2);
    const double ir = 1.0 / r;
    double w[3], lw[3], at[3];
    for (int p = 0; p < 3; p++) {
        const int q = (p + 1) % 3, s = (p + 2) % 3;
        const double o2 = a2[q] + a2[s];
        /* r + a_p, cancellation-free for a_p < 0; 0 only on an edge line (excluded). */
        w[p] = a[p] >= 0.0 ? r + a[p] : o2 / (r - a[p]);
        lw[p] = log(w[p]);
        at[p] = atan_p(a[q] * a[s], a[p] * r);
    }
    const double a123 = a[0] * a[1] * a[2];
    /* psi_,pppp */
    for (int p = 0; p < 3; p++) {
        const int q = (p + 1) % 3, s = (p + 2) % 3;
        h[P400 + p] = -2.0 * at[p] + ratio0(a123 * (r2 + a2[p]),
                                            r * (a2[p] + a2[q]) * (a2[p] + a2[s]));
    }
    /* psi_,pppq = ln(r + a_s) + a_p^2/(r (r + a_s)), s the axis that is neither p nor q */
    h[P310] = lw[2] + ratio0(a2[0], r * w[2]);
    h[P301] = lw[1] + ratio0(a2[0], r * w[1]);
    h[P130] = lw[2] + ratio0(a2[1], r * w[2]);
    h[P031] = lw[0] + ratio0(a2[1], r * w[0]);
    h[P103] = lw[1] + ratio0(a2[2], r * w[1]);
    h[P013] = lw[0] + ratio0(a2[2], r * w[0]);
    /* psi_,ppqq = a_p a_q/(r (r + a_s)) */
    h[P220] = ratio0(a[0] * a[1], r * w[2]);
    h[P202] = ratio0(a[0] * a[2], r * w[1]);
    h[P022] = ratio0(a[1] * a[2], r * w[0]);
    /* psi_,ppqs = a_p / r */
    h[P211] = a[0] * ir;
    h[P121] = a[1] * ir;
    h[P112] = a[2] * ir;
    /* phi */
    h[NP4 + F11] = -at[0];
    h[NP4 + F22] = -at[1];
    h[NP4 + F33] = -at[2];
    h[NP4 + F12] = lw[2];
    h[NP4 + F23] = lw[0];
    h[NP4 + F13] = lw[1];
}

/* Corner sums of all H over the cuboid [xlo,xhi] x [ylo,yhi] x [zlo,zhi] seen from (x, y, z). */
static void cuboid_H(double x, double y, double z, double xlo, double xhi, double ylo,
                     double yhi, double zlo, double zhi, double sum[NH])
{
    const double ax[2] = {x - xlo, x - xhi}, ay[2] = {y - ylo, y - yhi},
                 az[2] = {z - zlo, z - zhi};
    for (int n = 0; n < NH; n++)
        sum[n] = 0.0;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                const double a[3] = {ax[i], ay[j], az[k]};
                const double s = ((i + j + k) & 1) ? -1.0 : 1.0; /* +1 at the lower bound */
                double h[NH];
                corner_H(a, h);
                for (int n = 0; n < NH; n++)
                    sum[n] += s * h[n];
            }
}

/* The bar limit (docs/theory.md §8.5): the corner functions of an infinitely long bar along y,
 * the difference H(a_x, +L, a_z) - H(a_x, -L, a_z) of the y corners as L -> infinity, up to
 * parts that depend on a_x alone or a_z alone (they cancel in the corner sum over x and z).
 * With rho^2 = a_x^2 + a_z^2 and t_p = atan(a_s/a_p) for the in-plane pair (p, s) = (x, z):
 *   psi_,xxxx -4 t_x + 2 a_x a_z/rho^2    psi_,zzzz -4 t_z + 2 a_x a_z/rho^2
 *   psi_,xxxz -ln rho^2 - 2 a_x^2/rho^2   psi_,xzzz -ln rho^2 - 2 a_z^2/rho^2
 *   psi_,xxzz -2 a_x a_z/rho^2            phi_,xx -2 t_x, phi_,zz -2 t_z, phi_,xz -ln rho^2
 * and every function with a y derivative 0 (the field does not vary along y). */
static void corner_H_bar(double ax, double az, double h[NH])
{
    const double r2 = ax * ax + az * az;
    const double lr = log(r2);
    const double tx = atan_p(az, ax), tz = atan_p(ax, az);
    const double c = ratio0(ax * az, r2);
    for (int n = 0; n < NH; n++)
        h[n] = 0.0;
    h[P400] = -4.0 * tx + 2.0 * c;
    h[P004] = -4.0 * tz + 2.0 * c;
    h[P301] = -lr - 2.0 * ratio0(ax * ax, r2);
    h[P103] = -lr - 2.0 * ratio0(az * az, r2);
    h[P202] = -2.0 * c;
    h[NP4 + F11] = -2.0 * tx;
    h[NP4 + F33] = -2.0 * tz;
    h[NP4 + F13] = -lr;
}

/* Corner sums of the bar functions over the rectangle [xlo,xhi] x [zlo,zhi] seen from (x, z). */
static void bar_H(double x, double z, double xlo, double xhi, double zlo, double zhi,
                  double sum[NH])
{
    const double ax[2] = {x - xlo, x - xhi}, az[2] = {z - zlo, z - zhi};
    for (int n = 0; n < NH; n++)
        sum[n] = 0.0;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 2; i++) {
            const double s = ((i + k) & 1) ? -1.0 : 1.0; /* +1 at the lower bound */
            double h[NH];
            corner_H_bar(ax[i], az[k], h);
            for (int n = 0; n < NH; n++)
                sum[n] += s * h[n];
        }
}

/* Slot of psi_,ijkl among the 15, by how often axes 0 and 1 occur in ijkl (axis 2: the rest). */
static const int p4_slot[5][5] = {
    {P004, P013, P022, P031, P040},
    {P103, P112, P121, P130, -1},
    {P202, P211, P220, -1, -1},
    {P301, P310, -1, -1, -1},
    {P400, -1, -1, -1, -1},
};

/* Axis pairs of the six components (xx, yy, zz, xy, yz, xz) and the component of a pair. */
static const int comp_i[6] = {0, 1, 2, 0, 1, 0};
static const int comp_j[6] = {0, 1, 2, 1, 2, 2};
static const int pair_comp[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};

/* Total strains eps[o][c] (component o per unit eigenstrain column c, columns c0 <= c < c1) of
 * Chiu's formula from the corner sums. */
static void chiu_strain(const double sum[NH], double nu, int c0, int c1, double eps[6][6])
{
    double P[3][3][3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++) {
                    const int n0 = (i == 0) + (j == 0) + (k == 0) + (l == 0);
                    const int n1 = (i == 1) + (j == 1) + (k == 1) + (l == 1);
                    P[i][j][k][l] = sum[p4_slot[n0][n1]];
                }
    double Phi[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Phi[i][j] = sum[NP4 + pair_comp[i][j]];
    const double K = 1.0 / (8.0 * M_PI * (1.0 - nu));
    for (int c = c0; c < c1; c++) {
        const int k0 = comp_i[c], l0 = comp_j[c];
        const double tr = c < 3 ? 1.0 : 0.0;
        for (int o = 0; o < 6; o++) {
            const int i = comp_i[o], j = comp_j[o];
            /* psi_,klij eps*_kl with eps*_k0l0 = eps*_l0k0 = 1 */
            double v = c < 3 ? P[k0][k0][i][j] : 2.0 * P[k0][l0][i][j];
            v -= 2.0 * nu * tr * Phi[i][j];
            /* eps*_ik phi_,kj + eps*_jk phi_,ki */
            double e = 0.0;
            if (i == k0)
                e += Phi[l0][j];
            if (i == l0 && k0 != l0)
                e += Phi[k0][j];
            if (j == k0)
                e += Phi[l0][i];
            if (j == l0 && k0 != l0)
                e += Phi[k0][i];
            v -= 2.0 * (1.0 - nu) * e;
            eps[o][c] = K * v;
        }
    }
}

/* sigma/(2G) from the total strains, with -C:eps* / (2G) where chi = 1. */
static void hooke(const double eps[6][6], double nu, int chi, double S[6][6])
{
    const double lam = nu / (1.0 - 2.0 * nu); /* lambda / (2G) */
    for (int c = 0; c < 6; c++) {
        const double tr = chi && c < 3 ? 1.0 : 0.0;
        const double vol = lam * (eps[0][c] + eps[1][c] + eps[2][c] - tr);
        for (int o = 0; o < 6; o++) {
            S[o][c] = eps[o][c] - (chi && o == c ? 1.0 : 0.0);
            if (o < 3)
                S[o][c] += vol;
        }
    }
}

/* Inside the half-open cuboid of eigen.h (lower faces belong to it), matching atan_p's +0. */
static int inside(double x, double y, double z, double hx, double hy, double z1, double z2)
{
    return x >= -hx && x < hx && y >= -hy && y < hy && z >= z1 && z < z2;
}

_Static_assert(NH == MC_EIGEN_NH, "eigen.h counts the corner functions");

void mc_eigen_corner_h(double ax, double ay, double az, double h[MC_EIGEN_NH])
{
    const double a[3] = {ax, ay, az};
    corner_H(a, h);
}

void mc_eigen_stress1_sum(const double sum[MC_EIGEN_NH], double nu, int inside, double S[6][6])
{
    double eps[6][6];
    chiu_strain(sum, nu, 0, 6, eps);
    hooke(eps, nu, inside, S);
}

void mc_eigen_stress1(double x, double y, double z, double hx, double hy, double z1, double z2,
                      double nu, double S[6][6])
{
    double sum[NH], eps[6][6];
    cuboid_H(x, y, z, -hx, hx, -hy, hy, z1, z2, sum);
    chiu_strain(sum, nu, 0, 6, eps);
    hooke(eps, nu, inside(x, y, z, hx, hy, z1, z2), S);
}

void mc_eigen_stress12(double x, double y, double z, double hx, double hy, double z1, double z2,
                       double nu, double S[6][6])
{
    double s1[NH], s2[NH], sp[NH], sm[NH], eps[6][6];
    cuboid_H(x, y, z, -hx, hx, -hy, hy, z1, z2, s1);
    cuboid_H(x, y, z, -hx, hx, -hy, hy, -z2, -z1, s2);
    /* The mirror carries R eps* R: columns yz, xz with the opposite sign. Chiu's strain is linear
     * in the corner sums, so combine the sums first: s1 + s2 for columns xx..xy, s1 - s2 for yz,
     * xz. The field point (z >= 0) is never inside the mirror, so chi comes from S1 only. */
    for (int n = 0; n < NH; n++) {
        sp[n] = s1[n] + s2[n];
        sm[n] = s1[n] - s2[n];
    }
    chiu_strain(sp, nu, 0, 4, eps);
    chiu_strain(sm, nu, 4, 6, eps);
    hooke(eps, nu, inside(x, y, z, hx, hy, z1, z2), S);
}

void mc_eigen_surface_szz12(double x, double y, double hx, double hy, double z1, double z2,
                            double nu, double s[6])
{
    double S[6][6];
    /* sigma_zz^S2(x, y, 0) = sigma_zz^S1(x, y, -0) (mirror; R_zz^2 = 1) = sigma_zz^S1(x, y, +0)
     * (the traction is continuous across the face z = z1 = 0, or the field is smooth). */
    mc_eigen_stress1(x, y, 0.0, hx, hy, z1, z2, nu, S);
    for (int c = 0; c < 6; c++)
        s[c] = 2.0 * S[2][c];
}

/* ---- the bar limit (plane strain; docs/theory.md §8.5) --------------------------------------- */

static int inside_bar(double x, double z, double hx, double z1, double z2)
{
    return x >= -hx && x < hx && z >= z1 && z < z2;
}

void mc_eigen_stress1_bar(double x, double z, double hx, double z1, double z2, double nu,
                          double S[6][6])
{
    double sum[NH], eps[6][6];
    bar_H(x, z, -hx, hx, z1, z2, sum);
    chiu_strain(sum, nu, 0, 6, eps);
    hooke(eps, nu, inside_bar(x, z, hx, z1, z2), S);
}

void mc_eigen_stress12_bar(double x, double z, double hx, double z1, double z2, double nu,
                           double S[6][6])
{
    double s1[NH], s2[NH], sp[NH], sm[NH], eps[6][6];
    bar_H(x, z, -hx, hx, z1, z2, s1);
    bar_H(x, z, -hx, hx, -z2, -z1, s2);
    for (int n = 0; n < NH; n++) {
        sp[n] = s1[n] + s2[n];
        sm[n] = s1[n] - s2[n];
    }
    chiu_strain(sp, nu, 0, 4, eps);
    chiu_strain(sm, nu, 4, 6, eps);
    hooke(eps, nu, inside_bar(x, z, hx, z1, z2), S);
}

void mc_eigen_surface_szz12_bar(double x, double hx, double z1, double z2, double nu, double s[6])
{
    double S[6][6];
    mc_eigen_stress1_bar(x, 0.0, hx, z1, z2, nu, S);
    for (int c = 0; c < 6; c++)
        s[c] = 2.0 * S[2][c];
}
