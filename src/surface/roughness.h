/* roughness.h - standard roughness parameters of a height map.
 *
 * ISO 16610-21 Gaussian profile filter, ISO 4288 cut-off choice, ISO 4287 profile parameters,
 * ISO 13565-2 material-ratio (Rk) parameters and ISO 25178-2 areal parameters, computed on a
 * levelled height map (form removal is the caller's: level.h). Heights z are ny x nx, m,
 * row-major with x fastest; profiles are the rows (along x, the rolling direction); an optional
 * mask valid[] (1 = measured) excludes points from every sum (NULL: all valid). SI units in and
 * out; material ratios and Sdr in %. (Dossier theory.md §13.) */
#ifndef MC_ROUGHNESS_H
#define MC_ROUGHNESS_H

#include <stddef.h>

#include "core/error.h"

#define MC_ROUGHNESS_ALPHA 0.46971863934982566 /* sqrt(ln 2 / pi), ISO 16610-21 */

/* ---- Gaussian profile filter (ISO 16610-21) ---------------------------------------------- */

/* Half-width in samples of the truncated kernel at spacing d: floor(lambda_c / d). */
int mc_roughness_filter_halfwidth(double d, double lambda_c);

/* Mean line w (waviness) of every row of z along x, cut-off lambda_c (m); the roughness
 * profile is z - w. Weighting function s(x) = exp(-pi (x / (alpha lambda_c))^2) / (alpha
 * lambda_c), amplitude transmission of the mean line exp(-pi (alpha lambda_c / lambda)^2)
 * (50 % at lambda = lambda_c).
 *  - periodic = 0: s sampled at the spacing, truncated at +-lambda_c, renormalised to unit sum;
 *    at the ends of the row and next to invalid points the kernel is renormalised over the
 *    valid samples it covers: w = (s * (v z)) / (s * v), v the mask. Only points at least
 *    mc_roughness_filter_halfwidth samples from both ends see the whole kernel; ISO discards the
 *    others (mc_roughness_compute does).
 *  - periodic = 1: the row is one period; each harmonic is multiplied by the exact transmission
 *    (the FFT form, theory.md §13.1, nothing truncated or discarded), with the same mask rule.
 * w at an invalid point with no valid point within reach is 0. Computed by FFTW (plans made
 * here, FFTW_ESTIMATE, one thread; FFTW's planner is not thread-safe, so call from one thread,
 * as mc_roughness_compute too). Errors: MC_ERR_INPUT (sizes, spacing, cut-off),
 * MC_ERR_NOMEM, MC_ERR_INTERNAL (FFTW). */
int mc_roughness_mean_line(const double *z, const unsigned char *valid, int nx, int ny,
                           double dx, double lambda_c, int periodic, double *w, mc_error *err);

/* ---- ISO 4288 cut-off choice ------------------------------------------------------------- */

/* Cut-off lambda_c (m) for a non-periodic profile of the given Ra or Rz (m), from the table of
 * ISO 4288 (theory.md §13.2, pl_iso4288_cutoffs.csv): Ra in (0.006, 0.02] um -> 0.08 mm,
 * (0.02, 0.1] -> 0.25 mm, (0.1, 2] -> 0.8 mm, (2, 10] -> 2.5 mm, (10, 80] -> 8 mm; Rz in
 * (0.025, 0.1], (0.1, 0.5], (0.5, 10], (10, 50], (50, 200] um likewise. Upper bounds are
 * inclusive, compared with a relative slack of 1e-9 so that a value written as the table's
 * decimal lands in its row. Values below or above the table get its first or last row and
 * *in_table = 0 (may be NULL). The evaluation length is 5 lambda_c. */
double mc_iso4288_cutoff_ra(double ra, int *in_table);
double mc_iso4288_cutoff_rz(double rz, int *in_table);

/* ---- ISO 13565-2 material ratio ---------------------------------------------------------- */

typedef struct {
    double k;        /* core roughness depth Rk (Sk), m */
    double pk, vk;   /* reduced peak height Rpk and valley depth Rvk, m */
    double mr1, mr2; /* material ratios at the core's top and bottom, % */
    double c0, c100; /* heights of the equivalent straight line at Mr = 0 and 100 %, m
                        (k = c0 - c100) */
} mc_material_ratio;

