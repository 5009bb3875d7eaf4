/* dfft.c - the padded real 2-D FFT distributed over the run's ranks (see dfft.h). */
#include "operator/dfft.h"

#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/threads.h"

/* 0: FFTW-MPI's transposes even on one node (mc_dfft_shared_transposes) */
static int use_shared = 1;
/* the transposes the engines made so far use (mc_dfft_transposes_used) */
static int used;
/* tests: this rank's shared segment fails (mc_dfft_refuse_shared) */
static int refuse_shared;

void mc_dfft_refuse_shared(int on) { refuse_shared = on != 0; }

int mc_dfft_transposes_used(void) { return used; }

#ifdef MC_MPI
#include <fcntl.h>
#include <fftw3-mpi.h>
#include <stdatomic.h>
#include <stdio.h>
#include <sys/mman.h>
#include <unistd.h>

struct mc_dfft {
    MPI_Comm comm;
    int nx, ny, tx, ty, hx;
    ptrdiff_t nr, r0;   /* data rows of this rank: r0 .. r0 + nr - 1 (of ny) */
    ptrdiff_t nk, k0;   /* spectrum columns of this rank: k0 .. k0 + nk - 1 (of hx) */
    double *rows;       /* nr x hx complex: the row spectra (transpose input and output) */
    double *cols;       /* nk x ny complex: the columns after the transpose */
    fftw_complex *spec; /* nk x ty: the engine's spectrum */
    double *line;       /* one real row, tx */
    fftw_complex *cline; /* one complex line, max(hx, ty) */
    fftw_plan r2c, c2r, fwd, bwd; /* one line each, FFTW_ESTIMATE */
    fftw_plan tr_fwd, tr_bwd;     /* FFTW-MPI transposes ny x hx <-> hx x ny (complex pairs) */
    int *counts, *displs;         /* the gather of the output rows, in doubles per rank */
    int m;                        /* fields per batch (mc_dfft_create_many; 1: mc_dfft_create) */
    double *pack;                 /* batches: this rank's output rows, [r][f][x] */
    int *rcounts, *rdispls;       /* batches: the gather's rows per rank and first rows */
    /* all ranks on one node: rows and cols live in shared memory and the transposes copy
     * straight from the other ranks' buffers (shared_transpose); else FFTW-MPI's */
    int shared;
    double **seg;     /* every rank's segment (its rows, then its cols), mapped here */
    int nseg;         /* ranks (entries of seg) */
    size_t seg_bytes; /* bytes of each segment */
    size_t nbuf;      /* doubles from a segment's rows to its cols (the ranks' largest nbuf) */
    int *lay;         /* every rank's r0, nr, k0, nk */
};

static void unmap_segments(mc_dfft *d);

int mc_dfft_shared_transposes(int on)
{
    const int was = use_shared;
    use_shared = on != 0;
    return was;
}

void mc_dfft_destroy(mc_dfft **pd)
{
    if (!pd || !*pd)
        return;
    mc_dfft *d = *pd;
    fftw_plan plans[] = {d->r2c, d->c2r, d->fwd, d->bwd, d->tr_fwd, d->tr_bwd};
    for (size_t k = 0; k < sizeof plans / sizeof plans[0]; k++)
        if (plans[k])
            fftw_destroy_plan(plans[k]);
    mc_free(d->spec);
    mc_free(d->line);
    mc_free(d->cline);
    mc_free(d->counts);
    mc_free(d->displs);
    mc_free(d->pack);
    mc_free(d->rcounts);
    mc_free(d->rdispls);
    if (d->shared) {
        unmap_segments(d);
    } else {
        mc_free(d->rows);
        mc_free(d->cols);
    }
    mc_free(d->lay);
    mc_free(d);
    *pd = NULL;
}

static void *alloc_doubles(size_t n) { return mc_malloc((n ? n : 1) * sizeof(double)); }

/* Each rank's rows and cols as one POSIX shared-memory segment (rows, then cols, nbuf doubles
 * each), mapped by every rank of the node: d->seg[p] is rank p's, d->rows / d->cols this rank's.
 * Every step that can fail (the segment's creation or room: posix_fallocate reserves its pages,
 * so a full /dev/shm fails here instead of killing the process on first touch; mapping a peer's)
 * fails on its own rank, and the ranks agree after each: 1 when every rank has every mapping,
 * else 0 with nothing mapped (FFTW-MPI's transposes then). The names are unlinked once all
 * ranks have mapped them: nothing is left in /dev/shm, even by a killed run. Released by
 * munmap alone (unmap_segments): no collective. Collective. */
static void unmap_segments(mc_dfft *d)
{
    if (!d->seg)
        return;
    for (int p = 0; p < d->nseg; p++)
        if (d->seg[p])
            munmap(d->seg[p], d->seg_bytes);
    mc_free(d->seg);
    d->seg = NULL;
}

