/* stage_stress.c - the stress stage of the pipeline (see stage_stress.h): the depths (given, or
 * from the contact patches), the windows of a compact load, the layers group by group, the
 * invariants and the summary. */
#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "kernels/invariants.h"
#include "kernels/kernel.h"
#include "operator/box.h"
#include "stress/stress.h"
#include "pipeline/stage_stress.h"

#include "core/dist.h"
#include "stress/stress_internal.h"

/* A new group of layers starts when the window's area would grow beyond this factor of the
 * group's first window: the waste (cells computed beyond a layer's own window) stays below half,
 * about a quarter on average, while the planning (FFTW plans, tables, buffers: milliseconds) is
 * paid a few times only. */
#define GROUP_GROWTH 1.5

/* ---- contact patches (depth_max = auto) -------------------------------------------------------- */

/* Neighbour of cell (i, j) in direction d (0: +x, 1: -x, 2: +y, 3: -y); 0 if it falls off a free
 * edge. *wx, *wy: the period crossed along x, y (-1, 0, +1). */
static int neighbour(const mc_grid *g, int i, int j, int d, int *ni, int *nj, int *wx, int *wy)
{
    static const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    int a = i + di[d], b = j + dj[d];
    *wx = *wy = 0;
    if (a < 0 || a >= g->nx) {
        if (!g->periodic_x)
            return 0;
        *wx = a < 0 ? -1 : 1;
        a -= *wx * g->nx;
    }
    if (b < 0 || b >= g->ny) {
        if (!g->periodic_y)
            return 0;
        *wy = b < 0 ? -1 : 1;
        b -= *wy * g->ny;
    }
    *ni = a;
    *nj = b;
    return 1;
}

int mc_stage_stress_find_patches(const mc_grid *g, const double *p, double threshold,
                           mc_stage_stress_patches *out, mc_error *err)
{
    const size_t n = mc_grid_cells(g);
    memset(out, 0, sizeof *out);
    if (n > (size_t)INT_MAX) /* cells are labelled and stacked as int */
        return mc_fail(err, MC_ERR_LIMIT, "stress: %d x %d cells exceed the %d the labelling "
                                          "handles", g->nx, g->ny, INT_MAX);
    /* label (-1: not a contact cell, 0: not reached yet, > 0: patch), the search stack, and each
     * cell's periods crossed from its patch's seed: reaching a cell again with other periods means
     * the patch closes around that axis (a band). */
    int *label = mc_malloc(sizeof *label * n), *stack = mc_malloc(sizeof *stack * n);
    int *px = mc_malloc(sizeof *px * n), *py = mc_malloc(sizeof *py * n);
    if (!label || !stack || !px || !py) {
        mc_free(label);
        mc_free(stack);
        mc_free(px);
        mc_free(py);
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory labelling the contact patches");
    }
    for (size_t c = 0; c < n; c++) {
        label[c] = p[c] > threshold ? 0 : -1;
        out->cells += label[c] == 0;
    }
    const double A = mc_grid_cell_area(g), Lx = g->nx * g->dx, Ly = g->ny * g->dy;
    for (size_t seed = 0; seed < n; seed++) {
        if (label[seed] != 0)
            continue;
        const int id = ++out->patches;
        long top = 0, count = 0;
        int band_x = 0, band_y = 0;
        label[seed] = id;
        px[seed] = py[seed] = 0;
        stack[top++] = (int)seed;
        while (top > 0) {
            const int c = stack[--top];
            count++;
            const int i = c % g->nx, j = c / g->nx;
            for (int d = 0; d < 4; d++) {
                int a, b, wx, wy;
                if (!neighbour(g, i, j, d, &a, &b, &wx, &wy))
                    continue;
                const int q = b * g->nx + a;
                if (label[q] < 0)
                    continue;
                if (label[q] == 0) {
                    label[q] = id;
                    px[q] = px[c] + wx;
                    py[q] = py[c] + wy;
                    stack[top++] = q;
                } else {
                    band_x |= px[q] != px[c] + wx;
                    band_y |= py[q] != py[c] + wy;
                }
            }
        }
        const double area = A * (double)count;
        const double r = band_x && band_y ? area / (2.0 * fmax(Lx, Ly))
                         : band_y         ? area / (2.0 * Ly)
                         : band_x         ? area / (2.0 * Lx)
                                          : sqrt(area / M_PI);
        out->radius = fmax(out->radius, r);
    }
    mc_free(label);
    mc_free(stack);
    mc_free(px);
    mc_free(py);
    return MC_OK;
}

