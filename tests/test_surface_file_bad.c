/* test_surface_file_bad.c - the bad-file table of the measured-surface readers: each row writes
 * one broken file (made here byte by byte, or a good file cut short) and reads it through
 * mc_surface_file_read; the status must be the row's, the message one line that starts with the
 * file's path and names the problem, and *out empty. */
#include <check.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "io/npy.h"
#include "io/surface_file.h"
#include "surface_file_testkit.h"
#include "test_util.h"

/* A good 3 x 2 X3P of float64 heights, possibly altered by a spec tweak. */
static void good_x3p(const char *path, void (*tweak)(tk_x3p *))
{
    static const double z[6] = {1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6};
    tk_x3p sp = tk_x3p_default('D', 3, 2);
    if (tweak)
        tweak(&sp);
    tk_make_x3p(path, &sp, (const unsigned char *)z, sizeof z, NULL, 0);
}

static void t_bad_data_md5(tk_x3p *s) { s->bad_data_md5 = 1; }
static void t_bad_xml_md5(tk_x3p *s) { s->bad_xml_md5 = 1; }
static void t_no_main(tk_x3p *s) { s->no_main = 1; }
static void t_prf(tk_x3p *s) { s->feature = "PRF"; }
static void t_sizes(tk_x3p *s) { s->sizex = "4"; }
static void t_absurd(tk_x3p *s) { s->sizex = "100000", s->ny = 100000; }
static void t_overflow(tk_x3p *s) { s->sizex = "99999999999999999999999999"; }
static void t_negative(tk_x3p *s) { s->sizex = "-3"; }
static void t_link(tk_x3p *s) { s->data_link = "bindata/other.bin"; }
static void t_xxe(tk_x3p *s)
{
    s->prolog = "<!DOCTYPE ISO5436_2 [<!ENTITY xxe SYSTEM \"file:///etc/passwd\">]>\n";
}
static void t_lol(tk_x3p *s)
{
    s->prolog = "<!DOCTYPE ISO5436_2 [<!ENTITY a \"aaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;\">]>\n";
}
static void t_extdtd(tk_x3p *s)
{
    s->prolog = "<!DOCTYPE ISO5436_2 SYSTEM \"http://example.invalid/x3p.dtd\">\n";
}
static void t_badxml(tk_x3p *s) { s->xml = "<?xml version=\"1.0\"?>\n<ISO5436_2><Record1>\n"; }
static void t_root(tk_x3p *s) { s->xml = "<?xml version=\"1.0\"?>\n<html><body/></html>\n"; }

static void w_x3p(const char *p, void (*t)(tk_x3p *)) { good_x3p(p, t); }

static void w_truncated_x3p(const char *path, void (*t)(tk_x3p *))
{
    (void)t;
    good_x3p(path, NULL);
    unsigned char *b;
    size_t n;
    mc_error err = {0};
    ck_assert_int_eq(mc_io_read_file(path, &b, &n, &err), MC_OK);
    tk_write(path, b, n * 6 / 10);
    mc_free(b);
}

static const char *g_bytes; /* the bytes a text row writes */
static size_t g_len;
static void w_bytes(const char *path, void (*t)(tk_x3p *))
{
    (void)t;
    tk_write(path, g_bytes, g_len);
}

static void w_npy(const char *path, const char *dict, size_t data_bytes)
{
    unsigned char img[256];
    size_t n = tk_npy_header(img, dict);
    memset(img + n, 0, data_bytes);
    tk_write(path, img, n + data_bytes);
}

static void w_npy_c16(const char *path, void (*t)(tk_x3p *))
{
    (void)t;
    w_npy(path, "{'descr': '<c16', 'fortran_order': False, 'shape': (1,), }", 16);
}

static void w_npy_native(const char *path, void (*t)(tk_x3p *))
{
    (void)t;
    w_npy(path, "{'descr': '=f4', 'fortran_order': False, 'shape': (1,), }", 4);
}

typedef struct {
    const char *file;                      /* name in the temporary directory */
    void (*write)(const char *, void (*)(tk_x3p *));
    void (*tweak)(tk_x3p *);
    const char *bytes;                     /* for w_bytes */
    size_t len;                            /* for w_bytes; 0 = strlen(bytes) */
    int code;
    const char *expect;                    /* substring of the message */
} bad_row;

