/* runin.c - the running-in driver (runin.h): setup, the state carried from step to step,
 * checkpoints and resume; one step at a time. */
#include "pipeline/runin.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "core/dist.h"
#include "core/threads.h"
#include "kernels/invariants.h"
#include "lube/film.h"
#include "lube/volume.h"
#include "operator/operator.h"
#include "pipeline/bodies.h"
#include "pipeline/checkpoint.h"
#include "pipeline/memguard.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_lube.h"
#include "pipeline/stage_plastic.h"
#include "plastic/loop.h"
#include "plastic/return_map.h"
#include "stress/stress.h"
#include "stress/traction.h"
#include "surface/roughness.h"
#include "surface/surface.h"

/* History depth of the Anderson acceleration of the plastic fixed point (plastic/anderson.h):
 * on the running-in patches it cuts the sweeps per outer iteration about threefold (from ~26 to
 * ~10 at the same tolerance; measured on the 64 x 32 x 15 scene of the unit tests). 8, not 4:
 * the joint iteration's tail converges faster (512 x 256 x 16 step: 22 -> 19 evaluations, 18 %
 * less time; 20 at 6) for 12 bytes per volume cell of history per depth (theory §9.8). */
#define MC_RUNIN_ANDERSON 8

#define FNV_OFFSET 14695981039346656037ull
#define FNV_PRIME 1099511628211ull

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= FNV_PRIME;
    }
    return h;
}

uint64_t mc_runin_case_hash(const mc_scene *sc, const double *h0, size_t n)
{
    mc_scene *s = mc_malloc(sizeof *s);
    if (!s)
        return 0;
    memcpy(s, sc, sizeof *s); /* a byte copy: the padding stays what the defaults zeroed */
    memset(s->path, 0, sizeof s->path);
    memset(s->output.dir, 0, sizeof s->output.dir);
    memset(s->key_line, 0, sizeof s->key_line); /* where keys stand in the file is no matter */
    uint64_t h = fnv(FNV_OFFSET, s, sizeof *s);
    mc_free(s);
    return fnv(h, h0, n * sizeof *h0);
}

double mc_runin_hysteresis(const mc_runin_summary *r, int f)
{
    const int m = r->nspeeds, base = 2 * m * f;
    if (f < 0 || f >= r->nforces || r->done < base + 2 * m)
        return NAN;
    double area = 0;
    for (int k = 0; k + 1 < m; k++) { /* down rows base + k, up rows base + 2m - 1 - k */
        const mc_runin_row *d0 = &r->rows[base + k], *d1 = &r->rows[base + k + 1];
        const mc_runin_row *u0 = &r->rows[base + 2 * m - 1 - k];
        const mc_runin_row *u1 = &r->rows[base + 2 * m - 2 - k];
        double dl = log10(d0->speed) - log10(d1->speed);
        area += 0.5 * dl * ((d0->mu - u0->mu) + (d1->mu - u1->mu));
    }
    return area;
}

/* ---- the context ----------------------------------------------------------------------------- */

typedef struct {
    const mc_scene *sc;
    const mc_runin_options *opt;
    mc_results *res;
    mc_scene *step;           /* the scene of the current step: force and speed set */
    mc_grid g;
    size_t n;
    int nf, m, nsteps;
    double forces[MC_RUNIN_MAX];
    mc_operator *K;
    mc_contact_solver *solver;
    double *h0;               /* initial topography (= res->topography) */
    double *bowl;             /* K 1: the patch's deflection per unit nominal pressure, m/Pa */
    double *h_base, *h_extra; /* per step: h0 - p_nom bowl, f u_r */
    double *z;                /* scratch: the composite surface */
    double *shape;            /* the whole contact: the macro cylinder (topography = shape -
                                 heights), NULL for a patch */
    unsigned char *rmask;     /* the whole contact: the roughness is evaluated on the Hertz band
                                 of the largest force (the track every force runs on), else NULL */
    mc_roughness_options ropt;
    double factor;            /* gap opening per residual displacement of body 1 (1 or 2) */
    /* the material: state carried from step to step */
    int plastic;
    mc_hardening law;
    double G;
    mc_eigen_volume vol;
    int *group;               /* graded layers: vol.group (theory.md §8.8); NULL: uniform */
    long nvol;
    double *eps_p, *peq, *sig_r, *u_r; /* lent to the loop in place (plastic/loop.h) */
    mc_stress_plan *splan;    /* elastic stresses at the cuboid centres (the yield check); from
                                 the first plastic step on the operators' own (ops.elastic) */
    mc_plastic_ops ops;       /* the loop's operators, built at the first plastic step and kept
                                 for the others (plastic/loop.h) */
    double *s_layer;          /* 6 ny nx: one layer of the yield check's elastic stresses,
                                 s_lay[q] its components (the volume's are never held: the
                                 loop makes its own only if its nested iteration needs them) */
    double *s_lay[6], *qx;
    int qx_loads;             /* the yield check and the loop's operators take q_x too */
    double slide;             /* friction_in_yield: +1 (-1) when disc 2 slides in +x (-x)
                                 against disc 1, the sign of the traction on body 1; else 0 */
    uint64_t hash;
    double seconds;           /* compute time of the steps done (also those of a checkpoint) */
    /* a plastic loop that stopped short (plastic/loop.h): the running-in ends with that step */
    mc_plastic_stop stop;
    int stop_step;            /* its load step */
    double stop_load;         /* the load of its last increment, N */
} runin_ctx;

