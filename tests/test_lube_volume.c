/* test_lube_volume.c - the lubricant volume equilibrium (lube/volume.h) checked against
 * independent contact solves and the checks of theory.md §11, and the friction
 * split (lube/friction.h) against hand values. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "lube/friction.h"
#include "lube/volume.h"
#include "test_util.h"

/* A rough flat of Sq = 0.3 um under p_nominal = 1 GPa (theory.md §11.3 checks), two steels. */
static const double E_STAR = 115.4e9, SQ = 0.3e-6, P_NOM = 1e9, DX = 0.8e-6;

/* Contact solves stop at residual CT (gap scale, contact.h): the gap of each cell is then exact
 * to CT times the gap scale, the load to CT relative, far below every tolerance used below. */
#define CT 1e-11
/* KKT check tier: the stopping rule guarantees residual <= tolerance (plus round-off). */
#define KKT_SLACK 10.0
/* The root's tolerance on V (the default of volume.h). */
#define ROOT_TOL MC_VOLUME_TOL_DEFAULT
/* cg against the paper's active set at the same p_lub: both solve the same LCP; stopped at 1e-13
 * they agree to about cond(K_CC) 1e-13 (test_contact.c uses the same tier). */
#define AS_TOL 1e-13
#define TOL_METHODS 1e-8

typedef struct {
    mc_grid g;
    size_t n;
    double *h;   /* initial gap (= - heights), m */
    double load; /* F_N = P_NOM A_nom */
    double a_nom;
    mc_operator *K;
    mc_contact_solver *s;
} patch;

/* Random heights smoothed by a periodic binomial filter (correlation over a few cells), mean
 * removed, scaled to Sq. The same field (periodic by construction) serves free grids too. */
static void make_patch(patch *pt, int n, int periodic, mc_contact_method m)
{
    mc_grid g = {n, n, DX, DX, periodic, periodic};
    pt->g = g;
    pt->n = mc_grid_cells(&g);
    pt->h = mc_zeros(pt->n);
    ck_assert_ptr_nonnull(pt->h);
    test_smooth_rough_gap(pt->h, n, SQ, 20251124ULL);
    pt->a_nom = (double)pt->n * DX * DX;
    pt->load = P_NOM * pt->a_nom;
    mc_error err = {0};
    pt->K = NULL;
    pt->s = NULL;
    ck_assert_msg(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &pt->K, &err) == MC_OK, "%s",
                  err.msg);
    mc_contact_options opt = {m, m == MC_METHOD_ACTIVE_SET ? AS_TOL : CT, 20000, 0, 0};
    ck_assert_msg(mc_contact_create(pt->K, &opt, &pt->s, &err) == MC_OK, "%s", err.msg);
}

static void free_patch(patch *pt)
{
    mc_contact_destroy(&pt->s);
    mc_operator_destroy(&pt->K);
    mc_free(pt->h);
}

static double sum_gap_volume(const double *gap, size_t n)
{
    double v = 0;
    for (size_t i = 0; i < n; i++)
        v += gap[i];
    return v * DX * DX;
}

/* Gap scale of the stopping rule (contact.h) bounded from above: the height range. */
static double gap_scale(const patch *pt)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < pt->n; i++) {
        lo = fmin(lo, pt->h[i]);
        hi = test_worst(hi, pt->h[i]);
    }
    return hi - lo;
}

/* Independent contact solve at p_lub (cold start): V from its gap, into p/gap. */
static double direct_volume(patch *pt, double plub, double *p, double *gap)
{
    mc_contact_problem cp = {.h = pt->h, .p_lub = plub, .p_cap = INFINITY,
                             .control = MC_CONTROL_FORCE, .load = pt->load};
    mc_contact_summary sum;
    mc_error err = {0};
    ck_assert_msg(mc_contact_solve(pt->s, &cp, p, NULL, gap, &sum, &err) == MC_OK, "%s", err.msg);
    return sum_gap_volume(gap, pt->n);
}

/* Load split, complementarity and bounds of a returned state, computed from the fields alone:
 * F_solid + p_lub A_free = F_N (theory.md §11.3) to the solver's load tolerance. */
static void check_state(const patch *pt, const double *p, const double *gap, double plub)
{
    double fs = 0, afree = 0, sg = gap_scale(pt);
    for (size_t i = 0; i < pt->n; i++) {
        ck_assert_msg(p[i] >= plub, "cell %zu: p %g below p_lub %g", i, p[i], plub);
        if (p[i] > plub) {
            fs += p[i] * DX * DX;
            ck_assert_msg(fabs(gap[i]) <= KKT_SLACK * CT * sg, "open contact cell %zu: %g", i,
                          gap[i]);
        } else {
            afree += DX * DX;
            ck_assert_msg(gap[i] >= -KKT_SLACK * CT * sg, "penetration at cell %zu: %g", i, gap[i]);
        }
    }
    double split = fs + plub * afree;
    ck_assert_msg(fabs(split - pt->load) <= KKT_SLACK * CT * pt->load,
                  "F_solid + p_lub A_free = %.15g vs F_N %.15g", split, pt->load);
}

