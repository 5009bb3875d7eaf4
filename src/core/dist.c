/* dist.c - the run's communicator (dist.h). */
#include "core/dist.h"

#include <math.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"

static double comm_seconds, comm_cpu;

double mc_dist_comm_seconds(void) { return comm_seconds; }
double mc_dist_comm_cpu_seconds(void) { return comm_cpu; }
void mc_dist_comm_add(double s) { comm_seconds += s; }

double mc_dist_cpu_seconds(void)
{
    struct timespec t;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0)
        return 0;
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

mc_dist_mark mc_dist_comm_begin(void)
{
    return (mc_dist_mark){mc_dist_clock(), mc_dist_cpu_seconds()};
}

void mc_dist_comm_end(mc_dist_mark m)
{
    comm_seconds += mc_dist_clock() - m.wall;
    comm_cpu += mc_dist_cpu_seconds() - m.cpu;
}

void mc_dist_share(int n, int *first, int *count)
{
    const long long p = mc_dist_size(), r = mc_dist_rank();
    const int a = (int)(r * n / p), b = (int)((r + 1) * n / p);
    *first = a;
    *count = b - a;
}

#ifdef MC_MPI
double mc_dist_clock(void) { return MPI_Wtime(); }

static MPI_Comm run_comm = MPI_COMM_NULL;

void mc_dist_set(MPI_Comm comm) { run_comm = comm; }
MPI_Comm mc_dist_comm(void) { return run_comm; }
int mc_dist_active(void) { return run_comm != MPI_COMM_NULL; }

int mc_dist_size(void)
{
    int p = 1;
    if (run_comm != MPI_COMM_NULL)
        MPI_Comm_size(run_comm, &p);
    return p;
}

int mc_dist_rank(void)
{
    int r = 0;
    if (run_comm != MPI_COMM_NULL)
        MPI_Comm_rank(run_comm, &r);
    return r;
}

int mc_dist_root_int(int v)
{
    if (run_comm != MPI_COMM_NULL)
        MPI_Bcast(&v, 1, MPI_INT, 0, run_comm);
    return v;
}

int mc_dist_max_int(int v)
{
    if (run_comm != MPI_COMM_NULL)
        MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_MAX, run_comm);
    return v;
}

void mc_dist_bcast(double *v, size_t n, int root)
{
    if (run_comm == MPI_COMM_NULL)
        return;
    const mc_dist_mark t0 = mc_dist_comm_begin();
    const size_t chunk = (size_t)1 << 30; /* MPI counts are int */
    for (size_t at = 0; at < n; at += chunk)
        MPI_Bcast(v + at, (int)(n - at < chunk ? n - at : chunk), MPI_DOUBLE, root, run_comm);
    mc_dist_comm_end(t0);
}

int mc_dist_share_read(int rc, unsigned char **buf, size_t *len, const char *path, mc_error *err)
{
    if (run_comm == MPI_COMM_NULL)
        return rc;
    const mc_dist_mark t0 = mc_dist_comm_begin();
    const int rank = mc_dist_rank();
    MPI_Bcast(&rc, 1, MPI_INT, 0, run_comm);
    if (rc != MC_OK) { /* rank 0's message, so that every rank reports what rank 0 reports */
        char msg[MC_ERROR_MSG_MAX] = "";
        if (rank == 0 && err)
            memcpy(msg, err->msg, sizeof msg);
        MPI_Bcast(msg, (int)sizeof msg, MPI_CHAR, 0, run_comm);
        mc_dist_comm_end(t0);
        msg[sizeof msg - 1] = '\0';
        if (rank == 0)
            return rc;
        *buf = NULL;
        *len = 0;
        return mc_fail(err, (mc_status)rc, "%s", msg);
    }
    unsigned long long n = rank == 0 ? (unsigned long long)*len : 0;
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, run_comm);
    unsigned char *b = NULL;
    int short_of = 0; /* the highest rank without memory for its copy (rank 0 has its own) */
    if (rank == 0)
        b = *buf;
    else if (n >= (unsigned long long)SIZE_MAX || !(b = mc_malloc((size_t)n + 1)))
        short_of = rank;
    MPI_Allreduce(MPI_IN_PLACE, &short_of, 1, MPI_INT, MPI_MAX, run_comm);
    if (short_of) {
        mc_free(b);
        *buf = NULL;
        *len = 0;
        mc_dist_comm_end(t0);
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory on rank %d for a copy of its %llu bytes",
                       path ? path : "an input file", short_of, n);
    }
    const size_t chunk = (size_t)1 << 30; /* MPI counts are int */
    for (size_t at = 0; at < (size_t)n; at += chunk)
        MPI_Bcast(b + at, (int)((size_t)n - at < chunk ? (size_t)n - at : chunk), MPI_BYTE, 0,
                  run_comm);
    mc_dist_comm_end(t0);
    b[n] = '\0';
    *buf = b;
    *len = (size_t)n;
    return MC_OK;
}

