/* psum.c - the two common sums of psum.h. */
#include "core/psum.h"

double mc_psum_dot(const double *a, const double *b, size_t n)
{
    const mc_psum ps = mc_psum_blocks(n);
    double part[MC_PSUM_MAX_BLOCKS];
#pragma omp parallel for schedule(static) if (ps.nb > 1)
    for (long k = 0; k < ps.nb; k++) {
        double s = 0;
        for (size_t i = mc_psum_lo(&ps, k); i < mc_psum_hi(&ps, k); i++)
            s += a[i] * b[i];
        part[k] = s;
    }
    return mc_psum_total(part, ps.nb);
}

double mc_psum_masked(const double *v, const unsigned char *mask, size_t n, size_t *count)
{
    const mc_psum ps = mc_psum_blocks(n);
    double part[MC_PSUM_MAX_BLOCKS];
    size_t m = 0;
#pragma omp parallel for schedule(static) reduction(+ : m) if (ps.nb > 1)
    for (long k = 0; k < ps.nb; k++) {
        double s = 0;
        for (size_t i = mc_psum_lo(&ps, k); i < mc_psum_hi(&ps, k); i++)
            if (mask[i]) {
                s += v[i];
                m++;
            }
        part[k] = s;
    }
    *count = m;
    return mc_psum_total(part, ps.nb);
}
