/* output.c - the output contract (README.md, Outputs), written atomically (see output.h).
 *
 * Protocol: the directory is created if needed and locked (outdir.c), stale staging areas of
 * killed runs are removed, every file goes into DIR/.staging-XXXXXX; only when all of them are
 * complete are they renamed into DIR: first the old summary.json is removed (so a summary.json in
 * DIR always describes the files beside it), then the data files are renamed, contract files of
 * an earlier run that this run does not produce are removed, and summary.json is renamed last.
 * A request to stop (mc_output_interrupt) is honoured before each file and before the renames.
 */
#include "pipeline/output.h"

#include <dirent.h>
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "kernels/kernel.h"
#include "io/le.h"
#include "io/npy.h"
#include "io/surface_file.h"
#include "pipeline/summary_json.h"
#include "surface/roughness.h"

#define OUT_PATH_MAX 4096

static const char *const stress_npy[MC_NSTRESS] = {
    [MC_SXX] = "stress_xx.npy", [MC_SYY] = "stress_yy.npy", [MC_SZZ] = "stress_zz.npy",
    [MC_SXY] = "stress_xy.npy", [MC_SYZ] = "stress_yz.npy", [MC_SXZ] = "stress_xz.npy"};

/* The output table: every file a run can write, when it writes it and what it holds. The stale
 * file sweep, the commit, the bound of out_ctx.files, the CLI's "results in" line
 * (mc_output_files_joined) and docs/outputs.md (mc_output_reference_markdown) come from it; a
 * run that writes a file not in the table, or not the files the table says, fails with
 * MC_ERR_INTERNAL (check_written). To add a file: a row here and its writer below; nothing else.
 * No '|' in help (it goes into a Markdown table). */
typedef enum {
    OUT_ALWAYS,
    OUT_STRESS,        /* stress layers */
    OUT_VTK,           /* [output] vtk */
    OUT_VTK_STRESS,    /* vtk and stress layers */
    OUT_PLASTIC,       /* the elastic-plastic stage's fields */
    OUT_RUNIN,         /* [runin] */
    OUT_RUNIN_INITIAL, /* [runin] with the surface before */
    OUT_RUNIN_FINAL,   /* [runin] with the surface after */
    OUT_RUNIN_BOTH,    /* [runin] with the surfaces before and after */
    OUT_X3P,           /* [output] x3p */
    OUT_X3P_PLASTIC,   /* x3p and the elastic-plastic fields */
    OUT_X3P_INITIAL,   /* x3p and the running-in's surface before */
    OUT_X3P_FINAL,     /* x3p and the running-in's surface after */
    OUT_BODIES,        /* [roughness2]: each body's surface before */
    OUT_BODIES_FINAL,  /* [roughness2] and a final surface (plastic stage, running-in) */
    OUT_X3P_BODIES,    /* x3p and each body's surface before */
    OUT_X3P_BODIES_FINAL /* x3p and each body's surface after */
} out_when;

static const struct {
    const char *name;
    out_when when;
    const char *help;
} outputs[] = {
    {"summary.json", OUT_ALWAYS,
     "mesh, materials, load, roughness with its ISO parameters (with [roughness2] also each body's, roughness.body1 and roughness.body2, before and after), contact results, stress summary, lubrication{...} and plastic{...} when those stages ran, warnings, timings (SI units)"},
    {"pressure.npy", OUT_ALWAYS,
     "contact pressure, ny x nx float64, Pa"},
    {"gap.npy", OUT_ALWAYS,
     "gap = topography + displacement - approach, ny x nx, m"},
    {"displacement.npy", OUT_ALWAYS,
     "surface displacement, ny x nx, m"},
    {"topography.npy", OUT_ALWAYS,
     "gap at zero load (shape and roughness), ny x nx, m"},
    {"profile_x.csv", OUT_ALWAYS,
     "x, pressure, gap, displacement along the row through the maximum pressure"},
    {"von_mises.npy", OUT_STRESS,
     "von Mises stress, layers x ny x nx, Pa"},
    {"hydrostatic.npy", OUT_STRESS,
     "hydrostatic stress, layers x ny x nx, Pa"},
    {"stress_xx.npy", OUT_STRESS,
     "stress component xx, layers x ny x nx, Pa (tension positive)"},
    {"stress_yy.npy", OUT_STRESS,
     "stress component yy, layers x ny x nx, Pa"},
    {"stress_zz.npy", OUT_STRESS,
     "stress component zz, layers x ny x nx, Pa"},
    {"stress_xy.npy", OUT_STRESS,
     "stress component xy, layers x ny x nx, Pa"},
    {"stress_yz.npy", OUT_STRESS,
     "stress component yz, layers x ny x nx, Pa"},
    {"stress_xz.npy", OUT_STRESS,
     "stress component xz, layers x ny x nx, Pa"},
    {"depths.csv", OUT_STRESS,
     "the layer depths, m"},
    {"axis.csv", OUT_STRESS,
     "stresses versus depth under the maximum pressure"},
    {"field.vti", OUT_VTK,
     "ParaView image of the surface fields"},
    {"stress.vtr", OUT_VTK_STRESS,
     "ParaView grid of the stress fields"},
    {"residual_displacement.npy", OUT_PLASTIC,
     "the permanent surface displacement (positive into the body), ny x nx, m"},
    {"topography_final.npy", OUT_PLASTIC,
     "the unloaded gap the next load sees (initial gap + residual displacement), ny x nx, m"},
    {"plastic_strain.npy", OUT_PLASTIC,
     "accumulated equivalent plastic strain of body 1, nz x ny x nx, depth into the body (zero outside the columns under the contact; layer k at depth (k + 1/2) dz, or with graded layers at summary.json plastic.layer_depths[k], plastic.layer_thickness[k] thick); with bodies = both body 2's too, the same field (one material deforming alike: summary.json roughness.body2.plastic_strain names this file)"},
    {"residual_von_mises.npy", OUT_PLASTIC,
     "von Mises stress of the residual stresses after unloading, nz x ny x nx, Pa"},
    {"plastic.csv", OUT_PLASTIC,
     "one row per load step: load, approach, p_max, contact area, plastic volume, largest plastic strain and its position, largest residual displacement, iterations"},
    {"runin.csv", OUT_RUNIN,
     "one row per running-in step: force, phase down/up, speed, h_EHD, p_lub, psi_load, psi_area, pocket height, mu; the roughness of the surface after the step: Ra, Rq, Rz, Sa, Sq, Rpk, Rk, Rvk, Mr1, Mr2 (ISO 13565-2, mean over the rows), Sp, Spk, Sk, Svk, Smr1, Smr2 (ISO 25178-2, the whole map); largest residual displacement, converged, seconds, ... (SI: m, Pa, rad/s; material ratios in %)"},
    {"runin.gp", OUT_RUNIN,
     "the gnuplot script of the running-in figures (cd DIR; gnuplot runin.gp): Ra, psi and mu (the paper's Figs. 4-1 to 4-3), the material-ratio curves, the height maps before and after"},
    {"surface_initial.npy", OUT_RUNIN_INITIAL,
     "the composite surface before the running-in, ny x nx, m"},
    {"surface_final.npy", OUT_RUNIN_FINAL,
     "the composite surface after the running-in, ny x nx, m"},
    {"material_ratio.csv", OUT_RUNIN_BOTH,
     "the areal material-ratio (Abbott-Firestone) curves of the surface before and after the running-in: Mr in % (steps of 0.1 %), height of each about its mean plane, and the equivalent straight line of each (ISO 13565-2, 25178-2: its heights at Mr = 0 and 100 % bound the core Sk; the curve crosses them at Smr1 and Smr2), m"},
    {"topography.x3p", OUT_X3P,
     "topography.npy as X3P (ISO 25178-72), heights in m"},
    {"topography_final.x3p", OUT_X3P_PLASTIC,
     "topography_final.npy as X3P"},
    {"surface_initial.x3p", OUT_X3P_INITIAL,
     "surface_initial.npy as X3P"},
    {"surface_final.x3p", OUT_X3P_FINAL,
     "surface_final.npy as X3P"},
    {"surface_initial_body1.npy", OUT_BODIES,
     "body 1's surface ([roughness]) before the run: its heights, outward towards body 2, ny x nx, m; the gap's roughness is the sum of the two bodies' (topography = shape - body 1 - body 2)"},
    {"surface_initial_body2.npy", OUT_BODIES,
     "body 2's surface ([roughness2]) before the run, outward towards body 1, ny x nx, m"},
    {"surface_final_body1.npy", OUT_BODIES_FINAL,
     "body 1's surface after the elastic-plastic stage or the running-in: surface_initial_body1 minus its residual dent (residual_displacement.npy; with an elastic material unchanged), ny x nx, m"},
    {"surface_final_body2.npy", OUT_BODIES_FINAL,
     "body 2's surface after: surface_initial_body2 minus residual_displacement.npy with [plasticity] bodies = both, else unchanged (body 2 stays elastic), ny x nx, m"},
    {"surface_initial_body1.x3p", OUT_X3P_BODIES,
     "surface_initial_body1.npy as X3P"},
    {"surface_initial_body2.x3p", OUT_X3P_BODIES,
     "surface_initial_body2.npy as X3P"},
    {"surface_final_body1.x3p", OUT_X3P_BODIES_FINAL,
     "surface_final_body1.npy as X3P"},
    {"surface_final_body2.x3p", OUT_X3P_BODIES_FINAL,
     "surface_final_body2.npy as X3P"},
};
#define N_OUTPUTS ((int)(sizeof outputs / sizeof outputs[0]))

