/* scene.c - scene defaults, validation and derived quantities (see scene.h). */
#include "case/scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case/keys.h"
#include "case/scene_effect.h"
#include "kernels/kernel.h"
#include "reference/hertz.h"

void mc_scene_defaults(mc_scene *s)
{
    memset(s, 0, sizeof *s);
    mc_keys_defaults(s); /* every default the key table states as a value */
    /* defaults that are rules, not values (keys.c: def_rule) */
    s->load.kind = MC_LOAD_FORCE;
    s->load.pressure_cap = INFINITY; /* none */
    s->stress.enabled = 0;           /* yes when a case file has a [stress] section */
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

/* The rules between the keys of [stress] (checked when the stage runs). */
static int stress_rules(const mc_scene *s, mc_error *err, const char **section,
                        const char **keyname)
{
    if (s->stress.spacing == MC_SPACING_LIST)
        return MC_OK;
    if (s->stress.depth_max != MC_STRESS_DEPTH_AUTO && !(s->stress.depth_max > s->stress.depth_min))
        BLAME("stress", "depth_max", "[stress] depth_max = %g m: must be > depth_min = %g m",
              s->stress.depth_max, s->stress.depth_min);
    if (s->stress.spacing == MC_SPACING_GEOMETRIC && !(s->stress.depth_min > 0))
        BLAME("stress", "spacing",
              "[stress] spacing = geometric needs depth_min > 0 (log spacing cannot start at the "
              "surface)");
    return MC_OK;
}

/* The rules of the lubricant volume equilibrium ([lubrication] with lubricant_pressure = auto). */
static int lubrication_rules(const mc_scene *s, mc_error *err, const char **section,
                             const char **keyname)
{
    const int automatic = s->load.lubricant_pressure == MC_LUBRICANT_AUTO;
    if (automatic && !s->lubrication.enabled)
        BLAME("load", "lubricant_pressure",
              "[load] lubricant_pressure = auto needs a [lubrication] section (the film "
              "thickness that sets the lubricant volume)");
    if (!s->lubrication.enabled)
        return MC_OK;
    if (!automatic)
        BLAME("lubrication", "enabled",
              "[lubrication] has no effect unless [load] lubricant_pressure = auto");
    if (s->load.kind != MC_LOAD_FORCE)
        BLAME("load", "force",
              "[lubrication] needs [load] force (the macro normal force F_N); approach, "
              "force_per_length and pressure_file are not supported with the volume equilibrium");
    if (s->geometry.shape == MC_SHAPE_SPHERE)
        BLAME("geometry", "shape",
              "[lubrication] needs [geometry] shape = flat (a rough patch standing for the "
              "centre of the macro contact), cylinder (the whole line contact on a strip "
              "periodic along y) or ellipsoid (the whole crowned contact, radius_x = R_x of the "
              "discs, radius_y the crowning); for a sphere write shape = ellipsoid with "
              "radius_x = radius_y");
    const int crowned = s->geometry.shape == MC_SHAPE_ELLIPSOID;
    if (crowned) {
        /* the whole crowned contact (theory.md §11.4): an elliptical Hertz contact on a free grid */
        if (s->grid.periodic_x || s->grid.periodic_y)
            BLAME("mesh", s->grid.periodic_x ? "periodic_x" : "periodic_y",
                  "[lubrication] with [geometry] shape = ellipsoid (the whole crowned contact) "
                  "needs a grid free along x and y: the contact ellipse lies inside it");
        if (s->lubrication.width > 0)
            BLAME("lubrication", "width",
                  "[lubrication] width has no effect on the whole crowned contact (shape = "
                  "ellipsoid carries F_N on its ellipse): remove it");
        if (s->lubrication.film == MC_FILM_EHL && !mc_film_formula_is_point(s->lubrication.formula))
            BLAME("lubrication", "formula",
                  "[lubrication] formula = %s is a line-contact formula: the whole crowned "
                  "contact (shape = ellipsoid) needs a point-contact one (hamrock_dowson_central "
                  "or hamrock_dowson_min)",
                  mc_film_formula_name(s->lubrication.formula));
        double rx = s->lubrication.macro_radius;
        if (!(rx > 0) && s->lubrication.radius1 > 0 && s->lubrication.radius2 > 0)
            rx = s->lubrication.radius1 * s->lubrication.radius2 /
                 (s->lubrication.radius1 + s->lubrication.radius2);
        if (rx > 0 && !(fabs(s->geometry.radius_x - rx) <= 1e-9 * rx))
            BLAME("geometry", "radius_x",
                  "[geometry] radius_x = %.9g mm is not the reduced radius R_x = %.9g mm of "
                  "[lubrication]: the crowned contact's x radius is the discs' R1 R2 / (R1 + R2)",
                  s->geometry.radius_x * 1e3, rx * 1e3);
        double fmax_ = s->load.value;
        for (int f = 0; s->runin.enabled && f < s->runin.nforces; f++)
            fmax_ = fmax(fmax_, s->runin.forces[f]);
        mc_hertz_ellipse he;
        mc_error herr = {0};
        if (mc_hertz_ellipse_from_load(s->geometry.radius_x, s->geometry.radius_y,
                                       mc_scene_estar(s), fmax_, &he, &herr) != MC_OK)
            BLAME("geometry", "radius_y", "[geometry] %s", herr.msg);
        const double hx = 0.5 * s->grid.nx * s->grid.dx, hy = 0.5 * s->grid.ny * s->grid.dy;
        if (!(1.1 * he.ax <= hx) || !(1.1 * he.ay <= hy))
            BLAME("mesh", 1.1 * he.ax > hx ? "nx" : "ny",
                  "[mesh] the grid spans %.4g x %.4g um, too small for the whole crowned contact "
                  "at F_N = %.6g N: the Hertz ellipse of semi-axes %.4g um (x) and %.4g um (y) "
                  "plus 10 %% needs nx >= %.0f and ny >= %.0f",
                  2e6 * hx, 2e6 * hy, fmax_, he.ax * 1e6, he.ay * 1e6,
                  ceil(2.2 * he.ax / s->grid.dx), ceil(2.2 * he.ay / s->grid.dy));
    }
    if (s->geometry.shape == MC_SHAPE_CYLINDER) {
        /* the whole contact (theory.md §11.4): the grid carries the macro geometry */
        if (!s->grid.periodic_y || s->grid.periodic_x)
            BLAME("mesh", "periodic_y",
                  "[lubrication] with [geometry] shape = cylinder (the whole line contact) needs "
                  "a strip: periodic_y = yes and x free (the Hertz band lies across x)");
        if (!(s->lubrication.width > 0))
            BLAME("lubrication", "width",
                  "[lubrication] with [geometry] shape = cylinder needs width (the strip carries "
                  "w' = F_N / width per length along y)");
        double rx = s->lubrication.macro_radius;
        const char *rkey = "macro_radius";
        if (!(rx > 0) && s->lubrication.radius1 > 0 && s->lubrication.radius2 > 0) {
            rx = s->lubrication.radius1 * s->lubrication.radius2 /
                 (s->lubrication.radius1 + s->lubrication.radius2);
            rkey = "radius1";
        }
        if (rx > 0 && !(fabs(s->geometry.radius - rx) <= 1e-9 * rx))
            BLAME("geometry", "radius",
                  "[geometry] radius = %.9g mm is not the reduced radius R_x = %.9g mm of "
                  "[lubrication] %s%s: the whole contact's cylinder is the discs' macro gap "
                  "(R_x = R1 R2 / (R1 + R2)); make them equal",
                  s->geometry.radius * 1e3, rx * 1e3, rkey,
                  rkey[6] == '1' ? " and radius2" : "");
        /* the Hertz band of the largest force must lie inside the grid (stage_lube.h: the same
         * rule at run time, MC_WHOLE_BAND_MARGIN) */
        double fmax_ = s->load.value;
        for (int f = 0; s->runin.enabled && f < s->runin.nforces; f++)
            fmax_ = fmax(fmax_, s->runin.forces[f]);
        const double estar = mc_scene_estar(s), r = s->geometry.radius;
        const double b = sqrt(4.0 * (fmax_ / s->lubrication.width) * r / (M_PI * estar));
        const double half = 0.5 * s->grid.nx * s->grid.dx;
        if (!(1.1 * b <= half))
            BLAME("mesh", "nx",
                  "[mesh] the grid spans |x| <= %.4g um, too narrow for the whole contact at "
                  "F_N = %.6g N: the Hertz band |x| <= b = %.4g um plus 10 %% needs nx >= %.0f at "
                  "dx = %.4g um",
                  half * 1e6, fmax_, b * 1e6, ceil(2.2 * b / s->grid.dx), s->grid.dx * 1e6);
    }
    if (isfinite(s->load.pressure_cap))
        BLAME("load", "pressure_cap",
              "[load] pressure_cap cannot be combined with [lubrication] (not supported)");
    const double rx = s->lubrication.macro_radius;
    if (rx > 0 && !(s->lubrication.width > 0) && !crowned)
        BLAME("lubrication", "width",
              "[lubrication] macro_radius needs width (the load per length w' = F_N / width)");
    if (s->lubrication.film == MC_FILM_EHL) {
        const int by_rpm = s->lubrication.rpm > 0;
        if (by_rpm && !(s->lubrication.radius1 > 0 && s->lubrication.radius2 > 0))
            BLAME("lubrication", "rpm", "[lubrication] rpm needs radius1 and radius2");
        if (!by_rpm && s->lubrication.rpm2 > 0)
            BLAME("lubrication", "rpm2", "[lubrication] rpm2 has no effect without rpm");
        if (!by_rpm && (s->lubrication.radius1 > 0) != (s->lubrication.radius2 > 0))
            BLAME("lubrication", "radius1",
                  "[lubrication] give both radius1 and radius2 or neither");
        if (!(rx > 0) && !(s->lubrication.radius1 > 0 && s->lubrication.radius2 > 0))
            BLAME("lubrication", "macro_radius",
                  "[lubrication] film = ehl needs the reduced radius R_x: macro_radius, or "
                  "radius1 and radius2");
        if (!(s->lubrication.width > 0) && !crowned)
            BLAME("lubrication", "width",
                  "[lubrication] film = ehl needs width (the load per length w' = F_N / width)");
    } else if (!(rx > 0) && s->lubrication.width > 0 && s->geometry.shape != MC_SHAPE_CYLINDER)
        BLAME("lubrication", "width",
              "[lubrication] width has no effect without macro_radius when film = given (the "
              "scene's own load is used)");
    return MC_OK;
}

#define PLASTIC_DZ_MIN_RATIO 16.0 /* dz >= min(dx, dy) / 16 */
#define PLASTIC_LAYERS_MAX 1024    /* depth <= 1024 dz */

/* The rules of the elastic-plastic stage. */
static int plasticity_rules(const mc_scene *s, mc_error *err, const char **section,
                            const char **keyname)
{
    if (!s->plasticity.enabled)
        return MC_OK;
    if (s->load.kind != MC_LOAD_FORCE && s->load.kind != MC_LOAD_FORCE_PER_LENGTH)
        BLAME("load", "force",
              "[plasticity] needs [load] force or force_per_length (the load rises in steps to "
              "it); approach and pressure_file are not supported by the elastic-plastic stage");
    /* the eigenstrain operators take x free (y free, a strip periodic along y, or a line grid)
     * or both axes periodic (docs/theory.md §8.6) */
    if (s->grid.periodic_x && !s->grid.periodic_y)
        BLAME("mesh", "periodic_x",
              "[plasticity] with [mesh] periodic_x = yes needs periodic_y = yes too (a doubly "
              "periodic patch); accepted: x free, or x and y periodic");
    if (isfinite(s->load.pressure_cap))
        BLAME("load", "pressure_cap",
              "[load] pressure_cap cannot be combined with [plasticity] (criterion = "
              "pressure_cap takes its limit from [plasticity] hardness)");
    if (s->plasticity.criterion == MC_CRITERION_PRESSURE_CAP)
        return MC_OK;
    /* the plastic volume has depth / dz layers: a loop count set by values, not by the grid */
    const double dmin = fmin(s->grid.dx, s->grid.dy), dz = s->plasticity.dz;
    if (dz > 0 && dz < dmin / PLASTIC_DZ_MIN_RATIO)
        BLAME("plasticity", "dz",
              "[plasticity] dz = %g m: must be >= min(dx, dy) / %g = %g m (thinner layers than "
              "that resolve nothing the surface grid can carry, and their number makes the run "
              "take hours)",
              dz, PLASTIC_DZ_MIN_RATIO, dmin / PLASTIC_DZ_MIN_RATIO);
    if (s->plasticity.depth > 0 && s->plasticity.depth / (dz > 0 ? dz : dmin) > PLASTIC_LAYERS_MAX)
        BLAME("plasticity", "depth",
              "[plasticity] depth = %g m: more than %d layers of dz = %g m; accepted: depth <= "
              "%d dz = %g m (raise dz or lower depth)",
              s->plasticity.depth, PLASTIC_LAYERS_MAX, dz > 0 ? dz : dmin, PLASTIC_LAYERS_MAX,
              PLASTIC_LAYERS_MAX * (dz > 0 ? dz : dmin));
    if (!(s->body1.nu < 0.5))
        BLAME("body1", "nu",
              "[body1] nu = 0.5 with [plasticity]: an incompressible body has no finite bulk "
              "modulus for the return mapping (give nu < 0.5)");
    if (s->plasticity.hardening == MC_HARDENING_LINEAR &&
        !(s->plasticity.tangent_modulus < s->body1.E))
        BLAME("plasticity", "tangent_modulus",
              "[plasticity] tangent_modulus = %g Pa: must be < E of body1 = %g Pa",
              s->plasticity.tangent_modulus, s->body1.E);
    if (s->plasticity.both &&
        (s->body2.rigid || s->body2.E != s->body1.E || s->body2.nu != s->body1.nu))
        BLAME("plasticity", "bodies",
              "[plasticity] bodies = both needs body 2 of the same material as body 1 (E, nu; "
              "not rigid)");
    return MC_OK;
}

/* The rules of the running-in driver ([runin], pipeline/runin.h). */
static int runin_rules(const mc_scene *s, mc_error *err, const char **section,
                       const char **keyname)
{
    if (!s->runin.enabled)
        return MC_OK;
    if (s->load.lubricant_pressure != MC_LUBRICANT_AUTO)
        BLAME("load", "lubricant_pressure",
              "[runin] needs [load] lubricant_pressure = auto and [lubrication]: every step takes "
              "its lubricant pressure from the volume equilibrium at its speed");
    if (s->lubrication.film != MC_FILM_EHL)
        BLAME("lubrication", "film",
              "[runin] needs [lubrication] film = ehl: the speeds set the film thickness");
    if (!(s->lubrication.rpm > 0))
        BLAME("lubrication", "speed",
              "[runin] speeds are disc speeds: [lubrication] gives rpm (the first speed of the "
              "run-down) with radius1 and radius2, not speed");
    if (s->runin.nspeeds > 0 && s->runin.speeds[0] != s->lubrication.rpm)
        BLAME("runin", "speeds",
              "[runin] speeds: the first speed (%g rpm) must be [lubrication] rpm (%g rpm), the "
              "speed the run starts with",
              s->runin.speeds[0] * 60.0 / (2.0 * M_PI), s->lubrication.rpm * 60.0 / (2.0 * M_PI));
    if (s->runin.nforces > 0 && s->runin.forces[0] != s->load.value)
        BLAME("runin", "forces",
              "[runin] forces: the first force (%g N) must be [load] force (%g N), the force "
              "the run starts with",
              s->runin.forces[0], s->load.value);
    if (s->plasticity.enabled && s->plasticity.criterion != MC_CRITERION_VON_MISES)
        BLAME("plasticity", "criterion",
              "[runin] needs [plasticity] criterion = von_mises: a pressure cap carries no "
              "plastic state from one step to the next");
    if (s->stress.enabled)
        BLAME("stress", "enabled",
              "[stress] cannot be combined with [runin] (not supported: run the final surface, "
              "surface_final.npy, as a [roughness] file)");
    return MC_OK;
}

/* Largest ratio of the cell sizes of a grid periodic along x and y: the real-space part of the
 * Ewald table (operator/kernel_table.c) spans 15 max(dx, dy) along both axes, so its cost grows
 * with the ratio (about 2 s at 1000 for any grid size; 20 s at 10^4). */
#define MC_EWALD_ASPECT_MAX 1000.0

/* Scale rules: numbers the solver can represent and a load the grid can carry. A mean pressure
 * over the grid far above the reduced modulus E* (SCALE_MAX times) or an approach far beyond the
 * grid means strains far beyond one: linear elasticity has lost its meaning, and products such as
 * p A / E* leave the double range (1e300 N, E = 1e-300 Pa give NaN in the solver). Milder
 * excesses (p_max above E*) are a warning of the run (pipeline/warnings.h). Not for
 * lubricant_pressure = auto, whose force is the macro contact's (F_N), not the patch's. */
#define SCALE_MAX 1000.0
static int scale_rules(const mc_scene *s, mc_error *err, const char **section,
                       const char **keyname)
{
    const mc_grid *g = &s->grid;
    const double dmin = fmin(g->dx, g->dy), dmax = fmax(g->dx, g->dy);
    /* a floor of the number range only: the scale covariance of the solvers is verified down to
     * cells of 1e-11 m (verify/stability.c height_1e-12) */
    if (!(dmin >= 1e-150))
        BLAME("mesh", g->dx <= g->dy ? "dx" : "dy",
              "[mesh] %s = %g m: must be >= 1e-150 m (a cell area dx dy below 1e-300 m^2 leaves "
              "the double range)",
              g->dx <= g->dy ? "dx" : "dy", dmin);
    if (g->periodic_x && g->periodic_y && dmax / dmin > MC_EWALD_ASPECT_MAX)
        BLAME("mesh", g->dx > g->dy ? "dx" : "dy",
              "[mesh] dy/dx = %g on a grid periodic along x and y: the cell aspect ratio must be "
              "at most %g (and at least 1/%g), the Ewald table's cost grows with it; use cells "
              "closer to square, or a free axis",
              g->dy / g->dx, MC_EWALD_ASPECT_MAX, MC_EWALD_ASPECT_MAX);
    const double Lx = g->nx * g->dx, Ly = g->ny * g->dy, estar = mc_scene_estar(s);
    const double p_lub = s->load.lubricant_pressure;
    if (p_lub == MC_LUBRICANT_AUTO || s->load.kind == MC_LOAD_PRESSURE_FILE)
        return MC_OK;
    const double f = s->load.value;
    switch (s->load.kind) {
    case MC_LOAD_FORCE:
        if (!(f / (Lx * Ly) <= SCALE_MAX * estar))
            BLAME("load", "force",
                  "[load] force = %g N: the mean pressure over the grid, F / (nx dx ny dy) = %g "
                  "Pa, is more than %g times the reduced modulus E* = %g Pa (strains far beyond "
                  "one, outside linear elasticity and the solver's number range); accepted: "
                  "force <= %g E* nx dx ny dy = %g N (reduce the force, enlarge the grid or "
                  "check the moduli E)",
                  f, f / (Lx * Ly), SCALE_MAX, estar, SCALE_MAX, SCALE_MAX * estar * Lx * Ly);
        if (p_lub * Lx * Ly > f)
            BLAME("load", "lubricant_pressure",
                  "[load] lubricant_pressure = %g Pa over the whole grid (%g x %g m) carries "
                  "%g N, more than the requested force %g N: the contact cannot carry the "
                  "force asked for; lower lubricant_pressure below F / (nx dx ny dy) = %g Pa, or "
                  "raise the force",
                  p_lub, Lx, Ly, p_lub * Lx * Ly, f, f / (Lx * Ly));
        break;
    case MC_LOAD_FORCE_PER_LENGTH:
        if (!(f / Lx <= SCALE_MAX * estar))
            BLAME("load", "force_per_length",
                  "[load] force_per_length = %g N/m: the mean pressure over the grid, w / (nx "
                  "dx) = %g Pa, is more than %g times the reduced modulus E* = %g Pa (strains "
                  "far beyond one, outside linear elasticity and the solver's number range); "
                  "accepted: force_per_length <= %g E* nx dx = %g N/m",
                  f, f / Lx, SCALE_MAX, estar, SCALE_MAX, SCALE_MAX * estar * Lx);
        if (p_lub * Lx > f)
            BLAME("load", "lubricant_pressure",
                  "[load] lubricant_pressure = %g Pa over the grid's width (%g m) carries %g N/m, "
                  "more than the requested force_per_length %g N/m: lower lubricant_pressure "
                  "below w / (nx dx) = %g Pa, or raise the load",
                  p_lub, Lx, p_lub * Lx, f, f / Lx);
        break;
    case MC_LOAD_APPROACH:
        if (!(f <= SCALE_MAX * fmax(Lx, Ly)))
            BLAME("load", "approach",
                  "[load] approach = %g m: more than %g times the grid (%g x %g m), strains far "
                  "beyond one, outside linear elasticity and the solver's number range; "
                  "accepted: approach <= %g max(nx dx, ny dy) = %g m",
                  f, SCALE_MAX, Lx, Ly, SCALE_MAX, SCALE_MAX * fmax(Lx, Ly));
        break;
    case MC_LOAD_PRESSURE_FILE: break;
    }
    return MC_OK;
}

/* The rules that tie keys together; each key's own bounds are the table's (mc_keys_check_scene).
 * A key that is given but has no effect in its scene is refused here or by the table's use
 * conditions, never silently ignored. */
static int scene_rules(const mc_scene *s, mc_error *err, const char **section,
                       const char **keyname)
{
    if (s->roughness.type == MC_ROUGH_SELF_AFFINE) {
        if (s->roughness.rq > 0 && s->roughness.rms_slope > 0)
            BLAME("roughness", "rms_slope",
                  "[roughness] type = self_affine takes rq or rms_slope, not both");
        if (!(s->roughness.rq > 0 || s->roughness.rms_slope > 0))
            BLAME("roughness", "rq",
                  "[roughness] type = self_affine needs rq > 0 or rms_slope > 0");
        double lo, hi;
        mc_scene_cutoffs(s, &hi, &lo);
        if (!(lo < hi))
            BLAME("roughness", "lambda_short",
                  "[roughness] lambda_short = %g m: must be < lambda_long = %g m", lo, hi);
    }
    if (s->load.kind == MC_LOAD_FORCE_PER_LENGTH && !s->grid.periodic_y)
        BLAME("load", "force_per_length",
              "[load] force_per_length needs [mesh] periodic_y = yes (a load per unit length is "
              "carried by a body periodic along y)");
    if (s->load.kind == MC_LOAD_PRESSURE_FILE) {
        /* a prescribed pressure is not solved for: bounds and solver settings have no effect */
        if (s->load.lubricant_pressure != 0)
            BLAME("load", "lubricant_pressure",
                  "[load] lubricant_pressure has no effect with pressure_file (the pressure is "
                  "prescribed, not solved for): remove it");
        if (s->load.pressure_cap != INFINITY)
            BLAME("load", "pressure_cap",
                  "[load] pressure_cap has no effect with pressure_file (the pressure is "
                  "prescribed, not solved for): remove it");
    } else if (s->load.lubricant_pressure != MC_LUBRICANT_AUTO &&
               !(s->load.pressure_cap > s->load.lubricant_pressure))
        BLAME("load", "pressure_cap",
              "[load] pressure_cap = %g Pa: must be > lubricant_pressure = %g Pa",
              s->load.pressure_cap, s->load.lubricant_pressure);
    int rc = lubrication_rules(s, err, section, keyname);
    if (rc == MC_OK)
        rc = scale_rules(s, err, section, keyname);
    if (rc == MC_OK)
        rc = plasticity_rules(s, err, section, keyname);
    if (rc == MC_OK)
        rc = runin_rules(s, err, section, keyname);
    if (rc != MC_OK)
        return rc;
    if (s->stress.enabled)
        return stress_rules(s, err, section, keyname);
    return MC_OK;
}

int mc_scene_check_key(const mc_scene *s, mc_error *err, const char **section, const char **keyname)
{
    int rc = mc_keys_check_scene(s, NULL, err, section, keyname);
    if (rc == MC_OK)
        rc = scene_rules(s, err, section, keyname);
    if (rc == MC_OK)
        rc = mc_scene_effect_rules(s, err, section, keyname);
    return rc;
}

int mc_scene_check(const mc_scene *s, mc_error *err)
{
    return mc_scene_check_key(s, err, NULL, NULL);
}

void mc_scene_where(const mc_scene *s, const char *section, const char *name, char *buf,
                    size_t len)
{
    const int k = mc_key_find(section, name);
    const int line = k >= 0 && k < MC_SCENE_KEYS_MAX ? s->key_line[k] : 0;
    const char *path = s->path[0] ? s->path : "<scene>";
    if (line > 0)
        snprintf(buf, len, "%s:%d: ", path, line);
    else if (line < 0)
        snprintf(buf, len, "%s: --set %s.%s: ", path, section, name);
    else
        snprintf(buf, len, "%s: ", path);
}

double mc_scene_estar(const mc_scene *s)
{
    return mc_combined_modulus(s->body1.E, s->body1.nu, s->body2.E, s->body2.nu, s->body2.rigid);
}

int mc_scene_depths(const mc_scene *s, double *depths, int *ndepths, mc_error *err)
{
    mc_scene on = *s; /* the stress keys are checked whether or not the stage is enabled */
    on.stress.enabled = 1;
    int rc = mc_keys_check_scene(&on, "stress", err, NULL, NULL);
    if (rc == MC_OK)
        rc = stress_rules(&on, err, NULL, NULL);
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
