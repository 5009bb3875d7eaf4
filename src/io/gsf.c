/* gsf.c - Gwyddion Simple Field (.gsf) reader (see surface_file.h).
 *
 * Layout (Gwyddion user guide, "Simple Field Files"): the line "Gwyddion Simple Field 1.0\n";
 * header lines "name = value" (whitespace around the name, the '=' and the value ignored, names
 * case-sensitive); one to four NUL bytes so that the data start at a multiple of 4 bytes from the
 * start of the file; then XRes*YRes little-endian IEEE float32 values, x fastest. Keys used:
 * XRes, YRes (required), XReal, YReal (physical size; spacing = XReal/XRes), XOffset, YOffset,
 * XYUnits, ZUnits (length units; metres when absent). Other keys (Title, ...) are ignored.
 * NaN values mark points that were not measured.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "io/surface_formats.h"

#define GSF_MAGIC "Gwyddion Simple Field 1.0\n"
#define GSF_MAGIC_LEN (sizeof GSF_MAGIC - 1)

typedef struct {
    long long xres, yres;
    double xreal, yreal, xoff, yoff;
    int have_xres, have_yres, have_xreal, have_yreal;
    double xy_unit, z_unit;
} gsf_header;

static int bad_line(const char *what, long line, const char *b, size_t n, const char *why,
                    mc_error *err)
{
    char q[48];
    mc_surface_quote(q, sizeof q, (const unsigned char *)b, n);
    return mc_fail(err, MC_ERR_INPUT, "%s: GSF header line %ld '%s': %s", what, line, q, why);
}

static int key_is(const char *k, size_t kn, const char *name)
{
    return strlen(name) == kn && memcmp(k, name, kn) == 0;
}

/* One "name = value" line (already without its newline). */
static int header_line(gsf_header *h, const char *b, size_t n, long line, const char *what,
                       mc_error *err)
{
    const char *eq = memchr(b, '=', n);
    if (!eq)
        return bad_line(what, line, b, n, "not 'name = value'", err);
    const char *k = b, *v = eq + 1;
    size_t kn = (size_t)(eq - b), vn = n - kn - 1;
    while (kn > 0 && (*k == ' ' || *k == '\t'))
        k++, kn--;
    while (kn > 0 && (k[kn - 1] == ' ' || k[kn - 1] == '\t'))
        kn--;
    while (vn > 0 && (*v == ' ' || *v == '\t'))
        v++, vn--;
    while (vn > 0 && (v[vn - 1] == ' ' || v[vn - 1] == '\t' || v[vn - 1] == '\r'))
        vn--;
    if (key_is(k, kn, "XRes") || key_is(k, kn, "YRes")) {
        int x = k[0] == 'X';
        if (x ? h->have_xres : h->have_yres)
            return bad_line(what, line, b, n, "given twice", err);
        long long r;
        if (!mc_surface_integer(v, vn, &r))
            return bad_line(what, line, b, n, "not an integer", err);
        *(x ? &h->xres : &h->yres) = r;
        *(x ? &h->have_xres : &h->have_yres) = 1;
    } else if (key_is(k, kn, "XReal") || key_is(k, kn, "YReal")) {
        int x = k[0] == 'X';
        double r;
        if (!mc_surface_number(v, vn, &r) || !(r > 0.0))
            return bad_line(what, line, b, n, "need a positive number", err);
        *(x ? &h->xreal : &h->yreal) = r;
        *(x ? &h->have_xreal : &h->have_yreal) = 1;
    } else if (key_is(k, kn, "XOffset") || key_is(k, kn, "YOffset")) {
        double r;
        if (!mc_surface_number(v, vn, &r))
            return bad_line(what, line, b, n, "not a number", err);
        *(k[0] == 'X' ? &h->xoff : &h->yoff) = r;
    } else if (key_is(k, kn, "XYUnits") || key_is(k, kn, "ZUnits")) {
        double u = mc_surface_length_unit(v, vn);
        if (u == 0.0)
            return bad_line(what, line, b, n, "not a length unit (m, mm, um, nm, pm)", err);
        *(k[0] == 'X' ? &h->xy_unit : &h->z_unit) = u;
    }
    return MC_OK;
}

static double f32_le(const unsigned char *b)
{
    uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                 (uint32_t)b[3] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return (double)f;
}

int mc_gsf_parse(const unsigned char *buf, size_t len, const char *what, mc_surface_data *out,
                 mc_error *err)
{
    if (len < GSF_MAGIC_LEN || memcmp(buf, GSF_MAGIC, GSF_MAGIC_LEN) != 0)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: not a Gwyddion Simple Field file (no 'Gwyddion Simple Field 1.0' "
                       "first line)",
                       what);
    const unsigned char *nul = memchr(buf, '\0', len);
    if (!nul)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated GSF file: no NUL byte ends the text header", what);
    size_t hend = (size_t)(nul - buf);
    gsf_header h = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1.0, 1.0};
    long line = 1;
    for (size_t p = GSF_MAGIC_LEN; p < hend;) {
        const unsigned char *nl = memchr(buf + p, '\n', hend - p);
        size_t e = nl ? (size_t)(nl - buf) : hend;
        line++;
        size_t n = e - p;
        const char *b = (const char *)buf + p;
        int blank = 1;
        for (size_t q = 0; q < n; q++)
            if (b[q] != ' ' && b[q] != '\t' && b[q] != '\r')
                blank = 0;
        if (!blank) {
            int st = header_line(&h, b, n, line, what, err);
            if (st != MC_OK)
                return st;
        }
        p = e + 1;
    }
    if (!h.have_xres || !h.have_yres)
        return mc_fail(err, MC_ERR_INPUT, "%s: GSF header has no %s; need XRes and YRes", what,
                       h.have_xres ? "YRes" : "XRes");

    /* one to four NULs: the data start at the next multiple of 4 after the header text */
    size_t start = (hend / 4 + 1) * 4;
    if (start > len)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated GSF file: the header's NUL padding runs past the end", what);
    for (size_t q = hend; q < start; q++)
        if (buf[q] != '\0')
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: GSF header padding at byte %zu is not NUL (the data must start at "
                           "a multiple of 4 bytes)",
                           what, q);
    int st = mc_surface_check_dims(h.xres, h.yres, what, err);
    if (st != MC_OK)
        return st;
    size_t n = (size_t)h.xres * (size_t)h.yres;
    if (len - start != 4 * n)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: XRes x YRes = %lld x %lld points need %zu bytes of float32 data, the "
                       "file has %zu (%s)",
                       what, h.xres, h.yres, 4 * n, len - start,
                       len - start < 4 * n ? "truncated" : "trailing bytes");
    st = mc_surface_alloc(out, h.xres, h.yres, what, err);
    if (st != MC_OK)
        return st;
    for (size_t k = 0; k < n; k++)
        out->z[k] = f32_le(buf + start + 4 * k) * h.z_unit;
    out->dx = h.have_xreal ? h.xreal * h.xy_unit / (double)out->nx : 0.0;
    out->dy = h.have_yreal ? h.yreal * h.xy_unit / (double)out->ny : 0.0;
    out->x0 = h.xoff * h.xy_unit;
    out->y0 = h.yoff * h.xy_unit;
    if (!isfinite(out->dx) || !isfinite(out->dy) || !isfinite(out->x0) || !isfinite(out->y0))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: GSF XReal, YReal, XOffset or YOffset out of range in metres", what);
    return MC_OK;
}
