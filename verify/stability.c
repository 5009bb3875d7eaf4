/* stability.c - suite `stability`: numerical stability stress tests. A matrix of extreme scenes
 * (a single element in contact, full contact, roughness that dwarfs the elastic deformation,
 * anisotropic cells, Poisson's ratio 0 and 0.5, moduli 1:1000, lubricant pressure near the mean
 * pressure, a heavy pressure cap, 1 x n grids, a periodic 2048^2 rough surface, heights of 1e-12 m
 * and 1e-2 m, loads over ten decades) x both operator backends x the solvers that apply.
 *
 * Every run must converge with its conditions satisfied - checked here from the output arrays
 * alone: the stopping measure of contact.h recomputed on a gap rebuilt as topography + K p -
 * approach (our own operator plan: load balance and complementarity), the bounds of p, the gap
 * identity and u = K p. Only a scene designed to hit a solver limit (its row names the reason,
 * st_scene.may_stop) may stop short, and must then report non-convergence honestly. No output
 * may be NaN/Inf and no run may crash: each run is a forked child, so a crash (or a hang: a
 * time limit) is recorded as a failed check instead of ending the suite. The scene builders, the
 * measures and the checks live in this file; stability_run.c forks, limits and collects the
 * runs. (Over 800 lines: a scene row, its builder, its measure and its checks are read together;
 * the process machinery is already apart.)
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/threads.h"
#include "contact/contact.h"
#include "harness.h"
#include "reference/hertz.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "stability_run.h"
#include "suites.h"

/* ---- the scenes ------------------------------------------------------------------------------ */

#define R_SPHERE 10e-3  /* combined radius of the sphere scenes, m */
#define W_BASE 1.0      /* load of the sphere scenes, N: Hertz a = 40.2 um, p0 = 297 MPa (steel) */
#define A_CELLS 5.0     /* contact radius / dx of the 24^2 sphere scenes (the grid spans +-2.4 a) */
#define N_SMALL 24      /* the small grid: every method applies (active-set <= 24^2) */
#define DIRECT_MAX_CELLS 4096    /* the O(N^2) direct backend is run up to 64^2 */
#define ACTIVE_MAX_CELLS 576     /* the O(N^3) active set is run up to 24^2 */
#define ROUGH_FACTOR 1000.0      /* rq of the very rough scenes / the Hertz approach */
#define LINE_LOAD 1e5            /* line contacts: 100 N/mm */
#define P_PERIODIC 5.8e8         /* nominal pressure of the periodic rough scenes: ~10 % contact */

static double sphere_a(const mc_scene *sc, double W)
{
    mc_hertz_point hz;
    mc_error err = {0};
    if (mc_hertz_point_from_load(R_SPHERE, mc_scene_estar(sc), W, &hz, &err) != MC_OK)
        return NAN;
    return hz.a;
}

/* A sphere of R_SPHERE under force W on an nx x ny grid of cells a/cells_per_a (materials as
 * already set in sc). */
static void sphere(mc_scene *sc, int nx, int ny, double W, double cells_per_a)
{
    double dx = sphere_a(sc, W) / cells_per_a;
    sc->grid.nx = nx;
    sc->grid.ny = ny;
    sc->grid.dx = sc->grid.dy = dx;
    sc->geometry.shape = MC_SHAPE_SPHERE;
    sc->geometry.radius = R_SPHERE;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = W;
}

static void b_sphere(mc_scene *sc, double arg)
{
    (void)arg;
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
}

/* One element in contact: 23^2 (a cell centre at the apex), dx = 2 um; a load of arg N. The
 * neighbours stay open while the centre cell's own displacement, 4 d ln(1 + sqrt 2) p / (pi E*),
 * minus theirs (~0.8 p d / E*) is below their initial gap d^2/2R: p < 1.4e7 Pa, W < 6e-5 N. */
#define ONE_CELL_DX 2e-6
static void b_single_cell(mc_scene *sc, double arg)
{
    sphere(sc, 23, 23, arg, 1.0);
    sc->grid.dx = sc->grid.dy = ONE_CELL_DX;
}

/* Flat punch: every cell in contact. arg = cells per side; approach 0.1 um. */
static void b_punch(mc_scene *sc, double arg)
{
    sc->grid.nx = sc->grid.ny = (int)arg;
    sc->grid.dx = sc->grid.dy = 10e-6;
    sc->load.kind = MC_LOAD_APPROACH;
    sc->load.value = 0.1e-6;
}

static void b_flat_force(mc_scene *sc, double arg)
{
    sc->grid.nx = sc->grid.ny = N_SMALL;
    sc->grid.dx = sc->grid.dy = 10e-6;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = arg;
}

/* Sphere plus roughness of rq = ROUGH_FACTOR x the Hertz approach; arg = cells per side. */
static void rough(mc_scene *sc, double arg, mc_roughness_type type)
{
    sphere(sc, (int)arg, (int)arg, W_BASE, A_CELLS);
    double a = sphere_a(sc, W_BASE);
    sc->roughness.type = type;
    sc->roughness.rq = ROUGH_FACTOR * a * a / R_SPHERE;
    if (type == MC_ROUGH_GAUSSIAN)
        sc->roughness.correlation_x = sc->roughness.correlation_y = 2 * sc->grid.dx;
}
static void b_rough_gauss(mc_scene *sc, double arg) { rough(sc, arg, MC_ROUGH_GAUSSIAN); }
static void b_rough_sa(mc_scene *sc, double arg) { rough(sc, arg, MC_ROUGH_SELF_AFFINE); }

/* dx/dy = arg: the sphere of W_BASE (a = 40 um) on cells of 4 um x 40 um (or the transpose). */
static void b_aspect(mc_scene *sc, double arg)
{
    sphere(sc, arg > 1 ? 8 : 64, arg > 1 ? 64 : 8, W_BASE, 1.0);
    double a = sphere_a(sc, W_BASE), fine = a / 10;
    sc->grid.dx = arg > 1 ? fine * arg : fine;
    sc->grid.dy = arg > 1 ? fine : fine / arg;
}

static void b_nu_both(mc_scene *sc, double arg)
{
    sc->body1.nu = sc->body2.nu = arg;
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
}

static void b_nu_rigid(mc_scene *sc, double arg)
{
    sc->body1.nu = arg;
    sc->body2.rigid = 1;
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
}

static void b_moduli(mc_scene *sc, double arg)
{
    sc->body1.E = arg * sc->body2.E;
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
}

/* Lubricant pressure arg x W / A_nominal. */
static void b_lub(mc_scene *sc, double arg)
{
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
    double area = sc->grid.nx * sc->grid.dx * sc->grid.ny * sc->grid.dy;
    sc->load.lubricant_pressure = arg * W_BASE / area;
}

/* Pressure cap arg x the Hertz p0; arg < 0 on the 64^2 grid (same domain, finer cells). */
static void b_cap(mc_scene *sc, double arg)
{
    int n = arg < 0 ? 64 : N_SMALL;
    sphere(sc, n, n, W_BASE, A_CELLS * n / N_SMALL);
    mc_hertz_point hz;
    mc_error err = {0};
    mc_hertz_point_from_load(R_SPHERE, mc_scene_estar(sc), W_BASE, &hz, &err);
    sc->load.pressure_cap = fabs(arg) * hz.p0;
}

