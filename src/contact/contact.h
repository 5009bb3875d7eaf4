/* contact.h - frictionless normal contact of two elastic half-spaces (combined into one with E*).
 *
 * Unknowns: the pressure p (Pa, per cell) and the rigid approach delta (m). With the initial gap
 * h (plus an optional extra term such as a residual plastic displacement) and the influence
 * operator K (operator.h, Love kernel / E*):
 *
 *     g = h + h_extra + K p - delta                    (gap, m)
 *     p_lower <= p <= p_cap                             (p_lower: lubricant pressure, may vary)
 *     g >= 0 where p = p_lower,  g = 0 where p_lower < p < p_cap,  g <= 0 where p = p_cap
 *     A * sum(p) = W  (force control)   or   delta given (approach control)
 *
 * The lubricant pressure acts outside solid contact and deforms the surface too (theory.md §4.2):
 * the solvers work on the excess q = p - p_lower with h~ = h + h_extra + K p_lower.
 *
 * Methods (a row each in a table; all use the operator through mc_operator_apply and
 * mc_operator_apply_rows only, so they run on either backend, and cg and pk over the ranks of a
 * distributed operator, each on its rows: contact_internal.h):
 *   cg         - constrained conjugate gradients with an FFT-based preconditioner (the inverse
 *                of the continuum Love symbol on the contact's bounding box, restricted to the
 *                free cells; after Vollebregt, J. Comput. Phys. 257 (2014) 333-351) and a load
 *                projection; bounds by gradient projection with restart. With a pressure cap
 *                it runs nested: bound-constrained inner solves at fixed delta, delta from the
 *                load by a safeguarded secant (theory.md §4.5, "robust nested variant").
 *   pk         - plain Polonsky & Keer (1999) as in theory.md §4.5, with the lower bound of §4.2
 *                and the free-set cap variant of §4.5 (falls back to nested when the free set
 *                empties).
 *   active-set - the paper's algorithm (Mevissen et al. 2025, Fig. 3-1): dense influence matrix,
 *                GSL Cholesky solve of the free cells with the load equation eliminated by
 *                superposition (K + c 11' on periodic grids, where K alone is singular or
 *                indefinite; the load fixes the sum, c leaves the pressure unchanged), cells
 *                with p < p_lower leave, penetrating cells re-enter (theory.md §11);
 *                O(N^3): refused above MC_ACTIVE_SET_MAX_CELLS.
 *
 * Restriction (cg): when the contact found by the start (coarse solution or warm start) has a
 * bounding box of at most MC_BOX_FRACTION of the grid, the solve runs on that box (plus a margin)
 * with a box-sized operator; the full operator then checks the gap outside the box, and cells that
 * penetrate there widen the box and the solve resumes. The result is the full-grid solution (the
 * final residual is measured on the full grid); only the cost changes.
 *
 * Start: a warm start if given; else, for cg with opt.estar > 0 on a large grid, the solution of
 * the same problem on a 2:1 coarser grid (topography, bounds and extra term block-averaged, the
 * load kept), itself started the same way; else the uniform pressure.
 *
 * Stopping rule (scale-free): with the gap scale s_g = delta - min h~ (the rigid interference:
 * the approach of a Hertz contact, the indentation of a punch), floored at 1e-6 of the range of
 * h~ and at 1e-12 of its magnitude so that it never vanishes, and the load W,
 *     residual = max( max_free |g| / s_g,  max_{p=p_lower} (-g) / s_g,  max_{p=p_cap} g / s_g,
 *                     |A sum p - W| / W  (force control) )
 * and the solve stops when residual <= tolerance (below about 1e-14 it is round-off and cannot be
 * reached). Non-convergence after max_iterations returns MC_NOT_CONVERGED with the last iterate
 * and converged = 0 in the summary (not hidden).
 */
#ifndef MC_CONTACT_H
#define MC_CONTACT_H

#include "core/error.h"
#include "operator/operator.h"

typedef enum {
    MC_METHOD_CG,        /* preconditioned constrained conjugate gradients (default, fast) */
    MC_METHOD_PK,        /* plain Polonsky & Keer (1999) */
    MC_METHOD_ACTIVE_SET /* the paper's dense active-set reference (small grids only) */
} mc_contact_method;

#define MC_ACTIVE_SET_MAX_CELLS 4096 /* dense O(N^3) reference: 4096 cells = 2 x 128 MiB */