static int map_segments(mc_dfft *d, size_t nbuf)
{
    static unsigned serial; /* this process's segments so far: unique names */
    enum { NAME = 64 };
    int size, rank;
    MPI_Comm_size(d->comm, &size);
    MPI_Comm_rank(d->comm, &rank);
    /* one layout for all: rows at 0, cols at the largest nbuf of the ranks (it varies by rank) */
    unsigned long long most = nbuf;
    MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, d->comm);
    nbuf = (size_t)most;
    const long page = sysconf(_SC_PAGESIZE) > 0 ? sysconf(_SC_PAGESIZE) : 4096;
    const size_t want = 2 * (nbuf ? nbuf : 1) * sizeof(double);
    d->seg_bytes = (want + (size_t)page - 1) / (size_t)page * (size_t)page;
    d->nseg = size;
    d->seg = mc_calloc((size_t)size, sizeof *d->seg);
    char *names = mc_calloc((size_t)size, NAME);
    char mine[NAME];
    snprintf(mine, sizeof mine, "/microcontact-dfft.%ld.%u", (long)getpid(), serial++);
    int fd = d->seg && names && !refuse_shared ? shm_open(mine, O_CREAT | O_EXCL | O_RDWR, 0600)
                                               : -1;
    int ok = fd >= 0 && posix_fallocate(fd, 0, (off_t)d->seg_bytes) == 0;
    if (ok) {
        void *at = mmap(NULL, d->seg_bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        ok = at != MAP_FAILED;
        d->seg[rank] = ok ? at : NULL;
    }
    if (fd >= 0)
        close(fd);
    MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, d->comm);
    if (ok) { /* every rank's segment, mapped here */
        MPI_Allgather(mine, NAME, MPI_CHAR, names, NAME, MPI_CHAR, d->comm);
        for (int p = 0; p < size && ok; p++) {
            if (p == rank)
                continue;
            const int pfd = shm_open(names + (size_t)p * NAME, O_RDWR, 0);
            void *at = pfd >= 0 ? mmap(NULL, d->seg_bytes, PROT_READ | PROT_WRITE, MAP_SHARED,
                                       pfd, 0)
                                : MAP_FAILED;
            if (pfd >= 0)
                close(pfd);
            ok = at != MAP_FAILED;
            d->seg[p] = ok ? at : NULL;
        }
        MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, d->comm);
    }
    if (fd >= 0)
        shm_unlink(mine); /* (every rank has mapped it, or none will) */
    mc_free(names);
    if (!ok) {
        unmap_segments(d);
        return 0;
    }
    d->nbuf = nbuf;
    d->rows = d->seg[rank];
    d->cols = d->seg[rank] + nbuf;
    return 1;
}

/* The transposes' buffers, nbuf doubles each: shared (map_segments) when every rank of the
 * communicator is on this node (MPI_COMM_TYPE_SHARED), with every rank's layout; else
 * private. Collective; every rank takes the same branch. 0 or MC_ERR_NOMEM. */
static int alloc_transpose_buffers(mc_dfft *d, size_t nbuf)
{
    int size, nsize;
    MPI_Comm_size(d->comm, &size);
    MPI_Comm node;
    MPI_Comm_split_type(d->comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &nsize);
    MPI_Comm_free(&node);
    int shared = use_shared && nsize == size;
    MPI_Allreduce(MPI_IN_PLACE, &shared, 1, MPI_INT, MPI_MIN, d->comm);
    if (shared) {
        d->lay = mc_calloc(4 * (size_t)size, sizeof *d->lay);
        shared = d->lay != NULL;
        MPI_Allreduce(MPI_IN_PLACE, &shared, 1, MPI_INT, MPI_MIN, d->comm);
    }
    if (shared && !map_segments(d, nbuf))
        shared = 0; /* (no shared memory to be had: FFTW-MPI's transposes) */
    if (!shared) {
        used |= MC_DFFT_TRANSPOSES_FFTW;
        d->rows = alloc_doubles(nbuf);
        d->cols = alloc_doubles(nbuf);
        return d->rows && d->cols ? 0 : MC_ERR_NOMEM;
    }
    used |= MC_DFFT_TRANSPOSES_SHARED;
    d->shared = 1;
    const int mine[4] = {(int)d->r0, (int)d->nr, (int)d->k0, (int)d->nk};
    MPI_Allgather(mine, 4, MPI_INT, d->lay, 4, MPI_INT, d->comm);
    return 0;
}

/* Between the writers and the readers of the shared buffers: each rank's stores visible to the
 * others (full fences on both sides of the barrier), and no rank past this point before all
 * have reached it. */
static void shared_fence(mc_dfft *d)
{
    atomic_thread_fence(memory_order_seq_cst);
    MPI_Barrier(d->comm);
    atomic_thread_fence(memory_order_seq_cst);
}

/* The transposes on one node, as FFTW-MPI's (the same values moved: the same bits), each
 * element copied once, straight from the rank that holds it: forward, every rank's rows
 * [r][kx] (elements of 2 m doubles) into this rank's columns [kx - k0][r0_p + r]; inverse, every
 * rank's columns into this rank's rows. Tiles keep both sides in the cache. */