static const char *const when_text[] = {
    [OUT_ALWAYS] = "always",
    [OUT_STRESS] = "with [stress]",
    [OUT_VTK] = "with [output] vtk = yes",
    [OUT_VTK_STRESS] = "with [output] vtk = yes and [stress]",
    [OUT_PLASTIC] = "with [plasticity]",
    [OUT_RUNIN] = "with [runin]",
    [OUT_RUNIN_INITIAL] = "with [runin]",
    [OUT_RUNIN_FINAL] = "with [runin]",
    [OUT_RUNIN_BOTH] = "with [runin]",
    [OUT_X3P] = "with [output] x3p = yes",
    [OUT_X3P_PLASTIC] = "with [output] x3p = yes and [plasticity]",
    [OUT_X3P_INITIAL] = "with [output] x3p = yes and [runin]",
    [OUT_X3P_FINAL] = "with [output] x3p = yes and [runin]",
    [OUT_BODIES] = "with [roughness2]",
    [OUT_BODIES_FINAL] = "with [roughness2] and [plasticity] or [runin]",
    [OUT_X3P_BODIES] = "with [output] x3p = yes and [roughness2]",
    [OUT_X3P_BODIES_FINAL] = "with [output] x3p = yes, [roughness2] and [plasticity] or [runin]"};

static int out_wanted(out_when w, const mc_scene *sc, const mc_results *r)
{
    int stress = r->nlayers > 0, plastic = r->plastic.enabled && r->residual_displacement;
    switch (w) {
    case OUT_ALWAYS: return 1;
    case OUT_STRESS: return stress;
    case OUT_VTK: return sc->output.vtk;
    case OUT_VTK_STRESS: return sc->output.vtk && stress;
    case OUT_PLASTIC: return plastic;
    case OUT_RUNIN: return r->runin.enabled;
    case OUT_RUNIN_INITIAL: return r->runin.enabled && r->surface_initial;
    case OUT_RUNIN_FINAL: return r->runin.enabled && r->surface_final;
    case OUT_RUNIN_BOTH: return r->runin.enabled && r->surface_initial && r->surface_final;
    case OUT_X3P: return sc->output.x3p;
    case OUT_X3P_PLASTIC: return sc->output.x3p && plastic;
    case OUT_X3P_INITIAL: return sc->output.x3p && r->runin.enabled && r->surface_initial;
    case OUT_X3P_FINAL: return sc->output.x3p && r->runin.enabled && r->surface_final;
    case OUT_BODIES: return r->two_bodies;
    case OUT_BODIES_FINAL: return r->two_bodies && r->body_has_final;
    case OUT_X3P_BODIES: return sc->output.x3p && r->two_bodies;
    case OUT_X3P_BODIES_FINAL: return sc->output.x3p && r->two_bodies && r->body_has_final;
    }
    return 0;
}

int mc_output_file_count(void) { return N_OUTPUTS; }

const char *mc_output_file_name(int i) { return i >= 0 && i < N_OUTPUTS ? outputs[i].name : NULL; }

const char *mc_output_file_help(int i) { return i >= 0 && i < N_OUTPUTS ? outputs[i].help : NULL; }

int mc_output_file_written(int i, const mc_scene *scene, const mc_results *res)
{
    return i >= 0 && i < N_OUTPUTS && out_wanted(outputs[i].when, scene, res);
}

void mc_output_files_joined(const mc_scene *scene, const mc_results *res, const char *sep,
                            char *buf, size_t len)
{
    size_t o = 0;
    if (len)
        buf[0] = '\0';
    for (int i = 0, first = 1; i < N_OUTPUTS && o + 1 < len; i++) {
        if (!out_wanted(outputs[i].when, scene, res))
            continue;
        int n = snprintf(buf + o, len - o, "%s%s", first ? "" : sep, outputs[i].name);
        o = n > 0 && o + (size_t)n < len ? o + (size_t)n : len - 1;
        first = 0;
    }
}