void mc_dist_max(double *v, int n)
{
    if (run_comm != MPI_COMM_NULL && n > 0)
        MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, run_comm);
}
/* The ranks' element counts and offsets of a row-split field of w values per row (static
 * tables: the row-split calls never allocate; cli/ refuses more than MC_DIST_MAX_RANKS ranks);
 * 0 if an MPI count would overflow. */
static int layout_in[2 * MC_DIST_MAX_RANKS], counts[MC_DIST_MAX_RANKS], displs[MC_DIST_MAX_RANKS];

static int row_layout(int r0, int nr, int w)
{
    int mine[2] = {r0, nr}, size;
    MPI_Comm_size(run_comm, &size);
    if (size > MC_DIST_MAX_RANKS)
        return 0;
    MPI_Allgather(mine, 2, MPI_INT, layout_in, 2, MPI_INT, run_comm);
    int ok = 1;
    for (int p = 0; p < size; p++) {
        ok &= ((double)layout_in[2 * p] + layout_in[2 * p + 1]) * w < 2147483647.0;
        counts[p] = layout_in[2 * p + 1] * w;
        displs[p] = layout_in[2 * p] * w;
    }
    return ok;
}

/* Every rank's rows to every rank; 0 (nothing moved) if the layout overflows MPI's counts. */
static int gather_rows(void *v, MPI_Datatype t, int r0, int nr, int nx)
{
    if (run_comm == MPI_COMM_NULL)
        return 1;
    const mc_dist_mark t0 = mc_dist_comm_begin();
    const int ok = row_layout(r0, nr, nx);
    if (ok)
        MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, v, counts, displs, t, run_comm);
    mc_dist_comm_end(t0);
    return ok;
}

int mc_dist_gather_rows(double *v, int r0, int nr, int nx)
{
    return gather_rows(v, MPI_DOUBLE, r0, nr, nx);
}

/* Every rank's slab (its rows alone) into whole on every rank. */
static int gather_slab(const void *mine, void *whole, size_t size, MPI_Datatype t, int r0, int nr,
                       int nx)
{
    if (run_comm == MPI_COMM_NULL) {
        if (nr > 0)
            memcpy((char *)whole + (size_t)r0 * nx * size, mine, (size_t)nr * nx * size);
        return 1;
    }
    const mc_dist_mark t0 = mc_dist_comm_begin();
    const int ok = row_layout(r0, nr, nx);
    if (ok)
        MPI_Allgatherv(mine, nr * nx, t, whole, counts, displs, t, run_comm);
    mc_dist_comm_end(t0);
    return ok;
}

int mc_dist_gather_slab(const double *mine, double *whole, int r0, int nr, int nx)
{
    return gather_slab(mine, whole, sizeof *mine, MPI_DOUBLE, r0, nr, nx);
}

int mc_dist_gather_slab_u8(const unsigned char *mine, unsigned char *whole, int r0, int nr, int nx)
{
    return gather_slab(mine, whole, 1, MPI_UNSIGNED_CHAR, r0, nr, nx);
}

int mc_dist_gather_rows_u8(unsigned char *v, int r0, int nr, int nx)
{
    return gather_rows(v, MPI_UNSIGNED_CHAR, r0, nr, nx);
}

