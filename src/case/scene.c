/* scene.c - scene defaults, validation and derived quantities (see scene.h). */
#include "case/scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "kernels/kernel.h"

void mc_scene_defaults(mc_scene *s)
{
    memset(s, 0, sizeof *s);
    s->geometry.shape = MC_SHAPE_FLAT;
    s->roughness.type = MC_ROUGH_NONE;
    s->roughness.hurst = 0.8;
    s->roughness.seed = 1;
    s->body1 = (mc_material){.E = 210e9, .nu = 0.3, .rigid = 0};
    s->body2 = (mc_material){.E = 210e9, .nu = 0.3, .rigid = 0};
    s->load.kind = MC_LOAD_FORCE;
    s->load.lubricant_pressure = 0.0;
    s->load.pressure_cap = INFINITY;
    s->solver.op = MC_BACKEND_FFT;
    s->solver.method = MC_METHOD_CG;
    s->solver.tolerance = 1e-8;
    s->solver.max_iterations = 2000;
    s->solver.threads = 0;
    s->stress.enabled = 0;
    s->stress.depth_min = 0.0;
    s->stress.layers = 32;
    s->stress.spacing = MC_SPACING_LINEAR;
    s->stress.kernel = MC_STRESS_PATCH;
    s->stress.friction = 0.0;
    s->stress.depth_max = MC_STRESS_DEPTH_AUTO;
    s->stress.window = MC_STRESS_WINDOW_AUTO;
}

/* A failed rule: names the key for mc_scene_check_key and raises MC_ERR_INPUT. */
#define BLAME(sec, key, ...)                                                                       \
    do {                                                                                           \
        if (section)                                                                               \
            *section = (sec);                                                                      \
        if (keyname)                                                                               \
            *keyname = (key);                                                                      \
        return mc_fail(err, MC_ERR_INPUT, __VA_ARGS__);                                            \
    } while (0)

static int positive(double v) { return isfinite(v) && v > 0; }
static int nonnegative(double v) { return isfinite(v) && v >= 0; }

static int check_stress(const mc_scene *s, mc_error *err, const char **section,
                        const char **keyname)
{
    if (s->stress.kernel != MC_STRESS_PATCH && s->stress.kernel != MC_STRESS_POINT)
        BLAME("stress", "kernel", "[stress] kernel = %d: not a known stress kernel",
              (int)s->stress.kernel);
    if (!(isfinite(s->stress.friction) && s->stress.friction >= 0 && s->stress.friction <= 1))
        BLAME("stress", "friction", "[stress] friction = %g: must be in 0..1", s->stress.friction);
    if (s->stress.window != MC_STRESS_WINDOW_AUTO && s->stress.window != MC_STRESS_WINDOW_FULL)
        BLAME("stress", "window", "[stress] window = %d: not a known window mode",
              (int)s->stress.window);
    if (s->stress.spacing == MC_SPACING_LIST) {
        int n = s->stress.ndepths;
        if (n < 1 || n > MC_MAX_DEPTHS)
            BLAME("stress", "depths", "[stress] depths: %d given, 1..%d are accepted", n,
                  MC_MAX_DEPTHS);
        for (int k = 0; k < n; k++) {
            double z = s->stress.depths[k];
            if (!nonnegative(z))
                BLAME("stress", "depths", "[stress] depths: item %d = %g m must be >= 0", k + 1, z);
            if (k > 0 && !(z > s->stress.depths[k - 1]))
                BLAME("stress", "depths",
                      "[stress] depths: item %d = %g m must be > item %d = %g m (strictly "
                      "increasing)",
                      k + 1, z, k, s->stress.depths[k - 1]);
        }
        return MC_OK;
    }
    if (s->stress.spacing != MC_SPACING_LINEAR && s->stress.spacing != MC_SPACING_GEOMETRIC)
        BLAME("stress", "spacing", "[stress] spacing = %d: not a known spacing",
              (int)s->stress.spacing);
    if (s->stress.layers < 1 || s->stress.layers > MC_MAX_DEPTHS)
        BLAME("stress", "layers", "[stress] layers = %d: must be in 1..%d", s->stress.layers,
              MC_MAX_DEPTHS);
    if (!nonnegative(s->stress.depth_min))
        BLAME("stress", "depth_min", "[stress] depth_min = %g m: must be >= 0",
              s->stress.depth_min);
    if (s->stress.depth_max != MC_STRESS_DEPTH_AUTO &&
        !(isfinite(s->stress.depth_max) && s->stress.depth_max > s->stress.depth_min))
        BLAME("stress", "depth_max", "[stress] depth_max = %g m: must be > depth_min = %g m",
              s->stress.depth_max, s->stress.depth_min);
    if (s->stress.spacing == MC_SPACING_GEOMETRIC && !(s->stress.depth_min > 0))
        BLAME("stress", "spacing",
              "[stress] spacing = geometric needs depth_min > 0 (log spacing cannot start at the "
              "surface)");
    return MC_OK;
}

