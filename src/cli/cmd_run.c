/* cmd_run.c - `microcontact run CASE.ini [--out DIR] [--set section.key=value]...`
 *
 * Order of a run: parse the case; check the output directory without creating it (and lock it
 * when it exists: one run per directory); solve; print the solve (stdout is line buffered, so a
 * log shows each stage as it ends); commit the results (the directory is created here); print
 * where they are. Errors found after parsing name the case file. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "cli/cli.h"
#include "core/dist.h"
#include "operator/dfft.h"
#include "pipeline/checkpoint.h"
#include "pipeline/output.h"
#include "pipeline/pipeline.h"
#include "pipeline/runin.h"

#define MAX_SETS 256

static const char run_help[] =
    MC_USAGE_RUN "\n\n"
    "Solve the scene of CASE.ini and write its results (summary.json, *.npy, *.csv, VTK) to DIR\n"
    "(default: [output] dir of the case, else out/<case name>).\n\n"
    "  --out DIR                output directory\n"
    "  --set section.key=value  change one key of the case without editing it (repeatable);\n"
    "                           section.key= (empty) removes the key, e.g.\n"
    "                           --set load.force= --set load.approach=1um\n"
    "  --quiet                  no progress lines (a running-in prints one per step to stderr)\n"
    "  --resume                 continue the interrupted running-in whose checkpoint is in\n"
    "                           DIR/checkpoint/ (same case, same --set values)\n"
    "  -h, --help               this text\n\n"
    "Running-in ([runin]): one progress line per step on stderr (step, force, phase, speed,\n"
    "p_lub, psi, mu, Ra, elapsed and estimated time left). DIR is created at the start and the\n"
    "state after every step is checkpointed atomically in DIR/checkpoint/; SIGINT or SIGTERM\n"
    "stops the run after abandoning the step in progress, keeps the checkpoint and says how to\n"
    "resume; --resume gives the results of an uninterrupted run (same machine and threads).\n"
    "The checkpoint is removed when the results are committed.\n\n"
    "Output directory: created, with its parents, only when the results are committed (a run\n"
    "that fails creates nothing). Results go to DIR/.staging-XXXXXX first and are moved into DIR\n"
    "when all are complete: DIR holds the earlier results or the new ones, never a mix.\n"
    "One run per output directory at a time: a run locks DIR (flock); a second run into it\n"
    "refuses at once (exit 3) and names the pid of the run that holds it.\n"
    "SIGINT, SIGTERM or SIGHUP ends the run with status 128 + signal: at once while it\n"
    "computes (nothing is written yet); while results are written, once the partial files\n"
    "are removed. Staging areas a killed run left behind (SIGKILL) are removed by the next\n"
    "run into that directory.\n\n" MC_EXIT_STATUS_HELP;

static int fail(const mc_error *err)
{
    fprintf(stderr, "microcontact: error: %s\n", err->msg);
    return mc_status_exit_code(err->code);
}

/* An error found after parsing: name the case file unless the message does already. */
static int fail_case(const char *case_path, const mc_error *err)
{
    size_t n = strlen(case_path);
    if (strncmp(err->msg, case_path, n) == 0 && err->msg[n] == ':')
        return fail(err);
    fprintf(stderr, "microcontact: error: %s: %s\n", case_path, err->msg);
    return mc_status_exit_code(err->code);
}

static int usage_error(const char *what, const char *a, const char *b)
{
    if (b)
        fprintf(stderr, "microcontact run: %s (got '%s' and '%s')\n%s\n", what, a, b, MC_USAGE_RUN);
    else
        fprintf(stderr, "microcontact run: %s '%s'\n%s\n", what, a, MC_USAGE_RUN);
    return 2;
}

static const char *signal_name(int sig)
{
    switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    }
    return "a signal";
}

/* Peak resident memory of this process (VmHWM), MiB; NAN where /proc is not there. */
static double peak_memory_mib(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    double kb = NAN;
    if (f) {
        char line[256];
        while (fgets(line, sizeof line, f))
            if (sscanf(line, "VmHWM: %lf kB", &kb) == 1)
                break;
        fclose(f);
    }
    return kb / 1024.0;
}

