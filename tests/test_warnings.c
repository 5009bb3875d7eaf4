/* test_warnings.c - the warnings of a finished solve (pipeline/warnings.h), on Hertzian contacts
 * whose contact radius a = (3 F R / 4 E*)^(1/3) (Johnson 1985 eq. 4.22) sets what must be warned:
 * the expectations come from the theory and the grid, not from our own outputs. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/case.h"
#include "pipeline/pipeline.h"
#include "pipeline/warnings.h"
#include "test_util.h"

/* steel on steel: E* = E / (2 (1 - nu^2)) */
#define E_STEEL 210e9
#define NU 0.3

static double hertz_radius(double force, double radius)
{
    const double estar = E_STEEL / (2.0 * (1.0 - NU * NU));
    return cbrt(3.0 * force * radius / (4.0 * estar));
}

/* Run the case text; returns the codes of its warnings joined by spaces into buf, and the run's
 * plastic layer thickness in *dz_used when not NULL. plastic: the scene must yield (the plastic
 * loop ran), and a loop that stops short of its tolerance still counts. */
static const char *run_codes(const char *text, int plastic, char *buf, size_t len,
                             double *dz_used)
{
    mc_scene s;
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(text, "w.ini", NULL, 0, NULL, &s, &err) == MC_OK, "%s",
                  err.msg);
    mc_results r;
    const int rc = mc_pipeline_run(&s, &r, &err);
    ck_assert_msg(rc == MC_OK || (plastic && rc == MC_NOT_CONVERGED), "%s", err.msg);
    if (plastic)
        ck_assert_msg(r.plastic.nz > 0 && !r.plastic.elastic_shortcut, "the scene must yield");
    if (dz_used)
        *dz_used = r.plastic.dz;
    buf[0] = '\0';
    for (int k = 0; k < r.nwarnings; k++) {
        ck_assert(r.warnings[k].message[0] != '\0');
        snprintf(buf + strlen(buf), len - strlen(buf), "%s%s", k ? " " : "", r.warnings[k].code);
    }
    mc_results_free(&r);
    return buf;
}

static const char *codes_of(const char *text, char *buf, size_t len)
{
    return run_codes(text, 0, buf, len, NULL);
}

static void sphere(char *text, size_t len, int n, double dx_um, double force, const char *extra)
{
    snprintf(text, len,
             "[mesh]\nnx = %d\nny = %d\ndx = %g um\n[geometry]\nshape = sphere\nradius = 10 mm\n"
             "[load]\nforce = %g N\n[solver]\nthreads = 1\n%s",
             n, n, dx_um, force, extra);
}

/* a = 18.7 um: on 1 um cells of a 64 um grid the contact is resolved (18.7 cells per radius) and
 * 13 um from every edge, its area 27 % of the grid: nothing to warn. */
START_TEST(resolved_contact_raises_none)
{
    ck_assert_double_lt(fabs(hertz_radius(0.1, 0.01) - 18.7e-6), 0.1e-6);
    char text[512], codes[256];
    sphere(text, sizeof text, 64, 1.0, 0.1, "");
    ck_assert_str_eq(codes_of(text, codes, sizeof codes), "");
}
END_TEST

/* the same contact on 4 um cells: a / dx = 4.7 < 10, the contact still inside the grid */
START_TEST(coarse_cells)
{
    const double a = hertz_radius(0.1, 0.01);
    ck_assert_double_lt(a / 4e-6, MC_WARN_CELLS_PER_RADIUS);
    char text[512], codes[256];
    sphere(text, sizeof text, 16, 4.0, 0.1, "");
    ck_assert_str_eq(codes_of(text, codes, sizeof codes), "coarse_contact");
}
END_TEST

/* the same contact on a 32 um grid: a = 18.7 um > 16 um, the half-width of the grid */
START_TEST(contact_beyond_the_grid)
{
    ck_assert_double_gt(hertz_radius(0.1, 0.01), 16e-6);
    char text[512], codes[256];
    sphere(text, sizeof text, 64, 0.5, 0.1, "");
    const char *c = codes_of(text, codes, sizeof codes);
    ck_assert_msg(strstr(c, "contact_at_edge") != NULL, "codes: %s", c);
    ck_assert_msg(strstr(c, "coarse_contact") == NULL, "codes: %s", c);
}
END_TEST

