/* keys.c - the one key table of case files (keys.h): every key's bounds, default, unit kind and
 * help text; the conversion of one value text into the scene; the Markdown reference generated
 * from the table. The reader (reader.c) and the scene check (scene.c) use the same rows.
 * Longer than 800 lines on purpose: most of it is the one declarative table of every key (issue
 * "one key table"); splitting the rows by section would scatter the single place where bounds,
 * defaults and help live.
 */
#include "case/keys.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "case/units.h"

/* Enums are stored through an int (the table's value is the index of the choice). */
_Static_assert(sizeof(mc_shape) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_roughness_type) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_load_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_backend) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_contact_method) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_spacing) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_stress_kernel) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_scene_stress_window) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_scene_film_source) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_film_formula) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_psi_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_yield_criterion) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_hardening_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_scene_table_unit) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_nominal_deflection) == sizeof(int), "enum size");
_Static_assert(sizeof(mc_plan_rigor) == sizeof(int), "enum size");
_Static_assert(MC_PLANS_MEASURE == 1 && MC_PLANS_WISDOM == 2,
               "[solver] plans choices follow the enum");
_Static_assert(MC_PROFILE_HERTZ == 1, "[lubrication] lubricant_profile choices follow the enum");
_Static_assert(MC_DEFLECTION_KEEP == 1, "[runin] nominal_deflection choices follow the enum");
_Static_assert(MC_LAYERING_GRADED == 2, "[plasticity] layering choices follow the enum");
_Static_assert(MC_SHAPE_ELLIPSOID == 3 && MC_ROUGH_FILE == 3 && MC_BACKEND_DIRECT == 1 &&
                   MC_METHOD_ACTIVE_SET == 2 && MC_SPACING_GEOMETRIC == 1 && MC_STRESS_POINT == 1 &&
                   MC_STRESS_WINDOW_FULL == 1 && MC_FILM_GIVEN == 1 &&
                                      MC_CRITERION_PRESSURE_CAP == 1 && MC_TABLE_UNIT_GPA == 2,
               "choice lists below follow the enum order");


/* ---- choices owned by their modules ------------------------------------------------------------ */

/* Enum rows whose names live in a module's table (.choice/.choice_help): name and help of choice
 * i, NULL past the last. Adding a formula or a law to its module adds it here too. */
static const char *film_formula_choice(int i) { return mc_film_formula_name((mc_film_formula)i); }
static const char *film_formula_help(int i) { return mc_film_formula_help((mc_film_formula)i); }
static const char *hardening_choice(int i) { return mc_hardening_name((mc_hardening_kind)i); }
static const char *hardening_help(int i) { return mc_hardening_help((mc_hardening_kind)i); }
static const char *psi_choice(int i) { return mc_psi_name((mc_psi_kind)i); }
static const char *psi_help(int i) { return mc_psi_help((mc_psi_kind)i); }

/* ---- the key table --------------------------------------------------------------------------- */


#define AT(field) offsetof(mc_scene, field)

/* The keys of a roughness section: [roughness] (the composite gap surface, or body 1's with
 * [roughness2]) and [roughness2] (body 2's) have the same rows, each over its own
 * mc_roughness_spec (docs/theory.md §4.11). */
#define ROUGHNESS_ROWS(SEC, FIELD, TYPEDOC, SEEDDEF, SEEDDOC, MESHDOC) \
    {.section = SEC, .name = "type", .kind = K_ENUM, \
     .choices = "none gaussian self_affine file", .def = "none", .off = AT(FIELD.type), \
     .doc = TYPEDOC}, \
    {.section = SEC, .name = "rq", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0, \
     .hi = HUGE_VAL, .group = "height", .use = USE_WHEN, .use_key = "type", \
     .use_values = "gaussian self_affine", .off = AT(FIELD.rq), \
     .doc = "RMS height Rq (required for gaussian; for self_affine give rq or rms_slope)."}, \
    {.section = SEC, .name = "rms_slope", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0, \
     .lo_open = 1, .hi = HUGE_VAL, .group = "height", .use = USE_WHEN, .use_key = "type", \
     .use_values = "self_affine", .off = AT(FIELD.rms_slope), \
     .doc = "RMS slope, instead of rq."}, \
    {.section = SEC, .name = "correlation_x", .kind = K_REAL, .unit = MC_UNIT_LENGTH, \
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .required = 1, .use = USE_WHEN, .use_key = "type", \
     .use_values = "gaussian", .off = AT(FIELD.correlation_x), \
     .doc = "Correlation length along x: autocorrelation exp(-(tx/lx)^2 - (ty/ly)^2)."}, \
    {.section = SEC, .name = "correlation_y", .kind = K_REAL, .unit = MC_UNIT_LENGTH, \
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .def = "correlation_x", .def_from = "correlation_x", \
     .use = USE_WHEN, .use_key = "type", .use_values = "gaussian", \
     .off = AT(FIELD.correlation_y), .doc = "Correlation length along y."}, \
    {.section = SEC, .name = "hurst", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0, \
     .lo_open = 1, .hi = 1, .hi_open = 1, .def = "0.8", .use = USE_WHEN, .use_key = "type", \
     .use_values = "self_affine", .off = AT(FIELD.hurst), \
     .doc = "Hurst exponent H (power spectrum ~ q^-2(1+H))."}, \
    {.section = SEC, .name = "lambda_long", .kind = K_REAL, .unit = MC_UNIT_LENGTH, \
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .def = "the longer domain side", .def_rule = 1, \
     .use = USE_WHEN, .use_key = "type", .use_values = "self_affine", \
     .off = AT(FIELD.lambda_long), .doc = "Longest wavelength (long cut-off)."}, \
    {.section = SEC, .name = "lambda_short", .kind = K_REAL, .unit = MC_UNIT_LENGTH, \
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .def = "2 max(dx, dy)", .def_rule = 1, \
     .use = USE_WHEN, .use_key = "type", .use_values = "self_affine", \
     .off = AT(FIELD.lambda_short), \
     .doc = "Shortest wavelength (short cut-off), below lambda_long."}, \
    {.section = SEC, .name = "seed", .kind = K_SEED, .def = SEEDDEF, .use = USE_WHEN, \
     .use_key = "type", .use_values = "gaussian self_affine", .off = AT(FIELD.seed), \
     .doc = "Random seed: the same seed gives the same surface on every run" SEEDDOC}, \
    {.section = SEC, .name = "file", .kind = K_PATH, .required = 1, .use = USE_WHEN, \
     .use_key = "type", .use_values = "file", .off = AT(FIELD.file), .relative = 1, \
     .doc = "Measured height map, relative to the case file: X3P, SDF, GSF, text matrix, x y z " \
            "triplets or .npy (by extension, or format). " MESHDOC}, \
    {.section = SEC, .name = "format", .kind = K_ENUM, \
     .choices = "auto x3p sdf gsf txt xyz npy", .def = "auto", .use = USE_WHEN, .use_key = "type", \
     .use_values = "file", .off = AT(FIELD.format), \
     .doc = "File format; auto: by extension (.x3p .sdf .gsf .txt/.asc/.dat .xyz .npy)."}, \
    {.section = SEC, .name = "units", .kind = K_ENUM, .choices = "m mm um nm", \
     .def = "m", .use = USE_WHEN, .use_key = "type", .use_values = "file", \
     .off = AT(FIELD.units), \
     .doc = "Unit of the numbers in a txt, xyz or npy file (X3P, SDF and GSF carry their own)."}, \
    {.section = SEC, .name = "verify_checksum", .kind = K_BOOL, .def = "yes", \
     .use = USE_WHEN, .use_key = "type", .use_values = "file", \
     .off = AT(FIELD.verify_checksum), \
     .doc = "X3P: an MD5 mismatch is an error (no: read the file anyway)."}, \
    {.section = SEC, .name = "region", .kind = K_REGION, .unit = MC_UNIT_LENGTH, \
     .use = USE_WHEN, .use_key = "type", .use_values = "file", .off = AT(FIELD.region), \
     .tagged = 1, .tag = 1, .tag_off = AT(FIELD.has_region), \
     .doc = "Crop: x0, y0, width, height in the file's coordinates, e.g. 0 mm, 0 mm, 0.5 mm, " \
            "0.2 mm."}, \
    {.section = SEC, .name = "detrend", .kind = K_ENUM, \
     .choices = "none mean plane quadratic", .def = "plane", .use = USE_WHEN, .use_key = "type", \
     .use_values = "file", .off = AT(FIELD.detrend), \
     .doc = "Levelling of the measured map by least squares (after the crop)."}, \
    {.section = SEC, .name = "missing", .kind = K_ENUM, .choices = "error fill", \
     .def = "error", .use = USE_WHEN, .use_key = "type", .use_values = "file", \
     .off = AT(FIELD.missing), \
     .doc = "Points the instrument did not measure: an error, or filled by harmonic " \
            "interpolation from their neighbours (the count is reported)."}, \
    {.section = SEC, .name = "resample", .kind = K_ENUM, .choices = "none linear", \
     .def = "none", .use = USE_WHEN, .use_key = "type", .use_values = "file", \
     .off = AT(FIELD.resample), \
     .doc = "When [mesh] gives a grid other than the file's: none is an error naming both, " \
            "linear interpolates onto the mesh."}, \
    {.section = SEC, .name = "scale", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = -1e6, \
     .hi = 1e6, .def = "1", .use = USE_WHEN, .use_key = "type", .use_values = "file", \
     .off = AT(FIELD.scale), .doc = "Factor on the heights (not 0)."}, \
    {.section = SEC, .name = "invert", .kind = K_BOOL, .def = "no", .use = USE_WHEN, \
     .use_key = "type", .use_values = "file", .off = AT(FIELD.invert), \
     .doc = "Negate the heights (a map of a replica, or a map that points into the body)."}, \
 \
    {.section = SEC, .name = "cutoff", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0, \
     .lo_open = 1, .hi = 1, .def = "ISO 4288 from Ra", .def_rule = 1, .use = USE_WHEN, \
     .use_key = "type", .use_values = "gaussian self_affine file", .off = AT(FIELD.cutoff), \
     .doc = "Cut-off wavelength lambda_c of the Gaussian filter (ISO 16610-21) for the " \
            "roughness parameters in summary.json; clipped with a warning on a short surface. " \
            "[roughness]'s serves the gap's (composite) parameters and body 1's, [roughness2]'s " \
            "body 2's."},

