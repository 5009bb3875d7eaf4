/* test_case.c - case files -> scene: valid cases round-trip every key into SI values, a table of
 * malformed inputs gives precise messages, --set overrides, relative paths, the generated
 * reference equals docs/case-format.md; and the scene module (defaults, rules, depths). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "case/case.h"
#include "case/scene.h"
#include "test_util.h"

#define NAME "cases/t.ini"

static int parse(const char *text, int nov, const char *const *ov, mc_scene *s, mc_error *err)
{
    mc_error_clear(err);
    return mc_case_parse_text(text, NAME, "cases", nov, ov, s, err);
}

/* a and b agree to round-off (the unit factors are exact to a few ulps) */
#define EQ(a, b)                                                                                   \
    ck_assert_msg(fabs((a) - (b)) <= TOL_TIGHT * fabs(b), "%s = %.17g, expected %.17g", #a,        \
                  (double)(a), (double)(b))

static void parse_ok(const char *text, int nov, const char *const *ov, mc_scene *s)
{
    mc_error err;
    int rc = parse(text, nov, ov, s, &err);
    ck_assert_msg(rc == MC_OK, "rc %d: %s", rc, err.msg);
}

/* ---- valid cases: every key round-trips ------------------------------------------------------ */

static const char case_a[] = "[mesh]\n"
                             "nx = 128\n"
                             "ny = 96\n"
                             "dx = 0.5 um\n"
                             "dy = 250 nm\n"
                             "periodic_x = yes\n"
                             "periodic_y = no\n"
                             "[geometry]\n"
                             "shape = ellipsoid\n"
                             "radius_x = 12 mm\n"
                             "radius_y = 0.02 m\n"
                             "[roughness]\n"
                             "type = gaussian\n"
                             "rq = 0.1 um\n"
                             "correlation_x = 2 um\n"
                             "correlation_y = 3 \xc2\xb5m\n"
                             "seed = 18446744073709551615\n"
                             "[body1]\n"
                             "E = 200 GPa\n"
                             "nu = 0.29\n"
                             "[body2]\n"
                             "rigid = no\n"
                             "E = 70000 MPa\n"
                             "nu = 0.33\n"
                             "[load]\n"
                             "force = 1.5 kN\n"
                             "lubricant_pressure = 2 MPa\n"
                             "pressure_cap = 3 GPa\n"
                             "[solver]\n"
                             "operator = direct\n"
                             "method = active-set\n"
                             "tolerance = 1e-10\n"
                             "max_iterations = 500\n"
                             "threads = 4\n"
                             "[stress]\n"
                             "enabled = yes\n"
                             "depth_min = 0.1 um\n"
                             "depth_max = 20 um\n"
                             "layers = 16\n"
                             "spacing = geometric\n"
                             "kernel = point\n"
                             "friction = 0.25\n"
                             "[output]\n"
                             "dir = results/a\n"
                             "vtk = yes\n";

START_TEST(test_case_a)
{
    mc_scene s;
    parse_ok(case_a, 0, NULL, &s);
    ck_assert_str_eq(s.path, NAME);
    ck_assert_int_eq(s.grid.nx, 128);
    ck_assert_int_eq(s.grid.ny, 96);
    EQ(s.grid.dx, 0.5e-6);
    EQ(s.grid.dy, 250e-9);
    ck_assert_int_eq(s.grid.periodic_x, 1);
    ck_assert_int_eq(s.grid.periodic_y, 0);
    ck_assert_int_eq(s.geometry.shape, MC_SHAPE_ELLIPSOID);
    EQ(s.geometry.radius_x, 12e-3);
    EQ(s.geometry.radius_y, 0.02);
    ck_assert_int_eq(s.roughness.type, MC_ROUGH_GAUSSIAN);
    EQ(s.roughness.rq, 0.1e-6);
    EQ(s.roughness.correlation_x, 2e-6);
    EQ(s.roughness.correlation_y, 3e-6);
    ck_assert(s.roughness.seed == UINT64_MAX);
    EQ(s.body1.E, 200e9);
    EQ(s.body1.nu, 0.29);
    ck_assert_int_eq(s.body2.rigid, 0);
    EQ(s.body2.E, 70e9);
    EQ(s.body2.nu, 0.33);
    ck_assert_int_eq(s.load.kind, MC_LOAD_FORCE);
    EQ(s.load.value, 1500.0);
    EQ(s.load.lubricant_pressure, 2e6);
    EQ(s.load.pressure_cap, 3e9);
    ck_assert_int_eq(s.solver.backend, MC_BACKEND_DIRECT);
    ck_assert_int_eq(s.solver.method, MC_METHOD_ACTIVE_SET);
    EQ(s.solver.tolerance, 1e-10);
    ck_assert_int_eq(s.solver.max_iterations, 500);
    ck_assert_int_eq(s.solver.threads, 4);
    ck_assert_int_eq(s.stress.enabled, 1);
    EQ(s.stress.depth_min, 0.1e-6);
    EQ(s.stress.depth_max, 20e-6);
    ck_assert_int_eq(s.stress.layers, 16);
    ck_assert_int_eq(s.stress.spacing, MC_SPACING_GEOMETRIC);
    ck_assert_int_eq(s.stress.kernel, MC_STRESS_POINT);
    EQ(s.stress.friction, 0.25);
    ck_assert_str_eq(s.output.dir, "results/a");
    ck_assert_int_eq(s.output.vtk, 1);
}
END_TEST

static const char case_b[] = "# line contact on a periodic strip\n"
                             "[mesh]\n"
                             "nx = 64\n"
                             "ny = 32\n"
                             "dx = 1 um\n"
                             "periodic_y = true\n"
                             "[geometry]\n"
                             "shape = cylinder\n"
                             "radius = 5 mm\n"
                             "[roughness]\n"
                             "type = self_affine\n"
                             "hurst = 0.7\n"
                             "rq = 50 nm\n"
                             "lambda_long = 32 um\n"
                             "lambda_short = 4 um\n"
                             "seed = 7\n"
                             "[body2]\n"
                             "rigid = yes\n"
                             "[load]\n"
                             "force_per_length = 500 N/mm\n"
                             "[stress]\n"
                             "depths = 0 um, 0.5 um,   ; first line\n"
                             "   1.3 um, 2 um\n"
                             "   ; a comment line between\n"
                             "\t4 um\n"
                             "kernel = patch\n";

