/* test_x3p_compat.c - X3P files as other tools write them (issue 23, class 1), on small files
 * made here: members under one top-level folder (x3ptools), points listed in main.xml
 * (DataList, openGPS's samples), float heights with a CZ Increment other than 1 (ignored, as the
 * reference implementation does, with a warning naming the value), and offsets kept by the
 * writer. */
#include <check.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zip.h>

#include "core/alloc.h"
#include "io/surface_file.h"
#include "io/surface_formats.h"
#include "surface_file_testkit.h"
#include "test_util.h"

enum { NX = 3, NY = 2, N = NX * NY };
static const double raw[N] = {1.5e-6, -2.25e-6, 1e-9, 0.0, 7e-7, -1.25e-7};

static void put_doubles(unsigned char *data)
{
    for (int k = 0; k < N; k++)
        tk_put_value(data + 8 * k, raw[k], 'f', 8, 0);
}

START_TEST(test_top_level_folder)
{
    unsigned char data[N * 8];
    put_doubles(data);
    tk_x3p spec = tk_x3p_default('D', NX, NY);
    spec.folder = "scan_1/";
    const char *path = tk_path("folder.x3p");
    tk_make_x3p(path, &spec, data, sizeof data, NULL, 0);
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(mc_surface_file_read(path, NULL, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(r.nx, NX);
    ck_assert_int_eq(r.ny, NY);
    tk_assert_heights(&r, raw, N);
    ck_assert(r.dx == spec.dx && r.x0 == spec.x0 && r.y0 == spec.y0);
    ck_assert_str_eq(r.warning, "");
    mc_surface_data_free(&r);
    /* the checksums under the folder are still verified */
    spec.bad_data_md5 = 1;
    tk_make_x3p(path, &spec, data, sizeof data, NULL, 0);
    ck_assert_int_eq(mc_surface_file_read(path, NULL, &r, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "MD5 mismatch"));
}
END_TEST

/* main.xml with Record3/DataList: one Datum per point, an empty one not measured */
static const char *datalist_xml(char type, double zinc, double zoff, const char *data)
{
    static char xml[4096];
    snprintf(xml, sizeof xml,
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\n"
             "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>\n"
             "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment>"
             "<Offset>2e-6</Offset></CX>\n"
             "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment>"
             "<Offset>0</Offset></CY>\n"
             "<CZ><AxisType>A</AxisType><DataType>%c</DataType><Increment>%g</Increment>"
             "<Offset>%g</Offset></CZ></Axes></Record1>\n"
             "<Record3><MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ>"
             "</MatrixDimension>\n<DataList>%s</DataList></Record3>\n"
             "<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>\n"
             "</p:ISO5436_2>\n",
             type, zinc, zoff, data);
    return xml;
}

START_TEST(test_data_list)
{
    unsigned char dummy[8] = {0};
    tk_x3p spec = tk_x3p_default('D', NX, NY);
    spec.xml = datalist_xml('D', 1, 0,
                            "<Datum>1.5e-6</Datum><Datum>-2.25e-6</Datum><Datum>1e-9</Datum>\n"
                            "<Datum/><Datum> 7e-7 </Datum><Datum>-1.25e-7</Datum>");
    const char *path = tk_path("datalist.x3p");
    tk_make_x3p(path, &spec, dummy, sizeof dummy, NULL, 0);
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(mc_surface_file_read(path, NULL, &r, &err) == MC_OK, "%s", err.msg);
    const double want[N] = {1.5e-6, -2.25e-6, 1e-9, NAN, 7e-7, -1.25e-7};
    tk_assert_heights(&r, want, N);
    ck_assert_int_eq(r.missing, 1);
    ck_assert(r.dx == 1e-6 && r.dy == 2e-6 && r.x0 == 2e-6);
    mc_surface_data_free(&r);
    /* integer types: offset + increment * stored value */
    spec.xml = datalist_xml('I', 1e-9, 1e-6, "<Datum>1</Datum><Datum>-2</Datum><Datum>3</Datum>"
                                             "<Datum>4</Datum><Datum>5</Datum><Datum>6</Datum>");
    tk_make_x3p(path, &spec, dummy, sizeof dummy, NULL, 0);
    ck_assert_msg(mc_surface_file_read(path, NULL, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(r.z[1] == 1e-6 + 1e-9 * -2.0);
    mc_surface_data_free(&r);
    /* a count that does not match, and a Datum that is not a number, are named */
    spec.xml = datalist_xml('D', 1, 0, "<Datum>1</Datum><Datum>2</Datum>");
    tk_make_x3p(path, &spec, dummy, sizeof dummy, NULL, 0);
    ck_assert_int_eq(mc_surface_file_read(path, NULL, &r, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "DataList has 2 Datum elements"));
    spec.xml = datalist_xml('D', 1, 0, "<Datum>1</Datum><Datum>2</Datum><Datum>x</Datum>"
                                       "<Datum>4</Datum><Datum>5</Datum><Datum>6</Datum>");
    tk_make_x3p(path, &spec, dummy, sizeof dummy, NULL, 0);
    ck_assert_int_eq(mc_surface_file_read(path, NULL, &r, &err), MC_ERR_INPUT);
    ck_assert_ptr_nonnull(strstr(err.msg, "Datum 3 (row 0, column 2) is 'x', not a number"));
}
END_TEST

/* Float heights with Increment 1e-6: read as the reference implementation reads them (the
 * increment ignored, the offset kept) and a warning names the value */
START_TEST(test_float_increment)
{
    const char type = "FD"[_i];
    unsigned char data[N * 8];
    size_t elem = type == 'F' ? 4 : 8;
    for (int k = 0; k < N; k++)
        tk_put_value(data + elem * (size_t)k, raw[k], 'f', elem, 0);
    tk_x3p spec = tk_x3p_default(type, NX, NY);
    spec.zinc = 1e-6;
    spec.zoff = 0.5e-6;
    const char *path = tk_path("float_inc.x3p");
    tk_make_x3p(path, &spec, data, (size_t)N * elem, NULL, 0);
    mc_surface_data r;
    mc_error err = {0};
    ck_assert_msg(mc_surface_file_read(path, NULL, &r, &err) == MC_OK, "%s", err.msg);
    for (int k = 0; k < N; k++) {
        double stored = type == 'F' ? (double)(float)raw[k] : raw[k];
        ck_assert_msg(r.z[k] == 0.5e-6 + stored, "%c point %d: %.17g", type, k, r.z[k]);
    }
    ck_assert_ptr_nonnull(strstr(r.warning, "CZ Increment = 1e-06"));
    ck_assert_ptr_nonnull(strstr(r.warning, path));
    mc_surface_data_free(&r);
}
END_TEST

Suite *suite_x3p_compat(void);
Suite *suite_x3p_compat(void)
{
    Suite *s = suite_create("x3p_compat");
    TCase *tc = tcase_create("x3p");
    tcase_add_test(tc, test_top_level_folder);
    tcase_add_test(tc, test_data_list);
    tcase_add_loop_test(tc, test_float_increment, 0, 2);
    suite_add_tcase(s, tc);
    return s;
}
