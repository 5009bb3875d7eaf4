/* loop.h - the semi-analytical elastic-plastic contact loop (Jacq, Nelias, Lormand, Girodin 2002;
 * docs/theory.md §9): load steps, each an under-relaxed outer iteration of
 *   (a) the contact with the residual displacement added to the gap (lubricant bound kept),
 *   (b) the elastic stress of the pressure (and friction traction) at the cuboid centres,
 *   (c) the plastic fixed point: trial stress sigma_e + sigma_r(eps_p + d eps_p) + 2G d eps_p,
 *       radial return from the accumulated plastic strain (return_map.h),
 *   (d) the residual surface displacement of the plastic strain (eigen_op.h),
 * then unloading: the residual topography and the residual stress of the plastic strain alone.
 *
 * The plastic body is body 1 (the stresses are body 1's: nu1, G1). With `both` the counter body
 * is of the same material and sees the same contact stresses mirrored, so it deforms alike: the
 * gap opens by twice the residual displacement of body 1 (an assumption stated in the docs).
 * The volume grid is nz layers of cuboids of thickness dz under a window of surface columns;
 * the rest of the half-space stays elastic. With operators that read a dense field plus a sparse
 * addend (the spectral kernel) the joint iteration holds the step's increment on its cells alone
 * (plastic/increment.h, docs/theory.md §9.9). Pure numerics: no scene, no printing.
 */
#ifndef MC_PLASTIC_LOOP_H
#define MC_PLASTIC_LOOP_H

#include "contact/contact.h"
#include "core/error.h"
#include "operator/operator.h"
#include "plastic/eigen_op.h"
#include "plastic/hardening.h"
#include "plastic/local_op.h"
#include "stress/stress.h"

/* How an increment iterates its coupled state (docs/theory.md §9.1, §9.8). */
typedef enum {
    MC_PLASTIC_JOINT = 0, /* Anderson mixing of the plastic increment through the whole map */
    MC_PLASTIC_NESTED = 1 /* outer iteration on u_r around the plastic fixed point */
} mc_plastic_iteration;

/* The key word of each ([plasticity] iteration, summary.json). */
static inline const char *mc_plastic_iteration_name(mc_plastic_iteration it)
{
    return it == MC_PLASTIC_NESTED ? "nested" : "joint";
}

/* The operators of the loop - the elastic stresses of the surface tractions at the cuboid
 * centres (stress/stress.h: patch kernels, p and, with friction, q_x), the residual surface
 * displacement and the residual stress of the plastic strain (eigen_op.h) - for one grid, volume,
 * nu and backend. Building them (the kernel tables) costs as much as tens of fixed-point sweeps;
 * a caller that runs the loop many times on the same problem (the running-in: one run per
 * run-down step) builds them once with mc_plastic_ops_create and passes them in
 * mc_plastic_problem.ops. The fields besides the three operators record what they were made for
 * (checked by mc_plastic_run). */
typedef struct {
    mc_stress_plan *elastic;
    mc_eigen_disp *disp;
    mc_eigen_stress *resid;
    mc_grid g;
    mc_eigen_volume volume;    /* its group points to the copy below */
    int *group;                /* the layering's copy (NULL: uniform) */
    double nu;
    mc_backend backend;
    int friction;              /* 1: the elastic plan takes the friction traction q_x too */
    mc_plastic_local *near;    /* the near field of resid (local_op.h), made by the first run
                                  that asks for it (mc_plastic_problem.near_reach), NULL before */
    int near_reach;            /* the lateral reach it was made with */
} mc_plastic_ops;

/* 1 when the operators of volume v on grid g fold the surface loads into the residual stress
 * operator (eigen_op.h mc_eigen_stress_loads; theory §8.9): a volume under the whole grid. The
 * loop then takes the elastic stresses from resid (one set of inverse transforms for both fields
 * in the joint iteration's sweep), and elastic serves only the caller (the running-in's yield
 * check); its tables cost 6 nz quadrants per load beside Love's (the memory guard counts them). */
static inline int mc_plastic_ops_fold(const mc_grid *g, const mc_eigen_volume *v)
{
    return v->i0 == 0 && v->j0 == 0 && v->nx == g->nx && v->ny == g->ny;
}

/* Build the operators for grid g, volume v, Poisson ratio nu, backend b, with the friction
 * traction when friction != 0. *ops is zeroed on failure. MC_OK, MC_ERR_INPUT, MC_ERR_NOMEM or
 * the operators' own errors (stress.h, eigen_op.h). */
int mc_plastic_ops_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                          int friction, mc_plastic_ops *ops, mc_error *err);

/* Free the operators and zero *ops (zeroed or partly built ops too). */
void mc_plastic_ops_destroy(mc_plastic_ops *ops);

