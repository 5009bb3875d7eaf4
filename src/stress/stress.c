/* stress.c - the subsurface stress over depth layers, planned once (mc_stress_plan, see stress.h).
 * Kernel tables come from stress_table.c; the transforms from the engine of operator.h (any grid,
 * either backend) or from the symmetric engine of stress_sym.c (fft backend, free axes); the
 * sparse sums over the loaded cells from stress_sym.c. The pipeline stage is
 * pipeline/stage_stress.c. */
#include "stress/stress.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fftsize.h"
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
 *   COST_MADD    per multiply-add of the sparse sum over the loaded cells (vectorised rows):
 *                0.47 ... 0.57 ns.
 * Only the ratio of the two paths matters; a factor 2 off moves the switch-over by 2x in the
 * number of loaded cells, where both paths cost the same. The engine of operator.h transforms the
 * full table (r2c, plus a copy in and a scaled copy out): COST_FULL_KERNEL times COST_FFT. */
#define COST_FFT 0.4e-9
#define COST_R2R 0.65e-9
#define COST_PRODUCT 2.0e-9
#define COST_MADD 0.5e-9
#define COST_FULL_KERNEL 1.5

struct mc_stress_plan {
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
    /* per announced load: 6 kernel arrays (general: spectra, or raw tables for the sparse sum;
     * symmetric: quadrant tables, turned into their spectra in place) and the load's spectrum */
    double *spectra;
    double *kspec[NLOADS][MC_NSTRESS];
    double *lspec[NLOADS];
    /* the current call */
    const double *cur[NLOADS]; /* the loads of mc_stress_prepare (NULL: none) */
    int li[NLOADS], ng;
    int *cells; /* loaded cells (indices into nx*ny) */
    long ncells;
    int sparse; /* 1: the sparse sum over the loaded cells */
    /* kernel spectra of every (layer, load) once built: a plan is applied to the same layers
     * many times in the plastic loop (once per joint evaluation). On the general engine of a grid
     * with a periodic axis the image sums make a table ~100x a free one's quadrant (85 % of a
     * doubly periodic running-in step rebuilt them, measured); on the symmetric engine of free
     * axes the quadrant tables and their transforms took 7.6 s of the 512 x 256 x 16 running-in
     * step's 19 evaluations on one thread, 3.7 s with the cache (measured on a loaded machine),
     * for 6 quadrant spectra per layer and load, ~48 bytes per volume cell and load. NULL when
     * it would exceed MC_STRESS_CACHE_BYTES (the tables are then rebuilt per layer) */
    double *kcache;
    unsigned char *kcached; /* [(layer - ck0) * nslots + slot]: built */
    int slot[NLOADS];       /* the cache's index of each load the plan serves (-1: none) */
    int nslots;
    int ck0, cnk;           /* the layers kept: all, or under MPI a repeated plan's own block
                             * (mc_dist_share, the layers mc_stress_field_split computes here) */
    size_t klen;            /* doubles per cached kernel array */
    int compact;            /* 1: the cache holds the general engine's spectra in their compact
                             * form (compact_spectrum: a quarter of the doubles) */
    mc_stress_timing timing;
};

void mc_stress_destroy(mc_stress_plan **planp)
{
    if (!planp || !*planp)
        return;
    mc_stress_plan *plan = *planp;
    mc_stress_tables_destroy(&plan->tb);
    mc_conv_destroy(&plan->conv);
    mc_stress_sym_destroy(&plan->sym);
    mc_free(plan->tables);
    mc_free(plan->spectra);
    mc_free(plan->kcache);
    mc_free(plan->kcached);
    mc_free(plan->cells);
    mc_free(plan->depths);
    mc_free(plan);
    *planp = NULL;
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
    int rc = MC_OK;
    for (int k = 0; k < opt->nlayers && rc == MC_OK; k++) {
        char what[40];
        snprintf(what, sizeof what, "stress, layer %d", k);
        rc = mc_stress_check_depth(opt->kernel, opt->depths[k], what, err);
    }
    return rc;
}

