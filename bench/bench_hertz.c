/* bench_hertz.c - work-precision of the Hertz point contact (steel/steel, R = 10 mm, F = 100 N,
 * square of side 3a): error of p_max, contact radius, approach and maximum von Mises against run
 * time, per backend and per solver, with iterations; compared with the published cost of CONTACT
 * and ContactMechanics on this kind of machine. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "contact/contact.h"
#include "reference/hertz.h"
#include "pipeline/pipeline.h"
#include "vutil.h"

#define R_SPHERE 10e-3
#define E_STEEL 210e9
#define NU 0.3
#define LOAD 100.0
#define BENCH_TOL 1e-6 /* CONTACT's accuracy in the published timings */
#define VM_MAX_P0 0.62004 /* theory.md §6.1, nu = 0.3 */
#define VM_DEPTH_A 0.48086

typedef struct {
    const char *id; /* CSV key (no commas: gnuplot splits on them) */
    const char *label;
    mc_contact_method method;
    mc_backend op;
    int max_n; /* largest grid this configuration runs at (the direct backend is O(N^2)) */
} config_t;

typedef struct {
    int N, iterations, converged;
    double total, contact, setup, stress, err_p, err_a, err_d, err_vm;
} result_t;

static int run(const mc_hertz_point *hz, int N, const config_t *cf, int with_stress, result_t *r)
{
    mc_scene sc;
    vu_scene(&sc, N, N, 3 * hz->a / N, 3 * hz->a / N);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = R_SPHERE;
    sc.body1 = sc.body2 = (mc_scene_material){E_STEEL, NU, 0};
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = LOAD;
    sc.solver.method = cf->method;
    sc.solver.backend = cf->op;
    sc.solver.tolerance = BENCH_TOL;
    sc.solver.max_iterations = 5000;
    if (with_stress) { /* five layers bracketing the depth of the von Mises maximum */
        sc.stress.enabled = 1;
        sc.stress.spacing = MC_SPACING_LIST;
        sc.stress.ndepths = 5;
        for (int k = 0; k < 5; k++)
            sc.stress.depths[k] = (VM_DEPTH_A - 0.02 + 0.01 * k) * hz->a;
    }
    mc_results res;
    mc_error err = {0};
    int rc = mc_pipeline_run(&sc, &res, &err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED) {
        fprintf(stderr, "bench hertz %s N=%d: %s\n", cf->label, N, err.msg);
        mc_results_free(&res);
        return rc;
    }
    r->N = N;
    r->iterations = res.contact.iterations;
    r->converged = res.contact.converged;
    r->total = res.timing.total_s;
    r->contact = res.timing.contact_s;
    r->setup = res.timing.setup_s;
    r->stress = res.timing.stress_s;
    r->err_p = fabs(res.contact.p_max / hz->p0 - 1);
    r->err_a = fabs(vu_fit_radius(&res, 0, hz->a, 0.8, NULL) / hz->a - 1);
    r->err_d = fabs(res.contact.approach / hz->delta - 1);
    r->err_vm = with_stress ? fabs(res.stress_summary.vm_max / (VM_MAX_P0 * hz->p0) - 1) : NAN;
    mc_results_free(&res);
    return MC_OK;
}

