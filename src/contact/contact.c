/* contact.c - normal contact: the shift to the excess pressure, method dispatch, summary
 * (see contact.h). */
#include "contact/contact.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "contact/contact_internal.h"
#include "core/dist.h"

/* Loops over a rank's rows run on the run's threads from this many cells on. */
#define PAR_MIN MC_THREADS_MIN_LOOP

typedef int (*method_fn)(mc_contact_solver *, mc_qproblem *, double *, mc_qresult *, mc_error *);

/* The methods as rows: the driver never asks which one it runs. */
static const struct {
    mc_contact_method id;
    const char *name;
    method_fn force;     /* force control, no cap */
    method_fn approach;  /* approach control (with or without cap) */
    method_fn capped;    /* force control with a cap */
} methods[] = {
    {MC_METHOD_CG, "cg", mc_contact_cg, mc_contact_cg, mc_contact_nested},
    {MC_METHOD_PK, "pk", mc_contact_pk, mc_contact_pk, mc_contact_pk},
    {MC_METHOD_ACTIVE_SET, "active-set", mc_contact_active_set, mc_contact_active_set,
     mc_contact_active_set},
};
#define NMETHODS (int)(sizeof methods / sizeof methods[0])

const char *mc_contact_method_name(mc_contact_method m)
{
    for (int k = 0; k < NMETHODS; k++)
        if (methods[k].id == m)
            return methods[k].name;
    return "?";
}

void mc_contact_apply(mc_contact_solver *s, const double *in, double *out)
{
    mc_operator_apply(s->K, in, out);
    s->applies++;
}

void mc_contact_apply_rows(mc_contact_solver *s, const double *in, double *out)
{
    if (s->dist)
        mc_operator_apply_rows(s->K, in, out);
    else /* whole workspaces (a serial operator, or the active set's replicated ones) */
        mc_operator_apply(s->K, in, out);
    s->applies++;
}

void mc_contact_totals(mc_contact_solver *s, int m, double *out)
{
    if (s->dist) {
        mc_dist_row_totals(s->rpart, s->nr, s->g.ny, m, s->rall, out);
        return;
    }
    for (int k = 0; k < m; k++) { /* without ranks: the blocks in order, as core/psum.h */
        double v = 0;
        for (long r = 0; r < s->ps.nb; r++)
            v += s->rpart[(size_t)r * m + k];
        out[k] = v;
    }
}

double mc_contact_max(const mc_contact_solver *s, double v)
{
    if (s->dist)
        mc_dist_max(&v, 1);
    return v;
}

double mc_contact_sum(mc_contact_solver *s, const double *v)
{
    double sum = 0;
    if (!s->dist) { /* the serial program's plain sum */
        for (size_t i = 0; i < s->nl; i++)
            sum += v[i];
        return sum;
    }
    for (int k = 0; k < s->nr; k++) { /* row by row over the ranks */
        double r = 0;
        for (size_t i = mc_contact_piece_lo(s, k); i < mc_contact_piece_hi(s, k); i++)
            r += v[i];
        s->rpart[k] = r;
    }
    mc_contact_totals(s, 1, &sum);
    return sum;
}

long mc_contact_last_applies(const mc_contact_solver *s) { return s->applies; }

long mc_contact_last_box_cells(const mc_contact_solver *s) { return s->box_cells; }
long mc_contact_last_box_applies(const mc_contact_solver *s) { return s->box_applies; }

long mc_contact_last_coarse_applies(const mc_contact_solver *s)
{
    long n = 0;
    for (const mc_contact_solver *c = s->coarse; c; c = c->coarse)
        n += c->applies;
    return n;
}

/* ---- coarse start: restriction to, and prolongation from, a 2:1 coarser grid ------------- */

static int coarsen_factor(int n, int periodic)
{
    return n >= MC_COARSEN_MIN && (!periodic || n % 2 == 0) ? 2 : 1;
}

