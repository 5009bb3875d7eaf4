/* surface_file_testkit.h - file builders shared by test_surface_file.c and
 * test_surface_file_bad.c: encoders for every binary layout, hand-made X3P containers (zipped
 * with libzip, MD5s by nettle directly: independent of the code under test), paths in the test's
 * temporary directory. Header-only (static inline), test code only. */
#ifndef MC_SURFACE_FILE_TESTKIT_H
#define MC_SURFACE_FILE_TESTKIT_H

#include <check.h>
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <nettle/md5.h>
#include <zip.h>

#include "io/surface_file.h"
#include "test_util.h"

/* A path in one temporary directory per process (test_tmpdir makes a new one per call); 8
 * rotating buffers. */
static inline const char *tk_path(const char *name)
{
    static char dir[256], buf[8][1024];
    static int next;
    if (!dir[0])
        snprintf(dir, sizeof dir, "%s", test_tmpdir());
    char *p = buf[next++ % 8];
    snprintf(p, sizeof buf[0], "%s/%s", dir, name);
    return p;
}

static inline int tk_exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

static inline void tk_write(const char *path, const void *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    ck_assert_msg(f != NULL, "cannot create %s", path);
    ck_assert_uint_eq(fwrite(b, 1, n, f), n);
    ck_assert_int_eq(fclose(f), 0);
}

static inline void tk_md5(const void *b, size_t n, char hex[33])
{
    struct md5_ctx c;
    uint8_t d[MD5_DIGEST_SIZE];
    md5_init(&c);
    md5_update(&c, n, b);
    md5_digest(&c, MD5_DIGEST_SIZE, d);
    for (int k = 0; k < MD5_DIGEST_SIZE; k++)
        snprintf(hex + 2 * k, 3, "%02x", d[k]);
}

static inline int tk_contains(const unsigned char *b, size_t n, const char *s)
{
    size_t m = strlen(s);
    for (size_t k = 0; k + m <= n; k++)
        if (memcmp(b + k, s, m) == 0)
            return 1;
    return 0;
}

/* Member name of the zip at path into *buf (malloc'ed): 1, or 0 when absent. */
static inline int tk_unzip(const char *path, const char *name, unsigned char **buf, size_t *len)
{
    int e = 0;
    zip_t *za = zip_open(path, ZIP_RDONLY, &e);
    ck_assert_msg(za != NULL, "%s: not a zip (%d)", path, e);
    zip_stat_t st;
    *buf = NULL;
    *len = 0;
    if (zip_stat(za, name, 0, &st) != 0) {
        zip_discard(za);
        return 0;
    }
    *buf = malloc(st.size + 1);
    zip_file_t *f = zip_fopen(za, name, 0);
    ck_assert(*buf && f);
    ck_assert(zip_fread(f, *buf, st.size) == (zip_int64_t)st.size);
    zip_fclose(f);
    zip_discard(za);
    *len = (size_t)st.size;
    return 1;
}

/* A zip at path holding count members (buffers must live until this returns). */
static inline void tk_zip(const char *path, int count, const char *const *names,
                          const void *const *bufs, const size_t *lens)
{
    int e = 0;
    remove(path);
    zip_t *za = zip_open(path, ZIP_CREATE | ZIP_TRUNCATE, &e);
    ck_assert_msg(za != NULL, "zip_open %s: %d", path, e);
    for (int k = 0; k < count; k++) {
        zip_source_t *s = zip_source_buffer(za, bufs[k], lens[k], 0);
        ck_assert(s && zip_file_add(za, names[k], s, ZIP_FL_OVERWRITE) >= 0);
    }
    ck_assert_msg(zip_close(za) == 0, "zip_close %s", path);
}

/* Encode v at dst as kind 'f' (IEEE binary16/32/64), 'i' (two's complement) or 'u', size bytes,
 * little- or big-endian. Half floats: v must be exactly representable (normal or zero). */
