/* bench_skips.c - what each skip saves, measured on a scene where it applies, and the effect of
 * threads. A skip must not change results beyond its stated tolerance: the tests prove that
 * (tests/test_contact.c, tests/test_stress.c, tests/test_operator.c); here only time is measured. */
#include <math.h>
#include <stdio.h>

#include "core/alloc.h"
#include "contact/contact.h"
#include "surface/surface.h"
#include "bench.h"
#include "reference/hertz.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "stress/stress.h"
#include "pipeline/stage_stress.h"
#include "vutil.h"

static void hertz_scene(mc_scene *sc, int N)
{
    const double a = 186.6e-6;
    vu_scene(sc, N, N, 3 * a / N, 3 * a / N);
    sc->geometry.shape = MC_SHAPE_SPHERE;
    sc->geometry.radius = 10e-3;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = 100;
    sc->solver.tolerance = 1e-6;
}

static double run_time(const mc_scene *sc, double *contact_s, double *stress_s, int *iters)
{
    mc_results res;
    mc_error err = {0};
    int rc = mc_pipeline_run(sc, &res, &err);
    double t = rc == MC_OK ? res.timing.total_s : NAN;
    if (contact_s)
        *contact_s = res.timing.contact_s;
    if (stress_s)
        *stress_s = res.timing.stress_s;
    if (iters)
        *iters = res.contact.iterations;
    mc_results_free(&res);
    return t;
}

typedef struct {
    mc_operator *op;
    double *f;
} ap_arg;

static void do_apply(void *a)
{
    ap_arg *x = a;
    mc_operator_apply(x->op, x->f, x->f);
}

static double apply_time(int N, int periodic)
{
    mc_grid g = {N, N, 1e-6, 1e-6, periodic, periodic};
    mc_error err = {0};
    ap_arg a = {NULL, mc_zeros((size_t)N * N)};
    double t = NAN;
    if (a.f && mc_operator_plan_love(&g, 1e11, MC_BACKEND_FFT, &a.op, &err) == MC_OK)
        t = mc_bench_time(do_apply, &a, 7);
    mc_operator_destroy(&a.op);
    mc_free(a.f);
    return t;
}

/* Solver creation plus solve (s) of the scene's contact with or without the nested start. */
static double contact_time(const mc_scene *sc, int nested, int box, int *iters)
{
    const mc_grid *g = &sc->grid;
    size_t n = mc_grid_cells(g);
    double *h = mc_zeros(n), *p = mc_zeros(n), t = NAN;
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    mc_error err = {0};
    double estar = mc_scene_estar(sc);
    if (h && p && mc_surface_topography(g, &sc->geometry, &sc->roughness, h, &err) == MC_OK &&
        mc_operator_plan_love(g, estar, MC_BACKEND_FFT, &K, &err) == MC_OK) {
        mc_contact_options opt = {MC_METHOD_CG, sc->solver.tolerance, 5000, nested ? estar : 0,
                                  !box};
        mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                                   .load = sc->load.value};
        mc_contact_summary sum;
        double t0 = mc_clock();
        if (mc_contact_create(K, &opt, &s, &err) == MC_OK &&
            mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err) == MC_OK) {
            t = mc_clock() - t0;
            *iters = sum.iterations;
        }
    }
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_free(h);
    mc_free(p);
    return t;
}

/* Seconds of the stress stage on solved results with the speed-ups of tune: the best of three
 * (the first run of a configuration pays page faults for its volumes). */
static double stage_time(const mc_scene *sc, mc_results *res, const mc_stress_tuning *tune)
{
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        mc_error err = {0};
        double t0 = mc_clock();
        if (mc_stage_stress_tuned(sc, res, tune, &err) != MC_OK)
            return NAN;
        best = fmin(best, mc_clock() - t0);
    }
    return best;
}

/* Solve a Hertz contact of radius a_cells on an N x N grid (dx = 1 um) with a [stress] section of
 * 32 layers to the automatic depth and friction 0.3 (W scales the Hertz load). */
