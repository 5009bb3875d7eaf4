/* test_eigen_graded.c - graded layers of the eigenstrain operators (src/plastic/eigen_op.h,
 * docs/theory.md §8.8): direct vs fft on graded volumes (free window, line grid, strip, doubly
 * periodic); every group 1 against the uniform volume, bit for bit; the graded operator against
 * the uniform FINE operator applied to the repeated eigenstrain and read at the layer centres
 * (superposition, an independent path through the lateral transforms); a laterally uniform graded
 * field on a doubly periodic grid against its closed form; the grading rule. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plastic/eigen_internal.h"
#include "plastic/eigen_op.h"
#include "eigen_testkit.h"
#include "test_util.h"

static const double NU = 0.3;
static const double E_MOD = 210e9;
#define G_MOD (E_MOD / (2.0 * (1.0 + NU)))

/* Backends: the same tables summed directly or by FFT: round-off (the issue asks <= 1e-10). */
#define TOL_BACKENDS 1e-10
/* Superposition: the graded operator and the fine one share the S1 tables and the depth step;
 * they differ by the lateral transforms of the repeated layers (round-off) and by the p3 table
 * of a thick cuboid against the sum of its fine ones (the closed-form integrals of
 * kernels/eigen.h over [z1, z2] against their sum over the sub-intervals: round-off of terms that
 * cancel, ~1e-13 measured). */
#define TOL_SUPERPOSE 1e-10
/* The fft backend's two depth steps on a graded volume (eigen_stress_fft.c): the same fine-lattice
 * sums, by depth DFTs or by prefix sums over the coarse boundaries; round-off of sums of ~nzf
 * terms of the size of the largest entry (measured <= 1e-14). */
#define TOL_DEPTH 1e-12
/* The laterally uniform field's closed form (as test_eigen_periodic.c TOL_MEAN). */
#define TOL_MEAN 1e-11

typedef struct {
    int nx, ny, px, py; /* grid and periodicity */
    int i0, j0, wx, wy; /* window */
    int nz;
    int group[6];
    double dx, dy, dz;
} gcase;

static const gcase cases[] = {
    {13, 10, 0, 0, 2, 1, 9, 8, 4, {1, 1, 3, 5}, 1e-6, 1.3e-6, 0.4e-6},  /* free, window inside */
    {9, 7, 0, 0, 0, 0, 9, 7, 3, {3, 1, 5}, 1e-6, 1e-6, 0.5e-6},         /* free, whole grid */
    {12, 1, 0, 1, 2, 0, 8, 1, 4, {1, 3, 3, 7}, 1e-6, 1e-6, 0.5e-6},     /* line grid */
    {10, 8, 0, 1, 0, 0, 10, 8, 3, {1, 3, 5}, 1e-6, 1e-6, 0.5e-6},       /* strip, even ny */
    {12, 7, 0, 1, 2, 0, 7, 7, 3, {1, 1, 3}, 1e-6, 1.3e-6, 0.6e-6},      /* strip, odd ny */
    {8, 6, 1, 1, 0, 0, 8, 6, 3, {1, 3, 5}, 1e-6, 1e-6, 0.5e-6},         /* doubly periodic */
    {7, 9, 1, 1, 0, 0, 7, 9, 2, {3, 3}, 1.1e-6, 0.9e-6, 0.7e-6},        /* doubly, odd */
};
#define N_CASES ((int)(sizeof cases / sizeof cases[0]))

static mc_grid grid_of(const gcase *c)
{
    mc_grid g = {c->nx, c->ny, c->dx, c->dy, c->px, c->py};
    return g;
}

static mc_eigen_volume vol_of(const gcase *c, const int *group)
{
    mc_eigen_volume v = {c->i0, c->j0, c->wx, c->wy, c->nz, c->dz, MC_EIG_CELL_AVERAGE, group, MC_EIG_KERNEL_CUBOID};
    return v;
}

/* ---- direct vs fft ---------------------------------------------------------------------------- */