/* V(p_lub) strictly increasing over a sweep up to 0.99 p_nominal (theory.md §11.1), towards the
 * onset volume, which on a doubly periodic grid is A_nom (max z - mean z) (K 1 = 0). */
START_TEST(volume_monotone)
{
    patch pt;
    make_patch(&pt, 32, 1, MC_METHOD_CG);
    double *p = mc_zeros(pt.n), *gap = mc_zeros(pt.n);
    const double frac[] = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99};
    const int nf = (int)(sizeof frac / sizeof frac[0]);
    /* the volume error of a solve: CT times the gap scale per cell */
    const double noise = KKT_SLACK * CT * gap_scale(&pt) * pt.a_nom;
    double vprev = -INFINITY, hmin = INFINITY;
    for (size_t i = 0; i < pt.n; i++)
        hmin = fmin(hmin, pt.h[i]);
    const double v_onset = -hmin * pt.a_nom; /* mean h = 0 */
    for (int k = 0; k < nf; k++) {
        double v = direct_volume(&pt, frac[k] * P_NOM, p, gap);
        check_state(&pt, p, gap, frac[k] * P_NOM);
        ck_assert_msg(v > vprev + noise, "V(%.2f p_nom) = %.6e not above %.6e", frac[k], v, vprev);
        ck_assert_msg(v < v_onset, "V(%.2f p_nom) above the onset volume", frac[k]);
        vprev = v;
    }
    /* the equilibrium's own onset volume, by another route (one operator application) */
    mc_volume_problem vp = {.h = pt.h, .load = pt.load, .h_target = 2 * SQ * 10};
    mc_volume_result res;
    mc_error err = {0};
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err), MC_OK);
    ck_assert(fabs(res.v_onset - v_onset) <= TOL_ROUNDOFF * v_onset);
    mc_free(p);
    mc_free(gap);
    free_patch(&pt);
}
END_TEST

/* The mixed root on a periodic patch and on a free one (where K 1 is not uniform): the returned
 * state meets |V - V*| <= tol V*, the load split, complementarity, and the paper's active-set
 * solver at the returned p_lub gives the same pressures. */
START_TEST(mixed_root)
{
    const int periodic = _i == 0;
    patch pt, as;
    make_patch(&pt, 32, periodic, MC_METHOD_CG);
    make_patch(&as, 32, periodic, MC_METHOD_ACTIVE_SET);
    double *p = mc_zeros(pt.n), *gap = mc_zeros(pt.n), *u = mc_zeros(pt.n);
    double *p2 = mc_zeros(pt.n), *gap2 = mc_zeros(pt.n);
    const double targets[] = {0.2, 0.5, 0.999}; /* between V(0) and the onset volume */
    for (int t = 0; t < 3; t++) {
        mc_volume_problem vp = {.h = pt.h, .load = pt.load, .h_target = 0};
        mc_volume_result res;
        mc_error err = {0};
        /* the limits, with a target far above: full film, v_onset and no solve */
        vp.h_target = 1.0;
        ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, u, gap, &res, &err), MC_OK);
        double v0 = direct_volume(&pt, 0.0, p2, gap2);
        double vstar = v0 + targets[t] * (res.v_onset - v0);
        vp.h_target = vstar / pt.a_nom;
        ck_assert_msg(mc_volume_equilibrium(pt.s, pt.K, &vp, p, u, gap, &res, &err) == MC_OK,
                      "%s", err.msg);
        ck_assert_int_eq(res.regime, MC_REGIME_MIXED);
        ck_assert(res.converged && res.p_lub > 0 && res.p_lub < P_NOM);
        ck_assert(fabs(res.v_dry - v0) <= KKT_SLACK * CT * gap_scale(&pt) * pt.a_nom);
        double v = sum_gap_volume(gap, pt.n), vs = vp.h_target * pt.a_nom;
        ck_assert_msg(fabs(v - vs) <= ROOT_TOL * vs, "|V - V*|/V* = %.3e", fabs(v - vs) / vs);
        ck_assert(fabs(res.volume - v) <= TOL_ROUNDOFF * v);
        check_state(&pt, p, gap, res.p_lub);
        /* u is K p of the returned pressure */
        mc_operator_apply(pt.K, p, p2);
        ck_assert(test_rel_maxdiff(u, p2, pt.n) <= TOL_ROUNDOFF);
        /* pocket height = h_EHD / (1 - psi_A) (theory.md §11.3) */
        mc_lube_split sp;
        ck_assert_int_eq(mc_lube_split_of(p, gap, pt.n, DX * DX, res.p_lub, pt.load, &sp, &err),
                         MC_OK);
        ck_assert(fabs(sp.pocket_height - vp.h_target / (1 - sp.psi_area)) <=
                  2 * ROOT_TOL * sp.pocket_height);
        ck_assert(sp.psi_load > sp.psi_area && sp.psi_load < 1 && sp.psi_area > 0);
        /* the paper's active set at the root, cold */
        mc_contact_problem cp = {.h = pt.h, .p_lub = res.p_lub, .p_cap = INFINITY,
                                 .control = MC_CONTROL_FORCE, .load = pt.load};
        mc_contact_summary sum;
        ck_assert_msg(mc_contact_solve(as.s, &cp, p2, NULL, gap2, &sum, &err) == MC_OK, "%s",
                      err.msg);
        double pmax = 0, d = 0;
        for (size_t i = 0; i < pt.n; i++) {
            pmax = test_worst(pmax, p2[i]);
            d = test_worst(d, fabs(p[i] - p2[i]));
        }
        ck_assert_msg(d <= TOL_METHODS * pmax, "cg vs active set at the root: %.3e of p_max",
                      d / pmax);
        double v2 = sum_gap_volume(gap2, pt.n);
        ck_assert(fabs(v2 - vs) <= ROOT_TOL * vs);
    }
    mc_free(p);
    mc_free(gap);
    mc_free(u);
    mc_free(p2);
    mc_free(gap2);
    free_patch(&pt);
    free_patch(&as);
}
END_TEST