START_TEST(test_case_b)
{
    mc_scene s;
    parse_ok(case_b, 0, NULL, &s);
    EQ(s.grid.dy, 1e-6); /* default: dx */
    ck_assert_int_eq(s.grid.periodic_x, 0);
    ck_assert_int_eq(s.grid.periodic_y, 1);
    ck_assert_int_eq(s.geometry.shape, MC_SHAPE_CYLINDER);
    EQ(s.geometry.radius, 5e-3);
    ck_assert_int_eq(s.roughness.type, MC_ROUGH_SELF_AFFINE);
    EQ(s.roughness.hurst, 0.7);
    EQ(s.roughness.rq, 50e-9);
    ck_assert(s.roughness.rms_slope == 0);
    EQ(s.roughness.lambda_long, 32e-6);
    EQ(s.roughness.lambda_short, 4e-6);
    ck_assert(s.roughness.seed == 7);
    ck_assert_int_eq(s.body2.rigid, 1);
    ck_assert_int_eq(s.load.kind, MC_LOAD_FORCE_PER_LENGTH);
    EQ(s.load.value, 5e5);
    ck_assert(isinf(s.load.pressure_cap));
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert_int_eq(s.stress.spacing, MC_SPACING_LIST);
    ck_assert_int_eq(s.stress.ndepths, 5);
    const double z[] = {0, 0.5e-6, 1.3e-6, 2e-6, 4e-6};
    for (int k = 0; k < 5; k++)
        EQ(s.stress.depths[k], z[k]);
    ck_assert_str_eq(s.output.dir, "out/t");
    /* untouched keys keep the documented defaults */
    EQ(s.body1.E, 210e9);
    EQ(s.body1.nu, 0.3);
    ck_assert_int_eq(s.solver.max_iterations, 2000);
    EQ(s.solver.tolerance, 1e-8);
    ck_assert_int_eq(s.solver.backend, MC_BACKEND_FFT);
    ck_assert_int_eq(s.solver.method, MC_METHOD_CG);
}
END_TEST

static const char case_c[] = "[mesh]\n"
                             "nx = 16\n"
                             "ny = 16\n"
                             "dx = 2 um\n"
                             "[geometry]\n"
                             "shape = sphere\n"
                             "radius = 1 mm\n"
                             "[roughness]\n"
                             "type = file\n"
                             "file = data/heights.npy\n"
                             "[load]\n"
                             "pressure_file = /abs/p.npy\n"
                             "[stress]\n"
                             "depth_max = 10 um\n";

START_TEST(test_case_c)
{
    mc_scene s;
    parse_ok(case_c, 0, NULL, &s);
    ck_assert_int_eq(s.geometry.shape, MC_SHAPE_SPHERE);
    ck_assert_int_eq(s.roughness.type, MC_ROUGH_FILE);
    ck_assert_str_eq(s.roughness.file, "cases/data/heights.npy");
    ck_assert_int_eq(s.load.kind, MC_LOAD_PRESSURE_FILE);
    ck_assert_str_eq(s.load.pressure_file, "/abs/p.npy");
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert_int_eq(s.stress.layers, 32);
    ck_assert_int_eq(s.stress.spacing, MC_SPACING_LINEAR);
    ck_assert(s.stress.depth_min == 0);
    EQ(s.stress.depth_max, 10e-6);
    ck_assert_int_eq(s.stress.kernel, MC_STRESS_PATCH);
}
END_TEST

static const char case_d[] = "\xef\xbb\xbf[mesh]\r\n" /* a BOM and CRLF line ends */
                             "nx = 8\r\n"
                             "ny = 8\r\n"
                             "dx = 1 mm\r\n"
                             "dy = 1 mm\r\n"
                             "[roughness]\r\n"
                             "type = self_affine\r\n"
                             "rms_slope = 0.05\r\n"
                             "[load]\r\n"
                             "approach = 1.5 um ; inline comment\r\n"
                             "[stress]\r\n"
                             "enabled = no\r\n";

START_TEST(test_case_d)
{
    mc_scene s;
    parse_ok(case_d, 0, NULL, &s);
    ck_assert_int_eq(s.geometry.shape, MC_SHAPE_FLAT);
    EQ(s.roughness.rms_slope, 0.05);
    ck_assert(s.roughness.rq == 0);
    EQ(s.roughness.hurst, 0.8);
    ck_assert(s.roughness.seed == 1);
    ck_assert_int_eq(s.load.kind, MC_LOAD_APPROACH);
    EQ(s.load.value, 1.5e-6);
    ck_assert_int_eq(s.stress.enabled, 0);
}
END_TEST

#define BASE "[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\nforce = 1 N\n" /* lines 1-6 */

START_TEST(test_sections_accumulate)
{
    mc_scene s;
    parse_ok("[mesh]\nnx = 8\n[load]\nforce = 1 N\n[mesh]\nny = 4\ndx = 1 um\n", 0, NULL, &s);
    ck_assert_int_eq(s.grid.nx, 8);
    ck_assert_int_eq(s.grid.ny, 4);
    /* no [stress] section: the stage is off */
    ck_assert_int_eq(s.stress.enabled, 0);
    /* an empty [stress] section with an explicit range turns it on */
    parse_ok(BASE "[stress]\n[solver]\n[stress]\ndepth_max = 1 um\n", 0, NULL, &s);
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert_int_eq(s.stress.window, MC_STRESS_WINDOW_AUTO);
    /* [stress] alone, or created by an override: depth_max = auto (from the contact) */
    parse_ok(BASE "[stress]\n", 0, NULL, &s);
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert(s.stress.depth_max == MC_STRESS_DEPTH_AUTO);
    const char *on[] = {"stress.enabled=yes", "stress.window=full"};
    parse_ok(BASE, 2, on, &s);
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert(s.stress.depth_max == MC_STRESS_DEPTH_AUTO);
    ck_assert_int_eq(s.stress.window, MC_STRESS_WINDOW_FULL);
    parse_ok(BASE "[stress]\ndepth_max = auto\nlayers = 8\n", 0, NULL, &s);
    ck_assert(s.stress.depth_max == MC_STRESS_DEPTH_AUTO);
    ck_assert_int_eq(s.stress.layers, 8);
}
END_TEST

START_TEST(test_line_limit_edge)
{
    /* 199 characters are inih's limit: exactly 199 pass, 200 fail */
    char text[600];
    for (int len = 199; len <= 200; len++) {
        snprintf(text, sizeof text, BASE "[output]\ndir = ");
        size_t n = strlen(text), head = strlen("dir = ");
        memset(text + n, 'd', (size_t)len - head);
        text[n + (size_t)len - head] = '\0';
        strcat(text, "\n");
        mc_scene s;
        mc_error err;
        int rc = parse(text, 0, NULL, &s, &err);
        if (len == 199) {
            ck_assert_msg(rc == MC_OK, "%s", err.msg);
            ck_assert_uint_eq(strlen(s.output.dir), 199 - head);
        } else {
            ck_assert_int_eq(rc, MC_ERR_INPUT);
            ck_assert_msg(strstr(err.msg, NAME ":8: line 8 is longer than 199 characters"), "%s",
                          err.msg);
        }
    }
}
END_TEST

