/* loop.c - the semi-analytical elastic-plastic contact loop (loop.h; docs/theory.md §9). */
#include "plastic/loop.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "kernels/invariants.h"
#include "kernels/kernel.h"
#include "plastic/anderson.h"
#include "plastic/increment.h"
#include "plastic/return_map.h"
#include "stress/stress.h"
#include "stress/traction.h"

/* The local-global fixed point (theory §9.7). Its constants change the work, never the fixed
 * point (the global sweep's test settles it); chosen on the 64 x 32 .. 256 x 128 x 16 running-in
 * steps of the default scene at 350 rpm (applies 18, 37, 62 -> 6, 20, 19).
 * NEAR_MARGIN: a cell joins the local solve when its trial von Mises stress is within this
 * fraction of its yield stress (besides the cells that yield or carry an increment): 0.2 put a
 * third of the volume in the set for the same global applications as 0.05.
 * NEAR_FORCING: the local solve stops at this fraction of the global sweep's relative change
 * (at least tol_plastic / 2); 0.3 took more global applications (35 against 20 at 128 x 64).
 * NEAR_SPREAD: a source's change is spread to its neighbours once it exceeds this fraction of
 * the local tolerance (the near-field stress then lags by at most that much; it cut the
 * spreads sixfold at the same counts).
 * NEAR_MAX_SWEEPS: local sweeps per global sweep at most. */
#define NEAR_MARGIN 0.05
#define NEAR_FORCING 0.1
#define NEAR_SPREAD 0.05
#define NEAR_MAX_SWEEPS 50

/* Everything one run needs, freed in one place. */
typedef struct {
    const mc_grid *g;
    const mc_plastic_problem *pb;
    long nvol, nwx, nwy;
    size_t ncell;
    double G;
    mc_plastic_ops own;          /* the operators when the problem brings none */
    mc_stress_plan *elastic;       /* Love-rectangle stresses at the cuboid centres */
    mc_eigen_disp *disp;      /* eigenstrain -> surface residual displacement */
    mc_eigen_stress *resid;   /* eigenstrain -> residual stress at the cuboid centres */
    double *depths;              /* nz cuboid-centre depths */
    int whole;                   /* 1: the window is the whole grid (the elastic stresses go
                                    straight into sig_e) */
    int folded;                  /* 1: the residual stress operator carries the surface loads
                                    (mc_eigen_stress_loads; theory §8.9): the elastic stresses
                                    come from it, and the joint iteration's sweep takes both
                                    fields from one apply into sig_r */
    int shared;                  /* 1: folded, and the displacement operator reads the stress
                                    operator's forward transforms of the same strain (one
                                    forward per joint evaluation; theory §8.9) */
    double *s_layer;             /* 6 ny*nx: one layer of elastic stresses on the whole grid
                                    (a window smaller than the grid; NULL when whole) */
    double *qx;                  /* friction traction, ny*nx */
    double *sig_e, *sig_r;       /* 6*nvol, window: elastic and residual stresses */
    int lent_sig_e, lent_sig_r;  /* 1: the problem's work_sig_e, state_sig_r (not freed here) */
    double *d_eps, *tot;         /* 6*nvol: the step's increment, eps_p + d_eps */
    double *d_new;               /* the increment's update: the same array as tot (tot is
                                    consumed by the residual stress before d_new is written) */
    double *dp, *dp_new;         /* nvol: the step's plastic strain increment, its update */
    double *u_r, *u_new, *h_extra; /* ny*nx */
    double p_lub;                /* lubricant pressure of the last contact solve, Pa */
    int solves;                  /* contact solves (step a) */
    mc_anderson *aa;             /* acceleration of the plastic fixed point (NULL: none) */
    mc_anderson *aa_outer;       /* and of the outer iteration on u_r */
    /* the last converged increment, the warm start of the next (theory §9.6): its plastic
     * strain increment and equivalent plastic strain increment on the cells where they are not
     * zero (increment.h: the plastic zone is usually a small part of the volume, so this holds
     * far less than the dense 56 bytes per volume cell), the change of u_r and the load, N */
    mc_plastic_incr warm;
    double *w_ur;
    double w_load;
    int w_have;                  /* 1: the w_ arrays hold a converged increment */
    long stress_applies;         /* residual stress applications (sweeps that were not skipped) */
    /* the local-global fixed point (near_reach > 0; theory §9.7) */
    mc_plastic_local *near;      /* the near field (the operators'), NULL: one apply per sweep */
    int *active;                 /* nvol: index of a cell in the active list, -1 outside */
    long *list;                  /* the active cells (capacity cap) */
    double *d0c;                 /* 6 per active cell: the increment at the last global apply */
    double *dnc, *dpc;           /* 6 and 1 per active cell: a near-field sweep's update */
    double *corr;                /* 6 per active cell: the near-field stress (per G) of the
                                    increment's change since the global sweep */
    long cap;
    long local_sweeps, local_cells;
    int sig_r_fresh;             /* 1: sig_r is S(eps_p + d_eps) of the current increment (the
                                    global sweep that follows needs no apply) */
    int row0, rows;              /* the window rows (y) whose cells this rank's sweep maps, in
                                    every layer (sweep_split_join; 0, nwy on one process) */
    int rows_ok;                 /* 1: the joint iteration may keep to this rank's rows (kept) */
    int kept;                    /* 1: in the joint iteration, the volume arrays' passes, the
                                    residual stress and Anderson's mixing keep to this rank's
                                    rows (theory §8.4); the other rows of d_eps, dp, d_new,
                                    dp_new and sig_r are stale until joint_iteration gathers */
    /* the sparse increment (theory §9.9): with operators that take a sparse addend the joint
     * iteration holds its iterate (d eps_p, d p) in inc and the sweep's image in inc_new, and
     * the dense d_eps, tot, dp, dp_new exist only once an increment falls back to the nested
     * iteration (dense_arrays) */
    int sparse;                  /* 1: the joint iteration runs on inc */
    int dense_now;               /* 1: this increment's state is in the dense arrays */
    int eps_any;                 /* 1: the committed eps_p is not zero somewhere */
    int begun;                   /* 1: joint_displacement began the stress apply of eps_p + inc
                                    (mc_eigen_stress_begin_sum), which sparse_sweep ends */
    mc_plastic_incr inc, inc_new, inc_tmp;
    double *lay7;                /* 7 x one layer of the window: the sweep's values per layer */
} loop_ctx;

static void ctx_free(loop_ctx *c)
{
    mc_free(c->active);
    mc_free(c->list);
    mc_free(c->d0c);
    mc_free(c->dnc);
    mc_free(c->dpc);
    mc_free(c->corr);
    mc_plastic_ops_destroy(&c->own); /* (borrowed operators are the caller's) */
    mc_anderson_destroy(&c->aa);
    mc_anderson_destroy(&c->aa_outer);
    mc_incr_free(&c->warm);
    mc_incr_free(&c->inc);
    mc_incr_free(&c->inc_new);
    mc_incr_free(&c->inc_tmp);
    mc_free(c->lay7);
    if (c->lent_sig_e)
        c->sig_e = NULL;
    if (c->lent_sig_r)
        c->sig_r = NULL;
    double *arrays[] = {c->depths, c->s_layer, c->qx,     c->sig_e, c->sig_r, c->d_eps,
                        c->tot,    c->dp,      c->dp_new, c->u_r,   c->u_new, c->h_extra,
                        c->w_ur};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        mc_free(arrays[k]);
}

/* mc_plastic_ops_create; elastic 0: without the elastic stress plan (a run that builds its own
 * folded operators never uses it: theory §8.9) */
static int ops_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                      int friction, int elastic, mc_plastic_ops *ops, mc_error *err)
{
    memset(ops, 0, sizeof *ops);
    if (v->nz < 1 || !(v->dz > 0))
        return mc_fail(err, MC_ERR_INPUT, "plastic operators: nz = %d, dz = %g m", v->nz, v->dz);
    double *depths = mc_zeros((size_t)v->nz);
    if (!depths)
        return mc_fail(err, MC_ERR_NOMEM, "plastic operators: out of memory");
    for (int k = 0; k < v->nz; k++)
        depths[k] = mc_eigen_layer_depth(v, k);
    mc_stress_options so = {.kernel = MC_STRESS_PATCH,
                            .nu = nu,
                            .nlayers = v->nz,
                            .depths = depths,
                            .backend = b,
                            .loads = MC_TRACTION_P | (friction ? MC_TRACTION_QX : 0),
                            /* folded: the loop never uses this plan (theory §8.9) */
                            .repeated = !mc_plastic_ops_fold(g, v)};
    int rc = elastic ? mc_stress_create(g, &so, &ops->elastic, err) : MC_OK;
    mc_free(depths);
    if (rc == MC_OK)
        rc = mc_eigen_disp_create(g, v, nu, b, &ops->disp, err);
    if (rc == MC_OK)
        rc = mc_eigen_stress_create(g, v, nu, b, &ops->resid, err);
    /* a volume under the whole grid takes the elastic stresses from the residual stress
     * operator's inverse transforms (theory §8.9): one set of transforms for both fields */
    if (rc == MC_OK && mc_plastic_ops_fold(g, v))
        rc = mc_eigen_stress_loads(ops->resid, MC_TRACTION_P | (friction ? MC_TRACTION_QX : 0),
                                   err);
    if (rc != MC_OK) {
        mc_plastic_ops_destroy(ops);
        return rc;
    }
    /* the spectral kernel: one set of workspaces for both operators (destroyed disp first) */
    (void)mc_eigen_disp_borrow(ops->disp, ops->resid);
    ops->g = *g;
    ops->volume = *v;
    if (v->group) {
        if (!(ops->group = mc_malloc((size_t)v->nz * sizeof *ops->group))) {
            mc_plastic_ops_destroy(ops);
            return mc_fail(err, MC_ERR_NOMEM, "plastic operators: out of memory");
        }
        memcpy(ops->group, v->group, (size_t)v->nz * sizeof *ops->group);
        ops->volume.group = ops->group;
    }
    ops->nu = nu;
    ops->backend = b;
    ops->friction = friction != 0;
    return MC_OK;
}

int mc_plastic_ops_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                          int friction, mc_plastic_ops *ops, mc_error *err)
{
    return ops_create(g, v, nu, b, friction, 1, ops, err);
}

void mc_plastic_ops_destroy(mc_plastic_ops *ops)
{
    mc_plastic_local_destroy(&ops->near);
    mc_stress_destroy(&ops->elastic);
    mc_eigen_disp_destroy(&ops->disp);
    mc_eigen_stress_destroy(&ops->resid);
    mc_free(ops->group);
    ops->group = NULL;
    memset(ops, 0, sizeof *ops);
}