/* Takes the transform engine of the plan's path and the table builder; sets the kernel array and
 * load spectrum lengths. */
static int create_engine(mc_stress_plan *plan, mc_backend backend, const mc_stress_options *opt,
                         size_t *klen, size_t *llen, mc_error *err)
{
    const mc_grid *g = &plan->g;
    int rc, tx, ty;
    const int sym = backend == MC_BACKEND_FFT && !g->periodic_x && !g->periodic_y &&
                    plan->tune.symmetric != MC_STRESS_OFF;
    if (sym) {
        if ((rc = mc_stress_sym_create(g, &plan->sym, err)))
            return rc;
        mc_stress_sym_dims(plan->sym, &plan->qx, &plan->qy);
        tx = 2 * (plan->qx - 1);
        ty = 2 * (plan->qy - 1);
        *klen = mc_stress_sym_quad_len(plan->sym);
        *llen = mc_stress_sym_spec_len(plan->sym);
    } else {
        if ((rc = mc_conv_create(g, backend, &plan->conv, err)))
            return rc;
        mc_conv_table_dims(plan->conv, &tx, &ty);
        *klen = *llen = mc_conv_spectrum_len(plan->conv);
        size_t ntab;
        if (!mc_size_mul((size_t)tx * ty, MC_NSTRESS, &ntab) ||
            !(plan->tables = mc_malloc(sizeof *plan->tables * ntab)))
            return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory for the tables of a %d x %d "
                                              "grid", g->nx, g->ny);
        for (int c = 0; c < MC_NSTRESS; c++)
            plan->tab[c] = (mc_kernel_table){*g, tx, ty, plan->tables + (size_t)c * tx * ty};
    }
    plan->tx = tx;
    plan->ty = ty;
    plan->timing.symmetric = sym;
    return mc_stress_tables_create(g, tx, ty, opt->kernel, opt->nu, 0, &plan->tb, err);
}

/* The compact form of a kernel spectrum of the general engine (ty rows of hx = tx/2 + 1 complex
 * values, operator/padfft.h): a real table of parity par (mc_stress_parity: bit 0 odd in x,
 * bit 1 odd in y) has a spectrum F that is real when both parities agree and imaginary when
 * they differ (F(-kx, -ky) = conj F and F(-kx, ky) = sx F), with F(kx, -ky) = sy F(kx, ky);
 * so rows 0 .. ty/2 of its real or imaginary part hold it: (ty/2 + 1) hx doubles against
 * 2 ty hx. The periodic axes' image sums make these spectra cost ~100x a free table's to build,
 * so a plan on such a grid keeps every layer's (theory.md §9.9: at 256^2 x 32 on a strip, 96 ->
 * 24 bytes per volume cell). Compressing averages F(kx, ky) and sy F(kx, -ky) and drops the other
 * part: it projects the spectrum on its exact symmetry, removing only round-off. */
static size_t compact_len(const mc_stress_plan *plan)
{
    return (size_t)(plan->ty / 2 + 1) * (size_t)(plan->tx / 2 + 1);
}

static void compact_spectrum(const mc_stress_plan *plan, int par, const double *spec,
                             double *cmp)
{
    const int hx = plan->tx / 2 + 1, ty = plan->ty, part = (par & 1) != ((par >> 1) & 1);
    const double sy = (par & 2) ? -1.0 : 1.0;
    for (int r = 0; r <= ty / 2; r++) {
        const int m = (ty - r) % ty; /* the row of -ky */
        for (int kx = 0; kx < hx; kx++)
            cmp[(size_t)r * hx + kx] = 0.5 * (spec[2 * ((size_t)r * hx + kx) + part] +
                                              sy * spec[2 * ((size_t)m * hx + kx) + part]);
    }
}

