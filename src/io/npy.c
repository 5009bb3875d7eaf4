/* npy.c - NumPy .npy reader and writer (see npy.h).
 *
 * Format: "\x93NUMPY", major, minor, header length (uint16 LE for 1.0, uint32 LE for 2.0/3.0),
 * then a Python dict literal {'descr': ..., 'fortran_order': ..., 'shape': (...)} padded with
 * spaces and a newline, then the raw data. The reader parses the dict with a small bounded
 * scanner (never a NUL-terminated string function on the input) because mc_npy_parse is fuzzed.
 */
#include "io/npy.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"

#define NPY_MAGIC "\x93NUMPY"
#define NPY_MAGIC_LEN 6
#define NPY_MAX_RANK 64 /* NumPy's own limit (NPY_MAXDIMS) */
#define NPY_ALIGN 64
#define NPY_PATH_MAX 4096
#define NPY_CHUNK 512 /* doubles encoded per fwrite */

static const char accepted[] = "need a 1-D or 2-D float64 array ('<f8', fortran_order False)";

/* ---- little-endian encoding, independent of the host's byte order ------------------------ */

static double le64_get(const unsigned char *b)
{
    uint64_t u = 0;
    for (int k = 7; k >= 0; k--)
        u = (u << 8) | b[k];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static void le64_put(unsigned char *b, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    for (int k = 0; k < 8; k++) {
        b[k] = (unsigned char)(u & 0xff);
        u >>= 8;
    }
}

/* A printable, bounded copy of untrusted bytes for an error message. */
static void printable(char *out, size_t outlen, const unsigned char *s, size_t n)
{
    size_t k = 0;
    for (; k < n && k + 1 < outlen; k++)
        out[k] = (s[k] >= 0x20 && s[k] < 0x7f) ? (char)s[k] : '?';
    out[k] = '\0';
    if (k < n && outlen > 4)
        memcpy(out + outlen - 4, "...", 4);
}

/* ---- header dict scanner ----------------------------------------------------------------- */

typedef struct {
    const unsigned char *p, *end, *start;
} cursor;

static void skip_ws(cursor *c)
{
    while (c->p < c->end && (*c->p == ' ' || *c->p == '\t' || *c->p == '\n' || *c->p == '\r'))
        c->p++;
}

static int accept_char(cursor *c, char ch)
{
    skip_ws(c);
    if (c->p < c->end && *c->p == (unsigned char)ch) {
        c->p++;
        return 1;
    }
    return 0;
}

static long cur_pos(const cursor *c) { return (long)(c->p - c->start); }

/* A quoted Python string without escapes (all NumPy writes); *s, *n point into the buffer. */
static int scan_string(cursor *c, const unsigned char **s, size_t *n)
{
    skip_ws(c);
    if (c->p >= c->end || (*c->p != '\'' && *c->p != '"'))
        return 0;
    unsigned char q = *c->p++;
    const unsigned char *b = c->p;
    while (c->p < c->end && *c->p != q) {
        if (*c->p == '\\')
            return 0;
        c->p++;
    }
    if (c->p >= c->end)
        return 0;
    *s = b;
    *n = (size_t)(c->p - b);
    c->p++;
    return 1;
}

static int scan_word(cursor *c, const char *w)
{
    skip_ws(c);
    size_t n = strlen(w);
    if ((size_t)(c->end - c->p) < n || memcmp(c->p, w, n) != 0)
        return 0;
    const unsigned char *after = c->p + n;
    if (after < c->end && ((*after >= 'a' && *after <= 'z') || (*after >= 'A' && *after <= 'Z') ||
                           (*after >= '0' && *after <= '9') || *after == '_'))
        return 0;
    c->p = after;
    return 1;
}

/* Non-negative integer, optional Python 2 'L' suffix; *big = 1 if it exceeds INT_MAX. */
static int scan_dim(cursor *c, long long *v, int *big)
{
    skip_ws(c);
    if (c->p >= c->end || *c->p < '0' || *c->p > '9')
        return 0;
    long long x = 0;
    while (c->p < c->end && *c->p >= '0' && *c->p <= '9') {
        if (x <= INT_MAX)
            x = x * 10 + (*c->p - '0');
        c->p++;
    }
    if (c->p < c->end && (*c->p == 'L' || *c->p == 'l'))
        c->p++;
    *big = x > INT_MAX;
    *v = x;
    return 1;
}

typedef struct {
    int have_descr, have_order, have_shape;
    const unsigned char *descr;
    size_t descr_len;
    int descr_is_list;
    int fortran;
    int rank;
    long long dim[NPY_MAX_RANK];
    int dim_big;
} npy_header;

static int header_error(mc_error *err, const char *what, const cursor *c, const char *expected)
{
    return mc_fail(err, MC_ERR_INPUT,
                   "%s: malformed .npy header: %s at byte %ld of the header dict", what, expected,
                   cur_pos(c));
}

static int parse_shape(cursor *c, npy_header *h, const char *what, mc_error *err)
{
    h->rank = 0;
    h->dim_big = 0;
    if (!accept_char(c, '('))
        return header_error(err, what, c, "expected '(' to open 'shape'");
    if (accept_char(c, ')'))
        return MC_OK;
    for (;;) {
        long long v;
        int big;
        if (!scan_dim(c, &v, &big))
            return header_error(err, what, c, "expected a non-negative integer in 'shape'");
        if (h->rank >= NPY_MAX_RANK)
            return mc_fail(err, MC_ERR_INPUT, "%s: 'shape' has more than %d dimensions; %s", what,
                           NPY_MAX_RANK, accepted);
        h->dim[h->rank++] = v;
        h->dim_big |= big;
        if (accept_char(c, ')'))
            return MC_OK;
        if (!accept_char(c, ','))
            return header_error(err, what, c, "expected ',' or ')' in 'shape'");
        if (accept_char(c, ')'))
            return MC_OK;
    }
}

static int parse_dict(cursor *c, npy_header *h, const char *what, mc_error *err)
{
    memset(h, 0, sizeof *h);
    if (!accept_char(c, '{'))
        return header_error(err, what, c, "expected '{'");
    for (;;) {
        if (accept_char(c, '}'))
            break;
        const unsigned char *key;
        size_t klen;
        if (!scan_string(c, &key, &klen))
            return header_error(err, what, c, "expected a quoted key or '}'");
        if (!accept_char(c, ':'))
            return header_error(err, what, c, "expected ':' after a key");
        int st = MC_OK;
        if (klen == 5 && memcmp(key, "descr", 5) == 0) {
            if (h->have_descr)
                return header_error(err, what, c, "duplicate key 'descr'");
            h->have_descr = 1;
            skip_ws(c);
            if (c->p < c->end && *c->p == '[') {
                h->descr_is_list = 1;
                /* Structured dtype: refused below; skip to the matching bracket. */
                int depth = 0;
                do {
                    if (*c->p == '[')
                        depth++;
                    else if (*c->p == ']')
                        depth--;
                    c->p++;
                } while (depth > 0 && c->p < c->end);
                if (depth != 0)
                    return header_error(err, what, c, "unterminated '[' in 'descr'");
            } else if (!scan_string(c, &h->descr, &h->descr_len)) {
                return header_error(err, what, c, "expected a quoted dtype for 'descr'");
            }
        } else if (klen == 13 && memcmp(key, "fortran_order", 13) == 0) {
            if (h->have_order)
                return header_error(err, what, c, "duplicate key 'fortran_order'");
            h->have_order = 1;
            if (scan_word(c, "True"))
                h->fortran = 1;
            else if (scan_word(c, "False"))
                h->fortran = 0;
            else
                return header_error(err, what, c, "expected True or False for 'fortran_order'");
        } else if (klen == 5 && memcmp(key, "shape", 5) == 0) {
            if (h->have_shape)
                return header_error(err, what, c, "duplicate key 'shape'");
            h->have_shape = 1;
            st = parse_shape(c, h, what, err);
        } else {
            char k[40];
            printable(k, sizeof k, key, klen);
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: malformed .npy header: unknown key '%s' (expected 'descr', "
                           "'fortran_order', 'shape')",
                           what, k);
        }
        if (st != MC_OK)
            return st;
        if (accept_char(c, '}'))
            break;
        if (!accept_char(c, ','))
            return header_error(err, what, c, "expected ',' or '}' after a value");
    }
    skip_ws(c);
    while (c->p < c->end && *c->p == '\0') /* some writers pad with NULs */
        c->p++;
    if (c->p != c->end)
        return header_error(err, what, c, "unexpected text after '}'");
    if (!h->have_descr || !h->have_order || !h->have_shape)
        return mc_fail(err, MC_ERR_INPUT, "%s: malformed .npy header: missing key '%s'", what,
                       !h->have_descr ? "descr" : !h->have_order ? "fortran_order" : "shape");
    return MC_OK;
}

static void shape_text(char *out, size_t outlen, const npy_header *h)
{
    size_t k = 0;
    k += (size_t)snprintf(out, outlen, "(");
    for (int d = 0; d < h->rank && k < outlen; d++) {
        if (h->dim[d] > INT_MAX)
            k += (size_t)snprintf(out + k, outlen - k, "%s>%d", d ? ", " : "", INT_MAX);
        else
            k += (size_t)snprintf(out + k, outlen - k, "%s%lld", d ? ", " : "", h->dim[d]);
    }
    if (k < outlen)
        snprintf(out + k, outlen - k, "%s)", h->rank == 1 ? "," : "");
}

int mc_npy_parse(const unsigned char *buf, size_t len, const char *what, double **data, int *rows,
                 int *cols, mc_error *err)
{
    *data = NULL;
    if (len < NPY_MAGIC_LEN + 2 || memcmp(buf, NPY_MAGIC, NPY_MAGIC_LEN) != 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: not a NumPy .npy file (no \\x93NUMPY magic)", what);
    int major = buf[6], minor = buf[7];
    size_t pre, hlen;
    if (major == 1 && len >= 10) {
        pre = 10;
        hlen = (size_t)buf[8] | (size_t)buf[9] << 8;
    } else if ((major == 2 || major == 3) && len >= 12) {
        pre = 12;
        hlen = (size_t)buf[8] | (size_t)buf[9] << 8 | (size_t)buf[10] << 16 | (size_t)buf[11] << 24;
    } else if (major >= 1 && major <= 3) {
        return mc_fail(err, MC_ERR_INPUT, "%s: truncated .npy file (%zu bytes, no header length)",
                       what, len);
    } else {
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: .npy format version %d.%d not supported; need 1.0, 2.0 or 3.0", what,
                       major, minor);
    }
    if (hlen > len - pre)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated .npy file: header length %zu, only %zu bytes follow", what,
                       hlen, len - pre);

    cursor c = {buf + pre, buf + pre + hlen, buf + pre};
    npy_header h;
    int st = parse_dict(&c, &h, what, err);
    if (st != MC_OK)
        return st;

    if (h.descr_is_list)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: structured dtype not supported; need float64 ('<f8')", what);
    if (h.descr_len != 3 || memcmp(h.descr, "<f8", 3) != 0) {
        char d[40];
        printable(d, sizeof d, h.descr, h.descr_len);
        return mc_fail(err, MC_ERR_INPUT, "%s: dtype '%s' not supported; need float64 ('<f8')",
                       what, d);
    }
    if (h.fortran)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: fortran_order True not supported; need a C-order array "
                       "(fortran_order False)",
                       what);
    char shp[96];
    shape_text(shp, sizeof shp, &h);
    if (h.rank != 1 && h.rank != 2)
        return mc_fail(err, MC_ERR_INPUT, "%s: %d-dimensional array (shape %s) not supported; %s",
                       what, h.rank, shp, accepted);
    if (h.dim_big)
        return mc_fail(err, MC_ERR_INPUT, "%s: shape %s too large: each dimension must be <= %d",
                       what, shp, INT_MAX);
    int r = h.rank == 1 ? 1 : (int)h.dim[0];
    int cl = (int)h.dim[h.rank - 1];
    if (r == 0 || cl == 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: empty array (shape %s); %s", what, shp, accepted);

    size_t avail = len - pre - hlen, n, bytes;
    int fits = mc_size_mul((size_t)r, (size_t)cl, &n) && mc_size_mul(n, sizeof(double), &bytes);
    if (!fits || bytes > avail) {
        char need[48];
        if (fits)
            snprintf(need, sizeof need, "%zu bytes", bytes);
        else
            snprintf(need, sizeof need, "more bytes than memory can address");
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated: header says %d x %d values (%s), file has %zu bytes of data",
                       what, r, cl, need, avail);
    }
    if (bytes < avail)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: header says %d x %d values (%zu bytes), file has %zu bytes of data "
                       "(trailing bytes after the array)",
                       what, r, cl, bytes, avail);

    const unsigned char *src = buf + pre + hlen;
    for (size_t k = 0; k < n; k++) {
        double v = le64_get(src + 8 * k);
        if (!isfinite(v)) {
            const char *kind = isnan(v) ? "NaN" : "infinite";
            if (h.rank == 1)
                return mc_fail(err, MC_ERR_INPUT, "%s: value [%zu] is %s; values must be finite",
                               what, k, kind);
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: value [%zu, %zu] (flat index %zu) is %s; values must be finite",
                           what, k / (size_t)cl, k % (size_t)cl, k, kind);
        }
    }
    double *d = mc_malloc(bytes);
    if (!d)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %d x %d values", what, r, cl);
    for (size_t k = 0; k < n; k++)
        d[k] = le64_get(src + 8 * k);
    *data = d;
    *rows = r;
    *cols = cl;
    return MC_OK;
}

