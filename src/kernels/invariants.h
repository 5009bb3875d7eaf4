/* invariants.h - scalar measures of a stress tensor: von Mises, hydrostatic, principal stresses
 * and Tresca (maximum shear). Pure math, no allocation; the volume version is OpenMP-parallel and
 * gives bit-identical results for any thread count (each point is independent).
 *
 * Input tensors are double s[6] in the order of kernel.h: xx, yy, zz, xy, yz, xz (MC_SXX...),
 * tension positive, any stress unit; results are in the same unit.
 */
#ifndef MC_INVARIANTS_H
#define MC_INVARIANTS_H

#include <stddef.h>

#include "core/error.h"

/* Von Mises equivalent stress, >= 0:
 * sqrt( ((sxx-syy)^2 + (syy-szz)^2 + (szz-sxx)^2)/2 + 3 (sxy^2 + syz^2 + sxz^2) ) = sqrt(3 J2). */
double mc_von_mises(const double s[6]);

/* Hydrostatic (mean normal) stress (sxx + syy + szz)/3; negative in compression. */
double mc_hydrostatic(const double s[6]);

/* Principal stresses p[0] >= p[1] >= p[2] of the symmetric tensor. Closed-form trigonometric
 * solution of the deviatoric cubic (Smith 1961, Comm. ACM 4:168) with the angle taken as
 * atan2(sqrt(D), 3 sqrt(3) J3), where the discriminant D = 4 J2^3 - 27 J3^2 = prod (si - sj)^2 is
 * formed as a sum of squares (Parlett 2002, Linear Algebra Appl. 355: D is the determinant of the
 * Gram matrix of I, S, S^2; Habera & Zilian 2021, arXiv:2111.02117). acos() of J3/J2^(3/2) loses
 * half the digits near repeated roots (1e-8 |S|); this form keeps a few eps |S| (tested: <= 64 eps
 * |S|_F against GSL's QR solver) for distinct, repeated and triple (hydrostatic) roots alike.
 * A NaN or infinite component gives NaN in all three. */
void mc_principal_stresses(const double s[6], double p[3]);

/* Tresca maximum shear (s1 - s3)/2 >= 0, formed from the deviator without the cancellation of
 * subtracting two principal stresses (equal to (p[0] - p[2])/2 of mc_principal_stresses up to
 * round-off). */
double mc_tresca(const double s[6]);

/* Invariants of n stress tensors given as six component arrays of n values each (a volume, any
 * layout; e.g. the stress stage's layers*ny*nx arrays): point i is (sxx[i], syy[i], szz[i],
 * sxy[i], syz[i], sxz[i]). Writes vm[i], hydro[i], tresca[i]; any of the three outputs may be NULL
 * to skip it. Each value equals the scalar function's result bit for bit, for any number of
 * OpenMP threads. Returns MC_OK, or MC_ERR_INPUT when n > 0 and a component array is NULL. Outputs
 * must not alias the inputs. Separate pointers (not a table) so that both const and non-const
 * arrays pass without casts. */
int mc_invariants_volume(size_t n, const double *sxx, const double *syy, const double *szz,
                         const double *sxy, const double *syz, const double *sxz, double *vm,
                         double *hydro, double *tresca, mc_error *err);

#endif
