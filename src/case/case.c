/* case.c - INI case files with units -> mc_scene (see case.h).
 *
 * Three passes: inih reads the text through our own line reader (which counts lines, enforces
 * inih's line limit and UTF-8, and knows which lines are continuations) and every [section]
 * header and key = value pair is collected; --set overrides replace or add entries; then the
 * entries are validated against the one declarative key table below, written into a scene, and
 * the scene's cross-key rules are checked. The same table generates the Markdown reference.
 */
#include "case/case.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
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
_Static_assert(sizeof(mc_stress_window_mode) == sizeof(int), "enum size");
_Static_assert(MC_SHAPE_ELLIPSOID == 3 && MC_ROUGH_FILE == 3 && MC_BACKEND_DIRECT == 1 &&
                   MC_METHOD_ACTIVE_SET == 2 && MC_SPACING_GEOMETRIC == 1 && MC_STRESS_POINT == 1 &&
                   MC_STRESS_WINDOW_FULL == 1,
               "choice lists below follow the enum order");

#define MAX_FILE_BYTES (16L << 20) /* a case file is a few kB; refuse to slurp devices */

/* ---- the key table --------------------------------------------------------------------------- */

typedef enum {
    K_INT,    /* int in lo..hi */
    K_SEED,   /* uint64_t, any value */
    K_REAL,   /* double with a unit kind, in (lo|[lo, hi]|hi) */
    K_ENUM,   /* one of choices; stored as the index */
    K_BOOL,   /* yes/no; stored as 0/1 in an int */
    K_PATH,   /* char[MC_PATH_MAX] */
    K_LENGTHS /* comma-separated lengths, strictly increasing, >= 0 */
} key_kind;

typedef enum {
    USE_ALWAYS,
    USE_WHEN,  /* used when use_key's value is one of use_values (space-separated) */
    USE_UNLESS /* used unless use_key is given */
} key_use;

typedef struct {
    const char *section, *name;
    key_kind kind;
    mc_unit_kind unit;    /* K_REAL, K_LENGTHS */
    double lo, hi;        /* K_INT, K_REAL: accepted range */
    int lo_open, hi_open; /* K_REAL: strict bounds */
    const char *lo_text;  /* replaces the lower bound in messages: a cross-key bound */
    const char *choices;  /* K_ENUM: space-separated names */
    const char *def;      /* documented default; NULL: none */
    int def_rule;         /* def states a rule, not a value (not checked against the scene) */
    const char *def_from; /* default: the value of this key of the same section */
    int required;         /* must be given whenever it is used */
    const char *group;    /* exactly one of the used keys of a group must be given */
    key_use use;
    const char *use_key, *use_values;
    size_t off;      /* destination in mc_scene */
    int tagged, tag; /* when given, also store tag (an enum value) at tag_off */
    size_t tag_off;
    size_t count_off; /* K_LENGTHS: int count */
    int relative;     /* K_PATH: resolved against the case file's directory */
    const char *word; /* K_REAL: a word accepted instead of a number, stored as word_value */
    double word_value;
    const char *doc;
} case_key;

#define AT(field) offsetof(mc_scene, field)

static const case_key keys[] = {
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

    /* [roughness] */
    {.section = "roughness", .name = "type", .kind = K_ENUM,
     .choices = "none gaussian self_affine file", .def = "none", .off = AT(roughness.type),
     .doc = "Roughness heights added to the surface (positive towards the counter body)."},
    {.section = "roughness", .name = "rq", .kind = K_REAL, .unit = MC_UNIT_LENGTH, .lo = 0,
     .hi = HUGE_VAL, .group = "height", .use = USE_WHEN, .use_key = "type",
     .use_values = "gaussian self_affine", .off = AT(roughness.rq),
     .doc = "RMS height Rq (required for gaussian; for self_affine give rq or rms_slope)."},
    {.section = "roughness", .name = "rms_slope", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .group = "height", .use = USE_WHEN, .use_key = "type",
     .use_values = "self_affine", .off = AT(roughness.rms_slope),
     .doc = "RMS slope, instead of rq."},
    {.section = "roughness", .name = "correlation_x", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .required = 1, .use = USE_WHEN, .use_key = "type",
     .use_values = "gaussian", .off = AT(roughness.correlation_x),
     .doc = "Correlation length along x: autocorrelation exp(-(tx/lx)^2 - (ty/ly)^2)."},
    {.section = "roughness", .name = "correlation_y", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .def = "correlation_x", .def_from = "correlation_x",
     .use = USE_WHEN, .use_key = "type", .use_values = "gaussian",
     .off = AT(roughness.correlation_y), .doc = "Correlation length along y."},
    {.section = "roughness", .name = "hurst", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 0,
     .lo_open = 1, .hi = 1, .hi_open = 1, .def = "0.8", .use = USE_WHEN, .use_key = "type",
     .use_values = "self_affine", .off = AT(roughness.hurst),
     .doc = "Hurst exponent H (power spectrum ~ q^-2(1+H))."},
    {.section = "roughness", .name = "lambda_long", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .def = "the longer domain side", .def_rule = 1,
     .use = USE_WHEN, .use_key = "type", .use_values = "self_affine",
     .off = AT(roughness.lambda_long), .doc = "Longest wavelength (long cut-off)."},
    {.section = "roughness", .name = "lambda_short", .kind = K_REAL, .unit = MC_UNIT_LENGTH,
     .lo = 0, .lo_open = 1, .hi = HUGE_VAL, .def = "2 max(dx, dy)", .def_rule = 1,
     .use = USE_WHEN, .use_key = "type", .use_values = "self_affine",
     .off = AT(roughness.lambda_short),
     .doc = "Shortest wavelength (short cut-off), below lambda_long."},
    {.section = "roughness", .name = "seed", .kind = K_SEED, .def = "1", .use = USE_WHEN,
     .use_key = "type", .use_values = "gaussian self_affine", .off = AT(roughness.seed),
     .doc = "Random seed: the same seed gives the same surface on every run."},
    {.section = "roughness", .name = "file", .kind = K_PATH, .required = 1, .use = USE_WHEN,
     .use_key = "type", .use_values = "file", .off = AT(roughness.file), .relative = 1,
     .doc = "Height map (.npy or whitespace-separated text), relative to the case file."},

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
     .lo = 0, .hi = HUGE_VAL, .def = "0", .off = AT(load.lubricant_pressure),
     .doc = "Lower bound of the pressure outside solid contact (a lubricant film)."},
    {.section = "load", .name = "pressure_cap", .kind = K_REAL, .unit = MC_UNIT_PRESSURE, .lo = 0,
     .lo_open = 1, .hi = HUGE_VAL, .lo_text = "> lubricant_pressure", .def = "none (unbounded)",
     .def_rule = 1, .off = AT(load.pressure_cap),
     .doc = "Upper bound of the pressure (e.g. a hardness)."},

    /* [solver] */
    {.section = "solver", .name = "operator", .kind = K_ENUM, .choices = "fft direct",
     .def = "fft", .off = AT(solver.op),
     .doc = "Convolution backend: fft (DC-FFT) or direct (O(N^2) sums, the reference)."},
    {.section = "solver", .name = "method", .kind = K_ENUM, .choices = "cg pk active-set",
     .def = "cg", .off = AT(solver.method),
     .doc = "cg: preconditioned constrained conjugate gradients; pk: Polonsky & Keer (1999); "
            "active-set: the dense reference (small grids)."},
    {.section = "solver", .name = "tolerance", .kind = K_REAL, .unit = MC_UNIT_NONE, .lo = 1e-15,
     .hi = 1e-2, .def = "1e-8", .off = AT(solver.tolerance),
     .doc = "Relative stopping tolerance."},
    {.section = "solver", .name = "max_iterations", .kind = K_INT, .lo = 1, .hi = 10000000,
     .def = "2000", .off = AT(solver.max_iterations),
     .doc = "Iteration limit; reaching it is reported as not converged."},
    {.section = "solver", .name = "threads", .kind = K_INT, .lo = 0, .hi = 1024, .def = "0",
     .off = AT(solver.threads), .doc = "Threads for FFTW and OpenMP; 0 = all cores."},

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

    /* [output] */
    {.section = "output", .name = "dir", .kind = K_PATH, .def = "out/(case file name without .ini)",
     .def_rule = 1, .off = AT(output.dir),
     .doc = "Output directory, relative to the current directory (not to the case file)."},
    {.section = "output", .name = "vtk", .kind = K_BOOL, .def = "no", .off = AT(output.vtk),
     .doc = "Also write field.vti for ParaView."},
};

