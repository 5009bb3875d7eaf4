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
#include "core/psum.h"

/* Loops over the n cells run on the run's threads from MC_THREADS_MIN_CELLS cells on; their sums
 * go through core/psum.h (the same bits on any thread count). */
#define PAR(n) ((n) > MC_THREADS_MIN_CELLS)

/* sum of a[i] b[i] over the cells of S */
static double masked_dot(const double *a, const double *b, const unsigned char *S, size_t n)
{
    const mc_psum ps = mc_psum_blocks(n);
    double part[MC_PSUM_MAX_BLOCKS];
#pragma omp parallel for schedule(static) if (ps.nb > 1)
    for (long k = 0; k < ps.nb; k++) {
        double sum = 0;
        for (size_t i = mc_psum_lo(&ps, k); i < mc_psum_hi(&ps, k); i++)
            if (S[i])
                sum += a[i] * b[i];
        part[k] = sum;
    }
    return mc_psum_total(part, ps.nb);
}

/* sum(q) over the cells below their cap (*free_) and at it (*capped) */
static void split_sums(const double *q, const double *cap, size_t n, double *free_,
                       double *capped)
{
    const mc_psum ps = mc_psum_blocks(n);
    double pf[MC_PSUM_MAX_BLOCKS], pc[MC_PSUM_MAX_BLOCKS];
#pragma omp parallel for schedule(static) if (ps.nb > 1)
    for (long k = 0; k < ps.nb; k++) {
        double sf = 0, sc = 0;
        for (size_t i = mc_psum_lo(&ps, k); i < mc_psum_hi(&ps, k); i++) {
            if (cap && q[i] >= cap[i])
                sc += q[i];
            else
                sf += q[i];
        }
        pf[k] = sf;
        pc[k] = sc;
    }
    *free_ = mc_psum_total(pf, ps.nb);
    *capped = mc_psum_total(pc, ps.nb);
}

int mc_contact_pk(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res, mc_error *err)
{
    const size_t n = s->n;
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
        for (size_t i = 0; i < n; i++)
            if (q[i] > cap[i])
                q[i] = cap[i];
    }
    memset(d, 0, n * sizeof *d);
    memset(S_prev, 0, n);
    res->converged = 0;
    for (;;) {
        mc_contact_apply(s, q, u);
#pragma omp parallel for schedule(static) if (PAR(n))
        for (size_t i = 0; i < n; i++) {
            g[i] = qp->h[i] + u[i];
            S[i] = q[i] > 0 && (!cap || q[i] < cap[i]);
        }
        size_t m;
        const double gsum = mc_psum_masked(g, S, n, &m);
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
            delta = gsum / (double)m;
        }
#pragma omp parallel for schedule(static) if (PAR(n))
        for (size_t i = 0; i < n; i++)
            g[i] -= delta;
        if (!force) {
            /* approach control has no load to rescale with: bound cells whose gradient points
             * inwards join the free set directly (projected gradient), restarting the conjugate
             * recurrence on change */
            int changed = 0;
            m = 0;
            for (size_t i = 0; i < n; i++) {
                double c = cap ? cap[i] : INFINITY;
                unsigned char f = mc_contact_free(q[i], c, g[i]);
                changed |= f != S_prev[i];
                S[i] = S_prev[i] = f;
                m += f;
            }
            if (changed)
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
        const double G = masked_dot(g, g, S, n);
        double beta = !restart && G_old > 0 ? G / G_old : 0.0;
#pragma omp parallel for schedule(static) if (PAR(n))
        for (size_t i = 0; i < n; i++)
            d[i] = S[i] ? g[i] + beta * d[i] : 0.0;
        G_old = G;
        mc_contact_apply(s, d, Kd);
        if (force) {
            size_t mk;
            const double mKd = mc_psum_masked(Kd, S, n, &mk) / (double)m;
#pragma omp parallel for schedule(static) if (PAR(n))
            for (size_t i = 0; i < n; i++)
                Kd[i] -= mKd;
        }
        const double num = masked_dot(g, d, S, n), den = masked_dot(Kd, d, S, n);
        double alpha = den != 0 ? num / den : 0.0;
        int overlap = 0;
#pragma omp parallel for schedule(static) reduction(| : overlap) if (PAR(n))
        for (size_t i = 0; i < n; i++) {
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
        restart = overlap;
        if (force) { /* load balance: scale the excess of the uncapped cells */
            double sum_free, sum_cap;
            split_sums(q, cap, n, &sum_free, &sum_cap);
            double target = qp->W / s->A - sum_cap;
            if (sum_free > 0 && target > 0) {
                double f = target / sum_free;
#pragma omp parallel for schedule(static) if (PAR(n))
                for (size_t i = 0; i < n; i++)
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