/* Block average over the fine cells of each coarse cell (partial blocks at odd ends). */
static void restrict_field(const mc_contact_solver *s, const double *fine, const double *extra,
                           double uniform, double *coarse)
{
    const mc_grid *g = &s->g, *cg = &s->coarse->g;
    for (int J = 0; J < cg->ny; J++)
        for (int I = 0; I < cg->nx; I++) {
            double sum = 0;
            int m = 0;
            for (int j = J * s->fy; j < (J + 1) * s->fy && j < g->ny; j++)
                for (int i = I * s->fx; i < (I + 1) * s->fx && i < g->nx; i++) {
                    size_t k = (size_t)j * g->nx + i;
                    sum += (fine ? fine[k] : uniform) + (extra ? extra[k] : 0.0);
                    m++;
                }
            coarse[(size_t)J * cg->nx + I] = sum / m;
        }
}

/* Into a workspace: the rows r0 .. r0 + nr - 1 (contact_internal.h). */
static void prolong_field(const mc_contact_solver *s, const double *coarse, double *fine)
{
    const mc_grid *g = &s->g;
    const int cnx = s->coarse->g.nx;
    for (int j = s->r0; j < s->r0 + s->nr; j++)
        for (int i = 0; i < g->nx; i++)
            fine[(size_t)(j - s->r0) * g->nx + i] = coarse[(size_t)(j / s->fy) * cnx + i / s->fx];
}

static int create_coarse(mc_contact_solver *s, mc_operator *K, mc_error *err)
{
    const mc_grid *g = mc_operator_grid(K);
    s->fx = coarsen_factor(g->nx, g->periodic_x);
    s->fy = coarsen_factor(g->ny, g->periodic_y);
    if (s->opt.method != MC_METHOD_CG || !(s->opt.estar > 0) || (s->fx == 1 && s->fy == 1))
        return MC_OK;
    mc_grid cg = *g;
    cg.nx = (g->nx + s->fx - 1) / s->fx;
    cg.ny = (g->ny + s->fy - 1) / s->fy;
    cg.dx = g->dx * s->fx;
    cg.dy = g->dy * s->fy;
    int rc = mc_operator_plan_love(&cg, s->opt.estar, mc_operator_backend(K), &s->coarse_op, err);
    if (rc != MC_OK)
        return rc;
    mc_contact_options copt = s->opt;
    /* the coarse solution is only a start: a modest tolerance suffices */
    if (copt.tolerance < 1e-5)
        copt.tolerance = 1e-5;
    rc = mc_contact_create(s->coarse_op, &copt, &s->coarse, err);
    if (rc != MC_OK)
        return rc;
    size_t nc = mc_grid_cells(&cg);
    if (!(s->coarse_h = mc_zeros(nc)) || !(s->coarse_low = mc_zeros(nc)) ||
        !(s->coarse_p = mc_zeros(nc)))
        return mc_fail(err, MC_ERR_NOMEM, "contact solver: out of memory for the coarse grid");
    return MC_OK;
}

/* Solve the problem on the coarse grid (its arrays whole, the coarse solver's own rows split
 * over the ranks) and prolong its pressure into the workspace s->z. */