static void ctx_free(runin_ctx *c)
{
    mc_free(c->step);
    mc_contact_destroy(&c->solver);
    mc_operator_destroy(&c->K);
    double *a[] = {c->bowl, c->h_base, c->h_extra, c->z,     c->eps_p,  c->peq,
                   c->sig_r, c->u_r,   c->qx,      c->shape, c->s_layer};
    mc_free(c->rmask);
    mc_free(c->group);
    for (size_t k = 0; k < sizeof a / sizeof a[0]; k++)
        mc_free(a[k]);
    if (c->splan != c->ops.elastic) /* (else the operators' own) */
        mc_stress_destroy(&c->splan);
    mc_plastic_ops_destroy(&c->ops);
    mc_hardening_free(&c->law);
}

/* A stop asked (a signal): under MPI the ranks agree (a signal may reach one process only), so
 * every rank stops at the same step boundary or outer iteration. Collective: called at the same
 * points on every rank (the replicated loop's counts, plastic/loop.h; never a clock). */
static int stopped(const runin_ctx *c)
{
    int mine = c->opt && c->opt->stop && c->opt->stop(c->opt->stop_ctx);
    return mc_dist_max_int(mine);
}

/* A status every rank must share before the next collective step: the worst over the ranks
 * (the codes grow with their gravity, MC_OK = 0). A rank that succeeded where another failed
 * says so in err (only rank 0 speaks: its message is the one printed). Collective. */
static int agree(int rc, const char *what, mc_error *err)
{
    int all = mc_dist_max_int(rc);
    if (all != rc && rc == MC_OK)
        mc_fail(err, all, "running-in: %s failed on another MPI process", what);
    return all;
}

static int stop_poll(void *ctx) { return stopped(ctx); }

/* ISO parameters of the composite surface z = -(h0 + f u_r). */
static int surface_roughness(runin_ctx *c, double *z, mc_roughness_params *out, mc_error *err)
{
    for (size_t i = 0; i < c->n; i++)
        z[i] = (c->shape ? c->shape[i] : 0.0) - (c->h0[i] + c->factor * c->u_r[i]);
    return mc_roughness_compute(z, c->rmask, c->g.nx, c->g.ny, c->g.dx, c->g.dy, &c->ropt, out, err);
}

/* The macro contact of step (force F, disc speed n) into res->lube; the step's base gap. */
static int step_macro(runin_ctx *c, double F, double speed, mc_error *err)
{
    c->step->load.value = F;
    c->step->lubrication.rpm = speed;
    if (c->sc->lubrication.rpm2 > 0) /* rolling-sliding: the slide-to-roll ratio stays */
        c->step->lubrication.rpm2 = c->sc->lubrication.rpm2 * speed / c->sc->lubrication.rpm;
    int rc = mc_stage_lube_macro(c->step, &c->g, &c->res->lube, err);
    if (rc == MC_OK)
        rc = mc_stage_lube_profile(c->step, c->res, err);
    if (rc != MC_OK)
        return rc;
    const double pnom = c->res->lube.nominal_pressure;
    for (size_t i = 0; i < c->n; i++) {
        c->h_base[i] = c->bowl ? c->h0[i] - pnom * c->bowl[i] : c->h0[i];
        c->h_extra[i] = c->factor * c->u_r[i];
    }
    return MC_OK;
}

/* The volume equilibrium of the current step on the current surface, from a cold start, into
 * res's fields. */
static int equilibrium(runin_ctx *c, mc_volume_result *vr, mc_error *err)
{
    mc_results *r = c->res;
    mc_volume_problem prob = {.h = c->h_base,
                              .weight = r->lube_profile,
                              .h_extra = c->h_extra,
                              .load = r->lube.patch_load,
                              .h_target = r->lube.h_ehd,
                              .tolerance = c->sc->lubrication.tolerance};
    return mc_volume_equilibrium(c->solver, c->K, &prob, r->pressure, r->displacement, r->gap, vr,
                                 err);
}

/* Does anything yield under pressure p (lubricant pressure p_lub, shaped by the whole
 * contact's profile) and the traction q_x = f (p - p_l) in solid contact (f signed, 0: none;
 * stress/traction.h) with the residual stress and hardening
 * of the state? The loop's first sweep (plastic/loop.c) from a zero increment. */
/* One layer of the yield check: does a cell of layer k yield (hit), is a trial stress not finite
 * (bad)? */
typedef struct {
    runin_ctx *c;
    int hit, bad;
} yield_scan;

static int yield_layer(void *ctx, int k, double *const s[6])
{
    yield_scan *y = ctx;
    const runin_ctx *c = y->c;
    const long n = (long)c->n, v0 = (long)k * n;
    int hit = 0, bad = 0;
#pragma omp parallel for schedule(static) reduction(| : hit, bad) if (n > 4096)
    for (long i = 0; i < n; i++) {
        double trial[6], out[6], de[6], dp;
        for (int q = 0; q < 6; q++)
            trial[q] = s[q][i] + c->sig_r[(size_t)q * (size_t)c->nvol + (size_t)(v0 + i)];
        mc_error e1;
        if (mc_return_map(trial, c->peq[v0 + i], &c->law, c->G, out, de, &dp, &e1) != MC_OK)
            bad = 1;
        else
            hit |= dp > 0;
    }
    y->hit |= hit;
    y->bad |= bad;
    return MC_OK;
}

static int yields(runin_ctx *c, const double *p, double p_lub, double f, int *any, mc_error *err)
{
    if (f != 0)
        mc_traction_friction(p, p_lub, c->res->lube_profile, f, c->n, c->qx);
    /* layer by layer: the volume's elastic stresses (48 bytes per volume cell) are never held */
    yield_scan y = {c, 0, 0};
    int rc = mc_stress_field_layers(c->splan, p, f != 0 ? c->qx : NULL, NULL, c->s_lay,
                                    yield_layer, &y, err);
    if (rc != MC_OK)
        return rc;
    if (y.bad)
        return mc_fail(err, MC_ERR_NUMERIC, "running-in: non-finite stress in the yield check");
    *any = y.hit;
    return MC_OK;
}

