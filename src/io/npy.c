/* npy.c - NumPy .npy reader and writer (see npy.h).
 *
 * The preamble and header dict are parsed by npy_header.c (bounded, fuzzed). mc_npy_parse is the
 * strict float64 reader of the contact pipeline's maps; mc_npy_parse_any converts every float
 * and integer dtype, either byte order and either memory order, for measured surfaces.
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
#include "io/le.h"
#include "io/npy_header.h"

#define NPY_MAGIC "\x93NUMPY"
#define NPY_MAGIC_LEN 6
#define NPY_ALIGN 64
#define NPY_PATH_MAX 4096

static const char accepted[] = "need a 1-D or 2-D float64 array ('<f8', fortran_order False)";

/* Rank, emptiness and data size shared by both readers: fills the matrix shape (a 1-D array is
 * 1 x n) and the value count n, after checking that the image holds exactly n * itemsize bytes of
 * data. need = what the reader accepts, for the messages. */
static int check_shape(const mc_npy_header *h, const char *what, size_t itemsize, const char *need,
                       int *rows, int *cols, size_t *count, mc_error *err)
{
    char shp[96];
    mc_npy_shape_text(shp, sizeof shp, h);
    if (h->rank != 1 && h->rank != 2)
        return mc_fail(err, MC_ERR_INPUT, "%s: %d-dimensional array (shape %s) not supported; %s",
                       what, h->rank, shp, need);
    if (h->dim_big)
        return mc_fail(err, MC_ERR_INPUT, "%s: shape %s too large: each dimension must be <= %d",
                       what, shp, INT_MAX);
    int r = h->rank == 1 ? 1 : (int)h->dim[0];
    int cl = (int)h->dim[h->rank - 1];
    if (r == 0 || cl == 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: empty array (shape %s); %s", what, shp, need);

    size_t avail = h->data_len, n, bytes;
    int fits = mc_size_mul((size_t)r, (size_t)cl, &n) && mc_size_mul(n, itemsize, &bytes);
    if (!fits || bytes > avail) {
        char want[48];
        if (fits)
            snprintf(want, sizeof want, "%zu bytes", bytes);
        else
            snprintf(want, sizeof want, "more bytes than memory can address");
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: truncated: header says %d x %d values (%s), file has %zu bytes of data",
                       what, r, cl, want, avail);
    }
    if (bytes < avail)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: header says %d x %d values (%zu bytes), file has %zu bytes of data "
                       "(trailing bytes after the array)",
                       what, r, cl, bytes, avail);
    *rows = r;
    *cols = cl;
    *count = n;
    return MC_OK;
}

int mc_npy_parse(const unsigned char *buf, size_t len, const char *what, double **data, int *rows,
                 int *cols, mc_error *err)
{
    *data = NULL;
    mc_npy_header h;
    int st = mc_npy_header_parse(buf, len, what, &h, err);
    if (st != MC_OK)
        return st;

    if (h.descr_is_list)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: structured dtype not supported; need float64 ('<f8')", what);
    if (h.descr_len != 3 || memcmp(h.descr, "<f8", 3) != 0) {
        char d[40];
        mc_npy_printable(d, sizeof d, h.descr, h.descr_len);
        return mc_fail(err, MC_ERR_INPUT, "%s: dtype '%s' not supported; need float64 ('<f8')",
                       what, d);
    }
    if (h.fortran)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: fortran_order True not supported; need a C-order array "
                       "(fortran_order False)",
                       what);
    int r, cl;
    size_t n;
    st = check_shape(&h, what, sizeof(double), accepted, &r, &cl, &n, err);
    if (st != MC_OK)
        return st;

    const unsigned char *src = h.data;
    for (size_t k = 0; k < n; k++) {
        double v = mc_le64_get(src + 8 * k);
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
    double *d = mc_malloc(n * sizeof(double));
    if (!d)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %d x %d values", what, r, cl);
    for (size_t k = 0; k < n; k++)
        d[k] = mc_le64_get(src + 8 * k);
    *data = d;
    *rows = r;
    *cols = cl;
    return MC_OK;
}

/* ---- any numeric dtype ------------------------------------------------------------------- */

typedef enum { KIND_FLOAT, KIND_INT, KIND_UINT } num_kind;

static const char any_need[] =
    "need a 1-D or 2-D array of a float (f2, f4, f8) or integer (i1..i8, u1..u8) dtype";

static int in_set(const char *set, unsigned char c) { return c != 0 && strchr(set, c) != NULL; }