START_TEST(test_depth_list_limit)
{
    /* 512 depths over continuation lines load; a 513th is refused */
    size_t cap = 20000;
    char *text = malloc(cap);
    ck_assert_ptr_nonnull(text);
    for (int total = 512; total <= 513; total++) {
        snprintf(text, cap, BASE "[stress]\ndepths = 0 nm");
        for (int k = 1; k < total; k++) {
            size_t n = strlen(text);
            snprintf(text + n, cap - n, "%s%d nm", k % 16 == 0 ? ",\n  " : ", ", k);
        }
        strcat(text, "\n");
        mc_scene s;
        mc_error err;
        int rc = parse(text, 0, NULL, &s, &err);
        if (total == 512) {
            ck_assert_msg(rc == MC_OK, "%s", err.msg);
            ck_assert_int_eq(s.stress.ndepths, 512);
            EQ(s.stress.depths[511], 511e-9);
        } else {
            ck_assert_int_eq(rc, MC_ERR_INPUT);
            ck_assert_msg(strstr(err.msg, NAME ":8: [stress] depths = ") &&
                              strstr(err.msg, "more than 512 depths"),
                          "%s", err.msg);
        }
    }
    free(text);
}
END_TEST

/* ---- malformed inputs ------------------------------------------------------------------------ */

typedef struct {
    const char *text;    /* NULL: the file does not exist */
    const char *want[4]; /* substrings of the message (file name and line, key, what is accepted) */
} bad_case;

#define X20 "xxxxxxxxxxxxxxxxxxxx"