/* The elastic-plastic loop of a run-down step from the carried state, with the traction
 * coefficient f (signed; 0: none); the state is updated. */
static int plastic_step(runin_ctx *c, double f, const mc_volume_result *seed,
                        mc_plastic_step *record, mc_stage_lube_contact *lc, int *conv,
                        mc_error *err)
{
    const mc_scene *sc = c->sc;
    mc_results *r = c->res;
    if (!c->ops.resid) {
        int rc = mc_plastic_ops_create(&c->g, &c->vol, sc->body1.nu, sc->solver.backend,
                                       c->qx_loads, &c->ops, err);
        if (rc != MC_OK)
            return rc;
        /* the yield check's plan was made with the same options (grid, layer depths, nu,
         * backend, loads): the operators take it and drop their own, one plan for both */
        mc_stress_destroy(&c->ops.elastic);
        c->ops.elastic = c->splan;
    }
    *lc = (mc_stage_lube_contact){.solver = c->solver,
                            .K = c->K,
                            .h_target = r->lube.h_ehd,
                            .weight = r->lube_profile,
                            .tolerance = sc->lubrication.tolerance,
                            .last = *seed, /* its pressure is still in r->pressure */
                            .seeded = 1};
    mc_plastic_problem pb = {.h = c->h_base,
                             .load = r->lube.patch_load,
                             .p_lub = r->lube.p_lub,
                             .lube_shape = r->lube_profile,
                             .friction = f,
                             .load_steps = sc->plasticity.load_steps,
                             .E = sc->body1.E,
                             .nu = sc->body1.nu,
                             .law = &c->law,
                             .both = sc->plasticity.both,
                             .volume = c->vol,
                             .backend = sc->solver.backend,
                             .relaxation = sc->plasticity.relaxation,
                             .tol_outer = sc->plasticity.tolerance,
                             .max_outer = sc->plasticity.max_outer,
                             .tol_plastic = sc->plasticity.plastic_tolerance,
                             .max_plastic = sc->plasticity.max_plastic,
                             .iteration = sc->plasticity.iteration,
                             .near_reach = sc->plasticity.near_field,
                             .anderson = MC_RUNIN_ANDERSON,
                             .state_eps_p = c->eps_p, /* lent: the totals come back in them */
                             .state_peq = c->peq,
                             .state_sig_r = c->sig_r,
                             .contact = mc_stage_lube_contact_step,
                             .contact_ctx = lc,
                             .ops = &c->ops,
                             .stop = stop_poll,
                             .stop_ctx = c};
    mc_plastic_result pr;
    int rc = mc_plastic_run(&c->g, c->K, c->solver, &pb, r->pressure, r->displacement, r->gap,
                            &r->contact, &pr, err);
    /* eps_p, peq and sig_r are the state's own arrays (lent); after an error other than
     * MC_NOT_CONVERGED they are undefined, and the running-in ends without writing them (its
     * checkpoint holds the state of the last step done) */
    if (rc == MC_OK || rc == MC_NOT_CONVERGED) {
        memcpy(c->u_r, pr.u_r, c->n * sizeof *c->u_r);
        if (pr.steps_done > 0)
            *record = pr.steps[pr.steps_done - 1];
        *conv = pr.converged;
        c->stop = pr.stop;
        c->stop_step = pr.stop_step;
        c->stop_load = pr.stop_load;
    }
    mc_plastic_result_free(&pr);
    return rc;
}