static int coarse_start(mc_contact_solver *s, const mc_contact_problem *p, mc_error *err)
{
    restrict_field(s, p->h, p->h_extra, 0.0, s->coarse_h);
    restrict_field(s, p->p_lower, NULL, p->p_lub, s->coarse_low);
    mc_contact_problem cp = *p;
    cp.h = s->coarse_h;
    cp.h_extra = NULL;
    cp.p_lower = s->coarse_low;
    cp.p_start = NULL;
    if (p->p_upper) { /* block averages keep each cell above its lower bound and the capacity */
        if (!s->coarse_cap && !(s->coarse_cap = mc_zeros(mc_grid_cells(&s->coarse->g))))
            return mc_fail(err, MC_ERR_NOMEM, "contact solver: out of memory for the coarse caps");
        restrict_field(s, p->p_upper, NULL, 0.0, s->coarse_cap);
        cp.p_upper = s->coarse_cap;
    }
    mc_contact_summary sum;
    int rc = mc_contact_solve(s->coarse, &cp, s->coarse_p, NULL, NULL, &sum, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    mc_error_clear(err);
    prolong_field(s, s->coarse_p, s->z); /* z is free until the method starts */
    return MC_OK;
}

int mc_contact_create(mc_operator *K, const mc_contact_options *opt, mc_contact_solver **out,
                      mc_error *err)
{
    *out = NULL;
    const mc_grid *g = mc_operator_grid(K);
    size_t n = mc_grid_cells(g);
    if (!(opt->tolerance > 0 && opt->tolerance < 1) || opt->max_iterations < 1)
        return mc_fail(err, MC_ERR_INPUT,
                       "contact solver: tolerance %g must be in (0, 1) and max_iterations %d >= 1",
                       opt->tolerance, opt->max_iterations);
    int known = 0;
    for (int k = 0; k < NMETHODS; k++)
        known |= methods[k].id == opt->method;
    if (!known)
        return mc_fail(err, MC_ERR_INPUT, "contact solver: unknown method %d", (int)opt->method);
    if (opt->method == MC_METHOD_ACTIVE_SET && n > MC_ACTIVE_SET_MAX_CELLS)
        return mc_fail(err, MC_ERR_LIMIT,
                       "method = active-set is the dense O(N^3) reference and accepts at most %d "
                       "cells; this grid has %zu (%d x %d): use method = cg",
                       MC_ACTIVE_SET_MAX_CELLS, n, g->nx, g->ny);
    mc_contact_solver *s = mc_calloc(1, sizeof *s);
    if (!s)
        return mc_fail(err, MC_ERR_NOMEM, "contact solver: out of memory");
    s->K = K;
    s->g = *g;
    s->n = n;
    s->A = mc_grid_cell_area(g);
    s->opt = *opt;
    s->dist = mc_operator_rows(K, &s->r0, &s->nr);
    if (opt->method == MC_METHOD_ACTIVE_SET) { /* the dense reference: whole on every rank */
        s->dist = 0;
        s->r0 = 0;
        s->nr = g->ny;
    }
    s->nl = (size_t)s->nr * (size_t)g->nx;
    s->off = (size_t)s->r0 * (size_t)g->nx;
    s->lo = 0;
    s->hi = s->nl;
    s->ps = mc_psum_blocks(n);
    if (s->ps.nb == 1 && n > MC_THREADS_MIN_LOOP) {
        /* the sums in pieces the threads share (MC_THREADS_MIN_LOOP): still fixed by n alone */
        s->ps.blk = MC_THREADS_MIN_LOOP / 2;
        s->ps.nb = (long)((n + s->ps.blk - 1) / s->ps.blk);
    }
    /* plow, capq and ulow (K p_lower) are allocated by the first solve that needs them */
    const size_t nl = s->nl;
    double **arrays[] = {&s->htil, &s->q, &s->u, &s->gap, &s->z, &s->dir, &s->kdir};
    int ok = 1;
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        ok &= (*arrays[k] = mc_zeros(nl)) != NULL;
    ok &= (s->free_set = mc_calloc(nl, 1)) != NULL;
    ok &= (s->free_prev = mc_calloc(nl, 1)) != NULL;
    const size_t npieces = (size_t)(g->ny > MC_PSUM_MAX_BLOCKS ? g->ny : MC_PSUM_MAX_BLOCKS);
    ok &= (s->rpart = mc_zeros(npieces * MC_CONTACT_SUMS)) != NULL;
    ok &= (s->rall = mc_zeros((size_t)g->ny * MC_CONTACT_SUMS)) != NULL;
    if (!ok) {
        mc_contact_destroy(&s);
        return mc_fail(err, MC_ERR_NOMEM, "contact solver: out of memory for %zu cells", n);
    }
    int rc = MC_OK;
    if (opt->method != MC_METHOD_ACTIVE_SET) /* distributed: the box's FFT over the ranks */
        rc = s->dist ? mc_precond_create_rows(g, s->r0, s->nr, &s->pc, err)
                     : mc_precond_create(g, &s->pc, err);
    else
        rc = mc_contact_active_set_prepare(s, err);
    if (rc == MC_OK)
        rc = create_coarse(s, K, err);
    if (rc != MC_OK) {
        mc_contact_destroy(&s);
        return rc;
    }
    *out = s;
    return MC_OK;
}

void mc_contact_destroy(mc_contact_solver **sp)
{
    if (!sp || !*sp)
        return;
    mc_contact_solver *s = *sp;
    double *arrays[] = {s->htil, s->plow, s->capq, s->q,    s->u,     s->gap,
                        s->z,    s->dir,  s->kdir, s->ulow, s->dense, s->factor,
                        s->rpart, s->rall};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        mc_free(arrays[k]);
    mc_free(s->free_set);
    mc_free(s->free_prev);
    mc_free(s->map);
    mc_free(s->coarse_h);
    mc_free(s->coarse_low);
    mc_free(s->coarse_p);
    mc_free(s->coarse_cap);
    mc_contact_destroy(&s->coarse);
    mc_contact_destroy(&s->box);
    mc_operator_destroy(&s->box_op);
    mc_free(s->box_h);
    mc_free(s->box_cap);
    mc_free(s->box_q);
    mc_operator_destroy(&s->coarse_op);
    mc_precond_destroy(&s->pc);
    mc_free(s);
    *sp = NULL;
}

double mc_contact_gap_scale(const mc_contact_solver *s, const mc_qproblem *qp, double delta)
{
    (void)s;
    const double hmin = qp->hmin, hmax = qp->hmax;
    double scale = delta - hmin;
    /* a floor relative to the topography's own range (and to its magnitude), so a flat punch
     * and a barely touching asperity still get a meaningful scale */
    double floor_ = 1e-6 * (hmax - hmin);
    double mag = fmax(fabs(hmin), fabs(hmax));
    if (floor_ < 1e-12 * mag)
        floor_ = 1e-12 * mag;
    if (!(scale > floor_))
        scale = floor_;
    return scale > 1e-300 ? scale : 1e-300;
}

double mc_contact_residual(mc_contact_solver *s, const mc_qproblem *qp, const double *q,
                           const double *u, double delta)
{
    double sg = mc_contact_gap_scale(s, qp, delta);
    /* per piece (contact_internal.h): the worst violation and sum(q); the sums added in piece
     * order (mc_contact_totals), the worst the largest */
    double worst = 0;
#pragma omp parallel for schedule(static) reduction(max : worst) if (s->hi - s->lo > PAR_MIN)
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sum = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++) {
            double g = qp->h[i] + u[i] - delta, v;
            double c = qp->cap ? qp->cap[i] : INFINITY;
            if (q[i] <= 0)
                v = -g;
            else if (q[i] >= c)
                v = g;
            else
                v = fabs(g);
            if (v > worst)
                worst = v;
            sum += q[i];
        }
        s->rpart[r] = sum;
    }
    worst = mc_contact_max(s, worst);
    double sum;
    mc_contact_totals(s, 1, &sum);
    double res = worst / sg;
    if (qp->control == MC_CONTROL_FORCE && qp->W > 0) {
        double lr = fabs(s->A * sum - qp->W) / qp->W;
        if (lr > res)
            res = lr;
    }
    return res;
}

