/* fuzz_surface.h - the contract shared by the measured-surface fuzz targets (fuzz_x3p, fuzz_sdf,
 * fuzz_gsf, fuzz_xyz, fuzz_npy_any): one call of mc_surface_parse_buffer, checked.
 *
 *  - status MC_OK or MC_ERR_INPUT; MC_ERR_NOMEM only for an injected failure (input prefix
 *    "\x01" n makes the (n+1)th mc_malloc of the parse fail); never MC_OK after one;
 *  - failure: one printable UTF-8 line starting with the input's name, the record left empty;
 *  - success: 1 <= nx, ny, nx*ny <= MC_SURFACE_MAX_POINTS and no more points than the image can
 *    hold (a per-format bound); the format name set; spacings finite and >= 0, offsets finite;
 *    valid[k] == 0 exactly where z[k] is not finite, missing counts them, valid NULL iff none.
 */
#ifndef MC_FUZZ_SURFACE_H
#define MC_FUZZ_SURFACE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_common.h"
#include "io/surface_file.h"

#define FUZZ_SURFACE_NAME "fuzz.surface"

/* Strip the allocation-failure prefix; returns the allocation to fail (0 = none). */
static inline long fuzz_alloc_prefix(const uint8_t **data, size_t *size)
{
    if (*size >= 2 && (*data)[0] == 0x01) {
        long n = (long)(*data)[1] + 1;
        *data += 2;
        *size -= 2;
        return n;
    }
    return 0;
}

static inline int fuzz_surface_parse(const char *format, const uint8_t *buf, size_t len,
                                     const mc_surface_read_options *opt, long fail_at,
                                     double max_points)
{
    mc_surface_data s;
    mc_error err = {0};
    memset(&s, 0x5a, sizeof s);
    long injected = mc_alloc_injected();
    mc_alloc_fail_at(fail_at);
    int rc = mc_surface_parse_buffer(format, buf, len, FUZZ_SURFACE_NAME, opt, &s, &err);
    mc_alloc_fail_at(0);
    int fired = mc_alloc_injected() != injected;
    FUZZ_CHECK(rc == MC_OK || rc == MC_ERR_INPUT || (rc == MC_ERR_NOMEM && fired),
               "status %d: %s", rc, err.msg);
    FUZZ_CHECK(!(fired && rc == MC_OK), "an allocation failed but the parse returned MC_OK");
    if (rc != MC_OK) {
        fuzz_check_error(&err, rc);
        FUZZ_CHECK(strncmp(err.msg, FUZZ_SURFACE_NAME ":", sizeof FUZZ_SURFACE_NAME) == 0,
                   "message does not start with the input's name: %s", err.msg);
        FUZZ_CHECK(s.z == NULL && s.valid == NULL && s.nx == 0 && s.ny == 0 && s.missing == 0,
                   "record not left empty on failure");
        return rc;
    }
    FUZZ_CHECK(s.nx >= 1 && s.ny >= 1 && (long long)s.nx * s.ny <= MC_SURFACE_MAX_POINTS,
               "grid %d x %d", s.nx, s.ny);
    size_t n = (size_t)s.nx * (size_t)s.ny;
    FUZZ_CHECK((double)n <= max_points, "%zu points from %zu bytes", n, len);
    FUZZ_CHECK(strcmp(s.format, format) == 0, "format '%s'", s.format);
    FUZZ_CHECK(isfinite(s.dx) && isfinite(s.dy) && s.dx >= 0 && s.dy >= 0, "dx %g dy %g", s.dx,
               s.dy);
    FUZZ_CHECK(isfinite(s.x0) && isfinite(s.y0), "x0 %g y0 %g", s.x0, s.y0);
    FUZZ_CHECK(s.z != NULL, "no heights");
    long missing = 0;
    for (size_t k = 0; k < n; k++) {
        int finite = isfinite(s.z[k]) != 0;
        missing += !finite;
        if (s.valid)
            FUZZ_CHECK(s.valid[k] == finite, "valid[%zu] = %d, z = %g", k, s.valid[k], s.z[k]);
    }
    FUZZ_CHECK(missing == s.missing, "missing %ld, counted %ld", s.missing, missing);
    FUZZ_CHECK((s.valid == NULL) == (missing == 0), "mask present %d, missing %ld",
               s.valid != NULL, missing);
    mc_surface_data_free(&s);
    return rc;
}

#endif
