/* contact_cg.c - preconditioned constrained conjugate gradients, and the nested variant for a
 * pressure cap under force control (see contact.h).
 *
 * One solve minimises the complementary energy 1/2 q'Kq + q'(h~ - delta) over 0 <= q <= cap,
 * under force control with the load as a linear constraint (delta is its multiplier). Each
 * iteration: free set S (cells strictly inside their bounds, plus bound cells whose gradient
 * points inwards), the gradient g = gap on S, preconditioned z = P M P g (P: zero-mean projection
 * that keeps the load; M: precond.h), conjugate direction d (restarted when S changes by more than
 * RESTART_FRAC, or when it stops being a descent direction), exact step along d, projection
 * onto the bounds. One operator application per iteration (K d), plus one after an iteration that
 * clipped (u = K q is recomputed then, and before convergence is declared). The buffers are named
 * as in contact_internal.h, and as in the other methods.
 */
#include <math.h>
#include <string.h>

#include "contact/contact_internal.h"

/* Restart the conjugate recurrence only when more than this fraction of the free set changed.
 * Restarting on every change (or clipping) made rough contacts converge like steepest descent
 * (periodic self-affine 512^2: 51 iterations; 22 with this rule; 1024^2: 27). Across a small
 * change the old direction is re-projected to keep the load, and a direction that is no longer
 * a descent direction is replaced by the preconditioned residual. */
#define RESTART_FRAC 0.1

/* The per-cell loops run over the workspaces' cells s->lo .. s->hi - 1 (this rank's rows when
 * distributed, contact_internal.h),
 * on the run's threads from MC_THREADS_MIN_LOOP cells on; their sums go piece by piece through
 * mc_contact_totals, so the iterates are the same bits on any thread count, and on any rank
 * count in the MPI executable. */
#define PAR(s) ((s)->hi - (s)->lo > MC_THREADS_MIN_LOOP)


/* Mean of v over the cells with mask != 0. */
static double mean_on(mc_contact_solver *s, const double *v, const unsigned char *mask)
{
#pragma omp parallel for schedule(static) if (PAR(s))
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sum = 0, m = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++)
            if (mask[i]) {
                sum += v[i];
                m++;
            }
        s->rpart[2 * r] = sum;
        s->rpart[2 * r + 1] = m;
    }
    double t[2];
    mc_contact_totals(s, 2, t);
    return t[1] > 0 ? t[0] / t[1] : 0.0;
}

/* sum a[i] b[i] */
static double dot(mc_contact_solver *s, const double *a, const double *b)
{
#pragma omp parallel for schedule(static) if (PAR(s))
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sum = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++)
            sum += a[i] * b[i];
        s->rpart[r] = sum;
    }
    double t;
    mc_contact_totals(s, 1, &t);
    return t;
}

/* Sum of the gaps h~ + u over the loaded cells (q > 0; below the cap unless at_cap), and their
 * number in *m. */
static double loaded_gap_sum(mc_contact_solver *s, const mc_qproblem *qp, const double *q,
                             int at_cap, double *m)
{
#pragma omp parallel for schedule(static) if (PAR(s))
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sum = 0, cnt = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++)
            if (q[i] > 0 && (at_cap || !qp->cap || q[i] < qp->cap[i])) {
                sum += qp->h[i] + s->u[i];
                cnt++;
            }
        s->rpart[2 * r] = sum;
        s->rpart[2 * r + 1] = cnt;
    }
    double t[2];
    mc_contact_totals(s, 2, t);
    *m = t[1];
    return t[0];
}

/* Lagrange multiplier of the load constraint: the mean gap over the loaded cells. */
static double force_delta(mc_contact_solver *s, const mc_qproblem *qp, const double *q)
{
    double m;
    double sum = loaded_gap_sum(s, qp, q, 0, &m);
    if (m == 0) /* every loaded cell sits at the cap: take the loaded cells */
        sum = loaded_gap_sum(s, qp, q, 1, &m);
    return m > 0 ? sum / m : 0.0;
}

/* The projected step q - alpha d onto 0 <= q <= cap on the free set, u - alpha Kd everywhere;
 * *qsum receives sum(q) after the step, *clipped whether a bound was hit (on any rank). */
static void take_step(mc_contact_solver *s, const unsigned char *S, const double *cap,
                      double alpha, double *q, double *qsum, int *clipped)
{
    const double *d = s->dir, *Kd = s->kdir;
    double *u = s->u;
    int clip = 0;
#pragma omp parallel for schedule(static) reduction(| : clip) if (PAR(s))
    for (long r = 0; r < mc_contact_pieces(s); r++) {
        double sum = 0;
        for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++) {
            u[i] -= alpha * Kd[i];
            if (!S[i]) {
                sum += q[i];
                continue;
            }
            double v = q[i] - alpha * d[i];
            const double c = cap ? cap[i] : INFINITY;
            if (v < 0) {
                v = 0;
                clip = 1;
            } else if (v > c) {
                v = c;
                clip = 1;
            }
            q[i] = v;
            sum += v;
        }
        s->rpart[r] = sum;
    }
    mc_contact_totals(s, 1, qsum);
    *clipped = mc_contact_max(s, clip) > 0;
}

