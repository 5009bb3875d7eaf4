/* precond.h - FFT-based preconditioner for the contact solvers.
 *
 * Approximates the inverse of the influence matrix restricted to a set S of free cells,
 *     z = R_S F^-1[ |q| F(R_S^T r) ]    on the bounding box of S (plus a margin),
 * i.e. the inverse of the continuum Love symbol 2/(E*|q|) (Johnson 1985 ch. 2; Stanley & Kato
 * 1997), up to the constant factor E* / 2 that a CG step length absorbs. The box is treated as
 * periodic; along periodic axes of the grid the box is the whole axis. After Vollebregt,
 * J. Comput. Phys. 257 (2014) 333-351 ("FFT-based preconditioner"). FFT plans are cached per box
 * size, so a solve plans only when its contact's bounding box changes size.
 */
#ifndef MC_PRECOND_H
#define MC_PRECOND_H

#include "core/error.h"
#include "core/grid.h"

typedef struct mc_precond mc_precond;

/* Allocate for grid g (buffers sized for the whole grid; never reallocated). */
int mc_precond_create(const mc_grid *g, mc_precond **out, mc_error *err);
void mc_precond_destroy(mc_precond **pc);

/* Fit the box to the cells with mask[i] != 0 (plans a new size if needed; MC_ERR_NOMEM if FFTW
 * cannot plan, MC_ERR_INTERNAL if its threads cannot start). Call when the set changes; cheap
 * when the box size did not change. */
int mc_precond_set_mask(mc_precond *pc, const unsigned char *mask, mc_error *err);

/* z = R_S M R_S^T r on the mask of the last set_mask call; z = 0 outside the mask.
 * r and z are full-grid arrays (ny*nx) and must not alias. Never allocates. */
void mc_precond_apply(mc_precond *pc, const unsigned char *mask, const double *r, double *z);

/* The same, but z holds rows r0 .. r0 + nr - 1 only (nr*nx values, row r0 + k at k*nx): a solver
 * whose work arrays are its slab of rows (contact/); mask and r are whole. The same values in
 * those rows as mc_precond_apply. Never allocates. */
void mc_precond_apply_rows(mc_precond *pc, const unsigned char *mask, const double *r, double *z,
                           int r0, int nr);

/* ---- distributed (core/dist.h): the box's transform split over the run's ranks ------------
 * Under a communicator the box's FFT runs over the ranks (operator/dfft.h, a transform of the
 * box's size): each rank passes its slab of grid rows r0 .. r0 + nr - 1 (nr * nx values, row
 * r0 + k at k * nx; the ranks' slabs ascend with the rank and cover the grid) of the mask, of r
 * and of z; the box is bounded by a reduction, the box's rows go to the transform's rows and
 * back by all-to-all exchanges (8 bytes a box cell each way): neither the gradient nor the mask
 * is gathered whole, no array of the grid's size is kept. The same bits on any number of ranks
 * (dfft.h: one-line transforms; the exchanges only move values); against the serial transform
 * (a 2-D FFTW plan) they differ by round-off. Without a communicator these are the calls above
 * on the whole grid (r0 = 0, nr = ny). */

/* Collective. */
int mc_precond_create_rows(const mc_grid *g, int r0, int nr, mc_precond **out, mc_error *err);

/* mc_precond_set_mask on this rank's rows of the mask. Collective. */
int mc_precond_set_mask_rows(mc_precond *pc, const unsigned char *mask, mc_error *err);

/* z = R_S M R_S^T r on this rank's rows (mask, r, z: slabs as above). Never allocates.
 * Collective. */
void mc_precond_apply_slab(mc_precond *pc, const unsigned char *mask, const double *r, double *z);

#endif
