/* measured.c - a measured height map made ready for a run (measured.h). */
#include "surface/measured.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "io/surface_file.h"

static const char *const format_names[] = {"auto", "x3p", "sdf", "gsf", "txt", "xyz", "npy"};

const char *mc_surface_format_name(mc_surface_format f)
{
    return f >= MC_FORMAT_AUTO && f <= MC_FORMAT_NPY ? format_names[f] : "?";
}

void mc_measured_free(mc_measured *m)
{
    mc_free(m->z);
    memset(m, 0, sizeof *m);
}

/* Crop d to the region (file coordinates): a new z/valid pair replaces the old one. */
static int crop(const mc_measured_spec *spec, mc_surface_data *d, mc_error *err)
{
    if (!(d->dx > 0 && d->dy > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: region needs the lateral spacing, which this %s file does not state",
                       spec->path, d->format);
    mc_level_grid g = {d->nx, d->ny, d->dx, d->dy, d->x0, d->y0}, sub;
    int i0, j0;
    int rc = mc_level_crop(&g, spec->region[0], spec->region[1], spec->region[2],
                           spec->region[3], &sub, &i0, &j0, err);
    if (rc != MC_OK) {
        mc_error_prefix(err, "%s: region: ", spec->path);
        return rc;
    }
    size_t n = (size_t)sub.nx * (size_t)sub.ny;
    double *z = mc_malloc(n * sizeof *z);
    unsigned char *v = d->valid ? mc_malloc(n) : NULL;
    if (!z || (d->valid && !v)) {
        mc_free(z);
        mc_free(v);
        return mc_fail(err, MC_ERR_NOMEM, "%s: out of memory for the region", spec->path);
    }
    mc_level_copy_block(d->z, d->valid, d->nx, i0, j0, sub.nx, sub.ny, z, v);
    long missing = 0;
    for (size_t k = 0; v && k < n; k++)
        missing += !v[k];
    mc_free(d->z);
    mc_free(d->valid);
    d->z = z;
    d->valid = missing ? v : NULL;
    if (!missing)
        mc_free(v);
    d->missing = missing;
    d->nx = sub.nx;
    d->ny = sub.ny;
    d->x0 = sub.x0;
    d->y0 = sub.y0;
    return MC_OK;
}

int mc_measured_load(const mc_measured_spec *spec, mc_measured *out, mc_error *err)
{
    memset(out, 0, sizeof *out);
    mc_surface_read_options ro = mc_surface_read_defaults();
    ro.format = spec->format == MC_FORMAT_AUTO ? NULL : format_names[spec->format];
    ro.units = spec->units > 0 ? spec->units : 0;
    ro.verify_checksum = spec->verify_checksum;
    mc_surface_data d;
    int rc = mc_surface_file_read(spec->path, &ro, &d, err);
    if (rc != MC_OK)
        return rc;
    if (spec->has_region)
        rc = crop(spec, &d, err);
    if (rc == MC_OK && d.missing > 0) {
        if (spec->missing == MC_MISSING_ERROR) {
            size_t first = 0;
            while (d.valid[first])
                first++;
            rc = mc_fail(err, MC_ERR_INPUT,
                         "%s: %ld of %ld points are missing (not measured or not finite; the "
                         "first at row %zu, column %zu): set %s missing = fill to "
                         "interpolate them from their neighbours",
                         spec->path, d.missing, (long)d.nx * d.ny, first / (size_t)d.nx,
                         first % (size_t)d.nx, spec->label ? spec->label : "[roughness]");
        } else {
            int filled = 0;
            rc = mc_level_fill_missing(d.z, d.valid, d.nx, d.ny, &filled, err);
            if (rc != MC_OK)
                mc_error_prefix(err, "%s: missing = fill: ", spec->path);
            out->filled = filled;
        }
    }
    if (rc == MC_OK && spec->detrend != MC_DETREND_NONE) {
        double coef[6];
        /* unknown spacing: level in index units (a plane is a plane in any scale) */
        double dx = d.dx > 0 ? d.dx : 1.0, dy = d.dy > 0 ? d.dy : 1.0;
        rc = mc_level_detrend(d.z, NULL, d.nx, d.ny, dx, dy, spec->detrend, coef, err);
    }
    if (rc == MC_OK) {
        double s = (spec->scale != 0 ? spec->scale : 1.0) * (spec->invert ? -1.0 : 1.0);
        size_t n = (size_t)d.nx * (size_t)d.ny;
        for (size_t k = 0; k < n; k++)
            d.z[k] *= s;
        out->grid = (mc_level_grid){d.nx, d.ny, d.dx, d.dy, d.x0, d.y0};
        out->z = d.z;
        d.z = NULL;
        out->missing = d.missing;
        memcpy(out->format, d.format, sizeof out->format);
        memcpy(out->warning, d.warning, sizeof out->warning);
        out->path = spec->path;
        out->label = spec->label ? spec->label : "[roughness]";
    }
    mc_surface_data_free(&d);
    return rc;
}

static int same(double a, double b) { return fabs(a - b) <= 1e-9 * fmax(fabs(a), fabs(b)); }

int mc_measured_matches(const mc_measured *m, const mc_grid *g)
{
    const mc_level_grid *s = &m->grid;
    const int spacing_known = s->dx > 0 && s->dy > 0;
    return s->nx == g->nx && s->ny == g->ny &&
           (!spacing_known || (same(s->dx, g->dx) && same(s->dy, g->dy)));
}

void mc_measured_describe(const mc_measured *m, char *buf, size_t len)
{
    const mc_level_grid *s = &m->grid;
    if (s->dx > 0 && s->dy > 0)
        snprintf(buf, len, "%s: %d x %d points of %g x %g m (nx x ny, dx x dy)",
                 m->path ? m->path : "?", s->nx, s->ny, s->dx, s->dy);
    else
        snprintf(buf, len, "%s: %d x %d points (nx x ny) without a lateral spacing",
                 m->path ? m->path : "?", s->nx, s->ny);
}

int mc_measured_onto(const mc_measured *m, const mc_grid *g, mc_resample_rule resample,
                     double *heights, mc_error *err)
{
    const mc_level_grid *s = &m->grid;
    const int spacing_known = s->dx > 0 && s->dy > 0;
    if (s->nx == g->nx && s->ny == g->ny &&
        (!spacing_known || (same(s->dx, g->dx) && same(s->dy, g->dy)))) {
        memcpy(heights, m->z, mc_grid_cells(g) * sizeof *heights);
        return MC_OK;
    }
    if (!spacing_known)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: the height map has %d x %d points (ny x nx) and no lateral spacing, "
                       "the mesh %d x %d: they must match (or use a file with a lateral scale "
                       "and resample = linear)",
                       m->path ? m->path : "?", s->ny, s->nx, g->ny, g->nx);
    if (resample == MC_RESAMPLE_NONE)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: the height map is %d x %d points of %g x %g m (nx x ny, dx x dy), the "
                       "mesh %d x %d cells of %g x %g m: set %s resample = linear to "
                       "interpolate, or omit nx, ny, dx, dy in [mesh] to take them from the file",
                       m->path ? m->path : "?", s->nx, s->ny, s->dx, s->dy, g->nx, g->ny, g->dx,
                       g->dy, m->label ? m->label : "[roughness]");
    /* both centred on the origin: the mesh's cell centres and the map's samples */
    mc_level_grid src = *s;
    src.x0 = (1.0 - s->nx) * s->dx / 2;
    src.y0 = (1.0 - s->ny) * s->dy / 2;
    mc_level_grid dst = {g->nx, g->ny, g->dx, g->dy, (1.0 - g->nx) * g->dx / 2,
                         (1.0 - g->ny) * g->dy / 2};
    int rc = mc_level_resample_linear(m->z, &src, heights, &dst, err);
    if (rc != MC_OK)
        mc_error_prefix(err, "%s: resample = linear: ", m->path ? m->path : "?");
    return rc;
}
