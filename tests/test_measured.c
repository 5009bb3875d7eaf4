/* test_measured.c - a measured map made ready for a run (surface/measured.h) and the case
 * reader's mesh from the file: size and spacing taken over, region, missing points, levelling,
 * scale and inversion, resampling, and the errors that name both grids. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case/case.h"
#include "core/alloc.h"
#include "io/surface_file.h"
#include "surface/measured.h"
#include "test_util.h"

/* An X3P of nx x ny points of dx x dy holding z = a + b x + c y + ripple, with one NaN when
 * hole >= 0; returns its path. */
static const char *write_map(const char *name, int nx, int ny, double dx, double dy, int hole)
{
    static char path[4][512];
    static int slot;
    char *p = path[slot++ % 4];
    snprintf(p, 512, "%s/%s", test_tmpdir(), name);
    size_t n = (size_t)nx * (size_t)ny;
    double *z = mc_zeros(n);
    unsigned char *v = mc_calloc(n, 1);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * nx + i;
            z[k] = 1e-6 + 2e-3 * i * dx - 1e-3 * j * dy + 0.2e-6 * sin(2 * M_PI * i / 8.0);
            v[k] = 1;
        }
    if (hole >= 0) {
        z[hole] = NAN;
        v[hole] = 0;
    }
    mc_surface_data s = {.nx = nx, .ny = ny, .dx = dx, .dy = dy, .z = z, .valid = v,
                         .missing = hole >= 0};
    mc_error err = {0};
    ck_assert_msg(mc_x3p_write(p, &s, "test", &err) == MC_OK, "%s", err.msg);
    mc_free(z);
    mc_free(v);
    return p;
}

static int parse(const char *text, mc_scene *s, mc_error *err)
{
    return mc_case_parse_text(text, "m.ini", "", 0, NULL, s, err);
}

