/* pipeline.c - the stages of one run (see pipeline.h). */
#include "pipeline/pipeline.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "contact/contact.h"
#include "io/heightmap.h"
#include "pipeline/bodies.h"
#include "pipeline/memguard.h"
#include "operator/operator.h"
#include "stress/stress.h"
#include "pipeline/stage_stress.h"
#include "pipeline/stage_lube.h"
#include "pipeline/stage_plastic.h"
#include "pipeline/runin.h"
#include "pipeline/warnings.h"
#include "surface/surface.h"
#include "core/dist.h"

double mc_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* An error found after parsing: prefix it with the place of the key that caused it in the case
 * file ("case.ini:12: "), as the case reader's errors are (case/scene.h mc_scene_where). */
static int blame_key(const mc_scene *sc, const char *section, const char *name, int rc,
                     mc_error *err)
{
    if (rc != MC_OK && err) {
        char where[MC_PATH_MAX + 64] = "", key[96];
        if (sc->path[0]) /* a scene built in code has no file to point at */
            mc_scene_where(sc, section, name, where, sizeof where);
        snprintf(key, sizeof key, "[%s]", section); /* the message names the section already */
        if (strncmp(err->msg, key, strlen(key)) == 0)
            mc_error_prefix(err, "%s", where);
        else
            mc_error_prefix(err, "%s[%s] %s: ", where, section, name);
    }
    return rc;
}

static const char *load_key(const mc_scene *sc)
{
    switch (sc->load.kind) {
    case MC_LOAD_FORCE_PER_LENGTH: return "force_per_length";
    case MC_LOAD_APPROACH: return "approach";
    case MC_LOAD_PRESSURE_FILE: return "pressure_file";
    case MC_LOAD_FORCE: break;
    }
    return "force";
}

/* Prescribed pressure: [load] pressure_file into res->pressure (>= 0, the mesh's shape), before
 * the stages begin. */
static int read_prescribed(const mc_scene *sc, mc_results *res, mc_error *err)
{
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    double *p = NULL;
    int rc = mc_heightmap_read(sc->load.pressure_file, g->ny, g->nx, &p, err);
    if (rc != MC_OK) {
        if (err)
            mc_error_prefix(err, "[load] pressure_file: ");
        return blame_key(sc, "load", "pressure_file", rc, err);
    }
    for (size_t i = 0; i < n; i++) {
        if (p[i] < 0) {
            double v = p[i];
            mc_free(p);
            mc_fail(err, MC_ERR_INPUT,
                    "[load] pressure_file: %s: pressure %g Pa at row %zu, column %zu is "
                    "negative; a prescribed pressure map must be >= 0 (compressive)",
                    sc->load.pressure_file, v, i / (size_t)g->nx, i % (size_t)g->nx);
            return blame_key(sc, "load", "pressure_file", MC_ERR_INPUT, err);
        }
    }
    memcpy(res->pressure, p, n * sizeof *p);
    mc_free(p);
    return MC_OK;
}

/* Prescribed pressure (read_prescribed): the displacement is K p; the approach is the largest one
 * that keeps the gap non-negative, so the gap closes exactly where a consistent pressure would be
 * in contact. */
static int run_prescribed(const mc_scene *sc, mc_operator *K, mc_results *res, mc_error *err)
{
    (void)sc, (void)err;
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    double t0 = mc_clock();
    mc_operator_apply(K, res->pressure, res->displacement);
    double delta = INFINITY, load = 0, pmax = 0;
    size_t ncontact = 0;
    for (size_t i = 0; i < n; i++) {
        delta = fmin(delta, res->topography[i] + res->displacement[i]);
        load += res->pressure[i];
        pmax = fmax(pmax, res->pressure[i]);
        ncontact += res->pressure[i] > 0;
    }
    for (size_t i = 0; i < n; i++)
        res->gap[i] = res->topography[i] + res->displacement[i] - delta;
    mc_contact_summary *c = &res->contact;
    double A = mc_grid_cell_area(g);
    c->solved = 0;
    c->load = A * load;
    c->solid_load = A * load;
    c->p_max = pmax;
    c->area = A * (double)ncontact;
    c->contact_ratio = (double)ncontact / (double)n;
    c->approach = delta;
    c->converged = 0; /* nothing was solved: "prescribed" is its own state (summary.json) */
    c->solver = "prescribed";
    c->backend = mc_operator_backend(K);
    res->timing.contact_s = mc_clock() - t0;
    return MC_OK;
}

