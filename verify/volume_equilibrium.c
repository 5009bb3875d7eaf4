/* volume_equilibrium.c - suite `volume_equilibrium`: the lubricant volume equilibrium
 * (lube/volume.h; Mevissen et al. 2025; docs/theory.md §11) against an independent solve of the
 * dossier's checks (plastic-lubrication §5): V(p_lub) rises monotonically, the load splits into
 * F_solid + p_lub A_free = F_N, the full-film and dry limits, the root of Brent's method against
 * a bisection of its own over another contact solver (Polonsky-Keer), V(0) and V(0.95 p_nom)
 * against dry Polonsky-Keer solves at the load the solids carry (the periodic identity), and the
 * paper's active-set solver agreeing with cg at the root. The dossier's reference figures (a
 * 96 x 96 patch of its own random surface) are reported beside ours: the surfaces differ, so
 * they are read, not checked. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "harness.h"
#include "kernels/kernel.h"
#include "lube/friction.h"
#include "lube/volume.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "suites.h"
#include "surface/surface.h"
#include "vutil.h"

#define E_STEEL 210e9
#define NU_STEEL 0.3
#define P_NOM 1e9      /* nominal pressure of the dossier's patch, Pa */
#define SQ 0.3e-6      /* its rms roughness, m */
#define DX 0.8e-6      /* the paper's cell size, m */
/* Correlation length: the dossier does not state its own. 8 um makes V(0) / A_nom of the 96 x 96
 * patch agree with the dossier's 0.204 um within 3 % (one figure used to calibrate; the others
 * are then compared as they come). */
#define CORR 8e-6
#define CONTACT_TOL 1e-12 /* contact solves: 1e6 below the root tolerance (volume.h) */
#define ROOT_TOL 1e-6  /* relative on V, the default of [lubrication] tolerance */

/* Tolerance tiers. Load split: the contact solver meets A sum p = W to its tolerance, and the
 * split is an identity of the fields (friction.h): 1e3 x CONTACT_TOL. Independent root: both
 * roots meet |V - V*| <= ROOT_TOL V*, so they may differ by 2 ROOT_TOL V* / (dV/dp) in p_lub;
 * with the other solver's own V error (its tolerance times the gap scale) 3 ROOT_TOL is allowed.
 * Active set against cg at the same p_lub: both solve the LCP to round-off (active set: a direct
 * solve; cg to 1e-12), pressures compared relative to p_nom: 1e-9. */
#define SPLIT_TOL (1e3 * CONTACT_TOL)
#define ROOT_CMP_TOL (3 * ROOT_TOL)
#define AS_TOL 1e-9
#define DRY_TOL (1e3 * CONTACT_TOL)

typedef struct {
    mc_grid g;
    size_t n;
    double dA, a_nom, load;
    double *h, *p, *u, *gap;
    mc_operator *K;
    mc_contact_solver *cg, *pk;
} patch;

static void patch_free(patch *pt)
{
    mc_contact_destroy(&pt->cg);
    mc_contact_destroy(&pt->pk);
    mc_operator_destroy(&pt->K);
    mc_free(pt->h);
    mc_free(pt->p);
    mc_free(pt->u);
    mc_free(pt->gap);
}

