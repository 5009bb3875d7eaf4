/* test_surface.c - random numbers, shapes, synthetic roughness, statistics (surface.c). */
#include <check.h>
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/npy.h"
#include "case/scene.h"
#include "surface/surface.h"
#include "test_util.h"

static mc_grid make_grid(int nx, int ny, double dx, double dy)
{
    mc_grid g = {nx, ny, dx, dy, 1, 1};
    return g;
}

static void blank_scene(mc_scene *s, const mc_grid *g)
{
    memset(s, 0, sizeof *s);
    s->grid = *g;
}

static double *generate(const mc_grid *g, const mc_scene *s)
{
    double *h = mc_zeros(mc_grid_cells(g));
    ck_assert(h != NULL);
    mc_error err = {0};
    int st = mc_surface_roughness(g, &s->roughness, h, &err);
    ck_assert_msg(st == MC_OK, "%s", err.msg);
    return h;
}

/* ---- random numbers ---------------------------------------------------------------------- */

START_TEST(test_rng_reference)
{
    mc_rng r;
    mc_rng_seed(&r, 0);
    ck_assert_uint_eq(r.s[0], 0xe220a8397b1dcdafULL); /* splitmix64(0), Vigna's reference */
    /* xoshiro256** outputs for seed 42, from an independent (Python) implementation. */
    const uint64_t want[4] = {0x15780b2e0c2ec716ULL, 0x6104d9866d113a7eULL, 0xae17533239e499a1ULL,
                              0xecb8ad4703b360a1ULL};
    mc_rng_seed(&r, 42);
    for (int k = 0; k < 4; k++)
        ck_assert_uint_eq(mc_rng_next(&r), want[k]);
    mc_rng_seed(&r, 42);
    ck_assert_double_eq(mc_rng_uniform(&r), (double)(want[0] >> 11) * 0x1.0p-53);
}
END_TEST

START_TEST(test_rng_normal)
{
    /* Box-Muller uses both values: two normals consume exactly two raw outputs. */
    mc_rng a, b;
    mc_rng_seed(&a, 7);
    mc_rng_seed(&b, 7);
    mc_rng_normal(&a);
    mc_rng_normal(&a);
    mc_rng_next(&b);
    mc_rng_next(&b);
    ck_assert_uint_eq(mc_rng_next(&a), mc_rng_next(&b));

    /* Moments of 1e6 normals; tolerances are 5 standard errors: mean 1/sqrt(n), variance
     * sqrt(2/n), fourth moment sqrt(96/n). */
    const int n = 1000000;
    double s1 = 0, s2 = 0, s4 = 0, umin = 1, umax = 0;
    mc_rng_seed(&a, 2024);
    for (int k = 0; k < n; k++) {
        double z = mc_rng_normal(&a);
        s1 += z;
        s2 += z * z;
        s4 += z * z * z * z;
        double u = mc_rng_uniform(&b);
        umin = fmin(umin, u);
        umax = test_worst(umax, u);
    }
    ck_assert_double_le(fabs(s1 / n), 5.0 / sqrt(n));
    ck_assert_double_le(fabs(s2 / n - 1.0), 5.0 * sqrt(2.0 / n));
    ck_assert_double_le(fabs(s4 / n - 3.0), 5.0 * sqrt(96.0 / n));
    ck_assert(umin >= 0.0 && umin < 1e-4 && umax < 1.0 && umax > 1.0 - 1e-4);
}
END_TEST

/* ---- shapes ------------------------------------------------------------------------------ */