/* One step: s in [0, nsteps). Fills row and, for a plastic run-down step, record. */
static int run_step(runin_ctx *c, int s, mc_runin_row *row, mc_plastic_step *record,
                    mc_error *err)
{
    const int m = c->m, f = s / (2 * m), k = s % (2 * m), up = k >= m;
    const double F = c->forces[f], speed = c->sc->runin.speeds[up ? 2 * m - 1 - k : k];
    double t0 = mc_clock();
    mc_results *r = c->res;
    memset(row, 0, sizeof *row);
    row->force_index = f;
    row->up = up;
    row->force = F;
    row->speed = speed;
    int rc = step_macro(c, F, speed, err);
    if (rc != MC_OK)
        return rc;
    mc_volume_result vr;
    rc = equilibrium(c, &vr, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    row->converged = rc == MC_OK;
    row->solves = vr.solves;
    row->roots = 1;
    const mc_volume_result *last = &vr;
    mc_stage_lube_contact lc;
    if (!up && c->plastic && rc == MC_OK) {
        /* the traction of the yield check: [plasticity] friction, or (friction_in_yield) the mu
         * of this step's equilibrium before it yields, along the sliding (theory.md §19.7) */
        double fr = c->sc->plasticity.friction;
        if (c->slide != 0) {
            rc = mc_stage_lube_outcome(c->step, &vr, r, err);
            if (rc != MC_OK)
                return rc;
            fr = c->slide * r->lube.mu;
        }
        int any = 0;
        rc = yields(c, r->pressure, vr.p_lub, fr, &any, err);
        if (rc != MC_OK)
            return rc;
        if (any) {
            int conv = 0;
            memset(record, 0, sizeof *record);
            rc = plastic_step(c, fr, &vr, record, &lc, &conv, err);
            if (rc != MC_OK && rc != MC_NOT_CONVERGED)
                return rc;
            row->plastic = 1;
            row->converged = rc == MC_OK && conv && lc.last.converged;
            row->solves += lc.solves;
            row->roots += lc.calls;
            if (lc.calls > 0)
                last = &lc.last;
        }
    }
    int src = mc_stage_lube_outcome(c->step, last, r, err);
    if (src != MC_OK)
        return src;
    const mc_stage_lube_summary *l = &r->lube;
    row->entrainment = l->entrainment;
    row->h_ehd = l->h_ehd;
    row->p_lub = l->p_lub;
    row->psi_load = l->psi_load;
    row->psi_area = l->psi_area;
    row->pocket_height = l->pocket_height;
    row->mu = l->mu;
    row->regime = (int)last->regime;
    row->root_error = last->rel_error;
    mc_roughness_params rp;
    src = surface_roughness(c, c->z, &rp, err);
    if (src != MC_OK)
        return src;
    row->ra = rp.Ra;
    row->rq = rp.Rq;
    row->rz = rp.Rz;
    row->sa = rp.Sa;
    row->sq = rp.Sq;
    row->rpk = rp.Rpk;
    row->rk = rp.Rk;
    row->rvk = rp.Rvk;
    row->mr1 = rp.Mr1;
    row->mr2 = rp.Mr2;
    row->sp = rp.Sp;
    row->spk = rp.Spk;
    row->sk = rp.Sk;
    row->svk = rp.Svk;
    row->smr1 = rp.Smr1;
    row->smr2 = rp.Smr2;
    for (size_t i = 0; i < c->n; i++)
        row->residual_max = fmax(row->residual_max, c->u_r[i]);
    row->seconds = mc_clock() - t0;
    return rc;
}

/* ---- setup ----------------------------------------------------------------------------------- */

/* The plastic volume under the whole grid: nz layers of [plasticity] dz down to [plasticity]
 * depth, or (auto) to 1.25 times the deepest layer where the elastic von Mises stress of the
 * dry contact (p_lub = 0) at the largest force exceeds the initial yield stress. (The
 * elastic-plastic stage of a single contact keeps the layers above half of it; a rough patch
 * under a dry load stays above that deep below the asperities, where nothing yields.) */
static int plan_volume(runin_ctx *c, mc_error *err)
{
    const mc_scene *sc = c->sc;
    const double dz = sc->plasticity.dz > 0 ? sc->plasticity.dz : fmin(c->g.dx, c->g.dy);
    double depth = sc->plasticity.depth;
    if (!(depth > 0)) {
        double fmax_ = 0;
        for (int f = 0; f < c->nf; f++)
            fmax_ = fmax(fmax_, c->forces[f]);
        int rc = step_macro(c, fmax_, sc->runin.speeds[0], err);
        mc_contact_problem prob = {.h = c->h_base,
                                   .p_cap = INFINITY,
                                   .control = MC_CONTROL_FORCE,
                                   .load = c->res->lube.patch_load};
        mc_contact_summary cs;
        if (rc == MC_OK)
            rc = mc_contact_solve(c->solver, &prob, c->res->pressure, c->res->displacement,
                                  c->res->gap, &cs, err);
        enum { NPROBE = 48 };
        double z[NPROBE], vm[NPROBE];
        for (int k = 0; k < NPROBE; k++)
            z[k] = (k + 0.5) * dz;
        if (rc == MC_OK)
            rc = mc_stage_plastic_layer_maxima(sc, &c->g, c->res->pressure, 0.0, NULL, z,
                                               NPROBE, vm, err);
        if (rc != MC_OK)
            return rc;
        double deepest = 0, y0 = mc_hardening_initial(&c->law);
        for (int k = 0; k < NPROBE; k++)
            if (vm[k] > y0)
                deepest = z[k] + 0.5 * dz;
        depth = fmax(1.25 * deepest, 2 * dz);
    }
    int nz = (int)ceil(depth / dz - 1e-9);
    nz = nz < 1 ? 1 : nz;
    /* graded layers (theory.md §8.8): by default with depth = auto, as the stage */
    if (sc->plasticity.layering == MC_LAYERING_GRADED ||
        (sc->plasticity.layering == MC_LAYERING_AUTO && !(sc->plasticity.depth > 0))) {
        const double fine = sc->plasticity.fine_depth > 0 ? sc->plasticity.fine_depth
                                                          : 8 * fmin(c->g.dx, c->g.dy);
        if (!(c->group = mc_malloc((size_t)nz * sizeof *c->group)))
            return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory for the layering");
        nz = mc_eigen_grade(dz, depth, fine, sc->plasticity.grading, c->group, nz);
    }
    c->vol = mc_eigen_volume_full(&c->g, nz, dz);
    c->vol.stress_points = sc->plasticity.stress_points;
    c->vol.kernel = sc->plasticity.kernel;
    c->vol.group = c->group;
    c->nvol = (long)c->vol.nz * c->g.nx * c->g.ny;
    return MC_OK;
}

static int setup(runin_ctx *c, mc_error *err)
{
    const mc_scene *sc = c->sc;
    mc_results *r = c->res;
    c->g = sc->grid;
    c->n = mc_grid_cells(&c->g);
    c->m = sc->runin.nspeeds;
    c->nf = sc->runin.nforces > 0 ? sc->runin.nforces : 1;
    for (int f = 0; f < c->nf; f++)
        c->forces[f] = sc->runin.nforces > 0 ? sc->runin.forces[f] : sc->load.value;
    c->nsteps = 2 * c->nf * c->m;
    c->plastic = sc->plasticity.enabled;
    c->factor = c->plastic && sc->plasticity.both ? 2.0 : 1.0;
    r->grid = c->g;
    r->roughness_seed = sc->roughness.seed;
    double **fields[] = {&r->topography, &r->pressure, &r->gap, &r->displacement,
                         &r->surface_initial, &r->surface_final};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++)
        if (!(*fields[k] = mc_zeros(c->n)))
            return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory for the fields");
    if (!(c->step = mc_malloc(sizeof *c->step)) || !(c->h_base = mc_zeros(c->n)) ||
        !(c->h_extra = mc_zeros(c->n)) || !(c->z = mc_zeros(c->n)) || !(c->u_r = mc_zeros(c->n)))
        return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory");
    memcpy(c->step, sc, sizeof *c->step);
    c->h0 = r->topography;
    int rc = mc_bodies_topography(sc, r, c->h0, NULL, err); /* with [roughness2]: z1 + z2 */
    if (rc != MC_OK)
        return rc;
    c->hash = mc_runin_case_hash(sc, c->h0, c->n);
    if (mc_lube_is_whole(sc)) { /* the whole contact (stage_lube.h) */
        double fmax_ = 0;
        for (int f = 0; f < c->nf; f++)
            fmax_ = fmax(fmax_, c->forces[f]);
        mc_stage_lube_summary widest;
        c->step->load.value = fmax_; /* the largest band must fit the grid: say so up front */
        rc = mc_stage_lube_macro(c->step, &c->g, &widest, err);
        if (rc != MC_OK)
            return rc;
        if (!(c->shape = mc_zeros(c->n)) || !(c->rmask = mc_malloc(c->n)))
            return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory");
        mc_surface_shape(&c->g, &sc->geometry, c->shape);
        for (int j = 0; j < c->g.ny; j++)
            for (int i = 0; i < c->g.nx; i++)
                c->rmask[(size_t)j * c->g.nx + i] =
                    mc_stage_lube_nominal_shape(&widest, mc_grid_x(&c->g, i), mc_grid_y(&c->g, j), 0) > 0;
    }
    /* a simulated window is much shorter than the ISO 4288 cut-off (0.8 mm for ground
     * surfaces): without a [roughness] cutoff the rows are only levelled (their mean removed),
     * not filtered (dossier plastic-lubrication §6.2) */
    mc_roughness_options_default(&c->ropt);
    c->ropt.cutoff = sc->roughness.cutoff;
    c->ropt.filter = sc->roughness.cutoff > 0;
    c->ropt.periodic_x = c->g.periodic_x;
    c->ropt.periodic_y = c->g.periodic_y;
    if (sc->roughness.type != MC_ROUGH_NONE) {
        rc = surface_roughness(c, r->surface_initial, &r->roughness_initial, err);
        if (rc == MC_OK)
            rc = mc_bodies_initial_parameters(sc, 1, r, NULL, err);
        if (rc != MC_OK)
            return rc;
        r->has_roughness = 1;
    } else
        for (size_t i = 0; i < c->n; i++)
            r->surface_initial[i] = -c->h0[i];
    double t0 = mc_clock();
    const double estar = mc_scene_estar(sc);
    rc = mc_operator_plan_love(&c->g, estar, sc->solver.backend, &c->K, err);
    mc_contact_options copt = {.method = sc->solver.method,
                               .tolerance = sc->solver.tolerance,
                               .max_iterations = sc->solver.max_iterations,
                               .estar = estar};
    if (rc == MC_OK)
        rc = mc_contact_create(c->K, &copt, &c->solver, err);
    const int whole = mc_lube_is_whole(sc);
    if (rc == MC_OK && sc->runin.deflection == MC_DEFLECTION_REMOVE && !whole) {
        double *one = mc_zeros(c->n);
        if (!one || !(c->bowl = mc_zeros(c->n))) {
            mc_free(one);
            return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory");
        }
        for (size_t i = 0; i < c->n; i++)
            one[i] = 1.0;
        mc_operator_apply(c->K, one, c->bowl);
        mc_free(one);
    }
    if (rc == MC_OK && c->plastic) {
        rc = mc_stage_plastic_law(sc, &c->law, err);
        if (rc != MC_OK)
            mc_error_prefix(err, "[plasticity] ");
        c->G = sc->body1.E / (2.0 * (1.0 + sc->body1.nu));
        /* the surface speeds of the first step (every step keeps their ratio); pure rolling is
         * refused by the scene rules */
        if (sc->runin.friction_in_yield && sc->lubrication.rpm2 > 0) {
            const double u1 = sc->lubrication.rpm * sc->lubrication.radius1;
            const double u2 = sc->lubrication.rpm2 * sc->lubrication.radius2;
            c->slide = u2 > u1 ? 1.0 : u2 < u1 ? -1.0 : 0.0;
        }
        /* with mu_solid = mu_fluid = 0 every step's traction is 0: the operators without q_x, so
         * the run is the one without the option to the bit */
        c->qx_loads = sc->plasticity.friction > 0 ||
                      (c->slide != 0 &&
                       (sc->lubrication.mu_solid > 0 || sc->lubrication.mu_fluid > 0));
        if (rc == MC_OK)
            rc = plan_volume(c, err);
        if (rc == MC_OK) /* the plastic guard, once the volume is known (pipeline/memguard.h) */
            rc = mc_memory_check_runin(sc, &c->g, &c->vol, err);
        const size_t nv = (size_t)c->nvol;
        if (rc == MC_OK && (!(c->eps_p = mc_zeros(6 * nv)) || !(c->peq = mc_zeros(nv)) ||
                            !(c->sig_r = mc_zeros(6 * nv)) || !(c->qx = mc_zeros(c->n)) ||
                            !(c->s_layer = mc_zeros(6 * c->n))))
            rc = mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory for %ld volume cells",
                         c->nvol);
        for (int q = 0; rc == MC_OK && q < 6; q++)
            c->s_lay[q] = c->s_layer + (size_t)q * c->n;
        double *depths = rc == MC_OK ? mc_zeros((size_t)c->vol.nz) : NULL;
        if (rc == MC_OK && !depths)
            rc = mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory");
        for (int k = 0; rc == MC_OK && k < c->vol.nz; k++)
            depths[k] = mc_eigen_layer_depth(&c->vol, k);
        mc_stress_options so = {.kernel = MC_STRESS_PATCH,
                                .nu = sc->body1.nu,
                                .nlayers = c->vol.nz,
                                .depths = depths,
                                .backend = sc->solver.backend,
                                .loads = MC_TRACTION_P | (c->qx_loads ? MC_TRACTION_QX : 0)};
        if (rc == MC_OK)
            rc = mc_stress_create(&c->g, &so, &c->splan, err);
        mc_free(depths);
    }
    r->timing.setup_s = mc_clock() - t0;
    return rc;
}