/* A periodic rough patch of N x N cells under P_NOM; solvers cg (and pk). */
static int patch_make(patch *pt, int N, int with_pk, mc_contact_method method, mc_error *err)
{
    memset(pt, 0, sizeof *pt);
    pt->g = (mc_grid){.nx = N, .ny = N, .dx = DX, .dy = DX, .periodic_x = 1, .periodic_y = 1};
    pt->n = mc_grid_cells(&pt->g);
    pt->dA = DX * DX;
    pt->a_nom = pt->dA * (double)pt->n;
    pt->load = P_NOM * pt->a_nom;
    if (!(pt->h = mc_zeros(pt->n)) || !(pt->p = mc_zeros(pt->n)) || !(pt->u = mc_zeros(pt->n)) ||
        !(pt->gap = mc_zeros(pt->n)))
        return mc_fail(err, MC_ERR_NOMEM, "out of memory");
    mc_shape_spec flat = {.shape = MC_SHAPE_FLAT};
    mc_roughness_spec rs = {.type = MC_ROUGH_GAUSSIAN, .rq = SQ, .correlation_x = CORR,
                            .correlation_y = CORR, .seed = 7};
    int rc = mc_surface_topography(&pt->g, &flat, &rs, pt->h, err);
    const double estar = mc_combined_modulus(E_STEEL, NU_STEEL, E_STEEL, NU_STEEL, 0);
    if (rc == MC_OK)
        rc = mc_operator_plan_love(&pt->g, estar, MC_BACKEND_FFT, &pt->K, err);
    mc_contact_options o = {.method = method, .tolerance = CONTACT_TOL, .max_iterations = 20000,
                            .estar = method == MC_METHOD_CG ? estar : 0};
    if (rc == MC_OK)
        rc = mc_contact_create(pt->K, &o, &pt->cg, err);
    mc_contact_options opk = {.method = MC_METHOD_PK, .tolerance = CONTACT_TOL,
                              .max_iterations = 200000};
    if (rc == MC_OK && with_pk)
        rc = mc_contact_create(pt->K, &opk, &pt->pk, err);
    return rc;
}

/* V(p_lub) by one contact solve of solver s; the load split's defect into *split (relative). */
static int volume_at(patch *pt, mc_contact_solver *s, double plub, double *v, double *split,
                     mc_error *err)
{
    mc_contact_problem cp = {.h = pt->h, .p_lub = plub, .p_cap = INFINITY,
                             .control = MC_CONTROL_FORCE, .load = pt->load};
    mc_contact_summary cs;
    int rc = mc_contact_solve(s, &cp, pt->p, pt->u, pt->gap, &cs, err);
    if (rc != MC_OK)
        return rc;
    mc_lube_split sp;
    rc = mc_lube_split_of(pt->p, pt->gap, pt->n, pt->dA, plub, pt->load, &sp, err);
    *v = sp.volume;
    if (split)
        *split = fabs(sp.f_solid + plub * (sp.a_nom - sp.a_contact) - pt->load) / pt->load;
    return rc;
}

/* The periodic identity (dossier §5.1: in a periodic formulation K 1 is a rigid shift): p >= p_lub
 * under F_N has the gap of p' = p - p_lub >= 0 under F_N - p_lub A_nom, i.e. V(p_lub) = V_dry(F_N -
 * p_lub A_nom). The dry solve here is an independent route: the other solver (pk), no lower bound,
 * the reduced load. */
static int volume_dry(patch *pt, double load, double *v, mc_error *err)
{
    mc_contact_problem cp = {.h = pt->h, .p_lub = 0, .p_cap = INFINITY,
                             .control = MC_CONTROL_FORCE, .load = load};
    mc_contact_summary cs;
    int rc = mc_contact_solve(pt->pk, &cp, pt->p, pt->u, pt->gap, &cs, err);
    double sum = 0;
    for (size_t i = 0; i < pt->n; i++)
        sum += pt->gap[i];
    *v = pt->dA * sum;
    return rc;
}

/* The independent root: bisection on p_lub in [0, p_nom) with solver pk until |V - V*| <=
 * 1e-9 V* or the bracket is below 1e-12 p_nom. */
static int bisect(patch *pt, double vstar, double *root, int *solves, mc_error *err)
{
    double lo = 0, hi = P_NOM * (1 - 1e-9), v;
    *solves = 0;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        int rc = volume_at(pt, pt->pk, mid, &v, NULL, err);
        ++*solves;
        if (rc != MC_OK)
            return rc;
        if (fabs(v - vstar) <= 1e-9 * vstar || hi - lo < 1e-12 * P_NOM) {
            *root = mid;
            return MC_OK;
        }
        if (v < vstar)
            lo = mid;
        else
            hi = mid;
    }
    *root = 0.5 * (lo + hi);
    return MC_OK;
}

static int equilibrium(patch *pt, mc_contact_solver *s, double h_ehd, mc_volume_result *vr,
                       mc_error *err)
{
    mc_volume_problem prob = {.h = pt->h, .load = pt->load, .h_target = h_ehd,
                              .tolerance = ROOT_TOL};
    return mc_volume_equilibrium(s, pt->K, &prob, pt->p, pt->u, pt->gap, vr, err);
}

