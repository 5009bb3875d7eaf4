/* threads.h - the thread count of a run: OpenMP loops and FFTW transforms.
 *
 * OpenMP and FFTW keep their thread counts per process, so a run that asks for n threads sets
 * them for its own duration only: mc_threads_begin(n) at the start, mc_threads_end() at the end
 * restores what was there before (the pipeline does this; suites and benches that want a count
 * do the same). Nothing else in the library changes the thread count.
 */
#ifndef MC_THREADS_H
#define MC_THREADS_H

#include "core/error.h"

/* Transforms and loops smaller than this many values run on one thread: below it a thread team
 * costs more than it saves (64 x 64 transforms: 20 us on one thread, 30 us on two), and on a
 * machine whose cores are busy with other work, fine-grained synchronisation of small loops
 * made a 141 x 141 capped contact 250 times slower (73 s instead of 0.3 s, measured). */
#define MC_THREADS_MIN_CELLS (1 << 18)

/* The contact solvers' per-cell loops (a few flops per cell, no transform) on more than this many
 * cells run on the run's threads. Lower than MC_THREADS_MIN_CELLS: on 512 x 256 cells those loops
 * were a quarter of a running-in step's serial work (theory §8.10); a loop of 2^16 cells takes
 * about 30 us, a sleeping team's barrier a few. Their sums are the same bits on any thread count
 * (mc_contact_totals). */
#define MC_THREADS_MIN_LOOP (1 << 16)

/* Saved state of mc_threads_begin, for mc_threads_end. */
typedef struct {
    int previous; /* the count before begin (0: the OpenMP default) */
} mc_threads_scope;

/* Use n threads (n <= 0: the OpenMP default, i.e. OMP_NUM_THREADS if set, else all cores) until
 * the matching mc_threads_end. Scopes nest. Call before planning. */
void mc_threads_begin(int n, mc_threads_scope *scope);
void mc_threads_end(const mc_threads_scope *scope);

/* The thread count in force. */
int mc_threads_count(void);

/* Initialise FFTW's threads once (the first call) and set the planner's thread count to
 * mc_threads_count(). Every module calls it before creating an FFTW plan; FFTW's planner is not
 * thread-safe, so plan from one thread only. MC_OK or MC_ERR_INTERNAL. */
int mc_fftw_prepare(mc_error *err);

#endif
