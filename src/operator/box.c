/* box.c - bounding boxes of cell sets (see box.h). */
#include "operator/box.h"

#include "core/dist.h"

int mc_box_bound(const mc_grid *g, const unsigned char *mask, const double *f, mc_box *b)
{
    int ilo = g->nx, ihi = -1, jlo = g->ny, jhi = -1;
    for (int j = 0; j < g->ny; j++) {
        const size_t row = (size_t)j * (size_t)g->nx;
        int lo = -1, hi = -1;
        for (int i = 0; i < g->nx; i++)
            if (mask ? mask[row + i] != 0 : f[row + i] != 0.0) {
                lo = lo < 0 ? i : lo;
                hi = i;
            }
        if (lo < 0)
            continue;
        ilo = lo < ilo ? lo : ilo;
        ihi = hi > ihi ? hi : ihi;
        jlo = j < jlo ? j : jlo;
        jhi = j;
    }
    if (ihi < 0) {
        *b = (mc_box){0, 0, 0, 0};
        return 0;
    }
    *b = (mc_box){ilo, jlo, ihi - ilo + 1, jhi - jlo + 1};
    return 1;
}

/* [*start, *start + *len) widened by m within 0 .. n - 1, or the whole axis if periodic. */
static void widen_axis(int n, int periodic, int m, int *start, int *len)
{
    if (periodic) {
        *start = 0;
        *len = n;
        return;
    }
    const int lo = *start - m < 0 ? 0 : *start - m;
    const int hi = *start + *len - 1 + m > n - 1 ? n - 1 : *start + *len - 1 + m;
    *start = lo;
    *len = hi - lo + 1;
}

void mc_box_widen(const mc_grid *g, int mx, int my, mc_box *b)
{
    widen_axis(g->nx, g->periodic_x, mx, &b->i0, &b->nx);
    widen_axis(g->ny, g->periodic_y, my, &b->j0, &b->ny);
}

mc_box mc_box_union(const mc_box *a, const mc_box *b)
{
    const int i0 = a->i0 < b->i0 ? a->i0 : b->i0, j0 = a->j0 < b->j0 ? a->j0 : b->j0;
    const int i1 = a->i0 + a->nx > b->i0 + b->nx ? a->i0 + a->nx : b->i0 + b->nx;
    const int j1 = a->j0 + a->ny > b->j0 + b->ny ? a->j0 + a->ny : b->j0 + b->ny;
    return (mc_box){i0, j0, i1 - i0, j1 - j0};
}

int mc_box_bound_rows(const mc_grid *g, const unsigned char *mask, int r0, int nr, mc_box *b)
{
    mc_grid gl = *g;
    gl.ny = nr;
    mc_box mine;
    /* each rank's bound, shifted to grid rows; an empty slab bounds nothing (the -1 sentinels) */
    double v[4] = {-1, -1, -1, -1}; /* -i0, -j0, i1, j1 (maxima over the ranks) */
    if (nr > 0 && mc_box_bound(&gl, mask, NULL, &mine)) {
        v[0] = -(double)mine.i0;
        v[1] = -(double)(mine.j0 + r0);
        v[2] = (double)(mine.i0 + mine.nx);
        v[3] = (double)(mine.j0 + r0 + mine.ny);
    } else {
        v[0] = -(double)g->nx;
        v[1] = -(double)g->ny;
    }
    mc_dist_max(v, 4);
    if (v[2] < 0) {
        *b = (mc_box){0, 0, 0, 0};
        return 0;
    }
    *b = (mc_box){(int)-v[0], (int)-v[1], (int)v[2] + (int)v[0], (int)v[3] + (int)v[1]};
    return 1;
}
