/* eigen_spectral_op.c - the spectral eigenstrain operator (eigen_spectral_op.h; docs/theory.md
 * §8.10): lateral FFTs around the per-mode kernel of kernels/eigen_spectral.h.
 *
 * fft backend, one apply, in two passes over the layers (a lateral mode's depth step needs only
 * its own running sums, so no layer's spectra need to be kept):
 *   down - each layer in turn: its six components transformed (x rows, then y columns, pruned to
 *          the ny rows of a padded y axis), every mode's state advanced past it
 *          (mc_spec_down_layer: the layers above, its own, the local term), the stresses
 *          transformed back and written;
 *   turn - p3 and u_z of every mode from the states' totals; u_z and p3 transformed back;
 *   up   - each layer from the bottom: transformed again, the layers below, the mirror layers
 *          and S3 (mc_spec_up_layer), added to the stresses.
 * A bin of the half spectrum holds one wave vector, or two or four at a Nyquist index (both signs,
 * weighted). Memory: the states (60 doubles per wave vector), one layer's six spectra, the padded
 * rows; neither the kernel nor the layers' spectra. The displacement alone (create_uz) streams the
 * layers once with an 8-double state per wave vector. */
#include "plastic/eigen_spectral_op.h"

#include <complex.h> /* before fftw3.h: fftw_complex is then double complex */
#include <fftw3.h>
#include <math.h>
#include <omp.h>
#include <string.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "kernels/eigen_spectral.h"
#include "plastic/eigen_internal.h"

struct mc_eigen_spectral {
    mc_grid g;
    int nz, nx, ny;
    int px, py, hx;          /* periods (padded on free axes), x half spectrum */
    double nu;
    mc_spec_point pt;
    mc_backend backend;
    mc_spec_coef coef;
    double *b;               /* nz + 1 layer boundaries, m */
    double uz0[3];           /* k = 0 surface displacement per unit (eps_xx, eps_yy, eps_zz) and
                                thickness: the mean over the directions the free axes allow */
    int nthr;
    int uz_only;             /* 1: made by mc_eigen_spectral_create_uz (no stresses) */
    int borrowed;            /* 1: lay, lrows and U are another object's
                                (mc_eigen_spectral_borrow) */
    /* fft, u_z only: one layer's six spectra at a time (py x hx each) and its padded rows */
    fftw_complex *lay;
    double *lrows;
    fftw_plan lay_r2c;
    mc_spec_uzstate *ust;    /* nent: each wave vector's state */
    /* fft, streamed (two passes over the layers, theory §8.10): per lateral bin its wave vectors
     * (two or four at a Nyquist index, weighted), each with its depth state */
    int nbins, nent;
    size_t sstride;          /* complex values from one slot's spectrum to the next: nbins
                                rounded up to 64 bytes, so every spectrum is as aligned as sp6 */
    size_t rstride;          /* doubles from one thread's padded rows to the next's: ny px
                                rounded up to 64 bytes, as aligned as prow */
    int nblk;                /* layers per visit of the states (stream_block) */
    int down_done;           /* 1: the down pass of mc_eigen_spectral_begin_sum has run */
    int *bin_first;          /* nbins + 1: the entries of bin b are bin_first[b] .. [b + 1] - 1 */
    double *ent_k;           /* 3 per entry: kx, ky, weight */
    /* the modes' arrays: bin b's first wave vector at index b (bin 0, k = 0, stays out of the
     * passes); the others of the Nyquist bins (extras) as single states */
    mc_spec_modes sm;
    double *mq;              /* 3 x nbins: q, cq, sq of sm */
    double *wgt;             /* nbins: the weight of bin b's first wave vector */
    double wt_t;             /* the layer thickness of sm.wt (m; < 0: none) */
    int divide;              /* 1: e^{-q depth} of every mode stays above underflow */
    int nextra;
    int *extra_bin;          /* nextra: the bin of each extra */
    double *extra_k;         /* 3 x nextra: kx, ky, weight */
    mc_spec_state *extra;    /* nextra */
    double complex *extra_out; /* nextra x STREAM_BLOCK_MAX x 6: a block's results */
    fftw_complex *sp6;       /* 6 spectra py x hx: a layer's six components, in and out */
    double *prow;            /* py x px: padded rows */
    fftw_plan a_r2c, b_fwd, c_bwd, d_c2r; /* x rows, y columns, and back */
    fftw_complex *U;         /* py x hx: the surface displacement's modes */
    mc_eigen_spectral_hook hook; /* the up pass's added spectra (mc_eigen_spectral_set_hook) */
    void *hook_ctx;
    double *p3;              /* ny x nx: p3 of the last apply (stresses), Pa */
    fftw_plan uz_c2r;
    /* direct */
    double *tab;             /* [(i nz + j) 36 + r 6 + c][py][px]: stress per 2G */
    double *dtab;            /* [j 6 + c][py][px]: u_z, m */
    double *dsum;            /* 6 nz ny nx: eps + a sparse addend, formed before the sums */
    size_t bytes;
};

static int free_axis_pad(int n, int periodic) { return periodic ? n : mc_fftsize_good(2 * n); }

/* the x and y wave numbers of DFT index m of period p, d the cell size; *nyq: the index is the
 * Nyquist frequency (p even, m = p / 2), which stands for both signs */
static double wave(int m, int p, double d, int *nyq)
{
    *nyq = (p % 2 == 0 && m == p / 2);
    const int s = m <= p / 2 ? m : m - p;
    return 2.0 * M_PI * s / (p * d);
}

static int check(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                 mc_error *err)
{
    int rc = mc_grid_check(g, err);
    if (rc)
        return mc_error_prefix(err, "spectral eigen operator: ");
    if (!v)
        return mc_fail(err, MC_ERR_INPUT, "spectral eigen operator: no volume given");
    if (!(nu > -1.0 && nu < 0.5))
        return mc_fail(err, MC_ERR_INPUT,
                       "spectral eigen operator: Poisson ratio %g (accepted: -1 < nu < 0.5)", nu);
    if (b != MC_BACKEND_FFT && b != MC_BACKEND_DIRECT)
        return mc_fail(err, MC_ERR_INPUT, "spectral eigen operator: unknown backend %d", (int)b);
    if (v->i0 != 0 || v->j0 != 0 || v->nx != g->nx || v->ny != g->ny)
        return mc_fail(err, MC_ERR_LIMIT,
                       "spectral eigen operator: the volume must lie under the whole grid "
                       "(window %d x %d at (%d, %d) of %d x %d)",
                       v->nx, v->ny, v->i0, v->j0, g->nx, g->ny);
    if (v->nz < 1 || !(v->dz > 0.0) || !isfinite(v->dz))
        return mc_fail(err, MC_ERR_INPUT,
                       "spectral eigen operator: need nz >= 1 layers of finite dz > 0 (got %d, %g)",
                       v->nz, v->dz);
    for (int k = 0; v->group && k < v->nz; k++)
        if (v->group[k] < 1 || v->group[k] % 2 == 0)
            return mc_fail(err, MC_ERR_INPUT,
                           "spectral eigen operator: layer %d groups %d fine layers (accepted: "
                           "an odd count >= 1)", k, v->group[k]);
    return MC_OK;
}

