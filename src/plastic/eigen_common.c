/* eigen_common.c - validation, quadrant tables and their real-to-real spectra, and the pruned
 * zero-padded 2-D FFT shared by the eigenstrain operators (see eigen_internal.h). */
#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/threads.h"
#include "operator/operator.h"
#include "plastic/eigen_internal.h"

int mc_eig_check(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                 const char *who, mc_error *err)
{
    int rc = mc_grid_check(g, err);
    if (rc)
        return mc_error_prefix(err, "%s: ", who);
    /* a periodic x axis comes with a periodic y axis (a doubly periodic patch, or a line grid
     * periodic along x): the limits of the image sums are the layer and the bar along y */
    if (g->periodic_x && !g->periodic_y)
        return mc_fail(err, MC_ERR_LIMIT,
                       "%s: a grid periodic along x alone is not supported (accepted: x free, or "
                       "x and y periodic)", who);
    if (!v)
        return mc_fail(err, MC_ERR_INPUT, "%s: no volume given", who);
    if ((mc_eig_per_x(g) && (v->i0 != 0 || v->nx != g->nx)) ||
        (mc_eig_per_y(g) && (v->j0 != 0 || v->ny != g->ny)))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: along a periodic axis the volume must span the whole period (window "
                       "%d x %d at (%d, %d) on the %d x %d grid)", who, v->nx, v->ny, v->i0, v->j0,
                       g->nx, g->ny);
    if (v->nx < 1 || v->ny < 1 || v->i0 < 0 || v->j0 < 0 || v->nx > g->nx - v->i0 ||
        v->ny > g->ny - v->j0)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: window of %d x %d columns at (%d, %d) is not inside the %d x %d grid",
                       who, v->nx, v->ny, v->i0, v->j0, g->nx, g->ny);
    if (v->nz < 1 || !(v->dz > 0.0) || !isfinite(v->dz))
        return mc_fail(err, MC_ERR_INPUT, "%s: need nz >= 1 layers of finite dz > 0 (got %d, %g)",
                       who, v->nz, v->dz);
    if (v->group) {
        long fine = 0;
        for (int k = 0; k < v->nz; k++) {
            if (v->group[k] < 1 || v->group[k] % 2 == 0 || v->group[k] > (1 << 20))
                return mc_fail(err, MC_ERR_INPUT,
                               "%s: layer %d groups %d fine layers (accepted: an odd count >= 1)",
                               who, k, v->group[k]);
            fine += v->group[k];
        }
        if (fine > (1 << 20))
            return mc_fail(err, MC_ERR_LIMIT, "%s: %ld fine layers exceed the supported sizes",
                           who, fine);
    }
    if (!(nu > -1.0 && nu < 0.5))
        return mc_fail(err, MC_ERR_INPUT, "%s: Poisson's ratio %g is not in (-1, 0.5)", who, nu);
    if (b != MC_BACKEND_FFT && b != MC_BACKEND_DIRECT)
        return mc_fail(err, MC_ERR_INPUT, "%s: unknown backend %d (accepted: fft, direct)", who,
                       (int)b);
    /* transform lengths are at most ~2 (grid + window) per axis and 2 (2 nz) in depth: keep
     * the products of index arithmetic inside int */
    if (v->nz > (1 << 20) ||
        4.0 * ((double)g->nx + v->nx + 2) * ((double)g->ny + v->ny + 2) > (double)INT_MAX / 8)
        return mc_fail(err, MC_ERR_LIMIT, "%s: %d x %d x %d cells exceed the supported sizes", who,
                       v->nx, v->ny, v->nz);
    return MC_OK;
}

int mc_eigen_volume_equal(const mc_eigen_volume *a, const mc_eigen_volume *b)
{
    if (a->i0 != b->i0 || a->j0 != b->j0 || a->nx != b->nx || a->ny != b->ny || a->nz != b->nz ||
        a->dz != b->dz || a->stress_points != b->stress_points || a->kernel != b->kernel)
        return 0;
    for (int k = 0; k < a->nz; k++)
        if (mc_eigen_layer_count(a, k) != mc_eigen_layer_count(b, k))
            return 0;
    return 1;
}

