/* test_eigen_spectral_op.c - the spectral eigenstrain operator (src/plastic/eigen_spectral_op.h;
 * docs/theory.md §8.10):
 *   - direct (pair kernels taken to space by a plain DFT, summed cell by cell) against fft (the
 *     running sums per mode, lateral FFTs) on free, strip, doubly periodic (even, odd), x-periodic,
 *     line, graded and deep (e^{-q depth} beyond the up pass's division) volumes, centre and
 *     layer-average points;
 *   - against the cuboid operators (plastic/eigen_op.h, an independent discretisation and kernel):
 *     on a smooth field the two converge to each other like h^2 as the grid is refined;
 *   - identities of the trigonometric field: a y-uniform field on a strip equals the line grid,
 *     a field tiled 2 x 2 equals its period, a laterally uniform field the layer's closed form;
 *   - the refusals. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "plastic/eigen_op.h"
#include "plastic/eigen_spectral_op.h"
#include "stress/stress.h"
#include "eigen_testkit.h"
#include "test_util.h"

static const double NU = 0.3;
static const double G_MOD = 210e9 / 2.6;

/* direct vs fft: the same per-mode kernels summed two ways, round-off */
#define TOL_BACKENDS 1e-10
/* identities of the trigonometric field (the same modes, other transform sizes): round-off */
#define TOL_SAME_MODES 1e-11

typedef struct {
    int nx, ny, px, py, nz;
    double dx, dy, dz;
    int graded;
} scase;

static const scase cases[] = {
    {7, 5, 0, 0, 3, 1e-6, 1.2e-6, 0.5e-6, 0}, /* free */
    {6, 6, 0, 1, 2, 1e-6, 1e-6, 0.4e-6, 0},   /* strip */
    {8, 6, 1, 1, 3, 1e-6, 1e-6, 0.5e-6, 0},   /* doubly periodic, even */
    {7, 9, 1, 1, 2, 1.1e-6, 0.9e-6, 0.7e-6, 0}, /* doubly periodic, odd */
    {6, 5, 1, 0, 2, 1e-6, 1e-6, 0.5e-6, 0},   /* x periodic alone */
    {10, 1, 0, 1, 3, 1e-6, 1e-6, 0.5e-6, 0},  /* line grid (bars along y) */
    {6, 4, 0, 0, 3, 1e-6, 1e-6, 0.25e-6, 1},  /* graded, free */
    {6, 5, 0, 0, 3, 1e-6, 1e-6, 60e-6, 0},    /* deep: e^{-q depth} below the up pass's division
                                                 (q depth up to 800: exp() per layer) */
};
#define N_CASES ((int)(sizeof cases / sizeof cases[0]))
static const int GROUPS[3] = {1, 3, 5};

static mc_grid grid_of(const scase *c)
{
    mc_grid g = {c->nx, c->ny, c->dx, c->dy, c->px, c->py};
    return g;
}

static mc_eigen_volume vol_of(const scase *c, mc_eig_stress_points pt)
{
    mc_eigen_volume v = {0, 0, c->nx, c->ny, c->nz, c->dz, pt, c->graded ? GROUPS : NULL, MC_EIG_KERNEL_CUBOID};
    return v;
}

static mc_eigen_spectral *spec_op(const mc_grid *g, const mc_eigen_volume *v, mc_backend b)
{
    mc_eigen_spectral *op = NULL;
    mc_error err = {0};
    const int rc = mc_eigen_spectral_create(g, v, NU, b, &op, &err);
    ck_assert_msg(rc == MC_OK, "create: %s", err.msg);
    return op;
}

/* ---- direct vs fft ---------------------------------------------------------------------------- */

