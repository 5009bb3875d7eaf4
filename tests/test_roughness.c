/* test_roughness.c - Gaussian profile filter, ISO 4288 choice, profile, Rk and areal
 * parameters against analytic surfaces (roughness*.c; theory.md §13). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface/roughness.h"
#include "test_util.h"

/* Transmission of the truncated, sampled kernel against the ideal Gaussian: the weight cut off
 * beyond +-lambda_c is erfc(sqrt(pi)/alpha) = 1.6e-7, so the transfer function differs from the
 * ideal one by at most about twice that plus the sampling error (negligible at >= 100 samples
 * per cut-off); 1e-6 leaves a margin and is still 100 times tighter than the dossier's 1e-4. */
#define TOL_TRUNCATION 1e-6

static void sine_rows(double *z, int nx, int ny, double dx, double amp, double lambda)
{
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            z[(size_t)j * nx + i] = amp * sin(2 * M_PI * i * dx / lambda);
}

/* Standard normal values (Box-Muller on test_random_field's uniforms). */
static void normal_field(double *z, size_t n, unsigned long long seed)
{
    double *u = malloc(sizeof(double) * (n + 1));
    ck_assert(u != NULL);
    test_random_field(u, n + 1, seed);
    for (size_t k = 0; k < n; k += 2) {
        double u1 = 0.5 * (u[k] + 1.0), u2 = 0.5 * (u[k + 1] + 1.0);
        double rad = sqrt(-2.0 * log(1.0 - u1)); /* 1 - u1 in (0, 1] */
        z[k] = rad * cos(2 * M_PI * u2);
        if (k + 1 < n)
            z[k + 1] = rad * sin(2 * M_PI * u2);
    }
    free(u);
}