static void expand_spectrum(const mc_stress_plan *plan, int par, const double *cmp,
                            double *spec)
{
    const int hx = plan->tx / 2 + 1, ty = plan->ty, part = (par & 1) != ((par >> 1) & 1);
    const double sy = (par & 2) ? -1.0 : 1.0;
    for (int ky = 0; ky < ty; ky++) {
        const int r = ky <= ty / 2 ? ky : ty - ky;
        const double s = ky <= ty / 2 ? 1.0 : sy;
        for (int kx = 0; kx < hx; kx++) {
            const size_t q = (size_t)ky * hx + kx;
            spec[2 * q + part] = s * cmp[(size_t)r * hx + kx];
            spec[2 * q + 1 - part] = 0.0;
        }
    }
}

double mc_stress_cache_layer_bytes(const mc_grid *g)
{
    const int px = g->periodic_x, py = g->periodic_y;
    const double tx = px ? g->nx : mc_fftsize_good(2 * g->nx - 1);
    const double ty = py ? g->ny : mc_fftsize_good(2 * g->ny - 1);
    const double quad = (mc_fftsize_good(g->nx < 2 ? 2 : g->nx) + 1.0) *
                        (mc_fftsize_good(g->ny < 2 ? 2 : g->ny) + 1.0) * 8;
    const double half = (tx / 2 + 1) * ty * 16, compact = (tx / 2 + 1) * (ty / 2 + 1) * 8;
    return MC_NSTRESS * (!px && !py ? quad : mc_dist_active() ? half : compact);
}

int mc_stress_create_tuned(const mc_grid *g, const mc_stress_options *opt,
                           const mc_stress_tuning *tune, mc_stress_plan **out, mc_error *err)
{
    *out = NULL;
    const mc_stress_tuning automatic = {MC_STRESS_AUTO, MC_STRESS_AUTO, MC_STRESS_AUTO};
    if (!tune)
        tune = &automatic;
    int rc = mc_grid_check(g, err);
    if (rc || (rc = check_options(opt, tune, err)))
        return rc;
    if (mc_grid_cells(g) > (size_t)INT_MAX) /* the loaded cells are listed as int */
        return mc_fail(err, MC_ERR_LIMIT, "stress: %d x %d cells exceed the %d the plan handles",
                       g->nx, g->ny, INT_MAX);
    mc_stress_plan *plan = mc_calloc(1, sizeof *plan);
    if (!plan)
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    plan->g = *g;
    plan->kernel = opt->kernel;
    plan->nlayers = opt->nlayers;
    plan->loads = opt->loads;
    plan->tune = *tune;
    if (!(plan->depths = mc_malloc(sizeof *plan->depths * (size_t)opt->nlayers)) ||
        !(plan->cells = mc_malloc(sizeof *plan->cells * mc_grid_cells(g)))) {
        mc_stress_destroy(&plan);
        return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory");
    }
    memcpy(plan->depths, opt->depths, sizeof *plan->depths * (size_t)opt->nlayers);
    size_t klen, llen;
    if ((rc = create_engine(plan, opt->backend, opt, &klen, &llen, err))) {
        mc_stress_destroy(&plan);
        return rc;
    }
    int nl = 0;
    for (int li = 0; li < NLOADS; li++)
        nl += (opt->loads >> li) & 1;
    size_t per, nspec;
    if (!mc_size_mul(klen, MC_NSTRESS, &per) || (per += llen) < llen ||
        !mc_size_mul(per, (size_t)nl, &nspec) ||
        !(plan->spectra = mc_malloc(sizeof *plan->spectra * nspec))) {
        mc_stress_destroy(&plan);
        return mc_fail(err, MC_ERR_NOMEM,
                       "stress: out of memory for the spectra of a %d x %d grid (%d loads)",
                       g->nx, g->ny, nl);
    }
    double *sp = plan->spectra;
    for (int li = 0; li < NLOADS; li++) {
        if (!((opt->loads >> li) & 1))
            continue;
        for (int c = 0; c < MC_NSTRESS; c++, sp += klen)
            plan->kspec[li][c] = sp;
        plan->lspec[li] = sp;
        sp += llen;
    }
    /* the spectra cache (see the struct), where it fits; without it the tables are rebuilt */
    for (int li = 0; li < NLOADS; li++)
        plan->slot[li] = ((opt->loads >> li) & 1) ? plan->nslots++ : -1;
    plan->ck0 = 0;
    plan->cnk = opt->nlayers;
    if (opt->repeated && mc_dist_active())
        mc_dist_share(opt->nlayers, &plan->ck0, &plan->cnk);
    /* the general engine's spectra by their parity (one process, fft backend): a quarter */
    int r0, nr;
    plan->compact = !plan->sym && mc_conv_backend(plan->conv) == MC_BACKEND_FFT &&
                    !mc_conv_rows(plan->conv, &r0, &nr);
    const size_t kcache_len = plan->compact ? compact_len(plan) : klen;
    const size_t ncache = (size_t)plan->cnk * plan->nslots * MC_NSTRESS * kcache_len;
    if ((opt->repeated || g->periodic_x || g->periodic_y) &&
        ncache <= MC_STRESS_CACHE_BYTES / sizeof(double)) {
        plan->kcache = mc_malloc(ncache * sizeof *plan->kcache);
        plan->kcached = mc_calloc((size_t)plan->cnk * plan->nslots + 1, 1);
        plan->klen = kcache_len;
        if (!plan->kcache || !plan->kcached) {
            mc_stress_destroy(&plan);
            return mc_fail(err, MC_ERR_NOMEM, "stress: out of memory for the kernel spectra of "
                           "%d layers", opt->nlayers);
        }
    }
    *out = plan;
    return MC_OK;
}

