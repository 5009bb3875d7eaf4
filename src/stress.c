/* stress.c - the subsurface stress operator over depth layers and the pipeline stage (see
 * stress.h). Kernel tables come from stress_table.c; the transforms from the engine of
 * operator.h, whose two backends read the same tables. */
#include "stress.h"

#include <math.h>
#include <omp.h>
#include <string.h>

#include "alloc.h"
#include "invariants.h"
#include "kernel.h"

#define NLOADS 3 /* p, q_x, q_y: index li of the load bit 1 << li */

struct mc_stress_op {
    mc_grid g;
    mc_stress_kernel kernel;
    int nlayers;
    double *depths;
    int loads;
    mc_conv *conv;
    mc_stress_tables *tb;
    mc_kernel_table tab[MC_NSTRESS]; /* views into tables (not owned by the structs) */
    double *tables;                  /* 6 tables of tx*ty */
    double *spectra;                 /* per announced load: 6 kernel spectra and the load's */
    double *kspec[NLOADS][MC_NSTRESS];
    double *lspec[NLOADS];
    mc_stress_timing timing;
};

void mc_stress_destroy(mc_stress_op **opp)
{
    if (!opp || !*opp)
        return;
    mc_stress_op *op = *opp;
    mc_stress_tables_destroy(&op->tb);
    mc_conv_destroy(&op->conv);
    mc_free(op->tables);
    mc_free(op->spectra);
    mc_free(op->depths);
    mc_free(op);
    *opp = NULL;
}

static int check_options(const mc_stress_options *opt, mc_error *err)
{
    if (opt->kernel != MC_STRESS_PATCH && opt->kernel != MC_STRESS_POINT)
        return mc_fail(err, MC_ERR_INPUT, "stress: unknown kernel %d (accepted: patch, point)",
                       (int)opt->kernel);
    if (!(opt->nu > -1.0 && opt->nu <= 0.5))
        return mc_fail(err, MC_ERR_INPUT, "stress: Poisson ratio %g not in (-1, 0.5]", opt->nu);
    if (opt->nlayers < 1 || !opt->depths)
        return mc_fail(err, MC_ERR_INPUT, "stress: %d layers; at least one depth is needed",
                       opt->nlayers);
    if (opt->loads <= 0 || (opt->loads & ~(MC_LOAD_P | MC_LOAD_QX | MC_LOAD_QY)))
        return mc_fail(err, MC_ERR_INPUT,
                       "stress: loads %d must be a non-empty combination of MC_LOAD_P, "
                       "MC_LOAD_QX, MC_LOAD_QY",
                       opt->loads);
    for (int k = 0; k < opt->nlayers; k++) {
        const double z = opt->depths[k];
        if (!(isfinite(z) && z >= 0.0))
            return mc_fail(err, MC_ERR_INPUT, "stress: depth %d is %g m; depths must be >= 0", k,
                           z);
        if (opt->kernel == MC_STRESS_POINT && z == 0.0)
            return mc_fail(err, MC_ERR_INPUT,
                           "stress: depth %d is 0, where the point kernel is singular (use the "
                           "patch kernel, or depths > 0)",
                           k);
    }
    return MC_OK;
}