/* Line contact: a cylinder (curvature in x) periodic in y, ny = 1; half-width b = 105 um. */
static void b_line_x(mc_scene *sc, double arg)
{
    mc_hertz_line hl;
    mc_error err = {0};
    mc_hertz_line_from_load(R_SPHERE, mc_scene_estar(sc), LINE_LOAD, &hl, &err);
    sc->grid.nx = (int)arg;
    sc->grid.ny = 1;
    sc->grid.dx = sc->grid.dy = hl.b / 10;
    sc->grid.periodic_y = 1;
    sc->geometry.shape = MC_SHAPE_CYLINDER;
    sc->geometry.radius = R_SPHERE;
    sc->load.kind = MC_LOAD_FORCE_PER_LENGTH;
    sc->load.value = LINE_LOAD;
}

/* The same line contact turned: nx = 1, periodic in x, curvature in y (an ellipsoid whose x
 * radius does not matter on the single column x = 0); force = the line load x the period. */
static void b_line_y(mc_scene *sc, double arg)
{
    mc_hertz_line hl;
    mc_error err = {0};
    mc_hertz_line_from_load(R_SPHERE, mc_scene_estar(sc), LINE_LOAD, &hl, &err);
    sc->grid.nx = 1;
    sc->grid.ny = (int)arg;
    sc->grid.dx = sc->grid.dy = hl.b / 10;
    sc->grid.periodic_x = 1;
    sc->geometry.shape = MC_SHAPE_ELLIPSOID;
    sc->geometry.radius_x = 1.0;
    sc->geometry.radius_y = R_SPHERE;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = LINE_LOAD * sc->grid.dx;
}

/* One free row (column) of cells through a sphere, no periodicity: arg > 0 a row, < 0 a column. */
static void b_strip(mc_scene *sc, double arg)
{
    int n = (int)fabs(arg);
    sphere(sc, arg > 0 ? n : 1, arg > 0 ? 1 : n, 0.01, 1.0);
    sc->grid.dx = sc->grid.dy = 5e-6;
}

/* Periodic self-affine surface (H = 0.8, rms slope 0.1, cut-offs L and 2 dx) on a flat, dx = 1 um,
 * nominal pressure P_PERIODIC: ~10 % contact (11.4 % at 256^2, 10.3 % at 2048^2). */
static void b_periodic(mc_scene *sc, double arg)
{
    sc->grid.nx = sc->grid.ny = (int)arg;
    sc->grid.dx = sc->grid.dy = 1e-6;
    sc->grid.periodic_x = sc->grid.periodic_y = 1;
    sc->roughness.type = MC_ROUGH_SELF_AFFINE;
    sc->roughness.rms_slope = 0.1;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = P_PERIODIC * (arg * 1e-6) * (arg * 1e-6);
}

/* The sphere scene of b_sphere scaled by L so that its largest height is arg (m): R, dx, dy times
 * L, the load times L^2. Pressures are invariant under this similarity, the approach scales by
 * L. */
static double height_scale(double target)
{
    mc_scene s;
    mc_scene_defaults(&s);
    b_sphere(&s, 0);
    double r = hypot(mc_grid_x(&s.grid, 0), mc_grid_y(&s.grid, 0));
    return target / (r * r / (2 * R_SPHERE));
}

static void b_height(mc_scene *sc, double arg)
{
    double L = height_scale(arg);
    b_sphere(sc, 0);
    sc->geometry.radius *= L;
    sc->grid.dx *= L;
    sc->grid.dy *= L;
    sc->load.value *= L * L;
}

/* Gaussian roughness of rq = arg on a flat, approach control with the approach = rq. */
static void b_rough_flat(mc_scene *sc, double arg)
{
    sc->grid.nx = sc->grid.ny = N_SMALL;
    sc->grid.dx = sc->grid.dy = 1e-6;
    sc->roughness.type = MC_ROUGH_GAUSSIAN;
    sc->roughness.rq = arg;
    sc->roughness.correlation_x = sc->roughness.correlation_y = 2e-6;
    sc->load.kind = MC_LOAD_APPROACH;
    sc->load.value = arg;
}

/* Sphere on 64^2 cells of 5 um (1 N: a = 8 dx) under the load arg: from sub-cell (1e-6 N,
 * a = 0.4 um) to a contact far larger than the grid (1e4 N, a = 0.86 mm: every cell loaded). */
static void b_load(mc_scene *sc, double arg)
{
    sphere(sc, 64, 64, arg, 1.0);
    sc->grid.dx = sc->grid.dy = 5e-6;
}

/* Pressure cap and lubricant together: cap arg (Pa), lubricant 10 MPa = 0.37 W/A_nominal. The
 * active set used to end with every contact cell at the cap and none free, the load unbalanced
 * (by 1.4 % at a cap of 100 MPa, 19 % at 60 MPa), and report it converged. */
static void b_cap_lub(mc_scene *sc, double arg)
{
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
    sc->load.pressure_cap = arg;
    sc->load.lubricant_pressure = 10e6;
}

/* Periodic in x and y, gaussian rq = 0.1 um (correlation 3 um) on a flat of arg^2 cells of 1 um,
 * nominal pressure 49 MPa. The kernel has zero mean there (K 1 = 0): K is singular. */
static void b_periodic_small(mc_scene *sc, double arg)
{
    sc->grid.nx = sc->grid.ny = (int)arg;
    sc->grid.dx = sc->grid.dy = 1e-6;
    sc->grid.periodic_x = sc->grid.periodic_y = 1;
    sc->roughness.type = MC_ROUGH_GAUSSIAN;
    sc->roughness.rq = 0.1e-6;
    sc->roughness.correlation_x = sc->roughness.correlation_y = 3e-6;
    sc->load.kind = MC_LOAD_FORCE;
    sc->load.value = 4.9e7 * (arg * 1e-6) * (arg * 1e-6);
}

/* A sphere on a grid periodic in x and y (an array of spheres) under approach control, 0.1 um:
 * feasible, because the mean initial gap (0.31 um) exceeds the approach (the displacement has
 * zero mean there, so the mean gap after loading is mean(h) - approach). */
static void b_periodic_sphere_approach(mc_scene *sc, double arg)
{
    (void)arg;
    sphere(sc, N_SMALL, N_SMALL, W_BASE, A_CELLS);
    sc->grid.periodic_x = sc->grid.periodic_y = 1;
    sc->load.kind = MC_LOAD_APPROACH;
    sc->load.value = 0.1e-6;
}

/* The same rough flat as b_periodic_small (24^2) under approach control, 0.05 um: no solution
 * exists - the mean gap after loading is mean(h) - approach = -0.05 um whatever the pressure -
 * so the only right answer is a clear input error. */
static void b_periodic_flat_approach(mc_scene *sc, double arg)
{
    b_periodic_small(sc, N_SMALL);
    sc->load.kind = MC_LOAD_APPROACH;
    sc->load.value = arg;
}

/* The line contact of b_line_x scaled by L = arg: cells, radius and the line load times L
 * (pressures are invariant; the approach of a line contact is not - the log kernel's constant
 * is in metres, operator.h). */
static void b_line_scaled(mc_scene *sc, double arg)
{
    b_line_x(sc, 64);
    sc->grid.dx *= arg;
    sc->grid.dy *= arg;
    sc->geometry.radius *= arg;
    sc->load.value *= arg;
}

/* The sphere with the solver held short: at most arg iterations (non-convergence must be
 * reported as such), or (arg < 1) the tolerance arg, at the lower limit of the case files. */