/* sizes only (create and estimate) */
static void shape(const mc_grid *g, const mc_eigen_volume *v, mc_eigen_spectral *op)
{
    op->g = *g;
    op->nz = v->nz;
    op->nx = g->nx;
    op->ny = g->ny;
    op->px = free_axis_pad(g->nx, g->periodic_x);
    op->py = free_axis_pad(g->ny, g->periodic_y);
    op->hx = op->px / 2 + 1;
    /* a lateral mode costs ~300 flops per layer and pass: threads pay from ~32k modes (the
     * team's wake-ups dominated a 44^2 run, 36 % of its time in the scheduler) */
    op->nthr = mc_eig_threads(8 * (size_t)op->hx * op->py);
}

static size_t stream_entries(const mc_eigen_spectral *op);

static size_t uz_bytes(const mc_eigen_spectral *op)
{
    const size_t bins = (size_t)op->py * op->hx, nent = stream_entries(op);
    return 7 * bins * sizeof(fftw_complex) + (size_t)op->py * op->px * sizeof(double) +
           (bins + 1) * sizeof(int) + nent * (3 * sizeof(double) + sizeof(mc_spec_uzstate)) +
           ((size_t)op->nz + 1) * sizeof(double) + sizeof(mc_eigen_spectral);
}

static size_t direct_values(const mc_eigen_spectral *op)
{
    return ((op->uz_only ? 0 : (size_t)op->nz * op->nz * 36) + 6 * (size_t)op->nz) * op->py *
           op->px;
}

static size_t direct_bytes(const mc_eigen_spectral *op)
{
    return (direct_values(op) + 6 * (size_t)op->nz * op->nx * op->ny) * sizeof(double) +
           (op->nz + 1) * sizeof(double) + sizeof(mc_eigen_spectral);
}

/* entries per bin: 1, or 2 / 4 at a Nyquist index (both signs stand for the bin) */
static int bin_entries(const mc_eigen_spectral *op, int ky, int kx)
{
    int nyqx, nyqy;
    (void)wave(kx, op->px, op->g.dx, &nyqx);
    (void)wave(ky, op->py, op->g.dy, &nyqy);
    return (nyqx ? 2 : 1) * (nyqy ? 2 : 1);
}

static size_t stream_entries(const mc_eigen_spectral *op)
{
    size_t n = 0;
    for (int ky = 0; ky < op->py; ky++)
        for (int kx = 0; kx < op->hx; kx++)
            n += (size_t)bin_entries(op, ky, kx);
    return n;
}

#define STREAM_BLOCK_MAX 4
static int stream_block(const mc_eigen_spectral *op);
static size_t stream_rows(const mc_eigen_spectral *op);

/* Every array a plan executes on starts on a 64-byte boundary, as the planned ones (mc_malloc),
 * so the plans are made without FFTW_UNALIGNED and FFTW may use its SIMD codelets: 1.5 times
 * faster on 1024 x 512 (theory §8.10). */
static size_t slot_stride(size_t bins) { return (bins + 3) / 4 * 4; }
static size_t rows_stride(size_t values) { return (values + 7) / 8 * 8; }

/* the modes' arrays per bin: the states, q and the frame, the scalars, the weight */
#define MODE_VALUES (MC_SPEC_FIELDS + 3 + MC_SPEC_WEIGHTS + 1)

static size_t stream_bytes(const mc_eigen_spectral *op)
{
    const size_t bins = (size_t)op->py * op->hx, nent = stream_entries(op), extra = nent - bins;
    return bins * MODE_VALUES * sizeof(double) +
           extra * (sizeof(mc_spec_state) + sizeof(int) + 3 * sizeof(double) +
                    STREAM_BLOCK_MAX * 6 * sizeof(double complex)) +
           (6 * (size_t)stream_block(op) * slot_stride(bins) + bins) *
               sizeof(fftw_complex) /* sp6 and U */ +
           (size_t)op->nx * op->ny * sizeof(double) /* p3 */ +
           stream_rows(op) * sizeof(double) + ((size_t)op->nz + 1) * sizeof(double) +
           sizeof(mc_eigen_spectral);
}

/* the bytes create(g, v, b, uz_only) would hold, from the sizes alone; 0 for what it refuses */
static size_t estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b, int uz_only)
{
    mc_error err = {0};
    if (check(g, v, 0.3, b, &err) != MC_OK)
        return 0;
    mc_eigen_spectral op;
    memset(&op, 0, sizeof op);
    shape(g, v, &op);
    op.uz_only = uz_only;
    if (b == MC_BACKEND_DIRECT)
        return direct_values(&op) > (size_t)MC_SPEC_DIRECT_MAX ? 0 : direct_bytes(&op);
    return uz_only ? uz_bytes(&op) : stream_bytes(&op);
}

size_t mc_eigen_spectral_estimate_uz(const mc_grid *g, const mc_eigen_volume *v, mc_backend b)
{
    return estimate(g, v, b, 1);
}

size_t mc_eigen_spectral_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b)
{
    return estimate(g, v, b, 0);
}

void mc_eigen_spectral_destroy(mc_eigen_spectral **op)
{
    if (!op || !*op)
        return;
    mc_eigen_spectral *o = *op;
    fftw_plan plans[] = {o->uz_c2r, o->lay_r2c, o->a_r2c, o->b_fwd, o->c_bwd, o->d_c2r};
    for (size_t p = 0; p < sizeof plans / sizeof plans[0]; p++)
        if (plans[p])
            fftw_destroy_plan(plans[p]);
    mc_free(o->b);
    if (o->borrowed)
        o->U = NULL, o->lay = NULL, o->lrows = NULL;
    mc_free(o->U);
    mc_free(o->p3);
    mc_free(o->tab);
    mc_free(o->dtab);
    mc_free(o->dsum);
    mc_free(o->lay);
    mc_free(o->lrows);
    mc_free(o->ust);
    mc_free(o->bin_first);
    mc_free(o->ent_k);
    mc_free(o->sm.st);
    mc_free(o->sm.wt);
    mc_free(o->mq);
    mc_free(o->wgt);
    mc_free(o->extra_bin);
    mc_free(o->extra_k);
    mc_free(o->extra);
    mc_free(o->extra_out);
    mc_free(o->sp6);
    mc_free(o->prow);
    mc_free(o);
    *op = NULL;
}

