/* surface.c - shapes, synthetic roughness and statistics (see surface.h). */
#include "surface/surface.h"

#include "operator/operator.h"

#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "io/heightmap.h"

/* ---- random numbers ---------------------------------------------------------------------- */

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void mc_rng_seed(mc_rng *r, uint64_t seed)
{
    uint64_t x = seed;
    for (int k = 0; k < 4; k++)
        r->s[k] = splitmix64(&x); /* never all zero: splitmix64 is a bijection of distinct x */
    r->spare = 0.0;
    r->has_spare = 0;
}

uint64_t mc_rng_next(mc_rng *r)
{
    uint64_t *s = r->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double mc_rng_uniform(mc_rng *r) { return (double)(mc_rng_next(r) >> 11) * 0x1.0p-53; }

double mc_rng_normal(mc_rng *r)
{
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    double u1 = 1.0 - mc_rng_uniform(r); /* (0, 1]: log stays finite */
    double u2 = mc_rng_uniform(r);
    double rad = sqrt(-2.0 * log(u1));
    double th = 2.0 * M_PI * u2;
    r->spare = rad * sin(th);
    r->has_spare = 1;
    return rad * cos(th);
}

/* ---- shapes ------------------------------------------------------------------------------ */

void mc_surface_shape(const mc_grid *g, const mc_shape_spec *s, double *h)
{
    for (int j = 0; j < g->ny; j++) {
        double y = mc_grid_y(g, j);
        for (int i = 0; i < g->nx; i++) {
            double x = mc_grid_x(g, i), v = 0.0;
            switch (s->shape) {
            case MC_SHAPE_FLAT: v = 0.0; break;
            case MC_SHAPE_SPHERE: v = (x * x + y * y) / (2.0 * s->radius); break;
            case MC_SHAPE_CYLINDER: v = x * x / (2.0 * s->radius); break;
            case MC_SHAPE_ELLIPSOID:
                v = x * x / (2.0 * s->radius_x) + y * y / (2.0 * s->radius_y);
                break;
            }
            h[(size_t)j * (size_t)g->nx + (size_t)i] = v;
        }
    }
}

/* ---- spectral synthesis ------------------------------------------------------------------ */

typedef struct {
    int self_affine;
    double lx, ly;          /* gaussian correlation lengths */
    double q_long, q_short; /* self-affine band */
    double expo;            /* -2(1 + H) */
} psd_params;

/* Band edges are compared with a relative slack so that a cut-off placed exactly on a grid
 * wavenumber (e.g. the Nyquist default) keeps that mode despite rounding of sqrt. */
#define BAND_SLACK 1e-12

static double psd(const psd_params *p, double qx, double qy)
{
    if (!p->self_affine)
        return exp(-0.25 * (qx * p->lx * qx * p->lx + qy * p->ly * qy * p->ly));
    double q = sqrt(qx * qx + qy * qy);
    if (q == 0.0 || q > p->q_short * (1.0 + BAND_SLACK))
        return 0.0;
    if (q < p->q_long * (1.0 - BAND_SLACK))
        q = p->q_long;
    return pow(q, p->expo);
}

/* Fill h with the filtered noise, zero mean, scaled to rq (slope = 0) or to the rms slope. */
static int synthesize(const mc_grid *g, uint64_t seed, const psd_params *p, double rq, double slope,
                      double *h, mc_error *err)
{
    int nx = g->nx, ny = g->ny, nxh = nx / 2 + 1;
    size_t n = mc_grid_cells(g), nspec = (size_t)ny * (size_t)nxh;
    double *w = mc_malloc(n * sizeof(double));
    fftw_complex *W = mc_malloc(nspec * sizeof(fftw_complex));
    if (!w || !W) {
        mc_free(w);
        mc_free(W);
        return mc_fail(err, MC_ERR_NOMEM, "roughness: no memory for a %d x %d spectrum", ny, nx);
    }
    /* ESTIMATE plans do not touch the arrays and are the same on every run; one thread, so the
     * surface of a seed does not depend on the thread count either. */
    int prep = mc_fftw_prepare(err);
    if (prep != MC_OK) {
        mc_free(w);
        mc_free(W);
        return prep;
    }
    fftw_plan_with_nthreads(1);
    fftw_plan fwd = fftw_plan_dft_r2c_2d(ny, nx, w, W, FFTW_ESTIMATE);
    fftw_plan bwd = fftw_plan_dft_c2r_2d(ny, nx, W, w, FFTW_ESTIMATE);
    mc_fftw_prepare(NULL); /* back to the configured thread count */
    if (!fwd || !bwd) {
        if (fwd)
            fftw_destroy_plan(fwd);
        if (bwd)
            fftw_destroy_plan(bwd);
        mc_free(w);
        mc_free(W);
        return mc_fail(err, MC_ERR_INTERNAL, "roughness: FFTW planning failed for %d x %d", ny, nx);
    }
    mc_rng rng;
    mc_rng_seed(&rng, seed);
    for (size_t k = 0; k < n; k++)
        w[k] = mc_rng_normal(&rng);
    fftw_execute(fwd);

    /* Parseval over the full spectrum: a half-spectrum column other than 0 and nx/2 (nx even)
     * stands for itself and its mirror. */
    double sum_h2 = 0.0, sum_g2 = 0.0;
    for (int j = 0; j < ny; j++) {
        int jj = j <= ny / 2 ? j : j - ny;
        double qy = 2.0 * M_PI * jj / (ny * g->dy);
        for (int i = 0; i < nxh; i++) {
            double qx = 2.0 * M_PI * i / (nx * g->dx);
            size_t k = (size_t)j * (size_t)nxh + (size_t)i;
            double f = sqrt(psd(p, qx, qy));
            if (i == 0 && j == 0)
                f = 0.0;
            W[k][0] *= f;
            W[k][1] *= f;
            double m = (i == 0 || (nx % 2 == 0 && i == nx / 2)) ? 1.0 : 2.0;
            double a2 = m * (W[k][0] * W[k][0] + W[k][1] * W[k][1]);
            sum_h2 += a2;
            sum_g2 += a2 * (qx * qx + qy * qy);
        }
    }
    fftw_execute(bwd); /* unnormalised: w = n * (field with spectrum W / n) */
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(bwd);
    mc_free(W);

    double mean = 0.0;
    for (size_t k = 0; k < n; k++)
        mean += w[k];
    mean /= (double)n;
    double ss = 0.0;
    for (size_t k = 0; k < n; k++) {
        w[k] -= mean;
        ss += w[k] * w[k];
    }
    double rms = sqrt(ss / (double)n);
    if (!(sum_h2 > 0.0) || !(rms > 0.0)) {
        mc_free(w);
        return mc_fail(err, MC_ERR_INPUT,
                       "[roughness]: the spectrum has no non-zero mode on this %d x %d grid "
                       "(check the cut-off wavelengths against the grid size and spacing)",
                       ny, nx);
    }
    /* slope of w: the unnormalised c2r output has rms gradient sqrt(sum_g2) (Parseval / n^2,
     * times n). */
    double scale = slope > 0.0 ? slope / sqrt(sum_g2) : rq / rms;
    for (size_t k = 0; k < n; k++)
        h[k] = scale * w[k];
    mc_free(w);
    return MC_OK;
}

static int finite_nonneg(double v) { return isfinite(v) && v >= 0.0; }

void mc_surface_measured_spec(const mc_roughness_spec *s, mc_measured_spec *out)
{
    static const double unit_m[] = {1.0, 1e-3, 1e-6, 1e-9};
    memset(out, 0, sizeof *out);
    out->path = s->file;
    out->format = (mc_surface_format)s->format;
    out->units = s->units >= 0 && s->units < 4 ? unit_m[s->units] : 1.0;
    out->verify_checksum = s->verify_checksum;
    out->has_region = s->has_region;
    memcpy(out->region, s->region, sizeof out->region);
    out->missing = (mc_missing_rule)s->missing;
    out->detrend = (mc_detrend_kind)s->detrend;
    out->scale = s->scale;
    out->invert = s->invert;
}

/* synthesize's messages start "[roughness]: "; another section's name replaces it. */
static int relabel(int rc, const char *label, mc_error *err)
{
    static const char tag[] = "[roughness]:";
    if (rc != MC_OK && err && strcmp(label, "[roughness]") != 0 &&
        strncmp(err->msg, tag, sizeof tag - 1) == 0) {
        const size_t drop = sizeof tag - 2; /* keep the ':' */
        memmove(err->msg, err->msg + drop, strlen(err->msg + drop) + 1);
        mc_error_prefix(err, "%s", label);
    }
    return rc;
}

/* mc_surface_roughness with the messages naming label ("[roughness]", "[roughness2]"). */
static int roughness_as(const mc_grid *g, const mc_roughness_spec *s, const char *label,
                        double *heights, mc_error *err)
{
    size_t n = mc_grid_cells(g);
    int st = mc_grid_check(g, err);
    if (st != MC_OK)
        return st;
    psd_params p;
    memset(&p, 0, sizeof p);
    switch (s->type) {
    case MC_ROUGH_NONE:
        memset(heights, 0, n * sizeof(double));
        return MC_OK;
    case MC_ROUGH_FILE: {
        mc_measured_spec ms;
        mc_measured m;
        mc_surface_measured_spec(s, &ms);
        ms.label = label;
        st = mc_measured_load(&ms, &m, err);
        if (st == MC_OK)
            st = mc_measured_onto(&m, g, (mc_resample_rule)s->resample, heights, err);
        mc_measured_free(&m);
        if (st != MC_OK && err)
            mc_error_prefix(err, "%s file: ", label);
        return st;
    }
    case MC_ROUGH_GAUSSIAN:
        if (!finite_nonneg(s->rq) || !finite_nonneg(s->correlation_x) ||
            !finite_nonneg(s->correlation_y))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s gaussian: rq = %g m, correlation_x = %g m, correlation_y = "
                           "%g m: each must be finite and >= 0",
                           label, s->rq, s->correlation_x, s->correlation_y);
        if (s->rq == 0.0) {
            memset(heights, 0, n * sizeof(double));
            return MC_OK;
        }
        p.lx = s->correlation_x;
        p.ly = s->correlation_y;
        return relabel(synthesize(g, s->seed, &p, s->rq, 0.0, heights, err), label, err);
    case MC_ROUGH_SELF_AFFINE: {
        if (!finite_nonneg(s->rq) || !finite_nonneg(s->rms_slope))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s self_affine: rq = %g m, rms_slope = %g: each must be "
                           "finite and >= 0",
                           label, s->rq, s->rms_slope);
        if (!(s->hurst >= 0.0 && s->hurst <= 1.0))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s self_affine: hurst = %g: must be in 0..1", label,
                           s->hurst);
        if (!finite_nonneg(s->lambda_long) || !finite_nonneg(s->lambda_short))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s self_affine: lambda_long = %g m, lambda_short = %g m: each "
                           "must be finite and >= 0 (0 = automatic)",
                           label, s->lambda_long, s->lambda_short);
        double Lx = g->nx * g->dx, Ly = g->ny * g->dy;
        double ll = s->lambda_long > 0 ? s->lambda_long : fmax(Lx, Ly);
        double ls = s->lambda_short > 0 ? s->lambda_short
                                                   : 2.0 * fmax(g->dx, g->dy);
        if (!(ls < ll))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s self_affine: lambda_short = %g m must be below "
                           "lambda_long = %g m",
                           label, ls, ll);
        if (s->rq == 0.0 && s->rms_slope == 0.0) {
            memset(heights, 0, n * sizeof(double));
            return MC_OK;
        }
        p.self_affine = 1;
        p.q_long = 2.0 * M_PI / ll;
        p.q_short = 2.0 * M_PI / ls;
        p.expo = -2.0 * (1.0 + s->hurst);
        return relabel(synthesize(g, s->seed, &p, s->rq, s->rms_slope, heights, err), label,
                       err);
    }
    }
    return mc_fail(err, MC_ERR_INPUT, "%s: unknown type %d", label, (int)s->type);
}

