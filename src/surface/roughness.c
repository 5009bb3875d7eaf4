/* roughness.c - all roughness parameters of a map: cut-off choice and clipping, warnings, the
 * name table (see roughness.h; theory.md §13). */
#include "surface/roughness.h"

#include <math.h>
#include <stdio.h>
#include <stddef.h>
#include <string.h>

#include "surface/roughness_internal.h"

#define ISO4288_ROUNDS 5  /* table rows: the choice cannot move further */
#define ISO4288_SAMPLING 5 /* sampling lengths in the ISO 4288 evaluation length */

void mc_roughness_options_default(mc_roughness_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->filter = 1;
}

/* Cut-off actually used for a nominal one: a non-periodic filtered row loses lambda_c at each
 * end and must keep one sampling length, so it needs L >= 3 lambda_c; otherwise L >= lambda_c. */
static double clip_cutoff(double nominal, double len, int periodic, int filter, int *clipped)
{
    double need = (filter && !periodic) ? 3.0 : 1.0;
    *clipped = len < need * nominal * (1 - 1e-12);
    return *clipped ? len / need : nominal;
}

static void append(char *buf, size_t size, const char *text)
{
    size_t len = strlen(buf);
    if (len + 3 < size)
        snprintf(buf + len, size - len, "%s%s", len ? "; " : "", text);
}

