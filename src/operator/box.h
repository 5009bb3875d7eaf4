/* box.h - the bounding box of a set of grid cells, widened by a margin: the box of the contact's
 * restricted solve (contact/contact_box.c), of the preconditioner (precond.c) and the windows of
 * a compact load in the stress stage (pipeline/stage_stress.c).
 */
#ifndef MC_BOX_H
#define MC_BOX_H

#include "core/grid.h"

typedef struct {
    int i0, j0; /* first cell */
    int nx, ny; /* cells i0 .. i0 + nx - 1 by j0 .. j0 + ny - 1; 0 x 0: empty */
} mc_box;

/* The bounding box of the cells of grid g (row-major, x fastest) with mask[k] != 0, or, when mask
 * is NULL, with f[k] != 0. Returns 1, or 0 with an empty box if there is no such cell. */
int mc_box_bound(const mc_grid *g, const unsigned char *mask, const double *f, mc_box *b);

/* The same over the run's ranks (core/dist.h): mask holds rows r0 .. r0 + nr - 1 of g alone
 * (nr * nx values, row r0 + r at r * nx), the ranks' slabs together the whole grid; every rank
 * gets the bounding box of the whole set (the rows' bounds reduced, no mask gathered). Without a
 * communicator r0 = 0, nr = ny: mc_box_bound. Collective. */
int mc_box_bound_rows(const mc_grid *g, const unsigned char *mask, int r0, int nr, mc_box *b);

/* Widen b by mx cells on each side along x and my along y, clipped to the grid. A periodic axis
 * always takes the whole axis: a box on it must keep the period. */
void mc_box_widen(const mc_grid *g, int mx, int my, mc_box *b);

/* The margin of the solvers' boxes along an axis where the box is width cells wide: an eighth of
 * the width, at least min cells. */
static inline int mc_box_margin(int width, int min) { return width / 8 > min ? width / 8 : min; }

/* The smallest box holding a and b (both non-empty). */
mc_box mc_box_union(const mc_box *a, const mc_box *b);

static inline long mc_box_cells(const mc_box *b) { return (long)b->nx * (long)b->ny; }

#endif