/* The fft stress operator with its depth step forced (eigen_internal.h). */
static mc_eigen_stress *stress_depth(const mc_grid *g, const mc_eigen_volume *v, int depth)
{
    mc_eigen_stress *op = NULL;
    mc_error err;
    const int rc = mc_eig_stress_create_depth(g, v, NU, MC_BACKEND_FFT, depth, &op, &err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
    ck_assert_int_eq(mc_eig_stress_fft_depth(op), depth);
    return op;
}

START_TEST(test_backends)
{
    const gcase *gc = &cases[_i];
    const mc_grid g = grid_of(gc);
    const mc_eigen_volume v = vol_of(gc, gc->group);
    const size_t nw = (size_t)v.nx * v.ny, n = nw * v.nz, ns = mc_grid_cells(&g);
    double *eps[6], *sd[6], *sf[6], *sc[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sd), *b3 = eig_fields(n, sf);
    double *b4 = eig_fields(n, sc);
    test_random_field(b1, 6 * n, 91 + (unsigned)_i);
    double *ud = malloc(ns * sizeof *ud), *uf = malloc(ns * sizeof *uf);
    double *pd = malloc(nw * sizeof *pd), *pf = malloc(nw * sizeof *pf);
    double *pc = malloc(nw * sizeof *pc);
    mc_eigen_disp *dd = eig_disp_op(&g, &v, NU, MC_BACKEND_DIRECT);
    mc_eigen_disp *df = eig_disp_op(&g, &v, NU, MC_BACKEND_FFT);
    mc_eigen_stress *od = eig_stress_op(&g, &v, NU, MC_BACKEND_DIRECT);
    /* both depth steps of the fft backend (the fine lattice's DFTs, the coarse pair sum) */
    mc_eigen_stress *of = stress_depth(&g, &v, MC_EIG_DEPTH_FINE);
    mc_eigen_stress *oc = stress_depth(&g, &v, MC_EIG_DEPTH_COARSE);
    mc_eigen_disp_apply(dd, (const double *const *)eps, ud);
    mc_eigen_disp_apply(df, (const double *const *)eps, uf);
    mc_eigen_stress_apply(od, (const double *const *)eps, G_MOD, sd);
    mc_eigen_stress_apply(of, (const double *const *)eps, G_MOD, sf);
    mc_eigen_stress_p3(od, pd);
    mc_eigen_stress_p3(of, pf);
    mc_eigen_stress_apply(oc, (const double *const *)eps, G_MOD, sc);
    mc_eigen_stress_p3(oc, pc);
    const double eu = test_rel_maxdiff(uf, ud, ns), es = test_rel_maxdiff(b3, b2, 6 * n);
    const double ep = test_rel_maxdiff(pf, pd, nw);
    const double ec = test_rel_maxdiff(b4, b2, 6 * n), ez = test_rel_maxdiff(b4, b3, 6 * n);
    const double epc = test_rel_maxdiff(pc, pf, nw);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr,
                "graded case %d: fft vs direct u_z %.3g, stress %.3g (coarse depth %.3g), p3 "
                "%.3g; coarse vs fine depth step: stress %.3g, p3 %.3g\n",
                _i, eu, es, ec, ep, ez, epc);
    ck_assert_msg(ec <= TOL_BACKENDS, "case %d: stress fft (coarse) vs direct %.3g", _i, ec);
    ck_assert_msg(ez <= TOL_DEPTH, "case %d: stress coarse vs fine depth step %.3g", _i, ez);
    ck_assert_msg(epc <= TOL_DEPTH, "case %d: p3 coarse vs fine depth step %.3g", _i, epc);
    ck_assert_msg(eu <= TOL_BACKENDS, "case %d: u_z fft vs direct %.3g", _i, eu);
    ck_assert_msg(es <= TOL_BACKENDS, "case %d: stress fft vs direct %.3g", _i, es);
    ck_assert_msg(ep <= TOL_BACKENDS, "case %d: p3 fft vs direct %.3g", _i, ep);
    ck_assert(eig_max_abs(ud, ns) > 0.0 && eig_max_abs(b2, 6 * n) > 0.0);
    mc_eigen_disp_destroy(&dd);
    mc_eigen_disp_destroy(&df);
    mc_eigen_stress_destroy(&od);
    mc_eigen_stress_destroy(&of);
    mc_eigen_stress_destroy(&oc);
    free(ud), free(uf), free(pd), free(pf), free(pc), free(b1), free(b2), free(b3), free(b4);
}
END_TEST

/* ---- every group 1: the uniform volume, the same bits ------------------------------------------ */

