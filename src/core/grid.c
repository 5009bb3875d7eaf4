/* grid.c - mesh validation (see grid.h). */
#include "core/grid.h"

#include <math.h>

int mc_grid_check(const mc_grid *g, mc_error *err)
{
    if (g->nx < 1 || g->nx > MC_GRID_MAX_N || g->ny < 1 || g->ny > MC_GRID_MAX_N)
        return mc_fail(err, MC_ERR_INPUT, "grid %d x %d: each of nx, ny must be in 1..%d", g->nx,
                       g->ny, MC_GRID_MAX_N);
    if (!(isfinite(g->dx) && g->dx > 0 && isfinite(g->dy) && g->dy > 0))
        return mc_fail(err, MC_ERR_INPUT, "grid spacing dx = %g m, dy = %g m: must be finite and > 0",
                       g->dx, g->dy);
    return MC_OK;
}
