/* test_surface_outputs.c - issue 10 items 3 and 4 at the level of a run: [output] x3p writes an
 * X3P beside every surface height map .npy that reads back bit for bit (checksums verified by the
 * reader, records 1-4 present), and summary.json roughness.final of the elastic-plastic stage is
 * the roughness of topography_final computed independently through the library. */
#include <jansson.h>
#include <math.h>
#include <string.h>

#include "case/case.h"
#include "core/alloc.h"
#include "io/npy.h"
#include "pipeline/output.h"
#include "pipeline/pipeline.h"
#include "surface/roughness.h"
#include "surface/surface.h"
#include "surface_file_testkit.h"
#include "test_util.h"

/* cases/elastic_plastic.ini, smaller load steps count kept: it yields (the tips of the
 * asperities) within a fraction of a second */
static const char ep_case[] =
    "[mesh]\nnx = 24\nny = 24\ndx = 8 um\n"
    "[geometry]\nshape = sphere\nradius = 5 mm\n"
    "[roughness]\ntype = gaussian\nrq = 0.2 um\ncorrelation_x = 16 um\ncorrelation_y = 24 um\n"
    "seed = 11\n"
    "[body2]\nrigid = yes\n"
    "[load]\nforce = 1.5 N\n"
    "[plasticity]\nhardening = linear\nyield_stress = 1 GPa\ntangent_modulus = 20 GPa\n"
    "load_steps = 2\n"
    "[output]\nx3p = yes\n";

static void run_case(const char *text, mc_scene *s, mc_results *r)
{
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(text, "t.ini", "", 0, NULL, s, &err) == MC_OK, "%s",
                  err.msg);
    int rc = mc_pipeline_run(s, r, &err);
    ck_assert_msg(rc == MC_OK, "%s", err.msg);
}

static const char *in(const char *dir, const char *name)
{
    static char buf[4][1024];
    static int next;
    char *p = buf[next++ % 4];
    snprintf(p, sizeof buf[0], "%s/%s", dir, name);
    return p;
}

/* name.x3p in dir reads back (MD5s verified) as exactly the field of name.npy and want, on the
 * run's grid (cell centres); main.xml holds records 1 to 4 and md5checksum.hex is there. */
static void check_x3p(const char *dir, const char *stem, const double *want, const mc_grid *g)
{
    char npy[64], x3p[64];
    snprintf(npy, sizeof npy, "%s.npy", stem);
    snprintf(x3p, sizeof x3p, "%s.x3p", stem);
    mc_error err = {0};
    double *a = NULL;
    int rows = 0, cols = 0;
    ck_assert_msg(mc_npy_read(in(dir, npy), &a, &rows, &cols, &err) == MC_OK, "%s", err.msg);
    mc_surface_data s;
    mc_surface_read_options opt = mc_surface_read_defaults(); /* checksums verified */
    ck_assert_msg(mc_surface_file_read(in(dir, x3p), &opt, &s, &err) == MC_OK, "%s", err.msg);
    ck_assert_str_eq(s.format, "x3p");
    ck_assert_int_eq(s.nx, g->nx);
    ck_assert_int_eq(s.ny, g->ny);
    ck_assert_int_eq(rows, g->ny);
    ck_assert_int_eq(cols, g->nx);
    ck_assert(s.valid == NULL && s.missing == 0);
    const size_t n = mc_grid_cells(g);
    ck_assert_msg(memcmp(s.z, a, n * sizeof *a) == 0, "%s: heights differ from %s", x3p, npy);
    ck_assert_msg(memcmp(s.z, want, n * sizeof *a) == 0, "%s: heights differ from the run's",
                  x3p);
    /* spacings and offsets exact (17 digits in main.xml) */
    ck_assert(s.dx == g->dx && s.dy == g->dy);
    ck_assert(s.x0 == mc_grid_x(g, 0) && s.y0 == mc_grid_y(g, 0));
    unsigned char *xml = NULL, *md5 = NULL;
    size_t nxml = 0, nmd5 = 0;
    ck_assert(tk_unzip(in(dir, x3p), "main.xml", &xml, &nxml));
    for (int k = 1; k <= 4; k++) {
        char rec[32];
        snprintf(rec, sizeof rec, "<Record%d>", k);
        ck_assert_msg(tk_contains(xml, nxml, rec), "%s: no %s", x3p, rec);
    }
    ck_assert(tk_unzip(in(dir, x3p), "md5checksum.hex", &md5, &nmd5));
    char hex[33];
    tk_md5(xml, nxml, hex); /* nettle, independent of the writer's MD5 */
    ck_assert_msg(nmd5 >= 32 && memcmp(md5, hex, 32) == 0, "%s: md5checksum.hex", x3p);
    free(xml);
    free(md5);
    mc_surface_data_free(&s);
    mc_free(a);
}