START_TEST(test_shapes)
{
    mc_grid g = make_grid(8, 6, 1e-6, 2e-6);
    mc_scene s;
    blank_scene(&s, &g);
    double h[48];
    const double R = 1e-3, Rx = 2e-3, Ry = 5e-4;
    /* cells (i, j) and their centres x = (i + 1/2 - nx/2) dx */
    const int cells[3][2] = {{0, 0}, {4, 3}, {7, 1}};
    for (int shape = 0; shape < 4; shape++) {
        s.geometry.shape = (mc_shape)shape;
        s.geometry.radius = R;
        s.geometry.radius_x = Rx;
        s.geometry.radius_y = Ry;
        for (int k = 0; k < 48; k++)
            h[k] = NAN;
        mc_surface_shape(&g, &s.geometry, h);
        for (int c = 0; c < 3; c++) {
            int i = cells[c][0], j = cells[c][1];
            double x = (i + 0.5 - 4.0) * 1e-6, y = (j + 0.5 - 3.0) * 2e-6, want = 0;
            if (shape == MC_SHAPE_SPHERE)
                want = (x * x + y * y) / (2 * R);
            else if (shape == MC_SHAPE_CYLINDER)
                want = x * x / (2 * R);
            else if (shape == MC_SHAPE_ELLIPSOID)
                want = x * x / (2 * Rx) + y * y / (2 * Ry);
            ck_assert_double_le(fabs(h[j * 8 + i] - want), TOL_TIGHT * fabs(want));
        }
        /* apex at the grid centre: the four central cells share the minimum */
        if (shape != MC_SHAPE_FLAT)
            ck_assert_double_eq_tol(h[2 * 8 + 3], h[3 * 8 + 4], TOL_TIGHT * h[3 * 8 + 4]);
    }
    s.geometry.shape = MC_SHAPE_SPHERE;
    mc_surface_shape(&g, &s.geometry, h);
    ck_assert_double_eq_tol(h[0], (3.5e-6 * 3.5e-6 + 5e-6 * 5e-6) / 2e-3, TOL_TIGHT * h[0]);
}
END_TEST

/* ---- gaussian roughness ------------------------------------------------------------------ */

START_TEST(test_gaussian_exact_and_reproducible)
{
    mc_grid g = make_grid(96, 80, 0.5e-6, 0.8e-6); /* non-square, dx != dy */
    mc_scene s;
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_GAUSSIAN;
    s.roughness.rq = 0.37e-6;
    s.roughness.correlation_x = 3e-6;
    s.roughness.correlation_y = 5e-6;
    s.roughness.seed = 99;
    double *a = generate(&g, &s), *b = generate(&g, &s);
    size_t n = mc_grid_cells(&g);
    ck_assert_mem_eq(a, b, n * sizeof(double)); /* same seed: bitwise identical */
    mc_surface_stats st;
    mc_surface_statistics(&g, a, &st);
    ck_assert_double_le(fabs(st.rq - s.roughness.rq), TOL_ROUNDOFF * s.roughness.rq);
    ck_assert_double_le(fabs(st.mean), TOL_ROUNDOFF * s.roughness.rq);
    s.roughness.seed = 100;
    mc_free(b);
    b = generate(&g, &s);
    ck_assert_double_gt(test_rel_maxdiff(a, b, n), 0.1); /* another seed: another surface */
    /* rq is a pure scale factor */
    s.roughness.seed = 99;
    s.roughness.rq = 2 * 0.37e-6;
    mc_free(b);
    b = generate(&g, &s);
    for (size_t k = 0; k < n; k++)
        ck_assert_double_eq_tol(b[k], 2 * a[k], TOL_TIGHT * s.roughness.rq * 8);
    mc_free(a);
    mc_free(b);
}
END_TEST

START_TEST(test_gaussian_height_distribution)
{
    /* Gaussian heights: Sa/Sq = sqrt(2/pi), Ssk = 0, Sku = 3. N_eff = N / (pi l^2 / (2 dx^2))
     * independent samples (integral of the squared ACF); 5 standard errors with
     * sd(Sa/Sq) = 0.212/sqrt(N_eff) (delta method), sd(Ssk) = sqrt(6/N_eff),
     * sd(Sku) = sqrt(24/N_eff). */
    const int nx = 512;
    const double dx = 1e-6, l = 2e-6;
    mc_grid g = make_grid(nx, nx, dx, dx);
    mc_scene s;
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_GAUSSIAN;
    s.roughness.rq = 1e-6;
    s.roughness.correlation_x = l;
    s.roughness.correlation_y = l;
    s.roughness.seed = 5;
    double *h = generate(&g, &s);
    mc_surface_stats st;
    mc_surface_statistics(&g, h, &st);
    double neff = (double)nx * nx / (M_PI * l * l / (2 * dx * dx));
    ck_assert_double_le(fabs(st.ra / st.rq - sqrt(2 / M_PI)), 5 * 0.212 / sqrt(neff));
    ck_assert_double_le(fabs(st.skewness), 5 * sqrt(6 / neff));
    ck_assert_double_le(fabs(st.kurtosis - 3), 5 * sqrt(24 / neff));
    mc_free(h);
}
END_TEST