/* ---- files ------------------------------------------------------------------------------- */

int mc_file_read(const char *path, unsigned char **buf, size_t *len, mc_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return mc_fail(err, MC_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat sb;
    size_t cap = 4096;
    if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > 0 &&
        (unsigned long long)sb.st_size < (unsigned long long)SIZE_MAX - 1)
        cap = (size_t)sb.st_size + 1;
    unsigned char *b = mc_malloc(cap);
    if (!b) {
        fclose(f);
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory to read %zu bytes", path, cap);
    }
    size_t n = 0;
    for (;;) {
        n += fread(b + n, 1, cap - n, f);
        if (ferror(f)) {
            int e = errno;
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_IO, "%s: cannot read: %s", path, strerror(e));
        }
        if (n < cap)
            break; /* end of file; one spare byte left for the terminator */
        if (cap > SIZE_MAX / 2) {
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_NOMEM, "%s: file too large", path);
        }
        unsigned char *nb = mc_malloc(cap * 2);
        if (!nb) {
            mc_free(b);
            fclose(f);
            return mc_fail(err, MC_ERR_NOMEM, "%s: no memory to read %zu bytes", path, cap * 2);
        }
        memcpy(nb, b, n);
        mc_free(b);
        b = nb;
        cap *= 2;
    }
    fclose(f);
    b[n] = '\0';
    *buf = b;
    *len = n;
    return MC_OK;
}

