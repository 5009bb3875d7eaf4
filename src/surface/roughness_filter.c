/* roughness_filter.c - ISO 16610-21 Gaussian profile filter and ISO 4288 cut-off table
 * (see roughness.h; theory.md §13.1-§13.2). */
#include "surface/roughness.h"

#include <fftw3.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "core/threads.h"

#define DEN_MIN 1e-12 /* kernel weight below which an (invalid) point has no mean line */

int mc_roughness_filter_halfwidth(double d, double lambda_c)
{
    double k = floor(lambda_c / d + 1e-9); /* a cut-off of exactly m spacings gives m */
    return k > 1e8 ? 100000000 : (int)k;
}

/* One line filter: circular convolution of length N by r2c/c2r with a real transfer function
 * H (already divided by N). Non-periodic lines are zero-padded to N >= n + K, so the circular
 * wrap never mixes the two ends: the result is the linear convolution with the truncated
 * kernel and zero extension. */
typedef struct {
    int n, N;
    double *H, *buf;
    fftw_complex *spec;
    fftw_plan fwd, inv;
} line_filter;

static void line_filter_free(line_filter *f)
{
    if (f->fwd)
        fftw_destroy_plan(f->fwd);
    if (f->inv)
        fftw_destroy_plan(f->inv);
    mc_free(f->H);
    mc_free(f->buf);
    mc_free(f->spec);
    memset(f, 0, sizeof *f);
}

static void line_filter_run(line_filter *f, const double *in, double *out)
{
    memcpy(f->buf, in, sizeof(double) * (size_t)f->n);
    memset(f->buf + f->n, 0, sizeof(double) * (size_t)(f->N - f->n));
    fftw_execute(f->fwd);
    for (int m = 0; m <= f->N / 2; m++) {
        f->spec[m][0] *= f->H[m];
        f->spec[m][1] *= f->H[m];
    }
    fftw_execute(f->inv);
    memcpy(out, f->buf, sizeof(double) * (size_t)f->n);
}

static int line_filter_make(line_filter *f, int n, double d, double lc, int periodic,
                            mc_error *err)
{
    memset(f, 0, sizeof *f);
    /* offsets beyond n - 1 never meet a sample of the line: leave them out */
    int K = mc_roughness_filter_halfwidth(d, lc);
    if (K > n - 1)
        K = n - 1;
    f->n = n;
    f->N = periodic ? n : mc_fftsize_good(n + K);
    int half = f->N / 2 + 1;
    f->H = mc_malloc(sizeof(double) * (size_t)half);
    f->buf = mc_malloc(sizeof(double) * (size_t)f->N);
    f->spec = mc_malloc(sizeof(fftw_complex) * (size_t)half);
    if (!f->H || !f->buf || !f->spec) {
        line_filter_free(f);
        return mc_fail(err, MC_ERR_NOMEM, "Gaussian filter: out of memory for a line of %d", n);
    }
    int rc = mc_fftw_prepare(err);
    if (rc) {
        line_filter_free(f);
        return rc;
    }
    fftw_plan_with_nthreads(1); /* one line: a thread team costs more than it saves */
    f->fwd = fftw_plan_dft_r2c_1d(f->N, f->buf, f->spec, FFTW_ESTIMATE);
    f->inv = fftw_plan_dft_c2r_1d(f->N, f->spec, f->buf, FFTW_ESTIMATE);
    mc_fftw_prepare(NULL); /* the run's thread count again */
    if (!f->fwd || !f->inv) {
        line_filter_free(f);
        return mc_fail(err, MC_ERR_INTERNAL, "Gaussian filter: FFTW could not plan length %d",
                       f->N);
    }
    const double al = MC_ROUGHNESS_ALPHA * lc;
    if (periodic) { /* exact transmission of harmonic m, wavelength n d / m */
        for (int m = 0; m < half; m++) {
            double t = al * m / (n * d);
            f->H[m] = exp(-M_PI * t * t) / f->N;
        }
        return MC_OK;
    }
    /* sampled kernel, truncated at +-K samples, unit sum; its (real, even) spectrum is H */
    memset(f->buf, 0, sizeof(double) * (size_t)f->N);
    double sum = 0;
    for (int k = -K; k <= K; k++) {
        double t = k * d / al, s = exp(-M_PI * t * t);
        f->buf[(k + f->N) % f->N] += s;
        sum += s;
    }
    for (int k = 0; k < f->N; k++)
        f->buf[k] /= sum;
    fftw_execute(f->fwd);
    for (int m = 0; m < half; m++)
        f->H[m] = f->spec[m][0] / f->N;
    return MC_OK;
}