static inline void tk_put_value(unsigned char *dst, double v, char kind, size_t size, int big)
{
    uint64_t u;
    if (kind == 'f' && size == 8) {
        memcpy(&u, &v, 8);
    } else if (kind == 'f' && size == 4) {
        float f = (float)v;
        uint32_t w;
        memcpy(&w, &f, 4);
        u = w;
    } else if (kind == 'f') {
        int e = 0;
        double m = frexp(fabs(v), &e); /* |v| = m 2^e, m in [0.5, 1) */
        u = v == 0 ? 0 : (uint64_t)(e - 1 + 15) << 10 | (uint64_t)((2 * m - 1) * 1024);
        if (signbit(v))
            u |= 0x8000;
    } else {
        int64_t s = (int64_t)v;
        memcpy(&u, &s, 8);
    }
    for (size_t k = 0; k < size; k++)
        dst[big ? size - 1 - k : k] = (unsigned char)(u >> (8 * k));
}

/* A .npy 1.0 header for dict, padded to 64 bytes; returns its length. */
static inline size_t tk_npy_header(unsigned char *img, const char *dict)
{
    size_t dl = strlen(dict), total = (10 + dl + 1 + 63) / 64 * 64, hlen = total - 10;
    memcpy(img, "\x93NUMPY\x01\x00", 8);
    img[8] = (unsigned char)(hlen & 0xff);
    img[9] = (unsigned char)(hlen >> 8);
    memcpy(img + 10, dict, dl);
    memset(img + 10 + dl, ' ', hlen - dl - 1);
    img[total - 1] = '\n';
    return total;
}

/* Parse from an exactly sized heap copy (ASan sees any read past the end), default options. */
static inline int tk_parse(const char *format, const void *b, size_t n, mc_surface_data *out,
                           mc_error *err)
{
    unsigned char *copy = malloc(n ? n : 1);
    ck_assert_ptr_nonnull(copy);
    memcpy(copy, b, n);
    int st = mc_surface_parse_buffer(format, copy, n, "hand", NULL, out, err);
    free(copy);
    return st;
}

/* Heights equal exactly; a NaN in want means an invalid point. */
static inline void tk_assert_heights(const mc_surface_data *r, const double *want, int n)
{
    for (int k = 0; k < n; k++) {
        int valid = r->valid ? r->valid[k] : 1;
        if (isnan(want[k]))
            ck_assert_msg(!valid && isnan(r->z[k]), "point %d: want missing", k);
        else
            ck_assert_msg(valid && r->z[k] == want[k], "point %d: %.17g, want %.17g", k, r->z[k],
                          want[k]);
    }
}

/* ---- hand-made X3P ---------------------------------------------------------------------- */

typedef struct {
    char type;                /* CZ DataType: I L F D */
    int nx, ny;
    double dx, dy, x0, y0, zinc, zoff;
    const char *feature;      /* FeatureType text */
    const char *sizex;        /* SizeX text, NULL = nx */
    const char *prolog;       /* text between the XML declaration and the root, or NULL */
    const char *data_link;    /* PointDataLink text */
    const char *data_member;  /* the member's name in the zip */
    const char *xml;          /* main.xml to use verbatim, or NULL */
    int bad_data_md5, bad_xml_md5, no_main;
    const char *folder;       /* NULL, or every member under this top-level folder ("scan/") */
} tk_x3p;

static inline tk_x3p tk_x3p_default(char type, int nx, int ny)
{
    tk_x3p s = {type, nx, ny, 2.5e-7, 4e-7, 1e-3, -2e-3, 1.0, 0.0, "SUR", NULL, NULL,
                "bindata/data.bin", "bindata/data.bin", NULL, 0, 0, 0, NULL};
    return s;
}

/* Write the container: main.xml in the default namespace without Record2 (both allowed by the
 * schema, unlike what mc_x3p_write produces), an upper-case bare digest in md5checksum.hex. */