/* each bin's wave vectors and weights (op->bin_first, op->ent_k allocated) */
static void entries_fill(mc_eigen_spectral *op)
{
    const int px = op->px, py = op->py, hx = op->hx;
    size_t e = 0;
    for (int ky = 0; ky < py; ky++)
        for (int kx = 0; kx < hx; kx++) {
            op->bin_first[(size_t)ky * hx + kx] = (int)e;
            int nyqx, nyqy;
            const double kxv = wave(kx, px, op->g.dx, &nyqx), kyv = wave(ky, py, op->g.dy, &nyqy);
            const int nsx = nyqx ? 2 : 1, nsy = nyqy ? 2 : 1, n = nsx * nsy;
            for (int a = 0; a < n; a++, e++) {
                op->ent_k[3 * e] = ((a % nsx) ? -1.0 : 1.0) * kxv;
                op->ent_k[3 * e + 1] = ((a / nsx) ? -1.0 : 1.0) * kyv;
                op->ent_k[3 * e + 2] = 1.0 / n;
            }
        }
    op->bin_first[(size_t)py * hx] = (int)e;
}

/* ---- fft, streamed: two passes over the layers, no layer spectra kept ---------------------- */

/* Layers per visit of the states: the mode loop streams every state (~0.5 kB per wave vector)
 * once per block of layers instead of once per layer (theory §8.10: the loop is bound by that
 * traffic). A block holds its layers' six spectra, so the extra spectra stay within
 * STREAM_BLOCK_SHARE of the states' bytes. */
#define STREAM_BLOCK_SHARE 0.5

static int stream_block(const mc_eigen_spectral *op)
{
    const double sp6 = 6.0 * op->py * op->hx * sizeof(fftw_complex);
    const double states = (double)op->py * op->hx * MODE_VALUES * sizeof(double);
    int nb = 1 + (int)(STREAM_BLOCK_SHARE * states / sp6);
    nb = nb < STREAM_BLOCK_MAX ? nb : STREAM_BLOCK_MAX;
    return nb < op->nz ? nb : op->nz;
}

/* the padded rows: one set of ny rows per thread (the transforms run per layer and component),
 * and at least the py x px that a borrowing displacement object takes as its lrows */
static size_t stream_rows(const mc_eigen_spectral *op)
{
    const size_t per = rows_stride((size_t)op->ny * op->px), all = (size_t)op->py * op->px;
    return (size_t)op->nthr * per > all ? (size_t)op->nthr * per : all;
}

static int stream_prepare(mc_eigen_spectral *op, mc_error *err)
{
    const int px = op->px, py = op->py, hx = op->hx, ny = op->ny;
    const size_t bins = (size_t)py * hx, nent = stream_entries(op);
    op->nbins = (int)bins;
    op->nent = (int)nent;
    op->sstride = slot_stride(bins);
    op->rstride = rows_stride((size_t)ny * px);
    op->nblk = stream_block(op);
    const size_t extra = nent - bins;
    op->nextra = (int)extra;
    op->bin_first = mc_malloc((bins + 1) * sizeof *op->bin_first);
    op->ent_k = mc_malloc(3 * nent * sizeof *op->ent_k);
    op->sm.n = (long)bins;
    op->sm.st = mc_malloc((size_t)MC_SPEC_FIELDS * bins * sizeof *op->sm.st);
    op->sm.wt = mc_malloc((size_t)MC_SPEC_WEIGHTS * bins * sizeof *op->sm.wt);
    op->mq = mc_malloc(3 * bins * sizeof *op->mq);
    op->wgt = mc_malloc(bins * sizeof *op->wgt);
    op->extra_bin = mc_malloc((extra + 1) * sizeof *op->extra_bin);
    op->extra_k = mc_malloc((3 * extra + 1) * sizeof *op->extra_k);
    op->extra = mc_malloc((extra + 1) * sizeof *op->extra);
    op->extra_out = mc_malloc((extra * STREAM_BLOCK_MAX * 6 + 1) * sizeof *op->extra_out);
    op->sp6 = mc_malloc(6 * (size_t)op->nblk * op->sstride * sizeof *op->sp6);
    op->U = mc_malloc(bins * sizeof *op->U);
    op->prow = mc_malloc(stream_rows(op) * sizeof *op->prow);
    op->p3 = mc_zeros((size_t)op->nx * op->ny);
    if (!op->bin_first || !op->ent_k || !op->sm.st || !op->sm.wt || !op->mq || !op->wgt ||
        !op->extra_bin || !op->extra_k || !op->extra || !op->extra_out || !op->sp6 || !op->U ||
        !op->prow || !op->p3)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator: out of memory (%zu bytes)",
                       stream_bytes(op));
    entries_fill(op);
    /* each bin's first wave vector into the modes' arrays, the others to the extras */
    double *q = op->mq, *cq = q + bins, *sq = cq + bins, qmax = 0.0;
    int x = 0;
    for (size_t b = 0; b < bins; b++)
        for (int en = op->bin_first[b]; en < op->bin_first[b + 1]; en++) {
            const double kx = op->ent_k[3 * en], ky = op->ent_k[3 * en + 1], r = hypot(kx, ky);
            qmax = r > qmax ? r : qmax;
            if (en > op->bin_first[b]) {
                op->extra_bin[x] = (int)b;
                memcpy(op->extra_k + 3 * x, op->ent_k + 3 * en, 3 * sizeof *op->extra_k);
                x++;
                continue;
            }
            q[b] = r;
            cq[b] = r > 0.0 ? kx / r : 1.0;
            sq[b] = r > 0.0 ? ky / r : 0.0;
            op->wgt[b] = op->ent_k[3 * en + 2];
        }
    op->sm.q = q, op->sm.cq = cq, op->sm.sq = sq;
    op->wt_t = -1.0;
    mc_free(op->ent_k); /* (the arrays and the extras hold all the passes read) */
    mc_free(op->bin_first);
    op->ent_k = NULL;
    op->bin_first = NULL;
    /* the up pass divides e^{-q z} by e^{-q t} layer by layer from the volume's e^{-q depth}
     * while that stays far above underflow (e^{-600} ~ 1e-261) */
    op->divide = qmax * op->b[op->nz] < 600.0;
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    /* one thread per plan: the threads take the layers' components in parallel, and the bits do
     * not depend on how many there are */
    fftw_plan_with_nthreads(1);
    const unsigned fl = FFTW_ESTIMATE; /* aligned: slot_stride, rows_stride */
    int nxp[1] = {px}, nyp[1] = {py};
    /* forward: the ny rows along x (the padded rows are zero), then every column along y */
    op->a_r2c = fftw_plan_many_dft_r2c(1, nxp, ny, op->prow, NULL, 1, px, op->sp6, NULL, 1, hx, fl);
    op->b_fwd = fftw_plan_many_dft(1, nyp, hx, op->sp6, NULL, hx, 1, op->sp6, NULL, hx, 1,
                                   FFTW_FORWARD, fl);
    /* back: every column along y, then the ny rows along x */
    op->c_bwd = fftw_plan_many_dft(1, nyp, hx, op->sp6, NULL, hx, 1, op->sp6, NULL, hx, 1,
                                   FFTW_BACKWARD, fl);
    op->d_c2r = fftw_plan_many_dft_c2r(1, nxp, ny, op->sp6, NULL, 1, hx, op->prow, NULL, 1, px,
                                       fl | FFTW_DESTROY_INPUT);
    fftw_plan_with_nthreads(mc_threads_count());
    if (!op->a_r2c || !op->b_fwd || !op->c_bwd || !op->d_c2r)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator: FFTW could not plan");
    return MC_OK;
}

