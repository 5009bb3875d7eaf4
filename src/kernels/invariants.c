/* invariants.c - von Mises, hydrostatic, principal stresses, Tresca (see invariants.h). */
#include "kernels/invariants.h"

#include <math.h>

#include "kernels/kernel.h"
#include "core/threads.h" /* MC_THREADS_MIN_CELLS */

double mc_von_mises(const double s[6])
{
    double a = s[MC_SXX] - s[MC_SYY], b = s[MC_SYY] - s[MC_SZZ], c = s[MC_SZZ] - s[MC_SXX];
    double sh = s[MC_SXY] * s[MC_SXY] + s[MC_SYZ] * s[MC_SYZ] + s[MC_SXZ] * s[MC_SXZ];
    return sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * sh);
}

double mc_hydrostatic(const double s[6]) { return (s[MC_SXX] + s[MC_SYY] + s[MC_SZZ]) / 3.0; }

/* The deviatoric cubic in trigonometric form: the principal stresses are
 * m + 2 sqrt(J2/3) cos(theta + 2 pi k/3), k = 0, -1, 1, with theta in [0, pi/3]. */
typedef struct {
    double mean;  /* hydrostatic stress */
    double sJ2;   /* sqrt(J2) */
    double theta; /* Lode-type angle in [0, pi/3] */
} deviator_angle;

/* The discriminant D = 4 J2^3 - 27 J3^2 = prod_{i<j} (l_i - l_j)^2 of a symmetric d equals
 * det(B^T B) with B = [vec I, vec d, vec d^2] (Parlett 2002); by Cauchy-Binet it is the sum of
 * the squared 3x3 minors of B. Off-diagonal entries occur twice in vec(), hence the weight 2 per
 * off-diagonal row. Each minor is accurate to a few eps |d|^3 in absolute terms, so D keeps its
 * small value near repeated roots instead of being lost in 4 J2^3 - 27 J3^2 (Habera & Zilian 2021,
 * arXiv:2111.02117, make the same point). */
static double discriminant(const double d[6])
{
    double dd[6]; /* d^2, symmetric, kernel.h order */
    dd[MC_SXX] = d[MC_SXX] * d[MC_SXX] + d[MC_SXY] * d[MC_SXY] + d[MC_SXZ] * d[MC_SXZ];
    dd[MC_SYY] = d[MC_SXY] * d[MC_SXY] + d[MC_SYY] * d[MC_SYY] + d[MC_SYZ] * d[MC_SYZ];
    dd[MC_SZZ] = d[MC_SXZ] * d[MC_SXZ] + d[MC_SYZ] * d[MC_SYZ] + d[MC_SZZ] * d[MC_SZZ];
    dd[MC_SXY] = d[MC_SXX] * d[MC_SXY] + d[MC_SXY] * d[MC_SYY] + d[MC_SXZ] * d[MC_SYZ];
    dd[MC_SYZ] = d[MC_SXY] * d[MC_SXZ] + d[MC_SYY] * d[MC_SYZ] + d[MC_SYZ] * d[MC_SZZ];
    dd[MC_SXZ] = d[MC_SXX] * d[MC_SXZ] + d[MC_SXY] * d[MC_SYZ] + d[MC_SXZ] * d[MC_SZZ];
    /* rows of B: (1, d, d^2) for xx, yy, zz; (0, d, d^2) for xy, yz, xz */
    double sum = 0.0;
    for (int i = 0; i < 6; i++)
        for (int j = i + 1; j < 6; j++)
            for (int k = j + 1; k < 6; k++) {
                double ui = i < 3, uj = j < 3, uk = k < 3;
                if (ui + uj + uk == 0.0)
                    continue; /* the identity column vanishes on these rows */
                double m = ui * (d[j] * dd[k] - d[k] * dd[j]) - uj * (d[i] * dd[k] - d[k] * dd[i]) +
                           uk * (d[i] * dd[j] - d[j] * dd[i]);
                double w = (i >= 3 ? 2.0 : 1.0) * (j >= 3 ? 2.0 : 1.0) * (k >= 3 ? 2.0 : 1.0);
                sum += w * m * m;
            }
    return sum;
}

