/* warnings.h - warnings a user can act on, found after a run: the result is computed, but it may
 * not be what the user wants (summary.json "warnings", and stderr through the CLI).
 *
 * Codes (stable, for scripts):
 *   contact_at_edge      solid contact reaches the edge of a free (non-periodic) axis of a grid
 *                        whose shape has a macro geometry (sphere, cylinder, ellipsoid): the grid
 *                        truncates the contact. Not for shape = flat: a flat rough patch stands
 *                        for a piece of a larger nominal contact, and contact at its edges is
 *                        what a nominal load gives.
 *   contact_ratio_high   more than 90 % of the grid in solid contact: the grid holds little free
 *                        surface (enlarge it, or lower the load).
 *   coarse_contact       fewer than 10 cells per contact radius (shapes with a macro geometry):
 *                        smooth, r = sqrt(A/pi) for a point-like contact (sphere, ellipsoid), the
 *                        half-width A / (2 ny dy) for a line contact (cylinder); rough, from the
 *                        extent of the solid contact (the micro-contacts' area is a fraction of
 *                        the macro contact's): half-extents a_x, a_y of the box around the
 *                        contact cells, r = sqrt(a_x a_y) (point) or a_x (line). Cells per radius
 *                        r / dx (line) or r / max(dx, dy) (point).
 *   pressure_above_moduli  p_max above the reduced modulus E*: strains of order one, outside the
 *                        linear elasticity the solve assumes.
 *   roughness_cutoff     the ISO roughness parameters deviate from the standard (cut-off clipped
 *                        on a short surface, short evaluation length; surface/roughness.h).
 *   plastic_checkerboard  [plasticity] stress_points = centre with dz between 0.6 and 1.6 dx, or
 *                        0.6 and 1.6 dy (not on a
 *                        line grid, periodic y with ny = 1, where dy is no cell size): the
 *                        residual stress operator's x-z (y-z) checkerboard mode releases energy
 *                        there (docs/theory.md §8.5), and a plastic run can lock into it.
 *   plastic_checkered    more than MC_WARN_CHECKERED of the cells with significant plastic strain
 *                        (above MC_CHECKER_SIGNIFICANT of the largest) zigzag along x or y (both
 *                        steps to the neighbours above MC_CHECKER_STEP of the largest, of
 *                        opposite signs): the field has locked into a checkerboard mode of the
 *                        residual stress operator (docs/theory.md §8.5). Measured: 99 % for the
 *                        perfectly plastic rough sphere of cases/elastic_plastic.ini at dz = dx
 *                        (locked in), 16 % at dz = dx/2; 35 % for the final state of the default
 *                        running-in scene (sharp asperity-scale fields, not locked in).
 *   surface_file         the [roughness] file was read in a way another reader may not: an X3P
 *                        with float heights and a CZ Increment other than 1 (ignored, as the
 *                        ISO 5436-2 reference reader does; the message names the value).
 *   wisdom_not_written   [solver] plans = wisdom: the wisdom file could not be written at the
 *                        end of the run (the results stand; the next run measures again).
 */
#ifndef MC_WARNINGS_H
#define MC_WARNINGS_H

#include "case/scene.h"
#include "pipeline/results.h"

#define MC_WARN_CONTACT_RATIO 0.9 /* contact_ratio_high above this fraction */
#define MC_WARN_CELLS_PER_RADIUS 10.0 /* coarse_contact below this many cells */
#define MC_WARN_CHECKERED 0.75         /* plastic_checkered above this fraction */
#define MC_CHECKER_SIGNIFICANT 0.3     /* cells above this fraction of the largest strain count */
#define MC_CHECKER_STEP 0.01           /* a step to a neighbour counts above this fraction */
#define MC_WARN_CHECKER_LO 0.6 /* plastic_checkerboard: dz/dx or dz/dy strictly between these */
#define MC_WARN_CHECKER_HI 1.6

/* Add one warning to r (dropped when MC_WARNINGS_MAX are there). */
void mc_results_warn(mc_results *r, const char *code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Fraction of the cells of the nz x ny x nx plastic strain field peq (grid g) with more than
 * MC_CHECKER_SIGNIFICANT of its largest value that zigzag along x or y (see plastic_checkered);
 * 0 for a field without plastic strain. */
double mc_stage_plastic_checkered_fraction(const mc_grid *g, int nz, const double *peq);

/* The warnings of a finished solve of scene sc (the fields and summaries of r filled). */
void mc_results_warnings(const mc_scene *sc, mc_results *r);

#endif