static void b_solver_limit(mc_scene *sc, double arg)
{
    b_sphere(sc, 0);
    if (arg >= 1)
        sc->solver.max_iterations = (int)arg;
    else
        sc->solver.tolerance = arg;
}

/* Combos: bit (backend * 3 + method). */
enum { FC = 1, FP = 2, FA = 4, DC = 8, DP = 16, DA = 32, ALL = 63, FFT_ALL = 7, NONE = 0 };
static const mc_backend combo_backend[6] = {MC_BACKEND_FFT,    MC_BACKEND_FFT,
                                            MC_BACKEND_FFT,    MC_BACKEND_DIRECT,
                                            MC_BACKEND_DIRECT, MC_BACKEND_DIRECT};
static const mc_contact_method combo_method[6] = {MC_METHOD_CG, MC_METHOD_PK, MC_METHOD_ACTIVE_SET,
                                                  MC_METHOD_CG, MC_METHOD_PK,
                                                  MC_METHOD_ACTIVE_SET};

enum {
    X_NONE,
    X_ONE_CELL,  /* exactly one cell loaded, approach from Love's square */
    X_FULL,      /* every cell in contact */
    X_SIMILAR,   /* p_max and approach / L as the base scene's (geometry scaled by L) */
    X_SIMILAR_P, /* p_max as the base scene's (the approach is not scale-covariant) */
    X_INFEASIBLE /* no solution exists: an input error is the only right answer */
};

typedef struct {
    const char *id;
    const char *family; /* the bullet of the issue it belongs to */
    const char *what;   /* the scene in words */
    void (*build)(mc_scene *, double);
    double arg;
    unsigned fast, full; /* combos run in the fast and the full variant (where they apply) */
    int stress;          /* also run the stress stage (cg runs) */
    int extra;           /* scene-specific check */
    int timeout;         /* s, per run */
    const char *base;    /* X_SIMILAR, X_SIMILAR_P: the unscaled scene */
    int as_cells;        /* active-set cell limit for this scene (0: ACTIVE_MAX_CELLS) */
    /* Whether the scene must converge, stated by every row (-Wextra refuses a row without it):
     * MUST_CONVERGE (NULL): every run must end converged, else check `converged` fails. A
     * string only for a scene designed to hit a solver limit: the one-line reason why it may
     * stop short (its non-convergence must then be reported honestly, check `honest`); for an
     * X_INFEASIBLE scene, why it is not solved (check `refused`). */
    const char *may_stop;
} st_scene;