/* The depths of the stage: as the scene gives them, or from the contact (depth_max = auto). */
static int stage_depths(const mc_scene *sc, const mc_results *res, double *depths, int *nd,
                        mc_stage_stress_layout *lay, mc_error *err)
{
    if (sc->stress.spacing == MC_SPACING_LIST || sc->stress.depth_max != MC_STRESS_DEPTH_AUTO)
        return mc_scene_depths(sc, depths, nd, err);
    const mc_grid *g = &res->grid;
    const double solid = res->contact.solved ? sc->load.lubricant_pressure : 0.0;
    mc_stage_stress_patches pt;
    int rc = mc_stage_stress_find_patches(g, res->pressure, solid, &pt, err);
    if (rc == MC_OK && pt.patches == 0 && solid > 0.0) /* no solid contact: the loaded cells */
        rc = mc_stage_stress_find_patches(g, res->pressure, 0.0, &pt, err);
    if (rc)
        return rc;
    lay->depth_auto = 1;
    lay->patches = pt.patches;
    lay->patch_radius = pt.radius > 0.0 ? pt.radius : fmax(g->dx, g->dy);
    mc_scene s = *sc;
    s.stress.depth_max = MC_STRESS_DEPTH_RADII * lay->patch_radius;
    if (!(s.stress.depth_max > s.stress.depth_min))
        return mc_fail(err, MC_ERR_INPUT,
                       "[stress] depth_max = auto gives %g x the largest contact patch's radius "
                       "%g m = %g m, not beyond depth_min = %g m: give depth_max",
                       MC_STRESS_DEPTH_RADII, lay->patch_radius, s.stress.depth_max,
                       s.stress.depth_min);
    return mc_scene_depths(&s, depths, nd, err);
}

/* ---- windows ------------------------------------------------------------------------------------ */

/* The window of depth z around the load box lb (MC_STRESS_WINDOW_CR), clipped to the grid (free
 * axes). */
static mc_box window_of(const mc_grid *g, const mc_box *lb, double z)
{
    const double R = 0.5 * fmax(lb->nx * g->dx, lb->ny * g->dy);
    const double m = MC_STRESS_WINDOW_CR * R + MC_STRESS_WINDOW_CZ * z;
    const int mx = (int)fmax(MC_STRESS_WINDOW_MIN, fmin(ceil(m / g->dx), g->nx));
    const int my = (int)fmax(MC_STRESS_WINDOW_MIN, fmin(ceil(m / g->dy), g->ny));
    mc_box w = *lb;
    mc_box_widen(g, mx, my, &w);
    return w;
}

/* Layers k0..k1 on box w, as the layout lists them (inclusive cell ranges). */
static mc_stage_stress_window window_entry(int k0, int k1, const mc_box *w)
{
    return (mc_stage_stress_window){k0, k1, w->i0, w->i0 + w->nx - 1, w->j0, w->j0 + w->ny - 1, 0};
}

/* Groups of consecutive layers and their windows into lay (windowed = 0: one group, the grid). */
static void plan_windows(const mc_grid *g, const double *p, const double *depths, int nd,
                         int windowed, mc_stage_stress_layout *lay)
{
    const mc_box full = {0, 0, g->nx, g->ny};
    mc_box lb;
    lay->nwindows = 0;
    lay->windowed = 0;
    /* A periodic axis repeats the load: beyond a period it acts as a line load, whose stress
     * decays like 1/r (a traction's sigma_xx at the surface), not like the 1/r^2 the margin was
     * measured for: no window then. No load: one trivial group. */
    if (!windowed || g->periodic_x || g->periodic_y || !mc_box_bound(g, NULL, p, &lb)) {
        lay->window[0] = window_entry(0, nd - 1, &full);
        lay->nwindows = 1;
        return;
    }
    int k = 0;
    while (k < nd) {
        mc_box w = window_of(g, &lb, depths[k]);
        const long a0 = mc_box_cells(&w);
        int k1 = k;
        /* the last group takes every remaining layer */
        const int last = lay->nwindows == MC_STRESS_MAX_WINDOWS - 1;
        while (k1 + 1 < nd) {
            const mc_box v = window_of(g, &lb, depths[k1 + 1]), u = mc_box_union(&w, &v);
            if (!last && (double)mc_box_cells(&u) > GROUP_GROWTH * (double)a0)
                break;
            w = u;
            k1++;
        }
        lay->window[lay->nwindows++] = window_entry(k, k1, &w);
        lay->windowed |= mc_box_cells(&w) < mc_box_cells(&full);
        k = k1 + 1;
    }
}

