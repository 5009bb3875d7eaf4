/* friction.h - the load and area split between solid contact and lubricant of a lubricated
 * rough contact, the mean pocket height, and the mixed-friction coefficient
 * (Mevissen, Lopenhaus & Bergs 2019; theory.md §11.3).
 *
 * From the pressure p (Pa) and gap g (m) of a contact solve with lubricant pressure p_lub on n
 * cells of area dA (nominal area A_nom = n dA) under the nominal load F_N:
 *     C        = { i : p_i > p_lub }                 (solid contact cells)
 *     A_C      = dA |C|
 *     F_solid  = dA sum_{i in C} p_i                 (load carried by the solid contacts)
 *              = F_N - p_lub (A_nom - A_C)           when the load balance holds
 *     psi_load = F_solid / F_N,   psi_area = A_C / A_nom
 *     V        = dA sum_i g_i                         (pocket volume; g = 0 in contact)
 *     h_pocket = V / (A_nom - A_C)                    (mean lubricant pocket height)
 *     mu       = psi mu_solid + (1 - psi) mu_fluid,   psi = psi_load (default) | psi_area
 * Which psi the paper mixes with is not confirmed (theory.md §15, point 4): both are kept. The
 * excess-pressure form dA sum_C (p_i - p_lub) / F_N is reported as an alternative.
 */
#ifndef MC_LUBE_FRICTION_H
#define MC_LUBE_FRICTION_H

#include <stddef.h>

#include "core/error.h"

typedef enum { MC_PSI_LOAD = 0, MC_PSI_AREA = 1, MC_PSI_NKINDS } mc_psi_kind;

/* The psi table (friction.c): name ("load" | "area") and one line of help of kind k; NULL when
 * out of range. Iterate k = 0 .. mc_psi_count() - 1. */
int mc_psi_count(void);
const char *mc_psi_name(mc_psi_kind k);
const char *mc_psi_help(mc_psi_kind k);
/* "load" | "area" -> kind. MC_OK or MC_ERR_INPUT naming the accepted names. */
int mc_psi_from_name(const char *name, mc_psi_kind *out, mc_error *err);

typedef struct {
    double a_nom;          /* nominal area n dA, m^2 */
    double a_contact;      /* solid contact area A_C, m^2 */
    double f_solid;        /* dA sum over C of p, N */
    double f_solid_excess; /* dA sum over C of (p - p_lub), N (alternative) */
    double f_fluid;        /* p_lub (A_nom - A_C), N: the lubricant's share */
    double volume;         /* pocket volume V = dA sum g, m^3 */
    double psi_load;       /* F_solid / F_N */
    double psi_area;       /* A_C / A_nom */
    double psi_load_excess;/* F_solid_excess / F_N (alternative) */
    double pocket_height;  /* V / (A_nom - A_C), m; 0 when A_C = A_nom (no pocket left) */
} mc_lube_split;

/* The split of the module header from the fields p (Pa) and gap (m), n cells of area dA (m^2),
 * lubricant pressure p_lub >= 0 (Pa) and nominal load F_N > 0 (N). Arrays are read only.
 * MC_OK or MC_ERR_INPUT (n = 0, dA, p_lub or F_N out of range, a non-finite value). */
int mc_lube_split_of(const double *p, const double *gap, size_t n, double dA, double p_lub,
                     double f_n, mc_lube_split *s, mc_error *err);

/* The same with a lubricant pressure profile w (volume.h; NULL = 1 everywhere): solid contact
 * cells are those with p_i > p_lub w_i; A_nom, V and psi_area are of the nominal area (w > 0);
 * F_solid counts every solid contact cell; f_fluid = dA sum over the other cells of p_lub w. */
int mc_lube_split_weighted(const double *p, const double *gap, const double *w, size_t n,
                           double dA, double p_lub, double f_n, mc_lube_split *s, mc_error *err);

/* h_pocket = V / (A_nom - A_C), m, from V >= 0 (m^3), A_nom > 0 and 0 <= A_C <= A_nom (m^2);
 * 0 when A_C = A_nom. MC_OK or MC_ERR_INPUT. */
int mc_pocket_height(double volume, double a_nom, double a_contact, double *h, mc_error *err);

/* mu = psi mu_solid + (1 - psi) mu_fluid with 0 <= psi <= 1 and mu_solid, mu_fluid >= 0 finite.
 * MC_OK or MC_ERR_INPUT. */
int mc_friction_mu(double psi, double mu_solid, double mu_fluid, double *mu, mc_error *err);

/* psi of kind k from a split (psi_load or psi_area). */
double mc_lube_split_psi(const mc_lube_split *s, mc_psi_kind k);

#endif
