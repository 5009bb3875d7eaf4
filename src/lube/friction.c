/* friction.c - solid/lubricant split, pocket height and mixed friction (friction.h). */
#include "lube/friction.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The psi table: the one place that names and documents each solid contact ratio; the key
 * table ([lubrication] psi), the docs and the messages take them from here. To add one: a value
 * in mc_psi_kind (before MC_PSI_NKINDS), a row here, its case in mc_lube_split_psi. */
static const struct {
    const char *name, *help;
} psis[] = {
    [MC_PSI_LOAD] = {"load", "F_solid / F_N, the solid contacts' share of the load"},
    [MC_PSI_AREA] = {"area", "A_C / A_nom, the solid contacts' share of the nominal area"},
};
_Static_assert(sizeof psis / sizeof psis[0] == MC_PSI_NKINDS, "one row per mc_psi_kind");

int mc_psi_count(void) { return MC_PSI_NKINDS; }

const char *mc_psi_name(mc_psi_kind k)
{
    return (int)k >= 0 && k < MC_PSI_NKINDS ? psis[k].name : NULL;
}

const char *mc_psi_help(mc_psi_kind k)
{
    return (int)k >= 0 && k < MC_PSI_NKINDS ? psis[k].help : NULL;
}

int mc_psi_from_name(const char *name, mc_psi_kind *out, mc_error *err)
{
    char list[128];
    size_t o = 0;
    for (int k = 0; k < MC_PSI_NKINDS; k++) {
        if (name && strcmp(name, psis[k].name) == 0) {
            *out = (mc_psi_kind)k;
            return MC_OK;
        }
        int n = snprintf(list + o, sizeof list - o, "%s%s", k ? " | " : "", psis[k].name);
        o = n > 0 && o + (size_t)n < sizeof list ? o + (size_t)n : o;
    }
    return mc_fail(err, MC_ERR_INPUT, "solid contact ratio psi '%s' is unknown; accepted: %s",
                   name ? name : "(none)", list);
}

int mc_pocket_height(double volume, double a_nom, double a_contact, double *h, mc_error *err)
{
    if (!(a_nom > 0 && isfinite(a_nom)) || !(a_contact >= 0 && a_contact <= a_nom))
        return mc_fail(err, MC_ERR_INPUT,
                       "pocket height: nominal area %g m^2 must be finite and > 0, contact area "
                       "%g m^2 in [0, nominal area]",
                       a_nom, a_contact);
    if (!(volume >= 0 && isfinite(volume)))
        return mc_fail(err, MC_ERR_INPUT, "pocket height: volume %g m^3 must be finite and >= 0",
                       volume);
    double free_area = a_nom - a_contact;
    *h = free_area > 0 ? volume / free_area : 0.0;
    return MC_OK;
}

int mc_friction_mu(double psi, double mu_solid, double mu_fluid, double *mu, mc_error *err)
{
    if (!(psi >= 0 && psi <= 1))
        return mc_fail(err, MC_ERR_INPUT, "friction: psi %g must be in [0, 1]", psi);
    if (!(mu_solid >= 0 && isfinite(mu_solid)) || !(mu_fluid >= 0 && isfinite(mu_fluid)))
        return mc_fail(err, MC_ERR_INPUT,
                       "friction: mu_solid %g and mu_fluid %g must be finite and >= 0", mu_solid,
                       mu_fluid);
    *mu = psi * mu_solid + (1.0 - psi) * mu_fluid;
    return MC_OK;
}

double mc_lube_split_psi(const mc_lube_split *s, mc_psi_kind k)
{
    return k == MC_PSI_AREA ? s->psi_area : s->psi_load;
}

int mc_lube_split_of(const double *p, const double *gap, size_t n, double dA, double p_lub,
                     double f_n, mc_lube_split *s, mc_error *err)
{
    return mc_lube_split_weighted(p, gap, NULL, n, dA, p_lub, f_n, s, err);
}

int mc_lube_split_weighted(const double *p, const double *gap, const double *w, size_t n,
                           double dA, double p_lub, double f_n, mc_lube_split *s, mc_error *err)
{
    if (n == 0 || !(dA > 0 && isfinite(dA)) || !(p_lub >= 0 && isfinite(p_lub)) ||
        !(f_n > 0 && isfinite(f_n)))
        return mc_fail(err, MC_ERR_INPUT,
                       "lubricant split: need cells > 0 (%zu), cell area > 0 (%g m^2), lubricant "
                       "pressure >= 0 (%g Pa) and load > 0 (%g N), all finite",
                       n, dA, p_lub, f_n);
    double sum_c = 0, sum_cx = 0, sum_g = 0, sum_f = 0;
    size_t nc = 0, nnom = 0, nc_nom = 0;
    for (size_t i = 0; i < n; i++) {
        const double wi = w ? w[i] : 1.0;
        if (!isfinite(p[i]) || !isfinite(gap[i]) || !(wi >= 0 && isfinite(wi)))
            return mc_fail(err, MC_ERR_INPUT,
                           "lubricant split: non-finite pressure, gap or profile at cell %zu", i);
        const double lo = p_lub * wi;
        const int nominal = wi > 0;
        nnom += (size_t)nominal;
        if (p[i] > lo) {
            sum_c += p[i];
            sum_cx += p[i] - lo;
            nc++;
            nc_nom += (size_t)nominal;
        } else
            sum_f += lo;
        if (nominal)
            sum_g += gap[i];
    }
    if (nnom == 0)
        return mc_fail(err, MC_ERR_INPUT, "lubricant split: the profile is zero everywhere");
    memset(s, 0, sizeof *s);
    s->a_nom = dA * (double)nnom;
    s->a_contact = dA * (double)nc;
    s->f_solid = dA * sum_c;
    s->f_solid_excess = dA * sum_cx;
    s->f_fluid = dA * sum_f;
    s->volume = dA * sum_g;
    s->psi_load = s->f_solid / f_n;
    /* solid contact just outside a profile's nominal area (a rough peak beyond the Hertz band)
     * counts as solid contact; the area ratio is of the nominal area's own cells */
    s->psi_area = (double)nc_nom / (double)nnom;
    s->psi_load_excess = s->f_solid_excess / f_n;
    /* a gap within round-off of zero may sum slightly negative in a nearly closed contact */
    double v = s->volume > 0 ? s->volume : 0.0;
    return mc_pocket_height(v, s->a_nom, dA * (double)nc_nom, &s->pocket_height, err);
}