char *mc_output_reference_markdown(void)
{
    size_t len = 256;
    for (int i = 0; i < N_OUTPUTS; i++)
        len += strlen(outputs[i].name) + strlen(outputs[i].help) + 64;
    char *s = mc_malloc(len);
    if (!s)
        return NULL;
    size_t o = (size_t)snprintf(s, len,
                                "<!-- generated by mc_output_reference_markdown() from the output "
                                "table in src/pipeline/output.c; edit that table, not the text "
                                "below -->\n\n| file | written | content |\n|---|---|---|\n");
    for (int i = 0; i < N_OUTPUTS && o < len; i++)
        o += (size_t)snprintf(s + o, len - o, "| `%s` | %s | %s |\n", outputs[i].name,
                              when_text[outputs[i].when], outputs[i].help);
    return s;
}

typedef struct {
    const char *dir;
    char stage[OUT_PATH_MAX];
    const char *files[N_OUTPUTS]; /* written so far, in order; static strings (record) */
    int nfiles;
    const mc_scene *scene;
    const mc_results *res;
    int ic, jc; /* cell of maximum pressure: profile row and stress axis */
} out_ctx;

static int join(char *out, const char *a, const char *b, mc_error *err)
{
    if (snprintf(out, OUT_PATH_MAX, "%s/%s", a, b) >= OUT_PATH_MAX)
        return mc_fail(err, MC_ERR_INPUT, "output path '%s/%s' too long", a, b);
    return MC_OK;
}

/* ---- interruption ------------------------------------------------------------------------ */

/* Dekker-style handshake (sequentially consistent atomics): a commit increments `active` and
 * then reads `stop`; mc_output_interrupt sets `stop` and then reads `active`. Either the commit
 * sees the request, or the interrupter sees the commit. */
static atomic_int stop_requested;
static atomic_int active_commits;

int mc_output_interrupt(int on)
{
    atomic_store(&stop_requested, on ? 1 : 0);
    return atomic_load(&active_commits) > 0;
}

void mc_output_hold(int on)
{
    if (on)
        atomic_fetch_add(&active_commits, 1);
    else
        atomic_fetch_sub(&active_commits, 1);
}

int mc_output_stop_requested(void)
{
    return atomic_load(&stop_requested);
}

static int check_stop(mc_error *err)
{
    if (atomic_load(&stop_requested))
        return mc_fail(err, MC_ERR_INTERRUPTED, "output: interrupted; no result was committed");
    return MC_OK;
}

/* ---- small writers ----------------------------------------------------------------------- */

/* Note a staged file: it must be a row of the output table, written once (this bounds files[]). */
static int record(out_ctx *c, const char *name, mc_error *err)
{
    int row = -1;
    for (int i = 0; i < N_OUTPUTS && row < 0; i++)
        if (strcmp(outputs[i].name, name) == 0)
            row = i;
    for (int k = 0; row >= 0 && k < c->nfiles; k++)
        if (strcmp(c->files[k], name) == 0)
            row = -1;
    if (row < 0 || c->nfiles >= N_OUTPUTS)
        return mc_fail(err, MC_ERR_INTERNAL,
                       "output: '%s' is not a row of the output table or is written twice", name);
    c->files[c->nfiles++] = outputs[row].name;
    return MC_OK;
}

static int open_staged(out_ctx *c, const char *name, FILE **f, mc_error *err)
{
    char path[OUT_PATH_MAX];
    int st = check_stop(err);
    if (st == MC_OK)
        st = join(path, c->stage, name, err);
    if (st != MC_OK)
        return st;
    *f = fopen(path, "wb");
    if (!*f)
        return mc_fail(err, MC_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    return MC_OK;
}

/* Close a staged file, checking every buffered write; records the name on success. */
static int close_staged(out_ctx *c, const char *name, FILE *f, mc_error *err)
{
    int bad = ferror(f), e = errno;
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (bad)
        return mc_fail(err, MC_ERR_IO, "%s/%s: cannot write: %s", c->stage, name, strerror(e));
    return record(c, name, err);
}

static int write_npy(out_ctx *c, const char *name, const double *data, int ndim,
                     const size_t *shape, mc_error *err)
{
    char path[OUT_PATH_MAX];
    int st = check_stop(err);
    if (st == MC_OK)
        st = join(path, c->stage, name, err);
    if (st == MC_OK)
        st = mc_npy_write(path, data, ndim, shape, err);
    if (st == MC_OK)
        st = record(c, name, err);
    return st;
}

static int produced(const out_ctx *c, const char *name)
{
    for (int k = 0; k < c->nfiles; k++)
        if (strcmp(c->files[k], name) == 0)
            return 1;
    return 0;
}

/* One surface height map (ny x nx, m) as X3P: points at the cell centres of the grid, so the
 * file's offsets are the centre of cell (0, 0); the heights bit for bit (io/surface_file.h). */
static int write_x3p(out_ctx *c, const char *name, const double *z, mc_error *err)
{
    const mc_grid *g = &c->res->grid;
    char path[OUT_PATH_MAX];
    int st = check_stop(err);
    if (st == MC_OK)
        st = join(path, c->stage, name, err);
    if (st != MC_OK)
        return st;
    mc_surface_data s = {.nx = g->nx, .ny = g->ny, .dx = g->dx, .dy = g->dy,
                         .x0 = mc_grid_x(g, 0), .y0 = mc_grid_y(g, 0), .z = (double *)z};
    st = mc_x3p_write(path, &s, "microcontact", err);
    if (st == MC_OK)
        st = record(c, name, err);
    return st;
}

/* [output] x3p: an .x3p beside every surface height map .npy, the same field. */
static int write_x3p_surfaces(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    int st = write_x3p(c, "topography.x3p", r->topography, err);
    if (st == MC_OK && produced(c, "topography_final.npy"))
        st = write_x3p(c, "topography_final.x3p", r->topography_final, err);
    if (st == MC_OK && produced(c, "surface_initial.npy"))
        st = write_x3p(c, "surface_initial.x3p", r->surface_initial, err);
    if (st == MC_OK && produced(c, "surface_final.npy"))
        st = write_x3p(c, "surface_final.x3p", r->surface_final, err);
    static const char *const body_x3p[2][2] = {
        {"surface_initial_body1.x3p", "surface_initial_body2.x3p"},
        {"surface_final_body1.x3p", "surface_final_body2.x3p"}};
    for (int k = 0; st == MC_OK && r->two_bodies && k < 2; k++) {
        st = write_x3p(c, body_x3p[0][k], r->body_initial[k], err);
        if (st == MC_OK && r->body_has_final)
            st = write_x3p(c, body_x3p[1][k], r->body_final[k], err);
    }
    return st;
}

/* ---- the files --------------------------------------------------------------------------- */

static size_t cells(const out_ctx *c) { return mc_grid_cells(&c->res->grid); }

static int write_surface_fields(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    size_t shape[2] = {(size_t)r->grid.ny, (size_t)r->grid.nx};
    int st = write_npy(c, "pressure.npy", r->pressure, 2, shape, err);
    if (st == MC_OK)
        st = write_npy(c, "gap.npy", r->gap, 2, shape, err);
    if (st == MC_OK)
        st = write_npy(c, "displacement.npy", r->displacement, 2, shape, err);
    if (st == MC_OK)
        st = write_npy(c, "topography.npy", r->topography, 2, shape, err);
    return st;
}

/* The elastic-plastic stage: residual and final surfaces, the plastic volume, one row per step. */
static int write_plastic(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    const mc_stage_plastic_summary *ps = &r->plastic;
    size_t shape[2] = {(size_t)r->grid.ny, (size_t)r->grid.nx};
    size_t vshape[3] = {(size_t)(ps->nz > 0 ? ps->nz : 1), shape[0], shape[1]};
    int st = write_npy(c, "residual_displacement.npy", r->residual_displacement, 2, shape, err);
    if (st == MC_OK)
        st = write_npy(c, "topography_final.npy", r->topography_final, 2, shape, err);
    if (st == MC_OK && r->plastic_strain)
        st = write_npy(c, "plastic_strain.npy", r->plastic_strain, 3, vshape, err);
    if (st == MC_OK && r->residual_von_mises)
        st = write_npy(c, "residual_von_mises.npy", r->residual_von_mises, 3, vshape, err);
    if (st != MC_OK)
        return st;
    FILE *f;
    st = open_staged(c, "plastic.csv", &f, err);
    if (st != MC_OK)
        return st;
    fprintf(f, "step,load,approach,p_max,contact_area,plastic_volume,peq_max,peq_max_x,peq_max_y,"
               "peq_max_depth,residual_max,outer_iterations,plastic_iterations,converged\n");
    for (int k = 0; k < ps->steps_done; k++) {
        const mc_plastic_step *s = &ps->steps[k];
        fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%d\n",
                k + 1, s->load, s->approach, s->p_max, s->area, s->plastic_volume, s->peq_max,
                s->peq_at[0], s->peq_at[1], s->peq_at[2], s->residual_max, s->outer_iterations,
                s->plastic_iterations, s->converged);
    }
    return close_staged(c, "plastic.csv", f, err);
}

