/* eigen_internal.h - what the eigenstrain operators (eigen_disp_op.c, eigen_stress_op.c,
 * eigen_stress_fft.c) share; not a public header.
 *
 * Kernel tables. Every kernel here is even or odd in each lateral offset (field minus source), so
 * a table is stored as one QUADRANT of offsets: q[dj * qx + di] holds the kernel at offset
 * (di, dj) cells, 0 <= di < qx, 0 <= dj < qy; the kernel at (-di, dj) is (-1)^(odd in x) times it,
 * likewise in y. Offsets beyond those used (>= the used extent) are 0, and along an odd axis the
 * entry at offset 0 is exactly 0 (the kernel's value there by symmetry).
 *
 * Quadrant spectra (fft backend). A table of half period m along an axis (cyclic length 2m,
 * m >= the used extent, so slots m .. 2m - m_used are never reached by an output cell) is the
 * even or odd extension of its quadrant, and its DFT is a real-to-real transform of the quadrant
 * (FFTW REDFT00 = DCT-I of length m + 1 on an even axis, RODFT00 = DST-I of length m - 1 on an
 * odd one, both unnormalised, i.e. exactly the DFT sums of the extended sequence):
 *   even axis: K^(k) = R(k), K^(2m - k) = R(k);   odd axis: K^(k) = -i R(k), K^(2m - k) = +i R(k).
 * So the 2-D spectrum of a kernel of parity (ox, oy) at frequency (kx, ky) of a half spectrum
 * (kx <= mx) is (-i)^(ox + oy) s R(kx, ky'), ky' = min(ky, 2my - ky), s = (-1)^oy when ky > my.
 * For a stress kernel (row i, eigenstrain column c) the parity along an axis is odd(i) XOR odd(c)
 * and (-i)^(a XOR b) = (-i)^a (-i)^b (-1)^(a b): the factors (-i)^a s_a of the row and of the
 * column are applied to the output and to the input spectra, the sign (-1)^(a b) is folded into
 * the stored table, leaving a real matrix per frequency.
 */
#ifndef MC_EIGEN_INTERNAL_H
#define MC_EIGEN_INTERNAL_H

#include <fftw3.h>
#include <stddef.h>

#include "core/error.h"
#include "core/grid.h"
#include "plastic/eigen_op.h"

/* ---- components ------------------------------------------------------------------------------ */

/* Oddness of a component (stress row or eigenstrain column, xx..xz) under x -> -x, y -> -y,
 * z -> -z: the parity of the number of x (y, z) indices: xy and xz are odd in x, xy and yz in y,
 * yz and xz in z. */
static inline int mc_eig_odd_x(int c) { return c == 3 || c == 5; }
static inline int mc_eig_odd_y(int c) { return c == 3 || c == 4; }
static inline int mc_eig_odd_z(int c) { return c == 4 || c == 5; }
/* Lateral parity bits of a component: bit 0 odd in x, bit 1 odd in y. */
static inline int mc_eig_par(int c) { return mc_eig_odd_x(c) | mc_eig_odd_y(c) << 1; }
/* Weight of a component in sigma : eps (shear entries occur twice). */
static inline double mc_eig_weight(int c) { return c < 3 ? 1.0 : 2.0; }

/* The 21 stored (row, column) pairs of the symmetric 6 x 6 stress kernel: i <= c, by rows. */
#define MC_EIG_NSYM 21
static inline int mc_eig_sym(int i, int c)
{
    if (i > c) {
        const int t = i;
        i = c;
        c = t;
    }
    return i * 6 - i * (i - 1) / 2 + (c - i);
}
/* Kernel (row i, column c) = mc_eig_sym_factor(i, c) * stored (min, max): the major symmetry of
 * the Eshelby-Chiu kernel with the shear columns carrying both tensor entries,
 * S[c][i] = (w_i / w_c) S[i][c]. */
static inline double mc_eig_sym_factor(int i, int c)
{
    return i <= c ? 1.0 : mc_eig_weight(c) / mc_eig_weight(i);
}

/* The grid is a line contact (periodic along y with ny = 1): every source cell is a bar
 * infinitely long along y and the tables hold the bar kernels of kernels/eigen.h (plane strain;
 * eigen_op.h). */
static inline int mc_eig_line(const mc_grid *g) { return g->periodic_y && g->ny == 1; }

/* Periodic axes with images (docs/theory.md §8.6): a periodic x axis, and a periodic y axis of more
 * than one row (the line grid's one row is a bar instead). Along such an axis the window is the
 * whole period, the tables hold the periodic kernel (the sum over the images) at the offsets
 * 0 .. n/2, and the fft backends transform over the period itself, unpadded. */
