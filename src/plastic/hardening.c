/* hardening.c - isotropic hardening laws sigma_y(p) (see hardening.h). */
#include "plastic/hardening.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fileguard.h"
#include "io/file.h"

#define SWIFT_MICRO 1e6     /* p in micro-strain in the Swift law (theory.md §7.2) */
#define LINE_MAX_CHARS 1024 /* longest line of a table file */

int mc_hardening_linear_from_tangent(double E, double Et, double *H, mc_error *err)
{
    if (!H)
        return mc_fail(err, MC_ERR_INPUT, "linear hardening: NULL result");
    if (!isfinite(E) || !(E > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "linear hardening: Young's modulus E = %g Pa must be finite and > 0", E);
    if (!isfinite(Et) || !(Et >= 0) || !(Et < E))
        return mc_fail(err, MC_ERR_INPUT,
                       "linear hardening: tangent modulus Et = %g Pa must be finite with "
                       "0 <= Et < E = %g Pa",
                       Et, E);
    *H = E * Et / (E - Et);
    return MC_OK;
}

static int check_yield(const char *law, double Y0, mc_error *err)
{
    if (!isfinite(Y0) || !(Y0 > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s hardening: yield stress Y0 = %g Pa must be finite and > 0", law, Y0);
    return MC_OK;
}

/* Row rules of a table; names the row as "what:line" when lines != NULL, else "row k". */
static int check_table(const double *e, const double *s, size_t n, const long *lines,
                       const char *what, mc_error *err)
{
    char where[256];
    if (n < 1 || !e || !s)
        return mc_fail(err, MC_ERR_INPUT, "%s: needs at least one row (eps_p, sigma_y)",
                       what ? what : "table hardening");
    for (size_t i = 0; i < n; i++) {
        if (lines)
            snprintf(where, sizeof where, "%s:%ld", what, lines[i]);
        else
            snprintf(where, sizeof where, "table hardening: row %zu", i + 1);
        if (!isfinite(e[i]) || !isfinite(s[i]))
            return mc_fail(err, MC_ERR_INPUT, "%s: eps_p = %g, sigma_y = %g Pa must be finite",
                           where, e[i], s[i]);
        if (!(s[i] > 0))
            return mc_fail(err, MC_ERR_INPUT, "%s: yield stress sigma_y = %g Pa must be > 0",
                           where, s[i]);
        if (i == 0 && lines && e[0] != 0) /* a file: the documented "eps_p from 0" */
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: the first plastic strain eps_p = %g must be 0 (the initial yield "
                           "stress; the table starts at yield)",
                           where, e[0]);
        if (i == 0 && !(e[0] >= 0))
            return mc_fail(err, MC_ERR_INPUT, "%s: plastic strain eps_p = %g must be >= 0",
                           where, e[0]);
        if (!(s[i] <= MC_HARDENING_STRESS_MAX))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: yield stress sigma_y = %g Pa must be <= %g Pa (the bound of "
                           "[plasticity] yield_stress)",
                           where, s[i], MC_HARDENING_STRESS_MAX);
        if (i > 0 && !(e[i] > e[i - 1]))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: plastic strain eps_p = %g is not larger than the previous row's "
                           "%g; eps_p must increase strictly",
                           where, e[i], e[i - 1]);
        if (i > 0 && !(s[i] >= s[i - 1]))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: yield stress sigma_y = %g Pa is below the previous row's %g Pa; "
                           "sigma_y must not decrease (no softening)",
                           where, s[i], s[i - 1]);
    }
    return MC_OK;
}

int mc_hardening_validate(const mc_hardening *h, mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hardening: NULL law");
    switch (h->kind) {
    case MC_HARDENING_PERFECT:
        return check_yield("perfect", h->yield_stress, err);
    case MC_HARDENING_LINEAR:
        if (check_yield("linear", h->yield_stress, err))
            return MC_ERR_INPUT;
        if (!isfinite(h->plastic_modulus) || !(h->plastic_modulus >= 0))
            return mc_fail(err, MC_ERR_INPUT,
                           "linear hardening: plastic modulus H = %g Pa must be finite and >= 0",
                           h->plastic_modulus);
        return MC_OK;
    case MC_HARDENING_SWIFT:
        if (!isfinite(h->swift_B) || !(h->swift_B > 0))
            return mc_fail(err, MC_ERR_INPUT,
                           "swift hardening: B = %g Pa must be finite and > 0", h->swift_B);
        if (!isfinite(h->swift_C) || !(h->swift_C > 0))
            return mc_fail(err, MC_ERR_INPUT,
                           "swift hardening: C = %g (micro-strain) must be finite and > 0",
                           h->swift_C);
        if (!isfinite(h->swift_n) || !(h->swift_n >= 0) || !(h->swift_n < 1))
            return mc_fail(err, MC_ERR_INPUT,
                           "swift hardening: exponent n = %g must be finite with 0 <= n < 1",
                           h->swift_n);
        return MC_OK;
    case MC_HARDENING_TABLE:
        return check_table(h->eps_p, h->sigma_y, h->n_rows, NULL, NULL, err);
    case MC_HARDENING_NKINDS: break;
    }
    return mc_fail(err, MC_ERR_INPUT, "hardening: unknown law kind %d", (int)h->kind);
}

/* Validate a candidate law and install it in *h only if it is valid. */
static int install(const mc_hardening *t, mc_hardening *h, mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hardening: NULL result");
    if (mc_hardening_validate(t, err))
        return MC_ERR_INPUT;
    *h = *t;
    return MC_OK;
}

int mc_hardening_perfect(double Y0, mc_hardening *h, mc_error *err)
{
    return install(&(mc_hardening){.kind = MC_HARDENING_PERFECT, .yield_stress = Y0}, h, err);
}

int mc_hardening_linear(double Y0, double H, mc_hardening *h, mc_error *err)
{
    mc_hardening t = {.kind = MC_HARDENING_LINEAR, .yield_stress = Y0, .plastic_modulus = H};
    return install(&t, h, err);
}

int mc_hardening_swift(double B, double C, double n, mc_hardening *h, mc_error *err)
{
    mc_hardening t = {.kind = MC_HARDENING_SWIFT, .swift_B = B, .swift_C = C, .swift_n = n};
    t.swift_y0 = B * pow(C + SWIFT_MICRO * 0.0, n); /* the bits of sigma_y(0) */
    return install(&t, h, err);
}

/* Copy validated rows into a new TABLE law. */
static int table_copy(const double *e, const double *s, size_t n, mc_hardening *h, mc_error *err)
{
    size_t bytes;
    if (!mc_size_mul(n, sizeof(double), &bytes))
        return mc_fail(err, MC_ERR_NOMEM, "table hardening: %zu rows are too many", n);
    double *ce = mc_malloc(bytes);
    double *cs = mc_malloc(bytes);
    if (!ce || !cs) {
        mc_free(cs);
        mc_free(ce);
        return mc_fail(err, MC_ERR_NOMEM, "table hardening: no memory for %zu rows", n);
    }
    memcpy(ce, e, bytes);
    memcpy(cs, s, bytes);
    *h = (mc_hardening){.kind = MC_HARDENING_TABLE, .eps_p = ce, .sigma_y = cs, .n_rows = n};
    return MC_OK;
}

int mc_hardening_table(const double *eps_p, const double *sigma_y, size_t n_rows,
                       mc_hardening *h, mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hardening: NULL result");
    if (check_table(eps_p, sigma_y, n_rows, NULL, NULL, err))
        return MC_ERR_INPUT;
    return table_copy(eps_p, sigma_y, n_rows, h, err);
}

/* One field [b, e) as a finite number: 0 on success. Blanks around it are skipped. */
static int parse_field(const char *b, const char *e, double *v)
{
    while (b < e && (*b == ' ' || *b == '\t'))
        b++;
    while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r'))
        e--;
    if (b == e || e - b > 100)
        return 1;
    char tok[128];
    memcpy(tok, b, (size_t)(e - b));
    tok[e - b] = '\0';
    if (strpbrk(tok, "xXpP")) /* decimal only, as everywhere else: no hexadecimal (0x10) */
        return 1;
    char *end;
    *v = strtod(tok, &end);
    return (end != tok + (e - b) || !isfinite(*v)) ? 1 : 0;
}

/* Parse one comment-stripped line [b, e): 0 a data row (*x, *y set), 1 blank, 2 the first field
 * is not a number (a header candidate), 3 any other malformed row. */
static int parse_row(const char *b, const char *e, double *x, double *y)
{
    const char *p = b;
    while (p < e && (*p == ' ' || *p == '\t' || *p == '\r'))
        p++;
    if (p == e)
        return 1;
    const char *c1 = memchr(b, ',', (size_t)(e - b));
    if (parse_field(b, c1 ? c1 : e, x))
        return 2;
    if (!c1 || memchr(c1 + 1, ',', (size_t)(e - c1 - 1)) || parse_field(c1 + 1, e, y))
        return 3;
    return 0;
}

/* Read the next line of f into buf (comment and line end cut off). 1 on a line, 0 at the end,
 * -1 for a line too long. */
static int next_line(FILE *f, char *buf, size_t size, long *line)
{
    if (!fgets(buf, (int)size, f))
        return 0;
    (*line)++;
    size_t len = strlen(buf);
    if (len == size - 1 && buf[len - 1] != '\n' && !feof(f))
        return -1;
    buf[strcspn(buf, "#\n")] = '\0';
    return 1;
}

/* One pass over the file: count the data rows (e == NULL), or store up to cap of them. */
static int scan_rows(FILE *f, const char *path, double unit, double *e, double *s, long *lines,
                     size_t cap, size_t *n, mc_error *err)
{
    char buf[LINE_MAX_CHARS + 2];
    long line = 0;
    int k, header_seen = 0;
    size_t m = 0;
    while ((k = next_line(f, buf, sizeof buf, &line)) != 0) {
        double x = 0, y = 0;
        if (k < 0)
            return mc_fail(err, MC_ERR_INPUT, "%s:%ld: line longer than %d characters", path,
                           line, LINE_MAX_CHARS);
        k = parse_row(buf, buf + strlen(buf), &x, &y);
        if (k == 1)
            continue;
        if (k == 2 && m == 0 && !header_seen) {
            header_seen = 1; /* a header line such as "eps_p, sigma_y_MPa" */
            continue;
        }
        if (k != 0)
            return mc_fail(err, MC_ERR_INPUT,
                           "%s:%ld: expected a row 'eps_p, sigma_y' of two finite numbers "
                           "separated by a comma",
                           path, line);
        if (e && m == cap)
            return mc_fail(err, MC_ERR_IO, "%s: file changed while being read", path);
        if (e) {
            e[m] = x;
            s[m] = y * unit;
            lines[m] = line;
        }
        m++;
    }
    if (ferror(f))
        return mc_fail(err, MC_ERR_IO, "%s: read error", path);
    *n = m;
    return MC_OK;
}

int mc_hardening_table_read(const char *path, double stress_unit, mc_hardening *h, mc_error *err)
{
    if (!path || !h)
        return mc_fail(err, MC_ERR_INPUT, "table hardening: NULL path or result");
    if (!isfinite(stress_unit) || !(stress_unit > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: stress unit = %g Pa must be finite and > 0 (1 for Pa, 1e6 for MPa)",
                       path, stress_unit);
    /* through the one file reader (io/file.h): the guard, and under mpirun rank 0's read shared
     * with every rank; the rows are then scanned from memory */
    unsigned char *text = NULL;
    size_t len = 0;
    int rd = mc_io_read_data(path, MC_FILE_MAX_TABLE, "a hardening table", &text, &len, err);
    if (rd != MC_OK)
        return rd;
    if (len == 0) { /* fmemopen may refuse an empty buffer */
        mc_free(text);
        return mc_fail(err, MC_ERR_INPUT, "%s: no data rows; need 'eps_p, sigma_y' rows", path);
    }
    FILE *f = fmemopen(text, len, "r");
    if (!f) {
        mc_free(text);
        return mc_fail(err, MC_ERR_NOMEM, "%s: cannot scan the hardening table: %s", path,
                       strerror(errno));
    }
    size_t n = 0;
    double *e = NULL, *s = NULL;
    long *lines = NULL;
    int rc = scan_rows(f, path, stress_unit, NULL, NULL, NULL, 0, &n, err);
    if (rc == MC_OK && n == 0)
        rc = mc_fail(err, MC_ERR_INPUT, "%s: no data rows; need 'eps_p, sigma_y' rows", path);
    if (rc == MC_OK) {
        e = mc_malloc(n * sizeof *e); /* n is bounded by the file's line count */
        s = mc_malloc(n * sizeof *s);
        lines = mc_malloc(n * sizeof *lines);
        if (!e || !s || !lines)
            rc = mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %zu rows", path, n);
    }
    if (rc == MC_OK) {
        rewind(f);
        rc = scan_rows(f, path, stress_unit, e, s, lines, n, &n, err);
    }
    fclose(f);
    mc_free(text);
    if (rc == MC_OK && check_table(e, s, n, lines, path, err))
        rc = MC_ERR_INPUT;
    mc_free(lines);
    if (rc != MC_OK) {
        mc_free(s);
        mc_free(e);
        return rc;
    }
    *h = (mc_hardening){.kind = MC_HARDENING_TABLE, .eps_p = e, .sigma_y = s, .n_rows = n};
    return MC_OK;
}

/* Index i of the table segment [eps_p[i], eps_p[i+1]) holding p, with eps_p[0] <= p <
 * eps_p[n-1] (binary search). */
static size_t table_segment(const mc_hardening *h, double p)
{
    size_t lo = 0, hi = h->n_rows - 1;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (h->eps_p[mid] <= p)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

double mc_hardening_sigma_y(const mc_hardening *h, double p)
{
    if (!(p >= 0))
        return NAN;
    switch (h->kind) {
    case MC_HARDENING_PERFECT:
        return h->yield_stress;
    case MC_HARDENING_LINEAR:
        return h->yield_stress + h->plastic_modulus * p;
    case MC_HARDENING_SWIFT:
        if (p == 0.0)
            return h->swift_y0;
        return h->swift_B * pow(h->swift_C + SWIFT_MICRO * p, h->swift_n);
    case MC_HARDENING_TABLE: {
        size_t n = h->n_rows;
        if (p <= h->eps_p[0])
            return h->sigma_y[0];
        if (p >= h->eps_p[n - 1])
            return h->sigma_y[n - 1];
        size_t i = table_segment(h, p);
        double t = (p - h->eps_p[i]) / (h->eps_p[i + 1] - h->eps_p[i]);
        return h->sigma_y[i] + t * (h->sigma_y[i + 1] - h->sigma_y[i]);
    }
    case MC_HARDENING_NKINDS: break;
    }
    return NAN;
}

double mc_hardening_slope(const mc_hardening *h, double p)
{
    if (!(p >= 0))
        return NAN;
    switch (h->kind) {
    case MC_HARDENING_PERFECT:
        return 0.0;
    case MC_HARDENING_LINEAR:
        return h->plastic_modulus;
    case MC_HARDENING_SWIFT:
        return SWIFT_MICRO * h->swift_B * h->swift_n *
               pow(h->swift_C + SWIFT_MICRO * p, h->swift_n - 1.0);
    case MC_HARDENING_TABLE: {
        size_t n = h->n_rows;
        if (p < h->eps_p[0] || p >= h->eps_p[n - 1])
            return 0.0;
        size_t i = table_segment(h, p);
        return (h->sigma_y[i + 1] - h->sigma_y[i]) / (h->eps_p[i + 1] - h->eps_p[i]);
    }
    case MC_HARDENING_NKINDS: break;
    }
    return NAN;
}

double mc_hardening_initial(const mc_hardening *h) { return mc_hardening_sigma_y(h, 0.0); }

void mc_hardening_free(mc_hardening *h)
{
    if (!h)
        return;
    if (h->kind == MC_HARDENING_TABLE) {
        mc_free(h->eps_p);
        mc_free(h->sigma_y);
    }
    memset(h, 0, sizeof *h);
}

/* ---- the law table ------------------------------------------------------------------------ */

static int build_perfect(const mc_hardening_params *q, mc_hardening *h, mc_error *err)
{
    return mc_hardening_perfect(q->yield_stress, h, err);
}

static int build_linear(const mc_hardening_params *q, mc_hardening *h, mc_error *err)
{
    double H = 0;
    int rc = mc_hardening_linear_from_tangent(q->E, q->tangent_modulus, &H, err);
    return rc ? rc : mc_hardening_linear(q->yield_stress, H, h, err);
}

static int build_swift(const mc_hardening_params *q, mc_hardening *h, mc_error *err)
{
    return mc_hardening_swift(q->swift_B, q->swift_C, q->swift_n, h, err);
}

static int build_table(const mc_hardening_params *q, mc_hardening *h, mc_error *err)
{
    return mc_hardening_table_read(q->table, q->table_unit, h, err);
}

/* The one place that names, documents and constructs every law (hardening.h). To add a law: a
 * value in mc_hardening_kind (before MC_HARDENING_NKINDS), a row here, its cases in
 * mc_hardening_validate, mc_hardening_sigma_y and mc_hardening_slope; a law with new parameters
 * also needs them in mc_hardening_params, the scene and the key table. No '|' in help. */
static const struct {
    const char *name, *help, *reference;
    int (*build)(const mc_hardening_params *, mc_hardening *, mc_error *);
} laws[] = {
    [MC_HARDENING_PERFECT] = {"perfect", "sigma_y = Y0 (elastic-perfectly plastic)",
                              "theory.md §7.2", build_perfect},
    [MC_HARDENING_LINEAR] = {"linear", "sigma_y = Y0 + H p, H = E Et / (E - Et)",
                             "theory.md §7.2", build_linear},
    [MC_HARDENING_SWIFT] = {"swift", "sigma_y = B (C + 1e6 p)^n",
                            "Nelias, Boucher & Brunet 2006; theory.md §7.2", build_swift},
    [MC_HARDENING_TABLE] = {"table", "sigma_y(p) piecewise linear through the rows of a file",
                            "theory.md §7.2", build_table},
};
_Static_assert(sizeof laws / sizeof laws[0] == MC_HARDENING_NKINDS,
               "one row per value of mc_hardening_kind");

static int valid_kind(mc_hardening_kind k) { return (int)k >= 0 && k < MC_HARDENING_NKINDS; }

int mc_hardening_count(void) { return MC_HARDENING_NKINDS; }
const char *mc_hardening_name(mc_hardening_kind k) { return valid_kind(k) ? laws[k].name : NULL; }
const char *mc_hardening_help(mc_hardening_kind k) { return valid_kind(k) ? laws[k].help : NULL; }
const char *mc_hardening_reference(mc_hardening_kind k)
{
    return valid_kind(k) ? laws[k].reference : NULL;
}

int mc_hardening_from_name(const char *name, mc_hardening_kind *out, mc_error *err)
{
    char list[256];
    size_t o = 0;
    for (int k = 0; k < MC_HARDENING_NKINDS; k++) {
        if (name && strcmp(name, laws[k].name) == 0) {
            *out = (mc_hardening_kind)k;
            return MC_OK;
        }
        int n = snprintf(list + o, sizeof list - o, "%s%s", k ? " | " : "", laws[k].name);
        o = n > 0 && o + (size_t)n < sizeof list ? o + (size_t)n : o;
    }
    return mc_fail(err, MC_ERR_INPUT, "hardening law '%s' is unknown; accepted: %s",
                   name ? name : "(none)", list);
}

int mc_hardening_build(mc_hardening_kind k, const mc_hardening_params *par, mc_hardening *h,
                       mc_error *err)
{
    if (!valid_kind(k) || !par)
        return mc_fail(err, MC_ERR_INPUT, "hardening: unknown law kind %d", (int)k);
    return laws[k].build(par, h, err);
}
