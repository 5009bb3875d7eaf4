/* eigen_periodic.c - the eigenstrain tables on periodic axes (docs/theory.md §8.6): the periodic
 * kernel as an image sum with the smeared rest, and quadrant spectra of any transform size.
 *
 * Along a periodic axis of n cells the kernel of a source cell is the sum over its images,
 *   K_per(d) = sum over l = d (mod n) of K(l).
 * The images inside a box |l| <= Lambda = M n + n/2 are summed exactly (each offset of the
 * box belongs to exactly one residue d in -n/2 .. n/2, so the residue n/2 of an even n has
 * 2 M + 2 images, the others 2 M + 1); the rest, whose kernel varies slowly over a period, is
 * the same kernel smeared uniformly over the period: (1/n) sum over |l| > Lambda of K(l) =
 * (1/n) (limit - box sum), limit = the sum over all l in closed form (the bar of kernels/eigen.h
 * when y alone is periodic, the layer when both are). The period's sum of the table, its
 * Fourier mode 0, is then exactly the limit: a field uniform along the periodic axes gets the
 * bar (layer) response to round-off, whatever M.
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/alloc.h"
#include "plastic/eigen_internal.h"

int mc_eig_images(int n)
{
    const int m = (MC_EIG_IMAGE_REACH + n - 1) / n;
    return m < 1 ? 1 : m;
}

/* The image offsets of residue d (0 <= d <= n/2) along one axis and their weights; a free axis
 * (n = 0) has the offset itself. The box |l| <= Lambda is the union of the residues' blocks of n
 * cells centred on the images; for an even n the residue n/2 has images at both ends, -Lambda and
 * +Lambda, each the centre of half a block: weight 1/2 (the other halves belong to the rest). */
static int image_offsets(int d, int n, int m, int *out, double *w)
{
    if (n <= 0) {
        out[0] = d;
        w[0] = 1.0;
        return 1;
    }
    int c = 0;
    const int ends = n % 2 == 0 && 2 * d == n;
    for (int a = ends ? -m - 1 : -m; a <= m; a++) {
        out[c] = d + a * n;
        w[c++] = ends && (a == -m - 1 || a == m) ? 0.5 : 1.0;
    }
    return c;
}

/* Weight of residue d in the period's sum (d and -d are both residues unless d is 0 or n/2). */
static double residue_weight(int d, int n)
{
    return (d == 0 || (n % 2 == 0 && 2 * d == n)) ? 1.0 : 2.0;
}

/* Zero entry by parity: odd along an axis at its offset 0, and at n/2 of a periodic even n. */
static int parity_zero(int par, int di, int dj, const int period[2])
{
    const int ox = par & 1, oy = (par >> 1) & 1;
    return (ox && (di == 0 || (period[0] > 0 && period[0] % 2 == 0 && 2 * di == period[0]))) ||
           (oy && (dj == 0 || (period[1] > 0 && period[1] % 2 == 0 && 2 * dj == period[1])));
}