static int small_contact(int N, double a_cells, double W_scale, mc_scene *sc, mc_results *res)
{
    const double R = 10e-3, estar = 210e9 / (2 * (1 - 0.09)), dx = 1e-6, a = a_cells * dx;
    vu_scene(sc, N, N, dx, dx);
    sc->geometry.shape = MC_SHAPE_SPHERE;
    sc->geometry.radius = R;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = W_scale * 4 * estar * a * a * a / (3 * R);
    sc->stress.enabled = 1;
    sc->stress.layers = 32;
    sc->stress.depth_max = MC_STRESS_DEPTH_AUTO;
    sc->stress.friction = 0.3;
    mc_error err = {0};
    int rc = mc_pipeline_run(sc, res, &err);
    if (rc != MC_OK)
        mc_results_free(res);
    return rc;
}

/* The stress skips, each on a scene where it applies: the symmetric quadrant transforms on a
 * small Hertz contact (radius N/32 cells); the window on a smaller one (N/64: the window pays
 * when the contact is small against the grid, its margin being 7 R + 2.5 z); the automatic depth
 * against covering 10 a at the same layer spacing; the sparse sum on a contact of a few cells. */
static void stress_skips(vf_ctx *ctx, int quick)
{
    const int N = quick ? 256 : 512;
    mc_scene sc;
    mc_results res;
    mc_stress_tuning on = {MC_STRESS_AUTO, MC_STRESS_AUTO, MC_STRESS_AUTO};
    mc_stress_tuning no_window = on, no_sym = on, no_sparse = on;
    mc_stress_tuning none = {MC_STRESS_OFF, MC_STRESS_OFF, MC_STRESS_OFF};
    no_window.window = MC_STRESS_OFF;
    no_sym.symmetric = MC_STRESS_OFF;
    no_sparse.sparse = MC_STRESS_OFF;
    if (small_contact(N, N / 32.0, 1.0, &sc, &res) == MC_OK) {
        double t_on = stage_time(&sc, &res, &on), t_ns = stage_time(&sc, &res, &no_sym);
        double t_none = stage_time(&sc, &res, &none);
        /* the same layer spacing down to 10 a instead of the automatic 3 patch radii */
        mc_scene deep = sc;
        double a = N / 32.0 * 1e-6, auto_depth = res.stress_summary.depth_max;
        deep.stress.depth_max = 10 * a;
        deep.stress.layers = (int)ceil(31 * 10 * a / auto_depth) + 1;
        if (deep.stress.layers > MC_MAX_DEPTHS)
            deep.stress.layers = MC_MAX_DEPTHS;
        double t_deep = stage_time(&deep, &res, &on);
        vf_text(ctx, "| stress kernel spectra by symmetric r2r transforms of one quadrant | Hertz a = "
                     "%d cells on %d², friction 0.3, 32 layers | %.3f | %.3f | %.0f %% |\n",
                N / 32, N, t_on, t_ns, 100 * (1 - t_on / t_ns));
        vf_text(ctx, "| stresses only to the depth that matters (depth_max = auto: %.1f a) | same, "
                     "against down to 10 a at the same spacing (%d layers) | %.3f | %.3f | %.0f %% "
                     "|\n",
                auto_depth / a, deep.stress.layers, t_on, t_deep, 100 * (1 - t_on / t_deep));
        vf_text(ctx, "| all stress skips together | Hertz a = %d cells on %d² | %.3f | %.3f | %.0f "
                     "%% |\n",
                N / 32, N, t_on, t_none, 100 * (1 - t_on / t_none));
        mc_results_free(&res);
    }
    if (small_contact(N, N / 64.0, 1.0, &sc, &res) == MC_OK) {
        double t_on = stage_time(&sc, &res, &on), t_nw = stage_time(&sc, &res, &no_window);
        vf_text(ctx, "| stresses only over the loaded region plus a margin (window) | Hertz a = %d "
                     "cells on %d², friction 0.3, 32 layers | %.3f | %.3f | %.0f %% |\n",
                N / 64, N, t_on, t_nw, 100 * (1 - t_on / t_nw));
        mc_results_free(&res);
    }
    if (small_contact(N, N / 32.0, 1e-4, &sc, &res) == MC_OK) {
        double t_sp = stage_time(&sc, &res, &on), t_nsp = stage_time(&sc, &res, &no_sparse);
        vf_text(ctx, "| sparse sum over the loaded cells (cost model) | a %ld-cell contact on %d², "
                     "32 layers | %.3f | %.3f | %.0f %% |\n",
                (long)(res.contact.area / 1e-12 + 0.5), N, t_sp, t_nsp, 100 * (1 - t_sp / t_nsp));
        mc_results_free(&res);
    }
}

