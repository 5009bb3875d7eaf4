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
#include "pipeline/output.h"
#include "pipeline/pipeline.h"

#define MAX_SETS 256

static const char run_help[] =
    MC_USAGE_RUN "\n\n"
    "Solve the scene of CASE.ini and write its results (summary.json, *.npy, *.csv, VTK) to DIR\n"
    "(default: [output] dir of the case, else out/<case name>).\n\n"
    "  --out DIR                output directory\n"
    "  --set section.key=value  change one key of the case without editing it (repeatable);\n"
    "                           section.key= (empty) removes the key, e.g.\n"
    "                           --set load.force= --set load.approach=1um\n"
    "  -h, --help               this text\n\n"
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

static void print_solve(const mc_results *r)
{
    const mc_contact_summary *c = &r->contact;
    printf("microcontact: %d x %d cells, dx = %.4g um, dy = %.4g um\n", r->grid.nx, r->grid.ny,
           r->grid.dx * 1e6, r->grid.dy * 1e6);
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
        const mc_stress_summary *s = &r->stress_summary;
        printf("  stress: %d layers, max von Mises %.6g MPa at z = %.4g um, max shear %.6g MPa\n",
               r->nlayers, s->vm_max * 1e-6, s->vm_max_at[2] * 1e6, s->tresca_max * 1e-6);
    }
    if (r->lube.enabled)
        printf("  lubrication: h_EHD %.4g um, p_lub %.6g MPa (%s), psi_load %.4g, psi_area %.4g, "
               "mu %.4g\n",
               r->lube.h_ehd * 1e6, r->lube.p_lub * 1e-6, r->lube.regime, r->lube.psi_load,
               r->lube.psi_area, r->lube.mu);
    if (r->plastic.enabled) {
        const mc_plastic_summary *q = &r->plastic;
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
    int nsets = 0;
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
    static mc_outdir od;
    if (mc_output_open(&od, dir, &err) != MC_OK) {
        mc_output_close(&od);
        return fail(&err);
    }

    mc_results res;
    int rc = mc_pipeline_run(&scene, &res, &err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED) {
        mc_results_free(&res);
        mc_output_close(&od);
        return fail_case(case_path, &err);
    }
    print_solve(&res);
    printf("  writing results to %s/\n", dir);
    mc_error werr = {0};
    int wrc = mc_output_commit(&od, &scene, &res, &werr);
    if (wrc == MC_ERR_INTERRUPTED) {
        int sig = mc_cli_signal_caught();
        fprintf(stderr,
                "microcontact: stopped by %s while writing results: the partial files are "
                "removed, '%s' is as it was\n",
                signal_name(sig), dir);
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
    printf("  results in %s/ (summary.json, pressure.npy, gap.npy, displacement.npy, "
           "topography.npy, profile_x.csv%s%s)\n",
           dir, res.nlayers > 0 ? ", von_mises.npy, stress_*.npy, axis.csv, depths.csv" : "",
           res.plastic.enabled ? ", residual_displacement.npy, topography_final.npy, "
                                 "plastic_strain.npy, residual_von_mises.npy, plastic.csv"
                               : "");
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
