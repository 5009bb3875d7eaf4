/* test_two_surfaces.c - two measured surfaces ([roughness] body 1, [roughness2] body 2;
 * pipeline/bodies.h, docs/theory.md §4.11): the gap's roughness is the sum of the outward heights
 * (read back from the written files); the sign convention (an outward bump of either body closes
 * the gap and carries the load); one composite map of z1 + z2 gives the same run; swapping the
 * two bodies gives the same composite results, also in a running-in; each body's final surface is
 * its initial one minus its own residual dent (bodies = one and both, pressure cap); and bad input
 * (roughness2 without roughness, maps of two grids, the rules of [roughness] applied to
 * [roughness2]) is refused naming the key and, for a grid mismatch, both files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "case/case.h"
#include "core/alloc.h"
#include "io/npy.h"
#include "pipeline/output.h"
#include "pipeline/pipeline.h"
#include "pipeline/runin.h"
#include "surface/roughness.h"
#include "test_util.h"

#define N 16 /* the maps' cells along x and y */

/* A smooth random map of N x N heights, rms sq, into DIR/name (.npy, metres). */
static void write_map(const char *dir, const char *name, double sq, unsigned long long seed,
                      double *z)
{
    test_smooth_rough_gap(z, N, sq, seed); /* a gap: minus the heights */
    for (int i = 0; i < N * N; i++)
        z[i] = -z[i];
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    size_t shape[2] = {N, N};
    mc_error err = {0};
    ck_assert_msg(mc_npy_write(path, z, 2, shape, &err) == MC_OK, "%s", err.msg);
}

/* A rough flat patch under a force on a free grid: body 1 and body 2 from files a, b in dir
 * (detrend = none: the heights are used as written, so that sums compare bit for bit). b NULL:
 * [roughness] alone. extra: more sections. */
static void scene(mc_scene *s, const char *dir, const char *a, const char *b, const char *extra,
                  int nset, const char *const *set)
{
    char text[2048];
    int n = snprintf(text, sizeof text,
                     "[mesh]\nnx = %d\nny = %d\ndx = 2 um\n[roughness]\ntype = file\nfile = %s\n"
                     "detrend = none\n[load]\nforce = 20 mN\n[solver]\nthreads = 1\n"
                     "tolerance = 1e-10\n",
                     N, N, a);
    if (b)
        n += snprintf(text + n, sizeof text - (size_t)n,
                      "[roughness2]\ntype = file\nfile = %s\ndetrend = none\n", b);
    snprintf(text + n, sizeof text - (size_t)n, "%s", extra ? extra : "");
    mc_error err = {0};
    char name[600];
    snprintf(name, sizeof name, "%s/c.ini", dir);
    ck_assert_msg(mc_case_parse_text(text, name, dir, nset, set, s, &err) == MC_OK, "%s",
                  err.msg);
}

static double *read_back(const char *dir, const char *name)
{
    char path[700];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    double *z = NULL;
    int rows = 0, cols = 0;
    mc_error err = {0};
    ck_assert_msg(mc_npy_read(path, &z, &rows, &cols, &err) == MC_OK, "%s", err.msg);
    ck_assert(rows == N && cols == N);
    return z;
}

/* The gap's roughness is z1 + z2 (theory §4.11): the written topography of a flat patch is
 * -(z1 + z2) bit for bit (one subtraction from 0 of one sum), the written body surfaces are the
 * maps as given, and the composite ISO parameters are those of z1 + z2. The same composite given
 * as one [roughness] map runs to the same pressure, bit for bit. */
