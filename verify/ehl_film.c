/* ehl_film.c - suite `ehl_film`: the EHL film thickness of the smooth macro contact (lube/film.h)
 * for every formula against the dossier (plastic-lubrication §4; docs/theory.md §10): the
 * disc-case table pl_ehl_film_disc_case.csv (four line-contact formulas and the groups U, G, W'
 * at 200-3000 rpm and two viscosities), the printed table of §4.4 (2 digits) with the macro Hertz
 * contact of the disc case, and each formula's expression as the dossier writes it, evaluated
 * here independently (line and point contact), at the disc case and at a ball-on-disc case. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "lube/film.h"
#include "suites.h"
#include "vutil.h"

/* The disc case of dossier §4.4: R1 = R2 = 40 mm, width 10 mm, 1086 N, pure rolling, steel. */
#define E_STEEL 210e9
#define NU_STEEL 0.3
#define R_DISC 0.040
#define WIDTH 0.010
#define FORCE 1086.0
#define ALPHA 2e-8

/* Tolerance tiers. The CSV prints films in um with 4 decimals: an exact evaluation differs by at
 * most half a unit of that digit (plus the binary slack of the printed decimal). U, G, W' and
 * v_Sigma have 5 significant digits: half a unit of the 5th. The §4.4 text table rounds to 2
 * decimals in um: half a unit of 0.01 um. b and p_H are printed to 4 and 3 digits. The dossier's
 * expressions evaluated here and in lube/film.c differ only in the order of a few pow and
 * multiplications: 1e-14 relative (about 50 ulp). */
#define TOL_CSV_UM (0.5e-4 * (1 + 1e-9))
#define TOL_TEXT_UM (0.5e-2 * (1 + 1e-9))
#define TOL_FORM 1e-14

static double half_unit_5(double printed)
{
    return 0.5 * pow(10.0, floor(log10(fabs(printed))) - 4) * (1 + 1e-9);
}

#define MAXCOLS 16

static int column(char header[][32], int cols, const char *name)
{
    size_t len = strlen(name);
    for (int c = 0; c < cols; c++)
        if (strncmp(header[c], name, len) == 0 && (header[c][len] == 0 || header[c][len] == '\r'))
            return c;
    return -1;
}

/* The dossier's table of §4.2 written out again, H = h / R_x from U, G and W' (line) or W and k
 * (point): an evaluation independent of lube/film.c. */
static double dossier_H(mc_film_formula f, double U, double G, double W, double k)
{
    switch (f) {
    case MC_FILM_DOWSON_HIGGINSON: return 2.65 * pow(U, 0.70) * pow(G, 0.54) * pow(W, -0.13);
    case MC_FILM_DOWSON_TOYODA: return 3.06 * pow(U, 0.69) * pow(G, 0.56) * pow(W, -0.10);
    case MC_FILM_PAN_HAMROCK_MIN: return 1.714 * pow(W, -0.128) * pow(U, 0.694) * pow(G, 0.568);
    case MC_FILM_PAN_HAMROCK_CENTRAL: return 2.922 * pow(W, -0.166) * pow(U, 0.692) * pow(G, 0.470);
    case MC_FILM_HAMROCK_DOWSON_MIN:
        return 3.63 * pow(U, 0.68) * pow(G, 0.49) * pow(W, -0.073) * (1 - exp(-0.68 * k));
    case MC_FILM_HAMROCK_DOWSON_CENTRAL:
        return 2.69 * pow(U, 0.67) * pow(G, 0.53) * pow(W, -0.067) * (1 - 0.61 * exp(-0.73 * k));
    default: return NAN;
    }
}

