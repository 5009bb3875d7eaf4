/* scene_effect.c - keys given with a value that has no effect in their scene, and documented
 * rules the key table's bounds cannot state (issue 23, classes 4 and 5): refused by
 * mc_scene_effect_rules, named as mc_scene_check_key names a key. Values are compared with the
 * defaults (scene.h: a key not given holds its documented default).
 *
 * The systematic pass (issue 23, class 5): every key of the table (keys.c, 105 keys with
 * friction_in_yield; the 20 of
 * [roughness2] since repeat those of [roughness]) against the
 * scene classes it can meet, 23 in all: the grid (free; periodic x; a strip periodic in y; doubly
 * periodic; one row, ny = 1, a line grid or a free row), the load (force, force_per_length,
 * approach, pressure_file), the roughness (none; gaussian or self_affine; a file with its own
 * units, x3p sdf gsf; a file of plain numbers, txt xyz npy; the mesh taken from the file),
 * [lubrication] on/off, [plasticity] von_mises / pressure_cap / off, [runin] on/off, [stress]
 * on/off. A pair with no effect is refused (exit 2, file:line: [section] key ... has no effect
 * ...) by the layer named below; every other pair was traced to the code that reads the field.
 *
 *  key                            scene class without effect                  refused by
 *  ----------------------------   ------------------------------------------  ----------------
 *  any key of another selector    type/shape/film/criterion/hardening/rigid/  key table (use =
 *   value (radius, rq, hurst,      plans value that does not use it (e.g.      USE_WHEN):
 *   film_thickness, hardness,      radius with shape = flat, hardness with     "is not used by"
 *   table_unit, wisdom_file, ...)  von_mises, body2 E with rigid = yes)
 *  solver method, tolerance,      load = pressure_file (no contact solve)      key table
 *   max_iterations; load                                                       (USE_UNLESS)
 *   lubricant_pressure, cap
 *  stress depth_min, layers,      depths given                                key table
 *   spacing                                                                    (USE_UNLESS)
 *  stress depth_max               layers = 1 (the one layer is depth_min)     here (new)
 *  stress spacing = geometric     layers = 1                                  here (new)
 *  stress window = full           grid periodic along x or y (auto is full)   here (new)
 *  geometry radius_y (ellipsoid)  one row, ny = 1 (y = 0 on every cell)       here (new)
 *  roughness correlation_y        gaussian on one row, ny = 1 (no y waves)    here (new)
 *  roughness units                file with its own units (x3p, sdf, gsf)     here
 *  roughness verify_checksum      file that is not X3P                        here
 *  roughness resample             mesh from the file (nothing to resample)    reader.c
 *  roughness scale = 0            (a documented rule, not a pair)             here
 *  roughness2 (every key)         as the same key of [roughness] above (the   here, scene.c,
 *                                  mesh comes from [roughness] file only, so   the key table
 *                                  roughness2 resample has an effect there)
 *  roughness2 type                [roughness] type = none (no body 1)         scene.c
 *  lubrication radius1, radius2   film = ehl by speed with macro_radius (R_x  here (new)
 *                                  given; the radii only convert rpm)
 *  lubrication rpm2               without rpm                                 scene.c
 *  lubrication width              film = given without macro_radius           scene.c
 *  lubrication (section)          lubricant_pressure not auto                 scene.c
 *  plasticity margin              a running-in (whole-grid columns)           here
 *  plasticity margin              doubly periodic grid (the volume spans the  here (new)
 *                                  whole period along x and y)
 *  plasticity margin              kernel = spectral (the volume spans the     here (new)
 *                                  whole grid)
 *  runin nominal_deflection       doubly periodic grid (no bowl)              here
 *  runin friction_in_yield        no [plasticity] (von_mises); pure rolling   here (new)
 *                                  (no sliding direction)
 *  plasticity friction            runin friction_in_yield = yes (replaced)    here (new)
 *  plasticity near_field          iteration = joint (global sweeps only)      here (new)
 *  stress / lubrication /         the section's enabled = no                  accepted: the
 *   plasticity / runin keys                                                    switch keeps a
 *                                                                              section for later
 *                                                                              (--set ...=no)
 *
 * Pairs examined and found to have an effect (not refused), with the code that reads them:
 * [mesh] dy on a line grid (cell area: forces, areas, pressures of a force load; dz default);
 * shape = sphere on one row (= a cylinder, but the shape differs from flat); [solver] plans with
 * operator = direct (roughness synthesis, stress and eigen tables still use FFTW); [stress]
 * window, kernel, friction with pressure_file (the prescribed load is stressed); [plasticity]
 * margin on a strip or line grid (bounds the columns along x); stress_points on every grid
 * (docs/theory.md §8.7); load_steps, depth, dz in a running-in (runin.c); [lubrication]
 * mu_solid, mu_fluid, psi (the friction mix of summary.json); [runin] forces without
 * [plasticity] (elastic steps at each force); [geometry] and [roughness] with pressure_file
 * (topography, gap and stresses written); [roughness] cutoff on every type (summary.json).
 */