int mc_stress_create(const mc_grid *g, const mc_stress_options *opt, mc_stress_op **out,
                     mc_error *err)
{
    *out = NULL;
    int rc = mc_grid_check(g, err);
    if (rc || (rc = check_options(opt, err)))
        return rc;
    mc_stress_op *op = mc_calloc(1, sizeof *op);
    if (!op)
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    op->g = *g;
    op->kernel = opt->kernel;
    op->nlayers = opt->nlayers;
    op->loads = opt->loads;
    if (!(op->depths = mc_malloc(sizeof *op->depths * (size_t)opt->nlayers))) {
        mc_stress_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    }
    memcpy(op->depths, opt->depths, sizeof *op->depths * (size_t)opt->nlayers);
    if ((rc = mc_conv_create(g, opt->backend, &op->conv, err))) {
        mc_stress_destroy(&op);
        return rc;
    }
    int tx, ty;
    mc_conv_table_dims(op->conv, &tx, &ty);
    if ((rc = mc_stress_tables_create(g, tx, ty, opt->kernel, opt->nu, 0, &op->tb, err))) {
        mc_stress_destroy(&op);
        return rc;
    }
    int nl = 0;
    for (int li = 0; li < NLOADS; li++)
        nl += (opt->loads >> li) & 1;
    const size_t slen = mc_conv_spectrum_len(op->conv);
    size_t ntab, nspec;
    if (!mc_size_mul((size_t)tx * ty, MC_NSTRESS, &ntab) ||
        !mc_size_mul(slen, (size_t)nl * (MC_NSTRESS + 1), &nspec) ||
        !(op->tables = mc_malloc(sizeof *op->tables * ntab)) ||
        !(op->spectra = mc_malloc(sizeof *op->spectra * nspec))) {
        mc_stress_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM,
                       "stress: out of memory for the tables and spectra of a %d x %d grid (%d "
                       "loads)",
                       g->nx, g->ny, nl);
    }
    double *sp = op->spectra;
    for (int li = 0; li < NLOADS; li++) {
        if (!((opt->loads >> li) & 1))
            continue;
        for (int c = 0; c < MC_NSTRESS; c++, sp += slen)
            op->kspec[li][c] = sp;
        op->lspec[li] = sp;
        sp += slen;
    }
    for (int c = 0; c < MC_NSTRESS; c++)
        op->tab[c] = (mc_kernel_table){*g, tx, ty, op->tables + (size_t)c * tx * ty};
    *out = op;
    return MC_OK;
}

/* The given loads: fills li[] with the indices of the non-NULL loads; checks they are announced. */
static int given_loads(const mc_stress_op *op, const double *const loads[NLOADS], int li[NLOADS],
                       int *ng, mc_error *err)
{
    static const char *names[NLOADS] = {"p", "q_x", "q_y"};
    *ng = 0;
    for (int l = 0; l < NLOADS; l++) {
        if (!loads[l])
            continue;
        if (!((op->loads >> l) & 1))
            return mc_fail(err, MC_ERR_INPUT,
                           "stress: load %s given but not announced in the options (loads = %d)",
                           names[l], op->loads);
        li[(*ng)++] = l;
    }
    return MC_OK;
}

static void transform_loads(mc_stress_op *op, const double *const loads[NLOADS], const int li[],
                            int ng)
{
    const double t0 = omp_get_wtime();
    for (int i = 0; i < ng; i++)
        mc_conv_load(op->conv, loads[li[i]], op->lspec[li[i]]);
    op->timing.loads += omp_get_wtime() - t0;
}

/* Layer k from the transformed loads li[0..ng-1] into out[c] (ny*nx each). */
static int compute_layer(mc_stress_op *op, int k, const int li[], int ng, double *const out[6],
                         mc_error *err)
{
    static const int bit[NLOADS] = {MC_LOAD_P, MC_LOAD_QX, MC_LOAD_QY};
    double *const tk[MC_NSTRESS] = {op->tab[0].k, op->tab[1].k, op->tab[2].k,
                                    op->tab[3].k, op->tab[4].k, op->tab[5].k};
    for (int i = 0; i < ng; i++) {
        double t0 = omp_get_wtime();
        int rc = mc_stress_tables_build(op->tb, bit[li[i]], op->depths[k], tk, err);
        double t1 = omp_get_wtime();
        op->timing.tables += t1 - t0;
        for (int c = 0; c < MC_NSTRESS && rc == MC_OK; c++)
            rc = mc_conv_kernel(op->conv, &op->tab[c], op->kspec[li[i]][c], err);
        op->timing.kernels += omp_get_wtime() - t1;
        if (rc)
            return rc;
    }
    const double t0 = omp_get_wtime();
    for (int c = 0; c < MC_NSTRESS; c++) {
        const double *ks[NLOADS], *ls[NLOADS];
        for (int i = 0; i < ng; i++) {
            ks[i] = op->kspec[li[i]][c];
            ls[i] = op->lspec[li[i]];
        }
        mc_conv_apply(op->conv, ng, ks, ls, out[c]);
    }
    op->timing.apply += omp_get_wtime() - t0;
    op->timing.layers++;
    return MC_OK;
}