#define T_DEF 120
#define MUST_CONVERGE NULL /* st_scene.may_stop of a scene whose every run must converge */
static const st_scene scenes[] = {
    {"sphere", "reference", "sphere R = 10 mm, 1 N, steel, 24^2, a/dx = 5", b_sphere, 0, ALL, ALL,
     0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"iter_limit", "solver limits", "the sphere scene with max_iterations = 2: not converged, "
                                    "reported honestly",
     b_solver_limit, 2, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0,
     "designed to hit max_iterations: 2 iterations cannot reach the tolerance"},
    {"tol_1e-15", "solver limits", "the sphere scene with tolerance 1e-15 (the lower limit)",
     b_solver_limit, 1e-15, ALL & ~DP, ALL, 0, X_NONE, T_DEF, NULL, 0,
     "tolerance at round-off: the stopping measure's floor here is ~1e-15 (reaching it is luck)"},
    {"one_cell", "single element",
     "sphere, 1e-5 N on 23^2 cells of 2 um: only the apex cell loaded",
     b_single_cell, 1e-5, ALL, ALL, 1, X_ONE_CELL, T_DEF, NULL, 0, MUST_CONVERGE},
    {"punch", "full contact", "flat punch 24^2 x 10 um, approach 0.1 um", b_punch, 24, ALL, ALL, 1,
     X_FULL, T_DEF, NULL, 0, MUST_CONVERGE},
    {"punch_256", "full contact", "flat punch 256^2 x 10 um, approach 0.1 um", b_punch, 256, FC,
     FC | FP, 0, X_FULL, T_DEF, NULL, 0, MUST_CONVERGE},
    {"flat_force", "full contact", "flat 24^2 x 10 um under 10 N (force control)", b_flat_force, 10,
     ALL, ALL, 0, X_FULL, T_DEF, NULL, 0, MUST_CONVERGE},
    {"rough_gauss", "very rough", "sphere 24^2 + gaussian rq = 1000 x Hertz approach (160 um), "
                                  "correlation 2 dx",
     b_rough_gauss, 24, ALL, ALL, 1, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"rough_gauss_64", "very rough", "as rough_gauss on 64^2", b_rough_gauss, 64, FC, ALL, 0,
     X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"rough_sa", "very rough", "sphere 24^2 + self-affine rq = 1000 x Hertz approach, H = 0.8",
     b_rough_sa, 24, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"rough_sa_64", "very rough", "as rough_sa on 64^2", b_rough_sa, 64, NONE, ALL, 0, X_NONE,
     T_DEF, NULL, 0, MUST_CONVERGE},
    {"dxdy_10", "anisotropic cells", "sphere 1 N, 8 x 64 cells of 40 x 4 um (dx/dy = 10)",
     b_aspect, 10, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"dxdy_0.1", "anisotropic cells", "sphere 1 N, 64 x 8 cells of 4 x 40 um (dx/dy = 0.1)",
     b_aspect, 0.1, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"nu_0", "Poisson's ratio", "sphere 1 N, both bodies nu = 0", b_nu_both, 0.0, FC | FP | FA,
     ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"nu_0.5", "Poisson's ratio", "sphere 1 N, both bodies nu = 0.5 (incompressible)", b_nu_both,
     0.5, FC | FP | FA, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"nu_0_rigid", "Poisson's ratio", "sphere 1 N, body 1 nu = 0 on a rigid body 2", b_nu_rigid,
     0.0, FC, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"nu_0.5_rigid", "Poisson's ratio", "sphere 1 N, body 1 nu = 0.5 on a rigid body 2",
     b_nu_rigid, 0.5, FC | DC, ALL, 1, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"E1_E2_1e-3", "moduli 1:1000", "sphere 1 N, E1 = 0.21 GPa, E2 = 210 GPa", b_moduli, 1e-3,
     FC | FP | FA, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"lub_0.9", "lubricant", "sphere 1 N, lubricant pressure 0.9 W / A_nominal", b_lub, 0.9,
     FC | FP | FA, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"lub_0.99", "lubricant", "sphere 1 N, lubricant pressure 0.99 W / A_nominal", b_lub, 0.99,
     FC | FP | FA, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"lub_1.01", "lubricant", "sphere 1 N, lubricant pressure 1.01 W / A_nominal: the lubricant "
                              "alone would carry more than W (issue 15: refused, no silent load)",
     b_lub, 1.01, FC | FP | FA, ALL, 0, X_INFEASIBLE, T_DEF, NULL, 0,
     "the requested load cannot be met: the run must be refused as an input error (check "
     "`refused`)"},
    {"cap_0.3p0", "pressure cap", "sphere 1 N, cap 0.3 p0 (Hertz p0 = 297 MPa), 24^2", b_cap, 0.3,
     ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"cap_0.3p0_64", "pressure cap", "as cap_0.3p0 on 64^2 (same domain)", b_cap, -0.3, FC | FP,
     ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"cap_0.13p0", "pressure cap", "sphere 1 N, cap 40 MPa (0.13 p0), 24^2", b_cap, 40e6 / 297e6,
     ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"cap_lub_100", "pressure cap", "sphere 1 N, cap 100 MPa (0.34 p0) and lubricant 10 MPa "
                                    "(0.37 W/A_nominal)",
     b_cap_lub, 100e6, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"cap_lub_60", "pressure cap", "sphere 1 N, cap 60 MPa (0.2 p0) and lubricant 10 MPa",
     b_cap_lub, 60e6, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"line_x", "1 x n grids", "cylinder 100 N/mm, 64 x 1 cells, periodic in y (plane strain)",
     b_line_x, 64, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"line_y", "1 x n grids", "the same line contact turned: 1 x 64 cells, periodic in x",
     b_line_y, 64, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"row_free", "1 x n grids", "sphere 0.01 N, one free row of 64 cells of 5 um", b_strip, 64,
     ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"col_free", "1 x n grids", "sphere 0.01 N, one free column of 64 cells of 5 um", b_strip, -64,
     ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"periodic_256", "periodic rough", "periodic self-affine 256^2 x 1 um, rms slope 0.1, "
                                       "580 MPa nominal",
     b_periodic, 256, FC | FP, FC | FP, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"periodic_512", "periodic rough", "as periodic_256 on 512^2", b_periodic, 512, NONE, FC | FP,
     0, X_NONE, 300, NULL, 0, MUST_CONVERGE},
    {"periodic_2048", "periodic rough", "as periodic_256 on 2048^2 (~10 % contact)", b_periodic,
     2048, NONE, FC, 0, X_NONE, 590, NULL, 0, MUST_CONVERGE},
    {"height_1e-12", "heights 1e-12 m / 1e-2 m", "the sphere scene scaled to heights <= 1e-12 m "
                                                  "(load x L^2)",
     b_height, 1e-12, ALL, ALL, 0, X_SIMILAR, T_DEF, "sphere", 0, MUST_CONVERGE},
    {"height_1e-2", "heights 1e-12 m / 1e-2 m", "the sphere scene scaled to heights <= 1e-2 m",
     b_height, 1e-2, ALL, ALL, 0, X_SIMILAR, T_DEF, "sphere", 0, MUST_CONVERGE},
    {"rough_1e-12_flat", "heights 1e-12 m / 1e-2 m", "flat 24^2 x 1 um, gaussian rq = 1e-12 m, "
                                                      "approach 1e-12 m",
     b_rough_flat, 1e-12, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
#define LOAD_SCENE(id, W, fastmask)                                                                \
    {id, "loads over ten decades", "sphere, 64^2 x 5 um, load " #W " N", b_load, W, fastmask,    \
     FC | FP | DC | DP, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE}
    {"line_x_1e4", "heights 1e-12 m / 1e-2 m", "line_x scaled by 1e4 (cells of 0.105 m, R = 100 m, "
                                                "1e9 N/m): the log kernel's constant matters",
     b_line_scaled, 1e4, ALL, ALL, 0, X_SIMILAR_P, T_DEF, "line_x", 0, MUST_CONVERGE},
    {"periodic_4", "periodic", "periodic in x and y, 4 x 4 cells of 1 um, gaussian rq = 0.1 um, "
                               "49 MPa nominal (K is singular: zero mean)",
     b_periodic_small, 4, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"periodic_32", "periodic", "as periodic_4 on 32 x 32 cells (active set allowed)",
     b_periodic_small, 32, ALL, ALL, 0, X_NONE, T_DEF, NULL, 1024, MUST_CONVERGE},
    {"periodic_sphere_approach", "periodic", "sphere 24^2 periodic in x and y, approach 0.1 um < "
                                             "mean initial gap 0.31 um (feasible)",
     b_periodic_sphere_approach, 0, ALL, ALL, 0, X_NONE, T_DEF, NULL, 0, MUST_CONVERGE},
    {"periodic_flat_approach", "periodic", "periodic_4's surface on 24^2, approach 0.05 um: no "
                                           "solution exists (mean gap = -approach)",
     b_periodic_flat_approach, 0.05e-6, ALL, ALL, 0, X_INFEASIBLE, T_DEF, NULL, 0,
     "no solution exists: the run must be refused as an input error (check `refused`)"},
    LOAD_SCENE("load_1e-6", 1e-6, FC | FP | DC),
    LOAD_SCENE("load_1e-5", 1e-5, FC),
    LOAD_SCENE("load_1e-4", 1e-4, FC),
    LOAD_SCENE("load_1e-3", 1e-3, FC),
    LOAD_SCENE("load_1e-2", 1e-2, FC | FP),
    LOAD_SCENE("load_1e-1", 1e-1, FC),
    LOAD_SCENE("load_1e0", 1e0, FC | FP | DC),
    LOAD_SCENE("load_1e1", 1e1, FC),
    LOAD_SCENE("load_1e2", 1e2, FC | FP),
    LOAD_SCENE("load_1e3", 1e3, FC),
    LOAD_SCENE("load_1e4", 1e4, FC | FP | DC),
#undef LOAD_SCENE
};
#define NSCENES (int)(sizeof scenes / sizeof scenes[0])

static void build_scene(const st_scene *s, int combo, mc_scene *sc)
{
    mc_scene_defaults(sc);
    s->build(sc, s->arg);
    sc->solver.backend = combo_backend[combo];
    sc->solver.method = combo_method[combo];
    /* one thread: GNU libgomp is not fork-safe - a child that starts a team of threads after its
     * parent ran parallel regions waits forever for the parent's (absent) workers */
    sc->solver.threads = 1;
    if (s->stress && combo_method[combo] == MC_METHOD_CG) {
        sc->stress.enabled = 1;
        sc->stress.depth_min = 0;
        sc->stress.depth_max = 0.25 * fmin(sc->grid.nx * sc->grid.dx, sc->grid.ny * sc->grid.dy);
        sc->stress.layers = 4;
    }
}

static int applicable(const st_scene *s, const mc_scene *sc, int combo)
{
    size_t n = mc_grid_cells(&sc->grid);
    size_t as_max = s->as_cells > 0 ? (size_t)s->as_cells : ACTIVE_MAX_CELLS;
    if (combo_backend[combo] == MC_BACKEND_DIRECT && n > DIRECT_MAX_CELLS)
        return 0;
    if (combo_method[combo] == MC_METHOD_ACTIVE_SET && n > as_max)
        return 0;
    return 1;
}

/* Scale factor L of a scaled scene against its base. */
static double scene_scale(const st_scene *s)
{
    return s->build == b_height ? height_scale(s->arg) : s->arg;
}

/* ---- the measures (computed in the child, from the output arrays) ---------------------------- */

static long count_nonfinite(const double *f, size_t n)
{
    long k = 0;
    if (!f)
        return 0;
    for (size_t i = 0; i < n; i++)
        k += !isfinite(f[i]);
    return k;
}

static double max_abs(const double *f, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = vf_worst(m, fabs(f[i]));
    return m;
}

/* Gap scale s of the stopping rule, as contact.c computes it (mc_contact_gap_scale): delta minus
 * the least h~, floored at 1e-6 of the range of h~ and 1e-12 of its magnitude. */
static double gap_scale(const double *ht, size_t n, double delta)
{
    double hmin = INFINITY, hmax = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        hmin = vf_least(hmin, ht[i]);
        hmax = vf_worst(hmax, ht[i]);
    }
    double s = delta - hmin, fl = 1e-6 * (hmax - hmin), mag = vf_worst(fabs(hmin), fabs(hmax));
    if (fl < 1e-12 * mag)
        fl = 1e-12 * mag;
    if (!(s > fl))
        s = fl;
    return s > 1e-300 ? s : 1e-300;
}

