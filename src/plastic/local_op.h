/* local_op.h - the near field of the residual stress operator (docs/theory.md §9.7): the
 * stress at a cuboid centre of the eigenstrain of the cuboids within `reach` columns along x
 * and y and `reach_z` layers, as dense 6 x 6 blocks of influence coefficients. The plastic fixed
 * point (loop.c) iterates with it between applications of the whole operator (eigen_op.h):
 * local-global defect correction, where each global application corrects the far field.
 *
 * The blocks are read off the residual stress operator itself (eigen_op.h, fft backend): the
 * response of a unit eigenstrain at the centre column of a small probe grid with the same cells,
 * layers, evaluation (stress_points) and lateral axes. Laterally the operator is a convolution,
 * so the blocks are those of the large grid up to the surface correction S3 of the probe's
 * smaller window (the part that decays as the cube of the inverse distance): they need not be
 * exact, only near, because the global application settles the fixed point (loop.c).
 * Pure numerics: no scene, no printing.
 */
#ifndef MC_PLASTIC_LOCAL_OP_H
#define MC_PLASTIC_LOCAL_OP_H

#include "core/error.h"
#include "core/grid.h"
#include "plastic/eigen_op.h"

typedef struct mc_plastic_local mc_plastic_local;

/* Plan the near-field operator of the residual stress on volume v of grid g (Poisson ratio nu)
 * with lateral reach `reach` >= 0 columns and depth reach `reach_z` >= 0 layers. Along an axis of
 * one column (a line contact's bars) or a periodic axis of fewer than 2 reach + 1 columns the
 * lateral reach is cut to what the axis holds. *out is NULL on failure. MC_OK, MC_ERR_INPUT,
 * MC_ERR_NOMEM or the errors of mc_eigen_stress_create. */
int mc_plastic_local_create(const mc_grid *g, const mc_eigen_volume *v, double nu, int reach,
                            int reach_z, mc_plastic_local **out, mc_error *err);

/* The near-field stress at volume cell (k, j, i) (window-relative; volume layout of eigen_op.h)
 * of the eigenstrain field d (component-major 6 x nvol) restricted to the cells where
 * active[cell] >= 0, minus the same of d0: sig[c] = G sum over near cells s of B(s) (d - d0)(s),
 * d0 given per active cell as d0[6 * active[s] + c]. Pa for G in Pa. */
void mc_plastic_local_apply(const mc_plastic_local *op, const double *d, const double *d0,
                            const int *active, double G, int k, long j, long i, double sig[6]);

/* The transpose of mc_plastic_local_apply for one source: add the near-field stress (per G) of
 * the eigenstrain r (6 components) at volume cell (k, j, i) to corr[6 active[t] + c] of every
 * active cell t within reach (the incremental form of the local solve: only the sources whose
 * eigenstrain moved are spread). */
void mc_plastic_local_scatter(const mc_plastic_local *op, const double r[6], const int *active,
                              int k, long j, long i, double *corr);

/* Bytes held (the blocks). */
size_t mc_plastic_local_bytes(const mc_plastic_local *op);

void mc_plastic_local_destroy(mc_plastic_local **op); /* frees, sets *op = NULL; NULL-safe */

#endif
