/* thread_default.c - the default thread count of a run started directly: the cores this process
 * may use less the other tasks running at its start (docs/architecture.md "Threads").
 *
 * Why: with two threads on a machine where another process holds one of the two cores, a run
 * was up to 6 % slower than with one thread even with sleeping waits (wait_policy.c; bench
 * threads, Hertz 512²), and 4-6x slower with spinning ones: a thread that shares its core with
 * another job makes every barrier wait for it. The kernel's count of runnable tasks
 * (/proc/loadavg, fourth field "running/total", this process included) says how many cores are
 * taken now; the least of a few samples 2 ms apart ignores a task that only passes by. A user's
 * OMP_NUM_THREADS, or [solver] threads / --set solver.threads=N in the case, decide instead.
 * Our own sums give the same bits on any thread count (tests/test_thread_count.c,
 * tests/test_eigen_threads.c), FFTW's threaded transforms not on every count (3 threads), so
 * `verify` takes every core (mc_cli_thread_all; docs/architecture.md "Threads").
 *
 * The decision is split from the reading so that it can be tested without a loaded machine:
 * mc_cli_loadavg_running parses one /proc/loadavg text, mc_cli_free_cores_from turns the samples
 * into the count (tests/test_thread_default.c); mc_cli_free_cores only reads and sleeps. */
#define _GNU_SOURCE
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "cli/cli.h"

#define SAMPLES 3

int mc_cli_loadavg_running(const char *text)
{
    double l1, l5, l15;
    int run, total;
    if (!text || sscanf(text, "%lf %lf %lf %d/%d", &l1, &l5, &l15, &run, &total) != 5 || run < 0)
        return -1;
    return run;
}

int mc_cli_free_cores_from(int procs, const int *running, int nsamples)
{
    int least = -1;
    for (int k = 0; k < nsamples; k++) /* < 1 cannot be (this process runs): unreadable */
        if (running[k] >= 1 && (least < 0 || running[k] < least))
            least = running[k];
    if (least < 1)
        return procs; /* unknown: every core, as the OpenMP runtime would */
    const int n = procs - (least - 1); /* this process is one of the running tasks */
    return n < 1 ? 1 : n;
}

/* Runnable tasks system-wide now, this one included; -1 when /proc/loadavg cannot be read. */
static int running_tasks(void)
{
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return -1;
    char line[128];
    const int run = fgets(line, sizeof line, f) ? mc_cli_loadavg_running(line) : -1;
    fclose(f);
    return run;
}

int mc_cli_free_cores(void)
{
    int running[SAMPLES];
    for (int k = 0; k < SAMPLES; k++) {
        if (k > 0)
            nanosleep(&(struct timespec){.tv_sec = 0, .tv_nsec = 2000000}, NULL);
        running[k] = running_tasks();
    }
    return mc_cli_free_cores_from(omp_get_num_procs(), running, SAMPLES);
}

void mc_cli_thread_default(void)
{
    if (getenv("OMP_NUM_THREADS"))
        return;
    omp_set_num_threads(mc_cli_free_cores());
}

void mc_cli_thread_all(void)
{
    if (getenv("OMP_NUM_THREADS"))
        return;
    omp_set_num_threads(omp_get_num_procs());
}
