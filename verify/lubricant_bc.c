/* lubricant_bc.c - suite `lubricant_bc`: the lubricant boundary condition p >= p_lub (the
 * paper's Fig. 3-1) on a wavy surface, where a closed form holds in every cell.
 *
 * Scene: one period of a sinusoidal surface, heights z = D cos(2 pi x / L), periodic in x and y
 * with one cell along y (plane strain), loaded by a mean pressure pbar (force per length
 * pbar L), through the whole pipeline (a [roughness] file, [load] force_per_length and
 * lubricant_pressure). Without lubricant this is Westergaard's wavy contact (Johnson 1985 13.2):
 * with p* = pi E* D / L and partial contact pbar < p*, the contact half-width a follows from
 * sin^2(pi a / L) = pbar / p* and
 *     p(x) = 2 pbar cos(pi x/L) sqrt(sin^2(pi a/L) - sin^2(pi x/L)) / sin^2(pi a/L),  |x| <= a.
 * With a lubricant pressure p_lub the excess q = p - p_lub solves the same problem with the load
 * pbar - p_lub (plastic-lubrication.md 5.1 "shift"; on a periodic patch K 1 is a rigid shift):
 * p = p_lub + Westergaard(pbar - p_lub). The suite checks that, the floor itself, the load split
 * F_solid + p_lub A_free = F, the paper's active-set solver against cg, and that the pockets open
 * (the mean gap grows) monotonically with p_lub (plastic-lubrication.md 5.1, 5.2). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "io/npy.h"
#include "kernels/kernel.h"
#include "pipeline/pipeline.h"
#include "suites.h"
#include "vutil.h"

#define E_STEEL 210e9
#define NU 0.30
#define WAVELENGTH 100e-6 /* L, m */
#define AMPLITUDE 0.5e-6  /* D, m */
#define PBAR_OVER_PSTAR 0.5
#define PLUB_OVER_PBAR 0.3
#define SOLVER_TOL 1e-11
#define NSWEEP 6 /* p_lub / pbar = 0, 0.1, ..., 0.5 */

/* Tolerances.
 * C_PROFILE: the pressure inside |x| < 0.8 a converges like the Hertz line contact's (the same
 *   square-root edge, elastic.md 4.3): measured max |p - p_ref| / q0 = 0.04-0.05 (dx/a)^2 dry
 *   and 0.04-0.12 (dx/a)^2 lubricated (its edge is not on a cell boundary, and the edge cell's
 *   pixel error reaches further in) from a/dx = 13 to 128; allowed 0.5 (dx/a)^2, four times the
 *   largest. (Up to 0.9 a the lubricated constant reaches 0.3: the edge cells are left out.)
 * C_PMAX: the crest x = 0 is a cell corner (even nx), so the largest sampled pressure lies dx/2
 *   from the peak, where q/q0 = 1 - O((dx/a)^2/8); with the discretisation error the measured
 *   (q0 - p_max + p_lub) / q0 is 0.13-0.18 (dx/a)^2 from a/dx = 13 to 103; allowed 0.3 (dx/a)^2.
 * GAP_OPEN: a cell is open (out of solid contact) when its gap exceeds 1e-8 D: in contact the
 *   solver leaves gaps of SOLVER_TOL times the interference (~D), 1000 times smaller.
 * HALF_CELLS: the contact half-width from the count of contact cells is quantised to the grid:
 *   the edge lies within one cell on each side, so |a_cells - a| <= dx (one cell).
 * ROUNDOFF: exact statements evaluated in floating point (the floor is set, not computed; the
 *   load split is a sum of O(1e3) terms): 1e-12 relative.
 * SOLVER: identities between two converged solves (shift principle, active set against cg):
 *   each solve stops at a residual of SOLVER_TOL (gap / interference and load), which bounds
 *   pressure differences relative to q0 by SOLVER_TOL times the conditioning of the periodic
 *   Love operator on the contact, about nx: 1e-11 x 512 ~ 5e-9; allowed 1e-7.
 * RIGID: the displacement of a uniform pressure on a periodic patch is the same in every cell,
 *   so u(lub) - u(shift) is constant up to the solver tolerance of the two solves (SOLVER).
 * LOAD: the load of a converged force-controlled solve: SOLVER_TOL with a factor 10. */
