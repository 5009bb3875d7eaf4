/* fuzz_x3p.c - libFuzzer target: the X3P reader (mc_surface_parse_buffer "x3p").
 *
 * Two input forms (after the optional allocation-failure prefix, see fuzz_surface.h):
 *  - an input starting with "PK" is a whole X3P archive, read with checksums verified (mutations
 *    mostly exercise the zip layer: libzip refuses a member whose CRC no longer matches);
 *  - anything else is split at each "\n#part#\n" into main.xml, bindata/data.bin,
 *    bindata/valid.bin and md5checksum.hex (up to four parts), which this harness zips (stored)
 *    into a valid archive, so that mutations reach the XML and layout checks. Checksums are
 *    verified only when the fourth part is present (mutated XML cannot keep its MD5 right).
 * Contracts: those of fuzz_surface.h, with at most 516 points per input byte (deflate inflates
 * at most 1032:1, each point takes at least 2 bytes) plus a constant.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <zip.h>

#include "fuzz_surface.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define X3P_SEP "\n#part#\n"

/* Zip up to 4 parts into *out (malloc'ed). 0 on success. */
static int x3p_zip_parts(const uint8_t *data, size_t size, uint8_t **out, size_t *out_len,
                         int *parts)
{
    static const char *const names[4] = {"main.xml", "bindata/data.bin", "bindata/valid.bin",
                                         "md5checksum.hex"};
    const uint8_t *b[4];
    size_t n[4];
    int np = 0;
    size_t p = 0, sl = sizeof X3P_SEP - 1;
    while (np < 4) {
        size_t q = p;
        while (q + sl <= size && memcmp(data + q, X3P_SEP, sl) != 0)
            q++;
        int last = q + sl > size || np == 3;
        b[np] = data + p;
        n[np] = last ? size - p : q - p;
        np++;
        if (last)
            break;
        p = q + sl;
    }
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(NULL, 0, 0, &ze);
    zip_t *za = src ? zip_open_from_source(src, ZIP_TRUNCATE, &ze) : NULL;
    zip_error_fini(&ze);
    if (!za) {
        if (src)
            zip_source_free(src);
        return -1;
    }
    for (int k = 0; k < np; k++) {
        zip_source_t *s = zip_source_buffer(za, b[k], n[k], 0);
        zip_int64_t idx = s ? zip_file_add(za, names[k], s, 0) : -1;
        if (idx < 0 || zip_set_file_compression(za, (zip_uint64_t)idx, ZIP_CM_STORE, 0) != 0) {
            if (s && idx < 0)
                zip_source_free(s);
            zip_discard(za);
            return -1;
        }
    }
    zip_source_keep(src);
    if (zip_close(za) != 0) {
        zip_discard(za);
        zip_source_free(src);
        return -1;
    }
    zip_stat_t st;
    int rc = -1;
    if (zip_source_stat(src, &st) == 0 && zip_source_open(src) == 0) {
        *out = malloc(st.size ? st.size : 1);
        if (*out && zip_source_read(src, *out, st.size) == (zip_int64_t)st.size) {
            *out_len = (size_t)st.size;
            rc = 0;
        }
        zip_source_close(src);
    }
    zip_source_free(src);
    if (rc != 0) {
        free(*out);
        *out = NULL;
    }
    *parts = np;
    return rc;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long fail_at = fuzz_alloc_prefix(&data, &size);
    mc_surface_read_options opt = mc_surface_read_defaults();
    if (size >= 2 && data[0] == 'P' && data[1] == 'K') {
        fuzz_surface_parse("x3p", data, size, &opt, fail_at, 516.0 * (double)size + 64);
        return 0;
    }
    uint8_t *zip = NULL;
    size_t zip_len = 0;
    int parts = 0;
    if (x3p_zip_parts(data, size, &zip, &zip_len, &parts) != 0)
        return 0; /* libzip could not build the archive: nothing to test */
    opt.verify_checksum = parts == 4;
    /* an exactly sized copy, so that ASan sees any read past the archive */
    fuzz_surface_parse("x3p", zip, zip_len, &opt, fail_at, 516.0 * (double)zip_len + 64);
    free(zip);
    return 0;
}
