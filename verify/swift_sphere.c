/* swift_sphere.c - suite `swift_sphere`: the AISI 52100 Swift-hardening sphere of the dossier
 * (plastic-lubrication §2.6; docs/theory.md §7.2 and §9.3) as a regression against the dossier's
 * reference loop on the same grids, and a grid-convergence study of the residual dent.
 *
 * Scene: a rigid sphere R = 15 mm ([body2] rigid = yes) pressed with W = 2000 N into a Swift
 * half-space, sigma_y = B (C + 1e6 p)^n with B = 1280 MPa, C = 4, n = 0.095 (initial yield
 * 1460 MPa), E = 210 GPa, nu = 0.3; Hertz p0 = 4.508 GPa, a = 460.3 um. Domain 3.2a x 3.2a, the
 * plastic volume under every column, 1.2a deep, 8 load steps: the dossier's arrangement, so the
 * dossier's numbers on 16^2 x 8, 32^2 x 12 and 48^2 x 16 are regression values for ours. Fast
 * variant: 16^2 x 8 and 32^2 x 12; full: also 24^2 x 10 and 48^2 x 16.
 *
 * Regression tolerances: two implementations of the same discrete method (stresses at the cell
 * centres, stress_points = centre) on the same grid
 * differ by their stopping rules (outer tolerance 1e-3 on the residual displacement, plastic
 * fixed point 1e-4): the dent and p_eq to 1 %, p_max to 0.2 % (p_max moves by 0.4 % between the
 * 16^2 and 32^2 grids, a discretisation change ten times what a stopping iterate can do), and the
 * depth of the largest p_eq to one layer (it is a cell centre: z/a is quantised by dz/a).
 *
 * Convergence: the dent d(h) on grids h = dx/a, extrapolated as d(h) = d0 + c h^q through the
 * last three grids (q solved from the two differences, unequal ratios allowed); the observed
 * order q is reported, and the finest grid's distance to d0 must be smaller than the coarsest's
 * (a check that can fail: a diverging or oscillating sequence). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "pipeline/pipeline.h"
#include "reference/hertz.h"
#include "suites.h"
#include "vutil.h"

#define E1 210e9
#define NU 0.30
#define R_SPHERE 15e-3
#define LOAD 2000.0
#define SWIFT_B 1280e6
#define SWIFT_C 4.0
#define SWIFT_N 0.095
#define TOL_DENT 0.01
#define TOL_PEQ 0.01
#define TOL_PMAX 0.002

typedef struct {
    int n, nz;
    double pmax, peq, zpeq, dent; /* dossier values (Pa, -, z/a, m) or 0 */
} grid_t;

/* dossier plastic-lubrication §2.6 table (docs/theory.md §9.3) */
static const grid_t grids[] = {
    {16, 8, 4.308e9, 1.51e-3, 0.53, 0.2247e-6},
    {24, 10, 0, 0, 0, 0},
    {32, 12, 4.324e9, 1.57e-3, 0.45, 0.2418e-6},
    {48, 16, 4.327e9, 1.62e-3, 0.49, 0.2451e-6},
};

typedef struct {
    double pmax, peq, zpeq, dent, time, dx, dz;
    int converged, outer;
} out_t;

static int run_grid(const grid_t *gr, double a, double bscale, out_t *o, mc_error *err)
{
    double dx = 3.2 * a / gr->n;
    mc_scene sc;
    vu_scene(&sc, gr->n, gr->n, dx, dx);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = R_SPHERE;
    sc.body1 = (mc_scene_material){E1, NU, 0};
    sc.body2 = (mc_scene_material){E1, NU, 1};
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = LOAD;
    sc.plasticity.enabled = 1;
    sc.plasticity.criterion = MC_CRITERION_VON_MISES;
    sc.plasticity.hardening = MC_HARDENING_SWIFT;
    sc.plasticity.swift_B = SWIFT_B * bscale;
    sc.plasticity.swift_C = SWIFT_C;
    sc.plasticity.swift_n = SWIFT_N;
    sc.plasticity.load_steps = 8;
    sc.plasticity.depth = 1.2 * a;
    sc.plasticity.dz = 1.2 * a / gr->nz;
    /* the dossier's discrete method: uniform cuboids (not the default spectral kernel, theory
     * §8.10) with the stresses at the cell centres; the cell averages (§8.7) move the 16^2 x 8
     * peak strain by 1.3 %, a change of method */
    sc.plasticity.kernel = MC_EIG_KERNEL_CUBOID;
    sc.plasticity.margin = 3.2 * a; /* every column */
    sc.plasticity.stress_points = MC_EIG_CELL_CENTRE;
    mc_results r;
    int rc = mc_pipeline_run(&sc, &r, err);
    if (rc == MC_OK || rc == MC_NOT_CONVERGED) {
        o->pmax = r.contact.p_max;
        o->peq = r.plastic.peq_max;
        o->zpeq = r.plastic.peq_max_at[2] / a;
        o->dent = r.plastic.residual_max;
        o->time = r.timing.total_s;
        o->converged = r.plastic.converged;
        o->outer = r.plastic.outer_iterations;
        o->dx = dx;
        o->dz = r.plastic.dz;
        rc = MC_OK;
    }
    mc_results_free(&r);
    return rc;
}