enum { TILE = 32 };

static void shared_transpose(mc_dfft *d, int inverse)
{
    int size;
    MPI_Comm_size(d->comm, &size);
    const size_t e = 2 * (size_t)d->m; /* doubles per element */
    const size_t ny = (size_t)d->ny, hx = (size_t)d->hx;
    shared_fence(d);
    for (int p = 0; p < size; p++) {
        const int *lp = d->lay + 4 * p;
        /* forward: rows r < nr_p of rank p, columns k of this rank; inverse: rows r < nr of this
         * rank, columns k < nk_p of rank p */
        const size_t nr = (size_t)(inverse ? d->nr : lp[1]),
                     nk = (size_t)(inverse ? lp[3] : d->nk);
        const size_t row0 = (size_t)(inverse ? d->r0 : lp[0]),
                     col0 = (size_t)(inverse ? lp[2] : d->k0);
        const double *src = d->seg[p] + (inverse ? d->nbuf : 0); /* its cols or rows */
        double *dst = inverse ? d->rows : d->cols;
        for (size_t kb = 0; kb < nk; kb += TILE)
            for (size_t rb = 0; rb < nr; rb += TILE) {
                const size_t ke = kb + TILE < nk ? kb + TILE : nk,
                             re = rb + TILE < nr ? rb + TILE : nr;
                for (size_t k = kb; k < ke; k++)
                    for (size_t r = rb; r < re; r++) {
                        /* rows [r][col0 + k], columns [k][row0 + r] */
                        const size_t at_row = (r * hx + col0 + k) * e,
                                     at_col = (k * ny + row0 + r) * e;
                        const double *s = src + (inverse ? at_col : at_row);
                        double *t = dst + (inverse ? at_row : at_col);
                        for (size_t c = 0; c < e; c++)
                            t[c] = s[c];
                    }
            }
    }
    shared_fence(d);
}

/* The forward (rows -> columns) or inverse transpose of the batch in rows / cols. */
static void transpose(mc_dfft *d, int inverse)
{
    const mc_dist_mark t0 = mc_dist_comm_begin();
    if (d->shared)
        shared_transpose(d, inverse);
    else
        fftw_execute(inverse ? d->tr_bwd : d->tr_fwd);
    mc_dist_comm_end(t0);
}

int mc_dfft_create(int nx, int ny, int tx, int ty, mc_dfft **out, mc_error *err)
{
    return mc_dfft_create_many(nx, ny, tx, ty, 1, out, err);
}

