/* roughness_internal.h - shared between the roughness_*.c files; not part of the API. */
#ifndef MC_ROUGHNESS_INTERNAL_H
#define MC_ROUGHNESS_INTERNAL_H

#include "surface/roughness.h"

/* Profile parameters of the rows at the (already clipped) cut-off lc: fills Ra..Mr2,
 * evaluation_length, n_sampling, rows and filtered of out (see mc_roughness_compute). */
int mc_rough_profiles(const double *z, const unsigned char *valid, int nx, int ny, double dx,
                      double lc, int periodic, int filter, mc_roughness_params *out,
                      mc_error *err);

/* Areal parameters Sa..Smr2 and points of out (see mc_roughness_compute). */
int mc_rough_areal(const double *z, const unsigned char *valid, int nx, int ny, double dx,
                   double dy, int periodic_x, int periodic_y, mc_roughness_params *out,
                   mc_error *err);

#endif