#include "case/scene_effect.h"

#include <string.h>

#include "io/surface_file.h"
#include "surface/measured.h"

#define BLAME(sec, key, ...)                                                                       \
    do {                                                                                           \
        if (section)                                                                               \
            *section = (sec);                                                                      \
        if (keyname)                                                                               \
            *keyname = (key);                                                                      \
        return mc_fail(err, MC_ERR_INPUT, __VA_ARGS__);                                            \
    } while (0)

/* The format a [roughness] file is read as: the format key, else the file's extension. */
static const char *file_format(const mc_roughness_spec *r)
{
    /* the names of mc_surface_format, here so that the case layer needs no surface code */
    static const char *const names[] = {"auto", "x3p", "sdf", "gsf", "txt", "xyz", "npy"};
    if (r->format > MC_FORMAT_AUTO && r->format <= MC_FORMAT_NPY)
        return names[r->format];
    const char *f = mc_surface_format_from_path(r->file);
    return f ? f : "";
}

/* The file keys of one roughness section (sec: "roughness" or "roughness2") over its spec r. */
static int roughness_file_rules(const mc_roughness_spec *r, const char *sec, mc_error *err,
                                const char **section, const char **keyname)
{
    if (r->type != MC_ROUGH_FILE)
        return MC_OK;
    if (r->scale == 0) /* also -0: the key's doc says "not 0"; 0 was taken as 1 */
        BLAME(sec, "scale",
              "[%s] scale = 0: must not be 0 (a factor on the heights, in -1e6..1e6; 1 "
              "leaves them as they are, invert = yes turns them over)",
              sec);
    const char *f = file_format(r);
    const int own_units = !strcmp(f, "x3p") || !strcmp(f, "sdf") || !strcmp(f, "gsf");
    if (own_units && r->units != 0)
        BLAME(sec, "units",
              "[%s] units has no effect with a %s file (it carries its own units): remove it",
              sec, f);
    if (strcmp(f, "x3p") != 0 && !r->verify_checksum)
        BLAME(sec, "verify_checksum",
              "[%s] verify_checksum has no effect with a %s file (only X3P files carry "
              "checksums): remove it",
              sec, f[0] ? f : "non-X3P");
    return MC_OK;
}

/* correlation_y of a gaussian section on one row (sec: "roughness" or "roughness2"). */
static int one_row_rules(const mc_scene *s, const mc_roughness_spec *r, const char *sec,
                         mc_error *err, const char **section, const char **keyname)
{
    if (r->type == MC_ROUGH_GAUSSIAN && s->grid.ny == 1 && r->correlation_y != r->correlation_x)
        BLAME(sec, "correlation_y",
              "[%s] correlation_y has no effect on a grid of one row (ny = 1: the heights "
              "have no wavelengths along y): remove it",
              sec);
    return MC_OK;
}

