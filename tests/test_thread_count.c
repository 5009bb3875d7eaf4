/* test_thread_count.c - the solvers' results do not depend on the thread count.
 *
 * The O(N) loops of the contact solvers (cg, its nested variant for a cap, pk, the residual, the
 * preconditioner) and of the Anderson mixing run on the run's threads from MC_THREADS_MIN_CELLS
 * cells on; their sums are taken in blocks fixed by the array length (core/psum.h), never in an
 * order that depends on the threads. Here: the blocked sums give the same bits on 1, 2 and 3
 * threads and the plain left-to-right sum up to MC_THREADS_MIN_CELLS values; a contact solve on a
 * grid above that size (so its loops do run threaded) gives the same pressure on 1 and 2 threads
 * (cg free and capped, pk), bit for bit: FFTW's threaded transforms share out whole 1-D
 * transforms, each computed as on one thread (measured: identical bits), so nothing else
 * depends on the count. Mutation tried:
 * an OpenMP reduction(+) in mc_psum_dot instead of the blocks turns test_psum_bits and both
 * solve tests red (the pressures then differ by 4e-15 and 9e-14 relative: below any tolerance
 * a looser test could have used); the same in pk's masked dot products turns test_pk_threads
 * red (3e-15). */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "core/psum.h"
#include "core/threads.h"
#include "operator/operator.h"
#include "test_util.h"

#define E_STAR 115.4e9
#define PK_ITERATIONS 40

START_TEST(test_psum_bits)
{
    /* above the threshold: several blocks, a short last one */
    const size_t n = MC_THREADS_MIN_CELLS + 3 * MC_PSUM_BLOCK + 777;
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    unsigned char *mask = malloc(n);
    ck_assert(a && b && mask);
    test_random_field(a, n, 11);
    test_random_field(b, n, 12);
    for (size_t i = 0; i < n; i++)
        mask[i] = b[i] > 0;
    const mc_psum ps = mc_psum_blocks(n);
    ck_assert_int_gt(ps.nb, 1);
    ck_assert_uint_eq(mc_psum_hi(&ps, ps.nb - 1), n);
    double dot[3], msum[3];
    size_t cnt[3];
    for (int t = 0; t < 3; t++) {
        mc_threads_scope scope;
        mc_threads_begin(t + 1, &scope);
        dot[t] = mc_psum_dot(a, b, n);
        msum[t] = mc_psum_masked(a, mask, n, &cnt[t]);
        mc_threads_end(&scope);
    }
    for (int t = 1; t < 3; t++) {
        ck_assert_msg(memcmp(&dot[t], &dot[0], sizeof dot[0]) == 0, "dot: %d threads %.17g vs %.17g",
                      t + 1, dot[t], dot[0]);
        ck_assert(memcmp(&msum[t], &msum[0], sizeof msum[0]) == 0);
        ck_assert_uint_eq(cnt[t], cnt[0]);
    }
    /* the blocks sum what the plain sum sums (to round-off of n terms) */
    double plain = 0;
    for (size_t i = 0; i < n; i++)
        plain += a[i] * b[i];
    ck_assert(fabs(plain - dot[0]) <= 1e-12 * (double)n);
    /* up to the threshold: one block, the plain left-to-right sum bit for bit */
    const size_t m = MC_THREADS_MIN_CELLS;
    ck_assert_int_eq(mc_psum_blocks(m).nb, 1);
    plain = 0;
    for (size_t i = 0; i < m; i++)
        plain += a[i] * b[i];
    const double one = mc_psum_dot(a, b, m);
    ck_assert(memcmp(&plain, &one, sizeof one) == 0);
    free(a), free(b), free(mask);
}
END_TEST

/* A rough flat on n x n cells (> MC_THREADS_MIN_CELLS): waviness plus white noise, loaded so that
 * much of it touches (the bounding box is the grid, no box restriction), with a lubricant lower
 * bound; solved with `threads` threads. cap = 0: force control; cap > 0: approach control with
 * that pressure cap (cg bounded on both sides; under force control a cap takes the nested
 * variant, which repeats the same cg at fixed approaches and costs 8 times as much here). The
 * unpreconditioned pk stops after PK_ITERATIONS (its iterates are what must not depend on the
 * threads; converging would cost it a minute here). */
