/* mpi_operator.c - the elastic operator distributed over MPI ranks (operator/dfft.h), run under
 * mpirun by tests/cli/mpi.sh with 1, 2, 3 and 4 processes.
 *
 * On grids that make every part of the slab layout work (free and periodic axes, odd sizes,
 * dx != dy, one row, more ranks than rows or spectrum columns): u = K f of the distributed fft
 * operator against the O(N^2) direct sum (the independent reference) and against the serial fft
 * operator, for the even Love kernel (the real-spectrum path) and an odd kernel (the complex
 * path). Rank 0 prints one line per check and, per grid and kernel, a hash of the result's bits:
 * the script requires the same hashes for every process count (the same bits on any P).
 * And the inputs read on rank 0 alone (io/file.h over mc_dist_share_read of core/dist.h): a
 * file that only rank 0 writes reaches every rank byte for byte, a missing one fails on every
 * rank with rank 0's message, a rank without memory for its copy fails every rank alike.
 * Closes with "N passed, N failed"; exit 1 on a failure. */
#include <errno.h>
#include <fftw3-mpi.h>
#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/threads.h"
#include "io/file.h"
#include "operator/dfft.h"
#include "operator/operator.h"
#include "operator/precond.h"
#include "mpi_check.h"

/* Round-off tier: an FFT of length m carries a relative error of a few eps log2 m against the
 * largest value (here < 1e-14 for m <= 256), the direct sum a few eps sqrt(N); 1e-12 leaves two
 * orders of magnitude and still catches any wrong slab, offset or missing row (errors of O(1)). */
#define TOL_ROUNDOFF 1e-12

/* An odd kernel (no symmetry in either offset): its spectrum is complex. */
static double odd_value(double ox, double oy, const void *ctx)
{
    const double *d = ctx;
    const double x = ox / d[0], y = oy / d[1];
    return (1.0 + 0.3 * x - 0.2 * y) / (1.0 + x * x + 2.0 * y * y) + 0.1 * x * y / (3.0 + x * x);
}

/* u = K f through an operator planned serially or distributed. */
static int apply(const mc_grid *g, const mc_kernel_table *t, mc_backend b, int distributed,
                 const double *f, double *u)
{
    MPI_Comm saved = mc_dist_comm();
    if (!distributed)
        mc_dist_set(MPI_COMM_NULL);
    mc_operator *op = NULL;
    mc_error err = {0};
    int rc = mc_operator_plan(g, t, b, &op, &err);
    if (rc == MC_OK)
        mc_operator_apply(op, f, u);
    else if (rank == 0)
        printf("FAIL plan: %s\n", err.msg);
    mc_operator_destroy(&op);
    mc_dist_set(saved);
    return rc;
}

/* The preconditioner's box transform over the ranks (precond.h: mc_precond_create_rows,
 * _set_mask_rows, _apply_slab on each rank's slab of rows, blocks of ceil(ny / P)) against the
 * serial one on the whole grid (a 2-D FFTW plan): the round-off tier; and the same bits for
 * every P (the hash). The mask: an ellipse off the centre (its box smaller than the grid along
 * free axes) and one far cell. */
static void precond_check(const char *name, const mc_grid *g, const double *f)
{
    const int nx = g->nx, ny = g->ny;
    const size_t n = mc_grid_cells(g);
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const int b = (ny + size - 1) / size, r0 = rank * b < ny ? rank * b : ny;
    const int nr = r0 + b < ny ? b : ny - r0;
    unsigned char *mask = mc_calloc(n, 1);
    double *zs = mc_malloc(n * sizeof *zs), *zl = mc_malloc((n + 1) * sizeof *zl),
           *zd = mc_malloc(n * sizeof *zd);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const double x = (i - 0.4 * nx) / (0.3 * nx), y = (j - 0.55 * ny) / (0.3 * ny + 0.5);
            mask[(size_t)j * nx + i] = x * x + y * y < 1.0;
        }
    mask[n - 1] = 1;
    MPI_Comm saved = mc_dist_comm();
    mc_precond *pc = NULL;
    mc_error err = {0};
    mc_dist_set(MPI_COMM_NULL);
    int rc = mc_precond_create(g, &pc, &err);
    if (rc == MC_OK && (rc = mc_precond_set_mask(pc, mask, &err)) == MC_OK)
        mc_precond_apply(pc, mask, f, zs);
    mc_precond_destroy(&pc);
    mc_dist_set(saved);
    const size_t off = (size_t)r0 * nx;
    if (rc == MC_OK && (rc = mc_precond_create_rows(g, r0, nr, &pc, &err)) == MC_OK &&
        (rc = mc_precond_set_mask_rows(pc, mask + off, &err)) == MC_OK)
        mc_precond_apply_slab(pc, mask + off, f + off, zl);
    mc_precond_destroy(&pc);
    char what[160];
    if (mc_dist_max_int(rc != MC_OK)) {
        failed++;
        if (rank == 0)
            printf("FAIL %s preconditioner: %s\n", name, err.msg);
    } else {
        mc_dist_gather_slab(zl, zd, r0, nr, nx);
        snprintf(what, sizeof what, "%s preconditioner over the ranks vs serial", name);
        check(what, rel_diff(zd, zs, n), TOL_ROUNDOFF);
        if (rank == 0)
            printf("hash %s precond %016llx\n", name, (unsigned long long)hash_bits(zd, n));
    }
    mc_free(mask);
    mc_free(zs);
    mc_free(zl);
    mc_free(zd);
}

