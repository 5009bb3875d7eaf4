/* scene_effect.c - keys given with a value that has no effect in their scene, and documented
 * rules the key table's bounds cannot state (issue 23, classes 4 and 5): refused by
 * mc_scene_effect_rules, named as mc_scene_check_key names a key. Values are compared with the
 * defaults (scene.h: a key not given holds its documented default). */
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

static int roughness_file_rules(const mc_scene *s, mc_error *err, const char **section,
                                const char **keyname)
{
    const mc_roughness_spec *r = &s->roughness;
    if (r->type != MC_ROUGH_FILE)
        return MC_OK;
    if (r->scale == 0) /* also -0: the key's doc says "not 0"; 0 was taken as 1 */
        BLAME("roughness", "scale",
              "[roughness] scale = 0: must not be 0 (a factor on the heights, in -1e6..1e6; 1 "
              "leaves them as they are, invert = yes turns them over)");
    const char *f = file_format(r);
    const int own_units = !strcmp(f, "x3p") || !strcmp(f, "sdf") || !strcmp(f, "gsf");
    if (own_units && r->units != 0)
        BLAME("roughness", "units",
              "[roughness] units has no effect with a %s file (it carries its own units): remove "
              "it",
              f);
    if (strcmp(f, "x3p") != 0 && !r->verify_checksum)
        BLAME("roughness", "verify_checksum",
              "[roughness] verify_checksum has no effect with a %s file (only X3P files carry "
              "checksums): remove it",
              f[0] ? f : "non-X3P");
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
    if (!s->runin.enabled)
        return MC_OK;
    if (vm && s->plasticity.margin > 0)
        BLAME("plasticity", "margin",
              "[plasticity] margin has no effect in a running-in ([runin]): every step's plastic "
              "columns span the whole grid; remove it");
    if (s->runin.deflection != MC_DEFLECTION_REMOVE && s->grid.periodic_x && s->grid.periodic_y)
        BLAME("runin", "nominal_deflection",
              "[runin] nominal_deflection has no effect on a grid periodic along x and y (the "
              "bowl of the nominal pressure is zero there): remove it");
    return MC_OK;
}

int mc_scene_effect_rules(const mc_scene *s, mc_error *err, const char **section,
                          const char **keyname)
{
    int rc = roughness_file_rules(s, err, section, keyname);
    return rc != MC_OK ? rc : plastic_runin_rules(s, err, section, keyname);
}