int mc_surface_roughness(const mc_grid *g, const mc_roughness_spec *s, double *heights,
                         mc_error *err)
{
    return roughness_as(g, s, "[roughness]", heights, err);
}

int mc_surface_roughness_labelled(const mc_grid *g, const mc_roughness_spec *s, const char *label,
                                  double *heights, mc_error *err)
{
    return roughness_as(g, s, label ? label : "[roughness]", heights, err);
}

int mc_surface_topography(const mc_grid *g, const mc_shape_spec *shape,
                          const mc_roughness_spec *rough_spec, double *topo, mc_error *err)
{
    int st = mc_grid_check(g, err);
    if (st != MC_OK)
        return st;
    size_t n = mc_grid_cells(g);
    double *rough = mc_zeros(n);
    if (!rough)
        return mc_fail(err, MC_ERR_NOMEM, "topography: no memory for %d x %d heights", g->ny,
                       g->nx);
    st = mc_surface_roughness(g, rough_spec, rough, err);
    if (st == MC_OK) {
        mc_surface_shape(g, shape, topo);
        for (size_t k = 0; k < n; k++)
            topo[k] -= rough[k];
    }
    mc_free(rough);
    return st;
}

/* ---- statistics -------------------------------------------------------------------------- */

/* Central difference of f along an axis of n samples with stride, spacing d, at index a. */
static double diff(const double *f, int a, int n, size_t stride, double d, int periodic)
{
    if (n < 2)
        return 0.0;
    int lo = a - 1, hi = a + 1;
    double span = 2.0 * d;
    if (periodic) {
        lo = (lo + n) % n;
        hi = hi % n;
    } else {
        if (lo < 0) {
            lo = a;
            span = d;
        }
        if (hi >= n) {
            hi = a;
            span = d;
        }
    }
    return (f[(size_t)hi * stride] - f[(size_t)lo * stride]) / span;
}