const case_key mc_keys[] = {
    /* [mesh] */
    {.section = "mesh", .name = "nx", .kind = K_INT, .lo = 1, .hi = MC_GRID_MAX_N,
     .required = 1, .off = AT(grid.nx), .doc = "Cells along x (the rolling direction)."},
    {.section = "mesh", .name = "ny", .kind = K_INT, .lo = 1, .hi = MC_GRID_MAX_N,
     .required = 1, .off = AT(grid.ny), .doc = "Cells along y (transverse, the cylinder axis)."},
    {.section = "mesh", .name = "dx", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = 1, .required = 1, .off = AT(grid.dx), .doc = "Cell size along x."},
    {.section = "mesh", .name = "dy", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = 1, .def = "dx", .def_from = "dx", .off = AT(grid.dy),
     .doc = "Cell size along y."},
    {.section = "mesh", .name = "periodic_x", .kind = K_BOOL, .def = "no",
     .off = AT(grid.periodic_x),
     .doc = "Periodic along x with period nx dx; otherwise the surface outside the mesh is free."},
    {.section = "mesh", .name = "periodic_y", .kind = K_BOOL, .def = "no",
     .off = AT(grid.periodic_y),
     .doc = "Periodic along y with period ny dy (required by force_per_length)."},

    /* [geometry] */
    {.section = "geometry", .name = "shape", .kind = K_ENUM,
     .choices = "flat sphere cylinder ellipsoid", .def = "flat", .off = AT(geometry.shape),
     .doc = "Gap at zero load: flat 0; sphere r^2/2R; cylinder x^2/2R (axis along y); "
            "ellipsoid x^2/2Rx + y^2/2Ry."},
    {.section = "geometry", .name = "radius", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .required = 1, .use = USE_WHEN, .use_key = "shape",
     .use_values = "sphere cylinder", .off = AT(geometry.radius),
     .doc = "Combined radius of curvature R (1/R = 1/R1 + 1/R2); for the cylinder, the "
            "curvature is in x."},
    {.section = "geometry", .name = "radius_x", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .required = 1, .use = USE_WHEN, .use_key = "shape",
     .use_values = "ellipsoid", .off = AT(geometry.radius_x),
     .doc = "Combined principal radius of curvature in the x-z plane."},
    {.section = "geometry", .name = "radius_y", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .required = 1, .use = USE_WHEN, .use_key = "shape",
     .use_values = "ellipsoid", .off = AT(geometry.radius_y),
     .doc = "Combined principal radius of curvature in the y-z plane."},

    /* [roughness], [roughness2] */
    ROUGHNESS_ROWS("roughness", roughness,
                   "Roughness heights added to the surface (positive towards the counter body); "
                   "with [roughness2], body 1's surface.",
                   "1", ".",
                   "Without nx, ny, dx, dy in [mesh] the mesh is the file's.")
    ROUGHNESS_ROWS("roughness2", roughness2,
                   "Body 2's roughness heights, measured outward (towards body 1): the gap's "
                   "roughness is the sum of [roughness] and [roughness2]. Needs [roughness].",
                   "2", " (default 2: another surface than body 1's default seed).",
                   "On the mesh of [mesh], or of [roughness] file: a map of another grid is an "
                   "error naming both files, unless resample = linear.")

    /* [body1], [body2] */
    {.section = "body1", .name = "E", .kind = K_REAL, .unit = MC_UNIT_PRESSURE, .lo = 0,
     .lo_open = 1, .hi = 1e13, .def = "210 GPa", .off = AT(body1.E), .doc = "Young's modulus."},
    {.section = "body1", .name = "nu", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0, .hi = 0.5,
     .def = "0.3", .off = AT(body1.nu), .doc = "Poisson's ratio."},
    {.section = "body2", .name = "rigid", .kind = K_BOOL, .def = "no", .off = AT(body2.rigid),
     .doc = "A rigid body 2: E* = E1/(1 - nu1^2)."},
    {.section = "body2", .name = "E", .kind = K_REAL, .unit = MC_UNIT_PRESSURE, .lo = 0,
     .lo_open = 1, .hi = 1e13, .def = "210 GPa", .use = USE_WHEN, .use_key = "rigid",
     .use_values = "no", .off = AT(body2.E), .doc = "Young's modulus."},
    {.section = "body2", .name = "nu", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0, .hi = 0.5,
     .def = "0.3", .use = USE_WHEN, .use_key = "rigid", .use_values = "no", .off = AT(body2.nu),
     .doc = "Poisson's ratio."},

    /* [load] */
    {.section = "load", .name = "force", .kind = K_REAL, .unit = MC_UNIT_FORCE, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .group = "load", .off = AT(load.value), .tagged = 1,
     .tag = MC_LOAD_FORCE, .tag_off = AT(load.kind), .doc = "Total normal force."},
    {.section = "load", .name = "force_per_length", .kind = K_REAL,
     .unit = MC_UNIT_FORCE_PER_LENGTH, .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .group = "load",
     .off = AT(load.value), .tagged = 1, .tag = MC_LOAD_FORCE_PER_LENGTH,
     .tag_off = AT(load.kind),
     .doc = "Normal force per unit length along y (line contact); needs [mesh] periodic_y = yes."},
    {.section = "load", .name = "approach", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .group = "load", .off = AT(load.value), .tagged = 1,
     .tag = MC_LOAD_APPROACH, .tag_off = AT(load.kind),
     .doc = "Rigid-body approach of the two bodies."},
    {.section = "load", .name = "pressure_file", .kind = K_PATH, .group = "load",
     .off = AT(load.pressure_file), .relative = 1, .tagged = 1, .tag = MC_LOAD_PRESSURE_FILE,
     .tag_off = AT(load.kind),
     .doc = "Prescribed pressure map (.npy, ny x nx, Pa), relative to the case file; no contact "
            "solve."},
    {.section = "load", .name = "lubricant_pressure", .kind = K_REAL, .unit = MC_UNIT_PRESSURE,
     .lo = 0, .hi = HUGE_VAL, .def = "0", .use = USE_UNLESS, .use_key = "pressure_file",
     .word = "auto", .word_value = MC_LUBRICANT_AUTO, .off = AT(load.lubricant_pressure),
     .doc = "Lower bound of the pressure outside solid contact (a lubricant film); auto: from "
            "the lubricant volume equilibrium of [lubrication]."},
    {.section = "load", .name = "pressure_cap", .kind = K_REAL, .unit = MC_UNIT_PRESSURE, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .lo_text = "> lubricant_pressure", .def = "none (unbounded)",
     .def_rule = 1, .use = USE_UNLESS, .use_key = "pressure_file", .off = AT(load.pressure_cap),
     .doc = "Upper bound of the pressure (e.g. a hardness)."},

    /* [solver] */
    {.section = "solver", .name = "operator", .kind = K_ENUM, .choices = "fft direct",
     .def = "fft", .off = AT(solver.backend),
     .doc = "Convolution backend: fft (DC-FFT) or direct (O(N^2) sums, the reference)."},
    {.section = "solver", .name = "method", .kind = K_ENUM, .choices = "cg pk active-set",
     .def = "cg", .use = USE_UNLESS, .use_key = "load.pressure_file", .off = AT(solver.method),
     .doc = "cg: preconditioned constrained conjugate gradients; pk: Polonsky & Keer (1999); "
            "active-set: the dense reference (small grids)."},
    {.section = "solver", .name = "tolerance", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 1e-15,
     .hi = 1e-2, .def = "1e-8", .use = USE_UNLESS, .use_key = "load.pressure_file",
     .off = AT(solver.tolerance),
     .doc = "Relative stopping tolerance."},
    {.section = "solver", .name = "max_iterations", .kind = K_INT, .lo = 1, .hi = 10000000,
     .def = "2000", .use = USE_UNLESS, .use_key = "load.pressure_file",
     .off = AT(solver.max_iterations),
     .doc = "Iteration limit; reaching it is reported as not converged."},
    {.section = "solver", .name = "threads", .kind = K_INT, .lo = 0, .hi = 1024, .def = "0",
     .off = AT(solver.threads),
     .doc = "Threads for FFTW and OpenMP; 0 = the cores free at the start of the run (all cores "
            "less the other running tasks; OMP_NUM_THREADS decides when set)."},
    {.section = "solver", .name = "plans", .kind = K_ENUM, .choices = "estimate measure wisdom",
     .def = "estimate", .off = AT(solver.plans),
     .doc = "How FFTW plans the repeated transforms: estimate (no trial runs: the same plan and "
            "the same results on every run); measure (times candidate algorithms while "
            "planning: faster transforms for seconds of planning on large grids; the last bits "
            "of the results may differ between runs); wisdom (measure, but the plans stored in "
            "wisdom_file are reused and new ones added to it: planned once, fast afterwards)."},
    {.section = "solver", .name = "wisdom_file", .kind = K_PATH, .required = 1, .use = USE_WHEN,
     .use_key = "plans", .use_values = "wisdom", .off = AT(solver.wisdom_file), .relative = 1,
     .doc = "FFTW wisdom of plans = wisdom, relative to the case file: read at the start if it "
            "exists (a file that is not FFTW wisdom is an error), rewritten at the end."},

    /* [stress] */
    {.section = "stress", .name = "enabled", .kind = K_BOOL,
     .def = "yes, when [stress] is present", .def_rule = 1,
     .off = AT(stress.enabled),
     .doc = "Run the stress stage (no: skip it, e.g. --set stress.enabled=no)."},
    {.section = "stress", .name = "depth_min", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .hi = HUGE_VAL, .def = "0", .use = USE_UNLESS, .use_key = "depths",
     .off = AT(stress.depth_min), .doc = "Depth of the first layer."},
    {.section = "stress", .name = "depth_max", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .lo_text = "> depth_min", .group = "range", .def = "auto",
     .word = "auto", .word_value = MC_STRESS_DEPTH_AUTO, .off = AT(stress.depth_max),
     .doc = "Depth of the last layer; auto: 3 times the radius of the largest contact patch "
            "(connected solid-contact cells; for a prescribed pressure the loaded region), found "
            "after the contact solve (a Hertz contact gives 3a)."},
    {.section = "stress", .name = "layers", .kind = K_INT, .lo = 1, .hi = MC_MAX_DEPTHS,
     .def = "32", .use = USE_UNLESS, .use_key = "depths", .off = AT(stress.layers),
     .doc = "Number of layers from depth_min to depth_max (1: depth_min only)."},
    {.section = "stress", .name = "spacing", .kind = K_ENUM, .choices = "linear geometric",
     .def = "linear", .use = USE_UNLESS, .use_key = "depths", .off = AT(stress.spacing),
     .doc = "Layer spacing; geometric (log-spaced) needs depth_min > 0."},
    {.section = "stress", .name = "depths", .kind = K_LENGTHS, .unit = MC_UNIT_LENGTH, .lo = 0,
     .hi = HUGE_VAL, .group = "range", .off = AT(stress.depths), .count_off = AT(stress.ndepths),
     .tagged = 1, .tag = MC_SPACING_LIST, .tag_off = AT(stress.spacing),
     .doc = "Explicit layer depths, e.g. 0.1 um, 0.5 um, 1.3 um; a long list continues on "
            "indented lines."},
    {.section = "stress", .name = "kernel", .kind = K_ENUM, .choices = "patch point",
     .def = "patch", .off = AT(stress.kernel),
     .doc = "patch: uniform pressure over each cell (exact for the discrete load); point: a "
            "point force per cell (singular near the surface)."},
    {.section = "stress", .name = "friction", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .hi = 1, .def = "0", .off = AT(stress.friction),
     .doc = "Coulomb coefficient: shear traction q_x = friction p (sliding in +x)."},
    {.section = "stress", .name = "window", .kind = K_ENUM, .choices = "auto full", .def = "auto",
     .off = AT(stress.window),
     .doc = "auto: a compact load on a grid with free axes (its bounding box well inside the "
            "grid) is stressed only on its bounding box widened by 7 R + 2.5 z (R its half-size, "
            "z the depth; at least 4 cells), where the rest is below 2 % of the layer's largest "
            "von Mises stress; the other cells hold 0 and summary.json lists the windows. full: "
            "every cell of every layer."},

    /* [lubrication] */
    {.section = "lubrication", .name = "enabled", .kind = K_BOOL,
     .def = "yes, when [lubrication] is present", .def_rule = 1, .off = AT(lubrication.enabled),
     .doc = "Run the lubricant volume equilibrium (needs [load] lubricant_pressure = auto)."},
    {.section = "lubrication", .name = "film", .kind = K_ENUM, .choices = "ehl given",
     .def = "ehl", .off = AT(lubrication.film),
     .doc = "Film thickness h_EHD of the smooth surfaces: from an EHL formula, or given."},
    {.section = "lubrication", .name = "film_thickness", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = 1e-3, .required = 1, .use = USE_WHEN, .use_key = "film",
     .use_values = "given", .off = AT(lubrication.film_thickness),
     .doc = "h_EHD: the lubricant volume is h_EHD times the nominal area."},
    {.section = "lubrication", .name = "formula", .kind = K_ENUM,
     .choice = film_formula_choice, .choice_help = film_formula_help,
     .def = "pan_hamrock_central", .use = USE_WHEN, .use_key = "film", .use_values = "ehl",
     .off = AT(lubrication.formula),
     .doc = "EHL film formula (Hamrock's groups; isothermal, fully flooded)."},
    {.section = "lubrication", .name = "viscosity", .kind = K_REAL, .unit = MC_UNIT_VISCOSITY,
     .lo = 0, .lo_open = 1, .hi = 1e6, .required = 1, .use = USE_WHEN, .use_key = "film",
     .use_values = "ehl", .off = AT(lubrication.viscosity),
     .doc = "Dynamic viscosity eta0 at the inlet temperature."},
    {.section = "lubrication", .name = "pressure_viscosity", .kind = K_REAL,
     .unit = MC_UNIT_NONE, .lo = 0, .lo_open = 1, .hi = 1e-6, .required = 1, .use = USE_WHEN,
     .use_key = "film", .use_values = "ehl", .off = AT(lubrication.pressure_viscosity),
     .doc = "Pressure-viscosity coefficient alpha (Barus) in 1/Pa, e.g. 2e-8."},
    {.section = "lubrication", .name = "speed", .kind = K_REAL, .unit = MC_UNIT_SPEED, .lo = 0,
     .lo_open = 1, .hi = 1e3, .group = "entrainment", .use = USE_WHEN, .use_key = "film",
     .use_values = "ehl", .off = AT(lubrication.speed),
     .doc = "Mean entrainment speed u = (u1 + u2)/2 (or give rpm)."},
    {.section = "lubrication", .name = "rpm", .kind = K_REAL, .unit = MC_UNIT_ROTATION, .lo = 0,
     .lo_open = 1, .hi = 1e5, .group = "entrainment", .use = USE_WHEN, .use_key = "film",
     .use_values = "ehl", .off = AT(lubrication.rpm),
     .doc = "Speed of disc 1 (with radius1, radius2); u_i = 2 pi n_i R_i / 60."},
    {.section = "lubrication", .name = "rpm2", .kind = K_REAL, .unit = MC_UNIT_ROTATION, .lo = 0,
     .hi = 1e5, .def = "equal surface speeds", .def_rule = 1, .use = USE_WHEN, .use_key = "film",
     .use_values = "ehl", .off = AT(lubrication.rpm2),
     .doc = "Speed of disc 2 (rolling-sliding); with rpm only."},
    {.section = "lubrication", .name = "radius1", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = 100, .use = USE_WHEN, .use_key = "film", .use_values = "ehl",
     .off = AT(lubrication.radius1),
     .doc = "Radius of disc 1 (needed with rpm; with radius2 it gives R_x if macro_radius is "
            "absent)."},
    {.section = "lubrication", .name = "radius2", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = 100, .use = USE_WHEN, .use_key = "film", .use_values = "ehl",
     .off = AT(lubrication.radius2), .doc = "Radius of disc 2."},
    {.section = "lubrication", .name = "macro_radius", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = 100, .off = AT(lubrication.macro_radius),
     .doc = "Reduced radius R_x of the macro line contact that the flat patch stands for (its "
            "centre, loaded with the Hertz pressure p_H)."},
    {.section = "lubrication", .name = "width", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = 100, .off = AT(lubrication.width),
     .doc = "Contact (face) width L of the macro contact: w' = F_N / L."},
    {.section = "lubrication", .name = "mu_solid", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .hi = 2, .def = "0.1", .off = AT(lubrication.mu_solid),
     .doc = "Friction coefficient of solid (boundary) contact (an assumption: 0.1-0.15 typical)."},
    {.section = "lubrication", .name = "mu_fluid", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .hi = 2, .def = "0.02", .off = AT(lubrication.mu_fluid),
     .doc = "Friction coefficient of the fluid film (an assumption; from EHL traction)."},
    {.section = "lubrication", .name = "psi", .kind = K_ENUM, .choice = psi_choice,
     .choice_help = psi_help, .def = "load", .off = AT(lubrication.psi),
     .doc = "Solid contact ratio of the friction mix mu = psi mu_solid + (1 - psi) mu_fluid."},
    {.section = "lubrication", .name = "lubricant_profile", .kind = K_ENUM,
     .choices = "uniform hertz", .def = "uniform", .use = USE_WHEN, .use_key = "geometry.shape",
     .use_values = "cylinder ellipsoid", .off = AT(lubrication.profile),
     .doc = "The whole contact (shape = cylinder: the line contact on a strip; ellipsoid: the "
            "crowned contact on a free grid): the lubricant pressure over the Hertz band (or "
            "ellipse), the nominal area of the volume equilibrium. uniform: one p_lub in the "
            "valleys (the paper's); hertz: a profile shaped like the smooth contact's pressure, "
            "scaled by the unknown (theory.md §11.4)."},
    {.section = "lubrication", .name = "tolerance", .kind = K_REAL, .unit = MC_UNIT_NONE,
     .lo = 1e-12, .hi = 0.1, .def = "1e-6", .off = AT(lubrication.tolerance),
     .doc = "Relative tolerance of the volume root: abs(V - V*) / V*."},

    /* [plasticity] */
    {.section = "plasticity", .name = "enabled", .kind = K_BOOL,
     .def = "yes, when [plasticity] is present", .def_rule = 1, .off = AT(plasticity.enabled),
     .doc = "Run the elastic-plastic stage (body 1 yields)."},
    {.section = "plasticity", .name = "criterion", .kind = K_ENUM,
     .choices = "von_mises pressure_cap", .def = "von_mises", .off = AT(plasticity.criterion),
     .doc = "von_mises: J2 yield of the volume stress with Prandtl-Reuss flow (the paper); "
            "pressure_cap: the usual limiting-pressure model (the contact pressure is capped at "
            "the hardness; the penetration there is the plastic deformation)."},
    {.section = "plasticity", .name = "hardness", .kind = K_REAL, .unit = MC_UNIT_PRESSURE,
     .lo = 0, .lo_open = 1, .hi = 1e12, .required = 1, .use = USE_WHEN, .use_key = "criterion",
     .use_values = "pressure_cap", .off = AT(plasticity.hardness),
     .doc = "Limiting pressure of criterion = pressure_cap (e.g. 3 Y)."},
    {.section = "plasticity", .name = "hardening", .kind = K_ENUM,
     .choice = hardening_choice, .choice_help = hardening_help, .def = "perfect", .use = USE_WHEN,
     .use_key = "criterion", .use_values = "von_mises", .off = AT(plasticity.hardening),
     .doc = "Isotropic hardening law sigma_y(p) of the accumulated plastic strain p."},
    {.section = "plasticity", .name = "yield_stress", .kind = K_REAL, .unit = MC_UNIT_PRESSURE,
     .lo = 0, .lo_open = 1, .hi = 1e12, .required = 1, .use = USE_WHEN, .use_key = "hardening",
     .use_values = "perfect linear", .off = AT(plasticity.yield_stress),
     .doc = "Initial yield stress Y0 (uniaxial)."},
    {.section = "plasticity", .name = "tangent_modulus", .kind = K_REAL, .unit = MC_UNIT_PRESSURE,
     .lo = 0, .hi = 1e13, .lo_text = ">= 0 and < E of body1", .required = 1, .use = USE_WHEN,
     .use_key = "hardening", .use_values = "linear", .off = AT(plasticity.tangent_modulus),
     .doc = "Slope E_t of the uniaxial stress-strain curve beyond yield (plastic modulus "
            "H = E E_t / (E - E_t))."},
    {.section = "plasticity", .name = "swift_B", .kind = K_REAL, .unit = MC_UNIT_PRESSURE, .lo = 0,
     .lo_open = 1, .hi = 1e12, .required = 1, .use = USE_WHEN, .use_key = "hardening",
     .use_values = "swift", .off = AT(plasticity.swift_B),
     .doc = "Swift law sigma_y = B (C + 1e6 p)^n with p in micro-strain through the 1e6: B, a "
            "stress (AISI 52100: 1280 MPa)."},
    {.section = "plasticity", .name = "swift_C", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .lo_open = 1, .hi = 1e9, .required = 1, .use = USE_WHEN, .use_key = "hardening",
     .use_values = "swift", .off = AT(plasticity.swift_C),
     .doc = "Swift C, in micro-strain: the initial yield is B C^n (AISI 52100: 4)."},
    {.section = "plasticity", .name = "swift_n", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .hi = 1, .hi_open = 1, .required = 1, .use = USE_WHEN, .use_key = "hardening",
     .use_values = "swift", .off = AT(plasticity.swift_n),
     .doc = "Swift hardening exponent n (AISI 52100: 0.095)."},
    {.section = "plasticity", .name = "table", .kind = K_PATH, .required = 1, .use = USE_WHEN,
     .use_key = "hardening", .use_values = "table", .off = AT(plasticity.table), .relative = 1,
     .doc = "CSV of (eps_p, sigma_y) rows, eps_p increasing from 0, sigma_y not decreasing; "
            "relative to the case file."},
    {.section = "plasticity", .name = "table_unit", .kind = K_ENUM, .choices = "Pa MPa GPa",
     .def = "MPa", .use = USE_WHEN, .use_key = "hardening", .use_values = "table",
     .off = AT(plasticity.table_unit), .doc = "Unit of sigma_y in the table."},
    {.section = "plasticity", .name = "bodies", .kind = K_ENUM, .choices = "one both",
     .def = "one", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.both),
     .doc = "one: body 1 yields, body 2 stays elastic (or rigid); both: the two bodies are of "
            "the same material and deform alike (each takes the same residual displacement)."},
    {.section = "plasticity", .name = "load_steps", .kind = K_INT, .lo = 1, .hi = 10000,
     .def = "10", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.load_steps), .doc = "Load increments up to the full load."},
    {.section = "plasticity", .name = "relaxation", .kind = K_REAL, .unit = MC_UNIT_NONE,
     .lo = 0, .lo_open = 1, .hi = 1, .def = "0.7", .use = USE_WHEN, .use_key = "criterion",
     .use_values = "von_mises", .off = AT(plasticity.relaxation),
     .doc = "Under-relaxation omega of the residual displacement between outer iterations."},
    {.section = "plasticity", .name = "tolerance", .kind = K_REAL, .unit = MC_UNIT_NONE,
     .lo = 1e-12, .hi = 0.5, .def = "1e-3", .use = USE_WHEN, .use_key = "criterion",
     .use_values = "von_mises", .off = AT(plasticity.tolerance),
     .doc = "Outer iteration: relative change of the residual displacement that ends a step."},
    {.section = "plasticity", .name = "max_outer", .kind = K_INT, .lo = 1, .hi = 100000,
     .def = "30", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.max_outer),
     .doc = "Outer iterations per load step; reaching it ends the run, not converged, "
            "with the results of the last iterate (docs/theory.md §9.5)."},
    {.section = "plasticity", .name = "plastic_tolerance", .kind = K_REAL, .unit = MC_UNIT_NONE,
     .lo = 1e-15, .hi = 0.1, .def = "1e-4", .use = USE_WHEN, .use_key = "criterion",
     .use_values = "von_mises", .off = AT(plasticity.plastic_tolerance),
     .doc = "Fixed point of the plastic strain increment: change relative to max(increment, "
            "1e-3). (1e-4 against 1e-7 changed the residual displacement of a rough yielding "
            "contact by 1e-5 relative, with half the sweeps.)"},
    {.section = "plasticity", .name = "max_plastic", .kind = K_INT, .lo = 1, .hi = 100000,
     .def = "100", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.max_plastic),
     .doc = "Fixed-point sweeps per outer iteration; a fixed point that uses them all in 8 "
            "successive outer iterations ends the run, not converged (docs/theory.md §9.5)."},
    {.section = "plasticity", .name = "iteration", .kind = K_ENUM, .choices = "joint nested",
     .def = "joint", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.iteration),
     .doc = "How a load increment iterates contact, residual displacement and plastic strain "
            "(docs/theory.md §9.8): joint, Anderson mixing of the plastic strain increment "
            "through the whole coupled map, one contact solve and one residual stress "
            "application per evaluation (a 512 x 256 x 16 running-in step: 19 applications "
            "instead of 125), the nested iteration going on from its state if it has not "
            "converged in max_outer evaluations; nested, an outer iteration on the residual "
            "displacement around a plastic fixed point (docs/theory.md §9.1, §9.4). The same "
            "stopping tests either way."},
    {.section = "plasticity", .name = "near_field", .kind = K_INT, .lo = 0, .hi = 8,
     .def = "0", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.near_field),
     .doc = "Local-global plastic fixed point (docs/theory.md §9.7): > 0 iterates the plastic "
            "strain increment between two applications of the residual stress operator with "
            "its near field (this many columns around each cell, and layers as deep), on the "
            "cells at or near yield; the same fixed point and stopping test with fewer "
            "applications (a 256 x 128 x 16 running-in step: 19 instead of 62; 512 x 256 x 16: "
            "71). 0: one application per sweep."},
    {.section = "plasticity", .name = "dz", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = 1, .def = "min(dx, dy) / 2", .def_rule = 1, .use = USE_WHEN,
     .use_key = "criterion", .use_values = "von_mises", .off = AT(plasticity.dz),
     .doc = "Thickness of the volume cells (dx / 2 on a line grid: periodic_y, ny = 1). With "
            "stress_points = centre a dz between 0.6 and 1.6 dx (or dy) gets the warning "
            "plastic_checkerboard: the centre values have an unstable x-z (y-z) checkerboard "
            "mode there, into which a perfectly plastic run can lock."},
    {.section = "plasticity", .name = "stress_points", .kind = K_ENUM,
     .choices = "cell_average centre", .def = "cell_average", .use = USE_WHEN,
     .use_key = "criterion", .use_values = "von_mises", .off = AT(plasticity.stress_points),
     .doc = "Where a volume cell's residual stress is taken: cell_average, the infinite-space "
            "part averaged over the cell near the source (Galerkin-like: no unstable "
            "checkerboard mode); centre, the cell-centre values (the earlier collocation, whose "
            "operator has energy-releasing checkerboard modes; docs/theory.md §8.5, §8.7)."},
    {.section = "plasticity", .name = "kernel", .kind = K_ENUM, .choices = "cuboid spectral",
     .def = "spectral", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.kernel),
     .doc = "Lateral discretisation of the plastic strain (docs/theory.md §8.10): spectral (the "
            "default), sampled trigonometric fields with the kernel evaluated per Fourier mode "
            "when used (~50 bytes per volume cell free, ~12 doubly periodic; a whole run ~190 "
            "bytes per volume cell; no build time; exact laterally for smooth fields), its "
            "volume under the whole grid, its operators replicated on every MPI process; "
            "cuboid, uniform cuboids whose kernels are tabulated and kept as spectra (~600 "
            "bytes per volume cell on a free grid, a whole run ~1000), its volume a window of "
            "columns ([plasticity] margin), its operators split over the MPI processes."},
    {.section = "plasticity", .name = "depth", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = 1, .def = "auto", .word = "auto", .word_value = 0, .use = USE_WHEN,
     .use_key = "criterion", .use_values = "von_mises", .off = AT(plasticity.depth),
     .doc = "Depth of the plastic volume; auto: where the elastic von Mises stress at the full "
            "load falls below half the initial yield stress, plus 25 %."},
    {.section = "plasticity", .name = "layering", .kind = K_ENUM,
     .choices = "auto uniform graded", .def = "auto", .use = USE_WHEN, .use_key = "criterion",
     .use_values = "von_mises", .off = AT(plasticity.layering),
     .doc = "Layer thickness in depth: uniform, every layer dz; graded, layers of dz down to "
            "fine_depth, below it each layer an odd number of dz at most grading x its depth "
            "(fine where the asperity fields are, coarse where only the macro field is; "
            "docs/theory.md §8.8); auto: graded when depth = auto, else uniform."},
    {.section = "plasticity", .name = "fine_depth", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = 1, .def = "auto", .word = "auto", .word_value = 0,
     .use = USE_WHEN, .use_key = "layering", .use_values = "auto graded",
     .off = AT(plasticity.fine_depth),
     .doc = "Graded layering: depth down to which the layers keep the thickness dz; auto: "
            "8 min(dx, dy) (8 dx on a line grid)."},
    {.section = "plasticity", .name = "grading", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .lo_open = 1, .hi = 1, .def = "0.25", .use = USE_WHEN, .use_key = "layering",
     .use_values = "auto graded", .off = AT(plasticity.grading),
     .doc = "Graded layering: a layer below fine_depth is at most this fraction of the depth "
            "of its top thick (rounded down to an odd number of dz, never thinner than the "
            "layer above)."},
    {.section = "plasticity", .name = "margin", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .lo_open = 1, .hi = 1, .def = "auto", .word = "auto", .word_value = 0, .use = USE_WHEN,
     .use_key = "criterion", .use_values = "von_mises", .off = AT(plasticity.margin),
     .doc = "Columns of plastic cells with kernel = cuboid: the elastic contact's bounding box "
            "widened by this on every side; auto: the depth of the volume (the default spectral "
            "kernel's volume is the whole grid)."},
    {.section = "plasticity", .name = "friction", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .hi = 1, .def = "0", .use = USE_WHEN, .use_key = "criterion", .use_values = "von_mises",
     .off = AT(plasticity.friction),
     .doc = "Coulomb coefficient of the traction q_x = friction (p - p_lub) in solid contact "
            "(sliding in +x), in the stresses that drive yield."},

    /* [runin] */
    {.section = "runin", .name = "enabled", .kind = K_BOOL,
     .def = "yes, when [runin] is present", .def_rule = 1, .off = AT(runin.enabled),
     .doc = "Run the running-in driver (no: one run of the scene, e.g. --set runin.enabled=no)."},
    {.section = "runin", .name = "forces", .kind = K_LIST, .unit = MC_UNIT_FORCE, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .list_max = MC_RUNIN_MAX, .def = "[load] force alone",
     .def_rule = 1, .off = AT(runin.forces), .count_off = AT(runin.nforces),
     .doc = "Macro normal forces F_N, e.g. 1086 N, 2172 N, 3258 N, in the order run: a run-down "
            "and a run-up each, each starting on the surface the one before left. The first "
            "must be [load] force."},
    {.section = "runin", .name = "speeds", .kind = K_LIST, .unit = MC_UNIT_ROTATION, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .order = -1, .list_max = MC_RUNIN_MAX, .required = 1,
     .off = AT(runin.speeds), .count_off = AT(runin.nspeeds),
     .doc = "The run-down: speeds of disc 1, e.g. 3000, 2000, 1000, 500, 200 rpm (the first is "
            "[lubrication] rpm; disc 2 keeps the ratio rpm2 / rpm, or equal surface speed); "
            "elastic-plastic steps that carry the surface over. The run-up takes them in "
            "reverse, elastic on the run-in surface."},
    {.section = "runin", .name = "nominal_deflection", .kind = K_ENUM, .choices = "remove keep",
     .def = "remove", .off = AT(runin.deflection),
     .doc = "remove: the patch, the centre of the macro contact, is not bent by its own nominal "
            "pressure (the bowl K p_nom of a load on a grid with free axes belongs to the macro "
            "contact; on a periodic grid it is zero); keep: the patch deflects as a loaded "
            "island."},
    {.section = "runin", .name = "friction_in_yield", .kind = K_BOOL, .def = "no",
     .off = AT(runin.friction_in_yield),
     .doc = "yes: every elastic-plastic run-down step loads its yield check with the friction "
            "traction q_x = mu (p - p_lub) in solid contact, mu the step's friction coefficient "
            "(psi mu_solid + (1 - psi) mu_fluid at the step's volume equilibrium), along the "
            "sliding of disc 2 against disc 1 (+x when disc 2 is the faster surface); needs "
            "[plasticity] and rolling-sliding ([lubrication] rpm2), and replaces [plasticity] "
            "friction (docs/theory.md §19.7). no: pressure alone, as the paper's model."},

    /* [output] */
    {.section = "output", .name = "dir", .kind = K_PATH, .def = "out/(case file name without .ini)",
     .def_rule = 1, .off = AT(output.dir),
     .doc = "Output directory, relative to the current directory (not to the case file)."},
    {.section = "output", .name = "vtk", .kind = K_BOOL, .def = "no", .off = AT(output.vtk),
     .doc = "Also write field.vti for ParaView."},
    {.section = "output", .name = "x3p", .kind = K_BOOL, .def = "no", .off = AT(output.x3p),
     .doc = "Also write every surface height map as X3P (ISO 25178-72, heights in m, the same "
            "field as the .npy of the same name): topography.x3p, and where the run has them "
            "topography_final.x3p (elastic-plastic), surface_initial.x3p and surface_final.x3p "
            "(running-in), surface_initial_body1.x3p, ... (with [roughness2])."},
};

