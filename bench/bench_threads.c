/* bench_threads.c - one against two threads (OpenMP loops and FFTW threads) on the Hertz solve
 * and on a stress layer. */
#include <math.h>
#include <stdio.h>

#include "bench.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "vutil.h"

static double hertz_time(int N, int threads, int stress)
{
    const double a = 186.6e-6;
    mc_scene sc;
    vu_scene(&sc, N, N, 3 * a / N, 3 * a / N);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = 10e-3;
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = 100;
    sc.solver.tolerance = 1e-6;
    sc.solver.threads = threads;
    if (stress) {
        sc.stress.enabled = 1;
        sc.stress.depth_max = 300e-6;
        sc.stress.layers = 8;
    }
    mc_results res;
    mc_error err = {0};
    int rc = mc_pipeline_run(&sc, &res, &err);
    double t = rc == MC_OK ? (stress ? res.timing.stress_s / 8 : res.timing.total_s) : NAN;
    mc_results_free(&res);
    return t;
}

int mc_bench_threads(vf_ctx *ctx, int quick)
{
    int N = quick ? 256 : 512;
    double h1 = hertz_time(N, 1, 0), h2 = hertz_time(N, 2, 0);
    double s1 = hertz_time(N, 1, 1), s2 = hertz_time(N, 2, 1);
    vf_text(ctx, "## Threads\n\n| task | 1 thread (s) | 2 threads (s) | speed-up |\n|---|---|---|---|\n"
                 "| Hertz %d², cg, whole elastic run | %.3f | %.3f | %.2f |\n"
                 "| stress layer at %d² (6 components) | %.4f | %.4f | %.2f |\n\n",
            N, h1, h2, h1 / h2, N, s1, s2, s1 / s2);
    return 0;
}