/* Fill the measures of rec from a finished pipeline run (child side). */
static void measure(const mc_scene *sc, const mc_results *res, st_record *rec)
{
    const mc_grid *g = &res->grid;
    const size_t n = mc_grid_cells(g);
    const mc_contact_summary *c = &res->contact;
    const double A = mc_grid_cell_area(g), plub = sc->load.lubricant_pressure,
                 pcap = sc->load.pressure_cap, delta = c->approach;
    const double *p = res->pressure, *gap = res->gap, *u = res->displacement,
                 *h = res->topography;
    double summ[] = {c->load, c->solid_load, c->p_max, c->area, c->contact_ratio, c->approach,
                     c->residual};
    rec->nonfinite = count_nonfinite(p, n) + count_nonfinite(gap, n) + count_nonfinite(u, n) +
                     count_nonfinite(h, n) + count_nonfinite(summ, sizeof summ / sizeof summ[0]);
    if (!p || !gap || !u || !h)
        rec->nonfinite++;
    if (rec->nonfinite)
        return;

    /* our own K p (and K p_lub), on the backend of the run */
    double *Kp = mc_zeros(n), *ht = mc_zeros(n);
    mc_operator *K = NULL;
    mc_error err = {0};
    if (!Kp || !ht ||
        mc_operator_plan_love(g, mc_scene_estar(sc), sc->solver.backend, &K, &err) != MC_OK) {
        snprintf(rec->measure_msg, sizeof rec->measure_msg,
                 "cannot plan the check operator: %.120s", err.msg);
        mc_free(Kp);
        mc_free(ht);
        return;
    }
    mc_operator_apply(K, p, Kp);
    for (size_t i = 0; i < n; i++)
        ht[i] = plub; /* h~ = h + K p_lub */
    mc_operator_apply(K, ht, ht);
    for (size_t i = 0; i < n; i++)
        ht[i] += h[i];
    mc_operator_destroy(&K);

    double s = gap_scale(ht, n, delta);
    double compl = 0, sum = 0, solid = 0, bnd = 0, gid = 0, mag = 0;
    double M = max_abs(h, n) + max_abs(u, n) + fabs(delta);
    long ncontact = 0;
    for (size_t i = 0; i < n; i++) {
        double gi = h[i] + Kp[i] - delta, v;
        if (p[i] <= plub)
            v = -gi;
        else if (p[i] >= pcap)
            v = gi;
        else
            v = fabs(gi);
        compl = vf_worst(compl, v);
        sum += p[i];
        solid += p[i] - plub;
        ncontact += p[i] > plub;
        bnd = vf_worst(bnd, vf_worst(plub - p[i], p[i] - pcap));
        gid = vf_worst(gid, fabs(gap[i] - (h[i] + u[i] - delta)));
        gid = vf_worst(gid, fabs(u[i] - Kp[i]));
        mag = vf_worst(mag, vf_worst(fabs(ht[i]), fabs(Kp[i])));
    }
    rec->scale = s;
    rec->compl = compl / s;
    rec->kkt_floor = 16 * DBL_EPSILON * (mag + fabs(delta)) / s;
    rec->ncontact = ncontact;
    rec->bounds = vf_worst(bnd, 0) / fmax(fmax(c->p_max, plub), DBL_MIN);
    rec->gapid = M > 0 ? gid / M : gid;
    rec->force = sc->load.kind == MC_LOAD_FORCE || sc->load.kind == MC_LOAD_FORCE_PER_LENGTH;
    rec->load_err = 0;
    if (rec->force) {
        double W = sc->load.value;
        if (sc->load.kind == MC_LOAD_FORCE_PER_LENGTH)
            W *= g->ny * g->dy;
        rec->W = W;
        rec->lub_all = W <= A * (double)n * plub;
        /* the lubricant alone carries more than W: then no solid load may remain */
        rec->load_err = rec->lub_all ? fabs(A * solid) / W : fabs(A * sum - W) / W;
    }
    rec->kkt = vf_worst(rec->compl, rec->load_err);
    /* the summary against the arrays: load, p_max, solid contact area */
    double pmax = -INFINITY;
    for (size_t i = 0; i < n; i++)
        pmax = vf_worst(pmax, p[i]);
    rec->summary_err = vf_worst(fabs(c->load - A * sum) / fmax(fabs(A * sum), DBL_MIN),
                            fabs(c->p_max - pmax) / fmax(fabs(pmax), DBL_MIN));
    rec->summary_err =
        vf_worst(rec->summary_err, fabs(c->area - A * (double)ncontact) / (A * (double)n));
    mc_free(Kp);
    mc_free(ht);

    /* stress stage: finite, and sigma_zz(z = 0) = -p (patch kernel: exact at cell centres) */
    if (res->nlayers > 0) {
        rec->stress_run = 1;
        size_t nv = (size_t)res->nlayers * n;
        long bad = 0;
        for (int k = 0; k < 6; k++)
            bad += count_nonfinite(res->stress[k], nv) + !res->stress[k];
        bad += count_nonfinite(res->von_mises, nv) + count_nonfinite(res->hydrostatic, nv) +
               count_nonfinite(res->tresca, nv);
        const mc_stage_stress_summary *ss = &res->stress_summary;
        double sv[] = {ss->vm_max, ss->hydro_at_vm_max, ss->tresca_max, ss->vm_max_at[2],
                       ss->tresca_max_at[2]};
        bad += count_nonfinite(sv, sizeof sv / sizeof sv[0]);
        rec->stress_nonfinite = bad;
        rec->stress_z0 = res->depths ? res->depths[0] : NAN;
        double e = 0;
        if (!bad && res->stress[2])
            for (size_t i = 0; i < n; i++)
                e = vf_worst(e, fabs(res->stress[2][i] + p[i]));
        rec->szz_err = e / fmax(c->p_max, DBL_MIN);
    }
}

/* Child side: build, run, measure - all on one thread. The scene's thread count holds for the
 * pipeline run only (core/threads.h), so measure() would otherwise plan and apply its operator on
 * the default count and start a thread team: in a child forked after the parent ran parallel
 * regions (another suite before this one, as `verify --fast` does) that team waits forever for
 * the parent's absent workers (GNU libgomp is not fork-safe). */
void st_child_run(int scene, int combo, st_record *rec)
{
    mc_threads_scope one;
    mc_threads_begin(1, &one);
    mc_scene sc;
    build_scene(&scenes[scene], combo, &sc);
    mc_results res;
    mc_error err = {0};
    double t0 = mc_clock();
    rec->status = mc_pipeline_run(&sc, &res, &err);
    rec->time_s = mc_clock() - t0;
    snprintf(rec->msg, sizeof rec->msg, "%.250s", err.msg);
    const mc_contact_summary *c = &res.contact;
    rec->converged = c->converged;
    rec->iterations = c->iterations;
    rec->residual = c->residual;
    rec->load = c->load;
    rec->p_max = c->p_max;
    rec->contact_ratio = c->contact_ratio;
    rec->approach = c->approach;
    rec->capped = c->capped_cells;
    if (rec->status == MC_OK || rec->status == MC_NOT_CONVERGED)
        measure(&sc, &res, rec);
    mc_results_free(&res);
    mc_threads_end(&one);
}

