/* memguard.c - memory estimate and guard (see memguard.h). */
#include "pipeline/memguard.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "contact/contact.h"
#include "core/dist.h"
#include "operator/dfft.h"
#include "core/fftsize.h"
#include "plastic/loop.h"
#include "stress/stress.h"

/* Cells of the transform of one axis (padded when free, as conv.c). */
static double axis_len(int n, int periodic) { return periodic ? n : mc_fftsize_good(2 * n - 1); }

/* Bytes of one operator on grid (nx, ny): fft - kernel spectrum, real and complex work buffers,
 * and the kernel table while it is built; direct - the table. Over P MPI processes
 * (operator/dfft.h) the spectrum, the work spectrum and the two transpose buffers are a slab each,
 * 1/P; the kernel table is built by slabs (operator.c, mc_conv_kernel_rows): free axes, a rank's
 * rows (8 tx ty / P) beside the corner lattice they read (8 nx ny: whole for few ranks, the
 * table's wrap-around rows reading every offset), then those rows and the exchange's columns
 * (8 tx ty / P more), all three counted together (the guard errs high: rank 0's measured peak
 * with 3 processes at 768^2 came within 6 % of the figure without that); a periodic axis builds
 * the whole table on every rank. The shared transposes read the other ranks' pages
 * (mc_dfft_peer_bytes). */
static double operator_bytes(int nx, int ny, int px, int py, mc_backend b, int ranks)
{
    double tx = axis_len(nx, px), ty = axis_len(ny, py), half = ty * (tx / 2 + 1);
    if (b == MC_BACKEND_DIRECT)
        return 8 * tx * ty;
    if (ranks > 1) {
        const double table =
            px || py ? 8 * tx * ty : 16 * tx * ty / ranks + 8 * (double)nx * (double)ny;
        return (16 * half * 2 + 2 * 16 * (double)ny * (tx / 2 + 1)) / ranks + table +
               (double)mc_dfft_peer_bytes(ny, (int)tx, 1, ranks, 0);
    }
    return 16 * half * 2 + 8 * tx * ty + 8 * tx * ty;
}

/* Bytes of one contact solver on `cells` cells: ten work arrays and two masks, over P > 1 MPI
 * processes a slab each (1/P, contact_internal.h: every rank holds its rows alone), plus the
 * preconditioner's box buffers: serially a real and a half complex array of the grid (16 bytes a
 * cell); over P > 1 processes its transform engine over the box (the box at most the grid:
 * transposes, spectrum, rows, symbol, about 52 bytes a cell) and its exchange's slab (8), all
 * divided by P (precond.h), and the peers' pages its shared transposes read (dfft.h). The
 * active set is whole on every rank. Measured per rank (Hertz 2048^2, P = 2, 3: reports/bench,
 * mpi section): the peak divides as R + S/P (R: the surface
 * fields of pipeline.h, the coarse start's whole arrays, the process); this model errs high
 * (the kernel table counted beside the solver). */
static double solver_bytes(int nx, int ny, mc_contact_method m, int ranks)
{
    const double cells = (double)nx * (double)ny;
    const double work = (10 * 8 + 2) * cells, precond = 16 * cells;
    if (ranks <= 1 || m == MC_METHOD_ACTIVE_SET)
        return work + precond;
    return (work + 60 * cells) / ranks + (double)mc_dfft_peer_bytes(ny, nx, 1, ranks, 0);
}

double mc_memory_estimate(const mc_scene *s) { return mc_memory_estimate_ranks(s, mc_dist_size()); }

double mc_memory_estimate_ranks(const mc_scene *s, int ranks)
{
    const mc_grid *g = &s->grid;
    double cells = (double)g->nx * (double)g->ny;
    double bytes = 4 * 8 * cells; /* topography, pressure, gap, displacement */
    if (s->roughness2.type != MC_ROUGH_NONE)
        bytes += 4 * 8 * cells; /* each body's surface before and after (pipeline/bodies.h) */
    if (s->load.kind == MC_LOAD_PRESSURE_FILE)
        bytes += 8 * cells; /* the map as read */
    bytes += operator_bytes(g->nx, g->ny, g->periodic_x, g->periodic_y, s->solver.backend, ranks);
    if (s->load.kind != MC_LOAD_PRESSURE_FILE) {
        double solver = solver_bytes(g->nx, g->ny, s->solver.method, ranks);
        if (s->solver.method == MC_METHOD_ACTIVE_SET)
            solver += 2 * 8 * cells * cells;
        /* nested start: each coarse level a quarter of the one above (operator and solver) */
        if (s->solver.method == MC_METHOD_CG && g->nx >= MC_COARSEN_MIN)
            solver += (solver + operator_bytes(g->nx, g->ny, g->periodic_x, g->periodic_y,
                                               s->solver.backend, ranks)) / 3.0;
        bytes += solver;
    }
    if (s->stress.enabled) {
        int layers = s->stress.spacing == MC_SPACING_LIST ? s->stress.ndepths : s->stress.layers;
        double tx = axis_len(g->nx, g->periodic_x), ty = axis_len(g->ny, g->periodic_y);
        /* six components, von Mises, hydrostatic, Tresca per layer; per load six tables and six
         * spectra, the load spectra, and a second operator's work buffers */
        int loads = s->stress.friction > 0 ? 2 : 1;
        bytes += 9 * 8 * cells * layers;
        bytes += loads * (6 * 8 * tx * ty + 6 * 16 * ty * (tx / 2 + 1) + 16 * ty * (tx / 2 + 1));
        bytes += 8 * tx * ty + 16 * ty * (tx / 2 + 1);
    }
    return bytes;
}