START_TEST(test_backends)
{
    const scase *sc = &cases[_i / 2];
    const mc_eig_stress_points pt = (_i & 1) ? MC_EIG_CELL_CENTRE : MC_EIG_CELL_AVERAGE;
    const mc_grid g = grid_of(sc);
    const mc_eigen_volume v = vol_of(sc, pt);
    const size_t ns = (size_t)g.nx * g.ny, n = ns * v.nz;
    double *eps[6], *sd[6], *sf[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sd), *b3 = eig_fields(n, sf);
    test_random_field(b1, 6 * n, 5 + (unsigned)_i);
    double *ud = malloc(ns * sizeof *ud), *uf = malloc(ns * sizeof *uf);
    mc_eigen_spectral *od = spec_op(&g, &v, MC_BACKEND_DIRECT), *of = spec_op(&g, &v, MC_BACKEND_FFT);
    mc_eigen_spectral_apply(od, (const double *const *)eps, G_MOD, sd, ud);
    mc_eigen_spectral_apply(of, (const double *const *)eps, G_MOD, sf, uf);
    const double es = test_rel_maxdiff(b3, b2, 6 * n), eu = test_rel_maxdiff(uf, ud, ns);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "spectral case %d (%s): fft vs direct stress %.3g, u_z %.3g\n", _i / 2,
                mc_eig_stress_points_name(pt), es, eu);
    ck_assert_msg(es <= TOL_BACKENDS, "case %d: stress fft vs direct %.3g", _i, es);
    ck_assert_msg(eu <= TOL_BACKENDS, "case %d: u_z fft vs direct %.3g", _i, eu);
    ck_assert(eig_max_abs(b2, 6 * n) > 0.0 && eig_max_abs(ud, ns) > 0.0);
    /* the displacement alone (the layers streamed; the direct tables of u_z only) */
    double *u1 = malloc(ns * sizeof *u1), *u2 = malloc(ns * sizeof *u2);
    for (int b = 0; b < 2; b++) {
        mc_eigen_spectral *ou = NULL;
        mc_error err = {0};
        const mc_backend be = b ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
        ck_assert_int_eq(mc_eigen_spectral_create_uz(&g, &v, NU, be, &ou, &err), MC_OK);
        mc_eigen_spectral_apply_uz(ou, (const double *const *)eps, u1);
        const double e1 = test_rel_maxdiff(u1, ud, ns);
        ck_assert_msg(e1 <= TOL_BACKENDS, "case %d: u_z alone (%s) vs direct %.3g", _i,
                      b ? "direct" : "fft", e1);
        ck_assert_uint_eq(mc_eigen_spectral_estimate_uz(&g, &v, be), mc_eigen_spectral_bytes(ou));
        mc_eigen_spectral_destroy(&ou);
    }
    mc_eigen_spectral_apply_uz(of, (const double *const *)eps, u2); /* a whole object's u_z alone */
    ck_assert(test_rel_maxdiff(u2, ud, ns) <= TOL_BACKENDS);
    free(u1), free(u2);
    /* the estimate is the object's size */
    ck_assert_uint_eq(mc_eigen_spectral_estimate(&g, &v, MC_BACKEND_DIRECT),
                      mc_eigen_spectral_bytes(od));
    ck_assert_uint_eq(mc_eigen_spectral_estimate(&g, &v, MC_BACKEND_FFT),
                      mc_eigen_spectral_bytes(of));
    mc_eigen_spectral_destroy(&od);
    mc_eigen_spectral_destroy(&of);
    free(ud), free(uf), free(b1), free(b2), free(b3);
}
END_TEST

/* ---- a dense field plus a sparse addend (theory.md §9.9) ------------------------------------- */

/* eps + inc read value by value (mc_eigen_spectral_apply_sum, _apply_uz_sum) gives the bits of
 * applying the summed field, on every case and both backends; through the eigen_op interface
 * too, and with the displacement object borrowing the stress object's workspaces (the same bits
 * as its own, both objects applied in turn); objects of the cuboid kernel refuse. */
