/* test_lube_film.c - EHL film formulas, disc kinematics and the macro Hertz line contact
 * (lube/film.h) against the dossier's disc case (theory.md §10.4,
 * pl_ehl_film_disc_case.csv) and hand values. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lube/film.h"
#include "reference/hertz.h"
#include "test_util.h"

/* The disc case of theory.md §10.4: two steel discs R1 = R2 = 40 mm, width 10 mm, F_N = 1086 N,
 * pure rolling, alpha = 2e-8 1/Pa. */
static const double E_STEEL = 210e9, NU_STEEL = 0.3, R_DISC = 0.040, WIDTH = 0.010,
                    FORCE = 1086.0, ALPHA = 2e-8;

/* The CSV prints the film thickness in um with 4 decimals, so an exact evaluation of the same
 * formula differs from it by at most half a unit of that digit; the slack covers the binary
 * representation of the printed decimals. */
#define TOL_CSV_UM (0.5e-4 * (1 + 1e-9))
/* U, W' and v_Sigma are printed with 5 significant digits (G with 5 as well): half a unit of the
 * last printed digit relative to the leading one. */
static double printed_half_unit(double printed, int decimals_of_mantissa)
{
    double e = floor(log10(fabs(printed)));
    return 0.5 * pow(10.0, e - decimals_of_mantissa) * (1 + 1e-9);
}

static int column(char header[][32], int cols, const char *name)
{
    size_t len = strlen(name);
    for (int c = 0; c < cols; c++) /* the table has CRLF line ends: ignore a trailing '\r' */
        if (strncmp(header[c], name, len) == 0 && (header[c][len] == 0 || header[c][len] == '\r'))
            return c;
    ck_abort_msg("column %s missing in pl_ehl_film_disc_case.csv", name);
    return -1;
}

START_TEST(csv_disc_case)
{
    double *d;
    int cols;
    char hdr[16][32];
    int rows = test_read_csv("pl_ehl_film_disc_case.csv", &d, &cols, hdr, 16);
    ck_assert_int_ge(rows, 10);
    const int c_eta = column(hdr, cols, "eta0_Pas"), c_n = column(hdr, cols, "n_rpm"),
              c_v = column(hdr, cols, "v_sum_mps"), c_U = column(hdr, cols, "U"),
              c_G = column(hdr, cols, "G"), c_W = column(hdr, cols, "W_line");
    const struct {
        const char *col;
        mc_film_formula f;
    } cmp[] = {{"h_min_DowsonHigginson_um", MC_FILM_DOWSON_HIGGINSON},
               {"h_c_DowsonToyoda_um", MC_FILM_DOWSON_TOYODA},
               {"h_min_PanHamrock_um", MC_FILM_PAN_HAMROCK_MIN},
               {"h_c_PanHamrock_um", MC_FILM_PAN_HAMROCK_CENTRAL}};
    mc_error err = {0};
    double ep, rx;
    ck_assert_int_eq(mc_film_eprime(E_STEEL, NU_STEEL, E_STEEL, NU_STEEL, &ep, &err), MC_OK);
    ck_assert_int_eq(mc_film_reduced_radius(R_DISC, R_DISC, &rx, &err), MC_OK);
    for (int r = 0; r < rows; r++) {
        const double *row = d + (size_t)r * cols;
        mc_film_kinematics k;
        ck_assert_int_eq(mc_film_kinematics_rpm(row[c_n], R_DISC, row[c_n], R_DISC, &k, &err),
                         MC_OK);
        ck_assert_msg(fabs(k.v_sum - row[c_v]) <= printed_half_unit(row[c_v], 4),
                      "row %d: v_sum %.6f vs %.4f", r, k.v_sum, row[c_v]);
        ck_assert(k.srr == 0); /* pure rolling */
        mc_film_input in = {.eta0 = row[c_eta], .alpha = ALPHA, .u = k.u, .eprime = ep, .rx = rx,
                            .load = FORCE / WIDTH};
        for (size_t f = 0; f < sizeof cmp / sizeof cmp[0]; f++) {
            mc_film_groups g;
            ck_assert_int_eq(mc_film_groups_of(cmp[f].f, &in, &g, &err), MC_OK);
            ck_assert_msg(fabs(g.U - row[c_U]) <= printed_half_unit(row[c_U], 4), "row %d: U", r);
            ck_assert_msg(fabs(g.G - row[c_G]) <= printed_half_unit(row[c_G], 4), "row %d: G", r);
            ck_assert_msg(fabs(g.W - row[c_W]) <= printed_half_unit(row[c_W], 4), "row %d: W'", r);
            double h;
            ck_assert_int_eq(mc_film_thickness(cmp[f].f, &in, &h, &err), MC_OK);
            double ref = row[column(hdr, cols, cmp[f].col)];
            double e = fabs(h * 1e6 - ref);
            ck_assert_msg(e <= TOL_CSV_UM, "row %d %s: %.6f um vs %.4f um", r,
                          mc_film_formula_name(cmp[f].f), h * 1e6, ref);
        }
    }
    free(d);
}
END_TEST