static mc_roughness_params compute(const double *z, const unsigned char *v, int nx, int ny,
                                   double dx, double dy, double cutoff, int px, int filter)
{
    mc_roughness_options o;
    mc_roughness_options_default(&o);
    o.cutoff = cutoff;
    o.periodic_x = px;
    o.periodic_y = px;
    o.filter = filter;
    mc_roughness_params p;
    mc_error err = {0};
    int rc = mc_roughness_compute(z, v, nx, ny, dx, dy, &o, &p, &err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
    return p;
}

/* ---- sine profile: Ra = 2A/pi, Rq = A/sqrt2, Rsk = 0, Rku = 1.5, Rp = Rv = A, Rz = Rt = 2A */

START_TEST(test_sine_profile)
{
    const int periodic = _i, N = 256; /* samples per wavelength, a multiple of 4: peaks sampled */
    const double A = 1e-6, dx = 0.5e-6, lambda = N * dx, lc = 8 * lambda;
    const int K = (int)(lc / dx), nx = periodic ? 5 * K : 7 * K, ny = 2;
    double *z = malloc(sizeof(double) * nx * ny);
    sine_rows(z, nx, ny, dx, A, lambda);
    mc_roughness_params p = compute(z, NULL, nx, ny, dx, dx, lc, periodic, 1);
    /* |sin| sampled N times per period averages to (2/N) cot(pi/N), not 2/pi: the kink at the
     * zero crossings costs pi^2/(3 N^2) = 5.0e-5 relative. The other moments of a sampled sine
     * are exact over whole periods. What remains is the filter's leakage at lambda_c/8: ideal
     * 2^-64, truncated kernel TOL_TRUNCATION. */
    const double ra_disc = A * 2.0 / N / tan(M_PI / N), tol = A * TOL_TRUNCATION;
    printf("sine (%s): Ra/(2A/pi) - 1 = %.3e (sampling bound %.3e), Rq %.2e, Rku %.2e, "
           "Rp %.2e, Rz %.2e relative errors\n", periodic ? "periodic" : "free",
           p.Ra / (2 * A / M_PI) - 1, M_PI * M_PI / (3.0 * N * N), p.Rq / (A / M_SQRT2) - 1,
           p.Rku / 1.5 - 1, p.Rp / A - 1, p.Rz / (2 * A) - 1);
    ck_assert_double_eq_tol(p.Ra, ra_disc, tol);
    ck_assert_double_le(fabs(p.Ra / (2 * A / M_PI) - 1), M_PI * M_PI / (3.0 * N * N) * 1.01);
    ck_assert_double_eq_tol(p.Rq, A / M_SQRT2, tol);
    ck_assert_double_eq_tol(p.Rsk, 0.0, TOL_TRUNCATION);
    ck_assert_double_eq_tol(p.Rku, 1.5, TOL_TRUNCATION);
    ck_assert_double_eq_tol(p.Rp, A, tol);
    ck_assert_double_eq_tol(p.Rv, A, tol);
    ck_assert_double_eq_tol(p.Rz, 2 * A, 2 * tol);
    ck_assert_double_eq_tol(p.Rt, 2 * A, 2 * tol);
    ck_assert_int_eq(p.n_sampling, 5);
    ck_assert_int_eq(p.rows, ny);
    ck_assert_double_eq_tol(p.evaluation_length, 5 * lc, TOL_ROUNDOFF * lc);
    ck_assert_msg(p.warning[0] == 0 && !p.cutoff_clipped && !p.short_evaluation, "%s",
                  p.warning);
    free(z);
}
END_TEST

/* ---- filter transmission: exp(-pi (alpha lambda_c / lambda)^2), 50 % at lambda_c ---------- */

START_TEST(test_transmission)
{
    const int periodic = _i, nx = 12800;
    const double dx = 1e-6, lc = 800e-6, A = 1e-6;
    const double ratio[] = {1.0, 0.25, 0.5, 2.0, 4.0}; /* lambda / lambda_c */
    double *z = malloc(sizeof(double) * nx), *w = malloc(sizeof(double) * nx);
    for (int c = 0; c < 5; c++) {
        double lambda = ratio[c] * lc;
        int per = (int)lround(lambda / dx);
        sine_rows(z, nx, 1, dx, A, lambda);
        mc_error err = {0};
        ck_assert_int_eq(mc_roughness_mean_line(z, NULL, nx, 1, dx, lc, periodic, w, &err), 0);
        /* amplitude by projection on sin and cos over whole periods inside the region where
         * the non-periodic kernel is whole */
        int K = periodic ? 0 : mc_roughness_filter_halfwidth(dx, lc);
        int m = ((nx - 2 * K) / per) * per;
        double s = 0, co = 0;
        for (int i = K; i < K + m; i++) {
            s += w[i] * sin(2 * M_PI * i / per);
            co += w[i] * cos(2 * M_PI * i / per);
        }
        double amp = 2.0 / m * hypot(s, co) / A;
        double t = MC_ROUGHNESS_ALPHA / ratio[c], ideal = exp(-M_PI * t * t);
        printf("transmission (%s) at lambda = %.2f lambda_c: %.8f, ideal %.8f, error %.2e\n",
               periodic ? "periodic" : "free", ratio[c], amp, ideal, amp - ideal);
        ck_assert_double_eq_tol(amp, ideal, periodic ? TOL_ROUNDOFF : TOL_TRUNCATION);
        if (ratio[c] == 1.0)
            ck_assert_double_eq_tol(amp, 0.5, periodic ? TOL_ROUNDOFF : TOL_TRUNCATION);
    }
    /* far from the cut-off: the roughness keeps ~100 % at lambda_c/4 and ~0 % at 4 lambda_c */
    ck_assert_double_lt(exp(-M_PI * pow(MC_ROUGHNESS_ALPHA / 0.25, 2)), 2e-5);
    ck_assert_double_gt(exp(-M_PI * pow(MC_ROUGHNESS_ALPHA / 4.0, 2)), 0.95);
    free(z);
    free(w);
}
END_TEST

/* ---- the mean line of a constant is that constant, at the ends and next to gaps -------- */

START_TEST(test_mean_line_constant)
{
    /* the kernel is renormalised over the samples it covers (ends of a free row, invalid
     * points), so a level stays a level everywhere */
    const int periodic = _i, nx = 500, ny = 4;
    const double dx = 1e-6, lc = 80e-6, c = 3e-6;
    double *z = malloc(sizeof(double) * nx * ny), *w = malloc(sizeof(double) * nx * ny);
    unsigned char *v = malloc((size_t)nx * ny);
    for (int k = 0; k < nx * ny; k++) {
        v[k] = (k % 10) != 3 && !(k > 1100 && k < 1200); /* 10 % scattered plus a gap */
        z[k] = v[k] ? c : NAN;
    }
    mc_error err = {0};
    for (int pass = 0; pass < 2; pass++) {
        int masked = pass == 0; /* with the gaps first, then all points valid */
        ck_assert_int_eq(mc_roughness_mean_line(z, masked ? v : NULL, nx, ny, dx, lc, periodic,
                                                w, &err), 0);
        for (int k = 0; k < nx * ny; k++)
            if (!masked || v[k])
                ck_assert_double_eq_tol(w[k], c, TOL_ROUNDOFF * c);
        for (int k = 0; k < nx * ny; k++) /* for the unmasked pass: every point a level */
            z[k] = c;
    }
    free(z);
    free(w);
    free(v);
}
END_TEST

/* ---- periodic filtering discards nothing and commutes with circular shifts --------------- */

START_TEST(test_periodic_nothing_discarded)
{
    const int nx = 1000, ny = 3, shift = 137;
    const double dx = 1e-6, lc = 250e-6;
    double *z = malloc(sizeof(double) * nx * ny), *zs = malloc(sizeof(double) * nx * ny);
    double *w = malloc(sizeof(double) * nx * ny), *ws = malloc(sizeof(double) * nx * ny);
    test_random_field(z, (size_t)nx * ny, 11);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            zs[j * nx + (i + shift) % nx] = z[j * nx + i];
    mc_error err = {0};
    ck_assert_int_eq(mc_roughness_mean_line(z, NULL, nx, ny, dx, lc, 1, w, &err), 0);
    ck_assert_int_eq(mc_roughness_mean_line(zs, NULL, nx, ny, dx, lc, 1, ws, &err), 0);
    double d = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            d = test_worst(d, fabs(ws[j * nx + (i + shift) % nx] - w[j * nx + i]));
    ck_assert_double_le(d, TOL_ROUNDOFF); /* no end is treated differently */
    mc_roughness_params pp = compute(z, NULL, nx, ny, dx, dx, lc, 1, 1);
    mc_roughness_params pf = compute(z, NULL, nx, ny, dx, dx, lc, 0, 1);
    ck_assert_double_eq(pp.evaluation_length, nx * dx);
    ck_assert_int_eq(pp.n_sampling, 4); /* 1000 um / 250 um */
    ck_assert_double_eq_tol(pf.evaluation_length, (nx - 2 * 250) * dx, TOL_ROUNDOFF * dx);
    free(z);
    free(zs);
    free(w);
    free(ws);
}
END_TEST

/* ---- Gaussian heights: Ra/Rq = sqrt(2/pi), Rku = 3 --------------------------------------- */

START_TEST(test_gaussian_heights)
{
    const int nx = 10000, ny = 100;
    const double dx = 1e-6, lc = 100e-6;
    double *z = malloc(sizeof(double) * nx * ny);
    normal_field(z, (size_t)nx * ny, 5);
    mc_roughness_params p = compute(z, NULL, nx, ny, dx, dx, lc, 0, 1);
    /* n independent normal values: Ra/Rq has relative standard error sqrt(0.0708/n) (delta
     * method: var|z| = 1 - 2/pi, var z^2 = 2, cov(|z|, z^2) = sqrt(2/pi)), the kurtosis
     * sqrt(24/n), the skewness sqrt(6/n). The filter removes only waves longer than lambda_c
     * = 100 samples (a fraction ~1/(alpha 100) of the variance) and keeps the values
     * Gaussian. 5 standard errors. The per-row kurtosis estimator's bias, -6/n_row = -6e-4, is
     * inside that. */
    double n = (double)p.rows * (p.evaluation_length / dx);
    double ratio = p.Ra / p.Rq, want = sqrt(2 / M_PI);
    printf("gaussian profiles (n = %.0f): Ra/Rq %.5f (%.5f), Rku %.4f, Rsk %.4f; areal Sa/Sq "
           "%.5f, Sku %.4f\n", n, ratio, want, p.Rku, p.Rsk, p.Sa / p.Sq, p.Sku);
    ck_assert_double_le(fabs(ratio / want - 1), 5 * sqrt(0.0708 / n));
    ck_assert_double_le(fabs(p.Rku - 3), 5 * sqrt(24 / n));
    ck_assert_double_le(fabs(p.Rsk), 5 * sqrt(6 / n));
    double na = (double)p.points; /* areal: unfiltered, all points */
    ck_assert_double_le(fabs(p.Sa / p.Sq / want - 1), 5 * sqrt(0.0708 / na));
    ck_assert_double_le(fabs(p.Sku - 3), 5 * sqrt(24 / na));
    free(z);
}
END_TEST

/* ---- ISO 13565-2 ------------------------------------------------------------------------- */

START_TEST(test_rk_triangle)
{
    /* triangle wave: heights uniform on [-A, A], a straight material-ratio curve */
    const int N = 200, periods = 50, nx = N * periods;
    const double A = 2e-6, dx = 1e-6;
    double *z = malloc(sizeof(double) * nx);
    for (int i = 0; i < nx; i++) {
        double t = fmod((i + 0.5) / N, 1.0);
        z[i] = A * (t < 0.5 ? 4 * t - 1 : 3 - 4 * t);
    }
    mc_roughness_params p = compute(z, NULL, nx, 1, dx, dx, nx * dx / 5, 1, 0);
    /* every height appears twice per period: the sampled curve is a staircase of steps 4A/N
     * about the line, so the secant, Rpk and Rvk may be off by about one step */
    const double step = 4 * A / N;
    printf("triangle: Rk/2A - 1 = %.2e, Rpk %.2e, Rvk %.2e m, Mr1 %.3f %%, Mr2 %.3f %% "
           "(step %.1e m)\n", p.Rk / (2 * A) - 1, p.Rpk, p.Rvk, p.Mr1, p.Mr2, step);
    ck_assert_double_eq_tol(p.Rk, 2 * A, step);
    ck_assert_double_le(p.Rpk, step);
    ck_assert_double_le(p.Rvk, step);
    ck_assert_double_le(p.Mr1, 100.0 * 2 / N);
    ck_assert_double_ge(p.Mr2, 100.0 - 100.0 * 2 / N);
    ck_assert_double_eq_tol(p.Sk, p.Rk, step); /* one row: the areal curve is the same */
    free(z);
}
END_TEST

START_TEST(test_rk_gaussian)
{
    const size_t n = 1000000;
    double *h = malloc(sizeof(double) * n), *work = malloc(sizeof(double) * n);
    normal_field(h, n, 77);
    mc_material_ratio mr;
    mc_roughness_material_ratio(h, n, work, &mr);
    /* theory for a unit normal: the flattest 40 % secant spans the 30 and 70 % quantiles, so
     * Rk = 2.5 * 2 * Phi^-1(0.7) with Phi^-1(0.7) = 0.524400512708041 (Abramowitz & Stegun
     * 26.2); c0 = Rk/2, Mr1 = 100 Q(c0), Rpk = 2 (phi(c0) - c0 Q(c0)) / Q(c0). */
    const double rk = 5 * 0.524400512708041, c0 = rk / 2;
    const double q = 0.5 * erfc(c0 / M_SQRT2), phi = exp(-c0 * c0 / 2) / sqrt(2 * M_PI);
    const double mr1 = 100 * q, rpk = 2 * (phi - c0 * q) / q;
    printf("gaussian Rk %.4f (%.4f), Mr1 %.3f (%.3f), Mr2 %.3f, Rpk %.4f (%.4f), Rvk %.4f\n",
           mr.k, rk, mr.mr1, mr1, mr.mr2, mr.pk, rpk, mr.vk);
    /* Standard errors at n = 1e6: Rk 3.5e-3 (the 30/70 % quantiles, sqrt(p(1-p)/n)/phi), and
     * picking the flattest of many noisy secants biases it low by a few of those: 0.02. Mr1:
     * binomial 0.03 % plus c0's error times the density, 0.04 %: 0.25 %. Rpk is the mean
     * excess of ~1e5 tail values, standard error 0.005, plus c0's error: 0.03. */
    ck_assert_double_eq_tol(mr.k, rk, 0.02);
    ck_assert_double_eq_tol(mr.mr1, mr1, 0.25);
    ck_assert_double_eq_tol(mr.mr2, 100 - mr1, 0.25);
    ck_assert_double_eq_tol(mr.pk, rpk, 0.03);
    ck_assert_double_eq_tol(mr.vk, rpk, 0.03);
    free(h);
    free(work);
}
END_TEST

/* ---- skewed, asymmetric surfaces: every signed parameter against a computation from its
 * definition (a symmetric profile cannot tell Rp from Rv or see the sign of Rsk) ----------- */

/* The ISO 13565-2 family of n heights written here from the contract in roughness.h: the k-th
 * highest at Mr = 100 (k + 1/2) / n, the secant over round(0.4 n) samples with the smallest
 * |slope|, c0 and c100 its heights at 0 and 100 %, Mr1 = share above c0, Mr2 = share at or
 * above c100, Rpk = 2 A1 / Mr1, Rvk = 2 A2 / (100 - Mr2). */
static int desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

static mc_material_ratio rk_by_hand(const double *h, size_t n)
{
    double *s = malloc(sizeof(double) * n);
    ck_assert(s != NULL);
    memcpy(s, h, sizeof(double) * n);
    qsort(s, n, sizeof(double), desc);
    size_t w = (size_t)lround(0.4 * (double)n), best = 0;
    double bslope = INFINITY;
    for (size_t a = 0; a + w < n; a++) {
        double slope = (s[a + w] - s[a]) / (100.0 * (double)w / (double)n);
        if (fabs(slope) < fabs(bslope)) {
            bslope = slope;
            best = a;
        }
    }
    double mra = 100.0 * ((double)best + 0.5) / (double)n;
    double c0 = s[best] - bslope * mra, c100 = c0 + 100 * bslope, a1 = 0, a2 = 0;
    size_t above = 0, atleast = 0;
    for (size_t k = 0; k < n; k++) {
        above += h[k] > c0;
        atleast += h[k] >= c100;
        a1 += h[k] > c0 ? (h[k] - c0) * 100.0 / (double)n : 0;
        a2 += h[k] < c100 ? (c100 - h[k]) * 100.0 / (double)n : 0;
    }
    mc_material_ratio m = {.k = c0 - c100,
                           .c0 = c0,
                           .c100 = c100,
                           .mr1 = 100.0 * (double)above / (double)n,
                           .mr2 = 100.0 * (double)atleast / (double)n};
    m.pk = m.mr1 > 0 ? 2 * a1 / m.mr1 : 0;
    m.vk = m.mr2 < 100 ? 2 * a2 / (100 - m.mr2) : 0;
    free(s);
    return m;
}

/* Two rows (the second twice the first, offset) of five sampling lengths of M samples: a ramp
 * (distinct values everywhere) with one tall narrow peak per sampling length: positively skewed,
 * Rp > Rv, Rpk > Rvk; and the same surface upside down (sign = -1), where each pair swaps and
 * the skewness changes sign. No filter, periodic rows: the roughness profile is the row minus its
 * mean, nothing discarded, the sampling lengths are the five blocks of M samples. */
START_TEST(test_skewed_signed_parameters)
{
    enum { M = 40, NS = 5, NX = M * NS, NY = 2 };
    const double sign = _i ? -1.0 : 1.0, dx = 1e-6, u = 1e-7; /* heights in units of 0.1 um */
    double z[NX * NY], hrow[NX], hmap[NX * NY];
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            int k = i % M, c = i / M;
            double v = k == 7 ? 5.0 + c : -1.0 + 0.05 * k + 0.01 * c;
            z[j * NX + i] = sign * u * ((1.0 + j) * v + 3.0 * j);
        }
    mc_roughness_params p = compute(z, NULL, NX, NY, dx, dx, M * dx, 1, 0);
    ck_assert_int_eq(p.n_sampling, NS);
    /* profile parameters: per row, then the mean over the rows */
    double ra = 0, rq = 0, rsk = 0, rp = 0, rv = 0, rt = 0, rk = 0, rpk = 0, rvk = 0, mr1 = 0,
           mr2 = 0;
    for (int j = 0; j < NY; j++) {
        double mean = 0, s1 = 0, s2 = 0, s3 = 0, hi = -INFINITY, lo = INFINITY;
        for (int i = 0; i < NX; i++)
            mean += z[j * NX + i] / NX;
        for (int i = 0; i < NX; i++) {
            double h = hrow[i] = z[j * NX + i] - mean;
            s1 += fabs(h) / NX;
            s2 += h * h / NX;
            s3 += h * h * h / NX;
            hi = test_worst(hi, h);
            lo = fmin(lo, h);
        }
        double q = sqrt(s2), pk = 0, vl = 0;
        for (int c = 0; c < NS; c++) {
            double bh = -INFINITY, bl = INFINITY;
            for (int i = c * M; i < (c + 1) * M; i++) {
                bh = test_worst(bh, hrow[i]);
                bl = fmin(bl, hrow[i]);
            }
            pk += bh / NS;
            vl += -bl / NS;
        }
        mc_material_ratio m = rk_by_hand(hrow, NX);
        ra += s1 / NY;
        rq += q / NY;
        rsk += s3 / (q * q * q) / NY;
        rp += pk / NY;
        rv += vl / NY;
        rt += (hi - lo) / NY;
        rk += m.k / NY;
        rpk += m.pk / NY;
        rvk += m.vk / NY;
        mr1 += m.mr1 / NY;
        mr2 += m.mr2 / NY;
    }
    /* areal: the whole map about its mean */
    double mean = 0, s2 = 0, s3 = 0, hi = -INFINITY, lo = INFINITY;
    for (int k = 0; k < NX * NY; k++)
        mean += z[k] / (NX * NY);
    for (int k = 0; k < NX * NY; k++) {
        double h = hmap[k] = z[k] - mean;
        s2 += h * h / (NX * NY);
        s3 += h * h * h / (NX * NY);
        hi = test_worst(hi, h);
        lo = fmin(lo, h);
    }
    double sq = sqrt(s2);
    mc_material_ratio am = rk_by_hand(hmap, NX * NY);
    const double t = 1e-9 * u; /* heights: round-off of sums of a few hundred terms */
    printf("skewed (sign %+.0f): Rsk %.4f Rp %.3g Rv %.3g Rpk %.3g Rvk %.3g Ssk %.4f Sp %.3g "
           "Sv %.3g Spk %.3g Svk %.3g\n", sign, p.Rsk, p.Rp, p.Rv, p.Rpk, p.Rvk, p.Ssk, p.Sp,
           p.Sv, p.Spk, p.Svk);
    ck_assert_double_eq_tol(p.Ra, ra, t);
    ck_assert_double_eq_tol(p.Rq, rq, t);
    ck_assert_double_eq_tol(p.Rsk, rsk, 1e-9);
    ck_assert_double_eq_tol(p.Rp, rp, t);
    ck_assert_double_eq_tol(p.Rv, rv, t);
    ck_assert_double_eq_tol(p.Rz, rp + rv, t);
    ck_assert_double_eq_tol(p.Rt, rt, t);
    ck_assert_double_eq_tol(p.Rk, rk, t);
    ck_assert_double_eq_tol(p.Rpk, rpk, t);
    ck_assert_double_eq_tol(p.Rvk, rvk, t);
    ck_assert_double_eq_tol(p.Mr1, mr1, 1e-9);
    ck_assert_double_eq_tol(p.Mr2, mr2, 1e-9);
    ck_assert_double_eq_tol(p.Sq, sq, t);
    ck_assert_double_eq_tol(p.Ssk, s3 / (sq * sq * sq), 1e-9);
    ck_assert_double_eq_tol(p.Sp, hi, t);
    ck_assert_double_eq_tol(p.Sv, -lo, t);
    ck_assert_double_eq_tol(p.Sz, hi - lo, t);
    ck_assert_double_eq_tol(p.Sk, am.k, t);
    ck_assert_double_eq_tol(p.Spk, am.pk, t);
    ck_assert_double_eq_tol(p.Svk, am.vk, t);
    ck_assert_double_eq_tol(p.Smr1, am.mr1, 1e-9);
    ck_assert_double_eq_tol(p.Smr2, am.mr2, 1e-9);
    /* the asymmetry is large, so the computation above is not trivially symmetric: peaks up
     * (sign +1) give Rsk > 0.5, Rp > 1.5 Rv, Rpk > 1.5 Rvk; upside down the reverse */
    ck_assert(sign * p.Rsk > 0.5 && sign * p.Ssk > 0.5);
    ck_assert(sign > 0 ? p.Rp > 1.5 * p.Rv : p.Rv > 1.5 * p.Rp);
    ck_assert(sign > 0 ? p.Rpk > 1.5 * p.Rvk : p.Rvk > 1.5 * p.Rpk);
    ck_assert(sign > 0 ? p.Sp > 1.5 * p.Sv : p.Sv > 1.5 * p.Sp);
    ck_assert(sign > 0 ? p.Spk > 1.5 * p.Svk : p.Svk > 1.5 * p.Spk);
}
END_TEST

