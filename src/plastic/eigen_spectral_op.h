/* eigen_spectral_op.h - the spectral eigenstrain operator (docs/theory.md §8.10): the residual
 * stress at the cell centres and the surface residual displacement of a volume of eigenstrain,
 * with the lateral field a sampled trigonometric polynomial and the kernel evaluated per lateral
 * Fourier mode when used (kernels/eigen_spectral.h), so that no kernel spectra are stored.
 *
 * It is a second discretisation, not a faster path to the cuboid operators' numbers
 * (plastic/eigen_op.h): laterally the eigenstrain of a cell is a sample of a band-limited field
 * instead of a uniform cuboid; in depth both hold it constant per layer. The two agree to the
 * lateral discretisation error, O((k h)^2) for a smooth field (tests/test_eigen_spectral_op.c
 * measures it).
 *
 * Grids: every combination of free and periodic axes (a periodic axis with one row: bars along
 * it, the line contact). A periodic axis is transformed over its period; a free axis is zero
 * padded to a period of at least twice the grid (mc_fftsize_good), so the field's images lie a
 * grid away: their stress falls like (zone / distance)^3 (theory §8.10 measures it). The volume
 * lies under the whole grid (a smaller window: MC_ERR_LIMIT). Graded layers as eigen_op.h.
 * Volume fields and units as eigen_op.h (six arrays nz * ny * nx, layer-major; sig in Pa with
 * G; u_z in m, > 0 into the body).
 *
 * Backends behind one interface:
 *   fft    - two passes over the layers (down, then up), each block of layers transformed when
 *            its turn comes (pruned padded FFTs, the layers' components in parallel), per lateral
 *            mode the running sums of the depth step (kernels/eigen_spectral.h
 *            mc_spec_modes_pass: many modes at once): neither the kernel nor the layers' spectra
 *            are stored, only a state of 61 doubles per lateral bin (~1 kB per surface cell on a
 *            free grid, 1/4 of it doubly periodic) and a block's spectra (up to 4 layers); at
 *            256^2 x 32: 46 (free) and 12 (doubly periodic) bytes per volume cell, one apply
 *            1.3 s (free) on one thread of this 2-core machine;
 *   direct - the kernel per pair of layers (mc_spec_pair) taken to space by a plain inverse DFT
 *            into tables over the period, summed cell by cell in O(N^2 nz^2): the reference, for
 *            small grids.
 * Points in depth: MC_EIG_CELL_AVERAGE (the default) averages the stress over the layer's depth
 * (Galerkin: no energy-releasing mode), MC_EIG_CELL_CENTRE takes it at the layer's centre.
 *
 * One thread at a time per object; create from one thread (FFTW's planner). Not distributed.
 */
#ifndef MC_EIGEN_SPECTRAL_OP_H
#define MC_EIGEN_SPECTRAL_OP_H

#include <stddef.h>

#include "core/error.h"
#include "core/grid.h"
#include "operator/operator.h"
#include "plastic/eigen_op.h"

typedef struct mc_eigen_spectral mc_eigen_spectral;

/* Plan for grid g, volume v (under the whole grid), Poisson ratio nu in (-1, 0.5), backend b.
 * MC_OK; MC_ERR_INPUT (bad grid, volume, nu, backend), MC_ERR_LIMIT (a window smaller than the
 * grid; the direct backend beyond MC_SPEC_DIRECT_MAX table values), MC_ERR_NOMEM. */
int mc_eigen_spectral_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                             mc_eigen_spectral **out, mc_error *err);

/* The direct backend's tables hold nz^2 x 36 x (periods) values: at most this many. */
#define MC_SPEC_DIRECT_MAX (1L << 26)

/* sig[6] (Pa, volume layout) = the residual stress of eps (G the shear modulus, Pa); uz (grid
 * ny * nx, m; NULL: not wanted) the surface residual displacement. Never fails. */
void mc_eigen_spectral_apply(mc_eigen_spectral *op, const double *const eps[6], double G,
                             double *const sig[6], double *uz);

/* The same of the field eps + inc, inc a sparse addend (eigen_op.h mc_eigen_sparse; NULL or
 * no entries: eps alone), the sum formed value by value as the layers are read, so the results
 * are the bits of applying the summed field and no volume array of the sum exists (the fft
 * backend; the direct one forms it in a scratch of the object). */
