/* run_tests.c - the Check runner: every tests/test_<name>.c defines Suite *suite_<name>(void);
 * the Makefile lists them in $(BUILD)/tests/suites.inc. CK_RUN_SUITE=<name> runs one suite. */
#include <check.h>
#include <stdlib.h>

#include "test_util.h"

#define SUITE(name) Suite *suite_##name(void);
#include "suites.inc"
#undef SUITE

int main(void)
{
    SRunner *sr = srunner_create(NULL);
#define SUITE(name) srunner_add_suite(sr, suite_##name());
#include "suites.inc"
#undef SUITE
    srunner_run_all(sr, CK_NORMAL);
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
