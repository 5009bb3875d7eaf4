/* test_plastic_stage.c - the elastic-plastic stage through the pipeline: the elastic shortcut
 * below yield onset, first yield at the depth of the von Mises maximum, the two backends of the
 * eigenstrain operators giving the same run, the pressure-cap criterion, and the [plasticity]
 * input rules. The Kogut-Etsion and Swift benchmarks are verification suites (verify/). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "pipeline/pipeline.h"
#include "reference/hertz.h"
#include "test_util.h"

/* A rigid sphere R = 15 mm on an elastic-perfectly plastic half-space (E = 210 GPa, nu = 0.3,
 * Y = 1 GPa): the Kogut-Etsion benchmark geometry (docs/theory.md §9.3), P_c = 91.96 N. */
static const char *SPHERE = "[mesh]\nnx = 20\nny = 20\ndx = 40 um\n[geometry]\nshape = sphere\n"
                            "radius = 15 mm\n[body2]\nrigid = yes\n[load]\nforce = %g N\n"
                            "[plasticity]\nyield_stress = 1 GPa\nload_steps = %d\n%s";

static void sphere(mc_scene *s, double force, int steps, const char *extra)
{
    char text[1024];
    snprintf(text, sizeof text, SPHERE, force, steps, extra);
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(text, "p.ini", "", 0, NULL, s, &err) == MC_OK, "%s",
                  err.msg);
}

/* Below the onset (p0 = 1.613 Y) nothing yields: the stage takes the elastic shortcut, and the
 * final topography is the initial one. 0.7 P_c gives p0 = 0.7^(1/3) 1.615 Y = 1.43 Y. */
START_TEST(elastic_below_onset)
{
    mc_scene s;
    sphere(&s, 0.7 * 91.96, 4, "");
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(r.plastic.enabled && r.plastic.elastic_shortcut && r.plastic.converged);
    ck_assert(r.plastic.vm_elastic_max < 1e9);
    ck_assert_double_eq(r.plastic.peq_max, 0.0);
    for (size_t i = 0; i < mc_grid_cells(&r.grid); i++)
        ck_assert_double_eq(r.topography_final[i], r.topography[i]);
    mc_results_free(&r);
}
END_TEST

/* Just above onset (2 P_c): plastic strain appears below the surface, at the depth of the
 * elastic von Mises maximum, 0.48 a (Johnson 1985), within one layer; the surface sinks (a dent,
 * residual displacement > 0 into the body) and every load step converged. The load is carried. */
START_TEST(first_yield_below_the_surface)
{
    mc_scene s;
    sphere(&s, 2 * 91.96, 4, "");
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    const mc_stage_plastic_summary *q = &r.plastic;
    ck_assert(!q->elastic_shortcut && q->converged && q->steps_done == 4);
    ck_assert(q->peq_max > 0);
    mc_hertz_point hz;
    ck_assert_int_eq(mc_hertz_point_from_load(15e-3, 210e9 / (1 - 0.09), 2 * 91.96, &hz, &err),
                     MC_OK);
    double zref = 0.481 * hz.a;
    ck_assert_msg(fabs(q->peq_max_at[2] - zref) <= q->dz, "peq max at z = %g, 0.481 a = %g",
                  q->peq_max_at[2], zref);
    ck_assert(q->residual_max > 0);
    /* the dent is at the centre of the contact */
    double umax = 0;
    size_t imax = 0;
    for (size_t i = 0; i < mc_grid_cells(&r.grid); i++)
        if (r.residual_displacement[i] > umax) {
            umax = r.residual_displacement[i];
            imax = i;
        }
    int ic = (int)(imax % (size_t)r.grid.nx), jc = (int)(imax / (size_t)r.grid.nx);
    ck_assert_msg(abs(ic - 10) <= 1 && abs(jc - 10) <= 1, "dent at (%d, %d)", ic, jc);
    double load = 0;
    for (size_t i = 0; i < mc_grid_cells(&r.grid); i++)
        load += r.pressure[i] * mc_grid_cell_area(&r.grid);
    ck_assert(fabs(load - 2 * 91.96) <= 1e-6 * 2 * 91.96);
    mc_results_free(&r);
}
END_TEST