/* Mean of h(x) h(x + lag) over the periodic grid, divided by the mean square. */
static double acf(const mc_grid *g, const double *h, int di, int dj)
{
    double num = 0, den = 0;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            double a = h[j * g->nx + i];
            double b = h[((j + dj) % g->ny) * g->nx + (i + di) % g->nx];
            num += a * b;
            den += a * a;
        }
    return num / den;
}

START_TEST(test_gaussian_acf)
{
    /* Ensemble ACF at lag l_x along x and l_y along y: e^-1 for R = rq^2 exp(-(t/l)^2).
     * The exact expectation of the discrete process (zero mean mode) is
     * sum_{q != 0} C(q) cos(q t) / sum_{q != 0} C(q); it differs from e^-1 by about
     * pi lx ly / L^2 (the removed mean), checked first. Tolerance: 4 standard errors from the
     * scatter of the seeds. */
    const int n = 256, nseeds = 32, lagx = 8, lagy = 4;
    const double dx = 1e-6;
    mc_grid g = make_grid(n, n, dx, dx);
    mc_scene s;
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_GAUSSIAN;
    s.roughness.rq = 0.5e-6;
    s.roughness.correlation_x = lagx * dx;
    s.roughness.correlation_y = lagy * dx;

    double sc = 0, scx = 0, scy = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            if (i == 0 && j == 0)
                continue;
            int ii = i <= n / 2 ? i : i - n, jj = j <= n / 2 ? j : j - n;
            double qx = 2 * M_PI * ii / (n * dx), qy = 2 * M_PI * jj / (n * dx);
            double c = exp(-0.25 * (pow(qx * lagx * dx, 2) + pow(qy * lagy * dx, 2)));
            sc += c;
            scx += c * cos(qx * lagx * dx);
            scy += c * cos(qy * lagy * dx);
        }
    double ex = scx / sc, ey = scy / sc;
    ck_assert_double_le(fabs(ex - exp(-1)), 2 * M_PI * lagx * lagy / (n * n));
    ck_assert_double_le(fabs(ey - exp(-1)), 2 * M_PI * lagx * lagy / (n * n));

    double mx = 0, mx2 = 0, my = 0, my2 = 0, cross = 0;
    for (int k = 0; k < nseeds; k++) {
        s.roughness.seed = 1000 + (uint64_t)k;
        double *h = generate(&g, &s);
        double rx = acf(&g, h, lagx, 0), ry = acf(&g, h, 0, lagy);
        mx += rx;
        mx2 += rx * rx;
        my += ry;
        my2 += ry * ry;
        cross += acf(&g, h, 0, lagx); /* lag l_x along y: exp(-(8/4)^2) = e^-4 */
        mc_free(h);
    }
    mx /= nseeds;
    my /= nseeds;
    double sex = sqrt((mx2 / nseeds - mx * mx) / (nseeds - 1));
    double sey = sqrt((my2 / nseeds - my * my) / (nseeds - 1));
    ck_assert_msg(fabs(mx - ex) < 4 * sex, "ACF x %g, expected %g +- %g", mx, ex, 4 * sex);
    ck_assert_msg(fabs(my - ey) < 4 * sey, "ACF y %g, expected %g +- %g", my, ey, 4 * sey);
    ck_assert_double_lt(sex, 0.02); /* the check is meaningful: SE well below e^-1 */
    ck_assert_double_lt(fabs(cross / nseeds - exp(-4)), 0.02); /* anisotropy: not e^-1 */
}
END_TEST

/* ---- self-affine roughness --------------------------------------------------------------- */