START_TEST(test_ones_are_uniform)
{
    const gcase *gc = &cases[_i >> 1];
    const mc_backend b = (_i & 1) ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = grid_of(gc);
    const int ones[6] = {1, 1, 1, 1, 1, 1};
    const mc_eigen_volume vu = vol_of(gc, NULL), vg = vol_of(gc, ones);
    const size_t nw = (size_t)vu.nx * vu.ny, n = nw * vu.nz, ns = mc_grid_cells(&g);
    double *eps[6], *su[6], *sg[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(n, su), *b3 = eig_fields(n, sg);
    test_random_field(b1, 6 * n, 17 + (unsigned)_i);
    double *uu = malloc(ns * sizeof *uu), *ug = malloc(ns * sizeof *ug);
    mc_eigen_disp *du = eig_disp_op(&g, &vu, NU, b), *dg = eig_disp_op(&g, &vg, NU, b);
    mc_eigen_stress *ou = eig_stress_op(&g, &vu, NU, b), *og = eig_stress_op(&g, &vg, NU, b);
    mc_eigen_disp_apply(du, (const double *const *)eps, uu);
    mc_eigen_disp_apply(dg, (const double *const *)eps, ug);
    mc_eigen_stress_apply(ou, (const double *const *)eps, G_MOD, su);
    mc_eigen_stress_apply(og, (const double *const *)eps, G_MOD, sg);
    ck_assert_msg(memcmp(uu, ug, ns * sizeof *uu) == 0, "case %d: u_z bits differ", _i);
    ck_assert_msg(memcmp(b2, b3, 6 * n * sizeof *b2) == 0, "case %d: stress bits differ", _i);
    mc_eigen_disp_destroy(&du);
    mc_eigen_disp_destroy(&dg);
    mc_eigen_stress_destroy(&ou);
    mc_eigen_stress_destroy(&og);
    free(uu), free(ug), free(b1), free(b2), free(b3);
}
END_TEST

/* ---- superposition: the uniform fine operator on the repeated field ---------------------------- */

START_TEST(test_superposition)
{
    const gcase *gc = &cases[_i];
    const mc_grid g = grid_of(gc);
    const mc_eigen_volume vg = vol_of(gc, gc->group);
    const int nzf = mc_eigen_layer_first(&vg, vg.nz);
    mc_eigen_volume vf = vg;
    vf.nz = nzf;
    vf.group = NULL;
    const size_t nw = (size_t)vg.nx * vg.ny, n = nw * vg.nz, nf = nw * nzf, ns = mc_grid_cells(&g);
    double *eps[6], *epf[6], *sg[6], *sf[6];
    double *b1 = eig_fields(n, eps), *b2 = eig_fields(nf, epf), *b3 = eig_fields(n, sg);
    double *b4 = eig_fields(nf, sf);
    test_random_field(b1, 6 * n, 29 + (unsigned)_i);
    for (int k = 0; k < vg.nz; k++) /* the field repeated over each layer's fine layers */
        for (int q = mc_eigen_layer_first(&vg, k); q < mc_eigen_layer_first(&vg, k + 1); q++)
            for (int c = 0; c < 6; c++)
                memcpy(epf[c] + q * nw, eps[c] + k * nw, nw * sizeof(double));
    double *ug = malloc(ns * sizeof *ug), *uf = malloc(ns * sizeof *uf);
    double *pg = malloc(nw * sizeof *pg), *pf = malloc(nw * sizeof *pf);
    mc_eigen_disp *dg = eig_disp_op(&g, &vg, NU, MC_BACKEND_FFT);
    mc_eigen_disp *df = eig_disp_op(&g, &vf, NU, MC_BACKEND_FFT);
    mc_eigen_stress *og = eig_stress_op(&g, &vg, NU, MC_BACKEND_FFT);
    mc_eigen_stress *of = eig_stress_op(&g, &vf, NU, MC_BACKEND_FFT);
    mc_eigen_disp_apply(dg, (const double *const *)eps, ug);
    mc_eigen_disp_apply(df, (const double *const *)epf, uf);
    mc_eigen_stress_apply(og, (const double *const *)eps, G_MOD, sg);
    mc_eigen_stress_apply(of, (const double *const *)epf, G_MOD, sf);
    mc_eigen_stress_p3(og, pg);
    mc_eigen_stress_p3(of, pf);
    /* the fine stresses at each layer's centre */
    double *sc[6], *b5 = eig_fields(n, sc);
    for (int k = 0; k < vg.nz; k++)
        for (int c = 0; c < 6; c++)
            memcpy(sc[c] + k * nw, sf[c] + mc_eigen_layer_centre(&vg, k) * nw,
                   nw * sizeof(double));
    const double eu = test_rel_maxdiff(ug, uf, ns), es = test_rel_maxdiff(b3, b5, 6 * n);
    const double ep = test_rel_maxdiff(pg, pf, nw);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "graded case %d: graded vs fine u_z %.3g, stress %.3g, p3 %.3g\n", _i, eu,
                es, ep);
    ck_assert_msg(eu <= TOL_SUPERPOSE, "case %d: u_z graded vs fine %.3g", _i, eu);
    ck_assert_msg(es <= TOL_SUPERPOSE, "case %d: stress graded vs fine %.3g", _i, es);
    ck_assert_msg(ep <= TOL_SUPERPOSE, "case %d: p3 graded vs fine %.3g", _i, ep);
    mc_eigen_disp_destroy(&dg);
    mc_eigen_disp_destroy(&df);
    mc_eigen_stress_destroy(&og);
    mc_eigen_stress_destroy(&of);
    free(ug), free(uf), free(pg), free(pf), free(b1), free(b2), free(b3), free(b4), free(b5);
}
END_TEST