static int check_problem(const mc_grid *g, const mc_plastic_problem *pb, mc_error *err)
{
    const mc_eigen_volume *w = &pb->volume;
    if (!pb->h || !pb->law)
        return mc_fail(err, MC_ERR_INPUT, "plastic loop: no initial gap or no material law");
    if (!(pb->load > 0 && isfinite(pb->load)) || pb->load_steps < 1)
        return mc_fail(err, MC_ERR_INPUT, "plastic loop: load %g N in %d steps", pb->load,
                       pb->load_steps);
    if (!(pb->E > 0) || !(pb->nu >= 0 && pb->nu < 0.5))
        return mc_fail(err, MC_ERR_INPUT, "plastic loop: E = %g Pa, nu = %g (0 <= nu < 0.5)",
                       pb->E, pb->nu);
    if (w->nz < 1 || !(w->dz > 0))
        return mc_fail(err, MC_ERR_INPUT, "plastic loop: nz = %d, dz = %g m", w->nz, w->dz);
    if (w->i0 < 0 || w->j0 < 0 || w->nx < 1 || w->ny < 1 || w->i0 + w->nx > g->nx ||
        w->j0 + w->ny > g->ny)
        return mc_fail(err, MC_ERR_INPUT,
                       "plastic loop: window of %d x %d columns from (%d, %d) outside %d x %d",
                       w->nx, w->ny, w->i0, w->j0, g->nx, g->ny);
    if (!(pb->relaxation > 0 && pb->relaxation <= 1) || !(pb->tol_outer > 0) ||
        pb->max_outer < 1 || !(pb->tol_plastic > 0) || pb->max_plastic < 1 ||
        pb->anderson < 0 || pb->anderson > MC_ANDERSON_MAX_DEPTH || pb->near_reach < 0 ||
        pb->near_reach > MC_PLASTIC_NEAR_REACH_MAX)
        return mc_fail(err, MC_ERR_INPUT, "plastic loop: bad iteration control");
    if (!pb->state_eps_p != !pb->state_peq || (pb->state_eps_p && (pb->eps_p0 || pb->peq0)))
        return mc_fail(err, MC_ERR_INPUT, "plastic loop: the state lent in place needs both "
                                          "state_eps_p and state_peq, and no eps_p0 or peq0");
    return MC_OK;
}

/* The dense increment arrays d_eps, tot (= d_new), dp, dp_new: made at the start, or with the
 * sparse increment when an increment first falls back to the nested iteration (zeroed). */
static int dense_arrays(loop_ctx *c, mc_error *err)
{
    const size_t nv6 = 6 * (size_t)c->nvol;
    if ((!c->d_eps && !(c->d_eps = mc_zeros(nv6))) || (!c->tot && !(c->tot = mc_zeros(nv6))) ||
        (!c->dp && !(c->dp = mc_zeros((size_t)c->nvol))) ||
        (!c->dp_new && !(c->dp_new = mc_zeros((size_t)c->nvol))))
        return mc_fail(err, MC_ERR_NOMEM,
                       "plastic loop: out of memory for the increment of %ld volume cells",
                       c->nvol);
    c->d_new = c->tot;
    return MC_OK;
}

static int ctx_init(loop_ctx *c, const mc_grid *g, const mc_plastic_problem *pb, mc_error *err)
{
    memset(c, 0, sizeof *c);
    c->g = g;
    c->pb = pb;
    c->nwx = pb->volume.nx;
    c->nwy = pb->volume.ny;
    c->nvol = (long)pb->volume.nz * c->nwx * c->nwy;
    c->ncell = mc_grid_cells(g);
    c->G = pb->E / (2.0 * (1.0 + pb->nu));
    const size_t nv6 = 6 * (size_t)c->nvol;
    c->lent_sig_e = pb->work_sig_e != NULL; /* lent: written before every read (loop.h) */
    c->lent_sig_r = pb->state_sig_r != NULL;
    c->whole = pb->volume.i0 == 0 && pb->volume.j0 == 0 && c->nwx == g->nx && c->nwy == g->ny;
    int ok = (c->depths = mc_zeros((size_t)pb->volume.nz)) && (c->qx = mc_zeros(c->ncell)) &&
             (c->whole || (c->s_layer = mc_zeros(6 * c->ncell))) &&
             /* a whole-grid volume's elastic stresses are made on first need (elastic_stresses):
              * the joint iteration with folded operators never needs them (theory §8.9) */
             (c->sig_e = pb->work_sig_e ? pb->work_sig_e : c->whole ? NULL : mc_zeros(nv6),
              c->sig_e || c->whole) &&
             (c->sig_r = pb->state_sig_r ? pb->state_sig_r : mc_zeros(nv6)) &&
             (c->u_r = mc_zeros(c->ncell)) && (c->u_new = mc_zeros(c->ncell)) &&
             (c->h_extra = mc_zeros(c->ncell)) && (c->w_ur = mc_zeros(c->ncell));
    mc_dist_share(c->nwy, &c->row0, &c->rows);
    if (mc_dist_size() > MC_DIST_MAX_RANKS) /* (the split gathers cannot fail below this) */
        return mc_fail(err, MC_ERR_LIMIT, "plastic loop: %d MPI processes, at most %d",
                       mc_dist_size(), MC_DIST_MAX_RANKS);
    if (!ok)
        return mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for %ld volume cells",
                       c->nvol);
    for (int k = 0; k < pb->volume.nz; k++)
        c->depths[k] = mc_eigen_layer_depth(&pb->volume, k);
    const mc_plastic_ops *ops = pb->ops;
    int rc = MC_OK;
    if (ops) {
        if (!ops->elastic || !ops->disp || !ops->resid || !(ops->g.nx == g->nx) ||
            !(ops->g.ny == g->ny) || !(ops->g.dx == g->dx) || !(ops->g.dy == g->dy) ||
            ops->g.periodic_x != g->periodic_x || ops->g.periodic_y != g->periodic_y ||
            !mc_eigen_volume_equal(&ops->volume, &pb->volume) ||
            !(ops->nu == pb->nu) || ops->backend != pb->backend ||
            (pb->friction != 0 && !ops->friction))
            return mc_fail(err, MC_ERR_INPUT,
                           "plastic loop: the operators given were made for another problem");
    } else {
        rc = ops_create(g, &pb->volume, pb->nu, pb->backend, pb->friction != 0,
                        !mc_plastic_ops_fold(g, &pb->volume), &c->own, err);
        ops = &c->own;
    }
    if (rc != MC_OK)
        return rc;
    c->elastic = ops->elastic;
    c->disp = ops->disp;
    c->resid = ops->resid;
    c->folded = c->whole && mc_eigen_stress_loads_of(c->resid) != 0;
    c->shared = c->folded && mc_eigen_disp_shares(c->disp, c->resid);
    /* distributed: the sweep maps the rows the residual stress operator's transforms read, and
     * with one forward for u_r and the sweep (shared: the displacement operator's transforms on
     * the same whole grid read the same rows) the joint iteration keeps to them */
    int r0, nr;
    if (rc == MC_OK && mc_dist_active() && mc_eigen_stress_keep_rows(c->resid, 0, &r0, &nr)) {
        c->row0 = r0;
        c->rows = nr;
        c->rows_ok = c->shared;
    }
    const int reach = pb->near_reach;
    if (rc == MC_OK && reach > 0) { /* made once per operators (the running-in's steps
                                                share it) */
        mc_plastic_ops *o = pb->ops ? pb->ops : &c->own;
        if (o->near && o->near_reach != reach)
            mc_plastic_local_destroy(&o->near);
        if (!o->near) {
            /* as deep as wide: the cells are flat (dz < dx) and couple most with the layers
             * under them */
            const double rz = reach * fmax(g->dx, g->dy) / pb->volume.dz;
            rc = mc_plastic_local_create(g, &pb->volume, pb->nu, reach,
                                         rz < 1 ? 1 : (int)lround(rz), &o->near, err);
            o->near_reach = reach;
        }
        c->near = o->near;
        if (rc == MC_OK && !(c->active = mc_malloc((size_t)c->nvol * sizeof *c->active)))
            rc = mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the active set");
    }
    /* the sparse increment (theory §9.9): the joint iteration alone, on one process, with
     * operators that read eps_p + a sparse increment */
    c->sparse = rc == MC_OK && c->folded && pb->iteration == MC_PLASTIC_JOINT &&
                pb->anderson > 0 && reach == 0 && !pb->tight_inner && !pb->dense_increment &&
                mc_dist_size() == 1 && mc_eigen_stress_takes_sum(c->resid) &&
                mc_eigen_disp_takes_sum(c->disp);
    if (rc == MC_OK && c->sparse &&
        !(c->lay7 = mc_malloc((size_t)MC_INCR_WIDTH * c->nwx * c->nwy * sizeof *c->lay7)))
        rc = mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the sweep's layer");
    if (rc == MC_OK && !c->sparse)
        rc = dense_arrays(c, err);
    if (rc == MC_OK && pb->anderson > 0)
        rc = mc_anderson_create(c->nvol, 6, pb->anderson, &c->aa, err);
    if (rc == MC_OK && pb->anderson > 0)
        rc = mc_anderson_create((long)c->ncell, 1, pb->anderson, &c->aa_outer, err);
    return rc;
}

/* Keep the converged increment as the warm start: its cells that are not zero (increment.h; a
 * cell whose seven values are all zero is left out: the warm start writes zeros there, the same
 * values), from the sparse increment or the dense arrays. */
static int warm_keep(loop_ctx *c, mc_error *err)
{
    const int ok = c->dense_now ? mc_incr_gather(&c->warm, c->nvol, c->d_eps, c->dp)
                                : mc_incr_scaled(&c->warm, &c->inc, 1.0);
    return ok ? MC_OK
              : mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the warm start");
}

/* The accepted increment as the next one's warm start (theory §9.6): its cells (warm_keep) and
 * its change of u_r against the committed res->u_r, for a load increment dload. */
static int warm_remember(loop_ctx *c, const mc_plastic_result *res, double dload, mc_error *err)
{
    const int rc = warm_keep(c, err);
    if (rc != MC_OK)
        return rc;
    for (size_t i = 0; i < c->ncell; i++)
        c->w_ur[i] = c->u_r[i] - res->u_r[i];
    c->w_have = 1;
    c->w_load = dload;
    return MC_OK;
}

/* The six component arrays of a component-major block of 6 * nvol values. */
static void split6(const loop_ctx *c, const double *block, const double *out[6])
{
    for (int q = 0; q < 6; q++)
        out[q] = block + (size_t)q * (size_t)c->nvol;
}

static void residual_stress(loop_ctx *c, const double *eps)
{
    const double *e[6];
    double *sg[6];
    split6(c, eps, e);
    for (int q = 0; q < 6; q++)
        sg[q] = c->sig_r + (size_t)q * (size_t)c->nvol;
    mc_eigen_stress_apply(c->resid, e, c->G, sg);
}

static void residual_displacement(loop_ctx *c, const double *eps, double *uz)
{
    const double *e[6];
    split6(c, eps, e);
    mc_eigen_disp_apply(c->disp, e, uz);
}

/* Volume index of window cell (i, j) (window-relative) in layer k. */
static long vidx(const loop_ctx *c, int k, long j, long i) { return ((long)k * c->nwy + j) * c->nwx + i; }

/* The friction traction of pressure p into c->qx (NULL without friction). */
static const double *friction_traction(loop_ctx *c, const double *p)
{
    const mc_plastic_problem *pb = c->pb;
    if (pb->friction == 0)
        return NULL;
    /* signed: the sign is the sliding direction (loop.h) */
    mc_traction_friction(p, c->p_lub, pb->lube_shape, pb->friction, c->ncell, c->qx);
    return c->qx;
}