static int run_contact(const mc_scene *sc, mc_operator *K, mc_results *res, mc_error *err)
{
    const mc_grid *g = &res->grid;
    mc_contact_options opt = {.method = sc->solver.method,
                              .tolerance = sc->solver.tolerance,
                              .max_iterations = sc->solver.max_iterations,
                              .estar = mc_scene_estar(sc)};
    mc_contact_problem prob = {.h = res->topography,
                               .p_lub = fmax(sc->load.lubricant_pressure, 0.0), /* auto: -1 */
                               .p_cap = sc->load.pressure_cap};
    switch (sc->load.kind) {
    case MC_LOAD_FORCE:
        prob.control = MC_CONTROL_FORCE;
        prob.load = sc->load.value;
        break;
    case MC_LOAD_FORCE_PER_LENGTH: /* the load on one period along y */
        prob.control = MC_CONTROL_FORCE;
        prob.load = sc->load.value * g->ny * g->dy;
        break;
    case MC_LOAD_APPROACH:
        prob.control = MC_CONTROL_APPROACH;
        prob.approach = sc->load.value;
        break;
    case MC_LOAD_PRESSURE_FILE:
        return mc_fail(err, MC_ERR_INTERNAL, "run_contact called for a prescribed pressure");
    }
    mc_contact_solver *solver = NULL;
    double t0 = mc_clock();
    int rc = mc_contact_create(K, &opt, &solver, err);
    res->timing.setup_s += mc_clock() - t0;
    if (rc != MC_OK)
        return rc;
    t0 = mc_clock();
    const double cpu0 = mc_dist_cpu_seconds(), ccpu0 = mc_dist_comm_cpu_seconds();
    if (sc->plasticity.enabled)
        rc = mc_stage_plastic(sc, K, solver, res, err);
    else if (sc->load.lubricant_pressure == MC_LUBRICANT_AUTO)
        rc = mc_stage_lube(sc, K, solver, NULL, NULL, res, err);
    else
        rc = mc_contact_solve(solver, &prob, res->pressure, res->displacement, res->gap,
                              &res->contact, err);
    res->timing.contact_s = mc_clock() - t0;
    res->timing.contact_cpu_s = mc_dist_cpu_seconds() - cpu0;
    res->timing.contact_comm_cpu_s = mc_dist_comm_cpu_seconds() - ccpu0;
    mc_contact_destroy(&solver);
    if (rc == MC_ERR_INPUT || rc == MC_ERR_LIMIT) /* a load the contact cannot take */
        return blame_key(sc, "load",
                         isfinite(prob.p_cap) && err && strstr(err->msg, "pressure cap")
                             ? "pressure_cap"
                             : load_key(sc),
                         rc, err);
    return rc;
}

/* The ISO parameters of roughness heights with the scene's cut-off rule and periodicity. */
static int roughness_of(const mc_scene *sc, const double *heights, mc_roughness_params *out,
                        mc_error *err)
{
    const mc_grid *g = &sc->grid;
    mc_roughness_options opt;
    mc_roughness_options_default(&opt);
    opt.cutoff = sc->roughness.cutoff;
    opt.periodic_x = g->periodic_x;
    opt.periodic_y = g->periodic_y;
    return mc_roughness_compute(heights, NULL, g->nx, g->ny, g->dx, g->dy, &opt, out, err);
}