/* V(p_lub) sweep, the load split and the limits on the main patch. */
static int sweep_and_limits(vf_ctx *ctx, patch *pt, double *slope_at, double root_guess)
{
    mc_error err = {0};
    const int np = vf_fast(ctx) ? 8 : 20;
    double vprev = -INFINITY, worst_split = 0, v0 = 0, v95 = 0, p95 = 0;
    int nonmono = 0;
    FILE *f = vf_open(ctx, "volume_vs_plub.csv");
    if (f)
        fprintf(f, "plub_over_pnom,V_over_Anom_um,split_defect\n");
    double vlast[2] = {0, 0}, plast[2] = {0, 0};
    for (int k = 0; k <= np; k++) {
        double frac = 0.95 * k / np, v, split;
        if (volume_at(pt, pt->cg, frac * P_NOM, &v, &split, &err) != MC_OK) {
            vf_fail(ctx, "sweep", "p_lub = %g p_nom: %s", frac, err.msg);
            if (f)
                vf_close(ctx, f);
            return 1;
        }
        nonmono += !(v > vprev);
        vprev = v;
        worst_split = vf_worst(worst_split, split);
        if (k == 0)
            v0 = v;
        if (k == np) {
            v95 = v;
            p95 = frac * P_NOM;
        }
        if (frac * P_NOM <= root_guess) { /* the secant just below and above the root */
            vlast[0] = v;
            plast[0] = frac * P_NOM;
        } else if (plast[1] == 0) {
            vlast[1] = v;
            plast[1] = frac * P_NOM;
        }
        if (f)
            fprintf(f, "%.6g,%.9g,%.3e\n", frac, v / pt->a_nom * 1e6, split);
    }
    if (f)
        vf_close(ctx, f);
    *slope_at = plast[1] > plast[0] ? (vlast[1] - vlast[0]) / (plast[1] - plast[0]) : NAN;
    char q[160];
    snprintf(q, sizeof q, "V(p_lub) on %d points from 0 to 0.95 p_nom: steps that do not rise",
             np + 1);
    vf_check(ctx, "monotone_V", q, "dossier §5.1: V strictly increasing", 0, nonmono, 0, VF_MAX);
    /* information: a force-controlled solve enforces F_N (its stopping test), so the split
     * F_solid + p_lub A_free = F_N cannot fail here */
    vf_info(ctx, "load_split", "max |F_solid + p_lub A_free - F_N| / F_N over the sweep",
            "by construction: the load a force-controlled solve enforces", NAN, worst_split);
    /* V0 and V95 against the dry solves of the other solver (the periodic identity above): both
     * solvers stop at a relative residual of CONTACT_TOL; V is a sum of gaps of the contact scale,
     * so they may differ by a few hundred CONTACT_TOL relative: DRY_TOL = 1e3 CONTACT_TOL (measured
     * 3e-15 and 2e-15 on 48 x 48). A lubricant bound that the solver does not carry as a
     * uniform shift (p_lub on the free cells, not subtracted from the load) moves V95 by order 1. */
    double v0_pk = NAN, v95_pk = NAN;
    if (volume_dry(pt, pt->load, &v0_pk, &err) != MC_OK ||
        volume_dry(pt, pt->load - p95 * pt->a_nom, &v95_pk, &err) != MC_OK)
        vf_fail(ctx, "dry_pk", "%s", err.msg);
    vf_check(ctx, "V0", "V(0) / A_nom, um (dry contact, cg)",
             "the same patch solved by pk (another solver)", v0_pk / pt->a_nom * 1e6,
             v0 / pt->a_nom * 1e6, DRY_TOL, VF_REL);
    vf_check(ctx, "V95", "V(0.95 p_nom) / A_nom, um (cg, p >= p_lub)",
             "V_dry(0.05 F_N) by pk: the periodic identity V(p_lub) = V_dry(F_N - p_lub A_nom)",
             v95_pk / pt->a_nom * 1e6, v95 / pt->a_nom * 1e6, DRY_TOL, VF_REL);
    /* the dossier's figures: another surface (its own generator, an unstated correlation length)
     * on 96 x 96 cells; the fast variant's 48 x 48 patch is a different realisation again (19 %
     * and 30 % off, against 2.5 % and 9.6 % on 96 x 96): no tolerance follows, so shown only */
    vf_info(ctx, "V0_dossier", "V(0) / A_nom, um (dry contact)",
            "dossier 96 x 96 patch (its own surface): 0.204 um", 0.204, v0 / pt->a_nom * 1e6);
    vf_info(ctx, "V95_dossier", "V(0.95 p_nom) / A_nom, um",
            "dossier 96 x 96 patch (its own surface): 0.636 um", 0.636, v95 / pt->a_nom * 1e6);
    /* the limits */
    mc_volume_result vr;
    if (equilibrium(pt, pt->cg, 5e-6, &vr, &err) != MC_OK) {
        vf_fail(ctx, "full_film", "%s", err.msg);
        return 1;
    }
    mc_lube_split sp;
    mc_lube_split_of(pt->p, pt->gap, pt->n, pt->dA, vr.p_lub, pt->load, &sp, &err);
    vf_check(ctx, "full_film_regime", "h_EHD = 5 um (far above the roughness): regime full_film",
             "dossier §5.1 limit", MC_REGIME_FULL_FILM, vr.regime, 0, VF_ABS);
    vf_check(ctx, "full_film_plub", "full film: p_lub / p_nom", "the fluid carries F_N", 1.0,
             vr.p_lub / P_NOM, 1e-15, VF_REL);
    vf_check(ctx, "full_film_psi", "full film: psi_load", "no solid contact", 0, sp.psi_load, 0,
             VF_MAX);
    vf_check(ctx, "full_film_volume", "full film: V / V*", "the surfaces separate by the excess",
             1.0, sp.volume / vr.v_target, 1e-12, VF_REL);
    if (equilibrium(pt, pt->cg, 1e-9, &vr, &err) != MC_OK) {
        vf_fail(ctx, "dry", "%s", err.msg);
        return 1;
    }
    mc_lube_split_of(pt->p, pt->gap, pt->n, pt->dA, vr.p_lub, pt->load, &sp, &err);
    vf_check(ctx, "dry_regime", "h_EHD = 1 nm (far below V(0) / A_nom): regime dry",
             "dossier §5.1 limit", MC_REGIME_DRY, vr.regime, 0, VF_ABS);
    vf_check(ctx, "dry_plub", "dry: p_lub, Pa", "p_lub = 0", 0, vr.p_lub, 0, VF_MAX);
    vf_check(ctx, "dry_psi", "dry: psi_load", "the solids carry F_N (to the contact tolerance)",
             1.0, sp.psi_load, SPLIT_TOL, VF_REL);
    return 0;
}

