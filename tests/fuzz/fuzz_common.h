/* fuzz_common.h - oracles shared by the libFuzzer targets (header-only; each target is one
 * translation unit linked with the parser sources it needs, see the Makefile's fuzz block).
 *
 * A crash is what libFuzzer reports: a sanitizer error, a leak (LeakSanitizer runs at exit of
 * every input that allocated), or a broken contract, which FUZZ_CHECK turns into abort() with a
 * line saying which one. */
#ifndef MC_FUZZ_COMMON_H
#define MC_FUZZ_COMMON_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "case/units.h"

#define FUZZ_CHECK(cond, ...)                                                                      \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz contract broken at %s:%d: %s: ", __FILE__, __LINE__, #cond);    \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

/* An error message of the library: one non-empty line of printable UTF-8 text (untrusted bytes
 * are quoted as \xNN or '?'), NUL-terminated within the buffer, and code == the status. */
static inline void fuzz_check_error(const mc_error *err, int status)
{
    FUZZ_CHECK(err->code == (mc_status)status, "status %d, err->code %d", status, (int)err->code);
    size_t n = strnlen(err->msg, sizeof err->msg);
    FUZZ_CHECK(n > 0 && n < sizeof err->msg, "message length %zu", n);
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)err->msg[i];
        FUZZ_CHECK(ch >= 0x20 && ch != 0x7f, "control byte 0x%02X at %zu in message: %s", ch, i,
                   err->msg);
    }
    size_t bad = 0;
    FUZZ_CHECK(mc_utf8_check(err->msg, n, &bad), "message is not UTF-8 at byte %zu: %s", bad,
               err->msg);
}

#endif