int mc_dfft_create_many(int nx, int ny, int tx, int ty, int m, mc_dfft **out, mc_error *err)
{
    *out = NULL;
    if (m < 1)
        return mc_fail(err, MC_ERR_INTERNAL, "distributed FFT: %d fields per batch", m);
    if (!mc_dist_active())
        return mc_fail(err, MC_ERR_INTERNAL, "distributed FFT: no MPI communicator");
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    mc_dfft *d = mc_calloc(1, sizeof *d);
    if (!d)
        return mc_fail(err, MC_ERR_NOMEM, "distributed FFT: out of memory");
    d->comm = mc_dist_comm();
    d->nx = nx;
    d->ny = ny;
    d->tx = tx;
    d->ty = ty;
    d->hx = tx / 2 + 1;
    d->m = m;
    const ptrdiff_t n[2] = {ny, d->hx};
    const ptrdiff_t alloc = fftw_mpi_local_size_many_transposed(
        2, n, 2, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, d->comm, &d->nr, &d->r0, &d->nk,
        &d->k0);
    /* the transposes' buffers: what FFTW asks for, at least both layouts (complex = 2 doubles),
     * m fields interleaved */
    size_t nbuf = 2 * (size_t)alloc * (size_t)m;
    const size_t nrow = 2 * (size_t)d->nr * (size_t)d->hx * m,
                 ncol = 2 * (size_t)d->nk * (size_t)ny * m;
    if (nbuf < nrow)
        nbuf = nrow;
    if (nbuf < ncol)
        nbuf = ncol;
    int size;
    MPI_Comm_size(d->comm, &size);
    const size_t cl = (size_t)(d->hx > ty ? d->hx : ty);
    if (alloc_transpose_buffers(d, nbuf) ||
        !(d->spec = alloc_doubles(2 * (size_t)d->nk * (size_t)ty)) ||
        !(d->line = alloc_doubles((size_t)tx)) || !(d->cline = alloc_doubles(2 * cl)) ||
        !(d->counts = mc_calloc((size_t)size, sizeof *d->counts)) ||
        !(d->displs = mc_calloc((size_t)size, sizeof *d->displs))) {
        mc_dfft_destroy(&d);
        return mc_fail(err, MC_ERR_NOMEM, "distributed FFT %d x %d: out of memory", tx, ty);
    }
    /* who holds which output rows: the gather's counts and offsets */
    int mine[2] = {(int)d->nr * nx, (int)d->r0 * nx};
    int *all = mc_malloc(2 * (size_t)size * sizeof *all);
    if (!all) {
        mc_dfft_destroy(&d);
        return mc_fail(err, MC_ERR_NOMEM, "distributed FFT: out of memory");
    }
    MPI_Allgather(mine, 2, MPI_INT, all, 2, MPI_INT, d->comm);
    for (int p = 0; p < size; p++) {
        d->counts[p] = all[2 * p];
        d->displs[p] = all[2 * p + 1];
    }
    if (m > 1) { /* the batches' gather: whole rows (m fields each) per rank */
        if (!(d->pack = alloc_doubles((size_t)d->nr * m * nx)) ||
            !(d->rcounts = mc_calloc((size_t)size, sizeof *d->rcounts)) ||
            !(d->rdispls = mc_calloc((size_t)size, sizeof *d->rdispls))) {
            mc_free(all);
            mc_dfft_destroy(&d);
            return mc_fail(err, MC_ERR_NOMEM, "distributed FFT: out of memory");
        }
        for (int p = 0; p < size; p++) {
            d->rcounts[p] = all[2 * p] / (nx > 0 ? nx : 1);
            d->rdispls[p] = all[2 * p + 1] / (nx > 0 ? nx : 1);
        }
    }
    mc_free(all);
    /* one-line plans on one thread, always FFTW_ESTIMATE: the same plan, hence the same bits, on
     * every rank (dfft.h) */
    fftw_plan_with_nthreads(1);
    d->r2c = fftw_plan_dft_r2c_1d(tx, d->line, d->cline, FFTW_ESTIMATE);
    d->c2r = fftw_plan_dft_c2r_1d(tx, d->cline, d->line, FFTW_ESTIMATE);
    d->fwd = fftw_plan_dft_1d(ty, d->cline, d->cline, FFTW_FORWARD, FFTW_ESTIMATE);
    d->bwd = fftw_plan_dft_1d(ty, d->cline, d->cline, FFTW_BACKWARD, FFTW_ESTIMATE);
    if (!d->shared) {
    d->tr_fwd = fftw_mpi_plan_many_transpose(ny, d->hx, 2 * m, FFTW_MPI_DEFAULT_BLOCK,
                                             FFTW_MPI_DEFAULT_BLOCK, d->rows, d->cols, d->comm,
                                             FFTW_ESTIMATE);
    d->tr_bwd = fftw_mpi_plan_many_transpose(d->hx, ny, 2 * m, FFTW_MPI_DEFAULT_BLOCK,
                                             FFTW_MPI_DEFAULT_BLOCK, d->cols, d->rows, d->comm,
                                             FFTW_ESTIMATE);
    }
    fftw_plan_with_nthreads(mc_threads_count());
    if (!d->r2c || !d->c2r || !d->fwd || !d->bwd ||
        (!d->shared && (!d->tr_fwd || !d->tr_bwd))) {
        mc_dfft_destroy(&d);
        return mc_fail(err, MC_ERR_NOMEM, "FFTW-MPI could not plan the %d x %d transforms", tx,
                       ty);
    }
    *out = d;
    return MC_OK;
}

size_t mc_dfft_spectrum_len(const mc_dfft *d) { return 2 * (size_t)d->nk * (size_t)d->ty; }

fftw_complex *mc_dfft_spectrum(mc_dfft *d) { return d->spec; }

/* 1 when the one-line plans, made on d->cline, may run on the complex line at p instead (FFTW's
 * new-array execute: the same alignment; the same plan, hence the same bits): one copy saved. */
static int plan_fits(const mc_dfft *d, fftw_complex *p)
{
    return fftw_alignment_of((double *)p) == fftw_alignment_of((double *)d->cline);
}

/* Row j of a real array of rows of w values, zero-padded to tx, into the row spectrum dst (hx
 * complex values). */
static void row_forward(mc_dfft *d, const double *src, int w, fftw_complex *dst)
{
    memcpy(d->line, src, (size_t)w * sizeof *d->line);
    memset(d->line + w, 0, (size_t)(d->tx - w) * sizeof *d->line);
    if (plan_fits(d, dst)) {
        fftw_execute_dft_r2c(d->r2c, d->line, dst);
        return;
    }
    fftw_execute_dft_r2c(d->r2c, d->line, d->cline);
    memcpy(dst, d->cline, (size_t)d->hx * sizeof *dst);
}

/* A column of m <= ty values, zero-padded to ty, forward into dst (ty values). */
static void col_forward(mc_dfft *d, const fftw_complex *src, int m, fftw_complex *dst)
{
    fftw_complex *at = plan_fits(d, dst) ? dst : d->cline; /* in place in dst when it fits */
    memcpy(at, src, (size_t)m * sizeof *at);
    memset(at + m, 0, (size_t)(d->ty - m) * sizeof *at);
    fftw_execute_dft(d->fwd, at, at);
    if (at != dst)
        memcpy(dst, at, (size_t)d->ty * sizeof *dst);
}