#define C_PROFILE 0.5
#define C_PMAX 0.3
#define GAP_OPEN 1e-8
#define HALF_CELLS 1.0
#define ROUNDOFF 1e-12
#define SOLVER 1e-7
#define RIGID 1e-7
#define LOAD (10 * SOLVER_TOL)

typedef struct {
    double p_lub;
    int nx;
    double *p, *gap, *u, *x; /* nx each */
    double a_cells;           /* contact half-width from the contact cells, m */
    double mean_gap;          /* m */
    double load, solid_load;  /* per length: sum p dx; sum over contact cells of p dx */
    double free_len;          /* length outside solid contact, m */
    int iterations;
    double time;
} run_t;

typedef struct {
    double estar, pstar, pbar;
    int nx;
    double dx;
    char surface[MC_PATH_MAX]; /* the .npy height map */
} setup_t;

static void run_free(run_t *r)
{
    free(r->p);
    memset(r, 0, sizeof *r);
}

/* Westergaard's pressure for mean pressure pb on the wavy surface (0 outside contact). */
static double westergaard(const setup_t *s, double pb, double x, double *a_out)
{
    double s2 = pb / s->pstar, sa = sqrt(s2), a = WAVELENGTH / M_PI * asin(sa);
    if (a_out)
        *a_out = a;
    double sx = sin(M_PI * x / WAVELENGTH);
    if (fabs(x) >= a)
        return 0;
    return 2 * pb * cos(M_PI * x / WAVELENGTH) * sqrt(s2 - sx * sx) / s2;
}

static int solve(const setup_t *s, double p_lub, double pbar_load, mc_contact_method method,
                 run_t *r, mc_error *err)
{
    memset(r, 0, sizeof *r);
    mc_scene sc;
    vu_scene(&sc, s->nx, 1, s->dx, s->dx);
    sc.grid.periodic_x = 1;
    sc.grid.periodic_y = 1;
    sc.body1 = (mc_scene_material){E_STEEL, NU, 0};
    sc.body2 = (mc_scene_material){E_STEEL, NU, 0};
    sc.roughness.type = MC_ROUGH_FILE;
    memcpy(sc.roughness.file, s->surface, sizeof sc.roughness.file);
    sc.roughness.format = MC_FORMAT_NPY;
    sc.roughness.detrend = MC_DETREND_NONE;
    sc.roughness.verify_checksum = 1;
    sc.roughness.scale = 1;
    sc.load.kind = MC_LOAD_FORCE_PER_LENGTH;
    sc.load.value = pbar_load * WAVELENGTH;
    sc.load.lubricant_pressure = p_lub;
    sc.solver.method = method;
    sc.solver.tolerance = SOLVER_TOL;
    mc_results res;
    int rc = mc_pipeline_run(&sc, &res, err);
    if (rc != MC_OK) {
        mc_results_free(&res);
        return rc;
    }
    int n = s->nx;
    r->p_lub = p_lub;
    r->nx = n;
    r->p = malloc(sizeof(double) * 4 * (size_t)n);
    if (!r->p) {
        mc_results_free(&res);
        return mc_fail(err, MC_ERR_NOMEM, "lubricant_bc: out of memory");
    }
    r->gap = r->p + n;
    r->u = r->p + 2 * n;
    r->x = r->p + 3 * n;
    int contact = 0;
    double free_cells = 0;
    for (int i = 0; i < n; i++) {
        r->p[i] = res.pressure[i];
        r->gap[i] = res.gap[i];
        r->u[i] = res.displacement[i];
        r->x[i] = mc_grid_x(&res.grid, i);
        r->mean_gap += r->gap[i] / n;
        r->load += r->p[i] * s->dx;
        if (r->p[i] > p_lub) { /* solid contact: above the floor */
            contact++;
            r->solid_load += r->p[i] * s->dx;
        } else
            free_cells++;
    }
    r->a_cells = 0.5 * contact * s->dx;
    r->free_len = free_cells * s->dx;
    r->iterations = res.contact.iterations;
    r->time = res.timing.total_s;
    mc_results_free(&res);
    return MC_OK;
}

