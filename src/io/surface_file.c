/* surface_file.c - the one loading interface for measured surfaces (see surface_file.h): format
 * choice, the text matrix and .npy adapters, and the helpers every format parser shares. */
#include "io/surface_file.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/alloc.h"
#include "core/fileguard.h"
#include "io/file.h"
#include "io/heightmap.h"
#include "io/npy.h"
#include "io/surface_formats.h"

static const char formats_list[] = "x3p, sdf, gsf, txt, xyz or npy";

mc_surface_read_options mc_surface_read_defaults(void)
{
    mc_surface_read_options o = {NULL, 0.0, 1};
    return o;
}

void mc_surface_data_free(mc_surface_data *s)
{
    if (!s)
        return;
    mc_free(s->z);
    mc_free(s->valid);
    memset(s, 0, sizeof *s);
}

void mc_surface_quote(char *out, size_t outlen, const unsigned char *s, size_t n)
{
    size_t k = 0;
    for (; k < n && k + 1 < outlen; k++)
        out[k] = (s[k] >= 0x20 && s[k] < 0x7f) ? (char)s[k] : '?';
    out[k] = '\0';
    if (k < n && outlen > 4)
        memcpy(out + outlen - 4, "...", 4);
}

int mc_surface_check_dims(long long nx, long long ny, const char *what, mc_error *err)
{
    if (nx < 1 || ny < 1)
        return mc_fail(err, MC_ERR_INPUT, "%s: grid of %lld x %lld points (nx x ny); need at "
                       "least 1 x 1", what, nx, ny);
    /* nx <= MAX and ny <= MAX first, so the product below cannot overflow */
    if (nx > MC_SURFACE_MAX_POINTS || ny > MC_SURFACE_MAX_POINTS ||
        nx * ny > MC_SURFACE_MAX_POINTS)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: absurd dimensions %lld x %lld points (nx x ny); at most %ld points",
                       what, nx, ny, MC_SURFACE_MAX_POINTS);
    return MC_OK;
}

int mc_surface_alloc(mc_surface_data *out, long long nx, long long ny, const char *what,
                     mc_error *err)
{
    int st = mc_surface_check_dims(nx, ny, what, err);
    if (st != MC_OK)
        return st;
    out->nx = (int)nx;
    out->ny = (int)ny;
    out->z = mc_malloc((size_t)(nx * ny) * sizeof(double));
    if (!out->z)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %lld x %lld heights", what, nx, ny);
    return MC_OK;
}

int mc_surface_finish(mc_surface_data *out, const char *what, mc_error *err)
{
    size_t n = (size_t)out->nx * (size_t)out->ny;
    long missing = 0;
    for (size_t k = 0; k < n; k++) {
        if (out->valid && !out->valid[k] && isfinite(out->z[k]))
            out->z[k] = NAN;
        if (!isfinite(out->z[k]))
            missing++;
    }
    out->missing = missing;
    if (missing == 0) {
        mc_free(out->valid);
        out->valid = NULL;
        return MC_OK;
    }
    if (!out->valid) {
        out->valid = mc_malloc(n);
        if (!out->valid)
            return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for the valid-point mask", what);
    }
    for (size_t k = 0; k < n; k++)
        out->valid[k] = isfinite(out->z[k]) ? 1 : 0;
    return MC_OK;
}

double mc_surface_length_unit(const char *name, size_t n)
{
    static const struct {
        const char *name;
        double metres;
    } units[] = {{"m", 1.0},   {"mm", 1e-3},        {"um", 1e-6},     {"\xC2\xB5m", 1e-6},
                 {"nm", 1e-9}, {"pm", 1e-12},       {"km", 1e3},      {"A", 1e-10},
                 {"\xC3\x85", 1e-10}, {"\xE2\x84\xAB", 1e-10}};
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++)
        if (strlen(units[k].name) == n && memcmp(units[k].name, name, n) == 0)
            return units[k].metres;
    return 0.0;
}

/* Trim blanks (space, tab, CR, LF) from both ends of s[0..*n). */
static const char *trim(const char *s, size_t *n)
{
    while (*n > 0 && strchr(" \t\r\n", s[0]) && s[0])
        s++, (*n)--;
    while (*n > 0 && strchr(" \t\r\n", s[*n - 1]) && s[*n - 1])
        (*n)--;
    return s;
}

int mc_surface_number(const char *s, size_t n, double *v)
{
    char tok[80];
    s = trim(s, &n);
    if (n == 0 || n >= sizeof tok)
        return 0;
    memcpy(tok, s, n);
    tok[n] = '\0';
    char *end;
    double x = strtod(tok, &end);
    if ((size_t)(end - tok) != n || !isfinite(x))
        return 0;
    *v = x;
    return 1;
}

