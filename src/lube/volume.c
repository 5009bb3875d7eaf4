/* volume.c - lubricant volume equilibrium by a bracketed root over contact solves (volume.h). */
#include "lube/volume.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/grid.h"

typedef struct {
    mc_contact_solver *s;
    mc_operator *K;
    const mc_volume_problem *prob;
    size_t n;
    double dA, pnom;
    const double *w;     /* the lubricant pressure profile (volume.h), or NULL */
    double *plower;      /* p_lub w, the contact solves' lower bound (with a profile) */
    double *p, *u, *gap; /* the caller's outputs: always the state of the last evaluation */
    double *warm;        /* pressure of the last solve, the next one's start */
    int have_warm;
    double last_x[2], last_v[2]; /* the last two contact solves (p_lub, V), newest first */
    int nlast;
    mc_volume_result *res;
} eval_ctx;

const char *mc_lube_regime_name(mc_lube_regime r)
{
    switch (r) {
    case MC_REGIME_DRY: return "dry";
    case MC_REGIME_MIXED: return "mixed";
    case MC_REGIME_FULL_FILM: return "full_film";
    }
    return "?";
}

/* V = dA sum of the gap over the nominal area (the cells with w > 0; all without a profile). */
static double gap_volume(const double *gap, const double *w, size_t n, double dA)
{
    double v = 0;
    for (size_t i = 0; i < n; i++)
        if (!w || w[i] > 0)
            v += gap[i];
    return dA * v;
}

/* The onset state p_lub = p_nominal (the fluid carries F_N, no solid contact), lifted by `lift`
 * (m) beyond touching: p = p_nominal, gap = h~ - min h~ + lift, h~ = h + h_extra + K p. This is
 * the contact solver's own answer when the lubricant carries the load (contact.c), without
 * asking it to decide the sign of F_N - p_lub A_nom at round-off. Returns V. */
static double onset_state(eval_ctx *c, double lift)
{
    const size_t n = c->n;
    double wsum = 0;
    for (size_t i = 0; i < n; i++) {
        c->p[i] = c->w ? c->pnom * c->w[i] : c->pnom;
        wsum += c->w ? c->w[i] : 1.0;
    }
    mc_operator_apply(c->K, c->p, c->gap); /* K p, the lubricant's deformation */
    if (c->u)
        memcpy(c->u, c->gap, n * sizeof *c->u);
    double hmin = INFINITY;
    for (size_t i = 0; i < n; i++) {
        c->gap[i] += c->prob->h[i] + (c->prob->h_extra ? c->prob->h_extra[i] : 0.0);
        hmin = fmin(hmin, c->gap[i]);
    }
    for (size_t i = 0; i < n; i++)
        c->gap[i] += lift - hmin;
    mc_contact_summary *sum = &c->res->contact;
    memset(sum, 0, sizeof *sum);
    sum->solved = 1;
    sum->load = c->pnom * c->dA * wsum;
    double pmax = 0;
    for (size_t i = 0; i < n; i++)
        pmax = fmax(pmax, c->p[i]);
    sum->p_max = pmax;
    sum->approach = hmin - lift;
    sum->converged = 1;
    sum->solver = "full-film";
    sum->backend = mc_operator_backend(c->K);
    return gap_volume(c->gap, c->w, n, c->dA);
}

/* One contact solve at lubricant pressure plub; *v = V(plub). p_lub >= p_nominal is the onset
 * state (no solve). */
static int eval_volume(eval_ctx *c, double plub, double *v, mc_error *err)
{
    if (plub >= c->pnom) {
        *v = onset_state(c, 0.0);
        return MC_OK;
    }
    const mc_volume_problem *pr = c->prob;
    if (c->w)
        for (size_t i = 0; i < c->n; i++)
            c->plower[i] = plub * c->w[i];
    mc_contact_problem cp = {.h = pr->h,
                             .h_extra = pr->h_extra,
                             .p_lub = plub,
                             .p_lower = c->plower,
                             .p_cap = INFINITY,
                             .control = MC_CONTROL_FORCE,
                             .load = pr->load,
                             .p_start = c->have_warm ? c->warm : pr->p_start};
    int rc = mc_contact_solve(c->s, &cp, c->p, c->u, c->gap, &c->res->contact, err);
    c->res->solves++;
    c->res->iterations += c->res->contact.iterations;
    if (rc == MC_NOT_CONVERGED) { /* the outputs hold this state: say which it is */
        c->res->p_lub = plub;
        c->res->volume = gap_volume(c->gap, c->w, c->n, c->dA);
        c->res->rel_error = c->res->v_target > 0
                                ? fabs(c->res->volume - c->res->v_target) / c->res->v_target
                                : 0.0;
        c->res->converged = 0;
        return mc_fail(err, MC_NOT_CONVERGED,
                       "volume equilibrium: the contact solve at p_lub = %.6g Pa did not converge "
                       "(%d iterations, residual %.3g); the pocket volume is not reliable",
                       plub, c->res->contact.iterations, c->res->contact.residual);
    }
    if (rc != MC_OK)
        return mc_error_prefix(err, "volume equilibrium at p_lub = %.6g Pa: ", plub);
    memcpy(c->warm, c->p, c->n * sizeof *c->warm);
    c->have_warm = 1;
    *v = gap_volume(c->gap, c->w, c->n, c->dA);
    c->last_x[1] = c->last_x[0];
    c->last_v[1] = c->last_v[0];
    c->last_x[0] = plub;
    c->last_v[0] = *v;
    c->nlast++;
    return MC_OK;
}