/* max |p - p_lub - westergaard(pb)| / q0 over |x| < 0.8 a, and p_max */
static double profile_error(const setup_t *s, const run_t *r, double pb, double *pmax)
{
    double a, worst = 0, q0 = westergaard(s, pb, 0, &a);
    *pmax = 0;
    for (int i = 0; i < r->nx; i++) {
        *pmax = vf_worst(*pmax, r->p[i]);
        if (fabs(r->x[i]) < 0.8 * a)
            worst = vf_worst(worst, fabs(r->p[i] - r->p_lub - westergaard(s, pb, r->x[i], NULL)));
    }
    return worst / q0;
}

/* the surface file: heights D cos(2 pi x / L) at the cell centres */
static int write_surface(vf_ctx *ctx, setup_t *s, mc_error *err)
{
    double *z = malloc(sizeof *z * (size_t)s->nx);
    if (!z)
        return mc_fail(err, MC_ERR_NOMEM, "lubricant_bc: out of memory");
    mc_grid g = {s->nx, 1, s->dx, s->dx, 1, 1};
    for (int i = 0; i < s->nx; i++)
        z[i] = AMPLITUDE * cos(2 * M_PI * mc_grid_x(&g, i) / WAVELENGTH);
    const char *path = vf_path(ctx, "wavy_surface.npy");
    if (strlen(path) >= sizeof s->surface) {
        free(z);
        return mc_fail(err, MC_ERR_INPUT, "lubricant_bc: report path too long: %s", path);
    }
    memcpy(s->surface, path, strlen(path) + 1);
    size_t shape[2] = {1, (size_t)s->nx};
    int rc = mc_npy_write(s->surface, z, 2, shape, err);
    free(z);
    return rc;
}

static void write_csv(vf_ctx *ctx, const setup_t *s, const run_t *dry, const run_t *lub,
                      const run_t *sweep, const double err[2], double split)
{
    /* profiles: displacement relative to its value at the crest (x = 0 lies between the two
     * middle cells: their mean) so that the rigid part of a periodic displacement drops out */
    int m = s->nx / 2;
    double u0d = 0.5 * (dry->u[m - 1] + dry->u[m]), u0l = 0.5 * (lub->u[m - 1] + lub->u[m]);
    double ad, al;
    westergaard(s, s->pbar, 0, &ad);
    westergaard(s, s->pbar - lub->p_lub, 0, &al);
    FILE *f = vf_open(ctx, "profiles.csv");
    if (f) {
        fprintf(f, "x_um,x_over_L,height_um,p_dry_MPa,p_lub_MPa,p_lub_floor_MPa,p_dry_ref_MPa,"
                   "p_lub_ref_MPa,u_dry_um,u_lub_um,gap_dry_um,gap_lub_um\n");
        for (int i = 0; i < s->nx; i++) {
            double x = dry->x[i];
            fprintf(f, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.8f,%.8f,%.8f,%.8f\n", x * 1e6,
                    x / WAVELENGTH, AMPLITUDE * cos(2 * M_PI * x / WAVELENGTH) * 1e6,
                    dry->p[i] * 1e-6, lub->p[i] * 1e-6, lub->p_lub * 1e-6,
                    westergaard(s, s->pbar, x, NULL) * 1e-6,
                    (lub->p_lub + westergaard(s, s->pbar - lub->p_lub, x, NULL)) * 1e-6,
                    (dry->u[i] - u0d) * 1e6, (lub->u[i] - u0l) * 1e6, dry->gap[i] * 1e6,
                    lub->gap[i] * 1e6);
        }
        vf_close(ctx, f);
    }
    if ((f = vf_open(ctx, "summary.csv"))) {
        fprintf(f, "case,cells,p_lub_over_pbar,a_over_lambda,a_ref_over_lambda,mean_gap_um,"
                   "solid_load_fraction,profile_err_q0,load_split,iterations\n");
        fprintf(f, "dry,%d,0,%.6f,%.6f,%.6f,%.6f,%.3e,%.3e,%d\n", s->nx,
                dry->a_cells / WAVELENGTH, ad / WAVELENGTH, dry->mean_gap * 1e6,
                dry->solid_load / dry->load, err[0], 0.0, dry->iterations);
        fprintf(f, "lub,%d,%.4f,%.6f,%.6f,%.6f,%.6f,%.3e,%.3e,%d\n", s->nx, lub->p_lub / s->pbar,
                lub->a_cells / WAVELENGTH, al / WAVELENGTH, lub->mean_gap * 1e6,
                lub->solid_load / lub->load, err[1], split, lub->iterations);
        vf_close(ctx, f);
    }
    if ((f = vf_open(ctx, "sweep.csv"))) {
        fprintf(f, "p_lub_over_pbar,mean_gap_um,solid_load_fraction,contact_fraction\n");
        for (int k = 0; k < NSWEEP; k++)
            fprintf(f, "%.3f,%.6f,%.6f,%.6f\n", sweep[k].p_lub / s->pbar,
                    sweep[k].mean_gap * 1e6, sweep[k].solid_load / sweep[k].load,
                    2 * sweep[k].a_cells / WAVELENGTH);
        vf_close(ctx, f);
    }
}