void mc_dfft_forward(mc_dfft *d, const double *field, fftw_complex *spec, int local)
{
    fftw_complex *rows = (fftw_complex *)d->rows, *cols = (fftw_complex *)d->cols;
    const ptrdiff_t first = local ? 0 : d->r0; /* the row of field that holds data row r0 */
    for (ptrdiff_t r = 0; r < d->nr; r++)
        row_forward(d, field + (size_t)(first + r) * d->nx, d->nx, rows + (size_t)r * d->hx);
    transpose(d, 0); /* ny x hx by rows -> hx x ny by columns */
    for (ptrdiff_t k = 0; k < d->nk; k++)
        col_forward(d, cols + (size_t)k * d->ny, d->ny, spec + (size_t)k * d->ty);
}

void mc_dfft_inverse(mc_dfft *d, double *out, int local)
{
    const ptrdiff_t first = local ? 0 : d->r0;
    fftw_complex *rows = (fftw_complex *)d->rows, *cols = (fftw_complex *)d->cols;
    for (ptrdiff_t k = 0; k < d->nk; k++) { /* only the ny data rows are kept */
        fftw_complex *at = d->spec + (size_t)k * d->ty; /* (the spectrum is destroyed) */
        if (!plan_fits(d, at)) {
            memcpy(d->cline, at, (size_t)d->ty * sizeof *d->cline);
            at = d->cline;
        }
        fftw_execute_dft(d->bwd, at, at);
        memcpy(cols + (size_t)k * d->ny, at, (size_t)d->ny * sizeof *cols);
    }
    transpose(d, 1); /* hx x ny by columns -> ny x hx by rows */
    for (ptrdiff_t r = 0; r < d->nr; r++) {
        fftw_complex *at = rows + (size_t)r * d->hx; /* (a c2r destroys its input: scratch) */
        if (!plan_fits(d, at)) {
            memcpy(d->cline, at, (size_t)d->hx * sizeof *d->cline);
            at = d->cline;
        }
        fftw_execute_dft_c2r(d->c2r, at, d->line);
        memcpy(out + (size_t)(first + r) * d->nx, d->line, (size_t)d->nx * sizeof *out);
    }
    if (local)
        return;
    const mc_dist_mark t0 = mc_dist_comm_begin();
    MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, out, d->counts, d->displs, MPI_DOUBLE,
                   d->comm);
    mc_dist_comm_end(t0);
}

void mc_dfft_forward_many(mc_dfft *d, const double *fields, size_t stride, int m,
                          fftw_complex *spec, size_t sstride)
{
    const int M = d->m;
    fftw_complex *rows = (fftw_complex *)d->rows, *cols = (fftw_complex *)d->cols;
    for (ptrdiff_t r = 0; r < d->nr; r++)
        for (int f = 0; f < M; f++) {
            fftw_complex *dst = rows + ((size_t)r * d->hx) * M + f;
            if (f >= m) { /* the batch's unused slots: zeros */
                for (int k = 0; k < d->hx; k++)
                    dst[(size_t)k * M][0] = dst[(size_t)k * M][1] = 0.0;
                continue;
            }
            const double *src = fields + f * stride + (size_t)(d->r0 + r) * d->nx;
            memcpy(d->line, src, (size_t)d->nx * sizeof *d->line);
            memset(d->line + d->nx, 0, (size_t)(d->tx - d->nx) * sizeof *d->line);
            fftw_execute_dft_r2c(d->r2c, d->line, d->cline);
            for (int k = 0; k < d->hx; k++) {
                dst[(size_t)k * M][0] = d->cline[k][0];
                dst[(size_t)k * M][1] = d->cline[k][1];
            }
        }
    transpose(d, 0); /* one transpose for the batch */
    for (int f = 0; f < m; f++)
        for (ptrdiff_t k = 0; k < d->nk; k++) {
            const fftw_complex *src = cols + ((size_t)k * d->ny) * M + f;
            fftw_complex *dst = spec + f * sstride + (size_t)k * d->ty;
            fftw_complex *at = plan_fits(d, dst) ? dst : d->cline; /* in place when it fits */
            for (int j = 0; j < d->ny; j++) {
                at[j][0] = src[(size_t)j * M][0];
                at[j][1] = src[(size_t)j * M][1];
            }
            memset(at + d->ny, 0, (size_t)(d->ty - d->ny) * sizeof *at);
            fftw_execute_dft(d->fwd, at, at);
            if (at != dst)
                memcpy(dst, at, (size_t)d->ty * sizeof *spec);
        }
}

