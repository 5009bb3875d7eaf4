/* warnings.c - warnings a user can act on (see warnings.h). */
#include "pipeline/warnings.h"

#include <math.h>
#include <string.h>
#include <stdarg.h>
#include <stdio.h>

void mc_results_warn(mc_results *r, const char *code, const char *fmt, ...)
{
    if (r->nwarnings >= MC_WARNINGS_MAX)
        return;
    mc_warning *w = &r->warnings[r->nwarnings++];
    w->code = code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->message, sizeof w->message, fmt, ap);
    va_end(ap);
}

/* Solid contact on a cell: the pressure exceeds the lubricant's (the contact's own test). */
static int in_contact(const mc_results *r, size_t q, double p_lub)
{
    return r->pressure[q] > p_lub;
}

/* Edges of the free axes that solid contact touches: bit 1 x, bit 2 y. */
static int edges_touched(const mc_results *r, int periodic_x, int periodic_y, double p_lub)
{
    const int nx = r->grid.nx, ny = r->grid.ny;
    int hit = 0;
    if (!periodic_x)
        for (int j = 0; j < ny && !(hit & 1); j++)
            if (in_contact(r, (size_t)j * nx, p_lub) || in_contact(r, (size_t)j * nx + nx - 1, p_lub))
                hit |= 1;
    if (!periodic_y)
        for (int i = 0; i < nx && !(hit & 2); i++)
            if (in_contact(r, (size_t)i, p_lub) || in_contact(r, (size_t)(ny - 1) * nx + i, p_lub))
                hit |= 2;
    return hit;
}

/* Radius of a rough macro contact from the extent of its solid contact (the box around every
 * contact cell): the half-width along x for a line contact, else sqrt(a_x a_y) of the
 * half-extents (the radius of a circular contact). */
static double extent_radius(const mc_results *r, int line, double p_lub)
{
    const int nx = r->grid.nx, ny = r->grid.ny;
    int i0 = nx, i1 = -1, j0 = ny, j1 = -1;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            if (in_contact(r, (size_t)j * nx + i, p_lub)) {
                i0 = i < i0 ? i : i0, i1 = i > i1 ? i : i1;
                j0 = j < j0 ? j : j0, j1 = j > j1 ? j : j1;
            }
    if (i1 < 0)
        return 0.0;
    const double ax = 0.5 * (i1 - i0 + 1) * r->grid.dx, ay = 0.5 * (j1 - j0 + 1) * r->grid.dy;
    return line ? ax : sqrt(ax * ay);
}

/* Cell v is a local extremum along the axis of stride st (it has both neighbours): both steps
 * larger than `step`, of opposite signs. */
static int extremum(const double *peq, size_t v, size_t st, double step)
{
    const double a = peq[v] - peq[v - st], b = peq[v + st] - peq[v];
    return a * b < 0 && fabs(a) > step && fabs(b) > step;
}

/* A zigzag along an axis: v and a neighbour along it are both extrema (up-down-up over at least
 * three steps). An isolated spike, e.g. an asperity tip of one cell, is one extremum whose
 * neighbours are not: the material's response to a sharp load, not the operator's mode. */
static int zigzag(const double *peq, size_t v, int i, int n, size_t st, double step)
{
    if (i < 1 || i > n - 2 || !extremum(peq, v, st, step))
        return 0;
    return (i >= 2 && extremum(peq, v - st, st, step)) ||
           (i <= n - 3 && extremum(peq, v + st, st, step));
}

double mc_stage_plastic_checkered_fraction(const mc_grid *g, int nz, const double *peq)
{
    const int nx = g->nx, ny = g->ny;
    const size_t n = (size_t)nz * (size_t)nx * (size_t)ny;
    double peak = 0;
    for (size_t v = 0; v < n; v++)
        peak = fmax(peak, peq[v]);
    if (!(peak > 0))
        return 0.0;
    const double floor_ = MC_CHECKER_SIGNIFICANT * peak, step = MC_CHECKER_STEP * peak;
    long significant = 0, checkered = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                const size_t v = ((size_t)k * ny + j) * nx + i;
                if (!(peq[v] > floor_))
                    continue;
                significant++;
                checkered += zigzag(peq, v, i, nx, 1, step) || zigzag(peq, v, j, ny, nx, step);
            }
    return significant ? (double)checkered / (double)significant : 0.0;
}

