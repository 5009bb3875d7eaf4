/* test_stage_lube.c - the lubrication stage of the pipeline: a case's [lubrication] turned into
 * the macro contact, the film and the volume equilibrium, checked from the output fields alone. */
#include <math.h>
#include <string.h>

#include "case/case.h"
#include "core/alloc.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_lube.h"
#include "test_util.h"

/* The twin-disc case of the paper's rig as a rough periodic patch (cases/lubricated_equilibrium.ini) */
static const char *CASE_TEXT = "[mesh]\nnx = 48\nny = 48\ndx = 0.8 um\nperiodic_x = yes\n"
                               "periodic_y = yes\n[roughness]\ntype = gaussian\nrq = 0.3 um\n"
                               "correlation_x = 4 um\ncorrelation_y = 12 um\nseed = 7\n"
                               "[load]\nforce = 1086 N\nlubricant_pressure = auto\n"
                               "[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\n"
                               "rpm = 500 rpm\nradius1 = 40 mm\nradius2 = 40 mm\nwidth = 10 mm\n"
                               "mu_solid = 0.12\nmu_fluid = 0.03\n";

static void load_case(mc_scene *s, int nset, const char *const *set)
{
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(CASE_TEXT, "lube.ini", "", nset, set, s, &err) == MC_OK,
                  "%s", err.msg);
}

/* The macro contact: b, p_H of the dossier's disc case (Hertz line, 1086 N on 10 mm, R = 40 mm
 * discs: b = 154.8 um, p_H = 447 MPa, printed to 4 and 3 digits) and the Pan-Hamrock central
 * film at 500 rpm, eta0 = 0.03 Pa s (0.55 um in pl_ehl_film_disc_case.csv, 2 digits). */
START_TEST(macro_contact_of_the_disc_case)
{
    mc_scene s;
    load_case(&s, 0, NULL);
    mc_lube_summary l;
    mc_error err = {0};
    ck_assert_int_eq(mc_lube_macro(&s, &s.grid, &l, &err), MC_OK);
    ck_assert_msg(fabs(l.hertz_half_width - 154.8e-6) <= 0.05e-6, "b = %g", l.hertz_half_width);
    ck_assert_msg(fabs(l.hertz_pressure - 447e6) <= 0.5e6, "p_H = %g", l.hertz_pressure);
    ck_assert_msg(fabs(l.h_ehd - 0.55e-6) <= 0.005e-6, "h_EHD = %g", l.h_ehd);
    /* the patch carries p_H over its area */
    double a_nom = 48 * 48 * 0.8e-6 * 0.8e-6;
    ck_assert(fabs(l.patch_load - l.hertz_pressure * a_nom) <= 1e-12 * l.patch_load);
    ck_assert_double_eq_tol(l.entrainment, 2 * M_PI * 500 / 60 * 0.04, 1e-12);
}
END_TEST

/* The whole run: the root holds on the output gap (V = dA sum g = h_EHD A_nom to the root
 * tolerance 1e-6 plus the contact tolerance's share), the load splits into solid and fluid parts
 * (F_solid + p_lub A_free = patch load, to the contact tolerance), mu is the mix of its psi. */
START_TEST(equilibrium_from_the_fields)
{
    mc_scene s;
    load_case(&s, 0, NULL);
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    const mc_lube_summary *l = &r.lube;
    ck_assert_str_eq(l->regime, "mixed");
    const size_t n = mc_grid_cells(&r.grid);
    const double dA = mc_grid_cell_area(&r.grid), a_nom = dA * (double)n;
    double v = 0, f_solid = 0, a_c = 0;
    for (size_t i = 0; i < n; i++) {
        v += dA * r.gap[i];
        if (r.pressure[i] > l->p_lub) {
            f_solid += dA * r.pressure[i];
            a_c += dA;
        }
    }
    ck_assert_msg(fabs(v - l->h_ehd * a_nom) <= 2e-6 * l->h_ehd * a_nom, "V = %g, V* = %g", v,
                  l->h_ehd * a_nom);
    double f = f_solid + l->p_lub * (a_nom - a_c);
    ck_assert_msg(fabs(f - l->patch_load) <= 1e-6 * l->patch_load, "F = %g of %g", f,
                  l->patch_load);
    ck_assert(l->p_lub > 0 && l->p_lub < l->nominal_pressure);
    ck_assert_double_eq_tol(l->psi_load, f_solid / l->patch_load, 1e-12);
    ck_assert_double_eq_tol(l->mu, l->psi_load * 0.12 + (1 - l->psi_load) * 0.03, 1e-14);
    mc_results_free(&r);
}
END_TEST

/* The limits: a film far thicker than the roughness is full film (no solid contact, mu = mu_fluid),
 * a film far thinner is dry (p_lub = 0, mu = mu_solid). */
START_TEST(regimes)
{
    mc_scene s;
    load_case(&s, 0, NULL);
    s.lubrication.film = MC_FILM_GIVEN;
    s.lubrication.film_thickness = 5e-6;
    s.lubrication.macro_radius = 0.02;
    s.lubrication.rpm = 0;
    s.lubrication.radius1 = s.lubrication.radius2 = 0;
    mc_results r;
    mc_error err = {0};
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert_str_eq(r.lube.regime, "full_film");
    ck_assert_double_eq_tol(r.lube.mu, 0.03, 1e-15);
    mc_results_free(&r);
    s.lubrication.film_thickness = 1e-9;
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert_str_eq(r.lube.regime, "dry");
    ck_assert_double_eq(r.lube.p_lub, 0.0);
    ck_assert_double_eq_tol(r.lube.mu, 0.12, 1e-12);
    mc_results_free(&r);
}
END_TEST

Suite *suite_stage_lube(void);
Suite *suite_stage_lube(void)
{
    Suite *s = suite_create("stage_lube");
    TCase *t = tcase_create("stage");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, macro_contact_of_the_disc_case);
    tcase_add_test(t, equilibrium_from_the_fields);
    tcase_add_test(t, regimes);
    suite_add_tcase(s, t);
    return s;
}