/* The ISO parameters of the roughness heights (surface/roughness.h), for summary.json. */
static int roughness_parameters(const mc_scene *sc, mc_results *res, mc_error *err)
{
    const mc_grid *g = &sc->grid;
    double *heights = mc_zeros(mc_grid_cells(g));
    if (!heights)
        return mc_fail(err, MC_ERR_NOMEM, "out of memory for the roughness heights");
    int rc;
    if (res->two_bodies) { /* the composite of the two bodies' heights (bodies.h) */
        for (size_t i = 0; i < mc_grid_cells(g); i++)
            heights[i] = res->body_initial[0][i] + res->body_initial[1][i];
        res->surface_missing = res->body_file[0].missing;
        res->surface_filled = res->body_file[0].filled;
        memcpy(res->surface_format, res->body_file[0].format, sizeof res->surface_format);
        for (int k = 0; k < 2; k++)
            if (res->body_file[k].warning[0])
                mc_results_warn(res, "surface_file", "[roughness%s] file: %s", k ? "2" : "",
                                res->body_file[k].warning);
        rc = MC_OK;
    } else if (sc->roughness.type == MC_ROUGH_FILE) { /* also what the file held: format, missing */
        mc_measured_spec ms;
        mc_measured m;
        mc_surface_measured_spec(&sc->roughness, &ms);
        rc = mc_measured_load(&ms, &m, err);
        if (rc == MC_OK)
            rc = mc_measured_onto(&m, g, (mc_resample_rule)sc->roughness.resample, heights, err);
        if (rc == MC_OK) {
            res->surface_missing = m.missing;
            res->surface_filled = m.filled;
            memcpy(res->surface_format, m.format, sizeof res->surface_format);
            if (m.warning[0])
                mc_results_warn(res, "surface_file", "[roughness] file: %s", m.warning);
        }
        mc_measured_free(&m);
    } else
        rc = mc_surface_roughness(g, &sc->roughness, heights, err);
    if (rc == MC_OK) {
        rc = roughness_of(sc, heights, &res->roughness_initial, err);
        res->has_roughness = rc == MC_OK;
        /* a cut-off given too short for the grid: the key to name is [roughness] cutoff
         * (MC_ERR_LIMIT, also exit 2, tells run_stages the message names its key already) */
        if (rc == MC_ERR_INPUT && err && strstr(err->msg, "cut-off lambda_c"))
            rc = blame_key(sc, "roughness", "cutoff", MC_ERR_LIMIT, err);
    }
    if (rc == MC_OK && res->two_bodies) { /* each body's, with its own section's cutoff */
        const char *sec = "roughness";
        rc = mc_bodies_initial_parameters(sc, 0, res, &sec, err);
        if (rc == MC_ERR_INPUT && err && strstr(err->msg, "cut-off lambda_c"))
            rc = blame_key(sc, sec, "cutoff", MC_ERR_LIMIT, err);
    }
    mc_free(heights);
    return rc;
}

/* roughness.final of an elastic-plastic run: the final roughness heights, shape minus
 * topography_final (surface.h: topography = shape - heights), with the rules of the initial. */
static int final_roughness(const mc_scene *sc, mc_results *res, mc_error *err)
{
    const mc_grid *g = &sc->grid;
    const size_t n = mc_grid_cells(g);
    double *heights = mc_zeros(n);
    if (!heights)
        return mc_fail(err, MC_ERR_NOMEM, "out of memory for the final roughness heights");
    mc_surface_shape(g, &sc->geometry, heights);
    for (size_t k = 0; k < n; k++)
        heights[k] -= res->topography_final[k];
    int rc = roughness_of(sc, heights, &res->roughness_final, err);
    res->has_roughness_final = rc == MC_OK;
    mc_free(heights);
    return rc;
}