/* Rk family of n heights h (any order; work: n doubles, on return the heights sorted highest
 * first: the material-ratio curve). The material-ratio curve
 * puts the k-th highest of n heights (k = 0..n-1) at Mr = 100 (k + 1/2) / n %. The equivalent
 * straight line is the secant spanning round(0.4 n) samples (Delta Mr = 40 %) with the smallest
 * |slope|; its heights at Mr = 0 and 100 % are c0, c100 and Rk = c0 - c100. Mr1 is the share of
 * heights above c0, Mr2 the share at or above c100; Rpk = 2 A1 / Mr1 and Rvk =
 * 2 A2 / (100 - Mr2) with A1 = sum over h > c0 of (h - c0) 100/n and A2 = sum over h < c100
 * of (c100 - h) 100/n (0 when the share is 0). n < 2 gives Rk = Rpk = Rvk = 0, Mr1 = 0,
 * Mr2 = 100, c0 = c100 = the height (0 for n = 0). (Dossier §6.4.) */
void mc_roughness_material_ratio(const double *h, size_t n, double *work, mc_material_ratio *out);

/* The areal material-ratio (Abbott-Firestone) curve of a height map (n points, mask valid as
 * above, NULL: all) sampled at npts >= 2 equally spaced ratios Mr_k = 100 k / (npts - 1) %:
 * height[k], m, about the mean of the valid points (the reference of the areal parameters). The
 * curve is that of mc_roughness_material_ratio (the j-th highest of the cnt valid heights at
 * Mr = 100 (j + 1/2) / cnt), linear between those points and constant beyond the first and the
 * last: height[0] = Sp and height[npts - 1] = -Sv. *line (may be NULL) receives the Sk family
 * of the same heights with its equivalent straight line c0 + (c100 - c0) Mr / 100: the same
 * numbers as Sk, Spk, Svk, Smr1, Smr2 of mc_roughness_compute on that map. (theory.md §13.4.)
 * Errors: MC_ERR_INPUT (npts < 2, no valid point, a non-finite valid height), MC_ERR_NOMEM. */
int mc_roughness_material_curve(const double *z, const unsigned char *valid, size_t n, int npts,
                                double *height, mc_material_ratio *line, mc_error *err);

/* ---- all parameters ---------------------------------------------------------------------- */

typedef struct {
    double cutoff;  /* lambda_c, m; 0: chosen by ISO 4288 from Ra (see mc_roughness_compute) */
    int periodic_x; /* 1: rows are periodic (filter wraps around, nothing discarded) */
    int periodic_y; /* 1: columns are periodic (areal slopes wrap around) */
    int filter;     /* 1: Gaussian profile filter; 0: only each row's mean is removed and
                       lambda_c just sets the sampling length */
} mc_roughness_options;

/* cutoff 0 (ISO 4288), not periodic, filter on. */
void mc_roughness_options_default(mc_roughness_options *opt);

typedef struct {
    /* ISO 4287 profile parameters: each row evaluated, then the mean over the rows, m */
    double Ra, Rq, Rz, Rp, Rv, Rt;
    double Rsk, Rku;                 /* dimensionless */
    /* ISO 13565-2 on each row's roughness profile, mean over the rows (m; Mr in %) */
    double Rk, Rpk, Rvk, Mr1, Mr2;
    /* ISO 25178-2 on the whole map about its mean plane (no areal filter), m */
    double Sa, Sq, Sz, Sp, Sv;
    double Ssk, Sku;                 /* dimensionless */
    double Sdq;                      /* rms slope, m/m */
    double Sdr;                      /* developed interfacial area ratio, % */
    double Sk, Spk, Svk, Smr1, Smr2; /* areal material ratio (ISO 25178-2), m and % */
    /* how they were obtained */
    double cutoff_nominal;    /* lambda_c requested or chosen by ISO 4288, m */
    double cutoff;            /* lambda_c used (cutoff_nominal unless clipped), m */
    double evaluation_length; /* per row, after the ends were discarded, m */
    int n_sampling;           /* sampling lengths per row behind Rp, Rv, Rz (5 in ISO 4288) */
    int rows;                 /* rows with at least one valid point evaluated */
    long points;              /* valid points behind the areal parameters */
    int filtered;             /* the Gaussian filter was applied */
    int cutoff_auto;          /* lambda_c came from ISO 4288 */
    int cutoff_clipped;       /* the profile was too short for lambda_c: reduced */
    int short_evaluation;     /* fewer than 5 sampling lengths were available */
    int profile_not_computable; /* lambda_c < MC_ROUGHNESS_MIN_SAMPLES dx (ISO 4288 choice):
                                   the profile family is left out (mc_roughness_entries) */
    char warning[512];        /* "" or one line saying what deviates from the standard */
} mc_roughness_params;