/* The same run on the direct backend (O(N^2) sums of every operator, the eigenstrain ones
 * included) and on the fft backend: the same plastic strain and residual displacement to the
 * iteration tolerances (outer 1e-3 relative of the residual displacement, set tighter here). */
START_TEST(backends_agree)
{
    const char *tight = "tolerance = 1e-7\nmax_outer = 200\nplastic_tolerance = 1e-10\n"
                        "max_plastic = 400\n";
    mc_scene a, b;
    sphere(&a, 2 * 91.96, 2, tight);
    a.grid.nx = a.grid.ny = 12;
    a.grid.dx = a.grid.dy = 60e-6;
    b = a;
    b.solver.backend = MC_BACKEND_DIRECT;
    mc_results ra, rb;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&a, &ra, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_pipeline_run(&b, &rb, &err) == MC_OK, "%s", err.msg);
    ck_assert(ra.plastic.peq_max > 0);
    ck_assert_int_eq(ra.plastic.nz, rb.plastic.nz);
    size_t n = mc_grid_cells(&ra.grid), nv = n * (size_t)ra.plastic.nz;
    double du = test_rel_maxdiff(rb.residual_displacement, ra.residual_displacement, n);
    double dp = test_rel_maxdiff(rb.plastic_strain, ra.plastic_strain, nv);
    ck_assert_msg(du < 1e-5 && dp < 1e-5, "residual displacement %g, plastic strain %g", du, dp);
    mc_results_free(&ra);
    mc_results_free(&rb);
}
END_TEST

/* Graded layers (docs/theory.md §8.8, the default with depth = auto) against uniform ones on the
 * 2 P_c sphere: the summary records the layering (thicknesses summing to the depth, odd counts),
 * and the dent and the plastic volume agree within the depth discretisation of the graded layers
 * (midpoint rule in depth over layers of up to grading x their depth). Here the grading is twice
 * the default, 0.5, from fine_depth = 2 dx, so that the plastic zone (~0.5 a, 5 layers of dz deep)
 * lies in layers of 3 dz: measured -2.2 % dent, +6.4 % plastic volume (a yielded layer counts
 * whole), bounds 4 % and 10 %. (With the defaults the zone stays in the fine layers here and the
 * runs agree to round-off; the default's figures on finer scenes are the bench's row "graded
 * against uniform" and the note of issue 20: -0.07 % and -0.3 % dent.) */
START_TEST(graded_layers)
{
    mc_scene g, u;
    sphere(&g, 2 * 91.96, 4, "fine_depth = 40 um\ngrading = 0.5\n");
    sphere(&u, 2 * 91.96, 4, "layering = uniform\n");
    mc_results rg, ru;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&g, &rg, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_pipeline_run(&u, &ru, &err) == MC_OK, "%s", err.msg);
    const mc_stage_plastic_summary *a = &rg.plastic, *b = &ru.plastic;
    ck_assert_str_eq(a->layering, "graded");
    ck_assert_str_eq(b->layering, "uniform");
    ck_assert(a->group != NULL && b->group == NULL && a->nz < b->nz);
    int fine = 0, thick = 0;
    for (int k = 0; k < a->nz; k++) {
        ck_assert(a->group[k] % 2 == 1);
        fine += a->group[k];
        thick += a->group[k] > 1;
    }
    ck_assert_int_gt(thick, 0);
    ck_assert(fabs(fine * a->dz - a->depth) <= 1e-12 * a->depth);
    const double ed = a->residual_max / b->residual_max - 1;
    const double ev = a->plastic_volume / b->plastic_volume - 1;
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "graded %d layers against uniform %d: dent %+.3g, plastic volume %+.3g\n",
                a->nz, b->nz, ed, ev);
    ck_assert_msg(fabs(ed) < 0.04 && fabs(ev) < 0.10, "dent %+.3g, plastic volume %+.3g", ed, ev);
    mc_results_free(&rg);
    mc_results_free(&ru);
}
END_TEST

/* The spectral kernel (docs/theory.md §8.10; [plasticity] kernel = spectral, the default) against
 * the cuboid kernel on the 2 P_c sphere: two lateral discretisations of the same plastic strain,
 * which agree to the discretisation error (the plastic zone spans ~5 cells: a few per cent); both
 * backends of the spectral kernel give the same run (on 12^2: the direct one is O(N^2 nz^2)).
 * Measured: dent +4.3 %, plastic volume -6.4 %, peak plastic strain +2.3 %; direct vs fft 1e-14. */