/* ---- checks and report (parent side) -------------------------------------------------------- */

/* Tolerances.
 * KKT_FACTOR: the solver stops when its measure is <= tol; recomputed from the outputs (a fresh
 *   K p from our own plan, the summary approach) it differs only by round-off, so 2 tol catches a
 *   solver that declares convergence on a stale, unprojected or unbalanced iterate. The
 *   round-off floor of the gap itself, 16 eps (max |h~| + max |K p| + |delta|) / s, is added
 *   (it matters only where s is tiny beside the heights).
 * CONSISTENT_TOL, one round-off tier for four identities that hold up to a few roundings:
 *   the bounds (p = p_lub + q with q clipped to [0, p_cap - p_lub]: exact at the lower bound, one
 *   rounding at the cap, relative to p_max); gap = topography + displacement - approach and
 *   displacement = K p (a few additions and one DC-FFT, ~eps log2 N, relative to max|h| +
 *   max|u| + |approach|); the summary's load, p_max and area against the arrays (relative).
 *   Measured <= 1e-14; 1e-12 leaves a factor ~100, and a solver that skips a projection or
 *   reports a stale displacement is off by orders of magnitude more.
 * SIMILAR_TOL: a scaled scene must reproduce the unscaled pressures and approach / L: the
 *   similarity is exact, so only the two solves' tolerances (1e-8 on the gap) separate them,
 *   amplified by the conditioning of the pressure (~a/dx): 1e-6.
 * ONE_CELL_TOL: with one cell loaded, p = W/A and the approach is p times the centre value of
 *   Love's square, 4 d ln(1 + sqrt 2) / (pi E*): round-off tier.
 * SZZ_TOL: sigma_zz(z = 0) = -p holds at cell centres for the patch kernel exactly; the DC-FFT
 *   of the stress tables adds round-off ~eps log N relative to p_max. */
#define KKT_FACTOR 2.0
#define CONSISTENT_TOL 1e-12
#define SIMILAR_TOL 1e-6
#define ONE_CELL_TOL 1e-10
#define SZZ_TOL 1e-10

static const char *result_text(const st_record *r, char *buf, size_t len)
{
    switch (r->outcome) {
    case ST_CRASH:
        snprintf(buf, len, "CRASH (%s)", r->msg);
        return buf;
    case ST_TIMEOUT:
        snprintf(buf, len, "TIMEOUT (%s)", r->msg);
        return buf;
    case ST_LOST:
        snprintf(buf, len, "LOST (%s)", r->msg);
        return buf;
    default:
        break;
    }
    if (r->status == MC_OK)
        snprintf(buf, len, r->converged ? "converged" : "status ok, converged = 0");
    else if (r->status == MC_NOT_CONVERGED)
        snprintf(buf, len, "not converged");
    else
        snprintf(buf, len, "error %s: %s", mc_status_name((mc_status)r->status), r->msg);
    return buf;
}

static void check_run(vf_ctx *ctx, int scene, int combo, const st_record *r, const st_record *base)
{
    const st_scene *s = &scenes[scene];
    mc_scene sc;
    build_scene(s, combo, &sc);
    const double tol = sc.solver.tolerance;
    char id[64], q[160];
    char run[48];
    snprintf(run, sizeof run, "%s.%s.%s", s->id, mc_backend_name(combo_backend[combo]),
             mc_contact_method_name(combo_method[combo]));
#define ID(suffix) (snprintf(id, sizeof id, "%s.%s", run, suffix), id)
    if (r->outcome != ST_DONE) {
        char b[320];
        vf_fail(ctx, ID("run"), "%s", result_text(r, b, sizeof b));
        return;
    }
    if (s->extra == X_INFEASIBLE) { /* the one right answer: refused as bad input, with a reason */
        char b[320];
        snprintf(q, sizeof q, "refused as input error with a message (got: %.100s)",
                 result_text(r, b, sizeof b));
        vf_check(ctx, ID("refused"), q, "no solution exists", 0,
                 (r->status != MC_ERR_INPUT) + (r->msg[0] == 0), 0, VF_MAX);
        return;
    }
    if (r->status != MC_OK && r->status != MC_NOT_CONVERGED) {
        vf_fail(ctx, ID("run"), "error %s: %s", mc_status_name((mc_status)r->status), r->msg);
        return;
    }
    if (r->measure_msg[0]) {
        vf_fail(ctx, ID("measure"), "%s", r->measure_msg);
        return;
    }
    vf_check(ctx, ID("finite"), "non-finite values in p, gap, u, h and the summary",
             "none allowed", 0, (double)r->nonfinite, 0, VF_MAX);
    if (r->nonfinite)
        return;
    int ok = r->status == MC_OK && r->converged;
    if (!s->may_stop) { /* the scene must converge: stopping short is a failure, however honest */
        char b[320];
        snprintf(q, sizeof q, "converged (status MC_OK, converged = 1); got: %.60s, %d iterations, "
                              "residual %.2g",
                 result_text(r, b, sizeof b), r->iterations, r->residual);
        vf_check(ctx, ID("converged"), q, "the scene must converge", 1, ok, 0, VF_ABS);
    }
    if (ok) {
        snprintf(q, sizeof q, "stopping measure recomputed: %s/s, gap from K p%s",
                 r->force ? (r->lub_all ? "solid load/W, complementarity" :
                                          "|A sum p - W|/W, complementarity")
                          : "complementarity",
                 r->capped ? ", cap" : "");
        vf_check(ctx, ID("kkt"), q, "<= 2 tol + round-off", 0, r->kkt,
                 KKT_FACTOR * tol + r->kkt_floor, VF_MAX);
    } else if (s->may_stop) {
        int bad = (r->status != MC_NOT_CONVERGED) + (r->converged != 0) + !(r->residual > tol);
        vf_check(ctx, ID("honest"),
                 "not converged, reported honestly (status, converged = 0, residual > tol)",
                 "0 inconsistencies", 0, bad, 0, VF_MAX);
    }
    vf_check(ctx, ID("consistent"),
             "bounds p_lub <= p <= p_cap (/p_max); gap = h + u - approach, u = K p (/magnitudes); "
             "summary vs arrays",
             "round-off", 0, vf_worst(r->bounds, vf_worst(r->gapid, r->summary_err)), CONSISTENT_TOL,
             VF_MAX);
    if (s->extra == X_ONE_CELL && ok) {
        vf_check(ctx, ID("cells"), "cells in contact", "the apex cell alone", 1,
                 (double)r->ncontact, 0, VF_ABS);
        double d = sc.grid.dx, p = sc.load.value / (d * d);
        double ref = 4 * d * log(1 + sqrt(2.0)) * p / (M_PI * mc_scene_estar(&sc));
        vf_check(ctx, ID("approach"), "approach with one cell loaded",
                 "Love's square: 4 d ln(1+sqrt 2) p/(pi E*)", ref, r->approach, ONE_CELL_TOL,
                 VF_REL);
    }
    if (s->extra == X_FULL && ok)
        vf_check(ctx, ID("full"), "contact ratio", "every cell in contact", 1, r->contact_ratio, 0,
                 VF_ABS);
    if ((s->extra == X_SIMILAR || s->extra == X_SIMILAR_P) && ok) {
        char ref[96];
        snprintf(ref, sizeof ref, "scene `%s`, same backend and method", s->base);
        if (base && base->outcome == ST_DONE && base->status == MC_OK && base->converged) {
            double L = scene_scale(s);
            double e = fabs(r->p_max / base->p_max - 1);
            if (s->extra == X_SIMILAR)
                e = vf_worst(e, fabs(r->approach / (L * base->approach) - 1));
            snprintf(q, sizeof q, "%s against the unscaled scene (L = %.3g)",
                     s->extra == X_SIMILAR ? "p_max and approach / L" : "p_max", L);
            vf_check(ctx, ID("similar"), q, ref, 0, e, SIMILAR_TOL, VF_MAX);
        } else {
            vf_fail(ctx, ID("similar"), "no converged run of %s to compare with", ref);
        }
    }
    if (r->stress_run) {
        vf_check(ctx, ID("stress_finite"), "non-finite stresses, invariants or summary",
                 "none allowed", 0, (double)r->stress_nonfinite, 0, VF_MAX);
        vf_check(ctx, ID("szz0"), "max |sigma_zz(z = 0) + p| / p_max",
                 "sigma_zz = -p at the surface", 0, r->stress_z0 == 0 ? r->szz_err : NAN, SZZ_TOL,
                 VF_MAX);
    }
#undef ID
}

