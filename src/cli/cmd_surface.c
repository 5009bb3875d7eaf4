/* cmd_surface.c - `microcontact surface FILE [--set section.key=value]... [--out DIR]`
 *
 * What a user checks before a run on a measured surface: the file is read through the path a run
 * takes (a case with [roughness] type = file and file = FILE, parsed by case/ with the --set
 * overrides: the mesh from the file or the [mesh] keys given, then surface/measured.c: crop,
 * missing points, levelling, scale, invert, resampling onto the mesh), and the roughness
 * parameters are those summary.json reports as roughness.initial for that run (same cut-off rule
 * and periodicity). --out DIR writes the heights on the mesh as surface.npy and surface.x3p, via
 * a staging directory inside DIR renamed into place; DIR is created only when both are written.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "case/case.h"
#include "cli/cli.h"
#include "core/alloc.h"
#include "io/npy.h"
#include "io/surface_file.h"
#include "pipeline/outdir.h"
#include "surface/measured.h"
#include "surface/roughness.h"
#include "surface/surface.h"

#define MAX_SETS 64

static const char surface_help[] =
    MC_USAGE_SURFACE "\n\n"
    "Read a surface file as a run reads it ([roughness] type = file) and print what to check\n"
    "before a run: format, grid, spacings, missing and filled points, height range after\n"
    "levelling, and the ISO roughness parameters (ISO 4287, 13565-2, 25178-2) with the cut-off\n"
    "used: the values summary.json reports as roughness.initial for a run on this surface.\n\n"
    "  --set section.key=value  a [roughness] key (format, units, verify_checksum, region,\n"
    "                           detrend, missing, resample, scale, invert, cutoff) or a [mesh]\n"
    "                           key (nx, ny, dx, dy, periodic_x, periodic_y: put the surface\n"
    "                           onto that mesh, as a run would), repeatable; e.g.\n"
    "                           --set roughness.units=um --set mesh.dx=1um --set mesh.dy=1um\n"
    "  --out DIR                write the prepared heights (m) as DIR/surface.npy and\n"
    "                           DIR/surface.x3p; DIR is created only when both are written\n"
    "  -h, --help               this text\n\n" MC_EXIT_STATUS_HELP;

static int usage_error(const char *what, const char *a)
{
    fprintf(stderr, "microcontact surface: %s '%s'\n%s\n", what, a, MC_USAGE_SURFACE);
    return 2;
}

static int fail(const mc_error *err)
{
    fprintf(stderr, "microcontact: error: %s\n", err->msg);
    return mc_status_exit_code(err->code);
}

/* An error of the case layer, worded for this command: it names the file once, and a missing
 * spacing says how to give it here. */
static int fail_parse(const char *path, mc_error *err)
{
    const char *tag = "[roughness] file: ", *tail = strstr(err->msg, tag);
    if (tail) /* "--set roughness.file=FILE: [roughness] file: ..." -> "..." */
        tail += strlen(tag);
    else
        tail = err->msg;
    fprintf(stderr, "microcontact: error: %s%s%s%s\n", strstr(tail, path) ? "" : path,
            strstr(tail, path) ? "" : ": ", tail,
            strstr(tail, "give [mesh] dx") ? " (here: --set mesh.dx=... --set mesh.dy=...)" : "");
    return mc_status_exit_code(err->code);
}

/* --set: only [roughness] keys other than type and file, and [mesh] keys. */
static int set_allowed(const char *s)
{
    if (!strncmp(s, "mesh.", 5))
        return 1;
    if (strncmp(s, "roughness.", 10))
        return 0;
    const char *k = s + 10;
    size_t n = strcspn(k, "= \t");
    return !(n == 4 && !strncmp(k, "type", 4)) && !(n == 4 && !strncmp(k, "file", 4));
}

/* A length in the unit that reads best: um below 1 mm, else mm. */
static void print_len(const char *label, double v)
{
    if (!isfinite(v))
        printf("  %-18s -\n", label);
    else if (fabs(v) < 1e-3)
        printf("  %-18s %.6g um\n", label, v * 1e6);
    else
        printf("  %-18s %.6g mm\n", label, v * 1e3);
}