static deviator_angle deviator_angle_of(const double s[6])
{
    deviator_angle r;
    double sxx = s[MC_SXX], syy = s[MC_SYY], szz = s[MC_SZZ];
    r.mean = (sxx + syy + szz) / 3.0;
    /* deviator from differences: exact-ish even under a large hydrostatic part */
    double d[6];
    d[MC_SXX] = ((sxx - syy) + (sxx - szz)) / 3.0;
    d[MC_SYY] = ((syy - sxx) + (syy - szz)) / 3.0;
    d[MC_SZZ] = ((szz - sxx) + (szz - syy)) / 3.0;
    d[MC_SXY] = s[MC_SXY];
    d[MC_SYZ] = s[MC_SYZ];
    d[MC_SXZ] = s[MC_SXZ];
    /* scale to O(1): keeps |d|^6 in D clear of overflow and underflow */
    double sc = 0.0;
    int bad = 0;
    for (int c = 0; c < 6; c++) {
        sc = fmax(sc, fabs(d[c]));
        bad |= !isfinite(d[c]);
    }
    if (bad) { /* NaN or Inf in, NaN out (fmax would hide a NaN) */
        r.mean = r.sJ2 = r.theta = NAN;
        return r;
    }
    if (sc == 0.0) { /* hydrostatic: a triple root */
        r.sJ2 = 0.0;
        r.theta = 0.0;
        return r;
    }
    for (int c = 0; c < 6; c++)
        d[c] /= sc;
    double a = sxx - syy, b = syy - szz, cc = szz - sxx;
    double J2 = (a * a + b * b + cc * cc) / (6.0 * sc * sc) + d[MC_SXY] * d[MC_SXY] +
                d[MC_SYZ] * d[MC_SYZ] + d[MC_SXZ] * d[MC_SXZ];
    double J3 = d[MC_SXX] * (d[MC_SYY] * d[MC_SZZ] - d[MC_SYZ] * d[MC_SYZ]) -
                d[MC_SXY] * (d[MC_SXY] * d[MC_SZZ] - d[MC_SYZ] * d[MC_SXZ]) +
                d[MC_SXZ] * (d[MC_SXY] * d[MC_SYZ] - d[MC_SYY] * d[MC_SXZ]);
    double D = discriminant(d);
    /* cos(3 theta) = 3 sqrt(3) J3 / (2 J2^1.5), sin(3 theta) = sqrt(D) / (2 J2^1.5) */
    r.theta = atan2(sqrt(D), 3.0 * sqrt(3.0) * J3) / 3.0;
    r.sJ2 = sqrt(J2) * sc;
    return r;
}

void mc_principal_stresses(const double s[6], double p[3])
{
    deviator_angle g = deviator_angle_of(s);
    double c = 2.0 / sqrt(3.0) * g.sJ2; /* 2 sqrt(J2/3) */
    double t = g.theta, third = 2.0 * M_PI / 3.0;
    double a = g.mean + c * cos(t);
    double b = g.mean + c * cos(t - third);
    double e = g.mean + c * cos(t + third);
    /* theta in [0, pi/3] orders them a >= b >= e; sort anyway against last-bit rounding */
    if (b > a) {
        double tmp = a;
        a = b;
        b = tmp;
    }
    if (e > b) {
        double tmp = b;
        b = e;
        e = tmp;
    }
    if (b > a) {
        double tmp = a;
        a = b;
        b = tmp;
    }
    p[0] = a;
    p[1] = b;
    p[2] = e;
}

double mc_tresca(const double s[6])
{
    deviator_angle g = deviator_angle_of(s);
    /* (s1 - s3)/2 = sqrt(J2) (cos t - cos(t + 2pi/3))/sqrt(3) = sqrt(J2) sin(t + pi/3) */
    return g.sJ2 * sin(g.theta + M_PI / 3.0);
}

int mc_invariants_volume(size_t n, const double *sxx, const double *syy, const double *szz,
                         const double *sxy, const double *syz, const double *sxz, double *vm,
                         double *hydro, double *tresca, mc_error *err)
{
    if (n == 0)
        return MC_OK;
    const double *in[MC_NSTRESS] = {sxx, syy, szz, sxy, syz, sxz}; /* kernel.h order */
    static const char *const names[MC_NSTRESS] = {"xx", "yy", "zz", "xy", "yz", "xz"};
    for (int c = 0; c < MC_NSTRESS; c++)
        if (!in[c])
            return mc_fail(err, MC_ERR_INPUT, "invariants: stress component s%s is NULL", names[c]);
    ptrdiff_t nn = (ptrdiff_t)n;
#pragma omp parallel for schedule(static) if (nn > MC_THREADS_MIN_CELLS)
    for (ptrdiff_t i = 0; i < nn; i++) {
        double t[6];
        t[MC_SXX] = sxx[i];
        t[MC_SYY] = syy[i];
        t[MC_SZZ] = szz[i];
        t[MC_SXY] = sxy[i];
        t[MC_SYZ] = syz[i];
        t[MC_SXZ] = sxz[i];
        if (vm)
            vm[i] = mc_von_mises(t);
        if (hydro)
            hydro[i] = mc_hydrostatic(t);
        if (tresca)
            tresca[i] = mc_tresca(t);
    }
    return MC_OK;
}
