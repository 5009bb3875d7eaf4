/* test_eigen_loads.c - surface loads folded into the residual stress operator
 * (mc_eigen_stress_loads, mc_eigen_stress_apply_loaded; docs/theory.md §8.9): on free, graded,
 * strip, doubly periodic and line grids, with both backends,
 *   - S eps + the folded loads' stresses equals mc_eigen_stress_apply plus mc_stress_field of the
 *     stress module's plan at the layers' centres (the loop's former elastic stresses);
 *   - the loads alone (eps NULL) equal mc_stress_field, and p3 is zero;
 *   - the fft and direct backends agree;
 *   - the plain apply is untouched by the folding, and the bytes grow by the estimate;
 * the forward transforms shared with the displacement operator (mc_eigen_stress_forward,
 * mc_eigen_disp_apply_shared, mc_eigen_stress_apply_forwarded);
 * and the refusals (a window smaller than the grid, q_x without p, folding twice). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plastic/eigen_op.h"
#include "stress/stress.h"
#include "eigen_testkit.h"
#include "test_util.h"

static const double NU = 0.3;
#define G_MOD (210e9 / (2.0 * (1.0 + NU)))

/* The same kernel tables through different transforms (the folded spectra of the operator's
 * quadrant transforms against the stress plan's own): round-off, measured <= 3e-15 of the largest
 * stress; 1e-12 leaves room for larger grids and other FFTW plans. */
#define TOL_SAME 1e-12
/* Periodic axes: the stress module's periodic tables are not exactly even or odd in the offset
 * (their image sums are truncated at M periods and smeared beyond, per offset; measured 3e-11 of
 * the largest entry between d and -d on the strip), while the folded quadrant holds the offsets
 * 0 .. n/2 and the rest by parity: the two differ within the tables' own accuracy, 5e-10 of the
 * largest entry (stress.h; measured 2e-10 of the largest stress on the line grid). */
#define TOL_PERIODIC 1e-9
/* fft against the direct sums of the same tables (as test_eigen_periodic.c). */
#define TOL_BACKENDS 1e-10

typedef struct {
    int nx, ny, px, py, nz;
    double dx, dy, dz;
    int graded; /* 1: layers of 1, 3, 1 fine layers */
} lcase;

static const lcase cases[] = {
    {9, 7, 0, 0, 3, 1e-6, 1.1e-6, 0.5e-6, 0},  /* free */
    {8, 6, 0, 0, 3, 1e-6, 1e-6, 0.4e-6, 1},    /* free, graded */
    {10, 8, 0, 1, 3, 1e-6, 1e-6, 0.5e-6, 0},   /* strip (y periodic) */
    {8, 6, 1, 1, 2, 1e-6, 1e-6, 0.5e-6, 0},    /* doubly periodic, even */
    {7, 9, 1, 1, 2, 1.1e-6, 0.9e-6, 0.7e-6, 0},/* doubly periodic, odd */
    {12, 1, 1, 1, 3, 1e-6, 1e-6, 0.5e-6, 0},   /* line grid periodic along x */
};
#define N_CASES ((int)(sizeof cases / sizeof cases[0]))
static const int GROUP[3] = {1, 3, 1};

static mc_grid grid_of(const lcase *c)
{
    mc_grid g = {c->nx, c->ny, c->dx, c->dy, c->px, c->py};
    return g;
}

static mc_eigen_volume vol_of(const lcase *c)
{
    mc_eigen_volume v = mc_eigen_volume_full(&(mc_grid){c->nx, c->ny, c->dx, c->dy, c->px, c->py},
                                             c->nz, c->dz);
    v.group = c->graded ? GROUP : NULL;
    return v;
}