const int mc_nkeys = (int)(sizeof mc_keys / sizeof mc_keys[0]);
_Static_assert(sizeof mc_keys / sizeof mc_keys[0] <= MC_MAX_KEYS, "raise MC_MAX_KEYS");


const case_section mc_key_sections[] = {
    {"mesh", NULL,
     "The surface mesh: nx x ny cells of dx x dy, centred on the apex of the shape. x is the "
     "rolling direction, y the transverse (axial) one."},
    {"geometry", NULL,
     "The combined gap of the two smooth bodies at zero load; its apex is at the grid centre."},
    {"roughness", NULL,
     "Roughness heights, positive towards the counter body, subtracted from the gap. Each type "
     "uses only its own keys; a key of another type is an error. Alone, the composite roughness "
     "of the gap; with [roughness2], body 1's surface."},
    {"roughness2", NULL,
     "Body 2's surface (the same keys as [roughness], which is then body 1's): each body's "
     "heights are measured outward, towards the other body, and the gap's roughness is their sum "
     "z1 + z2 (docs/theory.md §4.11). Both maps must come onto the same mesh. Each body's surface "
     "before and after (surface_initial_body1.npy, ...) and its ISO parameters "
     "(summary.json roughness.body1, roughness.body2) are written."},
    {"body1", NULL, "Body 1: an elastic half-space."},
    {"body2", NULL, "Body 2: an elastic half-space, or rigid."},
    {"load", NULL,
     "The normal load: give exactly one of force, force_per_length, approach, pressure_file."},
    {"solver", NULL, "The normal-contact solver."},
    {"stress", "enabled",
     "Subsurface stresses on depth layers under the contact. The stage runs only when this "
     "section is present (in the file, or created by an override such as --set "
     "stress.enabled=yes) and enabled. Layers run from depth_min to depth_max (layers, spacing) "
     "or are listed in depths; depth_max = auto (the default) takes the depth from the contact."},
    {"lubrication", "enabled",
     "The lubricant volume equilibrium (Mevissen et al. 2025): the lubricant pressure of the "
     "boundary condition is the one at which the pocket volume of the loaded rough gap equals "
     "h_EHD times the nominal area. Runs when this section is present and [load] "
     "lubricant_pressure = auto. A flat patch with macro_radius and width stands for the centre "
     "of a macro line contact under [load] force = F_N: it is loaded with the macro Hertz "
     "pressure p_H (w' = F_N / width); without macro_radius (film = given) the scene's load is "
     "used as it is."},
    {"plasticity", "enabled",
     "The elastic-plastic stage (Jacq et al. 2002; Mevissen et al. 2025): the load rises in "
     "steps; in each the contact, the elastic stress of the pressure, the J2 return mapping of "
     "the volume stress (stress-based yield, not a pressure cap) and the residual surface "
     "displacement of the plastic strain are iterated to convergence; then the load is removed "
     "and the run-in topography and residual stresses remain. Body 1 yields."},
    {"output", NULL, "Where the results go (the output contract: README.md, Outputs)."},
    {"runin", "enabled",
     "Running-in (Mevissen et al. 2025): for each force a speed run-down, every speed an "
     "elastic-plastic step with the lubricant volume equilibrium and the surface carried over, "
     "then the run-up, elastic on the run-in surface. The scene itself is the first step: [load] "
     "force is the first force, [lubrication] rpm (film = ehl, with radius1, radius2) the first "
     "speed, [load] lubricant_pressure = auto. Without [plasticity] the material is elastic and "
     "nothing runs in. Writes runin.csv, runin.gp, surface_initial.npy, surface_final.npy, "
     "material_ratio.csv; "
     "checkpoints in DIR/checkpoint/ for --resume."},
};

