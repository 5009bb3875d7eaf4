/* eigen_disp_op.c - eigenstrain -> surface normal residual displacement, direct and fft backends
 * over the same quadrant tables (see eigen_op.h; Jacq et al. 2002;
 * docs/theory.md §8.1).
 *
 *   u_z(f) = sum over source layers k, columns c and window cells s of T_kc(f - s) eps_c(k, s),
 *   T_kc(d) = mc_eigen_surface_uz of the cuboid of layer k centred at -d (source minus field),
 * d in cells, field f on the whole surface grid, source s in the window. T_kc is even or odd in
 * each offset like the column c (xx, yy, zz even; xy odd in x and y; xz odd in x; yz odd in y).
 */
#include <omp.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fftsize.h"
#include "kernels/eigen.h"
#include "operator/dfft.h"
#include "plastic/eigen_internal.h"
#include "plastic/eigen_spectral_op.h"

typedef struct disp_ops disp_ops;

struct mc_eigen_disp {
    mc_grid g;
    mc_eigen_volume v;
    double nu;
    const disp_ops *ops;
    int ux, uy;      /* used offsets: |d_x| < ux, |d_y| < uy */
    int qx, qy;      /* quadrant of the tables */
    size_t qlen;     /* doubles per quadrant (qx * qy, rounded up to a cache line) */
    double *tab;     /* 6 nz quadrants [k * 6 + c]: tables (direct) or quadrant spectra (fft) */
    /* fft */
    mc_eig_fft fft;  /* 2 mx x 2 my, forward rows j0 .. j0 + wy - 1, inverse rows 0 .. ny - 1 */
    int nthr;        /* workspaces */
    double *rows;    /* nthr x (ny * tx) */
    fftw_complex *spec; /* nthr spectra: each thread's transformed layer */
    int nb;          /* sum blocks (mc_eig_sum_blocks) */
    fftw_complex *sums; /* nb spectra: each block's sum */
    int *group;      /* the object's copy of v.group (NULL: uniform) */
    /* fft distributed (under mpirun, mc_dist_active at create; theory.md §8.4) */
    mc_dfft *d;      /* the grid's lateral transforms, the window embedded at (i0, j0) */
    int k0, nk;      /* this rank's frequencies kx = k0 .. k0 + nk - 1; tab holds them alone:
                      * quadrant t at t * tlen, [kx - k0][ky] (ky < qy) */
    size_t tlen;
    int bm;          /* layers per batch of transforms (min(nz, DIST_BATCH)) */
    double *whole;   /* bm x grid ny * nx: a batch of layers' windows embedded in zeros */
    fftw_complex *bs; /* bm x nk * ty: the batch's spectra, mc_dfft's layout */
    fftw_complex *acc; /* nk * ty: the sum, mc_dfft's layout */
    mc_eigen_spectral *sp; /* the spectral kernel (v.kernel): the whole operator, the layers
                                streamed (eigen_spectral_op.h mc_eigen_spectral_create_uz) */
    size_t bytes;
};

struct disp_ops {
    const char *name;
    mc_backend id;
    int (*create)(mc_eigen_disp *op, mc_error *err); /* sizes the quadrant, takes workspaces */
    void (*apply)(mc_eigen_disp *op, const double *const eps[6], double *uz);
};

/* ---- kernel tables --------------------------------------------------------------------------- */

typedef struct {
    double dx, dy, z1, z2, nu; /* the source layer spans depths z1 .. z2 (any thickness) */
    int line;  /* bars along y (mc_eig_line); only dj = 0 is used */
    int layer; /* periodic grids: the image sum's limit is the layer (x periodic), else the bar */
} disp_ctx;

static void disp_kernel(int di, int dj, const void *ctx, double *out)
{
    const disp_ctx *c = ctx;
    const double cx = -di * c->dx, cy = -dj * c->dy; /* cuboid centre relative to the field */
    if (c->line) {
        mc_eigen_surface_uz_bar(cx - 0.5 * c->dx, cx + 0.5 * c->dx, c->z1, c->z2, c->nu, out);
        return;
    }
    mc_eigen_surface_uz(cx - 0.5 * c->dx, cx + 0.5 * c->dx, cy - 0.5 * c->dy, cy + 0.5 * c->dy,
                        c->z1, c->z2, c->nu, out);
}

