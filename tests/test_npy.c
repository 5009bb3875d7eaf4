/* test_npy.c - .npy reader/writer and text/npy height maps (npy.c, heightmap.c). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "io/heightmap.h"
#include "io/npy.h"
#include "test_util.h"

#define IMG_MAX 65536

/* A .npy image with the given version, header dict and n doubles (little-endian host assumed
 * for the payload, as on every machine this project targets: checked below). */
static size_t make_npy(unsigned char *img, int major, const char *dict, const double *v, size_t n,
                       size_t pad_to)
{
    size_t pre = major == 1 ? 10 : 12, dl = strlen(dict);
    size_t total = pre + dl + 1;
    if (pad_to)
        total = (total + pad_to - 1) / pad_to * pad_to;
    size_t hlen = total - pre;
    memcpy(img, "\x93NUMPY", 6);
    img[6] = (unsigned char)major;
    img[7] = 0;
    for (size_t k = 0; k < pre - 8; k++)
        img[8 + k] = (unsigned char)(hlen >> (8 * k));
    memcpy(img + pre, dict, dl);
    memset(img + pre + dl, ' ', hlen - dl - 1);
    img[total - 1] = '\n';
    memcpy(img + total, v, n * sizeof(double));
    return total + n * sizeof(double);
}

/* Parse from an exactly sized heap copy so that ASan sees any read past the end. */
static int parse_copy(const unsigned char *img, size_t len, double **d, int *r, int *c,
                      mc_error *err)
{
    unsigned char *copy = malloc(len ? len : 1);
    ck_assert(copy != NULL);
    memcpy(copy, img, len);
    int st = mc_npy_parse(copy, len, "x.npy", d, r, c, err);
    free(copy);
    return st;
}

static void write_bytes(const char *path, const void *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    ck_assert(f != NULL);
    ck_assert_uint_eq(fwrite(b, 1, n, f), n);
    ck_assert_int_eq(fclose(f), 0);
}

START_TEST(test_host_little_endian)
{
    /* make_npy copies doubles raw; the library itself is byte-order independent. */
    double one = 1.0;
    unsigned char b[8];
    memcpy(b, &one, 8);
    ck_assert_uint_eq(b[7], 0x3f);
}
END_TEST

START_TEST(test_roundtrip_2d)
{
    const char *dir = test_tmpdir();
    char path[512];
    snprintf(path, sizeof path, "%s/a.npy", dir);
    double v[35];
    test_random_field(v, 35, 7);
    v[3] = -0.0;
    v[4] = 1e-310; /* subnormal survives */
    size_t shape[2] = {7, 5};
    mc_error err = {0};
    ck_assert_int_eq(mc_npy_write(path, v, 2, shape, &err), MC_OK);

    unsigned char *buf;
    size_t len;
    ck_assert_int_eq(mc_io_read_file(path, &buf, &len, &err), MC_OK);
    ck_assert_mem_eq(buf, "\x93NUMPY\x01\x00", 8);
    size_t hlen = buf[8] | (size_t)buf[9] << 8;
    ck_assert_uint_eq((10 + hlen) % 64, 0);
    ck_assert_uint_eq(buf[10 + hlen - 1], '\n');
    const char *dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (7, 5), }";
    ck_assert_mem_eq(buf + 10, dict, strlen(dict));
    for (size_t k = 10 + strlen(dict); k < 10 + hlen - 1; k++)
        ck_assert_uint_eq(buf[k], ' ');
    ck_assert_uint_eq(len, 10 + hlen + sizeof v);
    ck_assert_mem_eq(buf + 10 + hlen, v, sizeof v);
    mc_free(buf);

    double *d;
    int r, c;
    ck_assert_int_eq(mc_npy_read(path, &d, &r, &c, &err), MC_OK);
    ck_assert_int_eq(r, 7);
    ck_assert_int_eq(c, 5);
    ck_assert_mem_eq(d, v, sizeof v);
    ck_assert(signbit(d[3]));
    mc_free(d);
    char tmp[600];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    ck_assert_int_ne(access(tmp, F_OK), 0);
}
END_TEST