/* ---- the ranks ------------------------------------------------------------------------------ */

static uint64_t fnv_words(uint64_t h, const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        uint64_t w;
        memcpy(&w, &v[i], sizeof w);
        h ^= w;
        h *= FNV_PRIME;
    }
    return h;
}

/* Under mpirun every rank computes the carried state replicated, by the same code from the same
 * gathered pressure: the same bits, or a bug (a rank that diverged would feed its rows of other
 * numbers to the next distributed solve, and rank 0 alone writes). After each step the state's
 * hash (pressure, residual displacement, plastic strain, hardening, residual stress) is compared
 * with rank 0's. Collective; nothing without a communicator. */
static int same_state(const runin_ctx *c, int step, mc_error *err)
{
    if (mc_dist_size() <= 1)
        return MC_OK;
    uint64_t h = fnv_words(FNV_OFFSET, c->res->pressure, c->n);
    h = fnv_words(h, c->u_r, c->n);
    if (c->plastic) {
        const size_t nv = (size_t)c->nvol;
        h = fnv_words(h, c->eps_p, 6 * nv);
        h = fnv_words(h, c->peq, nv);
        h = fnv_words(h, c->sig_r, 6 * nv);
    }
    /* two 32-bit halves: exact in doubles */
    const double mine[2] = {(double)(h >> 32), (double)(h & 0xffffffffu)};
    double root[2] = {mine[0], mine[1]};
    mc_dist_bcast(root, 2, 0);
    if (mc_dist_max_int(root[0] != mine[0] || root[1] != mine[1]))
        return mc_fail(err, MC_ERR_INTERNAL,
                       "running-in: after step %d the MPI processes hold different states (they "
                       "compute them replicated and must agree to the bit: a bug)",
                       step);
    return MC_OK;
}

