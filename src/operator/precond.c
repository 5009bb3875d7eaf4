/* precond.c - FFT-based preconditioner for the contact solvers (see precond.h). */
#include "operator/precond.h"

#include <fftw3.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "operator/box.h"
#include "operator/operator.h"

#define PLAN_CACHE 6
#define BOX_MARGIN 2 /* cells at least, each side */

typedef struct {
    int fx, fy;           /* transform size */
    fftw_plan fwd, inv;   /* r2c / c2r on the shared buffers */
    double *symbol;       /* fy * (fx/2+1) multipliers, including 1/(fx*fy) */
} box_plan;

struct mc_precond {
    mc_grid g;
    mc_box box;           /* the current box */
    box_plan *cur;
    box_plan cache[PLAN_CACHE];
    int ncached, next_evict;
    double *real;         /* max fx * max fy */
    fftw_complex *spec;   /* max fy * (max fx/2+1) */
};

static int axis_fft_max(int n, int periodic) { return periodic ? n : mc_fftsize_good(n); }

int mc_precond_create(const mc_grid *g, mc_precond **out, mc_error *err)
{
    *out = NULL;
    mc_precond *pc = mc_calloc(1, sizeof *pc);
    if (!pc)
        return mc_fail(err, MC_ERR_NOMEM, "preconditioner: out of memory");
    pc->g = *g;
    int mx = axis_fft_max(g->nx, g->periodic_x), my = axis_fft_max(g->ny, g->periodic_y);
    pc->real = mc_malloc(sizeof(double) * (size_t)mx * (size_t)my);
    pc->spec = mc_malloc(sizeof(fftw_complex) * (size_t)my * (size_t)(mx / 2 + 1));
    if (!pc->real || !pc->spec) {
        mc_precond_destroy(&pc);
        return mc_fail(err, MC_ERR_NOMEM, "preconditioner: out of memory for %d x %d buffers", mx,
                       my);
    }
    *out = pc;
    return MC_OK;
}

static void free_plan(box_plan *b)
{
    if (b->fwd)
        fftw_destroy_plan(b->fwd);
    if (b->inv)
        fftw_destroy_plan(b->inv);
    mc_free(b->symbol);
    memset(b, 0, sizeof *b);
}

void mc_precond_destroy(mc_precond **pcp)
{
    if (!pcp || !*pcp)
        return;
    mc_precond *pc = *pcp;
    for (int k = 0; k < pc->ncached; k++)
        free_plan(&pc->cache[k]);
    mc_free(pc->real);
    mc_free(pc->spec);
    mc_free(pc);
    *pcp = NULL;
}

/* |q| on the periodic box: the inverse of the continuum Love symbol 2/(E*|q|) up to E* / 2.
 * The mean mode gets half the lowest non-zero wavenumber, so the operator stays definite under
 * approach control (under load control the mean is projected out anyway). */
static void fill_symbol(box_plan *b, double dx, double dy)
{
    int hx = b->fx / 2 + 1;
    double Lx = b->fx * dx, Ly = b->fy * dy;
    double scale = 1.0 / ((double)b->fx * (double)b->fy);
    double qmin = 2.0 * M_PI / (Lx > Ly ? Lx : Ly);
    for (int ky = 0; ky < b->fy; ky++) {
        int my = ky <= b->fy / 2 ? ky : ky - b->fy;
        double qy = 2.0 * M_PI * my / Ly;
        for (int kx = 0; kx < hx; kx++) {
            double qx = 2.0 * M_PI * kx / Lx;
            double q = sqrt(qx * qx + qy * qy);
            b->symbol[(size_t)ky * hx + kx] = (kx == 0 && my == 0 ? 0.5 * qmin : q) * scale;
        }
    }
}

static box_plan *plan_for(mc_precond *pc, int fx, int fy, mc_error *err)
{
    for (int k = 0; k < pc->ncached; k++)
        if (pc->cache[k].fx == fx && pc->cache[k].fy == fy)
            return &pc->cache[k];
    box_plan *b;
    int fresh_slot = pc->ncached < PLAN_CACHE;
    if (fresh_slot) {
        b = &pc->cache[pc->ncached++];
    } else {
        b = &pc->cache[pc->next_evict];
        pc->next_evict = (pc->next_evict + 1) % PLAN_CACHE;
        if (b == pc->cur)
            pc->cur = NULL;
        free_plan(b);
    }
    b->fx = fx;
    b->fy = fy;
    b->symbol = mc_malloc(sizeof(double) * (size_t)fy * (size_t)(fx / 2 + 1));
    if (mc_fftw_prepare(err) != MC_OK) {
        free_plan(b);
        if (fresh_slot)
            pc->ncached--;
        return NULL;
    }
    if ((size_t)fx * fy < MC_THREADS_MIN_CELLS)
        fftw_plan_with_nthreads(1);
    /* repeated: [solver] plans (operator.h); real and spec are scratch, filled after planning */
    b->fwd = fftw_plan_dft_r2c_2d(fy, fx, pc->real, pc->spec, mc_fft_plan_flags());
    b->inv = fftw_plan_dft_c2r_2d(fy, fx, pc->spec, pc->real, mc_fft_plan_flags());
    if (!b->symbol || !b->fwd || !b->inv) {
        free_plan(b); /* an evicted slot stays in the cache as an empty (0 x 0) entry */
        if (fresh_slot)
            pc->ncached--;
        mc_fail(err, MC_ERR_NOMEM, "preconditioner: cannot plan a %d x %d transform", fx, fy);
        return NULL;
    }
    fill_symbol(b, pc->g.dx, pc->g.dy);
    return b;
}

