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
    mc_stage_lube_summary l;
    mc_error err = {0};
    ck_assert_int_eq(mc_stage_lube_macro(&s, &s.grid, &l, &err), MC_OK);
    ck_assert_msg(fabs(l.hertz_half_width - 154.8e-6) <= 0.05e-6, "b = %g", l.hertz_half_width);
    ck_assert_msg(fabs(l.hertz_pressure - 447e6) <= 0.5e6, "p_H = %g", l.hertz_pressure);
    ck_assert_msg(fabs(l.h_ehd - 0.55e-6) <= 0.005e-6, "h_EHD = %g", l.h_ehd);
    /* the patch carries p_H over its area */
    double a_nom = 48 * 48 * 0.8e-6 * 0.8e-6;
    ck_assert(fabs(l.patch_load - l.hertz_pressure * a_nom) <= 1e-12 * l.patch_load);
    ck_assert_double_eq_tol(l.entrainment, 2 * M_PI * 500 / 60 * 0.04, 1e-12);
}
END_TEST

/* Unequal disc radii, rolling and rolling-sliding, against a hand computation: R1 = 30 mm,
 * R2 = 50 mm at 500 rpm. Without rpm2 disc 2 turns at the same surface speed
 * (u2 = u1 = 2 pi 500 0.03 / 60 m/s: pure rolling, SRR 0); with rpm2 = 700 rpm, u2 =
 * 2 pi 700 0.05 / 60, u = (u1 + u2) / 2, SRR = 2 |u1 - u2| / (u1 + u2). The macro contact against
 * the equal-disc case (R = 40 mm: R_x = 20 mm): b ~ sqrt(R_x), R_x = 1 / (1/R1 + 1/R2) = 18.75 mm;
 * the Pan-Hamrock central film at a fixed load per length, H = 2.922 U^0.692 G^0.470 W'^-0.166
 * (Pan & Hamrock 1989) with U ~ u / R_x and W' ~ 1 / R_x: h ~ u^0.692 R_x^0.474. */
START_TEST(unequal_discs_rolling_sliding)
{
    mc_scene s;
    mc_error err = {0};
    mc_stage_lube_summary l0, la, lb;
    load_case(&s, 0, NULL);
    ck_assert_int_eq(mc_stage_lube_macro(&s, &s.grid, &l0, &err), MC_OK);
    s.lubrication.radius1 = 0.030;
    s.lubrication.radius2 = 0.050;
    ck_assert_msg(mc_stage_lube_macro(&s, &s.grid, &la, &err) == MC_OK, "%s", err.msg);
    const double u0 = 2 * M_PI * 500 / 60 * 0.04, u1 = 2 * M_PI * 500 / 60 * 0.03;
    const double rx0 = 0.02, rx = 1 / (1 / 0.03 + 1 / 0.05);
    ck_assert_msg(fabs(la.entrainment - u1) <= 1e-12 * u1, "u = %.17g, want %.17g", la.entrainment,
                  u1);
    ck_assert_msg(la.srr <= 1e-12, "SRR = %g, want 0 (equal surface speeds)", la.srr);
    ck_assert_msg(fabs(la.hertz_half_width / l0.hertz_half_width - sqrt(rx / rx0)) <= 1e-12,
                  "b ratio %.17g", la.hertz_half_width / l0.hertz_half_width);
    double want = pow(u1 / u0, 0.692) * pow(rx / rx0, 0.474);
    ck_assert_msg(fabs(la.h_ehd / l0.h_ehd - want) <= 1e-12 * want, "h ratio %.17g, want %.17g",
                  la.h_ehd / l0.h_ehd, want);
    s.lubrication.rpm2 = 700 * s.lubrication.rpm / 500; /* the same unit as rpm */
    ck_assert_msg(mc_stage_lube_macro(&s, &s.grid, &lb, &err) == MC_OK, "%s", err.msg);
    const double u2 = 2 * M_PI * 700 / 60 * 0.05, u = (u1 + u2) / 2;
    ck_assert_msg(fabs(lb.entrainment - u) <= 1e-12 * u, "u = %.17g, want %.17g", lb.entrainment,
                  u);
    ck_assert_msg(fabs(lb.srr - 2 * fabs(u1 - u2) / (u1 + u2)) <= 1e-12, "SRR = %.17g", lb.srr);
    want = pow(u / u0, 0.692) * pow(rx / rx0, 0.474);
    ck_assert_msg(fabs(lb.h_ehd / l0.h_ehd - want) <= 1e-12 * want, "h ratio %.17g, want %.17g",
                  lb.h_ehd / l0.h_ehd, want);
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
    const mc_stage_lube_summary *l = &r.lube;
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
    tcase_add_test(t, unequal_discs_rolling_sliding);
    tcase_add_test(t, equilibrium_from_the_fields);
    tcase_add_test(t, regimes);
    suite_add_tcase(s, t);
    return s;
}