START_TEST(test_self_affine_spectrum)
{
    /* Radially averaged PSD of the generated surface: slope -2(1+H) between the cut-offs (log-log
     * least squares over log-spaced rings, 4 seeds), flat below q_long (roll-off) and zero above
     * q_short (to round-off). */
    const int n = 256;
    const double dx = 1e-6, L = n * dx, H = 0.7;
    mc_grid g = make_grid(n, n, dx, dx);
    mc_scene s;
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_SELF_AFFINE;
    s.roughness.rq = 0.3e-6;
    s.roughness.hurst = H;
    s.roughness.lambda_long = L / 8;   /* ring index 8 */
    s.roughness.lambda_short = L / 80; /* ring index 80 */
    const int nb = 12;
    double bin_p[12] = {0}, bin_q[12] = {0}, low = 0, at_long = 0, high = 0, peak = 0;
    int bin_n[12] = {0}, nlow = 0, nlong = 0;
    double *w = fftw_malloc(sizeof(double) * n * n);
    fftw_complex *W = fftw_malloc(sizeof(fftw_complex) * n * (n / 2 + 1));
    fftw_plan p = fftw_plan_dft_r2c_2d(n, n, w, W, FFTW_ESTIMATE);
    for (int seed = 0; seed < 4; seed++) {
        s.roughness.seed = (uint64_t)seed;
        double *h = generate(&g, &s);
        memcpy(w, h, sizeof(double) * n * n);
        mc_free(h);
        fftw_execute(p);
        for (int j = 0; j < n; j++)
            for (int i = 0; i <= n / 2; i++) {
                int jj = j <= n / 2 ? j : j - n;
                double k = sqrt((double)i * i + (double)jj * jj);
                double pw = W[j * (n / 2 + 1) + i][0] * W[j * (n / 2 + 1) + i][0] +
                            W[j * (n / 2 + 1) + i][1] * W[j * (n / 2 + 1) + i][1];
                peak = test_worst(peak, pw);
                if (k > 80.0 + 1e-9)
                    high = test_worst(high, pw);
                if (k > 0 && k < 8 - 1e-9) {
                    low += pw;
                    nlow++;
                }
                if (k >= 8 && k < 12) { /* compensated by the expected power law */
                    at_long += pw * pow(k / 8, 2 * (1 + H));
                    nlong++;
                }
                if (k >= 10 && k <= 72) { /* margins off both edges */
                    int b = (int)(nb * log(k / 10) / log(72.0 / 10));
                    if (b >= nb)
                        b = nb - 1;
                    bin_p[b] += pw;
                    bin_q[b] += log(k);
                    bin_n[b]++;
                }
            }
    }
    fftw_destroy_plan(p);
    fftw_free(w);
    fftw_free(W);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int b = 0; b < nb; b++) {
        ck_assert_int_gt(bin_n[b], 0);
        double x = bin_q[b] / bin_n[b], y = log(bin_p[b] / bin_n[b]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    double slope = (nb * sxy - sx * sy) / (nb * sxx - sx * sx);
    /* Each bin averages >= 4 x 100 exponentially distributed powers (5 % scatter): the fitted
     * slope scatters by ~0.02; 0.06 is three times that. */
    ck_assert_msg(fabs(slope - (-2 * (1 + H))) < 0.06, "slope %g, expected %g", slope,
                  -2 * (1 + H));
    /* roll-off: the mean power below q_long equals C(q_long), estimated from the ring
     * 8 <= k < 12 scaled back along the power law (~400 and ~500 modes: 7 % scatter of the
     * ratio; 0.2 is three times that) */
    double ratio = (low / nlow) / (at_long / nlong);
    ck_assert_msg(fabs(ratio - 1) < 0.2, "roll-off ratio %g", ratio);
    ck_assert_double_lt(high, 1e-20 * peak);
}
END_TEST

/* Spectral rms slope by a plain DFT (independent of FFTW and of the generator's bookkeeping). */
static double dft_rms_slope(const mc_grid *g, const double *h)
{
    int nx = g->nx, ny = g->ny;
    double sum = 0;
    for (int ky = 0; ky < ny; ky++)
        for (int kx = 0; kx < nx; kx++) {
            double re = 0, im = 0;
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++) {
                    double ph = -2 * M_PI * ((double)kx * i / nx + (double)ky * j / ny);
                    re += h[j * nx + i] * cos(ph);
                    im += h[j * nx + i] * sin(ph);
                }
            int ix = kx <= nx / 2 ? kx : kx - nx, iy = ky <= ny / 2 ? ky : ky - ny;
            double qx = 2 * M_PI * ix / (nx * g->dx), qy = 2 * M_PI * iy / (ny * g->dy);
            sum += (re * re + im * im) * (qx * qx + qy * qy);
        }
    return sqrt(sum) / ((double)nx * ny);
}

