/* operator.h - a planned convolution of a grid field with an influence kernel: the dual
 * implementation at the heart of microcontact.
 *
 *     u[j][i] = sum_{j',i'} K(i - i', j - j') f[j'][i']      (offsets FIELD minus SOURCE)
 *
 * Two backends behind one interface (rows {name, create, kernel, load, apply, convolve, destroy} of
 * a table, chosen by name; callers never ask which one they have):
 *   direct - plain O(N^2) summation over the kernel table, written for clarity: the reference;
 *   fft    - DC-FFT (Liu, Wang & Liu 2000): zero padding along free axes, cyclic along periodic
 *            axes, real transforms (FFTW r2c/c2r), kernel spectrum built once per plan.
 * Both read the SAME kernel table, so they agree to round-off (theory.md §3).
 *
 * Three layers, lowest first:
 *   mc_kernel_table - the kernel sampled at cell offsets in wrap-around layout;
 *   mc_conv         - the transform engine of one grid and backend (shared by many kernels:
 *                     the stress stage convolves one load with six kernels per layer);
 *   mc_operator     - conv + one kernel: plan / apply / destroy, what a solver uses.
 * Helpers of this folder with headers of their own: padfft.h (the zero-padded real 2-D FFT,
 * pruned along a free y axis, of the fft backend and of the symmetric stress engine), box.h
 * (bounding boxes of cell sets plus a margin), precond.h (the contact solvers' preconditioner).
 */
#ifndef MC_OPERATOR_H
#define MC_OPERATOR_H

#include <stddef.h>

#include "core/error.h"
#include "core/grid.h"
#include "core/threads.h"

typedef enum { MC_BACKEND_FFT = 0, MC_BACKEND_DIRECT = 1 } mc_backend;

const char *mc_backend_name(mc_backend b);            /* "fft" | "direct" */
int mc_backend_from_name(const char *name, mc_backend *out); /* MC_OK or MC_ERR_INPUT */

/* ---- kernel tables ----------------------------------------------------------------------- */

/* Kernel values at integer cell offsets, laid out for a cyclic convolution of length tx (ty):
 *  - free axis with n cells: length >= 2n - 1 (zero padding); entry t holds offset t for t < n,
 *    offset t - len for t > len - n, and 0 in between (never reached by an output cell);
 *  - periodic axis with n cells: length n; entry t holds the sum over all periodic images of
 *    offset t (t <= n/2) or t - n, i.e. the periodic Green's function (theory.md §3.2).
 * Row-major with x fastest: k[ty_index * tx + tx_index]. */
typedef struct {
    mc_grid grid;  /* the grid the table was built for */
    int tx, ty;    /* table length along x and y */
    double *k;     /* ty * tx values (owned; free with mc_kernel_table_free) */
} mc_kernel_table;

/* Offset in cells of table entry t (0 <= t < len) along an axis with n cells and table length len
 * (len == n: periodic axis, nearest image, +n/2 for even n; len >= 2n - 1: free axis). Sets
 * *used (if not NULL) to 0 for the padding slots of a free axis (then the offset is meaningless),
 * else to 1. */
int mc_table_offset(int t, int n, int len, int *used);

/* MC_OK if g is a valid grid (mc_grid_check) and tx x ty a table size for it as above (periodic
 * axis: n, free axis: >= 2n - 1); else MC_ERR_INPUT. */
int mc_kernel_table_check(const mc_grid *g, int tx, int ty, mc_error *err);

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

/* Fill a table of size tx x ty for grid g from kernel fn: each used entry is
 * sum over |k| <= images (periodic axes only, each independently) of fn->value at the offset plus
 * k periods, plus fn->tail at the offset when fn->tail is set and an axis is periodic; padding
 * slots are 0. Plain and slow (O(table * images^2) kernel calls, OpenMP over rows): for kernels
 * without a fast builder and as a reference. tx, ty as in mc_kernel_table; images >= 0.
 * Allocates out->k (NULL on failure). Returns MC_OK, MC_ERR_INPUT (bad grid, sizes, fn or images)
 * or MC_ERR_NOMEM. */