/* mc_dfft_inverse_many (gather = 1) and mc_dfft_inverse_many_rows (gather = 0). */
static void inverse_many(mc_dfft *d, fftw_complex *spec, size_t sstride, int m, double *out,
                         size_t stride, int gather)
{
    const int M = d->m;
    fftw_complex *rows = (fftw_complex *)d->rows, *cols = (fftw_complex *)d->cols;
    for (int f = 0; f < M; f++)
        for (ptrdiff_t k = 0; k < d->nk; k++) {
            fftw_complex *dst = cols + ((size_t)k * d->ny) * M + f;
            if (f >= m) {
                for (int j = 0; j < d->ny; j++)
                    dst[(size_t)j * M][0] = dst[(size_t)j * M][1] = 0.0;
                continue;
            }
            fftw_complex *at = spec + f * sstride + (size_t)k * d->ty; /* (destroyed) */
            if (!plan_fits(d, at)) {
                memcpy(d->cline, at, (size_t)d->ty * sizeof *d->cline);
                at = d->cline;
            }
            fftw_execute_dft(d->bwd, at, at);
            for (int j = 0; j < d->ny; j++) {
                dst[(size_t)j * M][0] = at[j][0];
                dst[(size_t)j * M][1] = at[j][1];
            }
        }
    transpose(d, 1);
    /* this rank's rows of each field, packed [r][f][x] for the gather (m = 1: in place), or
     * (no gather) straight into their places in out */
    double *pack = M > 1 && gather ? d->pack : out + (size_t)d->r0 * d->nx;
    for (ptrdiff_t r = 0; r < d->nr; r++)
        for (int f = 0; f < m; f++) {
            const fftw_complex *src = rows + ((size_t)r * d->hx) * M + f;
            for (int k = 0; k < d->hx; k++) {
                d->cline[k][0] = src[(size_t)k * M][0];
                d->cline[k][1] = src[(size_t)k * M][1];
            }
            fftw_execute_dft_c2r(d->c2r, d->cline, d->line);
            double *dst = M > 1 && gather ? pack + ((size_t)r * m + f) * d->nx
                                          : pack + f * stride + (size_t)r * d->nx;
            memcpy(dst, d->line, (size_t)d->nx * sizeof *pack);
        }
    if (!gather)
        return;
    const mc_dist_mark t0 = mc_dist_comm_begin();
    if (M == 1) {
        MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, out, d->counts, d->displs, MPI_DOUBLE,
                       d->comm);
    } else {
        /* one row of the m fields: m runs of nx at the fields' stride, its extent one row, so
         * that rank p's rows r0 .. r0 + nr - 1 land in every field at once */
        MPI_Datatype vec, row;
        MPI_Type_vector(m, d->nx, (int)stride, MPI_DOUBLE, &vec);
        MPI_Type_create_resized(vec, 0, (MPI_Aint)(d->nx * sizeof(double)), &row);
        MPI_Type_commit(&row);
        MPI_Allgatherv(d->pack, (int)(d->nr * m * d->nx), MPI_DOUBLE, out, d->rcounts,
                       d->rdispls, row, d->comm);
        MPI_Type_free(&row);
        MPI_Type_free(&vec);
    }
    mc_dist_comm_end(t0);
}

void mc_dfft_inverse_many(mc_dfft *d, fftw_complex *spec, size_t sstride, int m, double *out,
                          size_t stride)
{
    inverse_many(d, spec, sstride, m, out, stride, 1);
}

void mc_dfft_inverse_many_rows(mc_dfft *d, fftw_complex *spec, size_t sstride, int m,
                               double *out, size_t stride)
{
    inverse_many(d, spec, sstride, m, out, stride, 0);
}

int mc_dfft_is_shared(const mc_dfft *d) { return d->shared; }

void mc_dfft_rows(const mc_dfft *d, int *r0, int *nr)
{
    *r0 = (int)d->r0;
    *nr = (int)d->nr;
}

void mc_dfft_columns(const mc_dfft *d, int *k0, int *nk)
{
    *k0 = (int)d->k0;
    *nk = (int)d->nk;
}

size_t mc_dfft_bytes(const mc_dfft *d)
{
    int p, r;
    MPI_Comm_size(d->comm, &p);
    MPI_Comm_rank(d->comm, &r);
    return mc_dfft_estimate_many(d->nx, d->ny, d->tx, d->ty, d->m, p, r);
}

void mc_dfft_table(mc_dfft *d, const double *table, fftw_complex *spec)
{
    /* all ty rows along x, keeping this rank's columns; then its columns along y */
    for (int j = 0; j < d->ty; j++) {
        memcpy(d->line, table + (size_t)j * d->tx, (size_t)d->tx * sizeof *d->line);
        fftw_execute_dft_r2c(d->r2c, d->line, d->cline);
        for (ptrdiff_t k = 0; k < d->nk; k++)
            memcpy(spec + (size_t)k * d->ty + j, d->cline + d->k0 + k, sizeof *spec);
    }
    for (ptrdiff_t k = 0; k < d->nk; k++)
        col_forward(d, spec + (size_t)k * d->ty, d->ty, spec + (size_t)k * d->ty);
}

