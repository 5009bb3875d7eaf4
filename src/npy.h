/* npy.h - NumPy .npy files (format 1.0 written; 1.0, 2.0 and 3.0 read). */
#ifndef MC_NPY_H
#define MC_NPY_H

#include <stddef.h>

#include "error.h"

/* Read a 2-D little-endian float64 C-order array ("<f8", fortran_order False). Fills *rows (ny),
 * *cols (nx) and *data (mc_malloc'ed; caller frees with mc_free). 1-D arrays are read as 1 x n.
 * Any other dtype, order, rank, a truncated file or NaN/Inf values -> MC_ERR_INPUT naming the file
 * and what is accepted; unreadable -> MC_ERR_IO. */
int mc_npy_read(const char *path, double **data, int *rows, int *cols, mc_error *err);

/* Write a float64 array of ndim (1..3) dimensions, C order, format 1.0. Writes path.tmp then
 * renames it over path, so a failure leaves no half-written file. */
int mc_npy_write(const char *path, const double *data, int ndim, const size_t *shape, mc_error *err);

/* Parse an in-memory .npy image (for the fuzzer and tests); what = name used in messages. */
int mc_npy_parse(const unsigned char *buf, size_t len, const char *what, double **data, int *rows,
                 int *cols, mc_error *err);

#endif
