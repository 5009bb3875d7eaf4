/* two_bodies.c - the roughness heights of the two bodies of a contact (surface.h,
 * mc_surface_two_bodies; docs/theory.md §4.11). */
#include <stdio.h>
#include <string.h>

#include "surface/surface.h"

static const char *const label[3] = {"", "[roughness]", "[roughness2]"};

static const char *type_name(mc_roughness_type t)
{
    switch (t) {
    case MC_ROUGH_NONE: return "no roughness";
    case MC_ROUGH_GAUSSIAN: return "gaussian heights";
    case MC_ROUGH_SELF_AFFINE: return "self_affine heights";
    case MC_ROUGH_FILE: break;
    }
    return "a file";
}

/* Body k's surface for a message: its map's file and grid, or its synthetic type. */
static void describe(const mc_roughness_spec *s, const mc_measured *m, char *buf, size_t len)
{
    if (s->type == MC_ROUGH_FILE)
        mc_measured_describe(m, buf, len);
    else
        snprintf(buf, len, "%s made on the mesh", type_name(s->type));
}

/* Body k (1 or 2) does not come onto the mesh: name both bodies and the mesh. */
static int mismatch(const mc_grid *g, int k, const mc_roughness_spec *const s[3],
                    const mc_measured m[3], mc_error *err)
{
    char mine[600], other[600];
    describe(s[k], &m[k], mine, sizeof mine);
    describe(s[3 - k], &m[3 - k], other, sizeof other);
    const int spacing = m[k].grid.dx > 0 && m[k].grid.dy > 0;
    char fix[200];
    if (!spacing)
        snprintf(fix, sizeof fix, "a map without a lateral spacing cannot be resampled: give "
                                  "maps of the mesh's size");
    else if (k == 1)
        snprintf(fix, sizeof fix, "set %s resample = linear to interpolate it, or omit nx, ny, dx, "
                                  "dy in [mesh] (the mesh is then body 1's map)",
                 label[k]);
    else
        snprintf(fix, sizeof fix, "set %s resample = linear to interpolate body 2's map onto the "
                                  "mesh",
                 label[k]);
    return mc_fail(err, MC_ERR_INPUT,
                   "%s file: the two surfaces do not come onto one grid: body %d's map %s; body "
                   "%d's (%s) %s; the mesh %d x %d cells of %g x %g m: %s",
                   label[k], k, mine, 3 - k, label[3 - k], other, g->nx, g->ny, g->dx, g->dy, fix);
}

int mc_surface_two_bodies(const mc_grid *g, const mc_roughness_spec *s1,
                          const mc_roughness_spec *s2, double *z1, double *z2,
                          mc_surface_file_info *info1, mc_surface_file_info *info2, int *which,
                          mc_error *err)
{
    const mc_roughness_spec *const s[3] = {NULL, s1, s2};
    double *const z[3] = {NULL, z1, z2};
    mc_surface_file_info *const info[3] = {NULL, info1, info2};
    mc_measured m[3];
    memset(m, 0, sizeof m);
    int rc = mc_grid_check(g, err), k = 1;
    for (k = 1; rc == MC_OK && k <= 2; k++) {
        if (info[k])
            memset(info[k], 0, sizeof *info[k]);
        if (s[k]->type != MC_ROUGH_FILE)
            continue;
        mc_measured_spec ms;
        mc_surface_measured_spec(s[k], &ms);
        ms.label = label[k];
        rc = mc_measured_load(&ms, &m[k], err);
        if (rc != MC_OK) {
            mc_error_prefix(err, "%s file: ", label[k]);
            break;
        }
        if (info[k]) {
            memcpy(info[k]->format, m[k].format, sizeof info[k]->format);
            info[k]->missing = m[k].missing;
            info[k]->filled = m[k].filled;
            memcpy(info[k]->warning, m[k].warning, sizeof info[k]->warning);
        }
    }
    /* a map that does not come onto the mesh, with both bodies named (before any resampling) */
    for (int b = 1; rc == MC_OK && b <= 2; b++)
        if (s[b]->type == MC_ROUGH_FILE && s[b]->resample == MC_RESAMPLE_NONE &&
            !mc_measured_matches(&m[b], g)) {
            k = b;
            rc = mismatch(g, b, s, m, err);
        }
    for (int b = 1; rc == MC_OK && b <= 2; b++) {
        k = b;
        if (s[b]->type == MC_ROUGH_FILE) {
            rc = mc_measured_onto(&m[b], g, (mc_resample_rule)s[b]->resample, z[b], err);
            if (rc != MC_OK)
                mc_error_prefix(err, "%s file: ", label[b]);
        } else
            rc = mc_surface_roughness_labelled(g, s[b], label[b], z[b], err);
    }
    mc_measured_free(&m[1]);
    mc_measured_free(&m[2]);
    if (which)
        *which = rc == MC_OK ? 0 : k > 2 ? 2 : k;
    return rc;
}