/* the limit of the image sums on periodic grids (mc_eig_fill_images; theory.md §8.6) */
static void disp_limit(int di, int dj, const void *ctx, double *out)
{
    (void)dj;
    const disp_ctx *c = ctx;
    if (c->layer) {
        mc_eigen_surface_uz_layer(c->z1, c->z2, c->nu, out);
        return;
    }
    const double cx = -di * c->dx;
    mc_eigen_surface_uz_bar(cx - 0.5 * c->dx, cx + 0.5 * c->dx, c->z1, c->z2, c->nu, out);
}

/* Layer k's six tables into q[6] (quadrants of qlen). */
static void build_layer(mc_eigen_disp *op, int k, double *const q[6])
{
    const mc_grid *g = &op->g;
    const int px = mc_eig_per_x(g), py = mc_eig_per_y(g);
    const int period[2] = {px ? g->nx : 0, py ? g->ny : 0};
    const int images[2] = {px ? mc_eig_images(g->nx) : 0, py ? mc_eig_images(g->ny) : 0};
    int par[6];
    for (int c = 0; c < 6; c++)
        par[c] = mc_eig_par(c);
    /* a graded layer is one cuboid of its whole thickness (the kernels take any z1 < z2; the
     * same as the sum of its fine sub-cuboids, theory.md §8.8) */
    const int f = mc_eigen_layer_first(&op->v, k);
    const disp_ctx ctx = {g->dx, g->dy, f * op->v.dz,
                          (f + mc_eigen_layer_count(&op->v, k)) * op->v.dz, op->nu,
                          mc_eig_line(g), px};
    if (mc_eig_periodic(g))
        mc_eig_fill_images(op->qx, op->qy, op->ux, op->uy, 6, par, disp_kernel, disp_limit, &ctx,
                           period, images, q);
    else
        mc_eig_fill(op->qx, op->qy, op->ux, op->uy, 6, par, disp_kernel, &ctx, q);
}

static void build_tables(mc_eigen_disp *op)
{
    for (int k = 0; k < op->v.nz; k++) {
        double *q[6];
        for (int c = 0; c < 6; c++)
            q[c] = op->tab + (size_t)(k * 6 + c) * op->qlen;
        build_layer(op, k, q);
    }
}

/* ---- direct: the O(N^2) reference ------------------------------------------------------------ */

static int direct_create(mc_eigen_disp *op, mc_error *err)
{
    (void)err;
    op->qx = op->ux;
    op->qy = op->uy;
    return MC_OK;
}

static void direct_apply(mc_eigen_disp *op, const double *const eps[6], double *uz)
{
    const int nx = op->g.nx, ny = op->g.ny, wx = op->v.nx, wy = op->v.ny, nz = op->v.nz;
    const int i0 = op->v.i0, j0 = op->v.j0, qx = op->qx;
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g);
    const size_t wcells = (size_t)wx * wy;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double u = 0.0;
            for (int k = 0; k < nz; k++)
                for (int c = 0; c < 6; c++) {
                    const double *t = op->tab + (size_t)(k * 6 + c) * op->qlen;
                    const double *e = eps[c] + k * wcells;
                    const int ox = mc_eig_odd_x(c), oy = mc_eig_odd_y(c);
                    for (int js = 0; js < wy; js++) {
                        const int dj = mc_eig_wrap(j - (j0 + js), ny, py);
                        const double sy = (oy && dj < 0) ? -1.0 : 1.0;
                        const double *trow = t + (size_t)(dj < 0 ? -dj : dj) * qx;
                        for (int is = 0; is < wx; is++) {
                            const int di = mc_eig_wrap(i - (i0 + is), nx, px);
                            const double s = (ox && di < 0) ? -sy : sy;
                            u += s * trow[di < 0 ? -di : di] * e[(size_t)js * wx + is];
                        }
                    }
                }
            uz[(size_t)j * nx + i] = u;
        }
}

/* ---- fft: DC-FFT over quadrant spectra ------------------------------------------------------- */

