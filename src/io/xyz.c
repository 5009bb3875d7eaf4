/* xyz.c - "x y z" triplets on a regular grid, rows in any order (see surface_file.h).
 *
 * One point per line: three numbers separated by blanks, ',' or ';'; '#' starts a comment;
 * blank lines are skipped. z may be NaN (a point not measured); x and y must be finite.
 *
 * The grid is detected per axis: the sorted coordinates fall into clusters (values closer than
 * 1e-5 of the axis' extent are one grid line, which absorbs the rounding of a file written with
 * six or more significant digits); the spacing is the extent divided by the number of cells the
 * smallest cluster gap implies; every coordinate must then lie within
 * min(0.25, 1e-3 + 4e-5*(n-1)) spacings of its grid line, or the file is refused as irregular.
 * Grid points absent from the file become missing points, provided at least half of the grid is
 * present; a grid point given twice is an error. Row j of the result is the j-th smallest y.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/heightmap.h"
#include "io/surface_formats.h"

#define CLUSTER_REL 1e-5 /* grid-line width, relative to the axis extent */

typedef struct {
    double *x, *y, *z, *work;
    long *line;
    unsigned char *filled;
} xyz_work;

static void work_free(xyz_work *w)
{
    mc_free(w->x);
    mc_free(w->y);
    mc_free(w->z);
    mc_free(w->work);
    mc_free(w->line);
    mc_free(w->filled);
}

static int is_sep(char c) { return c == ' ' || c == '\t' || c == '\r' || c == ',' || c == ';'; }

/* Split line [b, e) into up to 4 tokens; returns the number found (4 = too many). */
static int tokens(const char *b, const char *e, const char **tb, size_t *tl)
{
    int n = 0;
    while (b < e && n < 4) {
        while (b < e && is_sep(*b))
            b++;
        if (b >= e)
            break;
        const char *t = b;
        while (b < e && !is_sep(*b))
            b++;
        tb[n] = t;
        tl[n++] = (size_t)(b - t);
    }
    return n;
}

static int number(const char *b, size_t n, double *v)
{
    char tok[80];
    if (n == 0 || n >= sizeof tok)
        return 0;
    memcpy(tok, b, n);
    tok[n] = '\0';
    const int is_nan = n == 3 && (tok[0] | 0x20) == 'n' && (tok[1] | 0x20) == 'a' &&
                       (tok[2] | 0x20) == 'n';
    if (!is_nan && !mc_text_is_decimal(tok, n)) /* the case file's forms: no hex, no inf */
        return 0;
    *v = strtod(tok, NULL);
    return is_nan || isfinite(*v);
}

static int cmp_double(const void *a, const void *b)
{
    double u = *(const double *)a, v = *(const double *)b;
    return (u > v) - (u < v);
}

/* Grid of one axis from its n coordinates: *cells grid lines from *origin with spacing *step. */
static int detect_axis(const double *v, size_t n, double *work, char axis, const char *what,
                       long long *cells, double *origin, double *step, mc_error *err)
{
    memcpy(work, v, n * sizeof *work);
    qsort(work, n, sizeof *work, cmp_double);
    double lo = work[0], span = work[n - 1] - lo, eps = CLUSTER_REL * span;
    double dmin = INFINITY, rep = lo;
    size_t clusters = 1;
    for (size_t k = 1; k < n; k++)
        if (work[k] - work[k - 1] > eps) {
            if (work[k] - rep < dmin)
                dmin = work[k] - rep;
            rep = work[k];
            clusters++;
        }
    *origin = lo;
    if (clusters == 1) {
        *cells = 1;
        *step = 0.0;
        return MC_OK;
    }
    double c = span / dmin;
    if (!(c < (double)MC_SURFACE_MAX_POINTS))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: irregular grid: %c values from %g to %g with gaps down to %g", what,
                       axis, lo, work[n - 1], dmin);
    *cells = llround(c) + 1;
    *step = span / (double)(*cells - 1);
    double tol = fmin(0.25, 1e-3 + 4.0 * CLUSTER_REL * (double)(*cells - 1)) * *step;
    for (size_t k = 0; k < n; k++) {
        double i = nearbyint((work[k] - lo) / *step);
        if (fabs(work[k] - (lo + i * *step)) > tol)
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: irregular grid: %c = %.9g is not on the grid %c0 + i*d%c "
                           "(%c0 = %.9g, d%c = %.9g from %zu distinct %c values)",
                           what, axis, work[k], axis, axis, axis, lo, axis, *step, clusters,
                           axis);
    }
    return MC_OK;
}

