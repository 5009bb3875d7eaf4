/* bench_whole.c - the whole run of the Hertz point case in FFT pairs (issue 13 item 1): the real
 * executable (`microcontact run` on a generated case file, the defaults of a new user: no
 * [solver] section) run as a child process, from fork to exit with its outputs written, divided
 * by one bare FFTW r2c + c2r pair of the padded size timed in the same run; the breakdown from
 * the run's own summary.json timings; CONTACT's whole process (quoted from issue 13) beside it. */
#include <fcntl.h>
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "core/alloc.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "reference/hertz.h"

#define R_SPHERE 10e-3
#define E_STEEL 210e9
#define NU 0.3
#define LOAD 100.0
#define NSIZES 3
#define SETUP_MAX_PAIRS 3.0  /* issue 13 item 1, at 1024^2 */
#define WHOLE_MAX_PAIRS 25.0 /* issue 13 item 1, at 1024^2 */
#define CONTACT_GOAL 10.0    /* issue 13 item 1: >= 10x CONTACT's whole process */

static const int sizes[NSIZES] = {256, 512, 1024};
/* CONTACT (Fortran + MKL, one thread, tolerance 1e-6), whole process of the same case on this
 * machine, as quoted in issue 13 (NOT measured by this bench). */
static const double contact_s[NSIZES] = {0.39, 2.14, 15.95};

double mc_bench_run_child_to(const char *const argv[], const char *out)
{
    fflush(NULL);
    const double t0 = mc_clock();
    const pid_t pid = fork();
    if (pid < 0)
        return NAN;
    if (pid == 0) {
        const int fn = open("/dev/null", O_WRONLY);
        const int fo = out ? open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644) : fn;
        if (fo >= 0)
            dup2(fo, 1);
        if (fn >= 0)
            dup2(fn, 2);
        execvp(argv[0], (char *const *)argv);
        _exit(127);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid)
        return NAN;
    const double t = mc_clock() - t0;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? t : NAN;
}

double mc_bench_run_child(const char *const argv[]) { return mc_bench_run_child_to(argv, NULL); }

int mc_bench_hertz_case(const char *path, int N)
{
    mc_hertz_point hz;
    mc_error err = {0};
    if (mc_hertz_point_from_load(R_SPHERE, E_STEEL / (2 * (1 - NU * NU)), LOAD, &hz, &err))
        return 1;
    const double side = 3 * hz.a;
    FILE *f = fopen(path, "w");
    if (!f)
        return 1;
    fprintf(f, "; Hertz point case of issue 13 at the defaults (no [solver] section)\n"
               "[mesh]\nnx = %d\nny = %d\ndx = %.17g\n[geometry]\nshape = sphere\n"
               "radius = %.17g\n[body1]\nE = %.17g\nnu = %.17g\n[body2]\nE = %.17g\n"
               "nu = %.17g\n[load]\nforce = %.17g\n",
            N, N, side / N, R_SPHERE, E_STEEL, NU, E_STEEL, NU, LOAD);
    return fclose(f) != 0;
}

double mc_bench_json_number(const char *path, const char *key)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return NAN;
    static char buf[1 << 16];
    const size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\":", key);
    const char *p = strstr(buf, pat);
    return p ? strtod(p + strlen(pat), NULL) : NAN;
}

void mc_bench_remove_tree(const char *dir)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) {
        /* a temporary directory left behind is not worth failing the bench for */
    }
}

typedef struct {
    double wall, total, setup, contact; /* s: least wall of the rounds; its summary timings */
    double pair;                        /* bare pair of the padded size, s */
    int tx, ty, iterations, ok;
} whole_t;

