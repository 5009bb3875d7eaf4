/* npy.h - NumPy .npy files (format 1.0 written; 1.0, 2.0 and 3.0 read).
 *
 * Two readers. mc_npy_read / mc_npy_parse (the contact pipeline's maps) accept: dtype '<f8'
 * only (little-endian IEEE float64; '>f8', '=f8', '|f8', other widths, integers and structured
 * dtypes are refused), fortran_order False, rank 1 or 2, no empty dimension, exactly rows*cols*8 bytes of data after the header, every value finite.
 * The header dict may list its keys in any order, with any spacing, single or double quotes,
 * a trailing comma, and Python 2 style "3L" integers in the shape.
 * mc_npy_parse_any (measured surfaces, see surface_file.h) takes any float or integer dtype in
 * either byte order and either memory order, with the same header rules.
 */
#ifndef MC_NPY_H
#define MC_NPY_H

#include <stddef.h>

#include "core/error.h"
#include "io/file.h" /* mc_io_read_file, which used to live here */

/* Read a 2-D little-endian float64 C-order array ("<f8", fortran_order False). Fills *rows (ny),
 * *cols (nx) and *data (mc_malloc'ed; caller frees with mc_free). 1-D arrays are read as 1 x n.
 * Any other dtype, order, rank, a truncated file or NaN/Inf values -> MC_ERR_INPUT naming the file
 * and what is accepted; unreadable -> MC_ERR_IO; no memory -> MC_ERR_NOMEM. */
int mc_npy_read(const char *path, double **data, int *rows, int *cols, mc_error *err);

/* Write a float64 array of ndim (1..3) dimensions, C order, format 1.0 (header padded with
 * spaces to a multiple of 64 bytes including its final newline, as NumPy does). Writes path.tmp
 * then renames it over path, so a failure leaves no half-written file (no fsync: atomic against
 * crashes of this process, not of the machine). MC_ERR_INPUT for a bad ndim/shape/path,
 * MC_ERR_IO when writing fails (the message names path and strerror). Allocates nothing. */
int mc_npy_write(const char *path, const double *data, int ndim, const size_t *shape, mc_error *err);

/* Parse an in-memory .npy image (for the fuzzer and tests); what = name used in messages.
 * Reads only buf[0..len) (no terminator needed) and never overflows a size computation. */
int mc_npy_parse(const unsigned char *buf, size_t len, const char *what, double **data, int *rows,
                 int *cols, mc_error *err);

/* General reader for measured surfaces: any of the dtypes f2 f4 f8 i1 i2 i4 i8 u1 u2 u4 u8,
 * little- ('<') or big-endian ('>'; '|' for one-byte types), fortran_order True or False, rank 1
 * (read as 1 x n) or 2. Values are converted to double in C order (*data[j*cols + i] = element
 * (j, i)); 64-bit integers beyond 2^53 round to the nearest double. Non-finite values are kept as
 * they are (the caller decides what they mean). Reads only buf[0..len). MC_ERR_INPUT naming what
 * and the problem (no magic: "not a NumPy .npy file"; dtype, rank, size), MC_ERR_NOMEM. */
int mc_npy_parse_any(const unsigned char *buf, size_t len, const char *what, double **data,
                     int *rows, int *cols, mc_error *err);


#endif