/* ---- checkpoints ----------------------------------------------------------------------------- */

static int save(runin_ctx *c, int done, const mc_plastic_step *records, int nrec, mc_error *err)
{
    if (!c->opt || !c->opt->checkpoint_dir)
        return MC_OK;
    mc_checkpoint ck = {.case_hash = c->hash,
                        .nx = c->g.nx,
                        .ny = c->g.ny,
                        .nz = c->plastic ? c->vol.nz : 0,
                        .nvol = c->plastic ? c->nvol : 0,
                        .nsteps = c->nsteps,
                        .done = done,
                        .seconds = c->seconds,
                        .rows = c->res->runin.rows,
                        .eps_p = c->eps_p,
                        .peq = c->peq,
                        .sig_r = c->sig_r,
                        .u_r = c->u_r,
                        .nrec = nrec,
                        .records = (mc_plastic_step *)records};
    /* rank 0 alone writes (the ranks hold the same state); its status for all */
    int rc = mc_dist_rank() == 0 ? mc_checkpoint_write(c->opt->checkpoint_dir, &ck, err) : MC_OK;
    int all = mc_dist_root_int(rc);
    if (all != rc)
        mc_fail(err, all, "checkpoint: rank 0 could not write it");
    return all;
}

static int restore(runin_ctx *c, int *start, mc_plastic_step *records, int *nrec, mc_error *err)
{
    const char *dir = c->opt->checkpoint_dir;
    mc_checkpoint ck;
    /* rank 0 reads the file and every rank receives its bytes or its error (checkpoint.c,
     * core/dist.h: DIR/checkpoint need only be visible to rank 0); the worst status for all */
    int rc = agree(mc_checkpoint_read(dir, &ck, err), "reading the checkpoint", err);
    if (rc != MC_OK) {
        mc_checkpoint_free(&ck); /* (nothing held when this rank's read failed) */
        return rc;
    }
    if (ck.case_hash != c->hash)
        rc = mc_fail(err, MC_ERR_INPUT,
                     "the checkpoint in '%s' belongs to another case (or other --set values): "
                     "resume with the case and settings that started it, or run without "
                     "--resume to start over",
                     dir);
    else if (ck.nx != c->g.nx || ck.ny != c->g.ny || ck.nsteps != c->nsteps ||
             ck.nvol != (c->plastic ? c->nvol : 0) || ck.nz != (c->plastic ? c->vol.nz : 0))
        rc = mc_fail(err, MC_ERR_INPUT,
                     "the checkpoint in '%s' does not fit this run (grid %d x %d, %d steps, %ld "
                     "volume cells; the case asks %d x %d, %d, %ld)",
                     dir, ck.nx, ck.ny, ck.nsteps, ck.nvol, c->g.nx, c->g.ny, c->nsteps,
                     c->plastic ? c->nvol : 0);
    if (rc == MC_OK) {
        const size_t nv = (size_t)ck.nvol;
        memcpy(c->res->runin.rows, ck.rows, (size_t)ck.done * sizeof *ck.rows);
        if (nv > 0) {
            memcpy(c->eps_p, ck.eps_p, 6 * nv * sizeof *c->eps_p);
            memcpy(c->peq, ck.peq, nv * sizeof *c->peq);
            memcpy(c->sig_r, ck.sig_r, 6 * nv * sizeof *c->sig_r);
        }
        memcpy(c->u_r, ck.u_r, c->n * sizeof *c->u_r);
        c->seconds = ck.seconds;
        memcpy(records, ck.records, (size_t)ck.nrec * sizeof *records);
        *nrec = ck.nrec;
        /* a finished run is resumed at its last step (a run-up: elastic, from the state, so it
         * adds no record), so that its fields are there to be written */
        *start = ck.done < ck.nsteps ? ck.done : ck.nsteps - 1;
        if (*start < ck.done)
            c->seconds -= ck.rows[*start].seconds; /* it is timed again */
        c->res->runin.resumed_from = *start;
    }
    mc_checkpoint_free(&ck);
    return rc;
}

