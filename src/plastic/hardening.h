/* hardening.h - isotropic hardening laws sigma_y(p) of J2 plasticity: the yield stress as a
 * function of the accumulated equivalent plastic strain p = integral sqrt(2/3 deps_p : deps_p)
 * (dimensionless, >= 0), and its slope H(p) = d sigma_y / dp (the plastic modulus). Pure math on
 * a small value object; no scene knowledge. (Dossier theory.md §7.2.)
 *
 * Laws, all stresses in Pa:
 *   PERFECT  sigma_y = Y0                                   H = 0
 *   LINEAR   sigma_y = Y0 + H p                             H constant >= 0
 *   SWIFT    sigma_y = B (C + 1e6 p)^n                      H = 1e6 B n (C + 1e6 p)^(n-1)
 *            Nelias-group form (Nelias, Boucher & Brunet 2006): the factor 1e6 puts p in
 *            micro-strain. B (Pa) is the stress scale, C (dimensionless, micro-strain) the
 *            pre-strain offset that sets the initial yield B C^n, and n the hardening exponent.
 *            It is the classical Swift law K (eps0 + p)^n with K = B 1e6^n, eps0 = 1e-6 C.
 *            AISI 52100 (remembered values, theory.md §7.2 [S]): B = 1280 MPa, C = 4, n = 0.095, giving
 *            sigma_y(0) = 1460 MPa. Dropping the 1e6 would make the law nearly perfect.
 *   TABLE    piecewise linear through rows (eps_p[i], sigma_y[i]); below the first row and
 *            beyond the last one sigma_y is constant (slope 0: perfectly plastic there).
 *
 * Ownership: a TABLE law owns copies of its two arrays (mc_malloc); release them with
 * mc_hardening_free. The other kinds own nothing, but mc_hardening_free is harmless on them.
 * Constructors validate and write *h only on success (on failure *h is untouched), so an
 * mc_hardening built by them is always valid. Code that fills the struct by hand calls
 * mc_hardening_validate before use; the evaluation functions assume a valid law.
 */
#ifndef MC_HARDENING_H
#define MC_HARDENING_H

#include <stddef.h>

#include "core/error.h"

typedef enum {
    MC_HARDENING_PERFECT, /* elastic-perfectly plastic */
    MC_HARDENING_LINEAR,  /* linear isotropic hardening */
    MC_HARDENING_SWIFT,   /* Swift power law, Nelias form */
    MC_HARDENING_TABLE,   /* tabulated, piecewise linear */
    MC_HARDENING_NKINDS
} mc_hardening_kind;

/* The law table (hardening.c): every law's name ("perfect", "linear", "swift", "table"), one
 * line of help, its reference and its constructor from mc_hardening_params; NULL when k is out
 * of range. The key table ([plasticity] hardening), the docs, the messages and the results
 * (summary.json plastic.hardening) take the names from here; iterate
 * k = 0 .. mc_hardening_count() - 1. */
int mc_hardening_count(void);
const char *mc_hardening_name(mc_hardening_kind k);
const char *mc_hardening_help(mc_hardening_kind k);
const char *mc_hardening_reference(mc_hardening_kind k);
/* Exact name -> kind. MC_OK, or MC_ERR_INPUT listing the accepted names. */
int mc_hardening_from_name(const char *name, mc_hardening_kind *out, mc_error *err);

typedef struct mc_hardening {
    mc_hardening_kind kind;
    double yield_stress;    /* Y0, Pa (PERFECT, LINEAR): the initial yield stress, > 0 */
    double plastic_modulus; /* H, Pa (LINEAR): d sigma_y / dp, >= 0 */
    double swift_B;         /* B, Pa (SWIFT), > 0 */
    double swift_C;         /* C, micro-strain (SWIFT), > 0 */
    double swift_n;         /* n (SWIFT), 0 <= n < 1 */
    double swift_y0;        /* B C^n (SWIFT): sigma_y(0), kept by mc_hardening_swift (the cells
                               that never yielded ask for it in every sweep: no pow() per cell) */
    double *eps_p;          /* TABLE: n_rows plastic strains, >= 0, strictly increasing; owned */
    double *sigma_y;        /* TABLE: n_rows yield stresses, Pa, > 0, non-decreasing; owned */
    size_t n_rows;          /* TABLE: number of rows, >= 1 */
} mc_hardening;