/* ---- areal slopes: Sdq, Sdr of sines with the central-difference factor ------------------ */

/* Complete elliptic integral of the second kind E(m), by the arithmetic-geometric mean. */
static double ellip_e(double m)
{
    double a = 1, b = sqrt(1 - m), c = sqrt(m), sum = 0.5 * c * c, pw = 0.5;
    for (int k = 0; k < 30 && fabs(c) > 1e-17; k++) {
        double an = 0.5 * (a + b);
        c = 0.5 * (a - b);
        b = sqrt(a * b);
        a = an;
        pw *= 2;
        sum += pw * c * c;
    }
    return M_PI / (2 * a) * (1 - sum);
}

/* The areal material-ratio curve (mc_roughness_material_curve). Heights a permutation of
 * 0 .. n-1 (uniform): the j-th highest, n - 1 - j, sits at Mr = 100 (j + 1/2) / n, so the curve
 * about the mean (n - 1) / 2 is exactly h(Mr) = (n - 1) / 2 - (n Mr / 100 - 1/2) between the
 * first and last points and constant beyond. Its Sk family is mc_roughness_compute's to the bit
 * (the same heights about the same mean), the line's c0 and c100 those of the contract written
 * out in rk_by_hand; a mask leaves the masked points out; bad input is refused. */
