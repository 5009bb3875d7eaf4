/* x3p_write.c - X3P writer, ISO 25178-72 (see mc_x3p_write in surface_file.h).
 *
 * main.xml follows the ISO 5436-2 schema's element order (Record1 Revision, FeatureType, Axes;
 * Record2 Date, Creator, Instrument{Manufacturer, Model, Serial, Version}, CalibrationDate,
 * ProbingSystem{Type, Identification}, Comment; Record3 MatrixDimension, DataLink; Record4
 * ChecksumFile), root prefixed p: in the openGPS namespace, children unqualified, as the openGPS
 * reference library writes it. Numbers use 17 significant digits, which strtod reads back to the
 * same double.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <zip.h>

#include "core/alloc.h"
#include "io/le.h"
#include "io/surface_formats.h"

#define XML_CAP 16384 /* main.xml with the longest creator text accepted */
#define CREATOR_MAX 1024
#define PATH_CAP 4096

typedef struct {
    char *s;
    size_t len, cap;
    int overflow;
} strbuf;

static void put(strbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(strbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= b->cap - b->len)
        b->overflow = 1;
    else
        b->len += (size_t)n;
}

/* Length of the well-formed UTF-8 sequence at s (1..4), 0 if it is not one. */
static size_t utf8_len(const unsigned char *s, size_t n)
{
    size_t len = s[0] < 0x80 ? 1 : (s[0] & 0xE0) == 0xC0 ? 2 : (s[0] & 0xF0) == 0xE0 ? 3
               : (s[0] & 0xF8) == 0xF0 ? 4 : 0;
    if (len == 0 || len > n || (len == 2 && s[0] < 0xC2) || (len == 4 && s[0] > 0xF4))
        return 0;
    for (size_t k = 1; k < len; k++)
        if ((s[k] & 0xC0) != 0x80)
            return 0;
    if ((len == 3 && s[0] == 0xE0 && s[1] < 0xA0) || (len == 3 && s[0] == 0xED && s[1] > 0x9F) ||
        (len == 4 && s[0] == 0xF0 && s[1] < 0x90) || (len == 4 && s[0] == 0xF4 && s[1] > 0x8F))
        return 0;
    return len;
}

/* Free text as XML character data: markup escaped, control bytes and broken UTF-8 as '?'. */
static void put_text(strbuf *b, const char *text)
{
    const unsigned char *s = (const unsigned char *)text;
    size_t n = strlen(text);
    if (n > CREATOR_MAX)
        n = CREATOR_MAX;
    for (size_t k = 0; k < n;) {
        size_t m = utf8_len(s + k, n - k);
        if (m == 0 || (m == 1 && s[k] < 0x20)) {
            put(b, "?");
            k++;
        } else if (m == 1 && strchr("<>&\"'", s[k])) {
            put(b, "%s", s[k] == '<' ? "&lt;" : s[k] == '>' ? "&gt;" : s[k] == '&' ? "&amp;"
                         : s[k] == '"' ? "&quot;" : "&apos;");
            k++;
        } else {
            put(b, "%.*s", (int)m, (const char *)s + k);
            k += m;
        }
    }
}

static time_t write_time(void)
{
    const char *e = getenv("SOURCE_DATE_EPOCH"); /* reproducible builds convention */
    if (e && *e) {
        char *end;
        errno = 0;
        long long t = strtoll(e, &end, 10);
        if (*end == '\0' && errno == 0 && t >= 0)
            return (time_t)t;
    }
    return time(NULL);
}

static void build_xml(strbuf *b, const mc_surface_data *s, const char *creator, const char *date,
                      const char *data_md5, const char *valid_md5)
{
    put(b, "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n"
           "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\" "
           "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
           "xsi:schemaLocation=\"http://www.opengps.eu/2008/ISO5436_2 "
           "http://www.opengps.eu/2008/ISO5436_2/ISO5436_2_XML.xsd\">\n"
           "  <Record1>\n    <Revision>ISO5436 - 2000</Revision>\n"
           "    <FeatureType>SUR</FeatureType>\n    <Axes>\n");
    const char *names[2] = {"CX", "CY"};
    double inc[2] = {s->dx, s->dy}, off[2] = {s->x0, s->y0};
    for (int a = 0; a < 2; a++)
        put(b,
            "      <%s>\n        <AxisType>I</AxisType>\n        <DataType>D</DataType>\n"
            "        <Increment>%.17g</Increment>\n        <Offset>%.17g</Offset>\n      </%s>\n",
            names[a], inc[a], off[a], names[a]);
    put(b, "      <CZ>\n        <AxisType>A</AxisType>\n        <DataType>D</DataType>\n"
           "        <Increment>1</Increment>\n        <Offset>0</Offset>\n      </CZ>\n"
           "    </Axes>\n  </Record1>\n");
    put(b, "  <Record2>\n    <Date>%s</Date>\n    <Creator>", date);
    put_text(b, creator ? creator : "microcontact");
    put(b, "</Creator>\n    <Instrument>\n      <Manufacturer>microcontact</Manufacturer>\n"
           "      <Model>microcontact</Model>\n      <Serial>not available</Serial>\n"
           "      <Version>not available</Version>\n    </Instrument>\n"
           "    <CalibrationDate>%s</CalibrationDate>\n    <ProbingSystem>\n"
           "      <Type>Software</Type>\n      <Identification>microcontact</Identification>\n"
           "    </ProbingSystem>\n    <Comment>heights in metres, written by microcontact"
           "</Comment>\n  </Record2>\n",
        date);
    put(b, "  <Record3>\n    <MatrixDimension>\n      <SizeX>%d</SizeX>\n      <SizeY>%d</SizeY>\n"
           "      <SizeZ>1</SizeZ>\n    </MatrixDimension>\n    <DataLink>\n"
           "      <PointDataLink>bindata/data.bin</PointDataLink>\n"
           "      <MD5ChecksumPointData>%s</MD5ChecksumPointData>\n",
        s->nx, s->ny, data_md5);
    if (valid_md5)
        put(b, "      <ValidPointsLink>bindata/valid.bin</ValidPointsLink>\n"
               "      <MD5ChecksumValidPoints>%s</MD5ChecksumValidPoints>\n",
            valid_md5);
    put(b, "    </DataLink>\n  </Record3>\n  <Record4>\n"
           "    <ChecksumFile>md5checksum.hex</ChecksumFile>\n  </Record4>\n</p:ISO5436_2>\n");
}