#define GSF_HEAD "Gwyddion Simple Field 1.0\n"
#define SDF_ASCII "aISO-1.0\nNumPoints = 3\nNumProfiles = 2\nXscale = 1e-6\nYscale = 1e-6\n" \
                  "Zscale = 1e-9\n*\n"

static const bad_row rows[] = {
    {"empty.x3p", w_bytes, NULL, "", 0, MC_ERR_INPUT, "empty file"},
    {"empty.sdf", w_bytes, NULL, "", 0, MC_ERR_INPUT, "empty file"},
    {"empty.gsf", w_bytes, NULL, "", 0, MC_ERR_INPUT, "empty file"},
    {"empty.txt", w_bytes, NULL, "", 0, MC_ERR_INPUT, "empty file"},
    {"empty.xyz", w_bytes, NULL, "", 0, MC_ERR_INPUT, "empty file"},
    {"empty.npy", w_bytes, NULL, "", 0, MC_ERR_INPUT, "empty file"},
    {"truncated.x3p", w_truncated_x3p, NULL, NULL, 0, MC_ERR_INPUT, "truncated or corrupt zip"},
    {"notzip.x3p", w_bytes, NULL, "hello, world\n", 0, MC_ERR_INPUT, "not a zip archive"},
    {"nomain.x3p", w_x3p, t_no_main, NULL, 0, MC_ERR_INPUT, "no main.xml"},
    {"md5data.x3p", w_x3p, t_bad_data_md5, NULL, 0, MC_ERR_INPUT,
     "MD5 mismatch: bindata/data.bin"},
    {"md5xml.x3p", w_x3p, t_bad_xml_md5, NULL, 0, MC_ERR_INPUT, "MD5 mismatch: main.xml"},
    {"xxe.x3p", w_x3p, t_xxe, NULL, 0, MC_ERR_INPUT, "declares XML entities"},
    {"lol.x3p", w_x3p, t_lol, NULL, 0, MC_ERR_INPUT, "declares XML entities"},
    {"extdtd.x3p", w_x3p, t_extdtd, NULL, 0, MC_ERR_INPUT, "external subset"},
    {"badxml.x3p", w_x3p, t_badxml, NULL, 0, MC_ERR_INPUT, "not well-formed XML"},
    {"root.x3p", w_x3p, t_root, NULL, 0, MC_ERR_INPUT, "not ISO5436_2"},
    {"prf.x3p", w_x3p, t_prf, NULL, 0, MC_ERR_INPUT, "feature type 'PRF' not supported"},
    {"sizes.x3p", w_x3p, t_sizes, NULL, 0, MC_ERR_INPUT, "sizes do not match the data"},
    {"absurd.x3p", w_x3p, t_absurd, NULL, 0, MC_ERR_INPUT, "absurd dimensions"},
    {"overflow.x3p", w_x3p, t_overflow, NULL, 0, MC_ERR_INPUT, "absurd dimensions"},
    {"negative.x3p", w_x3p, t_negative, NULL, 0, MC_ERR_INPUT, "need at least 1 x 1"},
    {"link.x3p", w_x3p, t_link, NULL, 0, MC_ERR_INPUT, "not in the archive"},
    {"foreign.npy", w_bytes, NULL, "GIF89a\x01\x00\x01\x00", 0, MC_ERR_INPUT,
     "not a NumPy .npy file"},
    {"complex.npy", w_npy_c16, NULL, NULL, 0, MC_ERR_INPUT, "dtype '<c16' not supported"},
    {"order.npy", w_npy_native, NULL, NULL, 0, MC_ERR_INPUT, "has no byte order"},
    {"notgsf.gsf", w_bytes, NULL, "Gwyddion Simple Field 2.0\nXRes = 1\n", 0, MC_ERR_INPUT,
     "not a Gwyddion Simple Field"},
    {"trunc.gsf", w_bytes, NULL, GSF_HEAD "XRes = 3\nYRes = 2\n\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0",
     44 + 16, MC_ERR_INPUT, "truncated"},
    {"absurd.gsf", w_bytes, NULL, GSF_HEAD "XRes = 1000000\nYRes = 1000000\n\0\0\0\0", 60,
     MC_ERR_INPUT, "absurd dimensions"},
    {"nores.gsf", w_bytes, NULL, GSF_HEAD "XRes = 3\n\0\0\0", 38, MC_ERR_INPUT, "no YRes"},
    {"units.gsf", w_bytes, NULL, GSF_HEAD "XRes = 1\nYRes = 1\nZUnits = V\n\0\0", 57,
     MC_ERR_INPUT, "not a length unit"},
    {"notsdf.sdf", w_bytes, NULL, "hello", 0, MC_ERR_INPUT, "not an SDF file"},
    {"count.sdf", w_bytes, NULL, SDF_ASCII "1 2 3\n4 5\n*\n", 0, MC_ERR_INPUT,
     "the data section has 5"},
    {"noscale.sdf", w_bytes, NULL, "aISO-1.0\nNumPoints = 1\nNumProfiles = 1\n*\n1\n", 0,
     MC_ERR_INPUT, "has no Xscale"},
    {"trunc.sdf", w_bytes, NULL, "bISO-1.0", 8, MC_ERR_INPUT, "truncated binary SDF"},
    /* issue 23 class 6: a bad spacing or height names the file and what in it is wrong */
    {"negdx.sdf", w_bytes, NULL,
     "aISO-1.0\nNumPoints = 2\nNumProfiles = 1\nXscale = -1e-6\nYscale = 1e-6\nZscale = 1e-9\n*\n1 2\n*\n",
     0, MC_ERR_INPUT, "SDF Xscale -1e-06"},
    {"hugedy.sdf", w_bytes, NULL,
     "aISO-1.0\nNumPoints = 2\nNumProfiles = 1\nXscale = 1e-6\nYscale = 1e9\nZscale = 1e-9\n*\n1 2\n*\n",
     0, MC_ERR_INPUT, "dy = 1e+09 m (Xscale/Yscale): it must be finite, > 0 and <= 1 m"},
    {"zerodx.xyz", w_bytes, NULL, "0 0 1\n1e-300 0 1\n0 1e-6 1\n1e-300 1e-6 1\n", 0,
     MC_ERR_INPUT, "(the step of the x/y coordinates)"},
    {"hugez.sdf", w_bytes, NULL,
     "aISO-1.0\nNumPoints = 2\nNumProfiles = 1\nXscale = 1e-6\nYscale = 1e-6\nZscale = 1\n*\n1 1e300\n*\n",
     0, MC_ERR_INPUT, "the height 1e+300 m at row 0, column 1 is more than 1000 times"},
    {"hugez.txt", w_bytes, NULL, "1 2\n3 -1e300\n", 0, MC_ERR_INPUT,
     "the height -1e+300 m at row 1, column 1"},
    {"hugez.xyz", w_bytes, NULL, "0 0 1\n1e-6 0 1e200\n", 0, MC_ERR_INPUT,
     "the height 1e+200 m at row 0, column 1"},
    {"irregular.xyz", w_bytes, NULL, "0 0 1\n1 0 1\n2.3 0 1\n", 0, MC_ERR_INPUT,
     "irregular grid: x = 1 is not on the grid"},
    {"sparse.xyz", w_bytes, NULL, "0 0 1\n1 0 1\n100 0 1\n", 0, MC_ERR_INPUT,
     "less than half"},
    {"dup.xyz", w_bytes, NULL, "0 0 1\n1 0 1\n0 0 2\n", 0, MC_ERR_INPUT, ":3: grid point"},
    {"nanxy.xyz", w_bytes, NULL, "0 0 1\nnan 0 1\n", 0, MC_ERR_INPUT, ":2: x and y must be"},
    {"two.xyz", w_bytes, NULL, "0 0 1\n1 0\n", 0, MC_ERR_INPUT, ":2: 2 values"},
    {"ragged.txt", w_bytes, NULL, "1 2\n3\n", 0, MC_ERR_INPUT, "same number of columns"},
    {"word.txt", w_bytes, NULL, "1 2\n3 x\n", 0, MC_ERR_INPUT, ":2: 'x' is not a number"},
    {"unknown.abc", w_bytes, NULL, "1\n", 0, MC_ERR_INPUT, "cannot tell the surface format"},
};

