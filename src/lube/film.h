/* film.h - EHL film thickness of the smooth macro contact (Hamrock's conventions), the rolling
 * kinematics of two discs and the macro Hertz line contact.
 *
 * The film formulas are Hamrock's regression fits for isothermal, fully flooded, Newtonian
 * elastohydrodynamic contacts (no inlet shear heating, no starvation). With Hamrock's groups
 *
 *     E' = 2 E*,  2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2        (reduced modulus, Pa)
 *     1/R_x = 1/R1 + 1/R2                                       (reduced radius in x, external discs)
 *     u = (u1 + u2)/2                                           (mean entrainment speed, m/s)
 *     U = eta0 u / (E' R_x),  G = alpha E',
 *     W' = w' / (E' R_x)   (line contact, w' = F_N / L in N/m),
 *     W  = F_N / (E' R_x^2) (point contact, F_N in N)
 *
 * each formula gives H = h / R_x (theory.md §10.1-§10.2):
 *     pan_hamrock_central     H_c   = 2.922 W'^-0.166 U^0.692 G^0.470   (Pan & Hamrock 1989; line)
 *     pan_hamrock_min         H_min = 1.714 W'^-0.128 U^0.694 G^0.568   (Pan & Hamrock 1989; line)
 *     dowson_toyoda           H_c   = 3.06  U^0.69 G^0.56 W'^-0.10      (Dowson & Toyoda 1979; line)
 *     dowson_higginson        H_min = 2.65  U^0.70 G^0.54 W'^-0.13      (Dowson & Higginson; line)
 *     hamrock_dowson_central  H_c   = 2.69  U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^(-0.73 k))  (point)
 *     hamrock_dowson_min      H_min = 3.63  U^0.68 G^0.49 W^-0.073 (1 - e^(-0.68 k))       (point)
 * with the ellipticity k = a/b of the point contact (Hamrock & Dowson 1977:
 * k = 1.03 (R_y/R_x)^0.64, mc_film_ellipticity).
 *
 * The default, pan_hamrock_central, stands for the paper's mean film thickness h_EHD: the central
 * film is the best proxy for the mean gap over the Hertz zone (theory.md §10.2, an open choice there).
 * The fits hold in the piezoviscous-elastic regime; at alpha = 0 every one of them degenerates to
 * h = 0 (G^x), which is not the isoviscous film, so alpha = 0 is refused.
 */
#ifndef MC_LUBE_FILM_H
#define MC_LUBE_FILM_H

#include "core/error.h"

typedef enum {
    MC_FILM_PAN_HAMROCK_CENTRAL = 0, /* line, central (default) */
    MC_FILM_PAN_HAMROCK_MIN,         /* line, minimum */
    MC_FILM_DOWSON_TOYODA,           /* line, central */
    MC_FILM_DOWSON_HIGGINSON,        /* line, minimum */
    MC_FILM_HAMROCK_DOWSON_CENTRAL,  /* point, central */
    MC_FILM_HAMROCK_DOWSON_MIN,      /* point, minimum */
    MC_FILM_NFORMULAS
} mc_film_formula;

#define MC_FILM_DEFAULT MC_FILM_PAN_HAMROCK_CENTRAL

/* The formula table (film.c): every formula's name ("pan_hamrock_central", ...), one line of
 * help (contact kind, film, expression) and its reference; NULL when f is out of range. The key
 * table, the docs and the messages list the formulas from these, in table order; iterate
 * f = 0 .. mc_film_formula_count() - 1. */
int mc_film_formula_count(void);
const char *mc_film_formula_name(mc_film_formula f);
const char *mc_film_formula_help(mc_film_formula f);
const char *mc_film_formula_reference(mc_film_formula f);

/* Exact (case-sensitive) name -> formula. MC_OK, or MC_ERR_INPUT naming the accepted names. */
int mc_film_formula_from_name(const char *name, mc_film_formula *out, mc_error *err);

/* 1 for the point-contact formulas (load F_N and ellipticity k), 0 for line contact (w'). */
int mc_film_formula_is_point(mc_film_formula f);

/* ---- material, geometry, kinematics -------------------------------------------------------- */

/* E' = 2 / [(1 - nu1^2)/E1 + (1 - nu2^2)/E2], Pa. E1, E2 > 0 (Pa; INFINITY for a rigid body, not both), -1 < nu <= 0.5.
 * MC_OK or MC_ERR_INPUT. */
