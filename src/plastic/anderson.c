/* anderson.c - Anderson acceleration on the active cells of a field (anderson.h). */
#include "plastic/anderson.h"

#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/psum.h"

struct mc_anderson {
    long ncells;
    int width, depth;
    int *map;     /* ncells: slot of a cell in the compact vectors, -1 when not active (4 bytes
                     per cell: the field's cells fit an int, create checks); made by the first
                     dense step (the sparse steps find slots through order) */
    long *cells;  /* nact active cells, in the order they joined (ccap of room) */
    long *order;  /* nact slots, their cells ascending (ccap of room) */
    long nact, cap, ccap;
    double *f[MC_ANDERSON_MAX_DEPTH + 1], *g[MC_ANDERSON_MAX_DEPTH + 1]; /* width * cap each */
    double *xo;   /* width * cap: the new iterate of a sparse step */
    int count;    /* stored iterates (<= depth + 1) */
    int head;     /* ring position of the next one */
    /* rows mode (mc_anderson_rows): cells nb x ny x nx, this rank's rows r0 .. r0 + nr - 1 of
     * every block; the dots' per-row partial sums (part: nr nb rows, all: ny nb rows, of up to
     * NPAIRS values each) */
    int nb, ny, nx, r0, nr; /* nr < 0: the whole field */
    double *part, *all;
};

/* dot products of the history: (depth + 1)(depth + 2) / 2 at most */
#define NPAIRS ((MC_ANDERSON_MAX_DEPTH + 1) * (MC_ANDERSON_MAX_DEPTH + 2) / 2)

int mc_anderson_create(long ncells, int width, int depth, mc_anderson **out, mc_error *err)
{
    *out = NULL;
    if (ncells < 1 || width < 1 || depth < 1 || depth > MC_ANDERSON_MAX_DEPTH)
        return mc_fail(err, MC_ERR_INPUT, "anderson: %ld cells of width %d, depth %d (1..%d)",
                       ncells, width, depth, MC_ANDERSON_MAX_DEPTH);
    if (ncells > INT_MAX)
        return mc_fail(err, MC_ERR_LIMIT, "anderson: %ld cells (at most %d)", ncells, INT_MAX);
    mc_anderson *a = mc_calloc(1, sizeof *a);
    if (!a)
        return mc_fail(err, MC_ERR_NOMEM, "anderson: out of memory");
    a->ncells = ncells;
    a->width = width;
    a->depth = depth;
    a->nr = -1;
    *out = a;
    return MC_OK;
}

void mc_anderson_restart(mc_anderson *a)
{
    for (long k = 0; k < a->nact && a->map; k++)
        a->map[a->cells[k]] = -1;
    a->nact = 0;
    a->count = 0;
    a->head = 0;
}

long mc_anderson_active(const mc_anderson *a) { return a->nact; }

int mc_anderson_rows(mc_anderson *a, int nblocks, int ny, int nx, int r0, int nr)
{
    mc_anderson_restart(a);
    mc_free(a->part);
    mc_free(a->all);
    a->part = a->all = NULL;
    a->nr = -1;
    if (nr < 0)
        return 1;
    if ((long)nblocks * ny * nx != a->ncells || r0 < 0 || r0 + nr > ny)
        return 0;
    const size_t np = (size_t)nr * nblocks * NPAIRS, na = (size_t)ny * nblocks * NPAIRS;
    if (!(a->part = mc_malloc((np ? np : 1) * sizeof *a->part)) ||
        !(a->all = mc_malloc(na * sizeof *a->all))) {
        mc_free(a->part);
        a->part = NULL;
        return 0;
    }
    a->nb = nblocks;
    a->ny = ny;
    a->nx = nx;
    a->r0 = r0;
    a->nr = nr;
    return 1;
}

/* Rows mode: ff[i][j] = f_ring[i] . f_ring[j] (i, j <= m) over the whole field, from this rank's
 * per-row partial sums (each row's cells in order, their components in order) added row by row in
 * a fixed order over the ranks (rows j-major: (j, b) for j = 0 .. ny - 1, b = 0 .. nb - 1; the
 * ranks' rows ascend with the rank), so that any number of ranks gives the same bits. */