/* runin.csv's columns, in order; runin.gp finds the columns it plots here, by name. */
static const char runin_header[] =
    "force,phase,speed,h_ehd,p_lub,psi_load,psi_area,pocket_height,mu,Ra,Rq,Rz,Sa,Sq,Rpk,Rk,Rvk,"
    "Mr1,Mr2,Sp,Spk,Sk,Svk,Smr1,Smr2,residual_max,converged,seconds,step,rpm,entrainment_speed,"
    "regime,plastic,contact_solves,volume_roots,root_error";

/* 1-based column of name in runin_header (0: none; a figure then plots nothing). */
static int runin_column(const char *name)
{
    const size_t len = strlen(name);
    int col = 1;
    for (const char *p = runin_header;; col++) {
        const char *q = strchr(p, ',');
        size_t l = q ? (size_t)(q - p) : strlen(p);
        if (l == len && strncmp(p, name, len) == 0)
            return col;
        if (!q)
            return 0;
        p = q + 1;
    }
}

/* Points of material_ratio.csv's curves: Mr in steps of 0.1 %. */
#define MR_POINTS 1001

/* The material-ratio curves of the surfaces before and after (surface/roughness.h). */
static int write_material_ratio(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    const size_t n = cells(c);
    double *z = mc_malloc(2 * MR_POINTS * sizeof *z);
    if (!z)
        return mc_fail(err, MC_ERR_NOMEM, "material_ratio.csv: out of memory");
    mc_material_ratio line[2];
    int st = mc_roughness_material_curve(r->surface_initial, NULL, n, MR_POINTS, z, &line[0], err);
    if (st == MC_OK)
        st = mc_roughness_material_curve(r->surface_final, NULL, n, MR_POINTS, z + MR_POINTS,
                                         &line[1], err);
    FILE *f = NULL;
    if (st == MC_OK)
        st = open_staged(c, "material_ratio.csv", &f, err);
    if (st != MC_OK) {
        mc_free(z);
        return st;
    }
    fprintf(f, "Mr,initial,final,line_initial,line_final\n");
    for (int k = 0; k < MR_POINTS; k++) {
        const double mr = 100.0 * k / (MR_POINTS - 1);
        fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", mr, z[k], z[MR_POINTS + k],
                line[0].c0 + (line[0].c100 - line[0].c0) * mr / 100.0,
                line[1].c0 + (line[1].c100 - line[1].c0) * mr / 100.0);
    }
    mc_free(z);
    return close_staged(c, "material_ratio.csv", f, err);
}

/* Bytes before the data of a .npy file written by this run (gnuplot skips them). */
static long npy_skip(const out_ctx *c, const char *name, mc_error *err)
{
    char path[OUT_PATH_MAX];
    struct stat sb;
    if (join(path, c->stage, name, err) != MC_OK)
        return -1;
    if (stat(path, &sb) != 0) {
        mc_fail(err, MC_ERR_IO, "%s: cannot stat: %s", path, strerror(errno));
        return -1;
    }
    return (long)sb.st_size - (long)(8 * cells(c));
}

/* runin.gp's height maps: the surface before and after on one colour scale, and with the
 * plastic fields the change, -f u_r (f = 2 when both bodies deform), in nm. */
