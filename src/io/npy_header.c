/* npy_header.c - .npy preamble and header dict scanner (see npy_header.h). */
#include "io/npy_header.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>

#define NPY_MAGIC "\x93NUMPY"
#define NPY_MAGIC_LEN 6

/* A printable, bounded copy of untrusted bytes for an error message. */
void mc_npy_printable(char *out, size_t outlen, const unsigned char *s, size_t n)
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
} seen_keys;

static int header_error(mc_error *err, const char *what, const cursor *c, const char *expected)
{
    return mc_fail(err, MC_ERR_INPUT,
                   "%s: malformed .npy header: %s at byte %ld of the header dict", what, expected,
                   cur_pos(c));
}

static int parse_shape(cursor *c, mc_npy_header *h, const char *what, mc_error *err)
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
        if (h->rank >= MC_NPY_MAX_RANK)
            return mc_fail(err, MC_ERR_INPUT, "%s: 'shape' has more than %d dimensions; need a 1-D or 2-D array",
                           what, MC_NPY_MAX_RANK);
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

static int parse_dict(cursor *c, mc_npy_header *h, const char *what, mc_error *err)
{
    seen_keys seen = {0, 0, 0};
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
            if (seen.have_descr)
                return header_error(err, what, c, "duplicate key 'descr'");
            seen.have_descr = 1;
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
            if (seen.have_order)
                return header_error(err, what, c, "duplicate key 'fortran_order'");
            seen.have_order = 1;
            if (scan_word(c, "True"))
                h->fortran = 1;
            else if (scan_word(c, "False"))
                h->fortran = 0;
            else
                return header_error(err, what, c, "expected True or False for 'fortran_order'");
        } else if (klen == 5 && memcmp(key, "shape", 5) == 0) {
            if (seen.have_shape)
                return header_error(err, what, c, "duplicate key 'shape'");
            seen.have_shape = 1;
            st = parse_shape(c, h, what, err);
        } else {
            char k[40];
            mc_npy_printable(k, sizeof k, key, klen);
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
    if (!seen.have_descr || !seen.have_order || !seen.have_shape)
        return mc_fail(err, MC_ERR_INPUT, "%s: malformed .npy header: missing key '%s'", what,
                       !seen.have_descr ? "descr" : !seen.have_order ? "fortran_order" : "shape");
    return MC_OK;
}

void mc_npy_shape_text(char *out, size_t outlen, const mc_npy_header *h)
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

int mc_npy_header_parse(const unsigned char *buf, size_t len, const char *what, mc_npy_header *h,
                        mc_error *err)
{
    memset(h, 0, sizeof *h);
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
    int st = parse_dict(&c, h, what, err);
    if (st != MC_OK)
        return st;
    h->data = buf + pre + hlen;
    h->data_len = len - pre - hlen;
    return MC_OK;
}