START_TEST(test_material_curve)
{
    enum { NX = 20, NY = 15, N = NX * NY, NPTS = 41 };
    double z[N], curve[NPTS], hm[N];
    for (int k = 0; k < N; k++)
        z[k] = 1e-7 * (double)((k * 7) % N); /* 7 and 300 coprime: a permutation */
    mc_material_ratio line;
    mc_error err = {0};
    ck_assert_int_eq(mc_roughness_material_curve(z, NULL, N, NPTS, curve, &line, &err), MC_OK);
    const double t = 1e-7 * N * TOL_ROUNDOFF; /* round-off of the mean of N heights */
    for (int k = 0; k < NPTS; k++) {
        double mr = 100.0 * k / (NPTS - 1), x = N * mr / 100.0 - 0.5;
        x = x < 0 ? 0 : x > N - 1 ? N - 1 : x;
        ck_assert_double_eq_tol(curve[k], 1e-7 * (0.5 * (N - 1) - x), t);
        if (k)
            ck_assert_double_le(curve[k], curve[k - 1]);
    }
    mc_roughness_params p = compute(z, NULL, NX, NY, 1e-6, 1e-6, 0, 0, 0);
    ck_assert_double_eq(curve[0], p.Sp);
    ck_assert_double_eq(curve[NPTS - 1], -p.Sv);
    ck_assert_double_eq(line.k, p.Sk);
    ck_assert_double_eq(line.pk, p.Spk);
    ck_assert_double_eq(line.vk, p.Svk);
    ck_assert_double_eq(line.mr1, p.Smr1);
    ck_assert_double_eq(line.mr2, p.Smr2);
    double mean = 0;
    for (int k = 0; k < N; k++)
        mean += z[k];
    mean /= N;
    for (int k = 0; k < N; k++)
        hm[k] = z[k] - mean;
    mc_material_ratio m = rk_by_hand(hm, N);
    ck_assert_double_eq_tol(line.c0, m.c0, t);
    ck_assert_double_eq_tol(line.c100, m.c100, t);
    ck_assert_double_eq_tol(line.c0 - line.c100, line.k, t);
    /* a mask: without the highest point the curve starts at the next one */
    unsigned char v[N];
    memset(v, 1, sizeof v);
    for (int k = 0; k < N; k++)
        v[k] = z[k] < 1e-7 * (N - 1.5);
    ck_assert_int_eq(mc_roughness_material_curve(z, v, N, NPTS, curve, NULL, &err), MC_OK);
    ck_assert_double_eq_tol(curve[0], 1e-7 * (N - 2) - 1e-7 * 0.5 * (N - 2), t);
    ck_assert_int_eq(mc_roughness_material_curve(z, NULL, N, 1, curve, NULL, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "at least 2"), "%s", err.msg);
    z[5] = NAN;
    ck_assert_int_eq(mc_roughness_material_curve(z, NULL, N, NPTS, curve, NULL, &err),
                     MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "not finite"), "%s", err.msg);
    memset(v, 0, sizeof v);
    ck_assert_int_eq(mc_roughness_material_curve(z, v, N, NPTS, curve, NULL, &err), MC_ERR_INPUT);
}
END_TEST