static int fft_create(mc_eigen_disp *op, mc_error *err)
{
    /* half periods: offsets |d| < u stay below m, and the window (at i0) and the field (at 0)
     * both fit in the cyclic length 2m */
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g);
    /* a periodic axis is transformed over its period, unpadded (theory.md §8.6) */
    const int mx = px ? op->g.nx / 2 : mc_fftsize_good(op->ux < 2 ? 2 : op->ux);
    const int my = py ? op->g.ny / 2 : mc_fftsize_good(op->uy < 2 ? 2 : op->uy);
    op->qx = mx + 1;
    op->qy = my + 1;
    if (mc_dist_active()) /* the distributed arrangement: dist_create */
        return MC_OK;
    int rc = mc_eig_fft_create(&op->fft, px ? op->g.nx : 2 * mx, py ? op->g.ny : 2 * my,
                               op->v.j0, op->v.ny, op->g.ny, err);
    if (rc)
        return rc;
    op->nthr = mc_eig_threads(6 * (size_t)op->v.nz * (size_t)op->fft.tx * (size_t)op->fft.ty);
    op->nb = mc_eig_sum_blocks(op->v.nz);
    const size_t rlen = (size_t)op->g.ny * op->fft.tx;
    if (!(op->rows = mc_malloc((size_t)op->nthr * rlen * sizeof *op->rows)) ||
        !(op->spec = mc_malloc((size_t)op->nthr * op->fft.speclen * sizeof *op->spec)) ||
        !(op->sums = mc_malloc((size_t)op->nb * op->fft.speclen * sizeof *op->sums)))
        return mc_fail(err, MC_ERR_NOMEM, "eigen displacement: out of memory for workspaces");
    op->bytes += (size_t)op->nthr * (rlen * sizeof *op->rows + op->fft.speclen * sizeof *op->spec) +
                 (size_t)op->nb * op->fft.speclen * sizeof *op->sums;
    return MC_OK;
}

static int make_quad(const mc_eigen_disp *op, mc_eig_quad *quad, mc_error *err)
{
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g);
    const int tx = px ? op->g.nx : 2 * (op->qx - 1), ty = py ? op->g.ny : 2 * (op->qy - 1);
    int rc = mc_eig_periodic(&op->g)
                 ? mc_eig_quad_create_full(quad, tx, ty, op->qx, op->qy, err)
                 : mc_eig_quad_create(quad, op->qx - 1, op->qy - 1, err);
    if (rc)
        mc_eig_quad_destroy(quad);
    return rc;
}

/* layers per batch of the distributed transforms (dfft.h batches: fewer collectives) */
#define DIST_BATCH 8

/* Layer k's six quadrant tables, filled and transformed (the same bits on every rank). */
static void layer_spectra(mc_eigen_disp *op, mc_eig_quad *quad, int k, double *const q[6])
{
    build_layer(op, k, q);
#pragma omp parallel for schedule(dynamic, 1)
    for (int c = 0; c < 6; c++)
        mc_eig_quad_transform(quad, mc_eig_par(c), q[c]);
}

/* This rank's columns of layer k's six quadrant spectra q into tab. */
static void keep_columns(mc_eigen_disp *op, int k, double *const q[6])
{
    for (int c = 0; c < 6; c++) {
        double *t = op->tab + (size_t)(k * 6 + c) * op->tlen;
        for (int kx = 0; kx < op->nk; kx++)
            for (int ky = 0; ky < op->qy; ky++)
                t[(size_t)kx * op->qy + ky] = q[c][(size_t)ky * op->qx + op->k0 + kx];
    }
}

/* Every layer's spectra, this rank's columns kept. The layers are split over the P ranks in
 * contiguous blocks, in rounds: in round i rank r makes its i-th layer, then every layer of the
 * round is broadcast from its maker (six quadrants) and each rank keeps its columns - as the
 * stress operator's fill_tables (eigen_stress_fft.c; theory.md §8.4). The same fills and
 * transforms as on one rank: the same bits. q: 12 quadrants of scratch (the own and the
 * received). Collective. */
static void dist_tables(mc_eigen_disp *op, mc_eig_quad *quad, double *const q[12])
{
    const int P = mc_dist_size(), me = mc_dist_rank(), nz = op->v.nz;
    const int per = (nz + P - 1) / P;
    for (int i = 0; i < per; i++) {
        if (me * per + i < nz)
            layer_spectra(op, quad, me * per + i, q);
        for (int src = 0; src < P; src++) {
            const int k = src * per + i;
            if (k >= nz)
                continue;
            double *const *t = src == me ? q : q + 6;
            if (P > 1)
                mc_dist_bcast(t[0], 6 * op->qlen, src); /* the six are contiguous */
            keep_columns(op, k, t);
        }
    }
}

/* The distributed fft backend (theory.md §8.4): the grid's transforms by mc_dfft, the window
 * embedded in a grid-sized field at (i0, j0) as the serial rows place it; this rank's columns of
 * the quadrant spectra, built layer by layer through a scratch of twelve whole quadrants (never
 * the whole tables), the layers split over the ranks (dist_tables). */
