/* sdf.c - Surface Data File reader, ISO 25178-71 (and the BCR/NIST "SDF" it grew from), see
 * surface_file.h.
 *
 * ASCII ("aISO-1.0", "aISO-2.0", "aBCR-1.0", "aBCR-0.0", "aNIST-1.0" first line): header lines
 * "Key = value" up to a line "*"; then NumPoints*NumProfiles numbers (points along x fastest),
 * whitespace separated, "BAD" or NaN marking a point that was not measured, up to a line "*" or
 * the end; then an optional trailer (ignored). Keys used: NumPoints, NumProfiles, Xscale, Yscale
 * (spacing, m), Zscale (m per stored unit), DataType, Compression and CheckType (must be 0).
 *
 * Binary ("bISO-1.0", "bBCR-1.0": 81-byte header; "bISO-2.0": 85 bytes, 32-bit counts), all
 * little-endian: version[8] ManufacID[10] CreateDate[12] ModDate[12] NumPoints NumProfiles
 * (uint16, or uint32 in 2.0) Xscale Yscale Zscale Zresolution (float64) Compression DataType
 * CheckType (uint8); then the data; then optionally a text trailer (printable bytes, ignored).
 * DataType: 0 uint8, 1 uint16, 2 uint32, 3 float32, 4 int8, 5 int16, 6 int32, 7 float64. A
 * point that was not measured holds the type's lowest value (signed and float types) or NaN.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/surface_formats.h"

#define SDF_BIN_HEADER 81
#define SDF_BIN_HEADER_V2 85

static const size_t type_size[8] = {1, 2, 4, 4, 1, 2, 4, 8};

typedef struct {
    long long nx, ny;
    double xscale, yscale, zscale;
    int data_type;
} sdf_header;

/* The "not measured" marker of each data type (signed: lowest integer; float: lowest value). */
static int is_marker(double raw, int type)
{
    switch (type) {
    case 3:
        return raw == -FLT_MAX;
    case 4:
        return raw == -128.0;
    case 5:
        return raw == -32768.0;
    case 6:
        return raw == -2147483648.0;
    case 7:
        return raw == -DBL_MAX;
    default:
        return 0;
    }
}

static int check_header(const sdf_header *h, const char *what, mc_error *err)
{
    if (h->data_type < 0 || h->data_type > 7)
        return mc_fail(err, MC_ERR_INPUT, "%s: SDF DataType %d not supported; need 0..7", what,
                       h->data_type);
    if (!isfinite(h->xscale) || !isfinite(h->yscale) || h->xscale < 0 || h->yscale < 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: SDF Xscale %g, Yscale %g; need spacings >= 0 m",
                       what, h->xscale, h->yscale);
    if (!isfinite(h->zscale) || h->zscale == 0.0)
        return mc_fail(err, MC_ERR_INPUT, "%s: SDF Zscale %g; need a finite, non-zero scale",
                       what, h->zscale);
    return mc_surface_check_dims(h->nx, h->ny, what, err);
}

static void set_grid(mc_surface_data *out, const sdf_header *h)
{
    out->dx = h->xscale;
    out->dy = h->yscale;
}

/* ---- ASCII ---------------------------------------------------------------------------------- */

typedef struct {
    const char *s;
    size_t len, pos;
    long line;
} text;

/* Next line [*b, *b + *n) without its line end; 0 at the end. */
static int next_line(text *t, const char **b, size_t *n)
{
    if (t->pos >= t->len)
        return 0;
    const char *p = t->s + t->pos;
    const char *nl = memchr(p, '\n', t->len - t->pos);
    size_t m = nl ? (size_t)(nl - p) : t->len - t->pos;
    t->pos += m + (nl ? 1 : 0);
    t->line++;
    if (m > 0 && p[m - 1] == '\r')
        m--;
    *b = p;
    *n = m;
    return 1;
}

static int is_star(const char *b, size_t n)
{
    while (n > 0 && (*b == ' ' || *b == '\t'))
        b++, n--;
    while (n > 0 && (b[n - 1] == ' ' || b[n - 1] == '\t'))
        n--;
    return n == 1 && *b == '*';
}

static int key_is(const char *k, size_t kn, const char *name)
{
    return strlen(name) == kn && memcmp(k, name, kn) == 0;
}

/* The header keys that must be present, in the order of have[] below. */
static const char *const num_keys[5] = {"NumPoints", "NumProfiles", "Xscale", "Yscale", "Zscale"};