const int mc_nsections = (int)(sizeof mc_key_sections / sizeof mc_key_sections[0]);

const case_section *mc_key_section(const char *name)
{
    for (int s = 0; s < mc_nsections; s++)
        if (strcmp(mc_key_sections[s].name, name) == 0)
            return &mc_key_sections[s];
    return NULL;
}

int mc_key_find(const char *section, const char *name)
{
    for (int k = 0; k < mc_nkeys; k++)
        if (strcmp(mc_keys[k].section, section) == 0 && strcmp(mc_keys[k].name, name) == 0)
            return k;
    return -1;
}

/* ---- small text helpers ---------------------------------------------------------------------- */

void mc_key_fmt(char *buf, size_t len, const char *f, ...)
{
    va_list ap;
    va_start(ap, f);
    vsnprintf(buf, len, f, ap);
    va_end(ap);
}

/* Word i of a space-separated list into buf; 0 if there is none. */
int mc_key_word(const char *list, int i, char *buf, size_t len)
{
    const char *p = list;
    for (;;) {
        while (*p == ' ')
            p++;
        if (!*p)
            return 0;
        size_t n = strcspn(p, " ");
        if (i-- == 0) {
            mc_key_fmt(buf, len, "%.*s", (int)n, p);
            return 1;
        }
        p += n;
    }
}