START_TEST(test_roundtrip_1d_and_3d)
{
    const char *dir = test_tmpdir();
    char path[512];
    snprintf(path, sizeof path, "%s/b.npy", dir);
    double v[24];
    test_random_field(v, 24, 3);
    size_t s1[1] = {9};
    mc_error err = {0};
    ck_assert_int_eq(mc_npy_write(path, v, 1, s1, &err), MC_OK);
    double *d;
    int r, c;
    ck_assert_int_eq(mc_npy_read(path, &d, &r, &c, &err), MC_OK);
    ck_assert_int_eq(r, 1);
    ck_assert_int_eq(c, 9);
    ck_assert_mem_eq(d, v, 9 * sizeof(double));
    mc_free(d);

    size_t s3[3] = {2, 3, 4};
    ck_assert_int_eq(mc_npy_write(path, v, 3, s3, &err), MC_OK);
    unsigned char *buf;
    size_t len;
    ck_assert_int_eq(mc_io_read_file(path, &buf, &len, &err), MC_OK);
    const char *dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3, 4), }";
    ck_assert_mem_eq(buf + 10, dict, strlen(dict));
    mc_free(buf);
    d = (double *)&err; /* must be reset to NULL on failure */
    ck_assert_int_eq(mc_npy_read(path, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_ptr_null(d);
    ck_assert_msg(strstr(err.msg, "3-dimensional array (shape (2, 3, 4)) not supported") &&
                      strstr(err.msg, path) == err.msg,
                  "%s", err.msg);
}
END_TEST

START_TEST(test_numpy_files)
{
    /* Headers exactly as NumPy writes them: legacy 16-byte alignment (numpy < 1.9), 64-byte
     * alignment with growth padding (numpy >= 1.22), and a Python 2 era "3L" shape. */
    static const double v[6] = {0, 1, 2, 3, 4, 5};
    const char *dicts[] = {"{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }",
                           "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }"
                           "                                                           ",
                           "{'descr': '<f8', 'fortran_order': False, 'shape': (2L, 3L), }"};
    size_t pads[] = {16, 64, 16};
    unsigned char img[512];
    for (int t = 0; t < 3; t++) {
        size_t len = make_npy(img, 1, dicts[t], v, 6, pads[t]);
        double *d;
        int r, c;
        mc_error err = {0};
        ck_assert_msg(parse_copy(img, len, &d, &r, &c, &err) == MC_OK, "%d: %s", t, err.msg);
        ck_assert_int_eq(r, 2);
        ck_assert_int_eq(c, 3);
        ck_assert_mem_eq(d, v, sizeof v);
        mc_free(d);
    }
}
END_TEST

START_TEST(test_header_variants)
{
    static const double v[6] = {1.5, -2, 3e-9, 4, 5, 6e300};
    const char *dicts[] = {
        "{'shape': (2, 3), 'fortran_order': False, 'descr': '<f8'}",
        "{ \"descr\" : \"<f8\" , \"fortran_order\":False,'shape':( 2 ,3 , ) , }",
        "{'fortran_order': False, 'descr': '<f8', 'shape': (2,3)}\t\r\n",
        "{'descr':'<f8','fortran_order':False,'shape':(2,3,),}",
    };
    unsigned char img[512];
    for (int major = 1; major <= 3; major++) {
        for (int t = 0; t < 4; t++) {
            size_t len = make_npy(img, major, dicts[t], v, 6, 64);
            double *d;
            int r, c;
            mc_error err = {0};
            ck_assert_msg(parse_copy(img, len, &d, &r, &c, &err) == MC_OK, "v%d #%d: %s", major, t,
                          err.msg);
            ck_assert_int_eq(r, 2);
            ck_assert_int_eq(c, 3);
            ck_assert_mem_eq(d, v, sizeof v);
            mc_free(d);
        }
    }
}
END_TEST

typedef struct {
    const char *dict;
    size_t ndata; /* doubles of payload */
    const char *expect; /* substring of the message; exact message when it starts with "x.npy" */
} bad_case;

static const bad_case bad_cases[] = {
    {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", 6,
     "x.npy: dtype '<f4' not supported; need float64 ('<f8')"},
    {"{'descr': '>f8', 'fortran_order': False, 'shape': (2, 3), }", 6,
     "x.npy: dtype '>f8' not supported; need float64 ('<f8')"},
    {"{'descr': '|u1', 'fortran_order': False, 'shape': (2, 3), }", 6, "dtype '|u1' not supported"},
    {"{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (2, 3), }", 6,
     "structured dtype not supported"},
    {"{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", 6,
     "x.npy: fortran_order True not supported; need a C-order array (fortran_order False)"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (), }", 1,
     "0-dimensional array (shape ()) not supported; need a 1-D or 2-D float64 array"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2, 3), }", 6, "3-dimensional"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (0, 3), }", 0, "empty array"},
    {"{'descr': '<f8', 'fortran_order': False, }", 6, "missing key 'shape'"},
    {"{'descr': '<f8', 'shape': (2, 3), }", 6, "missing key 'fortran_order'"},
    {"{'descr': '<f8', 'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", 6,
     "duplicate key 'descr'"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), 'extra': 1}", 6,
     "unknown key 'extra'"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), } x", 6, "unexpected text"},
    {"{'descr': '<f8', 'fortran_order': Maybe, 'shape': (2, 3), }", 6, "True or False"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (2, -3), }", 6, "non-negative integer"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (2 3), }", 6, "expected ',' or ')'"},
    {"{'descr': '<f8' 'fortran_order': False, 'shape': (2, 3), }", 6, "expected ',' or '}'"},
    {"{'descr: '<f8', 'fortran_order': False, 'shape': (2, 3), }", 6, "malformed"},
    {"'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", 6, "expected '{'"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999, 99999999999), }", 6,
     "too large"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (2147483647, 2147483647), }", 6,
     "truncated: header says 2147483647 x 2147483647 values ("},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (64, 64), }", 125,
     "x.npy: truncated: header says 64 x 64 values (32768 bytes), file has 1000 bytes of data"},
    {"{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", 7,
     "x.npy: header says 2 x 3 values (48 bytes), file has 56 bytes of data (trailing bytes"},
};