/* Every formula of the table against its expression as the dossier writes it (theory.md §10.2),
 * found by name: a formula added to the table without an expression here fails. The load group
 * is W' = w'/(E' Rx) for line and W = F/(E' Rx^2) for point formulas. */
static double dossier_H(const char *name, double U, double G, double W, double k)
{
    if (!strcmp(name, "pan_hamrock_central")) return 2.922 * pow(W, -0.166) * pow(U, 0.692) * pow(G, 0.470);
    if (!strcmp(name, "pan_hamrock_min")) return 1.714 * pow(W, -0.128) * pow(U, 0.694) * pow(G, 0.568);
    if (!strcmp(name, "dowson_toyoda")) return 3.06 * pow(U, 0.69) * pow(G, 0.56) * pow(W, -0.10);
    if (!strcmp(name, "dowson_higginson")) return 2.65 * pow(U, 0.70) * pow(G, 0.54) * pow(W, -0.13);
    if (!strcmp(name, "hamrock_dowson_central"))
        return 2.69 * pow(U, 0.67) * pow(G, 0.53) * pow(W, -0.067) * (1 - 0.61 * exp(-0.73 * k));
    if (!strcmp(name, "hamrock_dowson_min"))
        return 3.63 * pow(U, 0.68) * pow(G, 0.49) * pow(W, -0.073) * (1 - exp(-0.68 * k));
    return NAN; /* no expression for this formula: the test fails */
}

START_TEST(every_formula_matches_its_expression)
{
    mc_error err = {0};
    mc_film_input in = {.eta0 = 0.04, .alpha = 2.2e-8, .u = 3.0, .eprime = 2.2e11, .rx = 0.015,
                        .load = 2.0e5, .k = 4.0};
    ck_assert_int_ge(mc_film_formula_count(), 1);
    for (int i = 0; i < mc_film_formula_count(); i++) {
        mc_film_formula f = (mc_film_formula)i;
        const char *name = mc_film_formula_name(f);
        ck_assert_ptr_nonnull(name);
        mc_film_groups g;
        double h;
        ck_assert_int_eq(mc_film_groups_of(f, &in, &g, &err), MC_OK);
        ck_assert_int_eq(mc_film_thickness(f, &in, &h, &err), MC_OK);
        double Wref = mc_film_formula_is_point(f) ? in.load / (in.eprime * in.rx * in.rx)
                                                  : in.load / (in.eprime * in.rx);
        ck_assert(fabs(g.W - Wref) <= TOL_TIGHT * Wref);
        double ref = dossier_H(name, g.U, g.G, g.W, in.k) * in.rx;
        ck_assert_msg(h > 0 && fabs(h - ref) <= TOL_TIGHT * ref, "%s: %.17g vs %.17g", name, h,
                      ref);
    }
    /* the named functions are the table's rows */
    mc_film_groups g;
    ck_assert_int_eq(mc_film_groups_of(MC_FILM_DEFAULT, &in, &g, &err), MC_OK);
    const struct {
        const char *name;
        double h;
    } named[] = {
        {"pan_hamrock_central", mc_film_pan_hamrock_central(g.U, g.G, g.W, in.rx)},
        {"pan_hamrock_min", mc_film_pan_hamrock_min(g.U, g.G, g.W, in.rx)},
        {"dowson_toyoda", mc_film_dowson_toyoda(g.U, g.G, g.W, in.rx)},
        {"dowson_higginson", mc_film_dowson_higginson(g.U, g.G, g.W, in.rx)},
        {"hamrock_dowson_central", mc_film_hamrock_dowson_central(g.U, g.G, g.W, in.k, in.rx)},
        {"hamrock_dowson_min", mc_film_hamrock_dowson_min(g.U, g.G, g.W, in.k, in.rx)}};
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++) {
        double ref = dossier_H(named[i].name, g.U, g.G, g.W, in.k) * in.rx;
        ck_assert_msg(fabs(named[i].h - ref) <= TOL_TIGHT * ref, "%s", named[i].name);
    }
}
END_TEST