/* E = 1 MPa: the mean pressure over the grid, F / A = 24 MPa, is above E* = 0.55 MPa, so p_max
 * (>= the mean) is too, whatever the solve */
START_TEST(pressure_above_moduli)
{
    char text[512], codes[256];
    sphere(text, sizeof text, 64, 1.0, 0.1, "[body1]\nE = 1 MPa\n[body2]\nE = 1 MPa\n");
    const char *c = codes_of(text, codes, sizeof codes);
    ck_assert_msg(strstr(c, "pressure_above_moduli") != NULL, "codes: %s", c);
}
END_TEST

/* a flat rough patch under a nominal load: its contact touches the free edges by nature (a piece
 * of a larger nominal contact), no contact_at_edge */
START_TEST(flat_patch_edges_are_no_warning)
{
    char codes[256];
    const char *text = "[mesh]\nnx = 32\nny = 32\ndx = 4 um\n[roughness]\ntype = gaussian\n"
                       "rq = 0.2 um\ncorrelation_x = 20 um\ncorrelation_y = 20 um\ncutoff = 16 um\n"
                       "[load]\nforce = 1 N\n[solver]\nthreads = 1\n";
    const char *c = codes_of(text, codes, sizeof codes);
    ck_assert_msg(strstr(c, "contact_at_edge") == NULL, "codes: %s", c);
}
END_TEST

/* An elastic-plastic line contact (periodic y, ny = 1): the residual stress operator's x-z
 * checkerboard mode releases energy for 0.6 < dz/dx < 1.6 (docs/theory.md §8.5), so dz = dx is
 * warned; the default there is dx / 2, which is not. */
static const char *line_codes(const char *dz, char *buf, size_t len, double *dz_used)
{
    char text[700];
    snprintf(text, sizeof text,
             "[mesh]\nnx = 41\nny = 1\ndx = 20 um\nperiodic_y = yes\n[geometry]\nshape = "
             "cylinder\nradius = 10 mm\n[body2]\nrigid = yes\n[load]\nforce_per_length = "
             "550 kN/m\n[plasticity]\nyield_stress = 1 GPa\n%s[solver]\nthreads = 1\n",
             dz);
    return run_codes(text, 0, buf, len, dz_used);
}

START_TEST(line_grid_checkerboard_band)
{
    char codes[256];
    double dz;
    const char *c = line_codes("dz = 20 um\nstress_points = centre\n", codes, sizeof codes, &dz);
    ck_assert_double_eq_tol(dz, 20e-6, 1e-12);
    ck_assert_msg(strstr(c, "plastic_checkerboard") != NULL, "codes: %s", c);
    /* the default evaluation, cell averages, has no such mode (theory.md §8.7) */
    c = line_codes("dz = 20 um\n", codes, sizeof codes, &dz);
    ck_assert_msg(strstr(c, "plastic_checkerboard") == NULL, "codes: %s", c);
    c = line_codes("", codes, sizeof codes, &dz);
    ck_assert_double_eq_tol(dz, 10e-6, 1e-12); /* the line grid's default: dx / 2 */
    ck_assert_msg(strstr(c, "plastic_checkerboard") == NULL, "codes: %s", c);
    c = line_codes("dz = 34 um\nstress_points = centre\n", codes, sizeof codes, &dz); /* 1.7 dx */
    ck_assert_msg(strstr(c, "plastic_checkerboard") == NULL, "codes: %s", c);
}
END_TEST

/* The same band in 3-D (docs/theory.md §8.5; tests/test_eigen_checkerboard.c): a rigid sphere
 * on a perfectly plastic half-space (about 2 P_c), 15 x 15 cells; dz = dx is warned, the default
 * min(dx, dy) / 2 is not, nor is dz = 1.7 dy with dx = dy. */
static const char *sphere_codes(const char *dz, char *buf, size_t len, double *dz_used)
{
    char text[700];
    snprintf(text, sizeof text,
             "[mesh]\nnx = 15\nny = 15\ndx = 40 um\n[geometry]\nshape = sphere\nradius = 15 mm\n"
             "[body2]\nrigid = yes\n[load]\nforce = 200 N\n[plasticity]\nyield_stress = 1 GPa\n"
             "load_steps = 1\ndepth = 240 um\n%s[solver]\nthreads = 1\n",
             dz);
    return run_codes(text, 1, buf, len, dz_used);
}