static void row_dots(mc_anderson *a, const int *ring, int m,
                     double ff[][MC_ANDERSON_MAX_DEPTH + 1])
{
    const int w = a->width, nb = a->nb, D = (m + 1) * (m + 2) / 2;
    const long nrows = (long)a->nr * nb;
#pragma omp parallel for schedule(static) if (nrows * a->nx > 4096)
    for (long row = 0; row < nrows; row++) {
        const long jl = row / nb, b = row % nb;
        double *ps = a->part + (size_t)row * D;
        for (int d = 0; d < D; d++)
            ps[d] = 0.0;
        const long v0 = ((long)b * a->ny + a->r0 + jl) * a->nx;
        for (long i = 0; i < a->nx; i++) {
            const long s = a->map[v0 + i];
            if (s < 0)
                continue;
            int d = 0;
            for (int p = 0; p <= m; p++)
                for (int q = 0; q <= p; q++, d++) {
                    const double *fp = a->f[ring[p]] + (size_t)s * w,
                                 *fq = a->f[ring[q]] + (size_t)s * w;
                    double t = 0.0;
                    for (int c = 0; c < w; c++)
                        t += fp[c] * fq[c];
                    ps[d] += t;
                }
        }
    }
    double tot[NPAIRS];
    mc_dist_row_totals(a->part, (int)nrows, a->ny * nb, D, a->all, tot);
    int d = 0;
    for (int p = 0; p <= m; p++)
        for (int q = 0; q <= p; q++, d++)
            ff[p][q] = ff[q][p] = tot[d];
}

void mc_anderson_destroy(mc_anderson **pa)
{
    mc_anderson *a = pa ? *pa : NULL;
    if (!a)
        return;
    for (int k = 0; k <= MC_ANDERSON_MAX_DEPTH; k++) {
        mc_free(a->f[k]);
        mc_free(a->g[k]);
    }
    mc_free(a->map);
    mc_free(a->cells);
    mc_free(a->order);
    mc_free(a->xo);
    mc_free(a->part);
    mc_free(a->all);
    mc_free(a);
    *pa = NULL;
}

/* Room for need active cells in every history vector; new entries are zero. */
static int grow(mc_anderson *a, long need)
{
    if (need <= a->cap)
        return 1;
    long cap = a->cap ? a->cap : 1024;
    while (cap < need)
        cap *= 2;
    if (cap > a->ncells)
        cap = a->ncells;
    const size_t w = (size_t)a->width;
    double *nx = mc_malloc(w * (size_t)cap * sizeof *nx);
    if (!nx)
        return 0;
    mc_free(a->xo);
    a->xo = nx;
    for (int k = 0; k <= a->depth; k++) {
        double *nf = mc_zeros(w * (size_t)cap), *ng = mc_zeros(w * (size_t)cap);
        if (!nf || !ng) {
            mc_free(nf);
            mc_free(ng);
            return 0;
        }
        if (a->f[k]) {
            memcpy(nf, a->f[k], w * (size_t)a->cap * sizeof *nf);
            memcpy(ng, a->g[k], w * (size_t)a->cap * sizeof *ng);
        }
        mc_free(a->f[k]);
        mc_free(a->g[k]);
        a->f[k] = nf;
        a->g[k] = ng;
    }
    a->cap = cap;
    return 1;
}

/* Dot product of two compact vectors of n values: the same bits on any thread count
 * (core/psum.h). */
static double dot(const double *x, const double *y, size_t n) { return mc_psum_dot(x, y, n); }

/* Solve the m x m system A gamma = b in place (partial pivoting); 0 when singular. */
static int solve_small(int m, double A[][MC_ANDERSON_MAX_DEPTH], double *b, double *gamma)
{
    for (int c = 0; c < m; c++) {
        int piv = c;
        for (int r = c + 1; r < m; r++)
            if (fabs(A[r][c]) > fabs(A[piv][c]))
                piv = r;
        if (!(fabs(A[piv][c]) > 0))
            return 0;
        if (piv != c) {
            for (int q = 0; q < m; q++) {
                double t = A[c][q];
                A[c][q] = A[piv][q];
                A[piv][q] = t;
            }
            double t = b[c];
            b[c] = b[piv];
            b[piv] = t;
        }
        for (int r = c + 1; r < m; r++) {
            double f = A[r][c] / A[c][c];
            for (int q = c; q < m; q++)
                A[r][q] -= f * A[c][q];
            b[r] -= f * b[c];
        }
    }
    for (int c = m - 1; c >= 0; c--) {
        double s = b[c];
        for (int q = c + 1; q < m; q++)
            s -= A[c][q] * gamma[q];
        gamma[c] = s / A[c][c];
    }
    for (int c = 0; c < m; c++)
        if (!isfinite(gamma[c]))
            return 0;
    return 1;
}

/* Cell v joins the active set (slot need, then need + 1); 0 when the list cannot grow. */
static int join(mc_anderson *a, long v, long *need)
{
    if (*need == a->ccap) {
        long cap = a->ccap ? 2 * a->ccap : 1024;
        cap = cap > a->ncells ? a->ncells : cap;
        long *nc = mc_malloc((size_t)cap * sizeof *nc), *no = mc_malloc((size_t)cap * sizeof *no);
        if (!nc || !no) {
            mc_free(nc);
            mc_free(no);
            return 0;
        }
        if (a->cells) {
            memcpy(nc, a->cells, (size_t)*need * sizeof *nc);
            memcpy(no, a->order, (size_t)a->nact * sizeof *no);
        }
        mc_free(a->cells);
        mc_free(a->order);
        a->cells = nc;
        a->order = no;
        a->ccap = cap;
    }
    if (a->map)
        a->map[v] = (int)*need;
    a->cells[(*need)++] = v;
    return 1;
}

