/* eigen_spectral_op.c - the spectral eigenstrain operator (eigen_spectral_op.h; docs/theory.md
 * §8.10): lateral FFTs around the per-mode kernel of kernels/eigen_spectral.h.
 *
 * fft backend, one apply:
 *   1. every layer and component is transformed along x (zero padded on a free axis) into the
 *      layer spectra E: 6 nz slabs of ny x hx values, hx = px / 2 + 1;
 *   2. the x frequencies go in blocks of BLOCK columns: each block's slabs are transformed along
 *      y (padded on a free axis), every mode (kx, ky) of the block runs the depth step
 *      (mc_spec_depth: O(nz), the kernel evaluated there), the block goes back along y and its
 *      stress spectra overwrite the block's columns of E (the eigenstrain there is consumed);
 *   3. E is transformed back along x into the stresses; the surface displacement's modes,
 *      collected in step 2, by one 2-D inverse transform.
 * Nothing of the kernel is stored: the memory is E plus a block per thread. */
#include "plastic/eigen_spectral_op.h"

#include <complex.h> /* before fftw3.h: fftw_complex is then double complex */
#include <fftw3.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "kernels/eigen_spectral.h"

/* x frequencies per block of step 2: a block of all slabs (6 nz x py x BLOCK complex) stays
 * within a few MB at 512 x 32 layers, and a mode's gather touches BLOCK-wide rows */
#define BLOCK 8

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
    /* fft, u_z only: one layer's six spectra at a time (py x hx each) and its padded rows */
    fftw_complex *lay;
    double *lrows;
    fftw_plan lay_r2c;
    /* fft */
    fftw_complex *E;         /* 6 nz slabs [(c nz + l)][j][kx] */
    fftw_complex *U;         /* py x hx: the surface displacement's modes */
    double *rows;            /* nthr x ny x px (also py x px for u_z: the larger) */
    fftw_complex *blk;       /* nthr x 6 nz x py x BLOCK */
    double complex *mode;    /* nthr x 32 nz: eps, sig, the depth step's work, an average */
    fftw_plan x_r2c, x_c2r, y_fwd, y_bwd, y_fwd_tail, y_bwd_tail, uz_c2r;
    /* direct */
    double *tab;             /* [(i nz + j) 36 + r 6 + c][py][px]: stress per 2G */
    double *dtab;            /* [j 6 + c][py][px]: u_z, m */
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
}

static size_t fft_bytes(const mc_eigen_spectral *op, int nthr)
{
    const size_t nz = (size_t)op->nz, cplx = sizeof(fftw_complex);
    const size_t rowlen = (size_t)(op->ny > op->py ? op->ny : op->py) * op->px;
    return 6 * nz * op->ny * op->hx * cplx                      /* E */
           + (size_t)op->py * op->hx * cplx                     /* U */
           + (size_t)nthr * rowlen * sizeof(double)             /* rows */
           + (size_t)nthr * 6 * nz * op->py * BLOCK * cplx      /* blk */
           + (size_t)nthr * 32 * nz * sizeof(double complex)    /* mode */
           + (nz + 1) * sizeof(double) + sizeof(mc_eigen_spectral);
}

static size_t uz_bytes(const mc_eigen_spectral *op)
{
    const size_t per = (size_t)op->py * op->hx * sizeof(fftw_complex);
    return 7 * per + (size_t)op->py * op->px * sizeof(double) +
           ((size_t)op->nz + 1) * sizeof(double) + sizeof(mc_eigen_spectral);
}

static size_t direct_values(const mc_eigen_spectral *op)
{
    return ((op->uz_only ? 0 : (size_t)op->nz * op->nz * 36) + 6 * (size_t)op->nz) * op->py *
           op->px;
}

static size_t direct_bytes(const mc_eigen_spectral *op)
{
    return direct_values(op) * sizeof(double) + (op->nz + 1) * sizeof(double) +
           sizeof(mc_eigen_spectral);
}

size_t mc_eigen_spectral_estimate_uz(const mc_grid *g, const mc_eigen_volume *v, mc_backend b)
{
    mc_error err = {0};
    if (check(g, v, 0.3, b, &err) != MC_OK)
        return 0;
    mc_eigen_spectral op;
    memset(&op, 0, sizeof op);
    shape(g, v, &op);
    op.uz_only = 1;
    if (b == MC_BACKEND_DIRECT)
        return direct_values(&op) > (size_t)MC_SPEC_DIRECT_MAX ? 0 : direct_bytes(&op);
    return uz_bytes(&op);
}

