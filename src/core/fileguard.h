/* fileguard.h - what every reader checks before it opens a file the user named: the file is a
 * regular file (not a device, FIFO or socket, which may never end or block on open: /dev/zero as
 * a surface file read until memory ran out) and not larger than the reader's limit.
 *
 * In core/ (not io/) because readers of every layer use it: io/ (surface files, .npy, text
 * maps), operator/ (FFTW wisdom, read by FFTW itself), plastic/ (hardening tables), pipeline/
 * (checkpoints). */
#ifndef MC_FILEGUARD_H
#define MC_FILEGUARD_H

#include <stddef.h>

#include "core/error.h"

/* Limits of the readers, bytes. A surface file holds at most 2^28 points; text spends up to
 * about 30 bytes a point. */
#define MC_FILE_MAX_SURFACE ((size_t)8 << 30)   /* surface files, .npy, text height maps */
#define MC_FILE_MAX_TABLE ((size_t)16 << 20)    /* hardening tables: a few hundred rows */
#define MC_FILE_MAX_WISDOM ((size_t)64 << 20)   /* FFTW wisdom: a few kB per plan */
#define MC_FILE_MAX_CHECKPOINT ((size_t)64 << 30) /* a checkpoint: the fields of a run */

/* MC_OK when path is a regular file of at most max_bytes (0 = no limit), or a directory or a
 * path that does not exist (the caller's open or read then reports it in its own words).
 * Otherwise MC_ERR_INPUT: "PATH: not a regular file (a character device); WHAT must be a
 * regular file" or "PATH: N bytes, larger than M MiB; not WHAT" (what, e.g. "a surface file"). */
int mc_file_guard(const char *path, size_t max_bytes, const char *what, mc_error *err);

#endif