/* The active set grown to need cells (joined since nact): room in the history, or the joins
 * undone and the history dropped (0). */
static void undo(mc_anderson *a, long need)
{
    for (long k = a->nact; k < need && a->map; k++)
        a->map[a->cells[k]] = -1;
    mc_anderson_restart(a);
}

static int admit(mc_anderson *a, long need)
{
    if (grow(a, need)) {
        /* order: the slots that joined (their cells ascend: both steps join in cell order)
         * merged into it from the back */
        long i = a->nact - 1, j = need - 1;
        for (long k = need - 1; k >= 0 && j >= a->nact; k--)
            a->order[k] = i >= 0 && a->cells[a->order[i]] > a->cells[j] ? a->order[i--] : j--;
        a->nact = need;
        return 1;
    }
    undo(a, need);
    return 0;
}

/* The mixing of the stored pair (f_k, g_k in the slot a->head, not yet advanced): advances the
 * ring and writes x_{k+1} on the active cells through put(a, slot k, component q, value). */
static void mix_into(mc_anderson *a, double *x, int dense)
{
    const long N = a->ncells;
    const int w = a->width;
    const int cur = a->head;
    double *gc = a->g[cur];
    if (a->count < a->depth + 1)
        a->count++;
    a->head = (a->head + 1) % (a->depth + 1);
    const int m = a->count - 1; /* differences available */
    /* cells outside the active set are zero in x and g(x): they stay zero */
    double gamma[MC_ANDERSON_MAX_DEPTH];
    int mix = m > 0;
    const size_t len = (size_t)a->nact * (size_t)w;
    int ring[MC_ANDERSON_MAX_DEPTH + 1]; /* oldest .. newest (= cur) */
    if (mix) {
        for (int j = 0; j <= m; j++)
            ring[j] = (cur - m + j + 2 * (a->depth + 1)) % (a->depth + 1);
        /* dF_j = f_{ring[j+1]} - f_{ring[j]}; normal equations dF' dF gamma = dF' f_k */
        double A[MC_ANDERSON_MAX_DEPTH][MC_ANDERSON_MAX_DEPTH], b[MC_ANDERSON_MAX_DEPTH];
        double ff[MC_ANDERSON_MAX_DEPTH + 1][MC_ANDERSON_MAX_DEPTH + 1];
        if (a->nr >= 0)
            row_dots(a, ring, m, ff);
        else
            for (int i = 0; i <= m; i++)
                for (int j = 0; j <= i; j++)
                    ff[i][j] = ff[j][i] = dot(a->f[ring[i]], a->f[ring[j]], len);
        double trace = 0;
        for (int i = 0; i < m; i++) {
            for (int j = 0; j < m; j++)
                A[i][j] = ff[i + 1][j + 1] - ff[i + 1][j] - ff[i][j + 1] + ff[i][j];
            b[i] = ff[i + 1][m] - ff[i][m];
            trace += A[i][i];
        }
        /* a little Tikhonov regularisation keeps near-dependent differences harmless */
        for (int i = 0; i < m; i++)
            A[i][i] += 1e-12 * trace;
        mix = trace > 0 && solve_small(m, A, b, gamma);
    }
    for (long k = 0; k < a->nact; k++) {
        const size_t v = (size_t)a->cells[k];
        for (int q = 0; q < w; q++) {
            const size_t s = (size_t)k * (size_t)w + (size_t)q;
            double xv = gc[s];
            for (int j = 0; mix && j < m; j++)
                xv -= gamma[j] * (a->g[ring[j + 1]][s] - a->g[ring[j]][s]);
            if (dense)
                x[(size_t)q * (size_t)N + v] = xv;
            else
                x[s] = xv;
        }
    }
}