static void plots(vf_ctx *ctx)
{
    vf_plot(ctx, "pressure_profile.png",
            "Pressure across one wavelength without and with the lubricant pressure (points: "
            "microcontact; lines: Westergaard, shifted by p_lub); outside solid contact the "
            "pressure sits on the lubricant floor",
            "set datafile separator ','\nset xlabel 'x / wavelength (rolling direction)'\n"
            "set ylabel 'pressure p (MPa)'\nset grid\nset key top right\n"
            "set xrange [-0.5:0.5]\n"
            "plot 'profiles.csv' using 2:7 with lines lw 2 lc rgb '#1f77b4' "
            "title 'dry: Westergaard', "
            "'' using 2:4 with points pt 7 ps 0.5 lc rgb '#1f77b4' title 'dry: microcontact', "
            "'' using 2:8 with lines lw 2 lc rgb '#d62728' title 'lubricated: p_{lub} + "
            "Westergaard(p_{mean} - p_{lub})', "
            "'' using 2:5 with points pt 5 ps 0.5 lc rgb '#d62728' "
            "title 'lubricated: microcontact', "
            "'' using 2:6 with lines dt 2 lw 2 lc rgb 'black' title 'lubricant floor p_{lub}'");
    char script[2048];
    snprintf(script, sizeof script,
             "set datafile separator ','\nset multiplot layout 2,1\nset grid\n"
             "set xrange [-0.5:0.5]\nset format x ''\nset key bottom center maxrows 2\n"
             "set ylabel 'surface - counter face (um)'\nset yrange [:0.05]\n"
             "set lmargin 12\nset tmargin 1\nset bmargin 0.5\n"
             "plot 0 with lines lw 3 lc rgb 'black' title 'counter face', "
             "'profiles.csv' using 2:(-$11) with lines lw 2 lc rgb '#1f77b4' "
             "title 'loaded surface, dry', "
             "'' using 2:(-$12) with lines lw 2 dt 2 lc rgb '#d62728' "
             "title 'loaded surface, lubricated', "
             "'' using 2:($3 - %g) with lines lw 1 lc rgb 'gray' title 'unloaded (touching)'\n"
             "set format x '%%g'\nset xlabel 'x / wavelength (rolling direction)'\n"
             "set ylabel 'u - u(crest) (um)'\nset autoscale y\nset key bottom center\n"
             "set tmargin 0.5\nset bmargin 3\n"
             "plot 'profiles.csv' using 2:9 with lines lw 2 lc rgb '#1f77b4' title 'dry', "
             "'' using 2:10 with lines lw 2 dt 2 lc rgb '#d62728' title 'lubricated'\n"
             "unset multiplot",
             AMPLITUDE * 1e6);
    vf_plot(ctx, "gap_displacement.png",
            "Top: the loaded surface under the flat counter face (minus the gap), without and "
            "with the lubricant pressure - the contact shrinks and the lubricant pockets open. "
            "Bottom: the elastic displacement u (into the body) relative to the crest",
            script);
    vf_plot(ctx, "pockets_vs_plub.png",
            "Mean gap (pocket volume per nominal area) and solid load fraction against the "
            "lubricant pressure",
            "set datafile separator ','\nset xlabel 'p_{lub} / p_{mean}'\n"
            "set ylabel 'mean gap (um)'\nset y2label 'solid load fraction {/Symbol y}_F'\n"
            "set ytics nomirror\nset y2tics\nset grid\nset key top left\n"
            "plot 'sweep.csv' using 1:2 with linespoints pt 7 title 'mean gap', "
            "'' using 1:3 axes x1y2 with linespoints pt 5 title '{/Symbol y}_F (right)'");
}