/* Step (a) supplied by the caller: solve the contact problem cp (h, h_extra, load and warm start
 * as the loop sets them) into p, u, gap and sum as mc_contact_solve does, choosing the lubricant
 * pressure itself - e.g. by the lubricant volume equilibrium (lube/volume.h, which the plastic
 * layer does not see) - and return it in *p_lub (Pa, >= 0). inexact 1 (the joint iteration,
 * theory.md §9.8): the caller may return after one step of its own equilibrium (e.g. one secant
 * step of the root, one contact solve), a state that need not meet its tolerance yet; *settled
 * says whether the returned state meets it (1 always when inexact is 0 and MC_OK is returned).
 * Return codes as mc_contact_solve. */
typedef int (*mc_plastic_contact_fn)(void *ctx, const mc_contact_problem *cp, int inexact,
                                     double *p, double *u, double *gap, mc_contact_summary *sum,
                                     double *p_lub, int *settled, mc_error *err);

/* The largest near_reach of mc_plastic_problem (the near field's blocks grow as its square). */
#define MC_PLASTIC_NEAR_REACH_MAX 8

typedef struct {
    /* the contact (force control, the load rises linearly over the steps) */
    const double *h;   /* initial gap at zero approach (ny*nx), m */
    double load;       /* the maximum load, N */
    double p_lub;      /* uniform lubricant pressure (lower bound), Pa, >= 0 */
    double friction;   /* q_x = friction (p - p_lub) where in solid contact; 0 = none; signed:
                          > 0 the counter body slides in +x relative to body 1, < 0 in -x */
    int load_steps;    /* >= 1 */
    /* body 1 */
    double E, nu;              /* Pa; 0 <= nu < 0.5 */
    const mc_hardening *law;   /* yield stress and hardening */
    int both;                  /* 1: body 2 is the same material and deforms alike */
    /* the volume grid: nz layers of dz under a window of columns (eigen_op.h) */
    mc_eigen_volume volume;
    mc_backend backend;
    /* iteration control */
    double relaxation;         /* omega in (0, 1]: u_r += omega (u_r,new - u_r) */
    double tol_outer;          /* relative change of u_r that ends the outer iteration */
    int max_outer;             /* outer iterations per step */
    double tol_plastic;        /* relative change of d eps_p that ends the fixed point */
    int max_plastic;           /* fixed-point iterations per outer iteration */
    int tight_inner;           /* 1: every fixed point to tol_plastic; 0 (default): inexact
                                  inner solves, to max(tol_plastic, 0.05 x the last outer
                                  iteration's relative change of u_r), tight from the outer
                                  iteration after the one whose change met tol_outer, and for
                                  the rest of the increment once the outer iteration stalls,
                                  a fixed point hits max_plastic, or after 10 outer iterations;
                                  either way
                                  an outer iteration is accepted only on a fixed point that met
                                  tol_plastic (docs/theory.md §9.4) */
    int cold_start;            /* 1: every increment starts from a zero plastic strain
                                  increment and the committed u_r (the reference of the unit
                                  tests); 0 (default): from the last converged increment of the
                                  run scaled to this one's load (warm start, docs/theory.md
                                  §9.6) */
    mc_plastic_iteration iteration; /* MC_PLASTIC_JOINT (0, the default): each increment
                                  first iterates the coupled state by Anderson mixing, one
                                  contact solve and one residual stress application per
                                  evaluation (docs/theory.md §9.8), and goes on with the nested
                                  iteration below from its state only if that has not converged
                                  in max_outer evaluations; MC_PLASTIC_NESTED: the nested
                                  iteration alone (outer iteration on u_r, plastic fixed point
                                  inside). The joint iteration needs anderson > 0 and is not
                                  used with tight_inner or near_reach (nested schemes) */
    int near_reach;            /* > 0: local-global fixed point (docs/theory.md §9.7): between
                                  two applications of the residual stress operator the plastic
                                  increment is iterated on the cells at or near yield with the
                                  operator's near field (local_op.h) within near_reach columns;
                                  the same fixed point and stopping test as 0, far fewer
                                  applications; 0: one application per sweep (the reference) */
    int dense_increment;       /* 1: the joint iteration holds its increment in dense volume
                                  arrays even where the sparse increment applies (spectral kernel,
                                  one process; theory §9.9): the same bits, for the tests; 0
                                  (default): sparse where it applies */
    int anderson;              /* > 0: Anderson acceleration with this history depth
                                  (plastic/anderson.h, <= MC_ANDERSON_MAX_DEPTH) of the plastic
                                  fixed point and of the outer iteration (on the relaxed map
                                  u + omega (u_new - u): it also damps the two-cycles of a contact
                                  set that flips); 0: the adaptive under-relaxation of the fixed
                                  point and plain relaxation outside */
    /* the material state before the first step (running-in: what the steps before left), in
     * the volume layout of the result; NULL = virgin (zero). The residual displacement and the
     * residual stress of eps_p0 are taken into account from the first contact on. */
    const double *eps_p0;      /* 6 * nvol plastic strain, component-major */
    const double *peq0;        /* nvol accumulated equivalent plastic strain (hardening) */
    /* the state lent in place (NULL: none; the running-in, which carries it from step to step,
     * lends its arrays instead of passing eps_p0 / peq0 and copying the result back: no second
     * copy of the volume state). state_eps_p (6 * nvol) and state_peq (nvol), both or neither,
     * hold the state before the first step on entry (eps_p0 and peq0 must then be NULL) and the
     * totals on return: res->eps_p and res->peq are these arrays (res->lent says so;
     * mc_plastic_result_free leaves them). state_sig_r (6 * nvol, optional) is the loop's
     * residual stress array and res->sig_r on return (its content on entry is not read);
     * work_sig_e (6 * nvol, optional) is the loop's elastic stress array (scratch). The same bits
     * as eps_p0 / peq0 and the loop's own arrays. After an error other than MC_NOT_CONVERGED
     * their contents are undefined. */
    double *state_eps_p, *state_peq, *state_sig_r, *work_sig_e;
    /* step (a) by the caller (NULL: mc_contact_solve with the uniform p_lub above); the friction
     * traction then acts where p exceeds the lubricant pressure p_lub lube_shape[i] of the cell,
     * p_lub the one the caller returned (stress/traction.h) */
    mc_plastic_contact_fn contact;
    void *contact_ctx;
    const double *lube_shape;  /* ny*nx, the lubricant pressure's shape over the grid (the whole
                                  contact's profile); NULL = uniform */
    /* the operators, made by mc_plastic_ops_create for this grid, volume, nu, backend and
     * friction (!= 0 or not), borrowed for the run (NULL: the run builds its own and frees them;
     * the results are the same bits either way; operators with friction serve a problem with
     * friction 0 too). Another problem's: MC_ERR_INPUT. */
    mc_plastic_ops *ops;
    /* polled before every outer iteration (NULL: never); non-zero abandons the run with
     * MC_ERR_INTERRUPTED (the result is then incomplete and only to be freed) */
    int (*stop)(void *ctx);
    void *stop_ctx;
} mc_plastic_problem;