int mc_stress_create(const mc_grid *g, const mc_stress_options *opt, mc_stress_plan **out,
                     mc_error *err)
{
    return mc_stress_create_tuned(g, opt, NULL, out, err);
}

void mc_stress_cost(const mc_stress_plan *plan, long nloaded, int nterms, double *full_s,
                    double *sparse_s)
{
    const double n = (double)mc_grid_cells(&plan->g), pad = (double)plan->tx * (double)plan->ty;
    const double half = (double)plan->ty * (double)(plan->tx / 2 + 1);
    *sparse_s = COST_MADD * MC_NSTRESS * (double)nterms * (double)nloaded * n;
    if (plan->conv && mc_conv_backend(plan->conv) == MC_BACKEND_DIRECT) {
        *full_s = COST_MADD * MC_NSTRESS * (double)nterms * n * n; /* the dense sum */
        return;
    }
    /* pruned transforms: columns in full, rows only where the field lives (half the rows) */
    const double inv = COST_FFT * 0.75 * pad * log2(pad);
    double kern;
    if (plan->sym) {
        const double q = (double)plan->qx * (double)plan->qy;
        kern = COST_R2R * q * log2(q);
    } else {
        kern = COST_FULL_KERNEL * COST_FFT * pad * log2(pad);
    }
    *full_s = MC_NSTRESS * (nterms * kern + inv + COST_PRODUCT * nterms * half) +
             nterms * inv / plan->nlayers;
}

/* The given loads: fills li[] with the indices of the non-NULL loads; checks they are announced. */
static int given_loads(const mc_stress_plan *plan, const double *const loads[NLOADS],
                       int li[NLOADS], int *ng, mc_error *err)
{
    static const char *names[NLOADS] = {"p", "q_x", "q_y"};
    *ng = 0;
    for (int l = 0; l < NLOADS; l++) {
        if (!loads[l])
            continue;
        if (!((plan->loads >> l) & 1))
            return mc_fail(err, MC_ERR_INPUT,
                           "stress: load %s given but not announced in the options (loads = %d)",
                           names[l], plan->loads);
        li[(*ng)++] = l;
    }
    return MC_OK;
}

