/* stress_sym.c - the symmetric DC-FFT engine of the stress plan (free axes) and the sparse sums
 * over the loaded cells (see stress_internal.h).
 *
 * Transforms of size 2my x 2mx (the padded grid), pruned of the padding rows by operator/padfft.h
 * as in conv.c. The kernel spectra come from the quadrant by real-to-real transforms of a quarter
 * of the size (the whole point of the engine).
 */
#include <fftw3.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "operator/operator.h"
#include "operator/padfft.h"
#include "stress/stress_internal.h"

/* Below this many values a loop or transform runs on one thread (operator.h). */
#define PAR_MIN MC_THREADS_MIN_CELLS

struct mc_stress_sym {
    mc_grid g;
    int mx, my;       /* half periods: the transform is 2my x 2mx */
    int qx, qy;       /* quadrant: mx + 1, my + 1 */
    size_t qlen;      /* doubles per quadrant array */
    mc_padfft fft;    /* the pruned padded transforms of the loads and products */
    double *qscratch; /* the quadrant the r2r plans were made on */
    fftw_plan r2r[4]; /* by parity: bit 0 odd in x, bit 1 odd in y */
    int off[4];       /* first entry of the r2r's input in the quadrant, by parity */
    int one_thread;   /* 1: the r2r plans run on one thread (mc_stress_sym_kernels spreads them) */
};

void mc_stress_sym_destroy(mc_stress_sym **sp)
{
    if (!sp || !*sp)
        return;
    mc_stress_sym *s = *sp;
    for (int k = 0; k < 4; k++)
        if (s->r2r[k])
            fftw_destroy_plan(s->r2r[k]);
    mc_padfft_destroy(&s->fft);
    mc_free(s->qscratch);
    mc_free(s);
    *sp = NULL;
}

/* m >= 2 keeps the odd axes' DST-I (length m - 1) non-empty; 7-smooth m: FFTW computes the
 * DCT-I / DST-I through a real DFT of length m (and the padded transform has length 2m). */
static int half_period(int n) { return mc_fftsize_good(n < 2 ? 2 : n); }

int mc_stress_sym_create(const mc_grid *g, mc_stress_sym **out, mc_error *err)
{
    *out = NULL;
    int rc = mc_grid_check(g, err);
    if (rc)
        return rc;
    if (g->periodic_x || g->periodic_y)
        return mc_fail(err, MC_ERR_INPUT, "stress: the symmetric engine needs free axes");
    mc_stress_sym *s = mc_calloc(1, sizeof *s);
    if (!s)
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    s->g = *g;
    s->mx = half_period(g->nx);
    s->my = half_period(g->ny);
    s->qx = s->mx + 1;
    s->qy = s->my + 1;
    s->qlen = ((size_t)s->qx * (size_t)s->qy + 7) / 8 * 8;
    if ((rc = mc_padfft_create(&s->fft, g->nx, g->ny, 2 * s->mx, 2 * s->my, 0, err))) {
        mc_stress_sym_destroy(&s);
        return rc;
    }
    const int qx = s->qx, qy = s->qy;
    if (!(s->qscratch = mc_malloc(s->qlen * sizeof *s->qscratch))) {
        mc_stress_sym_destroy(&s);
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory for a %d x %d quadrant", qx, qy);
    }
    int ok = 1;
    s->one_thread = (size_t)s->qx * (size_t)s->qy < PAR_MIN;
    if (s->one_thread)
        fftw_plan_with_nthreads(1);
    for (int par = 0; par < 4 && ok; par++) {
        const int ox = par & 1, oy = (par >> 1) & 1;
        int n[2] = {oy ? s->my - 1 : s->my + 1, ox ? s->mx - 1 : s->mx + 1};
        int embed[2] = {s->qy, s->qx};
        fftw_r2r_kind kind[2] = {oy ? FFTW_RODFT00 : FFTW_REDFT00,
                                 ox ? FFTW_RODFT00 : FFTW_REDFT00};
        s->off[par] = (oy ? s->qx : 0) + ox;
        double *q = s->qscratch + s->off[par];
        /* run for every layer's kernels: [solver] plans (operator/operator.h; the default
         * estimate: the same plan every time, results reproducible); qscratch is scratch */
        s->r2r[par] = fftw_plan_many_r2r(2, n, 1, q, embed, 1, 0, q, embed, 1, 0, kind,
                                         mc_fft_plan_flags());
        ok = s->r2r[par] != NULL;
    }
    mc_fftw_prepare(NULL); /* the default thread count again */
    if (!ok) {
        mc_stress_sym_destroy(&s);
        return mc_fail(err, MC_ERR_NOMEM, "stress: FFTW could not plan the %d x %d quadrant", qx,
                       qy);
    }
    *out = s;
    return MC_OK;
}

void mc_stress_sym_dims(const mc_stress_sym *s, int *qx, int *qy)
{
    *qx = s->qx;
    *qy = s->qy;
}

size_t mc_stress_sym_quad_len(const mc_stress_sym *s) { return s->qlen; }

/* rounded up to whole cache lines: the arrays that follow keep FFTW's SIMD alignment (the
 * new-array executes require the planning arrays' alignment) */
size_t mc_stress_sym_spec_len(const mc_stress_sym *s)
{
    return (2 * (size_t)(2 * s->my) * (size_t)s->qx + 7) / 8 * 8;
}

void mc_stress_sym_kernel(mc_stress_sym *s, int par, double *quad)
{
    double *q = quad + s->off[par & 3];
    fftw_execute_r2r(s->r2r[par & 3], q, q);
}