/* Transform length along an axis for a box of len cells: the box's own length on a periodic axis
 * (where the box is the whole axis), else a 7-smooth length >= len, capped at the grid's own. */
static int box_fft_len(int len, int n, int periodic)
{
    if (periodic)
        return n;
    const int f = mc_fftsize_good(len), fmax_ = mc_fftsize_good(n);
    return f > fmax_ ? fmax_ : f;
}

int mc_precond_set_mask(mc_precond *pc, const unsigned char *mask, mc_error *err)
{
    mc_box b;
    if (!mc_box_bound(&pc->g, mask, NULL, &b))
        b = (mc_box){0, 0, 1, 1}; /* empty set: any box works, apply returns zeros */
    /* the margin keeps the periodic wrap of the box from coupling opposite edges of the contact
     * strongly */
    mc_box_widen(&pc->g, mc_box_margin(b.nx, BOX_MARGIN), mc_box_margin(b.ny, BOX_MARGIN), &b);
    const int fx = box_fft_len(b.nx, pc->g.nx, pc->g.periodic_x);
    const int fy = box_fft_len(b.ny, pc->g.ny, pc->g.periodic_y);
    box_plan *p = plan_for(pc, fx, fy, err);
    if (!p)
        return err ? err->code : MC_ERR_NOMEM;
    pc->box = b;
    pc->cur = p;
    return MC_OK;
}

/* The O(N) loops run on the run's threads from this many cells on (core/threads.h). */
#define PAR(n) ((size_t)(n) > MC_THREADS_MIN_CELLS)

void mc_precond_apply(mc_precond *pc, const unsigned char *mask, const double *r, double *z)
{
    mc_precond_apply_rows(pc, mask, r, z, 0, pc->g.ny);
}

void mc_precond_apply_rows(mc_precond *pc, const unsigned char *mask, const double *r, double *z,
                           int r0, int nr)
{
    const int nx = pc->g.nx;
    const box_plan *p = pc->cur;
    const int fx = p->fx, fy = p->fy, hx = fx / 2 + 1;
    const mc_box *box = &pc->box;
    const int par = PAR((size_t)fx * (size_t)fy);
#pragma omp parallel for schedule(static) if (par)
    for (int j = 0; j < fy; j++) {
        double *dst = pc->real + (size_t)j * fx;
        if (j >= box->ny) {
            memset(dst, 0, sizeof(double) * (size_t)fx);
            continue;
        }
        size_t src = (size_t)(box->j0 + j) * nx + (size_t)box->i0;
        for (int i = 0; i < box->nx; i++)
            dst[i] = mask[src + i] ? r[src + i] : 0.0;
        for (int i = box->nx; i < fx; i++)
            dst[i] = 0.0;
    }
    fftw_execute(p->fwd);
    const long nspec = (long)fy * hx;
#pragma omp parallel for schedule(static) if (par)
    for (long k = 0; k < nspec; k++) {
        pc->spec[k][0] *= p->symbol[k];
        pc->spec[k][1] *= p->symbol[k];
    }
    fftw_execute(p->inv);
#pragma omp parallel for schedule(static) if (par)
    for (int j = r0; j < r0 + nr; j++) {
        double *zr = z + (size_t)(j - r0) * nx;
        const int jb = j - box->j0;
        if (jb < 0 || jb >= box->ny) {
            memset(zr, 0, sizeof(double) * (size_t)nx);
            continue;
        }
        const double *src = pc->real + (size_t)jb * fx;
        const unsigned char *mr = mask + (size_t)j * nx;
        for (int i = 0; i < nx; i++) {
            const int ib = i - box->i0;
            zr[i] = ib >= 0 && ib < box->nx && mr[i] ? src[ib] : 0.0;
        }
    }
}
