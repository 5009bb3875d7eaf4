/* bench_stress.c - subsurface stress: time per depth layer (six components) against its FFT
 * lower bound (one forward and six inverse transforms of the padded size), and against the
 * published cost of CONTACT (1.2-1.4 s per layer at 512²). */
#include <fftw3.h>
#include <math.h>
#include <stdio.h>

#include "core/alloc.h"
#include "bench.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "stress/stress.h"

#define LAYERS 4

typedef struct {
    fftw_plan f, b;
} lb_arg;

static void do_lb(void *a)
{
    lb_arg *x = a;
    fftw_execute(x->f);
    for (int k = 0; k < 6; k++)
        fftw_execute(x->b);
}

static double lower_bound(int tx, int ty)
{
    double *r = fftw_malloc(sizeof(double) * (size_t)tx * ty);
    fftw_complex *c = fftw_malloc(sizeof(fftw_complex) * (size_t)ty * (tx / 2 + 1));
    if (!r || !c) {
        fftw_free(r);
        fftw_free(c);
        return NAN;
    }
    mc_fftw_prepare(NULL);
    lb_arg a = {fftw_plan_dft_r2c_2d(ty, tx, r, c, FFTW_ESTIMATE),
                fftw_plan_dft_c2r_2d(ty, tx, c, r, FFTW_ESTIMATE)};
    for (size_t i = 0; i < (size_t)tx * ty; i++)
        r[i] = (double)(i % 11);
    double t = mc_bench_time(do_lb, &a, 5);
    fftw_destroy_plan(a.f);
    fftw_destroy_plan(a.b);
    fftw_free(r);
    fftw_free(c);
    return t;
}

/* Seconds per layer of mc_stress_field over LAYERS layers, with the breakdown. */
static double layer_time(int N, int friction, mc_stress_timing *tm, int *tx, int *ty)
{
    mc_grid g = {N, N, 1e-6, 1e-6, 0, 0};
    double depths[LAYERS];
    for (int k = 0; k < LAYERS; k++)
        depths[k] = (2.0 + 8.0 * k) * g.dx;
    mc_stress_options o = {MC_STRESS_PATCH, 0.3, LAYERS, depths, MC_BACKEND_FFT,
                           MC_TRACTION_P | (friction ? MC_TRACTION_QX : 0), 0};
    mc_stress_plan *op = NULL;
    mc_error err = {0};
    size_t n = (size_t)N * N, nv = n * LAYERS;
    double *p = mc_zeros(n), *q = mc_zeros(n), *s[6] = {0};
    int ok = p && q;
    for (int c = 0; c < 6; c++)
        ok &= (s[c] = mc_zeros(nv)) != NULL;
    double t = NAN;
    if (ok && mc_stress_create(&g, &o, &op, &err) == MC_OK) {
        for (size_t i = 0; i < n; i++) {
            p[i] = 1e9 * (1.0 + 0.5 * sin(0.01 * (double)i));
            q[i] = 0.1 * p[i];
        }
        double t0 = mc_clock();
        if (mc_stress_field(op, p, friction ? q : NULL, NULL, s, &err) == MC_OK)
            t = (mc_clock() - t0) / LAYERS;
        mc_stress_timing_get(op, tm);
        mc_conv *c = NULL;
        if (mc_conv_create(&g, MC_BACKEND_FFT, &c, &err) == MC_OK) {
            mc_conv_table_dims(c, tx, ty);
            mc_conv_destroy(&c);
        }
    }
    mc_stress_destroy(&op);
    mc_free(p);
    mc_free(q);
    for (int c = 0; c < 6; c++)
        mc_free(s[c]);
    return t;
}

int mc_bench_stress(vf_ctx *ctx, int quick)
{
    static const int sizes[] = {256, 512, 1024};
    int nsizes = quick ? 2 : 3;
    FILE *f = vf_open(ctx, "stress.csv");
    if (!f)
        return 1;
    fprintf(f, "N,friction,layer_s,tables_s,kernels_s,apply_s,lower_bound_s,ratio\n");
    vf_text(ctx, "## Subsurface stress: time per layer\n\n"
                 "Six stress components of one depth layer on an N x N free grid (patch kernel, "
                 "mean over %d layers of one `mc_stress_field` call; the load transforms are "
                 "shared by the layers), pressure only and with a friction traction, against the "
                 "FFT lower bound of one r2c and six c2r of the same padded size. Breakdown per "
                 "layer: kernel tables, kernel transforms, products and inverse transforms. "
                 "CONTACT: 1.2-1.4 s per layer at 512².\n\n"
                 "| N | loads | per layer (ms) | tables | kernel FFTs | apply | FFT bound (ms) "
                 "| ratio |\n|---|---|---|---|---|---|---|---|\n",
            LAYERS);
    for (int k = 0; k < nsizes; k++)
        for (int fr = 0; fr < 2; fr++) {
            int N = sizes[k], tx = 2 * N, ty = 2 * N;
            mc_stress_timing tm = {0};
            double t = layer_time(N, fr, &tm, &tx, &ty);
            double lb = lower_bound(tx, ty);
            double L = tm.layers > 0 ? (double)tm.layers : 1.0;
            fprintf(f, "%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.4f\n", N, fr, t, tm.tables / L,
                    tm.kernels / L, tm.apply / L, lb, t / lb);
            vf_text(ctx, "| %d² | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f |\n", N,
                    fr ? "p + q_x" : "p", 1e3 * t, 1e3 * tm.tables / L, 1e3 * tm.kernels / L,
                    1e3 * tm.apply / L, 1e3 * lb, t / lb);
            if (N == 512) {
                char id[48];
                snprintf(id, sizeof id, "stress_layer_512_%s", fr ? "friction" : "normal");
                vf_check(ctx, id, fr ? "stress layer 512², p + q_x (s)" : "stress layer 512², p (s)",
                         "target <= 1/10 of CONTACT's 1.2 s", 0.12, t, 0.12, VF_MAX);
            }
        }
    vf_close(ctx, f);
    vf_text(ctx, "\n");
    return 0;
}