void mc_stress_sym_kernels(mc_stress_sym *s, int n, const int *par, double *const *quad)
{
    /* one-thread plans: the arrays' transforms side by side (each the bits of its own call) */
#pragma omp parallel for schedule(dynamic) if (s->one_thread && n > 1)
    for (int t = 0; t < n; t++)
        mc_stress_sym_kernel(s, par[t], quad[t]);
}

void mc_stress_sym_load(mc_stress_sym *s, const double *field, double *lspec)
{
    mc_padfft_forward(&s->fft, field, (fftw_complex *)lspec); /* mc_malloc'ed: FFTW's alignment */
}

/* cb (ty x hx half spectrum) = sum_t K_t f_t, normalised (its c2r gives the field); add: += */
static void product(const mc_stress_sym *s, int nterms, const double *const *kq, const int *par,
                    const double *const *ls, double *cb, int add)
{
    const int tx = 2 * s->mx, ty = 2 * s->my, hx = s->qx;
    const int my = s->my;
    const double scale = 1.0 / ((double)tx * (double)ty); /* FFTW does not normalise */
#pragma omp parallel for schedule(static) if ((size_t)ty * hx > PAR_MIN)
    for (int ky = 0; ky < ty; ky++) {
        const int kq_row = ky <= my ? ky : ty - ky; /* K^(2m - k) from K^(k) */
        double *o = cb + 2 * (size_t)ky * hx;
        for (int t = 0; t < nterms; t++) {
            const int ox = par[t] & 1, oy = (par[t] >> 1) & 1;
            /* the sign of the spectrum: -i per odd axis, conjugated in the upper y half */
            double sg = scale;
            if (oy && ky > my)
                sg = -sg;
            if (ox && oy)
                sg = -sg;
            const double *k = kq[t] + (size_t)kq_row * hx;
            const double *l = ls[t] + 2 * (size_t)ky * hx;
            if (ox ^ oy) { /* K^ = -i sg k */
                if (t == 0 && !add)
                    for (int kx = 0; kx < hx; kx++) {
                        const double a = sg * k[kx];
                        o[2 * kx] = a * l[2 * kx + 1];
                        o[2 * kx + 1] = -a * l[2 * kx];
                    }
                else
                    for (int kx = 0; kx < hx; kx++) {
                        const double a = sg * k[kx];
                        o[2 * kx] += a * l[2 * kx + 1];
                        o[2 * kx + 1] -= a * l[2 * kx];
                    }
            } else { /* K^ = sg k, real */
                if (t == 0 && !add)
                    for (int kx = 0; kx < hx; kx++) {
                        const double a = sg * k[kx];
                        o[2 * kx] = a * l[2 * kx];
                        o[2 * kx + 1] = a * l[2 * kx + 1];
                    }
                else
                    for (int kx = 0; kx < hx; kx++) {
                        const double a = sg * k[kx];
                        o[2 * kx] += a * l[2 * kx];
                        o[2 * kx + 1] += a * l[2 * kx + 1];
                    }
            }
        }
    }
}

void mc_stress_sym_apply(mc_stress_sym *s, int nterms, const double *const *kq, const int *par,
                         const double *const *ls, double *out)
{
    product(s, nterms, kq, par, ls, (double *)s->fft.cbuf, 0);
    mc_padfft_inverse(&s->fft, out); /* destroys cbuf: it is ours */
}

void mc_stress_sym_product_add(const mc_stress_sym *s, int nterms, const double *const *kq,
                               const int *par, const double *const *ls, double *spec)
{
    product(s, nterms, kq, par, ls, spec, 1);
}

void mc_stress_sym_transform(const mc_stress_sym *s, int *tx, int *ty)
{
    *tx = 2 * s->mx;
    *ty = 2 * s->my;
}

/* ---- sparse sums over the loaded cells -------------------------------------------------------- */

/* o[i] += v K(i - il, dj) for one term and one loaded cell at column il, row offset dj. */
static void sparse_row(const mc_stress_term *t, int nx, int il, int dj, double v, double *o)
{
    if (t->q) {
        const double *k = t->q + (size_t)(dj < 0 ? -dj : dj) * t->qx;
        const double a = (t->par & 2) && dj < 0 ? -v : v; /* odd in y */
        const double b = (t->par & 1) ? -a : a;           /* odd in x: negative offsets */
        for (int i = il; i < nx; i++)
            o[i] += a * k[i - il];
        for (int i = 0; i < il; i++)
            o[i] += b * k[il - i];
    } else {
        const double *k = t->w + (size_t)(dj < 0 ? dj + t->ty : dj) * t->tx;
        for (int i = il; i < nx; i++)
            o[i] += v * k[i - il];
        for (int i = 0; i < il; i++)
            o[i] += v * k[i - il + t->tx];
    }
}

void mc_stress_sparse_sum(const mc_grid *g, int ncells, const int *cells, int nterms,
                          const mc_stress_term *terms, double *out)
{
    const int nx = g->nx, ny = g->ny;
#pragma omp parallel for schedule(static) if ((size_t)nx * ny * (size_t)ncells > PAR_MIN)
    for (int j = 0; j < ny; j++) {
        double *o = out + (size_t)j * nx;
        memset(o, 0, (size_t)nx * sizeof *o);
        for (int t = 0; t < nterms; t++)
            for (int l = 0; l < ncells; l++) {
                const int c = cells[l];
                const double v = terms[t].f[c];
                if (v != 0.0)
                    sparse_row(&terms[t], nx, c % nx, j - c / nx, v, o);
            }
    }
}