static int check_problem(const mc_volume_problem *pr, double *p, double *gap, mc_error *err)
{
    if (!pr || !pr->h || !p || !gap)
        return mc_fail(err, MC_ERR_INPUT, "volume equilibrium: topography and outputs are required");
    if (!(pr->load > 0 && isfinite(pr->load)))
        return mc_fail(err, MC_ERR_INPUT, "volume equilibrium: load %g N must be finite and > 0",
                       pr->load);
    if (!(pr->h_target >= 0 && isfinite(pr->h_target)))
        return mc_fail(err, MC_ERR_INPUT,
                       "volume equilibrium: film thickness %g m must be finite and >= 0",
                       pr->h_target);
    if (pr->tolerance > 0.1 || isnan(pr->tolerance))
        return mc_fail(err, MC_ERR_INPUT,
                       "volume equilibrium: tolerance %g must be in (0, 0.1] (or <= 0 for the "
                       "default %g)",
                       pr->tolerance, MC_VOLUME_TOL_DEFAULT);
    return MC_OK;
}

/* Brent's zeroin on f(x) = V(x) - V*, bracket [a, b] with f(a) < 0 < f(b) (a < b).
 * Stops as soon as a freshly evaluated point meets |f| <= tol V* (so that the outputs, which hold
 * the last evaluation, belong to the returned p_lub). */