int mc_kernel_table_build(const mc_grid *g, int tx, int ty, const mc_kernel_fn *fn, int images,
                          mc_kernel_table *out, mc_error *err);
void mc_kernel_table_free(mc_kernel_table *t); /* frees t->k and sets it NULL; NULL-safe */

/* The normal-displacement kernel K = mc_love_uz / E* (m/Pa: displacement per unit pressure on one
 * cell), tx, ty as from mc_conv_table_dims, E* > 0 in Pa. Free axes hold Love's rectangle itself
 * (evaluated on the corner lattice, theory.md §5.5). Periodic axes hold the periodic Green's
 * function of the pixel load, whose plain image sum diverges like the 1/r kernel (theory.md §3.2):
 *  - both axes periodic: Ewald summation, no image truncation (the table changes by < 5e-15 of its
 *    largest entry when the splitting parameter changes; it is the limit of mc_kernel_fn_love's
 *    image sum). The mean of the table is removed (K^(0) = 0): the mean displacement of a fully
 *    periodic problem is undefined, the rigid approach absorbs it.
 *  - one periodic axis (period L = n d): the image sum over |k| <= MC_LOVE_IMAGES periods plus the
 *    tail of mc_kernel_fn_love (truncation < 2e-11, see MC_LOVE_IMAGES). The divergent constant
 *    of the 1/r image sum is dropped, so the table is defined up to a constant, which the approach
 *    absorbs. The convention chosen: summed over one period along the periodic axis the table is
 *    the plane-strain strip kernel -(2/(pi E*)) [(x+a) ln|x+a| - (x-a) ln|x-a| - 2a] (x the free
 *    offset in m, a the free half-width; ln of metres, so the constant depends on the unit of
 *    length), and each entry tends to 1/n of it far along the free axis.
 * Allocates out->k. Returns MC_OK, MC_ERR_INPUT (bad sizes or E*), MC_ERR_NOMEM. */
int mc_kernel_table_love(const mc_grid *g, int tx, int ty, double Estar, mc_kernel_table *out,
                         mc_error *err);

/* Rows j0 .. j0 + nj - 1 of mc_kernel_table_love's table into rows (nj * tx values, row j0 + r
 * at r * tx): the same values, for a rank that transforms only its rows of the table
 * (operator/dfft.h). Free axes: only the corner lattice's rows those table rows read are
 * evaluated; a periodic axis: the whole table is built and its rows kept. MC_OK, MC_ERR_INPUT,
 * MC_ERR_NOMEM, MC_ERR_INTERNAL (rows outside the table). */
int mc_kernel_table_love_rows(const mc_grid *g, int tx, int ty, double Estar, int j0, int nj,
                              double *rows, mc_error *err);

/* Images per side along a single periodic axis used by mc_kernel_table_love. The truncation error
 * of the image sum with the continued tail falls like M^-6; measured against M = 512, relative to
 * max |K - mean K| (unit-independent, unlike the largest entry: the constant is arbitrary), over
 * n = 2..64 and dx/dy = 0.2..5: <= 6.3e-11 at M = 16, <= 1.7e-11 at M = 20. Exact for n = 1 (the
 * cells tile the strip). */
#define MC_LOVE_IMAGES 20

/* Context of mc_kernel_fn_love: rectangle half-sides a = dx/2, b = dy/2 (m) and E* (Pa). */
typedef struct {
    double a, b, Estar;
} mc_kernel_love_ctx;

