/* bench_threads.c - one against two threads (OpenMP loops and FFTW threads), stage by stage
 * (issue 13 item 2): the whole Hertz run of bench_whole.c as a child process, its summary.json
 * timings per stage; a stress layer; an elastic-plastic running-in step. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "core/threads.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "vutil.h"

#define WHOLE_MIN_SPEEDUP 1.8 /* issue 13 item 2: the whole 1024^2 run, 1 -> 2 threads */
/* issue 22 item 5: the default thread count never slower than one thread; the least of three
 * whole runs of 0.2-0.5 s scatters by a few per cent between rounds (measured), hence 1.05 */
#define DEFAULT_MAX_RATIO 1.05

/* the stages of a whole run: summary.json timings, and the process around them */
enum { ST_SETUP, ST_CONTACT, ST_OTHER, ST_OUTSIDE, ST_WHOLE, NST };
static const char *stage_names[NST] = {
    "setup (kernel tables, spectra, plans)", "contact solve (coarse start, iterations, box)",
    "other (topography, summaries)", "outside (process start, case, writing outputs, exit)",
    "whole process"};

/* The least wall time over `rounds` runs of the Hertz case on T threads (1 and 2 alternate, so a
 * change of the machine's load hits both), with that run's stage times in st[T - 1][]. */
static int whole_runs(const char *self, const char *dir, int N, int rounds, double st[2][NST])
{
    char ini[1100], out[1100], js[1200];
    snprintf(ini, sizeof ini, "%s/hertz%d.ini", dir, N);
    if (mc_bench_hertz_case(ini, N))
        return 1;
    for (int t = 0; t < 2; t++)
        st[t][ST_WHOLE] = INFINITY;
    for (int r = 0; r < rounds; r++)
        for (int t = 0; t < 2; t++) {
            char set[40];
            snprintf(set, sizeof set, "solver.threads=%d", t + 1);
            snprintf(out, sizeof out, "%s/out%d_%d_%d", dir, N, t, r);
            const char *argv[] = {self, "run", ini, "--out", out, "--set", set, NULL};
            const double w = mc_bench_run_child(argv);
            if (!(w > 0))
                return 1;
            snprintf(js, sizeof js, "%s/summary.json", out);
            if (w < st[t][ST_WHOLE]) {
                const double total = mc_bench_json_number(js, "total_s");
                st[t][ST_SETUP] = mc_bench_json_number(js, "setup_s");
                st[t][ST_CONTACT] = mc_bench_json_number(js, "contact_s");
                st[t][ST_OTHER] = total - st[t][ST_SETUP] - st[t][ST_CONTACT];
                st[t][ST_OUTSIDE] = w - total;
                st[t][ST_WHOLE] = w;
            }
            mc_bench_remove_tree(out);
        }
    return 0;
}

/* ---- the default thread count against one thread, quiet and beside a busy process ----------- */

/* A process that spins on one core until killed: another user's job on a shared machine. */
static pid_t start_spinner(void)
{
    fflush(NULL);
    const pid_t pid = fork();
    if (pid == 0) {
        volatile unsigned long x = 0;
        for (;;)
            x++;
    }
    return pid;
}

static void stop_spinner(pid_t pid)
{
    if (pid > 0) {
        kill(pid, SIGKILL);
        waitpid(pid, NULL, 0);
    }
}

/* The least wall time of `rounds` whole Hertz runs of case ini for each variant, alternating:
 * v = 0 one thread; 1 the default (no thread count, OMP_WAIT_POLICY and OMP_NUM_THREADS unset:
 * the program sets passive waits itself and takes the cores that are free, cli/wait_policy.c,
 * cli/thread_default.c); 2 the OpenMP runtime's own defaults (every core, spinning waits:
 * OMP_WAIT_POLICY=active, OMP_NUM_THREADS = the cores); 3 every core with passive waits (the
 * program's default before it counted the free cores). */