/* Once per call: the loaded cells, the choice of the sparse sum, and (if not) the load spectra. */
static void prepare_loads(mc_stress_plan *plan, const double *const loads[NLOADS], const int li[],
                          int ng)
{
    const double t0 = omp_get_wtime();
    const size_t n = mc_grid_cells(&plan->g);
    long nc = 0;
    for (size_t i = 0; i < n; i++) {
        int any = 0;
        for (int t = 0; t < ng; t++)
            any |= loads[li[t]][i] != 0.0;
        if (any)
            plan->cells[nc++] = (int)i;
    }
    plan->ncells = nc;
    if (plan->tune.sparse == MC_STRESS_AUTO) {
        double full_s, sparse_s;
        mc_stress_cost(plan, nc, ng, &full_s, &sparse_s);
        plan->sparse = sparse_s < full_s;
    } else {
        plan->sparse = plan->tune.sparse == MC_STRESS_ON;
    }
    if (!plan->sparse)
        for (int i = 0; i < ng; i++) {
            if (plan->sym)
                mc_stress_sym_load(plan->sym, loads[li[i]], plan->lspec[li[i]]);
            else
                mc_conv_load(plan->conv, loads[li[i]], plan->lspec[li[i]]);
        }
    plan->timing.loads += omp_get_wtime() - t0;
}

static const int load_bit[NLOADS] = {MC_TRACTION_P, MC_TRACTION_QX, MC_TRACTION_QY};

/* The six tables of load li at depth z into the plan's kernel arrays of that load (quadrants on the
 * symmetric path, full tables otherwise; for the transform path of the general engine into the
 * shared table arrays, transformed after). */
static int build_tables(mc_stress_plan *plan, int li, double z, double *const *into,
                        mc_error *err)
{
    double *const *dst = plan->sym || plan->sparse ? (into ? into : plan->kspec[li]) : NULL;
    double *const full[MC_NSTRESS] = {plan->tab[0].k, plan->tab[1].k, plan->tab[2].k,
                                      plan->tab[3].k, plan->tab[4].k, plan->tab[5].k};
    if (plan->sym)
        return mc_stress_tables_quadrant(plan->tb, load_bit[li], z, plan->qx, plan->qy, dst, err);
    return mc_stress_tables_build(plan->tb, load_bit[li], z, dst ? dst : full, err);
}

/* The kernel arrays of layer k for the prepared loads li[0..ng-1] into kuse (built, or taken
 * from the cache). */