START_TEST(mesh_from_the_file)
{
    const char *f = write_map("a.x3p", 24, 10, 0.8e-6, 1.1e-6, -1);
    char text[1024];
    snprintf(text, sizeof text,
             "[mesh]\n[roughness]\ntype = file\nfile = %s\n[load]\nforce = 1 mN\n", f);
    mc_scene s;
    mc_error err = {0};
    ck_assert_msg(parse(text, &s, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(s.grid.nx, 24);
    ck_assert_int_eq(s.grid.ny, 10);
    ck_assert_double_eq(s.grid.dx, 0.8e-6);
    ck_assert_double_eq(s.grid.dy, 1.1e-6);
    /* the mesh's own dx overrides the file's spacing (the run then needs resample = linear) */
    snprintf(text, sizeof text,
             "[mesh]\ndx = 1 um\n[roughness]\ntype = file\nfile = %s\n[load]\nforce = 1 mN\n", f);
    ck_assert_msg(parse(text, &s, &err) == MC_OK, "%s", err.msg);
    ck_assert_double_eq(s.grid.dx, 1e-6);
    ck_assert_double_eq(s.grid.dy, 1e-6);
    /* nx without ny names the line */
    snprintf(text, sizeof text,
             "[mesh]\nnx = 24\n[roughness]\ntype = file\nfile = %s\n[load]\nforce = 1 mN\n", f);
    ck_assert_int_eq(parse(text, &s, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "m.ini:2:") && strstr(err.msg, "give both nx and ny"), "%s",
                  err.msg);
}
END_TEST

/* Levelling removes the plane exactly (the ripple's mean over whole periods is 0 along x); a
 * region crops; scale and invert act on the heights. */
START_TEST(prepare_the_map)
{
    const char *f = write_map("b.x3p", 32, 12, 1e-6, 1e-6, -1);
    mc_measured_spec ms = {.path = f, .verify_checksum = 1, .detrend = MC_DETREND_PLANE};
    mc_measured m;
    mc_error err = {0};
    ck_assert_msg(mc_measured_load(&ms, &m, &err) == MC_OK, "%s", err.msg);
    /* least squares: what was removed is a plane (its second differences vanish) and the rest
     * is orthogonal to 1, x and y (to round-off of the 1e-6 m heights) */
    double s1 = 0, sx = 0, sy = 0, d2 = 0;
    for (int j = 0; j < 12; j++)
        for (int i = 0; i < 32; i++) {
            double r = m.z[j * 32 + i];
            s1 += r;
            sx += r * i;
            sy += r * j;
            double raw = 1e-6 + 2e-3 * i * 1e-6 - 1e-3 * j * 1e-6 + 0.2e-6 * sin(2 * M_PI * i / 8.0);
            if (i > 0 && i < 31) {
                double rawm = 1e-6 + 2e-3 * (i - 1) * 1e-6 - 1e-3 * j * 1e-6 +
                              0.2e-6 * sin(2 * M_PI * (i - 1) / 8.0),
                       rawp = 1e-6 + 2e-3 * (i + 1) * 1e-6 - 1e-3 * j * 1e-6 +
                              0.2e-6 * sin(2 * M_PI * (i + 1) / 8.0);
                double dm = rawm - m.z[j * 32 + i - 1], d0 = raw - r, dp = rawp - m.z[j * 32 + i + 1];
                d2 = test_worst(d2, fabs(dp - 2 * d0 + dm));
            }
        }
    ck_assert_msg(fabs(s1) < 1e-18 && fabs(sx) < 1e-16 && fabs(sy) < 1e-16, "%g %g %g", s1, sx, sy);
    ck_assert_msg(d2 < 1e-20, "removed part is not a plane: %g", d2);
    mc_measured_free(&m);
    ms.detrend = MC_DETREND_NONE;
    ms.scale = 2;
    ms.invert = 1;
    ms.has_region = 1;
    ms.region[0] = 4e-6;
    ms.region[1] = 2e-6;
    ms.region[2] = 8e-6;
    ms.region[3] = 5e-6;
    ck_assert_msg(mc_measured_load(&ms, &m, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(m.grid.nx, 8);
    ck_assert_int_eq(m.grid.ny, 5);
    double want = -2 * (1e-6 + 2e-3 * 4e-6 - 1e-3 * 2e-6 + 0.2e-6 * sin(2 * M_PI * 4 / 8.0));
    ck_assert_msg(fabs(m.z[0] - want) <= 1e-15, "%g vs %g", m.z[0], want);
    mc_measured_free(&m);
}
END_TEST

START_TEST(missing_points)
{
    const char *f = write_map("c.x3p", 16, 16, 1e-6, 1e-6, 5 * 16 + 7);
    mc_measured_spec ms = {.path = f, .verify_checksum = 1, .missing = MC_MISSING_ERROR};
    mc_measured m;
    mc_error err = {0};
    ck_assert_int_eq(mc_measured_load(&ms, &m, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "c.x3p: 1 of 256 points are missing") &&
                      strstr(err.msg, "row 5, column 7") && strstr(err.msg, "missing = fill"),
                  "%s", err.msg);
    ms.missing = MC_MISSING_FILL;
    ck_assert_msg(mc_measured_load(&ms, &m, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(m.missing, 1);
    ck_assert_int_eq(m.filled, 1);
    /* the filled point lies between its neighbours (harmonic) */
    double z = m.z[5 * 16 + 7], lo = fmin(m.z[5 * 16 + 6], m.z[5 * 16 + 8]),
           hi = fmax(m.z[5 * 16 + 6], m.z[5 * 16 + 8]);
    ck_assert(isfinite(z) && z >= fmin(lo, fmin(m.z[4 * 16 + 7], m.z[6 * 16 + 7])) - 1e-12 &&
              z <= fmax(hi, fmax(m.z[4 * 16 + 7], m.z[6 * 16 + 7])) + 1e-12);
    mc_measured_free(&m);
}
END_TEST

/* Onto a mesh: same size and spacing copies; another spacing is an error naming both unless
 * resample = linear, which reproduces a linear field exactly. */
START_TEST(onto_the_mesh)
{
    const int nx = 20, ny = 14;
    mc_measured m = {.grid = {nx, ny, 1e-6, 1e-6, 0, 0}, .path = "x.x3p"};
    m.z = mc_zeros((size_t)nx * ny);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            m.z[j * nx + i] = 3e-3 * (i - (nx - 1) / 2.0) * 1e-6 + 5e-4 * (j - (ny - 1) / 2.0) * 1e-6;
    mc_grid same = {nx, ny, 1e-6, 1e-6, 0, 0}, other = {16, 12, 1.1e-6, 1.05e-6, 0, 0};
    double h[20 * 14];
    mc_error err = {0};
    ck_assert_int_eq(mc_measured_onto(&m, &same, MC_RESAMPLE_NONE, h, &err), MC_OK);
    ck_assert_mem_eq(h, m.z, sizeof h);
    ck_assert_int_eq(mc_measured_onto(&m, &other, MC_RESAMPLE_NONE, h, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "x.x3p") && strstr(err.msg, "20 x 14 points of 1e-06 x 1e-06") &&
                      strstr(err.msg, "16 x 12 cells of 1.1e-06 x 1.05e-06"),
                  "%s", err.msg);
    ck_assert_msg(mc_measured_onto(&m, &other, MC_RESAMPLE_LINEAR, h, &err) == MC_OK, "%s",
                  err.msg);
    for (int j = 0; j < 12; j++)
        for (int i = 0; i < 16; i++) {
            double x = mc_grid_x(&other, i), y = mc_grid_y(&other, j);
            double want = 3e-3 * x + 5e-4 * y;
            ck_assert_msg(fabs(h[j * 16 + i] - want) <= 1e-20, "(%d,%d): %g vs %g", i, j,
                          h[j * 16 + i], want);
        }
    mc_free(m.z);
}
END_TEST

Suite *suite_measured(void);
Suite *suite_measured(void)
{
    Suite *s = suite_create("measured");
    TCase *t = tcase_create("measured");
    tcase_add_test(t, mesh_from_the_file);
    tcase_add_test(t, prepare_the_map);
    tcase_add_test(t, missing_points);
    tcase_add_test(t, onto_the_mesh);
    suite_add_tcase(s, t);
    return s;
}