START_TEST(test_self_affine_rms_slope)
{
    mc_grid g = make_grid(40, 30, 0.5e-6, 0.7e-6);
    mc_scene s;
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_SELF_AFFINE;
    s.roughness.rq = 1e-6; /* ignored when rms_slope is set */
    s.roughness.rms_slope = 0.05;
    s.roughness.hurst = 0.8;
    s.roughness.seed = 3;
    double *h = generate(&g, &s);
    ck_assert_double_le(fabs(dft_rms_slope(&g, h) - 0.05), 1e-10 * 0.05);
    mc_surface_stats st;
    mc_surface_statistics(&g, h, &st);
    ck_assert_double_le(fabs(st.mean), 1e-12 * st.rq);
    /* central differences see less slope than the spectrum, but the same order */
    double fd = sqrt(st.rms_slope_x * st.rms_slope_x + st.rms_slope_y * st.rms_slope_y);
    ck_assert(fd < 0.05 && fd > 0.025);
    ck_assert_double_gt(fabs(st.rq - 1e-6), 1e-3 * 1e-6);

    s.roughness.rms_slope = 0.1; /* linear in the target */
    double *h2 = generate(&g, &s);
    for (size_t k = 0; k < mc_grid_cells(&g); k++)
        ck_assert_double_eq_tol(h2[k], 2 * h[k], TOL_ROUNDOFF * st.rq);
    mc_free(h2);

    s.roughness.rms_slope = 0; /* now rq applies, exactly */
    h2 = generate(&g, &s);
    mc_surface_statistics(&g, h2, &st);
    ck_assert_double_le(fabs(st.rq - 1e-6), TOL_ROUNDOFF * 1e-6);
    mc_free(h2);
    mc_free(h);
}
END_TEST

/* ---- files, topography, errors ----------------------------------------------------------- */

START_TEST(test_file_roughness_and_topography)
{
    const char *dir = test_tmpdir();
    mc_grid g = make_grid(8, 6, 1e-6, 1e-6);
    mc_scene s;
    blank_scene(&s, &g);
    double v[48], h[48], topo[48], shape[48];
    test_random_field(v, 48, 21);
    snprintf(s.roughness.file, sizeof s.roughness.file, "%s/h.npy", dir);
    size_t sh[2] = {6, 8};
    mc_error err = {0};
    ck_assert_int_eq(mc_npy_write(s.roughness.file, v, 2, sh, &err), MC_OK);
    s.roughness.type = MC_ROUGH_FILE;
    s.geometry.shape = MC_SHAPE_SPHERE;
    s.geometry.radius = 1e-4;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_OK);
    ck_assert_mem_eq(h, v, sizeof v);
    ck_assert_int_eq(mc_surface_topography(&g, &s.geometry, &s.roughness, topo, &err), MC_OK);
    mc_surface_shape(&g, &s.geometry, shape);
    for (int k = 0; k < 48; k++)
        ck_assert_double_eq(topo[k], shape[k] - v[k]);

    mc_grid g2 = make_grid(6, 8, 1e-6, 1e-6);
    ck_assert_int_eq(mc_surface_roughness(&g2, &s.roughness, h, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "[roughness] file: ") == err.msg &&
                      strstr(err.msg, "h.npy: the height map has 6 x 8 points (ny x nx)") &&
                      strstr(err.msg, "the mesh 8 x 6"),
                  "%s", err.msg);

    s.roughness.type = MC_ROUGH_NONE;
    for (int k = 0; k < 48; k++)
        h[k] = 1;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_OK);
    for (int k = 0; k < 48; k++)
        ck_assert_double_eq(h[k], 0);
}
END_TEST

START_TEST(test_bad_parameters)
{
    mc_grid g = make_grid(16, 16, 1e-6, 1e-6);
    mc_scene s;
    double h[256];
    mc_error err = {0};
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_GAUSSIAN;
    s.roughness.rq = -1e-6;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "[roughness] gaussian"), "%s", err.msg);
    s.roughness.rq = 1e-6;
    s.roughness.correlation_x = NAN;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_ERR_INPUT);

    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_SELF_AFFINE;
    s.roughness.rq = 1e-6;
    s.roughness.hurst = 1.5;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "hurst = 1.5"), "%s", err.msg);
    s.roughness.hurst = 0.5;
    s.roughness.lambda_long = 4e-6;
    s.roughness.lambda_short = 8e-6;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "must be below"), "%s", err.msg);
    /* a band entirely below the lowest grid wavenumber: nothing to synthesise */
    s.roughness.lambda_long = 64e-6;
    s.roughness.lambda_short = 32e-6;
    ck_assert_int_eq(mc_surface_roughness(&g, &s.roughness, h, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "no non-zero mode"), "%s", err.msg);

    mc_grid bad = make_grid(0, 16, 1e-6, 1e-6);
    ck_assert_int_eq(mc_surface_roughness(&bad, &s.roughness, h, &err), MC_ERR_INPUT);
}
END_TEST

