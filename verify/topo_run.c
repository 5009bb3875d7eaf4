/* topo_run.c - contact and elastic-plastic runs on a given topography (topo_run.h). */
#include "topo_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "core/alloc.h"
#include "core/threads.h"
#include "kernels/kernel.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_plastic.h"

static int run(const mc_scene *sc, const double *topo, mc_results *res, double *p_elastic,
               mc_error *err)
{
    int rc = mc_scene_check(sc, err);
    if (rc != MC_OK)
        return rc;
    if (sc->load.kind != MC_LOAD_FORCE)
        return mc_fail(err, MC_ERR_INPUT, "vt_run_topography: force control only");
    res->grid = sc->grid;
    const size_t n = mc_grid_cells(&sc->grid);
    double **fields[] = {&res->topography, &res->pressure, &res->gap, &res->displacement};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++)
        if (!(*fields[k] = mc_zeros(n)))
            return mc_fail(err, MC_ERR_NOMEM, "out of memory for the surface fields");
    memcpy(res->topography, topo, n * sizeof *topo);
    mc_operator *K = NULL;
    mc_contact_solver *solver = NULL;
    rc = mc_operator_plan_love(&sc->grid, mc_scene_estar(sc), sc->solver.backend, &K, err);
    mc_contact_options opt = {.method = sc->solver.method,
                              .tolerance = sc->solver.tolerance,
                              .max_iterations = sc->solver.max_iterations,
                              .estar = mc_scene_estar(sc)};
    if (rc == MC_OK)
        rc = mc_contact_create(K, &opt, &solver, err);
    if (rc == MC_OK && (p_elastic || !sc->plasticity.enabled)) {
        mc_contact_problem prob = {.h = res->topography,
                                   .p_lub = fmax(sc->load.lubricant_pressure, 0.0),
                                   .p_cap = sc->load.pressure_cap,
                                   .control = MC_CONTROL_FORCE,
                                   .load = sc->load.value};
        rc = mc_contact_solve(solver, &prob, res->pressure, res->displacement, res->gap,
                              &res->contact, err);
        if (rc == MC_OK && p_elastic)
            memcpy(p_elastic, res->pressure, n * sizeof *p_elastic);
    }
    if (rc == MC_OK && sc->plasticity.enabled)
        rc = mc_stage_plastic(sc, K, solver, res, err);
    mc_contact_destroy(&solver);
    mc_operator_destroy(&K);
    return rc;
}

int vt_run_topography(const mc_scene *sc, const double *topo, mc_results *res, double *p_elastic,
                      mc_error *err)
{
    memset(res, 0, sizeof *res);
    double t0 = mc_clock();
    mc_threads_scope scope;
    mc_threads_begin(sc->solver.threads, &scope);
    int rc = run(sc, topo, res, p_elastic, err);
    mc_threads_end(&scope);
    res->timing.total_s = mc_clock() - t0;
    return rc;
}

void vt_stress_at(const mc_grid *g, const double *p, double nu, int point_kernel, double x,
                  double y, const double *z, int nz, double *s)
{
    memset(s, 0, sizeof *s * 6 * (size_t)nz);
    const double a = 0.5 * g->dx, b = 0.5 * g->dy, A = g->dx * g->dy;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            const double pc = p[(size_t)j * g->nx + i];
            if (pc == 0)
                continue;
            const double rx = x - mc_grid_x(g, i), ry = y - mc_grid_y(g, j);
            for (int k = 0; k < nz; k++) {
                double t[6];
                if (point_kernel) {
                    mc_point_stress_p(rx, ry, z[k], nu, t);
                    for (int c = 0; c < 6; c++)
                        s[k * 6 + c] += pc * A * t[c];
                } else {
                    mc_rect_stress_p(rx, ry, z[k], a, b, nu, t);
                    for (int c = 0; c < 6; c++)
                        s[k * 6 + c] += pc * t[c];
                }
            }
        }
}

int vt_count_patches(const mc_grid *g, const double *p)
{
    const size_t n = (size_t)g->nx * g->ny;
    int *lab = calloc(n, sizeof *lab), *stack = malloc(n * sizeof *stack), np = 0;
    if (!lab || !stack) {
        free(lab);
        free(stack);
        return -1;
    }
    for (size_t s = 0; s < n; s++) {
        if (!(p[s] > 0) || lab[s])
            continue;
        np++;
        int top = 0;
        stack[top++] = (int)s;
        lab[s] = np;
        while (top) {
            int q = stack[--top], qi = q % g->nx, qj = q / g->nx;
            const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
            for (int e = 0; e < 4; e++) {
                int ii = qi + di[e], jj = qj + dj[e];
                if (ii < 0 || jj < 0 || ii >= g->nx || jj >= g->ny)
                    continue;
                size_t r = (size_t)jj * g->nx + ii;
                if (p[r] > 0 && !lab[r]) {
                    lab[r] = np;
                    stack[top++] = (int)r;
                }
            }
        }
    }
    free(lab);
    free(stack);
    return np;
}