#define NKEYS ((int)(sizeof keys / sizeof keys[0]))

typedef struct {
    const char *name;
    const char *switch_key; /* a bool key that turns the section's requirements off */
    const char *doc;
} case_section;

static const case_section sections[] = {
    {"mesh", NULL,
     "The surface mesh: nx x ny cells of dx x dy, centred on the apex of the shape. x is the "
     "rolling direction, y the transverse (axial) one."},
    {"geometry", NULL,
     "The combined gap of the two smooth bodies at zero load; its apex is at the grid centre."},
    {"roughness", NULL,
     "Roughness heights, positive towards the counter body, subtracted from the gap. Each type "
     "uses only its own keys; a key of another type is an error."},
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
    {"output", NULL, "Where the results go (see DESIGN.md, output contract)."},
};

#define NSECTIONS ((int)(sizeof sections / sizeof sections[0]))

static const case_section *find_section(const char *name)
{
    for (int s = 0; s < NSECTIONS; s++)
        if (strcmp(sections[s].name, name) == 0)
            return &sections[s];
    return NULL;
}

static int find_key(const char *section, const char *name)
{
    for (int k = 0; k < NKEYS; k++)
        if (strcmp(keys[k].section, section) == 0 && strcmp(keys[k].name, name) == 0)
            return k;
    return -1;
}

/* ---- small text helpers ---------------------------------------------------------------------- */

static void fmt(char *buf, size_t len, const char *f, ...) __attribute__((format(printf, 3, 4)));
static void fmt(char *buf, size_t len, const char *f, ...)
{
    va_list ap;
    va_start(ap, f);
    vsnprintf(buf, len, f, ap);
    va_end(ap);
}

/* Word i of a space-separated list into buf; 0 if there is none. */
static int nth_word(const char *list, int i, char *buf, size_t len)
{
    const char *p = list;
    for (;;) {
        while (*p == ' ')
            p++;
        if (!*p)
            return 0;
        size_t n = strcspn(p, " ");
        if (i-- == 0) {
            fmt(buf, len, "%.*s", (int)n, p);
            return 1;
        }
        p += n;
    }
}

static int word_index(const char *list, const char *word)
{
    char w[64];
    for (int i = 0; nth_word(list, i, w, sizeof w); i++)
        if (strcmp(w, word) == 0)
            return i;
    return -1;
}

/* The list as "a, b, c" (sep between words). */
static void words_joined(const char *list, const char *sep, char *buf, size_t len)
{
    char w[64];
    size_t o = 0;
    buf[0] = '\0';
    for (int i = 0; nth_word(list, i, w, sizeof w) && o < len; i++) {
        fmt(buf + o, len - o, "%s%s", i ? sep : "", w);
        o += strlen(buf + o);
    }
}

/* A value for a message: continuation line breaks shown as spaces, then quoted and cut. */
static void show(const char *v, char *buf, size_t len)
{
    char flat[256];
    size_t n = 0;
    for (; v[n] && n < sizeof flat - 1; n++)
        flat[n] = v[n] == '\n' ? ' ' : v[n];
    flat[n] = '\0';
    mc_text_quote(flat, buf, len);
}

static void fmt_bound(double v, mc_unit_kind unit, char *buf, size_t len)
{
    if (unit == MC_UNIT_NONE || v == 0)
        fmt(buf, len, "%g", v);
    else
        fmt(buf, len, "%g %s", v, mc_unit_si_symbol(unit));
}

/* What a key accepts: with noun "an integer in 1..65536", "a length > 0 and <= 1 m"; without
 * it (the docs' column) "1..65536", "> 0 and <= 1 m". */