static int write_runin_maps(out_ctx *c, FILE *f, mc_error *err)
{
    const mc_results *r = c->res;
    const mc_grid *g = &r->grid;
    const size_t n = cells(c);
    const int change = produced(c, "residual_displacement.npy");
    const double factor = c->scene->plasticity.both ? 2.0 : 1.0;
    long skip_i = npy_skip(c, "surface_initial.npy", err);
    long skip_f = skip_i >= 0 ? npy_skip(c, "surface_final.npy", err) : -1;
    long skip_u = change && skip_f >= 0 ? npy_skip(c, "residual_displacement.npy", err) : 0;
    if (skip_i < 0 || skip_f < 0 || skip_u < 0)
        return err ? err->code : MC_ERR_IO;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        lo = fmin(lo, fmin(r->surface_initial[i], r->surface_final[i]));
        hi = fmax(hi, fmax(r->surface_initial[i], r->surface_final[i]));
    }
    if (!(hi > lo))
        hi = lo + 1e-9;
    const double w = g->nx * g->dx * 1e6, h = g->ny * g->dy * 1e6;
    fprintf(f, "\n# the height maps: the .npy files read as raw float64, ny x nx with x fastest, "
               "after their\n# header (skip = its bytes); x and y in um at the cell centres, "
               "heights in um\n"
               "set output 'runin_surface.png'\n"
               "set terminal pngcairo size %d,%d font 'sans,11'\n"
               "unset logscale x\nunset key\nset size ratio -1\nset xlabel 'x [um]'\n"
               "set ylabel 'y [um]'\nset xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n"
               "set palette rgbformulae 33,13,10\nset multiplot layout 1,%d\n"
               "set cbrange [%.17g:%.17g]\nset cblabel 'height [um]'\n",
            change ? 1500 : 1000, h > w ? 700 : 500, -0.5 * w, 0.5 * w, -0.5 * h, 0.5 * h,
            change ? 3 : 2, lo * 1e6, hi * 1e6);
    const char *what[2] = {"surface_initial.npy", "surface_final.npy"};
    const char *title[2] = {"before the running-in", "after the running-in"};
    const long skip[2] = {skip_i, skip_f};
    for (int k = 0; k < 2 + change; k++) {
        fprintf(f, "set title '%s'\n", k < 2 ? title[k] : "change (after - before)");
        if (k == 2) { /* lowered blue, raised red, on a scale symmetric about 0 */
            double m = 0;
            for (size_t i = 0; i < n; i++)
                m = fmax(m, fabs(factor * r->residual_displacement[i]));
            fprintf(f, "set cbrange [%.17g:%.17g]\nset cblabel 'change [nm]'\n"
                       "set palette defined (0 'blue', 1 'white', 2 'red')\n",
                    -(m > 0 ? m : 1e-12) * 1e9, (m > 0 ? m : 1e-12) * 1e9);
        }
        fprintf(f,
                "plot '%s' binary skip=%ld array=(%d,%d) format='%%float64' endian=little "
                "dx=%.17g dy=%.17g origin=(%.17g,%.17g) using ($1 * %.17g) with image\n",
                k < 2 ? what[k] : "residual_displacement.npy", k < 2 ? skip[k] : skip_u, g->nx,
                g->ny, g->dx * 1e6, g->dy * 1e6, mc_grid_x(g, 0) * 1e6, mc_grid_y(g, 0) * 1e6,
                k < 2 ? 1e6 : -factor * 1e9);
    }
    fprintf(f, "unset multiplot\n");
    return MC_OK;
}

/* [roughness2]: each body's surface before and after (pipeline/bodies.h). */
static int write_bodies(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    size_t shape[2] = {(size_t)r->grid.ny, (size_t)r->grid.nx};
    static const char *const name[2][2] = {
        {"surface_initial_body1.npy", "surface_initial_body2.npy"},
        {"surface_final_body1.npy", "surface_final_body2.npy"}};
    int st = MC_OK;
    for (int k = 0; st == MC_OK && k < 2; k++) {
        st = write_npy(c, name[0][k], r->body_initial[k], 2, shape, err);
        if (st == MC_OK && r->body_has_final)
            st = write_npy(c, name[1][k], r->body_final[k], 2, shape, err);
    }
    return st;
}

/* The running-in: one row per step, the figures' script, the surfaces before and after and
 * their material-ratio curves. */
static int write_runin(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    const mc_runin_summary *ri = &r->runin;
    size_t shape[2] = {(size_t)r->grid.ny, (size_t)r->grid.nx};
    int st = MC_OK;
    if (r->surface_initial)
        st = write_npy(c, "surface_initial.npy", r->surface_initial, 2, shape, err);
    if (st == MC_OK && r->surface_final)
        st = write_npy(c, "surface_final.npy", r->surface_final, 2, shape, err);
    const int both = r->surface_initial && r->surface_final;
    if (st == MC_OK && both)
        st = write_material_ratio(c, err);
    FILE *f;
    if (st == MC_OK)
        st = open_staged(c, "runin.csv", &f, err);
    if (st != MC_OK)
        return st;
    static const char *const regimes[] = {"dry", "mixed", "full_film"};
    fprintf(f, "%s\n", runin_header);
    for (int k = 0; k < ri->done; k++) {
        const mc_runin_row *w = &ri->rows[k];
        fprintf(f,
                "%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
                "%.17g,",
                w->force, w->up ? "up" : "down", w->speed, w->h_ehd, w->p_lub, w->psi_load,
                w->psi_area, w->pocket_height, w->mu, w->ra, w->rq, w->rz, w->sa, w->sq);
        fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,", w->rpk,
                w->rk, w->rvk, w->mr1, w->mr2, w->sp, w->spk, w->sk, w->svk, w->smr1, w->smr2);
        fprintf(f, "%.17g,%d,%.6g,%d,%.17g,%.17g,%s,%d,%d,%d,%.6g\n", w->residual_max,
                w->converged, w->seconds, k + 1, w->speed * 60.0 / (2.0 * M_PI), w->entrainment,
                w->regime >= 0 && w->regime < 3 ? regimes[w->regime] : "?", w->plastic,
                w->solves, w->roots, w->root_error);
    }
    st = close_staged(c, "runin.csv", f, err);
    if (st == MC_OK)
        st = open_staged(c, "runin.gp", &f, err);
    if (st != MC_OK)
        return st;
    /* gnuplot selects each force's rows by value: the forces are written in full precision */
    fprintf(f, "# runin.gp - the running-in figures from runin.csv (Mevissen et al. 2025, Figs.\n"
               "# 4-1 to 4-3) and from the surfaces: cd into this directory and run  gnuplot "
               "runin.gp\n"
               "# runin_ra.png       Ra of the surface against the mean lubrication pocket "
               "height\n"
               "# runin_psi.png      solid contact ratio psi (load and area) against it\n"
               "# runin_mu.png       mu against the disc speed: run-down and run-up "
               "(hysteresis)\n"
               "# runin_mr.png       material-ratio (Abbott-Firestone) curves before and after\n"
               "# runin_surface.png  height maps before and after (and the change)\n"
               "set datafile separator ','\nset terminal pngcairo size 900,600 font 'sans,11'\n"
               "set key outside right\nset grid\n");
    fprintf(f, "down(F, v) = (strcol(2) eq 'down' && abs($1 - F) <= 1e-9 * F) ? v : 1/0\n"
               "up(F, v) = (strcol(2) eq 'up' && abs($1 - F) <= 1e-9 * F) ? v : 1/0\n");
    static const struct {
        const char *png, *xlabel, *ylabel, *x, *y;
        double xscale, yscale;
    } figs[] = {
        {"runin_ra.png", "mean pocket height h_pocket [um]", "Ra [um]", "pocket_height", "Ra",
         1e6, 1e6},
        {"runin_psi.png", "mean pocket height h_pocket [um]", "solid contact ratio psi_load",
         "pocket_height", "psi_load", 1e6, 1},
        {"runin_mu.png", "disc speed [rpm]", "friction coefficient mu", "rpm", "mu", 1, 1}};
    for (int g = 0; g < 3; g++)
        if (!runin_column(figs[g].x) || !runin_column(figs[g].y)) {
            fclose(f);
            return mc_fail(err, MC_ERR_INTERNAL, "runin.gp: '%s' or '%s' is not a column of "
                           "runin.csv", figs[g].x, figs[g].y);
        }
    for (int g = 0; g < 3; g++) {
        fprintf(f, "\nset output '%s'\nset xlabel '%s'\nset ylabel '%s'\n%s", figs[g].png,
                figs[g].xlabel, figs[g].ylabel, g == 2 ? "set logscale x\n" : "unset logscale x\n");
        fprintf(f, "plot");
        for (int k = 0; k < ri->nforces; k++) {
            const int first = 2 * ri->nspeeds * k;
            const double F = first < ri->done ? ri->rows[first].force : 0.0;
            for (int ph = 0; ph < 2; ph++)
                fprintf(f, "%s'runin.csv' every ::1 using ($%d * %g):(%s(%.17g, $%d * %g)) "
                           "with linespoints pt %d lc %d title '%.6g N %s'",
                        k || ph ? ", \\\n    " : " ", runin_column(figs[g].x), figs[g].xscale,
                        ph ? "up" : "down", F, runin_column(figs[g].y), figs[g].yscale,
                        ph ? 6 : 7, k + 1, F, ph ? "run-up" : "run-down");
        }
        fprintf(f, "\n");
    }
    if (both) {
        /* the material ratio: the whole curve, and its peak zone where running-in acts first */
        fprintf(f, "\n# material_ratio.csv: Mr [%%], heights about the mean plane [m]\n"
                   "set output 'runin_mr.png'\nset terminal pngcairo size 1200,600 font "
                   "'sans,11'\nunset logscale x\nset key inside top right\n"
                   "set xlabel 'material ratio Mr [%%]'\nset ylabel 'height [um]'\n"
                   "set multiplot layout 1,2\n");
        for (int zoom = 0; zoom < 2; zoom++)
            fprintf(f,
                    "set title '%s'\nset xrange [0:%d]\nplot 'material_ratio.csv' every ::1 using "
                    "1:($2 * 1e6) with lines lw 2 lc 1 title 'before', '' every ::1 using "
                    "1:($3 * 1e6) with lines lw 2 lc 2 title 'after', '' every ::1 using "
                    "1:($4 * 1e6) with lines dt 2 lc 1 title 'Sk line before', '' every ::1 "
                    "using 1:($5 * 1e6) with lines dt 2 lc 2 title 'Sk line after'\n",
                    zoom ? "the peaks: Mr 0 - 10 %" : "material-ratio (Abbott-Firestone) curve",
                    zoom ? 10 : 100);
        fprintf(f, "unset multiplot\nset xrange [*:*]\nunset title\n");
        st = write_runin_maps(c, f, err);
        if (st != MC_OK) {
            fclose(f);
            return st;
        }
    }
    return close_staged(c, "runin.gp", f, err);
}