START_TEST(test_sum_input)
{
    const scase *sc = &cases[_i / 2];
    const mc_backend be = (_i & 1) ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = grid_of(sc);
    mc_eigen_volume v = vol_of(sc, MC_EIG_CELL_AVERAGE);
    const size_t ns = (size_t)g.nx * g.ny, n = ns * v.nz;
    double *eps[6], *tot[6], *s1[6], *s2[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, tot), *b3 = eig_fields(n, s1),
           *b4 = eig_fields(n, s2);
    test_random_field(b1, 6 * n, 31 + (unsigned)_i);
    /* every third cell, and the last one, carry an addend of 7 values (the loop's stride) */
    long cell[64];
    double val[7 * 64];
    long m = 0;
    for (long k = 0; k < (long)n && m < 64; k += 3)
        cell[m++] = k;
    if (cell[m - 1] != (long)n - 1 && m < 64)
        cell[m++] = (long)n - 1;
    test_random_field(val, (size_t)(7 * m), 41 + (unsigned)_i);
    memcpy(b2, b1, 6 * n * sizeof *b2);
    for (long k = 0; k < m; k++)
        for (int c = 0; c < 6; c++)
            tot[c][cell[k]] = eps[c][cell[k]] + val[7 * k + c];
    const mc_eigen_sparse inc = {m, cell, val, 7};
    double *u1 = malloc(ns * sizeof *u1), *u2 = malloc(ns * sizeof *u2);
    mc_eigen_spectral *op = spec_op(&g, &v, be), *ou = NULL;
    mc_eigen_spectral_apply(op, (const double *const *)tot, G_MOD, s1, u1);
    mc_eigen_spectral_apply_sum(op, (const double *const *)eps, &inc, G_MOD, s2, u2);
    ck_assert_msg(memcmp(b3, b4, 6 * n * sizeof *b3) == 0, "case %d: stresses differ", _i);
    ck_assert_msg(memcmp(u1, u2, ns * sizeof *u1) == 0, "case %d: u_z differs", _i);
    mc_error err = {0};
    ck_assert_int_eq(mc_eigen_spectral_create_uz(&g, &v, NU, be, &ou, &err), MC_OK);
    mc_eigen_spectral_apply_uz(ou, (const double *const *)tot, u1);
    mc_eigen_spectral_apply_uz_sum(ou, (const double *const *)eps, &inc, u2);
    ck_assert_msg(memcmp(u1, u2, ns * sizeof *u1) == 0, "case %d: u_z alone differs", _i);
    /* borrowed workspaces (the fft backend): the same bits, applied in turn with the stress */
    const size_t own = mc_eigen_spectral_bytes(ou);
    ck_assert_int_eq(mc_eigen_spectral_borrow(ou, op), be == MC_BACKEND_FFT);
    if (be == MC_BACKEND_FFT)
        ck_assert(mc_eigen_spectral_bytes(ou) < own);
    mc_eigen_spectral_apply(op, (const double *const *)eps, G_MOD, s2, NULL);
    mc_eigen_spectral_apply_uz_sum(ou, (const double *const *)eps, &inc, u2);
    ck_assert_msg(memcmp(u1, u2, ns * sizeof *u1) == 0, "case %d: borrowed u_z differs", _i);
    mc_eigen_spectral_apply_sum(op, (const double *const *)eps, &inc, G_MOD, s2, NULL);
    ck_assert(memcmp(b3, b4, 6 * n * sizeof *b3) == 0);
    /* in two halves (begin: u_z and the down pass; end: the rest), a borrowing displacement
     * apply between them as in the joint iteration: the bits of one apply */
    double *u3 = malloc(ns * sizeof *u3), *u4 = malloc(ns * sizeof *u4);
    mc_eigen_spectral_apply_sum(op, (const double *const *)eps, &inc, G_MOD, s2, u3);
    memset(b4, 0, 6 * n * sizeof *b4);
    mc_eigen_spectral_begin_sum(op, (const double *const *)eps, &inc, G_MOD, s2, u4);
    mc_eigen_spectral_apply_uz_sum(ou, (const double *const *)eps, &inc, u2);
    mc_eigen_spectral_end_sum(op, (const double *const *)eps, &inc, G_MOD, s2);
    ck_assert_msg(memcmp(b3, b4, 6 * n * sizeof *b3) == 0, "case %d: begin + end differ", _i);
    ck_assert_msg(memcmp(u3, u4, ns * sizeof *u3) == 0, "case %d: begin's u_z differs", _i);
    mc_eigen_spectral_destroy(&ou);
    /* through eigen_op.h: the spectral kernel takes the sum, the cuboid one refuses */
    for (int k = 0; k < 2 && !sc->graded; k++) {
        v.kernel = k ? MC_EIG_KERNEL_CUBOID : MC_EIG_KERNEL_SPECTRAL;
        if (g.periodic_x && !g.periodic_y)
            continue; /* (eigen_op.h refuses x periodic alone) */
        mc_eigen_stress *os = eig_stress_op(&g, &v, NU, be);
        mc_eigen_disp *od = eig_disp_op(&g, &v, NU, be);
        ck_assert_int_eq(mc_eigen_stress_takes_sum(os), !k);
        ck_assert_int_eq(mc_eigen_disp_takes_sum(od), !k);
        const int rs = mc_eigen_stress_apply_sum(os, (const double *const *)eps, &inc, G_MOD,
                                                 NULL, NULL, s2);
        const int rd = mc_eigen_disp_apply_sum(od, (const double *const *)eps, &inc, u2);
        ck_assert_int_eq(rs, k ? MC_ERR_LIMIT : MC_OK);
        ck_assert_int_eq(rd, k ? MC_ERR_LIMIT : MC_OK);
        memset(b4, 0, 6 * n * sizeof *b4);
        const int rb = mc_eigen_stress_begin_sum(os, (const double *const *)eps, &inc, G_MOD, s2,
                                                 u4);
        const int re = mc_eigen_stress_end_sum(os, (const double *const *)eps, &inc, G_MOD, NULL,
                                               NULL, s2);
        ck_assert_int_eq(rb, k ? MC_ERR_LIMIT : MC_OK);
        ck_assert_int_eq(re, k ? MC_ERR_LIMIT : MC_OK);
        if (!k) {
            ck_assert(memcmp(b3, b4, 6 * n * sizeof *b3) == 0);
            ck_assert(memcmp(u3, u4, ns * sizeof *u3) == 0);
            ck_assert_int_eq(mc_eigen_stress_apply_sum(os, (const double *const *)eps, &inc,
                                                       G_MOD, NULL, NULL, s2), MC_OK);
            ck_assert(memcmp(b3, b4, 6 * n * sizeof *b3) == 0);
            ck_assert(memcmp(u1, u2, ns * sizeof *u1) == 0);
            ck_assert_int_eq(mc_eigen_disp_borrow(od, os), be == MC_BACKEND_FFT);
            ck_assert_int_eq(mc_eigen_disp_apply_sum(od, (const double *const *)eps, &inc, u2),
                             MC_OK);
            ck_assert(memcmp(u1, u2, ns * sizeof *u1) == 0);
        } else {
            ck_assert_int_eq(mc_eigen_disp_borrow(od, os), 0);
        }
        mc_eigen_disp_destroy(&od);
        mc_eigen_stress_destroy(&os);
    }
    mc_eigen_spectral_destroy(&op);
    free(u1), free(u2), free(u3), free(u4), free(b1), free(b2), free(b3), free(b4);
}
END_TEST

