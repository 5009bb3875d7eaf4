/* precond.c - FFT-based preconditioner for the contact solvers (see precond.h). */
#include "operator/precond.h"

#include <fftw3.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "operator/box.h"
#include "operator/dfft.h"
#include "operator/operator.h"

#define PLAN_CACHE 6
/* Distributed, each cached size holds its own transform engine and buffers (about 52 bytes per
 * box cell over P, against the 4 of a serial entry's symbol): one size is kept (a solve's box
 * changes size about once per grid level: 9 engines made in the Hertz run at 1024^2 with 1 or 2
 * kept alike). */
#define PLAN_CACHE_DIST 1
#define BOX_MARGIN 2 /* cells at least, each side */

typedef struct {
    int fx, fy;           /* transform size */
    fftw_plan fwd, inv;   /* r2c / c2r on the shared buffers */
    double *symbol;       /* fy * (fx/2+1) multipliers, including 1/(fx*fy); distributed: this
                           * rank's columns of the spectrum, nk * fy ([kx - k0][ky], dfft.h) */
    mc_dfft *d;           /* distributed: the box's fx x fy transform over the ranks */
    int rb0, nrb;         /* distributed: the box rows rb0 .. rb0 + nrb - 1 the transform gives
                           * this rank (of fy) */
    int *rball;           /* distributed: every rank's rb0, nrb (2 per rank) */
    double *field;        /* distributed: those rows, nrb * fx */
} box_plan;

struct mc_precond {
    mc_grid g;
    mc_box box;           /* the current box */
    box_plan *cur;
    box_plan cache[PLAN_CACHE];
    int ncached, next_evict, maxcache;
    double *real;         /* max fx * max fy (serial only) */
    fftw_complex *spec;   /* max fy * (max fx/2+1) (serial only) */
    /* distributed (mc_precond_create_rows under a communicator): mask, r and z are this rank's
     * grid rows r0 .. r0 + nr - 1 (the contact solver's slab); the box's rows travel to the
     * transform's rows and back by all-to-all exchanges, nothing is gathered whole */
    int dist, r0, nr, np;
    int *grows;           /* every rank's r0, nr (2 per rank) */
    double *send;         /* this rank's box rows, packed: at most nr * nx */
    int *sc, *sd, *rc, *rd; /* the exchange's counts and offsets per rank (doubles), rows to the
                             * transform (sc, sd out; rc, rd in); the way back swaps them */
};

static int axis_fft_max(int n, int periodic) { return periodic ? n : mc_fftsize_good(n); }

int mc_precond_create(const mc_grid *g, mc_precond **out, mc_error *err)
{
    *out = NULL;
    mc_precond *pc = mc_calloc(1, sizeof *pc);
    if (!pc)
        return mc_fail(err, MC_ERR_NOMEM, "preconditioner: out of memory");
    pc->g = *g;
    pc->maxcache = PLAN_CACHE;
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
    mc_dfft_destroy(&b->d);
    mc_free(b->rball);
    mc_free(b->field);
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
    mc_free(pc->grows);
    mc_free(pc->send);
    mc_free(pc->sc);
    mc_free(pc->sd);
    mc_free(pc->rc);
    mc_free(pc->rd);
    mc_free(pc);
    *pcp = NULL;
}

/* |q| on the periodic box: the inverse of the continuum Love symbol 2/(E*|q|) up to E* / 2.
 * The mean mode gets half the lowest non-zero wavenumber, so the operator stays definite under
 * approach control (under load control the mean is projected out anyway). */
static double symbol_at(const box_plan *b, double dx, double dy, int kx, int ky)
{
    double Lx = b->fx * dx, Ly = b->fy * dy;
    double scale = 1.0 / ((double)b->fx * (double)b->fy);
    double qmin = 2.0 * M_PI / (Lx > Ly ? Lx : Ly);
    int my = ky <= b->fy / 2 ? ky : ky - b->fy;
    double qy = 2.0 * M_PI * my / Ly;
    double qx = 2.0 * M_PI * kx / Lx;
    double q = sqrt(qx * qx + qy * qy);
    return (kx == 0 && my == 0 ? 0.5 * qmin : q) * scale;
}