/* The elastic stresses of pressure p (and its friction traction) on the window's cuboids. */
static int elastic_stresses(loop_ctx *c, const double *p, mc_error *err)
{
    const mc_plastic_problem *pb = c->pb;
    if (!c->sig_e) { /* first need (ctx_init); every rank alike before the collectives below */
        c->sig_e = mc_zeros(6 * (size_t)c->nvol);
        if (mc_dist_max_int(c->sig_e ? MC_OK : MC_ERR_NOMEM) != MC_OK)
            return mc_fail(err, MC_ERR_NOMEM,
                           "plastic loop: out of memory for the elastic stresses of %ld volume "
                           "cells",
                           c->nvol);
    }
    const double *qx = friction_traction(c, p);
    if (c->folded) { /* the residual stress operator's loads alone (theory §8.9) */
        double *s[6];
        for (int q = 0; q < 6; q++)
            s[q] = c->sig_e + (size_t)q * (size_t)c->nvol;
        mc_eigen_stress_apply_loaded(c->resid, NULL, c->G, p, qx, s);
        return MC_OK;
    }
    if (c->whole) { /* the volume layout is the stress plan's: straight into sig_e */
        double *const s[6] = {c->sig_e,                 c->sig_e + c->nvol,
                              c->sig_e + 2 * c->nvol,   c->sig_e + 3 * c->nvol,
                              c->sig_e + 4 * c->nvol,   c->sig_e + 5 * c->nvol};
        return mc_stress_field_split(c->elastic, p, qx, NULL, s, err);
    }
    /* layer by layer through one grid-sized layer (the same computation per layer as
     * mc_stress_field: the same bits), cut to the window: nz grid-sized layers would cost
     * (grid / window) x 48 bytes per volume cell */
    const mc_grid *g = c->g;
    double *const s[6] = {c->s_layer,              c->s_layer + c->ncell,
                          c->s_layer + 2 * c->ncell, c->s_layer + 3 * c->ncell,
                          c->s_layer + 4 * c->ncell, c->s_layer + 5 * c->ncell};
    /* over MPI each rank its block of layers, then the window's layers to every rank (as
     * mc_stress_field_split, which says why layers) */
    int k0, nk, rc = MC_OK;
    mc_dist_share(pb->volume.nz, &k0, &nk);
    for (int k = k0; k < k0 + nk && rc == MC_OK; k++) {
        rc = mc_stress_layer(c->elastic, k, p, qx, NULL, s, err);
        if (rc != MC_OK)
            break;
        for (int comp = 0; comp < 6; comp++)
            for (long j = 0; j < c->nwy; j++)
                for (long i = 0; i < c->nwx; i++) {
                    size_t src = (size_t)(j + pb->volume.j0) * g->nx + (size_t)(i + pb->volume.i0);
                    c->sig_e[comp * c->nvol + vidx(c, k, j, i)] = s[comp][src];
                }
    }
    if (!mc_dist_active())
        return rc;
    const int any = mc_dist_max_int(rc); /* all ranks fail alike before the collective gather */
    if (any != MC_OK)
        return rc != MC_OK ? rc
                           : mc_fail(err, (mc_status)any,
                                     "plastic loop: another MPI process failed (status %d)", any);
    mc_dist_gather_blocks(c->sig_e, 6, pb->volume.nz, (int)(c->nwy * c->nwx), k0, nk);
    return MC_OK;
}


/* Inexact inner solves (docs/theory.md §9.4): the plastic fixed point of outer iteration k is
 * solved to max(tol_plastic, INNER_FORCING x the relative change of u_r in outer iteration k - 1)
 * (1 before the first), and to tol_plastic once that change is within tol_outer; an outer
 * iteration is accepted only on an inner solve that met tol_plastic. 0.05 measured on the
 * 192 x 96 x 16 running-in step of cases/default.ini at 350 rpm: 170 sweeps in 11 outer
 * iterations -> 40 in 9 (0.03: 43 in 9; 0.1: 32 in 11; 0.3 and 1: the outer iteration stalls,
 * 30 iterations without convergence). */
#define INNER_FORCING 0.05

/* The safeguard of the inexact solves: an increment solves every further fixed point to
 * tol_plastic once its outer iteration stalls (a change of u_r not below the one two iterations
 * before), once a fixed point hit max_plastic, and after INEXACT_OUTER outer iterations (the
 * loop's usual 5-20, dossier §2.1). On the 256 x 128 x 16 step of the scene above the outer
 * change stalls between 0.1 and 0.6 with loose fixed points from the 6th iteration on. */
#define INEXACT_OUTER 10

/* Plastic strain increments beyond this are taken as divergence (the step is split). */
#define DIVERGED_STRAIN 0.5

/* The largest change of a sweep's increments (d_new against d_eps) into *change, their largest magnitude into *size; 1 when the
 * increments themselves are beyond DIVERGED_STRAIN or not finite (the sweep diverged). */
static int sweep_change(const loop_ctx *c, size_t nv6, double *change, double *size)
{
    double ch = 0, sz = 0;
    for (size_t i = 0; i < nv6; i++) {
        ch = fmax(ch, fabs(c->d_new[i] - c->d_eps[i]));
        sz = fmax(sz, fabs(c->d_new[i]));
    }
    *change = ch;
    *size = sz;
    return !(sz <= DIVERGED_STRAIN);
}

/* A trial von Mises stress below this is elastic at any accumulated plastic strain: the yield
 * stress never falls below the initial one (hardening.c refuses softening), and
 * SURELY_ELASTIC_MARGIN (relative) covers the rounding of sigma_y(p) against sigma_y(0) (an ulp
 * or two of a pow). Such a cell takes mc_return_map's elastic branch (zero increments) without
 * evaluating the law: the same bits, without a pow per cell and sweep for the Swift law. */
#define SURELY_ELASTIC_MARGIN 1e-12

static double surely_elastic_below(const mc_hardening *law)
{
    const double sy0 = mc_hardening_initial(law);
    return sy0 > 0 && isfinite(sy0) ? sy0 * (1.0 - SURELY_ELASTIC_MARGIN) : 0.0;
}

/* The stops of theory §9.5, in counts (never in seconds: a result must not depend on the
 * machine). An increment stops once its tight fixed point has hit max_plastic in INNER_STALL
 * successive outer iterations (the running-in at Y = 50 MPa of issue 20: 100 sweeps per outer
 * iteration from the 6th to the 30th, the change stuck at 5e-3 against 1e-4; a line contact in
 * the checkerboard band hits the cap in 4 successive ones and then converges, the line grid of
 * tests/test_warnings.c: twice that is the margin), or once the change of u_r,
 * at tight fixed points, has grown in OUTER_GROWTH successive outer iterations to over
 * OUTER_GROWTH_FACTOR times its least in the increment (the Swift sphere of issue 20: a
 * two-cycle of the contact set whose change grows 10 % per iteration). */
#define INNER_STALL 8
#define OUTER_GROWTH 5
#define OUTER_GROWTH_FACTOR 2.0

/* The plastic fixed point of dossier §1.4 at fixed elastic stresses: updates c->d_eps and c->dp
 * from the committed eps_p, peq, until the change of a sweep is within tol (relative, as
 * tol_plastic). *sweeps receives the sweeps done; *converged 0 when the cap was hit; *tight 1
 * when the last sweep's change was also within tol_plastic, *rel_change that change (relative;
 * 0 when elastic); *diverged 1 when the increments blew up (non-finite trial stresses, or an
 * increment beyond DIVERGED_STRAIN): the caller splits the load step. The update is under-relaxed
 * adaptively (omega halves whenever the change grows, dossier §1.4), and the residual operator is
 * skipped while nothing has yielded (the elastic shortcut). */
/* One global sweep of the plastic fixed point: sig_r = S(eps_p + d_eps) (zero without plastic
 * strain: *any 0), the trial stresses sigma_e + sig_r + 2 G d_eps and their return maps into
 * d_new, dp_new; the largest change |d_new - d_eps| and magnitude |d_new| into *change, *size,
 * whether a cell yields into *plastic. Returns 1 when a return map failed (non-finite trial).
 * p != NULL (folded operators, the joint iteration): sig_r receives sigma_e of the pressure p
 * (and its friction traction) plus S(eps_p + d_eps) from one apply (theory §8.9), and sig_e is
 * neither written nor read; forwarded: the forward transforms of eps_p + d_eps were made already
 * (mc_eigen_disp_apply_shared, for u_r) and are not made again. */
static void sweep_split_join(loop_ctx *c, double *change, double *size, int *plastic, int *bad);

/* The cells a pass over ncomp component blocks of the window visits: this rank's rows of every
 * layer when kept (nblk runs of rows nwx values), else all of them (one run). */
typedef struct {
    long nblk;
    size_t run;
} kept_span;

static kept_span span_of(const loop_ctx *c, int ncomp)
{
    if (!c->kept)
        return (kept_span){1, (size_t)ncomp * (size_t)c->nvol};
    return (kept_span){(long)ncomp * c->pb->volume.nz, (size_t)c->rows * (size_t)c->nwx};
}

static size_t span_at(const loop_ctx *c, long b)
{
    return c->kept ? ((size_t)b * (size_t)c->nwy + (size_t)c->row0) * (size_t)c->nwx : 0;
}

/* dst = a + b over ncomp component blocks on the cells this rank keeps; 1 when a value is not
 * zero there (on any rank, when kept: collective then). */
static int sum_kept(const loop_ctx *c, int ncomp, const double *a, const double *b, double *dst)
{
    const kept_span sp = span_of(c, ncomp);
    int any = 0;
    for (long k = 0; k < sp.nblk; k++)
        for (size_t i = span_at(c, k), end = i + sp.run; i < end; i++) {
            dst[i] = a[i] + b[i];
            any |= dst[i] != 0.0;
        }
    return c->kept ? mc_dist_max_int(any) : any;
}

/* dst = src over ncomp component blocks on the cells this rank keeps. */
static void copy_kept(const loop_ctx *c, int ncomp, double *dst, const double *src)
{
    const kept_span sp = span_of(c, ncomp);
    for (long k = 0; k < sp.nblk; k++)
        memcpy(dst + span_at(c, k), src + span_at(c, k), sp.run * sizeof *dst);
}