/* rows (pitch values per row, layer l's values of component c in place) += the entries of inc
 * in layer l: the sum eps + inc formed value by value, the bits of a summed field */
static void sparse_add(const mc_eigen_spectral *op, const mc_eigen_sparse *inc, int l, int c,
                       double *rows, int pitch)
{
    const size_t layer = (size_t)op->nx * op->ny;
    long k0 = 0, k1 = 0;
    if (inc)
        mc_eigen_sparse_range(inc, (long)((size_t)l * layer), (long)((size_t)(l + 1) * layer),
                              &k0, &k1);
    for (long k = k0; k < k1; k++) {
        const size_t at = (size_t)inc->cell[k] - (size_t)l * layer;
        rows[(at / (size_t)op->nx) * (size_t)pitch + at % (size_t)op->nx] +=
            inc->val[(size_t)inc->stride * (size_t)k + (size_t)c];
    }
}

/* the spectrum of component c of block slot s */
static fftw_complex *slot(const mc_eigen_spectral *op, int s, int c)
{
    return op->sp6 + ((size_t)s * 6 + (size_t)c) * op->sstride;
}

/* The block's nb layers of eps + inc (inc NULL: eps alone) into its spectra, slot s for layer
 * first + dir s (dir 1 down, -1 up; the layers' components in parallel, one thread each). */
static void stream_forward(mc_eigen_spectral *op, const double *const eps[6],
                           const mc_eigen_sparse *inc, int first, int dir, int nb)
{
    const int nx = op->nx, ny = op->ny, px = op->px, py = op->py, hx = op->hx;
    const size_t layer = (size_t)nx * ny;
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (int t = 0; t < 6 * nb; t++) {
        const int s = t / 6, c = t % 6, l = first + dir * s;
        double *rows = op->prow + (size_t)omp_get_thread_num() * op->rstride;
        const double *f = eps[c] + (size_t)l * layer;
        for (int j = 0; j < ny; j++) {
            memcpy(rows + (size_t)j * px, f + (size_t)j * nx, (size_t)nx * sizeof *rows);
            memset(rows + (size_t)j * px + nx, 0, (size_t)(px - nx) * sizeof *rows);
        }
        sparse_add(op, inc, l, c, rows, px);
        fftw_complex *S = slot(op, s, c);
        fftw_execute_dft_r2c(op->a_r2c, rows, S);
        memset(S + (size_t)ny * hx, 0, (size_t)(py - ny) * hx * sizeof *S);
        fftw_execute_dft(op->b_fwd, S, S);
    }
}

/* The block's spectra (already scaled) back into its layers of sig (as stream_forward); added
 * going up. */
static void stream_inverse(mc_eigen_spectral *op, double *const sig[6], int first, int dir,
                           int nb)
{
    const int nx = op->nx, ny = op->ny, px = op->px;
    const size_t layer = (size_t)nx * ny;
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (int t = 0; t < 6 * nb; t++) {
        const int s = t / 6, c = t % 6;
        double *rows = op->prow + (size_t)omp_get_thread_num() * op->rstride;
        fftw_complex *S = slot(op, s, c);
        fftw_execute_dft(op->c_bwd, S, S);
        fftw_execute_dft_c2r(op->d_c2r, S, rows);
        double *f = sig[c] + (size_t)(first + dir * s) * layer;
        for (int j = 0; j < ny; j++) {
            const double *r = rows + (size_t)j * px;
            double *o = f + (size_t)j * nx;
            if (dir < 0)
                for (int i = 0; i < nx; i++)
                    o[i] += r[i];
            else
                memcpy(o, r, (size_t)nx * sizeof *o);
        }
    }
}

/* The layers from first in direction dir that share first's thickness, at most nb of them (a
 * visit of the states uses one set of the modes' scalars). */
static int block_run(const mc_eigen_spectral *op, int first, int dir, int nb)
{
    const double t = op->b[first + 1] - op->b[first];
    int n = 1;
    while (n < nb) {
        const int l = first + dir * n;
        if (l < 0 || l >= op->nz || fabs((op->b[l + 1] - op->b[l]) - t) > 1e-12 * t)
            break;
        n++;
    }
    return n;
}

/* the modes' scalars for layer thickness t (m), kept while the thickness stays */
static void modes_weights(mc_eigen_spectral *op, double t)
{
    if (fabs(op->wt_t - t) <= 1e-14 * t)
        return;
    const long n = op->sm.n;
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (long i = 1; i < n; i++)
        mc_spec_modes_weights(&op->sm, i, i + 1, t, op->pt);
    op->wt_t = t;
}

#define MODES_TASK 512 /* modes per task of the mode loop (a multiple of its chunk) */

/* One visit of every state for the block's nb layers (slot s: layer first + dir s, all of one
 * thickness): each bin's spectra replaced by its stresses, scaled by scale (the pass's part).
 * One wave vector per bin runs in the modes' arrays; the few others of the Nyquist bins (extras)
 * one at a time, their results added last. */
