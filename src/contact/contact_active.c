/* contact_active.c - the paper's reference solver (Mevissen et al. 2025, Fig. 3-1): a dense
 * influence matrix and Cholesky solves on the set C of free cells.
 *
 *   1. C = all cells.
 *   2. Solve K_CC q_C = delta 1 - h~_C - K_CU cap_U, with A sum(q) = W for force control (the
 *      "constant part" of cells held at a bound moves to the right-hand side).
 *   3. Cells of C with q < 0 leave C (held at the lower bound); with q > cap they leave to the cap.
 *   4. Cells held at the lower bound that penetrate (g < 0), or held at the cap with g > 0,
 *      re-enter C: the rule the paper's description omits (theory.md §11, step 4).
 *   5. Repeat until nothing changes.
 * K_CC is symmetric positive definite: Cholesky (GSL), with the load equation eliminated by
 * superposition, q_C = x1 + delta x2 (under force control on K + c 1 1' where K alone is singular
 * or indefinite: periodic grids, see solve_free). Under force control a set with every cell held
 * at a bound and the load not met frees the held cells nearest to switching (release_held); under
 * approach control on a grid periodic in x and y the start is the penetrating cells, not all; a
 * stable set is accepted only if it meets the stopping rule of contact.h. The matrix is assembled
 * from impulse responses of the operator, so the reference sees exactly the kernel of the backend
 * it runs on.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "contact/contact_internal.h"

enum { AT_FREE = 0, AT_LOWER = 1, AT_CAP = 2 };

int mc_contact_active_set_prepare(mc_contact_solver *s, mc_error *err)
{
    const size_t n = s->n;
    size_t nn;
    if (!mc_size_mul(n, n, &nn) || !(s->dense = mc_malloc(nn * sizeof(double))) ||
        !(s->factor = mc_malloc(nn * sizeof(double))) || !(s->map = mc_malloc(n * sizeof(size_t))))
        return mc_fail(err, MC_ERR_NOMEM, "active-set: out of memory for a %zu x %zu matrix", n, n);
    /* column j = K e_j (e_j in the scratch z); K is symmetric, so rows equal columns */
    double *e = s->z;
    memset(e, 0, n * sizeof *e);
    for (size_t j = 0; j < n; j++) {
        e[j] = 1.0;
        mc_operator_apply(s->K, e, s->dense + j * n);
        e[j] = 0.0;
    }
    return MC_OK;
}

/* Solve the free block by Cholesky; returns the new q on C in q and the approach. */
static int solve_free(mc_contact_solver *s, const mc_qproblem *qp, const unsigned char *state,
                      double *q, double *delta, mc_error *err)
{
    const size_t n = s->n;
    size_t m = 0, *map = s->map;
    double *x1 = s->gap, *x2 = s->z; /* scratch */
    for (size_t i = 0; i < n; i++)
        if (state[i] == AT_FREE)
            map[m++] = i;
    if (m == 0)
        return MC_OK;
    /* Under force control K + c 1 1' gives the same q for any c, because sum(q) = W/A is
     * imposed: it only adds c W/A to the approach, taken off below. It is needed where K is not
     * positive definite although the problem is well posed: periodic in x and y, K has zero mean
     * (operator.h) and is singular (K 1 = 0), and so is K_CC with every cell free; periodic along
     * one axis, the log kernel's constant is arbitrary (metres), which makes K indefinite on
     * domains of metres. Both are positive definite on loads of zero sum, so a large enough c
     * works: start at the self-influence K_00 on periodic grids and double it while Cholesky
     * fails. */
    const int force = qp->control == MC_CONTROL_FORCE;
    double shift = force && (s->g.periodic_x || s->g.periodic_y) ? s->dense[0] : 0.0;
    double *F = s->factor;
    int st;
    for (int attempt = 0;; attempt++) {
        for (size_t a = 0; a < m; a++) {
            const double *row = s->dense + map[a] * n;
            double b = -qp->h[map[a]];
            for (size_t j = 0; j < n; j++)
                if (state[j] == AT_CAP)
                    b -= (row[j] + shift) * qp->cap[j];
            x1[a] = b;
            x2[a] = 1.0;
            for (size_t c = 0; c < m; c++)
                F[a * m + c] = row[map[c]] + shift;
        }
        gsl_matrix_view Fv = gsl_matrix_view_array(F, m, m);
        gsl_vector_view v1 = gsl_vector_view_array(x1, m), v2 = gsl_vector_view_array(x2, m);
        st = gsl_linalg_cholesky_decomp1(&Fv.matrix);
        if (!st)
            st = gsl_linalg_cholesky_svx(&Fv.matrix, &v1.vector);
        if (!st)
            st = gsl_linalg_cholesky_svx(&Fv.matrix, &v2.vector);
        if (!st || !force || attempt >= 64)
            break;
        shift = shift > 0 ? 2 * shift : fabs(s->dense[0]);
    }
    if (st)
        return mc_fail(err, MC_ERR_NUMERIC, "active-set: Cholesky failed (%s) on %zu free cells",
                       gsl_strerror(st), m);
    double d = qp->delta;
    if (qp->control == MC_CONTROL_FORCE) {
        double held = 0, s1 = 0, s2 = 0;
        for (size_t i = 0; i < n; i++)
            if (state[i] == AT_CAP)
                held += qp->cap[i];
        for (size_t a = 0; a < m; a++) {
            s1 += x1[a];
            s2 += x2[a];
        }
        d = (qp->W / s->A - held - s1) / s2;
    }
    for (size_t i = 0; i < n; i++)
        q[i] = state[i] == AT_CAP ? qp->cap[i] : 0.0;
    for (size_t a = 0; a < m; a++)
        q[map[a]] = x1[a] + d * x2[a];
    *delta = d - shift * qp->W / s->A;
    return MC_OK;
}