static int sweep(loop_ctx *c, const double *eps_p, const double *peq, const double *p,
                 int forwarded, double elastic_below, double *change_out, double *size_out,
                 int *plastic_out, int *any_out)
{
    const mc_plastic_problem *pb = c->pb;
    const size_t nv6 = 6 * (size_t)c->nvol;
    const int any = sum_kept(c, 6, eps_p, c->d_eps, c->tot);
    if (p) { /* both fields from one apply */
        const double *qx = friction_traction(c, p), *e[6];
        double *sg[6];
        split6(c, c->tot, e);
        for (int q = 0; q < 6; q++)
            sg[q] = c->sig_r + (size_t)q * (size_t)c->nvol;
        if (forwarded && any) /* the forward of this eps was made for u_r (joint_iteration) */
            mc_eigen_stress_apply_forwarded(c->resid, c->G, p, qx, sg);
        else if (c->begun && any) /* u_r's evaluation made its first half */
            (void)mc_eigen_stress_end_sum(c->resid, e, NULL, c->G, p, qx, sg);
        else
            mc_eigen_stress_apply_loaded(c->resid, any ? e : NULL, c->G, p, qx, sg);
        c->stress_applies += any;
        c->begun = 0;
    } else if (any) {
        residual_stress(c, c->tot);
        c->stress_applies++;
    } else
        memset(c->sig_r, 0, nv6 * sizeof *c->sig_r);
    int bad = 0, plastic = 0;
    double change = 0, size = 0;
    /* this rank's rows of the window in every layer (all of them on one process): the cells
     * are independent and the maxima order-free, so any split gives the same bits */
    const long nrow = (long)c->rows, nlines = (long)pb->volume.nz * nrow;
#pragma omp parallel for schedule(static) reduction(| : plastic, bad) \
    reduction(max : change, size) if (nlines * c->nwx > 4096)
    for (long line = 0; line < nlines; line++)
    for (long v = vidx(c, (int)(line / nrow), c->row0 + line % nrow, 0),
              vend = v + c->nwx; v < vend; v++) {
        double trial[6], out[6], de[6], dpv = 0.0;
        for (int q = 0; q < 6; q++) {
            const double s = p ? c->sig_r[q * c->nvol + v]
                               : c->sig_e[q * c->nvol + v] + c->sig_r[q * c->nvol + v];
            trial[q] = s + 2.0 * c->G * c->d_eps[q * c->nvol + v];
        }
        if (mc_von_mises(trial) < elastic_below) { /* mc_return_map's elastic branch */
            for (int q = 0; q < 6; q++)
                de[q] = 0.0;
        } else {
            mc_error e1;
            if (mc_return_map(trial, peq[v], pb->law, c->G, out, de, &dpv, &e1) != MC_OK) {
                bad = 1;
                continue;
            }
        }
        double ch = 0, sz = 0;
        for (int q = 0; q < 6; q++) {
            c->d_new[q * c->nvol + v] = de[q];
            ch = fmax(ch, fabs(de[q] - c->d_eps[q * c->nvol + v]));
            sz = fmax(sz, fabs(de[q]));
        }
        change = change > ch ? change : ch;
        size = size > sz ? size : sz;
        c->dp_new[v] = dpv;
        plastic |= dpv > 0;
    }
    if (mc_dist_active())
        sweep_split_join(c, &change, &size, &plastic, &bad);
    *change_out = change;
    *size_out = size;
    *plastic_out = plastic;
    *any_out = any;
    return bad;
}

/* The sweep split over the ranks (issue 22): each rank has mapped the cells of its rows of the
 * window (c->row0, c->rows: rows of y, in every layer). Rows rather than layers or a plain split
 * of the cell index: the plastic zone lies in a few layers under the contact spots, so a split
 * in depth would give one rank the return maps and the other the cheap elastic cells, while the
 * spots spread over the rows. The maxima and flags are reduced (the same on every rank: maxima
 * are order-free) and the new increments d_new (6 components x nz layers) and dp_new (nz
 * layers) gathered whole, so that the loop goes on as on one process. Exchange per sweep: each
 * rank receives (P - 1) / P x 7 doubles per volume cell (56 bytes), in two collective calls. */
static void sweep_split_join(loop_ctx *c, double *change, double *size, int *plastic, int *bad)
{
    double red[4] = {*change, *size, *plastic, *bad};
    const mc_dist_mark t0 = mc_dist_comm_begin();
    mc_dist_max(red, 4);
    mc_dist_comm_end(t0);
    *change = red[0];
    *size = red[1];
    *plastic = red[2] != 0;
    *bad = red[3] != 0;
    if (c->kept) /* the joint iteration goes on with this rank's rows */
        return;
    const int nz = c->pb->volume.nz, nx = (int)c->nwx, ny = (int)c->nwy;
    mc_dist_gather_blocks(c->d_new, 6 * nz, ny, nx, c->row0, c->rows);
    mc_dist_gather_blocks(c->dp_new, nz, ny, nx, c->row0, c->rows);
}

static int plastic_fixed_point_lg(loop_ctx *c, const double *eps_p, const double *peq,
                                  double tol, int *sweeps, int *converged, int *tight,
                                  double *rel_change, int *yielded, int *diverged,
                                  mc_error *err);

static int plastic_fixed_point(loop_ctx *c, const double *eps_p, const double *peq, double tol,
                               int *sweeps, int *converged, int *tight, double *rel_change,
                               int *yielded, int *diverged, mc_error *err)
{
    if (c->near)
        return plastic_fixed_point_lg(c, eps_p, peq, tol, sweeps, converged, tight, rel_change,
                                      yielded, diverged, err);
    const mc_plastic_problem *pb = c->pb;
    const size_t nv6 = 6 * (size_t)c->nvol;
    const double elastic_below = surely_elastic_below(pb->law);
    double omega = 1.0, prev_change = INFINITY;
    *converged = 0;
    *tight = 0;
    *rel_change = INFINITY;
    *yielded = 0;
    *diverged = 0;
    (void)err;
    for (int m = 1; m <= pb->max_plastic; m++) {
        *sweeps = m;
        int any = 0, plastic = 0;
        double change = 0, size = 0; /* sweep_change's maxima, taken in the same pass */
        if (sweep(c, eps_p, peq, NULL, 0, elastic_below, &change, &size, &plastic, &any)) {
            *diverged = 1;
            return MC_OK;
        }
        *yielded |= plastic;
        if (!(size <= DIVERGED_STRAIN)) { /* sweep_change's divergence test */
            *diverged = 1;
            return MC_OK;
        }
        if (c->aa) { /* Anderson mixing of the increments (the last images' dp with them) */
            if (m == 1)
                mc_anderson_restart(c->aa);
            mc_error aerr;
            if (mc_anderson_step(c->aa, c->d_eps, c->d_new, &aerr) != MC_OK) {
                mc_anderson_destroy(&c->aa); /* no memory to mix: plain iteration from here */
            }
            memcpy(c->dp, c->dp_new, (size_t)c->nvol * sizeof *c->dp);
        } else {
            if (change > prev_change && omega > 0.125)
                omega *= 0.5;
            prev_change = change;
            for (size_t i = 0; i < nv6; i++)
                c->d_eps[i] += omega * (c->d_new[i] - c->d_eps[i]);
            for (long v = 0; v < c->nvol; v++)
                c->dp[v] += omega * (c->dp_new[v] - c->dp[v]);
        }
        if (!plastic && !any) { /* nothing yields and nothing has: the step is elastic */
            *converged = *tight = 1;
            *rel_change = 0.0;
            return MC_OK;
        }
        *rel_change = change / fmax(size, 1e-3);
        if (change <= tol * fmax(size, 1e-3)) {
            *converged = 1;
            *tight = change <= pb->tol_plastic * fmax(size, 1e-3);
            return MC_OK;
        }
    }
    return MC_OK;
}

/* The local-global fixed point (theory §9.7): the same fixed point and stopping test as
 * plastic_fixed_point (a plain sweep with the whole residual stress operator changes the
 * increment by at most tol), but between two global sweeps the increment is iterated on the
 * active set (cells that yield, carry an increment, or whose trial stress is within
 * NEAR_MARGIN of yield) with the near field of the operator applied to the change since the
 * global sweep: sigma = sigma_e + S(eps_p + d_k) + N(d - d_k) + 2 G d. Each global sweep thus
 * corrects the far field N - S of the last local solve. Arguments as plastic_fixed_point. */
