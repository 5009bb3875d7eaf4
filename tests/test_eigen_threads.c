/* test_eigen_threads.c - the eigenstrain operators' thread count (plastic/eigen_internal.h
 * mc_eig_threads): a volume whose transforms move fewer than MC_THREADS_MIN_CELLS values runs on
 * one thread whatever the run's count (a thread team costs more than it saves there), so its
 * result is bit-for-bit the one-thread result and its per-thread workspaces are those of one
 * thread (mc_eigen_*_bytes: the observable of the count chosen); a larger one runs on the run's threads and agrees
 * with one thread to round-off (the displacement operator sums per-thread partial spectra). */
#include <check.h>
#include <stdlib.h>
#include <string.h>

#include "core/threads.h"
#include "plastic/eigen_op.h"
#include "test_util.h"

enum { NT = 3 }; /* thread counts 1, 2, 3 (3 on a 2-core machine: an uneven split all the same) */

typedef struct {
    double *blk, *eps[6], *sig[NT][6], *uz[NT], *uzs[NT]; /* uzs: the shared-forward apply */
    size_t bytes[NT][2]; /* [threads - 1][stress, displacement]: workspaces are per thread */
    int repeat_same[NT]; /* [threads - 1]: every repetition gave the first one's bits */
} fields;

/* Apply both fft operators on grid n x n (dx 1 um, dy 1.2 um), volume n x n x nz (dz 0.9 um)
 * with one, two and three threads; results in f (1 thread: index 0). */
static void run_both(int n, int nz, fields *f)
{
    const mc_grid g = {n, n, 1e-6, 1.2e-6, 0, 0};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, nz, 0.9e-6);
    const size_t nv = (size_t)n * n * nz, ns = (size_t)n * n;
    f->blk = malloc((6 * (NT + 1) * nv + 2 * NT * ns) * sizeof *f->blk);
    ck_assert_ptr_nonnull(f->blk);
    for (int c = 0; c < 6; c++) {
        f->eps[c] = f->blk + c * nv;
        for (int r = 0; r < NT; r++)
            f->sig[r][c] = f->blk + (6 * (r + 1) + c) * nv;
    }
    for (int r = 0; r < NT; r++) {
        f->uz[r] = f->blk + 6 * (NT + 1) * nv + 2 * r * ns;
        f->uzs[r] = f->uz[r] + ns;
    }
    test_random_field(f->blk, 6 * nv, 7);
    for (int r = 0; r < NT; r++) {
        mc_threads_scope scope;
        mc_threads_begin(r + 1, &scope);
        mc_eigen_stress *s = NULL;
        mc_eigen_disp *d = NULL;
        mc_error err = {0};
        ck_assert_int_eq(mc_eigen_stress_create(&g, &v, 0.3, MC_BACKEND_FFT, &s, &err), MC_OK);
        ck_assert_int_eq(mc_eigen_disp_create(&g, &v, 0.3, MC_BACKEND_FFT, &d, &err), MC_OK);
        f->bytes[r][0] = mc_eigen_stress_bytes(s);
        f->bytes[r][1] = mc_eigen_disp_bytes(d);
        /* repeated: the same count must give the same bits every time */
        double *first = malloc((nv + ns) * sizeof *first);
        ck_assert_ptr_nonnull(first);
        f->repeat_same[r] = 1;
        for (int rep = 0; rep < 6; rep++) {
            mc_eigen_stress_apply(s, (const double *const *)f->eps, 80e9, f->sig[r]);
            mc_eigen_disp_apply(d, (const double *const *)f->eps, f->uz[r]);
            if (rep == 0) {
                memcpy(first, f->sig[r][0], nv * sizeof *first);
                memcpy(first + nv, f->uz[r], ns * sizeof *first);
            } else {
                f->repeat_same[r] &= memcmp(first, f->sig[r][0], nv * sizeof *first) == 0 &&
                                     memcmp(first + nv, f->uz[r], ns * sizeof *first) == 0;
            }
        }
        free(first);
        ck_assert(mc_eigen_disp_shares(d, s));
        mc_eigen_disp_apply_shared(d, s, (const double *const *)f->eps, f->uzs[r]);
        mc_eigen_stress_destroy(&s);
        mc_eigen_disp_destroy(&d);
        mc_threads_end(&scope);
    }
}

