/* contact_internal.h - shared state of the contact methods (not a public header).
 *
 * Every method solves the SHIFTED problem in the excess pressure q = p - p_lower >= 0:
 *     g = h~ + K q - delta,   0 <= q <= cap,   A sum(q) = W (force control) or delta given,
 * where h~ = h + h_extra + K p_lower. contact.c does the shift and the bookkeeping.
 */
#ifndef MC_CONTACT_INTERNAL_H
#define MC_CONTACT_INTERNAL_H

#include <stddef.h>

#include "contact/contact.h"
#include "core/psum.h"
#include "operator/precond.h"

typedef struct {
    const double *h;   /* h~, m */
    double hmin, hmax; /* its range (fixed during a solve: the gap scale of the stopping rule) */
    const double *cap; /* per-cell upper bound of q, Pa; NULL = none */
    mc_control control;
    double W;          /* force control: target A*sum(q), N */
    double delta;      /* approach control: input; force control: output */
} mc_qproblem;

typedef struct {
    int iterations;
    double residual;
    int converged;
} mc_qresult;

/* Sums per row: at most this many quantities per distributed reduction (mc_contact_totals; the
 * solve's summary: load, solid load, contact and capped cells). */
#define MC_CONTACT_SUMS 4

struct mc_contact_solver {
    mc_operator *K;
    mc_grid g;
    size_t n;
    /* Rows of the iterations (the distributed operator's slab, operator/dfft.h; all rows
     * serially): r0 .. r0 + nr - 1. Distributed (dist), every per-cell workspace below holds
     * those rows alone (nl = nr * nx cells, grid cell off + i at index i, off = r0 * nx: the
     * memory of the iterations divides over the ranks), K is applied to them
     * (mc_contact_apply_rows, no whole field), and the whole-grid arrays of the caller
     * (mc_contact_problem, the outputs) are read and written at off + i. Serially nl = n and
     * off = 0. The methods' per-cell loops run over lo .. hi - 1 = 0 .. nl - 1, and their sums
     * go piece by piece through mc_contact_totals: the same bits on any number of threads, and
     * of ranks. */
    int r0, nr, dist;
    size_t lo, hi, nl, off;
    mc_psum ps;           /* the pieces of the sums without ranks (mc_contact_pieces) */
    double *rpart, *rall; /* piece sums: this rank's (MC_CONTACT_SUMS per piece), all rows' */
    double A; /* cell area, m^2 */
    mc_contact_options opt;
    /* workspaces, nl each (above), allocated once; every method (cg, pk, active set) names them alike:
     *   htil  h~;  q  the excess pressure p - p_lower (the iterate);  u  K q
     *   gap   g = h~ + u - delta, the gradient of the energy (cg projects it onto the free set)
     *   z     cg: the preconditioned gradient M g; the active set and the coarse start use it
     *         as scratch
     *   dir   the search direction d;  kdir  K d
     *   free_set   the cells free to move S (the active set keeps AT_FREE / AT_LOWER / AT_CAP)
     *   free_prev  the free set of the previous iteration (the box solve marks cells in it) */
    double *htil, *q, *u, *gap, *z, *dir, *kdir;
    double *plow, *capq, *ulow; /* lower bound, upper bound of q, K p_lower: on first need */
    int plow_on;                /* the current solve has a non-zero lower bound in plow */
    unsigned char *free_set, *free_prev;
    mc_precond *pc;
    long applies;
    /* coarse start (cg): the same problem on a 2:1 coarser grid (NULL when not coarsened) */
    mc_contact_solver *coarse;
    mc_operator *coarse_op;
    int fx, fy;                    /* coarsening factor per axis (1 or 2) */
    double *coarse_h, *coarse_low, *coarse_p; /* coarse arrays (the fine start goes into z) */
    double *coarse_cap;                       /* coarse per-cell caps, on first need */
    /* restriction to the contact's box (cg): built on demand, kept for the next solve */
    mc_contact_solver *box;
    mc_operator *box_op;
    int bi0, bj0, bnx, bny;          /* the box of the last restricted solve (bnx = 0: none) */
    long box_cells, box_applies;
    double *box_h, *box_cap, *box_q; /* box-sized arrays (allocated with the box solver) */
    /* active-set reference: dense influence matrix and factor workspace (n*n each) */
    double *dense, *factor;
    size_t *map; /* free-cell indices */
};

