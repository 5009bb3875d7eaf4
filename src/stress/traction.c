/* traction.c - the friction traction of solid contact (traction.h). */
#include "stress/traction.h"

void mc_traction_friction(const double *p, double p_lub, const double *shape, double f, size_t n,
                          double *qx)
{
    for (size_t i = 0; i < n; i++) {
        const double pl = mc_traction_lubricant(p_lub, shape, i);
        qx[i] = p[i] > pl ? f * (p[i] - pl) : 0.0;
    }
}
