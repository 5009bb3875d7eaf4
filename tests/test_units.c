/* test_units.c - unit suffixes: every suffix of every kind, wrong kinds, bare numbers, garbage,
 * and the text helpers used for messages. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "case/units.h"

typedef struct {
    const char *text;
    mc_unit_kind kind;
    double si;
} good_case;

static const good_case good[] = {
    {"2 m", MC_UNIT_LENGTH, 2.0},
    {"2 mm", MC_UNIT_LENGTH, 2e-3},
    {"0.8 um", MC_UNIT_LENGTH, 0.8e-6},
    {"0.8 \xc2\xb5m", MC_UNIT_LENGTH, 0.8e-6},
    {"0.8 \xce\xbcm", MC_UNIT_LENGTH, 0.8e-6},
    {"15nm", MC_UNIT_LENGTH, 15e-9},
    {"1086 N", MC_UNIT_FORCE, 1086.0},
    {"1.5 kN", MC_UNIT_FORCE, 1500.0},
    {"250 mN", MC_UNIT_FORCE, 0.25},
    {"3 Pa", MC_UNIT_PRESSURE, 3.0},
    {"3 kPa", MC_UNIT_PRESSURE, 3e3},
    {"1.2 MPa", MC_UNIT_PRESSURE, 1.2e6},
    {"210 GPa", MC_UNIT_PRESSURE, 210e9},
    {"7 N/m", MC_UNIT_FORCE_PER_LENGTH, 7.0},
    {"500 N/mm", MC_UNIT_FORCE_PER_LENGTH, 5e5},
    {"2 kN/m", MC_UNIT_FORCE_PER_LENGTH, 2e3},
    {"2 kN/mm", MC_UNIT_FORCE_PER_LENGTH, 2e6},
    {"0.5 Pa*s", MC_UNIT_VISCOSITY, 0.5},
    {"0.5 Pa.s", MC_UNIT_VISCOSITY, 0.5},
    {"30 mPa*s", MC_UNIT_VISCOSITY, 0.03},
    {"30 mPa.s", MC_UNIT_VISCOSITY, 0.03},
    {"2 m/s", MC_UNIT_SPEED, 2.0},
    {"20 mm/s", MC_UNIT_SPEED, 0.02},
    {"60 rpm", MC_UNIT_ROTATION, 6.283185307179586},
    {"2000 rpm", MC_UNIT_ROTATION, 2000.0 * 6.283185307179586 / 60.0},
    {"3 rad/s", MC_UNIT_ROTATION, 3.0},
    {"3 1/s", MC_UNIT_ROTATION, 3.0},
    /* bare numbers are SI, in every strtod decimal form */
    {"2.5e-6", MC_UNIT_LENGTH, 2.5e-6},
    {"  -4 ", MC_UNIT_NONE, -4.0},
    {"+.5", MC_UNIT_NONE, 0.5},
    {"5.", MC_UNIT_NONE, 5.0},
    {"1E3", MC_UNIT_FORCE, 1000.0},
    {"0", MC_UNIT_PRESSURE, 0.0},
    {"1e-400", MC_UNIT_NONE, 0.0}, /* underflow to zero is harmless */
    {"3\tmm", MC_UNIT_LENGTH, 3e-3},
};

START_TEST(test_good)
{
    const good_case *c = &good[_i];
    double v = -12345.0;
    char why[256] = "";
    int rc = mc_parse_quantity(c->text, c->kind, &v, why, sizeof why);
    ck_assert_msg(rc == 0, "'%s' rejected: %s", c->text, why);
    ck_assert_msg(fabs(v - c->si) <= TOL_TIGHT * fabs(c->si), "'%s' -> %.17g, expected %.17g",
                  c->text, v, c->si);
}
END_TEST

typedef struct {
    const char *text;
    mc_unit_kind kind;
    const char *why; /* the reason must contain this */
} bad_case;