int mc_bench_whole(vf_ctx *ctx, int quick)
{
    mc_hertz_point hz;
    mc_error err = {0};
    if (mc_hertz_point_from_load(R_SPHERE, E_STEEL / (2 * (1 - NU * NU)), LOAD, &hz, &err))
        return 1;
    char self[1024], dir[] = "/tmp/mc_bench_whole_XXXXXX";
    const ssize_t sl = readlink("/proc/self/exe", self, sizeof self - 1);
    if (sl <= 0 || !mkdtemp(dir))
        return 1;
    self[sl] = '\0';
    const int nsizes = quick ? 2 : NSIZES;
    whole_t w[NSIZES];
    memset(w, 0, sizeof w);
    /* fixed costs: a 16^2 run (process start, reading the case, writing six small files) */
    char ini[1100], out[1100];
    double floor_wall = INFINITY;
    snprintf(ini, sizeof ini, "%s/hertz16.ini", dir);
    if (mc_bench_hertz_case(ini, 16) == 0)
        for (int r = 0; r < 3; r++) {
            snprintf(out, sizeof out, "%s/out16_%d", dir, r);
            const char *argv[] = {self, "run", ini, "--out", out, NULL};
            floor_wall = fmin(floor_wall, mc_bench_run_child(argv));
        }
    for (int k = 0; k < nsizes; k++) {
        const int N = sizes[k];
        w[k].wall = INFINITY;
        snprintf(ini, sizeof ini, "%s/hertz%d.ini", dir, N);
        if (mc_bench_hertz_case(ini, N)) {
            vf_fail(ctx, "whole_case", "cannot write %s", ini);
            continue;
        }
        const int rounds = N >= 1024 ? 2 : 3;
        for (int r = 0; r < rounds; r++) {
            snprintf(out, sizeof out, "%s/out%d_%d", dir, N, r);
            const char *argv[] = {self, "run", ini, "--out", out, NULL};
            const double t = mc_bench_run_child(argv);
            char js[1200];
            snprintf(js, sizeof js, "%s/summary.json", out);
            if (!(t > 0)) {
                vf_fail(ctx, "whole_run", "microcontact run %s failed", ini);
                break;
            }
            if (t < w[k].wall) {
                w[k].wall = t;
                w[k].total = mc_bench_json_number(js, "total_s");
                w[k].setup = mc_bench_json_number(js, "setup_s");
                w[k].contact = mc_bench_json_number(js, "contact_s");
                w[k].iterations = (int)mc_bench_json_number(js, "iterations");
                w[k].ok = 1;
            }
            mc_bench_remove_tree(out);
        }
        mc_grid g = {N, N, 3 * hz.a / N, 3 * hz.a / N, 0, 0};
        mc_conv *c = NULL;
        w[k].tx = w[k].ty = 2 * N;
        if (mc_conv_create(&g, MC_BACKEND_FFT, &c, &err) == MC_OK) {
            mc_conv_table_dims(c, &w[k].tx, &w[k].ty);
            mc_conv_destroy(&c);
        }
        w[k].pair = mc_bench_pair_time(w[k].tx, w[k].ty, N >= 1024 ? 7 : 15, FFTW_ESTIMATE, NULL);
    }
    mc_bench_remove_tree(dir);

    FILE *f = vf_open(ctx, "whole.csv");
    if (f)
        fprintf(f, "N,tx,ty,pair_s,whole_s,total_s,setup_s,contact_s,iterations,contact_quoted_s\n");
    vf_text(ctx,
            "## Whole run in FFT pairs\n\n"
            "The Hertz point case of issue 13 (steel on steel, R = 10 mm, F = 100 N, a = %.1f um, "
            "square of side 3a, N x N cells) as a new user runs it: a case file without a "
            "[solver] section (the default tolerance and threads), `microcontact run CASE --out "
            "DIR` as a child process of this one, wall time from fork to exit with its six output "
            "files written; the least of 3 runs (2 at 1024²). A pair is one bare FFTW r2c + c2r "
            "of the padded size (FFTW_ESTIMATE, the same %d threads), median of repeated calls "
            "in this run. Breakdown from the run's summary.json `timing`: setup (kernel tables, "
            "spectra, plans), contact (the solve: coarse start, iterations, box and "
            "verification), other = total_s - setup - contact (topography, summaries); "
            "outside = whole - total_s (process start, reading the case, writing the outputs, "
            "exit). A 16 x 16 run (fixed costs only) took %.3f s. CONTACT's times are QUOTED from "
            "issue 13 (Fortran + MKL, one thread, tolerance 1e-6, measured on this machine by "
            "the issue's author), not measured in this run.\n\n"
            "| N | padded | pair (ms) | whole (s) | whole (pairs) | setup (pairs) | contact "
            "(pairs) | other (pairs) | outside (pairs) | iterations | CONTACT quoted (s) | "
            "CONTACT / whole |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            hz.a * 1e6, mc_threads_count(), floor_wall);
    for (int k = 0; k < nsizes; k++) {
        if (!w[k].ok)
            continue;
        const whole_t *x = &w[k];
        const double P = x->pair;
        vf_text(ctx,
                "| %d² | %d x %d | %.2f | %.3f | %.1f | %.2f | %.1f | %.2f | %.1f | %d | %.2f | "
                "%.1f |\n",
                sizes[k], x->tx, x->ty, 1e3 * P, x->wall, x->wall / P, x->setup / P,
                x->contact / P, (x->total - x->setup - x->contact) / P, (x->wall - x->total) / P,
                x->iterations, contact_s[k], contact_s[k] / x->wall);
        if (f)
            fprintf(f, "%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.4g\n", sizes[k], x->tx, x->ty, P,
                    x->wall, x->total, x->setup, x->contact, x->iterations, contact_s[k]);
    }
    if (f)
        vf_close(ctx, f);
    vf_text(ctx, "\n");
    const int big = nsizes - 1; /* 1024^2, or 512^2 with --quick */
    char q[200];
    if (w[big].ok) {
        snprintf(q, sizeof q, "whole run: setup in FFT pairs at %d²", sizes[big]);
        vf_check(ctx, "whole_setup_pairs", q, "target <= 3 pairs at 1024² (issue 13)",
                 SETUP_MAX_PAIRS, w[big].setup / w[big].pair, SETUP_MAX_PAIRS, VF_MAX);
        vf_regress(ctx, "whole_setup_pairs", VF_TIER_NONE);
        snprintf(q, sizeof q, "whole run (process start to exit, outputs written) in FFT pairs "
                              "at %d²", sizes[big]);
        vf_check(ctx, "whole_run_pairs", q, "target <= 25 pairs at 1024² (issue 13)",
                 WHOLE_MAX_PAIRS, w[big].wall / w[big].pair, WHOLE_MAX_PAIRS, VF_MAX);
        vf_regress(ctx, "whole_run_pairs", VF_TIER_NONE);
    }
    for (int k = 0; k < nsizes; k++) {
        if (!w[k].ok)
            continue;
        char id[48];
        snprintf(id, sizeof id, "whole_vs_contact_%d", sizes[k]);
        snprintf(q, sizeof q,
                 "whole run / CONTACT's whole process at %d² (CONTACT %.2f s quoted from issue "
                 "13, not measured here; ours %.3f s, i.e. %.1fx faster)",
                 sizes[k], contact_s[k], w[k].wall, contact_s[k] / w[k].wall);
        vf_check(ctx, id, q, "goal >= 10x faster, i.e. <= 0.1 (issue 13)", 1 / CONTACT_GOAL,
                 w[k].wall / contact_s[k], 1 / CONTACT_GOAL, VF_MAX);
        vf_regress(ctx, id, VF_TIER_NONE);
    }
    return 0;
}
