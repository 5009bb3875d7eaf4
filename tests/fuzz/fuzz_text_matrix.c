/* fuzz_text_matrix.c - libFuzzer target: mc_text_matrix_parse on arbitrary bytes.
 *
 * The buffer is exactly `size` bytes (no terminator), so AddressSanitizer catches any read past
 * it. Contracts beyond "no sanitizer error, no leak":
 *  - status MC_OK or MC_ERR_INPUT (MC_ERR_NOMEM only for an injected failure: input prefix
 *    "\x01" n makes the (n+1)th allocation fail);
 *  - failure: a printable one-line message, *data left NULL;
 *  - success: rows, cols >= 1, every value finite, and rows * cols equals the number of
 *    whitespace-separated tokens outside '#' comments (counted here independently).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_common.h"
#include "io/heightmap.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int blank(uint8_t c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/* Tokens outside comments, the reference count for a successful parse. */
static size_t count_tokens(const uint8_t *s, size_t n)
{
    size_t i = 0, count = 0;
    if (n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0)
        i = 3;
    int in_comment = 0, in_token = 0;
    for (; i < n; i++) {
        uint8_t c = s[i];
        if (c == '\n') {
            in_comment = in_token = 0;
            continue;
        }
        if (in_comment)
            continue;
        if (c == '#') {
            in_comment = 1;
            in_token = 0;
        } else if (blank(c)) {
            in_token = 0;
        } else if (!in_token) {
            in_token = 1;
            count++;
        }
    }
    return count;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long fail_at = 0;
    if (size >= 2 && data[0] == 0x01) {
        fail_at = (long)data[1] + 1;
        data += 2;
        size -= 2;
    }
    double *d = NULL;
    int rows = -1, cols = -1;
    mc_error err = {0};
    long injected = mc_alloc_injected();
    mc_alloc_fail_at(fail_at);
    int rc = mc_text_matrix_parse((const char *)data, size, "fuzz.txt", &d, &rows, &cols, &err);
    mc_alloc_fail_at(0);
    int fired = mc_alloc_injected() != injected;

    FUZZ_CHECK(rc == MC_OK || rc == MC_ERR_INPUT || (rc == MC_ERR_NOMEM && fired),
               "status %d: %s", rc, err.msg);
    FUZZ_CHECK(!(fired && rc == MC_OK), "an allocation failed but the parse returned MC_OK");
    if (rc != MC_OK) {
        fuzz_check_error(&err, rc);
        FUZZ_CHECK(d == NULL, "data set on failure");
        return 0;
    }
    FUZZ_CHECK(d != NULL && rows >= 1 && cols >= 1, "rows %d, cols %d", rows, cols);
    size_t n = (size_t)rows * (size_t)cols;
    FUZZ_CHECK(n == count_tokens(data, size), "%d x %d values, %zu tokens", rows, cols,
               count_tokens(data, size));
    for (size_t k = 0; k < n; k++)
        FUZZ_CHECK(isfinite(d[k]), "value %zu = %g", k, d[k]);
    mc_free(d);
    return 0;
}
