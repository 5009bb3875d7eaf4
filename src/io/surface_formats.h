/* surface_formats.h - the per-format parsers behind mc_surface_parse_buffer, and the helpers
 * they share (internal to src/io; callers use surface_file.h).
 *
 * Contract of every mc_<fmt>_parse: reads only buf[0..len) (len > 0), fills out->nx, ny, dx, dy,
 * x0, y0, z (and valid when the file has a mask), heights in metres. It may leave partial
 * allocations in *out on failure: the dispatcher frees them. It does not need to count missing
 * points or reconcile z with valid: mc_surface_finish does.
 */
#ifndef MC_SURFACE_FORMATS_H
#define MC_SURFACE_FORMATS_H

#include <stddef.h>

#include "core/error.h"
#include "io/surface_file.h"

/* Check nx, ny (as read, any size) against 1 <= nx, ny and nx*ny <= MC_SURFACE_MAX_POINTS:
 * MC_ERR_INPUT naming what and the sizes. Parsers call it before comparing the data size with
 * the file, and allocate only once the data are known to be there. */
int mc_surface_check_dims(long long nx, long long ny, const char *what, mc_error *err);

/* mc_surface_check_dims, then set out->nx, ny and allocate out->z (uninitialised). MC_ERR_INPUT,
 * MC_ERR_NOMEM. */
int mc_surface_alloc(mc_surface_data *out, long long nx, long long ny, const char *what,
                     mc_error *err);

/* Reconcile z and valid (a masked finite height becomes NaN; a non-finite one becomes invalid),
 * count missing, drop the mask when nothing is missing. MC_ERR_NOMEM. */
int mc_surface_finish(mc_surface_data *out, const char *what, mc_error *err);

/* Metres per unit for a length unit name of n bytes ("m", "mm", "um", "µm", "nm", "pm", "km",
 * "A" or "Å" for angstrom); 0 when it is not a length unit. */
double mc_surface_length_unit(const char *name, size_t n);

/* Copy untrusted bytes into a printable, bounded, NUL-terminated string for a message. */
void mc_surface_quote(char *out, size_t outlen, const unsigned char *s, size_t n);

/* The whole of s[0..n) (blanks around it allowed) as a number (strtod syntax, finite) or as a
 * decimal integer (saturating at +-LLONG_MAX, so size checks fail cleanly); 0 if it is not one. */
int mc_surface_number(const char *s, size_t n, double *v);
int mc_surface_integer(const char *s, size_t n, long long *v);

/* MD5 of buf[0..len) as 32 lowercase hex digits and a NUL (nettle). */
void mc_md5_hex(const unsigned char *buf, size_t len, char hex[33]);

int mc_x3p_parse(const unsigned char *buf, size_t len, const char *what,
                 const mc_surface_read_options *opt, mc_surface_data *out, mc_error *err);
int mc_sdf_parse(const unsigned char *buf, size_t len, const char *what, mc_surface_data *out,
                 mc_error *err);
int mc_gsf_parse(const unsigned char *buf, size_t len, const char *what, mc_surface_data *out,
                 mc_error *err);
/* units: metres per file unit for x, y and z. */
int mc_xyz_parse(const unsigned char *buf, size_t len, const char *what, double units,
                 mc_surface_data *out, mc_error *err);

#endif
