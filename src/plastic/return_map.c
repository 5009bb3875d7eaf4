/* return_map.c - J2 radial return at one material point (see return_map.h). */
#include "plastic/return_map.h"

#include <float.h>
#include <math.h>

#include "kernels/invariants.h"
#include "kernels/kernel.h"

/* Stopping tolerance of the scalar solve, in units of eps: r is a sum of three terms of size
 * q_tr, each rounded, and pow() adds an ulp, so a few eps q_tr is the attainable residual. */
#define RM_TOL (4.0 * DBL_EPSILON)

static int all_finite(const double s[6])
{
    for (int i = 0; i < 6; i++)
        if (!isfinite(s[i]))
            return 0;
    return 1;
}

/* r(dp) = q_tr - 3 G dp - sigma_y(p_n + dp). */
static double residual(double q_tr, double G, double p_n, double dp, const mc_hardening *h)
{
    return q_tr - 3.0 * G * dp - mc_hardening_sigma_y(h, p_n + dp);
}

/* Safeguarded Newton on the strictly decreasing r over [lo, hi] with r(lo) > 0 >= r(hi):
 * Newton from dp = 0; a step that would leave the bracket, or that does not at least halve
 * compared with the step before the last, is replaced by bisection (so a piecewise linear table
 * with kinks cannot make it cycle). Each evaluation shrinks the bracket. */
static int solve_dp(double q_tr, double G, double p_n, const mc_hardening *h, double f_tr,
                    double *dp_out, mc_error *err)
{
    double lo = 0.0, hi = f_tr / (3.0 * G), rhi = residual(q_tr, G, p_n, hi, h);
    if (isfinite(rhi) && rhi >= 0.0) { /* r(hi) = 0: flat hardening over the whole step */
        *dp_out = hi;
        return MC_OK;
    }
    double x = 0.0, rx = f_tr, step_old = 2.0 * hi, step = step_old; /* first steps free */
    for (int it = 0; it < MC_RETURN_MAP_MAX_ITER; it++) {
        double slope = -(3.0 * G + mc_hardening_slope(h, p_n + x)); /* r'(x) < 0 */
        double xn = x - rx / slope;
        double step_older = step_old;
        step_old = step;
        if (!(xn > lo && xn < hi) || fabs(2.0 * (xn - x)) > fabs(step_older))
            xn = 0.5 * (lo + hi); /* bisection */
        step = xn - x;
        double rn = residual(q_tr, G, p_n, xn, h);
        if (!isfinite(rn))
            break;
        if (rn > 0.0)
            lo = xn;
        else
            hi = xn;
        x = xn;
        rx = rn;
        if (fabs(rn) <= RM_TOL * q_tr || fabs(step) <= RM_TOL * xn || hi - lo <= RM_TOL * hi) {
            *dp_out = x;
            return MC_OK;
        }
    }
    return mc_fail(err, MC_ERR_NUMERIC,
                   "radial return: consistency solve did not converge in %d iterations "
                   "(q_trial = %g Pa, p_n = %g, dp in [%g, %g], r = %g Pa)",
                   MC_RETURN_MAP_MAX_ITER, q_tr, p_n, lo, hi, rx);
}

int mc_return_map(const double sig_trial[6], double p_n, const mc_hardening *h, double G,
                  double sig_out[6], double deps_p[6], double *dp, mc_error *err)
{
    if (!sig_trial || !h || !sig_out || !deps_p || !dp)
        return mc_fail(err, MC_ERR_INPUT, "radial return: NULL argument");
    if (!all_finite(sig_trial) || !isfinite(p_n) || !isfinite(G))
        return mc_fail(err, MC_ERR_NUMERIC,
                       "radial return: non-finite input (trial stress, p_n = %g or G = %g)", p_n,
                       G);
    if (!(G > 0))
        return mc_fail(err, MC_ERR_INPUT, "radial return: shear modulus G = %g Pa must be > 0",
                       G);
    if (!(p_n >= 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "radial return: accumulated plastic strain p_n = %g must be >= 0", p_n);
    double st[6];
    for (int i = 0; i < 6; i++)
        st[i] = sig_trial[i];
    double q_tr = mc_von_mises(st);
    double sy = mc_hardening_sigma_y(h, p_n), f_tr = q_tr - sy;
    if (!isfinite(sy))
        return mc_fail(err, MC_ERR_INPUT,
                       "radial return: hardening law gives sigma_y(%g) = %g (not a valid law)", p_n,
                       sy);
    if (!(f_tr > 0.0)) { /* elastic (or on the yield surface): Kuhn-Tucker gives dp = 0 */
        for (int i = 0; i < 6; i++) {
            sig_out[i] = st[i];
            deps_p[i] = 0.0;
        }
        *dp = 0.0;
        return MC_OK;
    }
    double d = 0.0;
    if (h->kind == MC_HARDENING_PERFECT)
        d = f_tr / (3.0 * G);
    else if (h->kind == MC_HARDENING_LINEAR)
        d = f_tr / (3.0 * G + h->plastic_modulus);
    else if (solve_dp(q_tr, G, p_n, h, f_tr, &d, err))
        return MC_ERR_NUMERIC;
    /* Flow direction n = 3/2 s_tr / q_tr; sigma = sigma_tr - 2 G dp n. */
    double mean = (st[MC_SXX] + st[MC_SYY] + st[MC_SZZ]) / 3.0;
    double c = 1.5 * d / q_tr;
    for (int i = 0; i < 6; i++) {
        double s = i < 3 ? st[i] - mean : st[i];
        deps_p[i] = c * s;
        sig_out[i] = st[i] - 2.0 * G * deps_p[i];
    }
    *dp = d;
    return MC_OK;
}

int mc_j2_strain_step(const double sig_n[6], double p_n, const double deps[6], double E,
                      double nu, const mc_hardening *h, double sig_out[6], double deps_p[6],
                      double *dp, mc_error *err)
{
    if (!sig_n || !deps)
        return mc_fail(err, MC_ERR_INPUT, "J2 strain step: NULL argument");
    if (!isfinite(E) || !(E > 0))
        return mc_fail(err, MC_ERR_INPUT,
                       "J2 strain step: Young's modulus E = %g Pa must be finite and > 0", E);
    if (!isfinite(nu) || !(nu > -1.0) || !(nu < 0.5))
        return mc_fail(err, MC_ERR_INPUT,
                       "J2 strain step: Poisson's ratio nu = %g must be finite with -1 < nu < 0.5",
                       nu);
    if (!all_finite(deps))
        return mc_fail(err, MC_ERR_NUMERIC, "J2 strain step: non-finite strain increment");
    double G = E / (2.0 * (1.0 + nu));
    double lambda = 2.0 * G * nu / (1.0 - 2.0 * nu);
    double tr = deps[MC_SXX] + deps[MC_SYY] + deps[MC_SZZ];
    double trial[6];
    for (int i = 0; i < 6; i++)
        trial[i] = sig_n[i] + 2.0 * G * deps[i] + (i < 3 ? lambda * tr : 0.0);
    return mc_return_map(trial, p_n, h, G, sig_out, deps_p, dp, err);
}
