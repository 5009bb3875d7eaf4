/* bench.c - the benchmark suite: its sections in report order (see bench.h). */
#include "bench.h"

#include <stdlib.h>

#include "operator/operator.h"
#include "pipeline/pipeline.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double mc_bench_time(void (*fn)(void *), void *arg, int reps)
{
    double t[64];
    if (reps > 64)
        reps = 64;
    if (reps < 1)
        reps = 1;
    fn(arg);
    for (int k = 0; k < reps; k++) {
        double t0 = mc_clock();
        fn(arg);
        t[k] = mc_clock() - t0;
    }
    qsort(t, (size_t)reps, sizeof t[0], cmp_double);
    return t[reps / 2];
}

static int run_bench(vf_ctx *ctx, int quick)
{
    vf_text(ctx, "All times on this machine (%d threads unless stated), measured in this run; the "
                 "ratios are what counts, absolute times drift with the machine's load.\n\n",
            mc_threads_count());
    int (*sections[])(vf_ctx *, int) = {mc_bench_operator, mc_bench_hertz,  mc_bench_rough,
                                         mc_bench_stress,   mc_bench_threads, mc_bench_skips,
                                         mc_bench_memory};
    int rc = 0;
    for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++)
        rc |= sections[k](ctx, quick);
    return rc;
}

const vf_suite mc_bench_suite = {"bench", "Benchmarks: run time against error and against FFTW",
                                 run_bench, "make bench"};