void mc_eigen_spectral_apply_sum(mc_eigen_spectral *op, const double *const eps[6],
                                 const mc_eigen_sparse *inc, double G, double *const sig[6],
                                 double *uz);

/* The same apply in two halves, for the plastic loop's evaluation (theory §9.9): begin makes
 * the down pass (the stresses of the layers above each layer, its own and the local term, into
 * sig) and u_z; end_sum adds the rest (the layers below, the mirror layers, S3) to sig. sig then
 * holds what apply_sum gives, with the same bits. Between the two, eps and inc must not change and
 * op must not be applied otherwise (a borrowing displacement object may be); sig holds a part.
 * The direct backend and the displacement alone make it all in begin. */
void mc_eigen_spectral_begin_sum(mc_eigen_spectral *op, const double *const eps[6],
                                 const mc_eigen_sparse *inc, double G, double *const sig[6],
                                 double *uz);
void mc_eigen_spectral_end_sum(mc_eigen_spectral *op, const double *const eps[6],
                               const mc_eigen_sparse *inc, double G, double *const sig[6]);

/* Spectra of the caller's added before the up pass's inverse transforms (the folded loads,
 * theory §8.10: one inverse per layer and component for both): while a hook is set, the fft
 * object's up pass calls hook(ctx, l, spec) once per layer l, spec[c] its six half spectra
 * (py rows of px/2 + 1 complex values) already scaled, so that FFTW's unnormalised c2r gives the
 * stresses; hook adds its own (it returns 0, or non-zero to make the layer NaN). NULL: none.
 * mc_eigen_spectral_padded gives px, py of an fft stress object (0 for any other). */
typedef int (*mc_eigen_spectral_hook)(void *ctx, int layer, double *const spec[6]);
void mc_eigen_spectral_set_hook(mc_eigen_spectral *op, mc_eigen_spectral_hook hook, void *ctx);
int mc_eigen_spectral_padded(const mc_eigen_spectral *op, int *px, int *py);

/* The surface displacement alone (the displacement operator of eigen_op.h with the spectral
 * kernel): an object made by mc_eigen_spectral_create_uz streams the layers one at a time (the
 * fft backend holds one layer's spectra and the surface's: a few hundred bytes per surface cell),
 * the direct backend only the displacement tables. mc_eigen_spectral_apply_uz works on either
 * kind of object. */
int mc_eigen_spectral_create_uz(const mc_grid *g, const mc_eigen_volume *v, double nu,
                                mc_backend b, mc_eigen_spectral **out, mc_error *err);
void mc_eigen_spectral_apply_uz(mc_eigen_spectral *op, const double *const eps[6], double *uz);
void mc_eigen_spectral_apply_uz_sum(mc_eigen_spectral *op, const double *const eps[6],
                                    const mc_eigen_sparse *inc, double *uz);
size_t mc_eigen_spectral_estimate_uz(const mc_grid *g, const mc_eigen_volume *v, mc_backend b);

/* The displacement object uz_op (create_uz, fft) takes the workspaces of the stress object op
 * (fft, the same grid and volume) instead of its own: one layer's six spectra, the padded rows
 * and the surface's spectrum (at 256^2 x 32 free: 17 MB, 8 bytes per volume cell). The two must
 * then be applied one at a time, and op destroyed after uz_op. 1 when done; 0 (nothing changed)
 * for objects that do not fit. */
int mc_eigen_spectral_borrow(mc_eigen_spectral *uz_op, mc_eigen_spectral *op);

/* p3 (Pa, grid ny * nx) of the last mc_eigen_spectral_apply of the fft backend: the surface normal
 * traction of S1 + S2 that S3 cancels (as eigen_op.h mc_eigen_stress_p3); zeros before the first
 * apply and for the direct backend and the displacement alone. */
void mc_eigen_spectral_p3(const mc_eigen_spectral *op, double *p3);

size_t mc_eigen_spectral_bytes(const mc_eigen_spectral *op);

/* What mc_eigen_spectral_bytes would return for create(g, v, b), from the sizes alone; 0 for
 * what create refuses. */
size_t mc_eigen_spectral_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b);

void mc_eigen_spectral_destroy(mc_eigen_spectral **op); /* NULL-safe; sets *op = NULL */

#endif