static void stream_modes(mc_eigen_spectral *op, int up, int first, int dir, int nb, double scale)
{
    const long bins = op->nbins;
    modes_weights(op, op->b[first + 1] - op->b[first]);
    double tops[STREAM_BLOCK_MAX];
    const double complex *e[STREAM_BLOCK_MAX][6];
    double complex *out[STREAM_BLOCK_MAX][6];
    for (int s = 0; s < nb; s++) {
        tops[s] = op->b[first + dir * s];
        for (int c = 0; c < 6; c++)
            e[s][c] = out[s][c] = slot(op, s, c);
    }
    /* the extras first (they read the spectra that the arrays' pass then overwrites) */
    for (int x = 0; x < op->nextra; x++) {
        const int b = op->extra_bin[x];
        for (int s = 0; s < nb; s++) {
            const int l = first + dir * s;
            double complex in[6], *one = op->extra_out + ((size_t)x * STREAM_BLOCK_MAX + s) * 6;
            for (int c = 0; c < 6; c++)
                in[c] = e[s][c][b];
            if (up)
                mc_spec_up_layer(&op->coef, op->b[l], op->b[l + 1], op->pt, in, &op->extra[x], one);
            else
                mc_spec_down_layer(&op->coef, op->b[l], op->b[l + 1], op->pt, in, &op->extra[x],
                                   one);
        }
    }
    double complex k0[STREAM_BLOCK_MAX][6]; /* bin 0, k = 0: the layer's local stresses alone */
    for (int s = 0; s < nb; s++)
        for (int m = 0; m < 6; m++) {
            k0[s][m] = 0.0;
            for (int c = 0; c < 6; c++)
                k0[s][m] += op->coef.Minf[m][c] * e[s][c][0];
            k0[s][m] *= up ? 0.0 : scale * op->wgt[0];
        }
    const long ntask = (bins - 1 + MODES_TASK - 1) / MODES_TASK;
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (long t = 0; t < ntask; t++) {
        const long i0 = 1 + t * MODES_TASK, i1 = i0 + MODES_TASK < bins ? i0 + MODES_TASK : bins;
        mc_spec_modes_pass(&op->coef, &op->sm, i0, i1, up, nb, tops, op->divide,
                           (const double complex *const(*)[6])e, op->wgt, scale,
                           (double complex *const(*)[6])out, 0);
    }
    for (int s = 0; s < nb; s++)
        for (int c = 0; c < 6; c++)
            out[s][c][0] = k0[s][c];
    for (int x = 0; x < op->nextra; x++) {
        const int b = op->extra_bin[x];
        const double w = scale * op->extra_k[3 * x + 2];
        for (int s = 0; s < nb; s++) {
            const double complex *one = op->extra_out + ((size_t)x * STREAM_BLOCK_MAX + s) * 6;
            for (int c = 0; c < 6; c++)
                out[s][c][b] += w * one[c];
        }
    }
}

/* the grid (ny x nx) of a spectrum (py x hx, destroyed), times scale */
static void stream_grid(mc_eigen_spectral *op, fftw_complex *S, double scale, double *grid)
{
    const int nx = op->nx, ny = op->ny, px = op->px;
    fftw_execute_dft(op->c_bwd, S, S);
    fftw_execute_dft_c2r(op->d_c2r, S, op->prow);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            grid[(size_t)j * nx + i] = scale * op->prow[(size_t)j * px + i];
}

/* The down pass (theory §8.10): every layer's stresses of the layers above, its own and the
 * local term written into sig (sig NULL: the displacement alone), then the turn: u_z and p3.
 * The states then hold what stream_up needs; eps and inc must not change in between. */
static void stream_down(mc_eigen_spectral *op, const double *const eps[6],
                        const mc_eigen_sparse *inc, double G, double *const sig[6], double *uz)
{
    const int nz = op->nz;
    const long bins = op->nbins;
    const double scale = 2.0 * G / ((double)op->px * op->py);
    double complex u0 = 0.0; /* the mode k = 0's surface displacement (bin 0) */
    mc_spec_modes_clear(&op->sm);
    for (int x = 0; x < op->nextra; x++)
        mc_spec_state_init(&op->extra[x], op->extra_k[3 * x], op->extra_k[3 * x + 1]);
    for (int first = 0; first < nz;) {
        const int n = block_run(op, first, 1, op->nblk);
        stream_forward(op, eps, inc, first, 1, n);
        for (int s = 0; s < n; s++)
            u0 -= (op->b[first + s + 1] - op->b[first + s]) *
                  (op->uz0[0] * slot(op, s, 0)[0] + op->uz0[1] * slot(op, s, 1)[0] +
                   op->uz0[2] * slot(op, s, 2)[0]);
        stream_modes(op, 0, first, 1, n, sig ? scale : 0.0);
        if (sig)
            stream_inverse(op, sig, first, 1, n);
        first += n;
    }
    /* the turn: p3 of every mode (into slot 0's first spectrum), the surface displacement */
    fftw_complex *P3 = slot(op, 0, 0);
    const long ntask = (bins - 1 + MODES_TASK - 1) / MODES_TASK;
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (long t = 0; t < ntask; t++) {
        const long i0 = 1 + t * MODES_TASK, i1 = i0 + MODES_TASK < bins ? i0 + MODES_TASK : bins;
        mc_spec_modes_turn(&op->coef, &op->sm, i0, i1, P3, op->U);
        for (long i = i0; i < i1; i++) {
            P3[i] *= op->wgt[i];
            op->U[i] *= op->wgt[i];
        }
    }
    P3[0] = 0.0;
    op->U[0] = u0;
    for (int x = 0; x < op->nextra; x++) {
        const int b = op->extra_bin[x];
        const double w = op->extra_k[3 * x + 2];
        op->U[b] += w * mc_spec_turn(&op->coef, &op->extra[x]);
        P3[b] += w * op->extra[x].p3;
    }
    if (sig) /* p3, Pa */
        stream_grid(op, P3, scale, op->p3);
    if (uz)
        stream_grid(op, op->U, 1.0 / ((double)op->px * op->py), uz);
    op->down_done = sig != NULL;
}

/* The up pass: the layers below, the mirror layers and S3 added to sig. */
static void stream_up(mc_eigen_spectral *op, const double *const eps[6],
                      const mc_eigen_sparse *inc, double G, double *const sig[6])
{
    const double scale = 2.0 * G / ((double)op->px * op->py);
    for (int last = op->nz - 1; last >= 0;) {
        const int n = block_run(op, last, -1, op->nblk); /* slot s: layer last - s */
        stream_forward(op, eps, inc, last, -1, n);
        stream_modes(op, 1, last, -1, n, scale);
        for (int s = 0; s < n && op->hook; s++) {
            double *sp[6];
            for (int c = 0; c < 6; c++)
                sp[c] = (double *)slot(op, s, c);
            if (op->hook(op->hook_ctx, last - s, sp) != 0)
                for (int c = 0; c < 6; c++)
                    for (size_t i = 0; i < 2 * (size_t)op->nbins; i++)
                        sp[c][i] = NAN;
        }
        stream_inverse(op, sig, last, -1, n);
        last -= n;
    }
    op->down_done = 0;
}