static int plastic_fixed_point_lg(loop_ctx *c, const double *eps_p, const double *peq,
                                  double tol, int *sweeps, int *converged, int *tight,
                                  double *rel_change, int *yielded, int *diverged,
                                  mc_error *err)
{
    const mc_plastic_problem *pb = c->pb;
    const size_t nv6 = 6 * (size_t)c->nvol;
    const long nvol = c->nvol;
    const double G2 = 2.0 * c->G;
    const double sy0 = mc_hardening_initial(pb->law);
    *converged = 0;
    *tight = 0;
    *rel_change = INFINITY;
    *yielded = 0;
    *diverged = 0;
    for (int m = 1; m <= pb->max_plastic; m++) {
        *sweeps = m;
        int any = 0;
        for (size_t i = 0; i < nv6; i++) {
            c->tot[i] = eps_p[i] + c->d_eps[i];
            any |= c->tot[i] != 0.0;
        }
        if (any && !c->sig_r_fresh) {
            residual_stress(c, c->tot);
            c->stress_applies++;
        } else if (!any)
            memset(c->sig_r, 0, nv6 * sizeof *c->sig_r);
        c->sig_r_fresh = 1;
        /* the global sweep: the plain image of every cell, and the active set */
        int bad = 0, plastic = 0;
        long count = 0;
#pragma omp parallel for schedule(static) reduction(| : plastic, bad) reduction(+ : count) \
    if (nvol > 4096)
        for (long v = 0; v < nvol; v++) {
            double trial[6], out[6], de[6], dpv;
            int carries = 0;
            for (int q = 0; q < 6; q++) {
                trial[q] = c->sig_e[q * nvol + v] + c->sig_r[q * nvol + v] +
                           G2 * c->d_eps[q * nvol + v];
                carries |= c->d_eps[q * nvol + v] != 0.0;
            }
            mc_error e1;
            if (mc_return_map(trial, peq[v], pb->law, c->G, out, de, &dpv, &e1) != MC_OK) {
                bad = 1;
                c->active[v] = -1;
                continue;
            }
            for (int q = 0; q < 6; q++)
                c->d_new[q * nvol + v] = de[q];
            c->dp_new[v] = dpv;
            plastic |= dpv > 0;
            const int near = dpv > 0 || carries ||
                             mc_von_mises(trial) >=
                                 (1.0 - NEAR_MARGIN) *
                                     (peq[v] > 0 ? mc_hardening_sigma_y(pb->law, peq[v]) : sy0);
            c->active[v] = near ? 0 : -1;
            count += near;
        }
        if (bad) {
            *diverged = 1;
            return MC_OK;
        }
        *yielded |= plastic;
        double change = 0, size = 0;
        if (sweep_change(c, nv6, &change, &size)) {
            *diverged = 1;
            return MC_OK;
        }
        const int elastic = !plastic && !any; /* nothing yields and nothing has */
        const double rel = change / fmax(size, 1e-3);
        const int done = elastic || change <= tol * fmax(size, 1e-3) || m == pb->max_plastic;
        long n = 0;
        if (!done) { /* the active list, with d0 = the increment the global apply saw */
            if (count > c->cap) {
                long cap = count > 2 * c->cap ? count : 2 * c->cap;
                if (cap > nvol)
                    cap = nvol;
                mc_free(c->list);
                mc_free(c->d0c);
                mc_free(c->dnc);
                mc_free(c->dpc);
                mc_free(c->corr);
                c->cap = 0;
                c->corr = NULL;
                c->list = NULL;
                c->dnc = c->dpc = c->d0c = NULL;
                if (!(c->list = mc_malloc((size_t)cap * sizeof *c->list)) ||
                    !(c->d0c = mc_malloc(6 * (size_t)cap * sizeof *c->d0c)) ||
                    !(c->dnc = mc_malloc(6 * (size_t)cap * sizeof *c->dnc)) ||
                    !(c->dpc = mc_malloc((size_t)cap * sizeof *c->dpc)) ||
                    !(c->corr = mc_malloc(6 * (size_t)cap * sizeof *c->corr)))
                    return mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the "
                                                      "active set of %ld cells", count);
                c->cap = cap;
            }
            for (long v = 0; v < nvol; v++)
                if (c->active[v] >= 0) {
                    c->active[v] = (int)n;
                    c->list[n] = v;
                    for (int q = 0; q < 6; q++)
                        c->d0c[6 * n + q] = c->d_eps[q * nvol + v];
                    n++;
                }
        }
        if (!elastic && change <= tol * fmax(size, 1e-3)) {
            /* converged: d_k is kept (within tol of its image), so sig_r stays S(eps_p + d_k)
             * and the next outer iteration's first global sweep needs no apply */
            *rel_change = rel;
            *converged = 1;
            *tight = change <= pb->tol_plastic * fmax(size, 1e-3);
            return MC_OK;
        }
        /* the image is the new iterate (the local solve starts from it) */
        memcpy(c->d_eps, c->d_new, nv6 * sizeof *c->d_eps);
        memcpy(c->dp, c->dp_new, (size_t)nvol * sizeof *c->dp);
        c->sig_r_fresh = 0;
        if (elastic) {
            *converged = *tight = 1;
            *rel_change = 0.0;
            return MC_OK;
        }
        *rel_change = rel;
        if (done)
            break;
        /* the local solve, to NEAR_FORCING x this sweep's change (at least tol / 2) */
        const double tol_l = fmax(0.5 * pb->tol_plastic, NEAR_FORCING * *rel_change);
        const double thr = NEAR_SPREAD * tol_l * fmax(size, 1e-3);
        memset(c->corr, 0, 6 * (size_t)n * sizeof *c->corr);
        double omega = 1.0, prev = INFINITY;
        for (int l = 1; l <= NEAR_MAX_SWEEPS; l++) {
            c->local_sweeps++;
            /* spread the sources that moved by more than thr since they were last spread:
             * corr = N(d_spread - d_k) with |d - d_spread| <= thr everywhere */
            for (long a = 0; a < n; a++) {
                const long v = c->list[a];
                double r6[6];
                int moved = 0;
                for (int q = 0; q < 6; q++) {
                    r6[q] = c->d_eps[q * nvol + v] - c->d0c[6 * a + q];
                    moved |= fabs(r6[q]) > thr;
                }
                if (!moved)
                    continue;
                c->local_cells++;
                const int k = (int)(v / (c->nwx * c->nwy));
                const long j = (v / c->nwx) % c->nwy, i = v % c->nwx;
                mc_plastic_local_scatter(c->near, r6, c->active, k, j, i, c->corr);
                for (int q = 0; q < 6; q++)
                    c->d0c[6 * a + q] = c->d_eps[q * nvol + v];
            }
#pragma omp parallel for schedule(static) reduction(| : bad) if (n > 512)
            for (long a = 0; a < n; a++) {
                const long v = c->list[a];
                double trial[6], out[6], de[6], dpv;
                for (int q = 0; q < 6; q++)
                    trial[q] = c->G * c->corr[6 * a + q] + c->sig_e[q * nvol + v] +
                               c->sig_r[q * nvol + v] + G2 * c->d_eps[q * nvol + v];
                mc_error e1;
                if (mc_return_map(trial, peq[v], pb->law, c->G, out, de, &dpv, &e1) != MC_OK) {
                    bad = 1;
                    continue;
                }
                for (int q = 0; q < 6; q++)
                    c->dnc[6 * a + q] = de[q];
                c->dpc[a] = dpv;
            }
            if (bad) {
                *diverged = 1;
                return MC_OK;
            }
            double ch = 0, sz = 0;
            for (long a = 0; a < n; a++)
                for (int q = 0; q < 6; q++) {
                    const double dn = c->dnc[6 * a + q];
                    ch = fmax(ch, fabs(dn - c->d_eps[q * nvol + c->list[a]]));
                    sz = fmax(sz, fabs(dn));
                }
            if (!(sz <= DIVERGED_STRAIN)) {
                *diverged = 1;
                return MC_OK;
            }
            if (ch > prev && omega > 0.125)
                omega *= 0.5;
            prev = ch;
            for (long a = 0; a < n; a++) {
                const long v = c->list[a];
                for (int q = 0; q < 6; q++)
                    c->d_eps[q * nvol + v] += omega * (c->dnc[6 * a + q] - c->d_eps[q * nvol + v]);
                c->dp[v] += omega * (c->dpc[a] - c->dp[v]);
            }
            if (ch <= tol_l * fmax(sz, 1e-3))
                break;
        }
    }
    return MC_OK;
}

static void step_record(const loop_ctx *c, const mc_contact_summary *cs, const double *peq,
                        const double *u_r, mc_plastic_step *st)
{
    const mc_plastic_problem *pb = c->pb;
    const mc_grid *g = c->g;
    st->approach = cs->approach;
    st->p_max = cs->p_max;
    st->area = cs->area;
    st->plastic_volume = 0;
    st->peq_max = 0;
    long at = -1;
    for (long v = 0; v < c->nvol; v++) {
        if (peq[v] > 0)
            st->plastic_volume +=
                g->dx * g->dy * mc_eigen_layer_thickness(&pb->volume, (int)(v / (c->nwx * c->nwy)));
        if (peq[v] > st->peq_max) {
            st->peq_max = peq[v];
            at = v;
        }
    }
    st->peq_at[0] = st->peq_at[1] = st->peq_at[2] = 0;
    if (at >= 0) {
        long i = at % c->nwx, j = (at / c->nwx) % c->nwy, k = at / (c->nwx * c->nwy);
        st->peq_at[0] = mc_grid_x(g, (int)(i + pb->volume.i0));
        st->peq_at[1] = mc_grid_y(g, (int)(j + pb->volume.j0));
        st->peq_at[2] = mc_eigen_layer_depth(&pb->volume, (int)k);
    }
    st->residual_max = 0;
    for (size_t i = 0; i < c->ncell; i++)
        st->residual_max = fmax(st->residual_max, u_r[i]);
}

const char *mc_plastic_stop_text(mc_plastic_stop why)
{
    switch (why) {
    case MC_PLASTIC_RUN_CONVERGED: return "";
    case MC_PLASTIC_STOP_OUTER_CAP:
        return "the outer iteration reached max_outer without meeting the tolerance (raise "
               "max_outer, lower relaxation or use more load_steps)";
    case MC_PLASTIC_STOP_INNER_STALL:
        return "the plastic fixed point stalls: it used all max_plastic sweeps in 8 successive "
               "outer iterations (raise max_plastic or plastic_tolerance)";
    case MC_PLASTIC_STOP_OUTER_DIVERGES:
        return "the outer iteration diverges: the change of the residual displacement grew in 5 "
               "successive outer iterations (lower relaxation or use more load_steps)";
    case MC_PLASTIC_STOP_SPLIT_LIMIT:
        return "the increments diverge (plastic strain increments beyond 0.5, or non-finite "
               "values) even in 32 sub-increments: the load exceeds what the material carries "
               "(use more load_steps or hardening)";
    case MC_PLASTIC_STOP_STEP_BUDGET:
        return "the split increments of the step used its budget of max_outer x max_plastic "
               "fixed-point sweeps";
    case MC_PLASTIC_STOP_CONTACT:
        return "the contact solve did not converge";
    }
    return "unknown";
}

/* One load increment to `load` (dload above the committed load) from the committed state
 * (res->eps_p, res->peq, res->u_r), started warm from the last converged increment unless
 * pb->cold_start (theory §9.6): the outer iteration of dossier §2.1. Returns MC_OK with *conv
 * set (committed), *diverged set (the plastic fixed point or u_r blew up: nothing committed, the
 * caller splits; the warm start forgets the last increment), or *why set (a stop of theory §9.5:
 * the last iterate committed, the caller ends the run); or an error. st accumulates the
 * iteration counts. */

/* Step (a) on the current u_r: the contact (with a lubricant, the volume equilibrium of the
 * problem's callback) under the load with h_extra = gap_factor u_r, warm from p when p_warm;
 * inexact and *settled as the callback's (loop.h; without a callback always settled). */
static int contact_on_ur(loop_ctx *c, mc_contact_solver *solver, double load, int p_warm,
                         int inexact, double *p, double *u, double *gap, mc_contact_summary *sum,
                         int *settled, mc_plastic_step *st, mc_error *err)
{
    const mc_plastic_problem *pb = c->pb;
    const double gap_factor = pb->both ? 2.0 : 1.0;
    for (size_t i = 0; i < c->ncell; i++)
        c->h_extra[i] = gap_factor * c->u_r[i];
    mc_contact_problem cp = {.h = pb->h,
                             .h_extra = c->h_extra,
                             .p_lub = pb->p_lub,
                             .p_cap = INFINITY,
                             .control = MC_CONTROL_FORCE,
                             .load = load,
                             .p_start = p_warm ? p : NULL};
    c->solves++;
    st->contact_solves++;
    *settled = 1;
    return pb->contact
               ? pb->contact(pb->contact_ctx, &cp, inexact, p, u, gap, sum, &c->p_lub, settled, err)
               : mc_contact_solve(solver, &cp, p, u, gap, sum, err);
}

/* The sweep on the sparse increment (theory §9.9): sig_r = sigma_e(p) + S(eps_p + inc) from one
 * apply (the operators read the sum as they read their input), then layer by layer the return
 * map of every cell from the trial stress sig_r + 2 G d, d the layer's entries of inc spread
 * into lay7, and the image (d eps_p, d p) of the cells where it is not zero appended to inc_new
 * in order. The same values, maxima and flags as sweep() on the dense arrays. Returns 1 when a
 * return map failed; *nomem 1 when inc_new could not grow. */
