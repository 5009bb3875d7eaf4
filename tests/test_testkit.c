/* test_testkit.c - the test helpers that every error check leans on (test_util.h): a worst error
 * that meets a NaN is NaN, so a bound `worst <= tol` fails on it (fmax would drop the NaN and the
 * bound would pass on a broken field). */
#include <check.h>
#include <math.h>

#include "test_util.h"

START_TEST(worst_keeps_nan)
{
    ck_assert_double_eq(test_worst(0.0, 2.5), 2.5);
    ck_assert_double_eq(test_worst(3.0, 2.5), 3.0);
    ck_assert(isnan(test_worst(1.0, NAN)));
    ck_assert(isnan(test_worst(NAN, 1.0)));
    /* a NaN in the middle of a run is not forgotten by a larger value after it */
    double w = 0.0;
    const double v[4] = {1.0, NAN, 5.0, 2.0};
    for (int i = 0; i < 4; i++)
        w = test_worst(w, v[i]);
    ck_assert(isnan(w));
    ck_assert(!(w <= 1e300)); /* the bound it meets fails */
}
END_TEST

START_TEST(rel_maxdiff_keeps_nan)
{
    const double b[3] = {1.0, -4.0, 2.0};
    const double a[3] = {1.0, -3.0, 2.0};
    ck_assert_double_eq(test_rel_maxdiff(a, b, 3), 0.25);
    const double an[3] = {1.0, NAN, 2.0};
    ck_assert(isnan(test_rel_maxdiff(an, b, 3)));
    const double bn[3] = {1.0, -4.0, NAN};
    ck_assert(isnan(test_rel_maxdiff(a, bn, 3)));
    const double ai[3] = {INFINITY, -3.0, 2.0}, bi[3] = {INFINITY, -4.0, 2.0};
    ck_assert(isnan(test_rel_maxdiff(ai, bi, 3))); /* inf - inf */
    const double z[2] = {0.0, 0.0};
    ck_assert_double_eq(test_rel_maxdiff(z, z, 2), 0.0);
}
END_TEST

Suite *suite_testkit(void);
Suite *suite_testkit(void)
{
    Suite *s = suite_create("testkit");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, worst_keeps_nan);
    tcase_add_test(tc, rel_maxdiff_keeps_nan);
    suite_add_tcase(s, tc);
    return s;
}