int mc_roughness_compute(const double *z, const unsigned char *valid, int nx, int ny, double dx,
                         double dy, const mc_roughness_options *opt, mc_roughness_params *out,
                         mc_error *err)
{
    mc_roughness_options def;
    if (!opt) {
        mc_roughness_options_default(&def);
        opt = &def;
    }
    memset(out, 0, sizeof *out);
    if (nx < 1 || ny < 1)
        return mc_fail(err, MC_ERR_INPUT, "roughness: %d x %d points, both must be >= 1", nx,
                       ny);
    if (!(dx > 0 && isfinite(dx) && dy > 0 && isfinite(dy)))
        return mc_fail(err, MC_ERR_INPUT, "roughness: spacings dx = %g m, dy = %g m must be "
                       "finite and > 0", dx, dy);
    if (!(opt->cutoff >= 0 && isfinite(opt->cutoff)))
        return mc_fail(err, MC_ERR_INPUT, "roughness: cut-off %g m must be finite and >= 0 "
                       "(0: ISO 4288)", opt->cutoff);
    size_t n = (size_t)nx * ny, nvalid = 0;
    for (size_t k = 0; k < n; k++) {
        if (valid && !valid[k])
            continue;
        if (!isfinite(z[k]))
            return mc_fail(err, MC_ERR_INPUT, "roughness: height at point (%zu, %zu) is not "
                           "finite", k % (size_t)nx, k / (size_t)nx);
        nvalid++;
    }
    if (nvalid == 0)
        return mc_fail(err, MC_ERR_INPUT, "roughness: the %d x %d map has no valid point", nx,
                       ny);

    const double len = nx * dx;
    const int px = opt->periodic_x != 0, filter = opt->filter != 0;
    int rc, in_table = 1, clipped = 0;
    double nominal = opt->cutoff, used;
    if (nominal == 0) { /* ISO 4288: first guess from the unfiltered rows */
        out->cutoff_auto = 1;
        if ((rc = mc_rough_profiles(z, valid, nx, ny, dx, len, px, 0, out, err)))
            return rc;
        nominal = mc_iso4288_cutoff_ra(out->Ra, &in_table);
    }
    double tried[ISO4288_ROUNDS];
    int ntried = 0;
    for (;;) {
        used = clip_cutoff(nominal, len, px, filter, &clipped);
        if ((rc = mc_rough_profiles(z, valid, nx, ny, dx, used, px, filter, out, err)))
            return rc;
        if (!out->cutoff_auto || !filter)
            break; /* without the filter Ra does not depend on the cut-off */
        tried[ntried++] = nominal;
        double next = mc_iso4288_cutoff_ra(out->Ra, &in_table);
        int seen = 0;
        for (int t = 0; t < ntried; t++)
            seen |= tried[t] == next;
        if (seen || ntried == ISO4288_ROUNDS)
            break; /* Ra falls in the row of the cut-off used (or the choice would cycle) */
        nominal = next;
    }
    /* A Gaussian mean line of a cut-off spanning a few samples is no mean line: a 0.8 mm cut-off
     * on a 27.5 mm grid gave Ra ~ 1e-18 m, negative Rp and Rz = 0 < Rt. Below
     * MC_ROUGHNESS_MIN_SAMPLES sampling intervals a given cut-off is refused; an ISO 4288
     * choice, or one clipped on a short profile, leaves the profile parameters out, saying why. */
    if (filter && used < MC_ROUGHNESS_MIN_SAMPLES * dx) {
        if (!out->cutoff_auto && !clipped)
            return mc_fail(err, MC_ERR_INPUT,
                           "roughness: cut-off lambda_c = %g m spans fewer than %d sampling "
                           "intervals (dx = %g m): the profile parameters cannot be computed; "
                           "accepted: cutoff >= %d dx = %g m",
                           used, MC_ROUGHNESS_MIN_SAMPLES, dx, MC_ROUGHNESS_MIN_SAMPLES,
                           MC_ROUGHNESS_MIN_SAMPLES * dx);
        out->profile_not_computable = 1;
    }
    out->cutoff_nominal = nominal;
    out->cutoff = used;
    out->cutoff_clipped = clipped;
    out->short_evaluation = out->n_sampling < ISO4288_SAMPLING;

    char msg[256];
    if (out->cutoff_auto && !in_table) {
        snprintf(msg, sizeof msg, "Ra %.3g m lies outside the ISO 4288 table; its nearest "
                 "cut-off %.3g m was taken", out->Ra, nominal);
        append(out->warning, sizeof out->warning, msg);
    }
    if (clipped) {
        if (filter && !px)
            snprintf(msg, sizeof msg, "profile length %.4g m is shorter than 3 cut-offs of "
                     "%.4g m (one sampling length and the discarded ends): cut-off clipped to "
                     "%.4g m", len, nominal, used);
        else
            snprintf(msg, sizeof msg, "profile length %.4g m is shorter than the cut-off "
                     "%.4g m: cut-off clipped to %.4g m", len, nominal, used);
        append(out->warning, sizeof out->warning, msg);
    }
    if (out->profile_not_computable) {
        snprintf(msg, sizeof msg, "profile parameters (Ra, Rq, Rz, ...) not computable: the "
                 "cut-off %.4g m spans fewer than %d sampling intervals (dx = %.4g m); give "
                 "[roughness] cutoff >= %.4g m to have them",
                 used, MC_ROUGHNESS_MIN_SAMPLES, dx, MC_ROUGHNESS_MIN_SAMPLES * dx);
        append(out->warning, sizeof out->warning, msg);
    } else if (out->short_evaluation) {
        snprintf(msg, sizeof msg, "evaluation length %.4g m holds %d sampling length%s of "
                 "%.4g m, not the 5 of ISO 4288", out->evaluation_length, out->n_sampling,
                 out->n_sampling == 1 ? "" : "s", used);
        append(out->warning, sizeof out->warning, msg);
    }
    return mc_rough_areal(z, valid, nx, ny, dx, dy, px, opt->periodic_y != 0, out, err);
}

/* The parameter table: the one place that names, documents and orders the parameters reported
 * (summary.json roughness{...}, mc_roughness_entries). To add one: its field in
 * mc_roughness_params, its computation, a row here and MC_ROUGHNESS_NENTRIES (roughness.h).
 * profile: 1 for the profile family (left out when profile_not_computable). */