static int sparse_sweep(loop_ctx *c, const double *eps_p, const double *peq, const double *p,
                        double elastic_below, double *change_out, double *size_out,
                        int *plastic_out, int *any_out, int *nomem)
{
    const mc_plastic_problem *pb = c->pb;
    const long lay = c->nwx * c->nwy, nvol = c->nvol;
    const int any = c->eps_any || mc_incr_any(&c->inc);
    const double *qx = friction_traction(c, p), *e[6];
    double *sg[6];
    split6(c, eps_p, e);
    for (int q = 0; q < 6; q++)
        sg[q] = c->sig_r + (size_t)q * (size_t)nvol;
    if (any) { /* (the operators take the sum: ctx_init checked) */
        const mc_eigen_sparse inc = mc_incr_strain(&c->inc);
        if (c->begun) /* u_r's evaluation made its first half */
            (void)mc_eigen_stress_end_sum(c->resid, e, &inc, c->G, p, qx, sg);
        else
            (void)mc_eigen_stress_apply_sum(c->resid, e, &inc, c->G, p, qx, sg);
        c->stress_applies++;
    } else
        mc_eigen_stress_apply_loaded(c->resid, NULL, c->G, p, qx, sg);
    c->begun = 0;
    int bad = 0, plastic = 0;
    double change = 0, size = 0;
    double *d7 = c->lay7;
    memset(d7, 0, (size_t)MC_INCR_WIDTH * (size_t)lay * sizeof *d7);
    c->inc_new.n = 0;
    *nomem = 0;
    for (int k = 0; k < pb->volume.nz; k++) {
        const long v0 = (long)k * lay;
        long k0, k1;
        mc_incr_range(&c->inc, v0, v0 + lay, &k0, &k1);
        for (long n = k0; n < k1; n++)
            for (int q = 0; q < 6; q++)
                d7[(size_t)q * (size_t)lay + (size_t)(c->inc.cell[n] - v0)] =
                    c->inc.val[(size_t)MC_INCR_WIDTH * (size_t)n + (size_t)q];
#pragma omp parallel for schedule(static) reduction(| : plastic, bad) \
    reduction(max : change, size) if (lay > 4096)
        for (long at = 0; at < lay; at++) {
            const long v = v0 + at;
            double trial[6], out[6], de[6] = {0}, dpv = 0.0;
            for (int q = 0; q < 6; q++)
                trial[q] = c->sig_r[q * nvol + v] + 2.0 * c->G * d7[q * lay + at];
            if (!(mc_von_mises(trial) < elastic_below)) { /* else mc_return_map's elastic branch */
                mc_error e1;
                if (mc_return_map(trial, peq[v], pb->law, c->G, out, de, &dpv, &e1) != MC_OK) {
                    bad = 1;
                    for (int q = 0; q < 6; q++)
                        de[q] = 0.0;
                    dpv = 0.0;
                }
            }
            double ch = 0, sz = 0;
            for (int q = 0; q < 6; q++) {
                ch = fmax(ch, fabs(de[q] - d7[q * lay + at]));
                sz = fmax(sz, fabs(de[q]));
                d7[q * lay + at] = de[q];
            }
            d7[6 * lay + at] = dpv;
            change = change > ch ? change : ch;
            size = size > sz ? size : sz;
            plastic |= dpv > 0;
        }
        for (long at = 0; at < lay; at++) { /* the image's cells, in order; lay7 zeroed again */
            double v7[MC_INCR_WIDTH];
            int nz = 0;
            for (int q = 0; q < MC_INCR_WIDTH; q++) {
                v7[q] = d7[q * lay + at];
                nz |= v7[q] != 0.0;
            }
            if (!nz)
                continue;
            for (int q = 0; q < MC_INCR_WIDTH; q++)
                d7[q * lay + at] = 0.0;
            if (!*nomem && !mc_incr_push(&c->inc_new, v0 + at, v7))
                *nomem = 1;
        }
    }
    *change_out = change;
    *size_out = size;
    *plastic_out = plastic;
    *any_out = any;
    return bad;
}

static void incr_swap(mc_plastic_incr *a, mc_plastic_incr *b)
{
    const mc_plastic_incr t = *a;
    *a = *b;
    *b = t;
}

/* u (grid) = D(eps_p + inc): the residual displacement of the committed strain and the sparse
 * increment */
static void sparse_displacement(loop_ctx *c, const double *eps_p, double *u)
{
    const double *e[6];
    split6(c, eps_p, e);
    const mc_eigen_sparse inc = mc_incr_strain(&c->inc);
    (void)mc_eigen_disp_apply_sum(c->disp, e, &inc, u); /* (ctx_init checked) */
}

/* The next iterate of the sparse joint iteration: Anderson's mix of inc (x) and inc_new (its
 * image) on the active cells, sorted, with d p of the image (as the dense iteration copies
 * dp_new). MC_OK, MC_ERR_NOMEM (inc is then the image, the history dropped). */
static int sparse_mix(loop_ctx *c, mc_error *err)
{
    long n;
    const long *cells;
    const double *vals;
    const int W = MC_INCR_WIDTH;
    if (mc_anderson_step_sparse(c->aa, c->inc.n, c->inc.cell, c->inc.val, c->inc_new.n,
                                c->inc_new.cell, c->inc_new.val, W, &n, &cells, &vals,
                                err) != MC_OK ||
        !mc_incr_reserve(&c->inc_tmp, n)) {
        incr_swap(&c->inc, &c->inc_new);
        return MC_ERR_NOMEM;
    }
    mc_plastic_incr *x = &c->inc_tmp;
    x->n = 0;
    for (long k = 0; k < n; k++) {
        double v[MC_INCR_WIDTH] = {0};
        memcpy(v, vals + 6 * k, 6 * sizeof *v);
        mc_incr_push(x, cells[k], v); /* (room reserved; sorted next) */
    }
    if (!mc_incr_sort(x, &c->inc)) {
        incr_swap(&c->inc, &c->inc_new);
        return mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the increment");
    }
    /* d p from the image: its cells with d p > 0 yield, so they are active (in x) */
    for (long k = 0, j = 0; k < x->n; k++) {
        while (j < c->inc_new.n && c->inc_new.cell[j] < x->cell[k])
            j++;
        if (j < c->inc_new.n && c->inc_new.cell[j] == x->cell[k])
            x->val[(size_t)W * k + 6] = c->inc_new.val[(size_t)W * j + 6];
    }
    incr_swap(&c->inc, x);
    return MC_OK;
}

/* The parts of the joint iteration that depend on how the increment is held (dense arrays, or
 * the sparse increment of theory §9.9): the same values either way. */

/* u_r = D(eps_p + x) (0 when that is zero everywhere); dense: tot = eps_p + x is left for the
 * sweep and, shared, the stress operator's forward made */
static void joint_displacement(loop_ctx *c, const mc_plastic_result *res)
{
    int any;
    c->begun = 0;
    if (c->sparse) {
        if ((any = c->eps_any || mc_incr_any(&c->inc))) {
            /* u_r from the stress operator's first half, which the sweep then ends (no
             * displacement apply of its own: theory §9.9) */
            const double *e[6];
            double *sg[6];
            split6(c, res->eps_p, e);
            for (int q = 0; q < 6; q++)
                sg[q] = c->sig_r + (size_t)q * (size_t)c->nvol;
            const mc_eigen_sparse inc = mc_incr_strain(&c->inc);
            c->begun = mc_eigen_stress_begin_sum(c->resid, e, &inc, c->G, sg, c->u_r) == MC_OK;
            if (!c->begun)
                sparse_displacement(c, res->eps_p, c->u_r);
        }
    } else if ((any = sum_kept(c, 6, res->eps_p, c->d_eps, c->tot)) && c->shared) {
        const double *e[6]; /* one forward transform of tot for u_r and the sweep */
        split6(c, c->tot, e);
        mc_eigen_disp_apply_shared(c->disp, c->resid, e, c->u_r);
    } else if (any && c->folded && mc_eigen_stress_takes_sum(c->resid)) {
        const double *e[6]; /* the first half of the sweep's apply, as the sparse branch */
        double *sg[6];
        split6(c, c->tot, e);
        for (int q = 0; q < 6; q++)
            sg[q] = c->sig_r + (size_t)q * (size_t)c->nvol;
        c->begun = mc_eigen_stress_begin_sum(c->resid, e, NULL, c->G, sg, c->u_r) == MC_OK;
    } else if (any) {
        residual_displacement(c, c->tot, c->u_r);
    }
    if (!any)
        memset(c->u_r, 0, c->ncell * sizeof *c->u_r);
}

/* x = 0, dp = 0 */
static void joint_clear(loop_ctx *c)
{
    c->inc.n = 0;
    if (!c->sparse) {
        memset(c->d_eps, 0, 6 * (size_t)c->nvol * sizeof *c->d_eps);
        memset(c->dp, 0, (size_t)c->nvol * sizeof *c->dp);
    }
}

/* The image becomes the iterate, and u_new = D(eps_p + image). Dense: d_new shares its array
 * with tot (ctx_init), so eps_p + d_new is formed in d_eps, which the image then overwrites. */
static void joint_take_image(loop_ctx *c, const mc_plastic_result *res)
{
    if (c->sparse) {
        incr_swap(&c->inc, &c->inc_new);
        sparse_displacement(c, res->eps_p, c->u_new);
        return;
    }
    (void)sum_kept(c, 6, res->eps_p, c->d_new, c->d_eps);
    residual_displacement(c, c->d_eps, c->u_new);
    copy_kept(c, 6, c->d_eps, c->d_new);
    copy_kept(c, 1, c->dp, c->dp_new);
}

/* Anderson's step from x and its image (dp the image's); MC_ERR_NOMEM when it cannot mix */
static int joint_mix(loop_ctx *c)
{
    mc_error aerr;
    if (c->sparse)
        return sparse_mix(c, &aerr);
    if (mc_anderson_step(c->aa, c->d_eps, c->d_new, &aerr) != MC_OK)
        return MC_ERR_NOMEM;
    copy_kept(c, 1, c->dp, c->dp_new);
    return MC_OK;
}

/* The joint iteration (docs/theory.md §9.8): Anderson mixing of the plastic strain increment x
 * through the whole coupled map, one contact solve and one residual stress application per
 * evaluation,
 *     u_r = D(eps_p + x),  p = contact(h + u_r),  x' = R(sigma_e(p) + S(eps_p + x) + 2 G x),
 * instead of an outer iteration on u_r around a plastic fixed point solved anew for every
 * contact solve. Its fixed point is the nested loop's, and so is its acceptance: the sweep
 * changes x by at most tol_plastic (the tight inner test of §9.4) and the residual displacement
 * of the image, D(eps_p + x'), differs from u_r by at most tol_outer (the outer test of §9.1);
 * the image is then the increment. *done 0: not converged within max_outer evaluations, or no
 * progress in JOINT_PATIENCE evaluations (the relative change of the sweep not below its least
 * so far), or a blow-up (the increment is then cleared: a cold start): the nested iteration goes
 * on from the state left in c->d_eps, c->dp. *contact_failed 1: the contact solve did not
 * converge (the run stops, §9.5). */
#define JOINT_PATIENCE 6