/* A line as each stage begins (stdout is line buffered): a log of a run killed while it computes
 * is not empty. The first comes once the input files are read and the memory guard has passed,
 * so a run refused for its input writes nothing on stdout. */
static void print_stage(void *ctx, const char *stage)
{
    const mc_scene *sc = ctx;
    if (!strcmp(stage, "contact"))
        printf("microcontact: %d x %d cells, dx = %.4g um, dy = %.4g um\n", sc->grid.nx,
               sc->grid.ny, sc->grid.dx * 1e6, sc->grid.dy * 1e6);
    else /* "stress" */
        printf("  contact solved; computing the %s\n", "subsurface stresses");
}

static void print_solve(const mc_results *r)
{
    const mc_contact_summary *c = &r->contact;
    if (c->solved)
        printf("  contact (%s, %s operator): %s in %d iterations, residual %.2e\n", c->solver,
               mc_backend_name(c->backend), c->converged ? "converged" : "NOT CONVERGED", c->iterations,
               c->residual);
    else
        printf("  prescribed pressure (no contact solve)\n");
    printf("  load %.6g N (solid %.6g N), p_max %.6g MPa, contact area %.6g mm^2 (%.3g %%), "
           "approach %.6g um\n",
           c->load, c->solid_load, c->p_max * 1e-6, c->area * 1e6, 100 * c->contact_ratio,
           c->approach * 1e6);
    if (r->nlayers > 0) {
        const mc_stage_stress_summary *s = &r->stress_summary;
        printf("  stress: %d layers, max von Mises %.6g MPa at z = %.4g um, max shear %.6g MPa\n",
               r->nlayers, s->vm_max * 1e-6, s->vm_max_at[2] * 1e6, s->tresca_max * 1e-6);
    }
    if (r->lube.enabled)
        printf("  lubrication: h_EHD %.4g um, p_lub %.6g MPa (%s), psi_load %.4g, psi_area %.4g, "
               "mu %.4g\n",
               r->lube.h_ehd * 1e6, r->lube.p_lub * 1e-6, r->lube.regime, r->lube.psi_load,
               r->lube.psi_area, r->lube.mu);
    if (r->plastic.enabled) {
        const mc_stage_plastic_summary *q = &r->plastic;
        if (q->elastic_shortcut)
            printf("  plasticity: nothing yields (max von Mises %.6g MPa < yield %.6g MPa)\n",
                   q->vm_elastic_max * 1e-6, q->yield_initial * 1e-6);
        else
            printf("  plasticity (%s): %s, %d of %d steps, %d outer iterations; max plastic "
                   "strain %.4g at z = %.4g um, residual dent %.4g um\n",
                   q->criterion, q->converged ? "converged" : "NOT CONVERGED", q->steps_done,
                   q->load_steps, q->outer_iterations, q->peq_max, q->peq_max_at[2] * 1e6,
                   q->residual_max * 1e6);
    }
    printf("  time %.3f s (setup %.3f, contact %.3f, stress %.3f), peak memory %.0f MiB\n",
           r->timing.total_s, r->timing.setup_s, r->timing.contact_s, r->timing.stress_s,
           peak_memory_mib());
    if (mc_dist_active()) { /* bin/microcontact-mpi: rank 0's share (README "Running on a
                              * cluster") */
        const int tr = mc_dfft_transposes_used();
        printf("  MPI: %d process%s; rank 0 spent %.3f s communicating (its peak memory "
               "above); its CPU %.3f s, %.3f s of it in communication; contact stage CPU "
               "%.3f s, %.3f s of it in communication; transposes %s\n",
               mc_dist_size(), mc_dist_size() > 1 ? "es" : "", r->timing.comm_s,
               mc_dist_cpu_seconds(), mc_dist_comm_cpu_seconds(), r->timing.contact_cpu_s,
               r->timing.contact_comm_cpu_s,
               tr == MC_DFFT_TRANSPOSES_SHARED ? "through shared memory"
               : tr == MC_DFFT_TRANSPOSES_FFTW ? "by FFTW-MPI (the ranks on several machines, MC_TRANSPOSES=fftw, or no room in /dev/shm)"
               : tr ? "through shared memory and by FFTW-MPI"
                    : "none");
    }
}

/* ---- running-in -------------------------------------------------------------------------- */