/* sig = the stress module's stresses of p, qx at the volume's layer centres */
static void stress_module(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                          const double *p, const double *qx, double *const sig[6])
{
    double depths[8];
    for (int k = 0; k < v->nz; k++)
        depths[k] = mc_eigen_layer_depth(v, k);
    mc_stress_options so = {.kernel = MC_STRESS_PATCH, .nu = NU, .nlayers = v->nz,
                            .depths = depths, .backend = b,
                            .loads = MC_TRACTION_P | MC_TRACTION_QX};
    mc_stress_plan *plan = NULL;
    mc_error err;
    ck_assert_msg(mc_stress_create(g, &so, &plan, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_stress_field(plan, p, qx, NULL, sig, &err) == MC_OK, "%s", err.msg);
    mc_stress_destroy(&plan);
}

/* _i = 2 case + backend (0 fft, 1 direct) */
START_TEST(test_folded)
{
    const lcase *lc = &cases[_i / 2];
    const mc_backend b = (_i & 1) ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = grid_of(lc);
    const mc_eigen_volume v = vol_of(lc);
    const size_t ns = mc_grid_cells(&g), n = ns * v.nz;
    double *eps[6], *plain[6], *before[6], *ref[6], *fold[6], *alone[6];
    double *be = eig_fields(n, eps), *bp = eig_fields(n, plain), *bb = eig_fields(n, before);
    double *br = eig_fields(n, ref), *bf = eig_fields(n, fold), *ba = eig_fields(n, alone);
    double *p = malloc(ns * sizeof *p), *qx = malloc(ns * sizeof *qx), *p3 = malloc(ns * sizeof *p3);
    test_random_field(be, 6 * n, 11 + (unsigned)_i);
    for (size_t i = 0; i < 6 * n; i++)
        be[i] *= 1e-3;
    test_random_field(p, ns, 31 + (unsigned)_i);
    test_random_field(qx, ns, 41 + (unsigned)_i);
    for (size_t i = 0; i < ns; i++) { /* a pressure of ~1 GPa, a traction a tenth of it */
        p[i] = 1e9 * (1.0 + p[i]);
        qx[i] *= 1e8;
    }
    mc_eigen_stress *op = eig_stress_op(&g, &v, NU, b);
    mc_eigen_stress_apply(op, (const double *const *)eps, G_MOD, before);
    const size_t bytes0 = mc_eigen_stress_bytes(op);
    mc_error err;
    ck_assert_int_eq(mc_eigen_stress_loads_of(op), 0);
    ck_assert_msg(mc_eigen_stress_loads(op, MC_TRACTION_P | MC_TRACTION_QX, &err) == MC_OK, "%s",
                  err.msg);
    ck_assert_int_eq(mc_eigen_stress_loads_of(op), MC_TRACTION_P | MC_TRACTION_QX);
    const size_t grew = mc_eigen_stress_bytes(op) - bytes0;
    const size_t est = mc_eigen_stress_loads_estimate(&g, &v, b, 0, MC_TRACTION_P | MC_TRACTION_QX);
    ck_assert_msg(grew == est, "case %d: folding took %zu bytes, the estimate says %zu", _i, grew,
                  est);
    ck_assert(grew > 0);
    mc_eigen_stress_apply(op, (const double *const *)eps, G_MOD, plain);
    mc_eigen_stress_apply_loaded(op, (const double *const *)eps, G_MOD, p, qx, fold);
    mc_eigen_stress_apply_loaded(op, NULL, G_MOD, p, qx, alone);
    mc_eigen_stress_p3(op, p3);
    stress_module(&g, &v, b, p, qx, ref);
    /* the plain apply is the same bits as before the folding */
    ck_assert_msg(memcmp(bb, bp, 6 * n * sizeof *bb) == 0, "case %d: plain apply changed", _i);
    const double e_alone = test_rel_maxdiff(ba, br, 6 * n);
    for (size_t i = 0; i < 6 * n; i++)
        br[i] += bp[i];
    const double e_fold = test_rel_maxdiff(bf, br, 6 * n);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "loads case %d (%s): folded vs apply + stress field %.3g, loads alone %.3g\n",
                _i / 2, b == MC_BACKEND_FFT ? "fft" : "direct", e_fold, e_alone);
    const double tol = lc->px || lc->py ? TOL_PERIODIC : TOL_SAME;
    ck_assert_msg(e_fold <= tol, "case %d: folded vs apply + stress field %.3g", _i, e_fold);
    ck_assert_msg(e_alone <= tol, "case %d: loads alone vs stress field %.3g", _i, e_alone);
    ck_assert_msg(eig_max_abs(p3, ns) == 0.0, "case %d: p3 of a zero eigenstrain", _i);
    ck_assert(eig_max_abs(ba, 6 * n) > 1e8);
    mc_eigen_stress_destroy(&op);
    free(p), free(qx), free(p3), free(be), free(bp), free(bb), free(br), free(bf), free(ba);
}
END_TEST

