/* contact_pk.c - plain Polonsky & Keer (1999) constrained conjugate gradients, as written in
 * theory.md §4.5, on the excess pressure (lower bound, §4.2) and with the free-set cap variant
 * (§4.5), which falls back to the nested solver when its free set empties. Kept unpreconditioned
 * on purpose: it is the baseline the preconditioned method is measured against. Two operator
 * applications per iteration (K q and K d), as in the original. The paper's g (gap), t
 * (direction), I_c (free set) and tau (step) are here g, d, S and alpha, the names of
 * contact_internal.h shared with the other methods.
 */
#include <math.h>
#include <string.h>

#include "contact/contact_internal.h"

/* The per-cell loops run over the workspaces' cells s->lo .. s->hi - 1 (this rank's rows when
 * distributed, contact_internal.h),
 * on the run's threads from MC_THREADS_MIN_LOOP cells on; their sums go piece by piece through
 * mc_contact_totals (the same bits on any thread count, and on any rank count). */
#define PAR(s) ((s)->hi - (s)->lo > MC_THREADS_MIN_LOOP)


/* sum of a[i] b[i] over the cells of S (b == NULL: of a[i]), and their number in *count */
static double masked_dot(mc_contact_solver *s, const double *a, const double *b,
                         const unsigned char *S, double *count)
{
#pragma omp parallel for schedule(static) if (PAR(s))
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sum = 0, m = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++)
            if (S[i]) {
                sum += b ? a[i] * b[i] : a[i];
                m++;
            }
        s->rpart[2 * r] = sum;
        s->rpart[2 * r + 1] = m;
    }
    double t[2];
    mc_contact_totals(s, 2, t);
    if (count)
        *count = t[1];
    return t[0];
}

/* sum(q) over the cells below their cap (*free_) and at it (*capped) */
static void split_sums(mc_contact_solver *s, const double *q, const double *cap, double *free_,
                       double *capped)
{
#pragma omp parallel for schedule(static) if (PAR(s))
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sf = 0, sc = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++) {
            if (cap && q[i] >= cap[i])
                sc += q[i];
            else
                sf += q[i];
        }
        s->rpart[2 * r] = sf;
        s->rpart[2 * r + 1] = sc;
    }
    double t[2];
    mc_contact_totals(s, 2, t);
    *free_ = t[0];
    *capped = t[1];
}

int mc_contact_pk(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res, mc_error *err)
{
    const size_t n = s->nl, lo = s->lo, hi = s->hi;
    const int force = qp->control == MC_CONTROL_FORCE;
    const double *cap = qp->cap;
    double *u = s->u, *g = s->gap, *d = s->dir, *Kd = s->kdir;
    unsigned char *S = s->free_set, *S_prev = s->free_prev;
    double G_old = 1, delta = qp->delta;
    int restart = 1, it = 0;

    if (force && cap) {
        /* theory.md §4.5: start from the converged uncapped solution */
        mc_qproblem free_ = *qp;
        free_.cap = NULL;
        mc_qresult r0 = {0};
        int rc = mc_contact_pk(s, &free_, q, &r0, err);
        it += r0.iterations;
        if (rc != MC_OK && rc != MC_NOT_CONVERGED)
            return rc;
        for (size_t i = lo; i < hi; i++)
            if (q[i] > cap[i])
                q[i] = cap[i];
    }
    memset(d, 0, n * sizeof *d);
    memset(S_prev, 0, n);
    res->converged = 0;
    for (;;) {
        mc_contact_apply_rows(s, q, u);
#pragma omp parallel for schedule(static) if (PAR(s))
        for (size_t i = lo; i < hi; i++) {
            g[i] = qp->h[i] + u[i];
            S[i] = q[i] > 0 && (!cap || q[i] < cap[i]);
        }
        double m;
        const double gsum = masked_dot(s, g, NULL, S, &m);
        if (force) {
            if (m == 0) {
                if (cap) { /* the free set emptied: P&K's cap variant breaks down here */
                    res->iterations = it;
                    mc_qresult rn = {0};
                    int rc = mc_contact_nested(s, qp, q, &rn, err);
                    res->iterations += rn.iterations;
                    res->residual = rn.residual;
                    res->converged = rn.converged;
                    return rc;
                }
                break;
            }
            delta = gsum / m;
        }
#pragma omp parallel for schedule(static) if (PAR(s))
        for (size_t i = lo; i < hi; i++)
            g[i] -= delta;
        if (!force) {
            /* approach control has no load to rescale with: bound cells whose gradient points
             * inwards join the free set directly (projected gradient), restarting the conjugate
             * recurrence on change */
            int changed = 0;
            for (size_t i = lo; i < hi; i++) {
                double c = cap ? cap[i] : INFINITY;
                unsigned char f = mc_contact_free(q[i], c, g[i]);
                changed |= f != S_prev[i];
                S[i] = S_prev[i] = f;
            }
            if (mc_contact_max(s, changed) > 0)
                restart = 1;
        }
        res->residual = mc_contact_residual(s, qp, q, u, delta);
        if (res->residual <= s->opt.tolerance) {
            res->converged = 1;
            break;
        }
        if (it >= s->opt.max_iterations)
            break;
        it++;
        const double G = masked_dot(s, g, g, S, NULL);
        double beta = !restart && G_old > 0 ? G / G_old : 0.0;
#pragma omp parallel for schedule(static) if (PAR(s))
        for (size_t i = lo; i < hi; i++)
            d[i] = S[i] ? g[i] + beta * d[i] : 0.0;
        G_old = G;
        mc_contact_apply_rows(s, d, Kd);
        if (force) {
            const double mKd = masked_dot(s, Kd, NULL, S, NULL) / m;
#pragma omp parallel for schedule(static) if (PAR(s))
            for (size_t i = lo; i < hi; i++)
                Kd[i] -= mKd;
        }
        const double num = masked_dot(s, g, d, S, NULL), den = masked_dot(s, Kd, d, S, NULL);
        double alpha = den != 0 ? num / den : 0.0;
        int overlap = 0;
#pragma omp parallel for schedule(static) reduction(| : overlap) if (PAR(s))
        for (size_t i = lo; i < hi; i++) {
            double c = cap ? cap[i] : INFINITY;
            if (S[i]) {
                double v = q[i] - alpha * d[i];
                q[i] = v < 0 ? 0 : (v > c ? c : v);
            } else if (q[i] <= 0 && g[i] < 0) { /* penetrating cell at the lower bound */
                q[i] = fmin(-alpha * g[i], c);
                overlap = 1;
            } else if (cap && q[i] >= c && g[i] > 0) { /* capped cell that wants to open */
                q[i] = fmax(c - alpha * g[i], 0.0);
                overlap = 1;
            }
        }
        restart = mc_contact_max(s, overlap) > 0;
        if (force) { /* load balance: scale the excess of the uncapped cells */
            double sum_free, sum_cap;
            split_sums(s, q, cap, &sum_free, &sum_cap);
            double target = qp->W / s->A - sum_cap;
            if (sum_free > 0 && target > 0) {
                double f = target / sum_free;
#pragma omp parallel for schedule(static) if (PAR(s))
                for (size_t i = lo; i < hi; i++)
                    if (!(cap && q[i] >= cap[i]))
                        q[i] = cap ? fmin(q[i] * f, cap[i]) : q[i] * f;
            }
        }
    }
    if (force)
        qp->delta = delta;
    res->iterations = it;
    return res->converged ? MC_OK : MC_NOT_CONVERGED;
}
