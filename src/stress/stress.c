/* stress.c - the subsurface stress operator over depth layers (see stress.h). Kernel tables come
 * from stress_table.c; the transforms from the engine of operator.h (any grid, either backend) or
 * from the symmetric engine of stress_sym.c (fft backend, free axes); the direct sums over the
 * loaded cells from stress_sym.c. The pipeline stage is in stress_stage.c. */
#include "stress/stress.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/alloc.h"
#include "kernels/kernel.h"
#include "stress/stress_internal.h"

#define NLOADS 3 /* p, q_x, q_y: index li of the load bit 1 << li */

/* ---- the cost model (mc_stress_cost) ----------------------------------------------------------
 * Seconds on one thread, measured on this machine (2-core x86-64 VM, FFTW 3.3.10 ESTIMATE plans,
 * gcc 12 -O2) as process CPU time, the best of 5, over grids 32^2 ... 1024^2 (the engine's parts
 * timed one by one; the fitted value for 256^2 ... 1024^2, where the choice matters):
 *   COST_FFT     per point and log2(points) of the padded 2-D transform (pruned c2r or r2c,
 *                column passes included): 0.22 (256^2) ... 0.48 ns (1024^2), cache bound;
 *   COST_R2R     the same for the quadrant's DCT-I/DST-I (FFTW's r2r codelets are not vectorised,
 *                so dearer per point than the r2c, on a quarter of the points): 0.56 ... 0.93 ns;
 *   COST_PRODUCT per complex multiply-add of a kernel and a load spectrum (memory bound, read
 *                from the quadrant): 2.2 ... 2.4 ns at 512^2 and 1024^2;
 *   COST_MADD    per multiply-add of the direct sum over the loaded cells (vectorised rows):
 *                0.47 ... 0.57 ns.
 * Only the ratio of the two paths matters; a factor 2 off moves the switch-over by 2x in the
 * number of loaded cells, where both paths cost the same. The engine of operator.h transforms the
 * full table (r2c, plus a copy in and a scaled copy out): COST_FULL_KERNEL times COST_FFT. */
#define COST_FFT 0.4e-9
#define COST_R2R 0.65e-9
#define COST_PRODUCT 2.0e-9
#define COST_MADD 0.5e-9
#define COST_FULL_KERNEL 1.5

struct mc_stress_op {
    mc_grid g;
    mc_stress_kernel kernel;
    int nlayers;
    double *depths;
    int loads;
    mc_stress_tuning tune;
    mc_stress_tables *tb;
    /* engine of operator.h (general path) */
    mc_conv *conv;
    int tx, ty;
    mc_kernel_table tab[MC_NSTRESS]; /* views into tables (not owned by the structs) */
    double *tables;                  /* 6 tables of tx*ty */
    /* symmetric engine (both axes free, fft backend) */
    mc_stress_sym *sym;
    int qx, qy;
    /* per announced load: 6 kernel arrays (general: spectra, or raw tables for the direct sum;
     * symmetric: quadrant tables, turned into their spectra in place) and the load's spectrum */
    double *spectra;
    double *kspec[NLOADS][MC_NSTRESS];
    double *lspec[NLOADS];
    /* the current call */
    const double *cur[NLOADS]; /* the loads of mc_stress_prepare (NULL: none) */
    int li[NLOADS], ng;
    int *cells; /* loaded cells (indices into nx*ny) */
    long ncells;
    int direct; /* 1: direct summation over the loaded cells */
    mc_stress_timing timing;
};

void mc_stress_destroy(mc_stress_op **opp)
{
    if (!opp || !*opp)
        return;
    mc_stress_op *op = *opp;
    mc_stress_tables_destroy(&op->tb);
    mc_conv_destroy(&op->conv);
    mc_stress_sym_destroy(&op->sym);
    mc_free(op->tables);
    mc_free(op->spectra);
    mc_free(op->cells);
    mc_free(op->depths);
    mc_free(op);
    *opp = NULL;
}