static int check_problem(const mc_contact_solver *s, const mc_contact_problem *p, mc_error *err)
{
    if (!p->h)
        return mc_fail(err, MC_ERR_INPUT, "contact: no topography given");
    if (!(p->p_lub >= 0 && isfinite(p->p_lub)))
        return mc_fail(err, MC_ERR_INPUT,
                       "contact: lubricant pressure %g Pa must be finite and >= 0", p->p_lub);
    if (p->control == MC_CONTROL_FORCE && !(p->load > 0 && isfinite(p->load)))
        return mc_fail(err, MC_ERR_INPUT, "contact: load %g N must be finite and > 0", p->load);
    if (p->control == MC_CONTROL_APPROACH && !isfinite(p->approach))
        return mc_fail(err, MC_ERR_INPUT, "contact: approach %g m must be finite", p->approach);
    if (!(p->p_cap > 0) || isnan(p->p_cap))
        return mc_fail(err, MC_ERR_INPUT, "contact: pressure cap %g Pa must be > 0 (or infinite)",
                       p->p_cap);
    double hsum = 0;
    for (size_t i = 0; i < s->n; i++) {
        double lo = p->p_lower ? p->p_lower[i] : p->p_lub;
        double h = p->h[i] + (p->h_extra ? p->h_extra[i] : 0.0);
        hsum += h;
        if (!isfinite(h))
            return mc_fail(err, MC_ERR_INPUT, "contact: topography is not finite at cell %zu", i);
        if (!(lo >= 0 && isfinite(lo)))
            return mc_fail(err, MC_ERR_INPUT, "contact: lower bound %g Pa at cell %zu must be >= 0",
                           lo, i);
        double hi = p->p_upper ? p->p_upper[i] : p->p_cap;
        if (!(hi > lo))
            return mc_fail(err, MC_ERR_INPUT,
                           "contact: pressure cap %g Pa must exceed the lower bound %g Pa (cell "
                           "%zu)",
                           hi, lo, i);
    }
    /* Periodic in x and y the displacement has zero mean (operator.h: K 1 = 0), so the mean gap
     * is mean(h) - approach whatever the pressure: with approach >= mean(h) no solution exists. */
    double hmean = hsum / (double)s->n;
    if (p->control == MC_CONTROL_APPROACH && s->g.periodic_x && s->g.periodic_y &&
        !(p->approach < hmean))
        return mc_fail(err, MC_ERR_INPUT,
                       "contact: approach %g m on a grid periodic in x and y has no solution: the "
                       "displacement has zero mean there, so the mean gap is mean(h) - approach = "
                       "%g m whatever the pressure, and it must be > 0 (approach < %g m, the mean "
                       "initial gap; a rough flat has mean(h) = 0); use force control",
                       p->approach, hmean - p->approach, hmean);
    return MC_OK;
}