/* Fewest sampling intervals a Gaussian cut-off must span for the profile parameters to mean
 * anything (a mean line of a few samples follows the heights themselves). */
#define MC_ROUGHNESS_MIN_SAMPLES 4

/* Every parameter of a height map (contract above; theory.md §13).
 *
 * Profiles (rows along x, length L = nx dx): with the filter, the roughness profile is z - w
 * (mc_roughness_mean_line); non-periodic rows lose halfwidth samples at each end (about
 * lambda_c, ISO 16610-21), periodic rows lose nothing. Without the filter, the roughness profile
 * is z minus the row's mean. Ra, Rq, Rsk, Rku, Rt and the Rk family are taken over the
 * evaluation length; Rp, Rv are the means over its sampling lengths (it is cut into
 * n_sampling = floor(evaluation length / lambda_c) equal parts, all of them when there are more
 * than 5) of the highest peak and deepest valley, Rz = Rp + Rv; then every parameter is averaged
 * over the rows.
 * Cut-off: opt->cutoff, or, when 0, ISO 4288 from Ra: Ra of the unfiltered rows gives the first
 * choice, then Ra is re-measured with the filter at the chosen cut-off and the choice repeated
 * until Ra falls in the chosen row of the table (at most 5 rounds; ISO 4288 §7).
 * A profile too short for one sampling length (L < 3 lambda_c non-periodic with filter, which
 * discards lambda_c at each end; L < lambda_c otherwise) is never an error: lambda_c is clipped
 * to L/3 (resp. L), the parameters are computed over what there is and a warning says so;
 * fewer than 5 sampling lengths set short_evaluation and a warning too. A 1 x n map or a single
 * column gives what its points allow (zeros where nothing varies).
 * Areal (the whole map, no L-filter: the caller's levelling defines the reference): heights
 * about their mean over the valid points; Sp, Sv the highest and deepest, Sz = Sp + Sv;
 * Sdq = sqrt(mean(z_x^2 + z_y^2)) and Sdr = 100 mean(sqrt(1 + z_x^2 + z_y^2) - 1) from
 * central differences (wrapped on periodic axes; on free axes only interior points whose
 * neighbours are valid; an axis of fewer than 3 free points contributes no slope). Central
 * differences see a mode of wavenumber k with the factor sin(k d)/(k d).
 * A cut-off (after clipping) below MC_ROUGHNESS_MIN_SAMPLES dx with the filter: a given one is
 * MC_ERR_INPUT naming it and the accepted minimum; one chosen by ISO 4288, or clipped, sets
 * profile_not_computable and a warning, and the areal parameters are still computed.
 * opt NULL means the defaults. Errors: MC_ERR_INPUT (sizes, spacings, cut-off < 0 or not finite,
 * no valid point, a non-finite valid height), MC_ERR_NOMEM, MC_ERR_INTERNAL (FFTW). */
int mc_roughness_compute(const double *z, const unsigned char *valid, int nx, int ny, double dx,
                         double dy, const mc_roughness_options *opt, mc_roughness_params *out,
                         mc_error *err);

/* One parameter by its standard name, for JSON output. */
typedef struct {
    const char *name; /* "Ra", "Rq", ..., "Sa", ..., "lambda_c" (static strings) */
    const char *unit; /* "m", "1" (dimensionless) or "%" */
    double value;     /* SI (m), or % where unit says so */
} mc_roughness_entry;

#define MC_ROUGHNESS_NENTRIES 28 /* rows of the parameter table (roughness.c) */

/* The parameter table (roughness.c): name ("Ra", ...) and one line of help of parameter i in
 * the reported order; NULL when out of range. Iterate i = 0 .. mc_roughness_entry_count() - 1. */
int mc_roughness_entry_count(void);
const char *mc_roughness_entry_name(int i);
const char *mc_roughness_entry_help(int i);

/* Fill out[] with every parameter in a fixed order (Ra Rq Rz Rp Rv Rt Rsk Rku Rk Rpk Rvk Mr1
 * Mr2 Sa Sq Sz Sp Sv Ssk Sku Sdq Sdr Sk Spk Svk Smr1 Smr2 lambda_c); returns the count,
 * MC_ROUGHNESS_NENTRIES; without the profile family (R..., Mr1, Mr2) when
 * profile_not_computable (fewer). */
int mc_roughness_entries(const mc_roughness_params *p, mc_roughness_entry out[]);

#endif