static void print_report(const char *path, const mc_measured *m, const mc_grid *g,
                         const double *z, const mc_roughness_params *rp)
{
    const size_t n = mc_grid_cells(g);
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k < n; k++) {
        lo = fmin(lo, z[k]);
        hi = fmax(hi, z[k]);
    }
    printf("%s\n", path);
    printf("  %-18s %s\n", "format", m->format);
    printf("  %-18s %d x %d points (nx x ny)\n", "file grid", m->grid.nx, m->grid.ny);
    if (m->grid.dx > 0)
        printf("  %-18s dx = %.6g um, dy = %.6g um\n", "file spacing", m->grid.dx * 1e6,
               m->grid.dy * 1e6);
    else
        printf("  %-18s not stated by the file (from [mesh])\n", "file spacing");
    const int same = g->nx == m->grid.nx && g->ny == m->grid.ny &&
                     (!(m->grid.dx > 0) || (fabs(g->dx - m->grid.dx) <= 1e-9 * m->grid.dx &&
                                            fabs(g->dy - m->grid.dy) <= 1e-9 * m->grid.dy));
    printf("  %-18s %d x %d, dx = %.6g um, dy = %.6g um, %.6g x %.6g mm%s\n", "mesh", g->nx,
           g->ny, g->dx * 1e6, g->dy * 1e6, g->nx * g->dx * 1e3, g->ny * g->dy * 1e3,
           same ? "" : " (resampled)");
    printf("  %-18s %ld of %ld (filled %ld)\n", "missing points", m->missing,
           (long)m->grid.nx * m->grid.ny, m->filled);
    printf("  %-18s %.6g .. %.6g um (peak to valley %.6g um)\n", "heights", lo * 1e6, hi * 1e6,
           (hi - lo) * 1e6);
    printf("roughness (%s, cut-off lambda_c %.6g mm",
           rp->filtered ? "Gaussian filter" : "row means removed", rp->cutoff * 1e3);
    if (rp->cutoff_clipped)
        printf(", clipped from %.6g mm", rp->cutoff_nominal * 1e3);
    printf(rp->cutoff_auto ? ", chosen by ISO 4288)\n" : ", [roughness] cutoff)\n");
    mc_roughness_entry e[MC_ROUGHNESS_NENTRIES];
    const int ne = mc_roughness_entries(rp, e);
    for (int k = 0; k < ne; k++) {
        if (!strcmp(e[k].unit, "m"))
            printf("  %-8s %14.6g um\n", e[k].name, e[k].value * 1e6);
        else if (!strcmp(e[k].unit, "1"))
            printf("  %-8s %14.6g\n", e[k].name, e[k].value);
        else
            printf("  %-8s %14.6g %s\n", e[k].name, e[k].value, e[k].unit);
    }
    print_len("evaluation length", rp->evaluation_length);
    printf("  %-18s %d per row, %d rows, %ld points\n", "sampling lengths", rp->n_sampling,
           rp->rows, rp->points);
    if (rp->warning[0])
        printf("warning: %s\n", rp->warning);
    if (m->warning[0])
        printf("warning: %s\n", m->warning);
}

/* surface.npy and surface.x3p into DIR: staged in DIR/.staging-XXXXXX, renamed into DIR; on
 * failure nothing stays (the directories created here are removed). */
static int write_out(const char *dir, const mc_grid *g, const mc_measured *m, const double *z,
                     mc_error *err)
{
    static const char *const names[] = {"surface.npy", "surface.x3p"};
    mc_outdir od;
    mc_outdir_init(&od);
    int st = mc_outdir_open(&od, dir, err);
    if (st == MC_OK)
        st = mc_outdir_acquire(&od, err);
    if (st != MC_OK) {
        mc_outdir_release(&od);
        return st;
    }
    mc_outdir_sweep(&od, names, 2);
    char stage[MC_OUTDIR_PATH_MAX], from[MC_OUTDIR_PATH_MAX + 32], to[MC_OUTDIR_PATH_MAX + 32];
    if (snprintf(stage, sizeof stage, "%s/.staging-XXXXXX", dir) >= (int)sizeof stage)
        st = mc_fail(err, MC_ERR_INPUT, "--out '%s': path too long", dir);
    else if (!mkdtemp(stage))
        st = mc_fail(err, MC_ERR_ENV, "--out '%s': cannot create a staging directory: %s", dir,
                     strerror(errno));
    int staged = st == MC_OK;
    if (st == MC_OK) {
        size_t shape[2] = {(size_t)g->ny, (size_t)g->nx};
        snprintf(from, sizeof from, "%s/%s", stage, names[0]);
        st = mc_npy_write(from, z, 2, shape, err);
    }
    if (st == MC_OK) {
        /* the file's coordinates: the mesh is centred on the map (measured.h), so its first
         * point lies half the mesh before the map's centre; a region given on the original
         * then selects the same points of the written file */
        double cx = 0, cy = 0;
        if (m->grid.dx > 0 && m->grid.dy > 0) {
            cx = m->grid.x0 + (m->grid.nx - 1) * m->grid.dx / 2;
            cy = m->grid.y0 + (m->grid.ny - 1) * m->grid.dy / 2;
        }
        mc_surface_data s = {.nx = g->nx, .ny = g->ny, .dx = g->dx, .dy = g->dy,
                             .x0 = cx + mc_grid_x(g, 0), .y0 = cy + mc_grid_y(g, 0),
                             .z = (double *)z};
        if (g->nx == m->grid.nx && g->ny == m->grid.ny && g->dx == m->grid.dx &&
            g->dy == m->grid.dy) { /* not resampled: the file's own offsets, bit for bit */
            s.x0 = m->grid.x0;
            s.y0 = m->grid.y0;
        }
        snprintf(from, sizeof from, "%s/%s", stage, names[1]);
        st = mc_x3p_write(from, &s, "microcontact surface", err);
    }
    for (int k = 0; st == MC_OK && k < 2; k++) {
        snprintf(from, sizeof from, "%s/%s", stage, names[k]);
        snprintf(to, sizeof to, "%s/%s", dir, names[k]);
        if (rename(from, to) != 0)
            st = mc_fail(err, MC_ERR_ENV, "%s: cannot write: %s", to, strerror(errno));
    }
    if (staged) {
        for (int k = 0; k < 2; k++) {
            snprintf(from, sizeof from, "%s/%s", stage, names[k]);
            unlink(from);
        }
        rmdir(stage);
    }
    if (st != MC_OK) {
        if (st == MC_ERR_IO)
            err->code = st = MC_ERR_ENV; /* writing into DIR failed: the environment */
        mc_outdir_rollback(&od);
    }
    mc_outdir_release(&od);
    return st;
}