static const struct {
    const char *name, *unit;
    size_t off;
    int profile;
    const char *help;
} params[] = {
#define P(f, u, prof, h) {#f, u, offsetof(mc_roughness_params, f), prof, h}
    P(Ra, "m", 1, "arithmetical mean height of the profile (ISO 4287)"),
    P(Rq, "m", 1, "root mean square height of the profile (ISO 4287)"),
    P(Rz, "m", 1, "maximum height Rp + Rv, mean over the sampling lengths (ISO 4287)"),
    P(Rp, "m", 1, "highest peak, mean over the sampling lengths (ISO 4287)"),
    P(Rv, "m", 1, "deepest valley, mean over the sampling lengths (ISO 4287)"),
    P(Rt, "m", 1, "total height over the evaluation length (ISO 4287)"),
    P(Rsk, "1", 1, "skewness of the profile (ISO 4287)"),
    P(Rku, "1", 1, "kurtosis of the profile (ISO 4287)"),
    P(Rk, "m", 1, "core roughness depth (ISO 13565-2)"),
    P(Rpk, "m", 1, "reduced peak height (ISO 13565-2)"),
    P(Rvk, "m", 1, "reduced valley depth (ISO 13565-2)"),
    P(Mr1, "%", 1, "material ratio at the top of the core (ISO 13565-2)"),
    P(Mr2, "%", 1, "material ratio at the bottom of the core (ISO 13565-2)"),
    P(Sa, "m", 0, "arithmetical mean height of the map (ISO 25178-2)"),
    P(Sq, "m", 0, "root mean square height of the map (ISO 25178-2)"),
    P(Sz, "m", 0, "maximum height Sp + Sv (ISO 25178-2)"),
    P(Sp, "m", 0, "highest peak (ISO 25178-2)"),
    P(Sv, "m", 0, "deepest valley (ISO 25178-2)"),
    P(Ssk, "1", 0, "skewness of the map (ISO 25178-2)"),
    P(Sku, "1", 0, "kurtosis of the map (ISO 25178-2)"),
    P(Sdq, "1", 0, "root mean square gradient (ISO 25178-2)"),
    P(Sdr, "%", 0, "developed interfacial area ratio (ISO 25178-2)"),
    P(Sk, "m", 0, "core height of the areal material ratio (ISO 25178-2)"),
    P(Spk, "m", 0, "reduced peak height (ISO 25178-2)"),
    P(Svk, "m", 0, "reduced dale height (ISO 25178-2)"),
    P(Smr1, "%", 0, "material ratio at the top of the core (ISO 25178-2)"),
    P(Smr2, "%", 0, "material ratio at the bottom of the core (ISO 25178-2)"),
#undef P
    {"lambda_c", "m", offsetof(mc_roughness_params, cutoff), 0,
     "cut-off wavelength used (ISO 16610-21, chosen by ISO 4288 unless given)"},
};
_Static_assert(sizeof params / sizeof params[0] == MC_ROUGHNESS_NENTRIES,
               "MC_ROUGHNESS_NENTRIES counts the rows of the parameter table");

int mc_roughness_entry_count(void) { return MC_ROUGHNESS_NENTRIES; }

const char *mc_roughness_entry_name(int i)
{
    return i >= 0 && i < MC_ROUGHNESS_NENTRIES ? params[i].name : NULL;
}

const char *mc_roughness_entry_help(int i)
{
    return i >= 0 && i < MC_ROUGHNESS_NENTRIES ? params[i].help : NULL;
}

int mc_roughness_entries(const mc_roughness_params *p, mc_roughness_entry out[])
{
    int n = 0; /* without the profile family (R..., Mr1, Mr2) when it has no meaning */
    for (int k = 0; k < MC_ROUGHNESS_NENTRIES; k++) {
        if (params[k].profile && p->profile_not_computable)
            continue;
        double v;
        memcpy(&v, (const char *)p + params[k].off, sizeof v);
        out[n++] = (mc_roughness_entry){params[k].name, params[k].unit, v};
    }
    return n;
}
