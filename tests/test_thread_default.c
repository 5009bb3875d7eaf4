/* test_thread_default.c - the CLI's default thread count (src/cli/thread_default.c): the cores
 * less the other running tasks of /proc/loadavg (its fourth field "running/total", this process
 * included), from the least of the samples; every core when no sample could be read; never
 * below 1. The decision and the parser are tested on given values, not on this machine's load.
 * Mutations tried: procs - least instead of procs - (least - 1) turns test_free_cores red (quiet
 * machine: 1 instead of 2); the largest sample instead of the least turns test_least_sample red. */
#include <check.h>
#include <omp.h>

#include "cli/cli.h"

static int free_cores(int procs, int a, int b, int c)
{
    const int running[3] = {a, b, c};
    return mc_cli_free_cores_from(procs, running, 3);
}

START_TEST(test_free_cores)
{
    ck_assert_int_eq(free_cores(2, 1, 1, 1), 2); /* quiet: only this process runs */
    ck_assert_int_eq(free_cores(2, 2, 2, 2), 1); /* one busy neighbour */
    ck_assert_int_eq(free_cores(2, 5, 5, 5), 1); /* more tasks than cores: still 1 */
    ck_assert_int_eq(free_cores(8, 3, 3, 3), 6);
}
END_TEST

START_TEST(test_least_sample)
{
    /* a task that only passes by in some samples does not count */
    ck_assert_int_eq(free_cores(2, 3, 1, 2), 2);
    ck_assert_int_eq(free_cores(4, 4, 2, 3), 3);
    /* an unreadable sample is skipped, not taken as the least */
    ck_assert_int_eq(free_cores(2, -1, 2, -1), 1);
}
END_TEST

START_TEST(test_unknown)
{
    ck_assert_int_eq(free_cores(2, -1, -1, -1), 2); /* every core, as the runtime would */
    ck_assert_int_eq(free_cores(16, -1, -1, -1), 16);
    ck_assert_int_eq(mc_cli_free_cores_from(3, NULL, 0), 3);
}
END_TEST

START_TEST(test_loadavg_parse)
{
    ck_assert_int_eq(mc_cli_loadavg_running("0.52 0.58 0.59 3/712 12345"), 3);
    ck_assert_int_eq(mc_cli_loadavg_running("0.52 0.58 0.59 3/712 12345\n"), 3);
    ck_assert_int_eq(mc_cli_loadavg_running(""), -1);
    ck_assert_int_eq(mc_cli_loadavg_running("0.1 0.2"), -1);
    ck_assert_int_eq(mc_cli_loadavg_running("a b c d/e"), -1);
    ck_assert_int_eq(mc_cli_loadavg_running(NULL), -1);
}
END_TEST

/* The whole path on this machine: whatever the load, between 1 and every core. */
START_TEST(test_this_machine)
{
    const int n = mc_cli_free_cores();
    ck_assert_int_ge(n, 1);
    ck_assert_int_le(n, omp_get_num_procs());
}
END_TEST

Suite *suite_thread_default(void);
Suite *suite_thread_default(void)
{
    Suite *s = suite_create("thread_default");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_free_cores);
    tcase_add_test(tc, test_least_sample);
    tcase_add_test(tc, test_unknown);
    tcase_add_test(tc, test_loadavg_parse);
    tcase_add_test(tc, test_this_machine);
    suite_add_tcase(s, tc);
    return s;
}