static int write_profile(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    const mc_grid *g = &r->grid;
    FILE *f;
    int st = open_staged(c, "profile_x.csv", &f, err);
    if (st != MC_OK)
        return st;
    fprintf(f, "x,pressure,gap,displacement\n");
    for (int i = 0; i < g->nx; i++) {
        size_t k = (size_t)c->jc * (size_t)g->nx + (size_t)i;
        fprintf(f, "%.17g,%.17g,%.17g,%.17g\n", mc_grid_x(g, i), r->pressure[k], r->gap[k],
                r->displacement[k]);
    }
    return close_staged(c, "profile_x.csv", f, err);
}

static int write_stress_fields(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    size_t shape[3] = {(size_t)r->nlayers, (size_t)r->grid.ny, (size_t)r->grid.nx};
    int st = write_npy(c, "von_mises.npy", r->von_mises, 3, shape, err);
    if (st == MC_OK)
        st = write_npy(c, "hydrostatic.npy", r->hydrostatic, 3, shape, err);
    for (int s = 0; s < MC_NSTRESS && st == MC_OK; s++)
        st = write_npy(c, stress_npy[s], r->stress[s], 3, shape, err);
    if (st != MC_OK)
        return st;

    FILE *f;
    st = open_staged(c, "depths.csv", &f, err);
    if (st != MC_OK)
        return st;
    fprintf(f, "layer,z\n");
    for (int k = 0; k < r->nlayers; k++)
        fprintf(f, "%d,%.17g\n", k, r->depths[k]);
    st = close_staged(c, "depths.csv", f, err);
    if (st != MC_OK)
        return st;

    st = open_staged(c, "axis.csv", &f, err);
    if (st != MC_OK)
        return st;
    fprintf(f, "z,sxx,syy,szz,sxy,syz,sxz,von_mises,hydrostatic,tresca\n");
    size_t n = cells(c), at = (size_t)c->jc * (size_t)r->grid.nx + (size_t)c->ic;
    for (int k = 0; k < r->nlayers; k++) {
        size_t q = (size_t)k * n + at;
        fprintf(f, "%.17g", r->depths[k]);
        for (int s = 0; s < MC_NSTRESS; s++)
            fprintf(f, ",%.17g", r->stress[s][q]);
        fprintf(f, ",%.17g,%.17g,%.17g\n", r->von_mises[q], r->hydrostatic[q], r->tresca[q]);
    }
    return close_staged(c, "axis.csv", f, err);
}

/* VTK XML ImageData: the surface fields as CellData, raw appended little-endian Float64 blocks
 * each preceded by its UInt64 byte count. Origin at the grid corner so that cell centres fall
 * on x_i = (i + 1/2 - nx/2) dx. */
static int write_vti(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    const mc_grid *g = &r->grid;
    const char *names[4] = {"pressure", "gap", "displacement", "topography"};
    const double *arrays[4] = {r->pressure, r->gap, r->displacement, r->topography};
    size_t n = cells(c), block = 8 + 8 * n;
    FILE *f;
    int st = open_staged(c, "field.vti", &f, err);
    if (st != MC_OK)
        return st;
    fprintf(f, "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
               "header_type=\"UInt64\">\n");
    fprintf(f,
            "  <ImageData WholeExtent=\"0 %d 0 %d 0 0\" Origin=\"%.17g %.17g 0\" "
            "Spacing=\"%.17g %.17g %.17g\">\n",
            g->nx, g->ny, -0.5 * g->nx * g->dx, -0.5 * g->ny * g->dy, g->dx, g->dy, g->dx);
    fprintf(f, "    <Piece Extent=\"0 %d 0 %d 0 0\">\n", g->nx, g->ny);
    fprintf(f, "      <CellData Scalars=\"pressure\">\n");
    for (int a = 0; a < 4; a++)
        fprintf(f,
                "        <DataArray type=\"Float64\" Name=\"%s\" format=\"appended\" "
                "offset=\"%zu\"/>\n",
                names[a], (size_t)a * block);
    fprintf(f, "      </CellData>\n    </Piece>\n  </ImageData>\n"
               "  <AppendedData encoding=\"raw\">\n   _");
    for (int a = 0; a < 4; a++) {
        (void)mc_le_write_u64(f, 8 * (uint64_t)n);
        (void)mc_le_write_doubles(f, arrays[a], n);
    }
    fprintf(f, "\n  </AppendedData>\n</VTKFile>\n");
    return close_staged(c, "field.vti", f, err);
}