static inline int mc_eig_per_x(const mc_grid *g) { return g->periodic_x; }
static inline int mc_eig_per_y(const mc_grid *g) { return g->periodic_y && g->ny > 1; }
static inline int mc_eig_periodic(const mc_grid *g) { return mc_eig_per_x(g) || mc_eig_per_y(g); }

/* Offset d (field minus source, |d| < n) along an axis of n cells, wrapped into -n/2 .. n/2 when
 * the axis is periodic (the periodic table holds offsets 0 .. n/2 by parity). */
static inline int mc_eig_wrap(int d, int n, int periodic)
{
    if (!periodic)
        return d;
    d %= n;
    if (d > n / 2)
        d -= n;
    else if (d < -(n / 2))
        d += n;
    return d;
}

/* ---- validation ------------------------------------------------------------------------------ */

/* MC_OK, or MC_ERR_INPUT (bad grid, volume, nu; a volume not spanning a periodic axis) /
 * MC_ERR_LIMIT (x periodic alone, more cells or transform sizes than int) with a message naming
 * what (prefix `who`). */
int mc_eig_check(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                 const char *who, mc_error *err);

/* Threads the apply loops may use (set at create: workspaces are per thread): the run's count,
 * or one when an application moves fewer than MC_THREADS_MIN_CELLS values (work: the values its
 * transforms touch, e.g. 6 nz times the padded lateral size), where a thread team costs more than
 * it saves (and, on a machine busy with other work, far more: a 16^2 x 13 elastic-plastic sphere
 * took 20 s on one thread and 150 s on two, measured). */
int mc_eig_threads(size_t work);

/* ---- quadrant tables ------------------------------------------------------------------------- */

/* A kernel with ncomp components at the lateral offset (di, dj) cells (di, dj >= 0): out[ncomp]. */
typedef void (*mc_eig_kfn)(int di, int dj, const void *ctx, double *out);

/* Fill q[n] (n < ncomp, each qy * qx, row stride qx): entry (di, dj) = fn's component n for
 * di < ux, dj < uy, 0 elsewhere; 0 at di = 0 (dj = 0) when par[n] is odd in x (y). OpenMP over
 * rows. ux <= qx, uy <= qy. */
void mc_eig_fill(int qx, int qy, int ux, int uy, int ncomp, const int *par, mc_eig_kfn fn,
                 const void *ctx, double *const *q);

/* The periodic kernel on a grid with periodic axes (mc_eig_per_x / _y; theory.md §8.6): like
 * mc_eig_fill, but entry (di, dj) is the sum of fn over the images of the offset along the
 * periodic axes (period nx or ny cells) out to the reach of a box of 2 M + 1 periods, plus the
 * rest of the infinite sum as the kernel smeared over the period: (limit - box sum) / cells of a
 * period, where limit(di, dj) is the sum of fn over EVERY position along the periodic axes (the
 * bar kernel when y alone is periodic, the layer kernel when both are; the box sum runs over the
 * same cells as the images, so the period's sum of the table is exactly the limit). Components
 * odd along a periodic axis have no smeared part (their limit is 0) and exact zeros at the
 * offsets 0 and n/2 of that axis. images[a] = M along axis a (0 on a free axis). OpenMP over
 * rows. */
void mc_eig_fill_images(int qx, int qy, int ux, int uy, int ncomp, const int *par, mc_eig_kfn fn,
                        mc_eig_kfn limit, const void *ctx, const int period[2],
                        const int images[2], double *const *q);

/* Images per side M of a periodic axis of n cells: the box of 2 M + 1 periods reaches at least
 * MC_EIG_IMAGE_REACH cells on each side (theory.md §8.6: the smeared rest then errs by ~1e-9 of the
 * near field). */
#define MC_EIG_IMAGE_REACH 48
int mc_eig_images(int n);

/* In-place real-to-real transforms of quadrants of half periods mx, my (>= 2); or, built by
 * mc_eig_quad_create_full, the same quadrant spectra R of a table of any transform size tx x ty
 * (a periodic axis of odd length included) through one full real 2-D FFT of the table unfolded
 * by parity, R = i^(ox + oy) K^ (the imaginary part is round-off and dropped). */
typedef struct {
    int mx, my, qx, qy;
    fftw_plan plan[4]; /* by parity (bit 0 odd in x, bit 1 odd in y) */
    int full;          /* 1: the full-FFT path below */
    void *fw;          /* full path: the transform and one workspace per thread */
} mc_eig_quad;

