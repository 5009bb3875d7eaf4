/* vutil.h - small numerical helpers shared by the verification suites and benchmarks. */
#ifndef MC_VERIFY_VUTIL_H
#define MC_VERIFY_VUTIL_H

#include <stddef.h>

#include "results.h"
#include "scene.h"

/* Least-squares line y = c0 + c1 x over n points; returns 0 on success. */
int vu_linfit(const double *x, const double *y, int n, double *c0, double *c1);

/* Slope of log(y) against log(x) over n points (convergence order); NAN if not computable. */
double vu_loglog_slope(const double *x, const double *y, int n);

/* Contact radius (or half-width) from a fit of p^2 = p0^2 (1 - r^2/a^2) over the cells with
 * 0 < r < frac * a_guess (the square-root edge is left out: it is where pixelation lives).
 * Point contact: r = sqrt(x^2 + y^2) about the grid centre; line: r = |x| (all rows). */
double vu_fit_radius(const mc_results *r, int line, double a_guess, double frac, double *p0_fit);

/* A scene with every default (mc_scene_defaults) and no roughness, for suites to fill in. */
void vu_scene(mc_scene *s, int nx, int ny, double dx, double dy);

/* The cell of maximum pressure (index j*nx + i). */
size_t vu_argmax(const double *f, size_t n);

#endif
