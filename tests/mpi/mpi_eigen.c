/* mpi_eigen.c - the eigenstrain operators' fft backend distributed over MPI ranks
 * (plastic/eigen_op.h, theory.md §8.4), run under mpirun by tests/cli/mpi.sh with 1, 2 and 3
 * processes.
 *
 * On every grid type the operators accept (free x and y, a window smaller than the grid, the
 * strip: y periodic, doubly periodic with odd periods, the line contact's bars, a graded volume
 * on both depth steps): the residual stress (and its p3) and the residual surface displacement
 * of a random eigenstrain through the distributed operators against the serial fft operators
 * built in the same process (mc_dist_set(MPI_COMM_NULL) around their creation). Rank 0 prints
 * one line per check and, per grid, hashes of the results' bits: the script requires the same
 * hashes for every process count. Closes with "N passed, N failed"; exit 1 on a failure. */
#include <fftw3-mpi.h>
#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/threads.h"
#include "plastic/eigen_internal.h"
#include "plastic/eigen_op.h"
#include "mpi_check.h"

/* Round-off tier: both sides evaluate the same sums over the same kernel spectra; they differ
 * only in the lateral transforms (one-line plans of operator/dfft.c against padfft-style plans
 * over many lines), each a relative error of a few eps log2 n of the largest value, carried
 * through the depth step's 6 x 6 products (~1e-15 measured). 1e-12, the brief's figure, leaves
 * two orders of magnitude and catches any wrong column, block or row (errors of O(1)). */
#define TOL_ROUNDOFF 1e-12

/* the same value on every rank (0 when so) */
static double same_on_ranks(const double *v, size_t n)
{
    double mine = (double)(hash_bits(v, n) >> 12), lo = mine, hi = mine;
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return lo == hi ? 0.0 : 1.0;
}

/* sig (6 nv), p3 (window) and uz (grid) through operators built serially or distributed. */
/* bytes of the built operators against the estimates from the sizes (exact, serial as
 * distributed: the memory guard's figures), on every rank (a rank with fewer columns holds no
 * more than rank 0's estimate) */