/* ---- the stage ---------------------------------------------------------------------------------- */

/* Work arrays of the stage: the traction, the loads cropped to a window, one layer of a window. */
typedef struct {
    double *qx, *pw, *qw, *layer[MC_NSTRESS];
} stage_work;

static void stage_work_free(stage_work *w)
{
    mc_free(w->qx);
    mc_free(w->pw);
    mc_free(w->qw);
    for (int c = 0; c < MC_NSTRESS; c++)
        mc_free(w->layer[c]);
}

/* The first index in volume order whose value is within MC_STRESS_TIE of the largest, and the
 * largest itself; *finite = 0 if any value is NaN or infinite. */
static size_t argmax(const double *v, size_t n, double *max, int *finite)
{
    double m = v[0];
    int ok = 1;
    for (size_t i = 0; i < n; i++) {
        ok &= isfinite(v[i]);
        m = v[i] > m ? v[i] : m;
    }
    *max = m;
    *finite &= ok;
    const double floor = m - MC_STRESS_TIE * fabs(m);
    for (size_t i = 0; i < n; i++)
        if (v[i] >= floor)
            return i;
    return 0;
}

/* (x, y, z) of volume index idx: cell centres of grid g, layer depths. */
static void volume_point(const mc_grid *g, const double *depths, size_t idx, double at[3])
{
    const size_t n = mc_grid_cells(g);
    const int k = (int)(idx / n);
    const size_t r = idx % n;
    at[0] = mc_grid_x(g, (int)(r % (size_t)g->nx));
    at[1] = mc_grid_y(g, (int)(r / (size_t)g->nx));
    at[2] = depths[k];
}

/* The summary of the volumes in vol; MC_ERR_NUMERIC if a stress is not finite (von Mises and
 * Tresca involve every component, the hydrostatic stress the normal ones), so no NaN reaches the
 * outputs. */
static int stage_summary(const mc_scene *sc, mc_results *vol, mc_error *err)
{
    const mc_grid *g = &vol->grid;
    const int nd = vol->nlayers;
    const size_t nv = mc_grid_cells(g) * (size_t)nd;
    mc_stage_stress_summary *ss = &vol->stress_summary;
    int finite = 1;
    double hmax;
    memset(ss, 0, sizeof *ss);
    const size_t iv = argmax(vol->von_mises, nv, &ss->vm_max, &finite);
    const size_t it = argmax(vol->tresca, nv, &ss->tresca_max, &finite);
    argmax(vol->hydrostatic, nv, &hmax, &finite);
    if (!finite)
        return mc_fail(err, MC_ERR_NUMERIC,
                       "stress: non-finite stresses (the pressure or the tractions are not finite "
                       "or out of range)");
    volume_point(g, vol->depths, iv, ss->vm_max_at);
    ss->hydro_at_vm_max = vol->hydrostatic[iv];
    volume_point(g, vol->depths, it, ss->tresca_max_at);
    ss->layers = nd;
    ss->depth_min = ss->depth_max = vol->depths[0];
    for (int k = 1; k < nd; k++) {
        ss->depth_min = fmin(ss->depth_min, vol->depths[k]);
        ss->depth_max = fmax(ss->depth_max, vol->depths[k]);
    }
    ss->kernel = sc->stress.kernel == MC_STRESS_POINT ? "point" : "patch";
    ss->friction = sc->stress.friction;
    return MC_OK;
}

/* One group of layers on its window w: the loads cropped to it, a stress plan for its sub-grid,
 * each layer computed and put in place in the volumes (zeros outside the window). */