static int run_stages(const mc_scene *sc, mc_stage_fn stage, void *ctx, mc_results *res,
                      mc_error *err)
{
    double t_start = mc_clock();
    memset(res, 0, sizeof *res);
    int rc = mc_scene_check(sc, err);
    if (rc != MC_OK)
        return rc;
    rc = mc_memory_check(sc, err);
    if (rc != MC_OK)
        return blame_key(sc, "mesh", "nx", rc, err);
    res->grid = sc->grid;
    res->roughness_seed = sc->roughness.seed;
    const size_t n = mc_grid_cells(&sc->grid);
    double **fields[] = {&res->topography, &res->pressure, &res->gap, &res->displacement};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++)
        if (!(*fields[k] = mc_zeros(n)))
            return mc_fail(err, MC_ERR_NOMEM, "out of memory for the %d x %d surface fields",
                           sc->grid.nx, sc->grid.ny);
    const char *rsec = "roughness"; /* the section at fault: [roughness2] is body 2's */
    rc = mc_bodies_topography(sc, res, res->topography, &rsec, err);
    if (rc == MC_OK && sc->roughness.type != MC_ROUGH_NONE)
        rc = roughness_parameters(sc, res, err);
    const int surface_rc = rc;
    if (rc == MC_OK && sc->load.kind == MC_LOAD_PRESSURE_FILE)
        rc = read_prescribed(sc, res, err);
    /* over MPI processes each reads the inputs itself: all go on only if all could (a process
     * that stopped alone would leave the others waiting in the first transform) */
    const int all = mc_dist_max_int(rc);
    if (all != MC_OK && rc == MC_OK)
        return mc_fail(err, all, "another MPI process could not read the inputs (status %d)", all);
    if (surface_rc == MC_ERR_LIMIT) /* named its key already ([roughness] cutoff) */
        return surface_rc;
    const mc_roughness_spec *rs = strcmp(rsec, "roughness2") ? &sc->roughness : &sc->roughness2;
    if (surface_rc != MC_OK && surface_rc != MC_ERR_NOMEM && rs->type != MC_ROUGH_NONE)
        return blame_key(sc, rsec, rs->type == MC_ROUGH_FILE ? "file" : "type", surface_rc, err);
    if (rc != MC_OK)
        return rc;

    if (stage)
        stage(ctx, "contact");
    mc_operator *K = NULL;
    double t0 = mc_clock();
    rc = mc_operator_plan_love(&sc->grid, mc_scene_estar(sc), sc->solver.backend, &K, err);
    res->timing.setup_s = mc_clock() - t0;
    if (rc != MC_OK)
        return rc;
    if (sc->load.kind == MC_LOAD_PRESSURE_FILE)
        rc = run_prescribed(sc, K, res, err);
    else
        rc = run_contact(sc, K, res, err);
    mc_operator_destroy(&K);
    if ((rc == MC_OK || rc == MC_NOT_CONVERGED) && res->has_roughness && res->topography_final) {
        mc_error ferr = {0};
        int frc = final_roughness(sc, res, &ferr);
        if (frc == MC_OK) /* each body's, minus its own dent (bodies.h) */
            frc = mc_bodies_final(sc, 0, res->residual_displacement, res, NULL, &ferr);
        if (frc != MC_OK) {
            *err = ferr;
            rc = frc;
        }
    }
    /* stresses of an unconverged solve are still worth writing; its status stays */
    if ((rc == MC_OK || rc == MC_NOT_CONVERGED) && sc->stress.enabled) {
        mc_error serr = {0};
        if (stage)
            stage(ctx, "stress");
        t0 = mc_clock();
        int src = mc_stage_stress(sc, res, &serr);
        res->timing.stress_s = mc_clock() - t0;
        if (src == MC_ERR_INPUT || src == MC_ERR_LIMIT) /* the [stress] settings */
            blame_key(sc, "stress",
                      sc->stress.kernel == MC_STRESS_POINT && strstr(serr.msg, "kernel") ? "kernel"
                                                                            : "depth_max",
                      src, &serr);
        if (src != MC_OK) {
            *err = serr;
            rc = src;
        }
    }
    res->timing.total_s = mc_clock() - t_start;
    return rc;
}

/* Under mpirun the whole pressure and gap are gathered on every rank and the elastic-plastic
 * stage is computed replicated (its volume whole on every rank): every rank must hold the same
 * bits, and rank 0 alone writes them. A rank that diverged (a bug) would go unseen in the files;
 * its hash is compared with rank 0's instead (runin.c checks the running-in's state after every
 * step alike). Collective; nothing without a communicator. */
static int same_results(const mc_results *res, mc_error *err)
{
    if (mc_dist_size() <= 1)
        return MC_OK;
    const size_t n = (size_t)res->grid.nx * (size_t)res->grid.ny;
    const double *f[] = {res->pressure, res->gap, res->residual_displacement, res->plastic_strain};
    const size_t len[] = {n, n, n, n * (size_t)(res->plastic.nz > 0 ? res->plastic.nz : 0)};
    uint64_t h = 14695981039346656037ull; /* FNV-1a over 64-bit words */
    for (int a = 0; a < 4; a++)
        for (size_t i = 0; f[a] && i < len[a]; i++) {
            uint64_t w;
            memcpy(&w, &f[a][i], sizeof w);
            h ^= w;
            h *= 1099511628211ull;
        }
    const double mine[2] = {(double)(h >> 32), (double)(h & 0xffffffffu)}; /* exact halves */
    double root[2] = {mine[0], mine[1]};
    mc_dist_bcast(root, 2, 0);
    if (mc_dist_max_int(root[0] != mine[0] || root[1] != mine[1]))
        return mc_fail(err, MC_ERR_INTERNAL,
                       "the MPI processes hold different results (pressure, gap or plastic "
                       "fields, computed replicated: they must agree to the bit; a bug)");
    return MC_OK;
}