START_TEST(test_areal_slopes)
{
    ck_assert_double_eq_tol(ellip_e(0.5), 1.3506438810476755, TOL_TIGHT); /* A&S table 17.1 */
    const int nx = 96, ny = 40, Nx = 32, Ny = 20; /* samples per wavelength */
    const double A = 1e-6, dx = 1e-6, dy = 1.5e-6;
    const double kx = 2 * M_PI / (Nx * dx), ky = 2 * M_PI / (Ny * dy);
    double *z = malloc(sizeof(double) * nx * ny);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            z[j * nx + i] = A * sin(kx * i * dx) * sin(ky * j * dy);
    mc_roughness_params p = compute(z, NULL, nx, ny, dx, dy, nx * dx, 1, 0);
    /* central differences of a sampled sine are exact sines of amplitude A sin(k d)/d */
    double kxe = sin(kx * dx) / dx, kye = sin(ky * dy) / dy;
    double sdq = 0.5 * A * hypot(kxe, kye);
    printf("product sine: Sdq error %.2e relative (continuous value %.4f, discrete %.4f)\n",
           p.Sdq / sdq - 1, 0.5 * A * hypot(kx, ky), sdq);
    ck_assert_double_eq_tol(p.Sdq, sdq, TOL_ROUNDOFF * sdq);
    ck_assert_double_eq_tol(p.Sq, A / 2, TOL_ROUNDOFF * A);
    ck_assert_double_eq_tol(p.Sku, 2.25, TOL_ROUNDOFF); /* (3/8)^2 / (1/4)^2 */
    ck_assert_double_eq_tol(p.Ssk, 0.0, TOL_ROUNDOFF);
    ck_assert_double_eq_tol(p.Sz, 2 * A, TOL_ROUNDOFF * A);

    /* z = A sin(kx x): Sdr = (2/pi) sqrt(1 + a^2) E(a^2/(1 + a^2)) - 1 with a the slope
     * amplitude; the sampled mean of a smooth periodic function is exact to round-off */
    const double As = 5e-6; /* slope amplitude ~1: the square root matters */
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            z[j * nx + i] = As * sin(kx * i * dx);
    p = compute(z, NULL, nx, ny, dx, dy, nx * dx, 1, 0);
    double ae = As * kxe, at = As * kx;
    double sdr_d = 100 * (2 / M_PI * sqrt(1 + ae * ae) * ellip_e(ae * ae / (1 + ae * ae)) - 1);
    double sdr_t = 100 * (2 / M_PI * sqrt(1 + at * at) * ellip_e(at * at / (1 + at * at)) - 1);
    double f = sin(kx * dx) / (kx * dx);
    printf("sine Sdr %.6f %% (discrete analytic %.6f, error %.1e); continuous %.6f %%: central "
           "differences %.3f %% low, small-slope factor (sin(kd)/kd)^2 - 1 = %.3f %%\n", p.Sdr,
           sdr_d, p.Sdr - sdr_d, sdr_t, 100 * (p.Sdr / sdr_t - 1), 100 * (f * f - 1));
    ck_assert_double_eq_tol(p.Sdr, sdr_d, TOL_ROUNDOFF * sdr_d);
    ck_assert_double_eq_tol(p.Sdq, ae / M_SQRT2, TOL_ROUNDOFF * ae);
    /* the dossier's factor: at small slopes Sdr ~ 25 a^2 %, so central differences scale it by
     * (sin(k d)/(k d))^2; the next term of sqrt(1 + s^2) - 1 changes the ratio by O(a^2) */
    const double small = 1e-8, a2 = small * kx; /* slope amplitude 0.0098 */
    for (int k = 0; k < nx * ny; k++)
        z[k] *= small / As;
    p = compute(z, NULL, nx, ny, dx, dy, nx * dx, 1, 0);
    sdr_t = 100 * (2 / M_PI * sqrt(1 + a2 * a2) * ellip_e(a2 * a2 / (1 + a2 * a2)) - 1);
    printf("small-slope sine: Sdr ratio discrete/continuous - 1 = %.4f %%, (sin(kd)/kd)^2 - 1 = "
           "%.4f %%\n", 100 * (p.Sdr / sdr_t - 1), 100 * (f * f - 1));
    ck_assert_double_eq_tol(p.Sdr / sdr_t, f * f, a2 * a2);
    free(z);
}
END_TEST