static int layer_kernels(mc_stress_plan *plan, int k, const int li[], int ng,
                         double *kuse[NLOADS][MC_NSTRESS], mc_error *err)
{
    for (int i = 0; i < ng; i++) {
        const int ck = k - plan->ck0; /* the layer's place in the cache */
        const int cache = plan->kcache && !plan->sparse && ck >= 0 && ck < plan->cnk;
        double *kept[MC_NSTRESS]; /* the cached arrays (compact: not the ones used) */
        for (int c = 0; c < MC_NSTRESS; c++) {
            kept[c] = cache ? plan->kcache + (((size_t)ck * plan->nslots + plan->slot[li[i]]) *
                                                  MC_NSTRESS + c) * plan->klen
                            : NULL;
            kuse[i][c] = cache && !plan->compact ? kept[c] : plan->kspec[li[i]][c];
        }
        if (cache && plan->kcached[(size_t)ck * plan->nslots + plan->slot[li[i]]]) {
            for (int c = 0; c < MC_NSTRESS && plan->compact; c++)
                expand_spectrum(plan, mc_stress_parity(load_bit[li[i]], c), kept[c], kuse[i][c]);
            continue;
        }
        const double t0 = omp_get_wtime();
        /* the symmetric engine transforms its quadrants in place: straight into the cache */
        int rc = build_tables(plan, li[i], plan->depths[k], cache && plan->sym ? kuse[i] : NULL,
                              err);
        const double t1 = omp_get_wtime();
        plan->timing.tables += t1 - t0;
        if (rc)
            return rc;
        if (plan->sparse)
            continue;
        if (plan->sym) {
            int par[MC_NSTRESS];
            for (int c = 0; c < MC_NSTRESS; c++)
                par[c] = mc_stress_parity(load_bit[li[i]], c);
            mc_stress_sym_kernels(plan->sym, MC_NSTRESS, par, kuse[i]);
        }
        for (int c = 0; c < MC_NSTRESS && rc == MC_OK && !plan->sym; c++)
            rc = mc_conv_kernel(plan->conv, &plan->tab[c], kuse[i][c], err);
        plan->timing.kernels += omp_get_wtime() - t1;
        if (rc)
            return rc;
        for (int c = 0; c < MC_NSTRESS && cache && plan->compact; c++) {
            /* kept compact, and used as kept: the first use gives the later ones' bits */
            const int par = mc_stress_parity(load_bit[li[i]], c);
            compact_spectrum(plan, par, kuse[i][c], kept[c]);
            expand_spectrum(plan, par, kept[c], kuse[i][c]);
        }
        if (cache)
            plan->kcached[(size_t)ck * plan->nslots + plan->slot[li[i]]] = 1;
    }
    return MC_OK;
}

/* Component c's terms of the loads li[0..ng-1]: their kernel arrays (of layer_kernels), load
 * spectra and parities */
static void component_terms(const mc_stress_plan *plan, double *kuse[NLOADS][MC_NSTRESS],
                            const int li[], int ng, int c, const double *ks[NLOADS],
                            const double *ls[NLOADS], int par[NLOADS])
{
    for (int i = 0; i < ng; i++) {
        ks[i] = kuse[i][c];
        ls[i] = plan->lspec[li[i]];
        par[i] = mc_stress_parity(load_bit[li[i]], c);
    }
}

/* Layer k from the prepared loads li[0..ng-1] into out[c] (ny*nx each), or (spec given: the
 * symmetric engine, not sparse) its spectra added to spec[c] (mc_stress_add_spectra). */
static int layer_out(mc_stress_plan *plan, int k, const double *const loads[NLOADS],
                     const int li[], int ng, double *const out[6], double *const spec[6],
                     mc_error *err)
{
    double *kuse[NLOADS][MC_NSTRESS]; /* the kernel arrays of this layer, per load */
    int rc = layer_kernels(plan, k, li, ng, kuse, err);
    if (rc)
        return rc;
    const double t0 = omp_get_wtime();
    for (int c = 0; c < MC_NSTRESS; c++) {
        const double *ks[NLOADS], *ls[NLOADS];
        int par[NLOADS];
        mc_stress_term terms[NLOADS];
        component_terms(plan, kuse, li, ng, c, ks, ls, par);
        for (int i = 0; i < ng; i++)
            terms[i] = (mc_stress_term){loads[li[i]], plan->sym ? ks[i] : NULL, plan->qx, par[i],
                                        plan->sym ? NULL : ks[i], plan->tx, plan->ty};
        if (spec)
            mc_stress_sym_product_add(plan->sym, ng, ks, par, ls, spec[c]);
        else if (plan->sparse)
            mc_stress_sparse_sum(&plan->g, (int)plan->ncells, plan->cells, ng, terms, out[c]);
        else if (plan->sym)
            mc_stress_sym_apply(plan->sym, ng, ks, par, ls, out[c]);
        else
            mc_conv_apply(plan->conv, ng, ks, ls, out[c]);
    }
    plan->timing.apply += omp_get_wtime() - t0;
    plan->timing.layers++;
    plan->timing.sparse_layers += plan->sparse;
    return MC_OK;
}