int mc_pipeline_run(const mc_scene *sc, mc_results *res, mc_error *err)
{
    return mc_pipeline_run_staged(sc, NULL, NULL, res, err);
}

int mc_pipeline_check_ranks(const mc_scene *sc, int ranks, mc_error *err)
{
    if (ranks <= 1)
        return MC_OK;
    /* distributed: the elastic operator (operator/dfft.h) and the contact solvers' iterations
     * (contact_internal.h); every other stage, the elastic-plastic loop and the running-in
     * included, computes the same replicated arrays on every rank (its volume is whole on each),
     * which needs the same plans on every rank. The running-in agrees on its stops and shares
     * its checkpoint's status (runin.c) */
    if (sc->solver.plans != MC_PLANS_ESTIMATE) {
        mc_fail(err, MC_ERR_INPUT,
                "[solver] plans = %s: with %d MPI processes only estimate is accepted (measured "
                "plans may differ from process to process, and the processes must compute the "
                "same numbers)",
                mc_plan_rigor_name(sc->solver.plans), ranks);
        return blame_key(sc, "solver", "plans", MC_ERR_INPUT, err);
    }
    return MC_OK;
}

int mc_pipeline_run_staged(const mc_scene *sc, mc_stage_fn stage, void *ctx, mc_results *res,
                           mc_error *err)
{
    int rc0 = mc_pipeline_check_ranks(sc, mc_dist_size(), err);
    if (rc0 != MC_OK) {
        memset(res, 0, sizeof *res); /* nothing computed; the caller frees res as after a run */
        return rc0;
    }
    /* the scene's thread count holds for this run only (core/threads.h) */
    mc_threads_scope scope;
    mc_threads_begin(sc->solver.threads, &scope);
    /* and its planner rigor, after the thread count (wisdom is per thread count) */
    mc_fft_plans_scope plans;
    int rc = mc_fft_plans_begin(sc->solver.plans, sc->solver.wisdom_file, &plans, err);
    if (rc != MC_OK) {
        memset(res, 0, sizeof *res); /* nothing computed; the caller frees res as after a run */
        mc_threads_end(&scope);
        return blame_key(sc, "solver", "wisdom_file", rc, err);
    }
    /* a running-in is its own sequence of stages (pipeline/runin.h) */
    const double comm0 = mc_dist_comm_seconds();
    rc = sc->runin.enabled ? mc_runin_run(sc, NULL, res, err)
                           : run_stages(sc, stage, ctx, res, err);
    /* every rank reaches this point (statuses are replicated); their results must agree */
    if (sc->plasticity.enabled && !sc->runin.enabled && mc_dist_size() > 1) {
        int all = mc_dist_max_int(rc); /* the worst status over the ranks, first */
        if (all != rc && rc == MC_OK)
            mc_fail(err, all, "the run failed on another MPI process");
        rc = all;
        if (rc == MC_OK || rc == MC_NOT_CONVERGED) {
            int src = same_results(res, err);
            if (src != MC_OK)
                rc = src;
        }
    }
    res->timing.comm_s = mc_dist_comm_seconds() - comm0;
    if (rc == MC_OK || rc == MC_NOT_CONVERGED)
        mc_results_warnings(sc, res);
    mc_error perr = {0};
    if (mc_fft_plans_end(&plans, &perr) != MC_OK && (rc == MC_OK || rc == MC_NOT_CONVERGED)) {
        /* the results stand: a wisdom file that cannot be written is a warning of the run */
        mc_results_warn(res, "wisdom_not_written", "[solver] wisdom_file: %s", perr.msg);
    }
    mc_threads_end(&scope);
    return rc;
}