static void stream_apply(mc_eigen_spectral *op, const double *const eps[6],
                         const mc_eigen_sparse *inc, double G, double *const sig[6], double *uz)
{
    stream_down(op, eps, inc, G, sig, uz);
    if (sig)
        stream_up(op, eps, inc, G, sig);
}

/* ---- fft, the surface displacement alone: one layer at a time, D evaluated per mode ---------- */

static int uz_prepare(mc_eigen_spectral *op, mc_error *err)
{
    const int px = op->px, py = op->py, hx = op->hx;
    const size_t per = (size_t)py * hx, nent = stream_entries(op);
    op->nbins = (int)per;
    op->nent = (int)nent;
    op->lay = mc_malloc(6 * per * sizeof *op->lay);
    op->U = mc_malloc(per * sizeof *op->U);
    op->lrows = mc_malloc((size_t)py * px * sizeof *op->lrows);
    op->bin_first = mc_malloc((per + 1) * sizeof *op->bin_first);
    op->ent_k = mc_malloc(3 * nent * sizeof *op->ent_k);
    op->ust = mc_malloc(nent * sizeof *op->ust);
    if (op->bin_first && op->ent_k)
        entries_fill(op);
    if (!op->lay || !op->U || !op->lrows || !op->bin_first || !op->ent_k || !op->ust)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen displacement: out of memory (%zu bytes)",
                       uz_bytes(op));
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    const unsigned fl = FFTW_ESTIMATE | FFTW_UNALIGNED;
    fftw_plan_with_nthreads(op->nthr);
    op->lay_r2c = fftw_plan_dft_r2c_2d(py, px, op->lrows, op->lay, fl);
    op->uz_c2r = fftw_plan_dft_c2r_2d(py, px, op->U, op->lrows, fl | FFTW_DESTROY_INPUT);
    fftw_plan_with_nthreads(mc_threads_count());
    if (!op->lay_r2c || !op->uz_c2r)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen displacement: FFTW could not plan");
    return MC_OK;
}

static void uz_apply(mc_eigen_spectral *op, const double *const eps[6],
                     const mc_eigen_sparse *inc, double *uz)
{
    const int nz = op->nz, nx = op->nx, ny = op->ny, px = op->px, py = op->py;
    const size_t bins = (size_t)op->nbins, layer = (size_t)nx * ny;
    memset(op->U, 0, bins * sizeof *op->U);
    for (int e = 0; e < op->nent; e++)
        mc_spec_uzstate_init(&op->ust[e], op->ent_k[3 * e], op->ent_k[3 * e + 1], op->b[0]);
    /* the padding rows stay zero (the out-of-place r2c keeps its input; the last apply's c2r
     * wrote over them) */
    memset(op->lrows, 0, (size_t)py * px * sizeof *op->lrows);
    for (int l = 0; l < nz; l++) {
        for (int c = 0; c < 6; c++) {
            const double *f = eps[c] + (size_t)l * layer;
            for (int j = 0; j < ny; j++)
                memcpy(op->lrows + (size_t)j * px, f + (size_t)j * nx, (size_t)nx * sizeof(double));
            sparse_add(op, inc, l, c, op->lrows, px);
            fftw_execute_dft_r2c(op->lay_r2c, op->lrows, op->lay + c * bins);
        }
        const double top = op->b[l], bottom = op->b[l + 1];
#pragma omp parallel for schedule(static) num_threads(op->nthr)
        for (size_t b = 0; b < bins; b++) {
            double complex u = 0.0;
            for (int en = op->bin_first[b]; en < op->bin_first[b + 1]; en++) {
                double complex D[6];
                if (op->ent_k[3 * en] == 0.0 && op->ent_k[3 * en + 1] == 0.0) {
                    for (int c = 0; c < 6; c++) /* the mode k = 0 (create says which limit) */
                        D[c] = c < 3 ? -(bottom - top) * op->uz0[c] : 0.0;
                } else {
                    mc_spec_uz_next(&op->coef, &op->ust[en], top, bottom, D);
                }
                for (int c = 0; c < 6; c++)
                    u += op->ent_k[3 * en + 2] * D[c] * op->lay[c * bins + b];
            }
            op->U[b] += u;
        }
    }
    fftw_execute_dft_c2r(op->uz_c2r, op->U, op->lrows);
    const double us = 1.0 / ((double)px * py);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            uz[(size_t)j * nx + i] = us * op->lrows[(size_t)j * px + i];
}

/* ---- direct backend: tables over the period by a plain inverse DFT, summed cell by cell -------- */

/* t[dy][dx] = Re (1 / (px py)) sum_k kv[ky][kx] e^{i k.d}: separable, along x then along y */
static void idft2(const mc_eigen_spectral *op, const double complex *kv, double complex *half,
                  double *t)
{
    const int px = op->px, py = op->py;
    const size_t per = (size_t)px * py;
    for (int ky = 0; ky < py; ky++)
        for (int dx = 0; dx < px; dx++) {
            double complex s = 0.0;
            for (int kx = 0; kx < px; kx++)
                s += kv[(size_t)ky * px + kx] * cexp(2.0 * I * M_PI * ((long)kx * dx % px) / px);
            half[(size_t)ky * px + dx] = s;
        }
    for (int dy = 0; dy < py; dy++)
        for (int dx = 0; dx < px; dx++) {
            double complex s = 0.0;
            for (int ky = 0; ky < py; ky++)
                s += half[(size_t)ky * px + dx] * cexp(2.0 * I * M_PI * ((long)ky * dy % py) / py);
            t[(size_t)dy * px + dx] = creal(s) / (double)per;
        }
}

/* the mode (kx, ky) of the pair (observation i, source j), or with i < 0 the surface
 * displacement of source j (into S[0][0..5]); the Nyquist indices averaged over both signs */