static int dist_create(mc_eigen_disp *op, mc_error *err)
{
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g), nz = op->v.nz;
    const int tx = px ? op->g.nx : 2 * (op->qx - 1), ty = py ? op->g.ny : 2 * (op->qy - 1);
    op->fft.tx = tx; /* the sizes alone: the serial transforms are not made */
    op->fft.ty = ty;
    op->fft.hx = tx / 2 + 1;
    op->bm = nz < DIST_BATCH ? nz : DIST_BATCH;
    int rc = mc_dfft_create_many(op->g.nx, op->g.ny, tx, ty, op->bm, &op->d, err);
    if (rc)
        return rc;
    mc_dfft_columns(op->d, &op->k0, &op->nk);
    op->tlen = ((size_t)op->nk * op->qy + 7) / 8 * 8;
    const size_t cells = (size_t)op->g.nx * op->g.ny, al = (size_t)op->nk * ty;
    const int nscr = mc_dist_size() > 1 ? 12 : 6; /* the received layer's six too */
    double *scr = NULL;
    const int ok = (op->whole = mc_zeros((size_t)op->bm * cells)) &&
                   (op->acc = mc_malloc((al + 1) * sizeof *op->acc)) &&
                   (op->bs = mc_malloc(((size_t)op->bm * al + 1) * sizeof *op->bs)) &&
                   (op->tab = mc_malloc((6 * (size_t)nz * op->tlen + 1) * sizeof *op->tab)) &&
                   (scr = mc_malloc((size_t)nscr * op->qlen * sizeof *scr));
    /* every rank or none goes on to the collective fill */
    if (mc_dist_max_int(ok ? MC_OK : MC_ERR_NOMEM) != MC_OK) {
        mc_free(scr);
        return mc_fail(err, MC_ERR_NOMEM, "eigen displacement: out of memory");
    }
    op->bytes += (size_t)op->bm * cells * sizeof(double) + (op->bm + 1) * al * sizeof *op->acc +
                 6 * (size_t)nz * op->tlen * sizeof *op->tab + mc_dfft_bytes(op->d);
    mc_eig_quad quad;
    if ((rc = make_quad(op, &quad, err))) {
        mc_free(scr);
        return rc;
    }
    double *q[12];
    for (int c = 0; c < nscr; c++)
        q[c] = scr + (size_t)c * op->qlen;
    dist_tables(op, &quad, q);
    mc_eig_quad_destroy(&quad);
    mc_free(scr);
    return MC_OK;
}

/* u_z distributed: each column's layers forward over the ranks in batches, K E summed on this
 * rank's frequencies (batch by batch, column by column, layer by layer: an order fixed by the
 * sizes, each frequency alone: the same bits on any number of ranks and threads), one inverse
 * gathered whole on every rank. Collective. */
static void dist_apply(mc_eigen_disp *op, const double *const eps[6], double *uz)
{
    const int nz = op->v.nz, ty = op->fft.ty, my = op->qy - 1, nk = op->nk, bm = op->bm;
    const int nx = op->g.nx, wx = op->v.nx, wy = op->v.ny, i0 = op->v.i0, j0 = op->v.j0;
    const size_t wcells = (size_t)wx * wy, cells = (size_t)nx * op->g.ny, al = (size_t)nk * ty;
    fftw_complex *acc = op->acc;
    memset(acc, 0, al * sizeof *acc);
    for (int k0 = 0; k0 < nz; k0 += bm) {
        const int m = nz - k0 < bm ? nz - k0 : bm;
        for (int c = 0; c < 6; c++) {
            for (int q = 0; q < m; q++) {
                const double *e = eps[c] + (k0 + q) * wcells;
                for (int j = 0; j < wy; j++)
                    memcpy(op->whole + q * cells + (size_t)(j0 + j) * nx + i0,
                           e + (size_t)j * wx, (size_t)wx * sizeof *e);
            }
            mc_dfft_forward_many(op->d, op->whole, cells, m, op->bs, al);
            const int rot = mc_eig_odd_x(c) + mc_eig_odd_y(c), oy = mc_eig_odd_y(c);
#pragma omp parallel for schedule(static) num_threads(op->nthr)
            for (int kx = 0; kx < nk; kx++)
                for (int q = 0; q < m; q++) {
                    const double *r = op->tab + (size_t)((k0 + q) * 6 + c) * op->tlen +
                                      (size_t)kx * op->qy;
                    const fftw_complex *E = op->bs + q * al;
                    for (int ky = 0; ky < ty; ky++) {
                        const int mirror = ky > my;
                        const double s = (mirror && oy) ? -1.0 : 1.0,
                                     v = r[mirror ? ty - ky : ky];
                        const size_t at = (size_t)kx * ty + ky;
                        double re = s * v * E[at][0], im = s * v * E[at][1];
                        mc_eig_rot(&re, &im, rot);
                        acc[at][0] += re;
                        acc[at][1] += im;
                    }
                }
        }
    }
    memcpy(op->bs, acc, al * sizeof *acc);
    mc_dfft_inverse_many(op->d, op->bs, al, 1, uz, cells);
    const double scale = 1.0 / ((double)op->fft.tx * ty); /* FFTW does not normalise */
    for (size_t q = 0; q < cells; q++)
        uz[q] *= scale;
}