int mc_key_word_index(const char *list, const char *word)
{
    char w[64];
    for (int i = 0; mc_key_word(list, i, w, sizeof w); i++)
        if (strcmp(w, word) == 0)
            return i;
    return -1;
}

/* The list as "a, b, c" (sep between words). */
void mc_key_words_joined(const char *list, const char *sep, char *buf, size_t len)
{
    char w[64];
    size_t o = 0;
    buf[0] = '\0';
    for (int i = 0; mc_key_word(list, i, w, sizeof w) && o < len; i++) {
        mc_key_fmt(buf + o, len - o, "%s%s", i ? sep : "", w);
        o += strlen(buf + o);
    }
}

int mc_key_choice(const case_key *k, int i, char *buf, size_t len)
{
    if (!k->choice)
        return mc_key_word(k->choices, i, buf, len);
    const char *name = i >= 0 ? k->choice(i) : NULL;
    if (!name)
        return 0;
    mc_key_fmt(buf, len, "%s", name);
    return 1;
}

int mc_key_choice_index(const case_key *k, const char *word)
{
    char w[64];
    for (int i = 0; mc_key_choice(k, i, w, sizeof w); i++)
        if (strcmp(w, word) == 0)
            return i;
    return -1;
}

void mc_key_choices_joined(const case_key *k, const char *sep, char *buf, size_t len)
{
    char w[64];
    size_t o = 0;
    buf[0] = '\0';
    for (int i = 0; mc_key_choice(k, i, w, sizeof w) && o < len; i++) {
        mc_key_fmt(buf + o, len - o, "%s%s", i ? sep : "", w);
        o += strlen(buf + o);
    }
}