/* Both limits: dry (p_lub = 0, one solve) and full film (p_lub = p_nominal, no solve, uniform
 * pressure, the gap lifted so that V = V*), on a periodic and on a free patch. */
START_TEST(limits)
{
    const int periodic = _i == 0;
    patch pt;
    make_patch(&pt, 32, periodic, MC_METHOD_CG);
    double *p = mc_zeros(pt.n), *gap = mc_zeros(pt.n), *p2 = mc_zeros(pt.n),
           *gap2 = mc_zeros(pt.n);
    double v0 = direct_volume(&pt, 0.0, p2, gap2);
    mc_volume_result res;
    mc_error err = {0};
    mc_lube_split sp;
    /* dry: half of V(0), and a zero film */
    for (int k = 0; k < 2; k++) {
        mc_volume_problem vp = {.h = pt.h, .load = pt.load, .h_target = k ? 0.0 : 0.5 * v0 / pt.a_nom};
        ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err), MC_OK);
        ck_assert_int_eq(res.regime, MC_REGIME_DRY);
        ck_assert_str_eq(mc_lube_regime_name(res.regime), "dry");
        ck_assert(res.p_lub == 0 && res.solves == 1 && res.converged);
        ck_assert(test_rel_maxdiff(p, p2, pt.n) <= TOL_METHODS);
        check_state(&pt, p, gap, 0.0);
        ck_assert_int_eq(mc_lube_split_of(p, gap, pt.n, DX * DX, 0.0, pt.load, &sp, &err), MC_OK);
        ck_assert(fabs(sp.psi_load - 1) <= KKT_SLACK * CT);
    }
    /* either side of V(0), closer than the root tolerance allows to confuse: dry, then mixed
     * with a small p_lub */
    const double side[] = {1 - 1e-4, 1 + 1e-4};
    for (int k = 0; k < 2; k++) {
        mc_volume_problem vp = {.h = pt.h, .load = pt.load, .h_target = side[k] * v0 / pt.a_nom};
        ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err), MC_OK);
        ck_assert_int_eq(res.regime, (k ? MC_REGIME_MIXED : MC_REGIME_DRY));
        ck_assert(k ? res.p_lub > 0 && res.p_lub < 0.01 * P_NOM : res.p_lub == 0);
    }
    /* full film: above the onset volume (A_nom (max z - mean z) on the periodic patch, where
     * K 1 = 0; a little more on the free one, whose centre deflects more than its edges) */
    double hmin = INFINITY;
    for (size_t i = 0; i < pt.n; i++)
        hmin = fmin(hmin, pt.h[i]);
    const double lift = 0.1e-6;
    mc_volume_problem vp = {.h = pt.h, .load = pt.load, .h_target = -hmin + lift};
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err), MC_OK);
    if (periodic)
        ck_assert(fabs(res.v_onset + hmin * pt.a_nom) <= TOL_ROUNDOFF * res.v_onset);
    vp.h_target = res.v_onset / pt.a_nom + lift;
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err), MC_OK);
    ck_assert_int_eq(res.regime, MC_REGIME_FULL_FILM);
    ck_assert_str_eq(mc_lube_regime_name(res.regime), "full_film");
    ck_assert(fabs(res.p_lub - P_NOM) <= 4 * DBL_EPSILON * P_NOM); /* F_N / A_nom */
    ck_assert(res.solves == 0 && res.converged && res.contact.area == 0);
    ck_assert(fabs(res.separation - lift) <= TOL_ROUNDOFF * SQ);
    double gmin = INFINITY;
    for (size_t i = 0; i < pt.n; i++) {
        ck_assert(p[i] == res.p_lub);
        gmin = fmin(gmin, gap[i]);
    }
    ck_assert(fabs(gmin - lift) <= TOL_ROUNDOFF * SQ);
    ck_assert(fabs(sum_gap_volume(gap, pt.n) - res.v_target) <= TOL_ROUNDOFF * res.v_target);
    ck_assert_int_eq(mc_lube_split_of(p, gap, pt.n, DX * DX, res.p_lub, pt.load, &sp, &err), MC_OK);
    ck_assert(sp.psi_load == 0 && sp.psi_area == 0);
    ck_assert(fabs(sp.pocket_height - vp.h_target) <= TOL_ROUNDOFF * vp.h_target);
    /* the contact solver's own full-film answer at p_lub just above p_nominal is the same gap
     * (it includes the lubricant's deformation K p_lub, not uniform on the free patch) */
    mc_contact_problem cp = {.h = pt.h, .p_lub = P_NOM * (1 + 1e-12), .p_cap = INFINITY,
                             .control = MC_CONTROL_FORCE, .load = pt.load};
    mc_contact_summary sum;
    ck_assert_int_eq(mc_contact_solve(pt.s, &cp, p2, NULL, gap2, &sum, &err), MC_OK);
    for (size_t i = 0; i < pt.n; i++)
        ck_assert_msg(fabs(gap2[i] + lift - gap[i]) <= TOL_ROUNDOFF * SQ, "cell %zu: %g vs %g", i,
                      gap2[i] + lift, gap[i]);
    /* the same root with h split into h - x and an extra term x (a residual displacement) */
    double *hx = mc_zeros(pt.n), *x = mc_zeros(pt.n);
    test_random_field(x, pt.n, 99);
    for (size_t i = 0; i < pt.n; i++) {
        x[i] *= 0.1 * SQ;
        hx[i] = pt.h[i] - x[i];
    }
    vp.h_target = 0.5 * (v0 + res.v_onset) / pt.a_nom;
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err), MC_OK);
    mc_volume_problem vx = vp;
    vx.h = hx;
    vx.h_extra = x;
    mc_volume_result rx;
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vx, p2, NULL, gap2, &rx, &err), MC_OK);
    /* both roots meet |V - V*| <= ROOT_TOL V*; with dV/dp_lub of order V / p_nominal (the sweep)
     * that fixes p_lub to a few ROOT_TOL relative: 100 ROOT_TOL leaves room */
    ck_assert(rx.regime == MC_REGIME_MIXED &&
              fabs(rx.p_lub - res.p_lub) <= 100 * ROOT_TOL * res.p_lub);
    ck_assert(fabs(rx.volume - vx.h_target * pt.a_nom) <= ROOT_TOL * rx.volume);
    /* h_extra enters the onset (full-film) state too */
    ck_assert(fabs(rx.v_onset - res.v_onset) <= TOL_ROUNDOFF * res.v_onset);
    mc_free(hx);
    mc_free(x);
    mc_free(p);
    mc_free(gap);
    mc_free(p2);
    mc_free(gap2);
    free_patch(&pt);
}
END_TEST