/* ---- ISO 4288 ---------------------------------------------------------------------------- */

START_TEST(test_iso4288_table)
{
    double *t;
    int cols;
    char head[16][32];
    int rows = test_read_csv("pl_iso4288_cutoffs.csv", &t, &cols, head, 16);
    ck_assert_int_eq(rows, 5);
    ck_assert_str_eq(head[6], "lambda_c_mm");
    for (int r = 0; r < rows; r++) {
        const double *row = t + r * cols, lc = row[6] * 1e-3;
        for (int par = 0; par < 2; par++) { /* Ra (columns 0-1), Rz (2-3) */
            double lo = row[2 * par] * 1e-6, hi = row[2 * par + 1] * 1e-6;
            double (*pick)(double, int *) = par ? mc_iso4288_cutoff_rz : mc_iso4288_cutoff_ra;
            int in;
            ck_assert_double_eq(pick(hi, &in), lc); /* upper bound belongs to the row */
            ck_assert_int_eq(in, 1);
            ck_assert_double_eq(pick(lo * (1 + 1e-6), &in), lc);
            ck_assert_double_eq(pick(sqrt(lo * hi), &in), lc);
            if (r + 1 < rows)
                ck_assert_double_eq(pick(hi * (1 + 1e-6), &in), t[(r + 1) * cols + 6] * 1e-3);
        }
    }
    int in;
    ck_assert_double_eq(mc_iso4288_cutoff_ra(0.001e-6, &in), 0.08e-3);
    ck_assert_int_eq(in, 0);
    ck_assert_double_eq(mc_iso4288_cutoff_ra(100e-6, &in), 8e-3);
    ck_assert_int_eq(in, 0);
    free(t);
}
END_TEST

