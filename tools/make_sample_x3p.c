/* make_sample_x3p.c - writes cases/data/ground_sample.x3p, the "measured" surface of
 * cases/measured.ini: no freely licensed measurement of a ground disc was at hand, so this is a
 * synthetic ground-like surface (Gaussian heights, Sq = 0.3 um, correlation 3 um across and
 * 30 um along the grinding lay, i.e. along y; docs/theory.md §14) of 160 x 96 points at
 * 0.8 x 1.0 um (dx != dy, as instruments often have), with a tilt of 2 um/mm along x and a
 * 0.05 um offset that the default levelling (detrend = plane) removes, and four points marked
 * as not measured (missing = fill fills them). Written by the library's own X3P writer.
 *   make sample-x3p   (rebuilds the file; SOURCE_DATE_EPOCH fixes its date)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/grid.h"
#include "io/surface_file.h"
#include "surface/surface.h"

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "cases/data/ground_sample.x3p";
    mc_grid g = {.nx = 160, .ny = 96, .dx = 0.8e-6, .dy = 1.0e-6, .periodic_x = 0,
                 .periodic_y = 0};
    mc_roughness_spec r = {.type = MC_ROUGH_GAUSSIAN, .rq = 0.3e-6, .correlation_x = 3e-6,
                           .correlation_y = 30e-6, .seed = 4288};
    size_t n = mc_grid_cells(&g);
    double *z = mc_zeros(n);
    mc_error err = {0};
    if (!z || mc_surface_roughness(&g, &r, z, &err) != MC_OK) {
        fprintf(stderr, "make_sample_x3p: %s\n", err.msg);
        return 1;
    }
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++)
            z[(size_t)j * g.nx + i] += 0.05e-6 + 2e-3 * i * g.dx; /* offset and tilt */
    size_t holes[] = {5 * 160 + 7, 40 * 160 + 80, 41 * 160 + 80, 90 * 160 + 150};
    for (size_t k = 0; k < sizeof holes / sizeof holes[0]; k++)
        z[holes[k]] = NAN;
    unsigned char *valid = malloc(n);
    for (size_t k = 0; k < n; k++)
        valid[k] = isfinite(z[k]);
    mc_surface_data s = {.nx = g.nx, .ny = g.ny, .dx = g.dx, .dy = g.dy, .x0 = 0, .y0 = 0,
                         .z = z, .valid = valid, .missing = 4};
    int rc = mc_x3p_write(out, &s, "microcontact tools/make_sample_x3p.c (synthetic ground-like "
                                   "surface)", &err);
    if (rc != MC_OK)
        fprintf(stderr, "make_sample_x3p: %s\n", err.msg);
    free(valid);
    mc_free(z);
    return rc == MC_OK ? 0 : 1;
}