static int check_outputs(double *const s[6], mc_error *err)
{
    for (int c = 0; c < MC_NSTRESS; c++)
        if (!s || !s[c])
            return mc_fail(err, MC_ERR_INPUT, "stress: output array for component %s is NULL",
                           mc_stress_name(c));
    return MC_OK;
}

int mc_stress_field(mc_stress_op *op, const double *p, const double *qx, const double *qy,
                    double *const s[6], mc_error *err)
{
    const double *const loads[NLOADS] = {p, qx, qy};
    int li[NLOADS], ng;
    int rc = check_outputs(s, err);
    if (rc || (rc = given_loads(op, loads, li, &ng, err)))
        return rc;
    const size_t n = mc_grid_cells(&op->g);
    if (ng == 0) { /* no load, no stress */
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(s[c], 0, sizeof(double) * n * (size_t)op->nlayers);
        return MC_OK;
    }
    transform_loads(op, loads, li, ng);
    for (int k = 0; k < op->nlayers; k++) {
        double *const out[MC_NSTRESS] = {s[0] + k * n, s[1] + k * n, s[2] + k * n,
                                         s[3] + k * n, s[4] + k * n, s[5] + k * n};
        if ((rc = compute_layer(op, k, li, ng, out, err)))
            return rc;
    }
    return MC_OK;
}

int mc_stress_layer(mc_stress_op *op, int k, const double *p, const double *qx, const double *qy,
                    double *const s[6], mc_error *err)
{
    if (k < 0 || k >= op->nlayers)
        return mc_fail(err, MC_ERR_INPUT, "stress: layer %d out of range 0..%d", k,
                       op->nlayers - 1);
    const double *const loads[NLOADS] = {p, qx, qy};
    int li[NLOADS], ng;
    int rc = check_outputs(s, err);
    if (rc || (rc = given_loads(op, loads, li, &ng, err)))
        return rc;
    if (ng == 0) {
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(s[c], 0, sizeof(double) * mc_grid_cells(&op->g));
        return MC_OK;
    }
    transform_loads(op, loads, li, ng);
    return compute_layer(op, k, li, ng, s, err);
}

void mc_stress_timing_get(const mc_stress_op *op, mc_stress_timing *t) { *t = op->timing; }

/* ---- the pipeline stage ------------------------------------------------------------------- */

/* The arrays the stage fills; moved into the results only when everything succeeded. */
typedef struct {
    double *depths, *stress[MC_NSTRESS], *vm, *hydro, *tresca;
} stage_arrays;

static void stage_arrays_free(stage_arrays *a)
{
    mc_free(a->depths);
    for (int c = 0; c < MC_NSTRESS; c++)
        mc_free(a->stress[c]);
    mc_free(a->vm);
    mc_free(a->hydro);
    mc_free(a->tresca);
}