/* q with (d3 - d2)/(d2 - d1) = (h3^q - h2^q)/(h2^q - h1^q), h1 > h2 > h3, by bisection on
 * q in [0.1, 6]; NAN when the differences change sign (no monotone convergence). */
static double observed_order(const double *h, const double *d)
{
    double r = (d[2] - d[1]) / (d[1] - d[0]);
    if (!(r > 0 && r < 1))
        return NAN;
    double lo = 0.1, hi = 6;
    for (int it = 0; it < 200; it++) {
        double q = 0.5 * (lo + hi);
        double f = (pow(h[2], q) - pow(h[1], q)) / (pow(h[1], q) - pow(h[0], q)) - r;
        /* f falls with q */
        if (f > 0)
            lo = q;
        else
            hi = q;
    }
    return 0.5 * (lo + hi);
}

int vf_suite_swift_sphere(vf_ctx *ctx, int fast)
{
    double bscale = 1;
    const char *e = getenv("MC_VERIFY_YIELD_SCALE"); /* mutation: scale the Swift B */
    if (e && atof(e) > 0) {
        bscale = atof(e);
        vf_text(ctx, "**Mutation run**: Swift B scaled by %.4g (MC_VERIFY_YIELD_SCALE).", bscale);
    }
    mc_hertz_point hz;
    mc_error err = {0};
    if (mc_hertz_point_from_load(R_SPHERE, E1 / (1 - NU * NU), LOAD, &hz, &err) != MC_OK) {
        vf_fail(ctx, "hertz", "%s", err.msg);
        return 0;
    }
    vf_check(ctx, "hertz_p0", "Hertz p0 of the scene, GPa", "dossier §2.6: 4.508 GPa", 4.508,
             hz.p0 * 1e-9, 5e-4, VF_REL);
    vf_check(ctx, "hertz_a", "Hertz contact radius, um", "dossier §2.6: 460.3 um", 460.3,
             hz.a * 1e6, 5e-4, VF_REL);
    const int use[4] = {1, !fast, 1, !fast};
    out_t out[4];
    memset(out, 0, sizeof out);
    FILE *f = vf_open(ctx, "swift.csv");
    if (f)
        fprintf(f, "n,nz,dx_over_a,dz_over_a,p_max_GPa,peq_max,z_over_a,dent_um,"
                   "ref_p_max_GPa,ref_peq_max,ref_z_over_a,ref_dent_um,outer,time_s\n");
    double hs[4], ds[4];
    int m = 0;
    for (int g = 0; g < 4; g++) {
        if (!use[g])
            continue;
        const grid_t *gr = &grids[g];
        out_t *o = &out[g];
        char id[64], q[160];
        snprintf(id, sizeof id, "run_%d", gr->n);
        if (run_grid(gr, hz.a, bscale, o, &err) != MC_OK) {
            vf_fail(ctx, id, "%s", err.msg);
            continue;
        }
        hs[m] = o->dx / hz.a;
        ds[m++] = o->dent;
        if (f)
            fprintf(f, "%d,%d,%.5f,%.5f,%.6f,%.6g,%.4f,%.6f,%.4f,%.4g,%.3f,%.5f,%d,%.2f\n", gr->n,
                    gr->nz, o->dx / hz.a, o->dz / hz.a, o->pmax * 1e-9, o->peq, o->zpeq,
                    o->dent * 1e6, gr->pmax * 1e-9, gr->peq, gr->zpeq, gr->dent * 1e6, o->outer,
                    o->time);
        snprintf(id, sizeof id, "converged_%d", gr->n);
        snprintf(q, sizeof q, "%d^2 x %d: every load step converged", gr->n, gr->nz);
        vf_check(ctx, id, q, "loop contract", 1, o->converged, 0, VF_ABS);
        if (gr->dent > 0) {
            snprintf(id, sizeof id, "dent_%d", gr->n);
            snprintf(q, sizeof q, "%d^2 x %d: residual dent, um", gr->n, gr->nz);
            vf_check(ctx, id, q, "dossier §2.6 reference loop", gr->dent * 1e6, o->dent * 1e6,
                     TOL_DENT, VF_REL);
            snprintf(id, sizeof id, "pmax_%d", gr->n);
            snprintf(q, sizeof q, "%d^2 x %d: p_max at 2000 N, GPa", gr->n, gr->nz);
            vf_check(ctx, id, q, "dossier §2.6 reference loop", gr->pmax * 1e-9, o->pmax * 1e-9,
                     TOL_PMAX, VF_REL);
            snprintf(id, sizeof id, "peq_%d", gr->n);
            snprintf(q, sizeof q, "%d^2 x %d: largest equivalent plastic strain", gr->n, gr->nz);
            vf_check(ctx, id, q, "dossier §2.6 reference loop", gr->peq, o->peq, TOL_PEQ, VF_REL);
            snprintf(id, sizeof id, "zpeq_%d", gr->n);
            snprintf(q, sizeof q, "%d^2 x %d: depth of the largest p_eq, z/a (one layer: %.3f)",
                     gr->n, gr->nz, o->dz / hz.a);
            vf_check(ctx, id, q, "dossier §2.6 reference loop", gr->zpeq, o->zpeq,
                     o->dz / hz.a, VF_ABS);
        }
        snprintf(id, sizeof id, "time_%d", gr->n);
        snprintf(q, sizeof q, "%d^2 x %d: run time, s", gr->n, gr->nz);
        vf_info(ctx, id, q, "", NAN, o->time);
        vf_regress(ctx, id, VF_TIER_NONE);
    }
    if (f)
        vf_close(ctx, f);
    if (m >= 3) {
        const double *h = hs + m - 3, *d = ds + m - 3;
        double q = observed_order(h, d);
        vf_info(ctx, "dent_order", "observed order of the dent, last three grids", "", NAN, q);
        double d0 = isfinite(q) ? d[2] + (d[2] - d[1]) / (pow(h[1] / h[2], q) - 1) : NAN;
        vf_info(ctx, "dent_extrapolated_um", "dent extrapolated to dx -> 0, um",
                "dossier trend: about 0.25 um", 0.25, d0 * 1e6);
        vf_check(ctx, "dent_finest_closer", "finest grid's distance to the extrapolated dent / "
                 "coarsest grid's", "convergence", 0, fabs(ds[m - 1] - d0) / fabs(ds[0] - d0),
                 0.5, VF_MAX);
        vf_text(ctx, "Observed order of the residual dent: %.2f (grids dx/a = %.3f, %.3f, %.3f); "
                     "extrapolated dent %.4f um.", q, h[0], h[1], h[2], d0 * 1e6);
    } else if (m == 2) {
        vf_check(ctx, "dent_rises", "dent of the finer grid / coarser (the dossier: rising "
                 "towards about 0.25 um)", "dossier §2.6 trend", 1.076, ds[1] / ds[0], 0.01,
                 VF_REL);
        vf_text(ctx, "Fast variant: two grids, no order (the full variant has four).");
    }
    vf_text(ctx,
            "Scene: rigid sphere R = 15 mm on a Swift half-space (B = 1280 MPa, C = 4, n = 0.095, "
            "sigma_y(0) = 1460 MPa; E = 210 GPa, nu = 0.3), W = 2000 N in 8 load steps, domain "
            "3.2a x 3.2a with plastic cells under every column down to 1.2a; grids n^2 x nz as "
            "in the table of swift.csv. The dossier warns that p_eq at 1.2a is still about 4e-5 "
            "(1.5a would be deeper than needed for the regression, but the dent of the "
            "converged physics wants it); the regression keeps the dossier's 1.2a.");
    vf_plot(ctx, "dent_convergence.png", "Residual dent against the mesh: ours and the dossier's "
            "reference loop",
            "set datafile separator ','\nset grid\nset key bottom right\n"
            "set xlabel 'dx / a'\nset ylabel 'residual dent [um]'\n"
            "plot 'swift.csv' every ::1 using 3:8 with linespoints pt 7 title 'microcontact', "
            "'' every ::1 using 3:($12 > 0 ? $12 : 1/0) with points pt 6 ps 2 title "
            "'dossier reference loop'");
    return 0;
}