/* The Love kernel as a generic mc_kernel_fn for grid g (fills *ctx, and *fn pointing to it):
 * value = mc_love_uz(ox, oy, a, b) / E*, and the tail of the image sum beyond M periods, from
 * sum_{|k|>M} f(kL) ~ (1/L) int_{|s|>H} (1 + beta2 d^2/ds^2 + beta4 d^4/ds^4) f, H = (M+1/2) L
 * (midpoint Euler-Maclaurin, with the pixel's own extent folded in), applied to the point kernel
 * c/r, c = dx dy/(pi E*), divergent constants dropped:
 *  - one periodic axis (y; x likewise with the axes exchanged), u+- = H +- y:
 *      tail = (c/L) <J0 + beta2 J2 + beta4 J4>_x,   J0 = -sum+- ln(u + sqrt(u^2 + x^2)),
 *      J2 = sum+- u/rho^3, J4 = -sum+- 3u(3x^2 - 2u^2)/rho^7, rho = sqrt(u^2 + x^2),
 *      <>_x the exact average over the pixel width |x' - x| <= a, beta2 = (1 - n^2) dy^2/24,
 *      beta4 = [(1 - n^4)/120 + n^2 (n^2 - 1)/36] b^4 (both 0 for n = 1); error ~ M^-6;
 *  - both axes periodic, box half-sides Hx = (M+1/2) Lx, Hy = (M+1/2) Ly:
 *      tail = -(c/(Lx Ly)) [pi mc_love_uz(x, y, Hx, Hy) - bx Ixx - by Iyy],
 *      Ixx = S_H[Y/(X sqrt(X^2+Y^2))], Iyy = S_H[X/(Y sqrt(X^2+Y^2))] (the corner sum with the box
 *      half-sides), bx = (1 - nx^2) dx^2/24, by likewise; error ~ M^-5; the table is not
 *      mean-free (mc_kernel_table_love's Ewald table is, and is this sum's M -> inf limit).
 * The slow, plain reference of mc_kernel_table_love (mc_kernel_table_build with it). */
void mc_kernel_fn_love(const mc_grid *g, double Estar, mc_kernel_love_ctx *ctx, mc_kernel_fn *fn);

/* ---- the transform engine ---------------------------------------------------------------- */

typedef struct mc_conv mc_conv;

/* Plan the transforms for grid g and backend b. fft: FFTW_ESTIMATE plans (deterministic) on
 * buffers the engine owns; table length along a free axis = the smallest 7-smooth m >= 2n - 1.
 * *out is NULL on failure. Returns MC_OK, MC_ERR_INPUT (bad grid or backend), MC_ERR_NOMEM (an
 * allocation failed or FFTW could not plan) or MC_ERR_INTERNAL (FFTW threads). */
int mc_conv_create(const mc_grid *g, mc_backend b, mc_conv **out, mc_error *err);
void mc_conv_destroy(mc_conv **c); /* frees and sets *c = NULL; NULL-safe */

/* mc_conv_create, but under a run communicator (core/dist.h, an MPI build) the fft backend
 * distributes its transforms over the ranks (dfft.h): spectra are then this rank's slab of
 * columns (mc_conv_spectrum_len is its length), and mc_conv_kernel, _load, _apply, _convolve and
 * _kernel_real are collective (every rank calls them, with the same field; every rank gets the
 * whole output). Without a communicator, and for the direct backend, it is mc_conv_create. */
int mc_conv_create_distributed(const mc_grid *g, mc_backend b, mc_conv **out, mc_error *err);

/* Table length this engine convolves with (padded FFT size, or n along periodic axes). */
void mc_conv_table_dims(const mc_conv *c, int *tx, int *ty);

/* Doubles needed for one transformed kernel or transformed load ("spectrum"). */
size_t mc_conv_spectrum_len(const mc_conv *c);

/* Transform a kernel table (built with mc_conv_table_dims sizes) into kspec
 * (mc_conv_spectrum_len doubles, caller-owned). fft: r2c, scaled by 1/(tx*ty); direct: a copy.
 * Never allocates. MC_OK, or MC_ERR_INPUT when the table's grid or sizes do not match. */
int mc_conv_kernel(mc_conv *c, const mc_kernel_table *t, double *kspec, mc_error *err);

/* Transform a field (nx*ny) into lspec (mc_conv_spectrum_len doubles, caller-owned; may not
 * alias field). fft: zero-pad + r2c; direct: a copy. Never allocates; not reentrant per engine. */
void mc_conv_load(mc_conv *c, const double *field, double *lspec);

/* out (nx*ny) = sum over t < nterms of K_t (*) f_t, from transformed kernels and loads
 * (nterms >= 1). Never allocates; not reentrant per engine; out may alias none of the inputs. */
void mc_conv_apply(mc_conv *c, int nterms, const double *const *kspec, const double *const *lspec,
                   double *out);