/* the stage's Anderson depth (stage_plastic.c MC_ANDERSON_DEPTH) */
#define PLASTIC_ANDERSON 4
/* the yielding cells counted, a fraction of the volume: the plastic zone of a contact sits in
 * the volume under it with a margin and a depth to spare (bench plastic's sphere: a few %; a
 * Hertz sphere at 10 P_c: ~10 %). At 0.1 the model is 5-10 % above the measured peaks of bench
 * plastic's whole runs (its "guard's estimate / peak" column); a run whose yielding cells are a
 * larger part of its volume holds ~700 bytes more per extra yielding cell (mc_plastic_loop_bytes)
 * than the guard counted */
#define PLASTIC_YIELDING 0.1

/* The kernel spectra that a stress plan of the volume's layers keeps (stress.h: every layer when
 * they fit MC_STRESS_CACHE_BYTES, for a plan made `repeated` or on a periodic grid): 6 per layer
 * and load (mc_stress_cache_layer_bytes: compact spectra on a periodic grid, real quadrants of
 * (m_x + 1)(m_y + 1) on free axes); under
 * mpirun a repeated plan keeps its rank's layers (mc_dist_share: at most ceil(nz / P)). */
static double stress_cache(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                           int repeated)
{
    const int periodic = g->periodic_x || g->periodic_y;
    if (!repeated && !periodic)
        return 0.0;
    const int ranks = repeated && mc_dist_active() ? mc_dist_size() : 1;
    const int loads = s->plasticity.friction > 0 ? 2 : 1;
    const double cache = ceil((double)v->nz / ranks) * loads * mc_stress_cache_layer_bytes(g);
    return cache <= (double)MC_STRESS_CACHE_BYTES ? cache : 0.0;
}

double mc_memory_estimate_plastic(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                                  int shortcut)
{
    const double cells = (double)g->nx * g->ny;
    /* the output fields: plastic strain and residual von Mises on the grid's columns, the residual
     * displacement and the final topography */
    const double fields = 2 * 8 * cells * v->nz + 2 * 8 * cells;
    if (shortcut)
        return fields;
    const mc_backend b = s->solver.backend;
    /* the operators' exact bytes; under mpirun rank 0's share of their distributed fft backends
     * (their spectra divide by P, plastic/eigen_op.h); the loop's volume arrays below stay
     * whole on every rank */
    size_t parts[MC_EIGEN_STRESS_PARTS];
    mc_eigen_stress_estimate(g, v, b, parts);
    double ops = (double)mc_eigen_disp_estimate(g, v, b);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        ops += (double)parts[k];
    /* the Love stresses at the cuboid centres (stress/stress.h): per load six kernel spectra
     * and the load's, six tables, a cell list; on a periodic grid the spectra of every layer
     * when they fit its cache */
    const double tx = axis_len(g->nx, g->periodic_x), ty = axis_len(g->ny, g->periodic_y);
    const double spec = 16 * ty * (tx / 2 + 1);
    const int loads = s->plasticity.friction > 0 ? 2 : 1;
    ops += loads * 7 * spec + 6 * 8 * tx * ty + 4 * cells;
    /* a volume under the whole grid folds the loads into the residual stress operator
     * (plastic/loop.h mc_plastic_ops_fold, theory §8.9): their tables beside Love's, and the
     * loop never uses the plan above (its spectra, if it keeps any, are never touched) */
    const int fold = mc_plastic_ops_fold(g, v);
    if (fold)
        ops += (double)mc_eigen_stress_loads_estimate(
            g, v, b, mc_dist_active() ? mc_dist_size() : 0,
            MC_TRACTION_P | (loads > 1 ? MC_TRACTION_QX : 0));
    else
        ops += stress_cache(s, g, v, 1);
    const double nvol = (double)v->nz * v->nx * v->ny;
    /* with the arrays a fallback to the nested iteration makes: the guard holds for it too */
    const double loop = mc_plastic_loop_bytes(g, v, PLASTIC_ANDERSON, s->plasticity.near_field,
                                              PLASTIC_YIELDING * nvol, 1);
    /* the peak is in the loop; the fields come after it has freed its operators */
    return fmax(ops + loop, fields + loop);
}