START_TEST(test_fault_injection)
{
    mc_grid g = make_grid(32, 24, 1e-6, 1e-6);
    mc_scene s;
    blank_scene(&s, &g);
    s.roughness.type = MC_ROUGH_GAUSSIAN;
    s.roughness.rq = 1e-6;
    s.roughness.correlation_x = s.roughness.correlation_y = 3e-6;
    double topo[32 * 24];
    int failures = 0;
    for (long n = 1;; n++) {
        mc_error err = {0};
        mc_alloc_fail_at(n);
        int st = mc_surface_topography(&g, &s.geometry, &s.roughness, topo, &err);
        mc_alloc_fail_at(0);
        if (st == MC_OK)
            break;
        ck_assert_int_eq(st, MC_ERR_NOMEM);
        failures++;
        ck_assert_int_lt(n, 50);
    }
    ck_assert_int_eq(failures, 3); /* topography buffer, noise, spectrum */
}
END_TEST

START_TEST(test_statistics)
{
    /* A sine across x on a periodic grid: Sq = A/sqrt2, Sa -> 2A/pi, Ssk = 0, Sku = 3/2
     * exactly on whole periods; central differences give A sin(2 pi dx / L) / (dx sqrt 2)
     * exactly. */
    const int nx = 64, ny = 5;
    const double dx = 1e-6, A = 2e-6;
    mc_grid g = make_grid(nx, ny, dx, 2e-6);
    double h[64 * 5];
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            h[j * nx + i] = 1e-6 + A * sin(2 * M_PI * 2 * (i + 0.5) / nx);
    mc_surface_stats st;
    mc_surface_statistics(&g, h, &st);
    ck_assert_double_eq_tol(st.mean, 1e-6, TOL_ROUNDOFF * A);
    ck_assert_double_eq_tol(st.rq, A / sqrt(2), TOL_ROUNDOFF * A);
    /* sampled |sin|, 16 cells per half period: sum sin((2i+1) pi/32) = 1/sin(pi/32) */
    ck_assert_double_eq_tol(st.ra, A / (16 * sin(M_PI / 32)), TOL_ROUNDOFF * A);
    ck_assert_double_eq_tol(st.skewness, 0, TOL_ROUNDOFF);
    ck_assert_double_eq_tol(st.kurtosis, 1.5, TOL_ROUNDOFF);
    double want = A * sin(2 * M_PI * 2 * dx / (nx * dx)) / (dx * sqrt(2));
    ck_assert_double_eq_tol(st.rms_slope_x, want, TOL_ROUNDOFF * want);
    ck_assert_double_eq_tol(st.rms_slope_y, 0, TOL_ROUNDOFF);

    /* a ramp on free axes: one-sided differences at the ends keep the slope exact */
    g.periodic_x = g.periodic_y = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            h[j * nx + i] = 0.01 * i * dx - 0.02 * j * 2e-6;
    mc_surface_statistics(&g, h, &st);
    ck_assert_double_eq_tol(st.rms_slope_x, 0.01, TOL_ROUNDOFF);
    ck_assert_double_eq_tol(st.rms_slope_y, 0.02, TOL_ROUNDOFF);
}
END_TEST

Suite *suite_surface(void);
Suite *suite_surface(void)
{
    Suite *s = suite_create("surface");
    TCase *tc = tcase_create("surface");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_rng_reference);
    tcase_add_test(tc, test_rng_normal);
    tcase_add_test(tc, test_shapes);
    tcase_add_test(tc, test_gaussian_exact_and_reproducible);
    tcase_add_test(tc, test_gaussian_height_distribution);
    tcase_add_test(tc, test_gaussian_acf);
    tcase_add_test(tc, test_self_affine_spectrum);
    tcase_add_test(tc, test_self_affine_rms_slope);
    tcase_add_test(tc, test_file_roughness_and_topography);
    tcase_add_test(tc, test_bad_parameters);
    tcase_add_test(tc, test_fault_injection);
    tcase_add_test(tc, test_statistics);
    suite_add_tcase(s, tc);
    return s;
}