#define NVAR 4
static void policy_runs(const char *self, const char *dir, const char *ini, int rounds,
                        double w[NVAR])
{
    static const char *const policy[NVAR] = {NULL, NULL, "active", "passive"};
    char cores[16];
    snprintf(cores, sizeof cores, "%d", omp_get_num_procs());
    const char *const nthreads[NVAR] = {NULL, NULL, cores, cores};
    const char *saved = getenv("OMP_WAIT_POLICY"), *saved_n = getenv("OMP_NUM_THREADS");
    char keep[64] = "", keep_n[64] = "";
    if (saved)
        snprintf(keep, sizeof keep, "%s", saved);
    if (saved_n)
        snprintf(keep_n, sizeof keep_n, "%s", saved_n);
    for (int v = 0; v < NVAR; v++)
        w[v] = INFINITY;
    for (int r = 0; r < rounds; r++)
        for (int v = 0; v < NVAR; v++) {
            char out[1100];
            snprintf(out, sizeof out, "%s/pol%d_%d", dir, v, r);
            if (policy[v])
                setenv("OMP_WAIT_POLICY", policy[v], 1);
            else
                unsetenv("OMP_WAIT_POLICY");
            if (nthreads[v])
                setenv("OMP_NUM_THREADS", nthreads[v], 1);
            else
                unsetenv("OMP_NUM_THREADS");
            const char *one[] = {self, "run", ini, "--out", out, "--set", "solver.threads=1", NULL};
            const char *dflt[] = {self, "run", ini, "--out", out, NULL};
            const double t = mc_bench_run_child(v == 0 ? one : dflt);
            w[v] = t < w[v] ? t : w[v];
            mc_bench_remove_tree(out);
        }
    if (saved)
        setenv("OMP_WAIT_POLICY", keep, 1);
    else
        unsetenv("OMP_WAIT_POLICY");
    if (saved_n)
        setenv("OMP_NUM_THREADS", keep_n, 1);
    else
        unsetenv("OMP_NUM_THREADS");
}

/* One stress layer of the Hertz solve on N x N (the stage's time / layers), on T threads. */
static double layer_time(int N, int threads)
{
    const double a = 186.6e-6;
    mc_scene sc;
    vu_scene(&sc, N, N, 3 * a / N, 3 * a / N);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = 10e-3;
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = 100;
    sc.solver.threads = threads;
    sc.stress.enabled = 1;
    sc.stress.depth_max = 300e-6;
    sc.stress.layers = 8;
    mc_results res;
    mc_error err = {0};
    int rc = mc_pipeline_run(&sc, &res, &err);
    double t = rc == MC_OK ? res.timing.stress_s / 8 : NAN;
    mc_results_free(&res);
    return t;
}