static int csv_table(vf_ctx *ctx, double ep, double rx, FILE *out)
{
    double *d = NULL;
    int cols;
    char hdr[MAXCOLS][32], msg[256];
    int rows = vu_read_csv("pl_ehl_film_disc_case.csv", &d, &cols, hdr, MAXCOLS, NULL, msg,
                           sizeof msg);
    if (rows < 1) {
        vf_fail(ctx, "csv", "%s", msg);
        return 1;
    }
    const int c_eta = column(hdr, cols, "eta0_Pas"), c_n = column(hdr, cols, "n_rpm"),
              c_v = column(hdr, cols, "v_sum_mps"), c_U = column(hdr, cols, "U"),
              c_G = column(hdr, cols, "G"), c_W = column(hdr, cols, "W_line");
    static const struct {
        const char *col, *id;
        mc_film_formula f;
    } cmp[] = {{"h_min_DowsonHigginson_um", "dh", MC_FILM_DOWSON_HIGGINSON},
               {"h_c_DowsonToyoda_um", "dt", MC_FILM_DOWSON_TOYODA},
               {"h_min_PanHamrock_um", "phmin", MC_FILM_PAN_HAMROCK_MIN},
               {"h_c_PanHamrock_um", "phc", MC_FILM_PAN_HAMROCK_CENTRAL}};
    if (c_eta < 0 || c_n < 0 || c_v < 0 || c_U < 0 || c_G < 0 || c_W < 0) {
        vf_fail(ctx, "csv", "pl_ehl_film_disc_case.csv lacks a column");
        free(d);
        return 1;
    }
    fprintf(out, "eta0,rpm,formula,h_table_um,h_um,diff_um\n");
    double worst[4] = {0}, worst_groups = 0;
    mc_error err = {0};
    for (int r = 0; r < rows; r++) {
        const double *row = d + (size_t)r * MAXCOLS; /* vu_read_csv: row stride max_cols */
        mc_film_kinematics k;
        mc_film_kinematics_rpm(row[c_n], R_DISC, row[c_n], R_DISC, &k, &err);
        mc_film_input in = {.eta0 = row[c_eta], .alpha = ALPHA, .u = k.u, .eprime = ep,
                            .rx = rx, .load = FORCE / WIDTH};
        mc_film_groups g;
        mc_film_groups_of(MC_FILM_PAN_HAMROCK_CENTRAL, &in, &g, &err);
        worst_groups = vf_worst(worst_groups, fabs(k.v_sum - row[c_v]) / half_unit_5(row[c_v]));
        worst_groups = vf_worst(worst_groups, fabs(g.U - row[c_U]) / half_unit_5(row[c_U]));
        worst_groups = vf_worst(worst_groups, fabs(g.G - row[c_G]) / half_unit_5(row[c_G]));
        worst_groups = vf_worst(worst_groups, fabs(g.W - row[c_W]) / half_unit_5(row[c_W]));
        for (int f = 0; f < 4; f++) {
            int c = column(hdr, cols, cmp[f].col);
            double h = NAN;
            if (c < 0 || mc_film_thickness(cmp[f].f, &in, &h, &err) != MC_OK) {
                vf_fail(ctx, cmp[f].id, "%s: %s", cmp[f].col, c < 0 ? "column missing" : err.msg);
                continue;
            }
            double e = fabs(h * 1e6 - row[c]);
            worst[f] = vf_worst(worst[f], e);
            fprintf(out, "%g,%g,%s,%.4f,%.6f,%.2e\n", row[c_eta], row[c_n],
                    mc_film_formula_name(cmp[f].f), row[c], h * 1e6, e);
        }
    }
    char id[64], q[160];
    for (int f = 0; f < 4; f++) {
        snprintf(id, sizeof id, "csv_%s", cmp[f].id);
        snprintf(q, sizeof q, "%s: max |h - table| over the %d rows, um",
                 mc_film_formula_name(cmp[f].f), rows);
        vf_check(ctx, id, q, "pl_ehl_film_disc_case.csv (4 decimals)", 0, worst[f], TOL_CSV_UM,
                 VF_MAX);
    }
    vf_check(ctx, "csv_groups", "v_Sigma, U, G, W': worst |value - table| in half units of the "
             "5th digit", "pl_ehl_film_disc_case.csv (5 digits)", 0, worst_groups, 1.0, VF_MAX);
    free(d);
    return 0;
}

/* The printed table of §4.4 (h_c Pan-Hamrock at eta0 0.03 / 0.05 Pa s, h_min Dowson-Higginson at
 * both) and the macro Hertz contact of the disc case. */
