/* bench.c - the benchmark suite: its sections in report order (see bench.h). */
#include "bench.h"

#include <fftw3.h>

#include <stdlib.h>
#include <string.h>

#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "plastic/eigen_op.h"

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

/* The sections in report order, by name (`microcontact bench NAME...` runs those alone). */
static const struct {
    const char *name;
    int (*run)(vf_ctx *, int);
} sections[] = {
    {"operator", mc_bench_operator}, {"hertz", mc_bench_hertz},     {"rough", mc_bench_rough},
    {"stress", mc_bench_stress},     {"threads", mc_bench_threads}, {"skips", mc_bench_skips},
    {"memory", mc_bench_memory},     {"plastic", mc_bench_plastic},   {"whole", mc_bench_whole},
    {"growth", mc_bench_growth},     {"runin", mc_bench_runin},     {"plans", mc_bench_plans},
    {"mpi", mc_bench_mpi},
};

static const char *only; /* comma-separated section names; NULL = all */

int mc_bench_select(const char *names)
{
    for (const char *p = names; p && *p;) {
        const size_t n = strcspn(p, ",");
        int found = 0;
        for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++)
            found |= strlen(sections[k].name) == n && !strncmp(sections[k].name, p, n);
        if (!found)
            return -1;
        p += n + (p[n] == ',');
    }
    only = names && *names ? names : NULL;
    return 0;
}

const char *mc_bench_section_names(void)
{
    return "operator, hertz, rough, stress, threads, skips, memory, plastic, whole, growth, runin, "
           "plans, mpi";
}

static int selected(const char *name)
{
    if (!only)
        return 1;
    const size_t n = strlen(name);
    for (const char *p = only; *p;) {
        const size_t m = strcspn(p, ",");
        if (m == n && !strncmp(p, name, n))
            return 1;
        p += m + (p[m] == ',');
    }
    return 0;
}

static int run_bench(vf_ctx *ctx, int quick)
{
    vf_text(ctx, "All times on this machine (%d threads unless stated), measured in this run; the "
                 "ratios are what counts, absolute times drift with the machine's load.\n\n",
            mc_threads_count());
    int rc = 0;
    for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++)
        if (selected(sections[k].name))
            rc |= sections[k].run(ctx, quick);
    return rc;
}

const vf_suite mc_bench_suite = {"bench", "Benchmarks: run time against error and against FFTW",
                                 run_bench, "make bench"};

void mc_bench_eig_stress(void *arg)
{
    mc_bench_eig *a = arg;
    mc_eigen_stress_apply(a->s, a->e, 80e9, a->sg);
}

void mc_bench_eig_disp(void *arg)
{
    mc_bench_eig *a = arg;
    mc_eigen_disp_apply(a->d, a->e, a->uz);
}

void mc_bench_pair_run(void *arg)
{
    mc_bench_pair *p = arg;
    fftw_execute((fftw_plan)p->f);
    fftw_execute((fftw_plan)p->b);
}