static void pair_mode(const mc_eigen_spectral *op, int kx, int ky, int i, int j,
                      double complex S[6][6])
{
    int nyqx, nyqy;
    const double kxv = wave(kx, op->px, op->g.dx, &nyqx);
    const double kyv = wave(ky, op->py, op->g.dy, &nyqy);
    const int nsx = nyqx ? 2 : 1, nsy = nyqy ? 2 : 1, n = nsx * nsy;
    memset(S, 0, 36 * sizeof S[0][0]);
    if (i < 0 && kxv == 0.0 && kyv == 0.0) {
        for (int c = 0; c < 3; c++)
            S[0][c] = -(op->b[j + 1] - op->b[j]) * op->uz0[c];
        return;
    }
    for (int s = 0; s < n; s++) {
        const double sx = (s % nsx) ? -1.0 : 1.0, sy = (s / nsx) ? -1.0 : 1.0;
        double complex P[6][6], D[6];
        if (i < 0) {
            mc_spec_pair_uz(&op->coef, sx * kxv, sy * kyv, op->b[j], op->b[j + 1], D);
            for (int c = 0; c < 6; c++)
                S[0][c] += D[c] / n;
        } else {
            mc_spec_pair(&op->coef, sx * kxv, sy * kyv, op->b[i], op->b[i + 1], op->b[j],
                         op->b[j + 1], op->pt, P);
            for (int r = 0; r < 6; r++)
                for (int c = 0; c < 6; c++)
                    S[r][c] += P[r][c] / n;
        }
    }
}

static int direct_prepare(mc_eigen_spectral *op, mc_error *err)
{
    const int nz = op->nz, px = op->px, py = op->py;
    if (direct_values(op) > (size_t)MC_SPEC_DIRECT_MAX)
        return mc_fail(err, MC_ERR_LIMIT,
                       "spectral eigen operator, direct: %zu table values for %d x %d x %d "
                       "(at most %ld; the direct backend is the reference for small grids)",
                       direct_values(op), op->nx, op->ny, nz, MC_SPEC_DIRECT_MAX);
    const size_t per = (size_t)px * py;
    op->tab = op->uz_only ? NULL : mc_zeros((size_t)nz * nz * 36 * per);
    op->dtab = mc_zeros(6 * (size_t)nz * per);
    op->dsum = mc_malloc(6 * (size_t)nz * op->nx * op->ny * sizeof *op->dsum);
    double complex *kv = mc_malloc(per * sizeof *kv), *half = mc_malloc(per * sizeof *half);
    double complex(*all)[6][6] = mc_malloc(per * sizeof *all);
    if ((!op->tab && !op->uz_only) || !op->dtab || !op->dsum || !kv || !half || !all) {
        mc_free(kv), mc_free(half), mc_free(all);
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator, direct: out of memory");
    }
    /* pairs (i, j) of layers, then (i = -1) the displacement of each source layer */
    for (int i = -1; i < (op->uz_only ? 0 : nz); i++)
        for (int j = 0; j < nz; j++) {
            for (int ky = 0; ky < py; ky++)
                for (int kx = 0; kx < px; kx++)
                    pair_mode(op, kx, ky, i, j, all[(size_t)ky * px + kx]);
            for (int r = 0; r < (i < 0 ? 1 : 6); r++)
                for (int c = 0; c < 6; c++) {
                    for (size_t q = 0; q < per; q++)
                        kv[q] = all[q][r][c];
                    double *t = i < 0 ? op->dtab + ((size_t)j * 6 + c) * per
                                      : op->tab + (((size_t)i * nz + j) * 36 + r * 6 + c) * per;
                    idft2(op, kv, half, t);
                }
        }
    mc_free(kv), mc_free(half), mc_free(all);
    return MC_OK;
}

static void direct_apply(mc_eigen_spectral *op, const double *const eps[6], double G,
                         double *const sig[6], double *uz)
{
    const int nz = op->nz, nx = op->nx, ny = op->ny, px = op->px, py = op->py;
    const size_t layer = (size_t)nx * ny, per = (size_t)px * py;
    for (int i = 0; i < nz && sig; i++)
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++) {
                double s[6] = {0};
                for (int j = 0; j < nz; j++)
                    for (int y2 = 0; y2 < ny; y2++)
                        for (int x2 = 0; x2 < nx; x2++) {
                            const size_t d = (size_t)((y - y2 + py) % py) * px + (x - x2 + px) % px;
                            const size_t src = (size_t)j * layer + (size_t)y2 * nx + x2;
                            const double *t = op->tab + (size_t)(i * nz + j) * 36 * per + d;
                            for (int r = 0; r < 6; r++)
                                for (int c = 0; c < 6; c++)
                                    s[r] += t[(size_t)(r * 6 + c) * per] * eps[c][src];
                        }
                for (int r = 0; r < 6; r++)
                    sig[r][(size_t)i * layer + (size_t)y * nx + x] = 2.0 * G * s[r];
            }
    if (!uz)
        return;
    for (int y = 0; y < ny; y++)
        for (int x = 0; x < nx; x++) {
            double u = 0.0;
            for (int j = 0; j < nz; j++)
                for (int y2 = 0; y2 < ny; y2++)
                    for (int x2 = 0; x2 < nx; x2++) {
                        const size_t d = (size_t)((y - y2 + py) % py) * px + (x - x2 + px) % px;
                        const size_t src = (size_t)j * layer + (size_t)y2 * nx + x2;
                        for (int c = 0; c < 6; c++)
                            u += op->dtab[((size_t)j * 6 + c) * per + d] * eps[c][src];
                    }
            uz[(size_t)y * nx + x] = u;
        }
}

/* ---- the interface ----------------------------------------------------------------------------- */

static int create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                  int uz_only, mc_eigen_spectral **out, mc_error *err)
{
    *out = NULL;
    int rc = check(g, v, nu, b, err);
    if (rc)
        return rc;
    mc_eigen_spectral *op = mc_calloc(1, sizeof *op);
    if (!op)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator: out of memory");
    shape(g, v, op);
    op->nu = nu;
    op->backend = b;
    op->uz_only = uz_only;
    op->pt = v->stress_points == MC_EIG_CELL_CENTRE ? MC_SPEC_CENTRE : MC_SPEC_AVERAGE;
    mc_spec_coef_init(nu, &op->coef);
    /* the surface displacement of the mode k = 0 per unit thickness: u_z = -t (a e_xx + b e_yy
     * + e_zz). Over a periodic axis the field is uniform along it; along a free axis the mode
     * stands for the limit k -> 0 (theory §8.10): the laterally constrained layer when both
     * axes are periodic, the bar (1, 2 nu) or (2 nu, 1) with one free axis, the direction mean
     * (1 + 2 nu) / 2 with both free (the finite patch of §8.1) */
    const double lay = nu / (1.0 - nu);
    if (g->periodic_x && g->periodic_y)
        op->uz0[0] = op->uz0[1] = lay;
    else if (g->periodic_y) /* x free */
        op->uz0[0] = 1.0, op->uz0[1] = 2.0 * nu;
    else if (g->periodic_x)
        op->uz0[0] = 2.0 * nu, op->uz0[1] = 1.0;
    else
        op->uz0[0] = op->uz0[1] = 0.5 + nu;
    op->uz0[2] = 1.0;
    if (!(op->b = mc_malloc(((size_t)v->nz + 1) * sizeof *op->b))) {
        mc_eigen_spectral_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator: out of memory");
    }
    for (int k = 0; k <= v->nz; k++)
        op->b[k] = mc_eigen_layer_first(v, k) * v->dz;
    rc = b == MC_BACKEND_DIRECT ? direct_prepare(op, err)
         : uz_only             ? uz_prepare(op, err)
                               : stream_prepare(op, err);
    if (rc) {
        mc_eigen_spectral_destroy(&op);
        return rc;
    }
    op->bytes = b == MC_BACKEND_DIRECT ? direct_bytes(op)
                : uz_only             ? uz_bytes(op)
                                      : stream_bytes(op);
    *out = op;
    return MC_OK;
}