/* "12 s", "4 min 12 s", "1 h 02 min" */
static void duration(double s, char *buf, size_t len)
{
    if (!(s >= 0) || !isfinite(s))
        snprintf(buf, len, "?");
    else if (s < 60)
        snprintf(buf, len, "%.0f s", s);
    else if (s < 3600)
        snprintf(buf, len, "%d min %02d s", (int)(s / 60), (int)fmod(s, 60));
    else
        snprintf(buf, len, "%d h %02d min", (int)(s / 3600), (int)fmod(s / 60, 60));
}

static void progress_line(void *ctx, const mc_runin_progress *p)
{
    (void)ctx;
    const mc_runin_row *w = p->row;
    char el[32], left[32];
    duration(p->elapsed, el, sizeof el);
    duration(p->eta, left, sizeof left);
    fprintf(stderr,
            "step %*d/%d  F %.6g N  %-4s  %6.0f rpm  p_lub %7.2f MPa  psi %.4f  mu %.4f  "
            "Ra %.4f um%s  elapsed %s, left %s\n",
            p->nsteps >= 100 ? 3 : p->nsteps >= 10 ? 2 : 1, p->step, p->nsteps, w->force,
            w->up ? "up" : "down", w->speed * 60.0 / (2.0 * M_PI), w->p_lub * 1e-6, w->psi_load,
            w->mu, w->ra * 1e6, w->plastic ? "  (plastic)" : "", el, left);
}

static int stop_requested(void *ctx)
{
    (void)ctx;
    return mc_output_stop_requested();
}

static void print_runin(const mc_results *r)
{
    const mc_runin_summary *ri = &r->runin;
    int plastic = 0;
    for (int k = 0; k < ri->done; k++)
        plastic += ri->rows[k].plastic;
    printf("  running-in: %d force%s x %d speeds, %d steps (%d elastic-plastic)%s\n", ri->nforces,
           ri->nforces > 1 ? "s" : "", ri->nspeeds, ri->nsteps, plastic,
           ri->resumed_from ? ", resumed" : "");
    for (int f = 0; f < ri->nforces; f++) {
        const int m = ri->nspeeds, first = 2 * m * f, last = first + 2 * m - 1;
        if (last >= ri->done)
            break;
        const mc_runin_row *a = &ri->rows[first], *b = &ri->rows[first + m - 1];
        printf("    F %.6g N: mu %.4f -> %.4f (down), Ra %.4f -> %.4f um, hysteresis %.4g "
               "(mu x decades)\n",
               a->force, a->mu, b->mu, a->ra * 1e6, b->ra * 1e6, ri->hysteresis[f]);
    }
}

/* How to continue: the same case, directory and --set values. */
static void resume_hint(const char *case_path, const char *dir, const char *ckdir,
                        const char *const *sets, int nsets)
{
    fprintf(stderr, "microcontact: the checkpoint in %s/ keeps the completed steps; continue "
                    "with:\n  ",
            ckdir);
    if (mc_dist_active()) /* under mpirun: the same command, any number of processes */
        fprintf(stderr, "mpirun -np %d microcontact-mpi ", mc_dist_size());
    else
        fprintf(stderr, "microcontact ");
    fprintf(stderr, "run %s --out %s", case_path, dir);
    for (int k = 0; k < nsets; k++)
        fprintf(stderr, " --set '%s'", sets[k]);
    fprintf(stderr, " --resume\n");
}

/* The running-in: DIR exists from the start (it holds the checkpoints) and is locked; progress on
 * stderr; a signal stops the run between steps or outer iterations. Returns the status of
 * mc_runin_run, or minus the exit status when it has reported and ended the run itself. */
