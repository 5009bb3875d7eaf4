/* cmd_run.c - `microcontact run CASE.ini [--out DIR] [--set section.key=value]...` */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "cli/cli.h"
#include "pipeline/output.h"
#include "pipeline/pipeline.h"

#define MAX_SETS 256

static int fail(const mc_error *err)
{
    fprintf(stderr, "microcontact: error: %s\n", err->msg);
    return mc_status_exit_code(err->code);
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

static void print_summary(const char *dir, const mc_results *r)
{
    const mc_contact_summary *c = &r->contact;
    printf("microcontact: %d x %d cells, dx = %.4g um, dy = %.4g um\n", r->grid.nx, r->grid.ny,
           r->grid.dx * 1e6, r->grid.dy * 1e6);
    if (c->solved)
        printf("  contact (%s, %s operator): %s in %d iterations, residual %.2e\n", c->solver,
               mc_backend_name(c->op), c->converged ? "converged" : "NOT CONVERGED", c->iterations,
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
    printf("  time %.3f s (setup %.3f, contact %.3f, stress %.3f), peak memory %.0f MiB\n",
           r->timing.total_s, r->timing.setup_s, r->timing.contact_s, r->timing.stress_s,
           peak_memory_mib());
    printf("  results in %s/ (summary.json, pressure.npy, gap.npy, displacement.npy, "
           "topography.npy, profile_x.csv%s)\n",
           dir, r->nlayers > 0 ? ", von_mises.npy, stress_*.npy, axis.csv, depths.csv" : "");
}

int mc_cli_run(int argc, char **argv)
{
    const char *case_path = NULL, *out = NULL;
    const char *sets[MAX_SETS];
    int nsets = 0;
    for (int k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--out") && k + 1 < argc) {
            out = argv[++k];
        } else if (!strcmp(argv[k], "--set") && k + 1 < argc) {
            if (nsets == MAX_SETS) {
                fprintf(stderr, "microcontact: error: more than %d --set options\n", MAX_SETS);
                return 2;
            }
            sets[nsets++] = argv[++k];
        } else if (!strncmp(argv[k], "--set=", 6)) {
            if (nsets == MAX_SETS) {
                fprintf(stderr, "microcontact: error: more than %d --set options\n", MAX_SETS);
                return 2;
            }
            sets[nsets++] = argv[k] + 6;
        } else if (!strncmp(argv[k], "--out=", 6)) {
            out = argv[k] + 6;
        } else if (argv[k][0] == '-') {
            fprintf(stderr, "microcontact run: unknown or incomplete option '%s'\n"
                            "usage: microcontact run CASE.ini [--out DIR] [--set section.key=value]...\n",
                    argv[k]);
            return 2;
        } else if (!case_path) {
            case_path = argv[k];
        } else {
            fprintf(stderr, "microcontact run: one case file only (got '%s' and '%s')\n",
                    case_path, argv[k]);
            return 2;
        }
    }
    if (!case_path) {
        fprintf(stderr, "usage: microcontact run CASE.ini [--out DIR] [--set section.key=value]...\n");
        return 2;
    }
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
    if (mc_output_prepare(dir, &err) != MC_OK)
        return fail(&err);

    mc_results res;
    int rc = mc_pipeline_run(&scene, &res, &err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED) {
        mc_results_free(&res);
        return fail(&err);
    }
    mc_error werr = {0};
    if (mc_output_write(dir, &scene, &res, &werr) != MC_OK) {
        mc_results_free(&res);
        return fail(&werr);
    }
    print_summary(dir, &res);
    mc_results_free(&res);
    if (rc == MC_NOT_CONVERGED) {
        fprintf(stderr, "microcontact: %s\n", err.msg);
        return 1;
    }
    return 0;
}