static int check_options(const mc_stress_options *opt, const mc_stress_tuning *tune,
                         mc_error *err)
{
    if (opt->kernel != MC_STRESS_PATCH && opt->kernel != MC_STRESS_POINT)
        return mc_fail(err, MC_ERR_INPUT, "stress: unknown kernel %d (accepted: patch, point)",
                       (int)opt->kernel);
    if (!(opt->nu > -1.0 && opt->nu <= 0.5))
        return mc_fail(err, MC_ERR_INPUT, "stress: Poisson ratio %g not in (-1, 0.5]", opt->nu);
    if (opt->nlayers < 1 || !opt->depths)
        return mc_fail(err, MC_ERR_INPUT, "stress: %d layers; at least one depth is needed",
                       opt->nlayers);
    if (opt->loads <= 0 || (opt->loads & ~(MC_TRACTION_P | MC_TRACTION_QX | MC_TRACTION_QY)))
        return mc_fail(err, MC_ERR_INPUT,
                       "stress: loads %d must be a non-empty combination of MC_TRACTION_P, "
                       "MC_TRACTION_QX, MC_TRACTION_QY",
                       opt->loads);
    const mc_stress_switch sw[3] = {tune->symmetric, tune->sparse, tune->window};
    for (int k = 0; k < 3; k++)
        if (sw[k] != MC_STRESS_AUTO && sw[k] != MC_STRESS_OFF && sw[k] != MC_STRESS_ON)
            return mc_fail(err, MC_ERR_INPUT, "stress: tuning switch %d is %d (AUTO, OFF or ON)",
                           k, (int)sw[k]);
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

/* Takes the transform engine of the op's path and the table builder; sets the kernel array and
 * load spectrum lengths. */
static int create_engine(mc_stress_op *op, mc_backend backend, const mc_stress_options *opt,
                         size_t *klen, size_t *llen, mc_error *err)
{
    const mc_grid *g = &op->g;
    int rc, tx, ty;
    const int sym = backend == MC_BACKEND_FFT && !g->periodic_x && !g->periodic_y &&
                    op->tune.symmetric != MC_STRESS_OFF;
    if (sym) {
        if ((rc = mc_stress_sym_create(g, &op->sym, err)))
            return rc;
        mc_stress_sym_dims(op->sym, &op->qx, &op->qy);
        tx = 2 * (op->qx - 1);
        ty = 2 * (op->qy - 1);
        *klen = mc_stress_sym_quad_len(op->sym);
        *llen = mc_stress_sym_spec_len(op->sym);
    } else {
        if ((rc = mc_conv_create(g, backend, &op->conv, err)))
            return rc;
        mc_conv_table_dims(op->conv, &tx, &ty);
        *klen = *llen = mc_conv_spectrum_len(op->conv);
        size_t ntab;
        if (!mc_size_mul((size_t)tx * ty, MC_NSTRESS, &ntab) ||
            !(op->tables = mc_malloc(sizeof *op->tables * ntab)))
            return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory for the tables of a %d x %d "
                                              "grid", g->nx, g->ny);
        for (int c = 0; c < MC_NSTRESS; c++)
            op->tab[c] = (mc_kernel_table){*g, tx, ty, op->tables + (size_t)c * tx * ty};
    }
    op->tx = tx;
    op->ty = ty;
    op->timing.symmetric = sym;
    return mc_stress_tables_create(g, tx, ty, opt->kernel, opt->nu, 0, &op->tb, err);
}

int mc_stress_create_tuned(const mc_grid *g, const mc_stress_options *opt,
                           const mc_stress_tuning *tune, mc_stress_op **out, mc_error *err)
{
    *out = NULL;
    const mc_stress_tuning automatic = {MC_STRESS_AUTO, MC_STRESS_AUTO, MC_STRESS_AUTO};
    if (!tune)
        tune = &automatic;
    int rc = mc_grid_check(g, err);
    if (rc || (rc = check_options(opt, tune, err)))
        return rc;
    if (mc_grid_cells(g) > (size_t)INT_MAX) /* the loaded cells are listed as int */
        return mc_fail(err, MC_ERR_LIMIT, "stress: %d x %d cells exceed the %d the op handles",
                       g->nx, g->ny, INT_MAX);
    mc_stress_op *op = mc_calloc(1, sizeof *op);
    if (!op)
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    op->g = *g;
    op->kernel = opt->kernel;
    op->nlayers = opt->nlayers;
    op->loads = opt->loads;
    op->tune = *tune;
    if (!(op->depths = mc_malloc(sizeof *op->depths * (size_t)opt->nlayers)) ||
        !(op->cells = mc_malloc(sizeof *op->cells * mc_grid_cells(g)))) {
        mc_stress_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    }
    memcpy(op->depths, opt->depths, sizeof *op->depths * (size_t)opt->nlayers);
    size_t klen, llen;
    if ((rc = create_engine(op, opt->backend, opt, &klen, &llen, err))) {
        mc_stress_destroy(&op);
        return rc;
    }
    int nl = 0;
    for (int li = 0; li < NLOADS; li++)
        nl += (opt->loads >> li) & 1;
    size_t per, nspec;
    if (!mc_size_mul(klen, MC_NSTRESS, &per) || (per += llen) < llen ||
        !mc_size_mul(per, (size_t)nl, &nspec) ||
        !(op->spectra = mc_malloc(sizeof *op->spectra * nspec))) {
        mc_stress_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM,
                       "stress: out of memory for the spectra of a %d x %d grid (%d loads)",
                       g->nx, g->ny, nl);
    }
    double *sp = op->spectra;
    for (int li = 0; li < NLOADS; li++) {
        if (!((opt->loads >> li) & 1))
            continue;
        for (int c = 0; c < MC_NSTRESS; c++, sp += klen)
            op->kspec[li][c] = sp;
        op->lspec[li] = sp;
        sp += llen;
    }
    *out = op;
    return MC_OK;
}