void mc_dfft_table_split(const mc_dfft *d, int *j0, int *nj)
{
    int size, rank;
    MPI_Comm_size(d->comm, &size);
    MPI_Comm_rank(d->comm, &rank);
    const int b = (d->ty + size - 1) / size, lo = rank * b < d->ty ? rank * b : d->ty;
    *j0 = lo;
    *nj = lo + b < d->ty ? b : d->ty - lo;
}

int mc_dfft_table_rows(mc_dfft *d, double *rows, fftw_complex *spec)
{
    int size;
    MPI_Comm_size(d->comm, &size);
    int j0, nj;
    mc_dfft_table_split(d, &j0, &nj);
    const int hx = d->hx;
    /* each row along x in place (its hx complex values fill its room of 2 hx doubles) */
    for (int r = 0; r < nj; r++) {
        double *row = rows + (size_t)r * 2 * (size_t)hx;
        memcpy(d->line, row, (size_t)d->tx * sizeof *d->line);
        fftw_execute_dft_r2c(d->r2c, d->line, d->cline);
        memcpy(row, d->cline, (size_t)hx * sizeof *d->cline);
    }
    /* every rank's rows and columns; to rank q the columns k0_q .. of each of these rows (a
     * strided block), from rank p its rows of this rank's columns, [r][k] */
    int *all = mc_malloc(4 * (size_t)size * sizeof *all);
    int *cnt = mc_malloc(4 * (size_t)size * sizeof *cnt);
    MPI_Datatype *types = mc_malloc(2 * (size_t)size * sizeof *types);
    double *recv = mc_malloc((2 * (size_t)d->nk * (size_t)d->ty + 1) * sizeof *recv);
    int bad = !all || !cnt || !types || !recv;
    MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, d->comm);
    if (bad) {
        mc_free(all);
        mc_free(cnt);
        mc_free(types);
        mc_free(recv);
        return MC_ERR_NOMEM;
    }
    int mine[4] = {j0, nj, (int)d->k0, (int)d->nk};
    mc_dist_mark t0 = mc_dist_comm_begin();
    MPI_Allgather(mine, 4, MPI_INT, all, 4, MPI_INT, d->comm);
    int *sc = cnt, *sd = cnt + size, *rc = cnt + 2 * size, *rd = cnt + 3 * size;
    MPI_Datatype *st = types, *rt = types + size;
    int off = 0;
    for (int q = 0; q < size; q++) {
        const int k0q = all[4 * q + 2], nkq = all[4 * q + 3], njq = all[4 * q + 1];
        sc[q] = nj > 0 && nkq > 0 ? 1 : 0;
        sd[q] = (int)((size_t)2 * (size_t)k0q * sizeof(double));
        MPI_Type_vector(nj > 0 ? nj : 1, 2 * (nkq > 0 ? nkq : 1), 2 * hx, MPI_DOUBLE, &st[q]);
        MPI_Type_commit(&st[q]);
        rc[q] = njq * (int)d->nk * 2;
        rd[q] = (int)((size_t)off * sizeof(double));
        off += rc[q];
        rt[q] = MPI_DOUBLE;
    }
    MPI_Alltoallw(rows, sc, sd, st, recv, rc, rd, rt, d->comm);
    mc_dist_comm_end(t0);
    for (int q = 0; q < size; q++)
        MPI_Type_free(&st[q]);
    /* into the columns [k][jt], then each column along y (as mc_dfft_table) */
    const fftw_complex *rv = (const fftw_complex *)recv;
    size_t at = 0;
    for (int p = 0; p < size; p++)
        for (int r = 0; r < all[4 * p + 1]; r++)
            for (ptrdiff_t k = 0; k < d->nk; k++)
                memcpy(spec + (size_t)k * d->ty + all[4 * p] + r, rv + at++, sizeof *spec);
    for (ptrdiff_t k = 0; k < d->nk; k++)
        col_forward(d, spec + (size_t)k * d->ty, d->ty, spec + (size_t)k * d->ty);
    mc_free(all);
    mc_free(cnt);
    mc_free(types);
    mc_free(recv);
    return MC_OK;
}

#else /* no MPI: the engine is never made */

int mc_dfft_shared_transposes(int on)
{
    (void)on;
    return 0;
}

int mc_dfft_is_shared(const mc_dfft *d)
{
    (void)d;
    return 0;
}

void mc_dfft_columns(const mc_dfft *d, int *k0, int *nk)
{
    (void)d;
    *k0 = *nk = 0;
}

int mc_dfft_create_many(int nx, int ny, int tx, int ty, int m, mc_dfft **out, mc_error *err)
{
    (void)m;
    return mc_dfft_create(nx, ny, tx, ty, out, err);
}

void mc_dfft_forward_many(mc_dfft *d, const double *fields, size_t stride, int m,
                          fftw_complex *spec, size_t sstride)
{
    (void)d;
    (void)fields;
    (void)stride;
    (void)m;
    (void)spec;
    (void)sstride;
}