typedef struct {
    int solved;           /* 0: pressure was prescribed (pressure_file), no contact solve */
    double load;          /* total normal load A*sum(p), N */
    double solid_load;    /* A*sum(p - p_lub) over the solid contact cells, N */
    double p_max;         /* Pa */
    double area;          /* solid contact area (cells with p above the lower bound), m^2 */
    double contact_ratio; /* area / nominal area */
    double approach;      /* rigid approach delta, m */
    int iterations;
    double residual;      /* final value of the stopping measure (see contact.h) */
    int converged;
    const char *solver;   /* "cg", "pk", "active-set" or "prescribed" */
    mc_backend backend;   /* the operator's backend */
    int capped_cells;     /* cells at the pressure cap */
} mc_contact_summary;

typedef enum { MC_CONTROL_FORCE, MC_CONTROL_APPROACH } mc_control;

typedef struct {
    const double *h;       /* initial gap at zero approach, m (ny*nx); required */
    const double *h_extra; /* added to h (e.g. residual plastic displacement), m; NULL = none */
    const double *p_lower; /* per-cell lower bound, Pa; NULL = the uniform p_lub */
    double p_lub;          /* uniform lower bound (lubricant pressure), Pa, >= 0 */
    double p_cap;          /* upper bound, Pa; INFINITY = none */
    const double *p_upper; /* per-cell upper bound, Pa; NULL = the uniform p_cap */
    mc_control control;
    double load;           /* force control: total load A*sum(p), N */
    double approach;       /* approach control: delta, m */
    const double *p_start; /* warm start (ny*nx, Pa) or NULL; e.g. the previous load step */
} mc_contact_problem;

typedef struct {
    mc_contact_method method; /* MC_METHOD_CG | MC_METHOD_PK | MC_METHOD_ACTIVE_SET */
    double tolerance;         /* see the stopping rule above; e.g. 1e-8 */
    int max_iterations;
    /* Combined modulus E* (Pa) of the Love operator K. When > 0, method cg starts a solve
     * without a warm start from the solution on a grid coarsened 2:1 (recursively, while an axis
     * has >= MC_COARSEN_MIN cells): nested iteration, which spares the fine grid most of the
     * iterations that only shrink the contact set. 0 = start from the uniform pressure. */
    double estar; /* must be the E* of K's Love kernel: coarse and box levels plan their own */
    int no_box; /* 1: never restrict the solve to the contact's bounding box (for comparison) */
} mc_contact_options;

#define MC_COARSEN_MIN 96 /* an axis with fewer cells is not coarsened */
#define MC_BOX_FRACTION 0.25 /* restrict the solve to the contact's box below this area ratio */

typedef struct mc_contact_solver mc_contact_solver;

/* Plan a solver over operator K (not owned; must outlive the solver): allocates every workspace
 * once, so iterations never allocate. A solve allocates only to plan what depends on where the
 * contact is: the preconditioner's FFT for a new box size (cached) and, for the restricted solve,
 * a box-sized operator and solver (kept while the box size stays). Returns MC_OK, MC_ERR_INPUT
 * (bad options), MC_ERR_LIMIT (active-set above its size), MC_ERR_NOMEM, or MC_ERR_INTERNAL
 * (FFTW could not start its threads). */
int mc_contact_create(mc_operator *K, const mc_contact_options *opt, mc_contact_solver **out,
                      mc_error *err);

/* Solve. Outputs (ny*nx each, caller-owned): p (Pa), and optionally u (= K p, m) and gap (m);
 * u and gap may be NULL. sum receives the contact summary. Returns MC_OK, MC_NOT_CONVERGED (all
 * outputs still filled with the last iterate), MC_ERR_INPUT (bad problem), MC_ERR_NOMEM (a plan
 * of the preconditioner or of the box could not be made), MC_ERR_NUMERIC (non-finite values or a
 * breakdown) or MC_ERR_INTERNAL (FFTW threads). */
int mc_contact_solve(mc_contact_solver *s, const mc_contact_problem *prob, double *p, double *u,
                     double *gap, mc_contact_summary *sum, mc_error *err);

void mc_contact_destroy(mc_contact_solver **s);

/* Operator applications of the last solve on this grid, and on all coarser grids of the
 * coarse start (for benchmarks). */
long mc_contact_last_applies(const mc_contact_solver *s);
long mc_contact_last_coarse_applies(const mc_contact_solver *s);

/* Cells of the box the last solve ran on (0: the whole grid), and its applications there. */
long mc_contact_last_box_cells(const mc_contact_solver *s);
long mc_contact_last_box_applies(const mc_contact_solver *s);

const char *mc_contact_method_name(mc_contact_method m);

#endif