int mc_stress_create(const mc_grid *g, const mc_stress_options *opt, mc_stress_op **out,
                     mc_error *err)
{
    return mc_stress_create_tuned(g, opt, NULL, out, err);
}

void mc_stress_cost(const mc_stress_op *op, long nloaded, int nterms, double *fft_s,
                    double *direct_s)
{
    const double n = (double)mc_grid_cells(&op->g), pad = (double)op->tx * (double)op->ty;
    const double half = (double)op->ty * (double)(op->tx / 2 + 1);
    *direct_s = COST_MADD * MC_NSTRESS * (double)nterms * (double)nloaded * n;
    if (op->conv && mc_conv_backend(op->conv) == MC_BACKEND_DIRECT) {
        *fft_s = COST_MADD * MC_NSTRESS * (double)nterms * n * n; /* the dense sum */
        return;
    }
    /* pruned transforms: columns in full, rows only where the field lives (half the rows) */
    const double inv = COST_FFT * 0.75 * pad * log2(pad);
    double kern;
    if (op->sym) {
        const double q = (double)op->qx * (double)op->qy;
        kern = COST_R2R * q * log2(q);
    } else {
        kern = COST_FULL_KERNEL * COST_FFT * pad * log2(pad);
    }
    *fft_s = MC_NSTRESS * (nterms * kern + inv + COST_PRODUCT * nterms * half) +
             nterms * inv / op->nlayers;
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

/* Once per call: the loaded cells, the choice of the direct sum, and (if not) the load spectra. */
static void prepare_loads(mc_stress_op *op, const double *const loads[NLOADS], const int li[],
                          int ng)
{
    const double t0 = omp_get_wtime();
    const size_t n = mc_grid_cells(&op->g);
    long nc = 0;
    for (size_t i = 0; i < n; i++) {
        int any = 0;
        for (int t = 0; t < ng; t++)
            any |= loads[li[t]][i] != 0.0;
        if (any)
            op->cells[nc++] = (int)i;
    }
    op->ncells = nc;
    if (op->tune.sparse == MC_STRESS_AUTO) {
        double fft_s, direct_s;
        mc_stress_cost(op, nc, ng, &fft_s, &direct_s);
        op->direct = direct_s < fft_s;
    } else {
        op->direct = op->tune.sparse == MC_STRESS_ON;
    }
    if (!op->direct)
        for (int i = 0; i < ng; i++) {
            if (op->sym)
                mc_stress_sym_load(op->sym, loads[li[i]], op->lspec[li[i]]);
            else
                mc_conv_load(op->conv, loads[li[i]], op->lspec[li[i]]);
        }
    op->timing.loads += omp_get_wtime() - t0;
}

static const int load_bit[NLOADS] = {MC_TRACTION_P, MC_TRACTION_QX, MC_TRACTION_QY};

/* The six tables of load li at depth z into the op's kernel arrays of that load (quadrants on the
 * symmetric path, full tables otherwise; for the transform path of the general engine into the
 * shared table arrays, transformed after). */
static int build_tables(mc_stress_op *op, int li, double z, mc_error *err)
{
    double *const *dst = op->sym || op->direct ? op->kspec[li] : NULL;
    double *const full[MC_NSTRESS] = {op->tab[0].k, op->tab[1].k, op->tab[2].k,
                                      op->tab[3].k, op->tab[4].k, op->tab[5].k};
    if (op->sym)
        return mc_stress_tables_quadrant(op->tb, load_bit[li], z, op->qx, op->qy, dst, err);
    return mc_stress_tables_build(op->tb, load_bit[li], z, dst ? dst : full, err);
}

/* Layer k from the prepared loads li[0..ng-1] into out[c] (ny*nx each). */
static int compute_layer(mc_stress_op *op, int k, const double *const loads[NLOADS],
                         const int li[], int ng, double *const out[6], mc_error *err)
{
    for (int i = 0; i < ng; i++) {
        const double t0 = omp_get_wtime();
        int rc = build_tables(op, li[i], op->depths[k], err);
        const double t1 = omp_get_wtime();
        op->timing.tables += t1 - t0;
        if (rc)
            return rc;
        if (op->direct)
            continue;
        for (int c = 0; c < MC_NSTRESS && rc == MC_OK; c++) {
            if (op->sym)
                mc_stress_sym_kernel(op->sym, mc_stress_parity(load_bit[li[i]], c),
                                     op->kspec[li[i]][c]);
            else
                rc = mc_conv_kernel(op->conv, &op->tab[c], op->kspec[li[i]][c], err);
        }
        op->timing.kernels += omp_get_wtime() - t1;
        if (rc)
            return rc;
    }
    const double t0 = omp_get_wtime();
    for (int c = 0; c < MC_NSTRESS; c++) {
        const double *ks[NLOADS], *ls[NLOADS];
        int par[NLOADS];
        mc_stress_term terms[NLOADS];
        for (int i = 0; i < ng; i++) {
            ks[i] = op->kspec[li[i]][c];
            ls[i] = op->lspec[li[i]];
            par[i] = mc_stress_parity(load_bit[li[i]], c);
            terms[i] = (mc_stress_term){loads[li[i]], op->sym ? ks[i] : NULL, op->qx, par[i],
                                        op->sym ? NULL : ks[i], op->tx, op->ty};
        }
        if (op->direct)
            mc_stress_sparse_sum(&op->g, (int)op->ncells, op->cells, ng, terms, out[c]);
        else if (op->sym)
            mc_stress_sym_apply(op->sym, ng, ks, par, ls, out[c]);
        else
            mc_conv_apply(op->conv, ng, ks, ls, out[c]);
    }
    op->timing.apply += omp_get_wtime() - t0;
    op->timing.layers++;
    op->timing.sparse_layers += op->direct;
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
    prepare_loads(op, loads, li, ng);
    for (int k = 0; k < op->nlayers; k++) {
        double *const out[MC_NSTRESS] = {s[0] + k * n, s[1] + k * n, s[2] + k * n,
                                         s[3] + k * n, s[4] + k * n, s[5] + k * n};
        if ((rc = compute_layer(op, k, loads, li, ng, out, err)))
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
    prepare_loads(op, loads, li, ng);
    return compute_layer(op, k, loads, li, ng, s, err);
}

void mc_stress_timing_get(const mc_stress_op *op, mc_stress_timing *t) { *t = op->timing; }

int mc_stress_prepare(mc_stress_op *op, const double *p, const double *qx, const double *qy,
                      mc_error *err)
{
    const double *const loads[NLOADS] = {p, qx, qy};
    int rc = given_loads(op, loads, op->li, &op->ng, err);
    if (rc) {
        op->ng = 0;
        return rc;
    }
    for (int l = 0; l < NLOADS; l++)
        op->cur[l] = loads[l];
    op->direct = 1;
    op->ncells = 0;
    if (op->ng > 0)
        prepare_loads(op, loads, op->li, op->ng);
    return MC_OK;
}

int mc_stress_compute(mc_stress_op *op, int k, double *const s[6], mc_error *err)
{
    if (k < 0 || k >= op->nlayers)
        return mc_fail(err, MC_ERR_INPUT, "stress: layer %d out of range 0..%d", k,
                       op->nlayers - 1);
    int rc = check_outputs(s, err);
    if (rc)
        return rc;
    if (op->ng == 0) {
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(s[c], 0, sizeof(double) * mc_grid_cells(&op->g));
        return MC_OK;
    }
    return compute_layer(op, k, op->cur, op->li, op->ng, s, err);
}

int mc_stress_is_direct(const mc_stress_op *op) { return op->direct; }