/* Force control with every cell held at a bound: the load equation has no unknown left, so the
 * approach of the last solve is stale and the held load differs from W in general; the set can
 * look stable although it is no solution. Free the held cells nearest to switching (s->u = K q
 * of the held values): when the held load exceeds W, the capped cells of largest h~ + u, as many
 * as it takes for their caps to cover the excess; else the lower-bound cell of smallest h~ + u.
 * Returns 1 when it freed any. */
static int release_held(mc_contact_solver *s, const mc_qproblem *qp, unsigned char *state,
                        const double *q)
{
    const size_t n = s->n;
    double held = 0;
    for (size_t i = 0; i < n; i++) {
        if (state[i] == AT_FREE)
            return 0;
        held += q[i];
    }
    double excess = held - qp->W / s->A;
    if (fabs(excess) <= s->opt.tolerance * qp->W / s->A)
        return 0;
    int freed = 0;
    do {
        size_t pick = n;
        double best = excess > 0 ? -INFINITY : INFINITY;
        for (size_t i = 0; i < n; i++) {
            double v = qp->h[i] + s->u[i];
            int nearer = excess > 0 ? state[i] == AT_CAP && v > best
                                    : state[i] == AT_LOWER && v < best;
            if (nearer) {
                best = v;
                pick = i;
            }
        }
        if (pick == n)
            break;
        state[pick] = AT_FREE;
        freed = 1;
        excess -= q[pick];
    } while (excess > 0);
    return freed;
}

int mc_contact_active_set(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res,
                          mc_error *err)
{
    const size_t n = s->n;
    unsigned char *state = s->free_set; /* AT_FREE, AT_LOWER or AT_CAP */
    double delta = qp->delta;
    mc_gsl_quiet();
    memset(state, AT_FREE, n);
    /* periodic in x and y, K is singular (K 1 = 0): under approach control start from the
     * penetrating cells, a proper subset whenever a solution exists (it needs delta < mean h~) */
    if (qp->control == MC_CONTROL_APPROACH && s->g.periodic_x && s->g.periodic_y)
        for (size_t i = 0; i < n; i++)
            state[i] = qp->h[i] < delta ? AT_FREE : AT_LOWER;
    res->converged = 0;
    int it = 0;
    for (;;) {
        if (qp->control == MC_CONTROL_FORCE)
            release_held(s, qp, state, q);
        int rc = solve_free(s, qp, state, q, &delta, err);
        if (rc != MC_OK)
            return rc;
        it++;
        int changed = 0;
        for (size_t i = 0; i < n; i++) {
            if (state[i] != AT_FREE)
                continue;
            if (q[i] < 0) {
                state[i] = AT_LOWER;
                q[i] = 0;
                changed = 1;
            } else if (qp->cap && q[i] > qp->cap[i]) {
                state[i] = AT_CAP;
                q[i] = qp->cap[i];
                changed = 1;
            }
        }
        /* gap from the dense matrix; re-entry of penetrating or opening held cells */
        for (size_t i = 0; i < n; i++) {
            const double *row = s->dense + i * n;
            double ui = 0;
            for (size_t j = 0; j < n; j++)
                ui += row[j] * q[j];
            s->u[i] = ui;
        }
        if (!changed) {
            for (size_t i = 0; i < n; i++) {
                double g = qp->h[i] + s->u[i] - delta;
                if ((state[i] == AT_LOWER && g < 0) || (state[i] == AT_CAP && g > 0)) {
                    state[i] = AT_FREE;
                    changed = 1;
                }
            }
        }
        if (!changed) {
            res->converged = 1;
            break;
        }
        if (it >= s->opt.max_iterations)
            break;
    }
    qp->delta = delta;
    res->iterations = it;
    res->residual = mc_contact_residual(s, qp, q, s->u, delta);
    /* a stable active set is a solution only if it meets the stopping rule of contact.h */
    if (!(res->residual <= s->opt.tolerance))
        res->converged = 0;
    return res->converged ? MC_OK : MC_NOT_CONVERGED;
}
