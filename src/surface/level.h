/* level.h - preparing a measured height map: form removal, missing points, cropping, resampling.
 *
 * Height maps are ny x nx arrays of heights in m, row-major with x fastest (z[j*nx + i]). An
 * optional validity mask valid[j*nx + i] (1 = measured, 0 = missing) travels with them; NULL
 * means every point is valid. Values at invalid points are never read (they may be NaN).
 * Pure numerics: no file, no scene. */
#ifndef MC_LEVEL_H
#define MC_LEVEL_H

#include "core/error.h"

/* ---- form removal ------------------------------------------------------------------------ */

typedef enum {
    MC_DETREND_NONE = 0,     /* nothing removed */
    MC_DETREND_MEAN = 1,     /* c0 */
    MC_DETREND_PLANE = 2,    /* c0 + c1 x + c2 y */
    MC_DETREND_QUADRATIC = 3 /* c0 + c1 x + c2 y + c3 x^2 + c4 x y + c5 y^2 */
} mc_detrend_kind;

/* Subtract the least-squares polynomial of the given kind, fitted over the valid points, from
 * every valid point of z (invalid points are left as they are).
 *
 * x, y are the cell centres of grid.h, x_i = (i + 1/2 - nx/2) dx and y_j = (j + 1/2 - ny/2) dy,
 * so c0 is the fitted height at the centre of the map. coef[0..5] (may be NULL) receives c0 (m),
 * c1, c2 (slopes, m/m), c3, c4, c5 (1/m) as in the enum above; terms beyond the kind are 0.
 * The fit is solved in scaled coordinates (x, y mapped to [-1, 1]) by a pivoted Cholesky
 * factorisation of the normal equations, followed by one refinement pass on the residual, so an
 * exact polynomial of the kind is removed to round-off. Terms the valid points cannot determine
 * (a single row has no y terms, two columns no x^2 term) are dropped, i.e. set to 0.
 * MC_DETREND_NONE reads and changes nothing.
 * Errors: MC_ERR_INPUT (sizes, spacings, kind, no valid point, a non-finite valid height). */
int mc_level_detrend(double *z, const unsigned char *valid, int nx, int ny, double dx, double dy,
                     mc_detrend_kind kind, double coef[6], mc_error *err);

/* Fill the invalid points of z by harmonic in-painting: the filled values solve the discrete
 * Laplace equation (5-point stencil in index space) at the invalid points, with the valid
 * heights as Dirichlet data and zero-flux (mirror) conditions at the edges of the map. A hole
 * is thus bridged by the smoothest surface that meets its rim. In holes enclosed by valid
 * points linear fields are restored exactly and, by the discrete maximum principle, a smooth
 * field f within max|Lap_h f| (R + 1)^2 / 4 over a hole of radius R cells (Lap_h: the 5-point
 * Laplacian in index units); a hole touching the map's edge meets the zero-flux condition
 * there instead.
 * Solved by conjugate gradients preconditioned with an aggregation multigrid V-cycle (the
 * matrix is symmetric positive definite because every connected region of missing points
 * borders a valid one), started from an onion-peel guess (each ring the mean of its known
 * neighbours), to a relative residual of 1e-12: about 90 iterations for a hole of 500 000
 * points (radius 400 cells), at most 10 m + 100 for m missing points.
 * *filled (may be NULL) receives the number of filled points. valid is not changed: after
 * success every point of z holds a finite height (on failure the invalid points may hold the
 * start guess; they were invalid anyway).
 * Errors: MC_ERR_INPUT (sizes; every point invalid; a non-finite valid height), MC_ERR_NOMEM,
 * MC_ERR_NUMERIC (the iteration cap was reached; not expected). */
int mc_level_fill_missing(double *z, const unsigned char *valid, int nx, int ny, int *filled,
                          mc_error *err);

/* Mark the non-finite heights of z invalid: valid[k] = valid[k] && isfinite(z[k]) (valid must
 * be allocated, n points). Returns the number of invalid points afterwards. */
int mc_level_mask_nonfinite(const double *z, unsigned char *valid, int n);

/* ---- lateral grids ----------------------------------------------------------------------- */

/* A sampled map with its lateral position: sample (i, j) sits at (x0 + i dx, y0 + j dy), m.
 * Each sample stands for the cell dx x dy around it, so the map covers the extent
 * [x0 - dx/2, x0 + (nx - 1/2) dx] x [y0 - dy/2, y0 + (ny - 1/2) dy]. A grid.h mesh centred on
 * the origin has x0 = (1 - nx) dx / 2, y0 = (1 - ny) dy / 2. */
typedef struct {
    int nx, ny;    /* samples along x and y, >= 1 */
    double dx, dy; /* spacings, m, > 0 */
    double x0, y0; /* position of sample (0, 0), m */
} mc_level_grid;

/* MC_OK if sizes are >= 1 and spacings and offsets finite (spacings > 0); else MC_ERR_INPUT
 * naming `what`. */
int mc_level_grid_check(const mc_level_grid *g, const char *what, mc_error *err);

/* The samples inside the region [rx, rx + w) x [ry, ry + h) (m) of grid g: sub receives the
 * cropped grid (its offsets are the positions of its first sample), *i0, *j0 the index of its
 * first sample in g. A sample on the far edge of the region is excluded, one on the near edge
 * included (to 1e-6 of a spacing), so a region of k cells aligned with cell edges or samples
 * holds k samples per axis. Errors (MC_ERR_INPUT, naming the region and the grid extent): a
 * region with no positive, finite width or height, one reaching beyond the grid extent (see
 * mc_level_grid; the far edge may also be the sample after the last, x0 + n dx, so that a
 * region aligned with the samples selects the whole map it cut before), one that holds no
 * sample. */
int mc_level_crop(const mc_level_grid *g, double rx, double ry, double w, double h,
                  mc_level_grid *sub, int *i0, int *j0, mc_error *err);

/* Copy the sub-block (i0, j0, sub_nx x sub_ny) of a map of row length nx into dst; dst_valid
 * (may be NULL) receives the same block of src_valid, or ones when src_valid is NULL. No checks:
 * use the indices and sizes mc_level_crop returned. */
void mc_level_copy_block(const double *src, const unsigned char *src_valid, int nx, int i0,
                         int j0, int sub_nx, int sub_ny, double *dst, unsigned char *dst_valid);

/* Bilinear interpolation of src (on grid gs, every point valid: fill missing points first) onto
 * the samples of grid gd. Every destination sample must lie within the source extent (the cells
 * of gs, to 1e-6 of a spacing); in the half cell beyond the outermost source samples the edge
 * interval is extended linearly, so a linear field is reproduced exactly everywhere. An axis of
 * one source sample is constant along that axis. Errors: MC_ERR_INPUT (a bad grid; a destination
 * reaching beyond the source, naming both extents). */
int mc_level_resample_linear(const double *src, const mc_level_grid *gs, double *dst,
                             const mc_level_grid *gd, mc_error *err);

#endif