void mc_surface_statistics(const mc_grid *g, const double *heights, mc_surface_stats *st)
{
    size_t n = mc_grid_cells(g), nx = (size_t)g->nx;
    memset(st, 0, sizeof *st);
    if (n == 0)
        return;
    double mean = 0.0;
    for (size_t k = 0; k < n; k++)
        mean += heights[k];
    mean /= (double)n;
    double s1 = 0, s2 = 0, s3 = 0, s4 = 0, gx = 0, gy = 0;
    for (int j = 0; j < g->ny; j++) {
        for (int i = 0; i < g->nx; i++) {
            size_t k = (size_t)j * nx + (size_t)i;
            double d = heights[k] - mean, d2 = d * d;
            s1 += fabs(d);
            s2 += d2;
            s3 += d2 * d;
            s4 += d2 * d2;
            double sx = diff(heights + (size_t)j * nx, i, g->nx, 1, g->dx, g->periodic_x);
            double sy = diff(heights + (size_t)i, j, g->ny, nx, g->dy, g->periodic_y);
            gx += sx * sx;
            gy += sy * sy;
        }
    }
    double dn = (double)n;
    st->mean = mean;
    st->ra = s1 / dn;
    st->rq = sqrt(s2 / dn);
    st->rms_slope_x = sqrt(gx / dn);
    st->rms_slope_y = sqrt(gy / dn);
    if (st->rq > 0.0) {
        double v = s2 / dn;
        st->skewness = (s3 / dn) / (v * st->rq);
        st->kurtosis = (s4 / dn) / (v * v);
    }
}