static int check_material(const mc_material *m, const char *sec, mc_error *err,
                          const char **section, const char **keyname)
{
    if (!positive(m->E))
        BLAME(sec, "E", "[%s] E = %g Pa: must be > 0", sec, m->E);
    if (!(isfinite(m->nu) && m->nu >= 0 && m->nu <= 0.5))
        BLAME(sec, "nu", "[%s] nu = %g: must be in 0..0.5", sec, m->nu);
    return MC_OK;
}

static const char *load_key(mc_load_kind k)
{
    switch (k) {
    case MC_LOAD_FORCE: return "force";
    case MC_LOAD_FORCE_PER_LENGTH: return "force_per_length";
    case MC_LOAD_APPROACH: return "approach";
    case MC_LOAD_PRESSURE_FILE: return "pressure_file";
    }
    return "force";
}

int mc_scene_check_key(const mc_scene *s, mc_error *err, const char **section, const char **keyname)
{
    const mc_grid *g = &s->grid;
    if (g->nx < 1 || g->nx > MC_GRID_MAX_N)
        BLAME("mesh", "nx", "[mesh] nx = %d: must be in 1..%d", g->nx, MC_GRID_MAX_N);
    if (g->ny < 1 || g->ny > MC_GRID_MAX_N)
        BLAME("mesh", "ny", "[mesh] ny = %d: must be in 1..%d", g->ny, MC_GRID_MAX_N);
    if (!positive(g->dx))
        BLAME("mesh", "dx", "[mesh] dx = %g m: must be > 0", g->dx);
    if (!positive(g->dy))
        BLAME("mesh", "dy", "[mesh] dy = %g m: must be > 0", g->dy);

    switch (s->geometry.shape) {
    case MC_SHAPE_FLAT: break;
    case MC_SHAPE_SPHERE:
    case MC_SHAPE_CYLINDER:
        if (!positive(s->geometry.radius))
            BLAME("geometry", "radius", "[geometry] radius = %g m: shape = %s needs a radius > 0",
                  s->geometry.radius, s->geometry.shape == MC_SHAPE_SPHERE ? "sphere" : "cylinder");
        break;
    case MC_SHAPE_ELLIPSOID:
        if (!positive(s->geometry.radius_x))
            BLAME("geometry", "radius_x",
                  "[geometry] radius_x = %g m: shape = ellipsoid needs radius_x > 0",
                  s->geometry.radius_x);
        if (!positive(s->geometry.radius_y))
            BLAME("geometry", "radius_y",
                  "[geometry] radius_y = %g m: shape = ellipsoid needs radius_y > 0",
                  s->geometry.radius_y);
        break;
    default:
        BLAME("geometry", "shape", "[geometry] shape = %d: not a known shape",
              (int)s->geometry.shape);
    }

    switch (s->roughness.type) {
    case MC_ROUGH_NONE: break;
    case MC_ROUGH_GAUSSIAN:
        if (!nonnegative(s->roughness.rq))
            BLAME("roughness", "rq", "[roughness] rq = %g m: must be >= 0", s->roughness.rq);
        if (!positive(s->roughness.correlation_x))
            BLAME("roughness", "correlation_x", "[roughness] correlation_x = %g m: must be > 0",
                  s->roughness.correlation_x);
        if (!positive(s->roughness.correlation_y))
            BLAME("roughness", "correlation_y", "[roughness] correlation_y = %g m: must be > 0",
                  s->roughness.correlation_y);
        break;
    case MC_ROUGH_SELF_AFFINE: {
        if (!(isfinite(s->roughness.hurst) && s->roughness.hurst > 0 && s->roughness.hurst < 1))
            BLAME("roughness", "hurst", "[roughness] hurst = %g: must be > 0 and < 1",
                  s->roughness.hurst);
        if (!nonnegative(s->roughness.rq))
            BLAME("roughness", "rq", "[roughness] rq = %g m: must be >= 0", s->roughness.rq);
        if (!nonnegative(s->roughness.rms_slope))
            BLAME("roughness", "rms_slope", "[roughness] rms_slope = %g: must be > 0",
                  s->roughness.rms_slope);
        if (s->roughness.rq > 0 && s->roughness.rms_slope > 0)
            BLAME("roughness", "rms_slope",
                  "[roughness] type = self_affine takes rq or rms_slope, not both");
        if (!(s->roughness.rq > 0 || s->roughness.rms_slope > 0))
            BLAME("roughness", "rq",
                  "[roughness] type = self_affine needs rq > 0 or rms_slope > 0");
        if (!nonnegative(s->roughness.lambda_long))
            BLAME("roughness", "lambda_long", "[roughness] lambda_long = %g m: must be > 0",
                  s->roughness.lambda_long);
        if (!nonnegative(s->roughness.lambda_short))
            BLAME("roughness", "lambda_short", "[roughness] lambda_short = %g m: must be > 0",
                  s->roughness.lambda_short);
        double lo, hi;
        mc_scene_cutoffs(s, &hi, &lo);
        if (!(lo < hi))
            BLAME("roughness", "lambda_short",
                  "[roughness] lambda_short = %g m: must be < lambda_long = %g m", lo, hi);
        break;
    }
    case MC_ROUGH_FILE:
        if (!s->roughness.file[0])
            BLAME("roughness", "file", "[roughness] type = file needs a file");
        break;
    default:
        BLAME("roughness", "type", "[roughness] type = %d: not a known roughness type",
              (int)s->roughness.type);
    }

    int rc = check_material(&s->body1, "body1", err, section, keyname);
    if (rc)
        return rc;
    if (!s->body2.rigid && (rc = check_material(&s->body2, "body2", err, section, keyname)))
        return rc;

    switch (s->load.kind) {
    case MC_LOAD_FORCE:
    case MC_LOAD_FORCE_PER_LENGTH:
    case MC_LOAD_APPROACH:
        if (!positive(s->load.value))
            BLAME("load", load_key(s->load.kind),
                  "[load] %s = %g: must be > 0 (give exactly one of force, force_per_length, "
                  "approach, pressure_file)",
                  load_key(s->load.kind), s->load.value);
        break;
    case MC_LOAD_PRESSURE_FILE:
        if (!s->load.pressure_file[0])
            BLAME("load", "pressure_file", "[load] pressure_file: a file name is required");
        break;
    default: BLAME("load", "force", "[load] kind = %d: not a known load", (int)s->load.kind);
    }
    if (s->load.kind == MC_LOAD_FORCE_PER_LENGTH && !g->periodic_y)
        BLAME("load", "force_per_length",
              "[load] force_per_length needs [mesh] periodic_y = yes (a load per unit length is "
              "carried by a body periodic along y)");
    if (!nonnegative(s->load.lubricant_pressure))
        BLAME("load", "lubricant_pressure", "[load] lubricant_pressure = %g Pa: must be >= 0",
              s->load.lubricant_pressure);
    if (!(s->load.pressure_cap > s->load.lubricant_pressure))
        BLAME("load", "pressure_cap",
              "[load] pressure_cap = %g Pa: must be > lubricant_pressure = %g Pa",
              s->load.pressure_cap, s->load.lubricant_pressure);

    if (s->solver.op != MC_BACKEND_FFT && s->solver.op != MC_BACKEND_DIRECT)
        BLAME("solver", "operator", "[solver] operator = %d: not a known backend",
              (int)s->solver.op);
    if (s->solver.method != MC_METHOD_CG && s->solver.method != MC_METHOD_PK &&
        s->solver.method != MC_METHOD_ACTIVE_SET)
        BLAME("solver", "method", "[solver] method = %d: not a known method",
              (int)s->solver.method);
    if (!(s->solver.tolerance >= 1e-15 && s->solver.tolerance <= 1e-2))
        BLAME("solver", "tolerance", "[solver] tolerance = %g: must be in 1e-15..0.01",
              s->solver.tolerance);
    if (s->solver.max_iterations < 1)
        BLAME("solver", "max_iterations", "[solver] max_iterations = %d: must be >= 1",
              s->solver.max_iterations);
    if (s->solver.threads < 0)
        BLAME("solver", "threads", "[solver] threads = %d: must be >= 0 (0 = all cores)",
              s->solver.threads);

    if (s->stress.enabled)
        return check_stress(s, err, section, keyname);
    return MC_OK;
}