/* A cap on solves below what the root needs is reported, with a state that belongs to the
 * returned p_lub; bad inputs are refused. */
START_TEST(not_converged_and_bad_input)
{
    patch pt;
    make_patch(&pt, 32, 1, MC_METHOD_CG);
    double *p = mc_zeros(pt.n), *gap = mc_zeros(pt.n);
    mc_volume_result res;
    mc_error err = {0};
    double v0 = direct_volume(&pt, 0.0, p, gap);
    mc_volume_problem vp = {.h = pt.h, .load = pt.load, .h_target = 1.5 * v0 / pt.a_nom,
                            .max_solves = 2, .tolerance = 1e-12};
    ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err),
                     MC_NOT_CONVERGED);
    ck_assert(!res.converged && res.solves == 2 && res.regime == MC_REGIME_MIXED);
    ck_assert_msg(strstr(err.msg, "2 contact solves"), "%s", err.msg);
    check_state(&pt, p, gap, res.p_lub);
    ck_assert(fabs(sum_gap_volume(gap, pt.n) - res.volume) <= TOL_ROUNDOFF * res.volume);
    ck_assert(res.rel_error > 1e-12);
    /* a contact solve that stops short is reported, not hidden */
    mc_contact_options opt = {MC_METHOD_CG, CT, 2, 0, 0};
    mc_contact_solver *s2 = NULL;
    ck_assert_int_eq(mc_contact_create(pt.K, &opt, &s2, &err), MC_OK);
    vp.max_solves = 0;
    vp.tolerance = 0;
    ck_assert_int_eq(mc_volume_equilibrium(s2, pt.K, &vp, p, NULL, gap, &res, &err),
                     MC_NOT_CONVERGED);
    ck_assert(!res.converged && res.solves == 1 && res.p_lub == 0 && !res.contact.converged);
    ck_assert_msg(strstr(err.msg, "did not converge"), "%s", err.msg);
    mc_contact_destroy(&s2);
    /* an allocation failure anywhere is MC_ERR_NOMEM, nothing leaks (ASan) */
    for (long k = 1; k <= 3; k++) {
        mc_alloc_fail_at(k);
        int rc = mc_volume_equilibrium(pt.s, pt.K, &vp, p, NULL, gap, &res, &err);
        /* the first is the warm-start buffer; later ones may fall in the solver's lazily made
         * plans or past the last allocation */
        ck_assert_msg(k == 1 ? rc == MC_ERR_NOMEM : (rc == MC_OK || rc == MC_ERR_NOMEM), "rc %d: %s",
                      rc, err.msg);
        mc_alloc_fail_at(0);
    }
    const mc_volume_problem bad[] = {
        {.h = NULL, .load = pt.load, .h_target = 1e-7},
        {.h = pt.h, .load = 0, .h_target = 1e-7},
        {.h = pt.h, .load = NAN, .h_target = 1e-7},
        {.h = pt.h, .load = pt.load, .h_target = -1e-7},
        {.h = pt.h, .load = pt.load, .h_target = 1e-7, .tolerance = 0.5},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        ck_assert_int_eq(mc_volume_equilibrium(pt.s, pt.K, &bad[k], p, NULL, gap, &res, &err),
                         MC_ERR_INPUT);
    mc_free(p);
    mc_free(gap);
    free_patch(&pt);
}
END_TEST

