/* heightmap.c - 2-D maps from .npy or whitespace text files (see heightmap.h). */
#include "io/heightmap.h"

#include <errno.h>
#include <limits.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/alloc.h"
#include "io/npy.h"

#define TOKEN_MAX 256 /* longest number token accepted (digits of a long decimal) */

static int is_blank(unsigned char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f';
}

/* One physical line [b, e) with its comment cut off. */
typedef struct {
    const char *text;
    size_t len, pos;
    long lineno;
} line_reader;

static int next_line(line_reader *r, const char **b, const char **e)
{
    if (r->pos >= r->len)
        return 0;
    const char *s = r->text + r->pos;
    const char *nl = memchr(s, '\n', r->len - r->pos);
    const char *end = nl ? nl : r->text + r->len;
    r->pos = (size_t)(end - r->text) + (nl ? 1 : 0);
    r->lineno++;
    const char *hash = memchr(s, '#', (size_t)(end - s));
    *b = s;
    *e = hash ? hash : end;
    return 1;
}

/* Next whitespace-separated token of [*p, e); 0 at the end of the line. */
static int next_token(const char **p, const char *e, const char **tb, size_t *tl)
{
    const char *q = *p;
    while (q < e && is_blank((unsigned char)*q))
        q++;
    if (q >= e)
        return 0;
    const char *t = q;
    while (q < e && !is_blank((unsigned char)*q))
        q++;
    *tb = t;
    *tl = (size_t)(q - t);
    *p = q;
    return 1;
}

static void shown(char *out, size_t outlen, const char *s, size_t n)
{
    size_t k = 0;
    for (; k < n && k + 1 < outlen; k++)
        out[k] = ((unsigned char)s[k] >= 0x20 && (unsigned char)s[k] < 0x7f) ? s[k] : '?';
    out[k] = '\0';
    if (k < n && outlen > 4)
        memcpy(out + outlen - 4, "...", 4);
}

int mc_text_is_decimal(const char *s, size_t n)
{
    size_t k = 0, digits = 0;
    if (k < n && (s[k] == '+' || s[k] == '-'))
        k++;
    while (k < n && s[k] >= '0' && s[k] <= '9')
        k++, digits++;
    if (k < n && s[k] == '.') {
        k++;
        while (k < n && s[k] >= '0' && s[k] <= '9')
            k++, digits++;
    }
    if (digits == 0)
        return 0;
    if (k < n && (s[k] == 'e' || s[k] == 'E')) {
        k++;
        if (k < n && (s[k] == '+' || s[k] == '-'))
            k++;
        size_t e = 0;
        while (k < n && s[k] >= '0' && s[k] <= '9')
            k++, e++;
        if (e == 0)
            return 0;
    }
    return k == n;
}

static int parse_number(const char *tb, size_t tl, const char *what, long line, int finite_only,
                        double *v, mc_error *err)
{
    char tok[TOKEN_MAX + 1], show[40];
    shown(show, sizeof show, tb, tl);
    if (tl > TOKEN_MAX)
        return mc_fail(err, MC_ERR_INPUT, "%s:%ld: '%s' is not a number (token too long)", what,
                       line, show);
    memcpy(tok, tb, tl);
    tok[tl] = '\0';
    const int is_nan = tl == 3 && (tok[0] | 0x20) == 'n' && (tok[1] | 0x20) == 'a' &&
                       (tok[2] | 0x20) == 'n';
    if (is_nan && finite_only)
        return mc_fail(err, MC_ERR_INPUT, "%s:%ld: value '%s' is not finite; values must be finite",
                       what, line, show);
    if (!is_nan && !mc_text_is_decimal(tok, tl))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s:%ld: '%s' is not a number (accepted: decimal numbers as in a case file, "
                       "e.g. 12, -0.5, 1.5e-6; no hexadecimal, no infinity%s; values are separated "
                       "by spaces or tabs; '#' starts a comment)",
                       what, line, show, finite_only ? ", no NaN" : "; nan marks a missing point");
    errno = 0;
    double x = strtod(tok, NULL);
    if (!is_nan && !isfinite(x))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s:%ld: value '%s' is not finite (beyond %g, the double range); values "
                       "must be finite",
                       what, line, show, DBL_MAX);
    *v = x;
    return MC_OK;
}