/* VTK XML RectilinearGrid of the stress volume: points at the cell centres x, y and at
 * z = -depth; layers are written deepest first when depths increase, so z increases as VTK
 * expects of rectilinear coordinates. */
static int write_vtr(out_ctx *c, mc_error *err)
{
    const mc_results *r = c->res;
    const mc_grid *g = &r->grid;
    int nl = r->nlayers;
    int reverse = nl > 1 && r->depths[0] < r->depths[nl - 1];
    const char *names[MC_NSTRESS + 3] = {"stress_xx", "stress_yy", "stress_zz", "stress_xy",
                                         "stress_yz", "stress_xz", "von_mises", "hydrostatic",
                                         "tresca"};
    const double *arrays[MC_NSTRESS + 3];
    for (int s = 0; s < MC_NSTRESS; s++)
        arrays[s] = r->stress[s];
    arrays[MC_NSTRESS] = r->von_mises;
    arrays[MC_NSTRESS + 1] = r->hydrostatic;
    arrays[MC_NSTRESS + 2] = r->tresca;
    size_t n = cells(c), n3 = n * (size_t)nl;

    FILE *f;
    int st = open_staged(c, "stress.vtr", &f, err);
    if (st != MC_OK)
        return st;
    fprintf(f, "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"RectilinearGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
               "header_type=\"UInt64\">\n");
    fprintf(f, "  <RectilinearGrid WholeExtent=\"0 %d 0 %d 0 %d\">\n", g->nx - 1, g->ny - 1,
            nl - 1);
    fprintf(f, "    <Piece Extent=\"0 %d 0 %d 0 %d\">\n", g->nx - 1, g->ny - 1, nl - 1);
    size_t off = 0;
    fprintf(f, "      <PointData Scalars=\"von_mises\">\n");
    for (int a = 0; a < MC_NSTRESS + 3; a++) {
        fprintf(f,
                "        <DataArray type=\"Float64\" Name=\"%s\" format=\"appended\" "
                "offset=\"%zu\"/>\n",
                names[a], off);
        off += 8 + 8 * n3;
    }
    fprintf(f, "      </PointData>\n      <Coordinates>\n");
    const char *cn[3] = {"x", "y", "z"};
    size_t clen[3] = {(size_t)g->nx, (size_t)g->ny, (size_t)nl};
    for (int a = 0; a < 3; a++) {
        fprintf(f,
                "        <DataArray type=\"Float64\" Name=\"%s\" format=\"appended\" "
                "offset=\"%zu\"/>\n",
                cn[a], off);
        off += 8 + 8 * clen[a];
    }
    fprintf(f, "      </Coordinates>\n    </Piece>\n  </RectilinearGrid>\n"
               "  <AppendedData encoding=\"raw\">\n   _");
    for (int a = 0; a < MC_NSTRESS + 3; a++) {
        (void)mc_le_write_u64(f, 8 * (uint64_t)n3);
        for (int k = 0; k < nl; k++)
            (void)mc_le_write_doubles(f, arrays[a] + (size_t)(reverse ? nl - 1 - k : k) * n, n);
    }
    (void)mc_le_write_u64(f, 8 * (uint64_t)g->nx);
    for (int i = 0; i < g->nx; i++) {
        double x = mc_grid_x(g, i);
        (void)mc_le_write_doubles(f, &x, 1);
    }
    (void)mc_le_write_u64(f, 8 * (uint64_t)g->ny);
    for (int j = 0; j < g->ny; j++) {
        double y = mc_grid_y(g, j);
        (void)mc_le_write_doubles(f, &y, 1);
    }
    (void)mc_le_write_u64(f, 8 * (uint64_t)nl);
    for (int k = 0; k < nl; k++) {
        double z = -r->depths[reverse ? nl - 1 - k : k];
        (void)mc_le_write_doubles(f, &z, 1);
    }
    fprintf(f, "\n  </AppendedData>\n</VTKFile>\n");
    return close_staged(c, "stress.vtr", f, err);
}


static int write_summary(out_ctx *c, mc_error *err)
{
    static const char name[] = "summary.json";
    json_t *root = NULL;
    int st = mc_summary_json(c->scene, c->res, c->files, c->nfiles, name, &root, err);
    if (st != MC_OK)
        return st;
    /* json_dumpf, not json_dumps: jansson 2.14's do_dump ignores a failed append of an object
     * key, so json_dumps can return a corrupt document after an allocation failure in its
     * string buffer. Writing straight to the file leaves only the (checked) loop-detection
     * allocations inside jansson. */
    FILE *f;
    st = open_staged(c, name, &f, err);
    if (st != MC_OK) {
        json_decref(root);
        return st;
    }
    int dumped = json_dumpf(root, f, JSON_INDENT(2) | JSON_REAL_PRECISION(17));
    json_decref(root);
    fputc('\n', f);
    if (dumped != 0 && !ferror(f)) {
        fclose(f);
        return mc_fail(err, MC_ERR_NOMEM, "summary.json: no memory to write the document");
    }
    return close_staged(c, name, f, err);
}

/* ---- staging and commit ------------------------------------------------------------------ */

/* Remove the staging directory and everything in it (also a stray .tmp of mc_npy_write). */
static void remove_stage(const char *stage)
{
    DIR *d = opendir(stage);
    if (d) {
        struct dirent *e;
        char path[OUT_PATH_MAX];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            if (snprintf(path, sizeof path, "%s/%s", stage, e->d_name) < (int)sizeof path)
                unlink(path);
        }
        closedir(d);
    }
    rmdir(stage);
}

static int commit(out_ctx *c, mc_error *err)
{
    char from[OUT_PATH_MAX], to[OUT_PATH_MAX];
    /* Refuse before touching DIR when a target is a directory (rename would fail half-way). */
    for (int k = 0; k < N_OUTPUTS; k++) {
        struct stat sb;
        int st = join(to, c->dir, outputs[k].name, err);
        if (st != MC_OK)
            return st;
        if (lstat(to, &sb) == 0 && S_ISDIR(sb.st_mode))
            return mc_fail(err, MC_ERR_IO,
                           "output directory '%s': '%s' is a directory; cannot replace it with "
                           "a result file",
                           c->dir, outputs[k].name);
    }
    const char *failed = NULL;
    int e = 0;
    if (join(to, c->dir, "summary.json", err) != MC_OK)
        return MC_ERR_INPUT;
    if (unlink(to) != 0 && errno != ENOENT) {
        failed = "summary.json";
        e = errno;
    }
    for (int k = 0; !failed && k < c->nfiles; k++) {
        if (strcmp(c->files[k], "summary.json") == 0)
            continue;
        join(from, c->stage, c->files[k], err);
        join(to, c->dir, c->files[k], err);
        if (rename(from, to) != 0) {
            failed = c->files[k];
            e = errno;
        }
    }
    for (int k = 0; !failed && k < N_OUTPUTS; k++) {
        if (produced(c, outputs[k].name))
            continue;
        join(to, c->dir, outputs[k].name, err);
        if (unlink(to) != 0 && errno != ENOENT) {
            failed = outputs[k].name;
            e = errno;
        }
    }
    if (!failed) {
        join(from, c->stage, "summary.json", err);
        join(to, c->dir, "summary.json", err);
        if (rename(from, to) != 0) {
            failed = "summary.json";
            e = errno;
        }
    }
    if (failed)
        return mc_fail(err, MC_ERR_IO,
                       "output directory '%s': cannot replace '%s': %s (the directory holds an "
                       "incomplete result set without summary.json)",
                       c->dir, failed, strerror(e));
    return MC_OK;
}

