/* heightmap.h - measured or external 2-D maps: .npy (float64) or a plain whitespace text matrix
 * (one row per line, '#' comments allowed). Used for roughness height maps and prescribed
 * pressure maps. Row j of the file is grid row j (y index), column i is x index i: f[j*nx + i].
 *
 * Text format: numbers separated by spaces or tabs (strtod syntax, the whole token must be a
 * number), one matrix row per line; '#' starts a comment to the end of the line; blank lines
 * are skipped; CRLF line ends and a UTF-8 byte order mark are tolerated; every data row must
 * have the same number of columns. */
#ifndef MC_HEIGHTMAP_H
#define MC_HEIGHTMAP_H

#include <stddef.h>

#include "core/error.h"

/* Read path as .npy (by the "\x93NUMPY" magic) or as a text matrix. Checks rows == ny when
 * ny > 0 and cols == nx when nx > 0, and that all values are finite. *data is mc_malloc'ed
 * (caller mc_free's). Errors: MC_ERR_IO (cannot open/read), MC_ERR_INPUT (format, shape, NaN),
 * naming the file and, for text, the line ("h.txt:7: 'x' is not a number ..."; shape:
 * "h.npy: shape 64 x 32, the mesh is 64 x 64 (ny x nx)"), MC_ERR_NOMEM. */
int mc_heightmap_read(const char *path, int ny, int nx, double **data, mc_error *err);

/* Parse an in-memory text matrix (for the fuzzer and tests): reads only text[0..len), no
 * terminator needed. what = name used in messages. */
int mc_text_matrix_parse(const char *text, size_t len, const char *what, double **data, int *rows,
                         int *cols, mc_error *err);

/* As mc_text_matrix_parse, but "nan" (any case) is accepted and kept as NaN (measured surfaces: the
 * caller marks it as a missing point). */
int mc_text_matrix_parse_any(const char *text, size_t len, const char *what, double **data,
                             int *rows, int *cols, mc_error *err);

/* 1 when s[0..n) is a decimal number in the forms a case file accepts ([+-]digits[.digits]
 * [e[+-]digits], at least one digit before the exponent); 0 for anything else, hexadecimal,
 * "inf" and "nan" included. The text readers take only these forms. */
int mc_text_is_decimal(const char *s, size_t n);

#endif