static int stage_group(const mc_scene *sc, const mc_results *res, const mc_stress_tuning *tune,
                       const double *depths, mc_stage_stress_window *w, stage_work *wk,
                       mc_results *vol, mc_error *err)
{
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    const int wx = w->i1 - w->i0 + 1, wy = w->j1 - w->j0 + 1, nl = w->k1 - w->k0 + 1;
    const int whole = wx == g->nx && wy == g->ny;
    mc_grid sub = *g;
    sub.nx = wx;
    sub.ny = wy;
    const double *p = res->pressure, *q = wk->qx;
    if (!whole) {
        for (int j = 0; j < wy; j++) {
            const size_t from = (size_t)(w->j0 + j) * g->nx + w->i0, to = (size_t)j * wx;
            memcpy(wk->pw + to, p + from, sizeof *p * (size_t)wx);
            if (q)
                memcpy(wk->qw + to, q + from, sizeof *q * (size_t)wx);
        }
        p = wk->pw;
        q = q ? wk->qw : NULL;
    }
    const mc_stress_options opt = {.kernel = sc->stress.kernel,
                                   .nu = sc->body1.nu,
                                   .nlayers = nl,
                                   .depths = depths + w->k0,
                                   .backend = sc->solver.backend,
                                   .loads = MC_TRACTION_P | (q ? MC_TRACTION_QX : 0)};
    mc_stress_plan *plan = NULL;
    int rc = mc_stress_create_tuned(&sub, &opt, tune, &plan, err);
    if (rc == MC_OK)
        rc = mc_stress_prepare(plan, p, q, NULL, err);
    if (rc == MC_OK)
        w->sparse = mc_stress_is_sparse(plan);
    /* over MPI processes (core/dist.h) the layers are dealt out in turn, k mod P, and each
     * layer then sent from the rank that computed it to all: a layer is the same bits whichever
     * rank computes it (the same plan, the same load) */
    const int ranks = mc_dist_size(), me = mc_dist_rank();
    for (int k = 0; k < nl && rc == MC_OK; k++) {
        if (k % ranks != me)
            continue;
        const size_t at = (size_t)(w->k0 + k) * n;
        double *out[MC_NSTRESS];
        for (int c = 0; c < MC_NSTRESS; c++)
            out[c] = whole ? vol->stress[c] + at : wk->layer[c];
        rc = mc_stress_compute(plan, k, out, err);
        if (rc || whole)
            continue;
        for (int c = 0; c < MC_NSTRESS; c++) {
            double *v = vol->stress[c] + at;
            memset(v, 0, sizeof *v * n);
            for (int j = 0; j < wy; j++)
                memcpy(v + (size_t)(w->j0 + j) * g->nx + w->i0, out[c] + (size_t)j * wx,
                       sizeof *v * (size_t)wx);
        }
    }
    mc_stress_destroy(&plan);
    if (ranks > 1) { /* every rank goes on only if all succeeded; then each layer to all */
        const int any = mc_dist_max_int(rc);
        if (any != MC_OK && rc == MC_OK)
            rc = mc_fail(err, any, "stress stage: another MPI process failed (status %d)", any);
        for (int k = 0; k < nl && rc == MC_OK; k++)
            for (int c = 0; c < MC_NSTRESS; c++)
                mc_dist_bcast(vol->stress[c] + (size_t)(w->k0 + k) * n, n, k % ranks);
    }
    return rc;
}

/* The invariants of one group: over the whole layers, or only inside the window (the rest of
 * the layers holds zero stress, whose invariants are 0), point by point with the scalar
 * functions, which mc_invariants_volume equals bit for bit. */
static int group_invariants(mc_results *vol, const mc_stage_stress_window *w, mc_error *err)
{
    const mc_grid *g = &vol->grid;
    const size_t n = mc_grid_cells(g), at = (size_t)w->k0 * n;
    const size_t nl = (size_t)(w->k1 - w->k0 + 1);
    if (w->i1 - w->i0 + 1 == g->nx && w->j1 - w->j0 + 1 == g->ny)
        return mc_invariants_volume(nl * n, vol->stress[MC_SXX] + at, vol->stress[MC_SYY] + at,
                                    vol->stress[MC_SZZ] + at, vol->stress[MC_SXY] + at,
                                    vol->stress[MC_SYZ] + at, vol->stress[MC_SXZ] + at,
                                    vol->von_mises + at, vol->hydrostatic + at, vol->tresca + at,
                                    err);
    memset(vol->von_mises + at, 0, sizeof(double) * nl * n);
    memset(vol->hydrostatic + at, 0, sizeof(double) * nl * n);
    memset(vol->tresca + at, 0, sizeof(double) * nl * n);
    const int rows = (int)nl * (w->j1 - w->j0 + 1), wy = w->j1 - w->j0 + 1;
#pragma omp parallel for schedule(static) \
    if ((size_t)rows * (size_t)(w->i1 - w->i0 + 1) > MC_THREADS_MIN_CELLS)
    for (int r = 0; r < rows; r++) {
        const size_t row = at + (size_t)(r / wy) * n + (size_t)(w->j0 + r % wy) * g->nx;
        for (int i = w->i0; i <= w->i1; i++) {
            const size_t q = row + (size_t)i;
            double t[MC_NSTRESS];
            for (int c = 0; c < MC_NSTRESS; c++)
                t[c] = vol->stress[c][q];
            vol->von_mises[q] = mc_von_mises(t);
            vol->hydrostatic[q] = mc_hydrostatic(t);
            vol->tresca[q] = mc_tresca(t);
        }
    }
    return MC_OK;
}

