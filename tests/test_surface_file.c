/* test_surface_file.c - measured-surface readers and the X3P writer (src/io/surface_file.h).
 *
 * Every file here is made by the test itself, byte by byte (zip containers through libzip, MD5s
 * through nettle directly), from values whose expected heights follow from the format's
 * definition: z = offset + increment * stored value (X3P), stored value * Zscale (SDF), float32 *
 * unit (GSF). Heights are compared exactly: each expected value is the same single product the
 * definition prescribes, so no rounding separates reader and test. The bad-file table is in
 * test_surface_file_bad.c.
 */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <nettle/md5.h>
#include <zip.h>

#include "core/alloc.h"
#include "io/npy.h"
#include "io/surface_file.h"
#include "io/surface_formats.h"
#include "surface_file_testkit.h"
#include "test_util.h"

/* ---- X3P writer round trip ------------------------------------------------------------------ */

static void fill_surface(mc_surface_data *s, double *z, int nx, int ny)
{
    memset(s, 0, sizeof *s);
    s->nx = nx;
    s->ny = ny;
    s->dx = 1.25e-6 / 3.0; /* not a short decimal: the 17-digit text must round-trip */
    s->dy = 0.7e-6;        /* dx != dy, as real instruments have */
    s->x0 = -3.3e-5;
    s->y0 = 1e-7 / 7.0;
    test_random_field(z, (size_t)nx * (size_t)ny, 42);
    for (int k = 0; k < nx * ny; k++)
        z[k] *= 1e-6;
    z[1] = -0.0;   /* sign of zero survives */
    z[2] = 4.9e-324; /* a subnormal survives */
    s->z = z;
}

START_TEST(test_x3p_roundtrip)
{
    enum { NX = 9, NY = 5 };
    static double z[NX * NY];
    mc_surface_data s, r;
    fill_surface(&s, z, NX, NY);
    const char *path = tk_path("round.x3p");
    mc_error err = {0};
    for (int masked = 0; masked < 2; masked++) {
        unsigned char valid[NX * NY];
        memset(valid, 1, sizeof valid);
        if (masked) { /* two NaN points (one with a payload) and one masked-out NaN */
            uint64_t payload = 0x7ff8000000001234ull;
            memcpy(&z[7], &payload, sizeof z[7]);
            z[20] = NAN;
            valid[7] = valid[20] = 0;
            s.valid = valid;
        }
        ck_assert_msg(mc_x3p_write(path, &s, "round trip <test> & \"co\"", &err) == MC_OK, "%s",
                      err.msg);
        ck_assert_msg(!tk_exists(tk_path("round.x3p.tmp")), "temporary file left behind");
        ck_assert_msg(mc_surface_file_read(path, NULL, &r, &err) == MC_OK, "%s", err.msg);
        ck_assert_int_eq(r.nx, NX);
        ck_assert_int_eq(r.ny, NY);
        ck_assert_str_eq(r.format, "x3p");
        /* bit-identical: heights (NaN payloads included), spacings, offsets */
        ck_assert_mem_eq(r.z, z, sizeof z);
        ck_assert_mem_eq(&r.dx, &s.dx, sizeof s.dx);
        ck_assert_mem_eq(&r.dy, &s.dy, sizeof s.dy);
        ck_assert_mem_eq(&r.x0, &s.x0, sizeof s.x0);
        ck_assert_mem_eq(&r.y0, &s.y0, sizeof s.y0);
        ck_assert_int_eq(r.missing, masked ? 2 : 0);
        if (masked)
            ck_assert_mem_eq(r.valid, valid, sizeof valid);
        else
            ck_assert_ptr_null(r.valid);
        mc_surface_data_free(&r);

        /* the container: members, their checksums (computed here, by nettle directly), the
         * record structure of main.xml */
        unsigned char *xml, *sum, *data;
        size_t xml_len, sum_len, data_len;
        ck_assert(tk_unzip(path, "main.xml", &xml, &xml_len));
        ck_assert(tk_unzip(path, "md5checksum.hex", &sum, &sum_len));
        ck_assert(tk_unzip(path, "bindata/data.bin", &data, &data_len));
        ck_assert_uint_eq(data_len, sizeof z);
        ck_assert_mem_eq(data, z, sizeof z); /* little-endian host, checked in test_npy.c */
        char hex[33], want[80];
        tk_md5(xml, xml_len, hex);
        snprintf(want, sizeof want, "%s *main.xml\n", hex);
        ck_assert_uint_eq(sum_len, strlen(want));
        ck_assert_mem_eq(sum, want, sum_len);
        tk_md5(data, data_len, hex);
        ck_assert_msg(tk_contains(xml, xml_len, hex), "data MD5 %s not in main.xml", hex);
        free(data);
        ck_assert(tk_unzip(path, "bindata/valid.bin", &data, &data_len) == masked);
        xmlDocPtr doc = xmlReadMemory((const char *)xml, (int)xml_len, "main.xml", NULL,
                                      XML_PARSE_NONET);
        ck_assert_ptr_nonnull(doc);
        const char *records[4] = {"Record1", "Record2", "Record3", "Record4"};
        int k = 0;
        for (xmlNodePtr c = xmlDocGetRootElement(doc)->children; c; c = c->next)
            if (c->type == XML_ELEMENT_NODE) {
                ck_assert_int_lt(k, 4);
                ck_assert_str_eq((const char *)c->name, records[k++]);
            }
        ck_assert_int_eq(k, 4);
        ck_assert(tk_contains(xml, xml_len, "round trip &lt;test&gt; &amp; &quot;co&quot;"));
        xmlFreeDoc(doc);
        free(xml);
        free(sum);
        free(data);
    }
}
END_TEST