void mc_results_warnings(const mc_scene *sc, mc_results *r)
{
    const mc_contact_summary *c = &r->contact;
    const mc_grid *g = &r->grid;
    const int macro = sc->geometry.shape != MC_SHAPE_FLAT;
    const double p_lub = r->lube.enabled ? r->lube.p_lub : fmax(sc->load.lubricant_pressure, 0.0);
    const double estar = mc_scene_estar(sc);
    if (r->pressure && c->solved && macro && c->area > 0) {
        const int hit = edges_touched(r, g->periodic_x, g->periodic_y, p_lub);
        if (hit)
            mc_results_warn(r, "contact_at_edge",
                            "the contact reaches the %s of the grid (%d x %d cells of %.4g x "
                            "%.4g um): the grid truncates it and the pressure is not the "
                            "unbounded body's; enlarge the grid (nx, ny) or lower the load",
                            hit == 3 ? "x and y edges" : hit == 1 ? "x edges" : "y edges", g->nx,
                            g->ny, g->dx * 1e6, g->dy * 1e6);
    }
    if (c->solved && c->contact_ratio > MC_WARN_CONTACT_RATIO)
        mc_results_warn(r, "contact_ratio_high",
                        "%.1f %% of the grid is in solid contact (above %.0f %%): little free "
                        "surface is left; enlarge the grid or lower the load",
                        100.0 * c->contact_ratio, 100.0 * MC_WARN_CONTACT_RATIO);
    if (c->solved && macro && c->area > 0) {
        const int line = sc->geometry.shape == MC_SHAPE_CYLINDER;
        double radius;
        if (sc->roughness.type == MC_ROUGH_NONE)
            radius = line ? c->area / (2.0 * g->ny * g->dy) : sqrt(c->area / M_PI);
        else /* the micro-contacts' area is not the macro contact's: its extent is */
            radius = extent_radius(r, line, p_lub);
        const double cells = radius / (line ? g->dx : fmax(g->dx, g->dy));
        if (cells < MC_WARN_CELLS_PER_RADIUS)
            mc_results_warn(r, "coarse_contact",
                            "the contact %s %.4g um spans %.3g cells (fewer than %.0f): the "
                            "pressure peak and the stresses are under-resolved; use smaller cells "
                            "(dx%s)",
                            line ? "half-width" : "radius", radius * 1e6, cells,
                            MC_WARN_CELLS_PER_RADIUS, line ? "" : ", dy");
    }
    if (c->p_max > estar)
        mc_results_warn(r, "pressure_above_moduli",
                        "p_max = %.4g MPa is above the reduced modulus E* = %.4g MPa: strains of "
                        "order one, outside linear elasticity; check the load, the moduli and the "
                        "roughness heights",
                        c->p_max * 1e-6, estar * 1e-6);
    /* theory.md §8.5: the x-z (y-z) checkerboard of plastic strain releases energy for
     * 0.6 < dz/dx (dz/dy) < 1.6 (measured -0.10 .. -0.25 at 0.71 .. 1.41 on a line grid, down to
     * -0.15 at dz = dx in finite 3-D blocks; a perfectly plastic rough sphere at dz = dx: twice
     * the plastic strain, alternate cells yielding). dy is no cell size on a line grid. */
    if (r->plastic.nz > 0 && r->plastic.dz > 0 && r->plastic.stress_points &&
        strcmp(r->plastic.stress_points, "centre") == 0) { /* cell averages have no such mode */
        const int line = g->periodic_y && g->ny == 1;
        const double rx = r->plastic.dz / g->dx, ry = line ? 0 : r->plastic.dz / g->dy;
        const int bx = rx > MC_WARN_CHECKER_LO && rx < MC_WARN_CHECKER_HI;
        const int by = ry > MC_WARN_CHECKER_LO && ry < MC_WARN_CHECKER_HI;
        if (bx || by)
            mc_results_warn(r, "plastic_checkerboard",
                            "[plasticity] dz = %.4g um is %.2f %s: the residual stress operator "
                            "has an unstable checkerboard mode for %.1f < dz/d%s < %.1f "
                            "(alternate cells yielding, too much plastic strain, most with "
                            "perfect or weak hardening); use stress_points = cell_average (the "
                            "default) or dz <= min(dx, dy) / 2",
                            r->plastic.dz * 1e6, bx ? rx : ry, bx ? "dx" : "dy",
                            MC_WARN_CHECKER_LO, bx ? "x" : "y", MC_WARN_CHECKER_HI);
    }
    /* theory.md §8.5: the residual stress operator's checkerboard modes; whatever dz, a plastic
     * strain field that zigzags from cell to cell is the discretisation's, not the material's */
    if (r->plastic_strain && r->plastic.nz > 0) {
        const double f = mc_stage_plastic_checkered_fraction(g, r->plastic.nz, r->plastic_strain);
        if (f > MC_WARN_CHECKERED)
            mc_results_warn(r, "plastic_checkered",
                            "%.0f %% of the cells with significant plastic strain zigzag from cell "
                            "to cell (above %.0f %%): the residual stress operator's checkerboard "
                            "mode (docs/theory.md §8.5), not the material's response; use a "
                            "smaller dz (dx / 2), more hardening or finer cells",
                            100.0 * f, 100.0 * MC_WARN_CHECKERED);
    }
    if (r->has_roughness && r->roughness_initial.warning[0])
        mc_results_warn(r, "roughness_cutoff", "roughness parameters: %s",
                        r->roughness_initial.warning);
    for (int k = 0; r->two_bodies && k < 2; k++) /* each body's, with its section's cutoff */
        if (r->body_roughness_initial[k].warning[0] &&
            strcmp(r->body_roughness_initial[k].warning, r->roughness_initial.warning) != 0)
            mc_results_warn(r, "roughness_cutoff", "roughness parameters of body %d ([%s]): %s",
                            k + 1, k ? "roughness2" : "roughness",
                            r->body_roughness_initial[k].warning);
}