/* ---- the laterally uniform graded field: closed form ------------------------------------------ */

/* Doubly periodic (cases 5, 6), both backends: each layer's own closed form (in-plane total
 * strains 0, sigma_zz = sigma_xz = sigma_yz = 0), u_z = -sum of thickness x (eps_zz + a tr). */
START_TEST(test_uniform_closed_form)
{
    const gcase *gc = &cases[5 + (_i >> 1)];
    const mc_backend b = (_i & 1) ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const mc_grid g = grid_of(gc);
    const mc_eigen_volume v = vol_of(gc, gc->group);
    char label[40];
    snprintf(label, sizeof label, "graded uniform %d", _i);
    eig_check_uniform(&g, &v, b, NU, G_MOD, 5 + (unsigned)_i, TOL_MEAN, label);
}
END_TEST

/* ---- the grading rule and the refusals -------------------------------------------------------- */

START_TEST(test_grade)
{
    const double dz = 0.5e-6, fine = 4e-6, ratio = 0.25, depth = 40e-6;
    int group[256];
    const int nz = mc_eigen_grade(dz, depth, fine, ratio, group, 256);
    ck_assert_int_gt(nz, 0);
    int f = 0;
    for (int k = 0; k < nz; k++) {
        ck_assert_msg(group[k] % 2 == 1, "layer %d: even count %d", k, group[k]);
        if (f * dz < fine * (1 - 1e-9))
            ck_assert_int_eq(group[k], 1);
        else
            ck_assert_msg(group[k] == 1 || group[k] * dz <= ratio * f * dz * (1 + 1e-12) ||
                              group[k] == group[k - 1],
                          "layer %d: %d dz at depth %g", k, group[k], f * dz);
        if (k > 0 && k < nz - 1) /* the last layer may be cut */
            ck_assert_int_ge(group[k], group[k - 1]);
        f += group[k];
    }
    ck_assert(f * dz >= depth * (1 - 1e-9));
    ck_assert(f * dz - group[nz - 1] * dz < depth * (1 - 1e-9)); /* no layer more than needed */
    ck_assert(f <= (int)ceil(depth / dz - 1e-9) + 1);              /* within one dz of it */
    ck_assert_int_lt(nz, 40);                                     /* fewer than the 80 fine */
    ck_assert_int_eq(mc_eigen_grade(dz, depth, fine, ratio, group, 5), 0); /* no room */
    /* an even count is refused with a message */
    const int bad[2] = {1, 2};
    const mc_grid g = {6, 5, 1e-6, 1e-6, 0, 0};
    const mc_eigen_volume v = {0, 0, 6, 5, 2, 1e-6, MC_EIG_CELL_AVERAGE, bad, MC_EIG_KERNEL_CUBOID};
    mc_eigen_stress *op = NULL;
    mc_error err;
    ck_assert_int_eq(mc_eigen_stress_create(&g, &v, NU, MC_BACKEND_FFT, &op, &err), MC_ERR_INPUT);
    ck_assert(op == NULL && strstr(err.msg, "odd") != NULL);
    /* the volume's equality compares the layering by value */
    const int ones[2] = {1, 1}, odd[2] = {1, 3};
    mc_eigen_volume a = v, c = v;
    a.group = ones;
    c.group = NULL;
    ck_assert(mc_eigen_volume_equal(&a, &c));
    c.group = odd;
    ck_assert(!mc_eigen_volume_equal(&a, &c));
}
END_TEST

