/* dfft.h - the zero-padded real 2-D FFT of padfft.h distributed over the run's ranks
 * (core/dist.h; an MPI build, -DMC_MPI): the transforms of the elastic operator's fft backend
 * under mpirun.
 *
 * FFTW-MPI's slab layout. A field of nx x ny cells (row-major, x fastest) is zero-padded to
 * tx x ty as in padfft.h. Forward: each rank transforms its block of the ny data rows along x
 * (r2c of length tx, hx = tx/2 + 1 values per row); FFTW-MPI's transpose
 * (fftw_mpi_plan_many_transpose, blocks of fftw_mpi_local_size_many_transposed) turns the
 * ny x hx row spectra into slabs along x: rank r holds the columns kx = k0 .. k0 + nk - 1, each
 * of ny values, zero-padded to ty and transformed along y (c2c of length ty). The spectrum stays
 * distributed: nk x ty complex values per rank, [kx - k0][ky]. Inverse: the columns backward, of
 * which only the ny data rows are kept (pruned, as padfft.h prunes a free y axis), the transpose
 * back, the rows backward (c2r) cropped to nx, and the rows gathered on every rank
 * (MPI_Allgatherv): every rank ends with the whole field. Per transform pair the ranks exchange
 * 2 x 16 ny hx bytes in the transposes and 8 nx ny in the gather.
 *
 * The same bits on any number of ranks: every line (row or column) is copied into one aligned
 * scratch line and transformed by the same one-line FFTW_ESTIMATE plan, whichever rank does it;
 * the transposes and the gather only move values. Against padfft.h (plans over many lines, the
 * 2-D plan of a periodic grid) the numbers differ by round-off only. The plans are always
 * FFTW_ESTIMATE: a measured plan could differ from rank to rank, and the ranks' replicated
 * arrays with it. One thread per rank (the ranks are the parallelism).
 *
 * Without MC_MPI the functions exist but mc_dfft_create refuses (MC_ERR_INTERNAL).
 * Every function but mc_dfft_table and the accessors is collective: all ranks call it.
 */
#ifndef MC_DFFT_H
#define MC_DFFT_H

#include <fftw3.h>
#include <stddef.h>

#include "core/error.h"

typedef struct mc_dfft mc_dfft;

/* The transposes of the engines made from now on. When every rank of the communicator shares
 * one node's memory (MPI_COMM_TYPE_SHARED) the row and column buffers live in POSIX shared
 * memory (one segment per rank in /dev/shm, its pages reserved when made, its name removed as
 * soon as every rank has mapped it) and each rank copies its part of the transpose straight out
 * of the other ranks' buffers: one
 * copy per element and two barriers, instead of FFTW-MPI's local rearrangements around an
 * all-to-all (which on this 2-core machine cost as much with two ranks as the whole local
 * transpose with one; theory.md §3.8). Across nodes, or after mc_dfft_shared_transposes(0),
 * FFTW-MPI's transposes; also when a segment cannot be made or mapped on any rank (no room in
 * /dev/shm, ...), which every rank then agrees on. Both move the same values: the same bits.
 * Unlike MPI-3 shared windows (whose failure on one rank left the others waiting in OpenMPI
 * 4.1, and whose release is collective) nothing here can hang or needs the other ranks to
 * release. Returns the previous
 * setting (1 by default); call it on every rank alike. Without MC_MPI: 0, no effect. */
int mc_dfft_shared_transposes(int on);

/* Which transposes the engines made so far in this process use: MC_DFFT_TRANSPOSES_SHARED,
 * MC_DFFT_TRANSPOSES_FFTW (across nodes, switched off, or the MPI library could not make the
 * shared windows, e.g. no room in its backing directory), both, or 0 (none made). For the
 * run's report line. */
enum { MC_DFFT_TRANSPOSES_SHARED = 1, MC_DFFT_TRANSPOSES_FFTW = 2 };
int mc_dfft_transposes_used(void);

/* Tests: with on != 0 this rank cannot make its shared segment, as when /dev/shm is full; every
 * rank then falls back to FFTW-MPI's transposes alike. */
void mc_dfft_refuse_shared(int on);

/* 1 when d's transposes go through shared memory, 0 when FFTW-MPI's. */
int mc_dfft_is_shared(const mc_dfft *d);

/* Plan for an nx x ny field padded to tx x ty (tx >= nx, ty >= ny) over the run's communicator.
 * *out is NULL on failure. MC_OK, MC_ERR_NOMEM (allocation or planning) or MC_ERR_INTERNAL (no
 * MPI build or no communicator, FFTW threads). Collective. */
int mc_dfft_create(int nx, int ny, int tx, int ty, mc_dfft **out, mc_error *err);
void mc_dfft_destroy(mc_dfft **d); /* frees and sets *d = NULL; NULL-safe */

/* Doubles of this rank's part of a spectrum: 2 nk ty (0 on a rank without columns). */
size_t mc_dfft_spectrum_len(const mc_dfft *d);

/* The engine's own spectrum (mc_dfft_spectrum_len doubles): mc_dfft_inverse reads it. */
fftw_complex *mc_dfft_spectrum(mc_dfft *d);

/* The field, zero-padded, forward into spec (this rank's part; the engine's spectrum or an array
 * of as many doubles). local = 0: field is whole (nx*ny, the same on every rank; each reads its
 * rows); local = 1: field holds this rank's rows only (nr*nx values, data row r0 + r at r*nx: a
 * slab, mc_dfft_rows). Collective. */