void mc_dfft_inverse_many(mc_dfft *d, fftw_complex *spec, size_t sstride, int m, double *out,
                          size_t stride)
{
    (void)d;
    (void)spec;
    (void)sstride;
    (void)m;
    (void)out;
    (void)stride;
}

size_t mc_dfft_bytes(const mc_dfft *d)
{
    (void)d;
    return 0;
}

int mc_dfft_create(int nx, int ny, int tx, int ty, mc_dfft **out, mc_error *err)
{
    (void)nx;
    (void)ny;
    (void)tx;
    (void)ty;
    *out = NULL;
    return mc_fail(err, MC_ERR_INTERNAL, "distributed FFT: this build has no MPI (-DMC_MPI)");
}

void mc_dfft_destroy(mc_dfft **d)
{
    if (d)
        *d = NULL;
}

size_t mc_dfft_spectrum_len(const mc_dfft *d)
{
    (void)d;
    return 0;
}

fftw_complex *mc_dfft_spectrum(mc_dfft *d)
{
    (void)d;
    return NULL;
}

void mc_dfft_forward(mc_dfft *d, const double *field, fftw_complex *spec, int local)
{
    (void)d;
    (void)field;
    (void)spec;
    (void)local;
}

void mc_dfft_inverse(mc_dfft *d, double *out, int local)
{
    (void)d;
    (void)out;
    (void)local;
}

void mc_dfft_inverse_many_rows(mc_dfft *d, fftw_complex *spec, size_t sstride, int m,
                               double *out, size_t stride)
{
    mc_dfft_inverse_many(d, spec, sstride, m, out, stride);
}

void mc_dfft_rows(const mc_dfft *d, int *r0, int *nr)
{
    (void)d;
    *r0 = *nr = 0;
}

void mc_dfft_table(mc_dfft *d, const double *table, fftw_complex *spec)
{
    (void)d;
    (void)table;
    (void)spec;
}
void mc_dfft_table_split(const mc_dfft *d, int *j0, int *nj)
{
    (void)d;
    *j0 = *nj = 0;
}

int mc_dfft_table_rows(mc_dfft *d, double *rows, fftw_complex *spec)
{
    (void)d;
    (void)rows;
    (void)spec;
    return MC_ERR_INTERNAL;
}
#endif

void mc_dfft_split(int n, int p, int r, int *first, int *count)
{
    const int block = p > 0 ? (n + p - 1) / p : n;
    const long f = (long)r * block;
    *first = f < n ? (int)f : n;
    *count = f < n ? (n - (int)f < block ? n - (int)f : block) : 0;
}

size_t mc_dfft_estimate(int nx, int ny, int tx, int ty, int p, int r)
{
    return mc_dfft_estimate_many(nx, ny, tx, ty, 1, p, r);
}

/* Of each peer's rows, this rank's columns of every row; of each peer's columns, this rank's
 * rows of every column; a partly read page counts whole. */
size_t mc_dfft_peer_bytes(int ny, int tx, int m, int p, int r)
{
    const int hx = tx / 2 + 1;
    if (!use_shared || p < 2)
        return 0;
    const size_t e = 16 * (size_t)m, page = 4096; /* bytes per element */
    int r0, nr, k0, nk;
    mc_dfft_split(ny, p, r, &r0, &nr);
    mc_dfft_split(hx, p, r, &k0, &nk);
    size_t bytes = 0;
    for (int q = 0; q < p; q++) {
        if (q == r)
            continue;
        int q0, nrq, c0, nkq;
        mc_dfft_split(ny, p, q, &q0, &nrq);
        mc_dfft_split(hx, p, q, &c0, &nkq);
        const size_t rows = (size_t)nrq * (size_t)hx * e, cols = (size_t)nkq * (size_t)ny * e;
        const size_t from_rows = nk ? (size_t)nrq * ((size_t)nk * e + page) : 0,
                     from_cols = nr ? (size_t)nkq * ((size_t)nr * e + page) : 0;
        bytes += (from_rows < rows ? from_rows : rows) + (from_cols < cols ? from_cols : cols);
    }
    return bytes;
}

size_t mc_dfft_estimate_many(int nx, int ny, int tx, int ty, int m, int p, int r)
{
    const int hx = tx / 2 + 1;
    int r0, nr, k0, nk;
    mc_dfft_split(ny, p, r, &r0, &nr);
    mc_dfft_split(hx, p, r, &k0, &nk);
    const size_t nrow = 2 * (size_t)nr * (size_t)hx * m, ncol = 2 * (size_t)nk * (size_t)ny * m;
    const size_t nbuf = nrow > ncol ? nrow : ncol;
    const size_t cl = (size_t)(hx > ty ? hx : ty);
    const size_t pack = m > 1 ? (size_t)nr * m * nx : 0;
    return (2 * nbuf + 2 * (size_t)nk * (size_t)ty + (size_t)tx + 2 * cl + pack) *
               sizeof(double) +
           (m > 1 ? 4 : 2) * (size_t)p * sizeof(int) + mc_dfft_peer_bytes(ny, tx, m, p, r);
}