/* the tables, built by build_tables, into quadrant spectra */
static int fft_transform_tables(mc_eigen_disp *op, mc_error *err)
{
    mc_eig_quad quad;
    int rc = make_quad(op, &quad, err);
    if (rc)
        return rc;
    const int n = 6 * op->v.nz;
#pragma omp parallel for schedule(dynamic, 1)
    for (int t = 0; t < n; t++)
        mc_eig_quad_transform(&quad, mc_eig_par(t % 6), op->tab + (size_t)t * op->qlen);
    mc_eig_quad_destroy(&quad);
    return MC_OK;
}

/* acc += K_kc E for the layer spectrum E of column c: K = (-i)^(ox + oy) s R (eigen_internal.h) */
static void fft_accumulate(const mc_eigen_disp *op, const double *R, int c,
                           const fftw_complex *E, fftw_complex *acc)
{
    const int ty = op->fft.ty, hx = op->fft.hx, my = op->qy - 1, qx = op->qx;
    const int rot = mc_eig_odd_x(c) + mc_eig_odd_y(c), oy = mc_eig_odd_y(c);
    for (int ky = 0; ky < ty; ky++) {
        const int mirror = ky > my;
        const double s = (mirror && oy) ? -1.0 : 1.0;
        const double *r = R + (size_t)(mirror ? ty - ky : ky) * qx;
        const fftw_complex *e = E + (size_t)ky * hx;
        fftw_complex *a = acc + (size_t)ky * hx;
        for (int kx = 0; kx < hx; kx++) {
            double re = s * r[kx] * e[kx][0], im = s * r[kx] * e[kx][1];
            mc_eig_rot(&re, &im, rot);
            a[kx][0] += re;
            a[kx][1] += im;
        }
    }
}

/* The block sums into block 0's, per frequency in block order, then u_z = the inverse of it. */
static void finish_sums(mc_eigen_disp *op, double *uz)
{
    const size_t sl = op->fft.speclen;
    const long n = (long)((size_t)op->fft.ty * op->fft.hx);
    const int nx = op->g.nx, ny = op->g.ny, tx = op->fft.tx;
    fftw_complex *acc0 = op->sums;
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (long q = 0; q < n; q++)
        for (int b = 1; b < op->nb; b++) {
            acc0[q][0] += op->sums[(size_t)b * sl + q][0];
            acc0[q][1] += op->sums[(size_t)b * sl + q][1];
        }
    mc_eig_fft_inverse(&op->fft, acc0, op->rows);
    const double scale = 1.0 / ((double)tx * op->fft.ty); /* FFTW does not normalise */
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            uz[(size_t)j * nx + i] = scale * op->rows[(size_t)j * tx + i];
}

/* The 6 nz layer products in the sum blocks of mc_eig_sum_blocks: each block by one thread, its
 * layers in order into its own sum; then the blocks' sums in block order. Every addition's order
 * is fixed by the sizes: the same bits on any number of threads (theory.md §8.4). */
static void fft_apply(mc_eigen_disp *op, const double *const eps[6], double *uz)
{
    if (op->d) {
        dist_apply(op, eps, uz);
        return;
    }
    const int nz = op->v.nz, tx = op->fft.tx, nb = op->nb;
    const size_t sl = op->fft.speclen, rlen = (size_t)op->g.ny * tx;
    const size_t wcells = (size_t)op->v.nx * op->v.ny;
#pragma omp parallel num_threads(op->nthr)
    {
        const int me = omp_get_thread_num();
        double *rows = op->rows + (size_t)me * rlen;
        fftw_complex *E = op->spec + (size_t)me * sl;
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < nb; b++) {
            fftw_complex *acc = op->sums + (size_t)b * sl;
            memset(acc, 0, sl * sizeof *acc);
            for (int t = mc_eig_block_first(b, nb, nz); t < mc_eig_block_first(b + 1, nb, nz);
                 t++) {
                const int c = t / nz, k = t % nz; /* component-major, as the stress operator's */
                mc_eig_fill_rows(rows, tx, eps[c] + k * wcells, op->v.nx, op->v.ny, op->v.i0);
                mc_eig_fft_forward(&op->fft, rows, E);
                fft_accumulate(op, op->tab + (size_t)(k * 6 + c) * op->qlen, c, E, acc);
            }
        }
    }
    finish_sums(op, uz);
}