START_TEST(composite_is_the_sum)
{
    const char *dir = test_tmpdir();
    double z1[N * N], z2[N * N], sum[N * N];
    write_map(dir, "a.npy", 0.3e-6, 11, z1);
    write_map(dir, "b.npy", 0.2e-6, 12, z2);
    for (int i = 0; i < N * N; i++)
        sum[i] = z1[i] + z2[i];
    char path[700];
    snprintf(path, sizeof path, "%s/sum.npy", dir);
    size_t shape[2] = {N, N};
    mc_error err = {0};
    ck_assert(mc_npy_write(path, sum, 2, shape, &err) == MC_OK);

    mc_scene s;
    scene(&s, dir, "a.npy", "b.npy", NULL, 0, NULL);
    mc_results r;
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    char out[600];
    snprintf(out, sizeof out, "%s/o", dir);
    ck_assert_msg(mc_output_write(out, &s, &r, &err) == MC_OK, "%s", err.msg);
    double *t = read_back(out, "topography.npy"), *b1 = read_back(out, "surface_initial_body1.npy"),
           *b2 = read_back(out, "surface_initial_body2.npy");
    for (int i = 0; i < N * N; i++) {
        ck_assert_double_eq(b1[i], z1[i]);
        ck_assert_double_eq(b2[i], z2[i]);
        ck_assert_double_eq(t[i], 0.0 - (b1[i] + b2[i]));
    }
    /* no final surface without [plasticity] */
    snprintf(path, sizeof path, "%s/surface_final_body1.npy", out);
    ck_assert(access(path, F_OK) != 0);
    mc_roughness_params rp;
    mc_roughness_options opt;
    mc_roughness_options_default(&opt);
    ck_assert(mc_roughness_compute(sum, NULL, N, N, 2e-6, 2e-6, &opt, &rp, &err) == MC_OK);
    ck_assert(r.has_roughness && r.two_bodies);
    ck_assert_double_eq(r.roughness_initial.Sq, rp.Sq);
    ck_assert_double_eq(r.roughness_initial.Ra, rp.Ra);
    /* each body's parameters are its own map's */
    ck_assert(mc_roughness_compute(z2, NULL, N, N, 2e-6, 2e-6, &opt, &rp, &err) == MC_OK);
    ck_assert_double_eq(r.body_roughness_initial[1].Sq, rp.Sq);

    mc_scene one;
    scene(&one, dir, "sum.npy", NULL, NULL, 0, NULL);
    mc_results q;
    ck_assert_msg(mc_pipeline_run(&one, &q, &err) == MC_OK, "%s", err.msg);
    ck_assert(!q.two_bodies);
    ck_assert(memcmp(q.topography, r.topography, sizeof z1) == 0);
    ck_assert(memcmp(q.pressure, r.pressure, sizeof z1) == 0);
    free(t);
    free(b1);
    free(b2);
    mc_results_free(&q);
    mc_results_free(&r);
}
END_TEST

/* The sign: each body's heights point outward, towards the other body. A single outward bump of
 * body 2 (body 1 flat) closes the gap there and carries the whole load on that cell, as the same
 * bump of body 1 does; a bump of body 2 read as pointing into it (invert = yes) carries nothing
 * there. */
START_TEST(outward_bump_carries_the_load)
{
    const char *dir = test_tmpdir();
    double flat[N * N] = {0}, bump[N * N] = {0};
    const int at = 5 * N + 9;
    bump[at] = 1e-6;
    size_t shape[2] = {N, N};
    char path[600];
    mc_error err = {0};
    snprintf(path, sizeof path, "%s/flat.npy", dir);
    ck_assert(mc_npy_write(path, flat, 2, shape, &err) == MC_OK);
    snprintf(path, sizeof path, "%s/bump.npy", dir);
    ck_assert(mc_npy_write(path, bump, 2, shape, &err) == MC_OK);
    for (int k = 0; k < 3; k++) {
        mc_scene s;
        const char *inv[] = {"roughness2.invert=yes"};
        if (k < 2)
            scene(&s, dir, k == 1 ? "bump.npy" : "flat.npy", k == 1 ? "flat.npy" : "bump.npy",
                  NULL, 0, NULL);
        else
            scene(&s, dir, "flat.npy", "bump.npy", NULL, 1, inv);
        mc_results r;
        ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
        const double share = r.pressure[at] * mc_grid_cell_area(&r.grid) / r.contact.load;
        /* a 1 um bump on a 2 um cell under 20 mN: the cell alone is in contact (its elastic
         * deflection, 20 mN / (E* 2 um) ~ 0.1 um, is far below the bump) */
        if (k < 2)
            ck_assert_msg(share > 0.999, "body %d's bump carries %g of the load", 2 - k, share);
        else
            ck_assert_msg(share < 0.01, "an inward bump carries %g of the load", share);
        mc_results_free(&r);
    }
}
END_TEST

/* Swapping the files of body 1 and body 2 gives the same composite results: z1 + z2 = z2 + z1
 * exactly, so the same bits in every field, in the composite ISO parameters, and in every row
 * of an (elastic, periodic) running-in; each body's parameters trade places. */