size_t mc_eigen_spectral_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                  int threads)
{
    mc_error err = {0};
    if (check(g, v, 0.3, b, &err) != MC_OK)
        return 0;
    mc_eigen_spectral op;
    memset(&op, 0, sizeof op);
    shape(g, v, &op);
    if (b == MC_BACKEND_DIRECT)
        return direct_values(&op) > (size_t)MC_SPEC_DIRECT_MAX ? 0 : direct_bytes(&op);
    return fft_bytes(&op, threads < 1 ? 1 : threads);
}

void mc_eigen_spectral_destroy(mc_eigen_spectral **op)
{
    if (!op || !*op)
        return;
    mc_eigen_spectral *o = *op;
    fftw_plan plans[] = {o->x_r2c, o->x_c2r,      o->y_fwd,  o->y_bwd, o->y_fwd_tail,
                         o->y_bwd_tail, o->uz_c2r, o->lay_r2c};
    for (size_t p = 0; p < sizeof plans / sizeof plans[0]; p++)
        if (plans[p])
            fftw_destroy_plan(plans[p]);
    mc_free(o->b);
    mc_free(o->E);
    mc_free(o->U);
    mc_free(o->rows);
    mc_free(o->blk);
    mc_free(o->mode);
    mc_free(o->tab);
    mc_free(o->dtab);
    mc_free(o->lay);
    mc_free(o->lrows);
    mc_free(o);
    *op = NULL;
}

/* ---- the mode (kx, ky): the depth step, averaged over both signs at a Nyquist index ---------- */

/* eps, sig: nz x 6; work: 18 nz (the depth step's 12 nz and a second result) */
static void mode_step(const mc_eigen_spectral *op, double kx, int nyqx, double ky, int nyqy,
                      const double complex (*eps)[6], double complex (*sig)[6],
                      double complex *uz, double complex *work)
{
    const int nz = op->nz;
    if (kx == 0.0 && ky == 0.0) { /* the laterally uniform field: the layer, and the surface
                                     displacement's limit of a finite patch (theory §8.10) */
        mc_spec_depth(&op->coef, 0.0, 0.0, nz, op->b, op->pt, eps, sig, NULL, work);
        double complex u = 0.0;
        for (int l = 0; l < nz; l++)
            u -= (op->b[l + 1] - op->b[l]) *
                 (op->uz0[0] * eps[l][0] + op->uz0[1] * eps[l][1] + op->uz0[2] * eps[l][2]);
        *uz = u;
        return;
    }
    const int nsx = nyqx ? 2 : 1, nsy = nyqy ? 2 : 1, n = nsx * nsy;
    double complex(*one)[6] = (double complex(*)[6])(work + 12 * (size_t)nz);
    *uz = 0.0;
    for (int a = 0; a < n; a++) {
        const double sx = (a % nsx) ? -1.0 : 1.0, sy = (a / nsx) ? -1.0 : 1.0;
        double complex u;
        mc_spec_depth(&op->coef, sx * kx, sy * ky, nz, op->b, op->pt, eps, n == 1 ? sig : one,
                      &u, work);
        *uz += u / n;
        if (n == 1)
            return;
        for (int l = 0; l < nz; l++)
            for (int c = 0; c < 6; c++) {
                if (a == 0)
                    sig[l][c] = 0.0;
                sig[l][c] += one[l][c] / n;
            }
    }
}

/* ---- fft backend ------------------------------------------------------------------------------- */