/* Add one in-memory member (the buffer must outlive zip_close). 0 on success. */
static int add(zip_t *za, const char *name, const void *buf, size_t len, time_t t)
{
    zip_source_t *src = zip_source_buffer(za, buf, len, 0);
    if (!src)
        return -1;
    zip_int64_t idx = zip_file_add(za, name, src, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    if (idx < 0) {
        zip_source_free(src);
        return -1;
    }
    return zip_file_set_mtime(za, (zip_uint64_t)idx, t, 0);
}

static int write_zip(const char *path, const char *tmp, const unsigned char *xml, size_t xml_len,
                     const unsigned char *data, size_t data_len, const unsigned char *mask,
                     size_t mask_len, const char *sum, time_t t, mc_error *err)
{
    int zerr = 0;
    zip_t *za = zip_open(tmp, ZIP_CREATE | ZIP_TRUNCATE, &zerr);
    if (!za) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, zerr);
        int st = mc_fail(err, MC_ERR_IO, "%s: cannot create %s: %s", path, tmp,
                         zip_error_strerror(&ze));
        zip_error_fini(&ze);
        return st;
    }
    if (add(za, "main.xml", xml, xml_len, t) != 0 ||
        add(za, "bindata/data.bin", data, data_len, t) != 0 ||
        (mask && add(za, "bindata/valid.bin", mask, mask_len, t) != 0) ||
        add(za, "md5checksum.hex", sum, strlen(sum), t) != 0 || zip_close(za) != 0) {
        int st = mc_fail(err, MC_ERR_IO, "%s: cannot write %s: %s", path, tmp, zip_strerror(za));
        zip_discard(za);
        remove(tmp);
        return st;
    }
    return MC_OK;
}

int mc_x3p_write(const char *path, const mc_surface_data *s, const char *creator, mc_error *err)
{
    if (!s || !s->z)
        return mc_fail(err, MC_ERR_INPUT, "%s: no surface to write", path);
    int st = mc_surface_check_dims(s->nx, s->ny, path, err);
    if (st != MC_OK)
        return st;
    if (!(s->dx > 0) || !(s->dy > 0) || !isfinite(s->dx) || !isfinite(s->dy))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: spacing dx = %g m, dy = %g m; an X3P file needs both > 0 (set the "
                       "mesh spacing)",
                       path, s->dx, s->dy);
    if (!isfinite(s->x0) || !isfinite(s->y0))
        return mc_fail(err, MC_ERR_INPUT, "%s: offsets x0 = %g, y0 = %g must be finite", path,
                       s->x0, s->y0);
    char tmp[PATH_CAP];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return mc_fail(err, MC_ERR_INPUT, "%s: path too long", path);

    size_t n = (size_t)s->nx * (size_t)s->ny, mask_len = (n + 7) / 8;
    unsigned char *data = mc_malloc(8 * n), *mask = mc_calloc(mask_len, 1);
    char *xml = mc_malloc(XML_CAP);
    if (!data || !mask || !xml) {
        mc_free(data);
        mc_free(mask);
        mc_free(xml);
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory to write %d x %d points", path, s->nx,
                       s->ny);
    }
    int some_invalid = 0;
    for (size_t k = 0; k < n; k++) {
        mc_le64_put(data + 8 * k, s->z[k]);
        if ((s->valid && !s->valid[k]) || !isfinite(s->z[k]))
            some_invalid = 1;
        else
            mask[k >> 3] |= (unsigned char)(1u << (k & 7));
    }
    char data_md5[33], valid_md5[33], xml_md5[33], sum[64], date[32];
    mc_md5_hex(data, 8 * n, data_md5);
    if (some_invalid)
        mc_md5_hex(mask, mask_len, valid_md5);
    time_t t = write_time();
    struct tm tmv;
    if (!gmtime_r(&t, &tmv) || strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tmv) == 0)
        snprintf(date, sizeof date, "1970-01-01T00:00:00Z");
    strbuf b = {xml, 0, XML_CAP, 0};
    build_xml(&b, s, creator, date, data_md5, some_invalid ? valid_md5 : NULL);
    if (b.overflow) {
        st = mc_fail(err, MC_ERR_INPUT, "%s: main.xml would exceed %d bytes", path, XML_CAP);
    } else {
        mc_md5_hex((const unsigned char *)xml, b.len, xml_md5);
        snprintf(sum, sizeof sum, "%s *main.xml\n", xml_md5);
        st = write_zip(path, tmp, (const unsigned char *)xml, b.len, data, 8 * n,
                       some_invalid ? mask : NULL, mask_len, sum, t, err);
        if (st == MC_OK && rename(tmp, path) != 0) {
            int e = errno;
            remove(tmp);
            st = mc_fail(err, MC_ERR_IO, "%s: cannot rename %s into place: %s", path, tmp,
                         strerror(e));
        }
    }
    mc_free(data);
    mc_free(mask);
    mc_free(xml);
    return st;
}