/* The written topography_final.npy read back against its definition (README, results.h): the
 * unloaded gap the next load sees = topography.npy (the initial gap) + residual_displacement.npy
 * (the permanent displacement, positive into the body: a dent opens the gap). The residual must
 * be a dent somewhere (positive, not zero) for the sign to be seen. */
static void check_final_is_topography_plus_residual(const char *dir)
{
    mc_error err = {0};
    double *t = NULL, *u = NULL, *tf = NULL;
    int r1, c1, r2, c2, r3, c3;
    ck_assert_msg(mc_npy_read(in(dir, "topography.npy"), &t, &r1, &c1, &err) == MC_OK, "%s",
                  err.msg);
    ck_assert_msg(mc_npy_read(in(dir, "residual_displacement.npy"), &u, &r2, &c2, &err) == MC_OK,
                  "%s", err.msg);
    ck_assert_msg(mc_npy_read(in(dir, "topography_final.npy"), &tf, &r3, &c3, &err) == MC_OK,
                  "%s", err.msg);
    ck_assert(r1 == r2 && r2 == r3 && c1 == c2 && c2 == c3);
    double umax = 0, scale = 0;
    for (size_t k = 0; k < (size_t)r1 * (size_t)c1; k++) {
        umax = test_worst(umax, u[k]);
        scale = test_worst(scale, fabs(t[k]));
    }
    ck_assert_msg(umax > 1e-3 * scale, "no dent to see the sign by (max residual %g m)", umax);
    for (size_t k = 0; k < (size_t)r1 * (size_t)c1; k++)
        ck_assert_msg(fabs(tf[k] - (t[k] + u[k])) <= 1e-12 * scale,
                      "cell %zu: topography_final %.17g != topography %.17g + residual %.17g", k,
                      tf[k], t[k], u[k]);
    mc_free(t);
    mc_free(u);
    mc_free(tf);
}

/* Elastic-plastic run with x3p = yes: topography.x3p and topography_final.x3p as the .npy; no
 * running-in file. roughness.final = the roughness of (shape - topography_final.npy), computed
 * here with the case's cut-off rule, equal to the last bit (same arithmetic on the same numbers);
 * it differs from roughness.initial (the tips yielded). */
START_TEST(x3p_and_final_roughness_of_an_elastic_plastic_run)
{
    mc_scene s;
    mc_results r;
    run_case(ep_case, &s, &r);
    ck_assert(r.plastic.enabled && !r.plastic.elastic_shortcut);
    ck_assert(r.has_roughness && r.has_roughness_final);
    const char *dir = test_tmpdir();
    mc_error err = {0};
    ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
    check_x3p(dir, "topography", r.topography, &r.grid);
    check_x3p(dir, "topography_final", r.topography_final, &r.grid);
    ck_assert(!tk_exists(in(dir, "surface_final.x3p")));
    ck_assert(!tk_exists(in(dir, "surface_initial.x3p")));
    check_final_is_topography_plus_residual(dir);

    /* the final roughness, independently from the written file */
    double *tf = NULL;
    int rows, cols;
    ck_assert_msg(mc_npy_read(in(dir, "topography_final.npy"), &tf, &rows, &cols, &err) == MC_OK,
                  "%s", err.msg);
    const mc_grid *g = &s.grid;
    const size_t n = mc_grid_cells(g);
    double *h = mc_zeros(n);
    ck_assert(h != NULL);
    mc_surface_shape(g, &s.geometry, h);
    for (size_t k = 0; k < n; k++)
        h[k] -= tf[k];
    mc_roughness_options opt;
    mc_roughness_options_default(&opt);
    opt.cutoff = s.roughness.cutoff;
    mc_roughness_params want;
    ck_assert_msg(mc_roughness_compute(h, NULL, g->nx, g->ny, g->dx, g->dy, &opt, &want, &err) ==
                      MC_OK,
                  "%s", err.msg);
    mc_roughness_entry e[MC_ROUGHNESS_NENTRIES], got[MC_ROUGHNESS_NENTRIES],
        ini[MC_ROUGHNESS_NENTRIES];
    const int ne = mc_roughness_entries(&want, e);
    mc_roughness_entries(&r.roughness_final, got);
    mc_roughness_entries(&r.roughness_initial, ini);
    json_error_t je;
    json_t *root = json_load_file(in(dir, "summary.json"), 0, &je);
    ck_assert_msg(root != NULL, "summary.json: %s", je.text);
    json_t *fin = json_object_get(json_object_get(root, "roughness"), "final");
    ck_assert_msg(json_is_object(fin), "summary.json has no roughness.final");
    int differ = 0;
    for (int k = 0; k < ne; k++) {
        ck_assert_msg(got[k].value == e[k].value, "%s: final %.17g, from the file %.17g",
                      e[k].name, got[k].value, e[k].value);
        json_t *v = json_object_get(fin, e[k].name);
        ck_assert_msg(json_is_number(v) && json_number_value(v) == e[k].value,
                      "summary.json roughness.final.%s", e[k].name);
        /* 1e-6 relative: far above round-off, far below what yielding tips change */
        differ += fabs(ini[k].value - e[k].value) > 1e-6 * fabs(e[k].value);
    }
    ck_assert_msg(differ > 0, "roughness.final equals roughness.initial");
    json_decref(root);
    mc_free(h);
    mc_free(tf);
    mc_results_free(&r);
}
END_TEST

