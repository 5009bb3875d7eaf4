/* stage_plastic.c - the elastic-plastic stage of the pipeline (stage_plastic.h). */
#include "pipeline/stage_plastic.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "kernels/invariants.h"
#include "pipeline/memguard.h"
#include "pipeline/stage_lube.h"
#include "plastic/loop.h"
#include "stress/stress.h"
#include "stress/traction.h"

/* History depth of the Anderson acceleration of the loop (loop.h), dry or lubricated. Dry runs
 * mixed by the adaptive under-relaxation alone until issue 20; the Kogut-Etsion sphere at 8 P_c
 * in 16 steps (one thread; with the warm start of theory §9.6): 20^2 x 27 layers 1180 -> 281
 * sweeps (depth 8: 279), 32^2 x 43 1727 -> 314, w/w_c moved by 4e-5 (tol_outer 1e-3). */
#define MC_ANDERSON_DEPTH 4

/* The load of the scene on the grid, N: force, or force_per_length times the period along y (a
 * line contact: periodic y, ny = 1, as the elastic pipeline takes it). */
static double stage_load(const mc_scene *sc, const mc_grid *g)
{
    return sc->load.kind == MC_LOAD_FORCE_PER_LENGTH ? sc->load.value * g->ny * g->dy
                                                     : sc->load.value;
}

int mc_stage_plastic_law(const mc_scene *sc, mc_hardening *law, mc_error *err)
{
    const double unit[] = {1.0, 1e6, 1e9};
    const mc_hardening_params par = {.E = sc->body1.E,
                                     .yield_stress = sc->plasticity.yield_stress,
                                     .tangent_modulus = sc->plasticity.tangent_modulus,
                                     .swift_B = sc->plasticity.swift_B,
                                     .swift_C = sc->plasticity.swift_C,
                                     .swift_n = sc->plasticity.swift_n,
                                     .table = sc->plasticity.table,
                                     .table_unit = unit[sc->plasticity.table_unit]};
    return mc_hardening_build(sc->plasticity.hardening, &par, law, err);
}

int mc_stage_plastic_layer_maxima(const mc_scene *sc, const mc_grid *g, const double *p,
                                  double p_lub, const double *shape, const double *z, int nz,
                                  double *vm_layer, mc_error *err)
{
    const size_t n = mc_grid_cells(g);
    const double f = sc->plasticity.friction;
    mc_stress_options so = {.kernel = MC_STRESS_PATCH,
                            .nu = sc->body1.nu,
                            .nlayers = nz,
                            .depths = z,
                            .backend = sc->solver.backend,
                            .loads = MC_TRACTION_P | (f > 0 ? MC_TRACTION_QX : 0)};
    mc_stress_plan *plan = NULL;
    /* one layer at a time: nz layers of the whole grid would cost more than the plastic volume
     * itself (the probe reaches 3 contact half-widths, up to 256 layers) */
    double *s[6] = {0}, *qx = f > 0 ? mc_zeros(n) : NULL;
    int rc = mc_stress_create(g, &so, &plan, err);
    for (int c = 0; rc == MC_OK && c < 6; c++)
        if (!(s[c] = mc_zeros(n)))
            rc = mc_fail(err, MC_ERR_NOMEM, "plastic stage: out of memory for the depth probe");
    if (rc == MC_OK && f > 0 && !qx)
        rc = mc_fail(err, MC_ERR_NOMEM, "plastic stage: out of memory for the traction");
    if (rc == MC_OK && qx)
        mc_traction_friction(p, p_lub, shape, f, n, qx);
    for (int k = 0; rc == MC_OK && k < nz; k++) {
        if ((rc = mc_stress_layer(plan, k, p, qx, NULL, s, err)) != MC_OK)
            break;
        double m = 0;
        for (size_t i = 0; i < n; i++) {
            double t[6];
            for (int c = 0; c < 6; c++)
                t[c] = s[c][i];
            m = fmax(m, mc_von_mises(t));
        }
        vm_layer[k] = m;
    }
    for (int c = 0; c < 6; c++)
        mc_free(s[c]);
    mc_free(qx);
    mc_stress_destroy(&plan);
    return rc;
}