static size_t argmax(const double *v, size_t n)
{
    size_t im = 0;
    for (size_t i = 1; i < n; i++)
        if (v[i] > v[im])
            im = i;
    return im;
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

static void stage_summary(const mc_scene *sc, const mc_grid *g, const stage_arrays *a, int nd,
                          mc_stress_summary *ss)
{
    const size_t nv = mc_grid_cells(g) * (size_t)nd;
    const size_t iv = argmax(a->vm, nv), it = argmax(a->tresca, nv);
    memset(ss, 0, sizeof *ss);
    ss->vm_max = a->vm[iv];
    volume_point(g, a->depths, iv, ss->vm_max_at);
    ss->hydro_at_vm_max = a->hydro[iv];
    ss->tresca_max = a->tresca[it];
    volume_point(g, a->depths, it, ss->tresca_max_at);
    ss->layers = nd;
    ss->depth_min = ss->depth_max = a->depths[0];
    for (int k = 1; k < nd; k++) {
        ss->depth_min = fmin(ss->depth_min, a->depths[k]);
        ss->depth_max = fmax(ss->depth_max, a->depths[k]);
    }
    ss->kernel = sc->stress.kernel == MC_STRESS_POINT ? "point" : "patch";
    ss->friction = sc->stress.friction;
}

static int stage_compute(const mc_scene *sc, const mc_results *res, const double *depths, int nd,
                         stage_arrays *a, mc_error *err)
{
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    const double mu = sc->stress.friction;
    size_t nv;
    if (!mc_size_mul(n, (size_t)nd, &nv))
        return mc_fail(err, MC_ERR_NOMEM, "stress stage: %d layers of %d x %d cells overflow",
                       nd, g->nx, g->ny);
    double *qx = NULL;
    double **vols[MC_NSTRESS + 3] = {&a->vm, &a->hydro, &a->tresca};
    for (int c = 0; c < MC_NSTRESS; c++)
        vols[3 + c] = &a->stress[c];
    int ok = (a->depths = mc_malloc(sizeof *a->depths * (size_t)nd)) != NULL;
    for (int v = 0; v < MC_NSTRESS + 3 && ok; v++)
        ok = (*vols[v] = mc_malloc(sizeof(double) * nv)) != NULL;
    if (ok && mu != 0.0)
        ok = (qx = mc_malloc(sizeof *qx * n)) != NULL;
    if (!ok)
        return mc_fail(err, MC_ERR_NOMEM,
                       "stress stage: out of memory for %d layers of %d x %d cells (%.2g GB)", nd,
                       g->nx, g->ny, 9.0 * 8.0 * (double)nv / 1e9);
    memcpy(a->depths, depths, sizeof *depths * (size_t)nd);
    if (qx)
        for (size_t i = 0; i < n; i++)
            qx[i] = mu * res->pressure[i];
    const mc_stress_options opt = {.kernel = sc->stress.kernel,
                                   .nu = sc->body1.nu,
                                   .nlayers = nd,
                                   .depths = depths,
                                   .backend = sc->solver.op,
                                   .loads = MC_LOAD_P | (qx ? MC_LOAD_QX : 0)};
    mc_stress_op *op = NULL;
    int rc = mc_stress_create(g, &opt, &op, err);
    if (rc == MC_OK)
        rc = mc_stress_field(op, res->pressure, qx, NULL, a->stress, err);
    mc_stress_destroy(&op);
    mc_free(qx);
    if (rc == MC_OK)
        rc = mc_invariants_volume(nv, a->stress[MC_SXX], a->stress[MC_SYY], a->stress[MC_SZZ],
                                  a->stress[MC_SXY], a->stress[MC_SYZ], a->stress[MC_SXZ], a->vm,
                                  a->hydro, a->tresca, err);
    return rc;
}

int mc_stress_stage(const mc_scene *sc, mc_results *res, mc_error *err)
{
    if (!res->pressure)
        return mc_fail(err, MC_ERR_INPUT, "stress stage: the results hold no pressure field");
    double depths[MC_MAX_DEPTHS];
    int nd = 0;
    int rc = mc_scene_depths(sc, depths, &nd, err);
    if (rc)
        return rc;
    stage_arrays a = {0};
    if ((rc = stage_compute(sc, res, depths, nd, &a, err))) {
        stage_arrays_free(&a);
        return rc;
    }
    stage_summary(sc, &res->grid, &a, nd, &res->stress_summary);
    /* replace what an earlier run left */
    stage_arrays old = {res->depths, {0}, res->von_mises, res->hydrostatic, res->tresca};
    for (int c = 0; c < MC_NSTRESS; c++) {
        old.stress[c] = res->stress[c];
        res->stress[c] = a.stress[c];
    }
    stage_arrays_free(&old);
    res->nlayers = nd;
    res->depths = a.depths;
    res->von_mises = a.vm;
    res->hydrostatic = a.hydro;
    res->tresca = a.tresca;
    return MC_OK;
}