int mc_surface_integer(const char *s, size_t n, long long *v)
{
    char tok[80];
    s = trim(s, &n);
    if (n == 0 || n >= sizeof tok)
        return 0;
    memcpy(tok, s, n);
    tok[n] = '\0';
    size_t k = (tok[0] == '+' || tok[0] == '-') ? 1 : 0;
    if (k == n)
        return 0;
    for (size_t q = k; q < n; q++)
        if (tok[q] < '0' || tok[q] > '9')
            return 0;
    char *end;
    *v = strtoll(tok, &end, 10); /* saturates at +-LLONG_MAX on overflow */
    return 1;
}

const char *mc_surface_format_from_path(const char *path)
{
    static const struct {
        const char *ext, *format;
    } map[] = {{"x3p", "x3p"}, {"sdf", "sdf"}, {"gsf", "gsf"}, {"txt", "txt"}, {"asc", "txt"},
               {"dat", "txt"}, {"xyz", "xyz"}, {"npy", "npy"}};
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    if (!dot)
        return NULL;
    for (size_t k = 0; k < sizeof map / sizeof map[0]; k++)
        if (strcasecmp(dot + 1, map[k].ext) == 0)
            return map[k].format;
    return NULL;
}

/* ---- formats without units of their own --------------------------------------------------- */

static int from_matrix(double *d, int rows, int cols, double units, mc_surface_data *out)
{
    out->nx = cols;
    out->ny = rows;
    out->z = d;
    if (units != 1.0)
        for (size_t k = 0; k < (size_t)rows * (size_t)cols; k++)
            out->z[k] *= units;
    return MC_OK;
}

/* Two columns whose first rises or falls steadily are 'x z' pairs: a profile (line scan), not
 * a 2 x n surface (issue 23: a line scan read as a surface two points wide). */
static int refuse_profile(double *d, int rows, int cols, const char *what, mc_error *err)
{
    if (cols != 2 || rows < 3)
        return MC_OK;
    const double s = d[2] - d[0];
    for (int j = 1; j + 1 < rows; j++) {
        double t = d[2 * (j + 1)] - d[2 * j];
        if (!(s > 0 ? t > 0 : s < 0 && t < 0))
            return MC_OK;
    }
    const double x0 = d[0], x1 = d[2 * (rows - 1)];
    mc_free(d);
    return mc_fail(err, MC_ERR_INPUT,
                   "%s: 2 columns of %d rows whose first column is monotonic (x from %g to %g): "
                   "'x z' pairs of a profile (a line scan), not a surface; microcontact needs an "
                   "areal map (a matrix of heights, or x y z triplets)",
                   what, rows, x0, x1);
}

static int parse_txt(const unsigned char *buf, size_t len, const char *what, double units,
                     mc_surface_data *out, mc_error *err)
{
    double *d = NULL;
    int rows = 0, cols = 0;
    int st = mc_text_matrix_parse_any((const char *)buf, len, what, &d, &rows, &cols, err);
    if (st == MC_OK)
        st = refuse_profile(d, rows, cols, what, err);
    if (st != MC_OK)
        return st;
    if ((long long)rows * cols > MC_SURFACE_MAX_POINTS) {
        mc_free(d);
        return mc_surface_alloc(out, cols, rows, what, err); /* raises the size error */
    }
    return from_matrix(d, rows, cols, units, out);
}

static int parse_npy(const unsigned char *buf, size_t len, const char *what, double units,
                     mc_surface_data *out, mc_error *err)
{
    double *d = NULL;
    int rows = 0, cols = 0;
    int st = mc_npy_parse_any(buf, len, what, &d, &rows, &cols, err);
    if (st == MC_OK)
        st = refuse_profile(d, rows, cols, what, err);
    if (st != MC_OK)
        return st;
    if ((long long)rows * cols > MC_SURFACE_MAX_POINTS) {
        mc_free(d);
        return mc_surface_alloc(out, cols, rows, what, err);
    }
    return from_matrix(d, rows, cols, units, out);
}

/* What in a file of this format states the lateral spacing. */
static const char *spacing_source(const char *format)
{
    if (strcmp(format, "x3p") == 0)
        return "the CX/CY increment";
    if (strcmp(format, "sdf") == 0)
        return "Xscale/Yscale";
    if (strcmp(format, "gsf") == 0)
        return "XReal/YReal divided by XRes/YRes";
    if (strcmp(format, "xyz") == 0)
        return "the step of the x/y coordinates";
    return "its header";
}