static int check_results(const mc_results *r, mc_error *err)
{
    int st = mc_grid_check(&r->grid, err);
    if (st != MC_OK) {
        if (err) /* mc_error_prefix(NULL) would turn st into MC_ERR_INTERNAL */
            mc_error_prefix(err, "output: ");
        return st;
    }
    if (!r->pressure || !r->gap || !r->displacement || !r->topography)
        return mc_fail(err, MC_ERR_INTERNAL, "output: results lack a surface field");
    if (r->nlayers < 0)
        return mc_fail(err, MC_ERR_INTERNAL, "output: %d stress layers", r->nlayers);
    if (r->nlayers > 0) {
        size_t n3;
        int ok = r->depths && r->von_mises && r->hydrostatic && r->tresca &&
                 mc_size_mul(mc_grid_cells(&r->grid), (size_t)r->nlayers, &n3);
        for (int s = 0; s < MC_NSTRESS; s++)
            ok = ok && r->stress[s];
        if (!ok)
            return mc_fail(err, MC_ERR_INTERNAL, "output: results lack a stress field");
    }
    return MC_OK;
}

/* Cell of maximum pressure; ties go to the cell nearest the grid centre (a uniform or zero
 * pressure then gives the central row, not row 0). */
static void locate_pmax(out_ctx *c)
{
    const mc_grid *g = &c->res->grid;
    const double *p = c->res->pressure;
    double best = -INFINITY, bestd = INFINITY;
    c->ic = c->jc = 0;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            double v = p[(size_t)j * (size_t)g->nx + (size_t)i];
            double x = mc_grid_x(g, i), y = mc_grid_y(g, j), d = x * x + y * y;
            if (v > best || (v == best && d < bestd)) {
                best = v;
                bestd = d;
                c->ic = i;
                c->jc = j;
            }
        }
}

/* Stage every file and rename them into place; the caller holds DIR. */
static int stage_and_commit(out_ctx *c, mc_error *err)
{
    int st = join(c->stage, c->dir, ".staging-XXXXXX", err);
    if (st != MC_OK)
        return st;
    if (!mkdtemp(c->stage))
        return mc_fail(err, MC_ERR_ENV,
                       "output directory '%s': cannot create a staging directory: %s", c->dir,
                       strerror(errno));
    const mc_results *res = c->res;
    st = write_surface_fields(c, err);
    if (st == MC_OK)
        st = write_profile(c, err);
    if (st == MC_OK && res->nlayers > 0)
        st = write_stress_fields(c, err);
    if (st == MC_OK && res->plastic.enabled && res->residual_displacement)
        st = write_plastic(c, err);
    if (st == MC_OK && res->runin.enabled)
        st = write_runin(c, err);
    if (st == MC_OK && res->two_bodies)
        st = write_bodies(c, err);
    if (st == MC_OK && c->scene->output.x3p)
        st = write_x3p_surfaces(c, err);
    if (st == MC_OK && c->scene->output.vtk)
        st = write_vti(c, err);
    if (st == MC_OK && c->scene->output.vtk && res->nlayers > 0)
        st = write_vtr(c, err);
    if (st == MC_OK)
        st = write_summary(c, err);
    for (int i = 0; st == MC_OK && i < N_OUTPUTS; i++) /* the table tells the truth */
        if (produced(c, outputs[i].name) != out_wanted(outputs[i].when, c->scene, res))
            st = mc_fail(err, MC_ERR_INTERNAL, "output: '%s' %s written against the output table",
                         outputs[i].name, produced(c, outputs[i].name) ? "was" : "was not");
    if (st == MC_OK)
        st = check_stop(err);
    if (st == MC_OK)
        st = commit(c, err);
    remove_stage(c->stage);
    return st;
}

int mc_output_open(mc_outdir *out, const char *dir, mc_error *err)
{
    mc_outdir_init(out);
    return mc_outdir_open(out, dir, err);
}

void mc_output_close(mc_outdir *out)
{
    mc_outdir_release(out);
}

int mc_output_commit(mc_outdir *out, const mc_scene *scene, const mc_results *res, mc_error *err)
{
    static int jansson_ready;
    if (!jansson_ready) {
        json_set_alloc_funcs(mc_malloc, mc_free);
        jansson_ready = 1;
    }
    if (!out->path[0])
        return mc_fail(err, MC_ERR_INPUT, "output directory: empty path");
    if (!scene || !res)
        return mc_fail(err, MC_ERR_INTERNAL, "output: no scene or no results");
    int st = check_results(res, err);
    if (st != MC_OK)
        return st;
    out_ctx c;
    memset(&c, 0, sizeof c);
    c.dir = out->path;
    c.scene = scene;
    c.res = res;
    locate_pmax(&c);

    atomic_fetch_add(&active_commits, 1);
    st = check_stop(err);
    if (st == MC_OK)
        st = mc_outdir_acquire(out, err);
    if (st == MC_OK) {
        const char *names[N_OUTPUTS];
        for (int i = 0; i < N_OUTPUTS; i++)
            names[i] = outputs[i].name;
        mc_outdir_sweep(out, names, N_OUTPUTS);
        st = stage_and_commit(&c, err);
        if (st != MC_OK)
            mc_outdir_rollback(out);
    }
    atomic_fetch_sub(&active_commits, 1);
    if (st == MC_ERR_IO) { /* writing into DIR failed: the environment (disk full, quota, ...) */
        if (err)
            err->code = MC_ERR_ENV;
        st = MC_ERR_ENV;
    }
    return st;
}

int mc_output_prepare(const char *dir, mc_error *err)
{
    mc_outdir out;
    int st = mc_output_open(&out, dir, err);
    mc_output_close(&out);
    return st;
}

int mc_output_write(const char *dir, const mc_scene *scene, const mc_results *res, mc_error *err)
{
    mc_outdir out;
    int st = mc_output_open(&out, dir, err);
    if (st == MC_OK)
        st = mc_output_commit(&out, scene, res, err);
    mc_output_close(&out);
    return st;
}