int mc_eigen_grade(double dz, double depth, double fine_depth, double ratio, int *group, int max)
{
    /* the fine layers a uniform volume would have: the last layer is cut to end within one dz
     * of them (the depth step's cost follows the fine layers) */
    const int need = (int)ceil(depth / dz - 1e-9);
    int nz = 0, fine = 0, prev = 1;
    while (fine < need || nz == 0) {
        if (nz >= max)
            return 0;
        int c = 1;
        if (fine * dz >= fine_depth * (1 - 1e-9)) {
            /* the largest odd count not above ratio x the depth of the top */
            const double r = ratio * fine;
            c = r >= 1.0 ? (int)floor(r) : 1;
            c = c % 2 ? c : c - 1;
            c = c < prev ? prev : c;
            if (fine + c > need) /* the last layer: the odd count that reaches need */
                c = (need - fine) % 2 ? need - fine : need - fine + 1;
        }
        group[nz++] = c;
        fine += c;
        prev = c;
    }
    return nz;
}

int mc_eig_threads(size_t work)
{
    const int n = mc_threads_count();
    return n > 1 && work >= MC_THREADS_MIN_CELLS ? n : 1;
}

#define SUM_BLOCKS_MAX 8 /* eigen_internal.h: the threads that can share a blocked sum */

int mc_eig_sum_blocks(int nz) { return 6 * nz < SUM_BLOCKS_MAX ? 6 * nz : SUM_BLOCKS_MAX; }

int mc_eig_block_first(int b, int nb, int nz) { return (int)((long)b * 6 * nz / nb); }

/* ---- quadrant tables ------------------------------------------------------------------------- */

void mc_eig_fill(int qx, int qy, int ux, int uy, int ncomp, const int *par, mc_eig_kfn fn,
                 const void *ctx, double *const *q)
{
#pragma omp parallel for schedule(dynamic, 1)
    for (int dj = 0; dj < qy; dj++) {
        double v[MC_EIG_NSYM];
        for (int di = 0; di < qx; di++) {
            const size_t at = (size_t)dj * qx + di;
            if (di >= ux || dj >= uy) {
                for (int n = 0; n < ncomp; n++)
                    q[n][at] = 0.0;
                continue;
            }
            fn(di, dj, ctx, v);
            for (int n = 0; n < ncomp; n++) {
                const int zero = ((par[n] & 1) && di == 0) || ((par[n] & 2) && dj == 0);
                q[n][at] = zero ? 0.0 : v[n];
            }
        }
    }
}

void mc_eig_quad_destroy(mc_eig_quad *t)
{
    mc_eig_quad_full_destroy(t);
    for (int p = 0; p < 4; p++)
        if (t->plan[p])
            fftw_destroy_plan(t->plan[p]);
    memset(t, 0, sizeof *t);
}

int mc_eig_quad_create(mc_eig_quad *t, int mx, int my, mc_error *err)
{
    memset(t, 0, sizeof *t);
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    t->mx = mx;
    t->my = my;
    t->qx = mx + 1;
    t->qy = my + 1;
    double *scratch = mc_malloc((size_t)t->qx * t->qy * sizeof *scratch);
    if (!scratch)
        return mc_fail(err, MC_ERR_NOMEM, "eigen tables: out of memory");
    fftw_plan_with_nthreads(1);
    for (int p = 0; p < 4 && rc == MC_OK; p++) {
        const int ox = p & 1, oy = (p >> 1) & 1;
        /* odd axis: DST-I on the interior entries 1 .. m - 1 (0 and m are 0 by parity / padding) */
        int n[2] = {oy ? my - 1 : my + 1, ox ? mx - 1 : mx + 1};
        int embed[2] = {t->qy, t->qx};
        fftw_r2r_kind kind[2] = {oy ? FFTW_RODFT00 : FFTW_REDFT00,
                                 ox ? FFTW_RODFT00 : FFTW_REDFT00};
        double *at = scratch + (oy ? t->qx : 0) + (ox ? 1 : 0);
        /* setup only: UNALIGNED lets one plan run on every table (offset by one element when
         * odd) */
        t->plan[p] = fftw_plan_many_r2r(2, n, 1, at, embed, 1, 0, at, embed, 1, 0, kind,
                                        FFTW_ESTIMATE | FFTW_UNALIGNED);
        if (!t->plan[p])
            rc = mc_fail(err, MC_ERR_NOMEM, "eigen tables: FFTW could not plan a %d x %d r2r",
                         t->qx, t->qy);
    }
    mc_free(scratch);
    if (rc)
        mc_eig_quad_destroy(t);
    return rc;
}

void mc_eig_quad_transform(const mc_eig_quad *t, int par, double *quad)
{
    if (t->full) {
        mc_eig_quad_full_transform(t, par, quad);
        return;
    }
    double *at = quad + ((par & 2) ? t->qx : 0) + ((par & 1) ? 1 : 0);
    fftw_execute_r2r(t->plan[par & 3], at, at);
}

/* ---- pruned 2-D FFT -------------------------------------------------------------------------- */

