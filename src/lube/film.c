/* film.c - EHL film formulas, disc kinematics and the macro Hertz line contact (film.h). */
#include "lube/film.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The formula table: the one place that names, documents and defines every formula. The key
 * table ([lubrication] formula), docs/case-format.md and the error messages take the names and
 * help from here (mc_film_formula_name, mc_film_formula_help). To add a formula: a value in
 * mc_film_formula (film.h, before MC_FILM_NFORMULAS) and a row here; nothing else.
 *
 * Each row: H = c U^eu G^eg W^ew (1 - ka exp(-kb k)); ka = 0 for line contact.
 * Coefficients: theory.md §10.2 (Hamrock 1991, NASA RP-1255; Hamrock & Dowson,
 * J. Lubr. Technol. 99(2) 264, 1977). No '|' in help (it goes into a Markdown table). */
typedef struct {
    const char *name, *help, *reference;
    double c, eu, eg, ew;
    int point;
    double ka, kb;
} formula_row;

static const formula_row rows[] = {
    [MC_FILM_PAN_HAMROCK_CENTRAL] = {"pan_hamrock_central",
                                     "line contact, central film H_c = 2.922 W'^-0.166 U^0.692 G^0.470",
                                     "Pan & Hamrock 1989", 2.922, 0.692, 0.470, -0.166, 0, 0, 0},
    [MC_FILM_PAN_HAMROCK_MIN] = {"pan_hamrock_min",
                                 "line contact, minimum film H_min = 1.714 W'^-0.128 U^0.694 G^0.568",
                                 "Pan & Hamrock 1989", 1.714, 0.694, 0.568, -0.128, 0, 0, 0},
    [MC_FILM_DOWSON_TOYODA] = {"dowson_toyoda",
                               "line contact, central film H_c = 3.06 U^0.69 G^0.56 W'^-0.10",
                               "Dowson & Toyoda 1979", 3.06, 0.69, 0.56, -0.10, 0, 0, 0},
    [MC_FILM_DOWSON_HIGGINSON] = {"dowson_higginson",
                                  "line contact, minimum film H_min = 2.65 U^0.70 G^0.54 W'^-0.13",
                                  "Dowson & Higginson", 2.65, 0.70, 0.54, -0.13, 0, 0, 0},
    [MC_FILM_HAMROCK_DOWSON_CENTRAL] = {"hamrock_dowson_central",
                                        "point contact, central film H_c = 2.69 U^0.67 G^0.53 "
                                        "W^-0.067 (1 - 0.61 e^(-0.73 k))",
                                        "Hamrock & Dowson 1977", 2.69, 0.67, 0.53, -0.067, 1, 0.61,
                                        0.73},
    [MC_FILM_HAMROCK_DOWSON_MIN] = {"hamrock_dowson_min",
                                    "point contact, minimum film H_min = 3.63 U^0.68 G^0.49 "
                                    "W^-0.073 (1 - e^(-0.68 k))",
                                    "Hamrock & Dowson 1977", 3.63, 0.68, 0.49, -0.073, 1, 1.0,
                                    0.68},
};
_Static_assert(sizeof rows / sizeof rows[0] == MC_FILM_NFORMULAS,
               "one row per value of mc_film_formula");

static int valid_formula(mc_film_formula f) { return (int)f >= 0 && f < MC_FILM_NFORMULAS; }

int mc_film_formula_count(void) { return MC_FILM_NFORMULAS; }

const char *mc_film_formula_name(mc_film_formula f)
{
    return valid_formula(f) ? rows[f].name : NULL;
}

const char *mc_film_formula_help(mc_film_formula f)
{
    return valid_formula(f) ? rows[f].help : NULL;
}

const char *mc_film_formula_reference(mc_film_formula f)
{
    return valid_formula(f) ? rows[f].reference : NULL;
}