/* Pass 1 (store == 0): count the points; pass 2: store them. */
static int scan(const char *text, size_t len, const char *what, xyz_work *w, size_t *count,
                int store, mc_error *err)
{
    size_t k = 0, pos = 0;
    long line = 0;
    while (pos < len) {
        const char *b = text + pos;
        const char *nl = memchr(b, '\n', len - pos);
        const char *e = nl ? nl : text + len;
        pos = (size_t)(e - text) + (nl ? 1 : 0);
        line++;
        const char *hash = memchr(b, '#', (size_t)(e - b));
        if (hash)
            e = hash;
        const char *tb[4];
        size_t tl[4];
        int nt = tokens(b, e, tb, tl);
        if (nt == 0)
            continue;
        int numeric = 1;
        for (int q = 0; q < nt && q < 4; q++) {
            double v;
            numeric &= number(tb[q], tl[q], &v);
        }
        if (!numeric && k == 0) { /* words before the first point: a header such as "h=650" */
            char s[64];
            mc_surface_quote(s, sizeof s, (const unsigned char *)b, (size_t)(e - b));
            return mc_fail(err, MC_ERR_INPUT,
                           "%s:%ld: '%s' is a header line, not 'x y z' numbers: an xyz file holds "
                           "numbers only (remove the line or start it with '#')",
                           what, line, s);
        }
        if (nt == 2 && numeric)
            return mc_fail(err, MC_ERR_INPUT,
                           "%s:%ld: 2 values: 'x z' pairs are a profile (a line scan), not a "
                           "surface; need 'x y z' on each line (an areal map)",
                           what, line);
        if (nt != 3)
            return mc_fail(err, MC_ERR_INPUT, "%s:%ld: %s values; need 'x y z' on each line",
                           what, line, nt > 3 ? "more than 3" : nt == 2 ? "2" : "1");
        if (store) {
            double v[3];
            for (int q = 0; q < 3; q++)
                if (!number(tb[q], tl[q], &v[q])) {
                    char s[40];
                    mc_surface_quote(s, sizeof s, (const unsigned char *)tb[q], tl[q]);
                    return mc_fail(err, MC_ERR_INPUT, "%s:%ld: '%s' is not a number", what, line,
                                   s);
                }
            if (!isfinite(v[0]) || !isfinite(v[1]))
                return mc_fail(err, MC_ERR_INPUT, "%s:%ld: x and y must be finite", what, line);
            w->x[k] = v[0];
            w->y[k] = v[1];
            w->z[k] = v[2];
            w->line[k] = line;
        }
        if (++k > (size_t)MC_SURFACE_MAX_POINTS)
            return mc_fail(err, MC_ERR_INPUT, "%s: absurd dimensions: more than %ld points", what,
                           MC_SURFACE_MAX_POINTS);
    }
    *count = k;
    return MC_OK;
}

static int xyz_grid(const char *text, size_t len, const char *what, double units,
                    mc_surface_data *out, xyz_work *w, mc_error *err)
{
    size_t n;
    int st = scan(text, len, what, w, &n, 0, err);
    if (st != MC_OK)
        return st;
    if (n == 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: no 'x y z' lines (only blank lines and comments)",
                       what);
    w->x = mc_malloc(n * sizeof(double));
    w->y = mc_malloc(n * sizeof(double));
    w->z = mc_malloc(n * sizeof(double));
    w->work = mc_malloc(n * sizeof(double));
    w->line = mc_malloc(n * sizeof(long));
    if (!w->x || !w->y || !w->z || !w->work || !w->line)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %zu points", what, n);
    st = scan(text, len, what, w, &n, 1, err);
    if (st != MC_OK)
        return st;

    long long nx, ny;
    double x0, y0, dx, dy;
    st = detect_axis(w->x, n, w->work, 'x', what, &nx, &x0, &dx, err);
    if (st == MC_OK)
        st = detect_axis(w->y, n, w->work, 'y', what, &ny, &y0, &dy, err);
    if (st != MC_OK)
        return st;
    if ((double)nx * (double)ny > 2.0 * (double)n)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: irregular grid: the coordinates span %lld x %lld grid points but the "
                       "file has only %zu (less than half)",
                       what, nx, ny, n);
    st = mc_surface_alloc(out, nx, ny, what, err);
    if (st != MC_OK)
        return st;
    size_t cells = (size_t)nx * (size_t)ny;
    w->filled = mc_calloc(cells, 1);
    if (!w->filled)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %zu grid points", what, cells);
    for (size_t c = 0; c < cells; c++)
        out->z[c] = NAN; /* absent grid points are missing points */
    for (size_t k = 0; k < n; k++) {
        /* every coordinate was checked within a quarter spacing of a grid line in range */
        size_t i = nx > 1 ? (size_t)llround((w->x[k] - x0) / dx) : 0;
        size_t j = ny > 1 ? (size_t)llround((w->y[k] - y0) / dy) : 0;
        if (i >= (size_t)nx || j >= (size_t)ny)
            return mc_fail(err, MC_ERR_INTERNAL, "%s: grid index out of range", what);
        size_t c = j * (size_t)nx + i;
        if (w->filled[c])
            return mc_fail(err, MC_ERR_INPUT,
                           "%s:%ld: grid point x = %.9g, y = %.9g given twice", what, w->line[k],
                           w->x[k], w->y[k]);
        w->filled[c] = 1;
        out->z[c] = isfinite(w->z[k]) ? w->z[k] * units : w->z[k];
    }
    out->dx = dx * units;
    out->dy = dy * units;
    out->x0 = x0 * units;
    out->y0 = y0 * units;
    return MC_OK;
}

int mc_xyz_parse(const unsigned char *buf, size_t len, const char *what, double units,
                 mc_surface_data *out, mc_error *err)
{
    xyz_work w = {NULL, NULL, NULL, NULL, NULL, NULL};
    if (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) { /* UTF-8 byte order mark */
        buf += 3;
        len -= 3;
    }
    int st = xyz_grid((const char *)buf, len, what, units, out, &w, err);
    work_free(&w);
    return st;
}