int mc_film_eprime(double E1, double nu1, double E2, double nu2, double *eprime, mc_error *err);

/* 1/R_x = 1/R1 + 1/R2 (two external cylinders), m. R1, R2 > 0; INFINITY stands for a flat.
 * MC_OK or MC_ERR_INPUT (both flat included). */
int mc_film_reduced_radius(double R1, double R2, double *rx, mc_error *err);

/* Surface speed of a disc, m/s: u = 2 pi n R / 60 (n in rpm, R in m). No checks. */
double mc_film_surface_speed(double rpm, double radius);

typedef struct {
    double u1, u2; /* surface speeds, m/s */
    double u;      /* mean entrainment speed (u1 + u2)/2, m/s */
    double v_sum;  /* sum velocity u1 + u2, m/s */
    double srr;    /* slide-to-roll ratio 2 |u1 - u2| / (u1 + u2) */
} mc_film_kinematics;

/* From surface speeds (m/s): u1, u2 >= 0 finite, u1 + u2 > 0 (both surfaces move into the
 * contact). MC_OK or MC_ERR_INPUT. */
int mc_film_kinematics_speeds(double u1, double u2, mc_film_kinematics *k, mc_error *err);

/* From disc speeds n1, n2 (rpm, >= 0, not both 0) and radii R1, R2 (m, > 0 finite):
 * u_i = 2 pi n_i R_i / 60. MC_OK or MC_ERR_INPUT. */
int mc_film_kinematics_rpm(double n1, double R1, double n2, double R2, mc_film_kinematics *k,
                           mc_error *err);

/* Hamrock & Dowson's ellipticity k = 1.03 (R_y/R_x)^0.64 (point contacts). No checks. */
double mc_film_ellipticity(double ry_over_rx);

/* ---- film thickness -------------------------------------------------------------------------- */

typedef struct {
    double eta0;   /* viscosity at ambient pressure and inlet temperature, Pa s, > 0 */
    double alpha;  /* pressure-viscosity coefficient (Barus), 1/Pa, > 0 */
    double u;      /* mean entrainment speed, m/s, > 0 */
    double eprime; /* reduced modulus E' = 2 E*, Pa, > 0 */
    double rx;     /* reduced radius in the rolling direction, m, > 0 */
    double load;   /* line formulas: w' = F_N / L, N/m; point formulas: F_N, N; > 0 */
    double k;      /* point formulas: ellipticity a/b > 0 (ignored for line formulas) */
} mc_film_input;

typedef struct {
    double U, G;   /* speed and materials parameters */
    double W;      /* load parameter: W' (line) or W (point) */
} mc_film_groups;

/* Dimensionless groups of the module header for formula f (which decides W' or W). Every input
 * is checked (finite and in the range given in mc_film_input). MC_OK or MC_ERR_INPUT naming the
 * quantity, its value and the accepted range. */
int mc_film_groups_of(mc_film_formula f, const mc_film_input *in, mc_film_groups *g,
                      mc_error *err);

/* Film thickness h (m) by formula f: the groups as above, then h = H R_x. MC_OK or MC_ERR_INPUT
 * (unknown formula or a bad input, as mc_film_groups_of). */
int mc_film_thickness(mc_film_formula f, const mc_film_input *in, double *h, mc_error *err);

/* The formulas themselves, h = H R_x in m, from the groups (no checks). */
double mc_film_pan_hamrock_central(double U, double G, double W, double rx);
double mc_film_pan_hamrock_min(double U, double G, double W, double rx);
double mc_film_dowson_toyoda(double U, double G, double W, double rx);
double mc_film_dowson_higginson(double U, double G, double W, double rx);
double mc_film_hamrock_dowson_central(double U, double G, double W, double k, double rx);
double mc_film_hamrock_dowson_min(double U, double G, double W, double k, double rx);

/* ---- macro Hertz line contact ---------------------------------------------------------------- */

/* Half-width b (m) and maximum pressure p_H (Pa) of a Hertz line contact under w' (N/m) with
 * reduced radius R_x (m) and E* (Pa), in Hamrock's form b = R_x sqrt(8 W' / pi), W' = w'/(E' R_x),
 * E' = 2 E*, and p_H = 2 w' / (pi b) (Johnson: b^2 = 4 w' R / (pi E*)). All > 0 finite.
 * MC_OK or MC_ERR_INPUT. */
int mc_film_hertz_line(double wprime, double rx, double estar, double *b, double *p_h,
                       mc_error *err);

#endif