/* ---- against the cuboid operators ------------------------------------------------------------- */

/* A smooth field: per layer and component a random amplitude times a smooth lateral profile that
 * vanishes with its first three derivatives outside the central half of a free axis, and is a
 * few low modes along a periodic one. */
static void smooth_field(const mc_grid *g, int nz, double *f[6])
{
    double amp[6 * 16];
    test_random_field(amp, 6 * (size_t)nz, 2024);
    for (int c = 0; c < 6; c++)
        for (int k = 0; k < nz; k++)
            for (int j = 0; j < g->ny; j++)
                for (int i = 0; i < g->nx; i++) {
                    const double x = (i + 0.5) / g->nx, y = (j + 0.5) / g->ny;
                    const double bx = fabs(x - 0.5) < 0.25 ? pow(cos(2 * M_PI * (x - 0.5)), 4) : 0;
                    const double by = g->periodic_y ? 1.0 + 0.5 * sin(2 * M_PI * y + k)
                                      : fabs(y - 0.5) < 0.25 ? pow(cos(2 * M_PI * (y - 0.5)), 4)
                                                             : 0.0;
                    f[c][((size_t)k * g->ny + j) * g->nx + i] =
                        1e-3 * amp[6 * k + c] * bx * by * (1.0 + 0.3 * cos(2 * M_PI * x + c));
                }
}

/* max |spectral - cuboid| / max |cuboid| of stress and u_z on the grid of n x n cells over a
 * fixed lateral size (y periodic: a strip) */
static void compare_cuboid(int n, int strip, double *es, double *eu, double *ep)
{
    const double L = 64e-6;
    mc_grid g = {n, n, L / n, L / n, 0, strip};
    mc_eigen_volume v = {0, 0, n, n, 4, 1e-6, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID};
    const size_t ns = (size_t)n * n, nv = ns * v.nz;
    double *eps[6], *sc[6], *ss[6];
    double *b1 = eig_fields(nv, eps), *b2 = eig_fields(nv, sc), *b3 = eig_fields(nv, ss);
    double *uc = malloc(ns * sizeof *uc), *us = malloc(ns * sizeof *us);
    smooth_field(&g, v.nz, eps);
    mc_eigen_stress *cs = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_disp *cd = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_spectral *sp = spec_op(&g, &v, MC_BACKEND_FFT);
    mc_eigen_stress_apply(cs, (const double *const *)eps, G_MOD, sc);
    mc_eigen_disp_apply(cd, (const double *const *)eps, uc);
    mc_eigen_spectral_apply(sp, (const double *const *)eps, G_MOD, ss, us);
    *es = test_rel_maxdiff(b3, b2, 6 * nv);
    *eu = test_rel_maxdiff(us, uc, ns);
    double *pc = malloc(ns * sizeof *pc), *ps = malloc(ns * sizeof *ps);
    mc_eigen_stress_p3(cs, pc);
    mc_eigen_spectral_p3(sp, ps);
    *ep = test_rel_maxdiff(ps, pc, ns);
    free(pc), free(ps);
    mc_eigen_stress_destroy(&cs);
    mc_eigen_disp_destroy(&cd);
    mc_eigen_spectral_destroy(&sp);
    free(b1), free(b2), free(b3), free(uc), free(us);
}

