/* eigen_testkit.h - helpers shared by the eigenstrain operator tests (test_eigen_operator.c,
 * test_eigen_periodic.c): volume fields, the largest magnitude, operators created or the test
 * failed. Header-only (static inline), test code only. */
#ifndef MC_EIGEN_TESTKIT_H
#define MC_EIGEN_TESTKIT_H

#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "plastic/eigen_op.h"

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
        m = fmax(m, fabs(a[i]));
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

#endif
