/* fuzz_units.c - libFuzzer target: mc_parse_quantity for every unit kind, and the two text
 * helpers of units.h (mc_utf8_check, mc_case_quote) that quote untrusted bytes into messages.
 *
 * Input: arbitrary bytes, cut at the first NUL (the parser takes a C string). Contracts beyond
 * "no sanitizer error":
 *  - every kind: success gives a finite value; failure leaves *si untouched and explains itself
 *    in why (a non-empty printable UTF-8 line); the status and value do not depend on why being
 *    NULL or short, and a short why is cut but NUL-terminated within its length;
 *  - a text accepted as a bare number (MC_UNIT_NONE) is accepted by every kind with the same
 *    value (a bare number is SI);
 *  - mc_case_quote always gives a NUL-terminated printable UTF-8 string within its buffer, and
 *    reproduces a short well-formed text without control bytes exactly.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_common.h"
#include "case/units.h"

#define FUZZ_MAX_INPUT 4096
#define FUZZ_SENTINEL -12345.678

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_printable(const char *s, size_t cap, const char *what)
{
    size_t n = strnlen(s, cap);
    FUZZ_CHECK(n < cap, "%s: not NUL-terminated within %zu bytes", what, cap);
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)s[i];
        FUZZ_CHECK(ch >= 0x20 && ch != 0x7f, "%s: control byte 0x%02X at %zu", what, ch, i);
    }
    size_t bad = 0;
    FUZZ_CHECK(mc_utf8_check(s, n, &bad), "%s: not UTF-8 at byte %zu", what, bad);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char text[FUZZ_MAX_INPUT + 1];
    if (size > FUZZ_MAX_INPUT)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    size_t len = strlen(text);

    double bare = FUZZ_SENTINEL;
    int bare_ok = mc_parse_quantity(text, MC_UNIT_NONE, &bare, NULL, 0) == 0;
    for (int kind = MC_UNIT_NONE; kind <= MC_UNIT_ROTATION; kind++) {
        char why[256], tiny[7];
        double si = FUZZ_SENTINEL, si2 = FUZZ_SENTINEL, si3 = FUZZ_SENTINEL;
        int rc = mc_parse_quantity(text, (mc_unit_kind)kind, &si, why, sizeof why);
        int rc2 = mc_parse_quantity(text, (mc_unit_kind)kind, &si2, NULL, 0);
        memset(tiny, 'x', sizeof tiny);
        size_t tl = 1 + (size ? data[0] % (sizeof tiny - 1) : 0);
        int rc3 = mc_parse_quantity(text, (mc_unit_kind)kind, &si3, tiny, tl);
        FUZZ_CHECK((rc == 0) == (rc2 == 0) && (rc == 0) == (rc3 == 0),
                   "kind %d: status depends on why (%d, %d, %d)", kind, rc, rc2, rc3);
        FUZZ_CHECK(memcmp(&si, &si2, sizeof si) == 0 && memcmp(&si, &si3, sizeof si) == 0,
                   "kind %d: value depends on why", kind);
        if (rc == 0) {
            FUZZ_CHECK(isfinite(si), "kind %d: accepted a non-finite value %g", kind, si);
            if (bare_ok)
                FUZZ_CHECK(memcmp(&si, &bare, sizeof si) == 0,
                           "kind %d: bare number %g read as %g", kind, bare, si);
        } else {
            FUZZ_CHECK(si == FUZZ_SENTINEL, "kind %d: *si written on failure", kind);
            FUZZ_CHECK(why[0] != '\0', "kind %d: no reason given", kind);
            check_printable(why, sizeof why, "why");
            FUZZ_CHECK(memchr(tiny, '\0', tl) != NULL, "kind %d: short why not terminated", kind);
            FUZZ_CHECK(tiny[tl] == 'x', "kind %d: short why written past its length", kind);
        }
        if (bare_ok)
            FUZZ_CHECK(rc == 0, "kind %d: a bare number was refused: %s", kind, why);
    }

    static const size_t lens[] = {8, 9, 13, 64, 96};
    for (size_t i = 0; i < sizeof lens / sizeof lens[0]; i++) {
        char q[128];
        memset(q, 'x', sizeof q);
        mc_case_quote(text, q, lens[i]);
        check_printable(q, lens[i], "mc_case_quote");
        FUZZ_CHECK(q[lens[i]] == 'x', "mc_case_quote wrote past %zu bytes", lens[i]);
    }
    int clean = mc_utf8_check(text, len, NULL);
    for (size_t i = 0; clean && i < len; i++)
        clean = (unsigned char)text[i] >= 0x20 && text[i] != 0x7f;
    if (clean && len <= 60) {
        char q[128];
        mc_case_quote(text, q, sizeof q);
        FUZZ_CHECK(strcmp(q, text) == 0, "mc_case_quote changed a clean text");
    }
    return 0;
}