/* ---- the backend table and the object -------------------------------------------------------- */

static const disp_ops backends[] = {
    {"fft", MC_BACKEND_FFT, fft_create, fft_apply},
    {"direct", MC_BACKEND_DIRECT, direct_create, direct_apply},
};

void mc_eigen_disp_destroy(mc_eigen_disp **op)
{
    if (!op || !*op)
        return;
    mc_eig_fft_destroy(&(*op)->fft);
    mc_dfft_destroy(&(*op)->d);
    mc_free((*op)->whole);
    mc_free((*op)->bs);
    mc_free((*op)->acc);
    mc_free((*op)->tab);
    mc_free((*op)->rows);
    mc_free((*op)->spec);
    mc_free((*op)->sums);
    mc_free((*op)->group);
    mc_eigen_spectral_destroy(&(*op)->sp);
    mc_free(*op);
    *op = NULL;
}

int mc_eigen_disp_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                         mc_eigen_disp **out, mc_error *err)
{
    *out = NULL;
    int rc = mc_eig_check(g, v, nu, b, "eigen displacement", err);
    if (rc)
        return rc;
    mc_eigen_disp *op = mc_calloc(1, sizeof *op);
    if (!op)
        return mc_fail(err, MC_ERR_NOMEM, "eigen displacement: out of memory");
    op->g = *g;
    op->v = *v;
    op->nu = nu;
    if (v->group) {
        if (!(op->group = mc_malloc((size_t)v->nz * sizeof *op->group))) {
            mc_eigen_disp_destroy(&op);
            return mc_fail(err, MC_ERR_NOMEM, "eigen displacement: out of memory");
        }
        memcpy(op->group, v->group, (size_t)v->nz * sizeof *op->group);
        op->v.group = op->group;
    }
    for (size_t r = 0; r < sizeof backends / sizeof backends[0]; r++)
        if (backends[r].id == b)
            op->ops = &backends[r];
    if (v->kernel == MC_EIG_KERNEL_SPECTRAL) { /* theory.md §8.10 */
        rc = mc_eigen_spectral_create_uz(g, &op->v, nu, b, &op->sp, err);
        if (rc) {
            mc_eigen_disp_destroy(&op);
            return rc;
        }
        op->bytes = sizeof *op + mc_eigen_spectral_bytes(op->sp);
        *out = op;
        return MC_OK;
    }
    /* field minus source along x: from -(i0 + wx - 1) to nx - 1 - i0; a periodic axis: the
     * periodic kernel's offsets 0 .. n/2 */
    op->ux = v->i0 + v->nx > g->nx - v->i0 ? v->i0 + v->nx : g->nx - v->i0;
    op->uy = v->j0 + v->ny > g->ny - v->j0 ? v->j0 + v->ny : g->ny - v->j0;
    if (mc_eig_per_x(g))
        op->ux = g->nx / 2 + 1;
    if (mc_eig_per_y(g))
        op->uy = g->ny / 2 + 1;
    op->bytes = sizeof *op;
    if ((rc = op->ops->create(op, err)) == MC_OK && b == MC_BACKEND_FFT && mc_dist_active()) {
        op->qlen = ((size_t)op->qx * op->qy + 7) / 8 * 8;
        op->nthr = mc_eig_threads(6 * (size_t)v->nz * (size_t)op->fft.tx * (size_t)op->fft.ty);
        if ((rc = dist_create(op, err))) {
            mc_eigen_disp_destroy(&op);
            return rc;
        }
        *out = op;
        return MC_OK;
    }
    if (rc == MC_OK) {
        op->qlen = ((size_t)op->qx * op->qy + 7) / 8 * 8;
        const size_t n = 6 * (size_t)v->nz * op->qlen;
        if (!(op->tab = mc_malloc(n * sizeof *op->tab)))
            rc = mc_fail(err, MC_ERR_NOMEM, "eigen displacement: out of memory for %zu tables",
                         6 * (size_t)v->nz);
        else
            op->bytes += n * sizeof *op->tab;
    }
    if (rc == MC_OK) {
        build_tables(op);
        if (b == MC_BACKEND_FFT)
            rc = fft_transform_tables(op, err);
    }
    if (rc) {
        mc_eigen_disp_destroy(&op);
        return rc;
    }
    *out = op;
    return MC_OK;
}