START_TEST(spectral_kernel)
{
    const char *tight = "tolerance = 1e-7\nmax_outer = 200\nplastic_tolerance = 1e-10\n"
                        "max_plastic = 400\n";
    char extra[256];
    char cub[256];
    mc_scene c, sp, sd;
    snprintf(cub, sizeof cub, "%skernel = cuboid\n", tight);
    sphere(&c, 2 * 91.96, 2, cub);
    snprintf(extra, sizeof extra, "%skernel = spectral\n", tight);
    sphere(&sp, 2 * 91.96, 2, extra);
    mc_scene sf;
    sphere(&sf, 2 * 91.96, 2, extra); /* the backends on a coarser grid (the direct one is O(N^2)) */
    sf.grid.nx = sf.grid.ny = 12;
    sf.grid.dx = sf.grid.dy = 60e-6;
    sd = sf;
    sd.solver.backend = MC_BACKEND_DIRECT;
    mc_results rc, rs, rd, rf;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&c, &rc, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_pipeline_run(&sp, &rs, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_pipeline_run(&sd, &rd, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(mc_pipeline_run(&sf, &rf, &err) == MC_OK, "%s", err.msg);
    ck_assert_str_eq(rs.plastic.kernel, "spectral");
    ck_assert_str_eq(rc.plastic.kernel, "cuboid");
    ck_assert(rs.plastic.converged && rc.plastic.converged);
    const mc_stage_plastic_summary *a = &rs.plastic, *b = &rc.plastic;
    const double ed = a->residual_max / b->residual_max - 1;
    const double ev = a->plastic_volume / b->plastic_volume - 1;
    const double ep = a->peq_max / b->peq_max - 1;
    const size_t n = mc_grid_cells(&rf.grid), nv = n * (size_t)rf.plastic.nz;
    ck_assert(rf.plastic.peq_max > 0);
    const double du = test_rel_maxdiff(rd.residual_displacement, rf.residual_displacement, n);
    const double dp = test_rel_maxdiff(rd.plastic_strain, rf.plastic_strain, nv);
    if (getenv("MC_TEST_VERBOSE"))
        fprintf(stderr, "spectral against cuboid: dent %+.3g, plastic volume %+.3g, peak strain "
                        "%+.3g; spectral direct vs fft %.3g, %.3g\n",
                ed, ev, ep, du, dp);
    ck_assert_msg(fabs(ed) < 0.05 && fabs(ev) < 0.10 && fabs(ep) < 0.05,
                  "dent %+.3g, plastic volume %+.3g, peak %+.3g", ed, ev, ep);
    ck_assert_msg(du < 1e-5 && dp < 1e-5, "spectral backends: %g, %g", du, dp);
    mc_results_free(&rc);
    mc_results_free(&rs);
    mc_results_free(&rd);
    mc_results_free(&rf);
}
END_TEST

/* criterion = pressure_cap: no pressure above the hardness, the penetration at capped cells is
 * the permanent deformation, and nothing else deforms. */
START_TEST(pressure_cap_criterion)
{
    mc_scene s;
    char extra[] = "";
    char text[1024];
    snprintf(text, sizeof text,
             "[mesh]\nnx = 20\nny = 20\ndx = 40 um\n[geometry]\nshape = sphere\nradius = 15 mm\n"
             "[body2]\nrigid = yes\n[load]\nforce = 183.92 N\n[plasticity]\n"
             "criterion = pressure_cap\nhardness = 1.6 GPa\n%s",
             extra);
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(text, "c.ini", "", 0, NULL, &s, &err) == MC_OK, "%s",
                  err.msg);
    mc_results r;
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert_str_eq(r.plastic.criterion, "pressure_cap");
    int capped = 0;
    for (size_t i = 0; i < mc_grid_cells(&r.grid); i++) {
        ck_assert(r.pressure[i] <= 1.6e9 * (1 + 1e-12));
        if (r.residual_displacement[i] > 0) {
            capped++;
            ck_assert(r.pressure[i] >= 1.6e9 * (1 - 1e-9));
            ck_assert_double_eq_tol(r.residual_displacement[i], -r.gap[i], 1e-18);
        }
    }
    ck_assert(capped > 0 && r.plastic.residual_max > 0);
    mc_results_free(&r);
}
END_TEST

/* Bad [plasticity] input: exit-2 class errors naming the key. */
typedef struct {
    const char *extra; /* appended to a valid [plasticity] section */
    const char *want;
} bad_row;

static const bad_row bad_rows[] = {
    {"yield_stress = -1 GPa\n", "[plasticity] yield_stress = -1 GPa"},
    {"depth = 0 um\n", "[plasticity] depth = 0 um"},
    {"hardening = linear\nyield_stress = 1 GPa\ntangent_modulus = 300 GPa\n", "tangent_modulus"},
    {"relaxation = 0\n", "[plasticity] relaxation = 0"},
    {"hardening = swift\nswift_B = 1280 MPa\nswift_C = 4\nswift_n = 1.5\n", "swift_n = 1.5"},
    {"criterion = pressure_cap\n", "[plasticity] hardness is required"},
    {"bodies = both\n", "bodies = both needs body 2 of the same material"},
};

START_TEST(bad_input)
{
    const bad_row *b = &bad_rows[_i];
    char text[1024];
    int yield = strstr(b->extra, "yield_stress") == NULL && strstr(b->extra, "hardening") == NULL &&
                strstr(b->extra, "criterion") == NULL;
    snprintf(text, sizeof text,
             "[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[geometry]\nshape = sphere\nradius = 1 mm\n"
             "[body2]\n%s[load]\nforce = 1 N\n[plasticity]\n%s%s",
             strstr(b->extra, "both") ? "E = 200 GPa\n" : "rigid = yes\n",
             yield ? "yield_stress = 1 GPa\n" : "", b->extra);
    mc_scene s;
    mc_error err = {0};
    ck_assert_int_eq(mc_case_parse_text(text, "b.ini", "", 0, NULL, &s, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, b->want) && strstr(err.msg, "b.ini"), "row %d: %s", _i,
                  err.msg);
}
END_TEST

/* nu = 0.5 with plasticity; a table that is not increasing (naming its file and row). */
START_TEST(bad_material)
{
    mc_scene s;
    mc_error err = {0};
    const char *t = "[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[body1]\nnu = 0.5\n[load]\nforce = 1 N\n"
                    "[plasticity]\nyield_stress = 1 GPa\n";
    ck_assert_int_eq(mc_case_parse_text(t, "n.ini", "", 0, NULL, &s, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "[body1] nu = 0.5 with [plasticity]"), "%s", err.msg);
    char path[600], text[1200];
    snprintf(path, sizeof path, "%s/law.csv", test_tmpdir());
    FILE *f = fopen(path, "w");
    fprintf(f, "eps_p,sigma_y\n0,1000\n0.01,1200\n0.02,1100\n");
    fclose(f);
    snprintf(text, sizeof text,
             "[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[geometry]\nshape = sphere\nradius = 1 mm\n"
             "[load]\nforce = 1 N\n[plasticity]\nhardening = table\ntable = %s\n",
             path);
    /* the table is read with the case (issue 23): bad input of the case file, named there */
    ck_assert_int_eq(mc_case_parse_text(text, "t.ini", "", 0, NULL, &s, &err), MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "law.csv") && strstr(err.msg, "[plasticity] table") &&
                      strstr(err.msg, "t.ini:"),
                  "%s", err.msg);
}
END_TEST

Suite *suite_plastic_stage(void);
Suite *suite_plastic_stage(void)
{
    Suite *s = suite_create("plastic_stage");
    TCase *t = tcase_create("stage");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, elastic_below_onset);
    tcase_add_test(t, first_yield_below_the_surface);
    tcase_add_test(t, backends_agree);
    tcase_add_test(t, graded_layers);
    tcase_add_test(t, spectral_kernel);
    tcase_add_test(t, pressure_cap_criterion);
    suite_add_tcase(s, t);
    TCase *b = tcase_create("input");
    tcase_add_loop_test(b, bad_input, 0, (int)(sizeof bad_rows / sizeof bad_rows[0]));
    tcase_add_test(b, bad_material);
    suite_add_tcase(s, b);
    return s;
}
