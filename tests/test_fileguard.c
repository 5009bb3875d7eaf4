/* test_fileguard.c - nothing reads forever (issue 23, class 7): every reader of a file the user
 * names refuses a device, a FIFO or an oversized file before opening it, naming the file. */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "test_util.h"
#include "core/fileguard.h"
#include "io/file.h"
#include "io/npy.h"
#include "io/surface_file.h"
#include "pipeline/checkpoint.h"
#include "plastic/hardening.h"

static char fifo[512];

static void make_fifo(void)
{
    snprintf(fifo, sizeof fifo, "%s/a_fifo", test_tmpdir());
    remove(fifo);
    ck_assert_int_eq(mkfifo(fifo, 0600), 0);
}

START_TEST(test_guard_kinds)
{
    mc_error err = {0};
    ck_assert_int_eq(mc_file_guard("/dev/zero", 0, "a thing", &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "/dev/zero: not a regular file (a character device)"));
    ck_assert_ptr_nonnull(strstr(err.msg, "a thing must be a regular file"));
    make_fifo();
    ck_assert_int_eq(mc_file_guard(fifo, 0, "a thing", &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "a FIFO or pipe"));
    /* what the caller's open reports in its own words passes */
    ck_assert_int_eq(mc_file_guard("/nonexistent/x", 0, "a thing", &err), MC_OK);
    ck_assert_int_eq(mc_file_guard(test_tmpdir(), 0, "a thing", &err), MC_OK);
    char path[512];
    snprintf(path, sizeof path, "%s/small.txt", test_tmpdir());
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs("0123456789", f);
    fclose(f);
    ck_assert_int_eq(mc_file_guard(path, 10, "a thing", &err), MC_OK);
    ck_assert_int_eq(mc_file_guard(path, 9, "a thing", &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "larger than"));
}
END_TEST

/* Every reader: /dev/zero and a FIFO without writer are refused at once (before the guard, the
 * first read until memory ran out, the second blocked in open for ever). */
START_TEST(test_readers_refuse_devices)
{
    make_fifo();
    const char *paths[2] = {"/dev/zero", fifo};
    for (int k = 0; k < 2; k++) {
        const char *p = paths[k];
        mc_error err = {0};
        mc_surface_read_options o = mc_surface_read_defaults();
        o.format = "x3p";
        mc_surface_data s;
        ck_assert_int_eq(mc_surface_file_read(p, &o, &s, &err), MC_ERR_INPUT);
        ck_assert_ptr_nonnull(strstr(err.msg, "a surface file must be a regular file"));
        double *d = NULL;
        int r, c;
        ck_assert_int_eq(mc_npy_read(p, &d, &r, &c, &err), MC_ERR_INPUT);
        ck_assert_ptr_nonnull(strstr(err.msg, "not a regular file"));
        mc_hardening h;
        ck_assert_int_eq(mc_hardening_table_read(p, 1e6, &h, &err), MC_ERR_INPUT);
        ck_assert_ptr_nonnull(strstr(err.msg, "a hardening table must be a regular file"));
    }
    /* a checkpoint that is a FIFO */
    char dir[512], ck[600];
    snprintf(dir, sizeof dir, "%s/ckdir", test_tmpdir());
    mkdir(dir, 0700);
    snprintf(ck, sizeof ck, "%s/%s", dir, MC_CHECKPOINT_FILE);
    remove(ck);
    ck_assert_int_eq(mkfifo(ck, 0600), 0);
    mc_checkpoint c;
    mc_error err = {0};
    ck_assert_int_eq(mc_checkpoint_read(dir, &c, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "a checkpoint must be a regular file"));
    remove(ck);
}
END_TEST

Suite *suite_fileguard(void);
Suite *suite_fileguard(void)
{
    Suite *s = suite_create("fileguard");
    TCase *tc = tcase_create("guard");
    tcase_set_timeout(tc, 20);
    tcase_add_test(tc, test_guard_kinds);
    tcase_add_test(tc, test_readers_refuse_devices);
    suite_add_tcase(s, tc);
    return s;
}
