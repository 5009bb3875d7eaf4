/* test_fuzz_replay_surface.c - the measured-surface fuzz targets' inputs, replayed in the unit
 * tests (the same scheme as test_fuzz_replay.c, for fuzz_x3p, fuzz_sdf, fuzz_gsf, fuzz_xyz and
 * fuzz_npy_any): each target is compiled in here under another name with its contract checks
 * (a broken contract aborts, which Check reports as an error) and fed every file of
 * tests/fuzz/corpus/<target>/ and tests/fuzz/regressions/<target>/, so `make check` and
 * `make check-sanitize` replay them without clang. Each seed directory must hold inputs the
 * reader accepts and inputs it refuses.
 */
#include <check.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/surface_file.h"
#include "test_util.h"

#define LLVMFuzzerTestOneInput fuzz_x3p_one
#include "fuzz/fuzz_x3p.c"
#undef LLVMFuzzerTestOneInput

#define LLVMFuzzerTestOneInput fuzz_sdf_one
#include "fuzz/fuzz_sdf.c"
#undef LLVMFuzzerTestOneInput

#define LLVMFuzzerTestOneInput fuzz_gsf_one
#include "fuzz/fuzz_gsf.c"
#undef LLVMFuzzerTestOneInput

#define LLVMFuzzerTestOneInput fuzz_xyz_one
#include "fuzz/fuzz_xyz.c"
#undef LLVMFuzzerTestOneInput

#define LLVMFuzzerTestOneInput fuzz_npy_any_one
#include "fuzz/fuzz_npy_any.c"
#undef LLVMFuzzerTestOneInput

typedef int (*fuzz_fn)(const uint8_t *, size_t);

/* Whether the reader behind a target accepts an input, read as the target reads it; inputs
 * with the allocation-failure prefix count as refused. */
static int accepts(const char *format, const uint8_t *d, size_t n)
{
    if (n >= 2 && d[0] == 0x01)
        return 0;
    mc_surface_read_options opt = mc_surface_read_defaults();
    uint8_t *zip = NULL;
    size_t zip_len = 0;
    int parts = 0;
    if (strcmp(format, "x3p") == 0 && !(n >= 2 && d[0] == 'P' && d[1] == 'K')) {
        if (x3p_zip_parts(d, n, &zip, &zip_len, &parts) != 0)
            return 0;
        opt.verify_checksum = parts == 4;
        d = zip;
        n = zip_len;
    }
    mc_surface_data s;
    int ok = mc_surface_parse_buffer(format, d, n, "replay", &opt, &s, NULL) == MC_OK;
    mc_surface_data_free(&s);
    free(zip);
    return ok;
}

static const struct {
    const char *name, *format;
    fuzz_fn run;
} targets[] = {
    {"fuzz_x3p", "x3p", fuzz_x3p_one},   {"fuzz_sdf", "sdf", fuzz_sdf_one},
    {"fuzz_gsf", "gsf", fuzz_gsf_one},   {"fuzz_xyz", "xyz", fuzz_xyz_one},
    {"fuzz_npy_any", "npy", fuzz_npy_any_one},
};

/* One input through target *ctx: run, then whether it is accepted (test_util.h). */
static int replay_one(void *ctx, const uint8_t *in, size_t n)
{
    const int t = *(const int *)ctx;
    targets[t].run(in, n);
    return accepts(targets[t].format, in, n);
}

START_TEST(test_replay)
{
    int t = _i;
    test_replay_target(targets[t].name, replay_one, &t);
    mc_alloc_fail_at(0);
}
END_TEST

Suite *suite_fuzz_replay_surface(void);
Suite *suite_fuzz_replay_surface(void)
{
    Suite *s = suite_create("fuzz_replay_surface");
    TCase *tc = tcase_create("replay");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_replay, 0, (int)(sizeof targets / sizeof targets[0]));
    suite_add_tcase(s, tc);
    return s;
}