static int fft_prepare(mc_eigen_spectral *op, mc_error *err)
{
    const int nz = op->nz, nx = op->nx, ny = op->ny, px = op->px, py = op->py, hx = op->hx;
    const size_t rowlen = (size_t)(ny > py ? ny : py) * px;
    op->E = mc_malloc(6 * (size_t)nz * ny * hx * sizeof *op->E);
    op->U = mc_malloc((size_t)py * hx * sizeof *op->U);
    op->rows = mc_malloc((size_t)op->nthr * rowlen * sizeof *op->rows);
    op->blk = mc_malloc((size_t)op->nthr * 6 * nz * py * BLOCK * sizeof *op->blk);
    op->mode = mc_malloc((size_t)op->nthr * 32 * nz * sizeof *op->mode);
    if (!op->E || !op->U || !op->rows || !op->blk || !op->mode)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator: out of memory (%zu bytes)",
                       fft_bytes(op, op->nthr));
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    fftw_plan_with_nthreads(1); /* the operator's own loops run the threads */
    const unsigned fl = FFTW_ESTIMATE | FFTW_UNALIGNED;
    int n1[1] = {px}, ny1[1] = {py};
    op->x_r2c = fftw_plan_many_dft_r2c(1, n1, ny, op->rows, NULL, 1, px, op->E, NULL, 1, hx, fl);
    op->x_c2r = fftw_plan_many_dft_c2r(1, n1, ny, op->E, NULL, 1, hx, op->rows, NULL, 1, px,
                                       fl | FFTW_DESTROY_INPUT);
    op->y_fwd = fftw_plan_many_dft(1, ny1, BLOCK, op->blk, NULL, BLOCK, 1, op->blk, NULL, BLOCK,
                                   1, FFTW_FORWARD, fl);
    op->y_bwd = fftw_plan_many_dft(1, ny1, BLOCK, op->blk, NULL, BLOCK, 1, op->blk, NULL, BLOCK,
                                   1, FFTW_BACKWARD, fl);
    const int tail = hx % BLOCK;
    if (tail) {
        op->y_fwd_tail = fftw_plan_many_dft(1, ny1, tail, op->blk, NULL, BLOCK, 1, op->blk, NULL,
                                            BLOCK, 1, FFTW_FORWARD, fl);
        op->y_bwd_tail = fftw_plan_many_dft(1, ny1, tail, op->blk, NULL, BLOCK, 1, op->blk, NULL,
                                            BLOCK, 1, FFTW_BACKWARD, fl);
    }
    op->uz_c2r = fftw_plan_dft_c2r_2d(py, px, op->U, op->rows, fl | FFTW_DESTROY_INPUT);
    fftw_plan_with_nthreads(mc_threads_count());
    if (!op->x_r2c || !op->x_c2r || !op->y_fwd || !op->y_bwd || !op->uz_c2r ||
        (tail && (!op->y_fwd_tail || !op->y_bwd_tail)))
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen operator: FFTW could not plan");
    (void)nx;
    return MC_OK;
}

/* step 2 for the block of x frequencies k0 .. k0 + w - 1 on thread me */
static void fft_block(mc_eigen_spectral *op, int k0, int w, int me)
{
    const int nz = op->nz, ny = op->ny, py = op->py, hx = op->hx, ns = 6 * nz;
    const size_t slab = (size_t)ny * hx, bs = (size_t)py * BLOCK;
    fftw_complex *blk = op->blk + (size_t)me * ns * bs;
    double complex *m = op->mode + (size_t)me * 32 * nz;
    double complex(*eps)[6] = (double complex(*)[6])m;
    double complex(*sig)[6] = (double complex(*)[6])(m + 6 * (size_t)nz);
    double complex *work = m + 12 * (size_t)nz;
    const fftw_plan fwd = w == BLOCK ? op->y_fwd : op->y_fwd_tail;
    const fftw_plan bwd = w == BLOCK ? op->y_bwd : op->y_bwd_tail;
    for (int s = 0; s < ns; s++) {
        fftw_complex *b = blk + s * bs;
        const fftw_complex *e = op->E + s * slab;
        for (int j = 0; j < ny; j++)
            memcpy(b + (size_t)j * BLOCK, e + (size_t)j * hx + k0, (size_t)w * sizeof *b);
        for (int j = ny; j < py; j++)
            memset(b + (size_t)j * BLOCK, 0, (size_t)w * sizeof *b);
        fftw_execute_dft(fwd, b, b);
    }
    for (int ky = 0; ky < py; ky++) {
        int nyqy, nyqx;
        const double kyv = wave(ky, py, op->g.dy, &nyqy);
        for (int i = 0; i < w; i++) {
            const double kxv = wave(k0 + i, op->px, op->g.dx, &nyqx);
            const size_t at = (size_t)ky * BLOCK + i;
            for (int l = 0; l < nz; l++)
                for (int c = 0; c < 6; c++) {
                    const fftw_complex *v = blk + (size_t)(c * nz + l) * bs + at;
                    eps[l][c] = *v;
                }
            double complex uz;
            mode_step(op, kxv, nyqx, kyv, nyqy, (const double complex(*)[6])eps, sig, &uz, work);
            for (int l = 0; l < nz; l++)
                for (int c = 0; c < 6; c++) {
                    fftw_complex *v = blk + (size_t)(c * nz + l) * bs + at;
                    *v = sig[l][c];
                }
            fftw_complex *u = op->U + (size_t)ky * hx + k0 + i;
            *u = uz;
        }
    }
    for (int s = 0; s < ns; s++) {
        fftw_complex *b = blk + s * bs;
        fftw_execute_dft(bwd, b, b);
        fftw_complex *e = op->E + s * slab;
        for (int j = 0; j < ny; j++)
            memcpy(e + (size_t)j * hx + k0, b + (size_t)j * BLOCK, (size_t)w * sizeof *b);
    }
}