static const bad_case bad[] = {
    {NULL, {NAME ": cannot open: "}},
    {"", {NAME ": empty case file"}},
    {"; only a comment\n\n   \n", {NAME ": empty case file"}},
    {"[meshh]\n",
     {NAME ":1: unknown section [meshh]; known sections: mesh, geometry, roughness, roughness2, body1, body2, "
           "load, solver, stress, lubrication, plasticity, output"}},
    {"[Mesh]\nnx = 3\n", {NAME ":1: unknown section [Mesh]", "known sections: mesh,"}},
    {BASE "[mesh]\nnxx = 3\n",
     {NAME ":8: [mesh] unknown key 'nxx'; keys of [mesh]: nx, ny, dx, dy, periodic_x, periodic_y"}},
    {BASE "[mesh]\nnx = 9\n", {NAME ":8: [mesh] nx given twice (first on line 2)"}},
    {"nx = 1\n" BASE, {NAME ":1: nx = 1 comes before any [section]", "known sections: mesh"}},
    {"[mesh]\nnx = 0\n", {NAME ":2: [mesh] nx = 0: must be an integer in 1..65536"}},
    {"[mesh]\nnx = 1.5\n", {NAME ":2: [mesh] nx = 1.5: must be an integer in 1..65536"}},
    {"[mesh]\nnx = 65537\n", {NAME ":2: [mesh] nx = 65537: must be an integer in 1..65536"}},
    {"[mesh]\nnx = 99999999999999999999\n", {NAME ":2: [mesh] nx = ", "1..65536"}},
    {"[mesh]\nnx = \n", {NAME ":2: [mesh] nx = : a value is required (an integer in 1..65536)"}},
    {"[mesh]\nnx = 4\nny = 4\ndx = abc\n",
     {NAME ":4: [mesh] dx = abc: 'abc' is not a number; a length is due (m, mm, um, nm)"}},
    {"[mesh]\nnx = 4\nny = 4\ndx = 3 xm\n",
     {NAME ":4: [mesh] dx = 3 xm: unknown unit 'xm'; a length is due (m, mm, um, nm)"}},
    {"[mesh]\nnx = 4\nny = 4\ndx = 3 N\n",
     {NAME ":4: [mesh] dx = 3 N: unit 'N' is a force; a length is due (m, mm, um, nm)"}},
    {"[mesh]\nnx = 4\nny = 4\ndx = -1 um\n",
     {NAME ":4: [mesh] dx = -1 um: must be a length > 0 and <= 1 m"}},
    {"[mesh]\nnx = 4\nny = 4\ndx = nan\n",
     {NAME ":4: [mesh] dx = nan: NaN and infinity are not accepted"}},
    {BASE "[body1]\nnu = 0.6\n", {NAME ":8: [body1] nu = 0.6: must be a number >= 0 and <= 0.5"}},
    {BASE "[body1]\nnu = 0.3 mm\n",
     {NAME ":8: [body1] nu = 0.3 mm: unit 'mm' is a length; a plain number is due (no unit)"}},
    {BASE "[body2]\nE = 0 GPa\n",
     {NAME ":8: [body2] E = 0 GPa: must be a pressure > 0 and <= 1e+13 Pa"}},
    {BASE "[body2]\nE = -5\n", {NAME ":8: [body2] E = -5: must be a pressure > 0"}},
    {"[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\nforce = 0 N\n",
     {NAME ":6: [load] force = 0 N: must be a force > 0"}},
    {"[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\napproach = -1 um\n",
     {NAME ":6: [load] approach = -1 um: must be a length > 0"}},
    {"[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\nforce = 3 MN\n",
     {NAME ":6: [load] force = 3 MN: unknown unit 'MN'; a force is due (N, kN, mN)"}},
    {BASE "approach = 1 um\n",
     {NAME ":7: [load] approach: give exactly one of force, force_per_length, approach, "
           "pressure_file (force is on line 6)"}},
    {"[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\nforce_per_length = 5 N/mm\n",
     {NAME ":6: [load] force_per_length needs [mesh] periodic_y = yes"}},
    {"[mesh]\nnx = 8\nny = 8\ndx = 1 um\n",
     {NAME ": [load] give exactly one of force, force_per_length, approach, pressure_file: none "
           "is given"}},
    {"[mesh]\nny = 8\ndx = 1 um\n[load]\nforce = 1 N\n",
     {NAME ": [mesh] nx is required (an integer in 1..65536)"}},
    {BASE "[geometry]\nradius = 1 mm\n",
     {NAME ":8: [geometry] radius is not used by shape = flat"}},
    {BASE "[geometry]\nshape = ellipsoid\nradius_x = 1 mm\nradius = 1 mm\nradius_y = 2 mm\n",
     {NAME ":10: [geometry] radius is not used by shape = ellipsoid"}},
    {BASE "[geometry]\nshape = sphere\n",
     {NAME ": [geometry] radius is required for shape = sphere (a length > 0)"}},
    {BASE "[geometry]\nshape = cube\n",
     {NAME ":8: [geometry] shape = cube: must be one of flat, sphere, cylinder, ellipsoid"}},
    {BASE "[roughness]\ntype = gaussian\nrq = 1 um\ncorrelation_x = 5 um\nhurst = 0.5\n",
     {NAME ":11: [roughness] hurst is not used by type = gaussian"}},
    {BASE "[roughness]\ntype = gaussian\ncorrelation_x = 5 um\n",
     {NAME ": [roughness] rq is required for type = gaussian (a length >= 0)"}},
    {BASE "[roughness]\ntype = self_affine\nrq = 1 um\nrms_slope = 0.1\n",
     {NAME ":10: [roughness] rms_slope: give exactly one of rq, rms_slope (rq is on line 9)"}},
    {BASE "[roughness]\ntype = self_affine\n",
     {NAME
      ": [roughness] give exactly one of rq, rms_slope for type = self_affine: none is given"}},
    {BASE "[roughness]\ntype = self_affine\nrq = 1 um\nhurst = 1\n",
     {NAME ":10: [roughness] hurst = 1: must be a number > 0 and < 1"}},
    {BASE "[roughness]\ntype = self_affine\nrq = 1 um\nlambda_long = 2 um\nlambda_short = 3 um\n",
     {NAME ":11: [roughness] lambda_short = 3e-06 m: must be < lambda_long = 2e-06 m"}},
    {BASE "[roughness]\ntype = gaussian\nrq = 1 um\ncorrelation_x = 1 um\nseed = -1\n",
     {NAME ":11: [roughness] seed = -1: must be an integer in 0..18446744073709551615"}},
    {BASE "[roughness]\ntype = file\n",
     {NAME ": [roughness] file is required for type = file (a path)"}},
    {BASE "[body2]\nrigid = yes\nE = 1 GPa\n", {NAME ":9: [body2] E is not used by rigid = yes"}},
    {BASE "[mesh]\nperiodic_x = maybe\n",
     {NAME ":8: [mesh] periodic_x = maybe: must be yes or no (also true/false, on/off, 1/0)"}},
    {BASE "lubricant_pressure = 2 MPa\npressure_cap = 1 MPa\n",
     {NAME ":8: [load] pressure_cap = 1e+06 Pa: must be > lubricant_pressure = 2e+06 Pa"}},
    /* scale rules (issue 15): a load the grid cannot carry, numbers beyond the solver's range,
     * loop counts set by values */
    {BASE "lubricant_pressure = 20 GPa\n",
     {NAME ":7: [load] lubricant_pressure = 2e+10 Pa over the whole grid",
      "carries 1.28 N, more than the requested force 1 N"}},
    {BASE "[body1]\nE = 1 kPa\n[body2]\nE = 1 kPa\n",
     {NAME ":6: [load] force = 1 N: the mean pressure over the grid",
      "accepted: force <= 1000 E* nx dx ny dy"}},
    {BASE "[mesh]\nperiodic_x = yes\nperiodic_y = yes\ndy = 2 mm\n",
     {NAME ":10: [mesh] dy/dx = 2000 on a grid periodic along x and y", "at most 1000"}},
    {BASE "[plasticity]\nyield_stress = 1 GPa\ndz = 0.01 um\n",
     {NAME ":9: [plasticity] dz = 1e-08 m: must be >= min(dx, dy) / 16"}},
    {BASE "[solver]\ntolerance = 1\n",
     {NAME ":8: [solver] tolerance = 1: must be a number >= 1e-15 and <= 0.01"}},
    {BASE "[solver]\noperator = fast\n",
     {NAME ":8: [solver] operator = fast: must be one of fft, direct"}},
    {BASE "[solver]\nmethod = newton\n",
     {NAME ":8: [solver] method = newton: must be one of cg, pk, active-set"}},
    {BASE "[stress]\ndepths = 0.5 um, 0.1 um\n",
     {NAME ":8: [stress] depths = 0.5 um, 0.1 um: item 2 (0.1 um) must be greater than item 1 "
           "(0.5 um)"}},
    {BASE "[stress]\ndepths = 0.5 um,, 1 um\n", {NAME ":8: [stress] depths = ", "item 2 is empty"}},
    {BASE "[stress]\ndepths = 0.5 um, 1 N\n",
     {NAME ":8: [stress] depths = ", "item 2 (1 N): unit 'N' is a force; a length is due"}},
    {BASE "[stress]\ndepths = -1 um\n",
     {NAME ":8: [stress] depths = -1 um: item 1 (-1 um) must be a length >= 0"}},
    {BASE "[stress]\ndepths = 1 um, 2 um\nlayers = 4\n",
     {NAME ":9: [stress] layers cannot be combined with depths (on line 8)"}},
    {BASE "[stress]\ndepth_max = 3 um\ndepths = 1 um, 2 um\n",
     {NAME ":9: [stress] depths: give exactly one of depth_max, depths (depth_max is on line 8)"}},
    {BASE "[stress]\nwindow = small\n",
     {NAME ":8: [stress] window = small: must be one of auto, full"}},
    {BASE "[stress]\ndepth_max = automatic\n",
     {NAME ":8: [stress] depth_max = automatic: 'automatic' is not a number", "; or auto"}},
    {BASE "[stress]\ndepth_min = 2 um\ndepth_max = 1 um\n",
     {NAME ":9: [stress] depth_max = 1e-06 m: must be > depth_min = 2e-06 m"}},
    {BASE "[stress]\nspacing = geometric\ndepth_max = 1 um\n",
     {NAME ":8: [stress] spacing = geometric needs depth_min > 0"}},
    {BASE "[stress]\ndepth_max = 1 um\nlayers = 513\n",
     {NAME ":9: [stress] layers = 513: must be an integer in 1..512"}},
    {BASE "[stress]\ndepth_max = 1 um\nfriction = 1.5\n",
     {NAME ":9: [stress] friction = 1.5: must be a number >= 0 and <= 1"}},
    {"[mesh]\nnx = 3\n  ny = 4\n",
     {NAME ":3: [mesh] nx: this line starts with whitespace, so it continues nx from line 2",
      "nx takes a single value"}},
    {"[mesh\nnx = 3\n", {NAME ":1: section header '[mesh' lacks its closing ']'"}},
    {BASE "[stress\n", {NAME ":7: section header '[stress' lacks its closing ']'"}},
    {BASE "just words\n",
     {NAME ":7: cannot parse this line (expected key = value or [section]): 'just words'"}},
    {BASE "[output]\ndir = caf\xe9\n",
     {NAME ":8: line 8 is not UTF-8 text (byte 0xE9 at column 10)"}},
    {BASE "[output]\ndir = \xc0\xaf\n", {NAME ":8: line 8 is not UTF-8 text"}},
    {BASE "[output]\ndir = " X20 X20 X20 X20 X20 X20 X20 X20 X20 X20 "\n",
     {NAME ":8: line 8 is longer than 199 characters"}},
};

static void write_file(const char *path, const char *text, size_t n);

/* Each malformed text, from memory (named NAME) and from a file (named by its path): the same
 * message with the file name in front. */
