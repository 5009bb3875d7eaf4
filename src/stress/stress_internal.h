/* stress_internal.h - what stress.c, stress_table.c and stress_sym.c share; not a public header.
 *
 * The symmetric engine (stress_sym.c) is the fast DC-FFT of a grid whose axes are both free: each
 * stress kernel is even or odd in each offset (mc_stress_parity), so its zero-padded wrap-around
 * table of length 2m (m >= n, the middle slot m and all slots n..2m-n zero) is the even or odd
 * extension of one quadrant of offsets 0..m, and the table's DFT is a real-to-real transform of
 * that quadrant (FFTW REDFT00 = DCT-I of length m + 1 along an even axis, RODFT00 = DST-I of
 * length m - 1 along an odd one):
 *   even axis:  K^(k) = R(k)          for k <= m, K^(2m - k) = R(k)
 *   odd axis:   K^(k) = -i S(k)       for k <= m, K^(2m - k) = +i S(k)   (S(0) = S(m) = 0)
 * with R, S the r2r outputs (FFTW's r2r are unnormalised: DCT-I and DST-I as defined are exactly
 * the DFT sums of the extended sequence, with the factor 2 of the paired terms). The 2-D spectrum
 * is the product of the two axes' factors, so it is real (ee), -i times real (oe, eo) or minus
 * real (oo). The products with the loads' half spectra read the quadrant spectrum directly; no
 * full kernel spectrum is ever stored.
 */
#ifndef MC_STRESS_INTERNAL_H
#define MC_STRESS_INTERNAL_H

#include <stddef.h>

#include "core/error.h"
#include "core/grid.h"
#include "stress/stress.h"

typedef struct mc_stress_sym mc_stress_sym;

/* Plan for grid g (both axes free): half periods mx, my (7-smooth, >= n and >= 2), FFTW plans
 * (ESTIMATE) for the pruned r2c of a load, the pruned c2r of a product, and the four r2r parity
 * combinations in place on a quadrant array. MC_OK, MC_ERR_INPUT, MC_ERR_NOMEM. */
int mc_stress_sym_create(const mc_grid *g, mc_stress_sym **out, mc_error *err);
void mc_stress_sym_destroy(mc_stress_sym **s);

/* Quadrant sizes qx = mx + 1, qy = my + 1 (row stride qx), doubles per quadrant array and per
 * load spectrum (both rounded up to whole cache lines: arrays carved one after the other from a
 * 64-byte aligned block keep the alignment FFTW's new-array execute requires). */
void mc_stress_sym_dims(const mc_stress_sym *s, int *qx, int *qy);
size_t mc_stress_sym_quad_len(const mc_stress_sym *s);
size_t mc_stress_sym_spec_len(const mc_stress_sym *s);

/* Quadrant table (in) -> quadrant spectrum (in place), of parity par (bit 0 odd in x, bit 1 odd
 * in y). Entries along an odd axis at index 0 and m must be 0 (they are: parity, and m >= n). */
void mc_stress_sym_kernel(mc_stress_sym *s, int par, double *quad);
/* mc_stress_sym_kernel on n quadrants, side by side on the run's threads where the plans are
 * one-thread ones (quadrants below MC_THREADS_MIN_CELLS values): the same bits */
void mc_stress_sym_kernels(mc_stress_sym *s, int n, const int *par, double *const *quad);

/* Load (nx*ny) -> its half spectrum (2my rows of mx + 1 complex values, mc_stress_sym_spec_len). */
void mc_stress_sym_load(mc_stress_sym *s, const double *field, double *lspec);

/* out (nx*ny) = sum over t of K_t (*) f_t from quadrant spectra kq[t] of parity par[t] and load
 * spectra ls[t]. Never allocates. */
/* spec (2my rows of mx + 1 complex values: the layout of the transform's half spectrum, whose
 * unnormalised c2r gives the field) += sum over t of K_t (*) f_t, as mc_stress_sym_apply makes it
 * before its inverse. Never allocates. */
void mc_stress_sym_product_add(const mc_stress_sym *s, int nterms, const double *const *kq,
                               const int *par, const double *const *ls, double *spec);
/* the transform's size: 2 mx x 2 my */
void mc_stress_sym_transform(const mc_stress_sym *s, int *tx, int *ty);
void mc_stress_sym_apply(mc_stress_sym *s, int nterms, const double *const *kq, const int *par,
                         const double *const *ls, double *out);

/* MC_OK for a depth z (m) the tables of kernel can be built at: finite, >= 0, and > 0 for the
 * point kernel (singular at the surface); else MC_ERR_INPUT with a message prefixed by what. */
int mc_stress_check_depth(mc_stress_kernel kernel, double z, const char *what, mc_error *err);

/* ---- the plan, layer by layer (for the stage) ------------------------------------------------ */

/* (mc_stress_prepare and mc_stress_compute are in stress.h) */
/* 1 when the prepared loads take the sparse sum over the loaded cells. */
int mc_stress_is_sparse(const mc_stress_plan *plan);

/* ---- the sparse sum over the loaded cells --------------------------------------------------- */

/* One term of a sparse sum: the load f (nx*ny) and the table of one component, either a quadrant
 * (q != NULL: entry (|di|, |dj|) at q[|dj| qx + |di|], odd axes of par flip the sign of negative
 * offsets) or a wrap-around table (w != NULL, tx x ty, operator.h layout). */
typedef struct {
    const double *f;
    const double *q;
    int qx, par;
    const double *w;
    int tx, ty;
} mc_stress_term;

/* out[j nx + i] = sum over terms and over the ncells loaded cells (indices into nx*ny) of
 * f[cell] K(i - i_cell, j - j_cell). OpenMP over output rows; the order of the sum does not
 * depend on the thread count. */
void mc_stress_sparse_sum(const mc_grid *g, int ncells, const int *cells, int nterms,
                          const mc_stress_term *terms, double *out);

#endif