static void text_table(vf_ctx *ctx, double ep, double rx)
{
    static const struct {
        double rpm, phc[2], dh[2];
    } t[] = {{200, {0.29, 0.41}, {0.26, 0.38}},
             {500, {0.55, 0.78}, {0.50, 0.71}},
             {1000, {0.88, 1.26}, {0.81, 1.16}},
             {3000, {1.89, 2.69}, {1.75, 2.50}}};
    static const double eta[2] = {0.03, 0.05};
    double worst = 0;
    mc_error err = {0};
    for (size_t r = 0; r < sizeof t / sizeof t[0]; r++)
        for (int e = 0; e < 2; e++) {
            mc_film_kinematics k;
            mc_film_kinematics_rpm(t[r].rpm, R_DISC, t[r].rpm, R_DISC, &k, &err);
            mc_film_input in = {.eta0 = eta[e], .alpha = ALPHA, .u = k.u, .eprime = ep, .rx = rx,
                                .load = FORCE / WIDTH};
            double hc, hm;
            mc_film_thickness(MC_FILM_PAN_HAMROCK_CENTRAL, &in, &hc, &err);
            mc_film_thickness(MC_FILM_DOWSON_HIGGINSON, &in, &hm, &err);
            worst = vf_worst(worst, vf_worst(fabs(hc * 1e6 - t[r].phc[e]), fabs(hm * 1e6 - t[r].dh[e])));
        }
    vf_check(ctx, "text_table", "h_c Pan-Hamrock and h_min Dowson-Higginson, 16 entries: max "
             "|h - printed| in um", "dossier §4.4 table (2 decimals)", 0, worst, TOL_TEXT_UM,
             VF_MAX);
    double b, ph;
    mc_film_hertz_line(FORCE / WIDTH, rx, ep / 2, &b, &ph, &err);
    vf_check(ctx, "hertz_b", "macro Hertz half-width b, um", "dossier §4.4: 154.8 um", 154.8,
             b * 1e6, 0.05, VF_ABS);
    vf_check(ctx, "hertz_pH", "macro Hertz pressure p_H, MPa", "dossier §4.4: 447 MPa", 447.0,
             ph * 1e-6, 0.5, VF_ABS);
}

/* Every formula against its expression in the dossier's table, at the disc case (line: w') and
 * at a ball-on-disc point case (F = 50 N, R_x = 10 mm, k = 1 and 8). */
static void expressions(vf_ctx *ctx, double ep, double rx, FILE *out)
{
    mc_error err = {0};
    fprintf(out, "formula,case,H_dossier,H_code,rel_diff\n");
    for (int f = 0; f < MC_FILM_NFORMULAS; f++) {
        const int point = mc_film_formula_is_point((mc_film_formula)f);
        const double ks[2] = {1.0, 8.0};
        double worst = 0;
        for (int c = 0; c < 2; c++) {
            mc_film_input in = {.eta0 = 0.03, .alpha = ALPHA, .u = c ? 25.1 : 1.68, .eprime = ep,
                                .rx = point ? 0.010 : rx, .load = point ? 50.0 : FORCE / WIDTH,
                                .k = ks[c]};
            mc_film_groups g;
            double h;
            if (mc_film_groups_of((mc_film_formula)f, &in, &g, &err) != MC_OK ||
                mc_film_thickness((mc_film_formula)f, &in, &h, &err) != MC_OK) {
                vf_fail(ctx, mc_film_formula_name((mc_film_formula)f), "%s", err.msg);
                return;
            }
            /* the groups themselves from their definitions (dossier §4.1) */
            double U = in.eta0 * in.u / (ep * in.rx), G = ALPHA * ep,
                   W = point ? in.load / (ep * in.rx * in.rx) : in.load / (ep * in.rx);
            double Hd = dossier_H((mc_film_formula)f, U, G, W, in.k), H = h / in.rx;
            double e = fabs(H - Hd) / Hd;
            worst = vf_worst(worst, e);
            fprintf(out, "%s,%s,%.17g,%.17g,%.3e\n", mc_film_formula_name((mc_film_formula)f),
                    c ? "fast" : "slow", Hd, H, e);
        }
        char id[64], q[160];
        snprintf(id, sizeof id, "expr_%s", mc_film_formula_name((mc_film_formula)f));
        snprintf(q, sizeof q, "%s (%s contact): H against the dossier's expression",
                 mc_film_formula_name((mc_film_formula)f), point ? "point" : "line");
        vf_check(ctx, id, q, "dossier §4.2 table", 0, worst, TOL_FORM, VF_MAX);
    }
}