int mc_roughness_mean_line(const double *z, const unsigned char *valid, int nx, int ny,
                           double dx, double lambda_c, int periodic, double *w, mc_error *err)
{
    if (nx < 1 || ny < 1)
        return mc_fail(err, MC_ERR_INPUT, "Gaussian filter: %d x %d points, both must be >= 1",
                       nx, ny);
    if (!(dx > 0 && isfinite(dx)) || !(lambda_c > 0 && isfinite(lambda_c)))
        return mc_fail(err, MC_ERR_INPUT, "Gaussian filter: spacing %g m and cut-off %g m must "
                       "be finite and > 0", dx, lambda_c);
    line_filter f;
    int rc = line_filter_make(&f, nx, dx, lambda_c, periodic, err);
    if (rc)
        return rc;
    double *num = mc_malloc(sizeof(double) * (size_t)nx), *den = mc_zeros((size_t)nx);
    double *ones = mc_malloc(sizeof(double) * (size_t)nx);
    if (!num || !den || !ones) {
        rc = mc_fail(err, MC_ERR_NOMEM, "Gaussian filter: out of memory for a line of %d", nx);
        goto out;
    }
    for (int i = 0; i < nx; i++)
        ones[i] = 1.0;
    line_filter_run(&f, ones, ones); /* kernel weight each point sees when all are valid */
    for (int j = 0; j < ny; j++) {
        const double *zr = z + (size_t)j * nx;
        const unsigned char *vr = valid ? valid + (size_t)j * nx : NULL;
        double *wr = w + (size_t)j * nx;
        int all = 1;
        for (int i = 0; vr && i < nx; i++)
            all &= vr[i] != 0;
        if (all) {
            line_filter_run(&f, zr, num);
            for (int i = 0; i < nx; i++)
                wr[i] = num[i] / ones[i];
            continue;
        }
        for (int i = 0; i < nx; i++) { /* normalised convolution: invalid samples weigh 0 */
            num[i] = vr[i] ? zr[i] : 0.0;
            den[i] = vr[i] ? 1.0 : 0.0;
        }
        line_filter_run(&f, num, num);
        line_filter_run(&f, den, den);
        for (int i = 0; i < nx; i++)
            wr[i] = den[i] > DEN_MIN ? num[i] / den[i] : 0.0;
    }
out:
    mc_free(num);
    mc_free(den);
    mc_free(ones);
    line_filter_free(&f);
    return rc;
}

/* ---- ISO 4288 ---------------------------------------------------------------------------- */

/* Upper bounds (inclusive) of the parameter classes, um; lower bound of the first class. */
static const double RA_HI[5] = {0.02, 0.1, 2.0, 10.0, 80.0}, RA_LO = 0.006;
static const double RZ_HI[5] = {0.1, 0.5, 10.0, 50.0, 200.0}, RZ_LO = 0.025;
static const double CUTOFF_MM[5] = {0.08, 0.25, 0.8, 2.5, 8.0};
#define TABLE_SLACK 1e-9

static double table_cutoff(double v, const double hi[5], double lo, int *in_table)
{
    double um = v * 1e6;
    int row = 4;
    for (int r = 0; r < 5; r++)
        if (um <= hi[r] * (1 + TABLE_SLACK)) {
            row = r;
            break;
        }
    if (in_table)
        *in_table = um > lo * (1 + TABLE_SLACK) && um <= hi[4] * (1 + TABLE_SLACK);
    return CUTOFF_MM[row] * 1e-3;
}

double mc_iso4288_cutoff_ra(double ra, int *in_table)
{
    return table_cutoff(ra, RA_HI, RA_LO, in_table);
}

double mc_iso4288_cutoff_rz(double rz, int *in_table)
{
    return table_cutoff(rz, RZ_HI, RZ_LO, in_table);
}