START_TEST(test_converges_to_cuboid)
{
    const int strip = _i;
    double es[3], eu[3], ep[3];
    const int ns[3] = {32, 64, 128};
    for (int r = 0; r < 3; r++) {
        compare_cuboid(ns[r], strip, &es[r], &eu[r], &ep[r]);
        if (getenv("MC_TEST_VERBOSE"))
            fprintf(stderr, "%s %d^2: spectral vs cuboid stress %.3g, u_z %.3g, p3 %.3g\n",
                    strip ? "strip" : "free", ns[r], es[r], eu[r], ep[r]);
    }
    /* The cuboid discretisation errs at first order in h where a coupling is odd in the
     * lateral offset (a shear eigenstrain's jumps at the cell faces; theory §8.10), at second
     * order elsewhere; the spectral one is exact laterally for this smooth field, up to its
     * images a grid away. Measured (stress, u_z): free 0.070, 0.033, 0.018 and 0.018, 0.0056,
     * 0.0013; strip 0.039, 0.012, 0.0051 and 0.0084, 0.0027, 0.0016 (the images' floor). */
    for (int r = 1; r < 3; r++) {
        ck_assert_msg(es[r] < es[r - 1] / 1.7, "stress: %.3g -> %.3g", es[r - 1], es[r]);
        ck_assert_msg(eu[r] < eu[r - 1] / 1.5, "u_z: %.3g -> %.3g", eu[r - 1], eu[r]);
    }
    ck_assert(es[2] < 2e-2 && eu[2] < 2e-3);
    /* p3 (first order: the odd couplings at the surface; measured 0.14, 0.086, 0.044 free and
     * 0.095, 0.040, 0.021 strip) */
    ck_assert_msg(ep[2] < ep[0] / 2.5 && ep[2] < 5e-2, "p3: %.3g -> %.3g", ep[0], ep[2]);
}
END_TEST

/* ---- identities of the trigonometric field ---------------------------------------------------- */

START_TEST(test_strip_is_line)
{
    mc_grid line = {9, 1, 1e-6, 1e-6, 0, 1}, strip = {9, 4, 1e-6, 0.7e-6, 0, 1};
    mc_eigen_volume vl = mc_eigen_volume_full(&line, 3, 0.5e-6), vs = mc_eigen_volume_full(&strip, 3, 0.5e-6);
    const size_t nl = 27, ns = 108;
    double *el[6], *es[6], *sl[6], *ss[6];
    double *b1 = eig_fields(nl, el), *b2 = eig_fields(ns, es), *b3 = eig_fields(nl, sl),
           *b4 = eig_fields(ns, ss);
    test_random_field(b1, 6 * nl, 3);
    for (int c = 0; c < 6; c++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 9; i++)
                    es[c][(k * 4 + j) * 9 + i] = el[c][k * 9 + i];
    double ul[9], us[36];
    mc_eigen_spectral *ol = spec_op(&line, &vl, MC_BACKEND_FFT), *os = spec_op(&strip, &vs, MC_BACKEND_FFT);
    mc_eigen_spectral_apply(ol, (const double *const *)el, G_MOD, sl, ul);
    mc_eigen_spectral_apply(os, (const double *const *)es, G_MOD, ss, us);
    const double big = eig_max_abs(b3, 6 * nl);
    double worst = 0.0;
    for (int c = 0; c < 6; c++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 9; i++)
                    worst = test_worst(worst, fabs(ss[c][(k * 4 + j) * 9 + i] - sl[c][k * 9 + i]) / big);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 9; i++)
            worst = test_worst(worst, fabs(us[j * 9 + i] - ul[i]) / eig_max_abs(ul, 9));
    ck_assert_msg(worst <= TOL_SAME_MODES, "y-uniform strip vs line %.3g", worst);
    mc_eigen_spectral_destroy(&ol);
    mc_eigen_spectral_destroy(&os);
    free(b1), free(b2), free(b3), free(b4);
}
END_TEST

