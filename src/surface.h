/* surface.h - topography: analytic shapes, synthetic roughness, height maps.
 *
 * The initial gap (topography) at zero approach is h = shape - heights, where the shape is the
 * combined gap of the two smooth bodies with its apex (h = 0) at the grid centre and heights are
 * the composite roughness, positive towards the counter body. */
#ifndef MC_SURFACE_H
#define MC_SURFACE_H

#include <stdint.h>

#include "error.h"
#include "grid.h"
#include "scene.h"

/* ---- reproducible random numbers: xoshiro256** seeded by splitmix64 --------------------- */
typedef struct {
    uint64_t s[4];
} mc_rng;
void mc_rng_seed(mc_rng *r, uint64_t seed);
uint64_t mc_rng_next(mc_rng *r);
double mc_rng_uniform(mc_rng *r); /* [0, 1) with 53 random bits */
double mc_rng_normal(mc_rng *r);  /* standard normal (Box-Muller, both values used) */

/* ---- pieces ------------------------------------------------------------------------------ */

/* Smooth-body gap at cell centres (ny*nx): flat 0; sphere r^2/2R; cylinder x^2/2R (axis along
 * y); ellipsoid x^2/2Rx + y^2/2Ry. */
void mc_surface_shape(const mc_grid *g, const mc_scene *s, double *h);

/* Roughness heights (ny*nx) for the scene's [roughness] (zeros for none). Synthetic surfaces
 * have zero mean and exactly the requested rq (or rms slope); the same seed gives the same
 * surface on every run. Files are read via heightmap.h. */
int mc_surface_roughness(const mc_grid *g, const mc_scene *s, double *heights, mc_error *err);

/* Whole topography: shape - roughness (ny*nx). */
int mc_surface_topography(const mc_grid *g, const mc_scene *s, double *topo, mc_error *err);

/* Roughness statistics of a height field (for tests and reports). */
typedef struct {
    double mean, rq, ra, rms_slope_x, rms_slope_y, skewness, kurtosis;
} mc_surface_stats;
void mc_surface_statistics(const mc_grid *g, const double *heights, mc_surface_stats *st);

#endif