static int ascii_header(text *t, sdf_header *h, const char *what, mc_error *err)
{
    int have[5] = {0, 0, 0, 0, 0}; /* NumPoints NumProfiles Xscale Yscale Zscale */
    long long compression = 0, check = 0, dtype = 7;
    const char *b;
    size_t n;
    for (;;) {
        if (!next_line(t, &b, &n))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: truncated SDF file: the header has no closing '*' line", what);
        if (is_star(b, n))
            break;
        const char *eq = memchr(b, '=', n);
        if (!eq) {
            size_t m = 0;
            while (m < n && (b[m] == ' ' || b[m] == '\t'))
                m++;
            if (m == n)
                continue; /* blank line */
            char q[48];
            mc_surface_quote(q, sizeof q, (const unsigned char *)b, n);
            return mc_fail(err, MC_ERR_INPUT, "%s:%ld: SDF header line '%s' is not 'Key = value'",
                           what, t->line, q);
        }
        const char *k = b, *v = eq + 1;
        size_t kn = (size_t)(eq - b), vn = n - kn - 1;
        while (kn > 0 && (*k == ' ' || *k == '\t'))
            k++, kn--;
        while (kn > 0 && (k[kn - 1] == ' ' || k[kn - 1] == '\t'))
            kn--;
        int ok = 1;
        int idx = -1;
        for (int q = 0; q < 5; q++)
            if (key_is(k, kn, num_keys[q]))
                idx = q;
        if (idx == 0 || idx == 1)
            ok = mc_surface_integer(v, vn, idx == 0 ? &h->nx : &h->ny);
        else if (idx >= 2)
            ok = mc_surface_number(v, vn,
                                   idx == 2 ? &h->xscale : idx == 3 ? &h->yscale : &h->zscale);
        else if (key_is(k, kn, "DataType"))
            ok = mc_surface_integer(v, vn, &dtype);
        else if (key_is(k, kn, "Compression"))
            ok = mc_surface_integer(v, vn, &compression);
        else if (key_is(k, kn, "CheckType"))
            ok = mc_surface_integer(v, vn, &check);
        if (!ok) {
            char q[48];
            mc_surface_quote(q, sizeof q, (const unsigned char *)b, n);
            return mc_fail(err, MC_ERR_INPUT, "%s:%ld: SDF header line '%s': bad value", what,
                           t->line, q);
        }
        if (idx >= 0)
            have[idx] = 1;
    }
    for (int q = 0; q < 5; q++)
        if (!have[q])
            return mc_fail(err, MC_ERR_INPUT, "%s: SDF header has no %s", what, num_keys[q]);
    if (compression != 0 || check != 0)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: SDF Compression %lld, CheckType %lld not supported; need 0 and 0",
                       what, compression, check);
    h->data_type = dtype < 0 || dtype > 7 ? -1 : (int)dtype;
    return check_header(h, what, err);
}

/* Number of whitespace-separated tokens in the data section (up to a '*' line or the end). */
static size_t data_tokens(text *t)
{
    size_t count = 0;
    const char *b;
    size_t n;
    while (next_line(t, &b, &n)) {
        if (is_star(b, n))
            break;
        for (size_t p = 0; p < n;) {
            while (p < n && (b[p] == ' ' || b[p] == '\t' || b[p] == '\r'))
                p++;
            size_t q = p;
            while (q < n && b[q] != ' ' && b[q] != '\t' && b[q] != '\r')
                q++;
            if (q > p)
                count++;
            p = q;
        }
    }
    return count;
}

/* One data token: "BAD" or a non-finite number is a point not measured (NaN/Inf kept as is), so
 * is the data type's marker; anything else is scaled by Zscale. 0 if it is not a number. */
static int token_value(const char *b, size_t n, int type, double zscale, double *v)
{
    char tok[80];
    if (n == 3 && memcmp(b, "BAD", 3) == 0) {
        *v = NAN;
        return 1;
    }
    if (n >= sizeof tok)
        return 0;
    memcpy(tok, b, n);
    tok[n] = '\0';
    char *end;
    double x = strtod(tok, &end);
    if ((size_t)(end - tok) != n)
        return 0;
    *v = !isfinite(x) ? x : is_marker(x, type) ? NAN : x * zscale;
    return 1;
}

static int parse_ascii(const unsigned char *buf, size_t len, const char *what,
                       mc_surface_data *out, mc_error *err)
{
    text t = {(const char *)buf, len, 0, 0};
    const char *b;
    size_t n;
    next_line(&t, &b, &n); /* the version line, checked by the caller */
    sdf_header h = {0, 0, 0, 0, 0, 7};
    int st = ascii_header(&t, &h, what, err);
    if (st != MC_OK)
        return st;
    size_t data_at = t.pos;
    long data_line = t.line;
    size_t count = data_tokens(&t), need = (size_t)(h.nx * h.ny);
    if (count != need)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: SDF header says NumPoints x NumProfiles = %lld x %lld = %zu values, "
                       "the data section has %zu",
                       what, h.nx, h.ny, need, count);
    st = mc_surface_alloc(out, h.nx, h.ny, what, err);
    if (st != MC_OK)
        return st;
    set_grid(out, &h);
    t.pos = data_at;
    t.line = data_line;
    size_t k = 0;
    while (k < need && next_line(&t, &b, &n)) {
        for (size_t p = 0; p < n && k < need;) {
            while (p < n && (b[p] == ' ' || b[p] == '\t' || b[p] == '\r'))
                p++;
            size_t q = p;
            while (q < n && b[q] != ' ' && b[q] != '\t' && b[q] != '\r')
                q++;
            if (q == p)
                break;
            double v;
            if (!token_value(b + p, q - p, h.data_type, h.zscale, &v)) {
                char tq[40];
                mc_surface_quote(tq, sizeof tq, (const unsigned char *)b + p, q - p);
                return mc_fail(err, MC_ERR_INPUT, "%s:%ld: SDF value '%s' is not a number", what,
                               t.line, tq);
            }
            out->z[k++] = v;
            p = q;
        }
    }
    return MC_OK;
}