int mc_eig_quad_create(mc_eig_quad *t, int mx, int my, mc_error *err);
int mc_eig_quad_create_full(mc_eig_quad *t, int tx, int ty, int qx, int qy, mc_error *err);
/* quad (qy * qx) -> R of the header comment, in place. */
void mc_eig_quad_transform(const mc_eig_quad *t, int par, double *quad);
void mc_eig_quad_destroy(mc_eig_quad *t); /* NULL-safe on a zeroed struct */
/* the full path's parts (eigen_periodic.c), called by the two above */
void mc_eig_quad_full_transform(const mc_eig_quad *t, int par, double *quad);
void mc_eig_quad_full_destroy(mc_eig_quad *t);

/* ---- the zero-padded real 2-D FFT, pruned of all-zero rows ----------------------------------- */

/* Transform size tx x ty (half spectrum ty rows of hx = tx/2 + 1 complex values). Forward: the
 * data occupy rows row0 .. row0 + nin - 1 (the rest is zero and not transformed along x);
 * inverse: rows 0 .. nout - 1 are produced. Spectra passed to execute must be allocated with
 * mc_malloc and hold speclen complex values (a multiple of 4, so that arrays carved one after the
 * other keep FFTW's alignment); real row buffers likewise, rows * tx doubles. Plans are
 * single-threaded (callers run many transforms in parallel) and never allocate. */
typedef struct {
    int tx, ty, hx, row0, nin, nout;
    size_t speclen;
    fftw_plan row_r2c, col_fwd, col_bwd, row_c2r;
} mc_eig_fft;

int mc_eig_fft_create(mc_eig_fft *t, int tx, int ty, int row0, int nin, int nout, mc_error *err);
/* rows (nin x tx, the data with zero padding to tx) -> spec; rows are not changed. */
void mc_eig_fft_forward(const mc_eig_fft *t, double *rows, fftw_complex *spec);
/* spec -> rows (nout x tx); destroys spec. */
void mc_eig_fft_inverse(const mc_eig_fft *t, fftw_complex *spec, double *rows);
void mc_eig_fft_destroy(mc_eig_fft *t); /* NULL-safe on a zeroed struct */

/* rows (nrows x tx) = field (nrows x nx, row stride nx) at column col0, zeros elsewhere. */
void mc_eig_fill_rows(double *rows, int tx, const double *field, int nx, int nrows, int col0);

/* Multiply z by (-i)^n (n = 0..3). */
static inline void mc_eig_rot(double *re, double *im, int n)
{
    const double r = *re, i = *im;
    switch (n & 3) {
    case 1: *re = i; *im = -r; break;
    case 2: *re = -r; *im = -i; break;
    case 3: *re = -i; *im = r; break;
    default: break;
    }
}

/* ---- the stress operator (eigen_stress_op.c: object, tables, direct; eigen_stress_fft.c) ----- */

struct mc_eigen_stress {
    mc_grid g;
    mc_eigen_volume v;
    double nu;
    int nzf;           /* fine layers (= v.nz when uniform; eigen_op.h, graded layers) */
    int *group;        /* the object's copy of v.group (NULL: uniform) */
    int *first;        /* nz + 1: first fine layer of each layer, nzf at nz */
    int *centre;       /* nz (inside first's block): the fine layer of each layer's centre */
    int depth;         /* fft depth step: MC_EIG_DEPTH_AUTO / _FINE / _COARSE (eigen_stress_fft.c) */
    int replicated;    /* 1: never distributed (mc_eig_stress_create_replicated) */
    const struct mc_eig_stress_ops *ops; /* the backend's row (eigen_stress_op.c) */
    int qx, qy;        /* quadrant of the tables (direct: the window; fft: half periods + 1) */
    size_t qlen;       /* doubles per quadrant (rounded up to a cache line) */
    double *love;      /* nz x 6 quadrants [k * 6 + i]: Love's stresses at layer k's centre per
                        * unit pressure on one cell (mc_rect_stress_p), or their spectra (fft) */
    double *s1;        /* direct: 2 nzf x 21 quadrants [m * 21 + sym(i, c)], the infinite-space
                        * kernel at depth offset m dz (fine lattice) */
    double *p3k;       /* direct: nz x 6 quadrants [k * 6 + c], sigma_zz^(1+2)(z = 0) / 2G of
                        * source layer k (mc_eigen_surface_szz12) */
    int nloads;        /* surface loads folded into the apply (mc_eigen_stress_loads): 0..2 */
    int load_id[2];    /* MC_TRACTION_P or MC_TRACTION_QX (stress/stress.h) of each */
    int load_par[2][6];/* their kernels' lateral parities per component (mc_stress_parity) */
    double *lk;        /* nloads x nz x 6 quadrants [(l nz + k) 6 + c]: the stress at layer k's
                        * centre per unit load on one cell, the stress module's patch tables
                        * (centre values, images on periodic axes), or their spectra (fft, this
                        * rank's columns in Love's layout) */
    const double *const *fwd; /* eps of mc_eigen_stress_forward (its layer spectra in E, fft),
                        * consumed by mc_eigen_stress_apply_forwarded; NULL otherwise */
    const double *fwd_eps[6];
    double *p3;        /* window: p3 of the last apply, Pa */
    double *work;      /* window p3 / 2G */
    void *fft;         /* fft: spectra, transforms and workspaces (eigen_stress_fft.c) */
    int keep_rows;     /* distributed fft: 1 = the stresses are written on this rank's rows only,
                        * not gathered (mc_eigen_stress_keep_rows) */
    size_t part[MC_EIGEN_STRESS_PARTS]; /* bytes held, by part (mc_eigen_stress_parts) */
    struct mc_eigen_spectral *spec; /* the spectral kernel (v.kernel; eigen_spectral_op.h): the
                        * whole operator, nothing above is made but p3 */
    struct mc_stress_plan *lplan; /* spectral with loads: the stress module's plan of the Love
                        * stresses at the layer centres, computed layer by layer into lay6 and
                        * added to the residual stress (no kernel spectra kept on free axes) */
    double *lay6;      /* 6 x grid cells */
};

