/* vutil.c - helpers shared by the verification suites (see vutil.h). */
#include "vutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

int vu_read_csv(const char *name, double **data, int *cols, char header[][32], int max_cols,
                char (**labels)[16], char *msg, size_t msglen)
{
    const char *dir = getenv("MC_PHYSICS_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir && *dir ? dir : "tests/data/physics", name);
    *data = NULL;
    *cols = 0;
    if (labels)
        *labels = NULL;
    if (msg)
        snprintf(msg, msglen, "%s", path);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[8192];
    int ncols = 0, rows = 0, cap = 0;
    double *d = NULL;
    char(*lab)[16] = NULL;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n' || line[0] == '\r')
            continue;
        if (ncols == 0) { /* the header line */
            char *save = NULL;
            for (char *tok = strtok_r(line, ",\r\n", &save); tok && ncols < max_cols;
                 tok = strtok_r(NULL, ",\r\n", &save)) {
                if (header)
                    snprintf(header[ncols], 32, "%s", tok);
                ncols++;
            }
            continue;
        }
        if (rows == cap) {
            cap = cap ? 2 * cap : 64;
            double *nd = realloc(d, sizeof *d * (size_t)cap * (size_t)max_cols);
            char(*nl)[16] = labels ? realloc(lab, sizeof *lab * (size_t)cap * (size_t)max_cols)
                                   : NULL;
            if (nd)
                d = nd;
            if (nl)
                lab = nl;
            if (!nd || (labels && !nl)) {
                free(d);
                free(lab);
                fclose(f);
                return -1;
            }
        }
        char *p = line;
        for (int c = 0; c < ncols; c++) {
            char *end;
            size_t k = (size_t)rows * (size_t)max_cols + (size_t)c;
            double v = strtod(p, &end);
            if (end == p || (*end != ',' && *end != '\n' && *end != '\r' && *end != '\0')) {
                /* a text field: keep its label */
                end = p + strcspn(p, ",\r\n");
                v = NAN;
                if (lab)
                    snprintf(lab[k], 16, "%.*s", (int)(end - p), p);
            } else if (lab)
                lab[k][0] = '\0';
            d[k] = v;
            p = end;
            if (*p == ',')
                p++;
        }
        rows++;
    }
    fclose(f);
    *cols = ncols;
    *data = d;
    if (labels)
        *labels = lab;
    return rows;
}

double vu_parabola_peak(double fm, double f0, double fp, double h, double *fmax)
{
    double c2 = fm - 2 * f0 + fp, c1 = fp - fm; /* f(s) = f0 + c1 s/(2h) + c2 s^2/(2h^2) */
    if (c2 == 0) {
        if (fmax)
            *fmax = f0;
        return 0;
    }
    double s = -0.5 * c1 / c2 * h;
    if (s > h)
        s = h;
    if (s < -h)
        s = -h;
    if (fmax)
        *fmax = f0 + c1 * s / (2 * h) + c2 * s * s / (2 * h * h);
    return s;
}