static void describe(const case_key *k, int noun, char *buf, size_t len)
{
    char lo[64] = "", hi[64] = "", cond[160];
    switch (k->kind) {
    case K_INT: fmt(buf, len, "%s%.0f..%.0f", noun ? "an integer in " : "", k->lo, k->hi); return;
    case K_SEED: fmt(buf, len, "%s0..18446744073709551615", noun ? "an integer in " : ""); return;
    case K_ENUM: {
        char w[160];
        words_joined(k->choices, ", ", w, sizeof w);
        fmt(buf, len, "%s%s", noun ? "one of " : "", w);
        return;
    }
    case K_BOOL:
        fmt(buf, len, "%s", noun ? "yes or no (also true/false, on/off, 1/0)" : "yes, no");
        return;
    case K_PATH:
        if (noun)
            fmt(buf, len, "a path");
        else
            fmt(buf, len, "%s", k->relative ? "path, relative to the case file" : "path");
        return;
    case K_LENGTHS:
        fmt(buf, len, "%scomma-separated lengths >= 0, strictly increasing, at most %d",
            noun ? "a list of " : "", MC_MAX_DEPTHS);
        return;
    case K_REAL: break;
    }
    if (k->lo_text)
        fmt(lo, sizeof lo, "%s", k->lo_text);
    else if (isfinite(k->lo)) {
        char b[48];
        fmt_bound(k->lo, k->unit, b, sizeof b);
        fmt(lo, sizeof lo, "%s %s", k->lo_open ? ">" : ">=", b);
    }
    if (isfinite(k->hi)) {
        char b[48];
        fmt_bound(k->hi, k->unit, b, sizeof b);
        fmt(hi, sizeof hi, "%s %s", k->hi_open ? "<" : "<=", b);
    }
    fmt(cond, sizeof cond, "%s%s%s", lo, lo[0] && hi[0] ? " and " : "", hi);
    char alt[64] = "";
    if (k->word)
        fmt(alt, sizeof alt, ", or %s", k->word);
    if (!noun)
        fmt(buf, len, "%s%s", cond[0] ? cond : "any", alt);
    else if (k->unit == MC_UNIT_NONE)
        fmt(buf, len, "a number%s%s%s", cond[0] ? " " : "", cond, alt);
    else
        fmt(buf, len, "a %s%s%s%s", mc_unit_kind_name(k->unit), cond[0] ? " " : "", cond, alt);
}

static int in_range(const case_key *k, double x)
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

static void put_int(mc_scene *sc, size_t off, int v) { memcpy((char *)sc + off, &v, sizeof v); }

static int get_int(const mc_scene *sc, size_t off)
{
    int v;
    memcpy(&v, (const char *)sc + off, sizeof v);
    return v;
}

/* Comma-separated lengths; a line break (continuation) also separates, and a comma may end a
 * line. */
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
                fmt(why, wl, "item %d is empty; %s", n + 1, "give comma-separated lengths");
                return 1;
            }
        } else {
            if (n == MC_MAX_DEPTHS) {
                fmt(why, wl, "more than %d depths", MC_MAX_DEPTHS);
                return 1;
            }
            size_t il = (size_t)(b - a);
            if (il >= sizeof item)
                il = sizeof item - 1;
            memcpy(item, a, il);
            item[il] = '\0';
            mc_text_quote(item, shown, sizeof shown);
            char uwhy[200];
            if (mc_parse_quantity(item, k->unit, &z[n], uwhy, sizeof uwhy)) {
                fmt(why, wl, "item %d (%s): %s", n + 1, shown, uwhy);
                return 1;
            }
            if (!in_range(k, z[n])) {
                fmt(why, wl, "item %d (%s) must be a length >= 0", n + 1, shown);
                return 1;
            }
            if (n > 0 && !(z[n] > z[n - 1])) {
                fmt(why, wl,
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
        fmt(why, wl, "no depths given");
        return 1;
    }
    memcpy((char *)sc + k->off, z, sizeof(double) * (size_t)n);
    put_int(sc, k->count_off, n);
    return 0;
}

/* Convert text v for key k into the scene. base: directory for relative paths (NULL: none).
 * Returns 0, or 1 with the reason in why ("must be an integer in 1..65536"). */
static int convert(const case_key *k, const char *v, const char *base, mc_scene *sc, char *why,
                   size_t wl)
{
    char range[200];
    describe(k, 1, range, sizeof range);
    if (!*v) {
        fmt(why, wl, "a value is required (%s)", range);
        return 1;
    }
    char *dst = (char *)sc + k->off;
    switch (k->kind) {
    case K_INT: {
        long long x;
        if (!parse_ll(v, &x) || (double)x < k->lo || (double)x > k->hi) {
            fmt(why, wl, "must be %s", range);
            return 1;
        }
        put_int(sc, k->off, (int)x);
        return 0;
    }
    case K_SEED: {
        for (const char *q = v; *q; q++)
            if (!isdigit((unsigned char)*q)) {
                fmt(why, wl, "must be %s", range);
                return 1;
            }
        errno = 0;
        unsigned long long x = strtoull(v, NULL, 10);
        if (errno) {
            fmt(why, wl, "must be %s", range);
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
                fmt(why + used, wl - used, "; or %s", k->word);
            }
            return 1;
        }
        if (!in_range(k, x)) {
            fmt(why, wl, "must be %s", range);
            return 1;
        }
        memcpy(dst, &x, sizeof x);
        return 0;
    }
    case K_ENUM: {
        int i = word_index(k->choices, v);
        if (i < 0) {
            fmt(why, wl, "must be %s", range);
            return 1;
        }
        put_int(sc, k->off, i);
        return 0;
    }
    case K_BOOL: {
        static const char *const yes[] = {"yes", "true", "on", "1"};
        static const char *const no[] = {"no", "false", "off", "0"};
        for (int i = 0; i < 4; i++) {
            if (strcmp(v, yes[i]) == 0 || strcmp(v, no[i]) == 0) {
                put_int(sc, k->off, strcmp(v, yes[i]) == 0);
                return 0;
            }
        }
        fmt(why, wl, "must be %s", range);
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
            fmt(why, wl, "the path is longer than %d bytes%s", MC_PATH_MAX - 1,
                base && base[0] ? " (after prefixing the case file's directory)" : "");
            return 1;
        }
        return 0;
    }
    case K_LENGTHS: return convert_lengths(k, v, sc, why, wl);
    }
    return 1;
}

/* ---- collecting entries: the line reader and the inih handler -------------------------------- */

typedef struct {
    char *section;
    char *name; /* NULL: a [section] header line */
    char *value;
    size_t vlen, vcap;
    int line;        /* line of the key (or header) in the file; 0 for an override */
    int cont_line;   /* first continuation line of the value; 0 if none */
    const char *ovr; /* the --set text when the value comes from an override */
} entry;

typedef struct {
    const char *name;     /* for messages */
    const char *base_dir; /* for relative paths in the file */
    const char *text;
    mc_error *err;

    /* reader state */
    const char *p;
    int line;      /* lines handed to inih so far = the handler's line number */
    int cont;      /* the current line continues the previous key's value */
    int have_prev; /* mirror of inih's "previous key" (continuations need one) */
    int stop, nomem;
    int bad_line; /* first line the reader refused, with its reason */
    char bad[200];
    int unterminated; /* first "[section" line without ']' */

    entry *e;
    int n, cap;
    int slot[NKEYS]; /* entry index of each key, -1 if not given */
    mc_scene sc;
} ctx;