START_TEST(test_bad)
{
    const bad_case *c = &bad[_i];
    char path[600];
    snprintf(path, sizeof path, "%s/bad.ini", test_tmpdir());
    if (c->text)
        write_file(path, c->text, strlen(c->text));
    for (int from_file = !c->text; from_file < 2; from_file++) {
        mc_scene s;
        memset(&s, 0x5a, sizeof s);
        mc_scene before = s;
        mc_error err;
        mc_error_clear(&err);
        int rc = from_file ? mc_case_load(path, 0, NULL, &s, &err)
                           : parse(c->text, 0, NULL, &s, &err);
        int code = c->text ? MC_ERR_INPUT : MC_ERR_IO;
        ck_assert_msg(rc == code, "case %d (%s): rc %d (%s)", _i, from_file ? "file" : "text", rc,
                      err.msg);
        ck_assert_int_eq(err.code, code);
        for (int k = 0; k < 4 && c->want[k]; k++) {
            char want[800];
            if (from_file && strncmp(c->want[k], NAME, strlen(NAME)) == 0)
                snprintf(want, sizeof want, "%s%s", path, c->want[k] + strlen(NAME));
            else
                snprintf(want, sizeof want, "%s", c->want[k]);
            ck_assert_msg(strstr(err.msg, want) != NULL, "case %d: message\n  %s\nlacks\n  %s", _i,
                          err.msg, want);
        }
        if (!c->text)
            ck_assert_msg(strstr(err.msg, strerror(ENOENT)), "%s", err.msg);
        ck_assert_msg(strchr(err.msg, '\n') == NULL, "case %d: message spans lines", _i);
        ck_assert_msg(memcmp(&s, &before, sizeof s) == 0, "case %d: scene written on failure", _i);
    }
}
END_TEST

START_TEST(test_too_long_line_first)
{
    /* a long line is refused even when it is a comment: inih would misread its tail */
    char text[400];
    snprintf(text, sizeof text, BASE "; ");
    size_t n = strlen(text);
    memset(text + n, 'c', 250);
    strcpy(text + n + 250, "\n");
    mc_scene s;
    mc_error err;
    ck_assert_int_eq(parse(text, 0, NULL, &s, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, NAME ":7: line 7 is longer than 199 characters"), "%s", err.msg);
}
END_TEST

/* ---- overrides ------------------------------------------------------------------------------- */

START_TEST(test_override_replace_and_add)
{
    const char *ov[] = {"load.force=2 kN", " solver.threads = 4 ", "mesh.periodic_y=yes",
                        "solver.threads=8"};
    mc_scene s;
    parse_ok(BASE, 4, ov, &s);
    EQ(s.load.value, 2000.0);              /* replaced, not a duplicate */
    ck_assert_int_eq(s.solver.threads, 8); /* of two overrides the last wins */
    ck_assert_int_eq(s.grid.periodic_y, 1);
}
END_TEST

START_TEST(test_override_new_section)
{
    mc_scene s;
    mc_error err;
    const char *on[] = {"stress.enabled=yes", "stress.depth_max=10 um"};
    parse_ok(BASE, 2, on, &s);
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert_int_eq(s.stress.layers, 32);
    EQ(s.stress.depth_max, 10e-6);
    /* enabling alone takes the range from the contact (depth_max = auto) */
    parse_ok(BASE, 1, on, &s);
    ck_assert_int_eq(s.stress.enabled, 1);
    ck_assert(s.stress.depth_max == MC_STRESS_DEPTH_AUTO);
    /* a bad window is refused like any enum */
    const char *no_window[] = {"stress.enabled=yes", "stress.window=none"};
    ck_assert_int_eq(parse(BASE, 2, no_window, &s, &err), MC_ERR_INPUT);
    /* and a sweep can switch a file's stress stage off */
    const char *off[] = {"stress.enabled=no"};
    parse_ok(case_a, 1, off, &s);
    ck_assert_int_eq(s.stress.enabled, 0);
    /* an override path is relative to the current directory, not to the case file */
    const char *path[] = {"roughness.type=file", "roughness.file=data/h.npy"};
    parse_ok(BASE, 2, path, &s);
    ck_assert_str_eq(s.roughness.file, "data/h.npy");
}
END_TEST

typedef struct {
    const char *ov;
    const char *want[3];
} bad_override;

static const bad_override bad_ov[] = {
    {"mesh.nx=0", {"--set mesh.nx=0: [mesh] nx = 0: must be an integer in 1..65536"}},
    {"meshnx=3", {"--set meshnx=3: expected section.key=value"}},
    {"mesh.nx", {"--set mesh.nx: expected section.key=value"}},
    {".nx=3", {"--set .nx=3: expected section.key=value"}},
    {"mesh.=3", {"--set mesh.=3: expected section.key=value"}},
    {"mesh.foo=1", {"--set mesh.foo=1: [mesh] unknown key 'foo'; keys of [mesh]: nx, ny"}},
    {"meshh.nx=1", {"--set meshh.nx=1: unknown section [meshh]; known sections: mesh"}},
    {"load.approach=1 um",
     {"--set load.approach=1 um: [load] approach: give exactly one of force, force_per_length, "
      "approach, pressure_file (force is on line 6 of " NAME ")"}},
    {"mesh.dx=2 N", {"--set mesh.dx=2 N: [mesh] dx = 2 N: unit 'N' is a force; a length is due"}},
    {"load.force_per_length=1 N/m", {"--set load.force_per_length=1 N/m: [load] approach"}},
    {"geometry.radius=1 mm",
     {"--set geometry.radius=1 mm: [geometry] radius is not used by shape "
      "= flat"}},
};

START_TEST(test_override_bad)
{
    const bad_override *c = &bad_ov[_i];
    const char *ov[] = {c->ov};
    mc_scene s;
    mc_error err;
    /* case 9 combines two overrides: the message names the later one and where the other is */
    const char *pair[] = {"load.approach=1 um", c->ov};
    int two = strstr(c->ov, "force_per_length") != NULL;
    const char *text = two ? "[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\n" : BASE;
    int rc = parse(text, two ? 2 : 1, two ? pair : ov, &s, &err);
    ck_assert_msg(rc == MC_ERR_INPUT, "%s: rc %d (%s)", c->ov, rc, err.msg);
    if (two)
        ck_assert_msg(strstr(err.msg, "--set load.force_per_length=1 N/m: [load] force_per_length: "
                                      "give exactly one of") &&
                          strstr(err.msg, "(approach is given by --set load.approach=1 um)"),
                      "%s", err.msg);
    else
        ck_assert_msg(strstr(err.msg, c->want[0]), "message\n  %s\nlacks\n  %s", err.msg,
                      c->want[0]);
}
END_TEST

/* ---- files ----------------------------------------------------------------------------------- */

static void write_file(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    ck_assert_msg(f != NULL, "cannot write %s", path);
    ck_assert_uint_eq(fwrite(text, 1, n, f), n);
    fclose(f);
}