int mc_scene_check(const mc_scene *s, mc_error *err)
{
    return mc_scene_check_key(s, err, NULL, NULL);
}

double mc_scene_estar(const mc_scene *s)
{
    return mc_combined_modulus(s->body1.E, s->body1.nu, s->body2.E, s->body2.nu, s->body2.rigid);
}

int mc_scene_depths(const mc_scene *s, double *depths, int *ndepths, mc_error *err)
{
    int rc = check_stress(s, err, NULL, NULL);
    if (rc)
        return rc;
    if (s->stress.spacing == MC_SPACING_LIST) {
        memcpy(depths, s->stress.depths, sizeof(double) * (size_t)s->stress.ndepths);
        *ndepths = s->stress.ndepths;
        return MC_OK;
    }
    if (s->stress.depth_max == MC_STRESS_DEPTH_AUTO)
        return mc_fail(err, MC_ERR_INPUT,
                       "[stress] depth_max = auto: the depths follow from the contact (the stress "
                       "stage resolves them)");
    int n = s->stress.layers;
    double a = s->stress.depth_min, b = s->stress.depth_max;
    depths[0] = a;
    for (int k = 1; k < n; k++) {
        double t = (double)k / (double)(n - 1);
        depths[k] = s->stress.spacing == MC_SPACING_GEOMETRIC ? a * pow(b / a, t) : a + t * (b - a);
    }
    if (n > 1)
        depths[n - 1] = b; /* exact end, free of round-off */
    *ndepths = n;
    return MC_OK;
}