/* Why a run stopped short of the full load (docs/theory.md §9.5). Every way out of a load step
 * that is not convergence ends the run: the later steps would start from a state that is not an
 * equilibrium, and each would spend the caps again. */
typedef enum {
    MC_PLASTIC_RUN_CONVERGED = 0,
    MC_PLASTIC_STOP_OUTER_CAP,    /* max_outer outer iterations without meeting tol_outer */
    MC_PLASTIC_STOP_INNER_STALL,  /* the tight fixed point hit max_plastic in successive outer
                                     iterations */
    MC_PLASTIC_STOP_OUTER_DIVERGES, /* the change of u_r grew in successive outer iterations */
    MC_PLASTIC_STOP_SPLIT_LIMIT,  /* the increments blew up (plastic strain beyond 0.5,
                                     non-finite values) even in the finest split */
    MC_PLASTIC_STOP_STEP_BUDGET,  /* the step's increments used max_outer x max_plastic sweeps */
    MC_PLASTIC_STOP_CONTACT       /* the contact solve (step a) did not converge */
} mc_plastic_stop;

/* One line on why the run stopped ("" for MC_PLASTIC_RUN_CONVERGED). */
const char *mc_plastic_stop_text(mc_plastic_stop why);

/* One load step's record (plastic.csv). */
typedef struct {
    double load, approach, p_max, area;
    double plastic_volume;      /* m^3 of cuboids with p > 0 */
    double peq_max, peq_at[3];  /* largest accumulated plastic strain and its cell centre, m */
    double residual_max;        /* largest residual displacement (into the body), m */
    int outer_iterations;
    int plastic_iterations;     /* fixed-point sweeps, summed over the outer iterations */
    int contact_solves;         /* calls of step (a) (with a lubricant: volume equilibria) */
    int stress_applies;         /* residual stress applications (the sweeps' costly operator;
                                   a sweep with no plastic strain anywhere skips it) */
    int local_sweeps;           /* near-field sweeps between them (near_reach > 0) */
    long local_cells;           /* near-field spreads of those sweeps (cells whose change was
                                   spread to their neighbours: their cost) */
    int splits;                 /* the step diverged and was done in 2^splits increments */
    int joint_evaluations;      /* evaluations of the joint iteration (each also counted as an
                                   outer iteration, a sweep and a contact solve) */
    int joint_fallback;         /* 1: the joint iteration did not converge and the nested one
                                   went on from its state */
    long warm_cells;            /* volume cells the warm start of its (last) increment seeded
                                   with the increment before (0: a cold start) */
    int converged;
} mc_plastic_step;