START_TEST(test_iso4288_iteration)
{
    /* roughness Ra 0.05 um (0.25 mm class) on a 2 um waviness of 4 mm: the unfiltered Ra
     * (about 1.3 um) picks 0.8 mm, whose filtered Ra falls in the 0.25 mm class, which holds */
    const int nx = 12000;
    const double dx = 1e-6, ar = 0.05e-6 * M_PI / 2;
    double *z = malloc(sizeof(double) * nx);
    for (int i = 0; i < nx; i++)
        z[i] = ar * sin(2 * M_PI * i / 20.0) + 2e-6 * sin(2 * M_PI * i * dx / 4e-3 + 0.3);
    mc_roughness_params p = compute(z, NULL, nx, 1, dx, dx, 0, 0, 1);
    printf("ISO 4288 choice: %.3g m, Ra %.4g m\n", p.cutoff, p.Ra);
    ck_assert(p.cutoff_auto && !p.cutoff_clipped);
    ck_assert_double_eq(p.cutoff, 0.25e-3);
    ck_assert_double_eq_tol(p.Ra, 0.05e-6, 0.02 * 0.05e-6); /* waviness leak ~ 0.3 % */
    free(z);
}
END_TEST

/* ---- short profiles: parameters and a warning, never an error ---------------------------- */

START_TEST(test_short_profile)
{
    const double dx = 1e-6, lc = 0.8e-3, A = 1e-7;
    double *z = malloc(sizeof(double) * 4000);
    /* 100 points, free: lambda_c clipped to L/3 */
    sine_rows(z, 100, 1, dx, A, 10e-6);
    mc_roughness_params p = compute(z, NULL, 100, 1, dx, dx, lc, 0, 1);
    ck_assert(p.cutoff_clipped && p.short_evaluation);
    ck_assert_double_eq_tol(p.cutoff, 100 * dx / 3, TOL_ROUNDOFF * lc);
    ck_assert_ptr_nonnull(strstr(p.warning, "clipped"));
    ck_assert_double_gt(p.Ra, 0.5 * A);
    printf("short profile warning: %s\n", p.warning);
    /* periodic: clipped to L */
    p = compute(z, NULL, 100, 1, dx, dx, lc, 1, 1);
    ck_assert(p.cutoff_clipped);
    ck_assert_double_eq_tol(p.cutoff, 100 * dx, TOL_ROUNDOFF * lc);
    /* 4 lambda_c, free: two sampling lengths survive the ends, the cut-off stays */
    const int n4 = 4 * 200;
    sine_rows(z, n4, 1, dx, A, 10e-6);
    p = compute(z, NULL, n4, 1, dx, dx, 200e-6, 0, 1);
    ck_assert(!p.cutoff_clipped && p.short_evaluation);
    ck_assert_int_eq(p.n_sampling, 2);
    ck_assert_ptr_nonnull(strstr(p.warning, "2 sampling lengths"));
    /* a single column: profiles of one point, areal parameters from the column */
    sine_rows(z, 64, 1, dx, A, 16e-6);
    p = compute(z, NULL, 1, 64, dx, dx, lc, 0, 1);
    ck_assert(p.cutoff_clipped);
    ck_assert_double_eq(p.Ra, 0.0);
    ck_assert_double_eq_tol(p.Sq, A / M_SQRT2, TOL_ROUNDOFF * A);
    double c2 = 0; /* free column: central differences at the 62 interior points */
    for (int j = 1; j < 63; j++)
        c2 += pow(cos(2 * M_PI * j / 16), 2) / 62;
    double sdq = A * sin(2 * M_PI / 16) / dx * sqrt(c2);
    ck_assert_double_eq_tol(p.Sdq, sdq, TOL_ROUNDOFF * sdq);
    free(z);
}
END_TEST

/* ---- masks, errors, names ---------------------------------------------------------------- */

START_TEST(test_mask_and_errors)
{
    const int nx = 2048, ny = 2;
    const double dx = 1e-6, A = 1e-6;
    double *z = malloc(sizeof(double) * nx * ny);
    unsigned char *v = malloc((size_t)nx * ny);
    sine_rows(z, nx, ny, dx, A, 64e-6);
    memset(v, 1, (size_t)nx * ny);
    for (int k = 100; k < nx * ny; k += 97) {
        v[k] = 0;
        z[k] = NAN; /* never read */
    }
    mc_roughness_params p = compute(z, v, nx, ny, dx, dx, 256e-6, 1, 1);
    /* missing samples change the sampled moments by about their share (1 %) */
    ck_assert_double_eq_tol(p.Rq, A / M_SQRT2, 0.01 * A);
    ck_assert(isfinite(p.Sdq) && isfinite(p.Rk));
    mc_error err = {0};
    mc_roughness_params q;
    v[0] = 1;
    z[0] = NAN;
    ck_assert_int_eq(mc_roughness_compute(z, v, nx, ny, dx, dx, NULL, &q, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "not finite"));
    memset(v, 0, (size_t)nx * ny);
    ck_assert_int_eq(mc_roughness_compute(z, v, nx, ny, dx, dx, NULL, &q, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "no valid point"));
    mc_roughness_options o;
    mc_roughness_options_default(&o);
    o.cutoff = -1;
    ck_assert_int_eq(mc_roughness_compute(z, NULL, nx, ny, dx, dx, &o, &q, &err), MC_ERR_INPUT);
    free(z);
    free(v);
}
END_TEST

