/* eigen_testkit.h - helpers shared by the eigenstrain operator tests (test_eigen_operator.c,
 * test_eigen_periodic.c, test_eigen_graded.c, ...): volume fields, the largest magnitude,
 * operators created or the test failed, the laterally uniform field's closed form. Header-only
 * (static inline), test code only. */
#ifndef MC_EIGEN_TESTKIT_H
#define MC_EIGEN_TESTKIT_H

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "plastic/eigen_op.h"
#include "test_util.h"

/* Six component arrays of n values carved from one zeroed block (component-major); free the
 * returned block. */
static inline double *eig_fields(size_t n, double *f[6])
{
    double *b = calloc(6 * n, sizeof *b);
    ck_assert(b != NULL);
    for (int c = 0; c < 6; c++)
        f[c] = b + (size_t)c * n;
    return b;
}

static inline double eig_max_abs(const double *a, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++)
        m = test_worst(m, fabs(a[i]));
    return m;
}

static inline mc_eigen_disp *eig_disp_op(const mc_grid *g, const mc_eigen_volume *v, double nu,
                                         mc_backend b)
{
    mc_eigen_disp *op = NULL;
    mc_error err;
    int rc = mc_eigen_disp_create(g, v, nu, b, &op, &err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
    return op;
}

static inline mc_eigen_stress *eig_stress_op(const mc_grid *g, const mc_eigen_volume *v,
                                             double nu, mc_backend b)
{
    mc_eigen_stress *op = NULL;
    mc_error err;
    int rc = mc_eigen_stress_create(g, v, nu, b, &op, &err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
    return op;
}

/* A laterally uniform eigenstrain in a doubly periodic half-space, random per layer (seed), through
 * both operators of backend b on grid g, volume v: each layer's closed form (in-plane total
 * strains 0, sigma_zz = sigma_xz = sigma_yz = 0) and u_z = -sum of thickness x (eps_zz + a tr),
 * a = nu / (1 - nu), to tol of the largest stress and of |u_z| (theory.md §8.6). */
static inline void eig_check_uniform(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                     double nu, double G, unsigned seed, double tol,
                                     const char *label)
{
    const size_t nw = (size_t)v->nx * v->ny, n = nw * v->nz;
    double *e = malloc((size_t)v->nz * 6 * sizeof *e);
    ck_assert(e != NULL);
    test_random_field(e, (size_t)v->nz * 6, seed);
    double *eps[6], *sig[6], *b1 = eig_fields(n, eps), *b2 = eig_fields(n, sig);
    for (int k = 0; k < v->nz; k++)
        for (int c = 0; c < 6; c++)
            for (size_t s = 0; s < nw; s++)
                eps[c][k * nw + s] = e[k * 6 + c];
    const size_t ns = (size_t)g->nx * g->ny;
    double *u = malloc(ns * sizeof *u);
    ck_assert(u != NULL);
    mc_eigen_disp *od = eig_disp_op(g, v, nu, b);
    mc_eigen_stress *os = eig_stress_op(g, v, nu, b);
    mc_eigen_disp_apply(od, (const double *const *)eps, u);
    mc_eigen_stress_apply(os, (const double *const *)eps, G, sig);
    const double a = nu / (1.0 - nu);
    double uref = 0.0, smax = 0.0, worst = 0.0;
    for (int k = 0; k < v->nz; k++) {
        const double *ek = e + k * 6;
        uref -= mc_eigen_layer_thickness(v, k) * (ek[2] + a * (ek[0] + ek[1]));
        const double want[6] = {-2.0 * G * (ek[0] + a * (ek[0] + ek[1])),
                                -2.0 * G * (ek[1] + a * (ek[0] + ek[1])), 0.0, -2.0 * G * ek[3],
                                0.0, 0.0};
        for (int c = 0; c < 6; c++) {
            smax = test_worst(smax, fabs(want[c]));
            for (size_t s = 0; s < nw; s++)
                worst = test_worst(worst, fabs(sig[c][k * nw + s] - want[c]));
        }
    }
    double uworst = 0.0;
    for (size_t s = 0; s < nw; s++)
        uworst = test_worst(uworst, fabs(u[s] - uref));
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "%s: stress %.3g, u_z %.3g (relative)\n", label, worst / smax,
                uworst / fabs(uref));
    ck_assert_msg(worst <= tol * smax, "%s: stress off the closed form by %.3g of %.3g", label,
                  worst, smax);
    ck_assert_msg(uworst <= tol * fabs(uref), "%s: u_z off %.6g by %.3g", label, uref, uworst);
    mc_eigen_disp_destroy(&od);
    mc_eigen_stress_destroy(&os);
    free(u), free(b1), free(b2), free(e);
}

#endif
