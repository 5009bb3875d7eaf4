/* mpi_check.h - the checks the MPI test programs share (tests/mpi/mpi_operator.c, mpi_eigen.c):
 * a pass/fail counter printed by rank 0, the relative max-norm difference of two fields, and an
 * FNV-1a hash of a field's bits. Included once per test program (static definitions). */
#ifndef MC_MPI_CHECK_H
#define MC_MPI_CHECK_H

#include <fftw3-mpi.h>
#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>

#include "core/dist.h"
#include "core/threads.h"

static int passed, failed, rank;

/* One check: rel <= tol passes; rank 0 prints the line. */
static void check(const char *what, double rel, double tol)
{
    const int ok = rel <= tol;
    ok ? passed++ : failed++;
    if (rank == 0)
        printf("%s %s: max |a - b| / max |b| = %.3g (tol %.0e)\n", ok ? "PASS" : "FAIL", what,
               rel, tol);
}

/* max |a - b| / max |b| (max |a - b| when b is zero) */
static double rel_diff(const double *a, const double *b, size_t n)
{
    double d = 0, m = 0;
    for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        m = fmax(m, fabs(b[i]));
    }
    return m > 0 ? d / m : d;
}

static uint64_t hash_bits(const double *v, size_t n) /* FNV-1a over the bytes */
{
    uint64_t h = 1469598103934665603ull;
    const unsigned char *p = (const unsigned char *)v;
    for (size_t i = 0; i < n * sizeof *v; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* MPI and FFTW-MPI started, one thread per process, the run's communicator set, rank (above)
 * and *size filled, the title line printed by rank 0; 0, or 1 when FFTW could not be prepared. */
static int mpi_test_begin(int *argc, char ***argv, const char *title, mc_threads_scope *ts,
                          int *size)
{
    int provided;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    mc_threads_begin(1, ts);
    mc_error err = {0};
    if (mc_fftw_prepare(&err) != MC_OK)
        return 1;
    fftw_mpi_init();
    mc_dist_set(MPI_COMM_WORLD);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
    if (rank == 0)
        printf("%s, %d MPI process%s\n", title, *size, *size > 1 ? "es" : "");
    return 0;
}

#endif