START_TEST(test_load_file_and_relative_paths)
{
    char dir[512], sub[600], path[700];
    snprintf(dir, sizeof dir, "%s", test_tmpdir());
    snprintf(sub, sizeof sub, "%s/cases", dir);
    ck_assert_int_eq(mkdir(sub, 0700), 0);
    snprintf(path, sizeof path, "%s/line.ini", sub);
    const char *text = BASE "[roughness]\ntype = file\nfile = maps/h.npy\n";
    write_file(path, text, strlen(text));
    mc_scene s;
    mc_error err;
    int rc = mc_case_load(path, 0, NULL, &s, &err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
    char want[800];
    snprintf(want, sizeof want, "%s/maps/h.npy", sub);
    ck_assert_str_eq(s.roughness.file, want);
    ck_assert_str_eq(s.path, path);
    ck_assert_str_eq(s.output.dir, "out/line"); /* relative to the current directory */

    /* an absolute path stays as it is */
    const char *abs = BASE "[roughness]\ntype = file\nfile = /data/h.npy\n";
    write_file(path, abs, strlen(abs));
    ck_assert_int_eq(mc_case_load(path, 0, NULL, &s, &err), MC_OK);
    ck_assert_str_eq(s.roughness.file, "/data/h.npy");

    /* without a directory part the path is left relative to the current directory */
    ck_assert_int_eq(mc_case_parse_text(text, "x.ini", NULL, 0, NULL, &s, &err), MC_OK);
    ck_assert_str_eq(s.roughness.file, "maps/h.npy");
    ck_assert_str_eq(s.output.dir, "out/x");

    /* an error inside a loaded file names its path and line */
    const char *badtext = BASE "[mesh]\nnx = 2\n";
    write_file(path, badtext, strlen(badtext));
    ck_assert_int_eq(mc_case_load(path, 0, NULL, &s, &err), MC_ERR_INPUT);
    char head[800];
    snprintf(head, sizeof head, "%s:8: [mesh] nx given twice (first on line 2)", path);
    ck_assert_str_eq(err.msg, head);

    /* no error record: the status alone, also for the cross-key rules */
    const char *fpl = "[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\nforce_per_length = 5 N/mm\n";
    ck_assert_int_eq(mc_case_parse_text(fpl, "x.ini", NULL, 0, NULL, &s, NULL), MC_ERR_INPUT);
    ck_assert_int_eq(mc_case_parse_text(badtext, "x.ini", NULL, 0, NULL, &s, NULL), MC_ERR_INPUT);

    /* a NUL byte: not a text file */
    write_file(path, "[mesh]\nnx = 3\0\n", 15);
    ck_assert_int_eq(mc_case_load(path, 0, NULL, &s, &err), MC_ERR_INPUT);
    snprintf(head, sizeof head, "%s:2: contains a NUL byte", path);
    ck_assert_msg(strstr(err.msg, head), "%s", err.msg);
}
END_TEST

START_TEST(test_load_io_errors)
{
    mc_scene s;
    mc_error err;
    char path[600];
    snprintf(path, sizeof path, "%s/missing.ini", test_tmpdir());
    ck_assert_int_eq(mc_case_load(path, 0, NULL, &s, &err), MC_ERR_IO);
    ck_assert_msg(strstr(err.msg, path) && strstr(err.msg, strerror(ENOENT)), "%s", err.msg);
    /* a directory opens but cannot be read */
    const char *dir = test_tmpdir();
    ck_assert_int_eq(mc_case_load(dir, 0, NULL, &s, &err), MC_ERR_IO);
    ck_assert_msg(strstr(err.msg, dir) && strstr(err.msg, strerror(EISDIR)), "%s", err.msg);
    /* an empty file is bad input, not an I/O error */
    snprintf(path, sizeof path, "%s/empty.ini", dir);
    write_file(path, "", 0);
    ck_assert_int_eq(mc_case_load(path, 0, NULL, &s, &err), MC_ERR_INPUT);
    char want[700];
    snprintf(want, sizeof want, "%s: empty case file", path);
    ck_assert_msg(strstr(err.msg, want), "%s", err.msg);
}
END_TEST

/* ---- memory: every allocation failure is reported and leaks nothing -------------------------- */

START_TEST(test_fault_injection)
{
    const char *ov[] = {"stress.kernel=point", "solver.threads=2"};
    int failures = 0;
    for (long n = 1; n < 10000; n++) {
        long before = mc_alloc_injected();
        mc_alloc_fail_at(n);
        mc_scene s;
        mc_error err;
        int rc = parse(case_b, 2, ov, &s, &err);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == before) {
            ck_assert_msg(rc == MC_OK, "%s", err.msg);
            break;
        }
        ck_assert_msg(rc == MC_ERR_NOMEM, "allocation %ld failed: rc %d (%s)", n, rc, err.msg);
        failures++;
    }
    ck_assert_int_gt(failures, 5);
    for (long n = 1; n < 100; n++) {
        long before = mc_alloc_injected();
        mc_alloc_fail_at(n);
        char *md = mc_case_reference_markdown();
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == before) {
            ck_assert_ptr_nonnull(md);
            mc_free(md);
            break;
        }
        ck_assert_ptr_null(md);
    }
}
END_TEST

/* ---- the reference: table consistency and the docs ------------------------------------------- */