void mc_eig_fill_images(int qx, int qy, int ux, int uy, int ncomp, const int *par, mc_eig_kfn fn,
                        mc_eig_kfn limit, const void *ctx, const int period[2],
                        const int images[2], double *const *q)
{
    /* 1: the explicit images */
#pragma omp parallel for schedule(dynamic, 1)
    for (int dj = 0; dj < qy; dj++) {
        int lx[2 * MC_EIG_IMAGE_REACH + 4], ly[2 * MC_EIG_IMAGE_REACH + 4];
        double wx[2 * MC_EIG_IMAGE_REACH + 4], wy[2 * MC_EIG_IMAGE_REACH + 4];
        const int cy = dj < uy ? image_offsets(dj, period[1], images[1], ly, wy) : 0;
        for (int di = 0; di < qx; di++) {
            const size_t at = (size_t)dj * qx + di;
            double sum[MC_EIG_NSYM] = {0.0}, v[MC_EIG_NSYM];
            const int cx = di < ux ? image_offsets(di, period[0], images[0], lx, wx) : 0;
            for (int b = 0; b < cy && cx > 0; b++)
                for (int a = 0; a < cx; a++) {
                    fn(lx[a], ly[b], ctx, v);
                    for (int n = 0; n < ncomp; n++)
                        sum[n] += wx[a] * wy[b] * v[n];
                }
            for (int n = 0; n < ncomp; n++)
                q[n][at] = sum[n];
        }
    }
    /* 2: the smeared rest of the components even along every periodic axis, per free offset */
    const int px = period[0] > 0, py = period[1] > 0;
    const double cells = (px ? period[0] : 1) * (double)(py ? period[1] : 1);
    const int nfree = px && py ? 1 : px ? uy : ux; /* lines sharing one smeared value */
    for (int f = 0; f < nfree; f++) {
        double lim[MC_EIG_NSYM], box[MC_EIG_NSYM] = {0.0};
        limit(px ? 0 : f, py ? 0 : f, ctx, lim);
        const int i_lo = px ? 0 : f, i_hi = px ? ux : f + 1;
        const int j_lo = py ? 0 : f, j_hi = py ? uy : f + 1;
        for (int dj = j_lo; dj < j_hi; dj++)
            for (int di = i_lo; di < i_hi; di++) {
                const double w = (px ? residue_weight(di, period[0]) : 1.0) *
                                 (py ? residue_weight(dj, period[1]) : 1.0);
                for (int n = 0; n < ncomp; n++)
                    box[n] += w * q[n][(size_t)dj * qx + di];
            }
        /* one periodic axis: the midpoint Euler-Maclaurin terms of the rest (theory.md §8.6),
         * from the kernel at the box edge E along that axis */
        double fE[MC_EIG_NSYM] = {0.0}, dfE[MC_EIG_NSYM] = {0.0};
        const int one = px != py, ax = py, n1 = one ? period[ax] : 0;
        double cn = 0.0;
        if (one) {
            const int lam = images[ax] * n1 + n1 / 2;
            double a[MC_EIG_NSYM], b[MC_EIG_NSYM];
            if (n1 % 2 == 0) { /* E = Lambda, a cell centre */
                fn(ax ? f : lam - 1, ax ? lam - 1 : f, ctx, a);
                fn(ax ? f : lam + 1, ax ? lam + 1 : f, ctx, b);
                fn(ax ? f : lam, ax ? lam : f, ctx, fE);
                for (int n = 0; n < ncomp; n++)
                    dfE[n] = 0.5 * (b[n] - a[n]);
                cn = (n1 * (double)n1 + 2.0) / 12.0;
            } else { /* E = Lambda + 1/2, a cell face */
                fn(ax ? f : lam, ax ? lam : f, ctx, a);
                fn(ax ? f : lam + 1, ax ? lam + 1 : f, ctx, b);
                for (int n = 0; n < ncomp; n++) {
                    fE[n] = 0.5 * (a[n] + b[n]);
                    dfE[n] = b[n] - a[n];
                }
                cn = (n1 * (double)n1 - 1.0) / 12.0;
            }
        }
        for (int n = 0; n < ncomp; n++) {
            const int odd = ((par[n] & 1) && px) || ((par[n] & 2) && py);
            const double rest = odd ? 0.0 : (lim[n] - box[n]) / cells;
            for (int dj = j_lo; dj < j_hi; dj++)
                for (int di = i_lo; di < i_hi; di++) {
                    const double d = ax ? dj : di;
                    /* even: (c_n - d^2)/n f'(E), zero mean over the period; odd: -(2d/n) f(E) */
                    const double em = !one ? 0.0
                                      : odd ? -2.0 * d / n1 * fE[n]
                                            : (cn - d * d) / n1 * dfE[n];
                    q[n][(size_t)dj * qx + di] += rest + em;
                }
        }
    }
    /* 3: exact zeros by parity */
    for (int dj = 0; dj < qy; dj++)
        for (int di = 0; di < qx; di++)
            for (int n = 0; n < ncomp; n++)
                if (parity_zero(par[n], di, dj, period))
                    q[n][(size_t)dj * qx + di] = 0.0;
}

