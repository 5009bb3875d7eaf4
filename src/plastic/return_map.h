/* return_map.h - J2 (von Mises) plasticity with isotropic hardening at one material point: the
 * radial return of a trial stress (backward Euler, Simo & Hughes 1998 Box 3.2;
 * theory.md §7.1, §7.3) and a strain-driven step built on it. Pure numerics, no
 * allocation, no scene knowledge; thread-safe (no state).
 *
 * Tensors are double[6] in the order xx, yy, zz, xy, yz, xz (MC_SXX... of kernels/kernel.h).
 * Stresses are tension positive, Pa. Strains are small, dimensionless, with TENSOR shear
 * components (eps_xy = gamma_xy / 2), so sigma_xy = 2 G eps_xy elastically.
 *
 * Equations (f = q - sigma_y(p), q = sqrt(3/2 s:s), s the deviator of sigma):
 *   trial q_tr = q(sig_trial); elastic if q_tr <= sigma_y(p_n);
 *   otherwise dp > 0 solves r(dp) = q_tr - 3 G dp - sigma_y(p_n + dp) = 0, and
 *   n = 3/2 s_tr / q_tr,  deps_p = dp n,  sigma = sig_trial - 2 G deps_p,
 *   i.e. s = (1 - 3 G dp / q_tr) s_tr with the hydrostatic part unchanged, and q(sigma) equals
 *   sigma_y(p_n + dp). Plastic flow is incompressible (tr deps_p = 0) and
 *   sqrt(2/3 deps_p:deps_p) = dp.
 *
 * In the semi-analytical contact loop the trial stress is sigma_e,n+1 + sigma_r(eps_p,n +
 * deps_p) + 2 G deps_p (theory.md §7.5); that fixed point belongs to the caller.
 */
#ifndef MC_RETURN_MAP_H
#define MC_RETURN_MAP_H

#include "core/error.h"
#include "plastic/hardening.h"

/* Iterations allowed in the scalar consistency solve. Measured: at most 10 for the Swift law
 * of AISI 52100 (mean 4), 16 on a table with 40 alternating steep/flat segments; bisection
 * alone would reach the 4-eps stopping width of the initial bracket in about 50. */
#define MC_RETURN_MAP_MAX_ITER 60

/* Radial return from the trial stress sig_trial (Pa) at accumulated plastic strain p_n >= 0,
 * for the hardening law h (valid, e.g. built by a constructor of hardening.h) and shear modulus
 * G > 0 (Pa).
 * Outputs: sig_out (Pa; may alias sig_trial), the plastic strain increment deps_p (tensor
 * components) and *dp >= 0, the increment of p. An elastic step gives sig_out = sig_trial,
 * deps_p = 0, *dp = 0.
 * The scalar equation r(dp) = 0 is solved in closed form for PERFECT (dp = f_tr / 3G) and
 * LINEAR (dp = f_tr / (3G + H)) laws, f_tr = q_tr - sigma_y(p_n); for SWIFT and TABLE by Newton
 * from dp = 0, kept inside the bracket [0, f_tr / 3G] (r is continuous and strictly decreasing
 * there, r(0) > 0 >= r(f_tr / 3G) since sigma_y never decreases) with a bisection fallback, so it
 * converges for any valid law. Stops when |r| <= 4 eps q_tr, or the step or the bracket is below
 * 4 eps dp.
 * Returns MC_OK; MC_ERR_INPUT for NULL pointers, G <= 0, p_n < 0 or a law whose sigma_y(p_n)
 * is not finite (only a hand-filled, unvalidated law can do that); MC_ERR_NUMERIC for a
 * non-finite sig_trial, p_n or G, or when the iteration does not converge in
 * MC_RETURN_MAP_MAX_ITER iterations (outputs are then unspecified). */
int mc_return_map(const double sig_trial[6], double p_n, const mc_hardening *h, double G,
                  double sig_out[6], double deps_p[6], double *dp, mc_error *err);

/* One strain-driven step: from the converged state (sig_n, Pa; p_n) and a total strain
 * increment deps (tensor shear components), the elastic predictor
 *   sig_trial = sig_n + lambda tr(deps) I + 2 G deps,   G = E / (2 (1 + nu)),
 *   lambda = 2 G nu / (1 - 2 nu),
 * followed by mc_return_map. E > 0 (Pa) and -1 < nu < 1/2 (finite) or MC_ERR_INPUT. sig_out may
 * alias sig_n. Return codes as mc_return_map. */
int mc_j2_strain_step(const double sig_n[6], double p_n, const double deps[6], double E,
                      double nu, const mc_hardening *h, double sig_out[6], double deps_p[6],
                      double *dp, mc_error *err);

#endif