int vf_suite_ehl_film(vf_ctx *ctx, int fast)
{
    (void)fast; /* closed forms: the whole suite is fast */
    mc_error err = {0};
    double ep, rx;
    if (mc_film_eprime(E_STEEL, NU_STEEL, E_STEEL, NU_STEEL, &ep, &err) != MC_OK ||
        mc_film_reduced_radius(R_DISC, R_DISC, &rx, &err) != MC_OK) {
        vf_fail(ctx, "setup", "%s", err.msg);
        return 1;
    }
    vf_text(ctx,
            "The film thickness of the smooth discs that sets the lubricant volume of the "
            "running-in (docs/theory.md §10). Disc case of the dossier (§4.4): R1 = R2 = %.0f mm "
            "(R_x = %.0f mm), width %.0f mm, F_N = %.0f N (w' = %.4g N/m), steel/steel (E' = "
            "%.4g GPa), alpha = %.0e 1/Pa, pure rolling.\n\n"
            "References and tolerances: the disc table pl_ehl_film_disc_case.csv of the "
            "dossier's script (films to half a unit of its 4th decimal in um, the groups to half "
            "a unit of their 5th digit), the printed table of §4.4 (half of 0.01 um), the macro "
            "Hertz contact printed there (b = 154.8 um, p_H = 447 MPa, to their last digit), "
            "and each formula's expression as the dossier writes it, evaluated again in this "
            "suite from the definitions of U, G, W' and W (1e-14: the same arithmetic in another "
            "order). The table has no row for the point-contact formulas of Hamrock & Dowson: "
            "they are checked against their expressions only, at a ball-on-disc case (F = 50 N, "
            "R_x = 10 mm, k = 1 and 8). The line-contact coefficients are [S] in the dossier "
            "(quoted from Hamrock 1991); the default, pan_hamrock_central, stands for the "
            "paper's mean film h_EHD, an open choice (dossier §9 point 3).\n\n",
            R_DISC * 1e3, rx * 1e3, WIDTH * 1e3, FORCE, FORCE / WIDTH, ep * 1e-9, ALPHA);
    FILE *f = vf_open(ctx, "disc_case.csv");
    if (!f || csv_table(ctx, ep, rx, f) != 0) {
        if (f)
            vf_close(ctx, f);
        return 1;
    }
    vf_close(ctx, f);
    text_table(ctx, ep, rx);
    f = vf_open(ctx, "expressions.csv");
    if (f) {
        expressions(ctx, ep, rx, f);
        vf_close(ctx, f);
    }
    /* the film against the speed, every line formula, eta0 = 0.03 Pa s */
    f = vf_open(ctx, "film_vs_speed.csv");
    if (f) {
        fprintf(f, "rpm,pan_hamrock_central_um,pan_hamrock_min_um,dowson_toyoda_um,"
                   "dowson_higginson_um\n");
        for (double n = 100; n <= 5000 * 1.0001; n *= 1.2) {
            mc_film_kinematics k;
            mc_film_kinematics_rpm(n, R_DISC, n, R_DISC, &k, &err);
            mc_film_input in = {.eta0 = 0.03, .alpha = ALPHA, .u = k.u, .eprime = ep, .rx = rx,
                                .load = FORCE / WIDTH};
            double h[4];
            for (int q = 0; q < 4; q++)
                mc_film_thickness((mc_film_formula)q, &in, &h[q], &err);
            fprintf(f, "%.6g,%.6g,%.6g,%.6g,%.6g\n", n, h[0] * 1e6, h[1] * 1e6, h[2] * 1e6,
                    h[3] * 1e6);
        }
        vf_close(ctx, f);
        vf_plot(ctx, "film_vs_speed.png",
                "Film thickness of the disc case against the disc speed (eta0 = 0.03 Pa s); "
                "points: the dossier's table",
                "set datafile separator ','\nset logscale xy\nset xlabel 'disc speed [rpm]'\n"
                "set ylabel 'h [um]'\nset grid\nset key top left\n"
                "plot 'film_vs_speed.csv' using 1:2 with lines lw 2 title 'Pan-Hamrock central', "
                "'' using 1:3 with lines title 'Pan-Hamrock min', "
                "'' using 1:4 with lines title 'Dowson-Toyoda', "
                "'' using 1:5 with lines title 'Dowson-Higginson', "
                "'disc_case.csv' using ($1 == 0.03 && strcol(3) eq 'pan_hamrock_central' ? $2 : "
                "1/0):4 with points pt 7 title 'table: Pan-Hamrock central', "
                "'disc_case.csv' using ($1 == 0.03 && strcol(3) eq 'dowson_higginson' ? $2 : "
                "1/0):4 with points pt 5 title 'table: Dowson-Higginson'");
    }
    return 0;
}