static int joint_body(loop_ctx *c, mc_contact_solver *solver, double load, int warm,
                      double *p, double *u, double *gap, mc_contact_summary *sum,
                      mc_plastic_result *res, mc_plastic_step *st, int *done,
                      int *contact_failed, mc_error *err)
{
    const mc_plastic_problem *pb = c->pb;
    const size_t nv6 = 6 * (size_t)c->nvol;
    const double elastic_below = surely_elastic_below(pb->law);
    double least = INFINITY;
    int since_least = 0;
    int exact = 0; /* 1: the next contact step settles the caller's equilibrium (not inexact) */
    *done = 0;
    *contact_failed = 0;
    c->eps_any = 0; /* (the sparse increment's "eps_p + x is zero" test reads it) */
    for (size_t i = 0; c->sparse && i < nv6 && !c->eps_any; i++)
        c->eps_any = res->eps_p[i] != 0.0;
    mc_anderson_restart(c->aa);
    for (int k = 1; k <= pb->max_outer; k++) {
        if (pb->stop && pb->stop(pb->stop_ctx))
            return mc_fail(err, MC_ERR_INTERRUPTED, "plastic loop: stopped on request");
        st->joint_evaluations++;
        st->outer_iterations++;
        st->plastic_iterations++;
        joint_displacement(c, res);
        int settled;
        int rc = contact_on_ur(c, solver, load, warm || k > 1, !exact, p, u, gap, sum, &settled,
                               st, err);
        if (rc != MC_OK)
            c->begun = 0; /* (no sweep ends the apply that joint_displacement began) */
        if (rc == MC_NOT_CONVERGED) {
            *contact_failed = 1;
            return MC_OK;
        }
        if (rc != MC_OK)
            return rc;
        if (!c->folded && (rc = elastic_stresses(c, p, err)) != MC_OK)
            return rc;
        int plastic = 0, had = 0, nomem = 0;
        double change = 0, size = 0;
        const int bad = c->sparse ? sparse_sweep(c, res->eps_p, res->peq, p, elastic_below,
                                                 &change, &size, &plastic, &had, &nomem)
                                  : sweep(c, res->eps_p, res->peq, c->folded ? p : NULL,
                                          c->shared, elastic_below, &change, &size, &plastic,
                                          &had);
        if (nomem)
            return mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the increment");
        if (bad || !(size <= DIVERGED_STRAIN)) { /* blew up: the nested loop starts cold */
            joint_clear(c);
            memcpy(c->u_r, res->u_r, c->ncell * sizeof *c->u_r);
            return MC_OK;
        }
        if (!plastic && !had) { /* nothing yields and nothing has: the increment is elastic */
            joint_clear(c);
            res->yield_skips++;
            *done = 1;
            return MC_OK;
        }
        const double rel = change / fmax(size, 1e-3);
        if (rel <= pb->tol_plastic) {
            /* the tight inner test met: the image becomes the iterate (a plain step) and the
             * outer test compares its residual displacement with u_r */
            joint_take_image(c, res);
            double uch = 0, usz = 0;
            for (size_t i = 0; i < c->ncell; i++) {
                uch = fmax(uch, fabs(c->u_new[i] - c->u_r[i]));
                usz = fmax(usz, fabs(c->u_new[i]));
            }
            if (uch <= pb->tol_outer * usz && settled) {
                memcpy(c->u_r, c->u_new, c->ncell * sizeof *c->u_r);
                res->inner_change = fmax(res->inner_change, rel);
                *done = 1;
                return MC_OK;
            }
            exact |= !settled; /* the caller's equilibrium lags: settle it in the next step */
            continue; /* (the history keeps its pairs: the next one spans this step too) */
        }
        if (rel < least) {
            least = rel;
            since_least = 0;
        } else if (++since_least >= JOINT_PATIENCE)
            break;
        if (joint_mix(c) != MC_OK) {
            mc_anderson_destroy(&c->aa); /* no memory to mix: the nested loop, unaccelerated */
            break;
        }
    }
    st->joint_fallback = 1;
    return MC_OK;
}

/* joint_body, distributed with one forward for u_r and the sweep (rows_ok): each rank keeps to
 * its rows of the volume (theory §8.4) - the sums eps_p + x, the residual stress (not gathered),
 * the sweep (its increments not gathered) and Anderson's mixing (its dot products summed row by
 * row over the ranks) - and the increment x and dp are gathered whole once at the end, instead of
 * the stresses and the increments at every evaluation. */
static int joint_iteration(loop_ctx *c, mc_contact_solver *solver, double load, int warm,
                           double *p, double *u, double *gap, mc_contact_summary *sum,
                           mc_plastic_result *res, mc_plastic_step *st, int *done,
                           int *contact_failed, mc_error *err)
{
    const int nz = c->pb->volume.nz;
    int r0, nr;
    if (c->rows_ok) { /* every rank alike: one that lacks the memory keeps them all whole */
        const int ok = mc_anderson_rows(c->aa, nz, (int)c->nwy, (int)c->nwx, c->row0, c->rows);
        c->kept = !mc_dist_max_int(!ok);
        if (ok && !c->kept)
            mc_anderson_rows(c->aa, 0, 0, 0, 0, -1);
    }
    if (c->kept)
        mc_eigen_stress_keep_rows(c->resid, 1, &r0, &nr);
    const int rc = joint_body(c, solver, load, warm, p, u, gap, sum, res, st, done,
                              contact_failed, err);
    if (!c->kept)
        return rc;
    c->kept = 0;
    mc_eigen_stress_keep_rows(c->resid, 0, &r0, &nr);
    if (c->aa)
        mc_anderson_rows(c->aa, 0, 0, 0, 0, -1);
    mc_dist_gather_blocks(c->d_eps, 6 * nz, (int)c->nwy, (int)c->nwx, c->row0, c->rows);
    mc_dist_gather_blocks(c->dp, nz, (int)c->nwy, (int)c->nwx, c->row0, c->rows);
    return rc;
}

static int increment(loop_ctx *c, mc_contact_solver *solver, double load, double dload,
                     int warm, double *p, double *u, double *gap, mc_contact_summary *sum,
                     mc_plastic_result *res, mc_plastic_step *st, int *conv, int *diverged,
                     mc_plastic_stop *why, mc_error *err)
{
    const mc_plastic_problem *pb = c->pb;
    const size_t nv6 = 6 * (size_t)c->nvol;
    *conv = 0;
    *diverged = 0;
    *why = MC_PLASTIC_RUN_CONVERGED;
    /* a step's sweeps over all its increments: what one unsplit increment may spend (§9.5) */
    const long budget = (long)pb->max_outer * pb->max_plastic;
    int capped = 0, grew = 0; /* successive tight fixed points at their cap; growths of u_r's */
    double last_change = INFINITY, least_change = INFINITY; /* change at tight fixed points */
    c->sig_r_fresh = 0;
    c->dense_now = !c->sparse;
    c->inc.n = 0;
    if (c->dense_now) {
        memset(c->d_eps, 0, nv6 * sizeof *c->d_eps);
        memset(c->dp, 0, (size_t)c->nvol * sizeof *c->dp);
    }
    memcpy(c->u_r, res->u_r, c->ncell * sizeof *c->u_r);
    if (!pb->cold_start && c->w_have && c->w_load > 0) {
        /* the warm start (theory §9.6): the last converged increment, scaled to this one's load
         * (at most 1: a step after split increments starts from the smaller increment) */
        const double s = fmin(1.0, dload / c->w_load);
        st->warm_cells = c->warm.n;
        if (!mc_incr_scaled(&c->inc, &c->warm, s))
            return mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the warm start");
        if (c->dense_now) /* the other cells stay 0 (memset above) */
            mc_incr_scatter(&c->inc, c->nvol, c->d_eps, c->dp);
        for (size_t i = 0; i < c->ncell; i++)
            c->u_r[i] += s * c->w_ur[i];
    }
    int joint_done = 0, joint_contact = 0, rc = MC_OK;
    if (pb->iteration == MC_PLASTIC_JOINT && c->aa && !c->near && !pb->tight_inner &&
        (rc = joint_iteration(c, solver, load, warm, p, u, gap, sum, res, st, &joint_done,
                              &joint_contact, err)) != MC_OK)
        return rc;
    if (joint_contact)
        *why = MC_PLASTIC_STOP_CONTACT;
    if (joint_done) {
        if ((rc = warm_remember(c, res, dload, err)) != MC_OK)
            return rc;
        *conv = 1;
    }
    if (joint_done || joint_contact)
        goto commit;
    double outer_rel = 1.0; /* relative change of u_r in the last outer iteration */
    double rel_hist[2] = {INFINITY, INFINITY}; /* in the two before it, older first */
    double forcing = pb->tight_inner ? 0.0 : INNER_FORCING;
    for (int k = 1; k <= pb->max_outer && !*why; k++) {
        if (pb->stop && pb->stop(pb->stop_ctx))
            return mc_fail(err, MC_ERR_INTERRUPTED, "plastic loop: stopped on request");
        if (st->plastic_iterations > budget - pb->max_plastic) { /* (never in an unsplit step) */
            *why = MC_PLASTIC_STOP_STEP_BUDGET;
            break;
        }
        if (!c->dense_now) { /* the nested iteration runs on dense arrays, from the joint
                                 iteration's state (made when first needed: theory §9.9) */
            if ((rc = dense_arrays(c, err)) != MC_OK)
                return rc;
            memset(c->d_eps, 0, nv6 * sizeof *c->d_eps);
            memset(c->dp, 0, (size_t)c->nvol * sizeof *c->dp);
            mc_incr_scatter(&c->inc, c->nvol, c->d_eps, c->dp);
            c->dense_now = 1;
        }
        st->outer_iterations++;
        int settled;
        rc = contact_on_ur(c, solver, load, warm || k > 1, 0, p, u, gap, sum, &settled, st, err);
        if (rc == MC_NOT_CONVERGED) { /* ends the run with the iterate before it (§9.5) */
            *why = MC_PLASTIC_STOP_CONTACT;
            rc = MC_OK;
            break;
        }
        if (rc != MC_OK)
            return rc;
        if ((rc = elastic_stresses(c, p, err)) != MC_OK)
            return rc;
        int sweeps = 0, fp_ok = 0, tight = 0, yielded = 0;
        double fp_change;
        if (k > INEXACT_OUTER)
            forcing = 0.0; /* the safeguard: tight from here on */
        const double tol_k = fmax(pb->tol_plastic, forcing * outer_rel);
        rc = plastic_fixed_point(c, res->eps_p, res->peq, tol_k, &sweeps, &fp_ok, &tight,
                                 &fp_change, &yielded, diverged, err);
        st->plastic_iterations += sweeps;
        if (!fp_ok)
            forcing = 0.0; /* the safeguard: a fixed point that hit its cap */
        if (*diverged)
            c->w_have = 0;
        if (rc != MC_OK || *diverged)
            return rc;
        capped = tol_k <= pb->tol_plastic && !fp_ok ? capped + 1 : 0;
        if (capped >= INNER_STALL) {
            *why = MC_PLASTIC_STOP_INNER_STALL;
            break;
        }
        int any = 0;
        for (size_t i = 0; i < nv6; i++) {
            c->tot[i] = res->eps_p[i] + c->d_eps[i];
            any |= c->tot[i] != 0.0;
        }
        if (!any) { /* the elastic shortcut: no plastic strain, no residual displacement */
            res->yield_skips++;
            memset(c->u_new, 0, c->ncell * sizeof *c->u_new);
        } else
            residual_displacement(c, c->tot, c->u_new);
        double change = 0, size = 0;
        int finite = 1;
        for (size_t i = 0; i < c->ncell; i++) {
            change = fmax(change, fabs(c->u_new[i] - c->u_r[i]));
            size = fmax(size, fabs(c->u_new[i]));
            finite &= isfinite(c->u_new[i]) != 0; /* (fmax drops a NaN) */
        }
        if (!finite) { /* as a fixed point that blew up: the caller splits the step */
            c->w_have = 0;
            *diverged = 1;
            return MC_OK;
        }
        /* accepted only on a tight inner solve: never on a loose one */
        if (tight && change <= pb->tol_outer * size) {
            memcpy(c->u_r, c->u_new, c->ncell * sizeof *c->u_r);
            if ((rc = warm_remember(c, res, dload, err)) != MC_OK)
                return rc;
            res->inner_change = fmax(res->inner_change, fp_change);
            *conv = 1;
            break;
        }
        if (tight) { /* the divergence test of §9.5 (a loose fixed point's change is noise) */
            grew = change > last_change ? grew + 1 : 0;
            last_change = change;
            least_change = fmin(least_change, change);
            if (grew >= OUTER_GROWTH && change > OUTER_GROWTH_FACTOR * least_change) {
                *why = MC_PLASTIC_STOP_OUTER_DIVERGES;
                break;
            }
        }
        /* the next inner tolerance; tight once this change is within tol_outer */
        const double rel = size > 0 ? change / size : INFINITY;
        if (k >= 3 && !(rel < rel_hist[0]))
            forcing = 0.0; /* the safeguard: a stalled outer iteration */
        rel_hist[0] = rel_hist[1];
        rel_hist[1] = rel;
        outer_rel = change <= pb->tol_outer * size ? 0.0 : fmin(1.0, rel);
        if (c->aa_outer) { /* Anderson mixing of the relaxed map: g = u + omega (u_new - u) */
            if (k == 1)
                mc_anderson_restart(c->aa_outer);
            for (size_t i = 0; i < c->ncell; i++) /* h_extra is rebuilt from u_r next */
                c->h_extra[i] = c->u_r[i] + pb->relaxation * (c->u_new[i] - c->u_r[i]);
            mc_error aerr;
            if (mc_anderson_step(c->aa_outer, c->u_r, c->h_extra, &aerr) != MC_OK)
                mc_anderson_destroy(&c->aa_outer); /* plain relaxation from here */
        } else
            for (size_t i = 0; i < c->ncell; i++)
                c->u_r[i] += pb->relaxation * (c->u_new[i] - c->u_r[i]);
    }
    if (!*conv && !*why)
        *why = MC_PLASTIC_STOP_OUTER_CAP;
commit:
    /* commit: the converged state, or the last iterate of a stop (the run ends with it) */
    if (c->dense_now) {
        for (size_t i = 0; i < nv6; i++)
            res->eps_p[i] += c->d_eps[i];
        for (long v = 0; v < c->nvol; v++)
            res->peq[v] += c->dp[v];
    } else { /* the other cells add zeros */
        for (long k = 0; k < c->inc.n; k++) {
            const size_t v = (size_t)c->inc.cell[k];
            for (int q = 0; q < 6; q++)
                res->eps_p[(size_t)q * (size_t)c->nvol + v] += c->inc.val[MC_INCR_WIDTH * k + q];
            res->peq[v] += c->inc.val[MC_INCR_WIDTH * k + 6];
        }
    }
    memcpy(res->u_r, c->u_r, c->ncell * sizeof *c->u_r);
    return MC_OK;
}