/* ---- results --------------------------------------------------------------------------------- */

/* The plastic fields and summary of the final state (results.h). */
static int plastic_results(runin_ctx *c, const mc_plastic_step *records, int nrec, mc_error *err)
{
    const mc_scene *sc = c->sc;
    mc_results *r = c->res;
    mc_stage_plastic_summary *ps = &r->plastic;
    const size_t n = c->n, nv = (size_t)c->nvol;
    mc_free(ps->group);
    memset(ps, 0, sizeof *ps);
    ps->enabled = 1;
    ps->criterion = "von_mises";
    ps->hardening = mc_hardening_name(sc->plasticity.hardening);
    ps->stress_points = mc_eig_stress_points_name(sc->plasticity.stress_points);
    ps->kernel = mc_eig_kernel_name(sc->plasticity.kernel);
    ps->iteration = mc_plastic_iteration_name(sc->plasticity.iteration);
    ps->yield_initial = mc_hardening_initial(&c->law);
    ps->load_steps = nrec;
    ps->steps_done = nrec;
    ps->converged = 1;
    for (int s = 0; s < r->runin.done; s++)
        ps->converged &= r->runin.rows[s].converged;
    if (!(r->residual_displacement = mc_zeros(n)) || !(r->topography_final = mc_zeros(n)) ||
        !(r->plastic_strain = mc_zeros(nv)) || !(r->residual_von_mises = mc_zeros(nv)) ||
        (nrec > 0 && !(ps->steps = mc_calloc((size_t)nrec, sizeof *ps->steps))))
        return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory for the outputs");
    if (nrec > 0)
        memcpy(ps->steps, records, (size_t)nrec * sizeof *records);
    for (int k = 0; k < nrec; k++)
        ps->outer_iterations += records[k].outer_iterations;
    for (size_t i = 0; i < n; i++) {
        r->residual_displacement[i] = c->u_r[i];
        r->topography_final[i] = c->h0[i] + c->factor * c->u_r[i];
        ps->residual_max = fmax(ps->residual_max, c->u_r[i]);
    }
    long at = -1;
    for (size_t v = 0; v < nv; v++) {
        double s6[6];
        for (int q = 0; q < 6; q++)
            s6[q] = c->sig_r[(size_t)q * nv + v];
        r->residual_von_mises[v] = mc_von_mises(s6);
        r->plastic_strain[v] = c->peq[v];
        if (c->peq[v] > 0)
            ps->plastic_volume += c->g.dx * c->g.dy *
                                  mc_eigen_layer_thickness(&c->vol, (int)(v / c->n));
        if (c->peq[v] > ps->peq_max) {
            ps->peq_max = c->peq[v];
            at = (long)v;
        }
    }
    if (at >= 0) {
        long i = at % c->g.nx, j = (at / c->g.nx) % c->g.ny, k = at / ((long)c->g.nx * c->g.ny);
        ps->peq_max_at[0] = mc_grid_x(&c->g, (int)i);
        ps->peq_max_at[1] = mc_grid_y(&c->g, (int)j);
        ps->peq_max_at[2] = mc_eigen_layer_depth(&c->vol, (int)k);
    }
    ps->depth = mc_eigen_volume_depth(&c->vol);
    ps->layering = c->group ? "graded" : "uniform";
    if (c->group) {
        if (!(ps->group = mc_malloc((size_t)c->vol.nz * sizeof *ps->group)))
            return mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory for the outputs");
        memcpy(ps->group, c->group, (size_t)c->vol.nz * sizeof *ps->group);
    }
    ps->dz = c->vol.dz;
    ps->nz = c->vol.nz;
    ps->depth_auto = !(sc->plasticity.depth > 0);
    ps->wnx = c->g.nx;
    ps->wny = c->g.ny;
    ps->volume_cells = c->nvol;
    return MC_OK;
}

static int final_results(runin_ctx *c, const mc_plastic_step *records, int nrec, mc_error *err)
{
    mc_results *r = c->res;
    for (size_t i = 0; i < c->n; i++)
        r->surface_final[i] = (c->shape ? c->shape[i] : 0.0) - (c->h0[i] + c->factor * c->u_r[i]);
    if (r->has_roughness) {
        int rc = surface_roughness(c, c->z, &r->roughness_final, err);
        if (rc != MC_OK)
            return rc;
        r->has_roughness_final = 1;
        rc = mc_bodies_final(c->sc, 1, c->u_r, r, NULL, err); /* each body minus its own dent */
        if (rc != MC_OK)
            return rc;
    }
    for (int f = 0; f < c->nf; f++)
        r->runin.hysteresis[f] = mc_runin_hysteresis(&r->runin, f);
    return c->plastic ? plastic_results(c, records, nrec, err) : MC_OK;
}