int mc_anderson_step(mc_anderson *a, double *x, const double *gx, mc_error *err)
{
    const long N = a->ncells;
    const int w = a->width;
    if (!a->map) { /* the first dense step (the map of the cells joined so far) */
        if (!(a->map = mc_malloc((size_t)N * sizeof *a->map))) {
            mc_anderson_restart(a);
            memcpy(x, gx, (size_t)w * (size_t)N * sizeof *x);
            return mc_fail(err, MC_ERR_NOMEM, "anderson: out of memory for %ld cells", N);
        }
        for (long v = 0; v < N; v++)
            a->map[v] = -1;
        for (long k = 0; k < a->nact; k++)
            a->map[a->cells[k]] = (int)k;
    }
    /* cells that turned non-zero join the active set (rows mode: of this rank's rows) */
    long need = a->nact;
    int room = 1;
    const long nrun = a->nr < 0 ? 1 : a->nb, run = a->nr < 0 ? N : (long)a->nx * a->nr;
    for (long r = 0; r < nrun && room; r++)
    for (long v = a->nr < 0 ? 0 : ((long)r * a->ny + a->r0) * a->nx, vend = v + run;
         v < vend && room; v++) {
        if (a->map[v] >= 0)
            continue;
        int nz = 0;
        for (int q = 0; q < w && !nz; q++)
            nz = x[(size_t)q * (size_t)N + (size_t)v] != 0.0 ||
                 gx[(size_t)q * (size_t)N + (size_t)v] != 0.0;
        if (nz)
            room = join(a, v, &need);
    }
    if (!room)
        undo(a, need);
    if (!room || !admit(a, need)) {
        memcpy(x, gx, (size_t)w * (size_t)N * sizeof *x);
        return mc_fail(err, MC_ERR_NOMEM, "anderson: out of memory for %ld active cells", need);
    }
    /* store f_k = g(x_k) - x_k and g(x_k) on the active cells, slot-major */
    double *fc = a->f[a->head], *gc = a->g[a->head];
    for (long k = 0; k < a->nact; k++) {
        const size_t v = (size_t)a->cells[k];
        for (int q = 0; q < w; q++) {
            double gv = gx[(size_t)q * (size_t)N + v];
            fc[(size_t)k * (size_t)w + (size_t)q] = gv - x[(size_t)q * (size_t)N + v];
            gc[(size_t)k * (size_t)w + (size_t)q] = gv;
        }
    }
    mix_into(a, x, 1);
    return MC_OK;
}

int mc_anderson_step_sparse(mc_anderson *a, long nx, const long *xcell, const double *xval,
                            long ng, const long *gcell, const double *gval, int stride,
                            long *n, const long **cells, const double **vals, mc_error *err)
{
    const int w = a->width;
    *n = 0;
    *cells = NULL;
    *vals = NULL;
    if (a->nr >= 0 || stride < w)
        return mc_fail(err, MC_ERR_INPUT, "anderson: a sparse step in rows mode or of stride %d",
                       stride);
    long need = a->nact;
    int room = 1;
    /* new cells join in ascending order, as the dense step's scan: the lists merged, and
     * walked along the active cells in cell order (order) */
    for (long ex = 0, eg = 0, o = 0; (ex < nx || eg < ng) && room;) {
        const long cx = ex < nx ? xcell[ex] : LONG_MAX, cg = eg < ng ? gcell[eg] : LONG_MAX;
        const long v = cx < cg ? cx : cg;
        int nz = 0;
        for (int q = 0; q < w && !nz; q++)
            nz = (cx == v && xval[(size_t)stride * (size_t)ex + (size_t)q] != 0.0) ||
                 (cg == v && gval[(size_t)stride * (size_t)eg + (size_t)q] != 0.0);
        ex += cx == v;
        eg += cg == v;
        while (o < a->nact && a->cells[a->order[o]] < v)
            o++;
        if (nz && !(o < a->nact && a->cells[a->order[o]] == v))
            room = join(a, v, &need);
    }
    if (!room)
        undo(a, need);
    if (!room || !admit(a, need))
        return mc_fail(err, MC_ERR_NOMEM, "anderson: out of memory for %ld active cells", need);
    /* f_k = g(x_k) - x_k and g(x_k) on the active cells: g's entries first, then x's taken off,
     * the bits of the dense step (0 - x = -x, g - 0 = g) */
    double *fc = a->f[a->head], *gc = a->g[a->head];
    const size_t len = (size_t)a->nact * (size_t)w;
    memset(fc, 0, len * sizeof *fc);
    memset(gc, 0, len * sizeof *gc);
    for (int l = 0; l < 2; l++) { /* g's entries, then x's (each list and order ascend) */
        const long cnt = l ? nx : ng, *cl = l ? xcell : gcell;
        const double *vl = l ? xval : gval;
        for (long e = 0, o = 0; e < cnt; e++) {
            while (o < a->nact && a->cells[a->order[o]] < cl[e])
                o++;
            if (!(o < a->nact && a->cells[a->order[o]] == cl[e]))
                continue; /* (a zero entry of a cell that never joined) */
            const size_t sw = (size_t)a->order[o] * (size_t)w;
            for (int q = 0; q < w; q++) {
                const double v = vl[(size_t)stride * (size_t)e + (size_t)q];
                if (l)
                    fc[sw + q] = gc[sw + q] - v;
                else
                    fc[sw + q] = gc[sw + q] = v;
            }
        }
    }
    mix_into(a, a->xo, 0);
    *n = a->nact;
    *cells = a->cells;
    *vals = a->xo;
    return MC_OK;
}