int mc_film_formula_from_name(const char *name, mc_film_formula *out, mc_error *err)
{
    char list[512];
    size_t o = 0;
    for (int f = 0; f < MC_FILM_NFORMULAS; f++) {
        if (name && strcmp(name, rows[f].name) == 0) {
            *out = (mc_film_formula)f;
            return MC_OK;
        }
        int n = snprintf(list + o, sizeof list - o, "%s%s", f ? " | " : "", rows[f].name);
        o = n > 0 && o + (size_t)n < sizeof list ? o + (size_t)n : o;
    }
    return mc_fail(err, MC_ERR_INPUT, "film formula '%s' is unknown; accepted: %s",
                   name ? name : "(none)", list);
}

int mc_film_formula_is_point(mc_film_formula f) { return valid_formula(f) && rows[f].point; }

/* ---- checks ----------------------------------------------------------------------------------- */

static int need_positive(double v, const char *what, const char *unit, mc_error *err)
{
    if (v > 0 && isfinite(v))
        return MC_OK;
    return mc_fail(err, MC_ERR_INPUT, "%s %g %s must be finite and > 0", what, v, unit);
}

static int need_poisson(double nu, const char *what, mc_error *err)
{
    if (nu > -1 && nu <= 0.5)
        return MC_OK;
    return mc_fail(err, MC_ERR_INPUT, "%s %g must be in (-1, 0.5]", what, nu);
}

/* ---- material, geometry, kinematics ------------------------------------------------------------ */

int mc_film_eprime(double E1, double nu1, double E2, double nu2, double *eprime, mc_error *err)
{
    int rc;
    if (!(E1 > 0) || !(E2 > 0) || (isinf(E1) && isinf(E2)))
        return mc_fail(err, MC_ERR_INPUT,
                       "Young's moduli E1 %g Pa and E2 %g Pa must be > 0 (infinite for a rigid "
                       "body, not both)",
                       E1, E2);
    if ((rc = need_poisson(nu1, "Poisson's ratio nu1", err)) ||
        (rc = need_poisson(nu2, "Poisson's ratio nu2", err)))
        return rc;
    *eprime = 2.0 / ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2);
    return MC_OK;
}

int mc_film_reduced_radius(double R1, double R2, double *rx, mc_error *err)
{
    if (!(R1 > 0) || isnan(R1) || !(R2 > 0) || isnan(R2) || (isinf(R1) && isinf(R2)))
        return mc_fail(err, MC_ERR_INPUT,
                       "disc radii %g m and %g m must be > 0 (infinite for a flat, not both)", R1,
                       R2);
    *rx = 1.0 / (1.0 / R1 + 1.0 / R2);
    return MC_OK;
}

double mc_film_surface_speed(double rpm, double radius) { return 2.0 * M_PI * rpm * radius / 60.0; }