void mc_eig_fft_destroy(mc_eig_fft *t)
{
    fftw_plan p[] = {t->row_r2c, t->col_fwd, t->col_bwd, t->row_c2r};
    for (int k = 0; k < 4; k++)
        if (p[k])
            fftw_destroy_plan(p[k]);
    memset(t, 0, sizeof *t);
}

int mc_eig_fft_create(mc_eig_fft *t, int tx, int ty, int row0, int nin, int nout, mc_error *err)
{
    memset(t, 0, sizeof *t);
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    t->tx = tx;
    t->ty = ty;
    t->hx = tx / 2 + 1;
    t->row0 = row0;
    t->nin = nin;
    t->nout = nout;
    t->speclen = ((size_t)ty * t->hx + 3) / 4 * 4;
    const int nr = nin > nout ? nin : nout, hx = t->hx;
    double *rows = mc_malloc((size_t)nr * tx * sizeof *rows);
    fftw_complex *spec = mc_malloc(t->speclen * sizeof *spec);
    if (!rows || !spec) {
        mc_free(rows);
        mc_free(spec);
        return mc_fail(err, MC_ERR_NOMEM, "eigen FFT %d x %d: out of memory", tx, ty);
    }
    /* planned on scratch freed below (MEASURE overwrites its arrays); each plan runs
     * single-threaded on many arrays of the same alignment (new-array execute) from the callers'
     * parallel loops; repeated transforms: [solver] plans (operator/operator.h) */
    const unsigned rep = mc_fft_plan_flags();
    fftw_plan_with_nthreads(1);
    int nrow[1] = {tx}, ncol[1] = {ty};
    t->row_r2c = fftw_plan_many_dft_r2c(1, nrow, nin, rows, NULL, 1, tx,
                                        spec + (size_t)row0 * hx, NULL, 1, hx, rep);
    t->col_fwd = fftw_plan_many_dft(1, ncol, hx, spec, NULL, hx, 1, spec, NULL, hx, 1,
                                    FFTW_FORWARD, rep);
    t->col_bwd = fftw_plan_many_dft(1, ncol, hx, spec, NULL, hx, 1, spec, NULL, hx, 1,
                                    FFTW_BACKWARD, rep);
    t->row_c2r = fftw_plan_many_dft_c2r(1, nrow, nout, spec, NULL, 1, hx, rows, NULL, 1, tx,
                                        rep);
    mc_free(rows);
    mc_free(spec);
    if (!t->row_r2c || !t->col_fwd || !t->col_bwd || !t->row_c2r) {
        mc_eig_fft_destroy(t);
        return mc_fail(err, MC_ERR_NOMEM, "eigen FFT: FFTW could not plan %d x %d", tx, ty);
    }
    return MC_OK;
}

void mc_eig_fft_forward(const mc_eig_fft *t, double *rows, fftw_complex *spec)
{
    const size_t hx = (size_t)t->hx;
    /* the zero rows are not transformed along x: their half spectrum rows are zero */
    memset(spec, 0, (size_t)t->row0 * hx * sizeof *spec);
    memset(spec + (size_t)(t->row0 + t->nin) * hx, 0,
           (size_t)(t->ty - t->row0 - t->nin) * hx * sizeof *spec);
    fftw_execute_dft_r2c(t->row_r2c, rows, spec + (size_t)t->row0 * hx);
    fftw_execute_dft(t->col_fwd, spec, spec);
}

void mc_eig_fft_inverse(const mc_eig_fft *t, fftw_complex *spec, double *rows)
{
    fftw_execute_dft(t->col_bwd, spec, spec);
    fftw_execute_dft_c2r(t->row_c2r, spec, rows);
}

void mc_eig_fill_rows(double *rows, int tx, const double *field, int nx, int nrows, int col0)
{
    for (int j = 0; j < nrows; j++) {
        double *r = rows + (size_t)j * tx;
        memset(r, 0, (size_t)col0 * sizeof *r);
        memcpy(r + col0, field + (size_t)j * nx, (size_t)nx * sizeof *r);
        memset(r + col0 + nx, 0, (size_t)(tx - col0 - nx) * sizeof *r);
    }
}

/* the first entry of s whose cell is not below at */
static long sparse_lower(const mc_eigen_sparse *s, long at)
{
    long lo = 0, hi = s->n;
    while (lo < hi) {
        const long mid = lo + (hi - lo) / 2;
        if (s->cell[mid] < at)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

void mc_eigen_sparse_range(const mc_eigen_sparse *s, long first, long last, long *k0, long *k1)
{
    *k0 = sparse_lower(s, first);
    *k1 = sparse_lower(s, last);
}
