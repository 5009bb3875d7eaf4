/* padfft.c - the zero-padded real 2-D FFT, pruned along a free y axis (see padfft.h). */
#include "operator/padfft.h"

#include <string.h>

#include "core/alloc.h"
#include "core/threads.h"
#include "operator/operator.h"

/* Below this many values a memory-bound loop is not worth waking the thread team. */
#define PAR_MIN MC_THREADS_MIN_CELLS

void mc_padfft_destroy(mc_padfft *t)
{
    fftw_plan plans[] = {t->r2c, t->c2r, t->row_r2c, t->row_c2r, t->col_fwd, t->col_bwd};
    for (size_t k = 0; k < sizeof plans / sizeof plans[0]; k++)
        if (plans[k])
            fftw_destroy_plan(plans[k]);
    mc_free(t->rbuf);
    mc_free(t->cbuf);
    memset(t, 0, sizeof *t);
}

int mc_padfft_create(mc_padfft *t, int nx, int ny, int tx, int ty, int full, mc_error *err)
{
    memset(t, 0, sizeof *t);
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    t->nx = nx;
    t->ny = ny;
    t->tx = tx;
    t->ty = ty;
    t->hx = tx / 2 + 1;
    t->pruned = ty > ny;
    t->rows = t->pruned ? ny : ty;
    const int two_d = full || !t->pruned, hx = t->hx;
    size_t nr, nc;
    if (!mc_size_mul((size_t)tx, (size_t)(two_d ? ty : ny), &nr) ||
        !mc_size_mul((size_t)ty, (size_t)hx, &nc) || !(t->rbuf = mc_malloc(nr * sizeof *t->rbuf)) ||
        !(t->cbuf = mc_malloc(nc * sizeof *t->cbuf))) {
        mc_padfft_destroy(t);
        return mc_fail(err, MC_ERR_NOMEM, "FFT %d x %d: out of memory", tx, ty);
    }
    if ((size_t)tx * (size_t)ty < MC_THREADS_MIN_CELLS)
        fftw_plan_with_nthreads(1);
    int ok = 1;
    /* the repeated transforms follow [solver] plans (operator.h); the 2-D pair of a pruned
     * engine only transforms whole kernel tables, once: estimate */
    const unsigned rep = mc_fft_plan_flags(), flags2d = t->pruned ? FFTW_ESTIMATE : rep;
    if (two_d) { /* row-major (ty, tx) with x fastest */
        t->r2c = fftw_plan_dft_r2c_2d(ty, tx, t->rbuf, t->cbuf, flags2d);
        t->c2r = fftw_plan_dft_c2r_2d(ty, tx, t->cbuf, t->rbuf, flags2d);
        ok = t->r2c && t->c2r;
    }
    if (ok && t->pruned) {
        int nrow[1] = {tx}, ncol[1] = {ty};
        t->row_r2c = fftw_plan_many_dft_r2c(1, nrow, ny, t->rbuf, NULL, 1, tx, t->cbuf, NULL, 1,
                                            hx, rep);
        t->row_c2r = fftw_plan_many_dft_c2r(1, nrow, ny, t->cbuf, NULL, 1, hx, t->rbuf, NULL, 1,
                                            tx, rep);
        t->col_fwd = fftw_plan_many_dft(1, ncol, hx, t->cbuf, NULL, hx, 1, t->cbuf, NULL, hx, 1,
                                        FFTW_FORWARD, rep);
        t->col_bwd = fftw_plan_many_dft(1, ncol, hx, t->cbuf, NULL, hx, 1, t->cbuf, NULL, hx, 1,
                                        FFTW_BACKWARD, rep);
        ok = t->row_r2c && t->row_c2r && t->col_fwd && t->col_bwd;
    }
    if (!ok) {
        mc_padfft_destroy(t);
        return mc_fail(err, MC_ERR_NOMEM, "FFTW could not plan the %d x %d transforms", tx, ty);
    }
    return MC_OK;
}

size_t mc_padfft_spectrum_len(const mc_padfft *t) { return 2 * (size_t)t->ty * (size_t)t->hx; }

void mc_padfft_forward(mc_padfft *t, const double *field, fftw_complex *spec)
{
    /* the padding is rewritten each time: the inverse leaves rbuf dirty */
    const int nx = t->nx, ny = t->ny, tx = t->tx, rows = t->rows;
#pragma omp parallel for schedule(static) if ((size_t)tx * rows > PAR_MIN)
    for (int j = 0; j < rows; j++) {
        double *row = t->rbuf + (size_t)j * tx;
        if (j < ny) {
            memcpy(row, field + (size_t)j * nx, (size_t)nx * sizeof *row);
            memset(row + nx, 0, (size_t)(tx - nx) * sizeof *row);
        } else {
            memset(row, 0, (size_t)tx * sizeof *row);
        }
    }
    if (!t->pruned) {
        fftw_execute_dft_r2c(t->r2c, t->rbuf, spec);
        return;
    }
    const size_t hx = (size_t)t->hx;
    fftw_execute_dft_r2c(t->row_r2c, t->rbuf, spec);
    memset(spec + (size_t)ny * hx, 0, (size_t)(t->ty - ny) * hx * sizeof *spec);
    fftw_execute_dft(t->col_fwd, spec, spec);
}

void mc_padfft_inverse(mc_padfft *t, double *out)
{
    if (t->pruned) {
        fftw_execute(t->col_bwd);
        fftw_execute(t->row_c2r);
    } else {
        fftw_execute(t->c2r);
    }
    const int nx = t->nx, ny = t->ny, tx = t->tx;
#pragma omp parallel for schedule(static) if ((size_t)nx * ny > PAR_MIN)
    for (int j = 0; j < ny; j++)
        memcpy(out + (size_t)j * nx, t->rbuf + (size_t)j * tx, (size_t)nx * sizeof *out);
}

void mc_padfft_table(mc_padfft *t, const double *table)
{
    memcpy(t->rbuf, table, (size_t)t->tx * (size_t)t->ty * sizeof *table);
    fftw_execute(t->r2c);
}