/* Friction split on a hand-made 2 x 2 field: p = {3, 1, 1, 5} Pa, p_lub = 1 Pa, dA = 2 m^2,
 * gap = {0, 0.5, 1.5, 0} m, F_N = 20 N: C = {0, 3}, A_C = 4, A_nom = 8, F_solid = 16,
 * F_solid_excess = 12, F_fluid = 4, V = 4, psi_load = 0.8, psi_area = 0.5, h_pocket = 1. */
START_TEST(friction_hand_values)
{
    const double p[] = {3, 1, 1, 5}, gap[] = {0, 0.5, 1.5, 0};
    mc_lube_split s;
    mc_error err = {0};
    ck_assert_int_eq(mc_lube_split_of(p, gap, 4, 2.0, 1.0, 20.0, &s, &err), MC_OK);
    ck_assert(s.a_nom == 8 && s.a_contact == 4 && s.f_solid == 16 && s.f_solid_excess == 12);
    ck_assert(s.f_fluid == 4 && s.volume == 4 && s.pocket_height == 1);
    ck_assert(fabs(s.psi_load - 0.8) <= TOL_TIGHT && s.psi_area == 0.5);
    ck_assert(fabs(s.psi_load_excess - 0.6) <= TOL_TIGHT);
    ck_assert(mc_lube_split_psi(&s, MC_PSI_LOAD) == s.psi_load);
    ck_assert(mc_lube_split_psi(&s, MC_PSI_AREA) == s.psi_area);
    double mu, h;
    /* 0.8 * 0.12 + 0.2 * 0.02 = 0.1; 0.5 * 0.12 + 0.5 * 0.02 = 0.07 */
    ck_assert_int_eq(mc_friction_mu(s.psi_load, 0.12, 0.02, &mu, &err), MC_OK);
    ck_assert(fabs(mu - 0.1) <= TOL_TIGHT);
    ck_assert_int_eq(mc_friction_mu(s.psi_area, 0.12, 0.02, &mu, &err), MC_OK);
    ck_assert(fabs(mu - 0.07) <= TOL_TIGHT);
    ck_assert_int_eq(mc_friction_mu(1.0, 0.12, 0.02, &mu, &err), MC_OK);
    ck_assert(mu == 0.12);
    ck_assert_int_eq(mc_friction_mu(0.0, 0.12, 0.02, &mu, &err), MC_OK);
    ck_assert(mu == 0.02);
    ck_assert_int_eq(mc_friction_mu(1.5, 0.12, 0.02, &mu, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "psi") && strstr(err.msg, "[0, 1]"));
    ck_assert_int_eq(mc_friction_mu(0.5, -0.1, 0.02, &mu, &err), MC_ERR_INPUT);
    /* pocket height: V / (A_nom - A_C); no pocket left when all is in contact */
    ck_assert_int_eq(mc_pocket_height(3.0, 8.0, 2.0, &h, &err), MC_OK);
    ck_assert(h == 0.5);
    ck_assert_int_eq(mc_pocket_height(0.0, 8.0, 8.0, &h, &err), MC_OK);
    ck_assert(h == 0);
    ck_assert_int_eq(mc_pocket_height(1.0, 8.0, 9.0, &h, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_pocket_height(-1.0, 8.0, 2.0, &h, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_lube_split_of(p, gap, 4, 2.0, -1.0, 20.0, &s, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_lube_split_of(p, gap, 4, 2.0, 1.0, 0.0, &s, &err), MC_ERR_INPUT);
    /* names */
    mc_psi_kind k;
    ck_assert_int_eq(mc_psi_from_name("load", &k, &err), MC_OK);
    ck_assert_int_eq(k, MC_PSI_LOAD);
    ck_assert_int_eq(mc_psi_from_name("area", &k, &err), MC_OK);
    ck_assert_int_eq(k, MC_PSI_AREA);
    ck_assert_str_eq(mc_psi_name(MC_PSI_AREA), "area");
    ck_assert_int_eq(mc_psi_from_name("force", &k, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "load | area"));
}
END_TEST

/* ---- the whole contact: a lubricant pressure profile over the Hertz band (theory.md §11.4) -- */

/* A smooth cylinder R on a line grid (ny = 1, periodic y: plane strain), nx cells of dx; the band
 * |x| <= b holds the profile w = 1. */
typedef struct {
    mc_grid g;
    size_t n;
    double *h, *w, *p, *u, *gap;
    double R, b, dx, wprime; /* load per length, N/m */
    mc_operator *K;
    mc_contact_solver *s;
} line_band;

static void make_line_band(line_band *lb, int nx, double dx, double R, double wprime)
{
    mc_grid g = {nx, 1, dx, dx, 0, 1};
    lb->g = g;
    lb->n = (size_t)nx;
    lb->dx = dx;
    lb->R = R;
    lb->wprime = wprime;
    lb->b = sqrt(8.0 * wprime * R / (M_PI * 2.0 * E_STAR)); /* Hertz line: b^2 = 4 w' R / (pi E*) */
    lb->h = mc_zeros(lb->n);
    lb->w = mc_zeros(lb->n);
    lb->p = mc_zeros(lb->n);
    lb->u = mc_zeros(lb->n);
    lb->gap = mc_zeros(lb->n);
    ck_assert(lb->h && lb->w && lb->p && lb->u && lb->gap);
    for (int i = 0; i < nx; i++) {
        const double x = mc_grid_x(&g, i);
        lb->h[i] = x * x / (2.0 * R);
        lb->w[i] = fabs(x) <= lb->b ? 1.0 : 0.0;
    }
    mc_error err = {0};
    lb->K = NULL;
    lb->s = NULL;
    ck_assert_msg(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &lb->K, &err) == MC_OK, "%s",
                  err.msg);
    mc_contact_options opt = {MC_METHOD_CG, CT, 20000, 0, 0};
    ck_assert_msg(mc_contact_create(lb->K, &opt, &lb->s, &err) == MC_OK, "%s", err.msg);
}

static void free_line_band(line_band *lb)
{
    mc_contact_destroy(&lb->s);
    mc_operator_destroy(&lb->K);
    double *a[] = {lb->h, lb->w, lb->p, lb->u, lb->gap};
    for (int k = 0; k < 5; k++)
        mc_free(a[k]);
}

/* Dry: the profile's band does not change a solve at p_lub = 0, and the pressure is Hertz's
 * (p0 = 2 w' / (pi b)) within the edge cell's error: at dx = b/40 the cell straddling the edge
 * sees sqrt(1 - (x/b)^2) change by ~sqrt(2 dx / b) = 0.22 of p0 across it; the discrete
 * solution's largest deviation is ~1 % there, 1e-6 of p0 at the centre. */
START_TEST(whole_band_dry_is_hertz)
{
    line_band lb;
    make_line_band(&lb, 200, 0.5e-6, 2e-3, 2e4);
    const double ly = lb.g.dy, p0 = 2.0 * lb.wprime / (M_PI * lb.b);
    mc_volume_problem vp = {.h = lb.h, .load = lb.wprime * ly, .h_target = 0, .weight = lb.w};
    mc_volume_result res;
    mc_error err = {0};
    ck_assert_msg(mc_volume_equilibrium(lb.s, lb.K, &vp, lb.p, lb.u, lb.gap, &res, &err) == MC_OK,
                  "%s", err.msg);
    ck_assert_int_eq(res.regime, MC_REGIME_DRY);
    double worst = 0, centre = 0;
    for (size_t i = 0; i < lb.n; i++) {
        const double t = mc_grid_x(&lb.g, (int)i) / lb.b;
        const double ph = fabs(t) < 1 ? p0 * sqrt(1 - t * t) : 0.0;
        worst = test_worst(worst, fabs(lb.p[i] - ph) / p0);
        if (fabs(t) < 0.5)
            centre = test_worst(centre, fabs(lb.p[i] - ph) / p0);
    }
    if (getenv("MC_TEST_VERBOSE"))
        printf("whole band dry: |p - p_Hertz| / p0 max %.3g, |x| < b/2 %.3g\n", worst, centre);
    ck_assert_double_le(worst, 0.03);   /* measured 0.013 */
    ck_assert_double_le(centre, 1e-4);  /* measured 1.6e-6 */
    /* the nominal area is the band, not the grid */
    size_t nb = 0;
    for (size_t i = 0; i < lb.n; i++)
        nb += lb.w[i] > 0;
    ck_assert_double_eq_tol(res.a_nom, (double)nb * lb.dx * ly, 1e-15 * res.a_nom);
    free_line_band(&lb);
}
END_TEST

/* Full film: the fluid carries w' as a uniform pressure on the band's cells, whose plane-strain
 * deflection is closed form (both bodies, 1/E* = sum (1 - nu^2)/E):
 *   u(x) = -(2 p / (pi E*)) [(x + c) ln|x + c| - (x - c) ln|x - c|] + const,
 * c the half-width of the loaded cells (a whole number of cells). The onset gap is
 * h + u - min(h + u) (the solids touch at one point): compared cell by cell, and V with the sum
 * over the band alone. The line operator integrates the strip pressure exactly (operator.h), so
 * only round-off remains: 1e-9 of the largest gap. */
START_TEST(whole_band_full_film_closed_form)
{
    line_band lb;
    make_line_band(&lb, 240, 0.5e-6, 2e-3, 2e4);
    const double ly = lb.g.dy;
    mc_volume_problem vp = {.h = lb.h, .load = lb.wprime * ly, .h_target = 1e-3, .weight = lb.w};
    mc_volume_result res;
    mc_error err = {0};
    ck_assert_msg(mc_volume_equilibrium(lb.s, lb.K, &vp, lb.p, lb.u, lb.gap, &res, &err) == MC_OK,
                  "%s", err.msg);
    ck_assert_int_eq(res.regime, MC_REGIME_FULL_FILM);
    size_t nb = 0;
    for (size_t i = 0; i < lb.n; i++)
        nb += lb.w[i] > 0;
    const double c = 0.5 * (double)nb * lb.dx, pf = lb.wprime / (2.0 * c);
    ck_assert_double_eq_tol(res.p_lub, pf, 1e-14 * pf);
    /* the closed form's gap at onset, lifted by the separation */
    double *ref = mc_zeros(lb.n);
    ck_assert_ptr_nonnull(ref);
    double lo = INFINITY;
    for (size_t i = 0; i < lb.n; i++) {
        const double x = mc_grid_x(&lb.g, (int)i);
        const double f = (x + c) * log(fabs(x + c)) - (x - c) * log(fabs(x - c));
        ref[i] = lb.h[i] - 2.0 * pf / (M_PI * E_STAR) * f;
        lo = fmin(lo, ref[i]);
    }
    double worst = 0, gmax = 0, vref = 0;
    for (size_t i = 0; i < lb.n; i++) {
        ref[i] += res.separation - lo;
        gmax = test_worst(gmax, ref[i]);
        worst = test_worst(worst, fabs(lb.gap[i] - ref[i]));
        if (lb.w[i] > 0)
            vref += ref[i] * lb.dx * ly;
        ck_assert_double_eq_tol(lb.p[i], lb.w[i] > 0 ? pf : 0.0, 1e-14 * pf);
    }
    if (getenv("MC_TEST_VERBOSE"))
        printf("whole band full film: gap vs closed form %.3g of the largest gap; V %.9g vs %.9g\n",
               worst / gmax, res.volume, vref);
    ck_assert_double_le(worst, 1e-9 * gmax);
    ck_assert_double_eq_tol(res.volume, vref, 1e-9 * vref);
    ck_assert_double_eq_tol(res.volume, 1e-3 * res.a_nom, 1e-9 * res.volume); /* V = V* */
    mc_free(ref);
    free_line_band(&lb);
}
END_TEST

/* Mixed, rough: the root meets V = V* over the band; the bound is p_lub on the band and 0
 * outside (p >= bound, gap ~ 0 where p exceeds it); the split counts the band alone; and
 * w = 1 everywhere reproduces the solve without a profile. */
START_TEST(whole_band_mixed_rough)
{
    line_band lb;
    make_line_band(&lb, 256, 0.5e-6, 2e-3, 2e4);
    double *rough = mc_zeros(lb.n);
    ck_assert_ptr_nonnull(rough);
    uint64_t st = 7;
    for (size_t i = 0; i < lb.n; i++) { /* a few tenths of a um of random-walk roughness */
        st = st * 6364136223846793005ULL + 1442695040888963407ULL;
        rough[i] = (i ? rough[i - 1] : 0.0) + 0.05e-6 * ((double)(st >> 11) / 9007199254740992.0 - 0.5);
    }
    for (size_t i = 0; i < lb.n; i++)
        lb.h[i] += rough[i];
    const double ly = lb.g.dy;
    mc_volume_problem vp = {.h = lb.h, .load = lb.wprime * ly, .h_target = 0, .weight = lb.w};
    mc_volume_result res;
    mc_error err = {0};
    ck_assert_int_eq(mc_volume_equilibrium(lb.s, lb.K, &vp, lb.p, lb.u, lb.gap, &res, &err), MC_OK);
    /* a target between the dry pocket volume over the band and the onset's */
    const double vt = res.volume + 0.3 * (res.v_onset - res.volume);
    vp.h_target = vt / res.a_nom;
    ck_assert_msg(mc_volume_equilibrium(lb.s, lb.K, &vp, lb.p, lb.u, lb.gap, &res, &err) == MC_OK,
                  "%s", err.msg);
    ck_assert_int_eq(res.regime, MC_REGIME_MIXED);
    double vband = 0, gscale = 0;
    for (size_t i = 0; i < lb.n; i++)
        gscale = test_worst(gscale, fabs(lb.h[i]));
    for (size_t i = 0; i < lb.n; i++) {
        const double lo = res.p_lub * lb.w[i];
        ck_assert_double_ge(lb.p[i], lo - 1e-9 * res.p_nominal);
        if (lb.p[i] > lo * (1 + 1e-9) + 1e-9 * res.p_nominal)
            ck_assert_double_le(fabs(lb.gap[i]), 1e-6 * gscale);
        if (lb.w[i] > 0)
            vband += lb.gap[i] * lb.dx * ly;
    }
    ck_assert_double_le(fabs(vband - vt), 2 * ROOT_TOL * vt);
    mc_lube_split sp;
    ck_assert_int_eq(mc_lube_split_weighted(lb.p, lb.gap, lb.w, lb.n, lb.dx * ly, res.p_lub,
                                            vp.load, &sp, &err), MC_OK);
    ck_assert_double_eq_tol(sp.a_nom, res.a_nom, 1e-15 * res.a_nom);
    ck_assert_double_eq_tol(sp.volume, vband, 1e-12 * vband);
    /* the load balance: solid + fluid = F (force control) */
    ck_assert_double_eq_tol(sp.f_solid + sp.f_fluid, vp.load, 1e-8 * vp.load);
    /* w = 1 everywhere is the solve without a profile */
    for (size_t i = 0; i < lb.n; i++)
        lb.w[i] = 1.0;
    vp.h_target = vt / res.a_nom;
    mc_volume_result r1, r2;
    double *p2 = mc_zeros(lb.n), *g2 = mc_zeros(lb.n);
    ck_assert(p2 && g2);
    ck_assert_int_eq(mc_volume_equilibrium(lb.s, lb.K, &vp, lb.p, NULL, lb.gap, &r1, &err), MC_OK);
    vp.weight = NULL;
    ck_assert_int_eq(mc_volume_equilibrium(lb.s, lb.K, &vp, p2, NULL, g2, &r2, &err), MC_OK);
    ck_assert_double_eq_tol(r1.p_lub, r2.p_lub, 1e-10 * r2.p_nominal);
    for (size_t i = 0; i < lb.n; i++)
        ck_assert_double_eq_tol(lb.p[i], p2[i], 1e-8 * r2.p_nominal);
    mc_free(p2);
    mc_free(g2);
    mc_free(rough);
    free_line_band(&lb);
}
END_TEST

Suite *suite_lube_volume(void);
Suite *suite_lube_volume(void)
{
    Suite *s = suite_create("lube_volume");
    TCase *tc = tcase_create("volume");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, volume_monotone);
    tcase_add_loop_test(tc, mixed_root, 0, 2);
    tcase_add_loop_test(tc, limits, 0, 2);
    tcase_add_test(tc, not_converged_and_bad_input);
    tcase_add_test(tc, friction_hand_values);
    tcase_add_test(tc, whole_band_dry_is_hertz);
    tcase_add_test(tc, whole_band_full_film_closed_form);
    tcase_add_test(tc, whole_band_mixed_rough);
    suite_add_tcase(s, tc);
    return s;
}