START_TEST(test_entries)
{
    mc_roughness_params p;
    memset(&p, 0, sizeof p);
    p.Ra = 1;
    p.Sdr = 2;
    p.Mr2 = 3;
    p.cutoff = 4;
    mc_roughness_entry e[MC_ROUGHNESS_NENTRIES];
    const int n = mc_roughness_entry_count();
    ck_assert_int_eq(mc_roughness_entries(&p, e), n);
    /* the entries are the table's rows, in its order, names unique, with help */
    for (int k = 0; k < n; k++) {
        ck_assert_str_eq(e[k].name, mc_roughness_entry_name(k));
        ck_assert_ptr_nonnull(mc_roughness_entry_help(k));
        for (int j = 0; j < k; j++)
            ck_assert_str_ne(e[k].name, e[j].name);
    }
    ck_assert_ptr_null(mc_roughness_entry_name(n));
    /* each value is its field's (looked up by name, not by position) */
    const struct {
        const char *name, *unit;
        double value;
    } want[] = {{"Ra", "m", 1}, {"Sdr", "%", 2}, {"Mr2", "%", 3}, {"lambda_c", "m", 4},
                {"Rq", "m", 0}, {"Rsk", "1", 0}, {"Sq", "m", 0}};
    for (size_t w = 0; w < sizeof want / sizeof want[0]; w++) {
        int found = 0;
        for (int k = 0; k < n; k++)
            if (!strcmp(e[k].name, want[w].name)) {
                found = 1;
                ck_assert_str_eq(e[k].unit, want[w].unit);
                ck_assert_double_eq(e[k].value, want[w].value);
            }
        ck_assert_msg(found, "%s not reported", want[w].name);
    }
    /* without the profile family: only names of the areal family and lambda_c */
    p.profile_not_computable = 1;
    int m = mc_roughness_entries(&p, e);
    ck_assert_int_lt(m, n);
    for (int k = 0; k < m; k++)
        ck_assert_msg(e[k].name[0] != 'R' && strncmp(e[k].name, "Mr", 2), "%s", e[k].name);
}
END_TEST

/* A cut-off spanning fewer than MC_ROUGHNESS_MIN_SAMPLES sampling intervals (issue 23: a
 * 27.5 mm-spaced scan with the ISO 4288 cut-off of 0.8 mm gave Ra ~ 1e-18 m, negative Rp, Rz = 0
 * < Rt): chosen by ISO 4288, the profile parameters are left out with the reason; given, it is
 * refused naming the accepted minimum. The areal ones stay. */
START_TEST(test_cutoff_below_sampling)
{
    enum { NX = 64, NY = 8 };
    static double z[NX * NY];
    test_random_field(z, NX * NY, 23);
    for (int k = 0; k < NX * NY; k++)
        z[k] *= 1e-6;
    const double dx = 27.5e-3;
    mc_roughness_options o;
    mc_roughness_options_default(&o);
    mc_roughness_params p;
    mc_error err = {0};
    ck_assert_int_eq(mc_roughness_compute(z, NULL, NX, NY, dx, dx, &o, &p, &err), MC_OK);
    ck_assert(p.cutoff_auto && p.profile_not_computable);
    ck_assert_ptr_nonnull(strstr(p.warning, "profile parameters (Ra, Rq, Rz, ...) not computable"));
    mc_roughness_entry e[MC_ROUGHNESS_NENTRIES];
    int n = mc_roughness_entries(&p, e);
    ck_assert_int_eq(n, MC_ROUGHNESS_NENTRIES - 13);
    for (int k = 0; k < n; k++)
        ck_assert_msg(e[k].name[0] != 'R', "%s printed", e[k].name);
    ck_assert(p.Sq > 0);
    o.cutoff = 0.8e-3;
    ck_assert_int_eq(mc_roughness_compute(z, NULL, NX, NY, dx, dx, &o, &p, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "accepted: cutoff >= 4 dx = 0.11 m"));
}
END_TEST

Suite *suite_roughness(void);
Suite *suite_roughness(void)
{
    Suite *s = suite_create("roughness");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_loop_test(tc, test_sine_profile, 0, 2);
    tcase_add_loop_test(tc, test_transmission, 0, 2);
    tcase_add_loop_test(tc, test_mean_line_constant, 0, 2);
    tcase_add_test(tc, test_periodic_nothing_discarded);
    tcase_add_test(tc, test_gaussian_heights);
    tcase_add_test(tc, test_rk_triangle);
    tcase_add_test(tc, test_rk_gaussian);
    tcase_add_loop_test(tc, test_skewed_signed_parameters, 0, 2);
    tcase_add_test(tc, test_areal_slopes);
    tcase_add_test(tc, test_material_curve);
    tcase_add_test(tc, test_cutoff_below_sampling);
    tcase_add_test(tc, test_iso4288_table);
    tcase_add_test(tc, test_iso4288_iteration);
    tcase_add_test(tc, test_short_profile);
    tcase_add_test(tc, test_mask_and_errors);
    tcase_add_test(tc, test_entries);
    suite_add_tcase(s, tc);
    return s;
}