/* The corner lattice of the s1 and p3 tables (eigen_internal.h mc_eig_corners) against the
 * per-entry kernels, on the free cases (graded and uniform, centre values and cell averages):
 * the same corner sums, whose corner coordinates differ in their last bits ((I + 1) dx - hx
 * against I dx + hx). Both carry the round-off of sums of 8 corner functions of size up to ~30
 * (logarithms of lengths in metres), an absolute ~1e-15 that does not fall with the kernel, so
 * the difference is taken relative to the largest entry of all the tables of a kind (measured
 * ~3e-15; a deep offset's own table is 1e-4 of it). */
#define TOL_LATTICE 1e-13

typedef struct {
    double diff, size;
} table_cmp;

static void table_add(table_cmp *t, const double *a, const double *b, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        t->diff = test_worst(t->diff, fabs(a[i] - b[i]));
        t->size = test_worst(t->size, fabs(b[i]));
    }
}

START_TEST(test_corner_lattice)
{
    const gcase *gc = &cases[(_i / 2) % 2];
    const mc_grid g = grid_of(gc);
    mc_eigen_volume v = {gc->i0, gc->j0, gc->wx, gc->wy, gc->nz, gc->dz,
                         (_i & 1) ? MC_EIG_CELL_CENTRE : MC_EIG_CELL_AVERAGE, gc->group, MC_EIG_KERNEL_CUBOID};
    if (_i >= 4) /* the same windows, uniform */
        v.group = NULL;
    mc_eigen_stress *op = NULL;
    mc_error err;
    ck_assert_int_eq(mc_eigen_stress_create(&g, &v, NU, MC_BACKEND_DIRECT, &op, &err), MC_OK);
    mc_eig_corners cc;
    ck_assert_int_eq(mc_eig_corners_init(op, &cc, &err), MC_OK);
    ck_assert_ptr_nonnull(cc.h[0]); /* free axes, cuboids: the lattice applies */
    const size_t ql = op->qlen;
    double *a = calloc(MC_EIG_NSYM * ql, sizeof *a), *b = calloc(MC_EIG_NSYM * ql, sizeof *b);
    double *qa[MC_EIG_NSYM], *qb[MC_EIG_NSYM];
    for (int n = 0; n < MC_EIG_NSYM; n++) {
        qa[n] = a + n * ql;
        qb[n] = b + n * ql;
    }
    table_cmp s1 = {0, 0}, p3 = {0, 0};
    for (int m = 0; m < 2 * op->nzf; m++) {
        mc_eig_s1_fill(op, m, &cc, qa);
        mc_eig_s1_fill(op, m, NULL, qb);
        table_add(&s1, a, b, MC_EIG_NSYM * ql);
    }
    for (int k = 0; k < op->v.nz; k++) {
        mc_eig_p3_fill(op, k, &cc, qa);
        mc_eig_p3_fill(op, k, NULL, qb);
        table_add(&p3, a, b, 6 * ql);
    }
    const double e1 = s1.diff / s1.size, e3 = p3.diff / p3.size;
    if (getenv("MC_TEST_VERBOSE"))
        printf("corner lattice case %d: s1 %.3g, p3 %.3g\n", _i, e1, e3);
    ck_assert_msg(e1 <= TOL_LATTICE && e3 <= TOL_LATTICE,
                  "case %d: lattice vs per-entry tables: s1 %.3g, p3 %.3g", _i, e1, e3);
    mc_eig_corners_free(&cc);
    mc_eigen_stress_destroy(&op);
    free(a);
    free(b);
}
END_TEST

Suite *suite_eigen_graded(void);
Suite *suite_eigen_graded(void)
{
    Suite *s = suite_create("eigen_graded");
    TCase *tc = tcase_create("graded");
    tcase_set_timeout(tc, 300);
    tcase_add_loop_test(tc, test_backends, 0, N_CASES);
    tcase_add_loop_test(tc, test_ones_are_uniform, 0, 2 * N_CASES);
    tcase_add_loop_test(tc, test_superposition, 0, N_CASES);
    tcase_add_loop_test(tc, test_uniform_closed_form, 0, 4);
    tcase_add_test(tc, test_grade);
    tcase_add_loop_test(tc, test_corner_lattice, 0, 8); /* cases 0, 1: graded and uniform */
    suite_add_tcase(s, tc);
    return s;
}