static void solve(int n, int threads, mc_contact_method method, double cap, double *p,
                  mc_contact_summary *sum)
{
    mc_threads_scope scope;
    mc_threads_begin(threads, &scope);
    const mc_grid g = {n, n, 1e-6, 1e-6, 0, 0};
    const size_t nc = mc_grid_cells(&g);
    double *h = malloc(nc * sizeof *h);
    ck_assert_ptr_nonnull(h);
    test_random_field(h, nc, 5);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const double x = (double)i / n, y = (double)j / n;
            h[(size_t)j * n + i] = 1e-7 * (sin(2 * M_PI * 3 * x) * cos(2 * M_PI * 5 * y) + 1.0 +
                                           0.05 * h[(size_t)j * n + i]);
        }
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_operator_plan_love(&g, E_STAR, MC_BACKEND_FFT, &K, &err), MC_OK);
    const int max_it = method == MC_METHOD_PK ? PK_ITERATIONS : 2000;
    mc_contact_options opt = {method, 1e-8, max_it, E_STAR, 0};
    ck_assert_msg(mc_contact_create(K, &opt, &s, &err) == MC_OK, "%s", err.msg);
    const double area = (double)nc * 1e-12;
    mc_contact_problem pb = {.h = h,
                             .p_lub = 20e6,
                             .p_cap = cap > 0 ? cap : INFINITY,
                             .control = cap > 0 ? MC_CONTROL_APPROACH : MC_CONTROL_FORCE,
                             .load = 400e6 * area,
                             .approach = 7e-7};
    const int rc = mc_contact_solve(s, &pb, p, NULL, NULL, sum, &err);
    ck_assert_msg(rc == MC_OK || (method == MC_METHOD_PK && rc == MC_NOT_CONVERGED), "solve: %s",
                  err.msg);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    free(h);
    mc_threads_end(&scope);
}

static void one_against_two(mc_contact_method method, double cap)
{
    const int n = 520; /* 270400 cells > MC_THREADS_MIN_CELLS */
    const size_t nc = (size_t)n * n;
    ck_assert(nc > MC_THREADS_MIN_CELLS);
    double *p1 = malloc(nc * sizeof *p1), *p2 = malloc(nc * sizeof *p2);
    ck_assert(p1 && p2);
    mc_contact_summary s1, s2;
    solve(n, 1, method, cap, p1, &s1);
    solve(n, 2, method, cap, p2, &s2);
    /* much of the grid carries solid load: the full-grid loops ran, not a small box */
    ck_assert_msg(s1.contact_ratio > 0.25, "contact ratio %g", s1.contact_ratio);
    if (cap > 0)
        ck_assert_int_gt(s1.capped_cells, 0);
    ck_assert_int_eq(s1.iterations, s2.iterations);
    ck_assert_msg(memcmp(p1, p2, nc * sizeof *p1) == 0,
                  "1 vs 2 threads: pressures differ by %g (relative)", test_rel_maxdiff(p2, p1, nc));
    free(p1), free(p2);
}

START_TEST(test_cg_threads) { one_against_two(MC_METHOD_CG, 0); }
END_TEST

START_TEST(test_cg_capped_threads) { one_against_two(MC_METHOD_CG, 600e6); }
END_TEST

START_TEST(test_pk_threads) { one_against_two(MC_METHOD_PK, 0); }
END_TEST

Suite *suite_thread_count(void);
Suite *suite_thread_count(void)
{
    Suite *s = suite_create("thread_count");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_psum_bits);
    tcase_add_test(tc, test_cg_threads);
    tcase_add_test(tc, test_cg_capped_threads);
    tcase_add_test(tc, test_pk_threads);
    suite_add_tcase(s, tc);
    return s;
}
