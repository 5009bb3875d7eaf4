/* vutil.c - helpers shared by the verification suites (see vutil.h). */
#include "vutil.h"

#include <math.h>
#include <string.h>

int vu_linfit(const double *x, const double *y, int n, double *c0, double *c1)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < n; k++) {
        sx += x[k];
        sy += y[k];
        sxx += x[k] * x[k];
        sxy += x[k] * y[k];
    }
    double det = n * sxx - sx * sx;
    if (n < 2 || det == 0)
        return -1;
    *c1 = (n * sxy - sx * sy) / det;
    *c0 = (sy - *c1 * sx) / n;
    return 0;
}

double vu_loglog_slope(const double *x, const double *y, int n)
{
    double lx[64], ly[64];
    int m = 0;
    for (int k = 0; k < n && m < 64; k++) {
        if (x[k] > 0 && y[k] > 0) {
            lx[m] = log(x[k]);
            ly[m] = log(y[k]);
            m++;
        }
    }
    double c0, c1;
    return vu_linfit(lx, ly, m, &c0, &c1) == 0 ? c1 : NAN;
}

double vu_fit_radius(const mc_results *r, int line, double a_guess, double frac, double *p0_fit)
{
    const mc_grid *g = &r->grid;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    long m = 0;
    for (int j = 0; j < g->ny; j++)
        for (int i = 0; i < g->nx; i++) {
            double x = mc_grid_x(g, i), y = line ? 0.0 : mc_grid_y(g, j);
            double rr = x * x + y * y, p = r->pressure[(size_t)j * g->nx + i];
            if (p <= 0 || rr >= frac * frac * a_guess * a_guess)
                continue;
            sx += rr;
            sy += p * p;
            sxx += rr * rr;
            sxy += rr * p * p;
            m++;
        }
    double det = m * sxx - sx * sx;
    if (m < 3 || det == 0)
        return NAN;
    double c1 = (m * sxy - sx * sy) / det, c0 = (sy - c1 * sx) / m;
    if (p0_fit)
        *p0_fit = sqrt(c0);
    return sqrt(-c0 / c1);
}

void vu_scene(mc_scene *s, int nx, int ny, double dx, double dy)
{
    mc_scene_defaults(s);
    s->grid.nx = nx;
    s->grid.ny = ny;
    s->grid.dx = dx;
    s->grid.dy = dy;
}

size_t vu_argmax(const double *f, size_t n)
{
    size_t k = 0;
    for (size_t i = 1; i < n; i++)
        if (f[i] > f[k])
            k = i;
    return k;
}