/* the fft and direct backends of the folded apply */
START_TEST(test_backends)
{
    const lcase *lc = &cases[_i];
    const mc_grid g = grid_of(lc);
    const mc_eigen_volume v = vol_of(lc);
    const size_t ns = mc_grid_cells(&g), n = ns * v.nz;
    double *eps[6], *sd[6], *sf[6];
    double *be = eig_fields(n, eps), *bd = eig_fields(n, sd), *bf = eig_fields(n, sf);
    double *p = malloc(ns * sizeof *p), *qx = malloc(ns * sizeof *qx);
    test_random_field(be, 6 * n, 5 + (unsigned)_i);
    for (size_t i = 0; i < 6 * n; i++)
        be[i] *= 1e-3;
    test_random_field(p, ns, 7 + (unsigned)_i);
    test_random_field(qx, ns, 9 + (unsigned)_i);
    for (size_t i = 0; i < ns; i++) {
        p[i] *= 1e9;
        qx[i] *= 1e8;
    }
    mc_eigen_stress *od = eig_stress_op(&g, &v, NU, MC_BACKEND_DIRECT);
    mc_eigen_stress *of = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_error err;
    ck_assert(mc_eigen_stress_loads(od, MC_TRACTION_P | MC_TRACTION_QX, &err) == MC_OK);
    ck_assert(mc_eigen_stress_loads(of, MC_TRACTION_P | MC_TRACTION_QX, &err) == MC_OK);
    mc_eigen_stress_apply_loaded(od, (const double *const *)eps, G_MOD, p, qx, sd);
    mc_eigen_stress_apply_loaded(of, (const double *const *)eps, G_MOD, p, qx, sf);
    const double e = test_rel_maxdiff(bf, bd, 6 * n);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "loads case %d: fft vs direct %.3g\n", _i, e);
    ck_assert_msg(e <= TOL_BACKENDS, "case %d: folded fft vs direct %.3g", _i, e);
    mc_eigen_stress_destroy(&od);
    mc_eigen_stress_destroy(&of);
    free(p), free(qx), free(be), free(bd), free(bf);
}
END_TEST

/* The forward transforms shared by both operators: u_z from the stress operator's layer spectra
 * against the displacement operator's own transforms (the same transforms of the same size and
 * the same sum blocks, eigen_internal.h mc_eig_sum_blocks: the same bits), and the forwarded
 * stress apply against the plain one (the same spectra: the same bits). _i = 2 case + backend;
 * the direct backend shares nothing and falls back to the plain applies (the same bits). */