void mc_scene_cutoffs(const mc_scene *s, double *lambda_long, double *lambda_short)
{
    const mc_grid *g = &s->grid;
    double lx = g->nx * g->dx, ly = g->ny * g->dy;
    *lambda_long = s->roughness.lambda_long > 0 ? s->roughness.lambda_long : fmax(lx, ly);
    *lambda_short =
        s->roughness.lambda_short > 0 ? s->roughness.lambda_short : 2.0 * fmax(g->dx, g->dy);
}

int mc_scene_output_dir(const mc_scene *s, char *buf, size_t len, mc_error *err)
{
    int n;
    if (s->output.dir[0])
        n = snprintf(buf, len, "%s", s->output.dir);
    else if (!s->path[0])
        n = snprintf(buf, len, "out/scene");
    else {
        const char *base = strrchr(s->path, '/');
        base = base ? base + 1 : s->path;
        size_t stem = strlen(base);
        if (stem > 4 && strcmp(base + stem - 4, ".ini") == 0)
            stem -= 4;
        n = snprintf(buf, len, "out/%.*s", (int)stem, base);
    }
    if (n < 0 || (size_t)n >= len)
        return mc_fail(err, MC_ERR_INPUT, "output directory name is longer than %zu bytes",
                       len ? len - 1 : 0);
    return MC_OK;
}
