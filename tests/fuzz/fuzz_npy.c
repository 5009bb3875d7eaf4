/* fuzz_npy.c - libFuzzer target: mc_npy_parse on arbitrary bytes (an in-memory .npy image).
 *
 * The buffer libFuzzer passes is exactly `size` bytes, so AddressSanitizer catches any read past
 * the image (the parser must never rely on a terminator). Contracts beyond "no sanitizer error,
 * no leak":
 *  - status MC_OK or MC_ERR_INPUT (MC_ERR_NOMEM only for an injected failure: input prefix
 *    "\x01" n makes the (n+1)th allocation fail; every image allocates at most once);
 *  - failure: a printable one-line message, *data left NULL;
 *  - success: 1 <= rows, cols; the image is exactly header + rows*cols*8 bytes; every value is
 *    finite and equals the little-endian float64 at its place at the end of the image.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_common.h"
#include "io/npy.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

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
    int rc = mc_npy_parse(data, size, "fuzz.npy", &d, &rows, &cols, &err);
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
    FUZZ_CHECK(n <= size / 8 && size - 8 * n >= 10, "%d x %d values from %zu bytes", rows, cols,
               size);
    const uint8_t *src = data + size - 8 * n;
    for (size_t k = 0; k < n; k++) {
        uint64_t u = 0;
        for (int b = 7; b >= 0; b--)
            u = (u << 8) | src[8 * k + (size_t)b];
        double v;
        memcpy(&v, &u, sizeof v);
        FUZZ_CHECK(isfinite(d[k]) && memcmp(&v, &d[k], sizeof v) == 0, "value %zu", k);
    }
    mc_free(d);
    return 0;
}