static int text_matrix(const char *text, size_t len, const char *what, int finite_only,
                       double **data, int *rows, int *cols, mc_error *err)
{
    *data = NULL;
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) { /* UTF-8 byte order mark */
        text += 3;
        len -= 3;
    }
    /* Pass 1: shape and column consistency; pass 2: numbers (avoids growing arrays). */
    line_reader r = {text, len, 0, 0};
    const char *b, *e, *tb;
    size_t tl, nrows = 0, ncols = 0;
    long first_line = 0;
    while (next_line(&r, &b, &e)) {
        size_t n = 0;
        const char *p = b, *word = NULL;
        size_t word_len = 0;
        int lead_word = 0; /* the line starts with a word (a letter, not nan or inf) */
        while (next_token(&p, e, &tb, &tl)) {
            if (n == 0)
                lead_word = ((*tb | 0x20) >= 'a' && (*tb | 0x20) <= 'z') &&
                            strncasecmp(tb, "nan", 3) != 0 && strncasecmp(tb, "inf", 3) != 0;
            n++;
            if (!word && !mc_text_is_decimal(tb, tl) &&
                !(tl == 3 && strncasecmp(tb, "nan", 3) == 0)) {
                word = tb;
                word_len = tl;
            }
        }
        if (n == 0)
            continue;
        if (lead_word && nrows == 0) { /* words before the first row: "h=650 w=650" */
            char show[64];
            size_t ll = (size_t)(e - b);
            while (ll > 0 && is_blank((unsigned char)b[ll - 1]))
                ll--;
            shown(show, sizeof show, b, ll);
            return mc_fail(err, MC_ERR_INPUT,
                           "%s:%ld: '%s' is a header line, not a row of numbers: a text matrix "
                           "holds numbers only (remove the line or start it with '#')",
                           what, r.lineno, show);
        }
        if (word) /* the message of the number parser, with its accepted forms */
            return parse_number(word, word_len, what, r.lineno, finite_only, &(double){0}, err);
        if (nrows == 0) {
            ncols = n;
            first_line = r.lineno;
        } else if (n != ncols) {
            /* a short first row of numbers may be a header too (the sizes, "650 650") */
            const int header_like = nrows == 1 && ncols < n && ncols <= 3;
            return mc_fail(err, MC_ERR_INPUT,
                           "%s:%ld: %zu values, but the first data row (line %ld) has %zu; every "
                           "row needs the same number of columns%s",
                           what, r.lineno, n, first_line, ncols,
                           header_like ? " (if that line is a header, such as the sizes, remove "
                                         "it or start it with '#')"
                                       : "");
        }
        if (ncols > INT_MAX || ++nrows > INT_MAX)
            return mc_fail(err, MC_ERR_INPUT, "%s:%ld: matrix too large (more than %d rows or "
                           "columns)", what, r.lineno, INT_MAX);
    }
    if (nrows == 0)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: no data rows (only blank lines and '#' comments); need a whitespace "
                       "separated matrix, one row per line",
                       what);
    size_t n;
    if (!mc_size_mul(nrows, ncols, &n))
        return mc_fail(err, MC_ERR_INPUT, "%s: matrix too large", what);
    double *d = mc_zeros(n);
    if (!d)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %zu x %zu values", what, nrows, ncols);
    line_reader r2 = {text, len, 0, 0};
    size_t k = 0;
    while (next_line(&r2, &b, &e)) {
        const char *p = b;
        while (next_token(&p, e, &tb, &tl)) {
            int st = parse_number(tb, tl, what, r2.lineno, finite_only, &d[k++], err);
            if (st != MC_OK) {
                mc_free(d);
                return st;
            }
        }
    }
    *data = d;
    *rows = (int)nrows;
    *cols = (int)ncols;
    return MC_OK;
}

int mc_text_matrix_parse(const char *text, size_t len, const char *what, double **data, int *rows,
                         int *cols, mc_error *err)
{
    return text_matrix(text, len, what, 1, data, rows, cols, err);
}

int mc_text_matrix_parse_any(const char *text, size_t len, const char *what, double **data,
                             int *rows, int *cols, mc_error *err)
{
    return text_matrix(text, len, what, 0, data, rows, cols, err);
}

int mc_heightmap_read(const char *path, int ny, int nx, double **data, mc_error *err)
{
    unsigned char *buf;
    size_t len;
    *data = NULL;
    int st = mc_io_read_file(path, &buf, &len, err);
    if (st != MC_OK)
        return st;
    double *d = NULL;
    int rows = 0, cols = 0;
    size_t pl = strlen(path);
    const int npy_name = pl >= 4 && strcasecmp(path + pl - 4, ".npy") == 0;
    if (len >= 6 && memcmp(buf, "\x93NUMPY", 6) == 0)
        st = mc_npy_parse(buf, len, path, &d, &rows, &cols, err);
    else if (npy_name) /* named .npy but without the magic: say so, not a text complaint */
        st = mc_fail(err, MC_ERR_INPUT,
                     len == 0 ? "%s: not a .npy file (empty, 0 bytes)"
                              : "%s: not a .npy file (it does not start with the NumPy magic "
                                "\\x93NUMPY)",
                     path);
    else
        st = mc_text_matrix_parse((const char *)buf, len, path, &d, &rows, &cols, err);
    mc_free(buf);
    if (st != MC_OK)
        return st;
    if ((ny > 0 && rows != ny) || (nx > 0 && cols != nx)) {
        mc_free(d);
        return mc_fail(err, MC_ERR_INPUT, "%s: shape %d x %d, the mesh is %d x %d (ny x nx)", path,
                       rows, cols, ny, nx);
    }
    *data = d;
    return MC_OK;
}