int vf_suite_lubricant_bc(vf_ctx *ctx, int fast)
{
    mc_error err = {0};
    setup_t s;
    memset(&s, 0, sizeof s);
    s.estar = mc_combined_modulus(E_STEEL, NU, E_STEEL, NU, 0);
    s.pstar = M_PI * s.estar * AMPLITUDE / WAVELENGTH;
    s.pbar = PBAR_OVER_PSTAR * s.pstar;
    const double p_lub = PLUB_OVER_PBAR * s.pbar;
    static const int full[] = {64, 128, 256, 512}, quick[] = {64, 256};
    const int *Ns = fast ? quick : full;
    int nN = fast ? 2 : 4;
    vf_text(ctx,
            "One wavelength L = %.0f um of a sinusoidal surface of amplitude D = %.2f um "
            "(heights D cos(2 pi x/L), a [roughness] file), periodic in x and y with one cell "
            "along y (plane strain), steel on steel (E* = %.1f GPa), mean pressure p_mean = "
            "%.0f MPa = %.2f p* (p* = pi E* D / L = %.0f MPa: full contact), solver cg to %.0e; "
            "lubricated: [load] lubricant_pressure = %.0f MPa (%.2f p_mean). Reference: "
            "Westergaard's wavy contact (Johnson 1985 13.2) for the excess pressure p - p_lub "
            "under the load p_mean - p_lub (plastic-lubrication.md 5.1: on a periodic patch a "
            "uniform pressure only shifts the surface rigidly).\n\n"
            "Tolerances: profile (|x| < 0.8a) within %.1f (dx/a)^2 q0 and p_max within %.1f "
            "(dx/a)^2 q0 (q0: the peak of the excess pressure; discretisation tier, measured "
            "constants 0.04-0.12 and 0.13-0.18: the crest is a cell corner, the sampled peak "
            "lies dx/2 from it); contact half-width from the contact cells within "
            "one cell; the floor and the load split to round-off (%.0e); the shift principle, "
            "the rigid shift of the displacement and active set against cg to %.0e q0 (two "
            "solves at %.0e).\n\n",
            WAVELENGTH * 1e6, AMPLITUDE * 1e6, s.estar * 1e-9, s.pbar * 1e-6, PBAR_OVER_PSTAR,
            s.pstar * 1e-6, SOLVER_TOL, p_lub * 1e-6, PLUB_OVER_PBAR, C_PROFILE, C_PMAX,
            ROUNDOFF, SOLVER, SOLVER_TOL);
    run_t dry = {0}, lub = {0}, shift = {0}, act = {0}, sweep[NSWEEP];
    double fin_err[2] = {NAN, NAN}; /* profile errors of the finest mesh, dry and lubricated */
    memset(sweep, 0, sizeof sweep);
    int rc = MC_OK;
    vf_text(ctx, "| cells per wavelength | a/dx (lubricated) | profile error dry / lub (q0) | "
                 "iterations dry / lub | time (s) |\n|---|---|---|---|---|\n");
    for (int k = 0; k < nN && rc == MC_OK; k++) {
        s.nx = Ns[k];
        s.dx = WAVELENGTH / s.nx;
        if ((rc = write_surface(ctx, &s, &err)) != MC_OK)
            break;
        run_free(&dry);
        run_free(&lub);
        if ((rc = solve(&s, 0, s.pbar, MC_METHOD_CG, &dry, &err)) != MC_OK ||
            (rc = solve(&s, p_lub, s.pbar, MC_METHOD_CG, &lub, &err)) != MC_OK)
            break;
        double ad, al, pmd, pml;
        double q0d = westergaard(&s, s.pbar, 0, &ad), q0l = westergaard(&s, s.pbar - p_lub, 0, &al);
        double ed = profile_error(&s, &dry, s.pbar, &pmd);
        double el = profile_error(&s, &lub, s.pbar - p_lub, &pml);
        fin_err[0] = ed;
        fin_err[1] = el;
        double hd = (s.dx / ad) * (s.dx / ad), hl = (s.dx / al) * (s.dx / al);
        char id[64], q[200];
        snprintf(id, sizeof id, "profile_dry_N%d", s.nx);
        snprintf(q, sizeof q, "dry: max |p - p_W| / q0 for |x| < 0.8a, %d cells", s.nx);
        vf_check(ctx, id, q, "Westergaard (Johnson 1985 13.2)", 0, ed, C_PROFILE * hd, VF_MAX);
        snprintf(id, sizeof id, "profile_lub_N%d", s.nx);
        snprintf(q, sizeof q, "lubricated: max |p - p_lub - p_W| / q0 for |x| < 0.8a, %d cells",
                 s.nx);
        vf_check(ctx, id, q, "p_lub + Westergaard(p_mean - p_lub)", 0, el, C_PROFILE * hl,
                 VF_MAX);
        snprintf(id, sizeof id, "pmax_lub_N%d", s.nx);
        snprintf(q, sizeof q, "lubricated: (p_max - p_lub) / q0, %d cells", s.nx);
        vf_check(ctx, id, q, "Westergaard peak", 1, (pml - p_lub) / q0l, C_PMAX * hl, VF_ABS);
        snprintf(id, sizeof id, "half_width_dry_N%d", s.nx);
        snprintf(q, sizeof q, "dry: contact half-width / dx from the contact cells, %d cells",
                 s.nx);
        vf_check(ctx, id, q, "Westergaard a", ad / s.dx, dry.a_cells / s.dx, HALF_CELLS, VF_ABS);
        snprintf(id, sizeof id, "half_width_lub_N%d", s.nx);
        snprintf(q, sizeof q, "lubricated: contact half-width / dx, %d cells", s.nx);
        vf_check(ctx, id, q, "Westergaard a(p_mean - p_lub)", al / s.dx, lub.a_cells / s.dx,
                 HALF_CELLS, VF_ABS);
        snprintf(id, sizeof id, "iterations_dry_N%d", s.nx);
        vf_info(ctx, id, "cg iterations, dry", "regression only", NAN, dry.iterations);
        vf_regress(ctx, id, VF_TIER_ITER);
        snprintf(id, sizeof id, "iterations_lub_N%d", s.nx);
        vf_info(ctx, id, "cg iterations, lubricated", "regression only", NAN, lub.iterations);
        vf_regress(ctx, id, VF_TIER_ITER);
        vf_text(ctx, "| %d | %.1f | %.2e / %.2e | %d / %d | %.3f |\n", s.nx, al / s.dx, ed, el,
                dry.iterations, lub.iterations, dry.time + lub.time);
        (void)q0d;
        (void)pmd;
    }
    if (rc != MC_OK) {
        vf_fail(ctx, "solve", "nx = %d: %s", s.nx, err.msg);
        run_free(&dry);
        run_free(&lub);
        return 1;
    }
    /* the finest mesh (still in s, dry, lub): the floor, the split, the identities */
    double al, q0l = westergaard(&s, s.pbar - p_lub, 0, &al);
    double below = 0, off_floor = 0;
    for (int i = 0; i < lub.nx; i++) {
        below = vf_worst(below, (p_lub - lub.p[i]) / p_lub);
        if (lub.gap[i] > GAP_OPEN * AMPLITUDE)
            off_floor = vf_worst(off_floor, fabs(lub.p[i] - p_lub) / p_lub);
    }
    /* information, not checks: the solver projects every iterate onto p >= p_lub (so the floor
     * holds exactly by construction), and a force-controlled solve enforces the load (so the
     * split is its own stopping test); none of the three can fail. What tests the floor is the
     * independent solve below: rigid_shift (p_lub + the dry solve at load - p_lub L) and
     * active_vs_cg (another solver). */
    vf_info(ctx, "floor_min", "max (p_lub - p) / p_lub over all cells (p never below the floor)",
            "by construction: the solver projects onto p >= p_lub", NAN, vf_worst(below, 0));
    vf_info(ctx, "floor_outside",
            "max |p - p_lub| / p_lub over the cells with an open gap (the floor outside contact)",
            "by construction: the solver's complementarity", NAN, off_floor);
    double W = s.pbar * WAVELENGTH, split = fabs((lub.solid_load + p_lub * lub.free_len) / W - 1);
    vf_info(ctx, "load_split",
            "(F_solid + p_lub L_free) / F - 1 (F_solid: the pressure of the contact cells)",
            "by construction: the load a force-controlled solve enforces", NAN, split);
    vf_regress(ctx, "load_split", VF_TIER_PLAN);
    rc = solve(&s, 0, s.pbar - p_lub, MC_METHOD_CG, &shift, &err);
    if (rc == MC_OK)
        rc = solve(&s, p_lub, s.pbar, MC_METHOD_ACTIVE_SET, &act, &err);
    for (int k = 0; k < NSWEEP && rc == MC_OK; k++)
        rc = solve(&s, 0.1 * k * s.pbar, s.pbar, MC_METHOD_CG, &sweep[k], &err);
    if (rc != MC_OK) {
        vf_fail(ctx, "solve", "nx = %d: %s", s.nx, err.msg);
    } else {
        double dshift = 0, dact = 0, dmin = INFINITY, dmax = -INFINITY, umin = INFINITY,
               umax = -INFINITY;
        for (int i = 0; i < lub.nx; i++) {
            dshift = vf_worst(dshift, fabs(lub.p[i] - p_lub - shift.p[i]));
            dact = vf_worst(dact, fabs(act.p[i] - lub.p[i]));
            double du = lub.u[i] - shift.u[i];
            dmin = vf_least(dmin, du);
            dmax = vf_worst(dmax, du);
            umin = vf_least(umin, shift.u[i]);
            umax = vf_worst(umax, shift.u[i]);
        }
        vf_check(ctx, "shift_principle",
                 "max |p(p_lub) - p_lub - p(0; load - p_lub L)| / q0 (the excess pressure is "
                 "the dry solution under the remaining load)",
                 "plastic-lubrication.md 5.1", 0, dshift / q0l, SOLVER, VF_MAX);
        vf_check(ctx, "rigid_shift",
                 "spread of u(p_lub) - u(0; load - p_lub L) / range of u (a uniform pressure on a "
                 "periodic patch moves the surface rigidly)",
                 "periodic Love operator: K 1 uniform", 0, (dmax - dmin) / (umax - umin), RIGID,
                 VF_MAX);
        vf_check(ctx, "active_vs_cg",
                 "lubricated: max |p(active set) - p(cg)| / q0 (the paper's solver)",
                 "cg solve", 0, dact / q0l, SOLVER, VF_MAX);
        int notup = 0, notdown = 0;
        for (int k = 0; k + 1 < NSWEEP; k++) {
            notup += !(sweep[k + 1].mean_gap > sweep[k].mean_gap);
            notdown += !(sweep[k + 1].solid_load / sweep[k + 1].load <
                         sweep[k].solid_load / sweep[k].load);
        }
        vf_check(ctx, "pockets_open",
                 "steps of p_lub = 0, 0.1, ..., 0.5 p_mean where the mean gap does not grow "
                 "(of 5)",
                 "plastic-lubrication.md 5.1: V(p_lub) increasing", 0, notup, 0, VF_MAX);
        vf_check(ctx, "solid_share_falls",
                 "steps where the solid load fraction psi_F does not fall (of 5)",
                 "plastic-lubrication.md 5.2", 0, notdown, 0, VF_MAX);
        vf_info(ctx, "mean_gap_dry", "mean gap without lubricant pressure (um)", "regression only",
                NAN, dry.mean_gap * 1e6);
        vf_info(ctx, "mean_gap_lub", "mean gap with the lubricant pressure (um)",
                "regression only", NAN, lub.mean_gap * 1e6);
        vf_text(ctx,
                "\nOn the finest mesh (%d cells per wavelength): the contact half-width falls "
                "from %.4f L (dry) to %.4f L (Westergaard: %.4f L), the mean gap (pocket volume "
                "per area) grows from %.4f um to %.4f um, and the solid contacts carry %.1f %% "
                "of the load (the lubricant the rest). Active set: %d iterations (cg %d).\n\n",
                lub.nx, dry.a_cells / WAVELENGTH, lub.a_cells / WAVELENGTH, al / WAVELENGTH,
                dry.mean_gap * 1e6, lub.mean_gap * 1e6, 100 * lub.solid_load / lub.load,
                act.iterations, lub.iterations);
        write_csv(ctx, &s, &dry, &lub, sweep, fin_err, split);
        plots(ctx);
    }
    run_free(&dry);
    run_free(&lub);
    run_free(&shift);
    run_free(&act);
    for (int k = 0; k < NSWEEP; k++)
        run_free(&sweep[k]);
    return rc == MC_OK ? 0 : 1;
}