static char *dup_range(const char *s, size_t n)
{
    char *d = mc_malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

static int set_value(entry *e, const char *v)
{
    size_t n = strlen(v);
    char *d = dup_range(v, n);
    if (!d)
        return 0;
    mc_free(e->value);
    e->value = d;
    e->vlen = n;
    e->vcap = n + 1;
    return 1;
}

static int append_value(entry *e, const char *v)
{
    size_t n = strlen(v), need = e->vlen + 1 + n + 1;
    if (need > e->vcap) {
        size_t cap = 2 * e->vcap > need ? 2 * e->vcap : need;
        char *d = mc_malloc(cap);
        if (!d)
            return 0;
        memcpy(d, e->value, e->vlen);
        mc_free(e->value);
        e->value = d;
        e->vcap = cap;
    }
    e->value[e->vlen++] = '\n';
    memcpy(e->value + e->vlen, v, n + 1);
    e->vlen += n;
    return 1;
}

/* Append an entry (name NULL: a header); NULL when out of memory. */
static entry *add_entry(ctx *c, const char *section, size_t seclen, const char *name,
                        const char *value, int line)
{
    if (c->n == c->cap) {
        int cap = c->cap ? 2 * c->cap : 32;
        entry *e = mc_calloc((size_t)cap, sizeof *e);
        if (!e)
            return NULL;
        if (c->n)
            memcpy(e, c->e, sizeof *e * (size_t)c->n);
        mc_free(c->e);
        c->e = e;
        c->cap = cap;
    }
    entry *e = &c->e[c->n];
    memset(e, 0, sizeof *e);
    e->line = line;
    e->section = dup_range(section, seclen);
    if (!e->section)
        return NULL;
    if (name) {
        e->name = dup_range(name, strlen(name));
        if (!e->name || !set_value(e, value)) {
            mc_free(e->name);
            mc_free(e->section);
            return NULL;
        }
    }
    c->n++;
    return e;
}

static void free_entries(ctx *c)
{
    for (int i = 0; i < c->n; i++) {
        mc_free(c->e[i].section);
        mc_free(c->e[i].name);
        mc_free(c->e[i].value);
    }
    mc_free(c->e);
    c->e = NULL;
    c->n = c->cap = 0;
}

/* inih's find_chars_or_comment: first of chars, or an inline ';' after whitespace. */
static const char *chars_or_comment(const char *s, const char *chars)
{
    int was_space = 0;
    while (*s && !strchr(chars, *s) && !(was_space && *s == ';')) {
        was_space = isspace((unsigned char)*s);
        s++;
    }
    return s;
}

/* Classify the line the way inih will (multiline on, ';' and '#' comments): continuation,
 * section header, key line. Records headers, which inih does not report. */
static void classify(ctx *c, const char *line)
{
    const char *s = line;
    c->cont = 0;
    if (c->line == 1 && (unsigned char)s[0] == 0xEF && (unsigned char)s[1] == 0xBB &&
        (unsigned char)s[2] == 0xBF)
        s += 3;
    while (isspace((unsigned char)*s))
        s++;
    if (!*s || *s == ';' || *s == '#')
        return;
    if (c->have_prev && s > line) {
        c->cont = 1;
        return;
    }
    if (*s == '[') {
        const char *end = chars_or_comment(s + 1, "]");
        if (*end == ']') {
            c->have_prev = 0;
            if (!add_entry(c, s + 1, (size_t)(end - s - 1), NULL, NULL, c->line))
                c->nomem = c->stop = 1;
        } else if (!c->unterminated)
            c->unterminated = c->line;
        return;
    }
    const char *end = chars_or_comment(s, "=:");
    if ((*end == '=' || *end == ':') && end > s)
        c->have_prev = 1;
}

/* fgets-like reader over the text: one line per call (without its line break). */
static char *read_line(char *str, int num, void *stream)
{
    ctx *c = stream;
    if (c->stop || !*c->p || num < 2)
        return NULL;
    const char *s = c->p;
    size_t len = strcspn(s, "\n");
    const char *next = s[len] ? s + len + 1 : s + len;
    size_t clen = len;
    if (clen && s[clen - 1] == '\r')
        clen--;
    c->line++;
    size_t bad_at;
    if (clen > (size_t)(num - 1)) {
        c->bad_line = c->line;
        fmt(c->bad, sizeof c->bad,
            "line %d is longer than %d characters (the INI reader's limit); continue a long "
            "list on indented lines",
            c->line, num - 1);
        c->stop = 1;
        return NULL;
    }
    if (!mc_utf8_check(s, clen, &bad_at)) {
        c->bad_line = c->line;
        fmt(c->bad, sizeof c->bad, "line %d is not UTF-8 text (byte 0x%02X at column %zu)", c->line,
            (unsigned char)s[bad_at], bad_at + 1);
        c->stop = 1;
        return NULL;
    }
    memcpy(str, s, clen);
    str[clen] = '\0';
    c->p = next;
    classify(c, str);
    return c->stop ? NULL : str;
}

static int on_pair(void *user, const char *section, const char *name, const char *value)
{
    ctx *c = user;
    if (c->stop)
        return 1;
    if (c->cont && c->n > 0 && c->e[c->n - 1].name) {
        entry *e = &c->e[c->n - 1];
        if (!e->cont_line)
            e->cont_line = c->line;
        if (append_value(e, value))
            return 1;
    } else if (add_entry(c, section, strlen(section), name, value, c->line))
        return 1;
    c->nomem = c->stop = 1;
    return 0;
}

/* ---- messages -------------------------------------------------------------------------------- */

/* "--set mesh.nx=0: " for an override entry, else "x.ini:12: ", or "x.ini: " without a line. */
static void prefix(const ctx *c, const entry *e, int line, char *buf, size_t len)
{
    char q[96];
    if (e && e->ovr) {
        mc_text_quote(e->ovr, q, sizeof q);
        fmt(buf, len, "--set %s: ", q);
    } else if (line > 0)
        fmt(buf, len, "%s:%d: ", c->name, line);
    else
        fmt(buf, len, "%s: ", c->name);
}

static int fail_at(const ctx *c, const entry *e, int line, const char *f, ...)
    __attribute__((format(printf, 4, 5)));
static int fail_at(const ctx *c, const entry *e, int line, const char *f, ...)
{
    char head[MC_ERROR_MSG_MAX], body[MC_ERROR_MSG_MAX];
    prefix(c, e, line, head, sizeof head);
    va_list ap;
    va_start(ap, f);
    vsnprintf(body, sizeof body, f, ap);
    va_end(ap);
    return mc_fail(c->err, MC_ERR_INPUT, "%s%s", head, body);
}

/* Where another entry is, seen from a message about e: "on line 8", "on line 8 of x.ini",
 * "given by --set load.force=3 N". */
static void where(const ctx *c, const entry *from, const entry *other, char *buf, size_t len)
{
    char q[96];
    if (other->ovr) {
        mc_text_quote(other->ovr, q, sizeof q);
        fmt(buf, len, "given by --set %s", q);
    } else if (from && from->ovr)
        fmt(buf, len, "on line %d of %s", other->line, c->name);
    else
        fmt(buf, len, "on line %d", other->line);
}

static void known_sections(char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = '\0';
    for (int s = 0; s < NSECTIONS && o < len; s++) {
        fmt(buf + o, len - o, "%s%s", s ? ", " : "", sections[s].name);
        o += strlen(buf + o);
    }
}

static void keys_of(const char *section, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = '\0';
    for (int k = 0; k < NKEYS && o < len; k++) {
        if (strcmp(keys[k].section, section) != 0)
            continue;
        fmt(buf + o, len - o, "%s%s", o ? ", " : "", keys[k].name);
        o += strlen(buf + o);
    }
}

/* ---- validation ------------------------------------------------------------------------------ */

/* The effective value of an enum or bool key as text ("sphere", "yes"). */
static void value_text(const ctx *c, int k, char *buf, size_t len)
{
    int v = get_int(&c->sc, keys[k].off);
    if (keys[k].kind == K_BOOL)
        fmt(buf, len, "%s", v ? "yes" : "no");
    else if (!nth_word(keys[k].choices, v, buf, len))
        fmt(buf, len, "%d", v);
}

static int used(const ctx *c, int k)
{
    const case_key *key = &keys[k];
    if (key->use == USE_ALWAYS)
        return 1;
    int sel = find_key(key->section, key->use_key);
    if (key->use == USE_UNLESS)
        return c->slot[sel] < 0;
    char v[64];
    value_text(c, sel, v, sizeof v);
    return word_index(key->use_values, v) >= 0;
}

/* The section's requirements apply (its switch key, if any, is on). */
static int section_active(const ctx *c, const char *section)
{
    const case_section *s = find_section(section);
    if (!s->switch_key)
        return 1;
    return get_int(&c->sc, keys[find_key(section, s->switch_key)].off) != 0;
}

/* "force, force_per_length, approach, pressure_file": the used keys of k's group. */
static int group_members(const ctx *c, int k, char *buf, size_t len)
{
    size_t o = 0;
    int n = 0;
    buf[0] = '\0';
    for (int j = 0; j < NKEYS && o < len; j++) {
        if (!keys[j].group || strcmp(keys[j].group, keys[k].group) != 0 ||
            strcmp(keys[j].section, keys[k].section) != 0 || !used(c, j))
            continue;
        fmt(buf + o, len - o, "%s%s", n++ ? ", " : "", keys[j].name);
        o += strlen(buf + o);
    }
    return n;
}

/* " for shape = sphere" when k is conditional on a selector. */
static void condition_text(const ctx *c, int k, char *buf, size_t len)
{
    buf[0] = '\0';
    if (keys[k].use == USE_WHEN) {
        char v[64];
        value_text(c, find_key(keys[k].section, keys[k].use_key), v, sizeof v);
        fmt(buf, len, " for %s = %s", keys[k].use_key, v);
    }
}

static int check_structure(ctx *c)
{
    char list[512], q[96], qv[96];
    for (int i = 0; i < c->n; i++) {
        entry *e = &c->e[i];
        mc_text_quote(e->section, q, sizeof q);
        if (!e->name) {
            if (!find_section(e->section)) {
                known_sections(list, sizeof list);
                return fail_at(c, e, e->line, "unknown section [%s]; known sections: %s", q, list);
            }
            continue;
        }
        char qn[96];
        mc_text_quote(e->name, qn, sizeof qn);
        if (!e->section[0]) {
            known_sections(list, sizeof list);
            show(e->value, qv, sizeof qv);
            return fail_at(c, e, e->line, "%s = %s comes before any [section]; known sections: %s",
                           qn, qv, list);
        }
        if (!find_section(e->section)) {
            known_sections(list, sizeof list);
            return fail_at(c, e, e->line, "unknown section [%s]; known sections: %s", q, list);
        }
        int k = find_key(e->section, e->name);
        if (k < 0) {
            keys_of(e->section, list, sizeof list);
            return fail_at(c, e, e->line, "[%s] unknown key '%s'; keys of [%s]: %s", q, qn, q,
                           list);
        }
        if (c->slot[k] >= 0) {
            char w[160];
            where(c, e, &c->e[c->slot[k]], w, sizeof w);
            return fail_at(c, e, e->line, "[%s] %s given twice (first %s)", q, qn, w);
        }
        c->slot[k] = i;
    }
    return MC_OK;
}

static int key_of_entry(const entry *e) { return e->name ? find_key(e->section, e->name) : -1; }

static int convert_entries(ctx *c)
{
    char why[512], qv[96];
    for (int i = 0; i < c->n; i++) {
        const entry *e = &c->e[i];
        int k = key_of_entry(e);
        if (k < 0)
            continue;
        const case_key *key = &keys[k];
        show(e->value, qv, sizeof qv);
        if (e->cont_line && key->kind != K_LENGTHS)
            return fail_at(c, e, e->cont_line,
                           "[%s] %s: this line starts with whitespace, so it continues %s from "
                           "line %d, but %s takes a single value (remove the indentation)",
                           key->section, key->name, key->name, e->line, key->name);
        if (convert(key, e->value, e->ovr ? NULL : c->base_dir, &c->sc, why, sizeof why))
            return fail_at(c, e, e->line, "[%s] %s = %s: %s", key->section, key->name, qv, why);
    }
    return MC_OK;
}

static int check_use(ctx *c)
{
    char w[160], v[64], members[256];
    for (int i = 0; i < c->n; i++) {
        const entry *e = &c->e[i];
        int k = key_of_entry(e);
        if (k < 0)
            continue;
        const case_key *key = &keys[k];
        if (!used(c, k)) {
            int sel = find_key(key->section, key->use_key);
            if (key->use == USE_WHEN) {
                value_text(c, sel, v, sizeof v);
                return fail_at(c, e, e->line, "[%s] %s is not used by %s = %s", key->section,
                               key->name, key->use_key, v);
            }
            where(c, e, &c->e[c->slot[sel]], w, sizeof w);
            return fail_at(c, e, e->line, "[%s] %s cannot be combined with %s (%s)", key->section,
                           key->name, key->use_key, w);
        }
        if (!key->group)
            continue;
        for (int j = 0; j < NKEYS; j++) {
            if (j == k || !keys[j].group || strcmp(keys[j].group, key->group) != 0 ||
                strcmp(keys[j].section, key->section) != 0 || c->slot[j] < 0 || c->slot[j] >= i ||
                !used(c, j))
                continue;
            group_members(c, k, members, sizeof members);
            where(c, e, &c->e[c->slot[j]], w, sizeof w);
            return fail_at(c, e, e->line, "[%s] %s: give exactly one of %s (%s is %s)",
                           key->section, key->name, members, keys[j].name, w);
        }
    }
    return MC_OK;
}

static int check_required(ctx *c)
{
    char range[200], cond[96], members[256];
    for (int k = 0; k < NKEYS; k++) {
        const case_key *key = &keys[k];
        if (c->slot[k] >= 0 || !used(c, k) || !section_active(c, key->section))
            continue;
        condition_text(c, k, cond, sizeof cond);
        describe(key, 1, range, sizeof range);
        if (key->required)
            return fail_at(c, NULL, 0, "[%s] %s is required%s (%s)", key->section, key->name, cond,
                           range);
        if (!key->group)
            continue;
        int n = group_members(c, k, members, sizeof members), given = 0, first = -1;
        for (int j = 0; j < NKEYS; j++) {
            if (!keys[j].group || strcmp(keys[j].group, key->group) != 0 ||
                strcmp(keys[j].section, key->section) != 0 || !used(c, j))
                continue;
            if (first < 0)
                first = j;
            given |= c->slot[j] >= 0 || keys[j].def; /* a defaulted member stands in */
        }
        if (given || first != k)
            continue;
        if (n == 1)
            return fail_at(c, NULL, 0, "[%s] %s is required%s (%s)", key->section, key->name, cond,
                           range);
        return fail_at(c, NULL, 0, "[%s] give exactly one of %s%s: none is given", key->section,
                       members, cond);
    }
    return MC_OK;
}

static int parse_override(ctx *c, const char *ovr)
{
    char q[96];
    mc_text_quote(ovr, q, sizeof q);
    const char *eq = strchr(ovr, '=');
    const char *dot = eq ? memchr(ovr, '.', (size_t)(eq - ovr)) : NULL;
    if (!eq || !dot)
        return mc_fail(c->err, MC_ERR_INPUT, "--set %s: expected section.key=value", q);
    const char *s0 = ovr, *s1 = dot, *k0 = dot + 1, *k1 = eq, *v0 = eq + 1;
    while (s0 < s1 && isspace((unsigned char)*s0))
        s0++;
    while (s1 > s0 && isspace((unsigned char)s1[-1]))
        s1--;
    while (k0 < k1 && isspace((unsigned char)*k0))
        k0++;
    while (k1 > k0 && isspace((unsigned char)k1[-1]))
        k1--;
    while (isspace((unsigned char)*v0))
        v0++;
    size_t vn = strlen(v0);
    while (vn > 0 && isspace((unsigned char)v0[vn - 1]))
        vn--;
    if (s0 == s1 || k0 == k1)
        return mc_fail(c->err, MC_ERR_INPUT, "--set %s: expected section.key=value", q);
    char *key = dup_range(k0, (size_t)(k1 - k0)), *val = dup_range(v0, vn);
    entry *e = NULL;
    int ok = key && val;
    for (int i = 0; ok && i < c->n && !e; i++)
        if (c->e[i].name && strcmp(c->e[i].name, key) == 0 &&
            strlen(c->e[i].section) == (size_t)(s1 - s0) &&
            memcmp(c->e[i].section, s0, (size_t)(s1 - s0)) == 0)
            e = &c->e[i];
    if (ok && e) {
        ok = set_value(e, val);
        e->line = e->cont_line = 0;
    } else if (ok)
        ok = (e = add_entry(c, s0, (size_t)(s1 - s0), key, val, 0)) != NULL;
    if (ok)
        e->ovr = ovr;
    mc_free(key);
    mc_free(val);
    if (!ok)
        return mc_fail(c->err, MC_ERR_NOMEM, "out of memory reading --set %s", q);
    return MC_OK;
}

/* The text of line n (1-based) of c->text, quoted. */
static void line_text(const ctx *c, int n, char *buf, size_t len)
{
    const char *p = c->text;
    for (int l = 1; l < n && *p; l++) {
        p += strcspn(p, "\n");
        if (*p)
            p++;
    }
    char raw[128];
    size_t k = strcspn(p, "\r\n");
    fmt(raw, sizeof raw, "%.*s", (int)(k < sizeof raw ? k : sizeof raw - 1), p);
    mc_text_quote(raw, buf, len);
}

static int parse_and_check(ctx *c, int noverrides, const char *const *overrides)
{
    int rc = ini_parse_stream(read_line, c, on_pair, c);
    if (c->nomem || rc == -2)
        return mc_fail(c->err, MC_ERR_NOMEM, "%s: out of memory while reading", c->name);
    if (rc > 0 && (!c->bad_line || rc < c->bad_line)) {
        char t[96];
        line_text(c, rc, t, sizeof t);
        if (rc == c->unterminated)
            return fail_at(c, NULL, rc, "section header '%s' lacks its closing ']'", t);
        return fail_at(c, NULL, rc,
                       "cannot parse this line (expected key = value or [section]): '%s'", t);
    }
    if (c->bad_line)
        return fail_at(c, NULL, c->bad_line, "%s", c->bad);
    if (c->n == 0)
        return mc_fail(c->err, MC_ERR_INPUT, "%s: empty case file (no sections and no keys)",
                       c->name);
    for (int i = 0; i < noverrides; i++)
        if ((rc = parse_override(c, overrides[i])))
            return rc;

    for (int k = 0; k < NKEYS; k++)
        c->slot[k] = -1;
    if ((rc = check_structure(c)) || (rc = convert_entries(c)))
        return rc;

    for (int k = 0; k < NKEYS; k++) {
        const case_key *key = &keys[k];
        if (key->def_from && c->slot[k] < 0) {
            size_t from = keys[find_key(key->section, key->def_from)].off;
            memcpy((char *)&c->sc + key->off, (const char *)&c->sc + from, sizeof(double));
        }
        if (key->tagged && c->slot[k] >= 0)
            put_int(&c->sc, key->tag_off, key->tag);
    }
    int stress_present = 0;
    for (int i = 0; i < c->n; i++)
        stress_present |= strcmp(c->e[i].section, "stress") == 0;
    if (stress_present && c->slot[find_key("stress", "enabled")] < 0)
        c->sc.stress.enabled = 1;

    if ((rc = check_use(c)) || (rc = check_required(c)))
        return rc;

    if (c->slot[find_key("output", "dir")] < 0) {
        char dir[MC_PATH_MAX];
        if ((rc = mc_scene_output_dir(&c->sc, dir, sizeof dir, c->err))) {
            if (c->err)
                mc_error_prefix(c->err, "%s: [output] dir: ", c->name);
            return rc;
        }
        memcpy(c->sc.output.dir, dir, sizeof dir);
    }

    const char *sec = NULL, *key = NULL;
    if ((rc = mc_scene_check_key(&c->sc, c->err, &sec, &key))) {
        int k = sec && key ? find_key(sec, key) : -1;
        const entry *e = k >= 0 && c->slot[k] >= 0 ? &c->e[c->slot[k]] : NULL;
        char head[MC_ERROR_MSG_MAX];
        prefix(c, e, e ? e->line : 0, head, sizeof head);
        if (c->err)
            mc_error_prefix(c->err, "%s", head);
        return rc;
    }
    return MC_OK;
}

int mc_case_parse_text(const char *text, const char *name, const char *base_dir, int noverrides,
                       const char *const *overrides, mc_scene *scene, mc_error *err)
{
    if (!text)
        return mc_fail(err, MC_ERR_INPUT, "%s: no case text", name ? name : "<case>");
    ctx *c = mc_calloc(1, sizeof *c);
    if (!c)
        return mc_fail(err, MC_ERR_NOMEM, "out of memory reading a case");
    c->name = name ? name : "<case>";
    c->base_dir = base_dir ? base_dir : "";
    c->text = c->p = text;
    c->err = err;
    mc_scene_defaults(&c->sc);
    int rc = MC_OK;
    if (strlen(c->name) >= sizeof c->sc.path)
        rc = mc_fail(err, MC_ERR_INPUT, "case file name is longer than %d bytes", MC_PATH_MAX - 1);
    else {
        memcpy(c->sc.path, c->name, strlen(c->name) + 1);
        rc = parse_and_check(c, noverrides, overrides);
    }
    if (rc == MC_OK)
        *scene = c->sc;
    free_entries(c);
    mc_free(c);
    return rc;
}

int mc_case_load(const char *path, int noverrides, const char *const *overrides, mc_scene *scene,
                 mc_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return mc_fail(err, MC_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 4096, n = 0;
    char *text = mc_malloc(cap);
    int rc = text ? MC_OK : mc_fail(err, MC_ERR_NOMEM, "%s: out of memory", path);
    while (rc == MC_OK) {
        if (n + 1 == cap) {
            if (cap >= (size_t)MAX_FILE_BYTES) {
                rc = mc_fail(err, MC_ERR_INPUT, "%s: larger than %ld MiB; not a case file", path,
                             MAX_FILE_BYTES >> 20);
                break;
            }
            char *t = mc_malloc(2 * cap);
            if (!t) {
                rc = mc_fail(err, MC_ERR_NOMEM, "%s: out of memory", path);
                break;
            }
            memcpy(t, text, n);
            mc_free(text);
            text = t;
            cap *= 2;
        }
        size_t got = fread(text + n, 1, cap - 1 - n, f);
        n += got;
        if (got == 0) {
            if (ferror(f))
                rc = mc_fail(err, MC_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
            break;
        }
    }
    fclose(f);
    if (rc == MC_OK) {
        text[n] = '\0';
        const char *nul = memchr(text, '\0', n);
        if (nul) {
            int line = 1;
            for (const char *q = text; q < nul; q++)
                line += *q == '\n';
            rc = mc_fail(err, MC_ERR_INPUT, "%s:%d: contains a NUL byte (not a text file)", path,
                         line);
        }
    }
    char *dir = NULL;
    if (rc == MC_OK) {
        const char *slash = strrchr(path, '/');
        size_t dlen = slash ? (slash == path ? 1 : (size_t)(slash - path)) : 0;
        dir = dup_range(path, dlen);
        if (!dir)
            rc = mc_fail(err, MC_ERR_NOMEM, "%s: out of memory", path);
    }
    if (rc == MC_OK)
        rc = mc_case_parse_text(text, path, dir, noverrides, overrides, scene, err);
    mc_free(dir);
    mc_free(text);
    return rc;
}

/* "a, b" -> "`a`, `b`": code spans keep suffixes such as Pa*s from turning into emphasis. */
static void code_list(const char *list, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = '\0';
    for (const char *p = list; *p && o < len;) {
        size_t n = strcspn(p, ",");
        fmt(buf + o, len - o, "%s`%.*s`", o ? ", " : "", (int)n, p);
        o += strlen(buf + o);
        p += n;
        while (*p == ',' || *p == ' ')
            p++;
    }
}

/* ---- the reference --------------------------------------------------------------------------- */

typedef struct {
    char *s;
    size_t n, cap;
    int nomem;
} sbuf;

static void sb_add(sbuf *b, const char *f, ...) __attribute__((format(printf, 2, 3)));
static void sb_add(sbuf *b, const char *f, ...)
{
    if (b->nomem)
        return;
    va_list ap;
    va_start(ap, f);
    int need = vsnprintf(NULL, 0, f, ap);
    va_end(ap);
    if (need < 0) {
        b->nomem = 1;
        return;
    }
    if (b->n + (size_t)need + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->n + (size_t)need + 1)
            cap *= 2;
        char *s = mc_malloc(cap);
        if (!s) {
            b->nomem = 1;
            return;
        }
        if (b->n)
            memcpy(s, b->s, b->n);
        mc_free(b->s);
        b->s = s;
        b->cap = cap;
    }
    va_start(ap, f);
    vsnprintf(b->s + b->n, b->cap - b->n, f, ap);
    va_end(ap);
    b->n += (size_t)need;
}

char *mc_case_reference_markdown(void)
{
    sbuf b = {0};
    sb_add(&b, "<!-- generated by mc_case_reference_markdown() from the key table in src/case.c; "
               "edit that table, not the text below -->\n\n");
    sb_add(&b, "## Units\n\nA bare number is SI. Suffixes are case-sensitive (mN is a "
               "millinewton; MN is not accepted).\n\n");
    sb_add(&b, "| quantity | suffixes | SI unit |\n|---|---|---|\n");
    for (int u = MC_UNIT_LENGTH; u <= MC_UNIT_ROTATION; u++) {
        char list[160];
        code_list(mc_unit_suffixes((mc_unit_kind)u), list, sizeof list);
        sb_add(&b, "| %s | %s | `%s` |\n", mc_unit_kind_name((mc_unit_kind)u), list,
               mc_unit_si_symbol((mc_unit_kind)u));
    }
    sb_add(&b, "\nµm (U+00B5 or U+03BC) is accepted as um; 1/s is rad/s.\n");

    for (int s = 0; s < NSECTIONS; s++) {
        const char *sec = sections[s].name;
        sb_add(&b, "\n## [%s]\n\n%s\n\n", sec, sections[s].doc);
        sb_add(&b, "| key | unit | default | accepted range | meaning |\n|---|---|---|---|---|\n");
        for (int k = 0; k < NKEYS; k++) {
            const case_key *key = &keys[k];
            if (strcmp(key->section, sec) != 0)
                continue;
            char unit[160], def[128], range[200], note[256] = "", vals[96];
            if ((key->kind == K_REAL || key->kind == K_LENGTHS) && key->unit != MC_UNIT_NONE)
                code_list(mc_unit_suffixes(key->unit), unit, sizeof unit);
            else
                fmt(unit, sizeof unit, "-");
            describe(key, 0, range, sizeof range);
            if (key->def_from)
                fmt(def, sizeof def, "same as `%s`", key->def_from);
            else if (key->def && key->def_rule)
                fmt(def, sizeof def, "%s", key->def);
            else if (key->def)
                fmt(def, sizeof def, "`%s`", key->def);
            else if (key->required && key->use == USE_WHEN) {
                words_joined(key->use_values, ", ", vals, sizeof vals);
                fmt(def, sizeof def, "required for %s = %s", key->use_key, vals);
            } else if (key->required)
                fmt(def, sizeof def, "required");
            else
                fmt(def, sizeof def, "-");
            size_t o = 0;
            if (key->use == USE_WHEN) {
                words_joined(key->use_values, ", ", vals, sizeof vals);
                fmt(note, sizeof note, " Used by %s = %s.", key->use_key, vals);
            } else if (key->use == USE_UNLESS)
                fmt(note, sizeof note, " Not with %s.", key->use_key);
            o = strlen(note);
            if (key->group) {
                size_t m = 0;
                int defaulted = 0;
                char members[200] = "";
                for (int j = 0; j < NKEYS; j++)
                    if (keys[j].group && strcmp(keys[j].group, key->group) == 0 &&
                        strcmp(keys[j].section, sec) == 0) {
                        fmt(members + m, sizeof members - m, "%s%s", m ? ", " : "", keys[j].name);
                        m = strlen(members);
                        defaulted |= keys[j].def != NULL;
                    }
                fmt(note + o, sizeof note - o, " Give %s one of %s.",
                    defaulted ? "at most" : "exactly", members);
            }
            sb_add(&b, "| `%s` | %s | %s | %s | %s%s |\n", key->name, unit, def, range, key->doc,
                   note);
        }
    }
    if (b.nomem) {
        mc_free(b.s);
        return NULL;
    }
    return b.s;
}

/* ---- table self-check ------------------------------------------------------------------------ */

int mc_case_check_table(mc_error *err)
{
    mc_scene def, got;
    mc_scene_defaults(&def);
    for (int k = 0; k < NKEYS; k++) {
        const case_key *key = &keys[k];
        const char *texts[] = {key->doc, key->def, key->choices, key->use_values, key->lo_text};
        for (size_t t = 0; t < sizeof texts / sizeof texts[0]; t++)
            if (texts[t] && strchr(texts[t], '|'))
                return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s: '|' would break the Markdown table",
                               key->section, key->name);
        if (!find_section(key->section))
            return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s: section not in the section table",
                           key->section, key->name);
        if (find_key(key->section, key->name) != k)
            return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s declared twice", key->section, key->name);
        if (key->use != USE_ALWAYS) {
            int sel = key->use_key ? find_key(key->section, key->use_key) : -1;
            if (sel < 0)
                return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s: use_key is not a key of [%s]",
                               key->section, key->name, key->section);
            char w[64];
            for (int i = 0; key->use == USE_WHEN && nth_word(key->use_values, i, w, sizeof w);
                 i++) {
                int ok = keys[sel].kind == K_ENUM   ? word_index(keys[sel].choices, w) >= 0
                         : keys[sel].kind == K_BOOL ? strcmp(w, "yes") == 0 || strcmp(w, "no") == 0
                                                    : 0;
                if (!ok)
                    return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s: '%s' is not a value of %s",
                                   key->section, key->name, w, key->use_key);
            }
        }
        if (key->def_from) {
            int from = find_key(key->section, key->def_from);
            if (from < 0 || keys[from].kind != K_REAL || key->kind != K_REAL)
                return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s: bad def_from", key->section,
                               key->name);
        }
        if (key->group) {
            int n = 0, ndef = 0;
            for (int j = 0; j < NKEYS; j++)
                if (keys[j].group && strcmp(keys[j].group, key->group) == 0 &&
                    strcmp(keys[j].section, key->section) == 0) {
                    n++;
                    ndef += keys[j].def != NULL;
                }
            if (n < 2 || key->required || ndef > 1 || (key->def && (key->def_rule || key->def_from)))
                return mc_fail(err, MC_ERR_INTERNAL,
                               "[%s] %s: a group needs 2+ members, none required, at most one "
                               "defaulted (by a value)",
                               key->section, key->name);
        }
        if (!key->def || key->def_rule || key->def_from)
            continue;
        /* The documented default must be exactly what mc_scene_defaults gives. */
        char why[256];
        got = def;
        if (convert(key, key->def, NULL, &got, why, sizeof why))
            return mc_fail(err, MC_ERR_INTERNAL, "[%s] %s: default '%s' does not parse: %s",
                           key->section, key->name, key->def, why);
        size_t size = key->kind == K_REAL   ? sizeof(double)
                      : key->kind == K_SEED ? sizeof(uint64_t)
                                            : sizeof(int);
        if (memcmp((char *)&got + key->off, (char *)&def + key->off, size) != 0)
            return mc_fail(err, MC_ERR_INTERNAL,
                           "[%s] %s: documented default '%s' differs from mc_scene_defaults",
                           key->section, key->name, key->def);
    }
    return MC_OK;
}