int mc_cli_surface(int argc, char **argv)
{
    const char *path = NULL, *out = NULL;
    const char *sets[MAX_SETS + 2];
    int nsets = 0;
    for (int k = 0; k < argc; k++) {
        const char *set = NULL;
        if (mc_cli_is_help(argv[k])) {
            fputs(surface_help, stdout);
            return 0;
        }
        if (!strcmp(argv[k], "--out") && k + 1 < argc)
            out = argv[++k];
        else if (!strncmp(argv[k], "--out=", 6))
            out = argv[k] + 6;
        else if (!strcmp(argv[k], "--set") && k + 1 < argc)
            set = argv[++k];
        else if (!strncmp(argv[k], "--set=", 6))
            set = argv[k] + 6;
        else if (argv[k][0] == '-' && argv[k][1])
            return usage_error("unknown or incomplete option", argv[k]);
        else if (!path)
            path = argv[k];
        else
            return usage_error("one surface file only; got also", argv[k]);
        if (set) {
            if (!set_allowed(set))
                return usage_error("--set takes [roughness] keys other than type and file, and "
                                   "[mesh] keys; got",
                                   set);
            if (nsets == MAX_SETS) {
                fprintf(stderr, "microcontact: error: more than %d --set options\n", MAX_SETS);
                return 2;
            }
            sets[nsets++] = set;
        }
    }
    if (!path) {
        fprintf(stderr, "%s\n", MC_USAGE_SURFACE);
        return 2;
    }
    if (out && !out[0])
        return usage_error("--out needs a directory; got", out);

    /* the run's path: a case with [roughness] type = file, file = FILE (an override: relative
     * to the current directory, no INI quoting) */
    char fileset[MC_PATH_MAX + 32];
    if (snprintf(fileset, sizeof fileset, "roughness.file=%s", path) >= (int)sizeof fileset) {
        fprintf(stderr, "microcontact: error: %s: the file name is longer than %d bytes\n", path,
                MC_PATH_MAX - 1);
        return 2;
    }
    sets[nsets++] = fileset;
    static mc_scene scene;
    mc_error err = {0};
    /* a load only because a scene needs one: nothing is solved */
    if (mc_case_parse_text("[load]\nforce = 1\n[roughness]\ntype = file\n", path, NULL, nsets,
                           sets, &scene, &err) != MC_OK)
        return fail_parse(path, &err);

    const mc_grid *g = &scene.grid;
    mc_measured_spec ms;
    mc_measured m;
    mc_surface_measured_spec(&scene.roughness, &ms);
    double *z = NULL;
    int st = mc_measured_load(&ms, &m, &err);
    if (st == MC_OK && !(z = mc_zeros(mc_grid_cells(g))))
        st = mc_fail(&err, MC_ERR_NOMEM, "%s: out of memory for %d x %d heights", path, g->nx,
                     g->ny);
    if (st == MC_OK)
        st = mc_measured_onto(&m, g, (mc_resample_rule)scene.roughness.resample, z, &err);
    mc_roughness_params rp;
    if (st == MC_OK) { /* as pipeline.c computes roughness.initial */
        mc_roughness_options opt;
        mc_roughness_options_default(&opt);
        opt.cutoff = scene.roughness.cutoff;
        opt.periodic_x = g->periodic_x;
        opt.periodic_y = g->periodic_y;
        st = mc_roughness_compute(z, NULL, g->nx, g->ny, g->dx, g->dy, &opt, &rp, &err);
        if (st != MC_OK)
            mc_error_prefix(&err, "%s: roughness parameters: ", path);
    }
    if (st == MC_OK && out)
        st = write_out(out, g, &m, z, &err);
    if (st == MC_OK) {
        print_report(path, &m, g, z, &rp);
        if (out)
            printf("written: %s/surface.npy, %s/surface.x3p\n", out, out);
    }
    mc_measured_free(&m);
    mc_free(z);
    return st == MC_OK ? 0 : fail(&err);
}
