/* measured.h - a measured (or external) height map made ready for a run: read by io/surface_file,
 * cropped to a region, missing points refused or filled, levelled, scaled or inverted, and put
 * onto the run's mesh (taken from the file, or resampled onto a given one). docs/theory.md §13.
 */
#ifndef MC_MEASURED_H
#define MC_MEASURED_H

#include <stddef.h>

#include "core/error.h"
#include "core/grid.h"
#include "surface/level.h"

typedef enum { MC_MISSING_ERROR, MC_MISSING_FILL } mc_missing_rule;
typedef enum { MC_RESAMPLE_NONE, MC_RESAMPLE_LINEAR } mc_resample_rule;
typedef enum {
    MC_FORMAT_AUTO, MC_FORMAT_X3P, MC_FORMAT_SDF, MC_FORMAT_GSF, MC_FORMAT_TXT, MC_FORMAT_XYZ,
    MC_FORMAT_NPY
} mc_surface_format;

/* "auto" (by extension) or the io/surface_file.h name ("x3p", ...). */
const char *mc_surface_format_name(mc_surface_format f);

typedef struct {
    const char *path;
    mc_surface_format format;
    double units;            /* metres per file unit (txt, xyz, npy); 0 or 1 = metres */
    int verify_checksum;     /* X3P */
    int has_region;          /* crop to region[] = x0, y0, width, height (m, file coordinates) */
    double region[4];
    mc_missing_rule missing;
    mc_detrend_kind detrend;
    double scale;            /* heights multiplied by scale (0 = 1) */
    int invert;              /* heights negated (a map of a replica, or pointing into the body) */
    const char *label;       /* the case section its messages name: "[roughness]" (NULL) or
                                "[roughness2]" */
} mc_measured_spec;

typedef struct {
    mc_level_grid grid; /* the map as read (after the crop): nx, ny, dx, dy (0 when the file has
                           no lateral scale), x0, y0 */
    double *z;          /* ny*nx heights, m, levelled, scaled; owned */
    long missing;       /* points the file did not measure */
    long filled;        /* of which filled (missing = fill) */
    char format[16];    /* the format read */
    const char *path;   /* the file (the spec's), for messages */
    const char *label;  /* the spec's label ("[roughness]" when it had none), for messages */
    char warning[320];  /* "" or the reader's warning (io/surface_file.h), for the user */
} mc_measured;

/* Read and prepare the map of spec into *out (free with mc_measured_free). Errors name the file:
 * MC_ERR_IO, MC_ERR_INPUT (a reader's error; missing points with missing = error, naming their
 * count and the first one; a region outside the map), MC_ERR_NOMEM. */
int mc_measured_load(const mc_measured_spec *spec, mc_measured *out, mc_error *err);

/* Heights on the run's mesh g (ny*nx, centred as grid.h; cell centres): the map itself when its
 * size matches and its spacing is unknown or equal (to 1e-9 relative); otherwise with
 * resample = linear the bilinear interpolation of the map (centred on the mesh) onto the cell
 * centres, and with resample = none MC_ERR_INPUT naming both grids. */
int mc_measured_onto(const mc_measured *m, const mc_grid *g, mc_resample_rule resample,
                     double *heights, mc_error *err);

/* 1 when mc_measured_onto puts m onto g without resampling (the same size, and the same
 * spacing to 1e-9 relative or none stated), else 0. */
int mc_measured_matches(const mc_measured *m, const mc_grid *g);

/* "FILE: 256 x 128 points of 5e-07 x 5e-07 m (nx x ny, dx x dy)" (or "... points without a
 * lateral spacing"): the grid of m for a message, into buf (always NUL-terminated). */
void mc_measured_describe(const mc_measured *m, char *buf, size_t len);

void mc_measured_free(mc_measured *m);

#endif