int mc_eigen_spectral_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                             mc_eigen_spectral **out, mc_error *err)
{
    return create(g, v, nu, b, 0, out, err);
}

int mc_eigen_spectral_create_uz(const mc_grid *g, const mc_eigen_volume *v, double nu,
                                mc_backend b, mc_eigen_spectral **out, mc_error *err)
{
    return create(g, v, nu, b, 1, out, err);
}

/* The direct backend's input: eps itself, or eps + inc formed in op->dsum (o: six arrays). */
static const double *const *direct_input(mc_eigen_spectral *op, const double *const eps[6],
                                         const mc_eigen_sparse *inc, const double *o[6])
{
    if (!inc || inc->n <= 0)
        return eps;
    const size_t n = (size_t)op->nz * op->nx * op->ny;
    for (int c = 0; c < 6; c++) {
        double *d = op->dsum + (size_t)c * n;
        memcpy(d, eps[c], n * sizeof *d);
        for (long k = 0; k < inc->n; k++)
            d[inc->cell[k]] += inc->val[(size_t)inc->stride * (size_t)k + (size_t)c];
        o[c] = d;
    }
    return o;
}

void mc_eigen_spectral_apply_sum(mc_eigen_spectral *op, const double *const eps[6],
                                 const mc_eigen_sparse *inc, double G, double *const sig[6],
                                 double *uz)
{
    if (op->uz_only) { /* (a caller's slip: the object holds no stress path) */
        if (uz)
            mc_eigen_spectral_apply_uz_sum(op, eps, inc, uz);
        return;
    }
    const double *o[6];
    if (op->backend == MC_BACKEND_FFT)
        stream_apply(op, eps, inc, G, sig, uz);
    else
        direct_apply(op, direct_input(op, eps, inc, o), G, sig, uz);
}

void mc_eigen_spectral_begin_sum(mc_eigen_spectral *op, const double *const eps[6],
                                 const mc_eigen_sparse *inc, double G, double *const sig[6],
                                 double *uz)
{
    if (op->backend == MC_BACKEND_FFT && !op->uz_only) {
        stream_down(op, eps, inc, G, sig, uz);
        return;
    }
    mc_eigen_spectral_apply_sum(op, eps, inc, G, sig, uz); /* the whole of it */
}

void mc_eigen_spectral_end_sum(mc_eigen_spectral *op, const double *const eps[6],
                               const mc_eigen_sparse *inc, double G, double *const sig[6])
{
    if (op->backend != MC_BACKEND_FFT || op->uz_only)
        return; /* (begin made it all) */
    if (op->down_done)
        stream_up(op, eps, inc, G, sig);
    else /* (no down pass to finish: the whole apply) */
        stream_apply(op, eps, inc, G, sig, NULL);
}

void mc_eigen_spectral_apply(mc_eigen_spectral *op, const double *const eps[6], double G,
                             double *const sig[6], double *uz)
{
    mc_eigen_spectral_apply_sum(op, eps, NULL, G, sig, uz);
}

void mc_eigen_spectral_apply_uz_sum(mc_eigen_spectral *op, const double *const eps[6],
                                    const mc_eigen_sparse *inc, double *uz)
{
    const double *o[6];
    if (op->backend == MC_BACKEND_DIRECT)
        direct_apply(op, direct_input(op, eps, inc, o), 0.0, NULL, uz);
    else if (op->uz_only)
        uz_apply(op, eps, inc, uz);
    else
        stream_apply(op, eps, inc, 0.0, NULL, uz);
}

void mc_eigen_spectral_apply_uz(mc_eigen_spectral *op, const double *const eps[6], double *uz)
{
    mc_eigen_spectral_apply_uz_sum(op, eps, NULL, uz);
}

int mc_eigen_spectral_borrow(mc_eigen_spectral *uz_op, mc_eigen_spectral *op)
{
    if (!uz_op->uz_only || op->uz_only || uz_op->borrowed || uz_op->backend != MC_BACKEND_FFT ||
        op->backend != MC_BACKEND_FFT || uz_op->px != op->px || uz_op->py != op->py ||
        uz_op->hx != op->hx)
        return 0;
    /* the same shapes: lay (6 spectra py x hx) as sp6, lrows (py x px) as prow, U as U; uz_apply
     * zeroes lrows and U itself, and the stress passes write every value they read */
    const size_t bins = (size_t)op->py * op->hx;
    mc_free(uz_op->lay);
    mc_free(uz_op->lrows);
    mc_free(uz_op->U);
    uz_op->lay = op->sp6;
    uz_op->lrows = op->prow;
    uz_op->U = op->U;
    uz_op->borrowed = 1;
    uz_op->bytes -= 7 * bins * sizeof(fftw_complex) + (size_t)op->py * op->px * sizeof(double);
    return 1;
}

void mc_eigen_spectral_p3(const mc_eigen_spectral *op, double *p3)
{
    const size_t n = (size_t)op->nx * op->ny;
    if (op->p3)
        memcpy(p3, op->p3, n * sizeof *p3);
    else
        memset(p3, 0, n * sizeof *p3);
}

size_t mc_eigen_spectral_bytes(const mc_eigen_spectral *op) { return op->bytes; }

void mc_eigen_spectral_set_hook(mc_eigen_spectral *op, mc_eigen_spectral_hook hook, void *ctx)
{
    op->hook = hook;
    op->hook_ctx = ctx;
}

int mc_eigen_spectral_padded(const mc_eigen_spectral *op, int *px, int *py)
{
    if (op->backend != MC_BACKEND_FFT || op->uz_only)
        return 0;
    *px = op->px;
    *py = op->py;
    return 1;
}