static int stage_compute(const mc_scene *sc, const mc_results *res, const mc_stress_tuning *tune,
                         const double *depths, int nd, mc_results *vol, mc_error *err)
{
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    const double mu = sc->stress.friction;
    mc_stage_stress_layout *lay = &vol->stress_layout;
    size_t nv;
    if (!mc_size_mul(n, (size_t)nd, &nv))
        return mc_fail(err, MC_ERR_NOMEM, "stress stage: %d layers of %d x %d cells overflow",
                       nd, g->nx, g->ny);
    const int windowed = tune->window == MC_STRESS_AUTO ? sc->stress.window == MC_STRESS_WINDOW_AUTO
                                                        : tune->window == MC_STRESS_ON;
    plan_windows(g, res->pressure, depths, nd, windowed, lay);
    stage_work wk = {0};
    double **vols[MC_NSTRESS + 3] = {&vol->von_mises, &vol->hydrostatic, &vol->tresca};
    for (int c = 0; c < MC_NSTRESS; c++)
        vols[3 + c] = &vol->stress[c];
    int ok = (vol->depths = mc_malloc(sizeof *vol->depths * (size_t)nd)) != NULL;
    for (int v = 0; v < MC_NSTRESS + 3 && ok; v++)
        ok = (*vols[v] = mc_malloc(sizeof(double) * nv)) != NULL;
    if (ok && mu != 0.0)
        ok = (wk.qx = mc_malloc(sizeof *wk.qx * n)) != NULL;
    if (ok && lay->windowed) {
        ok = (wk.pw = mc_malloc(sizeof *wk.pw * n)) != NULL;
        if (ok && mu != 0.0)
            ok = (wk.qw = mc_malloc(sizeof *wk.qw * n)) != NULL;
        for (int c = 0; c < MC_NSTRESS && ok; c++)
            ok = (wk.layer[c] = mc_malloc(sizeof *wk.layer[c] * n)) != NULL;
    }
    if (!ok) {
        stage_work_free(&wk);
        return mc_fail(err, MC_ERR_NOMEM,
                       "stress stage: out of memory for %d layers of %d x %d cells (%.2g GB)", nd,
                       g->nx, g->ny, 9.0 * 8.0 * (double)nv / 1e9);
    }
    vol->nlayers = nd;
    memcpy(vol->depths, depths, sizeof *depths * (size_t)nd);
    long loaded = 0;
    for (size_t i = 0; i < n; i++)
        loaded += res->pressure[i] != 0.0;
    lay->loaded_cells = loaded;
    if (wk.qx)
        for (size_t i = 0; i < n; i++)
            wk.qx[i] = mu * res->pressure[i];
    int rc = MC_OK;
    for (int w = 0; w < lay->nwindows && rc == MC_OK; w++)
        rc = stage_group(sc, res, tune, depths, &lay->window[w], &wk, vol, err);
    stage_work_free(&wk);
    for (int w = 0; w < lay->nwindows && rc == MC_OK; w++)
        rc = group_invariants(vol, &lay->window[w], err);
    return rc;
}

int mc_stage_stress_tuned(const mc_scene *sc, mc_results *res, const mc_stress_tuning *tune,
                          mc_error *err)
{
    const mc_stress_tuning automatic = {MC_STRESS_AUTO, MC_STRESS_AUTO, MC_STRESS_AUTO};
    if (!tune)
        tune = &automatic;
    if (!res->pressure)
        return mc_fail(err, MC_ERR_INPUT, "stress stage: the results hold no pressure field");
    double depths[MC_MAX_DEPTHS];
    int nd = 0;
    /* the stage fills a results struct of its own; its stress members replace those of res only
     * when everything succeeded */
    mc_results vol = {.grid = res->grid};
    int rc = stage_depths(sc, res, depths, &nd, &vol.stress_layout, err);
    if (rc == MC_OK)
        rc = stage_compute(sc, res, tune, depths, nd, &vol, err);
    if (rc == MC_OK)
        rc = stage_summary(sc, &vol, err);
    if (rc == MC_OK)
        mc_results_move_stress(res, &vol);
    mc_results_free(&vol);
    return rc;
}

int mc_stage_stress(const mc_scene *sc, mc_results *res, mc_error *err)
{
    return mc_stage_stress_tuned(sc, res, NULL, err);
}