/* The lower bound p_lower and the upper bound of q (p_upper - p_lower) of grid cell i from the
 * problem's whole arrays, by the arithmetic that fills the workspaces plow and capq: sums over
 * the whole grid taken from these are the serial program's, bit for bit, on any number of ranks
 * (a read-only pass over the whole arrays every rank has). */
static inline double cell_low(const mc_contact_problem *p, int any_lower, size_t i)
{
    return any_lower ? (p->p_lower ? p->p_lower[i] : p->p_lub) : 0.0;
}

static inline double cell_capq(const mc_contact_problem *p, int any_lower, size_t i)
{
    return (p->p_upper ? p->p_upper[i] : p->p_cap) - cell_low(p, any_lower, i);
}

/* Start value of q (a workspace): the warm start if given (start: whole, or the workspace s->z
 * of the coarse start when start_ws), else uniform on every cell (Polonsky & Keer) for force
 * control and zero (the penetrating cells enter at once) for approach control. A whole warm
 * start's sum is the serial program's (cell_low); the coarse start's goes row by row. */
static void start_value(mc_contact_solver *s, const mc_contact_problem *p, const double *start,
                        int start_ws, const mc_qproblem *qp, double *q)
{
    const size_t nl = s->nl, at = start_ws ? 0 : s->off;
    double sum = 0;
    if (start) {
        for (size_t i = 0; i < nl; i++) {
            double v = start[at + i] - (s->plow_on ? s->plow[i] : 0.0);
            if (!(v > 0))
                v = 0;
            if (qp->cap && v > qp->cap[i])
                v = qp->cap[i];
            q[i] = v;
        }
        if (start_ws || !s->dist) {
            sum = mc_contact_sum(s, q);
        } else {
            for (size_t i = 0; i < s->n; i++) {
                double v = start[i] - cell_low(p, s->plow_on, i);
                if (!(v > 0))
                    v = 0;
                if (qp->cap && v > cell_capq(p, s->plow_on, i))
                    v = cell_capq(p, s->plow_on, i);
                sum += v;
            }
        }
    }
    if (qp->control == MC_CONTROL_APPROACH) {
        if (!start)
            memset(q, 0, nl * sizeof *q);
        return;
    }
    if (sum > 0) {
        if (!qp->cap) { /* a warm start scaled to the new load */
            double f = qp->W / (s->A * sum);
            for (size_t i = 0; i < nl; i++)
                q[i] *= f;
        }
        return;
    }
    double v = qp->W / (s->A * (double)s->n);
    for (size_t i = 0; i < nl; i++)
        q[i] = qp->cap && v > qp->cap[i] ? qp->cap[i] : v;
}

