/* increment.h - a load step's plastic strain increment held on the cells where it is not zero
 * (docs/theory.md §9.9): the joint iteration with the spectral kernel keeps its iterate and the
 * sweep's image this way instead of as dense volume arrays, since the plastic zone of one load
 * step is a small part of the volume. Entries ascend by volume index; each carries the six
 * components of d eps_p (xx .. xz, tensor components) and d p (the equivalent plastic strain
 * increment), MC_INCR_WIDTH values. Pure numerics. */
#ifndef MC_PLASTIC_INCREMENT_H
#define MC_PLASTIC_INCREMENT_H

#include "plastic/eigen_op.h"

#define MC_INCR_WIDTH 7

typedef struct {
    long n, cap;
    long *cell;  /* n volume indices, ascending */
    double *val; /* MC_INCR_WIDTH per entry */
} mc_plastic_incr;

/* Room for n entries (the contents kept); 0 when memory is short (nothing changed). */
int mc_incr_reserve(mc_plastic_incr *a, long n);

/* Append an entry (cell above the last one); 0 when memory is short (nothing appended). */
int mc_incr_push(mc_plastic_incr *a, long cell, const double v[MC_INCR_WIDTH]);

/* dst = s x src (entries whose values are all zero dropped); 0 when memory is short. */
int mc_incr_scaled(mc_plastic_incr *dst, const mc_plastic_incr *src, double s);

/* The entries of cells first <= cell < last: k0 .. k1 - 1. */
void mc_incr_range(const mc_plastic_incr *a, long first, long last, long *k0, long *k1);

/* Sort the entries by cell (each cell at most once); tmp is scratch of the same kind, swapped
 * with a when the order changes. 0 when memory is short (a unchanged). */
int mc_incr_sort(mc_plastic_incr *a, mc_plastic_incr *tmp);

/* The six strain components as the operators' sparse addend (eigen_op.h). */
mc_eigen_sparse mc_incr_strain(const mc_plastic_incr *a);

/* dense (MC_INCR_WIDTH component-major blocks: the six strain components of nvol cells, then
 * with dp != NULL d p into dp) at the listed cells, set; the other cells untouched. */
void mc_incr_scatter(const mc_plastic_incr *a, long nvol, double *d6, double *dp);

/* The cells of dense fields d6 (six blocks of nvol) and dp (nvol) where a value is not zero, in
 * order; 0 when memory is short. */
int mc_incr_gather(mc_plastic_incr *a, long nvol, const double *d6, const double *dp);

/* 1 when a value of the entries is not zero. */
int mc_incr_any(const mc_plastic_incr *a);

void mc_incr_free(mc_plastic_incr *a); /* frees and zeroes; zeroed structs too */

#endif