static const bad_case bad[] = {
    {"3 N", MC_UNIT_LENGTH, "unit 'N' is a force; a length is due (m, mm, um, nm)"},
    {"3 mm", MC_UNIT_FORCE, "unit 'mm' is a length; a force is due (N, kN, mN)"},
    {"3 GPa", MC_UNIT_LENGTH, "unit 'GPa' is a pressure; a length is due"},
    {"3 N/mm", MC_UNIT_FORCE, "unit 'N/mm' is a force per length; a force is due"},
    {"3 mPa*s", MC_UNIT_PRESSURE, "is a viscosity; a pressure is due (Pa, kPa, MPa, GPa)"},
    {"3 m/s", MC_UNIT_LENGTH, "is a speed"},
    {"3 rpm", MC_UNIT_SPEED, "unit 'rpm' is a rotation speed; a speed is due (m/s, mm/s)"},
    {"3 mm", MC_UNIT_NONE, "unit 'mm' is a length; a plain number is due (no unit)"},
    {"3 xyz", MC_UNIT_LENGTH, "unknown unit 'xyz'; a length is due (m, mm, um, nm)"},
    {"3 MN", MC_UNIT_FORCE, "unknown unit 'MN'; a force is due (N, kN, mN)"},
    {"3 Mm", MC_UNIT_LENGTH, "unknown unit 'Mm'"},
    {"3 gpa", MC_UNIT_PRESSURE, "unknown unit 'gpa'"},
    {"3 m m", MC_UNIT_LENGTH, "unknown unit 'm m'"},
    {"3 x", MC_UNIT_NONE, "unexpected 'x' after the number; a plain number is due"},
    {"1.5.3", MC_UNIT_NONE, "unexpected '.3'"},
    {"abc", MC_UNIT_LENGTH, "'abc' is not a number; a length is due"},
    {"- 3", MC_UNIT_NONE, "is not a number"},
    {".", MC_UNIT_NONE, "'.' is not a number"},
    {"", MC_UNIT_LENGTH, "a value is required"},
    {"   ", MC_UNIT_FORCE, "a value is required"},
    {"nan", MC_UNIT_NONE, "NaN and infinity are not accepted"},
    {"-Inf", MC_UNIT_NONE, "NaN and infinity are not accepted"},
    {"infinity m", MC_UNIT_LENGTH, "NaN and infinity are not accepted"},
    {"0x10", MC_UNIT_NONE, "hexadecimal numbers are not accepted"},
    {"1e999", MC_UNIT_NONE, "out of range"},
    {"1e300 GPa", MC_UNIT_PRESSURE, "out of range"},
    {"3 \xff", MC_UNIT_LENGTH, "unknown unit '\\xFF'"},
};

START_TEST(test_bad)
{
    const bad_case *c = &bad[_i];
    double v = -12345.0;
    char why[256] = "";
    int rc = mc_parse_quantity(c->text, c->kind, &v, why, sizeof why);
    ck_assert_msg(rc != 0, "'%s' accepted as %g", c->text, v);
    ck_assert_msg(v == -12345.0, "'%s': output written on failure", c->text);
    ck_assert_msg(strstr(why, c->why) != NULL, "'%s': reason '%s' lacks '%s'", c->text, why,
                  c->why);
}
END_TEST

START_TEST(test_why_optional_and_cut)
{
    double v = 0;
    ck_assert_int_ne(mc_parse_quantity("3 N", MC_UNIT_LENGTH, &v, NULL, 0), 0);
    char small[12];
    ck_assert_int_ne(mc_parse_quantity("3 N", MC_UNIT_LENGTH, &v, small, sizeof small), 0);
    ck_assert_uint_eq(strlen(small), sizeof small - 1);
}
END_TEST