/* out (nx*ny) = K (*) field for one transformed kernel: mc_conv_load + mc_conv_apply fused, without
 * the intermediate spectrum (the operator's hot path). work: mc_conv_spectrum_len doubles of
 * caller-owned scratch; field may be out. Never allocates; not reentrant per engine. */
void mc_conv_convolve(mc_conv *c, const double *kspec, const double *field, double *out,
                      double *work);

/* Scratch doubles mc_conv_convolve needs in work (0 for fft; the field for direct). */
size_t mc_conv_work_len(const mc_conv *c);

/* Kernels even in both offsets (the Love kernel) have a real spectrum. fft backend: transform
 * the table and, if the spectrum is real to round-off (|Im| <= 1e-13 max|Re|), store its real
 * parts in kre (mc_conv_spectrum_len / 2 doubles: half the memory) and return 1; otherwise (and
 * always for direct) return 0 and leave kre untouched. kre goes to mc_conv_convolve_real. */
int mc_conv_kernel_real(mc_conv *c, const mc_kernel_table *t, double *kre);

/* mc_conv_convolve with a compacted real spectrum (fft backend). Never allocates. */
void mc_conv_convolve_real(mc_conv *c, const double *kre, const double *field, double *out);

mc_backend mc_conv_backend(const mc_conv *c);
const mc_grid *mc_conv_grid(const mc_conv *c);

/* The rows of the field this process computes: r0 .. r0 + nr - 1 (of ny). All rows serially,
 * on the direct backend and on a serial engine; this rank's slab when the fft backend is
 * distributed (dfft.h; nr may be 0 on a rank left without rows). */
int mc_conv_rows(const mc_conv *c, int *r0, int *nr); /* 1: split over the ranks */

/* mc_conv_convolve (kre == NULL) or mc_conv_convolve_real (kre given), but on a distributed
 * engine field and out are this process's rows only (mc_conv_rows: nr*nx values, row r0 + r at
 * r*nx; no gather); serially (and on the direct backend) the same as the full call on whole
 * arrays. Collective. */
void mc_conv_convolve_rows(mc_conv *c, const double *kspec, const double *kre,
                           const double *field, double *out, double *work);

/* A distributed fft engine (mc_conv_rows) tabulates its kernel by slabs: the rows j0 .. j0 +
 * nj - 1 of the tx x ty table this rank builds (dfft.h, mc_dfft_table_split); returns 1, or 0
 * (j0 = 0, nj = ty: the whole table, mc_conv_kernel) on any other engine. */
int mc_conv_table_rows(const mc_conv *c, int *j0, int *nj);

/* The kernel spectrum from those rows (rows: nj rows at a stride of 2 (tx/2 + 1) doubles,
 * overwritten): the same bits as mc_conv_kernel_real, or when the spectrum is not real (*real =
 * 0) mc_conv_kernel, into kspec (mc_conv_spectrum_len doubles; *real = 1: its first half holds
 * the real parts). MC_OK, MC_ERR_NOMEM or MC_ERR_INTERNAL (not a distributed fft engine), alike
 * on every rank. Collective. */
int mc_conv_kernel_rows(mc_conv *c, double *rows, double *kspec, int *real, mc_error *err);

/* ---- planner rigor and stored wisdom ----------------------------------------------------- */

/* How the repeated transforms are planned ([solver] plans): the transform engine's field
 * transforms (padfft.h, also the stress engine's), the preconditioner's, the stress engine's
 * quadrant r2r, the eigenstrain operators' pruned and depth transforms. One-shot transforms
 * (a kernel table's spectrum, table set-up, surfaces) always use FFTW_ESTIMATE.
 *   estimate - FFTW_ESTIMATE: no trial runs; the same plan, hence the same round-off, on every
 *              run (the default: the regression baselines need it);
 *   measure  - FFTW_MEASURE: FFTW times candidate algorithms while planning (up to seconds for
 *              large sizes) and keeps the fastest; the plan, and the last bits of the results,
 *              may differ from run to run;
 *   wisdom   - measure, but first import the plans stored in a wisdom file and at the end store
 *              them there: a size planned once is planned at once on later runs. */
typedef enum { MC_PLANS_ESTIMATE = 0, MC_PLANS_MEASURE = 1, MC_PLANS_WISDOM = 2 } mc_plan_rigor;