static int run_runin(const mc_scene *scene, const char *case_path, const char *dir,
                     const char *ckdir, const char *const *sets, int nsets, int quiet,
                     int resume, mc_outdir *od, mc_results *res, mc_error *err)
{
    memset(res, 0, sizeof *res);
    /* under mpirun rank 0 holds DIR: its view of the checkpoint and its lock decide for all */
    const int root = mc_dist_rank() == 0;
    if (resume && !mc_dist_root_int(root && mc_checkpoint_exists(ckdir))) {
        fprintf(stderr, "microcontact: error: --resume: no checkpoint in '%s' (nothing to "
                        "resume; run without --resume to start)\n",
                ckdir);
        mc_output_close(od);
        return -2;
    }
    /* from here a signal asks the run to stop (and a signal before the first step leaves no
     * directory behind: the rollback below) */
    mc_output_hold(1);
    mc_error derr = {0};
    int arc = mc_dist_root_int(root ? mc_outdir_acquire(od, &derr) : MC_OK);
    if (arc != MC_OK) {
        mc_output_hold(0);
        fprintf(stderr, "microcontact: error: %s\n", derr.msg);
        mc_output_close(od);
        return -mc_status_exit_code(arc);
    }
    if (root && !resume && mc_checkpoint_exists(ckdir)) {
        fprintf(stderr, "microcontact: note: '%s' held the checkpoint of an unfinished run; "
                        "starting over (--resume continues one)\n",
                ckdir);
        mc_checkpoint_remove(ckdir);
    }
    mc_runin_options opt = {.checkpoint_dir = ckdir,
                            .resume = resume,
                            .progress = quiet ? NULL : progress_line,
                            .stop = stop_requested};
    const double comm0 = mc_dist_comm_seconds();
    int rc = mc_runin_run(scene, &opt, res, err);
    res->timing.comm_s = mc_dist_comm_seconds() - comm0; /* as mc_pipeline_run's */
    mc_output_hold(0);
    if (rc == MC_ERR_INTERRUPTED) {
        int sig = mc_cli_signal_caught();
        fprintf(stderr, "microcontact: stopped by %s after %d of %d steps\n", signal_name(sig),
                res->runin.done, res->runin.nsteps);
        if (res->runin.done > 0)
            resume_hint(case_path, dir, ckdir, sets, nsets);
        else if (root)
            mc_outdir_rollback(od);
        mc_results_free(res);
        mc_output_close(od);
        if (sig)
            mc_cli_signal_exit(sig);
        return -mc_status_exit_code(MC_ERR_INTERRUPTED);
    }
    if (rc != MC_OK && rc != MC_NOT_CONVERGED && !resume && root) {
        /* a failed run leaves nothing behind (a refused resume keeps its checkpoint) */
        mc_checkpoint_remove(ckdir);
        mc_outdir_rollback(od);
    }
    return rc;
}

static int add_set(const char **sets, int *nsets, const char *s)
{
    if (*nsets == MAX_SETS) {
        fprintf(stderr, "microcontact: error: more than %d --set options\n", MAX_SETS);
        return 2;
    }
    sets[(*nsets)++] = s;
    return 0;
}