/* The transposes of one node (shared memory, each rank copying from the others' buffers) and
 * FFTW-MPI's give the same bits (they only move values): single fields and batches of 3
 * interleaved fields, spectra and gathered results. And when one rank cannot make its shared
 * segment (the last: as with /dev/shm full) every rank falls back to FFTW-MPI's alike, without
 * hanging, with the same bits. Breaking the shared copy (an element from the wrong row or rank)
 * shows here and, through the operator, against direct above. */
static void transposes_agree(const char *name, const mc_grid *g, const double *f)
{
    const int nx = g->nx, ny = g->ny, tx = 2 * nx, ty = 2 * ny, m = 3;
    const size_t n = (size_t)nx * (size_t)ny;
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    /* per mode (0 FFTW-MPI's, 1 shared, 2 shared refused on the last rank): results [the single
     * field][the batch's m fields], spectra likewise, and whether the engines were shared */
    double *out[3], *spec[3] = {NULL, NULL, NULL}, *fs = mc_malloc(m * n * sizeof *fs);
    int shared_got[3] = {-1, -1, -1};
    size_t len = 0; /* doubles of one field's spectrum on this rank */
    int ok = fs != NULL;
    for (int mode = 0; mode < 3; mode++)
        ok = (out[mode] = mc_zeros((m + 1) * n)) && ok;
    for (int mode = 0; mode < 3 && ok; mode++) {
        const int was = mc_dfft_shared_transposes(mode > 0);
        mc_dfft_refuse_shared(mode == 2 && rank == size - 1);
        mc_dfft *d1 = NULL, *dm = NULL;
        mc_error err = {0};
        if (mc_dfft_create(nx, ny, tx, ty, &d1, &err) ||
            mc_dfft_create_many(nx, ny, tx, ty, m, &dm, &err) ||
            !(spec[mode] = mc_zeros((m + 1) * (len = mc_dfft_spectrum_len(d1)) + 1))) {
            ok = 0;
        } else {
            shared_got[mode] = mc_dfft_is_shared(d1) + 2 * mc_dfft_is_shared(dm);
            fftw_complex *sp = (fftw_complex *)spec[mode];
            mc_dfft_forward(d1, f, mc_dfft_spectrum(d1), 0);
            memcpy(spec[mode], mc_dfft_spectrum(d1), len * sizeof(double));
            mc_dfft_inverse(d1, out[mode], 0);
            for (int k = 0; k < m; k++) /* the batch: m different fields */
                for (size_t i = 0; i < n; i++)
                    fs[k * n + i] = f[(i + 7 * (size_t)k) % n] * (1.0 + k);
            mc_dfft_forward_many(dm, fs, n, m, sp + len / 2, len / 2);
            double *keep = mc_malloc((m * len + 1) * sizeof *keep); /* (the inverse destroys) */
            if (keep) {
                memcpy(keep, spec[mode] + len, m * len * sizeof *keep);
                mc_dfft_inverse_many(dm, (fftw_complex *)keep, len / 2, m, out[mode] + n, n);
            }
            ok = keep != NULL;
            mc_free(keep);
        }
        mc_dfft_destroy(&d1);
        mc_dfft_destroy(&dm);
        mc_dfft_refuse_shared(0);
        mc_dfft_shared_transposes(was);
    }
    char what[160];
    for (int mode = 0; mode < 3; mode += 2) {
        snprintf(what, sizeof what, "%s: shared-memory transposes and %s, the same bits", name,
                 mode == 0 ? "FFTW-MPI's" : "the fallback when one rank has no shared memory");
        int same = ok && memcmp(out[mode], out[1], (m + 1) * n * sizeof(double)) == 0 &&
                   memcmp(spec[mode], spec[1], (m + 1) * len * sizeof(double)) == 0;
        MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
        check(what, same ? 0.0 : 1.0, 0.0);
    }
    /* the engines took the transposes asked for, on every rank alike */
    int took = shared_got[0] == 0 && shared_got[1] == 3 && shared_got[2] == 0;
    MPI_Allreduce(MPI_IN_PLACE, &took, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    snprintf(what, sizeof what, "%s: shared memory used when asked and possible, on every rank",
             name);
    check(what, took ? 0.0 : 1.0, 0.0);
    for (int mode = 0; mode < 3; mode++) {
        mc_free(out[mode]);
        mc_free(spec[mode]);
    }
    mc_free(fs);
}

static void one_grid(const char *name, mc_grid g)
{
    const size_t n = mc_grid_cells(&g);
    double *f = mc_malloc(n * sizeof *f), *ud = mc_malloc(n * sizeof *ud),
           *us = mc_malloc(n * sizeof *us), *ur = mc_malloc(n * sizeof *ur);
    uint64_t s = 12345; /* the same field on every rank */
    for (size_t i = 0; i < n; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        f[i] = (double)(s >> 11) / 9007199254740992.0 - 0.25;
    }
    /* the table sizes of the fft backend (the direct one reads the same table) */
    mc_conv *c = NULL;
    mc_error err = {0};
    mc_conv_create(&g, MC_BACKEND_FFT, &c, &err);
    int tx, ty;
    mc_conv_table_dims(c, &tx, &ty);
    mc_conv_destroy(&c);
    const double dd[2] = {g.dx, g.dy};
    const mc_kernel_fn odd = {odd_value, NULL, dd};
    for (int kind = 0; kind < 2; kind++) {
        mc_kernel_table t;
        int rc = kind == 0 ? mc_kernel_table_love(&g, tx, ty, 210e9, &t, &err)
                           : mc_kernel_table_build(&g, tx, ty, &odd, 2, &t, &err);
        if (rc != MC_OK) {
            failed++;
            if (rank == 0)
                printf("FAIL %s: table: %s\n", name, err.msg);
            continue;
        }
        const char *kname = kind == 0 ? "love" : "odd";
        char what[128];
        if (apply(&g, &t, MC_BACKEND_FFT, 1, f, ud) || apply(&g, &t, MC_BACKEND_FFT, 0, f, us) ||
            apply(&g, &t, MC_BACKEND_DIRECT, 0, f, ur)) {
            failed++;
        } else {
            snprintf(what, sizeof what, "%s %s distributed fft vs direct", name, kname);
            check(what, rel_diff(ud, ur, n), TOL_ROUNDOFF);
            snprintf(what, sizeof what, "%s %s distributed fft vs serial fft", name, kname);
            check(what, rel_diff(ud, us, n), TOL_ROUNDOFF);
            /* every rank holds the whole result, the same bits as rank 0's */
            double mine = (double)(hash_bits(ud, n) >> 12), lo = mine, hi = mine;
            MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
            MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
            snprintf(what, sizeof what, "%s %s the same result on every rank", name, kname);
            check(what, lo == hi ? 0.0 : 1.0, 0.0);
            if (rank == 0)
                printf("hash %s %s %016llx\n", name, kname, (unsigned long long)hash_bits(ud, n));
            /* the Love operator as the solvers plan it: each rank tabulates and transforms its
             * rows of the table alone (mc_operator_plan_love, mc_conv_kernel_rows): the same
             * bits as from the whole table (the same line transforms; the exchange moves
             * values) */
            mc_operator *op = NULL;
            if (kind == 0 && mc_operator_plan_love(&g, 210e9, MC_BACKEND_FFT, &op, &err) == MC_OK) {
                mc_operator_apply(op, f, us);
                mc_operator_destroy(&op);
                snprintf(what, sizeof what, "%s love: kernel by slabs, the bits of the whole table",
                         name);
                check(what, memcmp(us, ud, n * sizeof *us) ? 1.0 : 0.0, 0.0);
            } else if (kind == 0) {
                failed++;
                if (rank == 0)
                    printf("FAIL %s: plan_love: %s\n", name, err.msg);
            }
        }
        mc_kernel_table_free(&t);
    }
    precond_check(name, &g, f);
    transposes_agree(name, &g, f);
    mc_free(f);
    mc_free(ud);
    mc_free(us);
    mc_free(ur);
}

/* A check that holds on every rank (reported by rank 0). */
static void check_all(const char *what, int ok)
{
    MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    ok ? passed++ : failed++;
    if (rank == 0)
        printf("%s %s\n", ok ? "PASS" : "FAIL", what);
}

/* The inputs read on rank 0 alone: the file exists for rank 0 only in the sense that only rank 0
 * writes it and opens it; the others receive its bytes. */
static void shared_reads(int size)
{
    char path[64] = "/tmp/mc_shared_read_XXXXXX";
    enum { N = 3001 };
    unsigned char want[N];
    for (int k = 0; k < N; k++)
        want[k] = (unsigned char)(k * 7 + k / 13); /* NUL bytes among them */
    int made = 1;
    if (rank == 0) {
        int fd = mkstemp(path);
        made = fd >= 0 && write(fd, want, N) == N;
        if (fd >= 0)
            close(fd);
    }
    MPI_Bcast(&made, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Bcast(path, sizeof path, MPI_CHAR, 0, MPI_COMM_WORLD); /* the same call on every rank */
    if (!made) {
        check_all("shared read: rank 0 could not write its file", 0);
        return;
    }
    unsigned char *buf = NULL;
    size_t len = 0;
    mc_error err = {0};
    int rc = mc_io_read_data(path, 1 << 20, "a test file", &buf, &len, &err);
    check_all("shared read: every rank holds rank 0's bytes and their NUL",
              rc == MC_OK && len == N && memcmp(buf, want, N) == 0 && buf[N] == 0);
    mc_free(buf);

    /* a file that does not exist: every rank fails with rank 0's status and message */
    char none[80], expect[MC_ERROR_MSG_MAX];
    snprintf(none, sizeof none, "%s.none", path);
    snprintf(expect, sizeof expect, "%s: cannot open: %s", none, strerror(ENOENT));
    rc = mc_io_read_file(none, &buf, &len, &err);
    check_all("shared read: a missing file fails on every rank with rank 0's message",
              rc == MC_ERR_IO && err.code == MC_ERR_IO && buf == NULL && len == 0 &&
                  strcmp(err.msg, expect) == 0);

    /* the last rank cannot allocate its copy: every rank fails alike, naming that rank */
    if (size > 1) {
        if (rank == size - 1)
            mc_alloc_fail_at(1); /* its copy is its first allocation in the call */
        rc = mc_io_read_data(path, 1 << 20, "a test file", &buf, &len, &err);
        char rk[32];
        snprintf(rk, sizeof rk, "no memory on rank %d", size - 1);
        check_all("shared read: a rank without memory for its copy fails every rank",
                  rc == MC_ERR_NOMEM && buf == NULL && len == 0 && strstr(err.msg, rk) &&
                      strstr(err.msg, path));
        mc_alloc_fail_at(0);
    }
    if (rank == 0)
        unlink(path);
}

int main(int argc, char **argv)
{
    int size;
    mc_threads_scope ts;
    if (mpi_test_begin(&argc, &argv, "distributed elastic operator", &ts, &size))
        return 1;
    const double d = 1e-6;
    struct {
        const char *name;
        mc_grid g;
    } grids[] = {
        {"free 37x23 dy=1.7dx", {37, 23, d, 1.7 * d, 0, 0}},
        {"free 64x48", {64, 48, d, d, 0, 0}},
        {"free 50x1", {50, 1, d, d, 0, 0}},
        {"free 3x2", {3, 2, d, 2 * d, 0, 0}},
        {"periodic-x 40x17", {40, 17, d, d, 1, 0}},
        {"periodic-y 31x20", {31, 20, 0.8 * d, d, 0, 1}},
        {"periodic 32x24", {32, 24, d, 1.3 * d, 1, 1}},
        {"line 60x1 periodic-y", {60, 1, d, d, 0, 1}},
    };
    for (size_t k = 0; k < sizeof grids / sizeof grids[0]; k++)
        one_grid(grids[k].name, grids[k].g);
    shared_reads(size);
    if (rank == 0)
        printf("%d passed, %d failed\n", passed, failed);
    mc_dist_set(MPI_COMM_NULL);
    fftw_mpi_cleanup();
    MPI_Finalize();
    return failed ? 1 : 0;
}