/* ---- the run --------------------------------------------------------------------------------- */

static int run(runin_ctx *c, mc_error *err)
{
    const mc_scene *sc = c->sc;
    mc_results *r = c->res;
    const double t_start = mc_clock();
    int rc = mc_scene_check(sc, err);
    if (rc == MC_OK && !sc->runin.enabled)
        rc = mc_fail(err, MC_ERR_INPUT, "running-in: the scene has no [runin] section");
    if (rc == MC_OK)
        rc = mc_memory_check(sc, err);
    if (rc == MC_OK)
        rc = setup(c, err);
    rc = agree(rc, "the setup", err);
    mc_runin_summary *ri = &r->runin;
    ri->enabled = 1;
    ri->nforces = c->nf;
    ri->nspeeds = c->m;
    ri->nsteps = c->nsteps;
    ri->deflection = sc->runin.deflection == MC_DEFLECTION_REMOVE ? "remove" : "keep";
    mc_plastic_step *records = NULL;
    if (rc == MC_OK && (!(ri->rows = mc_calloc((size_t)c->nsteps, sizeof *ri->rows)) ||
                        !(ri->hysteresis = mc_zeros((size_t)c->nf)) ||
                        !(records = mc_calloc((size_t)c->nsteps, sizeof *records))))
        rc = mc_fail(err, MC_ERR_NOMEM, "running-in: out of memory for the rows");
    int start = 0, nrec = 0, worst = MC_OK, stopped_at = 0;
    mc_error stop_err = {0};
    if (rc == MC_OK && c->opt && c->opt->resume) {
        if (!c->opt->checkpoint_dir)
            rc = mc_fail(err, MC_ERR_INPUT, "running-in: resume needs a checkpoint directory");
        else
            rc = restore(c, &start, records, &nrec, err);
    }
    const double t_session = mc_clock();
    for (int s = start; rc == MC_OK && s < c->nsteps; s++) {
        if (stopped(c)) {
            rc = mc_fail(err, MC_ERR_INTERRUPTED, "running-in: stopped before step %d of %d",
                         s + 1, c->nsteps);
            break;
        }
        mc_plastic_step rec;
        memset(&rec, 0, sizeof rec);
        int src = agree(run_step(c, s, &ri->rows[s], &rec, err), "a step", err);
        if (src == MC_ERR_INTERRUPTED) {
            rc = src;
            break;
        }
        if (src != MC_OK && src != MC_NOT_CONVERGED) {
            rc = mc_error_prefix(err, "running-in step %d of %d (%g N, %s, %.6g rpm): ", s + 1,
                                 c->nsteps, ri->rows[s].force, ri->rows[s].up ? "up" : "down",
                                 ri->rows[s].speed * 60.0 / (2.0 * M_PI));
            break;
        }
        if (src == MC_NOT_CONVERGED)
            worst = src;
        if (ri->rows[s].plastic)
            records[nrec++] = rec;
        if (c->stop) { /* the loop stopped short: the running-in ends with its last iterate */
            stop_err = *err;
            mc_error_prefix(&stop_err, "running-in step %d of %d (%g N, %s, %.6g rpm): ", s + 1,
                            c->nsteps, ri->rows[s].force, ri->rows[s].up ? "up" : "down",
                            ri->rows[s].speed * 60.0 / (2.0 * M_PI));
            stopped_at = s + 1;
        }
        c->seconds += ri->rows[s].seconds;
        ri->done = s + 1;
        rc = same_state(c, s + 1, err);
        if (rc == MC_OK)
            rc = save(c, ri->done, records, nrec, err);
        if (rc == MC_OK && c->opt && c->opt->progress) {
            const double el = mc_clock() - t_session;
            mc_runin_progress pr = {.step = s + 1,
                                    .nsteps = c->nsteps,
                                    .row = &ri->rows[s],
                                    .elapsed = el,
                                    .eta = el / (s + 1 - start) * (c->nsteps - s - 1)};
            c->opt->progress(c->opt->progress_ctx, &pr);
        }
        if (stopped_at)
            break;
    }
    if (rc == MC_OK)
        rc = final_results(c, records, nrec, err);
    if (rc == MC_OK && stopped_at) {
        r->plastic.stop_runin_step = stopped_at;
        r->plastic.stop_step = c->stop_step;
        r->plastic.stop_load = c->stop_load;
        r->plastic.stop_reason = mc_plastic_stop_text(c->stop);
    }
    mc_free(records);
    r->timing.total_s = mc_clock() - t_start;
    r->timing.contact_s = c->seconds;
    if (rc == MC_OK && stopped_at) {
        *err = stop_err;
        rc = MC_NOT_CONVERGED;
    } else if (rc == MC_OK && worst != MC_OK)
        rc = mc_fail(err, worst, "running-in: a solve did not converge (see runin.csv, column "
                                 "converged)");
    return rc;
}

int mc_runin_run(const mc_scene *sc, const mc_runin_options *opt, mc_results *res,
                 mc_error *err)
{
    memset(res, 0, sizeof *res);
    runin_ctx c;
    memset(&c, 0, sizeof c);
    c.sc = sc;
    c.opt = opt;
    c.res = res;
    mc_threads_scope scope;
    mc_threads_begin(sc->solver.threads, &scope);
    int rc = run(&c, err);
    mc_threads_end(&scope);
    ctx_free(&c);
    return rc;
}