/* Serially the whole half spectrum [ky][kx]; distributed this rank's columns kx = k0 .. k0 + nk
 * - 1, [kx - k0][ky] (the same values: one formula). */
static void fill_symbol(box_plan *b, double dx, double dy, int k0, int nk)
{
    if (b->d) {
        for (int k = 0; k < nk; k++)
            for (int ky = 0; ky < b->fy; ky++)
                b->symbol[(size_t)k * b->fy + ky] = symbol_at(b, dx, dy, k0 + k, ky);
        return;
    }
    int hx = b->fx / 2 + 1;
    for (int ky = 0; ky < b->fy; ky++)
        for (int kx = 0; kx < hx; kx++)
            b->symbol[(size_t)ky * hx + kx] = symbol_at(b, dx, dy, kx, ky);
}

#ifdef MC_MPI
/* The distributed transform of an fx x fy box (the ranks' rows of it, its symbol columns). */
static int plan_dist(mc_precond *pc, box_plan *b, mc_error *err)
{
    int rc = mc_dfft_create(b->fx, b->fy, b->fx, b->fy, &b->d, err);
    if (rc != MC_OK)
        return rc;
    int k0, nk;
    mc_dfft_columns(b->d, &k0, &nk);
    mc_dfft_rows(b->d, &b->rb0, &b->nrb);
    const size_t nf = (size_t)b->nrb * (size_t)b->fx;
    b->symbol = mc_malloc(sizeof(double) * ((size_t)nk * (size_t)b->fy + 1));
    b->rball = mc_malloc(2 * sizeof(int) * (size_t)pc->np);
    b->field = mc_malloc(sizeof(double) * (nf + 1));
    if (mc_dist_max_int(!b->symbol || !b->rball || !b->field))
        return mc_fail(err, MC_ERR_NOMEM, "preconditioner: out of memory for a %d x %d box", b->fx,
                       b->fy);
    int mine[2] = {b->rb0, b->nrb};
    const mc_dist_mark t0 = mc_dist_comm_begin();
    MPI_Allgather(mine, 2, MPI_INT, b->rball, 2, MPI_INT, mc_dist_comm());
    mc_dist_comm_end(t0);
    fill_symbol(b, pc->g.dx, pc->g.dy, k0, nk);
    return MC_OK;
}
#endif