/* Depth and columns of the plastic volume from the elastic solution at the full load (lubricant
 * pressure p_lub). */
static int plan_volume(const mc_scene *sc, mc_results *res, double yield0, double p_lub,
                       mc_eigen_volume *v, mc_error *err)
{
    const mc_grid *g = &res->grid;
    mc_stage_plastic_summary *ps = &res->plastic;
    /* default min(dx, dy) / 2 (dx / 2 on a line grid, whose dy is no cell size): below the band
     * 0.6 < dz/dx < 1.6 where the residual stress operator's x-z (and y-z) checkerboard mode
     * releases energy and a perfectly plastic run locks into it (theory §8.5) */
    const int line = g->periodic_y && g->ny == 1;
    const double dz = sc->plasticity.dz > 0 ? sc->plasticity.dz
                      : line                ? 0.5 * g->dx
                                            : 0.5 * fmin(g->dx, g->dy);
    /* the contact's bounding box */
    int i0 = g->nx, i1 = -1, j0 = g->ny, j1 = -1;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++)
            if (res->pressure[(size_t)j * g->nx + i] >
                mc_traction_lubricant(p_lub, res->lube_profile, (size_t)j * g->nx + i)) {
                i0 = i < i0 ? i : i0;
                i1 = i > i1 ? i : i1;
                j0 = j < j0 ? j : j0;
                j1 = j > j1 ? j : j1;
            }
    if (i1 < 0) /* no solid contact: nothing can yield */
        i0 = i1 = g->nx / 2, j0 = j1 = g->ny / 2;
    double half = 0.5 * fmax((i1 - i0 + 1) * g->dx, (j1 - j0 + 1) * g->dy);
    /* depth: probe down to 3 contact half-widths (the von Mises maximum of a Hertz contact is at
     * 0.48a), keep the layers above half the initial yield stress, plus 25 % */
    double depth = sc->plasticity.depth;
    ps->depth_auto = !(depth > 0);
    ps->vm_elastic_max = 0;
    {
        int nprobe = (int)ceil(3.0 * fmax(half, dz) / dz);
        nprobe = nprobe < 2 ? 2 : nprobe > 256 ? 256 : nprobe;
        double *z = mc_zeros((size_t)nprobe), *vm = mc_zeros((size_t)nprobe);
        int rc = z && vm ? MC_OK
                         : mc_fail(err, MC_ERR_NOMEM, "plastic stage: out of memory for the probe");
        double step = 3.0 * fmax(half, dz) / nprobe;
        for (int k = 0; rc == MC_OK && k < nprobe; k++)
            z[k] = (k + 0.5) * step;
        if (rc == MC_OK)
            rc = mc_stage_plastic_layer_maxima(sc, g, res->pressure, p_lub, res->lube_profile, z,
                                               nprobe, vm, err);
        double deepest = 0;
        for (int k = 0; rc == MC_OK && k < nprobe; k++) {
            ps->vm_elastic_max = fmax(ps->vm_elastic_max, vm[k]);
            if (vm[k] > 0.5 * yield0)
                deepest = z[k] + 0.5 * step;
        }
        mc_free(z);
        mc_free(vm);
        if (rc != MC_OK)
            return rc;
        if (ps->depth_auto)
            depth = fmax(1.25 * deepest, 2 * dz);
    }
    int nz = (int)ceil(depth / dz - 1e-9);
    nz = nz < 1 ? 1 : nz;
    /* graded layers (theory.md §8.8): by default with depth = auto */
    const int graded = sc->plasticity.layering == MC_LAYERING_GRADED ||
                       (sc->plasticity.layering == MC_LAYERING_AUTO && ps->depth_auto);
    ps->layering = graded ? "graded" : "uniform";
    if (graded) {
        const double fine = sc->plasticity.fine_depth > 0 ? sc->plasticity.fine_depth
                            : line                        ? 8 * g->dx
                                                          : 8 * fmin(g->dx, g->dy);
        if (!(ps->group = mc_malloc((size_t)nz * sizeof *ps->group)))
            return mc_fail(err, MC_ERR_NOMEM, "plastic stage: out of memory for the layering");
        /* at most nz layers: every layer holds at least one dz */
        nz = mc_eigen_grade(dz, depth, fine, sc->plasticity.grading, ps->group, nz);
    }
    const mc_eigen_volume lay = {0, 0, 1, 1, nz, dz, MC_EIG_CELL_AVERAGE, ps->group,
                                 MC_EIG_KERNEL_CUBOID};
    const double vdepth = mc_eigen_volume_depth(&lay);
    double margin = sc->plasticity.margin > 0 ? sc->plasticity.margin : vdepth;
    int mx = (int)ceil(margin / g->dx - 1e-9), my = (int)ceil(margin / g->dy - 1e-9);
    i0 = i0 - mx < 0 ? 0 : i0 - mx;
    j0 = j0 - my < 0 ? 0 : j0 - my;
    i1 = i1 + mx >= g->nx ? g->nx - 1 : i1 + mx;
    j1 = j1 + my >= g->ny ? g->ny - 1 : j1 + my;
    /* along a periodic axis the volume is the whole period (theory.md §8.6) */
    if (g->periodic_x)
        i0 = 0, i1 = g->nx - 1;
    if (g->periodic_y)
        j0 = 0, j1 = g->ny - 1;
    /* the spectral kernel transforms the whole grid (theory.md §8.10) */
    if (sc->plasticity.kernel == MC_EIG_KERNEL_SPECTRAL)
        i0 = j0 = 0, i1 = g->nx - 1, j1 = g->ny - 1;
    *v = (mc_eigen_volume){i0,  j0, i1 - i0 + 1, j1 - j0 + 1, nz, dz, sc->plasticity.stress_points,
                           ps->group, sc->plasticity.kernel};
    ps->depth = vdepth;
    ps->dz = dz;
    ps->nz = nz;
    ps->i0 = i0;
    ps->j0 = j0;
    ps->wnx = v->nx;
    ps->wny = v->ny;
    ps->volume_cells = (long)nz * v->nx * v->ny;
    return MC_OK;
}