START_TEST(test_kind_names)
{
    ck_assert_str_eq(mc_unit_kind_name(MC_UNIT_LENGTH), "length");
    ck_assert_str_eq(mc_unit_suffixes(MC_UNIT_LENGTH), "m, mm, um, nm");
    ck_assert_str_eq(mc_unit_si_symbol(MC_UNIT_PRESSURE), "Pa");
    ck_assert_str_eq(mc_unit_si_symbol(MC_UNIT_ROTATION), "rad/s");
    ck_assert_str_eq(mc_unit_suffixes(MC_UNIT_NONE), "");
    /* every advertised suffix of every kind parses as that kind */
    for (int k = MC_UNIT_LENGTH; k <= MC_UNIT_ROTATION; k++) {
        char list[128];
        snprintf(list, sizeof list, "%s", mc_unit_suffixes((mc_unit_kind)k));
        char *save = NULL;
        int n = 0;
        for (char *s = strtok_r(list, ", ", &save); s; s = strtok_r(NULL, ", ", &save), n++) {
            char text[64], why[256];
            double v = 0;
            snprintf(text, sizeof text, "1 %s", s);
            ck_assert_msg(mc_parse_quantity(text, (mc_unit_kind)k, &v, why, sizeof why) == 0,
                          "%s: %s", text, why);
            ck_assert_msg(v > 0, "%s -> %g", text, v);
        }
        ck_assert_int_ge(n, 2);
    }
}
END_TEST

START_TEST(test_utf8)
{
    size_t at = 99;
    const char *ok = "plain \xc2\xb5m \xe2\x89\xa4 \xf0\x9f\x98\x80";
    ck_assert(mc_utf8_check(ok, strlen(ok), &at));
    ck_assert(!mc_utf8_check(ok, strlen(ok) - 1, &at)); /* cut inside the last character */
    ck_assert_uint_eq(at, strlen(ok) - 4);
    ck_assert(!mc_utf8_check("ab\xff", 3, &at));
    ck_assert_uint_eq(at, 2);
    ck_assert(!mc_utf8_check("\xc0\xaf", 2, &at)); /* overlong '/' */
    ck_assert_uint_eq(at, 0);
    ck_assert(!mc_utf8_check("x\xed\xa0\x80", 4, &at)); /* surrogate */
    ck_assert_uint_eq(at, 1);
    ck_assert(!mc_utf8_check("\xf4\x90\x80\x80", 4, &at)); /* > U+10FFFF */
    ck_assert(!mc_utf8_check("\xe2\x89", 2, &at));         /* truncated */
}
END_TEST

START_TEST(test_quote)
{
    char buf[128];
    mc_case_quote("a\tb\xff \xc2\xb5m", buf, sizeof buf);
    ck_assert_str_eq(buf, "a\\x09b\\xFF \xc2\xb5m");
    char longtext[300];
    memset(longtext, 'x', sizeof longtext - 1);
    longtext[sizeof longtext - 1] = '\0';
    mc_case_quote(longtext, buf, sizeof buf);
    ck_assert_uint_eq(strlen(buf), 63);
    ck_assert_str_eq(buf + 60, "...");
    char small[10];
    mc_case_quote(longtext, small, sizeof small);
    ck_assert_uint_lt(strlen(small), sizeof small);
    ck_assert_str_eq(small + strlen(small) - 3, "...");
    /* a multi-byte character is never split */
    char mu[200] = "";
    for (int k = 0; k < 40; k++)
        strcat(mu, "\xc2\xb5");
    mc_case_quote(mu, buf, sizeof buf);
    size_t n = strlen(buf) - 3;
    ck_assert(mc_utf8_check(buf, n, NULL));
}
END_TEST

Suite *suite_units(void);
Suite *suite_units(void)
{
    Suite *s = suite_create("units");
    TCase *tc = tcase_create("parse");
    tcase_add_loop_test(tc, test_good, 0, (int)(sizeof good / sizeof good[0]));
    tcase_add_loop_test(tc, test_bad, 0, (int)(sizeof bad / sizeof bad[0]));
    tcase_add_test(tc, test_why_optional_and_cut);
    tcase_add_test(tc, test_kind_names);
    suite_add_tcase(s, tc);
    TCase *tt = tcase_create("text");
    tcase_add_test(tt, test_utf8);
    tcase_add_test(tt, test_quote);
    suite_add_tcase(s, tt);
    return s;
}