/* Point-contact formulas against hand values: H evaluated independently (Python, math.pow) from
 * theory.md §10.2, printed to 17 digits; the two libm evaluations agree to a few ulp. */
#define TOL_HAND 1e-13
START_TEST(point_formulas_hand_values)
{
    /* (U, G, W, k) -> H_c, H_min */
    const double cases[2][6] = {{1e-11, 5000, 1e-6, 1.0, 1.8665212146439957e-05, 1.0558108367437653e-05},
                                {2.5e-11, 4615.4, 3.7e-7, 6.0, 4.96595258763832e-05, 4.0558705242356417e-05}};
    for (int c = 0; c < 2; c++) {
        const double *v = cases[c];
        double hc = mc_film_hamrock_dowson_central(v[0], v[1], v[2], v[3], 1.0);
        double hm = mc_film_hamrock_dowson_min(v[0], v[1], v[2], v[3], 1.0);
        ck_assert_msg(fabs(hc - v[4]) <= TOL_HAND * v[4], "case %d: H_c %.17g vs %.17g", c, hc, v[4]);
        ck_assert_msg(fabs(hm - v[5]) <= TOL_HAND * v[5], "case %d: H_min %.17g vs %.17g", c, hm, v[5]);
        /* h = H R_x */
        ck_assert(fabs(mc_film_hamrock_dowson_central(v[0], v[1], v[2], v[3], 0.02) - 0.02 * hc) <=
                  TOL_HAND * 0.02 * hc);
    }
    /* ellipticity: k = 1.03 (Ry/Rx)^0.64; 1.03 for a sphere, 1.03 * 10^0.64 for Ry = 10 Rx */
    ck_assert(fabs(mc_film_ellipticity(1.0) - 1.03) <= TOL_TIGHT);
    ck_assert(fabs(mc_film_ellipticity(10.0) - 1.03 * pow(10.0, 0.64)) <= TOL_TIGHT * 5);
}
END_TEST

START_TEST(kinematics_and_geometry)
{
    mc_error err = {0};
    mc_film_kinematics k;
    /* 3000 rpm on 40 mm: 2 pi 3000 0.04 / 60 = 4 pi m/s; 1500 rpm: 2 pi m/s */
    ck_assert_int_eq(mc_film_kinematics_rpm(3000, 0.04, 1500, 0.04, &k, &err), MC_OK);
    ck_assert(fabs(k.u1 - 4 * M_PI) <= TOL_TIGHT * 4 * M_PI);
    ck_assert(fabs(k.u2 - 2 * M_PI) <= TOL_TIGHT * 2 * M_PI);
    ck_assert(fabs(k.u - 3 * M_PI) <= TOL_TIGHT * 3 * M_PI);
    ck_assert(fabs(k.v_sum - 6 * M_PI) <= TOL_TIGHT * 6 * M_PI);
    ck_assert(fabs(k.srr - 2.0 / 3.0) <= TOL_TIGHT);
    /* different radii, the same surface speed: pure rolling */
    ck_assert_int_eq(mc_film_kinematics_rpm(1000, 0.03, 1500, 0.02, &k, &err), MC_OK);
    ck_assert(fabs(k.u1 - k.u2) <= TOL_TIGHT * k.u1 && k.srr <= TOL_TIGHT);
    /* one surface at rest: SRR = 2 (pure sliding), u = half the speed */
    ck_assert_int_eq(mc_film_kinematics_speeds(2.0, 0.0, &k, &err), MC_OK);
    ck_assert(k.u == 1.0 && k.srr == 2.0 && k.v_sum == 2.0);
    /* E' = 2 E* = E / (1 - nu^2) for two equal bodies: 230.8 GPa for steel (theory.md §10.1) */
    double ep, rx;
    ck_assert_int_eq(mc_film_eprime(E_STEEL, NU_STEEL, E_STEEL, NU_STEEL, &ep, &err), MC_OK);
    ck_assert(fabs(ep - E_STEEL / (1 - NU_STEEL * NU_STEEL)) <= TOL_TIGHT * ep);
    ck_assert(fabs(ep - 230.8e9) <= 0.05e9); /* printed to 4 digits */
    /* steel on a rigid body: E' = 2 E / (1 - nu^2) */
    ck_assert_int_eq(mc_film_eprime(E_STEEL, NU_STEEL, INFINITY, 0.3, &ep, &err), MC_OK);
    ck_assert(fabs(ep - 2 * E_STEEL / (1 - NU_STEEL * NU_STEEL)) <= TOL_TIGHT * ep);
    ck_assert_int_eq(mc_film_reduced_radius(0.04, 0.04, &rx, &err), MC_OK);
    ck_assert(fabs(rx - 0.02) <= TOL_TIGHT * 0.02);
    ck_assert_int_eq(mc_film_reduced_radius(0.04, INFINITY, &rx, &err), MC_OK);
    ck_assert(rx == 0.04);
    ck_assert_int_eq(mc_film_reduced_radius(0.03, 0.06, &rx, &err), MC_OK);
    ck_assert(fabs(rx - 0.02) <= TOL_TIGHT * 0.02);
}
END_TEST

