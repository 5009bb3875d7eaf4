/* contact_box.c - the cg solve restricted to the contact's bounding box (see contact.h,
 * "Restriction"). Outside the box the excess pressure is held at zero; the full operator then
 * measures the gap there, and penetrating cells widen the box. */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "contact/contact_internal.h"
#include "operator/box.h"

#define BOX_ROUNDS 4

#define BOX_MARGIN 4 /* cells at least, each side */

/* The box around the cells flagged in mark (a workspace: this rank's rows when distributed, the
 * bound then reduced over the ranks, operator/box.h), widened by the solvers' margin, and never
 * smaller than prev when given; 0 if no cell is flagged. Collective. */
static int box_of(const mc_contact_solver *s, const unsigned char *mark, const mc_box *prev,
                  mc_box *b)
{
    if (!(s->dist ? mc_box_bound_rows(&s->g, mark, s->r0, s->nr, b)
                  : mc_box_bound(&s->g, mark, NULL, b)))
        return 0;
    mc_box_widen(&s->g, mc_box_margin(b->nx, BOX_MARGIN), mc_box_margin(b->ny, BOX_MARGIN), b);
    if (prev) /* never shrink while widening */
        *b = mc_box_union(b, prev);
    return 1;
}

static void free_box(mc_contact_solver *s)
{
    mc_contact_destroy(&s->box);
    mc_operator_destroy(&s->box_op);
    mc_free(s->box_h);
    mc_free(s->box_cap);
    mc_free(s->box_q);
    s->box_h = s->box_cap = s->box_q = NULL;
    s->bnx = s->bny = 0;
}

/* A box solver of the box's size (kept while the size stays). */
static int ensure_box(mc_contact_solver *s, const mc_box *b, mc_error *err)
{
    if (s->box && s->bnx == b->nx && s->bny == b->ny)
        return MC_OK;
    free_box(s);
    mc_grid g = s->g;
    g.nx = b->nx;
    g.ny = b->ny;
    g.periodic_x = s->g.periodic_x && b->nx == s->g.nx;
    g.periodic_y = s->g.periodic_y && b->ny == s->g.ny;
    int rc = mc_operator_plan_love(&g, s->opt.estar, mc_operator_backend(s->K), &s->box_op, err);
    if (rc != MC_OK)
        return rc;
    mc_contact_options o = s->opt;
    o.estar = 0; /* started from the fine solution's start: no coarse levels inside */
    o.no_box = 1;
    if ((rc = mc_contact_create(s->box_op, &o, &s->box, err)) != MC_OK)
        return rc;
    size_t nb = mc_grid_cells(&g);
    if (!(s->box_h = mc_zeros(nb)) || !(s->box_cap = mc_zeros(nb)) || !(s->box_q = mc_zeros(nb)))
        return mc_fail(err, MC_ERR_NOMEM, "contact: out of memory for the %d x %d box", b->nx,
                       b->ny);
    s->bnx = b->nx;
    s->bny = b->ny;
    return MC_OK;
}

int mc_contact_box_solve(mc_contact_solver *s, mc_qproblem *qp, double *q, mc_qresult *res,
                         int *handled, mc_error *err)
{
    /* q, qp's arrays, s->u and the marks are workspaces: this rank's rows r0 .. r0 + nr - 1
     * when distributed (contact_internal.h); the box's arrays are whole on every rank */
    const size_t n = s->n, nl = s->nl;
    const int nx = s->g.nx, r0 = s->r0, r1 = s->r0 + s->nr;
    unsigned char *mark = s->free_prev; /* scratch until the method runs */
    *handled = 0;
    s->box_cells = s->box_applies = 0;
    if (s->opt.method != MC_METHOD_CG || s->opt.no_box || !(s->opt.estar > 0))
        return MC_OK;
    for (size_t i = 0; i < nl; i++)
        mark[i] = q[i] > 0;
    mc_box b;
    if (!box_of(s, mark, NULL, &b) ||
        (double)mc_box_cells(&b) > MC_BOX_FRACTION * (double)n)
        return MC_OK;
    int iters = 0;
    for (int round = 0; round < BOX_ROUNDS; round++) {
        int rc = ensure_box(s, &b, err);
        if (rc != MC_OK) {
            free_box(s);
            return rc;
        }
        /* the box's rows this rank holds (grid rows j0 .. j1 - 1), then every rank's */
        const int j0 = b.j0 > r0 ? b.j0 : r0, j1 = b.j0 + b.ny < r1 ? b.j0 + b.ny : r1;
        for (int j = j0; j < j1; j++)
            for (int i = 0; i < b.nx; i++) {
                size_t f = (size_t)(j - r0) * nx + (b.i0 + i), k = (size_t)(j - b.j0) * b.nx + i;
                s->box_h[k] = qp->h[f];
                s->box_cap[k] = qp->cap ? qp->cap[f] : INFINITY;
                s->box_q[k] = q[f];
            }
        if (s->dist) {
            const int br0 = j1 > j0 ? j0 - b.j0 : 0, bnr = j1 > j0 ? j1 - j0 : 0;
            mc_dist_gather_rows(s->box_h, br0, bnr, b.nx);
            mc_dist_gather_rows(s->box_cap, br0, bnr, b.nx);
            mc_dist_gather_rows(s->box_q, br0, bnr, b.nx);
        }
        mc_contact_problem bp = {.h = s->box_h,
                                 .p_cap = INFINITY,
                                 .p_upper = qp->cap ? s->box_cap : NULL,
                                 .control = qp->control,
                                 .load = qp->W,
                                 .approach = qp->delta,
                                 .p_start = s->box_q};
        mc_contact_summary sum;
        rc = mc_contact_solve(s->box, &bp, s->box_q, NULL, NULL, &sum, err);
        iters += sum.iterations;
        s->box_applies += mc_contact_last_applies(s->box);
        if (rc != MC_OK && rc != MC_NOT_CONVERGED)
            return rc;
        memset(q, 0, nl * sizeof *q);
        for (int j = j0; j < j1; j++)
            memcpy(q + (size_t)(j - r0) * nx + b.i0, s->box_q + (size_t)(j - b.j0) * b.nx,
                   (size_t)b.nx * sizeof *q);
        qp->delta = sum.approach;
        mc_contact_apply_rows(s, q, s->u); /* the full operator: the gap outside the box */
        double tol = s->opt.tolerance * mc_contact_gap_scale(s, qp, qp->delta);
        int outside = 0;
        for (int j = r0; j < r1; j++)
            for (int i = 0; i < nx; i++) {
                size_t f = (size_t)(j - r0) * nx + i;
                int in = i >= b.i0 && i < b.i0 + b.nx && j >= b.j0 && j < b.j0 + b.ny;
                mark[f] = !in && qp->h[f] + s->u[f] - qp->delta < -tol;
                outside |= mark[f];
            }
        outside = mc_contact_max(s, outside) > 0; /* on any rank */
        if (!outside) {
            s->box_cells = mc_box_cells(&b);
            res->iterations = iters;
            res->residual = mc_contact_residual(s, qp, q, s->u, qp->delta);
            res->converged = res->residual <= s->opt.tolerance;
            *handled = 1;
            return res->converged ? MC_OK : MC_NOT_CONVERGED;
        }
        mc_box wider;
        if (!box_of(s, mark, &b, &wider) ||
            (double)mc_box_cells(&wider) > MC_BOX_FRACTION * (double)n)
            break; /* q is now a good warm start for the full-grid solve */
        b = wider;
    }
    res->iterations = iters;
    return MC_OK;
}