typedef struct {
    mc_plan_rigor previous;
    int active;      /* 1: this scope measured or imported (its end forgets the wisdom) */
    char file[4096]; /* wisdom file of this scope ("" = none) */
} mc_fft_plans_scope;

/* Use rigor r for the plans made until the matching mc_fft_plans_end (scopes nest, like
 * mc_threads_begin; call from one thread, before planning). With MC_PLANS_WISDOM, wisdom_file
 * (required) is imported if it exists; a file that exists but is not FFTW wisdom is
 * MC_ERR_INPUT (the message names the file; nothing is changed). MC_OK, MC_ERR_INPUT or
 * MC_ERR_INTERNAL (FFTW threads). */
int mc_fft_plans_begin(mc_plan_rigor r, const char *wisdom_file, mc_fft_plans_scope *scope,
                       mc_error *err);

/* End the scope: with MC_PLANS_WISDOM write the accumulated wisdom to the file (atomically: a
 * temporary file beside it renamed over it); then, if the scope measured, forget all wisdom, so
 * that later estimate plans of the process are the deterministic ones again (FFTW's estimate
 * planner would otherwise reuse measured plans). Restores the previous rigor. MC_OK, or
 * MC_ERR_ENV when the file cannot be written (the results stand). */
int mc_fft_plans_end(const mc_fft_plans_scope *scope, mc_error *err);

/* FFTW planner flags for a repeated transform under the rigor in force: FFTW_ESTIMATE or
 * FFTW_MEASURE (which overwrites the planning arrays: plan on scratch only). */
unsigned mc_fft_plan_flags(void);
mc_plan_rigor mc_fft_plan_rigor(void);
const char *mc_plan_rigor_name(mc_plan_rigor r); /* "estimate" | "measure" | "wisdom" */

/* ---- the operator: conv + one kernel ----------------------------------------------------- */

typedef struct mc_operator mc_operator;

/* Plan u = K f for grid g and backend b; the table (sized by mc_conv_table_dims for g) is
 * transformed and kept, so the caller may free it afterwards. *out is NULL on failure.
 * Under a run communicator (core/dist.h) the fft backend is distributed
 * (mc_conv_create_distributed): plan and apply are then collective, every rank passes the whole
 * field and gets the whole result, and the answer has the same bits on any number of ranks.
 * Returns as mc_conv_create and mc_conv_kernel. */
int mc_operator_plan(const mc_grid *g, const mc_kernel_table *t, mc_backend b, mc_operator **out,
                     mc_error *err);

/* Convenience: the normal-displacement operator u_z = K p for grid g (K from mc_kernel_table_love,
 * E* in Pa; p in Pa, u_z in m, positive into the bodies). Returns as mc_operator_plan and
 * mc_kernel_table_love. */
int mc_operator_plan_love(const mc_grid *g, double Estar, mc_backend b, mc_operator **out,
                          mc_error *err);

/* out = K in (nx*ny each). Never allocates and cannot fail; in and out may be the same array.
 * Not reentrant: one thread at a time per operator (it owns its workspace). */
void mc_operator_apply(mc_operator *op, const double *in, double *out);

void mc_operator_destroy(mc_operator **op); /* frees and sets *op = NULL; NULL-safe */

const mc_grid *mc_operator_grid(const mc_operator *op);

/* The rows of a field this process owns under mc_operator_apply_rows: r0 .. r0 + nr - 1 (of ny;
 * all of them unless the operator is distributed). Returns 1 when the operator is distributed
 * (its rows split over the run's ranks), else 0. */
int mc_operator_rows(const mc_operator *op, int *r0, int *nr);

/* out = K in on this process's rows only: in and out hold those rows alone (nr*nx values, row
 * r0 + r at r*nx, mc_operator_rows) when the operator is distributed, and no whole field is
 * formed anywhere; serially (not distributed) they are whole and this is mc_operator_apply. For
 * a solver that keeps its per-cell work and memory to its own rows (contact/). Collective. */
void mc_operator_apply_rows(mc_operator *op, const double *in, double *out);
mc_backend mc_operator_backend(const mc_operator *op);

#endif
