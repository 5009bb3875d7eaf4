/* vutil.h - small numerical helpers shared by the verification suites and benchmarks. */
#ifndef MC_VERIFY_VUTIL_H
#define MC_VERIFY_VUTIL_H

#include <stddef.h>

#include "pipeline/results.h"
#include "case/scene.h"

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

/* Reference table `name` of the physics dossier, read from $MC_PHYSICS_DIR or tests/data/physics
 * (relative to the working directory: the repository root for make). Lines starting with '#' are
 * comments; the first other line is the header (up to max_cols names, copied into header[c] when
 * header is not NULL); every further line is a row of numbers. A non-numeric field (e.g. a column
 * label such as "node") is stored as NAN and its text, when labels is not NULL, copied into
 * labels[row * max_cols + c] (16 bytes each). *data is malloc'ed with row stride max_cols (row r,
 * column c at (*data)[r * max_cols + c]); the caller frees it (and *labels). Returns the number of rows, or -1 when the file cannot be read
 * (path is then in msg, if given). */
int vu_read_csv(const char *name, double **data, int *cols, char header[][32], int max_cols,
                char (**labels)[16], char *msg, size_t msglen);

/* Vertex of the parabola through (-h, fm), (0, f0), (h, fp): returns the offset of the vertex
 * from the middle point (clamped to [-h, h]) and its value in *fmax (f0 if the three points are
 * collinear). Used to place a sampled maximum between grid points or layers. */
double vu_parabola_peak(double fm, double f0, double fp, double h, double *fmax);

#endif