int mc_bench_skips(vf_ctx *ctx, int quick)
{
    int N = quick ? 256 : 512;
    vf_text(ctx, "## Skips: what a scene does not need\n\n| skip | scene | with (s) | without (s) "
                 "| saved |\n|---|---|---|---|---|\n");
    mc_scene sc;
    /* 1. no stress stage unless asked for */
    hertz_scene(&sc, N);
    double t_off = run_time(&sc, NULL, NULL, NULL);
    sc.stress.enabled = 1;
    sc.stress.depth_min = 0;
    sc.stress.depth_max = 300e-6;
    sc.stress.layers = 32;
    double st = 0, t_on = run_time(&sc, NULL, &st, NULL);
    vf_text(ctx, "| no stress stage without [stress] | Hertz %d², 32 layers asked or not | %.3f | "
                 "%.3f | %.0f %% |\n",
            N, t_off, t_on, 100 * (1 - t_off / t_on));
    /* 2. nested coarse start: spares fine iterations that only shrink the contact set */
    hertz_scene(&sc, quick ? 512 : 1024);
    int i_nested = 0, i_plain = 0;
    double c_nested = contact_time(&sc, 1, 0, &i_nested), c_plain = contact_time(&sc, 0, 0, &i_plain);
    vf_text(ctx, "| coarse-grid (nested) start: spares the fine iterations that only shrink the "
                 "contact set | Hertz %d², cg, solver set-up + solve | %.3f (%d fine it.) | %.3f "
                 "(%d it.) | %.0f %% |\n",
            sc.grid.nx, c_nested, i_nested, c_plain, i_plain, 100 * (1 - c_nested / c_plain));
    /* 3. the solve on the contact's bounding box: a small contact on a large grid (side 10a) */
    hertz_scene(&sc, quick ? 512 : 1024);
    sc.grid.dx = sc.grid.dy = 10 * 186.6e-6 / sc.grid.nx;
    int i_box = 0, i_full = 0;
    double c_box = contact_time(&sc, 1, 1, &i_box), c_full = contact_time(&sc, 1, 0, &i_full);
    vf_text(ctx, "| solve on the contact's bounding box | Hertz on a %d² grid of side 10a, cg | %.3f "
                 "| %.3f | %.0f %% |\n",
            sc.grid.nx, c_box, c_full, 100 * (1 - c_box / c_full));
    /* 4. no padding along periodic axes */
    int Np = quick ? 512 : 1024;
    double t_free = apply_time(Np, 0), t_per = apply_time(Np, 1);
    vf_text(ctx, "| no padding along periodic axes | operator apply %d² | %.4f | %.4f | %.0f %% |\n",
            Np, t_per, t_free, 100 * (1 - t_per / t_free));
    stress_skips(ctx, quick);
    vf_text(ctx, "\nEach skip leaves the results unchanged within its stated tolerance: tests in "
                 "tests/test_contact.c (nested start, box), tests/test_stress.c (window, symmetric "
                 "transforms, sparse sums) and tests/test_operator.c (periodic axes).\n\n");
    return 0;
}