static void fft_apply(mc_eigen_spectral *op, const double *const eps[6], double G,
                      double *const sig[6], double *uz)
{
    const int nz = op->nz, nx = op->nx, ny = op->ny, px = op->px, py = op->py, hx = op->hx;
    const int ns = 6 * nz;
    const size_t slab = (size_t)ny * hx, layer = (size_t)nx * ny;
    const size_t rowlen = (size_t)(ny > py ? ny : py) * px;
    /* 1. along x */
#pragma omp parallel for schedule(dynamic, 1) num_threads(op->nthr)
    for (int s = 0; s < ns; s++) {
        double *r = op->rows + (size_t)omp_get_thread_num() * rowlen;
        const double *f = eps[s / nz] + (size_t)(s % nz) * layer;
        for (int j = 0; j < ny; j++) {
            memcpy(r + (size_t)j * px, f + (size_t)j * nx, (size_t)nx * sizeof *r);
            memset(r + (size_t)j * px + nx, 0, (size_t)(px - nx) * sizeof *r);
        }
        fftw_execute_dft_r2c(op->x_r2c, r, op->E + s * slab);
    }
    /* 2. blocks of x frequencies */
    const int nblk = (hx + BLOCK - 1) / BLOCK;
#pragma omp parallel for schedule(dynamic, 1) num_threads(op->nthr)
    for (int kb = 0; kb < nblk; kb++) {
        const int k0 = kb * BLOCK, w = hx - k0 < BLOCK ? hx - k0 : BLOCK;
        fft_block(op, k0, w, omp_get_thread_num());
    }
    /* 3. back along x: Pa */
    const double scale = 2.0 * G / ((double)px * py);
#pragma omp parallel for schedule(dynamic, 1) num_threads(op->nthr)
    for (int s = 0; s < (sig ? ns : 0); s++) {
        double *r = op->rows + (size_t)omp_get_thread_num() * rowlen;
        fftw_execute_dft_c2r(op->x_c2r, op->E + s * slab, r);
        double *f = sig[s / nz] + (size_t)(s % nz) * layer;
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                f[(size_t)j * nx + i] = scale * r[(size_t)j * px + i];
    }
    if (uz) {
        fftw_execute_dft_c2r(op->uz_c2r, op->U, op->rows);
        const double us = 1.0 / ((double)px * py);
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                uz[(size_t)j * nx + i] = us * op->rows[(size_t)j * px + i];
    }
}

/* ---- fft, the surface displacement alone: one layer at a time, D evaluated per mode ---------- */

static int uz_prepare(mc_eigen_spectral *op, mc_error *err)
{
    const int px = op->px, py = op->py, hx = op->hx;
    const size_t per = (size_t)py * hx;
    op->lay = mc_malloc(6 * per * sizeof *op->lay);
    op->U = mc_malloc(per * sizeof *op->U);
    op->lrows = mc_malloc((size_t)py * px * sizeof *op->lrows);
    if (!op->lay || !op->U || !op->lrows)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen displacement: out of memory (%zu bytes)",
                       uz_bytes(op));
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    const unsigned fl = FFTW_ESTIMATE | FFTW_UNALIGNED;
    op->lay_r2c = fftw_plan_dft_r2c_2d(py, px, op->lrows, op->lay, fl);
    op->uz_c2r = fftw_plan_dft_c2r_2d(py, px, op->U, op->lrows, fl | FFTW_DESTROY_INPUT);
    if (!op->lay_r2c || !op->uz_c2r)
        return mc_fail(err, MC_ERR_NOMEM, "spectral eigen displacement: FFTW could not plan");
    return MC_OK;
}