/* A value for a message: continuation line breaks shown as spaces, then quoted and cut. */
void mc_key_show(const char *v, char *buf, size_t len)
{
    char flat[256];
    size_t n = 0;
    for (; v[n] && n < sizeof flat - 1; n++)
        flat[n] = v[n] == '\n' ? ' ' : v[n];
    flat[n] = '\0';
    mc_case_quote(flat, buf, len);
}

void mc_key_fmt_bound(double v, mc_unit_kind unit, char *buf, size_t len)
{
    if (unit == MC_UNIT_NONE || v == 0)
        mc_key_fmt(buf, len, "%g", v);
    else
        mc_key_fmt(buf, len, "%g %s", v, mc_unit_si_symbol(unit));
}

/* What a key accepts: with noun "an integer in 1..65536", "a length > 0 and <= 1 m"; without
 * it (the docs' column) "1..65536", "> 0 and <= 1 m". */
void mc_key_describe(const case_key *k, int noun, char *buf, size_t len)
{
    char lo[64] = "", hi[64] = "", cond[160];
    switch (k->kind) {
    case K_INT: mc_key_fmt(buf, len, "%s%.0f..%.0f", noun ? "an integer in " : "", k->lo, k->hi); return;
    case K_SEED: mc_key_fmt(buf, len, "%s0..18446744073709551615", noun ? "an integer in " : ""); return;
    case K_ENUM: {
        char w[MC_KEY_DESCRIBE_MAX];
        mc_key_choices_joined(k, ", ", w, sizeof w);
        mc_key_fmt(buf, len, "%s%s", noun ? "one of " : "", w);
        return;
    }
    case K_BOOL:
        mc_key_fmt(buf, len, "%s", noun ? "yes or no (also true/false, on/off, 1/0)" : "yes, no");
        return;
    case K_PATH:
        if (noun)
            mc_key_fmt(buf, len, "a path");
        else
            mc_key_fmt(buf, len, "%s", k->relative ? "path, relative to the case file" : "path");
        return;
    case K_REGION:
        mc_key_fmt(buf, len, "%sx0, y0, width, height: four lengths, width and height > 0",
                   noun ? "" : "");
        return;
    case K_LENGTHS:
        mc_key_fmt(buf, len, "%scomma-separated lengths >= 0, strictly increasing, at most %d",
            noun ? "a list of " : "", MC_MAX_DEPTHS);
        return;
    case K_LIST: {
        case_key item = *k;
        char one[160];
        item.kind = K_REAL;
        mc_key_describe(&item, 0, one, sizeof one);
        mc_key_fmt(buf, len, "%scomma-separated %ss %s%s, at most %d", noun ? "a list of " : "",
                   mc_unit_kind_name(k->unit), one,
                   k->order > 0   ? ", strictly increasing"
                   : k->order < 0 ? ", strictly decreasing"
                                  : "",
                   k->list_max);
        return;
    }
    case K_REAL: break;
    }
    if (k->lo_text)
        mc_key_fmt(lo, sizeof lo, "%s", k->lo_text);
    else if (isfinite(k->lo)) {
        char b[48];
        mc_key_fmt_bound(k->lo, k->unit, b, sizeof b);
        mc_key_fmt(lo, sizeof lo, "%s %s", k->lo_open ? ">" : ">=", b);
    }
    if (isfinite(k->hi)) {
        char b[48];
        mc_key_fmt_bound(k->hi, k->unit, b, sizeof b);
        mc_key_fmt(hi, sizeof hi, "%s %s", k->hi_open ? "<" : "<=", b);
    }
    mc_key_fmt(cond, sizeof cond, "%s%s%s", lo, lo[0] && hi[0] ? " and " : "", hi);
    char alt[64] = "";
    if (k->word)
        mc_key_fmt(alt, sizeof alt, ", or %s", k->word);
    if (!noun)
        mc_key_fmt(buf, len, "%s%s", cond[0] ? cond : "any", alt);
    else if (k->unit == MC_UNIT_NONE)
        mc_key_fmt(buf, len, "a number%s%s%s", cond[0] ? " " : "", cond, alt);
    else
        mc_key_fmt(buf, len, "a %s%s%s%s", mc_unit_kind_name(k->unit), cond[0] ? " " : "", cond, alt);
}

int mc_key_in_range(const case_key *k, double x)
{
    if (k->lo_open ? !(x > k->lo) : !(x >= k->lo))
        return 0;
    if (k->hi_open ? !(x < k->hi) : !(x <= k->hi))
        return 0;
    return 1;
}

/* ---- value conversion (one key, one text) ---------------------------------------------------- */

static int parse_ll(const char *v, long long *out)
{
    const char *p = v + (*v == '+' || *v == '-');
    if (!*p)
        return 0;
    for (const char *q = p; *q; q++)
        if (!isdigit((unsigned char)*q))
            return 0;
    errno = 0;
    long long x = strtoll(v, NULL, 10);
    if (errno)
        return 0;
    *out = x;
    return 1;
}

void mc_key_put_int(mc_scene *sc, size_t off, int v) { memcpy((char *)sc + off, &v, sizeof v); }

int mc_key_get_int(const mc_scene *sc, size_t off)
{
    int v;
    memcpy(&v, (const char *)sc + off, sizeof v);
    return v;
}

/* Comma-separated lengths; a line break (continuation) also separates, and a comma may end a
 * line. */
/* Trimmed copy of p[0..n) into buf (NUL-terminated, cut to len). */
static void trimmed(const char *p, size_t n, char *buf, size_t len)
{
    while (n > 0 && isspace((unsigned char)*p)) {
        p++;
        n--;
    }
    while (n > 0 && isspace((unsigned char)p[n - 1]))
        n--;
    if (n >= len)
        n = len - 1;
    memcpy(buf, p, n);
    buf[n] = '\0';
}

/* K_LIST: comma-separated quantities, e.g. "1086 N, 1500 N" or "3000, 2000, 500 rpm": a unit
 * written after the last number applies to the bare numbers before it. */
static int convert_list_items(const case_key *k, const char *v, mc_scene *sc, char *why,
                              size_t wl);

/* A list continued on indented lines (the reader joins them with '\n'): a line end separates
 * items as a comma does, so "1086 N, 2172 N" + "3258 N" and "1086 N," + "2172 N" both read. */
