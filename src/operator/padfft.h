/* padfft.h - the zero-padded real 2-D FFT shared by the transform engine (conv.c) and the
 * symmetric stress engine (stress/stress_sym.c): planning, and the fill -> forward and
 * inverse -> crop halves of a DC-FFT convolution. The caller multiplies the spectra in between
 * (the products differ: complex, real, several terms, quadrant spectra).
 *
 * A field of nx x ny cells is zero-padded to tx x ty (tx >= nx, ty >= ny) and transformed by
 * FFTW r2c (row-major, x fastest; half spectrum of ty rows of hx = tx/2 + 1 complex values).
 * When ty > ny (a free y axis) the transforms are pruned of the all-zero padding rows: forward,
 * the ny data rows are transformed along x, the padding rows of the half spectrum zeroed and the
 * columns transformed in full; inverse, the columns in full and then only the ny output rows.
 * A quarter fewer butterflies than the 2-D pair, the same results to round-off (Liu, Wang & Liu
 * 2000 for the DC-FFT; dossier elastic §5.1).
 *
 * Plans follow the planner rigor in force (operator.h, [solver] plans; the default FFTW_ESTIMATE:
 * no trial runs, the same plan and the same numbers every time; the table-only 2-D pair of a
 * pruned engine is always FFTW_ESTIMATE), made on one thread below MC_THREADS_MIN_CELLS values. FFTW's planner is not thread-safe: create from
 * one thread. Execution never allocates; not reentrant per object (it owns rbuf and cbuf).
 */
#ifndef MC_PADFFT_H
#define MC_PADFFT_H

#include <fftw3.h>
#include <stddef.h>

#include "core/error.h"

typedef struct {
    int nx, ny;         /* field */
    int tx, ty;         /* transform; hx = tx/2 + 1 */
    int hx;
    int pruned;         /* ty > ny: row/column passes skip the padding rows */
    int rows;           /* rows of rbuf the forward transform reads: ny when pruned, else ty */
    double *rbuf;       /* real rows: ty x tx with the 2-D plans, else ny x tx (owned) */
    fftw_complex *cbuf; /* ty x hx half spectrum (owned) */
    fftw_plan r2c, c2r; /* 2-D plans rbuf <-> cbuf (only when asked for, or not pruned) */
    fftw_plan row_r2c, row_c2r, col_fwd, col_bwd; /* pruned passes (pruned only) */
} mc_padfft;

/* Plan for an nx x ny field padded to tx x ty. full = 1 also plans the 2-D pair on a ty x tx
 * rbuf (for whole kernel tables: mc_padfft_table); without pruning the 2-D pair is always
 * planned. Calls mc_fftw_prepare first. On failure *t is left destroyed (NULL-safe). MC_OK,
 * MC_ERR_NOMEM (an allocation failed or FFTW could not plan) or MC_ERR_INTERNAL (FFTW threads). */
int mc_padfft_create(mc_padfft *t, int nx, int ny, int tx, int ty, int full, mc_error *err);
void mc_padfft_destroy(mc_padfft *t); /* frees, zeroes *t; safe on a zeroed or half-made one */

/* Doubles of a half spectrum: 2 ty hx. */
size_t mc_padfft_spectrum_len(const mc_padfft *t);

/* The field (nx*ny), zero-padded, forward into spec: cbuf, or another array of
 * mc_padfft_spectrum_len doubles allocated like cbuf (mc_malloc: FFTW's alignment). */
void mc_padfft_forward(mc_padfft *t, const double *field, fftw_complex *spec);

/* cbuf backward (unnormalised: the caller scales) and its first ny rows and nx columns into
 * out (nx*ny). Destroys cbuf. */
void mc_padfft_inverse(mc_padfft *t, double *out);

/* A whole ty x tx table (kernel, wrap-around layout) forward into cbuf by the 2-D r2c (create
 * with full = 1 or on an unpruned transform). */
void mc_padfft_table(mc_padfft *t, const double *table);

#endif
