/* anderson.h - Anderson acceleration of a fixed-point iteration x <- g(x) whose iterates are
 * non-zero on a few cells of a large field (the plastic strain increment of plastic/loop.c: zero
 * wherever nothing yields).
 *
 * Anderson mixing (Anderson 1965; in the form of Walker & Ni, SIAM J. Numer. Anal. 49 (2011)
 * 1715-1735, "type II"): with the residuals f_k = g(x_k) - x_k of the last m + 1 iterates, the
 * next iterate is
 *     x_{k+1} = g(x_k) - sum_j gamma_j (g(x_{j+1}) - g(x_j)),
 *     gamma = argmin || f_k - sum_j gamma_j (f_{j+1} - f_j) ||_2,
 * i.e. the combination of the recent images whose linearised residual is smallest. On a
 * linearly converging iteration (the plastic fixed point contracts by about 0.8 per sweep) it
 * converges several times faster; with m = 0 it is the plain iteration.
 *
 * Storage is restricted to the active cells: a cell joins when x or g(x) is non-zero on it and
 * stays until the next restart; its earlier history entries are zero, which is exact (x and g(x)
 * were zero there). Memory: (2 (m + 1) + 1) width doubles and two indices per active cell, plus,
 * once a dense step is taken, a map of ncells ints (4 bytes per cell; at most INT_MAX cells; the
 * sparse steps find their cells through the active cells sorted by cell instead).
 * Fields are component-major: value q of cell v at [q * ncells + v], q < width.
 */
#ifndef MC_ANDERSON_H
#define MC_ANDERSON_H

#include "core/error.h"

#define MC_ANDERSON_MAX_DEPTH 8

typedef struct mc_anderson mc_anderson;

/* An accelerator for fields of ncells cells with width values each (component-major), history
 * depth 1 <= depth <= MC_ANDERSON_MAX_DEPTH. MC_OK, MC_ERR_INPUT, MC_ERR_NOMEM. */
int mc_anderson_create(long ncells, int width, int depth, mc_anderson **out, mc_error *err);

/* Forget the history (a new fixed-point problem, e.g. new elastic stresses). */
void mc_anderson_restart(mc_anderson *a);

/* One step: x holds the iterate x_k, gx its image g(x_k); x is replaced by x_{k+1}. The first
 * step after a restart (or one that cannot mix: a singular least-squares system) is the plain
 * x_{k+1} = g(x_k). MC_OK, or MC_ERR_NOMEM when the active set cannot grow (x is then g(x_k) and
 * the history is dropped: the iteration goes on unaccelerated). */
int mc_anderson_step(mc_anderson *a, double *x, const double *gx, mc_error *err);

/* The same step with x and g(x) given sparse, as the plastic loop holds its increment (theory
 * §9.9): nx entries of x at cells xcell (each cell once), their width values at
 * xval[stride e + q], and ng entries of g(x) likewise, each list ascending by cell; the cells
 * not listed are zero. The new
 * iterate is not zero on the active cells alone: *n of them, *cells (in the order they joined,
 * not sorted) with their width values at (*vals)[width k + q], both the accelerator's (valid
 * until its next call). The same bits as mc_anderson_step on the dense fields. MC_OK;
 * MC_ERR_NOMEM (history dropped; the caller goes on with g(x_k)); MC_ERR_INPUT in rows mode or
 * for stride < width. */
int mc_anderson_step_sparse(mc_anderson *a, long nx, const long *xcell, const double *xval,
                            long ng, const long *gcell, const double *gval, int stride,
                            long *n, const long **cells, const double **vals, mc_error *err);

/* Distributed runs (core/dist.h): the field's cells are nblocks x ny x nx (cell (b, j, i) at
 * (b ny + j) nx + i) and this rank keeps rows r0 .. r0 + nr - 1 of every block. The steps that
 * follow read and write those cells alone (the others of x are left as they are) and sum the dot
 * products row by row over the ranks in a fixed order: every rank mixes with the same
 * coefficients, and any number of ranks gives the same bits (not those of the whole field's
 * steps, whose sums run over the active cells). nr < 0: the whole field again (the default).
 * Restarts. Returns 0 (the whole field kept) when the shape does not fit or memory is short.
 * Every rank calls it alike; steps in rows mode are collective. */
int mc_anderson_rows(mc_anderson *a, int nblocks, int ny, int nx, int r0, int nr);

/* Active cells since the last restart. */
long mc_anderson_active(const mc_anderson *a);

void mc_anderson_destroy(mc_anderson **a); /* frees and sets *a = NULL; NULL-safe */

#endif