/* A cell can move: strictly inside its bounds 0 < q < cap, or at a bound with the gap g pointing
 * inwards (penetrating at 0, opening at the cap). */
static inline int mc_contact_free(double q, double cap, double g)
{
    return (q > 0 && q < cap) || (q <= 0 && g < 0) || (q >= cap && g > 0);
}

/* The pieces the methods' sums are cut into, summed each in index order and then added in piece
 * order (mc_contact_totals): distributed, the rows of this rank (r0 + k), added over all ranks in
 * row order (rows never straddle two ranks, so the bits do not depend on P); without ranks, the
 * thread-count-free blocks of core/psum.h over all cells (the serial program's sums, unchanged). */
static inline long mc_contact_pieces(const mc_contact_solver *s)
{
    return s->dist ? (long)s->nr : s->ps.nb;
}

static inline size_t mc_contact_piece_lo(const mc_contact_solver *s, long k)
{
    return s->dist ? (size_t)k * (size_t)s->g.nx : mc_psum_lo(&s->ps, k);
}

static inline size_t mc_contact_piece_hi(const mc_contact_solver *s, long k)
{
    return s->dist ? (size_t)(k + 1) * (size_t)s->g.nx : mc_psum_hi(&s->ps, k);
}

/* u = K in, counted: whole arrays, every row, on every rank. */
void mc_contact_apply(mc_contact_solver *s, const double *in, double *out);

/* u = K in on the workspaces' cells (nl each: this rank's rows distributed, whole serially),
 * counted. Collective. */
void mc_contact_apply_rows(mc_contact_solver *s, const double *in, double *out);

/* The m (<= MC_CONTACT_SUMS) sums whose per-piece parts the caller put in s->rpart[r * m + k]
 * (r: the r-th piece, mc_contact_pieces, summed in index order) into out[0..m): the piece sums
 * added in piece order, over all ranks in row order when distributed (core/dist.h), identical on
 * every rank. Collective. */
void mc_contact_totals(mc_contact_solver *s, int m, double *out);

/* The largest v (flags, maxima) over the ranks of a distributed solver. Collective. */
double mc_contact_max(const mc_contact_solver *s, double v);

/* The sum of v[0 .. nl) over all ranks: serially in index order (the serial program's plain
 * sum); distributed row by row, the row sums added in row order over the ranks (the same bits
 * on any P). Collective. */
double mc_contact_sum(mc_contact_solver *s, const double *v);

/* Gap scale of the stopping rule: delta - min(h~), floored so it is never zero. */
double mc_contact_gap_scale(const mc_contact_solver *s, const mc_qproblem *qp, double delta);

/* The scale-free KKT residual of contact.h for q, u = K q and delta (read on this rank's rows);
 * collective. */
double mc_contact_residual(mc_contact_solver *s, const mc_qproblem *qp, const double *q,
                           const double *u, double delta);

/* Methods: q holds the start on entry (feasible: 0 <= q <= cap) and the solution on exit; s->u
 * holds K q on exit; qp->delta is set for force control. MC_NOT_CONVERGED leaves the last iterate.
 * The other workspaces are theirs. q, s->u and qp's arrays are workspaces (nl cells: this rank's
 * rows when distributed); all ranks call the methods together. */
int mc_contact_cg(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res, mc_error *err);
int mc_contact_pk(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res, mc_error *err);
int mc_contact_nested(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res,
                      mc_error *err);
int mc_contact_active_set(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res,
                          mc_error *err);
int mc_contact_active_set_prepare(mc_contact_solver *s, mc_error *err);

/* The cg solve on the contact's bounding box when that is small (contact_box.c): *handled = 1
 * with the full-grid q, s->u = K q and qp->delta when it ran; 0 when not applicable or when the
 * box grew too large (q is then a warm start for the full solve). */
int mc_contact_box_solve(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res,
                         int *handled, mc_error *err);

#endif