static int convert_list(const case_key *k, const char *v, mc_scene *sc, char *why, size_t wl)
{
    if (!strchr(v, '\n'))
        return convert_list_items(k, v, sc, why, wl);
    size_t n = strlen(v);
    char *j = mc_malloc(n + 1);
    if (!j) {
        mc_key_fmt(why, wl, "out of memory");
        return 1;
    }
    size_t m = 0;
    for (size_t q = 0; q < n; q++) {
        if (v[q] != '\n') {
            j[m++] = v[q];
            continue;
        }
        size_t b = m;
        while (b > 0 && isspace((unsigned char)j[b - 1]))
            b--;
        j[m++] = b > 0 && j[b - 1] == ',' ? ' ' : ',';
    }
    j[m] = '\0';
    int rc = convert_list_items(k, j, sc, why, wl);
    mc_free(j);
    return rc;
}

static int convert_list_items(const case_key *k, const char *v, mc_scene *sc, char *why,
                              size_t wl)
{
    double x[MC_RUNIN_MAX > MC_MAX_DEPTHS ? MC_RUNIN_MAX : MC_MAX_DEPTHS];
    const int cap = k->list_max < (int)(sizeof x / sizeof x[0]) ? k->list_max
                                                                  : (int)(sizeof x / sizeof x[0]);
    char item[160], text[200], shown[96], prev[96] = "", unit[64] = "", uwhy[200];
    /* the unit of the last item, if it has one */
    const char *last = strrchr(v, ',');
    trimmed(last ? last + 1 : v, strlen(last ? last + 1 : v), item, sizeof item);
    char *end = NULL;
    (void)strtod(item, &end);
    if (end && end != item)
        trimmed(end, strlen(end), unit, sizeof unit);
    int n = 0;
    for (const char *p = v;; n++) {
        size_t len = strcspn(p, ",");
        trimmed(p, len, item, sizeof item);
        if (!item[0]) {
            mc_key_fmt(why, wl, "item %d is empty; give comma-separated values", n + 1);
            return 1;
        }
        if (n == cap) {
            mc_key_fmt(why, wl, "more than %d items", cap);
            return 1;
        }
        end = NULL;
        (void)strtod(item, &end);
        int bare = end && end != item && !*end;
        mc_key_fmt(text, sizeof text, "%s%s%s", item, bare && unit[0] ? " " : "",
                   bare ? unit : "");
        mc_case_quote(text, shown, sizeof shown);
        if (mc_parse_quantity(text, k->unit, &x[n], uwhy, sizeof uwhy)) {
            mc_key_fmt(why, wl, "item %d (%s): %s", n + 1, shown, uwhy);
            return 1;
        }
        if (!mc_key_in_range(k, x[n])) {
            case_key one = *k;
            char range[160];
            one.kind = K_REAL;
            mc_key_describe(&one, 1, range, sizeof range);
            mc_key_fmt(why, wl, "item %d (%s) must be %s", n + 1, shown, range);
            return 1;
        }
        if (n > 0 && k->order != 0 && !(k->order > 0 ? x[n] > x[n - 1] : x[n] < x[n - 1])) {
            mc_key_fmt(why, wl, "item %d (%s) must be %s than item %d (%s): the list is strictly "
                       "%s",
                       n + 1, shown, k->order > 0 ? "greater" : "less", n, prev,
                       k->order > 0 ? "increasing" : "decreasing");
            return 1;
        }
        memcpy(prev, shown, sizeof shown);
        if (!p[len])
            break;
        p += len + 1;
    }
    memcpy((char *)sc + k->off, x, sizeof(double) * (size_t)(n + 1));
    mc_key_put_int(sc, k->count_off, n + 1);
    return 0;
}

/* x0, y0, width, height (lengths; width and height > 0). */
static int convert_region(const case_key *k, const char *v, mc_scene *sc, char *why, size_t wl)
{
    static const char *const what[4] = {"x0", "y0", "width", "height"};
    double r[4];
    const char *p = v;
    for (int n = 0; n < 4; n++) {
        size_t len = strcspn(p, ",");
        if (!p[len] && n < 3) {
            mc_key_fmt(why, wl, "%d value%s given; give x0, y0, width, height", n + 1,
                       n ? "s" : "");
            return 1;
        }
        char item[160], shown[96], uwhy[200];
        size_t il = len < sizeof item - 1 ? len : sizeof item - 1;
        memcpy(item, p, il);
        item[il] = '\0';
        char *a = item;
        while (isspace((unsigned char)*a))
            a++;
        size_t al = strlen(a);
        while (al > 0 && isspace((unsigned char)a[al - 1]))
            a[--al] = '\0';
        mc_case_quote(a, shown, sizeof shown);
        if (mc_parse_quantity(a, k->unit, &r[n], uwhy, sizeof uwhy)) {
            mc_key_fmt(why, wl, "%s (%s): %s", what[n], shown, uwhy);
            return 1;
        }
        if (n >= 2 && !(r[n] > 0)) {
            mc_key_fmt(why, wl, "%s (%s) must be > 0", what[n], shown);
            return 1;
        }
        p += len + (p[len] ? 1 : 0);
        if (n == 3 && *p) {
            mc_key_fmt(why, wl, "more than four values; give x0, y0, width, height");
            return 1;
        }
    }
    memcpy((char *)sc + k->off, r, sizeof r);
    return 0;
}

static int convert_lengths(const case_key *k, const char *v, mc_scene *sc, char *why, size_t wl)
{
    double z[MC_MAX_DEPTHS];
    char item[160], shown[96], prev_shown[96] = "";
    int n = 0;
    const char *p = v;
    char before = '\0'; /* separator before the current item */
    for (;;) {
        size_t len = strcspn(p, ",\n");
        char after = p[len];
        const char *a = p, *b = p + len;
        while (a < b && isspace((unsigned char)*a))
            a++;
        while (b > a && isspace((unsigned char)b[-1]))
            b--;
        if (a == b) {
            if (!(before == ',' && after != ',')) {
                mc_key_fmt(why, wl, "item %d is empty; %s", n + 1, "give comma-separated lengths");
                return 1;
            }
        } else {
            if (n == MC_MAX_DEPTHS) {
                mc_key_fmt(why, wl, "more than %d depths", MC_MAX_DEPTHS);
                return 1;
            }
            size_t il = (size_t)(b - a);
            if (il >= sizeof item)
                il = sizeof item - 1;
            memcpy(item, a, il);
            item[il] = '\0';
            mc_case_quote(item, shown, sizeof shown);
            char uwhy[200];
            if (mc_parse_quantity(item, k->unit, &z[n], uwhy, sizeof uwhy)) {
                mc_key_fmt(why, wl, "item %d (%s): %s", n + 1, shown, uwhy);
                return 1;
            }
            if (!mc_key_in_range(k, z[n])) {
                mc_key_fmt(why, wl, "item %d (%s) must be a length >= 0", n + 1, shown);
                return 1;
            }
            if (n > 0 && !(z[n] > z[n - 1])) {
                mc_key_fmt(why, wl,
                    "item %d (%s) must be greater than item %d (%s): depths are strictly "
                    "increasing",
                    n + 1, shown, n, prev_shown);
                return 1;
            }
            memcpy(prev_shown, shown, sizeof shown);
            n++;
        }
        if (!after)
            break;
        before = after;
        p += len + 1;
    }
    if (n == 0) {
        mc_key_fmt(why, wl, "no depths given");
        return 1;
    }
    memcpy((char *)sc + k->off, z, sizeof(double) * (size_t)n);
    mc_key_put_int(sc, k->count_off, n);
    return 0;
}

/* Convert text v for key k into the scene. base: directory for relative paths (NULL: none).
 * Returns 0, or 1 with the reason in why ("must be an integer in 1..65536"). */
int mc_key_convert(const case_key *k, const char *v, const char *base, mc_scene *sc, char *why,
                   size_t wl)
{
    char range[MC_KEY_DESCRIBE_MAX];
    mc_key_describe(k, 1, range, sizeof range);
    if (!*v) {
        mc_key_fmt(why, wl, "a value is required (%s)", range);
        return 1;
    }
    char *dst = (char *)sc + k->off;
    switch (k->kind) {
    case K_INT: {
        long long x;
        if (!parse_ll(v, &x) || (double)x < k->lo || (double)x > k->hi) {
            mc_key_fmt(why, wl, "must be %s", range);
            return 1;
        }
        mc_key_put_int(sc, k->off, (int)x);
        return 0;
    }
    case K_SEED: {
        for (const char *q = v; *q; q++)
            if (!isdigit((unsigned char)*q)) {
                mc_key_fmt(why, wl, "must be %s", range);
                return 1;
            }
        errno = 0;
        unsigned long long x = strtoull(v, NULL, 10);
        if (errno) {
            mc_key_fmt(why, wl, "must be %s", range);
            return 1;
        }
        uint64_t u = (uint64_t)x;
        memcpy(dst, &u, sizeof u);
        return 0;
    }
    case K_REAL: {
        double x;
        if (k->word && strcmp(v, k->word) == 0) {
            memcpy(dst, &k->word_value, sizeof k->word_value);
            return 0;
        }
        if (mc_parse_quantity(v, k->unit, &x, why, wl)) {
            if (k->word) {
                const size_t used = strlen(why);
                mc_key_fmt(why + used, wl - used, "; or %s", k->word);
            }
            return 1;
        }
        if (!mc_key_in_range(k, x)) {
            mc_key_fmt(why, wl, "must be %s", range);
            return 1;
        }
        memcpy(dst, &x, sizeof x);
        return 0;
    }
    case K_ENUM: {
        int i = mc_key_choice_index(k, v);
        if (i < 0) {
            mc_key_fmt(why, wl, "must be %s", range);
            return 1;
        }
        mc_key_put_int(sc, k->off, i);
        return 0;
    }
    case K_BOOL: {
        static const char *const yes[] = {"yes", "true", "on", "1"};
        static const char *const no[] = {"no", "false", "off", "0"};
        for (int i = 0; i < 4; i++) {
            if (strcmp(v, yes[i]) == 0 || strcmp(v, no[i]) == 0) {
                mc_key_put_int(sc, k->off, strcmp(v, yes[i]) == 0);
                return 0;
            }
        }
        mc_key_fmt(why, wl, "must be %s", range);
        return 1;
    }
    case K_PATH: {
        int n;
        if (k->relative && base && base[0] && v[0] != '/')
            n = snprintf(dst, MC_PATH_MAX, "%s%s%s", base, base[strlen(base) - 1] == '/' ? "" : "/",
                         v);
        else
            n = snprintf(dst, MC_PATH_MAX, "%s", v);
        if (n < 0 || n >= MC_PATH_MAX) {
            dst[0] = '\0';
            mc_key_fmt(why, wl, "the path is longer than %d bytes%s", MC_PATH_MAX - 1,
                base && base[0] ? " (after prefixing the case file's directory)" : "");
            return 1;
        }
        return 0;
    }
    case K_LENGTHS: return convert_lengths(k, v, sc, why, wl);
    case K_REGION: return convert_region(k, v, sc, why, wl);
    case K_LIST: return convert_list(k, v, sc, why, wl);
    }
    return 1;
}