START_TEST(test_tiled)
{
    mc_grid one = {6, 5, 1e-6, 1.1e-6, 1, 1}, two = {12, 10, 1e-6, 1.1e-6, 1, 1};
    mc_eigen_volume v1 = mc_eigen_volume_full(&one, 2, 0.5e-6), v2 = mc_eigen_volume_full(&two, 2, 0.5e-6);
    const size_t n1 = 60, n2 = 240;
    double *e1[6], *e2[6], *s1[6], *s2[6];
    double *b1 = eig_fields(n1, e1), *b2 = eig_fields(n2, e2), *b3 = eig_fields(n1, s1),
           *b4 = eig_fields(n2, s2);
    test_random_field(b1, 6 * n1, 8);
    for (int c = 0; c < 6; c++)
        for (int k = 0; k < 2; k++)
            for (int j = 0; j < 10; j++)
                for (int i = 0; i < 12; i++)
                    e2[c][(k * 10 + j) * 12 + i] = e1[c][(k * 5 + j % 5) * 6 + i % 6];
    double u1[30], u2[120];
    mc_eigen_spectral *o1 = spec_op(&one, &v1, MC_BACKEND_FFT), *o2 = spec_op(&two, &v2, MC_BACKEND_FFT);
    mc_eigen_spectral_apply(o1, (const double *const *)e1, G_MOD, s1, u1);
    mc_eigen_spectral_apply(o2, (const double *const *)e2, G_MOD, s2, u2);
    const double big = eig_max_abs(b3, 6 * n1);
    double worst = 0.0;
    for (int c = 0; c < 6; c++)
        for (int k = 0; k < 2; k++)
            for (int j = 0; j < 10; j++)
                for (int i = 0; i < 12; i++)
                    worst = test_worst(worst, fabs(s2[c][(k * 10 + j) * 12 + i] -
                                                   s1[c][(k * 5 + j % 5) * 6 + i % 6]) / big);
    for (int j = 0; j < 10; j++)
        for (int i = 0; i < 12; i++)
            worst = test_worst(worst, fabs(u2[j * 12 + i] - u1[(j % 5) * 6 + i % 6]) /
                                          eig_max_abs(u1, 30));
    ck_assert_msg(worst <= TOL_SAME_MODES, "2 x 2 tiling vs the period %.3g", worst);
    mc_eigen_spectral_destroy(&o1);
    mc_eigen_spectral_destroy(&o2);
    free(b1), free(b2), free(b3), free(b4);
}
END_TEST

/* a laterally uniform field on a doubly periodic grid: the layer's closed form (theory §8.6) */
START_TEST(test_uniform_layer)
{
    const mc_backend b = _i ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = {6, 4, 1e-6, 1e-6, 1, 1};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, 3, 0.5e-6);
    const size_t nw = 24, n = 72;
    double e[18];
    test_random_field(e, 18, 41);
    double *eps[6], *sig[6], *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sig), u[24];
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < 6; c++)
            for (size_t s = 0; s < nw; s++)
                eps[c][k * nw + s] = e[k * 6 + c];
    mc_eigen_spectral *op = spec_op(&g, &v, b);
    mc_eigen_spectral_apply(op, (const double *const *)eps, G_MOD, sig, u);
    const double a = NU / (1.0 - NU), G = G_MOD;
    double uref = 0.0, smax = 0.0, worst = 0.0, uworst = 0.0;
    for (int k = 0; k < 3; k++) {
        const double *ek = e + k * 6;
        uref -= v.dz * (ek[2] + a * (ek[0] + ek[1]));
        const double want[6] = {-2.0 * G * (ek[0] + a * (ek[0] + ek[1])),
                                -2.0 * G * (ek[1] + a * (ek[0] + ek[1])), 0.0, -2.0 * G * ek[3],
                                0.0, 0.0};
        for (int c = 0; c < 6; c++) {
            smax = fmax(smax, fabs(want[c]));
            for (size_t s = 0; s < nw; s++)
                worst = test_worst(worst, fabs(sig[c][k * nw + s] - want[c]));
        }
    }
    for (size_t s = 0; s < nw; s++)
        uworst = test_worst(uworst, fabs(u[s] - uref));
    ck_assert_msg(worst <= TOL_SAME_MODES * smax, "stress off the layer by %.3g", worst / smax);
    ck_assert_msg(uworst <= TOL_SAME_MODES * fabs(uref), "u_z off the layer by %.3g",
                  uworst / fabs(uref));
    mc_eigen_spectral_destroy(&op);
    free(b1), free(b2);
}
END_TEST