int mc_npy_read(const char *path, double **data, int *rows, int *cols, mc_error *err)
{
    unsigned char *buf;
    size_t len;
    *data = NULL;
    int st = mc_file_read(path, &buf, &len, err);
    if (st != MC_OK)
        return st;
    st = mc_npy_parse(buf, len, path, data, rows, cols, err);
    mc_free(buf);
    return st;
}

int mc_npy_write(const char *path, const double *data, int ndim, const size_t *shape, mc_error *err)
{
    if (ndim < 1 || ndim > 3 || !shape)
        return mc_fail(err, MC_ERR_INPUT, "%s: cannot write a %d-dimensional array (1..3)", path,
                       ndim);
    size_t n = 1;
    for (int d = 0; d < ndim; d++)
        if (!mc_size_mul(n, shape[d], &n))
            return mc_fail(err, MC_ERR_INPUT, "%s: array shape overflows", path);
    size_t bytes;
    if (!mc_size_mul(n, sizeof(double), &bytes))
        return mc_fail(err, MC_ERR_INPUT, "%s: array shape overflows", path);
    if (n > 0 && !data)
        return mc_fail(err, MC_ERR_INPUT, "%s: no data to write", path);

    char dict[160];
    int dl;
    if (ndim == 1)
        dl = snprintf(dict, sizeof dict,
                      "{'descr': '<f8', 'fortran_order': False, 'shape': (%zu,), }", shape[0]);
    else if (ndim == 2)
        dl = snprintf(dict, sizeof dict,
                      "{'descr': '<f8', 'fortran_order': False, 'shape': (%zu, %zu), }", shape[0],
                      shape[1]);
    else
        dl = snprintf(dict, sizeof dict,
                      "{'descr': '<f8', 'fortran_order': False, 'shape': (%zu, %zu, %zu), }",
                      shape[0], shape[1], shape[2]);
    /* Preamble (10 bytes in 1.0) + dict + padding + '\n' is a multiple of 64, as NumPy does. */
    size_t total = (10 + (size_t)dl + 1 + NPY_ALIGN - 1) / NPY_ALIGN * NPY_ALIGN;
    size_t hlen = total - 10;
    unsigned char head[256];
    memcpy(head, NPY_MAGIC, NPY_MAGIC_LEN);
    head[6] = 1;
    head[7] = 0;
    head[8] = (unsigned char)(hlen & 0xff);
    head[9] = (unsigned char)(hlen >> 8);
    memcpy(head + 10, dict, (size_t)dl);
    memset(head + 10 + dl, ' ', hlen - (size_t)dl - 1);
    head[total - 1] = '\n';

    char tmp[NPY_PATH_MAX];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return mc_fail(err, MC_ERR_INPUT, "%s: path too long", path);
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return mc_fail(err, MC_ERR_IO, "%s: cannot create: %s", tmp, strerror(errno));
    int ok = fwrite(head, 1, total, f) == total;
    unsigned char chunk[NPY_CHUNK * 8];
    for (size_t k = 0; ok && k < n; k += NPY_CHUNK) {
        size_t m = n - k < NPY_CHUNK ? n - k : NPY_CHUNK;
        for (size_t q = 0; q < m; q++)
            le64_put(chunk + 8 * q, data[k + q]);
        ok = fwrite(chunk, 8, m, f) == m;
    }
    int e = errno;
    if (fclose(f) != 0 && ok) {
        ok = 0;
        e = errno;
    }
    if (!ok) {
        remove(tmp);
        return mc_fail(err, MC_ERR_IO, "%s: cannot write: %s", tmp, strerror(e));
    }
    if (rename(tmp, path) != 0) {
        e = errno;
        remove(tmp);
        return mc_fail(err, MC_ERR_IO, "%s: cannot rename %s into place: %s", path, tmp,
                       strerror(e));
    }
    return MC_OK;
}