int mc_contact_cg(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res, mc_error *err)
{
    const size_t n = s->nl, lo = s->lo, hi = s->hi;
    const int force = qp->control == MC_CONTROL_FORCE;
    const double *cap = qp->cap;
    double *u = s->u, *g = s->gap, *z = s->z, *d = s->dir, *Kd = s->kdir;
    unsigned char *S = s->free_set, *S_prev = s->free_prev;
    double gz_old = 1, delta = qp->delta;
    int restart = 1, fresh = 0, it = 0, rc = MC_OK;

    mc_contact_apply_rows(s, q, u);
    fresh = 1;
    memset(S_prev, 0, n);
    res->converged = 0;
    for (;;) {
        if (force)
            delta = force_delta(s, qp, q);
#pragma omp parallel for schedule(static) if (PAR(s))
        for (size_t i = lo; i < hi; i++)
            g[i] = qp->h[i] + u[i] - delta;
        res->residual = mc_contact_residual(s, qp, q, u, delta);
        if (res->residual <= s->opt.tolerance) {
            if (fresh) {
                res->converged = 1;
                break;
            }
            mc_contact_apply_rows(s, q, u); /* confirm on an exact K q, free of update drift */
            fresh = 1;
            continue;
        }
        if (it >= s->opt.max_iterations)
            break;
        it++;

#pragma omp parallel for schedule(static) if (PAR(s))
        for (long r = 0; r < mc_contact_pieces(s); r++) {
            double m = 0, nchanged = 0;
            for (size_t i = mc_contact_piece_lo(s, r); i < mc_contact_piece_hi(s, r); i++) {
                double c = cap ? cap[i] : INFINITY;
                unsigned char free_ = mc_contact_free(q[i], c, g[i]);
                S[i] = free_;
                nchanged += free_ != S_prev[i];
                m += free_;
            }
            s->rpart[2 * r] = m;
            s->rpart[2 * r + 1] = nchanged;
        }
        double counts[2]; /* free cells, changed cells: exact in doubles */
        mc_contact_totals(s, 2, counts);
        const double m = counts[0], nchanged = counts[1];
        if (m == 0) /* nothing can move although the residual is above tolerance */
            break;
        if (nchanged > 0) {
            /* distributed, the preconditioner bounds the set over the ranks (precond.h) */
            rc = s->dist ? mc_precond_set_mask_rows(s->pc, S, err)
                         : mc_precond_set_mask(s->pc, S, err);
            /* a plan that failed on one rank fails the solve on all (they must stay in step) */
            if (mc_contact_max(s, rc != MC_OK) > 0)
                return rc != MC_OK ? rc
                                   : mc_fail(err, MC_ERR_NOMEM,
                                             "contact cg: another process could not plan the "
                                             "preconditioner");
            memcpy(S_prev, S, n);
            if (nchanged > RESTART_FRAC * m)
                restart = 1;
        }
        if (force) { /* P g: directions must keep sum(q) */
            double mg = mean_on(s, g, S);
#pragma omp parallel for schedule(static) if (PAR(s))
            for (size_t i = lo; i < hi; i++)
                g[i] = S[i] ? g[i] - mg : 0.0;
        } else {
#pragma omp parallel for schedule(static) if (PAR(s))
            for (size_t i = lo; i < hi; i++)
                if (!S[i])
                    g[i] = 0.0;
        }
        /* distributed, the box's FFT runs over the ranks on their rows of g and z (precond.h) */
        if (s->dist)
            mc_precond_apply_slab(s->pc, S, g, z);
        else
            mc_precond_apply(s->pc, S, g, z);
        if (force) {
            double mz = mean_on(s, z, S);
#pragma omp parallel for schedule(static) if (PAR(s))
            for (size_t i = lo; i < hi; i++)
                if (S[i])
                    z[i] -= mz;
        }
        double gz = dot(s, g, z);
        if (!(gz > 0)) { /* M lost definiteness on this set (round-off): steepest descent */
            memcpy(z + lo, g + lo, (hi - lo) * sizeof *z);
            gz = dot(s, g, g);
            restart = 1;
            if (!(gz > 0))
                break;
        }
        double beta = restart ? 0.0 : gz / gz_old;
#pragma omp parallel for schedule(static) if (PAR(s))
        for (size_t i = lo; i < hi; i++)
            d[i] = S[i] ? z[i] + beta * d[i] : 0.0;
        if (force && beta != 0.0) { /* the old direction lost cells that left S: keep the load */
            double md = mean_on(s, d, S);
#pragma omp parallel for schedule(static) if (PAR(s))
            for (size_t i = lo; i < hi; i++)
                if (S[i])
                    d[i] -= md;
        }
        double gd = dot(s, g, d);
        if (!(gd > 0)) { /* the set changed under the recurrence: not a descent direction */
            memcpy(d + lo, z + lo, (hi - lo) * sizeof *d);
            gd = gz;
        }
        mc_contact_apply_rows(s, d, Kd);
        double dkd = dot(s, d, Kd);
        if (!(dkd > 0)) {
            rc = mc_fail(err, MC_ERR_NUMERIC, "contact cg: non-positive curvature d'Kd = %g", dkd);
            break;
        }
        double alpha = gd / dkd, qsum;
        int clipped;
        take_step(s, S, cap, alpha, q, &qsum, &clipped);
        fresh = 0;
        if (clipped) {
            if (force && !cap && qsum > 0) { /* clipping added load: restore the balance */
                double f = qp->W / (s->A * qsum);
#pragma omp parallel for schedule(static) if (PAR(s))
                for (size_t i = lo; i < hi; i++)
                    q[i] *= f;
            }
            mc_contact_apply_rows(s, q, u);
            fresh = 1;
        }
        restart = 0;
        gz_old = gz;
    }
    if (force)
        qp->delta = delta;
    res->iterations = it;
    if (rc != MC_OK)
        return rc;
    return res->converged ? MC_OK : MC_NOT_CONVERGED;
}