START_TEST(test_bad_file)
{
    const bad_row *row = &rows[_i];
    const char *path = tk_path(row->file);
    g_bytes = row->bytes;
    g_len = row->bytes && row->len == 0 ? strlen(row->bytes) : row->len;
    row->write(path, row->tweak);
    mc_surface_data out;
    memset(&out, 0xab, sizeof out); /* must come back empty */
    mc_error err = {0};
    int st = mc_surface_file_read(path, NULL, &out, &err);
    ck_assert_msg(st == row->code, "%s: status %d, want %d: %s", row->file, st, row->code,
                  err.msg);
    ck_assert_int_eq(err.code, row->code);
    ck_assert_msg(strncmp(err.msg, path, strlen(path)) == 0, "message does not name the file: %s",
                  err.msg);
    ck_assert_msg(strstr(err.msg, row->expect) != NULL, "%s: want '%s' in: %s", row->file,
                  row->expect, err.msg);
    ck_assert_msg(strchr(err.msg, '\n') == NULL, "not one line: %s", err.msg);
    ck_assert(out.z == NULL && out.valid == NULL && out.nx == 0 && out.missing == 0);
}
END_TEST

/* The rows' files are refused for the reason the row says, not for another: the same files
 * minus the defect are read (checksum rows with verification off; the others as good files). */