int mc_film_kinematics_speeds(double u1, double u2, mc_film_kinematics *k, mc_error *err)
{
    if (!(u1 >= 0 && isfinite(u1)) || !(u2 >= 0 && isfinite(u2)) || !(u1 + u2 > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "surface speeds %g and %g m/s must be finite and >= 0 with a sum > 0 "
                       "(both surfaces entrain lubricant into the contact)",
                       u1, u2);
    k->u1 = u1;
    k->u2 = u2;
    k->v_sum = u1 + u2;
    k->u = 0.5 * k->v_sum;
    k->srr = 2.0 * fabs(u1 - u2) / k->v_sum;
    return MC_OK;
}

int mc_film_kinematics_rpm(double n1, double R1, double n2, double R2, mc_film_kinematics *k,
                           mc_error *err)
{
    int rc;
    if ((rc = need_positive(R1, "disc radius R1", "m", err)) ||
        (rc = need_positive(R2, "disc radius R2", "m", err)))
        return rc;
    if (!(n1 >= 0 && isfinite(n1)) || !(n2 >= 0 && isfinite(n2)) || !(n1 + n2 > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "disc speeds %g and %g rpm must be finite and >= 0, not both 0", n1, n2);
    return mc_film_kinematics_speeds(mc_film_surface_speed(n1, R1), mc_film_surface_speed(n2, R2),
                                     k, err);
}

double mc_film_ellipticity(double ry_over_rx) { return 1.03 * pow(ry_over_rx, 0.64); }

/* ---- film thickness ---------------------------------------------------------------------------- */

static double eval_row(const formula_row *r, double U, double G, double W, double k, double rx)
{
    double H = r->c * pow(U, r->eu) * pow(G, r->eg) * pow(W, r->ew);
    if (r->point)
        H *= 1.0 - r->ka * exp(-r->kb * k);
    return H * rx;
}

double mc_film_pan_hamrock_central(double U, double G, double W, double rx)
{
    return eval_row(&rows[MC_FILM_PAN_HAMROCK_CENTRAL], U, G, W, 0, rx);
}

double mc_film_pan_hamrock_min(double U, double G, double W, double rx)
{
    return eval_row(&rows[MC_FILM_PAN_HAMROCK_MIN], U, G, W, 0, rx);
}

double mc_film_dowson_toyoda(double U, double G, double W, double rx)
{
    return eval_row(&rows[MC_FILM_DOWSON_TOYODA], U, G, W, 0, rx);
}

double mc_film_dowson_higginson(double U, double G, double W, double rx)
{
    return eval_row(&rows[MC_FILM_DOWSON_HIGGINSON], U, G, W, 0, rx);
}

double mc_film_hamrock_dowson_central(double U, double G, double W, double k, double rx)
{
    return eval_row(&rows[MC_FILM_HAMROCK_DOWSON_CENTRAL], U, G, W, k, rx);
}

double mc_film_hamrock_dowson_min(double U, double G, double W, double k, double rx)
{
    return eval_row(&rows[MC_FILM_HAMROCK_DOWSON_MIN], U, G, W, k, rx);
}

int mc_film_groups_of(mc_film_formula f, const mc_film_input *in, mc_film_groups *g,
                      mc_error *err)
{
    if (!valid_formula(f))
        return mc_fail(err, MC_ERR_INPUT, "film formula %d is out of range", (int)f);
    int point = rows[f].point, rc;
    if ((rc = need_positive(in->eta0, "viscosity", "Pa s", err)) ||
        (rc = need_positive(in->u, "entrainment speed", "m/s", err)) ||
        (rc = need_positive(in->eprime, "reduced modulus E'", "Pa", err)) ||
        (rc = need_positive(in->rx, "reduced radius R_x", "m", err)) ||
        (rc = need_positive(in->load, point ? "normal force" : "load per unit length w'",
                            point ? "N" : "N/m", err)) ||
        (point && (rc = need_positive(in->k, "ellipticity k", "", err))))
        return rc;
    if (!(in->alpha > 0 && isfinite(in->alpha)))
        return mc_fail(err, MC_ERR_INPUT,
                       "pressure-viscosity coefficient %g 1/Pa must be finite and > 0 (the film "
                       "formulas are piezoviscous fits: alpha = 0 would give h = 0)",
                       in->alpha);
    g->U = in->eta0 * in->u / (in->eprime * in->rx);
    g->G = in->alpha * in->eprime;
    g->W = point ? in->load / (in->eprime * in->rx * in->rx) : in->load / (in->eprime * in->rx);
    return MC_OK;
}

int mc_film_thickness(mc_film_formula f, const mc_film_input *in, double *h, mc_error *err)
{
    mc_film_groups g;
    int rc = mc_film_groups_of(f, in, &g, err);
    if (rc != MC_OK)
        return rc;
    *h = eval_row(&rows[f], g.U, g.G, g.W, in->k, in->rx);
    return MC_OK;
}

/* ---- macro Hertz line contact -------------------------------------------------------------------- */

int mc_film_hertz_line(double wprime, double rx, double estar, double *b, double *p_h,
                       mc_error *err)
{
    int rc;
    if ((rc = need_positive(wprime, "load per unit length w'", "N/m", err)) ||
        (rc = need_positive(rx, "reduced radius R_x", "m", err)) ||
        (rc = need_positive(estar, "combined modulus E*", "Pa", err)))
        return rc;
    double W = wprime / (2.0 * estar * rx); /* Hamrock's W' with E' = 2 E* */
    *b = rx * sqrt(8.0 * W / M_PI);
    *p_h = 2.0 * wprime / (M_PI * *b);
    return MC_OK;
}