int mc_cli_run(int argc, char **argv)
{
    const char *case_path = NULL, *out = NULL;
    const char *sets[MAX_SETS];
    int nsets = 0, quiet = 0, resume = 0;
    for (int k = 0; k < argc; k++) {
        if (mc_cli_is_help(argv[k])) {
            fputs(run_help, stdout);
            return 0;
        }
        if (!strcmp(argv[k], "--out") && k + 1 < argc) {
            out = argv[++k];
        } else if (!strcmp(argv[k], "--set") && k + 1 < argc) {
            if (add_set(sets, &nsets, argv[++k]))
                return 2;
        } else if (!strncmp(argv[k], "--set=", 6)) {
            if (add_set(sets, &nsets, argv[k] + 6))
                return 2;
        } else if (!strncmp(argv[k], "--out=", 6)) {
            out = argv[k] + 6;
        } else if (!strcmp(argv[k], "--quiet")) {
            quiet = 1;
        } else if (!strcmp(argv[k], "--resume")) {
            resume = 1;
        } else if (argv[k][0] == '-') {
            return usage_error("unknown or incomplete option", argv[k], NULL);
        } else if (!case_path) {
            case_path = argv[k];
        } else {
            return usage_error("one case file only", case_path, argv[k]);
        }
    }
    if (!case_path) {
        fprintf(stderr, "%s\n", MC_USAGE_RUN);
        return 2;
    }
    /* a log of a run that is killed shows every stage that ended */
    setvbuf(stdout, NULL, _IOLBF, 0);
    mc_cli_signals_start(); /* on failure signals keep their default action: nothing is lost
                             * but the staging area of an interrupted commit */

    static mc_scene scene;
    mc_error err = {0};
    if (mc_case_load(case_path, nsets, sets, &scene, &err) != MC_OK)
        return fail(&err);
    char dir[MC_PATH_MAX];
    if (out) {
        if (snprintf(dir, sizeof dir, "%s", out) >= (int)sizeof dir) {
            fprintf(stderr, "microcontact: error: --out: the directory name is longer than %d "
                            "bytes\n",
                    (int)sizeof dir - 1);
            return 2;
        }
    } else if (mc_scene_output_dir(&scene, dir, sizeof dir, &err) != MC_OK) {
        return fail(&err);
    }
    /* under mpirun (bin/microcontact-mpi): what the processes cannot yet compute together */
    if (mc_pipeline_check_ranks(&scene, mc_dist_size(), &err) != MC_OK)
        return fail_case(case_path, &err);
    /* rank 0 alone holds and writes the output directory; the others compute alongside */
    const int root = mc_dist_rank() == 0;
    if (resume && !scene.runin.enabled) {
        fprintf(stderr, "microcontact: error: --resume: %s has no [runin] section (only a "
                        "running-in is checkpointed)\n",
                case_path);
        return 2;
    }
    static mc_outdir od;
    int orc = MC_OK;
    if (root)
        orc = mc_output_open(&od, dir, &err);
    else
        mc_outdir_init(&od);
    orc = mc_dist_root_int(orc); /* every rank goes on, or stops, with rank 0's status */
    if (orc != MC_OK) {
        mc_output_close(&od);
        return root ? fail(&err) : mc_status_exit_code(orc);
    }

    mc_results res;
    int rc;
    char ckdir[MC_PATH_MAX + 16];
    snprintf(ckdir, sizeof ckdir, "%s/checkpoint", dir);
    if (scene.runin.enabled) {
        if (!resume || (root && mc_checkpoint_exists(ckdir))) /* DIR is rank 0's */
            print_stage(&scene, "contact");
        rc = run_runin(&scene, case_path, dir, ckdir, sets, nsets, quiet, resume, &od, &res,
                       &err);
        if (rc < 0) /* reported and ended there */
            return -rc;
    } else
        rc = mc_pipeline_run_staged(&scene, print_stage, &scene, &res, &err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED) {
        mc_results_free(&res);
        mc_output_close(&od);
        return fail_case(case_path, &err);
    }
    print_solve(&res);
    for (int k = 0; k < res.nwarnings; k++) /* pipeline/warnings.h */
        fprintf(stderr, "microcontact: warning: %s\n", res.warnings[k].message);
    if (res.runin.enabled)
        print_runin(&res);
    printf("  writing results to %s/\n", dir);
    mc_error werr = {0};
    int wrc = root ? mc_output_commit(&od, &scene, &res, &werr) : MC_OK;
    wrc = mc_dist_root_int(wrc);
    if (!root)
        werr.code = wrc;
    if (wrc == MC_ERR_INTERRUPTED) {
        int sig = mc_cli_signal_caught();
        fprintf(stderr,
                "microcontact: stopped by %s while writing results: the partial files are "
                "removed, '%s' is as it was\n",
                signal_name(sig), dir);
        if (res.runin.enabled)
            resume_hint(case_path, dir, ckdir, sets, nsets);
        mc_results_free(&res);
        mc_output_close(&od);
        if (sig)
            mc_cli_signal_exit(sig);
        return mc_status_exit_code(MC_ERR_INTERRUPTED);
    }
    if (wrc != MC_OK) {
        mc_results_free(&res);
        mc_output_close(&od);
        return fail(&werr);
    }
    if (res.runin.enabled && root)
        mc_checkpoint_remove(ckdir); /* the results are committed: nothing left to resume */
    char files[2048];
    mc_output_files_joined(&scene, &res, ", ", files, sizeof files);
    printf("  results in %s/ (%s)\n", dir, files);
    mc_results_free(&res);
    mc_output_close(&od);
    int sig = mc_cli_signal_caught();
    if (sig) /* it came during the final renames: the results are complete */
        mc_cli_signal_exit(sig);
    if (rc == MC_NOT_CONVERGED) {
        fprintf(stderr, "microcontact: %s\n", err.msg);
        return 1;
    }
    return 0;
}