static box_plan *plan_for(mc_precond *pc, int fx, int fy, mc_error *err)
{
    for (int k = 0; k < pc->ncached; k++)
        if (pc->cache[k].fx == fx && pc->cache[k].fy == fy)
            return &pc->cache[k];
    box_plan *b;
    int fresh_slot = pc->ncached < pc->maxcache;
    if (fresh_slot) {
        b = &pc->cache[pc->ncached++];
    } else {
        b = &pc->cache[pc->next_evict];
        pc->next_evict = (pc->next_evict + 1) % pc->maxcache;
        if (b == pc->cur)
            pc->cur = NULL;
        free_plan(b);
    }
    b->fx = fx;
    b->fy = fy;
#ifdef MC_MPI
    if (pc->dist) {
        if (plan_dist(pc, b, err) != MC_OK) {
            free_plan(b);
            if (fresh_slot)
                pc->ncached--;
            return NULL;
        }
        return b;
    }
#endif
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
    fill_symbol(b, pc->g.dx, pc->g.dy, 0, 0);
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

/* The box of the bound b (empty: ok = 0), widened, its transform size planned. */
static int set_box(mc_precond *pc, int ok, mc_box b, mc_error *err)
{
    if (!ok)
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

int mc_precond_set_mask(mc_precond *pc, const unsigned char *mask, mc_error *err)
{
    mc_box b;
    const int ok = mc_box_bound(&pc->g, mask, NULL, &b);
    return set_box(pc, ok, b, err);
}

/* The O(N) loops run on the run's threads from this many cells on (core/threads.h; element by
 * element, so the same bits on any thread count). */
#define PAR(n) ((size_t)(n) > MC_THREADS_MIN_LOOP)

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

/* ---- distributed: the box's transform over the ranks ----------------------------------------- */

int mc_precond_create_rows(const mc_grid *g, int r0, int nr, mc_precond **out, mc_error *err)
{
#ifdef MC_MPI
    if (mc_dist_active()) {
        *out = NULL;
        mc_precond *pc = mc_calloc(1, sizeof *pc);
        if (!pc)
            return mc_fail(err, MC_ERR_NOMEM, "preconditioner: out of memory");
        pc->g = *g;
        pc->maxcache = PLAN_CACHE_DIST;
        pc->dist = 1;
        pc->r0 = r0;
        pc->nr = nr;
        pc->np = mc_dist_size();
        const size_t np = (size_t)pc->np;
        pc->grows = mc_malloc(2 * np * sizeof *pc->grows);
            pc->send = mc_malloc(sizeof(double) * ((size_t)nr * (size_t)g->nx + 1));
        pc->sc = mc_calloc(np, sizeof *pc->sc);
        pc->sd = mc_calloc(np, sizeof *pc->sd);
        pc->rc = mc_calloc(np, sizeof *pc->rc);
        pc->rd = mc_calloc(np, sizeof *pc->rd);
        const int ok = pc->grows && pc->send && pc->sc && pc->sd && pc->rc && pc->rd;
        if (mc_dist_max_int(!ok)) { /* on any rank: all fail alike, before the gather */
            mc_precond_destroy(&pc);
            return mc_fail(err, MC_ERR_NOMEM, "preconditioner: out of memory for %d rows", nr);
        }
        int mine[2] = {r0, nr};
        MPI_Allgather(mine, 2, MPI_INT, pc->grows, 2, MPI_INT, mc_dist_comm());
        *out = pc;
        return MC_OK;
    }
#endif
    (void)r0;
    (void)nr;
    return mc_precond_create(g, out, err);
}

int mc_precond_set_mask_rows(mc_precond *pc, const unsigned char *mask, mc_error *err)
{
    if (!pc->dist)
        return mc_precond_set_mask(pc, mask, err);
    mc_box b;
    const int ok = mc_box_bound_rows(&pc->g, mask, pc->r0, pc->nr, &b);
    int rc = set_box(pc, ok, b, err);
#ifdef MC_MPI
    if (rc != MC_OK)
        return rc;
    /* the exchange: this rank's grid rows inside the box to the ranks whose transform rows they
     * are (box row jb = grid row j0 + jb), and the transform rows it is given from the ranks
     * that hold them; bx doubles a row, the box's columns */
    const box_plan *p = pc->cur;
    const int bj0 = pc->box.j0, bny = pc->box.ny, bx = pc->box.nx;
    for (int q = 0; q < pc->np; q++) {
        /* to rank q: grid rows [r0, r0 + nr) and box rows [rb0_q, rb0_q + nrb_q) of box rows
         * [0, bny) */
        int lo = pc->r0 - bj0, hi = pc->r0 + pc->nr - bj0;
        int qlo = p->rball[2 * q], qhi = qlo + p->rball[2 * q + 1];
        lo = lo > qlo ? lo : qlo;
        lo = lo > 0 ? lo : 0;
        hi = hi < qhi ? hi : qhi;
        hi = hi < bny ? hi : bny;
        pc->sc[q] = hi > lo ? (hi - lo) * bx : 0;
        /* from rank q: its grid rows and this rank's box rows */
        lo = pc->grows[2 * q] - bj0;
        hi = lo + pc->grows[2 * q + 1];
        lo = lo > p->rb0 ? lo : p->rb0;
        lo = lo > 0 ? lo : 0;
        hi = hi < p->rb0 + p->nrb ? hi : p->rb0 + p->nrb;
        hi = hi < bny ? hi : bny;
        pc->rc[q] = hi > lo ? (hi - lo) * bx : 0;
    }
    pc->sd[0] = pc->rd[0] = 0;
    for (int q = 1; q < pc->np; q++) {
        pc->sd[q] = pc->sd[q - 1] + pc->sc[q - 1];
        pc->rd[q] = pc->rd[q - 1] + pc->rc[q - 1];
    }
#endif
    return rc;
}

void mc_precond_apply_slab(mc_precond *pc, const unsigned char *mask, const double *r, double *z)
{
    if (!pc->dist) {
        mc_precond_apply_rows(pc, mask, r, z, 0, pc->g.ny);
        return;
    }
#ifdef MC_MPI
    box_plan *p = pc->cur;
    const mc_box *box = &pc->box;
    const int nx = pc->g.nx, fx = p->fx, bx = box->nx;
    MPI_Comm comm = mc_dist_comm();
    /* this rank's rows of the box (grid rows ja .. jb - 1), masked, packed in row order */
    const int ja = box->j0 > pc->r0 ? box->j0 : pc->r0;
    const int jb = box->j0 + box->ny < pc->r0 + pc->nr ? box->j0 + box->ny : pc->r0 + pc->nr;
    size_t k = 0;
    for (int j = ja; j < jb; j++) {
        const size_t f = (size_t)(j - pc->r0) * nx + (size_t)box->i0;
        for (int i = 0; i < bx; i++)
            pc->send[k++] = mask[f + i] ? r[f + i] : 0.0;
    }
    mc_dist_mark t0 = mc_dist_comm_begin();
    MPI_Alltoallv(pc->send, pc->sc, pc->sd, MPI_DOUBLE, p->field, pc->rc, pc->rd, MPI_DOUBLE,
                  comm);
    mc_dist_comm_end(t0);
    /* the transform's rows: box rows rb0 .. rb0 + nrb - 1, those inside the box from the
     * exchange (they arrive packed, bx a row, in row order: the ranks' rows ascend with the
     * rank), spread in place to fx a row from the last (row t moves up from t bx to t fx >= t bx)
     * and zero-padded */
    for (int t = p->nrb - 1; t >= 0; t--) {
        double *dst = p->field + (size_t)t * fx;
        const int jr = p->rb0 + t; /* box row */
        if (jr >= box->ny) {
            memset(dst, 0, sizeof(double) * (size_t)fx);
            continue;
        }
        memmove(dst, p->field + (size_t)t * bx, sizeof(double) * (size_t)bx);
        memset(dst + bx, 0, sizeof(double) * (size_t)(fx - bx));
    }
    fftw_complex *spec = mc_dfft_spectrum(p->d);
    mc_dfft_forward(p->d, p->field, spec, 1);
    const size_t nspec = mc_dfft_spectrum_len(p->d) / 2;
    for (size_t c = 0; c < nspec; c++) {
        spec[c][0] *= p->symbol[c];
        spec[c][1] *= p->symbol[c];
    }
    mc_dfft_inverse(p->d, p->field, 1);
    /* back: the box's columns of the rows inside the box, packed in place from the first row
     * (row t moves down from t fx to t bx), to the ranks that hold them */
    for (int t = 0; t < p->nrb && p->rb0 + t < box->ny; t++)
        memmove(p->field + (size_t)t * bx, p->field + (size_t)t * fx, sizeof(double) * (size_t)bx);
    t0 = mc_dist_comm_begin();
    MPI_Alltoallv(p->field, pc->rc, pc->rd, MPI_DOUBLE, pc->send, pc->sc, pc->sd, MPI_DOUBLE,
                  comm);
    mc_dist_comm_end(t0);
    for (int j = pc->r0; j < pc->r0 + pc->nr; j++) {
        double *zr = z + (size_t)(j - pc->r0) * nx;
        if (j < ja || j >= jb) {
            memset(zr, 0, sizeof(double) * (size_t)nx);
            continue;
        }
        const double *src = pc->send + (size_t)(j - ja) * bx;
        const unsigned char *mr = mask + (size_t)(j - pc->r0) * nx;
        for (int i = 0; i < nx; i++) {
            const int ib = i - box->i0;
            zr[i] = ib >= 0 && ib < bx && mr[i] ? src[ib] : 0.0;
        }
    }
#else
    (void)mask;
    (void)r;
    (void)z;
#endif
}