START_TEST(swap_gives_same_composite)
{
    const char *dir = test_tmpdir();
    double z1[N * N], z2[N * N];
    write_map(dir, "a.npy", 0.3e-6, 21, z1);
    write_map(dir, "b.npy", 0.2e-6, 22, z2);
    mc_scene s, t;
    scene(&s, dir, "a.npy", "b.npy", NULL, 0, NULL);
    scene(&t, dir, "b.npy", "a.npy", NULL, 0, NULL);
    mc_results r, q;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_pipeline_run(&t, &q, &err) == MC_OK, "%s", err.msg);
    ck_assert(memcmp(r.topography, q.topography, sizeof z1) == 0);
    ck_assert(memcmp(r.pressure, q.pressure, sizeof z1) == 0);
    ck_assert(memcmp(r.gap, q.gap, sizeof z1) == 0);
    ck_assert_double_eq(r.contact.approach, q.contact.approach);
    ck_assert_double_eq(r.roughness_initial.Sq, q.roughness_initial.Sq);
    ck_assert_double_eq(r.body_roughness_initial[0].Sq, q.body_roughness_initial[1].Sq);
    ck_assert_double_eq(r.body_roughness_initial[1].Ra, q.body_roughness_initial[0].Ra);
    ck_assert(r.body_roughness_initial[0].Sq != r.body_roughness_initial[1].Sq);
    mc_results_free(&r);
    mc_results_free(&q);

    /* a running-in (elastic: no [plasticity], so quick) on a periodic patch */
    static const char *RUNIN =
        "[mesh]\nperiodic_x = yes\nperiodic_y = yes\n[load]\nlubricant_pressure = auto\n"
        "[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\nrpm = 1000 rpm\n"
        "radius1 = 40 mm\nradius2 = 40 mm\nwidth = 10 mm\n[runin]\nspeeds = 1000, 300 rpm\n";
    const char *set[] = {"load.force=1086 N", "solver.tolerance=1e-8"};
    scene(&s, dir, "a.npy", "b.npy", RUNIN, 2, set);
    scene(&t, dir, "b.npy", "a.npy", RUNIN, 2, set);
    ck_assert_msg(mc_runin_run(&s, NULL, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_runin_run(&t, NULL, &q, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(r.runin.done, q.runin.done);
    for (int k = 0; k < r.runin.done; k++) {
        mc_runin_row x = r.runin.rows[k], y = q.runin.rows[k];
        x.seconds = y.seconds = 0;
        ck_assert_msg(memcmp(&x, &y, sizeof x) == 0, "row %d differs", k + 1);
    }
    ck_assert(memcmp(r.surface_final, q.surface_final, sizeof z1) == 0);
    ck_assert(r.body_has_final && q.body_has_final);
    ck_assert(memcmp(r.body_final[0], q.body_final[1], sizeof z1) == 0);
    mc_results_free(&r);
    mc_results_free(&q);
}
END_TEST

/* Each body's final surface is its initial one minus its own residual dent, read back from the
 * written files: with bodies = both both bodies take u_r, with bodies = one only body 1, with a
 * pressure cap only body 1 (the penetration). The two finals add up to the composite final
 * surface, minus topography_final on a flat patch, to round-off (different order of the same
 * additions: a few ulps of the heights). A sphere of R = 15 mm, steel on steel (E* = 115 GPa),
 * at 800 N: Hertz p0 = 2.08 GPa > 1.61 Y (yield onset, theory §6.5) and above the cap of
 * 1.8 GPa; a = 0.43 mm inside the 1.6 mm patch of 20 x 20 cells of 80 um. */
START_TEST(final_minus_own_dent)
{
    static const char *SPHERE =
        "[mesh]\nnx = 20\nny = 20\ndx = 80 um\n[geometry]\nshape = sphere\nradius = 15 mm\n"
        "[roughness]\ntype = gaussian\nrq = 0.2 um\ncorrelation_x = 120 um\n"
        "[roughness2]\ntype = gaussian\nrq = 0.1 um\ncorrelation_x = 80 um\n"
        "[load]\nforce = 800 N\n[plasticity]\n%s";
    static const char *const extra[] = {
        "yield_stress = 1 GPa\nload_steps = 2\nbodies = both\n",
        "yield_stress = 1 GPa\nload_steps = 2\n",
        "criterion = pressure_cap\nhardness = 1.8 GPa\n"};
    for (int k = 0; k < 3; k++) {
        char text[1024];
        snprintf(text, sizeof text, SPHERE, extra[k]);
        mc_scene s;
        mc_error err = {0};
        ck_assert_msg(mc_case_parse_text(text, "d.ini", "", 0, NULL, &s, &err) == MC_OK, "%s",
                      err.msg);
        mc_results r;
        ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "case %d: %s", k, err.msg);
        ck_assert_msg(r.plastic.residual_max > 0, "case %d: no dent", k);
        const char *dir = test_tmpdir();
        char out[600];
        snprintf(out, sizeof out, "%s/o", dir);
        ck_assert_msg(mc_output_write(out, &s, &r, &err) == MC_OK, "%s", err.msg);
        const int n = 400, both = k == 0;
        double *f[2], *i0[2], *u = NULL, *tf = NULL;
        int rows, cols;
        char path[700];
        static const char *const names[2][2] = {
            {"surface_initial_body1.npy", "surface_initial_body2.npy"},
            {"surface_final_body1.npy", "surface_final_body2.npy"}};
        for (int b = 0; b < 2; b++) {
            snprintf(path, sizeof path, "%s/%s", out, names[0][b]);
            ck_assert(mc_npy_read(path, &i0[b], &rows, &cols, &err) == MC_OK);
            snprintf(path, sizeof path, "%s/%s", out, names[1][b]);
            ck_assert(mc_npy_read(path, &f[b], &rows, &cols, &err) == MC_OK);
        }
        snprintf(path, sizeof path, "%s/residual_displacement.npy", out);
        ck_assert(mc_npy_read(path, &u, &rows, &cols, &err) == MC_OK);
        snprintf(path, sizeof path, "%s/topography_final.npy", out);
        ck_assert(mc_npy_read(path, &tf, &rows, &cols, &err) == MC_OK);
        double *shape = mc_zeros((size_t)n);
        mc_surface_shape(&r.grid, &s.geometry, shape);
        double hmax = 0;
        for (int i = 0; i < n; i++)
            hmax = test_worst(hmax, fabs(shape[i]) + fabs(tf[i]));
        for (int i = 0; i < n; i++) {
            ck_assert_double_eq(f[0][i], i0[0][i] - u[i]);
            ck_assert_double_eq(f[1][i], both ? i0[1][i] - u[i] : i0[1][i]);
            /* composite final = shape - topography_final: 8 eps of the largest height */
            ck_assert_msg(fabs(f[0][i] + f[1][i] - (shape[i] - tf[i])) <= 8 * DBL_EPSILON * hmax,
                          "case %d cell %d: %g vs %g", k, i, f[0][i] + f[1][i],
                          shape[i] - tf[i]);
        }
        ck_assert(r.body_dents[0] && r.body_dents[1] == both);
        /* Ra of the dented body falls; an undented body's stays */
        ck_assert(r.body_roughness_final[0].Sq != r.body_roughness_initial[0].Sq);
        if (!both)
            ck_assert_double_eq(r.body_roughness_final[1].Sq, r.body_roughness_initial[1].Sq);
        for (int b = 0; b < 2; b++) {
            free(f[b]);
            free(i0[b]);
        }
        free(u);
        free(tf);
        mc_free(shape);
        mc_results_free(&r);
    }
}
END_TEST

/* A warning about a body's roughness parameters names the body and its section (its cutoff is
 * its section's): a cut-off of 20 um clipped on the 32 um profiles of body 2 alone. */
START_TEST(body_warning_names_the_body)
{
    const char *dir = test_tmpdir();
    double z[N * N];
    write_map(dir, "a.npy", 0.3e-6, 41, z);
    write_map(dir, "b.npy", 0.2e-6, 42, z);
    const char *set[] = {"roughness.cutoff=8um", "roughness2.cutoff=20um"};
    mc_scene s;
    scene(&s, dir, "a.npy", "b.npy", NULL, 2, set);
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(r.body_roughness_initial[1].cutoff_clipped && !r.body_roughness_initial[0].cutoff_clipped);
    int named = 0;
    for (int k = 0; k < r.nwarnings; k++)
        named |= strstr(r.warnings[k].message, "of body 2 ([roughness2])") &&
                 strstr(r.warnings[k].message, "clipped") != NULL;
    ck_assert_msg(named, "no warning names body 2's clipped cut-off");
    mc_results_free(&r);
}
END_TEST

/* Bad input: the message names the file, the line, the [section] key and what is accepted. */
START_TEST(bad_input)
{
    const char *dir = test_tmpdir();
    double z[N * N];
    write_map(dir, "a.npy", 0.3e-6, 31, z);
    double small[8 * N] = {0};
    char path[600];
    snprintf(path, sizeof path, "%s/small.npy", dir);
    size_t shape[2] = {8, N};
    mc_error err = {0};
    ck_assert(mc_npy_write(path, small, 2, shape, &err) == MC_OK);
    static const struct {
        const char *text;
        const char *want[3];
    } rows[] = {
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness2]\ntype = gaussian\nrq = 0.1 um\n"
         "correlation_x = 4 um\n[load]\nforce = 1 N\n",
         {"c.ini:6:", "[roughness2] (body 2's surface) needs [roughness]", NULL}},
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = file\nfile = a.npy\nscale = 0\n[load]\nforce = 1 N\n",
         {"c.ini:11:", "[roughness2] scale = 0: must not be 0", NULL}},
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = file\nfile = a.npy\nverify_checksum = no\n[load]\nforce = 1 N\n",
         {"c.ini:11:", "[roughness2] verify_checksum has no effect with a npy file", NULL}},
        {"[mesh]\nnx = 16\nny = 1\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = gaussian\nrq = 0.1 um\ncorrelation_x = 4 um\n"
         "correlation_y = 8 um\n[load]\nforce = 1 N\n",
         {"c.ini:12:", "[roughness2] correlation_y has no effect on a grid of one row", NULL}},
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = self_affine\nrq = 0.1 um\nrms_slope = 0.1\n[load]\nforce = 1 N\n",
         {"c.ini:11:", "[roughness2] rms_slope: give exactly one of rq, rms_slope", NULL}},
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = self_affine\nrq = 0.1 um\nlambda_long = 4 um\n"
         "lambda_short = 8 um\n[load]\nforce = 1 N\n",
         {"c.ini:12:", "[roughness2] lambda_short = 8e-06 m: must be < lambda_long = 4e-06 m",
          NULL}},
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = gaussian\nrq = 0.1 um\nhurst = 0.5\n[load]\nforce = 1 N\n",
         {"c.ini:11:", "[roughness2] hurst is not used by type = gaussian", NULL}},
        {"[mesh]\nnx = 16\nny = 16\ndx = 1 um\n[roughness]\ntype = file\nfile = a.npy\n"
         "[roughness2]\ntype = file\n[load]\nforce = 1 N\n",
         {"[roughness2] file is required", NULL, NULL}},
    };
    char name[600];
    snprintf(name, sizeof name, "%s/c.ini", dir);
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        mc_scene s;
        memset(&err, 0, sizeof err);
        ck_assert_int_eq(mc_case_parse_text(rows[k].text, name, dir, 0, NULL, &s, &err),
                         MC_ERR_INPUT);
        for (int w = 0; w < 3 && rows[k].want[w]; w++)
            ck_assert_msg(strstr(err.msg, rows[k].want[w]), "row %zu: '%s' lacks '%s'", k,
                          err.msg, rows[k].want[w]);
    }
    /* maps of two grids: found when the run reads them, naming both files, the mesh and the
     * key to set; and from the mesh of body 1's file too */
    for (int from_file = 0; from_file < 2; from_file++) {
        mc_scene s;
        if (from_file) { /* the mesh from body 1's map (an .npy states no spacing: dx given) */
            static const char *text = "[mesh]\ndx = 2 um\n[roughness]\ntype = file\nfile = a.npy\n"
                                      "[roughness2]\ntype = file\nfile = small.npy\n[load]\n"
                                      "force = 1 N\n";
            memset(&err, 0, sizeof err);
            ck_assert_msg(mc_case_parse_text(text, name, dir, 0, NULL, &s, &err) == MC_OK, "%s",
                          err.msg);
        } else
            scene(&s, dir, "a.npy", "small.npy", NULL, 0, NULL);
        mc_results r;
        memset(&err, 0, sizeof err);
        ck_assert_int_eq(mc_pipeline_run(&s, &r, &err), MC_ERR_INPUT);
        const char *want[] = {"c.ini:", "[roughness2] file", "small.npy", "a.npy",
                              "the two surfaces do not come onto one grid", "16 x 8 points",
                              "the mesh 16 x 16 cells"};
        for (size_t w = 0; w < sizeof want / sizeof want[0]; w++)
            ck_assert_msg(strstr(err.msg, want[w]), "'%s' lacks '%s'", err.msg, want[w]);
        mc_results_free(&r);
    }
}
END_TEST

Suite *suite_two_surfaces(void);
Suite *suite_two_surfaces(void)
{
    Suite *s = suite_create("two_surfaces");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, composite_is_the_sum);
    tcase_add_test(tc, outward_bump_carries_the_load);
    tcase_add_test(tc, swap_gives_same_composite);
    tcase_add_test(tc, final_minus_own_dent);
    tcase_add_test(tc, body_warning_names_the_body);
    tcase_add_test(tc, bad_input);
    suite_add_tcase(s, tc);
    return s;
}