static void write_csv(vf_ctx *ctx, const st_job *jobs, int njobs)
{
    FILE *f = vf_open(ctx, "runs.csv");
    if (!f)
        return;
    fprintf(f, "scene,family,nx,ny,backend,method,outcome,status,converged,iterations,residual,"
               "kkt_recomputed,complementarity,load_err,bounds,gap_identity,contact_ratio,"
               "p_max_Pa,approach_m,capped_cells,time_s,wall_s,message\n");
    for (int k = 0; k < njobs; k++) {
        const st_job *j = &jobs[k];
        const st_record *r = &j->rec;
        mc_scene sc;
        build_scene(&scenes[j->scene], j->combo, &sc);
        char b[320];
        result_text(r, b, sizeof b);
        for (char *c = b; *c; c++)
            if (*c == ',' || *c == '"')
                *c = ';';
        fprintf(f, "%s,%s,%d,%d,%s,%s,%s,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.9g,%.9g,"
                   "%d,%.4f,%.4f,%s\n",
                scenes[j->scene].id, scenes[j->scene].family, sc.grid.nx, sc.grid.ny,
                mc_backend_name(combo_backend[j->combo]),
                mc_contact_method_name(combo_method[j->combo]),
                r->outcome == ST_DONE ? "done" : "failed", r->status, r->converged, r->iterations,
                r->residual, r->kkt, r->compl, r->load_err, r->bounds, r->gapid, r->contact_ratio,
                r->p_max, r->approach, r->capped, r->time_s, j->wall_s, b);
    }
    vf_close(ctx, f);
}

static void loads_figure(vf_ctx *ctx, const st_job *jobs, int njobs)
{
    FILE *f = vf_open(ctx, "loads.csv");
    if (!f)
        return;
    static const int cols[4] = {0, 1, 3, 4}; /* fft cg, fft pk, direct cg, direct pk */
    fprintf(f, "load_N,contact_ratio,it_fft_cg,it_fft_pk,it_direct_cg,it_direct_pk\n");
    for (int s = 0; s < NSCENES; s++) {
        if (scenes[s].build != b_load)
            continue;
        double it[4] = {NAN, NAN, NAN, NAN}, ratio = NAN;
        for (int k = 0; k < njobs; k++) {
            if (jobs[k].scene != s || jobs[k].rec.outcome != ST_DONE)
                continue;
            for (int c = 0; c < 4; c++)
                if (jobs[k].combo == cols[c]) {
                    it[c] = jobs[k].rec.iterations;
                    ratio = jobs[k].rec.contact_ratio;
                }
        }
        fprintf(f, "%.3g,%.6g,%.6g,%.6g,%.6g,%.6g\n", scenes[s].arg, ratio, it[0], it[1], it[2],
                it[3]);
    }
    vf_close(ctx, f);
    vf_plot(ctx, "loads.png",
            "Iterations against the load (sphere, 64^2 x 5 um: one cell at 1e-6 N, every cell "
            "at 1e4 N)",
            "set datafile separator ','\nset logscale x\nset key top left\nset format x '10^{%L}'\n"
            "set xlabel 'load (N)'\nset ylabel 'iterations'\nset y2label 'contact ratio'\n"
            "set y2tics\nset grid\nset datafile missing 'nan'\n"
            "plot 'loads.csv' using 1:3 with linespoints pt 7 title 'fft cg', "
            "'' using 1:4 with linespoints pt 5 title 'fft pk', "
            "'' using 1:5 with linespoints pt 9 dt 2 title 'direct cg', "
            "'' using 1:6 with linespoints pt 11 dt 2 title 'direct pk', "
            "'' using 1:2 axes x1y2 with lines lw 2 lc 'gray' title 'contact ratio'");
}

