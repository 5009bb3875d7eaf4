/* mesh_convergence.c - suite `mesh_convergence`: the mesh study of the paper's Fig. 2-4 (stress
 * against depth at a contact point, and the plastic surface deformation, for dx = dy = 2.0, 1.6,
 * 1.2, 0.8 and 0.4 um; the paper: comparable from 0.8 um on, too small on a coarse mesh), with
 * the minimum evaluation depth that a point-force kernel would have on each mesh (Fig. 2-3;
 * docs/theory.md §5.6; elastic.md 3.6).
 *
 * The surface is defined continuously: a section of 24 um x 24 um carrying Gaussian asperities
 * h_k exp(-r^2 / 2 s_k^2) at fixed positions (a table below: four tall ones on a jittered 12 um
 * lattice, three of which touch at the load, and four lower ones that stay out of contact),
 * evaluated at each mesh's cell centres, so every mesh samples the same surface (24 um is a whole
 * number of cells of every mesh). A rigid flat presses it with a fixed force; body 1 is
 * elastic-perfectly plastic steel.
 * Each mesh runs the elastic-plastic stage (pipeline/stage_plastic.h) through verify/topo_run.h,
 * and its elastic contact pressure at the full load gives the stress against depth under one
 * fixed point (the finest mesh's cell of the highest pressure) by direct sums of the closed-form
 * rectangle kernels (exact for each mesh's piecewise-constant pressure at any point and depth),
 * and of point forces for the minimum evaluation depth.
 *
 * Measured per mesh: the von Mises maximum under the point and its depth; the residual surface
 * displacement after unloading (its maximum, its positive volume, the profile through the point),
 * the largest equivalent plastic strain, the integrated plastic strain (int p dV) and the
 * plastic volume. Convergence: differences to the finest mesh, the observed order from the
 * three meshes that halve (1.6, 0.8, 0.4), and the Richardson estimate of the mesh limit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "harness.h"
#include "kernels/invariants.h"
#include "kernels/kernel.h"
#include "pipeline/pipeline.h"
#include "suites.h"
#include "topo_run.h"
#include "vutil.h"

#define UM 1e-6
#define SIDE (24 * UM) /* section side: 12, 15, 20, 30, 60 cells */
#define E1 210e9
#define NU 0.30
#define LOAD 0.10    /* N: three of the tall asperities touch, elastic p_max 2.0 GPa */
#define YIELD 0.7e9  /* EPP: the elastic von Mises peak under the point is 1.73 Y */
#define DEPTH (4.8 * UM) /* plastic volume: 12 dz at 0.4 um (checked: nothing yields in the
                          * deepest layer of any mesh) */
#define MAX_OUTER 60 /* outer iterations per load step (the key's default is 30) */

/* The asperities: centre x, y (um), width s (um), height h (um). */
static const double asperity[][4] = {
    /* the tall ones (a jittered 12 um lattice); the lowest, the last, stays out of contact */
    {-7.321, -6.295, 4.010, 0.1400},
    {-6.501, 4.882, 4.837, 0.1509},
    {5.037, -5.367, 4.733, 0.1551},
    {6.928, 6.171, 4.288, 0.1381},
    /* lower ones at the lattice's edge midpoints (roughness that stays out of contact: the
     * check `patches` counts the contact patches of every mesh) */
    {-0.8, -10.6, 2.6, 0.030},
    {10.4, -0.6, 2.4, 0.028},
    {-10.5, 0.9, 2.5, 0.032},
    {0.6, 10.5, 2.3, 0.029},
};
#define NASP ((int)(sizeof asperity / sizeof asperity[0]))

static double surface_height(double x, double y)
{
    double h = 0;
    for (int k = 0; k < NASP; k++) {
        double dx = x / UM - asperity[k][0], dy = y / UM - asperity[k][1], s = asperity[k][2];
        h += asperity[k][3] * exp(-(dx * dx + dy * dy) / (2 * s * s));
    }
    return h * UM;
}

