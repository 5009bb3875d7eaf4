/* grid.h - the surface mesh: nx x ny cells of dx x dy, each axis periodic or not.
 *
 * Cell centres: x_i = (i + 1/2 - nx/2) dx, y_j = (j + 1/2 - ny/2) dy (apex of a shape at the
 * grid centre). Fields are row-major with x fastest: f[j*nx + i].
 */
#ifndef MC_GRID_H
#define MC_GRID_H

#include <stddef.h>

#include "core/error.h"

#define MC_GRID_MAX_N 65536 /* per axis; far beyond what fits in memory as a square */

typedef struct {
    int nx, ny;                 /* cells along x (rolling) and y (transverse), >= 1 */
    double dx, dy;              /* cell size along x and y, m, > 0 */
    int periodic_x, periodic_y; /* 1: the axis is periodic with period n*d; 0: free */
} mc_grid;

/* MC_OK if sizes are in range and spacings finite and positive; MC_ERR_INPUT otherwise. */
int mc_grid_check(const mc_grid *g, mc_error *err);

static inline size_t mc_grid_cells(const mc_grid *g) { return (size_t)g->nx * (size_t)g->ny; }
static inline double mc_grid_x(const mc_grid *g, int i) { return (i + 0.5 - 0.5 * g->nx) * g->dx; }
static inline double mc_grid_y(const mc_grid *g, int j) { return (j + 0.5 - 0.5 * g->ny) * g->dy; }
static inline double mc_grid_cell_area(const mc_grid *g) { return g->dx * g->dy; }

#endif
