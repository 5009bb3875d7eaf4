/* psum.h - sums over long arrays that give the same bits on any thread count.
 *
 * An OpenMP reduction adds in an order that depends on the number of threads, so a solver whose
 * iterates depend on its sums would follow another path on another machine. Here an array of n
 * values is cut into blocks fixed by n alone (mc_psum_blocks): each block is summed in index
 * order (by whichever thread), and the block sums are then added in block order. Up to
 * MC_THREADS_MIN_CELLS values (where the loops run on one thread anyway) there is one block: the
 * plain left-to-right sum, bit for bit. Beyond, blocks of at least MC_PSUM_BLOCK values, at most
 * MC_PSUM_MAX_BLOCKS of them.
 *
 * Use:
 *     mc_psum ps = mc_psum_blocks(n);
 *     double part[MC_PSUM_MAX_BLOCKS];
 *     #pragma omp parallel for schedule(static) if (ps.nb > 1)
 *     for (long b = 0; b < ps.nb; b++) {
 *         double s = 0;
 *         for (size_t i = mc_psum_lo(&ps, b); i < mc_psum_hi(&ps, b); i++) s += ...;
 *         part[b] = s;
 *     }
 *     double total = mc_psum_total(part, ps.nb);
 */
#ifndef MC_PSUM_H
#define MC_PSUM_H

#include <stddef.h>

#include "core/threads.h"

#define MC_PSUM_BLOCK ((size_t)1 << 16)
#define MC_PSUM_MAX_BLOCKS 512

typedef struct {
    size_t n, blk; /* values, values per block (the last block may be shorter) */
    long nb;       /* blocks */
} mc_psum;

static inline mc_psum mc_psum_blocks(size_t n)
{
    mc_psum p = {n, n, 1};
    if (n > MC_THREADS_MIN_CELLS) {
        p.blk = MC_PSUM_BLOCK;
        while ((n + p.blk - 1) / p.blk > MC_PSUM_MAX_BLOCKS)
            p.blk *= 2;
        p.nb = (long)((n + p.blk - 1) / p.blk);
    }
    return p;
}

static inline size_t mc_psum_lo(const mc_psum *p, long b) { return (size_t)b * p->blk; }

static inline size_t mc_psum_hi(const mc_psum *p, long b)
{
    const size_t hi = (size_t)(b + 1) * p->blk;
    return hi < p->n ? hi : p->n;
}

/* The block sums in block order. */
static inline double mc_psum_total(const double *part, long nb)
{
    double s = 0;
    for (long b = 0; b < nb; b++)
        s += part[b];
    return s;
}

/* sum a[i] b[i], i < n. */
double mc_psum_dot(const double *a, const double *b, size_t n);

/* sum of v[i] over the cells with mask[i] != 0, and their number in *count. */
double mc_psum_masked(const double *v, const unsigned char *mask, size_t n, size_t *count);

#endif