void mc_eigen_disp_apply(mc_eigen_disp *op, const double *const eps[6], double *uz)
{
    if (op->sp)
        mc_eigen_spectral_apply_uz(op->sp, eps, uz);
    else
        op->ops->apply(op, eps, uz);
}

/* ---- u_z from the stress operator's layer spectra (theory.md §8.9) --------------------------- */

int mc_eigen_disp_borrow(mc_eigen_disp *dop, mc_eigen_stress *sop)
{
    if (!dop->sp || !sop->spec || !mc_eigen_volume_equal(&dop->v, &sop->v) ||
        dop->g.nx != sop->g.nx || dop->g.ny != sop->g.ny ||
        dop->g.periodic_x != sop->g.periodic_x || dop->g.periodic_y != sop->g.periodic_y ||
        !mc_eigen_spectral_borrow(dop->sp, sop->spec))
        return 0;
    dop->bytes = sizeof *dop + mc_eigen_spectral_bytes(dop->sp);
    return 1;
}

int mc_eigen_disp_takes_sum(const mc_eigen_disp *op) { return op->sp != NULL; }

int mc_eigen_disp_apply_sum(mc_eigen_disp *op, const double *const eps[6],
                            const mc_eigen_sparse *inc, double *uz)
{
    if (!op->sp)
        return MC_ERR_LIMIT;
    mc_eigen_spectral_apply_uz_sum(op->sp, eps, inc, uz);
    return MC_OK;
}

int mc_eigen_disp_shares(const mc_eigen_disp *dop, const mc_eigen_stress *sop)
{
    const mc_eigen_volume *v = &dop->v;
    if (dop->sp || sop->spec || dop->ops->id != MC_BACKEND_FFT || !sop->fft || !mc_eigen_volume_equal(v, &sop->v) ||
        v->i0 != 0 || v->j0 != 0 || v->nx != dop->g.nx || v->ny != dop->g.ny ||
        dop->g.nx != sop->g.nx || dop->g.ny != sop->g.ny ||
        dop->g.periodic_x != sop->g.periodic_x || dop->g.periodic_y != sop->g.periodic_y)
        return 0;
    mc_eig_layer_spectra S;
    mc_eig_stress_fft_spectra(sop, &S);
    if (S.tx != dop->fft.tx || S.ty != dop->fft.ty || S.dist != (dop->d != NULL))
        return 0;
    return S.dist ? S.k0 == dop->k0 && S.nk == dop->nk : S.k0 == 0 && S.nk == dop->fft.hx;
}

/* The stress operator's forward shows each layer spectrum E_kc as it is made (while it is in the
 * cache): serial, sum block `block` (mc_eig_sum_blocks) adds T_kc E_kc to its own sum, its layers
 * in order (the blocks' sums are added in block order afterwards, as fft_apply does); distributed
 * (block -1), the sum on this rank's columns, threads over kx. */
static void visit_layer(void *ctx, int block, int k, int c, const fftw_complex *E)
{
    mc_eigen_disp *op = ctx;
    const double *R = op->tab + (size_t)(k * 6 + c) * (op->d ? op->tlen : op->qlen);
    if (block >= 0) {
        fft_accumulate(op, R, c, E, op->sums + (size_t)block * op->fft.speclen);
        return;
    }
    const int ty = op->fft.ty, my = op->qy - 1, nk = op->nk;
    const int rot = mc_eig_odd_x(c) + mc_eig_odd_y(c), oy = mc_eig_odd_y(c);
#pragma omp parallel for schedule(static) num_threads(op->nthr)
    for (int kx = 0; kx < nk; kx++) {
        const double *r = R + (size_t)kx * op->qy;
        fftw_complex *a = op->acc + (size_t)kx * ty;
        for (int ky = 0; ky < ty; ky++) {
            const int mirror = ky > my;
            const double s = (mirror && oy) ? -1.0 : 1.0, v = r[mirror ? ty - ky : ky];
            const fftw_complex *e = E + (size_t)ky * nk + kx;
            double re = s * v * (*e)[0], im = s * v * (*e)[1];
            mc_eig_rot(&re, &im, rot);
            a[ky][0] += re;
            a[ky][1] += im;
        }
    }
}

