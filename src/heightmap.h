/* heightmap.h - measured or external 2-D maps: .npy (float64) or a plain whitespace text matrix
 * (one row per line, '#' comments allowed). Used for roughness height maps and prescribed
 * pressure maps. */
#ifndef MC_HEIGHTMAP_H
#define MC_HEIGHTMAP_H

#include <stddef.h>

#include "error.h"

/* Read path as .npy (by magic bytes) or as a text matrix. Checks rows == ny and cols == nx when
 * ny, nx > 0 and that all values are finite. *data is mc_malloc'ed (caller mc_free's).
 * Errors: MC_ERR_IO (cannot open/read), MC_ERR_INPUT (format, shape, NaN), naming the file and,
 * for text, the line. */
int mc_heightmap_read(const char *path, int ny, int nx, double **data, mc_error *err);

/* Parse an in-memory text matrix (for the fuzzer and tests). */
int mc_text_matrix_parse(const char *text, size_t len, const char *what, double **data, int *rows,
                         int *cols, mc_error *err);

#endif