START_TEST(sphere_checkerboard_band)
{
    char codes[256];
    double dz;
    const char *c = sphere_codes("dz = 40 um\nstress_points = centre\n", codes, sizeof codes, &dz);
    ck_assert_msg(strstr(c, "plastic_checkerboard") != NULL, "codes: %s", c);
    c = sphere_codes("dz = 40 um\n", codes, sizeof codes, &dz); /* cell averages: no band */
    ck_assert_msg(strstr(c, "plastic_checkerboard") == NULL, "codes: %s", c);
    c = sphere_codes("", codes, sizeof codes, &dz);
    ck_assert_double_eq_tol(dz, 20e-6, 1e-12); /* the default: min(dx, dy) / 2 */
    ck_assert_msg(strstr(c, "plastic_checkerboard") == NULL, "codes: %s", c);
    c = sphere_codes("dz = 68 um\nstress_points = centre\n", codes, sizeof codes, &dz); /* 1.7 dx */
    ck_assert_msg(strstr(c, "plastic_checkerboard") == NULL, "codes: %s", c);
}
END_TEST

/* plastic_checkered: the detector on fields whose answer is known by construction. A smooth
 * bump (a Gaussian in x, y, z) has local extrema only at its top: far below the threshold; the
 * same bump times (1 + 0.5 (-1)^(i+k)) zigzags along x in every significant cell. Mutation tried:
 * the opposite sign test in the detector counts the smooth bump's monotone slopes (0.93: red). */
START_TEST(checkered_fraction_of_known_fields)
{
    const mc_grid g = {24, 20, 1e-6, 1e-6, 0, 0};
    const int nz = 6;
    const size_t n = (size_t)nz * 24 * 20;
    double *smooth = malloc(n * sizeof *smooth), *checker = malloc(n * sizeof *checker);
    ck_assert(smooth && checker);
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < 20; j++)
            for (int i = 0; i < 24; i++) {
                const size_t v = ((size_t)k * 20 + j) * 24 + i;
                const double r2 = (i - 11.5) * (i - 11.5) / 30.0 + (j - 9.5) * (j - 9.5) / 20.0 +
                                  (k - 2.0) * (k - 2.0) / 4.0;
                smooth[v] = 1e-3 * exp(-r2);
                checker[v] = smooth[v] * (1.0 + 0.5 * (((i + k) % 2) ? -1.0 : 1.0));
            }
    const double fs = mc_stage_plastic_checkered_fraction(&g, nz, smooth);
    const double fc = mc_stage_plastic_checkered_fraction(&g, nz, checker);
    ck_assert_msg(fs < 0.1, "smooth bump: %g", fs);
    ck_assert_msg(fc > MC_WARN_CHECKERED, "checkerboard: %g", fc);
    /* isolated one-cell spikes (asperity tips under a rough load), three cells apart: every
     * significant cell is an extremum, none has an extremum beside it: not a checkerboard
     * (counted 100 % before the neighbour rule; a rough line contact was flagged so) */
    double *spikes = calloc(n, sizeof *spikes);
    ck_assert(spikes);
    for (int k = 0; k < nz; k++)
        for (int j = 1; j < 19; j += 3)
            for (int i = 1; i < 23; i += 3)
                spikes[((size_t)k * 20 + j) * 24 + i] = 1e-3 * (1.0 + 0.1 * k);
    const double fp = mc_stage_plastic_checkered_fraction(&g, nz, spikes);
    ck_assert_msg(fp < 0.1, "isolated spikes: %g", fp);
    free(spikes);
    for (size_t v = 0; v < n; v++)
        smooth[v] = 0.0;
    ck_assert_double_eq(mc_stage_plastic_checkered_fraction(&g, nz, smooth), 0.0);
    free(smooth), free(checker);
}
END_TEST

Suite *suite_warnings(void);
Suite *suite_warnings(void)
{
    Suite *s = suite_create("warnings");
    TCase *t = tcase_create("hertz");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, resolved_contact_raises_none);
    tcase_add_test(t, coarse_cells);
    tcase_add_test(t, contact_beyond_the_grid);
    tcase_add_test(t, pressure_above_moduli);
    tcase_add_test(t, flat_patch_edges_are_no_warning);
    tcase_add_test(t, line_grid_checkerboard_band);
    tcase_add_test(t, checkered_fraction_of_known_fields);
    tcase_add_test(t, sphere_checkerboard_band);
    suite_add_tcase(s, t);
    return s;
}