/* Tolerances (from the measured convergence; the report lists every number).
 * TOL_VM: the elastic von Mises maximum under the point on 0.8 um against 0.4 um: the patch
 *   kernels are exact for each mesh's pressure, whose error is the O(dx^2) pixelation of the
 *   contact (elastic.md 6.2: the Hertz p_max errs by 0.05-0.065 (dx/a)^2, ~0.6 % at a ~ 2.5 um and
 *   0.8 um); the sampled summit (up to dx/sqrt2 off a cell centre) adds a random O(dx^2) part of
 *   the same size. Measured 0.4 %; allowed 2 %. TOL_CURVE: the whole curve deeper than Z_CURVE
 *   (nearer the surface the meshes' piecewise-constant pressures differ by their steps, a
 *   first-order effect that fades with depth): measured 0.6 % of the maximum; allowed 3 %. The
 *   fast variant compares 1.2 um with 0.8 um: measured 5.1 %, allowed TOL_CURVE_FAST = 10 %.
 * TOL_VP: the plastic volume (cells that yielded): its boundary follows the elastic stress and is
 *   quantised by one layer of cells; measured 0.05 % (0.8 um), 2.6 % (1.2 and 1.6 um); 5 %, and
 *   never below TOL_VP_CELLS cells of the coarser mesh (the fast variant's volume is ~18 cells of
 *   1.2 um: one cell is 5.6 %, measured 4.2 % with centre values and 5.6 % with cell averages,
 *   theory.md §8.7).
 * TOL_PLASTIC: the deformation measures (largest residual displacement, dent volume, int p dV)
 *   do not converge with a clear order on these meshes: between 1.6, 1.2, 0.8 and 0.4 um they
 *   scatter by up to 12 % (0.8 against 0.4 um: 8-12 %; fast variant, 1.2 against 0.8 um: 3-13 %),
 *   because yield responds to the excess of the von Mises stress over Y (sigma_vM ~ 1.7 Y: a
 *   stress error e becomes ~2.4 e in the plastic strain) and the plastic zone, about two 0.8 um
 *   cells thick, is resolved by cell-centre values of an EPP strain field with a sharp boundary.
 *   The iteration contributes < 0.4 % (outer tolerance 1e-5, 20 load steps and a fixed point of
 *   1e-6 moved the 0.8, 1.2 and 2.0 um measures by less, measured once). Allowed 20 %: the checks
 *   catch a broken plastic stage (a missing or doubled residual displacement), not an order.
 *   TOL_PEQ: the largest plastic strain is one cell's value: measured 9 % (0.8 against 0.4 um) and
 *   19 % (1.2 against 0.8 um); 30 %.
 * Z_LATTICE: the point kernel's lattice artefact against the uniform-lattice analysis
 *   (theory.md §5.6, leading term 1.307 dx at eps = 1 %, 1.591 dx at 0.2 %): under a contact
 *   whose pressure varies over a few cells it is modulated by the neighbouring pressures;
 *   measured <= 0.055 dx on the meshes with a / dx >= 3 (0.8, 0.4 um), 0.67 dx on 1.6 um. Allowed
 *   0.1 dx on 0.8 um and finer, reported for all. */
#define TOL_VM 0.02
#define TOL_CURVE 0.03
#define TOL_CURVE_FAST 0.10
#define Z_CURVE (0.2 * UM)
#define TOL_VP 0.05
#define TOL_VP_CELLS 1.5
#define TOL_PLASTIC 0.20
#define TOL_PEQ 0.30
#define Z_LATTICE 0.1

#define NMESH_MAX 5
static const double mesh_full[] = {2.0, 1.6, 1.2, 0.8, 0.4};
static const double mesh_fast[] = {2.0, 1.2, 0.8};

/* the stress-depth curve: z = 0.02 ... 6 um by 0.02 um */
#define NZC 300
static double zc(int k) { return 0.02 * (k + 1) * UM; }

/* point-kernel scan: z = 0.30 ... 4.00 dx by 0.01 dx */
#define NZP 371
static double zp(int k, double dx) { return (0.30 + 0.01 * k) * dx; }

#define NEPS 2
static const double eps_list[NEPS] = {1e-2, 2e-3};
static const double lattice[NEPS] = {1.307, 1.591}; /* theory.md §5.6 leading term */

enum { Q_VM, Q_ZVM, Q_URMAX, Q_DENTVOL, Q_PEQ, Q_PEQINT, Q_VP, Q_PMAX, Q_AREA, NQ };
static const char *q_id[NQ] = {"vm_max",  "vm_depth", "residual_max", "dent_volume", "peq_max",
                               "peq_integral", "plastic_volume", "p_max", "contact_area"};
static const char *q_label[NQ] = {
    "elastic von Mises maximum under the point",  "its depth",
    "largest residual displacement",              "dent volume (positive residual displacement)",
    "largest equivalent plastic strain",          "integrated plastic strain, int p dV",
    "plastic volume (cells that yielded)",        "elastic p_max",
    "elastic contact area"};
static const char *q_unit[NQ] = {"MPa", "um", "nm", "um^3", "-", "um^3", "um^3", "MPa", "um^2"};
static const double q_scale[NQ] = {1e-6, 1e6, 1e9, 1e18, 1, 1e18, 1e18, 1e-6, 1e12};

typedef struct {
    double dx;
    int n;
    double q[NQ];
    double vm[NZC], szz[NZC];              /* at the point */
    double zmin[2][NEPS];                  /* z_min / dx of the lattice artefact, and of the
                                            * whole point-minus-patch difference on the node */
    double smooth;                         /* largest smooth part below 1.5 dx, / p */
    double pnode, pcorner;                 /* local pressures there */
    double bottom;                         /* largest plastic strain in the deepest layer */
    int converged, outer, nz, patches;
    double time;
    double *prof_x, *prof_u;               /* row through the point */
} mesh_t;

/* z_min / dx: the depth below which |err| stays <= eps (err sampled at zp), interpolated
 * log-linearly between the last layer above eps and the next; NAN if the scan never gets inside,
 * the first depth if it starts inside. */
static double zmin_scan(const double *err, double eps, double dx)
{
    int last = -1;
    for (int k = 0; k < NZP; k++)
        if (!(fabs(err[k]) <= eps)) /* a NaN error is not inside eps */
            last = k;
    if (last == NZP - 1)
        return NAN;
    if (last < 0)
        return zp(0, dx) / dx;
    double e0 = fabs(err[last]), e1 = fabs(err[last + 1]);
    double f = e1 > 0 ? log(e0 / eps) / log(e0 / e1) : 1.0;
    return (zp(last, dx) + f * (zp(last + 1, dx) - zp(last, dx))) / dx;
}