/* A uniform eigenstrain over the whole window of a free (strip) grid is a finite patch (band):
 * its surface sinks by -(1 + 2 nu) t for (1, 1, 0) at the centre of a wide thin patch, not by
 * the laterally constrained layer's -(1 + nu) / (1 - nu) t (theory §8.1): the mode k = 0 of a
 * padded axis stands for the limit k -> 0, the mean over the free directions. Against the
 * cuboid operators, which sum the patch's cuboids exactly. */
START_TEST(test_patch_mean_mode)
{
    const int strip = _i;
    mc_grid g = {64, 64, 1e-6, 1e-6, 0, strip};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, 1, 0.5e-6);
    const size_t n = 64 * 64;
    double *eps[6], *b1 = eig_fields(n, eps), *uc = malloc(n * sizeof *uc), *us = malloc(n * sizeof *us);
    double *sig[6], *b2 = eig_fields(n, sig);
    for (size_t q = 0; q < n; q++)
        eps[0][q] = eps[1][q] = 1e-3;
    mc_eigen_disp *cd = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_spectral *sp = spec_op(&g, &v, MC_BACKEND_FFT);
    mc_eigen_disp_apply(cd, (const double *const *)eps, uc);
    mc_eigen_spectral_apply(sp, (const double *const *)eps, G_MOD, sig, us);
    const size_t centre = 32 * 64 + 32;
    const double rel = fabs(us[centre] - uc[centre]) / fabs(uc[centre]);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "%s patch: u_z / t at the centre spectral %.4f, cuboid %.4f\n",
                strip ? "strip" : "free", us[centre] / 0.5e-9, uc[centre] / 0.5e-9);
    /* the patch's edges sit a grid away; Gibbs oscillations of the trigonometric field there
     * have decayed at the centre: measured 0.1 % (free), 0.2 % (strip); the constrained layer's
     * mean mode would be off by ~10 % */
    ck_assert_msg(rel < 1e-2, "patch centre u_z %.4g vs cuboid %.4g", us[centre], uc[centre]);
    mc_eigen_disp_destroy(&cd);
    mc_eigen_spectral_destroy(&sp);
    free(b1), free(b2), free(uc), free(us);
}
END_TEST

/* Through the eigenstrain operators' interface (plastic/eigen_op.h, v.kernel = spectral): the
 * residual stress and u_z are the spectral operator's; the folded loads add the stress module's
 * patch stresses at the layer centres (theory §8.10), the same values as mc_stress_field; the
 * estimates are the built objects' bytes. Free and doubly periodic, with friction. */