void mc_dfft_forward(mc_dfft *d, const double *field, fftw_complex *spec, int local);

/* The engine's spectrum backward (unnormalised: the caller scales), cropped to nx x ny: into out
 * whole on every rank (local = 0: the rows gathered), or into this rank's rows only, laid out as
 * mc_dfft_forward's local field (local = 1: out holds nr*nx values, no gather; a solver that
 * keeps to its rows saves the 8 nx ny bytes and the whole array). Destroys the spectrum.
 * Collective. */
void mc_dfft_inverse(mc_dfft *d, double *out, int local);

/* ---- batches: m fields through one transpose each way and one gather -------------------------
 * Fewer collectives (each a latency, and on a shared machine a wait for the other ranks to be
 * scheduled): the m fields' row spectra are interleaved (FFTW-MPI's howmany = 2 m) and moved by
 * one transpose; every line is still transformed alone by the same one-line plans, so a batch
 * gives the bits of m single transforms. Buffers m times the single engine's. */

/* An engine for batches of up to m >= 1 fields (mc_dfft_create is m = 1; the single-field
 * functions above work on m = 1 engines only). Collective. */
int mc_dfft_create_many(int nx, int ny, int tx, int ty, int m, mc_dfft **out, mc_error *err);

/* m fields (<= the engine's m), whole on every rank, field f at fields + f * stride (nx*ny
 * values each), forward into spec + f * sstride (complex values; each mc_dfft_spectrum_len / 2
 * of them: this rank's columns, [kx - k0][ky]). Collective. */
void mc_dfft_forward_many(mc_dfft *d, const double *fields, size_t stride, int m,
                          fftw_complex *spec, size_t sstride);

/* m spectra (spec + f * sstride, destroyed) backward, unnormalised, cropped to nx x ny and
 * gathered whole on every rank into out + f * stride (stride >= nx*ny). Collective. */
void mc_dfft_inverse_many(mc_dfft *d, fftw_complex *spec, size_t sstride, int m, double *out,
                          size_t stride);

/* The same without the gather: only this rank's rows (mc_dfft_rows) of each field are written,
 * at their places in out + f * stride; the other rows of out are not touched (a loop that keeps
 * to its rows, plastic/loop.c). Collective (the transposes). */
void mc_dfft_inverse_many_rows(mc_dfft *d, fftw_complex *spec, size_t sstride, int m,
                               double *out, size_t stride);

/* What mc_dfft_bytes gives for an engine of m fields (mc_dfft_estimate is m = 1), the pages of
 * mc_dfft_peer_bytes included. */
size_t mc_dfft_estimate_many(int nx, int ny, int tx, int ty, int m, int p, int r);

/* The other ranks' buffer pages that rank r of p reads in the shared transposes (resident in its
 * process too, so its peak counts them: (p - 1) / p^2 of the two buffers of the whole transform
 * and a page per line); 0 with FFTW-MPI's transposes (mc_dfft_shared_transposes(0)) or p < 2.
 * For the memory guard's models of the engines it does not build (pipeline/memguard.c). */
size_t mc_dfft_peer_bytes(int ny, int tx, int m, int p, int r);

/* This rank's data rows r0 .. r0 + nr - 1 (of ny): the rows mc_dfft_forward reads. */
void mc_dfft_rows(const mc_dfft *d, int *r0, int *nr);

/* This rank's spectrum columns k0 .. k0 + nk - 1 (of tx/2 + 1; nk may be 0). */
void mc_dfft_columns(const mc_dfft *d, int *k0, int *nk);

/* Bytes held by the engine (its transpose buffers, spectrum and lines; FFTW's plans aside). */
size_t mc_dfft_bytes(const mc_dfft *d);

/* What mc_dfft_bytes gives on rank r of p for an nx x ny field padded to tx x ty, from the sizes
 * alone (FFTW-MPI's default blocks, mc_dfft_split). Not collective; any build. */
size_t mc_dfft_estimate(int nx, int ny, int tx, int ty, int p, int r);

/* The columns of n that FFTW-MPI's default block gives rank r of p (blocks of ceil(n / p), the
 * last ones short or empty): what mc_dfft_columns returns for n = tx/2 + 1, computed from the
 * sizes alone (memory estimates). Not collective; any build. */
void mc_dfft_split(int n, int p, int r, int *first, int *count);

/* This rank's part of the spectrum of a whole ty x tx table (wrap-around layout, on every rank)
 * into spec, by the same line transforms; local (no communication): each rank transforms all ty
 * rows once. Not collective. */
void mc_dfft_table(mc_dfft *d, const double *table, fftw_complex *spec);

/* The rows j0 .. j0 + nj - 1 of a ty x tx table this rank tabulates for mc_dfft_table_rows
 * (blocks of ceil(ty / P) rows). Not collective. */
void mc_dfft_table_split(const mc_dfft *d, int *j0, int *nj);

/* mc_dfft_table from each rank's rows alone: rows holds this rank's table rows (mc_dfft_table_split)
 * at a stride of 2 (tx/2 + 1) doubles (row j0 + r at r * 2 (tx/2 + 1); the room of its spectrum,
 * which overwrites it). Each rank transforms its rows along x, an all-to-all brings every rank
 * its columns (16 bytes a table row and column, (P - 1)/P of it sent), then its columns along y:
 * the same bits as mc_dfft_table, a P-th of the work and of the table's memory on each rank.
 * MC_OK, or MC_ERR_NOMEM on every rank alike. Collective. */
int mc_dfft_table_rows(mc_dfft *d, double *rows, fftw_complex *spec);

#endif