static inline void tk_make_x3p(const char *path, const tk_x3p *sp, const unsigned char *data,
                               size_t data_len, const unsigned char *mask, size_t mask_len)
{
    static char xml[8192];
    char dmd5[33], vmd5[33], sizex[32], sum[40];
    tk_md5(data, data_len, dmd5);
    if (sp->bad_data_md5)
        dmd5[0] = dmd5[0] == '0' ? '1' : '0';
    if (mask)
        tk_md5(mask, mask_len, vmd5);
    snprintf(sizex, sizeof sizex, "%d", sp->nx);
    size_t n = 0;
    if (sp->xml) {
        n = (size_t)snprintf(xml, sizeof xml, "%s", sp->xml);
    } else {
        n += (size_t)snprintf(xml + n, sizeof xml - n,
                              "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n%s"
                              "<ISO5436_2 xmlns=\"http://www.opengps.eu/2008/ISO5436_2\">\n"
                              "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>%s"
                              "</FeatureType><Axes>\n",
                              sp->prolog ? sp->prolog : "", sp->feature);
        const char *ax[2] = {"CX", "CY"};
        double inc[2] = {sp->dx, sp->dy}, off[2] = {sp->x0, sp->y0};
        for (int a = 0; a < 2; a++)
            n += (size_t)snprintf(xml + n, sizeof xml - n,
                                  "<%s><AxisType>I</AxisType><DataType>D</DataType><Increment>"
                                  "%.17g</Increment><Offset>%.17g</Offset></%s>\n",
                                  ax[a], inc[a], off[a], ax[a]);
        n += (size_t)snprintf(
            xml + n, sizeof xml - n,
            "<CZ><AxisType>A</AxisType><DataType>%c</DataType><Increment>%.17g</Increment>"
            "<Offset>%.17g</Offset></CZ></Axes></Record1>\n<Record3><MatrixDimension><SizeX>%s"
            "</SizeX><SizeY>%d</SizeY><SizeZ>1</SizeZ></MatrixDimension>\n<DataLink>"
            "<PointDataLink>%s</PointDataLink><MD5ChecksumPointData>%s</MD5ChecksumPointData>",
            sp->type, sp->zinc, sp->zoff, sp->sizex ? sp->sizex : sizex, sp->ny, sp->data_link,
            dmd5);
        if (mask)
            n += (size_t)snprintf(xml + n, sizeof xml - n,
                                  "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>"
                                  "<MD5ChecksumValidPoints>%s</MD5ChecksumValidPoints>",
                                  vmd5);
        n += (size_t)snprintf(xml + n, sizeof xml - n,
                              "</DataLink></Record3>\n<Record4><ChecksumFile>md5checksum.hex"
                              "</ChecksumFile></Record4>\n</ISO5436_2>\n");
    }
    ck_assert_uint_lt(n, sizeof xml);
    tk_md5(xml, n, sum);
    for (int k = 0; k < 32; k++)
        sum[k] = (char)toupper((unsigned char)sum[k]);
    if (sp->bad_xml_md5)
        sum[5] = sum[5] == 'A' ? 'B' : 'A';
    sum[32] = '\n';
    const char *names[4] = {"main.xml", sp->data_member, "md5checksum.hex", "bindata/valid.bin"};
    const void *bufs[4] = {xml, data, sum, mask};
    const size_t lens[4] = {n, data_len, 33, mask_len};
    int count = mask ? 4 : 3;
    char full[4][256];
    for (int k = 0; sp->folder && k < 4; k++) { /* as x3ptools writes them: NAME/main.xml, ... */
        snprintf(full[k], sizeof full[k], "%s%s", sp->folder, names[k]);
        names[k] = full[k];
    }
    if (sp->no_main)
        tk_zip(path, count - 1, names + 1, bufs + 1, lens + 1);
    else
        tk_zip(path, count, names, bufs, lens);
}

#endif