/* Roots for a range of films: Brent against the bisection over pk; solves per root. */
static int roots(vf_ctx *ctx, patch *pt, double slope)
{
    mc_error err = {0};
    static const double films_um[] = {0.26, 0.30, 0.324, 0.40, 0.50};
    const int nf = vf_fast(ctx) ? 2 : 5;
    FILE *f = vf_open(ctx, "roots.csv");
    if (f)
        fprintf(f, "h_ehd_um,regime,p_lub_MPa,p_lub_bisect_MPa,rel_error,solves,iterations,"
                   "psi_load,psi_area,pocket_um\n");
    double worst_cmp = 0, worst_err = 0, worst_pocket = 0, worst_vol = 0, worst_pfield = 0;
    int total_solves = 0, nroots = 0, max_solves = 0;
    for (int k = 0; k < nf; k++) {
        const double h = films_um[vf_fast(ctx) ? 2 * k + 1 : k] * 1e-6;
        mc_volume_result vr;
        if (equilibrium(pt, pt->cg, h, &vr, &err) != MC_OK) {
            vf_fail(ctx, "root", "h_EHD = %g um: %s", h * 1e6, err.msg);
            continue;
        }
        mc_lube_split sp;
        mc_lube_split_of(pt->p, pt->gap, pt->n, pt->dA, vr.p_lub, pt->load, &sp, &err);
        if (vr.regime == MC_REGIME_MIXED) { /* V = V* there: h_pocket = V* / (A_nom - A_C) */
            double pocket_id = h / (1 - sp.psi_area); /* dossier §5.2 */
            worst_pocket = vf_worst(worst_pocket, fabs(sp.pocket_height - pocket_id) / pocket_id);
            /* independent of the solver and of the split: the returned fields summed here, V
             * against V* = h_EHD A_nom (volume.h), and the pocket height V / (A_nom - A_C) with
             * A_C the cells above the lubricant pressure */
            double sum_g = 0;
            size_t free_cells = 0;
            for (size_t i = 0; i < pt->n; i++) {
                sum_g += pt->gap[i];
                free_cells += !(pt->p[i] > vr.p_lub);
            }
            double vstar = h * pt->a_nom, vol = pt->dA * sum_g;
            worst_vol = vf_worst(worst_vol, fabs(vol - vstar) / vstar);
            double pocket = free_cells ? vol / (pt->dA * (double)free_cells) : 0;
            worst_pfield = vf_worst(worst_pfield, fabs(sp.pocket_height - pocket) / pocket);
        }
        double pb = NAN;
        int sb = 0;
        if (vr.regime == MC_REGIME_MIXED) {
            if (bisect(pt, vr.v_target, &pb, &sb, &err) != MC_OK) {
                vf_fail(ctx, "bisect", "h_EHD = %g um: %s", h * 1e6, err.msg);
                continue;
            }
            /* |dp| allowed: ROOT_CMP_TOL V* over the local slope dV/dp */
            worst_cmp = vf_worst(worst_cmp, fabs(vr.p_lub - pb) * slope / (ROOT_CMP_TOL * vr.v_target));
            total_solves += vr.solves;
            max_solves = vr.solves > max_solves ? vr.solves : max_solves;
            nroots++;
            worst_err = vf_worst(worst_err, vr.rel_error);
        }
        if (f)
            fprintf(f, "%.4g,%s,%.6f,%.6f,%.3e,%d,%ld,%.6f,%.6f,%.6f\n", h * 1e6,
                    mc_lube_regime_name(vr.regime), vr.p_lub * 1e-6, pb * 1e-6, vr.rel_error,
                    vr.solves, vr.iterations, sp.psi_load, sp.psi_area, sp.pocket_height * 1e6);
        if (fabs(h - 0.324e-6) < 1e-12) {
            vf_info(ctx, "ref_plub", "h_EHD = 0.324 um: p_lub, MPa", "dossier: 513.8 MPa", 513.8,
                    vr.p_lub * 1e-6);
            vf_info(ctx, "ref_psi_load", "h_EHD = 0.324 um: psi_load", "dossier: 0.533", 0.533,
                    sp.psi_load);
            vf_info(ctx, "ref_psi_area", "h_EHD = 0.324 um: psi_area", "dossier: 0.091", 0.091,
                    sp.psi_area);
            vf_info(ctx, "ref_pocket", "h_EHD = 0.324 um: mean pocket height, um",
                    "dossier: 0.357 um", 0.357, sp.pocket_height * 1e6);
        }
    }
    if (f)
        vf_close(ctx, f);
    vf_check(ctx, "root_vs_bisection",
             "max |p_lub(Brent, cg) - p_lub(bisection, pk)| in units of 3e-6 V* / (dV/dp)",
             "an independent solve of V(p_lub) = V*", 0, worst_cmp, 1.0, VF_MAX);
    /* information: the solver's own stopping test, and the same number again through the split
     * (h_pocket = V / (A_nom - A_C) equals h_EHD / (1 - psi_A) exactly when V = V*) */
    vf_info(ctx, "root_error", "max |V - V*| / V* of the returned states",
            "by construction: the solver's stopping test, 1e-6", NAN, worst_err);
    vf_info(ctx, "pocket_height", "max |h_pocket - h_EHD / (1 - psi_A)| / h_pocket (mixed)",
            "by construction: root_error again through the split", NAN, worst_pocket);
    vf_check(ctx, "root_volume_fields",
             "max |dA sum(gap) - h_EHD A_nom| / (h_EHD A_nom) of the returned fields (mixed)",
             "V* = h_EHD A_nom (dossier §5.1), V summed here from the gap", 0, worst_vol,
             ROOT_TOL * (1 + 1e-6), VF_MAX);
    vf_check(ctx, "pocket_fields",
             "max |h_pocket - V / (A_nom - A_C)| / h_pocket, V and A_C (p > p_lub) summed here "
             "from the fields (mixed)",
             "dossier §5.2 definition", 0, worst_pfield, 1e-12, VF_MAX);
    if (nroots > 0) {
        vf_info(ctx, "solves_per_root", "contact solves per root (mean, mixed regime)",
                "volume.h: Brent, warm-started", NAN, (double)total_solves / nroots);
        vf_info(ctx, "solves_per_root_max", "contact solves per root (max)", "cap 60", NAN,
                max_solves);
    }
    return 0;
}