/* ---- binary --------------------------------------------------------------------------------- */

static uint64_t le_get(const unsigned char *b, size_t n)
{
    uint64_t u = 0;
    for (size_t k = n; k-- > 0;)
        u = (u << 8) | b[k];
    return u;
}

static double le_f64(const unsigned char *b)
{
    uint64_t u = le_get(b, 8);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static double raw_value(const unsigned char *b, int type)
{
    uint64_t u = le_get(b, type_size[type]);
    switch (type) {
    case 3: {
        uint32_t w = (uint32_t)u;
        float f;
        memcpy(&f, &w, sizeof f);
        return (double)f;
    }
    case 4:
        return (double)(int8_t)(uint8_t)u;
    case 5:
        return (double)(int16_t)(uint16_t)u;
    case 6:
        return (double)(int32_t)(uint32_t)u;
    case 7: {
        double d;
        memcpy(&d, &u, sizeof d);
        return d;
    }
    default:
        return (double)u;
    }
}

static int parse_binary(const unsigned char *buf, size_t len, int v2, const char *what,
                        mc_surface_data *out, mc_error *err)
{
    size_t hsize = v2 ? SDF_BIN_HEADER_V2 : SDF_BIN_HEADER;
    if (len < hsize)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated binary SDF file: %zu bytes, the header alone has %zu", what,
                       len, hsize);
    size_t cw = v2 ? 4 : 2, p = 42;
    sdf_header h;
    h.nx = (long long)le_get(buf + p, cw);
    h.ny = (long long)le_get(buf + p + cw, cw);
    p += 2 * cw;
    h.xscale = le_f64(buf + p);
    h.yscale = le_f64(buf + p + 8);
    h.zscale = le_f64(buf + p + 16);
    p += 32; /* Zresolution is not used */
    int compression = buf[p], check = buf[p + 2];
    h.data_type = buf[p + 1] > 7 ? -1 : buf[p + 1];
    if (h.data_type < 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: SDF DataType %d not supported; need 0..7", what,
                       buf[p + 1]);
    if (compression != 0 || check != 0)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: SDF Compression %d, CheckType %d not supported; need 0 and 0", what,
                       compression, check);
    int st = check_header(&h, what, err);
    if (st != MC_OK)
        return st;
    size_t n = (size_t)(h.nx * h.ny), size = type_size[h.data_type], avail = len - hsize;
    if (avail < n * size)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated binary SDF: NumPoints x NumProfiles = %lld x %lld values of "
                       "%zu bytes need %zu bytes of data, the file has %zu",
                       what, h.nx, h.ny, size, n * size, avail);
    for (size_t q = hsize + n * size; q < len; q++) /* a trailer is text */
        if ((buf[q] < 0x20 || buf[q] > 0x7e) && buf[q] != '\n' && buf[q] != '\r' &&
            buf[q] != '\t')
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: binary SDF: %zu bytes after the %zu bytes of data are not a text "
                           "trailer (sizes do not match the data?)",
                           what, len - hsize - n * size, n * size);
    st = mc_surface_alloc(out, h.nx, h.ny, what, err);
    if (st != MC_OK)
        return st;
    set_grid(out, &h);
    for (size_t k = 0; k < n; k++) {
        double raw = raw_value(buf + hsize + k * size, h.data_type);
        out->z[k] = is_marker(raw, h.data_type) ? NAN : isfinite(raw) ? raw * h.zscale : raw;
    }
    return MC_OK;
}

int mc_sdf_parse(const unsigned char *buf, size_t len, const char *what, mc_surface_data *out,
                 mc_error *err)
{
    static const char *const ascii[] = {"aISO-1.0", "aISO-2.0", "aBCR-1.0", "aBCR-0.0",
                                        "aNIST-1.0"};
    for (size_t k = 0; k < sizeof ascii / sizeof ascii[0]; k++) {
        size_t m = strlen(ascii[k]);
        if (len >= m && memcmp(buf, ascii[k], m) == 0 &&
            (len == m || buf[m] == '\n' || buf[m] == '\r' || buf[m] == ' ' || buf[m] == '\t'))
            return parse_ascii(buf, len, what, out, err);
    }
    if (len >= 8 && (memcmp(buf, "bISO-1.0", 8) == 0 || memcmp(buf, "bBCR-1.0", 8) == 0))
        return parse_binary(buf, len, 0, what, out, err);
    if (len >= 8 && memcmp(buf, "bISO-2.0", 8) == 0)
        return parse_binary(buf, len, 1, what, out, err);
    char q[16];
    mc_surface_quote(q, sizeof q, buf, len < 8 ? len : 8);
    return mc_fail(err, MC_ERR_INPUT,
                   "%s: not an SDF file: starts with '%s'; need aISO-1.0, aBCR-1.0, bISO-1.0, "
                   "bBCR-1.0 or bISO-2.0",
                   what, q);
}