START_TEST(test_checksum_off_and_controls)
{
    mc_surface_read_options o = mc_surface_read_defaults();
    mc_surface_data out;
    mc_error err = {0};
    void (*md5_tweaks[2])(tk_x3p *) = {t_bad_data_md5, t_bad_xml_md5};
    for (int k = 0; k < 2; k++) {
        good_x3p(tk_path("md5off.x3p"), md5_tweaks[k]);
        o.verify_checksum = 0;
        ck_assert_msg(mc_surface_file_read(tk_path("md5off.x3p"), &o, &out, &err) == MC_OK, "%s",
                      err.msg);
        ck_assert_int_eq(out.nx * out.ny, 6);
        mc_surface_data_free(&out);
        o.verify_checksum = 1;
        ck_assert_int_eq(mc_surface_file_read(tk_path("md5off.x3p"), &o, &out, &err),
                         MC_ERR_INPUT);
    }
    good_x3p(tk_path("good.x3p"), NULL);
    ck_assert_msg(mc_surface_file_read(tk_path("good.x3p"), NULL, &out, &err) == MC_OK, "%s",
                  err.msg);
    mc_surface_data_free(&out);
    /* a bare DOCTYPE without entities or external subset is harmless and accepted */
    tk_x3p sp = tk_x3p_default('D', 3, 2);
    sp.prolog = "<!DOCTYPE ISO5436_2>\n";
    static const double z[6] = {1, 2, 3, 4, 5, 6};
    tk_make_x3p(tk_path("doctype.x3p"), &sp, (const unsigned char *)z, sizeof z, NULL, 0);
    ck_assert_msg(mc_surface_file_read(tk_path("doctype.x3p"), NULL, &out, &err) == MC_OK, "%s",
                  err.msg);
    mc_surface_data_free(&out);
    /* a file that does not exist: an I/O error naming it */
    ck_assert_int_eq(mc_surface_file_read(tk_path("missing.x3p"), NULL, &out, &err), MC_ERR_IO);
    ck_assert_msg(strstr(err.msg, "missing.x3p: cannot open"), "%s", err.msg);
    /* format named explicitly overrides the extension */
    o.format = "xyz";
    tk_write(tk_path("points.dat"), "0 0 1\n1 0 2\n", 12);
    ck_assert_msg(mc_surface_file_read(tk_path("points.dat"), &o, &out, &err) == MC_OK, "%s",
                  err.msg);
    ck_assert(out.nx == 2 && out.ny == 1 && out.dx == 1.0);
    mc_surface_data_free(&out);
}
END_TEST

Suite *suite_surface_file_bad(void);
Suite *suite_surface_file_bad(void)
{
    Suite *s = suite_create("surface_file_bad");
    TCase *tc = tcase_create("bad_files");
    tcase_add_loop_test(tc, test_bad_file, 0, (int)(sizeof rows / sizeof rows[0]));
    tcase_add_test(tc, test_checksum_off_and_controls);
    suite_add_tcase(s, tc);
    return s;
}