/* ---- the table applied to a scene ------------------------------------------------------------ */

int mc_key_selector(int k)
{
    const char *u = mc_keys[k].use_key, *dot = u ? strchr(u, '.') : NULL;
    if (!u)
        return -1;
    if (!dot)
        return mc_key_find(mc_keys[k].section, u);
    char sec[32];
    mc_key_fmt(sec, sizeof sec, "%.*s", (int)(dot - u), u);
    return mc_key_find(sec, dot + 1);
}

void mc_key_value_text(const mc_scene *sc, int k, char *buf, size_t len)
{
    int v = mc_key_get_int(sc, mc_keys[k].off);
    if (mc_keys[k].kind == K_BOOL)
        mc_key_fmt(buf, len, "%s", v ? "yes" : "no");
    else if (!mc_key_choice(&mc_keys[k], v, buf, len))
        mc_key_fmt(buf, len, "%d", v);
}

/* A tagged key is in force when the scene holds its tag. */
static int tag_in_force(const mc_scene *sc, int k)
{
    return mc_key_get_int(sc, mc_keys[k].tag_off) == mc_keys[k].tag;
}

int mc_key_used_in_scene(const mc_scene *sc, int k)
{
    const case_key *key = &mc_keys[k];
    if (key->tagged && !tag_in_force(sc, k))
        return 0;
    if (key->use == USE_ALWAYS)
        return 1;
    int sel = mc_key_selector(k);
    if (key->use == USE_UNLESS)
        return !(mc_keys[sel].tagged && tag_in_force(sc, sel));
    char v[64];
    mc_key_value_text(sc, sel, v, sizeof v);
    return mc_key_word_index(key->use_values, v) >= 0 && mc_key_used_in_scene(sc, sel);
}

static int section_on(const mc_scene *sc, const char *section)
{
    const case_section *s = mc_key_section(section);
    if (!s || !s->switch_key)
        return 1;
    return mc_key_get_int(sc, mc_keys[mc_key_find(section, s->switch_key)].off) != 0;
}

static double get_real(const mc_scene *sc, size_t off)
{
    double v;
    memcpy(&v, (const char *)sc + off, sizeof v);
    return v;
}

/* A value that stands for "not given": 0 for an optional key without a default value (its
 * absence is a rule, e.g. lambda_long: the domain; macro_radius: no macro contact) or for an
 * untagged member of a group (rq or rms_slope); the word's value (auto). */
static int unset_real(const case_key *k, double v)
{
    if (k->word && v == k->word_value)
        return 1;
    int optional = !k->required && (!k->def || k->def_rule);
    return v == 0 && ((optional && !k->tagged) || (k->group && !k->tagged));
}

static int fail_key(const case_key *k, mc_error *err, const char **section, const char **key,
                    const char *value, const char *item)
{
    char what[MC_KEY_DESCRIBE_MAX];
    mc_key_describe(k, 1, what, sizeof what);
    if (section)
        *section = k->section;
    if (key)
        *key = k->name;
    return mc_fail(err, MC_ERR_INPUT, "[%s] %s%s = %s: must be %s", k->section, k->name, item,
                   value, what);
}

/* K_LIST in a scene: an optional list may be empty (count 0: not given); otherwise 1..list_max
 * finite items in range and in order. */
static int check_list(const mc_scene *sc, const case_key *k, mc_error *err, const char **section,
                      const char **key)
{
    int n;
    memcpy(&n, (const char *)sc + k->count_off, sizeof n);
    char v[64], item[32];
    if (n == 0 && !k->required)
        return MC_OK;
    if (n < 1 || n > k->list_max) {
        mc_key_fmt(v, sizeof v, "%d items", n);
        return fail_key(k, err, section, key, v, "");
    }
    const double *x = (const double *)((const char *)sc + k->off);
    for (int i = 0; i < n; i++)
        if (!(isfinite(x[i]) && mc_key_in_range(k, x[i]) &&
              (i == 0 || k->order == 0 || (k->order > 0 ? x[i] > x[i - 1] : x[i] < x[i - 1])))) {
            mc_key_fmt(v, sizeof v, "%g %s", x[i], mc_unit_si_symbol(k->unit));
            mc_key_fmt(item, sizeof item, " item %d", i + 1);
            return fail_key(k, err, section, key, v, item);
        }
    return MC_OK;
}

static int check_lengths(const mc_scene *sc, const case_key *k, mc_error *err,
                         const char **section, const char **key)
{
    int n;
    memcpy(&n, (const char *)sc + k->count_off, sizeof n);
    char v[64], item[32];
    if (n < 1 || n > MC_MAX_DEPTHS) {
        mc_key_fmt(v, sizeof v, "%d items", n);
        return fail_key(k, err, section, key, v, "");
    }
    const double *z = (const double *)((const char *)sc + k->off);
    for (int i = 0; i < n; i++)
        if (!(isfinite(z[i]) && mc_key_in_range(k, z[i]) && (i == 0 || z[i] > z[i - 1]))) {
            mc_key_fmt(v, sizeof v, "%g %s", z[i], mc_unit_si_symbol(k->unit));
            mc_key_fmt(item, sizeof item, " item %d", i + 1);
            return fail_key(k, err, section, key, v, item);
        }
    return MC_OK;
}

int mc_keys_check_scene(const mc_scene *sc, const char *only, mc_error *err, const char **section,
                        const char **key)
{
    char v[96];
    for (int k = 0; k < mc_nkeys; k++) {
        const case_key *row = &mc_keys[k];
        if ((only && strcmp(row->section, only) != 0) || !section_on(sc, row->section) ||
            !mc_key_used_in_scene(sc, k))
            continue;
        switch (row->kind) {
        case K_INT: {
            int x = mc_key_get_int(sc, row->off);
            if (!(x >= row->lo && x <= row->hi)) {
                mc_key_fmt(v, sizeof v, "%d", x);
                return fail_key(row, err, section, key, v, "");
            }
            break;
        }
        case K_ENUM: {
            int x = mc_key_get_int(sc, row->off);
            if (x < 0 || !mc_key_choice(row, x, v, sizeof v)) {
                mc_key_fmt(v, sizeof v, "%d (no such choice)", x);
                return fail_key(row, err, section, key, v, "");
            }
            break;
        }
        case K_BOOL: {
            int x = mc_key_get_int(sc, row->off);
            if (x != 0 && x != 1) {
                mc_key_fmt(v, sizeof v, "%d", x);
                return fail_key(row, err, section, key, v, "");
            }
            break;
        }
        case K_REAL: {
            double x = get_real(sc, row->off);
            if (unset_real(row, x))
                break;
            if (!mc_key_in_range(row, x) || isnan(x)) {
                if (row->unit == MC_UNIT_NONE)
                    mc_key_fmt(v, sizeof v, "%g", x);
                else
                    mc_key_fmt(v, sizeof v, "%g %s", x, mc_unit_si_symbol(row->unit));
                return fail_key(row, err, section, key, v, "");
            }
            break;
        }
        case K_PATH:
            if ((row->required || row->tagged) && !((const char *)sc + row->off)[0])
                return fail_key(row, err, section, key, "\"\"", "");
            break;
        case K_LENGTHS: {
            int rc = check_lengths(sc, row, err, section, key);
            if (rc)
                return rc;
            break;
        }
        case K_LIST: {
            int rc = check_list(sc, row, err, section, key);
            if (rc)
                return rc;
            break;
        }
        case K_SEED: break;
        case K_REGION: {
            const double *r = (const double *)((const char *)sc + row->off);
            if (!(isfinite(r[0]) && isfinite(r[1]) && r[2] > 0 && r[3] > 0 && isfinite(r[2]) &&
                  isfinite(r[3]))) {
                mc_key_fmt(v, sizeof v, "%g, %g, %g, %g m", r[0], r[1], r[2], r[3]);
                return fail_key(row, err, section, key, v, "");
            }
            break;
        }
        }
    }
    return MC_OK;
}

void mc_keys_defaults(mc_scene *sc)
{
    char why[256];
    for (int k = 0; k < mc_nkeys; k++) {
        const case_key *row = &mc_keys[k];
        if (!row->def || row->def_rule || row->def_from || row->kind == K_PATH)
            continue;
        /* the table's own check (mc_case_check_table) proves every default converts */
        (void)mc_key_convert(row, row->def, NULL, sc, why, sizeof why);
    }
}