START_TEST(test_x3p_write_refusals)
{
    double z[4] = {0, 1, 2, 3};
    mc_surface_data s = {2, 2, 0.0, 1e-6, 0, 0, z, NULL, 0, "", ""};
    mc_error err = {0};
    const char *path = tk_path("refused.x3p");
    ck_assert_int_eq(mc_x3p_write(path, &s, NULL, &err), MC_ERR_INPUT); /* dx unknown */
    ck_assert_msg(strstr(err.msg, "needs both > 0"), "%s", err.msg);
    ck_assert(!tk_exists(path));
    s.dx = 1e-6;
    const char *nodir = tk_path("no/such/dir/s.x3p");
    ck_assert_int_eq(mc_x3p_write(nodir, &s, NULL, &err), MC_ERR_IO);
    ck_assert_msg(strncmp(err.msg, nodir, strlen(nodir)) == 0, "%s", err.msg);
    ck_assert(!tk_exists(nodir));
}
END_TEST

START_TEST(test_md5_vector)
{
    char hex[33]; /* RFC 1321 appendix A.5 */
    mc_md5_hex((const unsigned char *)"abc", 3, hex);
    ck_assert_str_eq(hex, "900150983cd24fb0d6963f7d28e17f72");
    mc_md5_hex((const unsigned char *)"", 0, hex);
    ck_assert_str_eq(hex, "d41d8cd98f00b204e9800998ecf8427e");
}
END_TEST

/* ---- hand-made X3P: data types I, L, F, D with a valid-points mask ------------------------- */