/* ---- quadrant spectra through the full transform --------------------------------------------- */

typedef struct {
    mc_eig_fft fft; /* tx x ty, every row in and out */
    int nthr;
    double *rows;       /* nthr x (ty x tx) */
    fftw_complex *spec; /* nthr x speclen */
} full_work;

int mc_eig_quad_create_full(mc_eig_quad *t, int tx, int ty, int qx, int qy, mc_error *err)
{
    memset(t, 0, sizeof *t);
    t->full = 1;
    t->qx = qx;
    t->qy = qy;
    t->mx = tx; /* the transform sizes, for the full path */
    t->my = ty;
    full_work *w = mc_calloc(1, sizeof *w);
    if (!w)
        return mc_fail(err, MC_ERR_NOMEM, "eigen tables: out of memory");
    t->fw = w;
    int rc = mc_eig_fft_create(&w->fft, tx, ty, 0, ty, ty, err);
    if (rc)
        return rc;
    w->nthr = omp_get_max_threads();
    w->rows = mc_malloc((size_t)w->nthr * ty * tx * sizeof *w->rows);
    w->spec = mc_malloc((size_t)w->nthr * w->fft.speclen * sizeof *w->spec);
    if (!w->rows || !w->spec)
        return mc_fail(err, MC_ERR_NOMEM, "eigen tables: out of memory for a %d x %d transform",
                       tx, ty);
    return MC_OK;
}

void mc_eig_quad_full_destroy(mc_eig_quad *t)
{
    full_work *w = t->fw;
    if (!w)
        return;
    mc_eig_fft_destroy(&w->fft);
    mc_free(w->rows);
    mc_free(w->spec);
    mc_free(w);
    t->fw = NULL;
}

/* Unfold the quadrant by parity into the wrap-around table, transform, keep i^(ox + oy) K^. */
void mc_eig_quad_full_transform(const mc_eig_quad *t, int par, double *quad)
{
    const full_work *w = t->fw;
    const int tx = t->mx, ty = t->my, qx = t->qx, qy = t->qy, hx = w->fft.hx;
    const int me = omp_get_thread_num() < w->nthr ? omp_get_thread_num() : 0;
    double *rows = w->rows + (size_t)me * ty * tx;
    fftw_complex *spec = w->spec + (size_t)me * w->fft.speclen;
    const int ox = par & 1, oy = (par >> 1) & 1;
    for (int j = 0; j < ty; j++) {
        const int oj = j <= ty / 2 ? j : j - ty, aj = oj < 0 ? -oj : oj;
        for (int i = 0; i < tx; i++) {
            const int oi = i <= tx / 2 ? i : i - tx, ai = oi < 0 ? -oi : oi;
            double v = 0.0;
            if (ai < qx && aj < qy) {
                v = quad[(size_t)aj * qx + ai];
                if ((ox && oi < 0) != (oy && oj < 0))
                    v = -v;
            }
            rows[(size_t)j * tx + i] = v;
        }
    }
    mc_eig_fft_forward(&w->fft, rows, spec);
    const int rot = (4 - (ox + oy)) & 3; /* i^n = (-i)^(4 - n) */
    for (int ky = 0; ky < qy; ky++)
        for (int kx = 0; kx < qx && kx < hx; kx++) {
            double re = spec[(size_t)ky * hx + kx][0], im = spec[(size_t)ky * hx + kx][1];
            mc_eig_rot(&re, &im, rot);
            quad[(size_t)ky * qx + kx] = re;
        }
}