/* The corner lattice of the s1 and p3 tables (theory.md §8.2, eigen.h mc_eigen_corner_h): on a
 * grid with both axes free and cuboids (not bars), a table entry's corner sum is read from planes
 * of corner functions at the lattice points (I dx - hx, J dy - hy), I <= ux, J <= uy, one plane
 * per depth of a corner, instead of 8 corner evaluations per entry; the planes of the corners
 * consecutive depth offsets share are kept (two at a time). The entries averaged over the
 * observation cell (MC_EIG_CELL_AVERAGE near the source) are evaluated as before. Fill the
 * tables of one kind in order of m (or k) with one object to reuse the planes. With h[0] == NULL
 * (other grids, or mc_eig_corners_init not called: a zeroed struct) every entry is evaluated on
 * its own (the reference the tests compare with). */
typedef struct {
    int n1x, n1y;  /* lattice points per plane: ux + 1, uy + 1 */
    double *h[2];  /* two planes of n1x n1y MC_EIGEN_NH corner functions */
    long key[2];   /* which depth each holds (LONG_MIN: none) */
} mc_eig_corners;
int mc_eig_corners_init(const mc_eigen_stress *op, mc_eig_corners *cc, mc_error *err);
void mc_eig_corners_free(mc_eig_corners *cc);
size_t mc_eig_corners_bytes(const mc_eigen_stress *op);

/* Lateral parity bits of the kernel pair (row i, column c): odd(i) XOR odd(c) per axis. */
int mc_eig_pair_par(int i, int c);

/* Quadrants (op->qx x op->qy, stride qx, used extent the window) of the kernels, divided by 2G:
 *   s1:   the 21 stored pairs of the infinite-space kernel at depth offset m dz (pairs odd in z
 *         exactly 0 at m = 0, their value by symmetry);
 *   p3:   sigma_zz^(1+2)(z = 0) of source layer k, per column;
 *   love: Love's stresses at depth (k + 1/2) dz per unit pressure on one cell, per row. */
void mc_eig_s1_fill(const mc_eigen_stress *op, int m, mc_eig_corners *cc,
                    double *const q[MC_EIG_NSYM]);
void mc_eig_p3_fill(const mc_eigen_stress *op, int k, mc_eig_corners *cc, double *const q[6]);
void mc_eig_love_fill(const mc_eigen_stress *op, int k, double *const q[6]);

/* The fft backend's depth step (theory.md §8.8): AUTO picks by the volume (a graded volume whose
 * pair sum costs less than the fine lattice's DFTs takes the coarse step); FINE, the depth DFTs on
 * the fine lattice; COARSE, the direct sum over coarse layer boundaries of prefix-summed tables. */
enum { MC_EIG_DEPTH_AUTO = 0, MC_EIG_DEPTH_FINE = 1, MC_EIG_DEPTH_COARSE = 2 };

/* mc_eigen_stress_create with the depth step forced (for checks and benchmarks; ignored by the
 * direct backend). */
int mc_eig_stress_create_depth(const mc_grid *g, const mc_eigen_volume *v, double nu,
                               mc_backend b, int depth, mc_eigen_stress **out, mc_error *err);
