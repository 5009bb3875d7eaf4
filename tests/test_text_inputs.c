/* test_text_inputs.c - text and profile inputs as other tools write them (issue 23, class 2): a
 * header line is reported as a header (not as a column-count mismatch), and 'x z' pairs of a
 * line scan are refused as a surface, saying it is a profile. */
#include <check.h>
#include <string.h>

#include "io/surface_file.h"
#include "test_util.h"

typedef struct {
    const char *format, *text, *want;
} text_case;

static const text_case cases[] = {
    {"txt", "h=650 w=650\n1 2 3\n4 5 6\n", "x:1: 'h=650 w=650' is a header line"},
    {"txt", "# made by a profiler\nWidth 3\n1 2 3\n", "x:2: 'Width 3' is a header line"},
    {"txt", "650 650\n1 2 3\n4 5 6\n", "if that line is a header"},
    {"txt", "0 1e-6\n1e-5 2e-6\n2e-5 1e-6\n", "a profile (a line scan), not a surface"},
    {"txt", "3 1e-6\n2 2e-6\n1 1e-6\n0 0\n", "a profile (a line scan), not a surface"},
    {"xyz", "0 1e-6\n1e-5 2e-6\n2e-5 1e-6\n", "x:1: 2 values: 'x z' pairs are a profile"},
    {"xyz", "x y z\n0 0 1\n", "x:1: 'x y z' is a header line"},
    /* a later word is still a number error, not a header */
    {"txt", "1 2\n3 x\n", "x:2: 'x' is not a number"},
};

START_TEST(test_text_case)
{
    const text_case *c = &cases[_i];
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_int_eq(mc_surface_parse_buffer(c->format, (const unsigned char *)c->text,
                                             strlen(c->text), "x", NULL, &r, &err),
                     MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, c->want) != NULL, "case %d: '%s' lacks '%s'", _i, err.msg,
                  c->want);
}
END_TEST

/* two columns that are not x z pairs stay a surface two points wide */
START_TEST(test_two_columns_surface)
{
    const char *t = "1 2\n0 5\n3 1\n";
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_int_eq(mc_surface_parse_buffer("txt", (const unsigned char *)t, strlen(t), "x", NULL,
                                             &r, &err),
                     MC_OK);
    ck_assert_int_eq(r.nx, 2);
    ck_assert_int_eq(r.ny, 3);
    mc_surface_data_free(&r);
}
END_TEST

Suite *suite_text_inputs(void);
Suite *suite_text_inputs(void)
{
    Suite *s = suite_create("text_inputs");
    TCase *tc = tcase_create("text");
    tcase_add_loop_test(tc, test_text_case, 0, (int)(sizeof cases / sizeof cases[0]));
    tcase_add_test(tc, test_two_columns_surface);
    suite_add_tcase(s, tc);
    return s;
}