typedef struct {
    int converged;              /* every step converged */
    int steps_done;
    mc_plastic_step *steps;     /* load_steps records (owned) */
    double *eps_p;              /* 6 * nvol plastic strain, component-major (owned unless
                                   lent) */
    double *peq;                /* nvol accumulated equivalent plastic strain (owned unless
                                   lent) */
    double *u_r;                /* ny*nx residual displacement of body 1, m (owned) */
    double *residual_vm;        /* nvol von Mises of the residual stress after unloading (owned) */
    double *sig_r;              /* 6 * nvol residual stress after unloading, Pa, component-major
                                   (owned unless lent) */
    int lent;                   /* bits: 1 eps_p and peq are the problem's state_eps_p and
                                   state_peq, 2 sig_r is its state_sig_r (not freed here) */
    long nvol;
    int sparse_increment;       /* 1: the joint iteration held its increment sparse (theory
                                   §9.9; mc_plastic_problem.dense_increment) */
    long yield_skips;           /* outer iterations where nothing yielded (shortcut taken) */
    double inner_change;        /* largest relative change of the plastic fixed point's last
                                   sweep at an accepted outer iteration (<= tol_plastic) */
    double p_lub;               /* lubricant pressure of the last contact solve, Pa */
    int contact_solves;         /* step (a) calls */
    mc_plastic_stop stop;       /* why the run stopped short (MC_PLASTIC_RUN_CONVERGED: it did
                                   not) */
    int stop_step;              /* the load step it stopped in, from 1 (0: none) */
    double stop_load;           /* the load of the increment it stopped in, N */
} mc_plastic_result;

/* Run the loop. solver is planned over K (the two-body Love operator of the surface grid);
 * p, u, gap (ny*nx, caller-owned) receive the state at the maximum load, sum its contact
 * summary. With eps_p0, peq0 the result's eps_p, peq are the totals (initial plus this run's)
 * and u_r the residual displacement of the total. The work is bounded by counts (theory §9.5):
 * at most load_steps x max_outer x max_plastic sweeps, however the steps split. Returns MC_OK,
 * MC_NOT_CONVERGED (a load step did not converge and the run stopped there: everything is
 * still filled from the last iterate, finite, res->converged = 0, res->stop and stop_step say
 * why and where, the step records end with that step, and err names both), MC_ERR_INTERRUPTED
 * (prob->stop asked), or an error. */
int mc_plastic_run(const mc_grid *g, mc_operator *K, mc_contact_solver *solver,
                   const mc_plastic_problem *prob, double *p, double *u, double *gap,
                   mc_contact_summary *sum, mc_plastic_result *res, mc_error *err);

void mc_plastic_result_free(mc_plastic_result *res);

/* The bytes mc_plastic_run holds besides its operators (mc_plastic_ops), for volume v on grid g
 * with Anderson depth `anderson` (0: none) and near_reach (0: none), at its peak (the sweeps),
 * with `yielding` cells in the plastic zone; fallback 1 adds what a nested iteration makes on
 * first need (the memory guard counts it; a run that never leaves the joint iteration never
 * makes it).
 *   Dense increment (the cuboid kernel; any kernel with near_reach or anderson 0): the dense
 *     volume arrays of the loop and the result (264 bytes per volume cell: sig_e, sig_r, d_eps,
 *     tot, eps_p 48 each, dp, dp_new, peq 8 each; a volume under the whole grid makes sig_e on
 *     first need, i.e. in the fallback), Anderson's map (4), the near field's index (4).
 *   Sparse increment (theory §9.9: the spectral kernel, a volume under the whole grid, Anderson,
 *     no near field; the default joint iteration on one process): sig_r, eps_p, peq (104 bytes
 *     per volume cell), one layer of 7 values; the fallback makes d_eps, tot, dp, dp_new and
 *     sig_e and Anderson's map (164 bytes per volume cell).
 * Per yielding cell: the warm start (64 bytes), Anderson's history (96 (anderson + 1) + 64), the
 * near-field lists (160), the sparse increment's three lists (192) and its sort (16); and the
 * surface arrays. The arrays a problem lends (state_eps_p, state_peq, state_sig_r, work_sig_e)
 * are counted too: the caller holds them instead of the loop. A split load step's copy of the
 * state (56 bytes per volume cell, taken only when a step diverges) is not counted. */
double mc_plastic_loop_bytes(const mc_grid *g, const mc_eigen_volume *v, int anderson,
                             int near_reach, double yielding, int fallback);

#endif
