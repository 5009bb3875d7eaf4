/* dist.h - the ranks of a run: the MPI communicator the distributed transforms use.
 *
 * A build with -DMC_MPI (bin/microcontact-mpi, README "Running on a cluster") runs as P
 * processes under mpirun. The front end (cli/) initialises MPI and hands the run's communicator
 * over with mc_dist_set; the numerics ask for it here, never for the scene: today the elastic
 * operator's fft backend (operator/dfft.h) splits its transforms over the ranks, the contact
 * solvers' iterations keep to the operator's rows (contact_internal.h, the row-split calls
 * below), the plastic loop splits its elastic stress layers and its sweeps' return maps
 * (mc_dist_share, mc_dist_gather_blocks), every other stage computes the same replicated arrays
 * on every rank. Without MC_MPI,
 * and before mc_dist_set, there is one rank and nothing is distributed.
 *
 * Process-wide like the thread count (threads.h): set once by the front end, read by the plans;
 * every rank must make the same calls in the same order (the transforms are collective).
 */
#ifndef MC_DIST_H
#define MC_DIST_H

#include <stddef.h>

#include "core/error.h"

#ifdef MC_MPI
#include <mpi.h>

/* The run's communicator (MPI_COMM_NULL: none, the default). Not owned; must stay valid while
 * plans made under it live. Call from one thread, between runs. */
void mc_dist_set(MPI_Comm comm);
MPI_Comm mc_dist_comm(void);
#endif

/* 1 when plans made now distribute their transforms (an MPI build with a communicator set). */
int mc_dist_active(void);

/* Ranks of the run's communicator (1 without one) and this process's rank (0 without one). */
int mc_dist_size(void);
int mc_dist_rank(void);

/* Rank 0's v on every rank (v unchanged without a communicator): a decision only rank 0 can
 * make (it writes the files), shared so that all ranks go on alike. Collective. */
int mc_dist_root_int(int v);

/* Rank 0's read of one input file, shared with every rank (the inputs of a run are read on rank
 * 0 alone, README "Running on a cluster"; io/file.h, pipeline/checkpoint.c). Collective. Rank 0
 * passes the status rc of its read and, when rc is MC_OK, the bytes it read (*buf mc_malloc'ed,
 * *len bytes followed by a NUL); the other ranks' rc, *buf and *len are not read. On return every
 * rank holds rank 0's status: on failure rank 0's message in *err (*buf NULL, *len 0), on
 * success a NUL-terminated copy of the bytes in its own mc_malloc'ed *buf. A rank that cannot
 * allocate its copy makes every rank fail alike (MC_ERR_NOMEM naming path, the rank and the
 * size; rank 0's buffer freed), so no rank goes on alone. Without a communicator: rc, nothing
 * touched. */
int mc_dist_share_read(int rc, unsigned char **buf, size_t *len, const char *path, mc_error *err);

/* The largest v over the ranks (v without a communicator): a status every rank must share before
 * the next collective step. Collective. */
int mc_dist_max_int(int v);

/* n values of v from rank root to every rank (nothing without a communicator). Collective. */
void mc_dist_bcast(double *v, size_t n, int root);

/* Seconds this process has spent in the distributed transforms' and stages' communication
 * (transposes, gathers, broadcasts: MPI_Wtime around them, waiting for the other ranks
 * included) since the process started; 0 without MPI. mc_dist_comm_add adds to it. */
double mc_dist_comm_seconds(void);
void mc_dist_comm_add(double s);

/* CPU seconds of this process (all its threads) so far, and those spent in the communication
 * steps timed by mc_dist_comm_begin / _end (the MPI library's polling while it waits included):
 * the CPU outside communication is the process's work, a figure the machine's load does not
 * inflate as it does the wall time. */
double mc_dist_cpu_seconds(void);
double mc_dist_comm_cpu_seconds(void);

/* A communication step: mc_dist_comm_end(mc_dist_comm_begin() before it) adds its wall time to
 * mc_dist_comm_seconds and its CPU time to mc_dist_comm_cpu_seconds. */
typedef struct {
    double wall, cpu;
} mc_dist_mark;
mc_dist_mark mc_dist_comm_begin(void);
void mc_dist_comm_end(mc_dist_mark m);

/* Wall clock of MPI (MPI_Wtime; 0 without MPI), for mc_dist_comm_add. */
double mc_dist_clock(void);

/* The maximum over the ranks of each of v[0..n) (unchanged without a communicator). Collective. */
void mc_dist_max(double *v, int n);

/* ---- fields split by rows (the slabs of operator/dfft.h) ----------------------------------
 * A field of ny rows of nx values whose rows r0 .. r0 + nr - 1 this rank computes (the ranks'
 * row ranges ascending with the rank, together 0 .. ny - 1, as FFTW-MPI hands them out). */

/* Sums over such a field that give the same bits on any number of ranks and threads: the caller
 * sums each of its rows in index order, m quantities per row, into part[r * m + k] (its row
 * r0 + r); the row sums of all ranks are gathered into all (room for ny * m doubles) and added in
 * row order: out[k] = sum over the ny rows. Without a communicator part holds all the rows and
 * all is not used. Collective. */
int mc_dist_row_totals(const double *part, int nr, int ny, int m, double *all, double *out);

/* Every rank's rows of v (ny * nx values) to every rank: v whole on each. Collective. */
int mc_dist_gather_rows(double *v, int r0, int nr, int nx);
int mc_dist_gather_rows_u8(unsigned char *v, int r0, int nr, int nx);

/* The same from a slab: mine holds this rank's rows alone (nr * nx values, row r0 + r at r * nx);
 * whole (ny * nx) receives every rank's rows on every rank. Without a communicator mine is
 * copied to its rows of whole. Collective. */
int mc_dist_gather_slab(const double *mine, double *whole, int r0, int nr, int nx);
int mc_dist_gather_slab_u8(const unsigned char *mine, unsigned char *whole, int r0, int nr,
                           int nx);

/* This rank's even share of n items split in order over the ranks: *first .. *first + *count - 1
 * (rank r holds r n / P .. (r + 1) n / P - 1: ascending with the rank, sizes within one; a rank
 * may hold none when n < P). Without a communicator: 0 and n. Not collective. */
void mc_dist_share(int n, int *first, int *count);

/* Every rank's rows r0 .. r0 + nr - 1 of each of nblocks blocks of ny rows of nx values (v holds
 * the blocks one after the other, nblocks * ny * nx values; block b's row r at (b ny + r) nx) to
 * every rank: v whole on each, in place, one collective call whatever nblocks (an MPI vector type
 * picks the rank's rows out of every block). The split fields of the plastic loop: the six
 * components x nz layers of an increment by rows of y (src/plastic/loop.c), the six components of
 * the elastic stresses by layers (stress.h mc_stress_field_split). Collective. */
int mc_dist_gather_blocks(double *v, int nblocks, int ny, int nx, int r0, int nr);

/* The row-split calls return 1, or 0 (the totals NaN, nothing gathered) when the run has more
 * than MC_DIST_MAX_RANKS ranks or a count exceeds MPI's int counts (the front end refuses such
 * runs first). */
#define MC_DIST_MAX_RANKS 4096

#endif