START_TEST(test_shared_forward)
{
    const lcase *lc = &cases[_i / 2];
    const mc_backend b = (_i & 1) ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = grid_of(lc);
    const mc_eigen_volume v = vol_of(lc);
    const size_t ns = mc_grid_cells(&g), n = ns * v.nz;
    double *eps[6], *s1[6], *s2[6];
    double *be = eig_fields(n, eps), *b1 = eig_fields(n, s1), *b2 = eig_fields(n, s2);
    double *p = malloc(ns * sizeof *p), *u1 = malloc(ns * sizeof *u1), *u2 = malloc(ns * sizeof *u2);
    test_random_field(be, 6 * n, 3 + (unsigned)_i);
    test_random_field(p, ns, 13 + (unsigned)_i);
    for (size_t i = 0; i < 6 * n; i++)
        be[i] *= 1e-3;
    for (size_t i = 0; i < ns; i++)
        p[i] *= 1e9;
    mc_eigen_stress *so = eig_stress_op(&g, &v, NU, b);
    mc_eigen_disp *dop = eig_disp_op(&g, &v, NU, b);
    mc_error err;
    ck_assert(mc_eigen_stress_loads(so, MC_TRACTION_P, &err) == MC_OK);
    ck_assert_int_eq(mc_eigen_disp_shares(dop, so), b == MC_BACKEND_FFT);
    const double *const *e = (const double *const *)eps;
    mc_eigen_disp_apply(dop, e, u1);
    mc_eigen_stress_apply_loaded(so, e, G_MOD, p, NULL, s1);
    mc_eigen_disp_apply_shared(dop, so, e, u2);
    ck_assert(mc_eigen_stress_forwarded(so));
    mc_eigen_stress_apply_forwarded(so, G_MOD, p, NULL, s2);
    ck_assert(!mc_eigen_stress_forwarded(so));
    const double eu = test_rel_maxdiff(u2, u1, ns);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "shared forward case %d (%s): u_z %.3g\n", _i / 2,
                b == MC_BACKEND_FFT ? "fft" : "direct", eu);
    ck_assert_msg(memcmp(u1, u2, ns * sizeof *u1) == 0, "case %d: u_z from the shared spectra %.3g",
                  _i, eu);
    ck_assert_msg(memcmp(b1, b2, 6 * n * sizeof *b1) == 0, "case %d: forwarded apply differs", _i);
    ck_assert(eig_max_abs(u1, ns) > 0.0);
    /* another apply forgets the forward: apply_forwarded gives the loads alone */
    mc_eigen_stress_forward(so, e);
    mc_eigen_stress_apply(so, e, G_MOD, s2);
    ck_assert(!mc_eigen_stress_forwarded(so));
    mc_eigen_stress_apply_forwarded(so, G_MOD, p, NULL, s2);
    mc_eigen_stress_apply_loaded(so, NULL, G_MOD, p, NULL, s1);
    ck_assert(memcmp(b1, b2, 6 * n * sizeof *b1) == 0);
    mc_eigen_stress_destroy(&so);
    mc_eigen_disp_destroy(&dop);
    free(p), free(u1), free(u2), free(be), free(b1), free(b2);
}
END_TEST

START_TEST(test_refused)
{
    const mc_grid g = {9, 7, 1e-6, 1e-6, 0, 0};
    mc_eigen_volume v = mc_eigen_volume_full(&g, 2, 0.5e-6);
    mc_error err;
    mc_eigen_stress *op = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    ck_assert_int_eq(mc_eigen_stress_loads(op, MC_TRACTION_QX, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_eigen_stress_loads(op, MC_TRACTION_P | MC_TRACTION_QY, &err),
                     MC_ERR_INPUT);
    ck_assert_int_eq(mc_eigen_stress_loads(op, MC_TRACTION_P, &err), MC_OK);
    ck_assert_int_eq(mc_eigen_stress_loads(op, MC_TRACTION_P, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "already") != NULL);
    mc_eigen_stress_destroy(&op);
    v.i0 = 1;
    v.nx = 6; /* a window inside the grid */
    op = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    ck_assert_int_eq(mc_eigen_stress_loads(op, MC_TRACTION_P, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "whole grid") != NULL, "%s", err.msg);
    ck_assert_int_eq(mc_eigen_stress_loads_estimate(&g, &v, MC_BACKEND_FFT, 0, MC_TRACTION_P), 0);
    mc_eigen_disp *dop = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    ck_assert_int_eq(mc_eigen_disp_shares(dop, op), 0); /* a window: its own transforms */
    mc_eigen_disp_destroy(&dop);
    mc_eigen_stress_destroy(&op);
}
END_TEST

Suite *suite_eigen_loads(void);
Suite *suite_eigen_loads(void)
{
    Suite *s = suite_create("eigen_loads");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_folded, 0, 2 * N_CASES);
    tcase_add_loop_test(tc, test_backends, 0, N_CASES);
    tcase_add_loop_test(tc, test_shared_forward, 0, 2 * N_CASES);
    tcase_add_test(tc, test_refused);
    suite_add_tcase(s, tc);
    return s;
}
