/* hertz_point.c - suite `hertz_point`: sphere on a flat of another material, frictionless, load
 * control, against Hertz (Johnson 1985 ch. 4; theory.md §6.1), over a mesh sequence from 10 to
 * 120 elements per contact radius. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "reference/hertz.h"
#include "pipeline/pipeline.h"
#include "suites.h"
#include "vutil.h"

/* Scene: steel ball (R = 10 mm) on an aluminium-like flat, 100 N. */
#define R_SPHERE 10e-3
#define E1 210e9
#define NU1 0.30
#define E2 70e9
#define NU2 0.33
#define LOAD 100.0
#define SOLVER_TOL 1e-10

/* Discretisation tier. The pressure of a cell-centred grid converges as (dx/a)^2 (theory.md §4.5:
 * +2.5e-5 at a/dx = 43); the approach likewise. With the apex on a cell centre (odd grids) the
 * measured errors are C (dx/a)^2 with C = 0.05-0.065 (p_max), 0.02-0.04 (approach) and 0.10-0.15
 * (fitted radius, p^2 linear in r^2 over r < 0.8 a) from a/dx = 10 to 120; the tolerances allow
 * 0.15, 0.15 and 0.4 (a factor 2.5-4 of margin, so the suite is a tight regression gate). The
 * requirement of the issue, 0.1 % for p_max and approach at >= 40 elements per radius, is checked
 * on its own. The radius from the contact area is quantised by one cell on the rim:
 * |error| <= dx/a. Load: solver tier. */
#define C_PMAX 0.15
#define C_DELTA 0.15
#define C_AFIT 0.4
#define REQUIRED_TOL 1e-3
#define LOAD_TOL 1e-8

typedef struct {
    int N, nx;
    double dx, pmax, afit, aarea, delta, load, time;
    int iterations;
} row_t;

static int run_mesh(const mc_hertz_point *hz, int N, mc_backend op, row_t *row, mc_results *keep)
{
    mc_scene sc;
    double dx = hz->a / N;
    int nx = 2 * (int)ceil(1.5 * N) + 1; /* odd: a cell centre at the apex; side >= 3a */
    vu_scene(&sc, nx, nx, dx, dx);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = R_SPHERE;
    sc.body1 = (mc_scene_material){E1, NU1, 0};
    sc.body2 = (mc_scene_material){E2, NU2, 0};
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = LOAD;
    sc.solver.tolerance = SOLVER_TOL;
    sc.solver.backend = op;
    mc_results res;
    mc_error err = {0};
    int rc = mc_pipeline_run(&sc, &res, &err);
    if (rc != MC_OK) {
        fprintf(stderr, "hertz_point: a/dx = %d: %s\n", N, err.msg);
        mc_results_free(&res);
        return rc;
    }
    row->N = N;
    row->nx = nx;
    row->dx = dx;
    row->pmax = res.contact.p_max;
    row->afit = vu_fit_radius(&res, 0, hz->a, 0.8, NULL);
    row->aarea = sqrt(res.contact.area / M_PI);
    row->delta = res.contact.approach;
    row->load = res.contact.load;
    row->time = res.timing.total_s;
    row->iterations = res.contact.iterations;
    if (keep)
        *keep = res;
    else
        mc_results_free(&res);
    return MC_OK;
}

static void profile_figure(vf_ctx *ctx, const mc_hertz_point *hz, const mc_results *res)
{
    const mc_grid *g = &res->grid;
    FILE *f = vf_open(ctx, "profile.csv");
    if (!f)
        return;
    int j = g->ny / 2;
    fprintf(f, "x_over_a,p_over_p0,hertz_over_p0\n");
    for (int i = 0; i < g->nx; i++) {
        double x = mc_grid_x(g, i);
        fprintf(f, "%.9g,%.9g,%.9g\n", x / hz->a, res->pressure[(size_t)j * g->nx + i] / hz->p0,
                mc_hertz_point_pressure(hz, x) / hz->p0);
    }
    vf_close(ctx, f);
    vf_plot(ctx, "profile.png", "Pressure along x through the centre (finest mesh) against Hertz",
            "set datafile separator ','\nset key top right\nset xlabel 'x / a'\n"
            "set ylabel 'p / p_0'\nset grid\nset samples 1000\n"
            "plot 'profile.csv' using 1:3 with lines lw 2 title 'Hertz', "
            "'profile.csv' using 1:2 with points pt 7 ps 0.6 title 'microcontact'");
}