/* Decode a dtype string such as "<f4", ">i2", "|u1" into kind, size and byte order. */
static int parse_dtype(const mc_npy_header *h, const char *what, num_kind *kind, size_t *size,
                       int *big_endian, mc_error *err)
{
    char d[40];
    mc_npy_printable(d, sizeof d, h->descr, h->descr_len);
    if (h->descr_is_list)
        return mc_fail(err, MC_ERR_INPUT, "%s: structured dtype not supported; %s", what, any_need);
    if (h->descr_len != 3 || !in_set("<>|=", h->descr[0]) || !in_set("fiu", h->descr[1]) ||
        !in_set("1248", h->descr[2]))
        return mc_fail(err, MC_ERR_INPUT, "%s: dtype '%s' not supported; %s", what, d, any_need);
    *kind = h->descr[1] == 'f' ? KIND_FLOAT : h->descr[1] == 'i' ? KIND_INT : KIND_UINT;
    *size = (size_t)(h->descr[2] - '0');
    if (*kind == KIND_FLOAT && *size == 1)
        return mc_fail(err, MC_ERR_INPUT, "%s: dtype '%s' not supported; %s", what, d, any_need);
    /* NumPy writes '<' or '>' (or '|' for one-byte types); '=' (native) says nothing about the
     * machine that wrote the file. */
    if (*size > 1 && (h->descr[0] == '|' || h->descr[0] == '='))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: dtype '%s' has no byte order; need '<' (little-endian) or '>' "
                       "(big-endian)",
                       what, d);
    *big_endian = h->descr[0] == '>';
    return MC_OK;
}

/* IEEE 754 binary16 to double (subnormals, infinities and NaN included). */
static double half_to_double(unsigned u)
{
    unsigned e = (u >> 10) & 0x1f, m = u & 0x3ff;
    double v;
    if (e == 0)
        v = ldexp((double)m, -24);
    else if (e == 31)
        v = m ? NAN : INFINITY;
    else
        v = ldexp((double)(m | 0x400), (int)e - 25);
    return (u & 0x8000) ? -v : v;
}

static double decode_value(const unsigned char *b, num_kind kind, size_t size, int big)
{
    uint64_t u = 0;
    for (size_t k = 0; k < size; k++)
        u = (u << 8) | b[big ? k : size - 1 - k];
    if (kind == KIND_FLOAT) {
        if (size == 2)
            return half_to_double((unsigned)u);
        if (size == 4) {
            uint32_t w = (uint32_t)u;
            float f;
            memcpy(&f, &w, sizeof f);
            return (double)f;
        }
        double d;
        memcpy(&d, &u, sizeof d);
        return d;
    }
    if (kind == KIND_UINT)
        return (double)u;
    /* sign-extend a two's complement integer of size bytes */
    if (size < 8 && (u >> (8 * size - 1)) & 1)
        u |= ~(uint64_t)0 << (8 * size);
    int64_t s;
    memcpy(&s, &u, sizeof s);
    return (double)s;
}

int mc_npy_parse_any(const unsigned char *buf, size_t len, const char *what, double **data,
                     int *rows, int *cols, mc_error *err)
{
    *data = NULL;
    mc_npy_header h;
    int st = mc_npy_header_parse(buf, len, what, &h, err);
    if (st != MC_OK)
        return st;
    num_kind kind = KIND_FLOAT;
    size_t size = 8;
    int big = 0;
    st = parse_dtype(&h, what, &kind, &size, &big, err);
    if (st != MC_OK)
        return st;
    int r, cl;
    size_t n;
    st = check_shape(&h, what, size, any_need, &r, &cl, &n, err);
    if (st != MC_OK)
        return st;
    double *d = mc_malloc(n * sizeof(double));
    if (!d)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for %d x %d values", what, r, cl);
    /* Fortran order stores element (i, j) of an r x c array at j*r + i: transpose to C order. */
    int fortran = h.fortran && h.rank == 2;
    for (size_t k = 0; k < n; k++) {
        size_t at = fortran ? (k % (size_t)cl) * (size_t)r + k / (size_t)cl : k;
        d[k] = decode_value(h.data + at * size, kind, size, big);
    }
    *data = d;
    *rows = r;
    *cols = cl;
    return MC_OK;
}

/* ---- files ------------------------------------------------------------------------------- */

int mc_npy_read(const char *path, double **data, int *rows, int *cols, mc_error *err)
{
    unsigned char *buf;
    size_t len;
    *data = NULL;
    int st = mc_io_read_file(path, &buf, &len, err);
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
    if (ok)
        ok = mc_le_write_doubles(f, data, n);
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
