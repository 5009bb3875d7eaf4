/* outdir.h - the output directory of a run: checked without being created, created only when
 * results are committed, and held by one run at a time.
 *
 * One run per directory: a run holds an exclusive flock(2) on the directory itself (an open
 * descriptor of DIR, no lock file) from the moment the directory exists for it - at the start of
 * the run when DIR already exists, else when the results are committed - until it ends; the
 * kernel releases the lock when the process dies, whatever kills it. A second run refuses at once
 * (MC_ERR_ENV) with a message naming DIR and the holder's pid (from /proc/locks; "pid unknown"
 * where that is not readable). It does not wait. On file systems without flock support the run
 * goes on unlocked.
 *
 * Staging areas: results are written into DIR/.staging-XXXXXX (mkdtemp) and renamed into DIR
 * (output.c). Only the lock holder stages, so every staging area the holder finds is a leftover
 * of a run that was killed (SIGKILL, a power cut): mc_outdir_sweep removes them. It removes only
 * what this program creates - directories named exactly ".staging-" and 6 letters or digits, and
 * in them only the result files named by the caller (and their ".tmp" siblings); anything else
 * stays, and with it the directory - plus regular files ".mc-probe-XXXXXX" of earlier versions.
 */
#ifndef MC_OUTDIR_H
#define MC_OUTDIR_H

#include <stddef.h>

#include "core/error.h"

#define MC_OUTDIR_PATH_MAX 4096
#define MC_OUTDIR_MAX_MADE 64 /* directories one run may create (deeper ones are not removed) */

typedef struct {
    char path[MC_OUTDIR_PATH_MAX]; /* DIR as given */
    int fd;                        /* open descriptor of DIR, flock'ed; -1 when not held */
    int nmade;                     /* directories this run created, outermost first ... */
    size_t made[MC_OUTDIR_MAX_MADE]; /* ... as lengths of prefixes of path */
} mc_outdir;

/* A released, empty handle (fd = -1). Always call before the other functions. */
void mc_outdir_init(mc_outdir *d);

/* Check that DIR can be created and written, creating nothing: every existing prefix of DIR is a
 * directory (a symbolic link is followed; a dangling one is named as such), and DIR, or the
 * deepest existing ancestor when DIR is missing, is writable and searchable. Then, when DIR
 * exists, take its lock (refused: MC_ERR_ENV as above). Fills d->path. MC_ERR_INPUT for an empty
 * or too long path; MC_ERR_ENV naming the path and the reason otherwise. */
int mc_outdir_open(mc_outdir *d, const char *dir, mc_error *err);

/* Make DIR exist and hold its lock: creates the missing directories (mkdir -p; each one it made
 * is recorded for mc_outdir_rollback), then locks DIR unless the handle holds it already (and DIR
 * is still the directory it holds). MC_ERR_ENV (cannot create, not a directory, held by another
 * run); nothing is left created on failure. */
int mc_outdir_acquire(mc_outdir *d, mc_error *err);

/* Remove stale staging areas and probe files in DIR (see above). names[0..n) are the result
 * file names that a staging area may hold. Needs the lock (does nothing without it). */
void mc_outdir_sweep(const mc_outdir *d, const char *const *names, int n);

/* Remove the directories this handle created, innermost first, while they are empty (results
 * were not committed). Only with the lock held. */
void mc_outdir_rollback(mc_outdir *d);

/* Release the lock (close DIR); the created directories stay. Idempotent. */
void mc_outdir_release(mc_outdir *d);

#endif
