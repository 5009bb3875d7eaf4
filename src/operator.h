/* operator.h - a planned convolution of a grid field with an influence kernel: the dual
 * implementation at the heart of microcontact.
 *
 *     u[j][i] = sum_{j',i'} K(i - i', j - j') f[j'][i']      (offsets FIELD minus SOURCE)
 *
 * Two backends behind one interface (a table of {name, create, apply, destroy} rows):
 *   direct - plain O(N^2) summation over the kernel table, written for clarity: the reference;
 *   fft    - DC-FFT (Liu, Wang & Liu 2000): zero padding along free axes, cyclic along periodic
 *            axes, real transforms (FFTW r2c/c2r), kernel spectrum built once per plan.
 * Both read the SAME kernel table, so they agree to round-off (elastic.md 5).
 *
 * Three layers, lowest first:
 *   mc_kernel_table - the kernel sampled at cell offsets in wrap-around layout;
 *   mc_conv         - the transform engine of one grid and backend (shared by many kernels:
 *                     the stress stage convolves one load with six kernels per layer);
 *   mc_operator     - conv + one kernel: plan / apply / destroy, what a solver uses.
 */
#ifndef MC_OPERATOR_H
#define MC_OPERATOR_H

#include <stddef.h>

#include "error.h"
#include "grid.h"

typedef enum { MC_BACKEND_FFT = 0, MC_BACKEND_DIRECT = 1 } mc_backend;

const char *mc_backend_name(mc_backend b);            /* "fft" | "direct" */
int mc_backend_from_name(const char *name, mc_backend *out); /* MC_OK or MC_ERR_INPUT */

/* ---- kernel tables ----------------------------------------------------------------------- */

/* Kernel values at integer cell offsets, laid out for a cyclic convolution of length tx (ty):
 *  - free axis with n cells: length >= 2n - 1 (zero padding); entry t holds offset t for t < n,
 *    offset t - len for t > len - n, and 0 in between (never reached by an output cell);
 *  - periodic axis with n cells: length n; entry t holds the sum over all periodic images of
 *    offset t (t <= n/2) or t - n, i.e. the periodic Green's function (elastic.md 5.2).
 * Row-major with x fastest: k[ty_index * tx + tx_index]. */
typedef struct {
    mc_grid grid;  /* the grid the table was built for */
    int tx, ty;    /* table length along x and y */
    double *k;     /* ty * tx values (owned; free with mc_kernel_table_free) */
} mc_kernel_table;

/* Offset in cells of table entry t along an axis with n cells and table length len; sets *used = 0
 * for the padding slots of a free axis (then the offset is meaningless). */
int mc_table_offset(int t, int n, int len, int *used);

/* A scalar kernel for the generic table builder. */
typedef struct {
    /* K at offset (ox, oy), metres (field minus source), per unit load on one cell. */
    double (*value)(double ox, double oy, const void *ctx);
    /* Optional continuation of the image sum along periodic axes: returns the contribution of all
     * images with |image index| > images along each periodic axis (divergent constants dropped,
     * see the kernel's documentation). NULL: the image sum is truncated at `images`. */
    double (*tail)(double ox, double oy, const mc_grid *g, int images, const void *ctx);
    const void *ctx;
} mc_kernel_fn;

/* Fill a table of size tx x ty for grid g from kernel fn (images per periodic axis: |k| <= images).
 * Allocates out->k. Returns MC_OK, MC_ERR_INPUT (bad sizes) or MC_ERR_NOMEM. */
int mc_kernel_table_build(const mc_grid *g, int tx, int ty, const mc_kernel_fn *fn, int images,
                          mc_kernel_table *out, mc_error *err);
void mc_kernel_table_free(mc_kernel_table *t);

/* The normal-displacement kernel: Love's rectangle (kernel.h) divided by E* (m/Pa), with the
 * periodic image sums continued analytically (mean displacement of a fully periodic grid is 0;
 * along a single periodic axis the divergent constant is dropped: approach is defined up to a
 * constant there). tx, ty as from mc_conv_table_dims. */
int mc_kernel_table_love(const mc_grid *g, int tx, int ty, double Estar, mc_kernel_table *out,
                         mc_error *err);

/* ---- the transform engine ---------------------------------------------------------------- */

typedef struct mc_conv mc_conv;

/* Plan the transforms for grid g and backend b (FFTW_ESTIMATE plans: deterministic). */
int mc_conv_create(const mc_grid *g, mc_backend b, mc_conv **out, mc_error *err);
void mc_conv_destroy(mc_conv **c);

/* Table length this engine convolves with (padded FFT size, or n along periodic axes). */
void mc_conv_table_dims(const mc_conv *c, int *tx, int *ty);

/* Doubles needed for one transformed kernel or transformed load ("spectrum"). */
size_t mc_conv_spectrum_len(const mc_conv *c);

/* Transform a kernel table (built with mc_conv_table_dims sizes) into kspec
 * (mc_conv_spectrum_len doubles). fft: r2c, scaled by 1/(tx*ty); direct: a copy. */
int mc_conv_kernel(mc_conv *c, const mc_kernel_table *t, double *kspec, mc_error *err);

/* Transform a field (nx*ny) into lspec. fft: zero-pad + r2c; direct: a copy. Never allocates. */
void mc_conv_load(mc_conv *c, const double *field, double *lspec);

/* out (nx*ny) = sum over t < nterms of K_t (*) f_t, from transformed kernels and loads.
 * Never allocates. out may alias nothing given. */
void mc_conv_apply(mc_conv *c, int nterms, const double *const *kspec, const double *const *lspec,
                   double *out);

mc_backend mc_conv_backend(const mc_conv *c);
const mc_grid *mc_conv_grid(const mc_conv *c);

/* ---- the operator: conv + one kernel ----------------------------------------------------- */

typedef struct mc_operator mc_operator;

/* Plan u = K f for grid g and backend b; the table is transformed and kept (the caller may free
 * its table afterwards). */
int mc_operator_plan(const mc_grid *g, const mc_kernel_table *t, mc_backend b, mc_operator **out,
                     mc_error *err);

/* Convenience: the normal-displacement operator (Love kernel / E*) for grid g. */
int mc_operator_plan_love(const mc_grid *g, double Estar, mc_backend b, mc_operator **out,
                          mc_error *err);

/* out = K in (nx*ny each). Never allocates and cannot fail; in and out may be the same array.
 * Not reentrant: one thread at a time per operator (it owns its workspace). */
void mc_operator_apply(mc_operator *op, const double *in, double *out);

void mc_operator_destroy(mc_operator **op);

const mc_grid *mc_operator_grid(const mc_operator *op);
mc_backend mc_operator_backend(const mc_operator *op);

/* ---- threads ------------------------------------------------------------------------------ */

/* Threads for FFTW and OpenMP loops (0 or negative: all cores). Call before planning. */
void mc_set_threads(int n);
int mc_get_threads(void);

#endif