/* Every reader's spacing and heights, named by the file (not by [mesh] dx, which the user did not
 * write): a spacing stated by the file is finite, > 0 and <= 1 m (the bounds of [mesh] dx, dy;
 * 0 along both axes means "not stated", along an axis of one point "no step"); a height is at most
 * 1000 times the map's size or 1 km (with no spacing, 1000 times the largest grid, 65536 x 1 m):
 * heights of 1e300 m overflowed the solve. */
static int check_scales(const char *format, const mc_surface_data *d, const char *what,
                        mc_error *err)
{
    const double sp[2] = {d->dx, d->dy};
    if (d->dx != 0.0 || d->dy != 0.0)
        for (int a = 0; a < 2; a++)
            if (!(sp[a] == 0.0 && (a ? d->ny : d->nx) == 1) && /* one point: no step */
                !(isfinite(sp[a]) && sp[a] > 0.0 && sp[a] <= 1.0 && sp[a] >= 1e-150))
                return mc_fail(err, MC_ERR_INPUT,
                               "%s: this %s file states a lateral spacing d%c = %g m (%s): it "
                               "must be finite, > 0 and <= 1 m",
                               what, format, a ? 'y' : 'x', sp[a], spacing_source(format));
    const double size = d->dx > 0.0 || d->dy > 0.0 ? fmax(d->nx * d->dx, d->ny * d->dy) : 65536.0;
    const double hmax = 1e3 * fmax(size, 1.0);
    const size_t n = (size_t)d->nx * (size_t)d->ny;
    for (size_t k = 0; k < n; k++)
        if (isfinite(d->z[k]) && !(fabs(d->z[k]) <= hmax))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: the height %g m at row %zu, column %zu is more than 1000 times "
                           "the map's size (%g m) or 1 km: not a surface height (check the file's height "
                           "unit or Z increment)",
                           what, d->z[k], k / (size_t)d->nx, k % (size_t)d->nx, size);
    return MC_OK;
}

/* ---- dispatch ----------------------------------------------------------------------------- */

int mc_surface_parse_buffer(const char *format, const unsigned char *buf, size_t len,
                            const char *what, const mc_surface_read_options *opt,
                            mc_surface_data *out, mc_error *err)
{
    mc_surface_read_options defaults = mc_surface_read_defaults();
    if (!opt)
        opt = &defaults;
    memset(out, 0, sizeof *out);
    if (!format || !*format)
        return mc_fail(err, MC_ERR_INPUT, "%s: no surface format given; need %s", what,
                       formats_list);
    double units = opt->units == 0.0 ? 1.0 : opt->units;
    if (!isfinite(units) || units <= 0.0)
        return mc_fail(err, MC_ERR_INPUT, "%s: units %g m per file unit; need a positive length",
                       what, opt->units);
    if (len == 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: empty file (0 bytes)", what);

    int st;
    if (strcmp(format, "x3p") == 0)
        st = mc_x3p_parse(buf, len, what, opt, out, err);
    else if (strcmp(format, "sdf") == 0)
        st = mc_sdf_parse(buf, len, what, out, err);
    else if (strcmp(format, "gsf") == 0)
        st = mc_gsf_parse(buf, len, what, out, err);
    else if (strcmp(format, "txt") == 0)
        st = parse_txt(buf, len, what, units, out, err);
    else if (strcmp(format, "xyz") == 0)
        st = mc_xyz_parse(buf, len, what, units, out, err);
    else if (strcmp(format, "npy") == 0)
        st = parse_npy(buf, len, what, units, out, err);
    else {
        char f[40];
        mc_surface_quote(f, sizeof f, (const unsigned char *)format, strlen(format));
        return mc_fail(err, MC_ERR_INPUT, "%s: unknown surface format '%s'; need %s", what, f,
                       formats_list);
    }
    if (st == MC_OK)
        st = mc_surface_finish(out, what, err);
    if (st == MC_OK)
        st = check_scales(format, out, what, err);
    if (st != MC_OK) {
        mc_surface_data_free(out);
        return st;
    }
    snprintf(out->format, sizeof out->format, "%s", format);
    return MC_OK;
}

int mc_surface_file_read(const char *path, const mc_surface_read_options *opt,
                         mc_surface_data *out, mc_error *err)
{
    memset(out, 0, sizeof *out);
    const char *format = opt && opt->format && *opt->format ? opt->format : NULL;
    if (!format) {
        format = mc_surface_format_from_path(path);
        if (!format)
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: cannot tell the surface format from the extension; name it "
                           "(format = %s)",
                           path, formats_list);
    }
    unsigned char *buf;
    size_t len;
    int st = mc_io_read_data(path, MC_FILE_MAX_SURFACE, "a surface file", &buf, &len, err);
    if (st != MC_OK)
        return st;
    st = mc_surface_parse_buffer(format, buf, len, path, opt, out, err);
    mc_free(buf);
    return st;
}
