/* traction.h - the friction traction of solid contact (docs/theory.md §9.1, §19.7):
 *     q_x = f (p - p_l)   where p > p_l,   0 elsewhere,
 * with p_l the lubricant pressure of the cell: p_lub on a patch, p_lub w (the whole contact's
 * profile of lube/volume.h, mean 1 over the nominal area, 0 outside it) on the whole contact.
 * The fluid carries p_l without shear; only the excess is solid contact. Pure numerics. */
#ifndef MC_STRESS_TRACTION_H
#define MC_STRESS_TRACTION_H

#include <stddef.h>

/* The lubricant pressure of cell i: p_lub shape[i], or p_lub when shape is NULL. */
static inline double mc_traction_lubricant(double p_lub, const double *shape, size_t i)
{
    return shape ? p_lub * shape[i] : p_lub;
}

/* qx[i] = f (p[i] - p_l,i) where p[i] > p_l,i, else 0, for i < n (f signed: the sliding
 * direction). */
void mc_traction_friction(const double *p, double p_lub, const double *shape, double f, size_t n,
                          double *qx);

#endif
