/* test_invariants.c - stress invariants against GSL's symmetric eigensolver and identities. */
#include <check.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "kernels/invariants.h"
#include "kernels/kernel.h"
#include "test_util.h"

/* Principal stresses vs gsl_eigen_symm, per unit Frobenius norm of the tensor. Both methods are
 * backward stable, so eigenvalues agree to a few eps |S|; 64 eps leaves room for the ~20 roundings
 * of each. A plain acos() closed form misses this by 1e-8 at repeated roots, which these tests
 * include on purpose. */
#define TOL_EIG (64.0 * DBL_EPSILON)
/* Identities evaluated in closed form (von Mises of pure shear, rotated tensors): a few roundings
 * of O(1) terms, per unit of the tensor's norm. */
#define TOL_IDENT (32.0 * DBL_EPSILON)
/* Number of random tensors per seed, and seeds (loop tests). */
#define N_RANDOM 4000
#define N_SEEDS 4

static double frob(const double s[6])
{
    return sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

static void gsl_principal(const double s[6], double p[3])
{
    gsl_matrix *m = gsl_matrix_alloc(3, 3);
    gsl_vector *ev = gsl_vector_alloc(3);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc(3);
    ck_assert(m && ev && w);
    gsl_matrix_set(m, 0, 0, s[MC_SXX]);
    gsl_matrix_set(m, 1, 1, s[MC_SYY]);
    gsl_matrix_set(m, 2, 2, s[MC_SZZ]);
    gsl_matrix_set(m, 0, 1, s[MC_SXY]);
    gsl_matrix_set(m, 1, 0, s[MC_SXY]);
    gsl_matrix_set(m, 1, 2, s[MC_SYZ]);
    gsl_matrix_set(m, 2, 1, s[MC_SYZ]);
    gsl_matrix_set(m, 0, 2, s[MC_SXZ]);
    gsl_matrix_set(m, 2, 0, s[MC_SXZ]);
    ck_assert_int_eq(gsl_eigen_symm(m, ev, w), 0);
    double a = gsl_vector_get(ev, 0), b = gsl_vector_get(ev, 1), c = gsl_vector_get(ev, 2);
    p[0] = fmax(a, fmax(b, c));
    p[2] = fmin(a, fmin(b, c));
    p[1] = a + b + c - p[0] - p[2];
    gsl_eigen_symm_free(w);
    gsl_vector_free(ev);
    gsl_matrix_free(m);
}

/* Rotation matrix from a (normalised) quaternion built from three random numbers. */
static void random_rotation(unsigned long long seed, double Q[3][3])
{
    double v[4];
    test_random_field(v, 4, seed);
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    double w = v[0] / n, x = v[1] / n, y = v[2] / n, z = v[3] / n;
    Q[0][0] = 1 - 2 * (y * y + z * z);
    Q[0][1] = 2 * (x * y - z * w);
    Q[0][2] = 2 * (x * z + y * w);
    Q[1][0] = 2 * (x * y + z * w);
    Q[1][1] = 1 - 2 * (x * x + z * z);
    Q[1][2] = 2 * (y * z - x * w);
    Q[2][0] = 2 * (x * z - y * w);
    Q[2][1] = 2 * (y * z + x * w);
    Q[2][2] = 1 - 2 * (x * x + y * y);
}

/* s = Q diag(l) Q^T in kernel.h order */
static void rotated_diag(const double Q[3][3], const double l[3], double s[6])
{
    double S[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double acc = 0.0;
            for (int k = 0; k < 3; k++)
                acc += Q[i][k] * l[k] * Q[j][k];
            S[i][j] = acc;
        }
    s[MC_SXX] = S[0][0];
    s[MC_SYY] = S[1][1];
    s[MC_SZZ] = S[2][2];
    s[MC_SXY] = S[0][1];
    s[MC_SYZ] = S[1][2];
    s[MC_SXZ] = S[0][2];
}

static void check_principal_vs_gsl(const double s[6], double *worst)
{
    double p[3], g[3];
    mc_principal_stresses(s, p);
    gsl_principal(s, g);
    double nrm = frob(s);
    ck_assert(p[0] >= p[1] && p[1] >= p[2]);
    for (int k = 0; k < 3; k++) {
        double e = fabs(p[k] - g[k]) / (nrm > 0 ? nrm : 1.0);
        if (e > *worst)
            *worst = e;
        ck_assert_msg(e <= TOL_EIG, "principal %d: %.17g vs gsl %.17g (err %.3g |S|)", k, p[k],
                      g[k], e);
    }
    /* Tresca from the deviator angle equals half the principal spread */
    ck_assert_msg(fabs(mc_tresca(s) - 0.5 * (p[0] - p[2])) <= TOL_EIG * nrm,
                  "tresca %.17g vs (p1-p3)/2 %.17g", mc_tresca(s), 0.5 * (p[0] - p[2]));
}

START_TEST(test_principal_random)
{
    double *v = malloc(sizeof(double) * 6 * N_RANDOM);
    ck_assert(v != NULL);
    test_random_field(v, 6 * N_RANDOM, 1000ULL + (unsigned long long)_i);
    double worst = 0.0;
    for (int n = 0; n < N_RANDOM; n++) {
        double s[6];
        /* mixed magnitudes (1e-3 .. 1e9) and a hydrostatic offset, as stresses in Pa come */
        double scale = pow(10.0, -3.0 + 12.0 * (0.5 + 0.5 * v[6 * n]));
        for (int c = 0; c < 6; c++)
            s[c] = scale * v[6 * n + c];
        check_principal_vs_gsl(s, &worst);
    }
    free(v);
}
END_TEST

/* Repeated roots: exact, rotated, and nearly repeated (gap 1e-9 |S|); index selects the case. */
START_TEST(test_principal_repeated)
{
    double worst = 0.0;
    const double cases[][3] = {
        {2.0, 2.0, -1.0},        /* axisymmetric, double root on top */
        {3.0, -0.5, -0.5},       /* double root below */
        {-7.0, -7.0, -7.0},      /* hydrostatic */
        {0.0, 0.0, 1.0},         /* uniaxial */
        {1.0, 1.0 + 1e-9, -2.0}, /* nearly double */
        {5e8, 5e8, 5e8 + 1e-3},  /* nearly hydrostatic, big offset */
        {0.0, 0.0, 0.0},         /* zero */
        {1.0, 0.0, -1.0},        /* pure shear, distinct */
    };
    const int ncases = (int)(sizeof cases / sizeof cases[0]);
    int c = _i % ncases;
    const double *l = cases[c];
    double lmax = fmax(fabs(l[0]), fmax(fabs(l[1]), fabs(l[2])));
    double sorted[3] = {l[0], l[1], l[2]};
    for (int a = 0; a < 3; a++) /* sort descending */
        for (int b = a + 1; b < 3; b++)
            if (sorted[b] > sorted[a]) {
                double t = sorted[a];
                sorted[a] = sorted[b];
                sorted[b] = t;
            }
    /* diagonal: exact tensors, exact answers expected to round-off */
    double s[6] = {l[0], l[1], l[2], 0.0, 0.0, 0.0}, p[3];
    mc_principal_stresses(s, p);
    for (int k = 0; k < 3; k++)
        ck_assert_msg(fabs(p[k] - sorted[k]) <= TOL_EIG * (lmax > 0 ? lmax : 1.0),
                      "case %d diag: p%d = %.17g, expected %.17g", c, k, p[k], sorted[k]);
    check_principal_vs_gsl(s, &worst);
    /* rotated: the rounding of Q diag Q^T perturbs the roots by ~eps |S| (Weyl) */
    for (int r = 0; r < 50; r++) {
        double Q[3][3];
        random_rotation(77ULL * (unsigned long long)r + (unsigned long long)c, Q);
        rotated_diag(Q, l, s);
        mc_principal_stresses(s, p);
        for (int k = 0; k < 3; k++)
            ck_assert_msg(fabs(p[k] - sorted[k]) <= TOL_EIG * (lmax > 0 ? lmax : 1.0),
                          "case %d rot %d: p%d = %.17g, expected %.17g (err %.3g)", c, r, k, p[k],
                          sorted[k], fabs(p[k] - sorted[k]) / lmax);
        check_principal_vs_gsl(s, &worst);
    }
}
END_TEST

START_TEST(test_von_mises_identities)
{
    const double tau = -3.7e8, sig = 2.5e8, pr = -1.2e9;
    /* pure shear in each shear component: sqrt(3)|tau|; Tresca |tau| */
    for (int c = MC_SXY; c <= MC_SXZ; c++) {
        double s[6] = {0};
        s[c] = tau;
        ck_assert(fabs(mc_von_mises(s) - sqrt(3.0) * fabs(tau)) <= TOL_IDENT * fabs(tau));
        ck_assert(fabs(mc_tresca(s) - fabs(tau)) <= TOL_IDENT * fabs(tau));
        ck_assert(fabs(mc_hydrostatic(s)) == 0.0);
    }
    /* pure shear as principal stresses (tau, -tau, 0) in a rotated frame */
    for (int r = 0; r < 20; r++) {
        double Q[3][3], s[6], l[3] = {tau, -tau, 0.0};
        random_rotation(500ULL + (unsigned long long)r, Q);
        rotated_diag(Q, l, s);
        ck_assert(fabs(mc_von_mises(s) - sqrt(3.0) * fabs(tau)) <= TOL_IDENT * fabs(tau));
        ck_assert(fabs(mc_tresca(s) - fabs(tau)) <= TOL_IDENT * fabs(tau));
        ck_assert(fabs(mc_hydrostatic(s)) <= TOL_IDENT * fabs(tau));
    }
    /* uniaxial along each axis and rotated: vm = |sig|, Tresca = |sig|/2, hydro = sig/3 */
    for (int c = MC_SXX; c <= MC_SZZ; c++) {
        double s[6] = {0};
        s[c] = sig;
        ck_assert(fabs(mc_von_mises(s) - fabs(sig)) <= TOL_IDENT * fabs(sig));
        ck_assert(fabs(mc_tresca(s) - 0.5 * fabs(sig)) <= TOL_IDENT * fabs(sig));
        ck_assert(fabs(mc_hydrostatic(s) - sig / 3.0) <= TOL_IDENT * fabs(sig));
    }
    for (int r = 0; r < 20; r++) {
        double Q[3][3], s[6], l[3] = {0.0, -sig, 0.0};
        random_rotation(900ULL + (unsigned long long)r, Q);
        rotated_diag(Q, l, s);
        ck_assert(fabs(mc_von_mises(s) - fabs(sig)) <= TOL_IDENT * fabs(sig));
        ck_assert(fabs(mc_tresca(s) - 0.5 * fabs(sig)) <= TOL_IDENT * fabs(sig));
        ck_assert(fabs(mc_hydrostatic(s) + sig / 3.0) <= TOL_IDENT * fabs(sig));
    }
    /* hydrostatic: vm and Tresca exactly 0 on the diagonal form, ~eps |p| rotated */
    {
        double s[6] = {pr, pr, pr, 0.0, 0.0, 0.0};
        ck_assert(mc_von_mises(s) == 0.0);
        ck_assert(mc_tresca(s) == 0.0);
        ck_assert(mc_hydrostatic(s) == pr);
        double Q[3][3], l[3] = {pr, pr, pr};
        random_rotation(4242ULL, Q);
        rotated_diag(Q, l, s);
        ck_assert(mc_von_mises(s) <= TOL_IDENT * fabs(pr));
        ck_assert(mc_tresca(s) <= TOL_IDENT * fabs(pr));
        ck_assert(fabs(mc_hydrostatic(s) - pr) <= TOL_IDENT * fabs(pr));
    }
}
END_TEST

/* Random tensors: vm^2 = ((p1-p2)^2 + (p2-p3)^2 + (p3-p1)^2)/2, hydro = mean of principal
 * stresses, and Tresca / vm within [1/2, 1/sqrt(3)] (pure shear and uniaxial bounds). */
START_TEST(test_invariant_relations)
{
    double v[6 * 500];
    test_random_field(v, 6 * 500, 31337ULL);
    for (int n = 0; n < 500; n++) {
        const double *s = v + 6 * n;
        double p[3];
        mc_principal_stresses(s, p);
        double vm = mc_von_mises(s), tr = mc_tresca(s), nrm = frob(s);
        double vm_p = sqrt(0.5 * ((p[0] - p[1]) * (p[0] - p[1]) + (p[1] - p[2]) * (p[1] - p[2]) +
                                  (p[2] - p[0]) * (p[2] - p[0])));
        ck_assert(fabs(vm - vm_p) <= TOL_EIG * nrm);
        ck_assert(fabs(mc_hydrostatic(s) - (p[0] + p[1] + p[2]) / 3.0) <= TOL_EIG * nrm);
        ck_assert(tr >= 0.5 * vm * (1.0 - TOL_IDENT) && tr <= vm / sqrt(3.0) * (1.0 + TOL_IDENT));
    }
}
END_TEST

/* Non-finite input gives NaN, not a silently finite number. */
START_TEST(test_nonfinite)
{
    double s[6] = {1.0, 2.0, 3.0, NAN, 0.0, 0.0}, p[3];
    mc_principal_stresses(s, p);
    ck_assert(isnan(p[0]) && isnan(p[1]) && isnan(p[2]));
    ck_assert(isnan(mc_tresca(s)));
    ck_assert(isnan(mc_von_mises(s)));
}
END_TEST

/* The volume version equals the scalar functions bit for bit, for 1 and several threads, and
 * with outputs skipped. */
START_TEST(test_volume_equals_scalar)
{
    const size_t n = 10007; /* odd, prime: uneven OpenMP chunks */
    double *buf = malloc(sizeof(double) * n * 9);
    ck_assert(buf != NULL);
    test_random_field(buf, 6 * n, 2024ULL);
    const double *s[6];
    for (int c = 0; c < 6; c++)
        s[c] = buf + (size_t)c * n;
    double *vm = buf + 6 * n, *hy = buf + 7 * n, *tr = buf + 8 * n;
    int threads[2] = {1, 4};
    for (int t = 0; t < 2; t++) {
        omp_set_num_threads(threads[t]);
        mc_error err;
        mc_error_clear(&err);
        memset(vm, 0, sizeof(double) * 3 * n);
        ck_assert_int_eq(
            mc_invariants_volume(n, s[0], s[1], s[2], s[3], s[4], s[5], vm, hy, tr, &err), MC_OK);
        for (size_t i = 0; i < n; i++) {
            double t6[6] = {s[0][i], s[1][i], s[2][i], s[3][i], s[4][i], s[5][i]};
            ck_assert(vm[i] == mc_von_mises(t6));
            ck_assert(hy[i] == mc_hydrostatic(t6));
            ck_assert(tr[i] == mc_tresca(t6));
        }
    }
    /* NULL outputs are skipped: only Tresca written */
    memset(vm, 0, sizeof(double) * 3 * n);
    ck_assert_int_eq(
        mc_invariants_volume(n, s[0], s[1], s[2], s[3], s[4], s[5], NULL, NULL, tr, NULL), MC_OK);
    for (size_t i = 0; i < n; i++) {
        double t6[6] = {s[0][i], s[1][i], s[2][i], s[3][i], s[4][i], s[5][i]};
        ck_assert(vm[i] == 0.0 && hy[i] == 0.0 && tr[i] == mc_tresca(t6));
    }
    free(buf);
}
END_TEST

START_TEST(test_volume_null_input)
{
    double a[1] = {0.0};
    mc_error err;
    mc_error_clear(&err);
    ck_assert_int_eq(mc_invariants_volume(1, a, a, a, NULL, a, a, a, NULL, NULL, &err),
                     MC_ERR_INPUT);
    ck_assert_int_eq(err.code, MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "sxy") != NULL);
    ck_assert_int_eq(mc_invariants_volume(1, a, a, a, a, a, NULL, a, NULL, NULL, NULL),
                     MC_ERR_INPUT);
    ck_assert_int_eq(
        mc_invariants_volume(0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &err), MC_OK);
}
END_TEST

Suite *suite_invariants(void);
Suite *suite_invariants(void)
{
    Suite *s = suite_create("invariants");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_loop_test(tc, test_principal_random, 0, N_SEEDS);
    tcase_add_loop_test(tc, test_principal_repeated, 0, 8);
    tcase_add_test(tc, test_von_mises_identities);
    tcase_add_test(tc, test_invariant_relations);
    tcase_add_test(tc, test_nonfinite);
    tcase_add_test(tc, test_volume_equals_scalar);
    tcase_add_test(tc, test_volume_null_input);
    suite_add_tcase(s, tc);
    return s;
}
