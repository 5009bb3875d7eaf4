/* fuzz_case.c - libFuzzer target: mc_case_parse_text on arbitrary text plus --set overrides.
 *
 * Input layout: [0x01 n] text [\0 override]... - an optional allocation-failure prefix (byte 0x01
 * then n: the (n+1)th allocation of the parse fails), the case text, then up to FUZZ_MAX_OVERRIDES
 * "section.key=value" overrides, each introduced by a NUL byte (a NUL cannot occur in a case
 * text, so the split is unambiguous). The corpus and dictionary are under tests/fuzz/.
 *
 * Contracts checked beyond "no sanitizer error, no leak":
 *  - the status is MC_OK, MC_ERR_INPUT or (only when an allocation failure was injected and
 *    happened) MC_ERR_NOMEM; an injected failure that happened never gives MC_OK;
 *  - on failure the message is one printable UTF-8 line and *scene is untouched;
 *  - on success the scene passes mc_scene_check, keeps the name as its path, has an output
 *    directory, and, with stress enabled (and depths not left to the stress stage, depth_max =
 *    auto), resolves to 1..MC_MAX_DEPTHS finite increasing depths.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "case/case.h"
#include "fuzz_common.h"
#include "case/scene.h"

#define FUZZ_MAX_OVERRIDES 4
#define FUZZ_MAX_INPUT (64 * 1024) /* longer texts only slow the search down */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static mc_scene scene, pristine;
    static char buf[FUZZ_MAX_INPUT + 1];
    if (size > FUZZ_MAX_INPUT)
        return 0;
    long fail_at = 0;
    if (size >= 2 && data[0] == 0x01) {
        fail_at = (long)data[1] + 1;
        data += 2;
        size -= 2;
    }
    memcpy(buf, data, size);
    buf[size] = '\0';

    /* Chunks: text, then overrides, separated by NUL bytes. */
    const char *text = buf;
    const char *ovr[FUZZ_MAX_OVERRIDES];
    int novr = 0;
    for (size_t i = strlen(buf); i < size && novr < FUZZ_MAX_OVERRIDES; i += strlen(buf + i)) {
        i++; /* skip the NUL */
        ovr[novr++] = buf + i;
    }

    memset(&scene, 0xA5, sizeof scene);
    memcpy(&pristine, &scene, sizeof scene);
    mc_error err = {0};
    long injected = mc_alloc_injected();
    mc_alloc_fail_at(fail_at);
    int rc = mc_case_parse_text(text, "fuzz.ini", "cases", novr, ovr, &scene, &err);
    mc_alloc_fail_at(0);
    int fired = mc_alloc_injected() != injected;

    FUZZ_CHECK(rc == MC_OK || rc == MC_ERR_INPUT || (rc == MC_ERR_NOMEM && fired),
               "status %d (%s), injected failure %s: %s", rc, mc_status_name((mc_status)rc),
               fired ? "happened" : "did not happen", err.msg);
    FUZZ_CHECK(!(fired && rc == MC_OK), "an allocation failed but the parse returned MC_OK");
    if (rc != MC_OK) {
        fuzz_check_error(&err, rc);
        FUZZ_CHECK(memcmp(&scene, &pristine, sizeof scene) == 0, "failed parse wrote the scene");
        return 0;
    }

    mc_error chk = {0};
    FUZZ_CHECK(mc_scene_check(&scene, &chk) == MC_OK, "accepted scene fails mc_scene_check: %s",
               chk.msg);
    FUZZ_CHECK(strcmp(scene.path, "fuzz.ini") == 0, "path '%.40s'", scene.path);
    FUZZ_CHECK(scene.output.dir[0] != '\0', "no output directory");
    FUZZ_CHECK(memchr(scene.output.dir, '\0', sizeof scene.output.dir) != NULL, "dir unterminated");
    /* depth_max = 0 passes the checks only as "auto" (resolved by the stress stage) */
    int auto_depth = scene.stress.spacing != MC_SPACING_LIST && scene.stress.depth_max == 0.0;
    if (scene.stress.enabled && !auto_depth) {
        static double z[MC_MAX_DEPTHS];
        int nz = 0;
        FUZZ_CHECK(mc_scene_depths(&scene, z, &nz, &chk) == MC_OK, "depths: %s", chk.msg);
        FUZZ_CHECK(nz >= 1 && nz <= MC_MAX_DEPTHS, "%d depths", nz);
        for (int k = 0; k < nz; k++) {
            FUZZ_CHECK(isfinite(z[k]) && z[k] >= 0, "depth %d = %g", k, z[k]);
            FUZZ_CHECK(k == 0 || z[k] > z[k - 1], "depth %d = %g after %g", k, z[k], z[k - 1]);
        }
    }
    return 0;
}