START_TEST(hertz_line_disc_case)
{
    mc_error err = {0};
    double ep, rx, b, ph;
    ck_assert_int_eq(mc_film_eprime(E_STEEL, NU_STEEL, E_STEEL, NU_STEEL, &ep, &err), MC_OK);
    ck_assert_int_eq(mc_film_reduced_radius(R_DISC, R_DISC, &rx, &err), MC_OK);
    ck_assert_int_eq(mc_film_hertz_line(FORCE / WIDTH, rx, ep / 2, &b, &ph, &err), MC_OK);
    /* theory.md §10.4: b = 154.8 um (4 digits), p_H = 447 MPa (3 digits) */
    ck_assert_msg(fabs(b - 154.8e-6) <= 0.05e-6, "b = %.4f um", b * 1e6);
    ck_assert_msg(fabs(ph - 447e6) <= 0.5e6, "p_H = %.2f MPa", ph / 1e6);
    /* Hamrock's form against Johnson's (reference/hertz.h): the same closed form two ways */
    mc_hertz_line hl;
    ck_assert_int_eq(mc_hertz_line_from_load(rx, ep / 2, FORCE / WIDTH, &hl, &err), MC_OK);
    ck_assert(fabs(b - hl.b) <= TOL_TIGHT * hl.b && fabs(ph - hl.p0) <= TOL_TIGHT * hl.p0);
    ck_assert_int_eq(mc_film_hertz_line(-1, rx, ep / 2, &b, &ph, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_hertz_line(1e5, rx, 0, &b, &ph, &err), MC_ERR_INPUT);
}
END_TEST

START_TEST(names)
{
    mc_error err = {0};
    const int n = mc_film_formula_count();
    ck_assert_int_eq(n, MC_FILM_NFORMULAS);
    ck_assert_str_eq(mc_film_formula_name(MC_FILM_DEFAULT), "pan_hamrock_central");
    for (int i = 0; i < n; i++) {
        mc_film_formula f = (mc_film_formula)i, out;
        const char *name = mc_film_formula_name(f);
        ck_assert_ptr_nonnull(name);
        ck_assert_ptr_nonnull(mc_film_formula_help(f));
        ck_assert_ptr_nonnull(mc_film_formula_reference(f));
        ck_assert_msg(!strchr(mc_film_formula_help(f), '|'), "%s: '|' in help", name);
        ck_assert_int_eq(mc_film_formula_from_name(name, &out, &err), MC_OK);
        ck_assert_int_eq(out, f);
        /* the point formulas say so in their help (load F_N and ellipticity k) */
        ck_assert_int_eq(mc_film_formula_is_point(f),
                         strncmp(mc_film_formula_help(f), "point", 5) == 0);
    }
    ck_assert_ptr_null(mc_film_formula_name((mc_film_formula)n));
    ck_assert_ptr_null(mc_film_formula_help((mc_film_formula)n));
    ck_assert_int_eq(mc_film_formula_is_point((mc_film_formula)n), 0);
    const char *bad[] = {"hamrock", "Pan_Hamrock_Central", "", NULL};
    for (int i = 0; i < 4; i++) {
        mc_film_formula out;
        mc_error_clear(&err);
        ck_assert_int_eq(mc_film_formula_from_name(bad[i], &out, &err), MC_ERR_INPUT);
        ck_assert_int_eq(err.code, MC_ERR_INPUT);
        for (int f = 0; f < n; f++) {
            const char *name = mc_film_formula_name((mc_film_formula)f);
            ck_assert_msg(strstr(err.msg, name), "'%s' not listed in: %s", name, err.msg);
        }
    }
}
END_TEST

/* Every bad input is MC_ERR_INPUT with a message naming the quantity and the accepted range. */
START_TEST(bad_values)
{
    const mc_film_input good = {.eta0 = 0.03, .alpha = 2e-8, .u = 1.0, .eprime = 2.3e11,
                                .rx = 0.02, .load = 1e5, .k = 3.0};
    const struct {
        int field; /* 0 eta0, 1 alpha, 2 u, 3 eprime, 4 rx, 5 load, 6 k */
        double value;
        mc_film_formula f;
        const char *word, *range;
    } cases[] = {
        {0, 0.0, MC_FILM_DEFAULT, "viscosity", "> 0"},
        {0, -0.03, MC_FILM_DEFAULT, "viscosity", "> 0"},
        {0, NAN, MC_FILM_DOWSON_TOYODA, "viscosity", "> 0"},
        {1, 0.0, MC_FILM_DEFAULT, "pressure-viscosity", "> 0"},
        {1, -1e-8, MC_FILM_DOWSON_HIGGINSON, "pressure-viscosity", "> 0"},
        {2, 0.0, MC_FILM_DEFAULT, "speed", "> 0"},
        {2, INFINITY, MC_FILM_PAN_HAMROCK_MIN, "speed", "> 0"},
        {3, -2e11, MC_FILM_DEFAULT, "modulus", "> 0"},
        {4, 0.0, MC_FILM_DEFAULT, "radius", "> 0"},
        {5, -1e5, MC_FILM_DEFAULT, "load per unit length", "> 0"},
        {5, 0.0, MC_FILM_HAMROCK_DOWSON_MIN, "normal force", "> 0"},
        {6, 0.0, MC_FILM_HAMROCK_DOWSON_CENTRAL, "ellipticity", "> 0"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        mc_film_input in = good;
        double *fld[] = {&in.eta0, &in.alpha, &in.u, &in.eprime, &in.rx, &in.load, &in.k};
        *fld[cases[c].field] = cases[c].value;
        mc_error err = {0};
        double h = -1;
        ck_assert_int_eq(mc_film_thickness(cases[c].f, &in, &h, &err), MC_ERR_INPUT);
        ck_assert_msg(strstr(err.msg, cases[c].word) && strstr(err.msg, cases[c].range),
                      "case %zu: %s", c, err.msg);
        ck_assert(h == -1); /* output untouched */
    }
    /* k is not used by line formulas */
    mc_film_input in = good;
    in.k = 0;
    mc_error err = {0};
    double h;
    ck_assert_int_eq(mc_film_thickness(MC_FILM_PAN_HAMROCK_CENTRAL, &in, &h, &err), MC_OK);
    ck_assert_int_eq(mc_film_thickness(MC_FILM_NFORMULAS, &good, &h, &err), MC_ERR_INPUT);
    /* materials, radii and speeds */
    double v;
    mc_film_kinematics k;
    ck_assert_int_eq(mc_film_eprime(0, 0.3, 2e11, 0.3, &v, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "E1") && strstr(err.msg, "> 0"));
    ck_assert_int_eq(mc_film_eprime(INFINITY, 0.3, INFINITY, 0.3, &v, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_eprime(2e11, 0.3, NAN, 0.3, &v, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_eprime(2e11, 0.6, 2e11, 0.3, &v, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "nu1") && strstr(err.msg, "(-1, 0.5]"));
    ck_assert_int_eq(mc_film_reduced_radius(-0.04, 0.04, &v, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_reduced_radius(INFINITY, INFINITY, &v, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_kinematics_rpm(-100, 0.04, 100, 0.04, &k, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "rpm") && strstr(err.msg, ">= 0"));
    ck_assert_int_eq(mc_film_kinematics_rpm(0, 0.04, 0, 0.04, &k, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_kinematics_rpm(100, 0, 100, 0.04, &k, &err), MC_ERR_INPUT);
    ck_assert(strstr(err.msg, "radius R1"));
    ck_assert_int_eq(mc_film_kinematics_speeds(1.0, -1.0, &k, &err), MC_ERR_INPUT);
    ck_assert_int_eq(mc_film_kinematics_speeds(NAN, 1.0, &k, &err), MC_ERR_INPUT);
}
END_TEST

Suite *suite_lube_film(void);
Suite *suite_lube_film(void)
{
    Suite *s = suite_create("lube_film");
    TCase *tc = tcase_create("film");
    tcase_add_test(tc, csv_disc_case);
    tcase_add_test(tc, every_formula_matches_its_expression);
    tcase_add_test(tc, point_formulas_hand_values);
    tcase_add_test(tc, kinematics_and_geometry);
    tcase_add_test(tc, hertz_line_disc_case);
    tcase_add_test(tc, names);
    tcase_add_test(tc, bad_values);
    suite_add_tcase(s, tc);
    return s;
}
