/* test_local_op.c - the near field of the residual stress operator (plastic/local_op.h,
 * docs/theory.md §9.7): its blocks are the residual stress operator's own response to a unit
 * eigenstrain, within the surface correction of the probe's smaller window; spreading
 * (mc_plastic_local_scatter) is the transpose of gathering (mc_plastic_local_apply). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "plastic/eigen_op.h"
#include "plastic/local_op.h"
#include "test_util.h"

/* The probe's window ends 4 + reach cells from the source; beyond it the probe misses the surface
 * traction of S1 + S2 that S3 cancels, which decays as the cube of the distance (eigen_op.h).
 * Measured on the 40 x 40 x 8 volume below (dz = dx / 4): the blocks within reach differ from
 * the large operator's response by 1.2e-5 of the largest stress (MC_TEST_VERBOSE); 1e-3 leaves a
 * margin for other volumes and is far below what an index, sign or component mix-up gives (order
 * one: an offset taken with the wrong sign failed at 0.20). */
#define NEAR_TOL 1e-3

/* Spreading and gathering are the same sums in another order: round-off. */
#define TRANSPOSE_TOL 1e-12

START_TEST(blocks_match_operator)
{
    const mc_grid g = {.nx = 40, .ny = 40, .dx = 0.8e-6, .dy = 0.8e-6};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, 8, 0.2e-6);
    const int reach = 1, reach_z = 4;
    const size_t nv = (size_t)g.nx * g.ny * v.nz;
    mc_error err = {0};
    mc_eigen_stress *S = NULL;
    mc_plastic_local *N = NULL;
    ck_assert_msg(mc_eigen_stress_create(&g, &v, 0.3, MC_BACKEND_FFT, &S, &err) == MC_OK, "%s",
                  err.msg);
    ck_assert_msg(mc_plastic_local_create(&g, &v, 0.3, reach, reach_z, &N, &err) == MC_OK, "%s",
                  err.msg);
    double *f = mc_zeros(12 * nv), *d0 = mc_zeros(6 * nv), *corr = mc_zeros(6 * nv);
    int *active = mc_malloc(nv * sizeof *active);
    ck_assert(f && d0 && corr && active);
    for (size_t c = 0; c < nv; c++)
        active[c] = (int)c; /* every cell active, d0 = 0 */
    const double *e[6];
    double *s[6];
    for (int q = 0; q < 6; q++) {
        e[q] = f + (size_t)q * nv;
        s[q] = f + (size_t)(6 + q) * nv;
    }
    const double G = 80e9;
    double worst = 0, worst_t = 0, largest = 0;
    const int ci = 20, cj = 17;
    for (int ks = 0; ks < v.nz; ks += 3)
        for (int q = 0; q < 6; q++) {
            double *eq = f + (size_t)q * nv;
            const size_t src = ((size_t)ks * g.ny + cj) * g.nx + ci;
            eq[src] = 1e-3;
            mc_eigen_stress_apply(S, e, G, s);
            double r6[6] = {0};
            r6[q] = 1e-3;
            memset(corr, 0, 6 * nv * sizeof *corr);
            mc_plastic_local_scatter(N, r6, active, ks, cj, ci, corr);
            for (int k = 0; k < v.nz; k++)
                for (int dj = -reach; dj <= reach; dj++)
                    for (int di = -reach; di <= reach; di++) {
                        const size_t t = ((size_t)k * g.ny + (size_t)(cj + dj)) * g.nx +
                                         (size_t)(ci + di);
                        double near[6];
                        mc_plastic_local_apply(N, f, d0, active, G, k, cj + dj, ci + di, near);
                        for (int c = 0; c < 6; c++) {
                            largest = test_worst(largest, fabs(s[c][t]));
                            worst_t = test_worst(worst_t, fabs(G * corr[6 * t + c] - near[c]));
                            if (abs(k - ks) <= reach_z)
                                worst = test_worst(worst, fabs(near[c] - s[c][t]));
                            else /* beyond the depth reach: nothing */
                                ck_assert(near[c] == 0.0);
                        }
                    }
            eq[src] = 0.0;
        }
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "near field: blocks within %.2e, spread vs gathered %.2e of the largest "
                        "stress %.3e Pa\n", worst / largest, worst_t / largest, largest);
    ck_assert(largest > 0);
    ck_assert_msg(worst <= NEAR_TOL * largest, "blocks off by %g of %g", worst, largest);
    ck_assert_msg(worst_t <= TRANSPOSE_TOL * largest, "spread vs gathered: %g of %g", worst_t,
                  largest);
    ck_assert(mc_plastic_local_bytes(N) > 0);
    mc_free(f);
    mc_free(d0);
    mc_free(corr);
    mc_free(active);
    mc_plastic_local_destroy(&N);
    mc_plastic_local_destroy(&N); /* NULL-safe */
    mc_eigen_stress_destroy(&S);
}
END_TEST

Suite *suite_local_op(void);
Suite *suite_local_op(void)
{
    Suite *s = suite_create("local_op");
    TCase *t = tcase_create("near_field");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, blocks_match_operator);
    suite_add_tcase(s, t);
    return s;
}
