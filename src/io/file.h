/* file.h - whole files into memory: the one file reader of the library (case files, height
 * maps, .npy, measured surfaces, hardening tables).
 *
 * Under mpirun (bin/microcontact-mpi, a communicator set in core/dist.h) these calls are
 * collective: rank 0 alone opens and reads the file and every rank receives its bytes, or its
 * error with rank 0's message (mc_dist_share_read), so the inputs need not be visible to the
 * other ranks and every rank fails alike. Every rank must make the same calls in the same order
 * (the run's stages are replicated, so they do). Without a communicator the read is the
 * process's own. */
#ifndef MC_FILE_H
#define MC_FILE_H

#include <stddef.h>

#include "core/error.h"

/* Read a whole data file into memory. *buf is mc_malloc'ed with len + 1 bytes, the last one a NUL
 * not counted in *len. MC_ERR_IO naming path and strerror, or MC_ERR_NOMEM; MC_ERR_INPUT for a
 * device, FIFO or socket, or a file beyond MC_FILE_MAX_SURFACE (core/fileguard.h): nothing reads
 * forever. */
int mc_io_read_file(const char *path, unsigned char **buf, size_t *len, mc_error *err);

/* The same, naming what the file should be ("a surface file") and with its own limit. */
int mc_io_read_data(const char *path, size_t max_bytes, const char *what, unsigned char **buf,
                      size_t *len, mc_error *err);

/* Any file, a stream too (the case file may come through a pipe), with a size limit (0 = none): a larger file, or a device that never ends, is
 * MC_ERR_INPUT "PATH: larger than N MiB; not WHAT" (what, e.g. "a case file"). */
int mc_io_read_limited(const char *path, size_t max_bytes, const char *what, unsigned char **buf,
                         size_t *len, mc_error *err);

#endif