static void uz_apply(mc_eigen_spectral *op, const double *const eps[6], double *uz)
{
    const int nz = op->nz, nx = op->nx, ny = op->ny, px = op->px, py = op->py, hx = op->hx;
    const size_t per = (size_t)py * hx, layer = (size_t)nx * ny;
    memset(op->U, 0, per * sizeof *op->U);
    for (int l = 0; l < nz; l++) {
        for (int c = 0; c < 6; c++) {
            memset(op->lrows, 0, (size_t)py * px * sizeof *op->lrows);
            const double *f = eps[c] + (size_t)l * layer;
            for (int j = 0; j < ny; j++)
                memcpy(op->lrows + (size_t)j * px, f + (size_t)j * nx, (size_t)nx * sizeof(double));
            fftw_execute_dft_r2c(op->lay_r2c, op->lrows, op->lay + c * per);
        }
        const double bl[2] = {op->b[l], op->b[l + 1]};
#pragma omp parallel for schedule(static) num_threads(op->nthr)
        for (int ky = 0; ky < py; ky++) {
            int nyqy, nyqx;
            const double kyv = wave(ky, py, op->g.dy, &nyqy);
            for (int kx = 0; kx < hx; kx++) {
                const double kxv = wave(kx, px, op->g.dx, &nyqx);
                double complex D[6];
                const size_t at = (size_t)ky * hx + kx;
                if (kxv == 0.0 && kyv == 0.0) {
                    for (int c = 0; c < 6; c++)
                        D[c] = c < 3 ? -(bl[1] - bl[0]) * op->uz0[c] : 0.0;
                } else {
                    const int nsx = nyqx ? 2 : 1, nsy = nyqy ? 2 : 1, n = nsx * nsy;
                    memset(D, 0, sizeof D);
                    for (int a = 0; a < n; a++) {
                        const double sx = (a % nsx) ? -1.0 : 1.0, sy = (a / nsx) ? -1.0 : 1.0;
                        double complex Dl[1][6];
                        mc_spec_uz_layers(&op->coef, sx * kxv, sy * kyv, 1, bl, Dl);
                        for (int c = 0; c < 6; c++)
                            D[c] += Dl[0][c] / n;
                    }
                }
                double complex u = 0.0;
                for (int c = 0; c < 6; c++)
                    u += D[c] * op->lay[c * per + at];
                op->U[at] += u;
            }
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
    double complex *kv = mc_malloc(per * sizeof *kv), *half = mc_malloc(per * sizeof *half);
    double complex(*all)[6][6] = mc_malloc(per * sizeof *all);
    if ((!op->tab && !op->uz_only) || !op->dtab || !kv || !half || !all) {
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
    op->nthr = mc_threads_count() < 1 ? 1 : mc_threads_count();
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
                               : fft_prepare(op, err);
    if (rc) {
        mc_eigen_spectral_destroy(&op);
        return rc;
    }
    op->bytes = b == MC_BACKEND_DIRECT ? direct_bytes(op)
                : uz_only             ? uz_bytes(op)
                                      : fft_bytes(op, op->nthr);
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

void mc_eigen_spectral_apply(mc_eigen_spectral *op, const double *const eps[6], double G,
                             double *const sig[6], double *uz)
{
    if (op->uz_only) { /* (a caller's slip: the object holds no stress path) */
        if (uz)
            mc_eigen_spectral_apply_uz(op, eps, uz);
        return;
    }
    if (op->backend == MC_BACKEND_FFT)
        fft_apply(op, eps, G, sig, uz);
    else
        direct_apply(op, eps, G, sig, uz);
}

void mc_eigen_spectral_apply_uz(mc_eigen_spectral *op, const double *const eps[6], double *uz)
{
    if (op->backend == MC_BACKEND_DIRECT)
        direct_apply(op, eps, 0.0, NULL, uz);
    else if (op->uz_only)
        uz_apply(op, eps, uz);
    else
        fft_apply(op, eps, 0.0, NULL, uz);
}

size_t mc_eigen_spectral_bytes(const mc_eigen_spectral *op) { return op->bytes; }