int vf_suite_stability(vf_ctx *ctx, int fast)
{
    /* the jobs of this variant */
    st_job *jobs = calloc((size_t)NSCENES * 6, sizeof *jobs);
    if (!jobs)
        return 1;
    int njobs = 0;
    for (int s = 0; s < NSCENES; s++) {
        unsigned mask = fast ? scenes[s].fast : scenes[s].full;
        for (int c = 0; c < 6; c++) {
            mc_scene sc;
            build_scene(&scenes[s], c, &sc);
            if (!(mask & (1u << c)) || !applicable(&scenes[s], &sc, c))
                continue;
            jobs[njobs].scene = s;
            jobs[njobs].combo = c;
            jobs[njobs].timeout = scenes[s].timeout;
            njobs++;
        }
    }
    double t0 = mc_clock();
    int workers = st_run_jobs(jobs, njobs);
    double wall = mc_clock() - t0;

    mc_scene def;
    mc_scene_defaults(&def);
    const double tol = def.solver.tolerance; /* every scene but tol_1e-15 */
    vf_text(ctx,
            "A matrix of extreme scenes x both operator backends (direct up to %d cells) x the "
            "solvers that apply (active-set up to %d cells): %d runs%s, each in a forked child "
            "process (%d at a time, one thread each: GNU libgomp is not fork-safe, a child that "
            "starts a thread team after its parent ran parallel regions hangs), with a time limit, "
            "so that a crash or a hang is a failed check and not the end of the suite. Runs took "
            "%.1f s of wall time in all. Solver settings are the defaults (tolerance %.0e, at most "
            "%d iterations).\n\n",
            DIRECT_MAX_CELLS, ACTIVE_MAX_CELLS, njobs,
            fast ? " (the fast subset; `microcontact verify stability` runs the full matrix)" : "",
            workers, wall, tol, def.solver.max_iterations);
    vf_text(ctx,
            "**What must hold.** Every run converges (`converged`: status MC_OK and "
            "`converged = 1`) with its conditions satisfied (`kkt`). Only a scene designed to hit "
            "a solver limit - its row gives the reason, marked *may stop short* below - may end "
            "without converging, and must then report it honestly (status MC_NOT_CONVERGED, "
            "`converged = 0`, its residual above the tolerance: check `honest`). Never NaN/Inf in "
            "an output array or "
            "a summary value (`finite`), never a crash or an error (`run`). The conditions are "
            "recomputed here from the output arrays alone, not taken from the solver:\n\n"
            "- `kkt`: the stopping measure of contact.h on a gap rebuilt as g = h + K p - "
            "approach, with K p from the suite's own operator plan (same backend): "
            "max(|A sum p - W| / W under force control, max over cells of -g/s where p = p_lub, "
            "|g|/s where p_lub < p < p_cap, g/s where p = p_cap), s the gap scale of the stopping "
            "rule (delta - min h~, h~ = h + K p_lub, floored at 1e-6 of the range of h~ and "
            "1e-12 of its magnitude, as mc_contact_gap_scale). Tolerance %.0f x the solver "
            "tolerance, plus the round-off floor of the gap 16 eps (max|h~| + max|K p| + "
            "|delta|)/s. A lubricant that alone would carry more than W (`lub_1.01`) is refused "
            "as an input error (check `refused`).\n"
            "- `consistent` (round-off tier, %.0e): the bounds, max(p_lub - p, p - p_cap, 0) / "
            "p_max (the solvers clip); max |gap - (topography + displacement - approach)| and "
            "max |displacement - K p| relative to max|h| + max|u| + |approach| (a few additions "
            "and one DC-FFT); the summary's load, p_max and area against the arrays (relative).\n"
            "- scene checks: `cells` and `approach` (one element: exactly one cell loaded, the "
            "approach equals p times the centre displacement of Love's square, 4 d ln(1+sqrt 2) "
            "/(pi E*), within %.0e); `full` (flat punch and flat under force: contact ratio 1); "
            "`similar` (the sphere scaled to heights of 1e-12 m and 1e-2 m, load x L^2, must "
            "give the same p_max and approach / L as the unscaled scene within %.0e: the "
            "similarity is exact, only the solver tolerance separates them; the line contact "
            "scaled by 1e4, p_max only: its approach carries the log kernel's constant, which is "
            "in metres); `refused` (`periodic_flat_approach` has no solution: the one right "
            "answer is an input error with a message); `stress_finite` and `szz0` (stress stage, "
            "patch kernel, layers from z = 0: finite, and sigma_zz(0) = -p within %.0e of "
            "p_max).\n\n"
            "**Regression guards.** These scenes hold bugs this suite found: `cap_0.13p0`, "
            "`cap_lub_100`, `cap_lub_60` (the active set ended with every contact cell held at a "
            "bound and none free, the load off by 0.4 to 19 %%, and reported it converged), "
            "`periodic_4`, `periodic_32`, `periodic_sphere_approach` and `line_x_1e4` (the "
            "active set's Cholesky failed: K is singular periodic in x and y, and indefinite "
            "periodic in one axis on a domain of metres), and "
            "`periodic_flat_approach` (cg stopped on a 'non-positive curvature' error, pk ran "
            "2000 iterations to pressures of 1e12 MPa, the active set failed in Cholesky: "
            "instead of saying that no solution exists).\n\n",
            KKT_FACTOR, CONSISTENT_TOL, ONE_CELL_TOL, SIMILAR_TOL, SZZ_TOL);

    vf_text(ctx, "## Scenes\n\n| scene | family | what |\n|---|---|---|\n");
    for (int s = 0; s < NSCENES; s++) {
        unsigned mask = fast ? scenes[s].fast : scenes[s].full;
        if (mask)
            vf_text(ctx, "| `%s` | %s | %s%s%s%s |\n", scenes[s].id, scenes[s].family,
                    scenes[s].what, scenes[s].stress ? "; with the stress stage (cg runs)" : "",
                    !scenes[s].may_stop                ? ""
                    : scenes[s].extra == X_INFEASIBLE ? "; *not solved*: "
                                                      : "; *may stop short*: ",
                    scenes[s].may_stop ? scenes[s].may_stop : "");
    }

    /* checks, in job order */
    for (int k = 0; k < njobs; k++) {
        const st_record *base = NULL;
        const st_scene *sk = &scenes[jobs[k].scene];
        if (sk->base)
            for (int b = 0; b < njobs; b++)
                if (!strcmp(scenes[jobs[b].scene].id, sk->base) && jobs[b].combo == jobs[k].combo)
                    base = &jobs[b].rec;
        check_run(ctx, jobs[k].scene, jobs[k].combo, &jobs[k].rec, base);
    }

    /* the matrix */
    int nconv = 0, nnot = 0, nshort = 0, nref = 0, nfail = 0;
    for (int k = 0; k < njobs; k++) {
        const st_record *r = &jobs[k].rec;
        if (r->outcome == ST_DONE && r->status == MC_OK && r->converged)
            nconv++;
        else if (r->outcome == ST_DONE && r->status == MC_NOT_CONVERGED &&
                 scenes[jobs[k].scene].may_stop)
            nnot++;
        else if (r->outcome == ST_DONE && r->status == MC_NOT_CONVERGED)
            nshort++;
        else if (r->outcome == ST_DONE && r->status == MC_ERR_INPUT &&
                 scenes[jobs[k].scene].extra == X_INFEASIBLE)
            nref++;
        else
            nfail++;
    }
    vf_text(ctx,
            "\n## Matrix\n\n%d runs: %d converged, %d not converged in scenes designed to stop "
            "short (reported as such), %d not converged although the scene must converge "
            "(failures), %d refused as infeasible (as they must be), %d failed (crash, time "
            "limit or error). "
            "`it`: iterations (the nested solver counts its "
            "inner iterations; active-set: its solves); `residual`: the solver's own measure; "
            "`kkt`: the measure recomputed here; `time`: the pipeline (setup, solve, stress) "
            "in the child, one thread. Data: `runs.csv`.\n\n"
            "| scene | grid | backend | method | result | it | residual | kkt | load err | "
            "contact | time (s) |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
            njobs, nconv, nnot, nshort, nref, nfail);
    for (int k = 0; k < njobs; k++) {
        const st_job *j = &jobs[k];
        const st_record *r = &j->rec;
        mc_scene sc;
        build_scene(&scenes[j->scene], j->combo, &sc);
        char b[320];
        result_text(r, b, sizeof b);
        for (char *c = b; *c; c++)
            if (*c == '|')
                *c = '/';
        int done = r->outcome == ST_DONE &&
                   (r->status == MC_OK || r->status == MC_NOT_CONVERGED) && !r->nonfinite;
        char le[32] = "-";
        if (r->force)
            snprintf(le, sizeof le, "%.1e", r->load_err);
        if (done)
            vf_text(ctx, "| %s | %dx%d | %s | %s | %s | %d | %.1e | %.1e | %s | %.3g | %.3f |\n",
                    scenes[j->scene].id, sc.grid.nx, sc.grid.ny,
                    mc_backend_name(combo_backend[j->combo]),
                    mc_contact_method_name(combo_method[j->combo]), b, r->iterations,
                    r->residual, r->kkt, le, r->contact_ratio, r->time_s);
        else
            vf_text(ctx, "| %s | %dx%d | %s | %s | %.120s | | | | | | %.3f |\n",
                    scenes[j->scene].id, sc.grid.nx, sc.grid.ny,
                    mc_backend_name(combo_backend[j->combo]),
                    mc_contact_method_name(combo_method[j->combo]), b, j->wall_s);
    }
    write_csv(ctx, jobs, njobs);
    loads_figure(ctx, jobs, njobs);
    free(jobs);
    return 0;
}