START_TEST(test_x3p_types)
{
    const char type = "ILFD"[_i];
    enum { NX = 3, NY = 2, N = NX * NY };
    /* stored values, one per point; points 1 and 4 masked out (mask byte 0b00101101) */
    const double ints[N] = {-300, 120, 0, 32767, -32768, 5};
    const double longs[N] = {100000, -7, 2147483647, -2147483647.0 - 1, 3, -99};
    const double reals[N] = {1.5, -2.25, 1e-3, NAN, 7.0, -0.125};
    const double *raw = type == 'I' ? ints : type == 'L' ? longs : reals;
    const double zinc = type == 'I' || type == 'L' ? 2e-9 : 1.0, zoff = 1e-6;
    unsigned char data[N * 8];
    size_t elem = type == 'I' ? 2 : type == 'L' || type == 'F' ? 4 : 8;
    for (int k = 0; k < N; k++)
        tk_put_value(data + (size_t)k * elem, raw[k], type == 'I' ? 'i' : type == 'L' ? 'i'
                                                                        : 'f', elem, 0);
    unsigned char mask[1] = {0x2D};
    tk_x3p spec = tk_x3p_default(type, NX, NY);
    spec.zinc = zinc;
    spec.zoff = zoff;
    const char *path = tk_path("types.x3p");
    tk_make_x3p(path, &spec, data, (size_t)N * elem, mask, 1);

    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(mc_surface_file_read(path, NULL, &r, &err) == MC_OK, "%c: %s", type, err.msg);
    ck_assert_int_eq(r.nx, NX);
    ck_assert_int_eq(r.ny, NY);
    ck_assert(r.dx == spec.dx && r.dy == spec.dy && r.x0 == spec.x0 && r.y0 == spec.y0);
    long missing = 0;
    for (int k = 0; k < N; k++) {
        double stored = type == 'F' ? (double)(float)raw[k] : raw[k];
        int valid = ((mask[0] >> k) & 1) && isfinite(raw[k]);
        missing += !valid;
        ck_assert_int_eq(r.valid[k], valid);
        if (valid) /* definition of the CZ axis: offset + increment * stored value */
            ck_assert_msg(r.z[k] == zoff + zinc * stored, "%c point %d: %.17g", type, k, r.z[k]);
        else
            ck_assert(isnan(r.z[k]));
    }
    ck_assert_int_eq(r.missing, missing);
    mc_surface_data_free(&r);
}
END_TEST

/* ---- SDF ------------------------------------------------------------------------------------ */