int vf_suite_hertz_point(vf_ctx *ctx, int fast)
{
    mc_error err = {0};
    mc_hertz_point hz;
    double Es = 1.0 / ((1 - NU1 * NU1) / E1 + (1 - NU2 * NU2) / E2);
    if (mc_hertz_point_from_load(R_SPHERE, Es, LOAD, &hz, &err) != MC_OK)
        return 1;
    static const int full[] = {10, 20, 40, 80, 120}, quick[] = {10, 20, 40};
    const int *Ns = fast ? quick : full;
    int nN = fast ? 3 : 5;
    vf_text(ctx,
            "Sphere (R = %.0f mm, E = %.0f GPa, nu = %.2f) on a flat (E = %.0f GPa, nu = %.2f), "
            "load %.0f N: Hertz gives a = %.6g um, p0 = %.6g MPa, delta = %.6g um "
            "(Johnson 1985 ch. 4). Square domain of side >= 3a, odd cell counts so that a cell "
            "centre sits at the apex, method cg on the fft operator, solver tolerance %.0e.\n\n"
            "Tolerances (discretisation tier, the errors converge as (dx/a)^2): p_max and delta "
            "within 0.15 (dx/a)^2, the fitted radius (p^2 linear in r^2 for r < 0.8a) within "
            "0.4 (dx/a)^2 — 2.5 to 4 times the measured constants, so the suite is a tight "
            "regression gate —, the radius from the contact area within one cell (dx/a, the "
            "area is quantised), the load within %.0e (solver tier). The required accuracy "
            "(p_max and approach within 0.1 %% from 40 elements per radius) is checked "
            "separately (`req_*`).\n\n",
            R_SPHERE * 1e3, E1 * 1e-9, NU1, E2 * 1e-9, NU2, LOAD, hz.a * 1e6, hz.p0 * 1e-6,
            hz.delta * 1e6, SOLVER_TOL, LOAD_TOL);
    row_t rows[8];
    mc_results finest;
    memset(&finest, 0, sizeof finest);
    for (int k = 0; k < nN; k++) {
        int last = k == nN - 1;
        if (run_mesh(&hz, Ns[k], MC_BACKEND_FFT, &rows[k], last ? &finest : NULL) != MC_OK) {
            vf_fail(ctx, "run", "solve failed at a/dx = %d", Ns[k]);
            return 1;
        }
        const row_t *r = &rows[k];
        double h2 = 1.0 / ((double)r->N * r->N);
        char id[64], q[128];
        snprintf(id, sizeof id, "pmax_N%d", r->N);
        snprintf(q, sizeof q, "p_max, a/dx = %d (%d x %d)", r->N, r->nx, r->nx);
        vf_check(ctx, id, q, "Hertz p0", hz.p0, r->pmax, C_PMAX * h2, VF_REL);
        snprintf(id, sizeof id, "delta_N%d", r->N);
        snprintf(q, sizeof q, "approach, a/dx = %d", r->N);
        vf_check(ctx, id, q, "Hertz a^2/R", hz.delta, r->delta, C_DELTA * h2, VF_REL);
        if (r->N >= 40) {
            snprintf(id, sizeof id, "req_pmax_N%d", r->N);
            snprintf(q, sizeof q, "p_max within 0.1 %%, a/dx = %d", r->N);
            vf_check(ctx, id, q, "Hertz p0", hz.p0, r->pmax, REQUIRED_TOL, VF_REL);
            snprintf(id, sizeof id, "req_delta_N%d", r->N);
            snprintf(q, sizeof q, "approach within 0.1 %%, a/dx = %d", r->N);
            vf_check(ctx, id, q, "Hertz a^2/R", hz.delta, r->delta, REQUIRED_TOL, VF_REL);
        }
        snprintf(id, sizeof id, "afit_N%d", r->N);
        snprintf(q, sizeof q, "contact radius (fit), a/dx = %d", r->N);
        vf_check(ctx, id, q, "Hertz a", hz.a, r->afit, C_AFIT * h2, VF_REL);
        snprintf(id, sizeof id, "aarea_N%d", r->N);
        snprintf(q, sizeof q, "contact radius (area), a/dx = %d", r->N);
        vf_check(ctx, id, q, "Hertz a", hz.a, r->aarea, 1.0 / r->N, VF_REL);
        snprintf(id, sizeof id, "load_N%d", r->N);
        snprintf(q, sizeof q, "load, a/dx = %d", r->N);
        vf_check(ctx, id, q, "imposed load", LOAD, r->load, LOAD_TOL, VF_REL);
    }
    /* the dual operator: the same answer from the direct backend on the coarsest mesh */
    row_t direct;
    if (run_mesh(&hz, Ns[0], MC_BACKEND_DIRECT, &direct, NULL) == MC_OK)
        vf_check(ctx, "direct_vs_fft", "p_max, direct vs fft backend, a/dx = 10", "fft result",
                 rows[0].pmax, direct.pmax, 1e-9, VF_REL);
    else
        vf_fail(ctx, "direct_vs_fft", "direct backend solve failed");

    double hx[8], ep[8], ed[8], ea[8];
    FILE *f = vf_open(ctx, "convergence.csv");
    if (f)
        fprintf(f, "a_over_dx,nx,dx_over_a,time_s,iterations,p_max_Pa,err_pmax,delta_m,err_delta,"
                   "a_fit_m,err_afit,a_area_m,err_aarea\n");
    for (int k = 0; k < nN; k++) {
        const row_t *r = &rows[k];
        hx[k] = 1.0 / r->N;
        ep[k] = fabs(r->pmax / hz.p0 - 1);
        ed[k] = fabs(r->delta / hz.delta - 1);
        ea[k] = fabs(r->afit / hz.a - 1);
        if (f)
            fprintf(f, "%d,%d,%.6g,%.6g,%d,%.10g,%.6e,%.10g,%.6e,%.10g,%.6e,%.10g,%.6e\n", r->N,
                    r->nx, hx[k], r->time, r->iterations, r->pmax, ep[k], r->delta, ed[k], r->afit,
                    ea[k], r->aarea, fabs(r->aarea / hz.a - 1));
    }
    if (f)
        vf_close(ctx, f);
    double slope = vu_loglog_slope(hx, ed, nN);
    vf_check(ctx, "order_delta", "convergence order of the approach (log-log slope)",
             "O(dx^2) >= 1.5", 2.0, slope, 0.5, VF_ABS);
    vf_text(ctx, "| a/dx | grid | iterations | time (s) | p_max error | approach error | radius "
                 "error (fit) |\n|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < nN; k++)
        vf_text(ctx, "| %d | %d² | %d | %.3f | %.2e | %.2e | %.2e |\n", rows[k].N, rows[k].nx,
                rows[k].iterations, rows[k].time, ep[k], ed[k], ea[k]);
    vf_text(ctx, "\n");
    profile_figure(ctx, &hz, &finest);
    mc_results_free(&finest);
    vf_plot(ctx, "error_vs_size.png", "Relative error against element size (log-log)",
            "set datafile separator ','\nset logscale xy\nset key bottom right\n"
            "set xlabel 'dx / a'\nset ylabel 'relative error'\nset grid\n"
            "plot 'convergence.csv' using 3:7 with linespoints pt 7 title 'p_{max}', "
            "'' using 3:9 with linespoints pt 5 title 'approach', "
            "'' using 3:11 with linespoints pt 9 title 'radius (fit)', "
            "'' using 3:(0.15*$3**2) with lines dt 2 title 'tolerance p_{max}, approach: 0.15 (dx/a)^2'");
    vf_plot(ctx, "error_vs_time.png", "Relative error against run time (log-log)",
            "set datafile separator ','\nset logscale xy\nset key top right\n"
            "set xlabel 'run time (s)'\nset ylabel 'relative error'\nset grid\n"
            "plot 'convergence.csv' using 4:7 with linespoints pt 7 title 'p_{max}', "
            "'' using 4:9 with linespoints pt 5 title 'approach', "
            "'' using 4:11 with linespoints pt 9 title 'radius (fit)'");
    if (vf_hertz_point_stress(ctx, fast) != 0) /* subsurface stresses: verify/hertz_stress.c */
        return 1;
    return 0;
}
