/* roughness.c - all roughness parameters of a map: cut-off choice and clipping, warnings, the
 * name table (see roughness.h; theory.md §13). */
#include "surface/roughness.h"

#include <math.h>
#include <stdio.h>
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

int mc_roughness_entries(const mc_roughness_params *p, mc_roughness_entry out[])
{
    const mc_roughness_entry e[MC_ROUGHNESS_NENTRIES] = {
        {"Ra", "m", p->Ra},     {"Rq", "m", p->Rq},     {"Rz", "m", p->Rz},
        {"Rp", "m", p->Rp},     {"Rv", "m", p->Rv},     {"Rt", "m", p->Rt},
        {"Rsk", "1", p->Rsk},   {"Rku", "1", p->Rku},   {"Rk", "m", p->Rk},
        {"Rpk", "m", p->Rpk},   {"Rvk", "m", p->Rvk},   {"Mr1", "%", p->Mr1},
        {"Mr2", "%", p->Mr2},   {"Sa", "m", p->Sa},     {"Sq", "m", p->Sq},
        {"Sz", "m", p->Sz},     {"Sp", "m", p->Sp},     {"Sv", "m", p->Sv},
        {"Ssk", "1", p->Ssk},   {"Sku", "1", p->Sku},   {"Sdq", "1", p->Sdq},
        {"Sdr", "%", p->Sdr},   {"Sk", "m", p->Sk},     {"Spk", "m", p->Spk},
        {"Svk", "m", p->Svk},   {"Smr1", "%", p->Smr1}, {"Smr2", "%", p->Smr2},
        {"lambda_c", "m", p->cutoff}};
    if (!p->profile_not_computable) {
        memcpy(out, e, sizeof e);
        return MC_ROUGHNESS_NENTRIES;
    }
    int n = 0; /* the profile family (R..., Mr1, Mr2) has no meaning: not printed */
    for (int k = 0; k < MC_ROUGHNESS_NENTRIES; k++)
        if (e[k].name[0] != 'R' && strncmp(e[k].name, "Mr", 2) != 0)
            out[n++] = e[k];
    return n;
}