/* Keys of the grid's shape, the stress layers and the film (the "new" rows of the table). */
static int grid_stress_lube_rules(const mc_scene *s, mc_error *err, const char **section,
                                  const char **keyname)
{
    const mc_grid *g = &s->grid;
    if (s->geometry.shape == MC_SHAPE_ELLIPSOID && g->ny == 1)
        BLAME("geometry", "radius_y",
              "[geometry] radius_y has no effect on a grid of one row (ny = 1: y = 0 on every "
              "cell): use shape = cylinder with radius = radius_x");
    int rc = one_row_rules(s, &s->roughness, "roughness", err, section, keyname);
    if (rc == MC_OK)
        rc = one_row_rules(s, &s->roughness2, "roughness2", err, section, keyname);
    if (rc != MC_OK)
        return rc;
    if (s->stress.enabled) {
        if (s->stress.window == MC_STRESS_WINDOW_FULL && (g->periodic_x || g->periodic_y))
            BLAME("stress", "window",
                  "[stress] window = full has no effect on a grid periodic along %s (window = "
                  "auto stresses every cell there: a periodic load is never compact): remove it",
                  g->periodic_x && g->periodic_y ? "x and y" : g->periodic_x ? "x" : "y");
        if (s->stress.spacing != MC_SPACING_LIST && s->stress.layers == 1) {
            if (s->stress.depth_max != MC_STRESS_DEPTH_AUTO)
                BLAME("stress", "depth_max",
                      "[stress] depth_max has no effect with layers = 1 (the one layer is at "
                      "depth_min): remove it, or raise layers");
            if (s->stress.spacing == MC_SPACING_GEOMETRIC)
                BLAME("stress", "spacing",
                      "[stress] spacing = geometric has no effect with layers = 1 (the one layer "
                      "is at depth_min): remove it, or raise layers");
        }
    }
    if (s->lubrication.enabled && s->load.lubricant_pressure == MC_LUBRICANT_AUTO && s->lubrication.film == MC_FILM_EHL &&
        !(s->lubrication.rpm > 0) && s->lubrication.macro_radius > 0 && (s->lubrication.radius1 > 0 || s->lubrication.radius2 > 0))
        BLAME("lubrication", s->lubrication.radius1 > 0 ? "radius1" : "radius2",
              "[lubrication] %s has no effect with speed and macro_radius (the disc radii give "
              "R_x only without macro_radius, and convert rpm to a speed only with rpm): remove "
              "radius1 and radius2",
              s->lubrication.radius1 > 0 ? "radius1" : "radius2");
    return MC_OK;
}