static int brent(eval_ctx *c, double a, double fa, double b, double fb, double vstar, double tol,
                 int cap, mc_error *err)
{
    double cc = a, fc = fa, d = b - a, e = d;
    double x_last = b, f_last = fb;
    for (;;) {
        if ((fb > 0) == (fc > 0)) { /* keep the root between b and cc */
            cc = a;
            fc = fa;
            d = e = b - a;
        }
        if (fabs(fc) < fabs(fb)) { /* b is the best estimate */
            a = b;
            b = cc;
            cc = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        /* resolution in p_lub: relative to b, floored at round-off of p_nominal (b may be 0) */
        double tol1 = 2.0 * DBL_EPSILON * (fabs(b) + c->pnom), m = 0.5 * (cc - b);
        if (fabs(m) <= tol1 || fb == 0)
            break; /* the bracket collapsed onto round-off */
        if (c->res->solves >= cap)
            break;
        if (fabs(e) >= tol1 && fabs(fa) > fabs(fb)) {
            double s = fb / fa, pp, q;
            if (a == cc) { /* secant */
                pp = 2.0 * m * s;
                q = 1.0 - s;
            } else { /* inverse quadratic interpolation through a, b, cc */
                double qa = fa / fc, r = fb / fc;
                pp = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if (pp > 0)
                q = -q;
            else
                pp = -pp;
            /* accept the interpolation only if it stays well inside and shrinks fast enough */
            if (2.0 * pp < fmin(3.0 * m * q - fabs(tol1 * q), fabs(e * q))) {
                e = d;
                d = pp / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += fabs(d) > tol1 ? d : (m > 0 ? tol1 : -tol1);
        double v;
        int rc = eval_volume(c, b, &v, err);
        if (rc != MC_OK)
            return rc;
        fb = v - vstar;
        x_last = b;
        f_last = fb;
        if (fabs(fb) <= tol * vstar) {
            c->res->p_lub = b;
            c->res->volume = v;
            c->res->rel_error = fabs(fb) / vstar;
            c->res->converged = 1;
            return MC_OK;
        }
    }
    c->res->p_lub = x_last;
    c->res->volume = f_last + vstar;
    c->res->rel_error = fabs(f_last) / vstar;
    c->res->converged = 0;
    return mc_fail(err, MC_NOT_CONVERGED,
                   "volume equilibrium: no p_lub with |V - V*| <= %.3g V* after %d contact solves "
                   "(last p_lub = %.9g Pa, |V - V*| / V* = %.3g)%s",
                   tol, c->res->solves, x_last, c->res->rel_error,
                   c->res->solves >= cap ? "" : "; the bracket shrank to round-off first: the "
                                                "contact tolerance is too coarse for this one");
}

/* The slope dV/dp_lub of the last two contact solves, for the next call's guess (volume.h); 0
 * when there were fewer than two or they coincide. */
static void record_slope(eval_ctx *c)
{
    c->res->slope = 0.0;
    if (c->nlast >= 2 && c->last_x[0] != c->last_x[1]) {
        const double sl = (c->last_v[0] - c->last_v[1]) / (c->last_x[0] - c->last_x[1]);
        c->res->slope = sl > 0 && isfinite(sl) ? sl : 0.0;
    }
}

/* The root from a guess g with slope s (volume.h): V(g), then up to SECANT_STEPS secant steps
 * -(V - V*) / s, s the guess's slope and then that of the two latest points (the elastic-plastic
 * loop's consecutive equilibria are close and V nearly linear there: measured on the running-in
 * step at 256 x 128, the first step left 1e-8..3e-2 of the guess's error, so most equilibria took
 * 2 solves instead of the 3 of an overshooting first step); when they fall short, steps of 1.25
 * times the correction (a little beyond the root, to bracket it), doubled while
 * V - V* keeps its sign, all clamped to [0, p_nominal]; a bracket goes to Brent. Reaching 0 with V(0) >= V* is the
 * dry regime (as the cold start's first test). *done 0 leaves the cold start to the caller (the
 * outputs are then overwritten by it). */
#define SECANT_STEPS 2

static int from_guess(eval_ctx *c, double vstar, double tol, int cap, int *done, mc_error *err)
{
    const mc_volume_problem *pr = c->prob;
    mc_volume_result *res = c->res;
    double x0 = pr->p_lub_guess, v;
    int rc = eval_volume(c, x0, &v, err);
    if (rc != MC_OK)
        return rc;
    double f0 = v - vstar;
    if (fabs(f0) <= tol * vstar) {
        res->regime = MC_REGIME_MIXED;
        res->p_lub = x0;
        res->volume = v;
        res->rel_error = fabs(f0) / vstar;
        res->converged = 1;
        *done = 1;
        return MC_OK;
    }
    /* the first steps: secant steps (the guess's slope, then the two latest points'), which land
     * within the tolerance or near the root; then steps of 1.25 times the correction (a little
     * beyond the root, to bracket it), doubled */
    double step = -f0 / pr->slope_guess, slope = pr->slope_guess;
    int secants = SECANT_STEPS;
    while (res->solves < cap) {
        double x1 = fmin(fmax(x0 + step, 0.0), c->pnom), f1;
        if (x1 == x0)
            return MC_OK; /* no room: the cold start decides */
        if (x1 >= c->pnom) {
            f1 = res->v_onset - vstar; /* > 0: full film was ruled out before */
        } else {
            if ((rc = eval_volume(c, x1, &v, err)) != MC_OK)
                return rc;
            f1 = v - vstar;
            if (x1 == 0.0) {
                res->v_dry = v;
                if (vstar <= v) { /* dry, as the cold start's first test */
                    res->regime = MC_REGIME_DRY;
                    res->p_lub = 0.0;
                    res->volume = v;
                    res->converged = 1;
                    *done = 1;
                    return MC_OK;
                }
            } else if (fabs(f1) <= tol * vstar) {
                res->regime = MC_REGIME_MIXED;
                res->p_lub = x1;
                res->volume = v;
                res->rel_error = fabs(f1) / vstar;
                res->converged = 1;
                *done = 1;
                return MC_OK;
            }
        }
        if ((f1 > 0) != (f0 > 0)) {
            res->regime = MC_REGIME_MIXED;
            *done = 1;
            return x0 < x1 ? brent(c, x0, f0, x1, f1, vstar, tol, cap, err)
                           : brent(c, x1, f1, x0, f0, vstar, tol, cap, err);
        }
        const double fresh = (f1 - f0) / (x1 - x0);
        if (fresh > 0 && isfinite(fresh))
            slope = fresh;
        if (--secants > 0) { /* short of the root: a secant step from the two latest points */
            step = -f1 / slope;
        } else if (secants == 0) { /* from here bracket the root */
            step = -1.25 * f1 / slope;
        } else {
            step *= 2.0;
        }
        x0 = x1;
        f0 = f1;
    }
    return MC_OK; /* the cap: the cold start reports it */
}

int mc_volume_equilibrium(mc_contact_solver *s, mc_operator *K, const mc_volume_problem *prob,
                          double *p, double *u, double *gap, mc_volume_result *res,
                          mc_error *err)
{
    memset(res, 0, sizeof *res);
    if (!s || !K)
        return mc_fail(err, MC_ERR_INPUT, "volume equilibrium: a planned solver and operator are required");
    int rc = check_problem(prob, p, gap, err);
    if (rc != MC_OK)
        return rc;
    const mc_grid *g = mc_operator_grid(K);
    eval_ctx c = {.s = s, .K = K, .prob = prob, .n = mc_grid_cells(g), .dA = mc_grid_cell_area(g),
                  .p = p, .u = u, .gap = gap, .res = res, .w = prob->weight};
    double wsum = (double)c.n, ncells = (double)c.n;
    if (c.w) {
        wsum = ncells = 0;
        for (size_t i = 0; i < c.n; i++) {
            if (!(c.w[i] >= 0 && isfinite(c.w[i])))
                return mc_fail(err, MC_ERR_INPUT,
                               "volume equilibrium: lubricant pressure profile %g at cell %zu "
                               "(must be finite and >= 0)",
                               c.w[i], i);
            wsum += c.w[i];
            ncells += c.w[i] > 0;
        }
        if (!(wsum > 0))
            return mc_fail(err, MC_ERR_INPUT,
                           "volume equilibrium: the lubricant pressure profile is zero everywhere "
                           "(no nominal area)");
    }
    const double a_nom = c.dA * ncells;
    const double tol = prob->tolerance > 0 ? prob->tolerance : MC_VOLUME_TOL_DEFAULT;
    const int cap = prob->max_solves > 0 ? prob->max_solves : MC_VOLUME_MAX_SOLVES;
    c.pnom = prob->load / (c.dA * wsum);
    res->p_nominal = c.pnom;
    res->a_nom = a_nom;
    res->v_target = prob->h_target * a_nom;
    const double vstar = res->v_target;

    /* full film first: it needs no contact solve */
    res->v_onset = onset_state(&c, 0.0);
    if (vstar >= res->v_onset) {
        res->regime = MC_REGIME_FULL_FILM;
        res->p_lub = c.pnom;
        res->separation = (vstar - res->v_onset) / a_nom;
        res->volume = onset_state(&c, res->separation);
        res->converged = 1;
        return MC_OK;
    }

    if (!(c.warm = mc_malloc(c.n * sizeof *c.warm)) ||
        (c.w && !(c.plower = mc_malloc(c.n * sizeof *c.plower)))) {
        mc_free(c.warm);
        return mc_fail(err, MC_ERR_NOMEM, "volume equilibrium: out of memory for %zu cells", c.n);
    }
    if (prob->one_solve) { /* the guess alone (volume.h) */
        double v;
        rc = prob->p_lub_guess > 0 && prob->p_lub_guess < c.pnom
                 ? eval_volume(&c, prob->p_lub_guess, &v, err)
                 : mc_fail(err, MC_ERR_INPUT,
                           "volume equilibrium: one solve at p_lub = %g Pa, outside (0, %g)",
                           prob->p_lub_guess, c.pnom);
        if (rc == MC_OK) {
            res->regime = MC_REGIME_MIXED;
            res->p_lub = prob->p_lub_guess;
            res->volume = v;
            res->rel_error = fabs(v - vstar) / vstar;
            res->converged = res->rel_error <= tol;
        }
        mc_free(c.warm);
        mc_free(c.plower);
        return rc;
    }
    if (prob->p_lub_guess > 0 && prob->p_lub_guess < c.pnom && prob->slope_guess > 0 &&
        isfinite(prob->slope_guess)) {
        int done = 0;
        rc = from_guess(&c, vstar, tol, cap, &done, err);
        if (rc != MC_OK || done) {
            record_slope(&c);
            mc_free(c.warm);
            mc_free(c.plower);
            return rc;
        }
    }
    double v0;
    rc = eval_volume(&c, 0.0, &v0, err);
    if (rc == MC_OK) {
        res->v_dry = v0;
        if (vstar <= v0 || vstar == 0) { /* (a fully closed gap sums to +-round-off) */
            res->regime = MC_REGIME_DRY;
            res->p_lub = 0.0;
            res->volume = v0;
            res->converged = 1;
        } else {
            res->regime = MC_REGIME_MIXED;
            rc = brent(&c, 0.0, v0 - vstar, c.pnom, res->v_onset - vstar, vstar, tol, cap, err);
        }
    }
    record_slope(&c);
    mc_free(c.warm);
    mc_free(c.plower);
    return rc;
}