/* Point kernel minus patch kernel for sigma_zz at (x, y), relative to p_local, at zp. */
static void point_minus_patch(const mc_grid *g, const double *p, double x, double y,
                              double p_local, double *err)
{
    double z[NZP], spt[NZP * 6], spa[NZP * 6];
    for (int k = 0; k < NZP; k++)
        z[k] = zp(k, g->dx);
    vt_stress_at(g, p, NU, 1, x, y, z, NZP, spt);
    vt_stress_at(g, p, NU, 0, x, y, z, NZP, spa);
    for (int k = 0; k < NZP; k++)
        err[k] = (spt[6 * k + MC_SZZ] - spa[6 * k + MC_SZZ]) / p_local;
}

static int run_mesh(mesh_t *m, int have_point, double *px, double *py, mc_error *err)
{
    const int n = (int)lround(SIDE / (m->dx * UM));
    m->n = n;
    mc_scene sc;
    vu_scene(&sc, n, n, m->dx * UM, m->dx * UM);
    sc.body1 = (mc_scene_material){E1, NU, 0};
    sc.body2 = (mc_scene_material){E1, NU, 1}; /* rigid flat */
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = LOAD;
    sc.solver.tolerance = 1e-10;
    sc.plasticity.enabled = 1;
    sc.plasticity.criterion = MC_CRITERION_VON_MISES;
    sc.plasticity.hardening = MC_HARDENING_PERFECT;
    sc.plasticity.yield_stress = YIELD;
    sc.plasticity.depth = DEPTH;
    sc.plasticity.max_outer = MAX_OUTER;
    const mc_grid *g = &sc.grid;
    const size_t cells = (size_t)n * n;
    double *h = mc_zeros(cells), *pel = mc_zeros(cells);
    m->prof_x = calloc((size_t)n, sizeof(double));
    m->prof_u = calloc((size_t)n, sizeof(double));
    if (!h || !pel || !m->prof_x || !m->prof_u) {
        mc_free(h);
        mc_free(pel);
        return mc_fail(err, MC_ERR_NOMEM, "mesh_convergence: out of memory");
    }
    /* the gap: a fixed reference level minus the heights, so that every mesh has the same
     * approach datum (the largest height of the asperity table is below 0.3 um) */
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            h[(size_t)j * n + i] = 0.3 * UM - surface_height(mc_grid_x(g, i), mc_grid_y(g, j));
    mc_results res;
    int rc = vt_run_topography(&sc, h, &res, pel, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED) {
        mc_results_free(&res);
        mc_free(h);
        mc_free(pel);
        return rc;
    }
    m->time = res.timing.total_s;
    m->converged = res.plastic.converged;
    m->outer = res.plastic.outer_iterations;
    m->nz = res.plastic.nz;
    m->patches = vt_count_patches(g, pel);
    /* elastic measures */
    size_t kmax = vu_argmax(pel, cells);
    if (!have_point) {
        *px = mc_grid_x(g, (int)(kmax % n));
        *py = mc_grid_y(g, (int)(kmax / n));
    }
    m->q[Q_PMAX] = pel[kmax];
    long nc = 0;
    for (size_t s = 0; s < cells; s++)
        nc += pel[s] > 0;
    m->q[Q_AREA] = nc * g->dx * g->dy;
    {
        double z[NZC], s6[NZC * 6];
        for (int k = 0; k < NZC; k++)
            z[k] = zc(k);
        vt_stress_at(g, pel, NU, 0, *px, *py, z, NZC, s6);
        int kb = 0;
        for (int k = 0; k < NZC; k++) {
            m->vm[k] = mc_von_mises(s6 + 6 * k);
            m->szz[k] = s6[6 * k + MC_SZZ];
            if (m->vm[k] > m->vm[kb])
                kb = k;
        }
        m->q[Q_VM] = m->vm[kb];
        m->q[Q_ZVM] = z[kb];
        if (kb > 0 && kb < NZC - 1)
            m->q[Q_ZVM] += vu_parabola_peak(m->vm[kb - 1], m->vm[kb], m->vm[kb + 1],
                                            0.02 * UM, &m->q[Q_VM]);
    }
    /* the point kernel on the cell centre nearest the point (a node of the force lattice) and
     * on the cell corner diagonally next to it: point minus patch splits into the lattice
     * artefact, which has opposite signs at a node and a corner (theory.md §5.6: 1 +- 4(1 + t)
     * e^-t), and a smooth O(dx^2) difference of the two quadratures of the same pressure, which
     * is the same at both; half their difference is the artefact, half their sum the rest */
    {
        int in = (int)floor(*px / g->dx + 0.5 * n), jn = (int)floor(*py / g->dy + 0.5 * n);
        in = in < 1 ? 1 : in > n - 2 ? n - 2 : in;
        jn = jn < 1 ? 1 : jn > n - 2 ? n - 2 : jn;
        const double xn = mc_grid_x(g, in), yn = mc_grid_y(g, jn);
        const int si = *px >= xn ? 1 : -1, sj = *py >= yn ? 1 : -1; /* towards the point */
        const int ic = in + (si > 0), jc = jn + (sj > 0); /* corner between in, in+si, ... */
        m->pnode = pel[(size_t)jn * n + in];
        m->pcorner = 0.25 * (pel[(size_t)jc * n + ic] + pel[(size_t)jc * n + ic - 1] +
                             pel[(size_t)(jc - 1) * n + ic] + pel[(size_t)(jc - 1) * n + ic - 1]);
        double en[NZP], ec[NZP], art[NZP];
        point_minus_patch(g, pel, xn, yn, m->pnode, en);
        point_minus_patch(g, pel, (ic - 0.5 * n) * g->dx, (jc - 0.5 * n) * g->dy, m->pcorner, ec);
        m->smooth = 0;
        for (int k = 0; k < NZP; k++) {
            art[k] = 0.5 * (en[k] - ec[k]);
            if (zp(k, g->dx) >= 1.5 * g->dx)
                m->smooth = vf_worst(m->smooth, fabs(0.5 * (en[k] + ec[k])));
        }
        for (int e = 0; e < NEPS; e++) {
            m->zmin[0][e] = zmin_scan(art, eps_list[e], g->dx);
            m->zmin[1][e] = zmin_scan(en, eps_list[e], g->dx);
        }
    }
    /* plastic measures */
    const int nz = res.plastic.nz;
    const double dV = g->dx * g->dy * res.plastic.dz;
    m->q[Q_URMAX] = m->q[Q_DENTVOL] = m->q[Q_PEQ] = m->q[Q_PEQINT] = m->q[Q_VP] = 0;
    for (size_t s = 0; s < cells; s++) {
        double u = res.residual_displacement[s];
        m->q[Q_URMAX] = vf_worst(m->q[Q_URMAX], u);
        m->q[Q_DENTVOL] += fmax(u, 0.0) * g->dx * g->dy;
    }
    m->bottom = 0;
    for (int l = 0; l < nz && res.plastic_strain; l++)
        for (size_t s = 0; s < cells; s++) {
            double e = res.plastic_strain[(size_t)l * cells + s];
            m->q[Q_PEQ] = vf_worst(m->q[Q_PEQ], e);
            m->q[Q_PEQINT] += e * dV;
            m->q[Q_VP] += e > 0 ? dV : 0;
            if (l == nz - 1)
                m->bottom = vf_worst(m->bottom, e);
        }
    int jrow = (int)floor(*py / g->dy + 0.5 * n);
    jrow = jrow < 0 ? 0 : jrow >= n ? n - 1 : jrow;
    for (int i = 0; i < n; i++) {
        m->prof_x[i] = mc_grid_x(g, i);
        m->prof_u[i] = res.residual_displacement[(size_t)jrow * n + i];
    }
    mc_results_free(&res);
    mc_free(h);
    mc_free(pel);
    return MC_OK;
}