static int check_outputs(double *const s[6], mc_error *err)
{
    for (int c = 0; c < MC_NSTRESS; c++)
        if (!s || !s[c])
            return mc_fail(err, MC_ERR_INPUT, "stress: output array for component %s is NULL",
                           mc_component_name(c));
    return MC_OK;
}

/* Layers k0 .. k0 + nk - 1 of the field of the loads into s (mc_stress_field's contract). */
static int field_block(mc_stress_plan *plan, const double *const loads[NLOADS], int k0, int nk,
                       double *const s[6], mc_error *err)
{
    int li[NLOADS], ng;
    int rc = check_outputs(s, err);
    if (rc || (rc = given_loads(plan, loads, li, &ng, err)))
        return rc;
    const size_t n = mc_grid_cells(&plan->g);
    if (ng == 0) { /* no load, no stress */
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(s[c] + (size_t)k0 * n, 0, sizeof(double) * n * (size_t)nk);
        return MC_OK;
    }
    prepare_loads(plan, loads, li, ng);
    for (int k = k0; k < k0 + nk; k++) {
        double *const out[MC_NSTRESS] = {s[0] + k * n, s[1] + k * n, s[2] + k * n,
                                         s[3] + k * n, s[4] + k * n, s[5] + k * n};
        if ((rc = layer_out(plan, k, loads, li, ng, out, NULL, err)))
            return rc;
    }
    return MC_OK;
}

int mc_stress_field(mc_stress_plan *plan, const double *p, const double *qx, const double *qy,
                    double *const s[6], mc_error *err)
{
    const double *const loads[NLOADS] = {p, qx, qy};
    return field_block(plan, loads, 0, plan->nlayers, s, err);
}

int mc_stress_field_layers(mc_stress_plan *plan, const double *p, const double *qx,
                           const double *qy, double *const s[6],
                           int (*visit)(void *ctx, int k, double *const s[6]), void *ctx,
                           mc_error *err)
{
    const double *const loads[NLOADS] = {p, qx, qy};
    int li[NLOADS], ng;
    int rc = check_outputs(s, err);
    if (rc || (rc = given_loads(plan, loads, li, &ng, err)))
        return rc;
    if (ng > 0)
        prepare_loads(plan, loads, li, ng);
    for (int k = 0; k < plan->nlayers; k++) {
        if (ng == 0) /* no load, no stress */
            for (int c = 0; c < MC_NSTRESS; c++)
                memset(s[c], 0, sizeof(double) * mc_grid_cells(&plan->g));
        else if ((rc = layer_out(plan, k, loads, li, ng, s, NULL, err)))
            return rc;
        if ((rc = visit(ctx, k, s)))
            return rc;
    }
    return MC_OK;
}

/* Layers split over the ranks in contiguous blocks (mc_dist_share), not rows of x: the plan's
 * transforms are whole-grid ones (operator.h's engine or the symmetric one), so a layer is one
 * rank's work without any exchange, and its bits are those of mc_stress_field whichever rank
 * computes it (the same plan, the same loads, compute_layer). Every layer costs the same (the
 * table build, 6 kernel and 6 inverse transforms, or the same sparse sum), so the blocks balance
 * to within one layer. The load transforms (one per load) are repeated on every rank. The
 * exchange: each rank receives the other ranks' layers, (P - 1) / P x 6 nlayers N doubles
 * (48 bytes per volume cell at most), in one gather per component. */