/* The paper's active-set solver against cg on a 24 x 24 patch (dossier §5.2: agree to 1e-10 at
 * p_lub = 0, 300, 700 MPa), and the root found with each. */
static int active_set(vf_ctx *ctx)
{
    mc_error err = {0};
    patch a, c;
    if (patch_make(&a, 24, 0, MC_METHOD_ACTIVE_SET, &err) != MC_OK ||
        patch_make(&c, 24, 0, MC_METHOD_CG, &err) != MC_OK) {
        vf_fail(ctx, "active_set", "%s", err.msg);
        patch_free(&a);
        patch_free(&c);
        return 1;
    }
    static const double plubs[] = {0, 300e6, 700e6};
    double worst = 0, v;
    for (int k = 0; k < 3; k++) {
        if (volume_at(&a, a.cg, plubs[k], &v, NULL, &err) != MC_OK ||
            volume_at(&c, c.cg, plubs[k], &v, NULL, &err) != MC_OK) {
            vf_fail(ctx, "active_set", "p_lub = %g: %s", plubs[k], err.msg);
            break;
        }
        for (size_t i = 0; i < a.n; i++)
            worst = vf_worst(worst, fabs(a.p[i] - c.p[i]) / P_NOM);
    }
    vf_check(ctx, "active_set_vs_cg", "max |p_active-set - p_cg| / p_nom at p_lub = 0, 300, 700 "
             "MPa (24 x 24)", "dossier §5.2: agree to 1e-10", 0, worst, AS_TOL, VF_MAX);
    mc_volume_result ra, rc_;
    int ok = equilibrium(&a, a.cg, 0.30e-6, &ra, &err) == MC_OK &&
             equilibrium(&c, c.cg, 0.30e-6, &rc_, &err) == MC_OK;
    if (ok && ra.regime == MC_REGIME_MIXED) {
        vf_check(ctx, "active_set_root", "root p_lub with the active-set solver against cg, "
                 "relative to p_nom (24 x 24, h_EHD = 0.30 um)", "the same equation",
                 rc_.p_lub / P_NOM, ra.p_lub / P_NOM, 1e-4, VF_ABS);
        for (size_t i = 0; i < a.n; i++)
            a.p[i] -= c.p[i];
        double d = 0;
        for (size_t i = 0; i < a.n; i++)
            d = vf_worst(d, fabs(a.p[i]) / P_NOM);
        vf_info(ctx, "active_set_root_p", "max |p_as - p_cg| / p_nom at the two roots",
                "differ by the roots' own tolerance", NAN, d);
    } else
        vf_fail(ctx, "active_set_root", "%s", ok ? "h_EHD = 0.30 um is not mixed on 24 x 24"
                                                  : err.msg);
    patch_free(&a);
    patch_free(&c);
    return 0;
}