int mc_dist_gather_blocks(double *v, int nblocks, int ny, int nx, int r0, int nr)
{
    if (run_comm == MPI_COMM_NULL)
        return 1;
    int size;
    MPI_Comm_size(run_comm, &size);
    if (size > MC_DIST_MAX_RANKS)
        return 0;
    const mc_dist_mark t0 = mc_dist_comm_begin();
    /* one "row" of the gather: row r of every block (nblocks runs of nx values, a block apart,
     * hvector: the stride in bytes is no int count), resized to one row so that the rank's nr
     * rows from r0 are nr elements at displacement r0 */
    MPI_Datatype rows, row;
    MPI_Type_create_hvector(nblocks, nx, (MPI_Aint)ny * nx * (MPI_Aint)sizeof *v, MPI_DOUBLE,
                            &rows);
    MPI_Type_create_resized(rows, 0, (MPI_Aint)nx * (MPI_Aint)sizeof *v, &row);
    MPI_Type_commit(&row);
    int mine[2] = {r0, nr};
    MPI_Allgather(mine, 2, MPI_INT, layout_in, 2, MPI_INT, run_comm);
    for (int p = 0; p < size; p++) {
        displs[p] = layout_in[2 * p];
        counts[p] = layout_in[2 * p + 1];
    }
    MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, v, counts, displs, row, run_comm);
    MPI_Type_free(&row);
    MPI_Type_free(&rows);
    mc_dist_comm_end(t0);
    return 1;
}

int mc_dist_row_totals(const double *part, int nr, int ny, int m, double *all, double *out)
{
    const double *rows = part;
    int ok = 1;
    if (run_comm != MPI_COMM_NULL) {
        const mc_dist_mark t0 = mc_dist_comm_begin();
        int r0 = 0; /* the ranks' rows ascend with the rank: the rows of the ranks before */
        MPI_Exscan(&nr, &r0, 1, MPI_INT, MPI_SUM, run_comm);
        if (mc_dist_rank() == 0)
            r0 = 0; /* MPI_Exscan leaves rank 0's result undefined */
        ok = row_layout(r0, nr, m);
        if (ok)
            MPI_Allgatherv(part, nr * m, MPI_DOUBLE, all, counts, displs, MPI_DOUBLE, run_comm);
        mc_dist_comm_end(t0);
        rows = all;
        nr = ny;
    }
    for (int k = 0; k < m; k++) {
        double s = 0;
        for (int r = 0; ok && r < nr; r++)
            s += rows[(size_t)r * m + k];
        out[k] = ok ? s : NAN;
    }
    return ok;
}
#else
double mc_dist_clock(void) { return 0; }
int mc_dist_active(void) { return 0; }
int mc_dist_size(void) { return 1; }
int mc_dist_rank(void) { return 0; }
int mc_dist_root_int(int v) { return v; }
int mc_dist_max_int(int v) { return v; }
void mc_dist_bcast(double *v, size_t n, int root)
{
    (void)v;
    (void)n;
    (void)root;
}
int mc_dist_share_read(int rc, unsigned char **buf, size_t *len, const char *path, mc_error *err)
{
    (void)buf;
    (void)len;
    (void)path;
    (void)err;
    return rc;
}
void mc_dist_max(double *v, int n)
{
    (void)v;
    (void)n;
}

int mc_dist_row_totals(const double *part, int nr, int ny, int m, double *all, double *out)
{
    (void)ny;
    (void)all;
    for (int k = 0; k < m; k++) {
        double s = 0;
        for (int r = 0; r < nr; r++)
            s += part[(size_t)r * m + k];
        out[k] = s;
    }
    return 1;
}

int mc_dist_gather_blocks(double *v, int nblocks, int ny, int nx, int r0, int nr)
{
    (void)v;
    (void)nblocks;
    (void)ny;
    (void)nx;
    (void)r0;
    (void)nr;
    return 1;
}

int mc_dist_gather_rows(double *v, int r0, int nr, int nx)
{
    (void)v;
    (void)r0;
    (void)nr;
    (void)nx;
    return 1;
}

int mc_dist_gather_rows_u8(unsigned char *v, int r0, int nr, int nx)
{
    (void)v;
    (void)r0;
    (void)nr;
    (void)nx;
    return 1;
}

int mc_dist_gather_slab(const double *mine, double *whole, int r0, int nr, int nx)
{
    if (nr > 0)
        memcpy(whole + (size_t)r0 * nx, mine, (size_t)nr * nx * sizeof *mine);
    return 1;
}

int mc_dist_gather_slab_u8(const unsigned char *mine, unsigned char *whole, int r0, int nr, int nx)
{
    if (nr > 0)
        memcpy(whole + (size_t)r0 * nx, mine, (size_t)nr * nx);
    return 1;
}
#endif