int mc_stress_field_split(mc_stress_plan *plan, const double *p, const double *qx,
                          const double *qy, double *const s[6], mc_error *err)
{
    if (!mc_dist_active())
        return mc_stress_field(plan, p, qx, qy, s, err);
    const double *const loads[NLOADS] = {p, qx, qy};
    int k0, nk;
    const size_t n = mc_grid_cells(&plan->g);
    mc_dist_share(plan->nlayers, &k0, &nk);
    const int rc = field_block(plan, loads, k0, nk, s, err);
    /* every rank goes on to the gather only if all succeeded (a collective call skipped by one
     * rank would hang the others) */
    const int any = mc_dist_max_int(rc);
    if (any != MC_OK)
        return rc != MC_OK ? rc
                           : mc_fail(err, (mc_status)any,
                                     "stress: another MPI process failed (status %d)", any);
    for (int c = 0; c < MC_NSTRESS; c++)
        if (!mc_dist_gather_rows(s[c], k0, nk, (int)n))
            return mc_fail(err, MC_ERR_LIMIT,
                           "stress: %d layers of %zu cells exceed MPI's int counts",
                           plan->nlayers, n);
    return MC_OK;
}

int mc_stress_layer(mc_stress_plan *plan, int k, const double *p, const double *qx,
                    const double *qy, double *const s[6], mc_error *err)
{
    if (k < 0 || k >= plan->nlayers)
        return mc_fail(err, MC_ERR_INPUT, "stress: layer %d out of range 0..%d", k,
                       plan->nlayers - 1);
    const double *const loads[NLOADS] = {p, qx, qy};
    int li[NLOADS], ng;
    int rc = check_outputs(s, err);
    if (rc || (rc = given_loads(plan, loads, li, &ng, err)))
        return rc;
    if (ng == 0) {
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(s[c], 0, sizeof(double) * mc_grid_cells(&plan->g));
        return MC_OK;
    }
    prepare_loads(plan, loads, li, ng);
    return layer_out(plan, k, loads, li, ng, s, NULL, err);
}

void mc_stress_timing_get(const mc_stress_plan *plan, mc_stress_timing *t) { *t = plan->timing; }

int mc_stress_prepare(mc_stress_plan *plan, const double *p, const double *qx, const double *qy,
                      mc_error *err)
{
    const double *const loads[NLOADS] = {p, qx, qy};
    int rc = given_loads(plan, loads, plan->li, &plan->ng, err);
    if (rc) {
        plan->ng = 0;
        return rc;
    }
    for (int l = 0; l < NLOADS; l++)
        plan->cur[l] = loads[l];
    plan->sparse = 1;
    plan->ncells = 0;
    if (plan->ng > 0)
        prepare_loads(plan, loads, plan->li, plan->ng);
    return MC_OK;
}

int mc_stress_compute(mc_stress_plan *plan, int k, double *const s[6], mc_error *err)
{
    if (k < 0 || k >= plan->nlayers)
        return mc_fail(err, MC_ERR_INPUT, "stress: layer %d out of range 0..%d", k,
                       plan->nlayers - 1);
    int rc = check_outputs(s, err);
    if (rc)
        return rc;
    if (plan->ng == 0) {
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(s[c], 0, sizeof(double) * mc_grid_cells(&plan->g));
        return MC_OK;
    }
    return layer_out(plan, k, plan->cur, plan->li, plan->ng, s, NULL, err);
}

int mc_stress_is_sparse(const mc_stress_plan *plan) { return plan->sparse; }

int mc_stress_spectra_size(const mc_stress_plan *plan, int *tx, int *ty)
{
    if (!plan->sym || plan->sparse || plan->ng == 0)
        return 0;
    mc_stress_sym_transform(plan->sym, tx, ty);
    return 1;
}

int mc_stress_add_spectra(mc_stress_plan *plan, int k, double *const spec[6], mc_error *err)
{
    int tx, ty;
    if (k < 0 || k >= plan->nlayers || !mc_stress_spectra_size(plan, &tx, &ty))
        return mc_fail(err, MC_ERR_INPUT, "stress: no spectra of layer %d (prepared loads on the "
                       "symmetric engine, not summed cell by cell, are needed)", k);
    return layer_out(plan, k, plan->cur, plan->li, plan->ng, NULL, spec, err);
}