/* mc_eigen_stress_create's fft operator, never distributed over the ranks even under mpirun
 * (not collective): for small operators applied many times by every rank alike, whose transforms
 * cost less than the collectives' latency (the near field's probe, local_op.c). */
int mc_eig_stress_create_replicated(const mc_grid *g, const mc_eigen_volume *v, double nu,
                                    mc_eigen_stress **out, mc_error *err);

/* The depth step an fft operator uses (MC_EIG_DEPTH_FINE or _COARSE; 0 for the direct backend). */
int mc_eig_stress_fft_depth(const mc_eigen_stress *op);

/* fft backend (eigen_stress_fft.c): sizes (qx, qy); spectra, plans and workspaces; apply (eps
 * NULL: no eigenstrain; loads NULL or op->nloads surface fields, mc_eigen_stress_apply_loaded);
 * the folded loads' tables op->lk into spectra; free what prepare took (NULL-safe). */
void mc_eig_stress_fft_size(mc_eigen_stress *op);
int mc_eig_stress_fft_prepare(mc_eigen_stress *op, mc_error *err);
void mc_eig_stress_fft_apply(mc_eigen_stress *op, const double *const eps[6], double G,
                             const double *const *loads, double *const sig[6]);
int mc_eig_stress_fft_loads(mc_eigen_stress *op, mc_error *err);
/* Sums over the 6 nz layer spectra that must not depend on the thread count go in sum blocks:
 * the tasks t = c nz + k (component-major) split into mc_eig_sum_blocks(nz) contiguous blocks,
 * block b holding t = mc_eig_block_first(b) .. mc_eig_block_first(b + 1) - 1, each block summed
 * by one thread in task order into its own sum, the blocks' sums added in block order. The
 * count is fixed by nz alone (at most 8: the threads that can share the work). */
int mc_eig_sum_blocks(int nz);
int mc_eig_block_first(int b, int nb, int nz);
/* The layer spectra of eps into E (mc_eigen_stress_forward); the apply that follows with
 * op->fwd set skips its forward transforms. With visit, visit->layer(ctx, block, k, c, E_kc)
 * sees each spectrum as soon as it is made (serial: the sum blocks above, visit->blocks of them,
 * each block's layers in task order on one thread, one thread per block at a time; distributed:
 * block -1, one call at a time, in a fixed order: the visitor may run its own threads). E_kc
 * has E's layout (mc_eig_layer_spectra). Collective when distributed. */
typedef struct {
    void (*layer)(void *ctx, int block, int k, int c, const fftw_complex *E);
    void *ctx;
    int blocks;
} mc_eig_forward_visit;
void mc_eig_stress_fft_forward(mc_eigen_stress *op, const double *const eps[6],
                               const mc_eig_forward_visit *visit);
/* mc_eigen_stress_forward with a visitor (fft backend; the direct backend ignores visit). */
void mc_eig_stress_forward_visit(mc_eigen_stress *op, const double *const eps[6],
                                 const mc_eig_forward_visit *visit);
/* Where E is, for the displacement operator (eigen_disp_op.c mc_eigen_disp_apply_shared):
 * spectrum c * nz + k at E + (c nz + k) speclen, rows of nk values [ky nk + kx - k0], ty rows. */
typedef struct {
    const fftw_complex *E;
    size_t speclen;
    int tx, ty, k0, nk, dist;
} mc_eig_layer_spectra;
void mc_eig_stress_fft_spectra(const mc_eigen_stress *op, mc_eig_layer_spectra *out);
/* 1 when the operator is distributed: this rank's window rows *r0 .. *r0 + *nr - 1 (those its
 * forward transforms read); 0 otherwise (*r0 = 0, *nr = v.ny). */
int mc_eig_stress_fft_rows(const mc_eigen_stress *op, int *r0, int *nr);
void mc_eig_stress_fft_free(mc_eigen_stress *op);
/* Bytes of the folded loads' spectra of nloads loads for op (its sizes set) with ranks as
 * mc_eig_stress_fft_estimate. */
size_t mc_eig_stress_fft_loads_bytes(const mc_eigen_stress *op, int ranks, int nloads);
/* Add to parts the bytes prepare would take for op (its sizes qx, qy, nzf, depth set), without
 * taking them; ranks = 0 the serial operator, ranks >= 1 rank 0's share of the distributed one
 * (part 3, Love's spectra, replaced by that share). */
void mc_eig_stress_fft_estimate(const mc_eigen_stress *op, int ranks,
                                size_t parts[MC_EIGEN_STRESS_PARTS]);

#endif