void mc_eigen_disp_apply_shared(mc_eigen_disp *dop, mc_eigen_stress *sop,
                                const double *const eps[6], double *uz)
{
    if (!mc_eigen_disp_shares(dop, sop)) {
        mc_eigen_stress_forward(sop, eps);
        mc_eigen_disp_apply(dop, eps, uz);
        return;
    }
    const int nx = dop->g.nx, ny = dop->g.ny, tx = dop->fft.tx, ty = dop->fft.ty;
    const double scale = 1.0 / ((double)tx * ty); /* FFTW does not normalise */
    const mc_eig_forward_visit visit = {visit_layer, dop, dop->d ? 1 : dop->nb};
    if (dop->d) {
        const size_t al = (size_t)dop->nk * ty, cells = (size_t)nx * ny;
        memset(dop->acc, 0, al * sizeof *dop->acc);
        mc_eig_stress_forward_visit(sop, eps, &visit);
        memcpy(dop->bs, dop->acc, al * sizeof *dop->acc);
        mc_dfft_inverse_many(dop->d, dop->bs, al, 1, uz, cells);
        for (size_t q = 0; q < cells; q++)
            uz[q] *= scale;
        return;
    }
    memset(dop->sums, 0, (size_t)dop->nb * dop->fft.speclen * sizeof *dop->sums);
    mc_eig_stress_forward_visit(sop, eps, &visit);
    finish_sums(dop, uz);
}

size_t mc_eigen_disp_bytes(const mc_eigen_disp *op) { return op->bytes; }

size_t mc_eigen_disp_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b)
{
    return mc_eigen_disp_estimate_ranks(g, v, b, mc_dist_active() ? mc_dist_size() : 0);
}

size_t mc_eigen_disp_estimate_ranks(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                    int ranks)
{
    mc_error err = {0};
    if (mc_eig_check(g, v, 0.3, b, "eigen displacement", &err) != MC_OK)
        return 0;
    if (v->kernel == MC_EIG_KERNEL_SPECTRAL) {
        const size_t s = mc_eigen_spectral_estimate_uz(g, v, b);
        return s ? sizeof(mc_eigen_disp) + s : 0;
    }
    /* the used offsets and the quadrant as mc_eigen_disp_create and fft_create set them */
    const int px = mc_eig_per_x(g), py = mc_eig_per_y(g);
    int ux = v->i0 + v->nx > g->nx - v->i0 ? v->i0 + v->nx : g->nx - v->i0;
    int uy = v->j0 + v->ny > g->ny - v->j0 ? v->j0 + v->ny : g->ny - v->j0;
    if (px)
        ux = g->nx / 2 + 1;
    if (py)
        uy = g->ny / 2 + 1;
    size_t bytes = sizeof(mc_eigen_disp), qx = (size_t)ux, qy = (size_t)uy;
    if (b == MC_BACKEND_FFT) {
        const int mx = px ? g->nx / 2 : mc_fftsize_good(ux < 2 ? 2 : ux);
        const int my = py ? g->ny / 2 : mc_fftsize_good(uy < 2 ? 2 : uy);
        const size_t tx = px ? (size_t)g->nx : 2 * (size_t)mx, ty = py ? (size_t)g->ny : 2 * (size_t)my;
        const size_t speclen = (ty * (tx / 2 + 1) + 3) / 4 * 4;
        const int nthr = mc_eig_threads(6 * (size_t)v->nz * tx * ty);
        qx = (size_t)mx + 1;
        qy = (size_t)my + 1;
        if (ranks > 0) { /* dist_create, rank 0's columns (the most) */
            int k0, nk;
            mc_dfft_split((int)qx, ranks, 0, &k0, &nk);
            const size_t cells = (size_t)g->nx * g->ny;
            const int bm = v->nz < DIST_BATCH ? v->nz : DIST_BATCH;
            return bytes + (size_t)bm * cells * sizeof(double) +
                   (size_t)(bm + 1) * nk * ty * sizeof(fftw_complex) +
                   6 * (size_t)v->nz * (((size_t)nk * qy + 7) / 8 * 8) * sizeof(double) +
                   mc_dfft_estimate_many(g->nx, g->ny, (int)tx, (int)ty, bm, ranks, 0);
        }
        bytes += (size_t)nthr * ((size_t)g->ny * tx * sizeof(double) +
                                 speclen * sizeof(fftw_complex)) +
                 (size_t)mc_eig_sum_blocks(v->nz) * speclen * sizeof(fftw_complex);
    }
    return bytes + 6 * (size_t)v->nz * ((qx * qy + 7) / 8 * 8) * sizeof(double);
}