/* Plastic modulus of a linear law from the uniaxial tangent modulus Et of the stress-strain
 * curve after yield: *H = E Et / (E - Et). (In uniaxial stress the elastic and plastic
 * compliances add, 1/Et = 1/E + 1/H; theory.md §7.2.) Needs finite E > 0 and 0 <= Et < E
 * (Et = 0 gives H = 0, perfect plasticity); otherwise MC_ERR_INPUT naming the quantity. */
int mc_hardening_linear_from_tangent(double E, double Et, double *H, mc_error *err);

/* Constructors. All arguments must be finite; accepted ranges are stated in the error message.
 * Return MC_OK, or MC_ERR_INPUT (*h untouched). */
int mc_hardening_perfect(double Y0, mc_hardening *h, mc_error *err);          /* Y0 > 0 */
int mc_hardening_linear(double Y0, double H, mc_hardening *h, mc_error *err); /* Y0 > 0, H >= 0 */
/* B > 0 (Pa), C > 0, 0 <= n < 1. */
int mc_hardening_swift(double B, double C, double n, mc_hardening *h, mc_error *err);

/* TABLE law from n_rows >= 1 rows (copied; the caller keeps its arrays). Rows: eps_p[0] >= 0,
 * eps_p strictly increasing, sigma_y > 0 and non-decreasing, all finite; an error names the
 * offending row (1-based). MC_ERR_INPUT, or MC_ERR_NOMEM when the copy cannot be allocated. */
int mc_hardening_table(const double *eps_p, const double *sigma_y, size_t n_rows,
                       mc_hardening *h, mc_error *err);

/* Every parameter any law takes, as a case gives them ([plasticity]); each law reads its own. */
typedef struct {
    double E;               /* Young's modulus of the yielding body, Pa (linear: H from Et) */
    double yield_stress;    /* Y0, Pa (perfect, linear) */
    double tangent_modulus; /* Et, Pa (linear) */
    double swift_B, swift_C, swift_n; /* swift */
    const char *table;      /* path of the table file (table) */
    double table_unit;      /* Pa per unit of the file's sigma_y column (table) */
} mc_hardening_params;

/* Law k from the parameters, by the law's constructor in the table (perfect: mc_hardening_perfect
 * (Y0); linear: H from mc_hardening_linear_from_tangent(E, Et), then mc_hardening_linear; swift;
 * table: mc_hardening_table_read). Returns what the constructor returns; MC_ERR_INPUT naming k
 * when it is out of range. */
int mc_hardening_build(mc_hardening_kind k, const mc_hardening_params *par, mc_hardening *h,
                       mc_error *err);

/* Largest yield stress of any law, Pa: the bound of the [plasticity] yield_stress key. */
#define MC_HARDENING_STRESS_MAX 1e12

/* TABLE law from a text file of "eps_p, sigma_y" rows (comma separated, blanks around fields
 * allowed). '#' starts a comment (whole line or trailing); blank lines are skipped; one header
 * line (a first field that is not a number) is allowed before the first data row. Numbers are
 * decimal (no hexadecimal); the first row's eps_p is 0; sigma_y <= MC_HARDENING_STRESS_MAX. stress_unit is
 * the value in Pa of one unit of the file's sigma_y column (1 for Pa, 1e6 for MPa; > 0). Each
 * error names "path:line" (table rules as mc_hardening_table). Returns MC_OK, MC_ERR_IO (cannot
 * open/read), MC_ERR_INPUT (syntax, values) or MC_ERR_NOMEM. */
int mc_hardening_table_read(const char *path, double stress_unit, mc_hardening *h, mc_error *err);

/* Check any mc_hardening (e.g. filled by hand) against the rules above. MC_OK or MC_ERR_INPUT. */
int mc_hardening_validate(const mc_hardening *h, mc_error *err);

/* Yield stress sigma_y(p), Pa, for p >= 0. NaN for p < 0 or p NaN (a broken caller shows up
 * downstream as a non-finite value rather than as a silently clamped one). */
double mc_hardening_sigma_y(const mc_hardening *h, double p);

/* Slope H(p) = d sigma_y / dp, Pa, for p >= 0 (NaN as above). TABLE: the slope of the segment
 * [eps_p[i], eps_p[i+1]) holding p (the right-hand slope at a row), 0 outside the table. */
double mc_hardening_slope(const mc_hardening *h, double p);

/* Initial yield stress sigma_y(0), Pa: Y0, B C^n, or sigma_y[0] of a table. */
double mc_hardening_initial(const mc_hardening *h);

/* Release a TABLE law's arrays and zero *h (safe on any kind, on a zeroed struct and on NULL). */
void mc_hardening_free(mc_hardening *h);

#endif