START_TEST(test_sdf_ascii)
{
    const char *text = "aISO-1.0\r\nManufacID   = test\r\nCreateDate  = 010120240000\r\n"
                       "ModDate     = 010120240000\r\nNumPoints   = 3\r\nNumProfiles = 2\r\n"
                       "Xscale      = 1.5e-06\r\nYscale      = 2.5e-06\r\nZscale      = 1e-09\r\n"
                       "Zresolution = -1\r\nCompression = 0\r\nDataType    = 7\r\n"
                       "CheckType   = 0\r\nNumDataSet  = 1\r\n*\r\n1.0 2.5 BAD\r\n"
                       "-4 5e1\r\n6\r\n*\r\nOperator = nobody\r\n*\r\n";
    const double want[6] = {1.0 * 1e-9, 2.5 * 1e-9, NAN, -4 * 1e-9, 5e1 * 1e-9, 6 * 1e-9};
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(tk_parse("sdf", text, strlen(text), &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(r.nx == 3 && r.ny == 2 && r.dx == 1.5e-6 && r.dy == 2.5e-6 && r.missing == 1);
    tk_assert_heights(&r, want, 6);
    mc_surface_data_free(&r);

    /* integer DataType: the type's lowest value marks a point not measured */
    const char *ints = "aBCR-1.0\nNumPoints = 2\nNumProfiles = 1\nXscale = 1e-6\n"
                       "Yscale = 1e-6\nZscale = 1e-8\nDataType = 5\n*\n-32768 17\n*\n";
    const double want2[2] = {NAN, 17 * 1e-8};
    ck_assert_msg(tk_parse("sdf", ints, strlen(ints), &r, &err) == MC_OK, "%s", err.msg);
    tk_assert_heights(&r, want2, 2);
    mc_surface_data_free(&r);
}
END_TEST

START_TEST(test_sdf_binary)
{
    /* variant 0: bISO-1.0 int16; 1: bBCR-1.0 float32; 2: bISO-2.0 (32-bit counts) float64 with a
     * text trailer */
    static const char *const magic[3] = {"bISO-1.0", "bBCR-1.0", "bISO-2.0"};
    const int dtype[3] = {5, 3, 7};
    const size_t size[3] = {2, 4, 8};
    const double raw[3][6] = {{-32768, 1, -2, 300, 32767, 0},
                              {1.5, -FLT_MAX, 0.25, NAN, 8, -3},
                              {0.5, 1e-3, NAN, -DBL_MAX, 2, 3}};
    const double zscale = 1e-9;
    unsigned char img[256];
    size_t p = 0;
    memcpy(img, magic[_i], 8);
    p = 8;
    memset(img + p, ' ', 34); /* ManufacID, CreateDate, ModDate */
    p += 34;
    size_t cw = _i == 2 ? 4 : 2;
    tk_put_value(img + p, 3, 'u', cw, 0);
    tk_put_value(img + p + cw, 2, 'u', cw, 0);
    p += 2 * cw;
    const double scales[4] = {2e-6, 3e-6, zscale, -1};
    for (int q = 0; q < 4; q++, p += 8)
        tk_put_value(img + p, scales[q], 'f', 8, 0);
    img[p++] = 0;
    img[p++] = (unsigned char)dtype[_i];
    img[p++] = 0;
    ck_assert_uint_eq(p, _i == 2 ? 85u : 81u); /* the standard's header sizes */
    for (int k = 0; k < 6; k++, p += size[_i])
        tk_put_value(img + p, raw[_i][k], dtype[_i] == 5 ? 'i' : 'f', size[_i], 0);
    if (_i == 2) {
        memcpy(img + p, "*\r\nOperator = x\r\n*\r\n", 20);
        p += 20;
    }
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(tk_parse("sdf", img, p, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(r.nx == 3 && r.ny == 2 && r.dx == 2e-6 && r.dy == 3e-6);
    double want[6];
    for (int k = 0; k < 6; k++) {
        double v = raw[_i][k];
        int marker = v == -32768 || v == -FLT_MAX || v == -DBL_MAX || isnan(v);
        want[k] = marker ? NAN : (dtype[_i] == 3 ? (double)(float)v : v) * zscale;
    }
    tk_assert_heights(&r, want, 6);
    mc_surface_data_free(&r);
}
END_TEST

/* ---- GSF, text matrix, xyz ---------------------------------------------------------------- */

START_TEST(test_gsf)
{
    const char *head = "Gwyddion Simple Field 1.0\nXRes = 3\nYRes = 2\n  XReal = 6 \n"
                       "YReal=5\nXOffset = -1\nYOffset = 2.5\nXYUnits = um\nZUnits = nm\n"
                       "Title = hand made\n";
    unsigned char img[256];
    size_t h = strlen(head), p = (h / 4 + 1) * 4; /* one to four NULs, data 4-byte aligned */
    memcpy(img, head, h);
    memset(img + h, 0, p - h);
    const float v[6] = {1.5f, -2.0f, NAN, 0.25f, 1e3f, -7.0f};
    for (int k = 0; k < 6; k++, p += 4)
        tk_put_value(img + p, v[k], 'f', 4, 0);
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(tk_parse("gsf", img, p, &r, &err) == MC_OK, "%s", err.msg);
    /* spacing = XReal / XRes in the XY unit (um); heights in the Z unit (nm); dx = 2 um != dy =
     * 2.5 um (and XRes != YRes), so a reader that swaps the axes is seen */
    ck_assert(r.nx == 3 && r.ny == 2 && r.missing == 1);
    ck_assert_msg(r.dx == 6 * 1e-6 / 3 && r.dy == 5 * 1e-6 / 2, "dx %g, dy %g", r.dx, r.dy);
    ck_assert(r.x0 == -1 * 1e-6 && r.y0 == 2.5 * 1e-6);
    double want[6];
    for (int k = 0; k < 6; k++)
        want[k] = (double)v[k] * 1e-9;
    tk_assert_heights(&r, want, 6);
    mc_surface_data_free(&r);
}
END_TEST

START_TEST(test_txt)
{
    const char *text = "# a text matrix in micrometres\n1 2 nan\n4 5e-1 6\n";
    mc_surface_read_options o = mc_surface_read_defaults();
    o.units = 1e-6;
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(mc_surface_parse_buffer("txt", (const unsigned char *)text, strlen(text),
                                          "h.txt", &o, &r, &err) == MC_OK,
                  "%s", err.msg);
    const double want[6] = {1 * 1e-6, 2 * 1e-6, NAN, 4 * 1e-6, 5e-1 * 1e-6, 6 * 1e-6};
    ck_assert(r.nx == 3 && r.ny == 2 && r.dx == 0 && r.dy == 0 && r.missing == 1);
    tk_assert_heights(&r, want, 6);
    mc_surface_data_free(&r);
}
END_TEST

START_TEST(test_xyz_shuffled)
{
    /* 4 x 3 grid in micrometres, x0 = 10, y0 = -5, dx = 2, dy = 3; point (2, 1) absent; lines
     * in a scrambled order (stride 7 through 11 points), 6 significant digits, mixed separators */
    enum { NX = 4, NY = 3 };
    char text[2048];
    size_t p = (size_t)snprintf(text, sizeof text, "# x y z [um]\n");
    int order[NX * NY - 1], n = 0;
    for (int k = 0; k < NX * NY; k++)
        if (k != 1 * NX + 2)
            order[n++] = k;
    for (int q = 0; q < n; q++) {
        int k = order[(q * 7) % n], i = k % NX, j = k / NX;
        p += (size_t)snprintf(text + p, sizeof text - p, q % 2 ? "%.6g, %.6g, %.6g\n"
                                                                : "%.6g\t%.6g %.6g\n",
                              10.0 + 2.0 * i, -5.0 + 3.0 * j, 0.1 * i + j);
    }
    mc_surface_read_options o = mc_surface_read_defaults();
    o.units = 1e-6;
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(mc_surface_parse_buffer("xyz", (const unsigned char *)text, p, "g.xyz", &o, &r,
                                          &err) == MC_OK,
                  "%s", err.msg);
    ck_assert_int_eq(r.nx, NX);
    ck_assert_int_eq(r.ny, NY);
    /* the extent 6 um over 3 cells is exact in binary: spacing and origin come out exact */
    ck_assert(r.dx == 6.0 / 3 * 1e-6 && r.dy == 6.0 / 2 * 1e-6);
    ck_assert(r.x0 == 10 * 1e-6 && r.y0 == -5 * 1e-6);
    ck_assert_int_eq(r.missing, 1);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            /* "%.6g" prints 0.1*i + j exactly as a short decimal, which strtod reads back to
             * within an ulp of the double computed here: TOL_TIGHT relative covers it */
            double want = (0.1 * i + j) * 1e-6;
            if (j == 1 && i == 2)
                ck_assert(!r.valid[j * NX + i] && isnan(r.z[j * NX + i]));
            else
                ck_assert_msg(fabs(r.z[j * NX + i] - want) <= TOL_TIGHT * 1e-6, "(%d,%d)", i, j);
        }
    mc_surface_data_free(&r);
}
END_TEST

/* ---- npy in every dtype, byte order and memory order ---------------------------------------- */

START_TEST(test_npy_layouts)
{
    static const char *const dtypes[] = {"<f2", ">f2", "<f4", ">f4", "<f8", ">f8", "|i1", "<i1",
                                         "<i2", ">i2", "<i4", ">i4", "<i8", ">i8", "|u1", "<u2",
                                         ">u2", "<u4", ">u4", "<u8", ">u8"};
    const int nd = (int)(sizeof dtypes / sizeof dtypes[0]);
    const char *dt = dtypes[_i % nd];
    int fortran = _i / nd % 2, one_d = _i / (2 * nd);
    char kind = dt[1];
    size_t size = (size_t)(dt[2] - '0');
    int big = dt[0] == '>';
    const double vals[6] = {1.5, -2.25, 3, 4, 100, -6}; /* exact in every float type */
    const double uvals[6] = {1, 2, 3, 4, 100, 200};
    const double ivals[6] = {1, -2, 3, 4, 100, -6};
    const double *v = kind == 'f' ? vals : kind == 'u' ? uvals : ivals;
    unsigned char img[512];
    char dict[128];
    snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': %s, 'shape': %s, }", dt,
             fortran ? "True" : "False", one_d ? "(6,)" : "(2, 3)");
    size_t p = tk_npy_header(img, dict);
    for (int k = 0; k < 6; k++) {
        /* element (r, c) of the 2 x 3 array at r*3 + c (C) or c*2 + r (Fortran) */
        int r = k / 3, c = k % 3, at = one_d || !fortran ? k : c * 2 + r;
        tk_put_value(img + p + (size_t)at * size, v[k], kind, size, big);
    }
    p += 6 * size;
    mc_surface_data s;
    mc_error err = {0};
    ck_assert_msg(tk_parse("npy", img, p, &s, &err) == MC_OK, "%s: %s", dict, err.msg);
    ck_assert_int_eq(s.nx, one_d ? 6 : 3);
    ck_assert_int_eq(s.ny, one_d ? 1 : 2);
    ck_assert(s.dx == 0 && s.dy == 0 && s.missing == 0);
    for (int k = 0; k < 6; k++)
        ck_assert_msg(s.z[k] == v[k], "%s k=%d: %g", dict, k, s.z[k]);
    mc_surface_data_free(&s);
}
END_TEST

/* ---- allocation failures: every path frees what it took -------------------------------------- */

START_TEST(test_fault_injection)
{
    static double z[12] = {1, 2, NAN, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    mc_surface_data s = {4, 3, 1e-6, 1e-6, 0, 0, z, NULL, 0, "", ""}, r;
    mc_error err = {0};
    const char *files[3] = {tk_path("fault.x3p"), tk_path("fault.xyz"), tk_path("fault.txt")};
    ck_assert_int_eq(mc_x3p_write(files[0], &s, NULL, &err), MC_OK);
    tk_write(files[1], "0 0 1\n1 0 2\n0 1 3\n1 1 nan\n", 26);
    tk_write(files[2], "1 2\n3 nan\n", 10);
    for (int f = 0; f < 3; f++) {
        int ok = 0;
        for (long n = 1; n < 60 && !ok; n++) {
            mc_alloc_fail_at(n);
            int st = mc_surface_file_read(files[f], NULL, &r, &err);
            mc_alloc_fail_at(0);
            ck_assert_msg(st == MC_OK || st == MC_ERR_NOMEM, "%s n=%ld: %s", files[f], n,
                          err.msg);
            if (st == MC_OK) {
                ck_assert_int_eq(r.missing, 1);
                mc_surface_data_free(&r);
                ok = 1;
            } else {
                ck_assert(r.z == NULL && r.valid == NULL);
            }
        }
        ck_assert_msg(ok, "%s: never succeeded", files[f]);
    }
    ck_assert_int_eq(mc_x3p_write(tk_path("fault2.x3p"), &s, NULL, &err), MC_OK);
    for (long n = 1; n < 6; n++) { /* the writer's three allocations */
        mc_alloc_fail_at(n);
        int st = mc_x3p_write(tk_path("fault3.x3p"), &s, NULL, &err);
        mc_alloc_fail_at(0);
        ck_assert(st == MC_OK || (st == MC_ERR_NOMEM && !tk_exists(tk_path("fault3.x3p"))));
    }
}
END_TEST

Suite *suite_surface_file(void);
Suite *suite_surface_file(void)
{
    Suite *s = suite_create("surface_file");
    TCase *tc = tcase_create("readers");
    tcase_add_test(tc, test_x3p_roundtrip);
    tcase_add_test(tc, test_x3p_write_refusals);
    tcase_add_test(tc, test_md5_vector);
    tcase_add_loop_test(tc, test_x3p_types, 0, 4);
    tcase_add_test(tc, test_sdf_ascii);
    tcase_add_loop_test(tc, test_sdf_binary, 0, 3);
    tcase_add_test(tc, test_gsf);
    tcase_add_test(tc, test_txt);
    tcase_add_test(tc, test_xyz_shuffled);
    tcase_add_loop_test(tc, test_npy_layouts, 0, 21 * 3);
    tcase_add_test(tc, test_fault_injection);
    suite_add_tcase(s, tc);
    return s;
}