int mc_contact_solve(mc_contact_solver *s, const mc_contact_problem *prob, double *pout,
                     double *uout, double *gapout, mc_contact_summary *sum, mc_error *err)
{
    /* the workspaces hold nl cells, grid cell off + i at i (contact_internal.h); prob's arrays
     * and the outputs are whole */
    const size_t n = s->n, nl = s->nl, off = s->off;
    s->applies = 0;
    memset(sum, 0, sizeof *sum);
    int rc = check_problem(s, prob, err);
    if (rc != MC_OK)
        return rc;
    const mc_contact_problem *p = prob;
    const double *start = prob->p_start;
    int start_ws = 0;
    if (s->coarse && !prob->p_start) {
        rc = coarse_start(s, prob, err);
        if (rc != MC_OK)
            return rc;
        start = s->z; /* the coarse solution prolonged into the workspace */
        start_ws = 1;
    }

    /* shift to the excess pressure: the lubricant pressure loads the half-space too */
    int any_lower = p->p_lub != 0;
    for (size_t i = 0; p->p_lower && i < n && !any_lower; i++)
        any_lower = p->p_lower[i] != 0;
    int capped = p->p_upper || isfinite(p->p_cap);
    if ((any_lower && ((!s->plow && !(s->plow = mc_zeros(nl))) ||
                       (!s->ulow && !(s->ulow = mc_zeros(nl))))) ||
        (capped && !s->capq && !(s->capq = mc_zeros(nl))))
        return mc_fail(err, MC_ERR_NOMEM,
                       "contact solver: out of memory for the bounds of %zu cells", n);
    s->plow_on = any_lower;
    double lower_sum = 0;
    if (any_lower) {
        for (size_t i = 0; i < nl; i++)
            s->plow[i] = p->p_lower ? p->p_lower[off + i] : p->p_lub;
        for (size_t i = 0; i < n; i++) /* the whole grid's, as serially (cell_low) */
            lower_sum += cell_low(p, 1, i);
        mc_contact_apply_rows(s, s->plow, s->ulow);
    }
    for (size_t i = 0; i < nl; i++)
        s->htil[i] = p->h[off + i] + (p->h_extra ? p->h_extra[off + i] : 0.0) +
                     (any_lower ? s->ulow[i] : 0.0);
    /* work relative to the lowest point: the gap h~ + u - delta then never cancels a large
     * offset (a 1 m datum under micrometre deformations kept the residual at 1e-7); minimum and
     * maximum over the ranks are exact */
    double hshift = INFINITY, hmax = -INFINITY;
    for (size_t i = 0; i < nl; i++)
        hshift = fmin(hshift, s->htil[i]);
    hshift = -mc_contact_max(s, -hshift);
    for (size_t i = 0; i < nl; i++) {
        s->htil[i] -= hshift;
        hmax = fmax(hmax, s->htil[i]);
    }
    hmax = mc_contact_max(s, hmax);
    /* s->ulow keeps K p_lower until the end */
    const double *ulow = any_lower ? s->ulow : NULL;
    const double *plow = any_lower ? s->plow : NULL;
    if (capped)
        for (size_t i = 0; i < nl; i++)
            s->capq[i] =
                (p->p_upper ? p->p_upper[off + i] : p->p_cap) - (plow ? plow[i] : 0.0);
    mc_qproblem qp = {.h = s->htil,
                      .hmin = 0.0,
                      .hmax = hmax,
                      .cap = capped ? s->capq : NULL,
                      .control = p->control,
                      .W = p->load - s->A * lower_sum,
                      .delta = p->approach - hshift};

    int method = 0;
    while (methods[method].id != s->opt.method)
        method++;
    mc_qresult res = {0};
    double *q = s->q;
    if (p->control == MC_CONTROL_FORCE && qp.W <= 0) {
        /* the lubricant alone carries the load: no solid contact (theory.md §4.2) */
        memset(q, 0, nl * sizeof *q);
        memset(s->u, 0, nl * sizeof *s->u);
        qp.delta = 0; /* contact onset: the lowest point of h~ */
        res.converged = 1;
        rc = MC_OK;
    } else {
        if (capped && p->control == MC_CONTROL_FORCE) {
            double capacity = 0; /* the whole grid's, as serially (cell_capq) */
            for (size_t i = 0; i < n; i++)
                capacity += cell_capq(p, any_lower, i);
            if (s->A * capacity <= qp.W)
                return mc_fail(err, MC_ERR_INPUT,
                               "contact: the load %g N exceeds what the whole grid can carry at "
                               "the pressure cap (%g N)",
                               p->load, p->load - qp.W + s->A * capacity);
        }
        start_value(s, p, start, start_ws, &qp, q);
        int handled = 0;
        rc = mc_contact_box_solve(s, &qp, q, &res, &handled, err);
        if (rc != MC_OK && rc != MC_NOT_CONVERGED)
            return rc;
        if (!handled) {
            int box_iterations = res.iterations;
            method_fn fn = p->control == MC_CONTROL_APPROACH ? methods[method].approach
                           : capped                         ? methods[method].capped
                                                            : methods[method].force;
            rc = fn(s, &qp, q, &res, err);
            res.iterations += box_iterations;
            if (rc != MC_OK && rc != MC_NOT_CONVERGED)
                return rc;
        }
    }

    /* back to the full pressure, the outputs (this rank's rows, then gathered whole); the
     * summary: sums serially in index order, distributed row by row over the ranks; maxima,
     * counts and flags exact */
    double pmax = -INFINITY;
    int finite = 1;
    const long pieces = s->dist ? s->nr : 1;
    for (long r = 0; r < pieces; r++) {
        const size_t a = s->dist ? mc_contact_piece_lo(s, r) : 0;
        const size_t b = s->dist ? mc_contact_piece_hi(s, r) : nl;
        double load = 0, solid = 0, ncontact = 0, ncap = 0;
        for (size_t i = a; i < b; i++) {
            double pi = (plow ? plow[i] : 0.0) + q[i];
            pout[off + i] = pi;
            finite &= isfinite(pi) && isfinite(s->u[i]);
            load += pi;
            if (q[i] > 0) {
                solid += q[i];
                ncontact++;
            }
            if (capped && q[i] >= s->capq[i])
                ncap++;
            if (pi > pmax)
                pmax = pi;
            if (uout)
                uout[off + i] = (ulow ? ulow[i] : 0.0) + s->u[i];
            if (gapout)
                gapout[off + i] = s->htil[i] + s->u[i] - qp.delta;
        }
        double *part = s->rpart + MC_CONTACT_SUMS * r;
        part[0] = load;
        part[1] = solid;
        part[2] = ncontact; /* counts: integers, exact in any order */
        part[3] = ncap;
    }
    double sums[MC_CONTACT_SUMS];
    memcpy(sums, s->rpart, sizeof sums);
    if (s->dist) {
        mc_contact_totals(s, MC_CONTACT_SUMS, sums);
        double ex[2] = {pmax, !finite}; /* the largest pressure, any non-finite value: exact */
        mc_dist_max(ex, 2);
        pmax = ex[0];
        finite = !(ex[1] > 0);
        mc_dist_gather_rows(pout, s->r0, s->nr, s->g.nx);
        if (uout)
            mc_dist_gather_rows(uout, s->r0, s->nr, s->g.nx);
        if (gapout)
            mc_dist_gather_rows(gapout, s->r0, s->nr, s->g.nx);
    }
    const double load = sums[0], solid = sums[1], ncontact = sums[2], ncap = sums[3];
    if (!finite || !isfinite(qp.delta))
        return mc_fail(err, MC_ERR_NUMERIC, "contact: the %s solver produced non-finite values",
                       methods[method].name);
    sum->solved = 1;
    sum->load = s->A * load;
    sum->solid_load = s->A * solid;
    sum->p_max = pmax;
    sum->area = s->A * (double)ncontact;
    sum->contact_ratio = (double)ncontact / (double)n;
    sum->approach = qp.delta + hshift;
    sum->iterations = res.iterations;
    sum->residual = res.residual;
    sum->converged = res.converged;
    sum->solver = methods[method].name;
    sum->backend = mc_operator_backend(s->K);
    sum->capped_cells = (int)ncap;
    if (!res.converged && rc == MC_OK)
        rc = MC_NOT_CONVERGED;
    if (rc == MC_NOT_CONVERGED)
        mc_fail(err, MC_NOT_CONVERGED,
                "contact: the %s solver did not converge in %d iterations (residual %.3g, "
                "tolerance %.3g)",
                methods[method].name, res.iterations, res.residual, s->opt.tolerance);
    return rc;
}