int vf_suite_mesh_convergence(vf_ctx *ctx, int fast)
{
    const double *list = fast ? mesh_fast : mesh_full;
    const int nm = fast ? 3 : 5;
    mesh_t m[NMESH_MAX];
    memset(m, 0, sizeof m);
    mc_error err = {0};
    double px = 0, py = 0, t_all = mc_clock();
    int rc = MC_OK;
    /* the finest mesh first: it fixes the point */
    for (int q = nm - 1; q >= 0 && rc == MC_OK; q--) {
        m[q].dx = list[q];
        rc = run_mesh(&m[q], q < nm - 1, &px, &py, &err);
        if (rc == MC_OK) {
            printf("   dx = %.1f um: %d^2 x %d, %.1f s, %d outer iterations%s\n", m[q].dx,
                   m[q].n, m[q].nz, m[q].time, m[q].outer,
                   m[q].converged ? "" : " (not converged)");
            fflush(stdout);
        }
    }
    t_all = mc_clock() - t_all;
    if (rc != MC_OK) {
        vf_fail(ctx, "run", "%s", err.msg);
        for (int q = 0; q < nm; q++) {
            free(m[q].prof_x);
            free(m[q].prof_u);
        }
        return 0;
    }
    const mesh_t *fine = &m[nm - 1];
    const double dxf = fine->dx;

    /* ---- the runs ---- */
    int notconv = 0, patch_bad = 0;
    double bottom = 0;
    for (int q = 0; q < nm; q++) {
        notconv += !m[q].converged;
        patch_bad += m[q].patches != fine->patches;
        bottom = vf_worst(bottom, m[q].bottom);
    }
    vf_check(ctx, "converged", "meshes whose elastic-plastic run did not converge",
             "stage_plastic: converged", 0, notconv, 0, VF_MAX);
    vf_check(ctx, "depth_sufficient",
             "largest plastic strain in the deepest layer of the plastic volume, all meshes",
             "the plastic zone ends above 4.8 um", 0, bottom, 0, VF_MAX);
    vf_check(ctx, "patches",
             "meshes whose elastic contact has another number of patches than the finest mesh "
             "(three: one per touching asperity)",
             "the same surface on every mesh", 0, patch_bad, 0, VF_MAX);

    /* ---- convergence of each measure against the finest mesh ---- */
    double rel[NQ][NMESH_MAX], order[NQ], rich[NQ], curve[NMESH_MAX] = {0};
    const int i16 = fast ? -1 : 1, i08 = fast ? 2 : 3;
    for (int k = 0; k < NQ; k++) {
        for (int q = 0; q < nm; q++)
            rel[k][q] = (m[q].q[k] - fine->q[k]) / fine->q[k];
        order[k] = rich[k] = NAN;
        if (i16 >= 0) { /* 1.6, 0.8, 0.4 halve */
            double d1 = m[i16].q[k] - m[i08].q[k], d2 = m[i08].q[k] - fine->q[k];
            if (d1 != 0 && d2 != 0 && d1 / d2 > 0)
                order[k] = log(d1 / d2) / log(2.0);
            if (order[k] > 0.5)
                rich[k] = fine->q[k] + d2 / (pow(2.0, order[k]) - 1);
        }
    }
    const char *fname = fast ? "0.8" : "0.4";
    const char *mname = fast ? "1.2" : "0.8";
    const int imid = fast ? 1 : 3; /* the mesh compared with the finest */
    {
        /* the measure, its tolerance against the finest mesh, and whether the coarsest mesh must
         * be the farther from it (only where the convergence is monotone: see TOL_*) */
        const int kq[] = {Q_VM, Q_VP, Q_PEQINT, Q_DENTVOL, Q_URMAX, Q_PEQ};
        const double tol[] = {TOL_VM, TOL_VP, TOL_PLASTIC, TOL_PLASTIC, TOL_PLASTIC, TOL_PEQ};
        const int coarse[] = {1, 1, 0, 0, 0, 0};
        for (int a = 0; a < 6; a++) {
            const int k = kq[a];
            char id[64], qn[240], ref[96];
            snprintf(id, sizeof id, "%s_%s_vs_%s", q_id[k], mname, fname);
            snprintf(qn, sizeof qn, "%s: %s um mesh against %s um, relative difference",
                     q_label[k], mname, fname);
            snprintf(ref, sizeof ref, "the %s um mesh", fname);
            /* the plastic volume is a count of cells: no finer than one cell of the coarser
             * mesh (dz = dx / 2) against the finest mesh's volume (TOL_VP) */
            const double cell = m[imid].dx * m[imid].dx * 0.5 * m[imid].dx;
            const double t = k == Q_VP ? fmax(tol[a], TOL_VP_CELLS * cell / fine->q[Q_VP]) : tol[a];
            vf_check(ctx, id, qn, ref, 0, fabs(rel[k][imid]), t, VF_MAX);
            if (!coarse[a])
                continue;
            snprintf(id, sizeof id, "%s_coarse_farther", q_id[k]);
            snprintf(qn, sizeof qn,
                     "%s: |%s um - %s um| / |2.0 um - %s um| (below 1: the coarsest mesh is "
                     "the farther from the finest)",
                     q_label[k], mname, fname, fname);
            vf_check(ctx, id, qn, "convergence", 1.0,
                     fabs(rel[k][imid]) / fmax(fabs(rel[k][0]), 1e-300), 1.0, VF_MAX);
        }
        /* the whole stress-depth curve below the near-surface layer, where the piecewise-
         * constant pressures of the meshes differ by their steps (first order) */
        for (int q = 0; q < nm - 1; q++) {
            double worst = 0;
            for (int k = 0; k < NZC; k++)
                if (zc(k) >= Z_CURVE)
                    worst = vf_worst(worst, fabs(m[q].vm[k] - fine->vm[k]));
            curve[q] = worst / fine->q[Q_VM];
            char id[64], qn[240];
            snprintf(id, sizeof id, "curve_%.1f", m[q].dx);
            snprintf(qn, sizeof qn,
                     "stress-depth curve on %.1f um against %s um: largest |von Mises "
                     "difference| below 0.2 um / the maximum",
                     m[q].dx, fname);
            if (q == imid)
                vf_check(ctx, id, qn, "the finest mesh", 0, curve[q],
                         fast ? TOL_CURVE_FAST : TOL_CURVE, VF_MAX);
            else
                vf_info(ctx, id, qn, "the finest mesh", NAN, curve[q]);
        }
    }
    for (int k = 0; k < NQ; k++) {
        char id[64], qn[240];
        for (int q = 0; q < nm - 1; q++) {
            snprintf(id, sizeof id, "%s_rel_%.1f", q_id[k], m[q].dx);
            snprintf(qn, sizeof qn, "%s on %.1f um relative to %s um", q_label[k], m[q].dx,
                     fname);
            vf_info(ctx, id, qn, "finest mesh", NAN, rel[k][q]);
        }
        if (!fast) {
            snprintf(id, sizeof id, "%s_order", q_id[k]);
            snprintf(qn, sizeof qn, "%s: observed order from 1.6, 0.8, 0.4 um%s", q_label[k],
                     isnan(order[k]) ? " (undefined, nan: the differences change sign or do "
                                       "not shrink)" : "");
            vf_info(ctx, id, qn, "2 for the smooth elastic part", NAN, order[k]);
        }
    }

    /* ---- the minimum evaluation depth of the point kernel ---- */
    double zworst = 0;
    for (int q = 0; q < nm; q++) {
        for (int e = 0; e < NEPS; e++) {
            char id[64], qn[240];
            snprintf(id, sizeof id, "zmin_%g_%.1f", 100 * eps_list[e], m[q].dx);
            snprintf(qn, sizeof qn,
                     "point kernel, lattice artefact below eps = %g %% of p from z_min / dx = "
                     "(on %.1f um)",
                     100 * eps_list[e], m[q].dx);
            vf_info(ctx, id, qn, "uniform lattice (theory.md §5.6)", lattice[e], m[q].zmin[0][e]);
            snprintf(id, sizeof id, "zmin_total_%g_%.1f", 100 * eps_list[e], m[q].dx);
            snprintf(qn, sizeof qn,
                     "point minus patch kernel on the node, below eps = %g %% of p from z / dx = "
                     "(on %.1f um)%s",
                     100 * eps_list[e], m[q].dx,
                     isnan(m[q].zmin[1][e]) ? " (nan: not below eps within the evaluated depths)"
                                            : "");
            vf_info(ctx, id, qn, "artefact plus the smooth quadrature difference", NAN,
                    m[q].zmin[1][e]);
            if (m[q].dx <= 0.8 + 1e-9) {
                double d = fabs(m[q].zmin[0][e] - lattice[e]);
                zworst = vf_worst(zworst, d);
            }
        }
        char id[64], qn[200];
        snprintf(id, sizeof id, "smooth_%.1f", m[q].dx);
        snprintf(qn, sizeof qn,
                 "point minus patch, smooth part below 1.5 dx, largest |.| / p (on %.1f um)",
                 m[q].dx);
        vf_info(ctx, id, qn, "O((dx/z)^2) quadrature difference", NAN, m[q].smooth);
    }
    vf_check(ctx, "zmin_lattice",
             "point kernel: worst |z_min / dx - lattice value| of the lattice artefact on the "
             "meshes of 0.8 um and finer (eps = 1 % and 0.2 %)",
             "theory.md §5.6: 1.307, 1.591", 0, zworst, Z_LATTICE, VF_MAX);
    const double zvm = fine->q[Q_ZVM];
    int resolved = 0;
    for (int q = 0; q < nm; q++)
        resolved += m[q].zmin[0][1] * m[q].dx * UM < zvm;

    for (int q = 0; q < nm; q++) {
        char id[64];
        snprintf(id, sizeof id, "time_%.1f", m[q].dx);
        vf_info(ctx, id, "run time of the mesh (elastic-plastic stage), s", "", NAN, m[q].time);
        vf_regress(ctx, id, VF_TIER_NONE);
    }

    /* ---- report ---- */
    vf_text(ctx,
            "**Scene.** A 24 um x 24 um section with %d Gaussian asperities (table in "
            "`surface.csv`; four of them are 4.0-4.8 um wide and 0.14-0.16 um high, and three "
            "of those touch), sampled at the cell centres of each mesh; a rigid flat presses it "
            "with %.2f N. Body 1: E = %.0f GPa, nu = %.2f, elastic-perfectly plastic with Y = %.0f "
            "MPa; plastic volume down to %.1f um in layers dz = dx / 2; 10 load steps, then "
            "unloading. The stress-depth curves are taken under the point (%.2f, %.2f) um, the "
            "cell of the highest elastic pressure on the %.1f um mesh.\n\n",
            NASP, LOAD, E1 / 1e9, NU, YIELD / 1e6, DEPTH / UM, px / UM, py / UM, dxf);
    vf_text(ctx, "### Measures per mesh\n\n| measure | unit |");
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %.1f um |", m[q].dx);
    if (!fast)
        vf_text(ctx, " order | Richardson |");
    vf_text(ctx, "\n|---|---|");
    for (int q = 0; q < nm + (fast ? 0 : 2); q++)
        vf_text(ctx, "---|");
    vf_text(ctx, "\n");
    for (int k = 0; k < NQ; k++) {
        vf_text(ctx, "| %s | %s |", q_label[k], q_unit[k]);
        for (int q = 0; q < nm; q++)
            vf_text(ctx, " %.4g |", m[q].q[k] * q_scale[k]);
        if (!fast)
            vf_text(ctx, " %.2f | %.4g |", order[k], rich[k] * q_scale[k]);
        vf_text(ctx, "\n");
    }
    vf_text(ctx, "| relative to %s um: residual max | |", fname);
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %+.1f %% |", 100 * rel[Q_URMAX][q]);
    vf_text(ctx, fast ? "\n" : " | |\n");
    vf_text(ctx, "| relative to %s um: int p dV | |", fname);
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %+.1f %% |", 100 * rel[Q_PEQINT][q]);
    vf_text(ctx, fast ? "\n" : " | |\n");
    vf_text(ctx, "| point kernel z_min / dx, node, 1 %% / 0.2 %% | |");
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %.2f / %.2f |", m[q].zmin[0][0], m[q].zmin[0][1]);
    vf_text(ctx, fast ? "\n" : " | |\n");
    vf_text(ctx, "| point kernel z_min, node, 0.2 %% | um |");
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %.2f |", m[q].zmin[0][1] * m[q].dx);
    vf_text(ctx, fast ? "\n" : " | |\n");
    vf_text(ctx, "| elastic contact patches | |");
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %d |", m[q].patches);
    vf_text(ctx, fast ? "\n" : " | |\n");
    vf_text(ctx, "| outer iterations (all steps) | |");
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %d |", m[q].outer);
    vf_text(ctx, fast ? "\n" : " | |\n");
    vf_text(ctx, "| run time | s |");
    for (int q = 0; q < nm; q++)
        vf_text(ctx, " %.1f |", m[q].time);
    vf_text(ctx, fast ? "\n\n" : " | |\n\n");
    vf_text(ctx,
            "**The paper's 0.8 um.** On %s um the elastic von Mises maximum under the point "
            "differs from the %s um result by %+.2f %% (the whole curve below 0.2 um by at most "
            "%.2f %% of the maximum), the plastic volume by %+.2f %%, and the plastic surface "
            "deformation by %+.1f %% (largest residual displacement), %+.1f %% (dent volume) and "
            "%+.1f %% (int p dV). On 2.0 um: %+.2f %%, %+.1f %%, %+.1f %%, %+.1f %% and %+.1f "
            "%%; there the coarse sampling of the summits also moves the elastic p_max by "
            "%+.1f %% and the contact area by %+.0f %%. The deformation measures do not converge "
            "with a clear order on these meshes (the order column: only the elastic stress, the "
            "plastic volume and the contact area have one): they scatter by about 10 %% between "
            "neighbouring meshes, while the elastic stress has converged to a fraction of a per "
            "cent from 1.2 um on. The largest residual displacement relative to the finest "
            "mesh: ",
            mname, fname, 100 * rel[Q_VM][imid], 100 * curve[imid], 100 * rel[Q_VP][imid],
            100 * rel[Q_URMAX][imid], 100 * rel[Q_DENTVOL][imid], 100 * rel[Q_PEQINT][imid],
            100 * rel[Q_VM][0], 100 * rel[Q_VP][0], 100 * rel[Q_URMAX][0],
            100 * rel[Q_DENTVOL][0], 100 * rel[Q_PEQINT][0], 100 * rel[Q_PMAX][0],
            100 * rel[Q_AREA][0]);
    for (int q = 0; q < nm - 1; q++)
        vf_text(ctx, "%.1f um %+.0f %%%s", m[q].dx, 100 * rel[Q_URMAX][q],
                q < nm - 2 ? ", " : "");
    int smaller = 0;
    for (int q = 0; q < nm - 1; q++)
        smaller += rel[Q_URMAX][q] < 0;
    if (smaller == nm - 1)
        vf_text(ctx, ": smaller on every coarser mesh, as the paper finds the plastic deformation "
                     "too small on a coarse mesh.\n\n");
    else
        vf_text(ctx, ": the paper's \"too small on a coarse mesh\" holds on %d of the %d coarser "
                     "meshes.\n\n",
                smaller, nm - 1);
    vf_text(ctx,
            "**Minimum evaluation depth.** A point-force kernel would be accurate to 0.2 %% only "
            "below %.2f dx (node) on the finest mesh, i.e. %.2f um at 0.8 um (the paper: "
            "1.3 um) and %.2f um at 2.0 um, while the von Mises maximum under the point lies at "
            "%.2f um: the point kernel resolves it on %d of the %d meshes. The patch kernels "
            "used here have no minimum depth (theory.md §5.6).\n\n",
            fine->zmin[0][1], fine->zmin[0][1] * 0.8, fine->zmin[0][1] * 2.0, zvm / UM, resolved,
            nm);
    vf_text(ctx, "Run time %.1f s in all.\n\n", t_all);

    FILE *f = vf_open(ctx, "surface.csv");
    if (f) {
        fprintf(f, "x_um,y_um,width_um,height_um\n");
        for (int k = 0; k < NASP; k++)
            fprintf(f, "%.3f,%.3f,%.3f,%.4f\n", asperity[k][0], asperity[k][1], asperity[k][2],
                    asperity[k][3]);
        vf_close(ctx, f);
    }
    if ((f = vf_open(ctx, "measures.csv"))) {
        fprintf(f, "dx_um,cells");
        for (int k = 0; k < NQ; k++)
            fprintf(f, ",%s", q_id[k]);
        fprintf(f, ",zmin_node_1pc,zmin_node_02pc,zmin_corner_1pc,zmin_corner_02pc,"
                   "outer_iterations,seconds\n");
        for (int q = 0; q < nm; q++) {
            fprintf(f, "%.1f,%d", m[q].dx, m[q].n);
            for (int k = 0; k < NQ; k++)
                fprintf(f, ",%.6g", m[q].q[k] * q_scale[k]);
            fprintf(f, ",%.4f,%.4f,%.4f,%.4f,%d,%.2f\n", m[q].zmin[0][0], m[q].zmin[0][1],
                    m[q].zmin[1][0], m[q].zmin[1][1], m[q].outer, m[q].time);
        }
        vf_close(ctx, f);
    }
    if ((f = vf_open(ctx, "stress_depth.csv"))) {
        fprintf(f, "dx_um,z_um,von_mises_MPa,szz_MPa\n");
        for (int q = 0; q < nm; q++) {
            for (int k = 0; k < NZC; k++)
                fprintf(f, "%.1f,%.3f,%.4f,%.4f\n", m[q].dx, zc(k) / UM, m[q].vm[k] * 1e-6,
                        m[q].szz[k] * 1e-6);
            fprintf(f, "\n\n"); /* gnuplot data blocks, one per mesh */
        }
        vf_close(ctx, f);
    }
    if ((f = vf_open(ctx, "profiles.csv"))) {
        fprintf(f, "dx_um,x_um,residual_nm\n");
        for (int q = 0; q < nm; q++) {
            for (int i = 0; i < m[q].n; i++)
                fprintf(f, "%.1f,%.4f,%.5f\n", m[q].dx, m[q].prof_x[i] / UM, m[q].prof_u[i] * 1e9);
            fprintf(f, "\n\n");
        }
        vf_close(ctx, f);
    }
    char script[2048];
    snprintf(script, sizeof script,
             "set datafile separator ','\nset xlabel 'depth z, um (paper: x)'\n"
             "set ylabel 'von Mises stress, MPa'\nset grid\nset key top right\n"
             "set xrange [0:6]\n"
             "plot for [i=0:%d] 'stress_depth.csv' index i using 2:3 with lines lw 2 "
             "title sprintf('dx = %%s um', word('%s', i+1)), "
             "%g with lines dt 2 lc rgb 'black' title 'Y'",
             nm - 1, fast ? "2.0 1.2 0.8" : "2.0 1.6 1.2 0.8 0.4", YIELD * 1e-6);
    vf_plot(ctx, "stress_depth.png",
            "Elastic von Mises stress against depth under the point of highest pressure, one "
            "curve per mesh (the paper's Fig. 2-4, left; the patch kernels are exact for each "
            "mesh's pressure, so the curves differ by the pressure's discretisation only)",
            script);
    snprintf(script, sizeof script,
             "set datafile separator ','\nset xlabel 'mesh size dx = dy, um'\n"
             "set ylabel 'relative to the finest mesh'\nset grid\nset key below\n"
             "set xrange [0:2.2]\n"
             "plot 'measures.csv' using 1:($5/%g) with linespoints pt 7 lw 2 "
             "title 'largest residual displacement', "
             "'' using 1:($6/%g) with linespoints pt 5 lw 2 title 'dent volume', "
             "'' using 1:($8/%g) with linespoints pt 9 title 'int p dV', "
             "'' using 1:($7/%g) with linespoints pt 11 title 'largest plastic strain', "
             "'' using 1:($9/%g) with linespoints pt 13 title 'plastic volume', "
             "'' using 1:($3/%g) with linespoints dt 2 pt 6 title 'elastic von Mises max', "
             "1 with lines dt 3 lc rgb 'black' notitle",
             fine->q[Q_URMAX] * q_scale[Q_URMAX], fine->q[Q_DENTVOL] * q_scale[Q_DENTVOL],
             fine->q[Q_PEQINT] * q_scale[Q_PEQINT], fine->q[Q_PEQ] * q_scale[Q_PEQ],
             fine->q[Q_VP] * q_scale[Q_VP], fine->q[Q_VM] * q_scale[Q_VM]);
    vf_plot(ctx, "plastic_vs_mesh.png",
            "Plastic surface deformation and plastic strain against the mesh size, relative to "
            "the finest mesh (the paper's Fig. 2-4, right)",
            script);
    snprintf(script, sizeof script,
             "set datafile separator ','\nset xlabel 'x, um'\n"
             "set ylabel 'residual displacement u_r (into the body), nm'\nset grid\n"
             "set key top left\n"
             "plot for [i=0:%d] 'profiles.csv' index i using 2:3 with linespoints pt 7 ps 0.5 "
             "title sprintf('dx = %%s um', word('%s', i+1))",
             nm - 1, fast ? "2.0 1.2 0.8" : "2.0 1.6 1.2 0.8 0.4");
    vf_plot(ctx, "profiles.png",
            "Residual surface displacement after unloading along the row through the point, "
            "one line per mesh",
            script);
    snprintf(script, sizeof script,
             "set datafile separator ','\nset xlabel 'mesh size dx, um'\n"
             "set ylabel 'depth, um'\nset grid\nset key top left\nset xrange [0:2.2]\n"
             "plot 'measures.csv' using 1:($1*$%d) with linespoints pt 7 lw 2 "
             "title 'point kernel z_{min}, 1 %%', "
             "'' using 1:($1*$%d) with linespoints pt 5 lw 2 title 'point kernel z_{min}, 0.2 %%', "
             "x*1.307 with lines dt 2 title '1.307 dx', x*1.591 with lines dt 2 title '1.591 dx', "
             "%g with lines dt 3 lc rgb 'black' title 'depth of the von Mises maximum', "
             "'-' with points pt 3 ps 2 lc rgb 'red' title 'paper: 1.3 um at 0.8 um'\n"
             "0.8,1.3\ne",
             3 + NQ, 4 + NQ, zvm / UM);
    vf_plot(ctx, "min_depth.png",
            "Minimum evaluation depth of a point-force kernel on each mesh (node column under "
            "the point, the rough contact's own pressure), against the depth of the von Mises "
            "maximum",
            script);
    for (int q = 0; q < nm; q++) {
        free(m[q].prof_x);
        free(m[q].prof_u);
    }
    return 0;
}