/* ---- nested variant: delta from the load, bound-constrained solves at fixed delta ---------- */

/* One bound-constrained solve at fixed delta; *load = A sum(q) of its result. An inner solve that
 * stops short still gives a usable iterate (MC_NOT_CONVERGED): the caller goes on with it and
 * judges the final state by the residual. */
static int solve_at(mc_contact_solver *s, const mc_qproblem *qp, double delta, double *q,
                    double *load, int *iters, double *x_last, mc_error *err)
{
    mc_qproblem inner = *qp;
    inner.control = MC_CONTROL_APPROACH;
    inner.delta = delta;
    *x_last = delta;
    mc_qresult r = {0};
    int rc = mc_contact_cg(s, &inner, q, &r, err);
    *iters += r.iterations;
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    const double sum = mc_contact_sum(s, q); /* row by row over the ranks when distributed */
    *load = s->A * sum;
    return MC_OK;
}

int mc_contact_nested(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res,
                      mc_error *err)
{
    int iters = 0, rc;
    res->converged = 0;
    /* the uncapped solution gives a lower bracket: capping lowers the load at equal delta */
    mc_qproblem free_ = *qp;
    free_.cap = NULL;
    mc_qresult r0 = {0};
    rc = mc_contact_cg(s, &free_, q, &r0, err);
    iters += r0.iterations;
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    for (size_t i = s->lo; i < s->hi; i++) /* this rank's rows: cg keeps to them */
        if (q[i] > qp->cap[i])
            q[i] = qp->cap[i];
    const double hmin = qp->hmin;
    double lo, Wlo, hi, Whi, x0 = free_.delta, W0, x = x0;
    rc = solve_at(s, qp, x0, q, &W0, &iters, &x, err);
    if (rc != MC_OK)
        goto out;
    if (W0 >= qp->W) { /* already enough: any delta <= min h~ carries nothing */
        hi = x0;
        Whi = W0;
        lo = hmin;
        Wlo = 0;
    } else { /* expand upwards until the capped contact carries the load */
        lo = x0;
        Wlo = W0;
        double step = fmax(x0 - hmin, 1e-300);
        hi = lo;
        Whi = Wlo;
        for (int k = 0; Whi < qp->W; k++) {
            if (k > 200) {
                rc = mc_fail(err, MC_NOT_CONVERGED, "contact nested: cannot bracket the approach");
                goto out;
            }
            lo = hi;
            Wlo = Whi;
            step *= 2;
            hi = lo + step;
            rc = solve_at(s, qp, hi, q, &Whi, &iters, &x, err);
            if (rc != MC_OK)
                goto out;
        }
    }
    /* Illinois regula falsi on W(delta) = W: W is continuous and non-decreasing */
    const double tol = s->opt.tolerance;
    double Wx = Whi;
    int side = 0;
    for (int k = 0; fabs(Wx - qp->W) > tol * qp->W && k < s->opt.max_iterations; k++) {
        double flo = Wlo - qp->W, fhi = Whi - qp->W;
        x = (fhi - flo) != 0 ? hi - fhi * (hi - lo) / (fhi - flo) : 0.5 * (lo + hi);
        if (!(x > lo && x < hi))
            x = 0.5 * (lo + hi);
        rc = solve_at(s, qp, x, q, &Wx, &iters, &x, err);
        if (rc != MC_OK)
            goto out;
        if (Wx < qp->W) {
            lo = x;
            Wlo = Wx;
            if (side == -1)
                Whi = qp->W + 0.5 * (Whi - qp->W);
            side = -1;
        } else {
            hi = x;
            Whi = Wx;
            if (side == 1)
                Wlo = qp->W + 0.5 * (Wlo - qp->W);
            side = 1;
        }
        if (hi - lo <= 1e-15 * fmax(fabs(hi), fabs(lo)))
            break;
    }
out:
    /* whatever stopped the search, report the state the last solve left: its delta and residual */
    qp->delta = x;
    res->residual = mc_contact_residual(s, qp, q, s->u, x);
    res->converged = rc == MC_OK && res->residual <= s->opt.tolerance;
    res->iterations = iters;
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    return res->converged ? MC_OK : MC_NOT_CONVERGED;
}