static double bytes_off(const mc_grid *g, const mc_eigen_volume *v, const mc_eigen_stress *s,
                        const mc_eigen_disp *d)
{
    size_t parts[MC_EIGEN_STRESS_PARTS], est = 0;
    mc_eigen_stress_estimate(g, v, MC_BACKEND_FFT, parts);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        est += parts[k];
    const size_t sb = mc_eigen_stress_bytes(s), db = mc_eigen_disp_bytes(d);
    const size_t de = mc_eigen_disp_estimate(g, v, MC_BACKEND_FFT);
    double off = rank == 0 ? (sb != est) + (db != de) : (sb > est) + (db > de);
    MPI_Allreduce(MPI_IN_PLACE, &off, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return off;
}

static double bytes_state; /* the last distributed create's bytes_off */

static int apply(const mc_grid *g, const mc_eigen_volume *v, int depth, int distributed,
                 const double *eps, double *sig, double *p3, double *uz)
{
    MPI_Comm saved = mc_dist_comm();
    if (!distributed)
        mc_dist_set(MPI_COMM_NULL);
    mc_eigen_stress *s = NULL;
    mc_eigen_disp *d = NULL;
    mc_error err = {0};
    int rc = mc_eig_stress_create_depth(g, v, 0.3, MC_BACKEND_FFT, depth, &s, &err);
    if (rc == MC_OK)
        rc = mc_eigen_disp_create(g, v, 0.3, MC_BACKEND_FFT, &d, &err);
    if (rc == MC_OK && distributed && depth == MC_EIG_DEPTH_AUTO)
        bytes_state = bytes_off(g, v, s, d);
    if (rc == MC_OK) {
        const size_t nv = (size_t)v->nz * v->ny * v->nx;
        const double *e[6];
        double *o[6];
        for (int c = 0; c < 6; c++) {
            e[c] = eps + c * nv;
            o[c] = sig + c * nv;
        }
        mc_eigen_stress_apply(s, e, 80e9, o);
        mc_eigen_stress_p3(s, p3);
        mc_eigen_disp_apply(d, e, uz);
    } else if (rank == 0) {
        printf("FAIL create: %s\n", err.msg);
    }
    mc_eigen_stress_destroy(&s);
    mc_eigen_disp_destroy(&d);
    mc_dist_set(saved);
    return rc;
}

static void one_case(const char *name, mc_grid g, mc_eigen_volume v, int depth)
{
    const size_t nv = (size_t)v.nz * v.ny * v.nx, nw = (size_t)v.ny * v.nx;
    const size_t ng = mc_grid_cells(&g);
    double *eps = mc_malloc(6 * nv * sizeof *eps);
    double *sd = mc_malloc(6 * nv * sizeof *sd), *ss = mc_malloc(6 * nv * sizeof *ss);
    double *pd = mc_malloc(nw * sizeof *pd), *ps = mc_malloc(nw * sizeof *ps);
    double *ud = mc_malloc(ng * sizeof *ud), *us = mc_malloc(ng * sizeof *us);
    uint64_t r = 987654321; /* the same field on every rank */
    for (size_t i = 0; i < 6 * nv; i++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        eps[i] = 1e-3 * ((double)(r >> 11) / 9007199254740992.0 - 0.3);
    }
    char what[160];
    if (apply(&g, &v, depth, 1, eps, sd, pd, ud) || apply(&g, &v, depth, 0, eps, ss, ps, us)) {
        failed++;
    } else {
        snprintf(what, sizeof what, "%s: residual stress, distributed vs serial fft", name);
        check(what, rel_diff(sd, ss, 6 * nv), TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: p3, distributed vs serial fft", name);
        check(what, rel_diff(pd, ps, nw), TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: residual u_z, distributed vs serial fft", name);
        check(what, rel_diff(ud, us, ng), TOL_ROUNDOFF);
        if (depth == MC_EIG_DEPTH_AUTO) {
            snprintf(what, sizeof what, "%s: bytes of the distributed operators = estimates", name);
            check(what, bytes_state, 0.0);
        }
        snprintf(what, sizeof what, "%s: the same stress and u_z on every rank", name);
        check(what, same_on_ranks(sd, 6 * nv) + same_on_ranks(ud, ng), 0.0);
        if (rank == 0)
            printf("hash %s %016llx %016llx\n", name, (unsigned long long)hash_bits(sd, 6 * nv),
                   (unsigned long long)hash_bits(ud, ng));
    }
    mc_free(eps);
    mc_free(sd);
    mc_free(ss);
    mc_free(pd);
    mc_free(ps);
    mc_free(ud);
    mc_free(us);
}

int main(int argc, char **argv)
{
    int size;
    mc_threads_scope ts;
    if (mpi_test_begin(&argc, &argv, "distributed eigenstrain operators", &ts, &size))
        return 1;
    const double d = 1e-6;
    static const int group[4] = {1, 1, 3, 5};
    const mc_grid free_g = {20, 14, d, 1.3 * d, 0, 0}, big = {26, 18, d, d, 0, 0};
    const mc_grid strip = {18, 12, d, d, 0, 1}, per = {15, 11, d, 1.2 * d, 1, 1};
    const mc_grid line = {30, 1, d, d, 0, 1};
    mc_eigen_volume vf = mc_eigen_volume_full(&free_g, 4, 0.5 * d);
    mc_eigen_volume vw = {5, 3, 13, 9, 3, 0.7 * d, MC_EIG_CELL_AVERAGE, NULL}; /* a window */
    mc_eigen_volume vs = {3, 0, 11, 12, 3, 0.5 * d, MC_EIG_CELL_CENTRE, NULL}; /* strip: all y */
    mc_eigen_volume vp = mc_eigen_volume_full(&per, 3, 0.6 * d);
    mc_eigen_volume vl = mc_eigen_volume_full(&line, 5, 0.5 * d);
    mc_eigen_volume vg = mc_eigen_volume_full(&free_g, 4, 0.3 * d);
    vg.group = group;
    one_case("free 20x14x4", free_g, vf, MC_EIG_DEPTH_AUTO);
    const mc_grid small = {12, 10, d, d, 0, 0}; /* 11 layers: batches of 8 and 3 */
    one_case("free 12x10x11", small, mc_eigen_volume_full(&small, 11, 0.4 * d), MC_EIG_DEPTH_AUTO);
    one_case("free 26x18, window 13x9x3 at (5,3)", big, vw, MC_EIG_DEPTH_AUTO);
    one_case("strip 18x12 (periodic y), window 11 at 3, centre", strip, vs, MC_EIG_DEPTH_AUTO);
    one_case("doubly periodic 15x11x3", per, vp, MC_EIG_DEPTH_AUTO);
    one_case("line 30x1 (bars)", line, vl, MC_EIG_DEPTH_AUTO);
    one_case("graded 20x14 (1,1,3,5) fine depth step", free_g, vg, MC_EIG_DEPTH_FINE);
    one_case("graded 20x14 (1,1,3,5) coarse depth step", free_g, vg, MC_EIG_DEPTH_COARSE);
    if (rank == 0)
        printf("%d passed, %d failed\n", passed, failed);
    mc_dist_set(MPI_COMM_NULL);
    fftw_mpi_cleanup();
    MPI_Finalize();
    return failed ? 1 : 0;
}