static int plastic_runin_rules(const mc_scene *s, mc_error *err, const char **section,
                               const char **keyname)
{
    const int vm = s->plasticity.enabled && s->plasticity.criterion == MC_CRITERION_VON_MISES;
    if (vm && s->plasticity.depth > 0 && s->plasticity.dz > 0 &&
        s->plasticity.depth < s->plasticity.dz)
        BLAME("plasticity", "depth",
              "[plasticity] depth = %g m is below dz = %g m: the plastic volume holds no layer; "
              "accepted: depth >= dz (or depth = auto)",
              s->plasticity.depth, s->plasticity.dz);
    /* layering = auto is uniform with a given depth: the grading keys would do nothing */
    if (vm && s->plasticity.layering == MC_LAYERING_AUTO && s->plasticity.depth > 0 &&
        (s->plasticity.fine_depth > 0 || s->plasticity.grading != 0.25))
        BLAME("plasticity", s->plasticity.fine_depth > 0 ? "fine_depth" : "grading",
              "[plasticity] %s has no effect with layering = auto and a given depth (the layers "
              "are then uniform): add layering = graded, or set depth = auto",
              s->plasticity.fine_depth > 0 ? "fine_depth" : "grading");
    /* the local-global fixed point is a scheme of the nested iteration (theory §9.7, §9.8) */
    if (vm && s->plasticity.near_field > 0 && s->plasticity.iteration == MC_PLASTIC_JOINT)
        BLAME("plasticity", "near_field",
              "[plasticity] near_field = %d has no effect with iteration = joint (the default: "
              "its evaluations sweep with the whole residual stress operator); add iteration = "
              "nested, or remove near_field",
              s->plasticity.near_field);
    if (vm && s->plasticity.margin > 0 && s->grid.periodic_x && s->grid.periodic_y &&
        !s->runin.enabled)
        BLAME("plasticity", "margin",
              "[plasticity] margin has no effect on a grid periodic along x and y (the plastic "
              "volume spans the whole period along both axes): remove it");
    if (vm && s->plasticity.margin > 0 && s->plasticity.kernel == MC_EIG_KERNEL_SPECTRAL &&
        !s->runin.enabled)
        BLAME("plasticity", "margin",
              "[plasticity] margin has no effect with kernel = spectral (its volume spans the "
              "whole grid, docs/theory.md §8.10): remove it");
    if (!s->runin.enabled)
        return MC_OK;
    if (vm && s->plasticity.margin > 0)
        BLAME("plasticity", "margin",
              "[plasticity] margin has no effect in a running-in ([runin]): every step's plastic "
              "columns span the whole grid; remove it");
    if (s->runin.friction_in_yield && !vm)
        BLAME("runin", "friction_in_yield",
              "[runin] friction_in_yield = yes has no effect without [plasticity] (criterion = "
              "von_mises): nothing yields; remove it, or add [plasticity]");
    if (s->runin.friction_in_yield && vm && s->plasticity.friction > 0)
        BLAME("plasticity", "friction",
              "[plasticity] friction has no effect with [runin] friction_in_yield = yes (each "
              "step's mu replaces it): remove one of them");
    if (s->runin.friction_in_yield && vm && s->lubrication.rpm > 0 &&
        !(s->lubrication.rpm2 > 0 && s->lubrication.rpm2 * s->lubrication.radius2 !=
                                         s->lubrication.rpm * s->lubrication.radius1))
        BLAME("runin", "friction_in_yield",
              "[runin] friction_in_yield = yes has no effect in pure rolling (equal surface "
              "speeds: no sliding, so no direction for the traction); accepted with "
              "[lubrication] rpm2 giving disc 2 another surface speed than disc 1");
    if (s->runin.deflection != MC_DEFLECTION_REMOVE && s->lubrication.enabled &&
        (s->geometry.shape == MC_SHAPE_CYLINDER || s->geometry.shape == MC_SHAPE_ELLIPSOID))
        BLAME("runin", "nominal_deflection",
              "[runin] nominal_deflection has no effect on the whole contact ([geometry] shape = "
              "cylinder or ellipsoid): the macro contact's own deflection is part of the solve; "
              "remove it");
    if (s->runin.deflection != MC_DEFLECTION_REMOVE && s->grid.periodic_x && s->grid.periodic_y)
        BLAME("runin", "nominal_deflection",
              "[runin] nominal_deflection has no effect on a grid periodic along x and y (the "
              "bowl of the nominal pressure is zero there): remove it");
    return MC_OK;
}

int mc_scene_effect_rules(const mc_scene *s, mc_error *err, const char **section,
                          const char **keyname)
{
    int rc = roughness_file_rules(&s->roughness, "roughness", err, section, keyname);
    if (rc == MC_OK)
        rc = roughness_file_rules(&s->roughness2, "roughness2", err, section, keyname);
    if (rc == MC_OK)
        rc = grid_stress_lube_rules(s, err, section, keyname);
    return rc != MC_OK ? rc : plastic_runin_rules(s, err, section, keyname);
}