/* Without x3p (the default) no .x3p is written, and a later run into the same directory removes
 * the .x3p files of an earlier one (they are contract files). */
START_TEST(x3p_off_by_default_and_stale_files_removed)
{
    static const char elastic_x3p[] = "[mesh]\nnx = 16\nny = 16\ndx = 2 um\n"
                                      "[geometry]\nshape = sphere\nradius = 5 mm\n"
                                      "[roughness]\ntype = gaussian\nrq = 0.1 um\n"
                                      "correlation_x = 6 um\n"
                                      "[load]\nforce = 0.05 N\n[output]\nx3p = yes\n";
    mc_scene s;
    mc_results r;
    run_case(elastic_x3p, &s, &r);
    ck_assert(s.output.x3p == 1);
    ck_assert(!r.has_roughness_final); /* elastic: no final surface */
    const char *dir = test_tmpdir();
    mc_error err = {0};
    ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
    check_x3p(dir, "topography", r.topography, &r.grid);
    ck_assert(!tk_exists(in(dir, "topography_final.x3p")));
    mc_scene d;
    mc_scene_defaults(&d);
    ck_assert_int_eq(d.output.x3p, 0);
    s.output.x3p = 0;
    ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(!tk_exists(in(dir, "topography.x3p")));
    json_error_t je;
    json_t *root = json_load_file(in(dir, "summary.json"), 0, &je);
    ck_assert(root != NULL);
    ck_assert(!json_object_get(json_object_get(root, "roughness"), "final"));
    json_decref(root);
    mc_results_free(&r);
}
END_TEST

/* A running-in's surface_initial and surface_final get their .x3p too (results of an elastic
 * run dressed as a running-in with no step: the writer goes by the .npy it wrote). */
START_TEST(x3p_of_the_runin_surfaces)
{
    static const char c[] = "[mesh]\nnx = 12\nny = 8\ndx = 2 um\ndy = 3 um\n"
                            "[roughness]\ntype = gaussian\nrq = 0.1 um\ncorrelation_x = 6 um\n"
                            "[load]\nforce = 0.01 N\n[output]\nx3p = yes\n";
    mc_scene s;
    mc_results r;
    run_case(c, &s, &r);
    const size_t n = mc_grid_cells(&r.grid);
    r.surface_initial = mc_zeros(n);
    r.surface_final = mc_zeros(n);
    ck_assert(r.surface_initial && r.surface_final);
    for (size_t k = 0; k < n; k++) {
        r.surface_initial[k] = -r.topography[k];
        r.surface_final[k] = -r.topography[k] * 0.75 + 1e-9 * (double)k;
    }
    r.runin.enabled = 1;
    const char *dir = test_tmpdir();
    mc_error err = {0};
    ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
    check_x3p(dir, "surface_initial", r.surface_initial, &r.grid);
    check_x3p(dir, "surface_final", r.surface_final, &r.grid);
    check_x3p(dir, "topography", r.topography, &r.grid);
    mc_results_free(&r);
}
END_TEST

Suite *suite_surface_outputs(void);
Suite *suite_surface_outputs(void)
{
    Suite *s = suite_create("surface_outputs");
    TCase *t = tcase_create("outputs");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, x3p_and_final_roughness_of_an_elastic_plastic_run);
    tcase_add_test(t, x3p_off_by_default_and_stale_files_removed);
    tcase_add_test(t, x3p_of_the_runin_surfaces);
    suite_add_tcase(s, t);
    return s;
}
