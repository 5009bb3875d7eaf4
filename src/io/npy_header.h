/* npy_header.h - the preamble and header dict of a NumPy .npy image, shared by the strict float64
 * reader (mc_npy_parse) and the general one (mc_npy_parse_any) in npy.c.
 *
 * Format: "\x93NUMPY", major, minor, header length (uint16 LE for 1.0, uint32 LE for 2.0/3.0),
 * then a Python dict literal {'descr': ..., 'fortran_order': ..., 'shape': (...)} padded with
 * spaces and a newline, then the raw data. The dict is parsed with a small bounded scanner (never
 * a NUL-terminated string function on the input) because both readers are fuzzed.
 */
#ifndef MC_NPY_HEADER_H
#define MC_NPY_HEADER_H

#include <stddef.h>

#include "core/error.h"

#define MC_NPY_MAX_RANK 64 /* NumPy's own limit (NPY_MAXDIMS) */

typedef struct {
    const unsigned char *descr; /* the dtype string (points into the image), unless a list */
    size_t descr_len;
    int descr_is_list;          /* structured dtype ('descr' is a list) */
    int fortran;                /* fortran_order True */
    int rank;                   /* number of dimensions, 0..MC_NPY_MAX_RANK */
    long long dim[MC_NPY_MAX_RANK]; /* each <= INT_MAX + a digit when dim_big */
    int dim_big;                /* some dimension exceeds INT_MAX */
    const unsigned char *data;  /* first byte after the header */
    size_t data_len;            /* bytes of data after the header */
} mc_npy_header;

/* Parse the preamble and header dict of buf[0..len). what = name used in messages. MC_ERR_INPUT
 * (no magic: "not a NumPy .npy file"; unsupported version; truncated; malformed dict) naming
 * what and the problem. Allocates nothing; *h points into buf. */
int mc_npy_header_parse(const unsigned char *buf, size_t len, const char *what, mc_npy_header *h,
                        mc_error *err);

/* The shape as Python writes it, e.g. "(2, 3)" or "(6,)", for messages. */
void mc_npy_shape_text(char *out, size_t outlen, const mc_npy_header *h);

/* A printable, bounded copy of untrusted bytes for an error message (non-printable -> '?'). */
void mc_npy_printable(char *out, size_t outlen, const unsigned char *s, size_t n);

#endif