int mc_bench_hertz(vf_ctx *ctx, int quick)
{
    mc_hertz_point hz;
    mc_error err = {0};
    if (mc_hertz_point_from_load(R_SPHERE, E_STEEL / (2 * (1 - NU * NU)), LOAD, &hz, &err))
        return 1;
    static const int full[] = {64, 128, 256, 512, 1024}, small[] = {64, 128, 256};
    const int *Ns = quick ? small : full;
    int nN = quick ? 3 : 5;
    static const config_t configs[] = {
        {"cg_fft", "cg (preconditioned), fft", MC_METHOD_CG, MC_BACKEND_FFT, 1 << 20},
        {"pk_fft", "pk (plain Polonsky-Keer), fft", MC_METHOD_PK, MC_BACKEND_FFT, 1 << 20},
        {"cg_direct", "cg, direct", MC_METHOD_CG, MC_BACKEND_DIRECT, 64},
        {"pk_direct", "pk, direct", MC_METHOD_PK, MC_BACKEND_DIRECT, 64},
    };
    FILE *f = vf_open(ctx, "hertz.csv");
    if (!f)
        return 1;
    fprintf(f, "config,N,iterations,converged,total_s,contact_s,setup_s,stress_s,err_pmax,"
               "err_radius,err_approach,err_vm\n");
    vf_text(ctx,
            "## Hertz point contact: run time against error\n\n"
            "Steel on steel, R = 10 mm, F = 100 N (a = %.1f um, p0 = %.0f MPa), square domain of "
            "side 3a with N x N cells, solver tolerance %.0e (CONTACT's accuracy in the published "
            "timings). `total` is the whole run (topography, kernel table and spectrum, solve, "
            "and five stress layers around the von Mises maximum at 0.48a); `contact` the solve "
            "alone. Errors against Hertz: p_max, the fitted radius, the approach and the maximum "
            "von Mises stress (0.62004 p0).\n\n"
            "| solver, backend | N | iterations | total (s) | contact (s) | stress (s) | p_max err "
            "| radius err | approach err | vM err |\n|---|---|---|---|---|---|---|---|---|---|\n",
            hz.a * 1e6, hz.p0 * 1e-6, BENCH_TOL);
    for (size_t c = 0; c < sizeof configs / sizeof configs[0]; c++) {
        for (int k = 0; k < nN; k++) {
            if (Ns[k] > configs[c].max_n)
                continue;
            result_t r;
            if (run(&hz, Ns[k], &configs[c], 1, &r) != MC_OK) {
                vf_fail(ctx, "hertz_run", "%s at N = %d failed", configs[c].label, Ns[k]);
                continue;
            }
            fprintf(f, "%s,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.4e,%.4e,%.4e,%.4e\n",
                    configs[c].id, r.N, r.iterations, r.converged, r.total, r.contact, r.setup,
                    r.stress, r.err_p, r.err_a, r.err_d, r.err_vm);
            vf_text(ctx, "| %s | %d² | %d%s | %.3f | %.3f | %.3f | %.1e | %.1e | %.1e | %.1e |\n",
                    configs[c].label, r.N, r.iterations, r.converged ? "" : " (not converged)",
                    r.total, r.contact, r.stress, r.err_p, r.err_a, r.err_d, r.err_vm);
        }
    }
    vf_close(ctx, f);
    /* the elastic run alone (no stress layers), as CONTACT's published whole-run times */
    const config_t *cg = &configs[0];
    result_t e512 = {0}, e1024 = {0};
    if (!quick && run(&hz, 1024, cg, 0, &e1024) == MC_OK)
        vf_check(ctx, "hertz_1024_time", "Hertz 1024², cg, whole elastic run (s)",
                 "target <= 2 s (1/4 of CONTACT's 7.6-12 s)", 2.0, e1024.total, 2.0, VF_MAX);
    if (run(&hz, 512, cg, 0, &e512) == MC_OK)
        vf_text(ctx, "\nWhole elastic run (no stress layers), cg on fft: 512² in %.3f s "
                     "(%d iterations). Published on this kind of machine: CONTACT (Fortran + MKL, "
                     "preconditioned CG) 512² in 1.1-2.6 s and 1024² in 7.6-12 s with 14 and 19 "
                     "iterations; ContactMechanics (Python, Polonsky-Keer) 512² in 8.2 s and "
                     "1024² in 36-45 s.\n",
                e512.total, e512.iterations);
    if (!quick && e1024.N)
        vf_text(ctx, "1024² in %.3f s (%d iterations): %.1f to %.1f times faster than CONTACT, "
                     "%.0f to %.0f times faster than ContactMechanics.\n",
                e1024.total, e1024.iterations, 7.6 / e1024.total, 12.0 / e1024.total,
                36.0 / e1024.total, 45.0 / e1024.total);
    vf_text(ctx, "\n");
    vf_plot(ctx, "hertz_work_precision.png",
            "Hertz point contact: error of p_max against whole run time, per solver and backend",
            "set datafile separator ','\nset logscale xy\nset key top right\n"
            "set xlabel 'run time (s)'\nset ylabel 'relative error of p_{max}'\nset grid\n"
            "plot 'hertz.csv' using (strcol(1) eq 'cg_fft' ? $5 : 1/0):9 "
            "with linespoints pt 7 title 'cg, fft', "
            "'' using (strcol(1) eq 'pk_fft' ? $5 : 1/0):9 "
            "with linespoints pt 5 title 'pk, fft', "
            "'' using (strcol(1) eq 'cg_direct' ? $5 : 1/0):9 with points pt 9 ps 1.5 "
            "title 'cg, direct', "
            "'' using (strcol(1) eq 'pk_direct' ? $5 : 1/0):9 with points pt 11 ps 1.5 "
            "title 'pk, direct'");
    vf_plot(ctx, "hertz_iterations.png", "Iterations against grid size: plain PK and cg",
            "set datafile separator ','\nset logscale x 2\nset key top left\n"
            "set xlabel 'N (N x N grid)'\nset ylabel 'iterations'\nset grid\n"
            "plot 'hertz.csv' using (strcol(1) eq 'cg_fft' ? $2 : 1/0):3 "
            "with linespoints pt 7 title 'cg (preconditioned, nested start)', "
            "'' using (strcol(1) eq 'pk_fft' ? $2 : 1/0):3 "
            "with linespoints pt 5 title 'pk'");
    return 0;
}