START_TEST(test_bad_headers)
{
    const bad_case *bc = &bad_cases[_i];
    static double v[200];
    for (int k = 0; k < 200; k++)
        v[k] = k;
    unsigned char img[4096];
    size_t len = make_npy(img, 1, bc->dict, v, bc->ndata, 64);
    double *d;
    int r, c;
    mc_error err = {0};
    ck_assert_int_eq(parse_copy(img, len, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_ptr_null(d);
    ck_assert_int_eq(err.code, MC_ERR_INPUT);
    if (strncmp(bc->expect, "x.npy", 5) == 0)
        ck_assert_msg(strncmp(err.msg, bc->expect, strlen(bc->expect)) == 0, "got: %s", err.msg);
    else
        ck_assert_msg(strstr(err.msg, bc->expect) != NULL, "want '%s', got: %s", bc->expect,
                      err.msg);
}
END_TEST

START_TEST(test_bad_preamble)
{
    unsigned char img[512];
    static const double v[6] = {0};
    const char *dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }";
    size_t len = make_npy(img, 1, dict, v, 6, 64);
    double *d;
    int r, c;
    mc_error err = {0};

    img[0] = 'X';
    ck_assert_int_eq(parse_copy(img, len, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "not a NumPy .npy file"), "%s", err.msg);
    img[0] = 0x93;

    img[6] = 4;
    ck_assert_int_eq(parse_copy(img, len, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "version 4.0 not supported; need 1.0, 2.0 or 3.0"), "%s",
                  err.msg);
    img[6] = 1;

    img[8] = 0xff; /* header length beyond the file */
    img[9] = 0xff;
    ck_assert_int_eq(parse_copy(img, len, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "header length 65535"), "%s", err.msg);
    ck_assert_ptr_null(d);
}
END_TEST

START_TEST(test_nonfinite)
{
    double v[6] = {0, 1, 2, 3, 4, 5};
    unsigned char img[512];
    double *d;
    int r, c;
    mc_error err = {0};
    v[5] = NAN;
    v[4] = NAN; /* the first bad value is reported */
    size_t len =
        make_npy(img, 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", v, 6, 64);
    ck_assert_int_eq(parse_copy(img, len, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_str_eq(err.msg, "x.npy: value [1, 1] (flat index 4) is NaN; values must be finite");
    v[4] = 4;
    v[5] = 5;
    v[3] = -INFINITY;
    len = make_npy(img, 2, "{'descr': '<f8', 'fortran_order': False, 'shape': (6,), }", v, 6, 64);
    ck_assert_int_eq(parse_copy(img, len, &d, &r, &c, &err), MC_ERR_INPUT);
    ck_assert_str_eq(err.msg, "x.npy: value [3] is infinite; values must be finite");
    ck_assert_ptr_null(d);
}
END_TEST

START_TEST(test_every_prefix_and_mutation)
{
    double v[6] = {1, 2, 3, 4, 5, 6};
    unsigned char img[512], mut[512];
    size_t len = make_npy(img, 2, "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }", v,
                          6, 64);
    for (size_t n = 0; n < len; n++) {
        double *d;
        int r, c;
        mc_error err = {0};
        ck_assert_int_eq(parse_copy(img, n, &d, &r, &c, &err), MC_ERR_INPUT);
        ck_assert_ptr_null(d);
        ck_assert(err.msg[0] != '\0');
    }
    /* Random byte mutations of the preamble and header: either a clean error or a result whose
     * shape accounts for every byte (ASan runs check the bounds). */
    unsigned long long x = 12345;
    for (int t = 0; t < 20000; t++) {
        memcpy(mut, img, len);
        for (int m = 0; m < 3; m++) {
            x = x * 6364136223846793005ULL + 1442695040888963407ULL;
            size_t pos = (size_t)(x >> 33) % 128;
            mut[pos] = (unsigned char)(x >> 20);
        }
        double *d;
        int r, c;
        mc_error err = {0};
        int st = parse_copy(mut, len, &d, &r, &c, &err);
        if (st == MC_OK) {
            ck_assert_uint_eq((size_t)r * (size_t)c * 8, 6 * 8);
            mc_free(d);
        } else {
            ck_assert_int_eq(st, MC_ERR_INPUT);
            ck_assert_ptr_null(d);
            ck_assert(err.msg[0] != '\0');
        }
    }
}
END_TEST

START_TEST(test_io_errors)
{
    const char *dir = test_tmpdir();
    char path[512];
    double *d;
    int r, c;
    mc_error err = {0};
    snprintf(path, sizeof path, "%s/missing.npy", dir);
    ck_assert_int_eq(mc_npy_read(path, &d, &r, &c, &err), MC_ERR_IO);
    ck_assert_msg(strstr(err.msg, path) && strstr(err.msg, "No such file"), "%s", err.msg);
    ck_assert_int_eq(mc_npy_read(dir, &d, &r, &c, &err), MC_ERR_IO);
    ck_assert_msg(strstr(err.msg, "Is a directory"), "%s", err.msg);

    double v[4] = {1, 2, 3, 4};
    size_t shape[2] = {2, 2};
    snprintf(path, sizeof path, "%s/nodir/a.npy", dir);
    ck_assert_int_eq(mc_npy_write(path, v, 2, shape, &err), MC_ERR_IO);
    ck_assert_msg(strstr(err.msg, "a.npy.tmp: cannot create"), "%s", err.msg);
    size_t s4[4] = {1, 1, 2, 2};
    snprintf(path, sizeof path, "%s/a.npy", dir);
    ck_assert_int_eq(mc_npy_write(path, v, 4, s4, &err), MC_ERR_INPUT);
    ck_assert_int_ne(access(path, F_OK), 0);
    /* A target that cannot be replaced (a directory): the temporary file is removed. */
    ck_assert_int_eq(mkdir(path, 0700), 0);
    ck_assert_int_eq(mc_npy_write(path, v, 2, shape, &err), MC_ERR_IO);
    char tmp[600];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    ck_assert_int_ne(access(tmp, F_OK), 0);
}
END_TEST

/* ---- height maps ------------------------------------------------------------------------- */

START_TEST(test_text_matrix)
{
    const char text[] = "\xEF\xBB\xBF# measured heights, m\r\n"
                        "\n"
                        "1 2.5\t-3e-6  4 # trailing comment\r\n"
                        "   # indented comment\n"
                        "5 6 7 0.25\n"
                        "\t\n"
                        "9 10 11 +12";
    double *d;
    int r, c;
    mc_error err = {0};
    ck_assert_int_eq(mc_text_matrix_parse(text, sizeof text - 1, "h.txt", &d, &r, &c, &err), MC_OK);
    ck_assert_int_eq(r, 3);
    ck_assert_int_eq(c, 4);
    const double want[12] = {1, 2.5, -3e-6, 4, 5, 6, 7, 0.25, 9, 10, 11, 12};
    for (int k = 0; k < 12; k++)
        ck_assert_double_eq(d[k], want[k]);
    mc_free(d);
}
END_TEST

START_TEST(test_text_matrix_errors)
{
    struct {
        const char *text;
        const char *msg;
    } cases[] = {
        {"# h\n1 2 3\n4 5 6\n7 8\n", "h.txt:4: 2 values, but the first data row (line 2) has 3; "
                                     "every row needs the same number of columns"},
        {"1 2\n3 4,\n", "h.txt:2: '4,' is not a number"},
        {"1 2\n3 nan\n", "h.txt:2: value 'nan' is not finite; values must be finite"},
        {"1e999 2\n", "h.txt:1: value '1e999' is not finite"},
        {"1 2\n3 x4\n", "h.txt:2: 'x4' is not a number"},
        {"# only a comment\n\n  \n", "h.txt: no data rows"},
        {"", "h.txt: no data rows"},
        {"1 2\n3 4\0\n", "h.txt:2: '4?' is not a number"},
        /* only the case file's decimal forms (issue 15: 0x10 was read as 16 m) */
        {"1 0x10\n", "h.txt:1: '0x10' is not a number (accepted: decimal numbers"},
        {"1 0x1p-2\n", "h.txt:1: '0x1p-2' is not a number"},
        {"1 2\n-inf 4\n", "h.txt:2: '-inf' is not a number"},
        {"1 2\n3 infinity\n", "h.txt:2: 'infinity' is not a number"},
        {"1 .e5\n", "h.txt:1: '.e5' is not a number"},
        {"1 1e\n", "h.txt:1: '1e' is not a number"},
    };
    size_t lens[] = {0, 0, 0, 0, 0, 0, 0, 9, 0, 0, 0, 0, 0, 0}; /* [7] holds a NUL byte */
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        double *d;
        int r, c;
        mc_error err = {0};
        size_t len = lens[t] ? lens[t] : strlen(cases[t].text);
        char *copy = malloc(len + 1);
        memcpy(copy, cases[t].text, len);
        int st = mc_text_matrix_parse(copy, len, "h.txt", &d, &r, &c, &err);
        free(copy);
        ck_assert_int_eq(st, MC_ERR_INPUT);
        ck_assert_ptr_null(d);
        ck_assert_msg(strncmp(err.msg, cases[t].msg, strlen(cases[t].msg)) == 0,
                      "case %zu: want '%s', got '%s'", t, cases[t].msg, err.msg);
    }
}
END_TEST

START_TEST(test_heightmap_read)
{
    const char *dir = test_tmpdir();
    char npy[512], txt[512];
    snprintf(npy, sizeof npy, "%s/heights.npy", dir);
    snprintf(txt, sizeof txt, "%s/heights.txt", dir);
    double v[64 * 32];
    test_random_field(v, 64 * 32, 11);
    size_t shape[2] = {64, 32};
    mc_error err = {0};
    ck_assert_int_eq(mc_npy_write(npy, v, 2, shape, &err), MC_OK);
    FILE *f = fopen(txt, "w");
    ck_assert(f != NULL);
    for (int j = 0; j < 64; j++) {
        for (int i = 0; i < 32; i++)
            fprintf(f, "%s%.17g", i ? " " : "", v[j * 32 + i]);
        fprintf(f, "\n");
    }
    ck_assert_int_eq(fclose(f), 0);

    const char *paths[2] = {npy, txt};
    for (int t = 0; t < 2; t++) {
        double *d;
        ck_assert_int_eq(mc_heightmap_read(paths[t], 64, 32, &d, &err), MC_OK);
        ck_assert_mem_eq(d, v, sizeof v); /* %.17g text round-trips exactly */
        mc_free(d);
        ck_assert_int_eq(mc_heightmap_read(paths[t], 0, 0, &d, &err), MC_OK);
        mc_free(d);
        ck_assert_int_eq(mc_heightmap_read(paths[t], 64, 64, &d, &err), MC_ERR_INPUT);
        ck_assert_ptr_null(d);
        char want[700];
        snprintf(want, sizeof want, "%s: shape 64 x 32, the mesh is 64 x 64 (ny x nx)", paths[t]);
        ck_assert_str_eq(err.msg, want);
        ck_assert_int_eq(mc_heightmap_read(paths[t], 32, 0, &d, &err), MC_ERR_INPUT);
    }
    /* Magic dispatch: a file that starts like .npy but is broken is reported as .npy. */
    write_bytes(npy, "\x93NUMPY\x01\x00\x02\x00{}", 12);
    double *d;
    ck_assert_int_eq(mc_heightmap_read(npy, 0, 0, &d, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "missing key"), "%s", err.msg);
    snprintf(txt, sizeof txt, "%s/none.txt", dir);
    ck_assert_int_eq(mc_heightmap_read(txt, 0, 0, &d, &err), MC_ERR_IO);
}
END_TEST

START_TEST(test_heightmap_fault_injection)
{
    const char *dir = test_tmpdir();
    char path[512];
    snprintf(path, sizeof path, "%s/h.txt", dir);
    write_bytes(path, "1 2 3\n4 5 6\n", 12);
    int failures = 0;
    for (long n = 1;; n++) {
        double *d = NULL;
        mc_error err = {0};
        mc_alloc_fail_at(n);
        int st = mc_heightmap_read(path, 2, 3, &d, &err);
        mc_alloc_fail_at(0);
        if (st == MC_OK) {
            ck_assert_double_eq(d[5], 6.0);
            mc_free(d);
            break;
        }
        ck_assert_int_eq(st, MC_ERR_NOMEM);
        ck_assert_ptr_null(d);
        failures++;
        ck_assert_int_lt(n, 100);
    }
    ck_assert_int_eq(failures, 2); /* the file buffer and the matrix */
}
END_TEST

Suite *suite_npy(void);
Suite *suite_npy(void)
{
    Suite *s = suite_create("npy");
    TCase *tc = tcase_create("npy");
    tcase_add_test(tc, test_host_little_endian);
    tcase_add_test(tc, test_roundtrip_2d);
    tcase_add_test(tc, test_roundtrip_1d_and_3d);
    tcase_add_test(tc, test_numpy_files);
    tcase_add_test(tc, test_header_variants);
    tcase_add_loop_test(tc, test_bad_headers, 0, (int)(sizeof bad_cases / sizeof bad_cases[0]));
    tcase_add_test(tc, test_bad_preamble);
    tcase_add_test(tc, test_nonfinite);
    tcase_add_test(tc, test_every_prefix_and_mutation);
    tcase_add_test(tc, test_io_errors);
    suite_add_tcase(s, tc);
    TCase *th = tcase_create("heightmap");
    tcase_add_test(th, test_text_matrix);
    tcase_add_test(th, test_text_matrix_errors);
    tcase_add_test(th, test_heightmap_read);
    tcase_add_test(th, test_heightmap_fault_injection);
    suite_add_tcase(s, th);
    return s;
}
