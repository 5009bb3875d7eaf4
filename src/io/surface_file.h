/* surface_file.h - measured surface topographies from files: one loading interface over X3P
 * (ISO 25178-72), SDF (ISO 25178-71, ASCII and binary), Gwyddion GSF, plain text matrices,
 * x y z triplets and NumPy .npy; and the X3P writer (x3p.c).
 *
 * Every reader returns the same record: a regular grid of heights in metres, row-major with x
 * fastest (z[j*nx + i] is the height at x = x0 + i*dx, y = y0 + j*dy; row j of the file's matrix
 * is grid row j), the lateral spacings and offsets when the file states them, and which points
 * the instrument did not measure. Invariant of a returned record: valid[k] == 0 exactly when
 * z[k] is not finite (a file's NaN/Inf is kept bit for bit; a point masked out by the file but
 * holding a finite number reads as NaN); missing = number of such points; valid == NULL when
 * missing == 0.
 *
 * Format by extension (case-insensitive) unless opt->format names one:
 *   .x3p -> x3p; .sdf -> sdf; .gsf -> gsf; .txt .asc .dat -> txt; .xyz -> xyz; .npy -> npy.
 * Spacing known from the file: x3p, sdf, gsf (XReal/YReal present), xyz (detected). Unknown
 * (txt, npy, gsf without XReal): dx = dy = 0, meaning "take the spacing from [mesh]".
 *
 * Errors: MC_ERR_IO when the file cannot be opened or read; MC_ERR_INPUT for everything about
 * the content, one line naming the file and what is wrong (empty file, not this format, truncated
 * or corrupt zip, missing main.xml, MD5 mismatch, XML with a DTD declaring entities or an
 * external subset, sizes that disagree with the data, absurd dimensions, irregular xyz grid);
 * MC_ERR_NOMEM. On any error *out is left empty (all zero; nothing to free).
 */
#ifndef MC_SURFACE_FILE_H
#define MC_SURFACE_FILE_H

#include <stddef.h>

#include "core/error.h"

/* Largest grid any reader accepts: nx*ny <= 2^28 points (2 GiB of doubles). */
#define MC_SURFACE_MAX_POINTS (1L << 28)

typedef struct {
    int nx, ny;           /* points along x (fastest) and y, >= 1 */
    double dx, dy;        /* lateral spacing [m]; 0 = not stated by the file */
    double x0, y0;        /* coordinates of point (0, 0) [m] as the file states them, else 0 */
    double *z;            /* ny*nx heights [m], mc_malloc'ed, owned */
    unsigned char *valid; /* ny*nx flags, 1 = measured; NULL = all valid; owned */
    long missing;         /* number of points with valid == 0 */
    char format[16];      /* "x3p", "sdf", "gsf", "txt", "xyz" or "npy" */
    char warning[320];    /* "" or one line naming what the reader read in a way another reader
                             may not (an X3P's CZ Increment ignored for float heights) */
} mc_surface_data;

typedef struct {
    const char *format;  /* NULL or "" = by the file's extension */
    double units;        /* metres per file unit for formats without units of their own (txt, xyz:
                            x, y and z; npy: z); 0 = metres. Ignored by x3p, sdf, gsf. */
    int verify_checksum; /* X3P MD5 checksums: 1 = a mismatch is an error (the default), 0 = not
                            checked */
} mc_surface_read_options;

/* The defaults: format by extension, units metres, checksums verified. */
mc_surface_read_options mc_surface_read_defaults(void);

/* Read path into *out (opt NULL = defaults). Returns MC_OK or an error as described above. */
int mc_surface_file_read(const char *path, const mc_surface_read_options *opt,
                         mc_surface_data *out, mc_error *err);

/* Parse an in-memory image of a file (for the fuzzers and tests): format as in the options
 * (required here: no extension to go by), what = name used in messages. Reads only
 * buf[0..len), no terminator needed. */
int mc_surface_parse_buffer(const char *format, const unsigned char *buf, size_t len,
                            const char *what, const mc_surface_read_options *opt,
                            mc_surface_data *out, mc_error *err);

/* The format name for path's extension ("x3p", ...), or NULL when the extension is unknown. */
const char *mc_surface_format_from_path(const char *path);

/* Free what *s owns and zero it (safe on a zeroed record, and twice). */
void mc_surface_data_free(mc_surface_data *s);

/* Write s as an X3P file (ISO 25178-72): main.xml (Record1 SUR with incremental x, y axes of
 * s->dx, s->dy and offsets s->x0, s->y0; absolute z in float64 'D', increment 1, offset 0;
 * Record2 date, creator, instrument "microcontact"; Record3 bindata/data.bin with its MD5 and,
 * when some point is invalid (valid[k] == 0 or z[k] not finite), bindata/valid.bin, one bit per
 * point, least significant bit first, 1 = valid, with its MD5; Record4 md5checksum.hex holding
 * the MD5 of main.xml). Heights are written as given, little-endian; increments and offsets with
 * 17 significant digits, so reading the file back gives bit-identical z, dx, dy, x0, y0.
 * creator: free text for Record2 (NULL = "microcontact"). The date is the current UTC time, or
 * SOURCE_DATE_EPOCH when set (reproducible files). Writes path.tmp then renames it over path: a
 * failure leaves no file. MC_ERR_INPUT (dx or dy not > 0, bad size, offsets not finite),
 * MC_ERR_IO naming the path, MC_ERR_NOMEM. */
int mc_x3p_write(const char *path, const mc_surface_data *s, const char *creator, mc_error *err);

#endif