/* 12^2 x 4: 12 nz (2 m)^2 = 12 x 4 x 24^2 = 27648 values < MC_THREADS_MIN_CELLS: one thread */
START_TEST(test_small_volume_one_thread)
{
    fields f;
    const int n = 12, nz = 4;
    ck_assert(12L * nz * (2 * n) * (2 * n) < MC_THREADS_MIN_CELLS);
    run_both(n, nz, &f);
    const size_t nv = (size_t)n * n * nz;
    for (int r = 1; r < NT; r++) {
        for (int c = 0; c < 6; c++)
            ck_assert(memcmp(f.sig[0][c], f.sig[r][c], nv * sizeof(double)) == 0);
        ck_assert(memcmp(f.uz[0], f.uz[r], (size_t)n * n * sizeof(double)) == 0);
        ck_assert_uint_eq(f.bytes[r][0], f.bytes[0][0]);
        ck_assert_uint_eq(f.bytes[r][1], f.bytes[0][1]);
    }
    free(f.blk);
}
END_TEST

/* 32^2 x 16: 6 nz (2 m)^2 = 393216 values >= MC_THREADS_MIN_CELLS for both operators: the run's
 * threads, the one-thread result's bits (stresses, u_z, and u_z from the shared forward) */
START_TEST(test_large_volume_threads)
{
    fields f;
    const int n = 32, nz = 16;
    ck_assert(6L * nz * (2 * n) * (2 * n) >= MC_THREADS_MIN_CELLS);
    run_both(n, nz, &f);
    const size_t nv = (size_t)n * n * nz, ns = (size_t)n * n;
    for (int r = 1; r < NT; r++) {
        for (int c = 0; c < 6; c++)
            ck_assert_msg(memcmp(f.sig[r][c], f.sig[0][c], nv * sizeof(double)) == 0,
                          "%d threads: stress %d differs by %.3g", r + 1, c,
                          test_rel_maxdiff(f.sig[r][c], f.sig[0][c], nv));
        ck_assert_msg(memcmp(f.uz[r], f.uz[0], ns * sizeof(double)) == 0,
                      "%d threads: u_z differs by %.3g", r + 1,
                      test_rel_maxdiff(f.uz[r], f.uz[0], ns));
        ck_assert_msg(memcmp(f.uzs[r], f.uzs[0], ns * sizeof(double)) == 0,
                      "%d threads: shared u_z differs by %.3g", r + 1,
                      test_rel_maxdiff(f.uzs[r], f.uzs[0], ns));
        ck_assert_uint_gt(f.bytes[r][0], f.bytes[0][0]); /* more threads' workspaces */
        ck_assert_uint_gt(f.bytes[r][1], f.bytes[0][1]);
    }
    ck_assert_msg(f.repeat_same[0] && f.repeat_same[1] && f.repeat_same[2],
                  "repeated applies differ");
    /* the two routes to u_z: the same forward transforms (plans of the same size) and the same
     * blocked sums, hence, measured, the same bits */
    ck_assert_msg(memcmp(f.uzs[0], f.uz[0], ns * sizeof(double)) == 0,
                  "shared and own u_z differ by %.3g", test_rel_maxdiff(f.uzs[0], f.uz[0], ns));
    free(f.blk);
}
END_TEST

Suite *suite_eigen_threads(void);
Suite *suite_eigen_threads(void)
{
    Suite *s = suite_create("eigen_threads");
    TCase *tc = tcase_create("threads");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_small_volume_one_thread);
    tcase_add_test(tc, test_large_volume_threads);
    suite_add_tcase(s, tc);
    return s;
}
