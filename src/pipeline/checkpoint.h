/* checkpoint.h - the state of a running-in after a completed step, on disk, for --resume.
 *
 * One file, DIR/state.bin (DIR: the run's checkpoint directory, e.g. OUT/checkpoint), written
 * to DIR/state.bin.tmp, flushed to the disk (fsync) and renamed over the old one, so that DIR
 * holds either the previous complete state or the new one whatever stops the process (a signal,
 * SIGKILL, a power cut). The format is this build's (native byte order and struct layout,
 * guarded by a header that names the sizes): a checkpoint is resumed on the machine and with the
 * program that wrote it. A trailing FNV-1a 64 checksum over everything before it detects a torn
 * or altered file.
 *
 * Contents: the identity of the case (case_hash: pipeline/runin.h mc_runin_case_hash), the grid
 * and plastic volume sizes, the steps done and their runin.csv rows, the compute time so far,
 * and the material state they left: plastic strain (6 nvol, component-major), accumulated
 * equivalent plastic strain (nvol), residual stress (6 nvol, Pa) and residual displacement
 * (ny*nx, m, body 1), and the plastic step records of the run-down steps that yielded
 * (plastic.csv). nvol = 0 for an elastic material (no arrays then but u_r).
 */
#ifndef MC_CHECKPOINT_H
#define MC_CHECKPOINT_H

#include <stdint.h>

#include "core/error.h"
#include "pipeline/results.h"

#define MC_CHECKPOINT_FILE "state.bin"

typedef struct {
    uint64_t case_hash;
    int nx, ny;           /* surface grid */
    int nz;               /* plastic layers (0: elastic material) */
    long nvol;            /* nz nx ny */
    int nsteps, done;     /* steps of the whole run; completed (rows held) */
    double seconds;       /* compute time of the steps done, s */
    mc_runin_row *rows;   /* done rows (owned by a read checkpoint) */
    double *eps_p, *peq, *sig_r; /* 6 nvol, nvol, 6 nvol (NULL when nvol = 0) */
    double *u_r;          /* nx ny, m */
    int nrec;             /* plastic step records */
    mc_plastic_step *records;
} mc_checkpoint;

/* Write c into dir (created if missing, one level) atomically as described above.
 * MC_OK or MC_ERR_ENV (cannot create, write or rename: the message names the path and the
 * reason); the previous checkpoint is then intact. */
int mc_checkpoint_write(const char *dir, const mc_checkpoint *c, mc_error *err);

/* 1 when dir holds a checkpoint file (complete or not), else 0. */
int mc_checkpoint_exists(const char *dir);

/* Read dir's checkpoint into *c (arrays allocated; free with mc_checkpoint_free, also after a
 * failure). MC_OK; MC_ERR_INPUT (none there; not a checkpoint of this program or build; torn or
 * altered: the checksum differs - the message says which); MC_ERR_NOMEM. */
int mc_checkpoint_read(const char *dir, mc_checkpoint *c, mc_error *err);

void mc_checkpoint_free(mc_checkpoint *c);

/* Remove dir's checkpoint file (and a stray .tmp) and then dir itself when it is empty. */
void mc_checkpoint_remove(const char *dir);

#endif