/* need against the available memory (rank 0's for all processes), else MC_ERR_NOMEM naming
 * `what`, the volume and `reduce`. */
static int check_volume(double need, const char *what, const char *reduce, const mc_grid *g,
                        const mc_eigen_volume *v, mc_error *err)
{
    double have = mc_memory_available();
    mc_dist_bcast(&have, 1, 0);
    if (need <= have)
        return MC_OK;
    const double GiB = 1073741824.0;
    return mc_fail(err, MC_ERR_NOMEM,
                   "%s needs about %.1f GiB, %.1f GiB available (grid %d x %d, plastic volume %d "
                   "x %d x %d cells); reduce %s",
                   what, need / GiB, have / GiB, g->nx, g->ny, v->nx, v->ny, v->nz, reduce);
}

int mc_memory_check_plastic(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                            int shortcut, mc_error *err)
{
    const double need = mc_memory_estimate(s) + mc_memory_estimate_plastic(s, g, v, shortcut);
    return check_volume(need, "the elastic-plastic stage",
                        "[plasticity] depth or margin, or the grid", g, v, err);
}

double mc_memory_estimate_runin(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v)
{
    /* the state it carries (eps_p, peq, sig_r) is lent to the loop (its result and residual
     * stress arrays: counted in mc_plastic_loop_bytes, which also counts the elastic stresses
     * the loop makes only for a nested iteration), and the yield check's stress plan becomes the
     * operators' (counted in the stage's estimate); at the end the operators are still held
     * beside the state and the output fields (168 bytes per volume cell, fewer than the loop's
     * dense arrays). Besides: its surface arrays (h_base, h_extra, z, u_r, qx, the bowl, the
     * shape, the lubricant profile, the residual displacement and final topography of each body,
     * and the yield check's layer of six stresses: 18 per cell). */
    const double cells = (double)g->nx * g->ny;
    /* with the loads folded, the yield check's plan is not the loop's stresses but still
     * computes every step: on a periodic grid its spectra are kept and used */
    const double check = mc_plastic_ops_fold(g, v) ? stress_cache(s, g, v, 0) : 0.0;
    return mc_memory_estimate_plastic(s, g, v, 0) + check + 18 * 8 * cells;
}

int mc_memory_check_runin(const mc_scene *s, const mc_grid *g, const mc_eigen_volume *v,
                          mc_error *err)
{
    const double need = mc_memory_estimate(s) + mc_memory_estimate_runin(s, g, v);
    return check_volume(need, "the running-in", "[plasticity] depth or dz, or the grid", g, v,
                        err);
}

double mc_memory_available(void)
{
    const char *env = getenv("MC_MEMORY_LIMIT");
    if (env && *env) {
        char *end;
        double v = strtod(env, &end);
        if (end != env && v > 0)
            return v;
    }
    FILE *f = fopen("/proc/meminfo", "r");
    if (f) {
        char line[256];
        while (fgets(line, sizeof line, f)) {
            unsigned long long kb;
            if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1) {
                fclose(f);
                return 1024.0 * (double)kb;
            }
        }
        fclose(f);
    }
    return (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
}

int mc_memory_check(const mc_scene *s, mc_error *err)
{
    double need = mc_memory_estimate(s), have = mc_memory_available();
    /* over MPI processes: rank 0's figure for all, so that they all go on or all stop */
    mc_dist_bcast(&have, 1, 0);
    if (need <= have)
        return MC_OK;
    const double GiB = 1073741824.0, MiB = 1048576.0;
    const int ranks = mc_dist_size();
    /* the figure is each process's: say so, and what twice the processes would need each
     * (bin/microcontact-mpi, README "Running on a cluster") */
    char per[128];
    snprintf(per, sizeof per, " per process with %d process%s (%.1f MiB each with %d)", ranks,
             ranks > 1 ? "es" : "", mc_memory_estimate_ranks(s, 2 * ranks) / MiB, 2 * ranks);
    return mc_fail(err, MC_ERR_NOMEM,
                   "the scene needs about %.1f GiB (%.1f MiB)%s, %.1f GiB available (grid %d x "
                   "%d%s); reduce the grid%s, or run with more MPI processes",
                   need / GiB, need / MiB, per, have / GiB, s->grid.nx, s->grid.ny,
                   s->stress.enabled ? " with stress layers" : "",
                   s->stress.enabled ? " or the number of stress layers" : "");
}