/* Splits of a diverging load step: up to 2^MAX_SPLIT sub-increments. */
#define MAX_SPLIT 5

int mc_plastic_run(const mc_grid *g, mc_operator *K, mc_contact_solver *solver,
                   const mc_plastic_problem *pb, double *p, double *u, double *gap,
                   mc_contact_summary *sum, mc_plastic_result *res, mc_error *err)
{
    memset(res, 0, sizeof *res);
    (void)K;
    int rc = check_problem(g, pb, err);
    if (rc != MC_OK)
        return rc;
    loop_ctx c;
    rc = ctx_init(&c, g, pb, err);
    const size_t nv6 = 6 * (size_t)c.nvol;
    double *save_eps = NULL, *save_peq = NULL, *save_ur = NULL;
    if (rc == MC_OK) {
        res->nvol = c.nvol;
        if (pb->state_eps_p) { /* lent: the state in place (loop.h) */
            res->eps_p = pb->state_eps_p;
            res->peq = pb->state_peq;
            res->lent |= 1;
        }
        if (!(res->steps = mc_calloc((size_t)pb->load_steps, sizeof *res->steps)) ||
            (!res->eps_p && !(res->eps_p = mc_zeros(nv6))) ||
            (!res->peq && !(res->peq = mc_zeros((size_t)c.nvol))) ||
            !(res->u_r = mc_zeros(c.ncell)) || !(save_ur = mc_zeros(c.ncell)))
            rc = mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the results");
    }
    c.p_lub = pb->p_lub;
    if (rc == MC_OK && (pb->eps_p0 || pb->peq0 || pb->state_eps_p)) {
        /* the state the steps before left (copied in, or lent in place) */
        int any = 0;
        if (pb->eps_p0)
            memcpy(res->eps_p, pb->eps_p0, nv6 * sizeof *res->eps_p);
        if (pb->eps_p0 || pb->state_eps_p)
            for (size_t i = 0; i < nv6 && !any; i++)
                any = res->eps_p[i] != 0.0;
        if (pb->peq0)
            memcpy(res->peq, pb->peq0, (size_t)c.nvol * sizeof *res->peq);
        if (any)
            residual_displacement(&c, res->eps_p, res->u_r);
    }
    res->converged = 1;
    for (int n = 1; rc == MC_OK && n <= pb->load_steps; n++) {
        mc_plastic_step *st = &res->steps[n - 1];
        const double l0 = pb->load * (n - 1) / pb->load_steps;
        st->load = pb->load * n / pb->load_steps;
        const long applies0 = c.stress_applies, local0 = c.local_sweeps, cells0 = c.local_cells;
        int all_conv = 0, diverged = 1;
        mc_plastic_stop why = MC_PLASTIC_RUN_CONVERGED;
        double at = st->load; /* the load of the increment in progress */
        for (int split = 0; rc == MC_OK && diverged && !why && split <= MAX_SPLIT; split++) {
            if (split == 1) { /* the unsplit increment diverged and committed nothing: the
                               * state is the one before the step; keep it for the finer splits
                               * (saved only now: a run that never splits holds no copy) */
                if (!save_eps && !(save_eps = mc_malloc(nv6 * sizeof *save_eps))) {
                    rc = mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the state "
                                                    "before a split load step");
                    break;
                }
                if (!save_peq && !(save_peq = mc_malloc((size_t)c.nvol * sizeof *save_peq))) {
                    rc = mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the state "
                                                    "before a split load step");
                    break;
                }
                memcpy(save_eps, res->eps_p, nv6 * sizeof *save_eps);
                memcpy(save_peq, res->peq, (size_t)c.nvol * sizeof *save_peq);
                memcpy(save_ur, res->u_r, c.ncell * sizeof *save_ur);
            } else if (split > 1) { /* back to the state before the step */
                memcpy(res->eps_p, save_eps, nv6 * sizeof *save_eps);
                memcpy(res->peq, save_peq, (size_t)c.nvol * sizeof *save_peq);
                memcpy(res->u_r, save_ur, c.ncell * sizeof *save_ur);
            }
            if (split > 0)
                st->splits = split;
            const int parts = 1 << split;
            all_conv = 1;
            diverged = 0;
            for (int q = 1; rc == MC_OK && !diverged && !why && q <= parts; q++) {
                int conv;
                at = l0 + (st->load - l0) * q / parts;
                rc = increment(&c, solver, at, (st->load - l0) / parts, n > 1 || q > 1, p, u,
                               gap, sum, res, st, &conv, &diverged, &why, err);
                all_conv &= conv;
            }
        }
        if (rc != MC_OK)
            break;
        if (diverged) /* the state is that of the last increment that did not blow up */
            why = MC_PLASTIC_STOP_SPLIT_LIMIT;
        st->converged = all_conv && !why;
        st->stress_applies = (int)(c.stress_applies - applies0);
        st->local_sweeps = (int)(c.local_sweeps - local0);
        st->local_cells = c.local_cells - cells0;
        res->converged &= st->converged;
        step_record(&c, sum, res->peq, res->u_r, st);
        res->steps_done = n;
        if (why) { /* the run ends here with its last iterate (theory §9.5) */
            res->stop = why;
            res->stop_step = n;
            res->stop_load = at;
            break;
        }
    }
    if (rc == MC_OK) { /* unloading: the residual field of the plastic strain alone */
        residual_displacement(&c, res->eps_p, res->u_r);
        residual_stress(&c, res->eps_p);
        res->sig_r = c.sig_r; /* handed over, not copied: the loop is done with it */
        c.sig_r = NULL;
        if (c.lent_sig_r)
            res->lent |= 2;
        res->residual_vm = c.dp_new; /* likewise: a volume array the loop no longer needs (the
                                        sparse increment's runs make it now) */
        c.dp_new = NULL;
        if (!res->residual_vm &&
            !(res->residual_vm = mc_malloc((size_t)c.nvol * sizeof *res->residual_vm)))
            rc = mc_fail(err, MC_ERR_NOMEM, "plastic loop: out of memory for the results");
    }
    if (rc == MC_OK) {
        for (long v = 0; v < c.nvol; v++) {
            double s3[6];
            for (int q = 0; q < 6; q++)
                s3[q] = res->sig_r[q * c.nvol + v];
            res->residual_vm[v] = mc_von_mises(s3);
        }
        if (!res->converged)
            rc = mc_fail(err, MC_NOT_CONVERGED,
                         "plastic loop: load step %d of %d (%g N, stopped at %g N): %s; the "
                         "results are those of the last iterate",
                         res->stop_step, pb->load_steps, res->steps[res->stop_step - 1].load,
                         res->stop_load, mc_plastic_stop_text(res->stop));
    }
    res->p_lub = c.p_lub;
    res->contact_solves = c.solves;
    res->sparse_increment = c.sparse;
    mc_free(save_eps);
    mc_free(save_peq);
    mc_free(save_ur);
    ctx_free(&c);
    return rc;
}

void mc_plastic_result_free(mc_plastic_result *res)
{
    mc_free(res->steps);
    if (!(res->lent & 1)) {
        mc_free(res->eps_p);
        mc_free(res->peq);
    }
    mc_free(res->u_r);
    mc_free(res->residual_vm);
    if (!(res->lent & 2))
        mc_free(res->sig_r);
    memset(res, 0, sizeof *res);
}

double mc_plastic_loop_bytes(const mc_grid *g, const mc_eigen_volume *v, int anderson,
                             int near_reach, double yielding, int fallback)
{
    const double nvol = (double)v->nz * v->nx * v->ny, ncell = (double)g->nx * g->ny;
    const int whole = v->i0 == 0 && v->j0 == 0 && v->nx == g->nx && v->ny == g->ny;
    const int sparse = v->kernel == MC_EIG_KERNEL_SPECTRAL && whole && anderson > 0 &&
                       near_reach == 0;
    /* the result's eps_p (6) and peq, sig_r (6); dense: sig_e (6, in the fallback when whole),
     * d_eps, tot (6 each), dp, dp_new; sparse: those in the fallback, one layer of 7 */
    double per_vol = (6 + 1 + 6) * 8.0, per_layer = 0;
    double per_yield = 7 * 8.0 + 8; /* warm start: 7 values and the index */
    if (sparse) {
        per_layer = 7 * 8.0;
        per_yield += 3 * (7 * 8.0 + 8) + 16;
        per_vol += fallback ? (6 + 6 + 6 + 1 + 1) * 8.0 : 0.0;
    } else
        per_vol += (6 + 6 + 1 + 1) * 8.0 + (!whole || fallback ? 6 * 8.0 : 0.0);
    if (anderson > 0) { /* the map of the active cells (dense steps); histories, iterate, lists */
        per_vol += sparse && !fallback ? 0.0 : 4.0;
        per_yield += 2.0 * (anderson + 1) * 6 * 8 + 6 * 8 + 16;
    }
    if (near_reach > 0) {
        per_vol += 4;                  /* the active index */
        per_yield += 8 + 3 * 6 * 8 + 8; /* list, d0c, dnc, corr, dpc */
    }
    /* qx, u_r, u_new, h_extra, w_ur, the result's u_r, save_ur; a window smaller than the grid: one
     * layer of elastic stresses; Anderson on u_r */
    double per_cell = 7 * 8.0 + (whole ? 0 : 6 * 8.0) + (anderson > 0 ? 16 + 16.0 * (anderson + 1)
                                                                        : 0);
    return per_vol * nvol + per_layer * v->nx * v->ny + per_yield * yielding + per_cell * ncell;
}