int vf_suite_volume_equilibrium(vf_ctx *ctx, int fast)
{
    const int N = fast ? 48 : 96;
    vf_text(ctx,
            "A periodic rough patch of %d x %d cells of %.1f um (the paper's spacing), Gaussian "
            "heights with Sq = %.1f um and correlation length %.0f um (the dossier does not "
            "state its own: this one brings V(0) / A_nom of the 96 x 96 patch within 3 %% of the "
            "dossier's 0.204 um; the other reference figures are then compared as they come), "
            "steel on steel, under a nominal pressure of %.0f GPa, as in the dossier's check of "
            "§5.2. Contact solves: cg to %.0e (method pk for the independent "
            "root), the root to |V - V*| <= %.0e V* (docs/theory.md §11.2).\n\n"
            "Checks: V(p_lub) strictly increasing; the load split F_solid + p_lub A_free = F_N "
            "(to %.0e: the solver's load balance); V(0) and V(0.95 p_nom) against dry solves of "
            "the other solver (Polonsky-Keer) at F_N and 0.05 F_N: on a periodic patch a uniform "
            "lubricant pressure is a rigid shift, so V(p_lub) = V_dry(F_N - p_lub A_nom) "
            "(to 1e-9 relative: both solves stop at 1e-12); the limits (full film: p_lub = p_nom, no solid "
            "contact, V = V*; dry: p_lub = 0, psi_load = 1); Brent's root against a bisection of "
            "this suite over the Polonsky-Keer solver (the two may differ by 3e-6 V* over the "
            "local slope dV/dp); the mean pocket height h_EHD / (1 - psi_A); the paper's "
            "active-set solver against cg (24 x 24, the dossier's check). The dossier's "
            "reference figures come from a surface of its own (another generator and an unstated "
            "correlation length): they are shown as information beside ours. Why V0 and V95 differ "
            "from the dossier's 0.204 and 0.636 um: a different surface. The 96 x 96 patch "
            "(correlation length chosen to match V0) is 2.5 %% and 9.6 %% off; the fast variant's "
            "48 x 48 patch, another realisation with fewer long wavelengths, 19 %% and 30 %%. "
            "V95 is set by the few highest summits of one realisation, so no tolerance against "
            "another surface follows; the independent route above checks our numbers "
            "instead.\n\n",
            N, N, DX * 1e6, SQ * 1e6, CORR * 1e6, P_NOM * 1e-9, CONTACT_TOL, ROOT_TOL, SPLIT_TOL);
    mc_error err = {0};
    patch pt;
    if (patch_make(&pt, N, 1, MC_METHOD_CG, &err) != MC_OK) {
        vf_fail(ctx, "setup", "%s", err.msg);
        patch_free(&pt);
        return 1;
    }
    /* the root at h = 0.324 um first: its p_lub places the secant of dV/dp */
    mc_volume_result vr;
    double slope = NAN;
    int rc = equilibrium(&pt, pt.cg, 0.324e-6, &vr, &err);
    if (rc == MC_OK)
        rc = sweep_and_limits(ctx, &pt, &slope, vr.p_lub);
    if (rc == MC_OK && !(slope > 0))
        vf_fail(ctx, "slope", "dV/dp at the root is not positive (%g)", slope);
    if (rc == MC_OK && slope > 0)
        rc = roots(ctx, &pt, slope);
    patch_free(&pt);
    if (rc == MC_OK)
        rc = active_set(ctx);
    vf_plot(ctx, "volume_vs_plub.png", "Pocket volume per nominal area against the lubricant "
            "pressure (monotone: the root is unique)",
            "set datafile separator ','\nset xlabel 'p_{lub} / p_{nom}'\n"
            "set ylabel 'V / A_{nom} [um]'\nset grid\n"
            "plot 'volume_vs_plub.csv' every ::1 using 1:2 with linespoints pt 7 title "
            "'V(p_{lub})', 'roots.csv' every ::1 using ($3 / 1000):1 with points pt 5 ps 1.5 "
            "title 'roots: h_{EHD}'");
    vf_plot(ctx, "psi_vs_film.png", "Solid contact ratios at the root against the film "
            "thickness of the smooth surfaces",
            "set datafile separator ','\nset xlabel 'h_{EHD} [um]'\nset ylabel 'psi'\nset grid\n"
            "plot 'roots.csv' every ::1 using 1:8 with linespoints pt 7 title 'psi_{load}', "
            "'' every ::1 using 1:9 with linespoints pt 5 title 'psi_{area}'");
    return rc == MC_OK ? 0 : 1;
}