/* The window's volume fields placed on the whole grid (zeros outside the window). */
static void place(const mc_results *res, const mc_eigen_volume *v, const double *src, double *dst)
{
    const mc_grid *g = &res->grid;
    for (int k = 0; k < v->nz; k++)
        for (int j = 0; j < v->ny; j++)
            for (int i = 0; i < v->nx; i++)
                dst[((size_t)k * g->ny + (size_t)(j + v->j0)) * g->nx + (size_t)(i + v->i0)] =
                    src[((size_t)k * v->ny + j) * v->nx + i];
}

static int alloc_fields(mc_results *res, int nz, mc_error *err)
{
    const size_t n = mc_grid_cells(&res->grid);
    if (!(res->residual_displacement = mc_zeros(n)) || !(res->topography_final = mc_zeros(n)) ||
        !(res->plastic_strain = mc_zeros(n * (size_t)nz)) ||
        !(res->residual_von_mises = mc_zeros(n * (size_t)nz)))
        return mc_fail(err, MC_ERR_NOMEM, "plastic stage: out of memory for the outputs");
    return MC_OK;
}

/* criterion = pressure_cap: the capped elastic contact; where the pressure sits at the cap the
 * surface has penetrated the counter body, and that penetration is the permanent deformation. */
static int run_cap(const mc_scene *sc, mc_contact_solver *solver, mc_results *res, mc_error *err)
{
    mc_stage_plastic_summary *ps = &res->plastic;
    ps->criterion = "pressure_cap";
    ps->hardening = "";
    mc_contact_problem prob = {.h = res->topography,
                               .p_lub = fmax(sc->load.lubricant_pressure, 0.0),
                               .p_cap = sc->plasticity.hardness,
                               .control = MC_CONTROL_FORCE,
                               .load = stage_load(sc, &res->grid)};
    int rc = mc_contact_solve(solver, &prob, res->pressure, res->displacement, res->gap,
                              &res->contact, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    int arc = alloc_fields(res, 1, err);
    if (arc != MC_OK)
        return arc;
    const size_t n = mc_grid_cells(&res->grid);
    ps->residual_max = 0;
    for (size_t i = 0; i < n; i++) {
        double dent = res->pressure[i] >= sc->plasticity.hardness * (1 - 1e-12) && res->gap[i] < 0
                          ? -res->gap[i]
                          : 0.0;
        res->residual_displacement[i] = dent;
        res->topography_final[i] = res->topography[i] + dent;
        ps->residual_max = fmax(ps->residual_max, dent);
    }
    ps->nz = 1;
    ps->converged = rc == MC_OK;
    return rc;
}

int mc_stage_plastic(const mc_scene *sc, mc_operator *K, mc_contact_solver *solver,
                     mc_results *res, mc_error *err)
{
    mc_stage_plastic_summary *ps = &res->plastic;
    mc_free(ps->group);
    memset(ps, 0, sizeof *ps);
    ps->enabled = 1;
    if (sc->plasticity.criterion == MC_CRITERION_PRESSURE_CAP)
        return run_cap(sc, solver, res, err);
    ps->criterion = "von_mises";
    ps->hardening = mc_hardening_name(sc->plasticity.hardening);
    ps->stress_points = mc_eig_stress_points_name(sc->plasticity.stress_points);
    ps->kernel = mc_eig_kernel_name(sc->plasticity.kernel);
    ps->iteration = mc_plastic_iteration_name(sc->plasticity.iteration);
    ps->load_steps = sc->plasticity.load_steps;
    mc_hardening law;
    memset(&law, 0, sizeof law);
    int rc = mc_stage_plastic_law(sc, &law, err);
    if (rc != MC_OK) {
        mc_error_prefix(err, "[plasticity] ");
        return rc;
    }
    ps->yield_initial = mc_hardening_initial(&law);
    /* the elastic solve at the full load: the volume's depth and columns, and the shortcut;
     * lubricated, the volume equilibrium sets p_lub, at every contact of the loop too */
    const int lubricated = sc->load.lubricant_pressure == MC_LUBRICANT_AUTO;
    double p_lub = fmax(sc->load.lubricant_pressure, 0.0);
    mc_volume_result seed = {0}; /* the loop's first equilibrium starts from this one's root */
    if (lubricated) {
        rc = mc_stage_lube_seed(sc, K, solver, NULL, NULL, res, &seed, err);
        p_lub = res->lube.p_lub;
    } else {
        mc_contact_problem prob = {.h = res->topography,
                                   .p_lub = p_lub,
                                   .p_cap = INFINITY,
                                   .control = MC_CONTROL_FORCE,
                                   .load = stage_load(sc, &res->grid)};
        rc = mc_contact_solve(solver, &prob, res->pressure, res->displacement, res->gap,
                              &res->contact, err);
    }
    mc_eigen_volume v;
    if (rc == MC_OK)
        rc = plan_volume(sc, res, ps->yield_initial, p_lub, &v, err);
    const int shortcut = rc == MC_OK && ps->vm_elastic_max < ps->yield_initial;
    if (rc == MC_OK)
        rc = mc_memory_check_plastic(sc, &res->grid, &v, shortcut, err);
    /* the output fields (16 bytes per cell of the grid's depth) now only when nothing yields:
     * otherwise after the loop, which has then freed its operators (the run's peak is in it) */
    if (rc == MC_OK && shortcut)
        rc = alloc_fields(res, ps->nz, err);
    if (rc != MC_OK) {
        mc_hardening_free(&law);
        return rc;
    }
    const size_t n = mc_grid_cells(&res->grid);
    if (shortcut) { /* nothing yields: the elastic result stands */
        ps->elastic_shortcut = 1;
        ps->converged = 1;
        memcpy(res->topography_final, res->topography, n * sizeof *res->topography);
        mc_hardening_free(&law);
        return MC_OK;
    }
    /* seeded as the running-in's step is (pipeline/runin.c): the equilibrium just solved is the
     * same problem without plastic strain, and its pressure is still in res->pressure, which
     * the loop starts from */
    mc_stage_lube_contact lc = {.solver = solver,
                          .K = K,
                          .h_target = res->lube.h_ehd,
                          .weight = res->lube_profile,
                          .tolerance = sc->lubrication.tolerance,
                          .last = seed,
                          .seeded = lubricated};
    mc_plastic_problem pb = {.h = res->topography,
                             .load = lubricated ? res->lube.patch_load : stage_load(sc, &res->grid),
                             .contact = lubricated ? mc_stage_lube_contact_step : NULL,
                             .contact_ctx = &lc,
                             .lube_shape = lubricated ? res->lube_profile : NULL,
                             /* lubricated, p_lub moves with every outer iteration: Anderson
                              * mixing keeps the two-cycles of a flipping contact set from
                              * stalling it; dry, it cuts the sweeps 4-5 fold (theory §9.6) */
                             .anderson = MC_ANDERSON_DEPTH,
                             .p_lub = p_lub,
                             .friction = sc->plasticity.friction,
                             .load_steps = sc->plasticity.load_steps,
                             .E = sc->body1.E,
                             .nu = sc->body1.nu,
                             .law = &law,
                             .both = sc->plasticity.both,
                             .volume = v,
                             .backend = sc->solver.backend,
                             .relaxation = sc->plasticity.relaxation,
                             .tol_outer = sc->plasticity.tolerance,
                             .max_outer = sc->plasticity.max_outer,
                             .tol_plastic = sc->plasticity.plastic_tolerance,
                             .max_plastic = sc->plasticity.max_plastic,
                             .iteration = sc->plasticity.iteration,
                             .near_reach = sc->plasticity.near_field};
    mc_plastic_result pr;
    (void)K;
    rc = mc_plastic_run(&res->grid, K, solver, &pb, res->pressure, res->displacement, res->gap,
                        &res->contact, &pr, err);
    if (rc == MC_OK || rc == MC_NOT_CONVERGED) {
        const int arc = alloc_fields(res, ps->nz, err);
        if (arc != MC_OK) {
            mc_plastic_result_free(&pr);
            mc_hardening_free(&law);
            return arc;
        }
        const double factor = sc->plasticity.both ? 2.0 : 1.0;
        for (size_t i = 0; i < n; i++) {
            res->residual_displacement[i] = pr.u_r[i];
            res->topography_final[i] = res->topography[i] + factor * pr.u_r[i];
        }
        place(res, &v, pr.peq, res->plastic_strain);
        place(res, &v, pr.residual_vm, res->residual_von_mises);
        ps->converged = pr.converged;
        if (pr.stop_step > 0) {
            ps->stop_step = pr.stop_step;
            ps->stop_load = pr.stop_load;
            ps->stop_reason = mc_plastic_stop_text(pr.stop);
        }
        ps->steps_done = pr.steps_done;
        ps->steps = pr.steps;
        pr.steps = NULL;
        for (int s = 0; s < ps->steps_done; s++)
            ps->outer_iterations += ps->steps[s].outer_iterations;
        if (ps->steps_done > 0) {
            const mc_plastic_step *last = &ps->steps[ps->steps_done - 1];
            ps->peq_max = last->peq_max;
            memcpy(ps->peq_max_at, last->peq_at, sizeof ps->peq_max_at);
            ps->plastic_volume = last->plastic_volume;
        }
        ps->residual_max = 0;
        for (size_t i = 0; i < n; i++)
            ps->residual_max = fmax(ps->residual_max, pr.u_r[i]);
        if (lubricated && lc.calls > 0) { /* the figures of the last equilibrium */
            mc_error lerr = {0};
            int lrc = mc_stage_lube_outcome(sc, &lc.last, res, &lerr);
            if (lrc != MC_OK) {
                *err = lerr;
                rc = lrc;
            }
        }
    }
    mc_plastic_result_free(&pr);
    mc_hardening_free(&law);
    return rc;
}