int mc_bench_threads(vf_ctx *ctx, int quick)
{
    const int N = quick ? 512 : 1024;
    char self[1024], dir[] = "/tmp/mc_bench_threads_XXXXXX";
    const ssize_t sl = readlink("/proc/self/exe", self, sizeof self - 1);
    if (sl <= 0 || !mkdtemp(dir))
        return 1;
    self[sl] = '\0';
    double st[2][NST];
    const int bad = whole_runs(self, dir, N, quick ? 2 : 3, st);
    /* the default thread count, quiet and beside a spinning process (issue 22 item 5) */
    const int NP = quick ? 256 : 512;
    char pini[1100];
    snprintf(pini, sizeof pini, "%s/hertz%d.ini", dir, NP);
    double wq[NVAR], wb[NVAR];
    const int pbad = mc_bench_hertz_case(pini, NP);
    if (!pbad) {
        policy_runs(self, dir, pini, 3, wq);
        const pid_t spin = start_spinner();
        policy_runs(self, dir, pini, 3, wb);
        stop_spinner(spin);
    }
    mc_bench_remove_tree(dir);
    const int SN = quick ? 256 : 512;
    const double s1 = layer_time(SN, 1), s2 = layer_time(SN, 2);
    /* the default running-in scene's first force at 350 rpm on 128 x 64 cells (8 layers) */
    int plastic = 0;
    const double r1 = mc_bench_runin_step(128, 64, "350 rpm", "solver.threads=1", &plastic);
    const double r2 = mc_bench_runin_step(128, 64, "350 rpm", "solver.threads=2", NULL);

    vf_text(ctx, "## Threads\n\n"
                 "One against two threads (OpenMP loops and FFTW's threads; the machine has %d "
                 "cores). The whole run: the Hertz case of the next section's table at %d² as a "
                 "child process (`microcontact run CASE --set solver.threads=T`), 1 and 2 threads "
                 "alternating, the least wall time of %d runs each with its own stage times "
                 "(summary.json `timing`). The O(N) loops of the solvers run threaded from "
                 "%d cells on, with sums in blocks fixed by the size (core/psum.h): the results "
                 "are the same bits on any thread count (tests/test_thread_count.c).\n\n"
                 "| stage | 1 thread (s) | 2 threads (s) | speed-up |\n|---|---|---|---|\n",
            mc_threads_count(), N, quick ? 2 : 3, MC_THREADS_MIN_CELLS);
    if (!bad)
        for (int k = 0; k < NST; k++)
            vf_text(ctx, "| Hertz %d², %s | %.3f | %.3f | %.2f |\n", N, stage_names[k], st[0][k],
                    st[1][k], st[0][k] / st[1][k]);
    vf_text(ctx, "| stress layer at %d² (6 components) | %.4f | %.4f | %.2f |\n", SN, s1, s2,
            s1 / s2);
    vf_text(ctx, "| running-in step, elastic-plastic%s (default scene, 128 x 64 x 8, 350 rpm) | "
                 "%.2f | %.2f | %.2f |\n\n",
            plastic ? "" : " (NOTHING YIELDED)", r1, r2, r1 / r2);
    if (!pbad) {
        vf_text(ctx, "A user's run started directly (no `solver.threads`, no OMP_WAIT_POLICY, "
                     "no OMP_NUM_THREADS: the program sets passive waits itself and executes "
                     "again, cli/wait_policy.c, and takes the cores that are free at its start: "
                     "the cores less the other runnable tasks of /proc/loadavg, "
                     "cli/thread_default.c) against one thread, against the OpenMP runtime's "
                     "own defaults (every core, spinning waits: OMP_WAIT_POLICY=active) and "
                     "against every core with passive waits (the default before the free cores "
                     "were counted); the Hertz case at %d² as a child process, least of 3 "
                     "alternating runs; quiet, and beside a process that spins on one core "
                     "(another job on a shared machine).\n\n"
                     "| machine | 1 thread (s) | default (s) | every core, active (s) | every "
                     "core, passive (s) |\n|---|---|---|---|---|\n"
                     "| quiet | %.3f | %.3f | %.3f | %.3f |\n"
                     "| one core busy | %.3f | %.3f | %.3f | %.3f |\n\n",
                NP, wq[0], wq[1], wq[2], wq[3], wb[0], wb[1], wb[2], wb[3]);
        char q[200];
        snprintf(q, sizeof q, "Hertz %d², one core busy: default run time / one thread", NP);
        vf_check(ctx, "threads_default_busy", q, "target <= 1 (issue 22: never slower than one "
                 "thread), within the 5 % the least of 3 sub-second runs scatters",
                 1.0, wb[1] / wb[0], DEFAULT_MAX_RATIO, VF_MAX);
        vf_regress(ctx, "threads_default_busy", VF_TIER_NONE);
        snprintf(q, sizeof q, "Hertz %d², quiet: default run time / one thread", NP);
        vf_check(ctx, "threads_default_quiet", q, "target <= 1, within the same 5 %", 1.0,
                 wq[1] / wq[0], DEFAULT_MAX_RATIO, VF_MAX);
        vf_regress(ctx, "threads_default_quiet", VF_TIER_NONE);
        snprintf(q, sizeof q, "Hertz %d², one core busy: every core, spinning (active) / default",
                 NP);
        vf_info(ctx, "threads_active_busy", q, "what the default saves over the runtime's", NAN,
                wb[2] / wb[1]);
        vf_regress(ctx, "threads_active_busy", VF_TIER_NONE);
        snprintf(q, sizeof q, "Hertz %d², one core busy: every core, passive / default", NP);
        vf_info(ctx, "threads_allcores_busy", q, "what counting the free cores saves", NAN,
                wb[3] / wb[1]);
        vf_regress(ctx, "threads_allcores_busy", VF_TIER_NONE);
    }
    if (bad) {
        vf_fail(ctx, "threads_whole", "the whole Hertz run at %d² failed", N);
        return 0;
    }
    char q[200];
    snprintf(q, sizeof q, "whole run at %d²: 2-thread time / 1-thread time (speed-up %.2f)", N,
             st[0][ST_WHOLE] / st[1][ST_WHOLE]);
    vf_check(ctx, "threads_whole", q, "target speed-up >= 1.8 at 1024², i.e. <= 0.556 (issue 13)",
             1 / WHOLE_MIN_SPEEDUP, st[1][ST_WHOLE] / st[0][ST_WHOLE], 1 / WHOLE_MIN_SPEEDUP,
             VF_MAX);
    vf_regress(ctx, "threads_whole", VF_TIER_NONE);
    snprintf(q, sizeof q, "contact solve at %d²: 2-thread time / 1-thread time (speed-up %.2f)",
             N, st[0][ST_CONTACT] / st[1][ST_CONTACT]);
    vf_info(ctx, "threads_contact", q, "ideal 0.5", NAN, st[1][ST_CONTACT] / st[0][ST_CONTACT]);
    vf_regress(ctx, "threads_contact", VF_TIER_NONE);
    return 0;
}