START_TEST(test_through_eigen_op)
{
    const int per = _i;
    mc_grid g = {10, 8, 1e-6, 1.2e-6, per, per};
    mc_eigen_volume v = mc_eigen_volume_full(&g, 3, 0.5e-6);
    v.kernel = MC_EIG_KERNEL_SPECTRAL;
    const size_t ns = 80, n = ns * 3;
    double *eps[6], *s1[6], *s2[6], *se[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, s1), *b3 = eig_fields(n, s2),
           *b4 = eig_fields(n, se);
    test_random_field(b1, 6 * n, 77);
    double p[80], qx[80], u1[80], u2[80];
    test_random_field(p, ns, 78);
    for (size_t i = 0; i < ns; i++) {
        p[i] = 1e9 * (1.5 + p[i]);
        qx[i] = 0.1 * p[i];
    }
    mc_eigen_stress *os = eig_stress_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_disp *od = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_spectral *sp = spec_op(&g, &v, MC_BACKEND_FFT);
    mc_eigen_stress_apply(os, (const double *const *)eps, G_MOD, s1);
    mc_eigen_disp_apply(od, (const double *const *)eps, u1);
    mc_eigen_spectral_apply(sp, (const double *const *)eps, G_MOD, s2, u2);
    ck_assert(test_rel_maxdiff(b2, b3, 6 * n) <= TOL_SAME_MODES);
    ck_assert(test_rel_maxdiff(u1, u2, ns) <= TOL_SAME_MODES);
    /* the estimates */
    size_t parts[MC_EIGEN_STRESS_PARTS], est = 0;
    mc_eigen_stress_estimate(&g, &v, MC_BACKEND_FFT, parts);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        est += parts[k];
    ck_assert_uint_eq(est, mc_eigen_stress_bytes(os));
    ck_assert_uint_eq(mc_eigen_disp_estimate(&g, &v, MC_BACKEND_FFT), mc_eigen_disp_bytes(od));
    /* folded loads */
    mc_error err = {0};
    const int loads = MC_TRACTION_P | MC_TRACTION_QX;
    ck_assert_int_eq(mc_eigen_stress_loads(os, loads, &err), MC_OK);
    ck_assert_int_eq(mc_eigen_stress_loads_of(os), loads);
    mc_eigen_stress_apply_loaded(os, (const double *const *)eps, G_MOD, p, qx, s1);
    double depths[3];
    for (int k = 0; k < 3; k++)
        depths[k] = mc_eigen_layer_depth(&v, k);
    const mc_stress_options so = {.kernel = MC_STRESS_PATCH, .nu = NU, .nlayers = 3,
                                  .depths = depths, .backend = MC_BACKEND_FFT, .loads = loads};
    mc_stress_plan *plan = NULL;
    ck_assert_int_eq(mc_stress_create(&g, &so, &plan, &err), MC_OK);
    ck_assert_int_eq(mc_stress_field(plan, p, qx, NULL, se, &err), MC_OK);
    for (int c = 0; c < 6; c++)
        for (size_t i = 0; i < n; i++)
            s2[c][i] += se[c][i];
    const double e = test_rel_maxdiff(b2, b3, 6 * n);
    ck_assert_msg(e <= TOL_SAME_MODES, "folded loads %.3g", e);
    ck_assert_uint_eq(mc_eigen_stress_loads_estimate(&g, &v, MC_BACKEND_FFT, 0, loads) > 0, 1);
    mc_stress_destroy(&plan);
    mc_eigen_stress_destroy(&os);
    mc_eigen_disp_destroy(&od);
    mc_eigen_spectral_destroy(&sp);
    free(b1), free(b2), free(b3), free(b4);
}
END_TEST

START_TEST(test_refusals)
{
    mc_grid g = {8, 8, 1e-6, 1e-6, 0, 0};
    mc_eigen_volume v = {1, 0, 6, 8, 3, 0.5e-6, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID};
    mc_eigen_spectral *op = NULL;
    mc_error err = {0};
    ck_assert_int_eq(mc_eigen_spectral_create(&g, &v, NU, MC_BACKEND_FFT, &op, &err), MC_ERR_LIMIT);
    ck_assert_ptr_null(op);
    ck_assert_ptr_nonnull(strstr(err.msg, "whole grid"));
    v = mc_eigen_volume_full(&g, 3, 0.5e-6);
    ck_assert_int_eq(mc_eigen_spectral_create(&g, &v, 0.5, MC_BACKEND_FFT, &op, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "Poisson"));
    ck_assert_uint_eq(mc_eigen_spectral_estimate(&g, &v, MC_BACKEND_FFT) > 0, 1);
    /* out of memory at every allocation: a clean failure */
    for (long n = 1; n <= 8; n++) {
        mc_alloc_fail_at(n);
        const int rc = mc_eigen_spectral_create(&g, &v, NU, MC_BACKEND_FFT, &op, &err);
        mc_alloc_fail_at(0);
        ck_assert(rc == MC_OK || rc == MC_ERR_NOMEM);
        ck_assert(rc == MC_OK ? op != NULL : op == NULL);
        mc_eigen_spectral_destroy(&op);
    }
}
END_TEST

Suite *suite_eigen_spectral_op(void);
Suite *suite_eigen_spectral_op(void)
{
    Suite *s = suite_create("eigen_spectral_op");
    TCase *tc = tcase_create("operator");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_backends, 0, 2 * N_CASES);
    tcase_add_loop_test(tc, test_sum_input, 0, 2 * N_CASES);
    tcase_add_loop_test(tc, test_converges_to_cuboid, 0, 2);
    tcase_add_test(tc, test_strip_is_line);
    tcase_add_test(tc, test_tiled);
    tcase_add_loop_test(tc, test_uniform_layer, 0, 2);
    tcase_add_loop_test(tc, test_patch_mean_mode, 0, 2);
    tcase_add_loop_test(tc, test_through_eigen_op, 0, 2);
    tcase_add_test(tc, test_refusals);
    suite_add_tcase(s, tc);
    return s;
}