START_TEST(test_table_consistent)
{
    mc_error err = {0};
    int rc = mc_case_check_table(&err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
}
END_TEST

#define DOC_MARK "<!-- generated by mc_case_reference_markdown()"

START_TEST(test_docs_match_generated)
{
    char *md = mc_case_reference_markdown();
    ck_assert_ptr_nonnull(md);
    ck_assert(strncmp(md, DOC_MARK, strlen(DOC_MARK)) == 0);
    /* every section and key appears in the reference */
    const char *expect[] = {"## [mesh]",
                            "## [stress]",
                            "| `depth_max` |",
                            "| `pressure_cap` |",
                            "| `force_per_length` |",
                            "`kN/mm`"};
    for (size_t k = 0; k < sizeof expect / sizeof expect[0]; k++)
        ck_assert_msg(strstr(md, expect[k]), "reference lacks %s", expect[k]);

    const char *path = getenv("MC_CASE_DOC");
    if (!path || !*path)
        path = "docs/case-format.md";
    FILE *f = fopen(path, "rb");
    ck_assert_msg(f != NULL, "cannot open %s (run the tests from the repository root)", path);
    static char doc[1 << 17];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = '\0';
    const char *gen = strstr(doc, DOC_MARK);
    ck_assert_msg(gen && gen > doc, "%s: no hand-written introduction before the generated part",
                  path);
    /* the introduction's example case is valid */
    const char *ex = strstr(doc, "```ini\n");
    ck_assert_msg(ex && ex < gen, "%s: no ```ini example before the reference", path);
    ex += strlen("```ini\n");
    const char *end = strstr(ex, "```");
    ck_assert_ptr_nonnull(end);
    char example[4096];
    ck_assert_uint_lt((size_t)(end - ex), sizeof example);
    memcpy(example, ex, (size_t)(end - ex));
    example[end - ex] = '\0';
    mc_scene s;
    mc_error err;
    ck_assert_msg(parse(example, 0, NULL, &s, &err) == MC_OK, "%s example: %s", path, err.msg);
    ck_assert_int_eq(s.stress.enabled, 1);
    if (strcmp(gen, md) != 0) {
        char fresh[700];
        snprintf(fresh, sizeof fresh, "%s/case-format.md", test_tmpdir_kept());
        FILE *o = fopen(fresh, "wb");
        if (o) {
            fwrite(doc, 1, (size_t)(gen - doc), o);
            fputs(md, o);
            fclose(o);
        }
        mc_free(md);
        ck_abort_msg("%s is out of date with the key table in src/case/keys.c; the regenerated file "
                     "is %s (copy it over)",
                     path, fresh);
    }
    mc_free(md);
}
END_TEST

/* ---- scene ----------------------------------------------------------------------------------- */

static mc_scene valid_scene(void)
{
    mc_scene s;
    mc_scene_defaults(&s);
    s.grid = (mc_grid){.nx = 16, .ny = 8, .dx = 1e-6, .dy = 2e-6};
    s.load.kind = MC_LOAD_FORCE;
    s.load.value = 10.0;
    return s;
}

START_TEST(test_scene_defaults)
{
    mc_scene s;
    memset(&s, 0x7f, sizeof s);
    mc_scene_defaults(&s);
    ck_assert_str_eq(s.path, "");
    ck_assert_str_eq(s.output.dir, "");
    ck_assert_int_eq(s.geometry.shape, MC_SHAPE_FLAT);
    ck_assert_int_eq(s.roughness.type, MC_ROUGH_NONE);
    ck_assert(s.roughness.seed == 1);
    EQ(s.roughness.hurst, 0.8);
    EQ(s.body1.E, 210e9);
    EQ(s.body2.nu, 0.3);
    ck_assert(isinf(s.load.pressure_cap) && s.load.pressure_cap > 0);
    ck_assert_int_eq(s.solver.max_iterations, 2000);
    ck_assert_int_eq(s.stress.enabled, 0);
    ck_assert_int_eq(s.stress.layers, 32);
    /* keys without defaults are left invalid until set */
    mc_error err;
    ck_assert_int_eq(mc_scene_check(&s, &err), MC_ERR_INPUT);
    mc_scene v = valid_scene();
    ck_assert_msg(mc_scene_check(&v, &err) == MC_OK, "%s", err.msg);
}
END_TEST

typedef struct {
    void (*mutate)(mc_scene *s);
    const char *section, *key, *want;
} rule_case;

static void m_nx(mc_scene *s) { s->grid.nx = 0; }
static void m_dy(mc_scene *s) { s->grid.dy = NAN; }
static void m_sphere(mc_scene *s) { s->geometry.shape = MC_SHAPE_SPHERE; }
static void m_ellipsoid(mc_scene *s)
{
    s->geometry.shape = MC_SHAPE_ELLIPSOID;
    s->geometry.radius_x = 1e-3;
}
static void m_gauss(mc_scene *s)
{
    s->roughness.type = MC_ROUGH_GAUSSIAN;
    s->roughness.rq = 1e-7;
    s->roughness.correlation_x = 1e-6;
}
static void m_affine_both(mc_scene *s)
{
    s->roughness.type = MC_ROUGH_SELF_AFFINE;
    s->roughness.rq = 1e-7;
    s->roughness.rms_slope = 0.1;
}
static void m_affine_cut(mc_scene *s)
{
    s->roughness.type = MC_ROUGH_SELF_AFFINE;
    s->roughness.rq = 1e-7;
    s->roughness.lambda_short = 1.0; /* above the default long cut-off, the domain size */
}
static void m_file(mc_scene *s) { s->roughness.type = MC_ROUGH_FILE; }
static void m_nu(mc_scene *s) { s->body1.nu = 0.6; }
static void m_E2(mc_scene *s) { s->body2.E = 0; }
static void m_noload(mc_scene *s) { s->load.value = 0; }
static void m_fpl(mc_scene *s) { s->load.kind = MC_LOAD_FORCE_PER_LENGTH; }
static void m_pfile(mc_scene *s) { s->load.kind = MC_LOAD_PRESSURE_FILE; }
static void m_cap(mc_scene *s)
{
    s->load.lubricant_pressure = 2e6;
    s->load.pressure_cap = 2e6;
}
static void m_tol(mc_scene *s) { s->solver.tolerance = 0.5; }
static void m_iter(mc_scene *s) { s->solver.max_iterations = 0; }
static void m_range(mc_scene *s)
{
    s->stress.enabled = 1;
    s->stress.depth_min = 1e-6;
    s->stress.depth_max = 1e-6;
}
static void m_geom(mc_scene *s)
{
    s->stress.enabled = 1;
    s->stress.depth_max = 1e-6;
    s->stress.spacing = MC_SPACING_GEOMETRIC;
}
static void m_list(mc_scene *s)
{
    s->stress.enabled = 1;
    s->stress.spacing = MC_SPACING_LIST;
    s->stress.ndepths = 2;
    s->stress.depths[0] = 1e-6;
    s->stress.depths[1] = 1e-6;
}
static void m_friction(mc_scene *s)
{
    s->stress.enabled = 1;
    s->stress.depth_max = 1e-6;
    s->stress.friction = -0.1;
}

static const rule_case rules[] = {
    {m_nx, "mesh", "nx", "[mesh] nx = 0: must be an integer in 1..65536"},
    {m_dy, "mesh", "dy", "[mesh] dy = nan m: must be a length > 0"},
    {m_sphere, "geometry", "radius", "[geometry] radius = 0 m: must be a length > 0"},
    {m_ellipsoid, "geometry", "radius_y", "[geometry] radius_y = 0 m: must be a length > 0"},
    {m_gauss, "roughness", "correlation_y", "[roughness] correlation_y = 0 m: must be a length > 0"},
    {m_affine_both, "roughness", "rms_slope", "rq or rms_slope, not both"},
    {m_affine_cut, "roughness", "lambda_short", "must be < lambda_long = 1.6e-05 m"},
    {m_file, "roughness", "file", "[roughness] file = \"\": must be a path"},
    {m_nu, "body1", "nu", "[body1] nu = 0.6: must be a number >= 0 and <= 0.5"},
    {m_E2, "body2", "E", "[body2] E = 0 Pa: must be a pressure > 0 and <= 1e+13 Pa"},
    {m_noload, "load", "force", "[load] force = 0 N: must be a force > 0"},
    {m_fpl, "load", "force_per_length", "[load] force_per_length needs [mesh] periodic_y = yes"},
    {m_pfile, "load", "pressure_file", "[load] pressure_file = \"\": must be a path"},
    {m_cap, "load", "pressure_cap", "must be > lubricant_pressure = 2e+06 Pa"},
    {m_tol, "solver", "tolerance", "[solver] tolerance = 0.5: must be a number >= 1e-15 and <= 0.01"},
    {m_iter, "solver", "max_iterations", "[solver] max_iterations = 0: must be an integer in 1..10000000"},
    {m_range, "stress", "depth_max", "must be > depth_min = 1e-06 m"},
    {m_geom, "stress", "spacing", "spacing = geometric needs depth_min > 0"},
    {m_list, "stress", "depths", "[stress] depths item 2 = 1e-06 m: must be a list of comma-separated lengths >= 0, strictly increasing"},
    {m_friction, "stress", "friction", "[stress] friction = -0.1: must be a number >= 0 and <= 1"},
};

START_TEST(test_scene_rules)
{
    const rule_case *c = &rules[_i];
    mc_scene s = valid_scene();
    c->mutate(&s);
    mc_error err;
    const char *sec = NULL, *key = NULL;
    ck_assert_int_eq(mc_scene_check_key(&s, &err, &sec, &key), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, c->want), "message\n  %s\nlacks\n  %s", err.msg, c->want);
    ck_assert_ptr_nonnull(sec);
    ck_assert_ptr_nonnull(key);
    ck_assert_str_eq(sec, c->section);
    ck_assert_str_eq(key, c->key);
    ck_assert_int_eq(mc_scene_check(&s, &err), MC_ERR_INPUT);
}
END_TEST

