/* test_fuzz_replay.c - the fuzz targets' inputs, replayed in the unit tests.
 *
 * Each libFuzzer target (tests/fuzz/fuzz_<x>.c) is compiled in here under another name, with its
 * contract checks (fuzz_common.h: a broken contract aborts, which Check reports as an error), and
 * fed every file of tests/fuzz/corpus/fuzz_<x>/ (the seeds) and of tests/fuzz/regressions/fuzz_<x>/
 * (inputs that once crashed a target: put a crashing input there, named after the bug, together
 * with its fix). So `make check` and `make check-sanitize` (ASan, UBSan, LeakSanitizer) replay
 * them without clang or libFuzzer, and a seed that stops exercising what it was written for shows
 * up here (each seed directory must hold inputs the parser accepts and inputs it refuses).
 */
#include <check.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "case/case.h"
#include "io/heightmap.h"
#include "io/npy.h"
#include "test_util.h"
#include "case/units.h"

#define LLVMFuzzerTestOneInput fuzz_case_one
#include "fuzz/fuzz_case.c"
#undef LLVMFuzzerTestOneInput
#undef FUZZ_MAX_INPUT
#undef FUZZ_MAX_OVERRIDES

#define LLVMFuzzerTestOneInput fuzz_npy_one
#include "fuzz/fuzz_npy.c"
#undef LLVMFuzzerTestOneInput

#define LLVMFuzzerTestOneInput fuzz_text_matrix_one
#include "fuzz/fuzz_text_matrix.c"
#undef LLVMFuzzerTestOneInput

#define LLVMFuzzerTestOneInput fuzz_units_one
#include "fuzz/fuzz_units.c"
#undef LLVMFuzzerTestOneInput
#undef FUZZ_MAX_INPUT

typedef int (*fuzz_fn)(const uint8_t *, size_t);

/* Whether the parser behind a target accepts an input (the replay itself checks contracts). */
typedef int (*accept_fn)(const uint8_t *, size_t);

static int strip_prefix(const uint8_t **d, size_t *n)
{
    if (*n >= 2 && (*d)[0] == 0x01) { /* allocation-failure prefix: not a plain input */
        *d += 2;
        *n -= 2;
        return 1;
    }
    return 0;
}

static int accept_case(const uint8_t *d, size_t n)
{
    if (strip_prefix(&d, &n) || memchr(d, 0, n)) /* overrides: counted with the refused ones */
        return 0;
    char *t = malloc(n + 1);
    ck_assert_ptr_nonnull(t);
    memcpy(t, d, n);
    t[n] = '\0';
    static mc_scene sc;
    int ok = mc_case_parse_text(t, "replay.ini", "", 0, NULL, &sc, NULL) == MC_OK;
    free(t);
    return ok;
}

static int accept_npy(const uint8_t *d, size_t n)
{
    double *v = NULL;
    int r, c;
    if (strip_prefix(&d, &n))
        return 0;
    int ok = mc_npy_parse(d, n, "replay.npy", &v, &r, &c, NULL) == MC_OK;
    mc_free(v);
    return ok;
}

static int accept_text_matrix(const uint8_t *d, size_t n)
{
    double *v = NULL;
    int r, c;
    if (strip_prefix(&d, &n))
        return 0;
    int ok = mc_text_matrix_parse((const char *)d, n, "replay.txt", &v, &r, &c, NULL) == MC_OK;
    mc_free(v);
    return ok;
}

static int accept_units(const uint8_t *d, size_t n)
{
    char t[256];
    if (n >= sizeof t)
        return 0;
    memcpy(t, d, n);
    t[n] = '\0';
    double si;
    for (int k = MC_UNIT_NONE; k <= MC_UNIT_ROTATION; k++)
        if (mc_parse_quantity(t, (mc_unit_kind)k, &si, NULL, 0) == 0)
            return 1;
    return 0;
}

static const struct {
    const char *name;
    fuzz_fn run;
    accept_fn accepts;
} targets[] = {
    {"fuzz_case", fuzz_case_one, accept_case},
    {"fuzz_npy", fuzz_npy_one, accept_npy},
    {"fuzz_text_matrix", fuzz_text_matrix_one, accept_text_matrix},
    {"fuzz_units", fuzz_units_one, accept_units},
};

/* One input through target *ctx: run, then whether it is accepted (test_util.h). */
static int replay_one(void *ctx, const uint8_t *in, size_t n)
{
    const int t = *(const int *)ctx;
    targets[t].run(in, n);
    return targets[t].accepts(in, n);
}

START_TEST(test_replay)
{
    int t = _i;
    test_replay_target(targets[t].name, replay_one, &t);
    mc_alloc_fail_at(0);
}
END_TEST

Suite *suite_fuzz_replay(void);
Suite *suite_fuzz_replay(void)
{
    Suite *s = suite_create("fuzz_replay");
    TCase *tc = tcase_create("replay");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_replay, 0, (int)(sizeof targets / sizeof targets[0]));
    suite_add_tcase(s, tc);
    return s;
}