START_TEST(test_scene_rules_pass)
{
    /* the rules accept what they should: a rigid body 2 with junk E, periodic line loads, a
     * disabled stress stage with junk depths */
    mc_scene s = valid_scene();
    mc_error err;
    s.body2.rigid = 1;
    s.body2.E = 0;
    s.load.kind = MC_LOAD_FORCE_PER_LENGTH;
    s.grid.periodic_y = 1;
    s.stress.depth_max = -1;
    ck_assert_msg(mc_scene_check(&s, &err) == MC_OK, "%s", err.msg);
}
END_TEST

START_TEST(test_scene_estar)
{
    mc_scene s = valid_scene();
    /* identical steel bodies: E* = E / (2 (1 - nu^2)) */
    EQ(mc_scene_estar(&s), 210e9 / (2 * (1 - 0.09)));
    s.body2.rigid = 1;
    EQ(mc_scene_estar(&s), 210e9 / (1 - 0.09));
}
END_TEST

START_TEST(test_scene_depths)
{
    mc_scene s = valid_scene();
    double z[MC_MAX_DEPTHS];
    int n = 0;
    mc_error err;
    s.stress.enabled = 1;
    s.stress.depth_min = 1e-6;
    s.stress.depth_max = 5e-6;
    s.stress.layers = 5;
    ck_assert_int_eq(mc_scene_depths(&s, z, &n, &err), MC_OK);
    ck_assert_int_eq(n, 5);
    for (int k = 0; k < 5; k++)
        EQ(z[k], (1.0 + k) * 1e-6);
    s.stress.spacing = MC_SPACING_GEOMETRIC;
    s.stress.depth_max = 16e-6;
    ck_assert_int_eq(mc_scene_depths(&s, z, &n, &err), MC_OK);
    for (int k = 0; k < 5; k++)
        EQ(z[k], ldexp(1e-6, k));
    ck_assert(z[4] == 16e-6); /* ends exact */
    s.stress.layers = 1;
    ck_assert_int_eq(mc_scene_depths(&s, z, &n, &err), MC_OK);
    ck_assert_int_eq(n, 1);
    ck_assert(z[0] == 1e-6);
    s.stress.spacing = MC_SPACING_LIST;
    s.stress.ndepths = 3;
    s.stress.depths[0] = 0;
    s.stress.depths[1] = 2e-6;
    s.stress.depths[2] = 7e-6;
    ck_assert_int_eq(mc_scene_depths(&s, z, &n, &err), MC_OK);
    ck_assert_int_eq(n, 3);
    ck_assert(z[2] == 7e-6);
    s.stress.ndepths = 0;
    ck_assert_int_eq(mc_scene_depths(&s, z, &n, &err), MC_ERR_INPUT);
}
END_TEST

START_TEST(test_scene_cutoffs_and_dir)
{
    mc_scene s = valid_scene(); /* 16 x 1 um by 8 x 2 um */
    double hi, lo;
    mc_scene_cutoffs(&s, &hi, &lo);
    EQ(hi, 16e-6);
    EQ(lo, 4e-6);
    s.roughness.lambda_long = 1e-3;
    s.roughness.lambda_short = 1e-5;
    mc_scene_cutoffs(&s, &hi, &lo);
    ck_assert(hi == 1e-3 && lo == 1e-5);

    char dir[64];
    mc_error err;
    ck_assert_int_eq(mc_scene_output_dir(&s, dir, sizeof dir, &err), MC_OK);
    ck_assert_str_eq(dir, "out/scene");
    snprintf(s.path, sizeof s.path, "cases/hertz_point.ini");
    ck_assert_int_eq(mc_scene_output_dir(&s, dir, sizeof dir, &err), MC_OK);
    ck_assert_str_eq(dir, "out/hertz_point");
    snprintf(s.output.dir, sizeof s.output.dir, "/tmp/x");
    ck_assert_int_eq(mc_scene_output_dir(&s, dir, sizeof dir, &err), MC_OK);
    ck_assert_str_eq(dir, "/tmp/x");
    ck_assert_int_eq(mc_scene_output_dir(&s, dir, 4, &err), MC_ERR_INPUT);
}
END_TEST

Suite *suite_case(void);
Suite *suite_case(void)
{
    Suite *s = suite_create("case");
    TCase *tv = tcase_create("valid");
    tcase_add_test(tv, test_case_a);
    tcase_add_test(tv, test_case_b);
    tcase_add_test(tv, test_case_c);
    tcase_add_test(tv, test_case_d);
    tcase_add_test(tv, test_sections_accumulate);
    tcase_add_test(tv, test_line_limit_edge);
    tcase_add_test(tv, test_depth_list_limit);
    suite_add_tcase(s, tv);

    TCase *tb = tcase_create("malformed");
    tcase_add_loop_test(tb, test_bad, 0, (int)(sizeof bad / sizeof bad[0]));
    tcase_add_test(tb, test_too_long_line_first);
    suite_add_tcase(s, tb);

    TCase *to = tcase_create("overrides");
    tcase_add_test(to, test_override_replace_and_add);
    tcase_add_test(to, test_override_new_section);
    tcase_add_loop_test(to, test_override_bad, 0, (int)(sizeof bad_ov / sizeof bad_ov[0]));
    suite_add_tcase(s, to);

    TCase *tf = tcase_create("files");
    tcase_add_test(tf, test_load_file_and_relative_paths);
    tcase_add_test(tf, test_load_io_errors);
    tcase_add_test(tf, test_fault_injection);
    suite_add_tcase(s, tf);

    TCase *tr = tcase_create("reference");
    tcase_add_test(tr, test_table_consistent);
    tcase_add_test(tr, test_docs_match_generated);
    suite_add_tcase(s, tr);

    TCase *ts = tcase_create("scene");
    tcase_add_test(ts, test_scene_defaults);
    tcase_add_loop_test(ts, test_scene_rules, 0, (int)(sizeof rules / sizeof rules[0]));
    tcase_add_test(ts, test_scene_rules_pass);
    tcase_add_test(ts, test_scene_estar);
    tcase_add_test(ts, test_scene_depths);
    tcase_add_test(ts, test_scene_cutoffs_and_dir);
    suite_add_tcase(s, ts);
    return s;
}
