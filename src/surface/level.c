/* level.c - form removal, cropping and bilinear resampling of height maps (see level.h). */
#include "surface/level.h"

#include <math.h>
#include <string.h>

#define NTERM 6          /* 1, u, v, u^2, u v, v^2 */
#define PIVOT_TOL 1e-10  /* a term whose scaled Schur pivot is below this is not determined */
#define EDGE_TOL 1e-6    /* slack on lateral comparisons, in spacings */

static int check_map(int nx, int ny, double dx, double dy, mc_error *err)
{
    if (nx < 1 || ny < 1)
        return mc_fail(err, MC_ERR_INPUT, "height map of %d x %d points: both sizes must be >= 1",
                       nx, ny);
    if (!(dx > 0 && isfinite(dx) && dy > 0 && isfinite(dy)))
        return mc_fail(err, MC_ERR_INPUT, "height map spacings dx = %g m, dy = %g m: must be "
                       "finite and > 0", dx, dy);
    return MC_OK;
}

/* ---- least-squares polynomial ------------------------------------------------------------ */

/* Normal equations of the first nt basis functions over the valid points, in scaled
 * coordinates u = x / hu, v = y / hv (both in [-1, 1]). */
static void normal_equations(const double *z, const unsigned char *valid, int nx, int ny, int nt,
                             double G[NTERM][NTERM], double b[NTERM])
{
    memset(G, 0, sizeof(double) * NTERM * NTERM);
    memset(b, 0, sizeof(double) * NTERM);
    for (int j = 0; j < ny; j++) {
        double v = (j + 0.5 - 0.5 * ny) / (0.5 * ny);
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * nx + i;
            if (valid && !valid[k])
                continue;
            double u = (i + 0.5 - 0.5 * nx) / (0.5 * nx);
            double phi[NTERM] = {1.0, u, v, u * u, u * v, v * v};
            for (int a = 0; a < nt; a++) {
                b[a] += phi[a] * z[k];
                for (int c = a; c < nt; c++)
                    G[a][c] += phi[a] * phi[c];
            }
        }
    }
    for (int a = 0; a < nt; a++)
        for (int c = 0; c < a; c++)
            G[a][c] = G[c][a];
}

/* Solve G x = b (nt x nt, symmetric positive semi-definite) by Gaussian elimination with
 * diagonal pivoting on the Jacobi-scaled matrix; unresolvable terms get x = 0. */
static void solve_pivoted(double G[NTERM][NTERM], double b[NTERM], int nt, double x[NTERM])
{
    double s[NTERM], A[NTERM][NTERM], r[NTERM];
    int perm[NTERM], rank = 0;
    for (int a = 0; a < nt; a++) {
        s[a] = G[a][a] > 0 ? 1.0 / sqrt(G[a][a]) : 0.0;
        perm[a] = a;
        x[a] = 0.0;
    }
    for (int a = 0; a < nt; a++) {
        for (int c = 0; c < nt; c++)
            A[a][c] = s[a] * G[a][c] * s[c];
        r[a] = s[a] * b[a];
    }
    for (int k = 0; k < nt; k++) {
        int p = k;
        for (int q = k + 1; q < nt; q++)
            if (A[q][q] > A[p][p])
                p = q;
        if (!(A[p][p] > PIVOT_TOL))
            break;
        if (p != k) { /* symmetric swap of rows and columns k, p */
            for (int c = 0; c < nt; c++) {
                double t = A[k][c]; A[k][c] = A[p][c]; A[p][c] = t;
            }
            for (int c = 0; c < nt; c++) {
                double t = A[c][k]; A[c][k] = A[c][p]; A[c][p] = t;
            }
            double t = r[k]; r[k] = r[p]; r[p] = t;
            int ti = perm[k]; perm[k] = perm[p]; perm[p] = ti;
        }
        for (int q = k + 1; q < nt; q++) {
            double f = A[q][k] / A[k][k];
            for (int c = k; c < nt; c++)
                A[q][c] -= f * A[k][c];
            r[q] -= f * r[k];
        }
        rank = k + 1;
    }
    double y[NTERM] = {0};
    for (int k = rank - 1; k >= 0; k--) { /* trailing (dropped) unknowns are 0 */
        double acc = r[k];
        for (int c = k + 1; c < rank; c++)
            acc -= A[k][c] * y[c];
        y[k] = acc / A[k][k];
    }
    for (int k = 0; k < rank; k++)
        x[perm[k]] = y[k] * s[perm[k]];
}

static void subtract_fit(double *z, const unsigned char *valid, int nx, int ny,
                         const double bcoef[NTERM])
{
    for (int j = 0; j < ny; j++) {
        double v = (j + 0.5 - 0.5 * ny) / (0.5 * ny);
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * nx + i;
            if (valid && !valid[k])
                continue;
            double u = (i + 0.5 - 0.5 * nx) / (0.5 * nx);
            z[k] -= bcoef[0] + bcoef[1] * u + bcoef[2] * v + bcoef[3] * u * u + bcoef[4] * u * v +
                    bcoef[5] * v * v;
        }
    }
}

int mc_level_detrend(double *z, const unsigned char *valid, int nx, int ny, double dx, double dy,
                     mc_detrend_kind kind, double coef[6], mc_error *err)
{
    if (coef)
        memset(coef, 0, sizeof(double) * NTERM);
    int rc = check_map(nx, ny, dx, dy, err);
    if (rc)
        return rc;
    static const int nterms[] = {0, 1, 3, 6};
    if ((int)kind < 0 || (int)kind > 3)
        return mc_fail(err, MC_ERR_INPUT, "detrend kind %d: expected none, mean, plane or "
                       "quadratic", (int)kind);
    int nt = nterms[kind];
    if (nt == 0)
        return MC_OK;
    size_t n = (size_t)nx * ny, nvalid = 0;
    for (size_t k = 0; k < n; k++) {
        if (valid && !valid[k])
            continue;
        if (!isfinite(z[k]))
            return mc_fail(err, MC_ERR_INPUT, "detrend: height at point (%zu, %zu) is not "
                           "finite (mark it invalid or fill it)", k % (size_t)nx, k / (size_t)nx);
        nvalid++;
    }
    if (nvalid == 0)
        return mc_fail(err, MC_ERR_INPUT, "detrend: the %d x %d map has no valid point", nx, ny);

    double total[NTERM] = {0};
    for (int pass = 0; pass < 2; pass++) { /* fit, then fit the residual (refinement) */
        double G[NTERM][NTERM], b[NTERM], x[NTERM] = {0};
        normal_equations(z, valid, nx, ny, nt, G, b);
        solve_pivoted(G, b, nt, x);
        subtract_fit(z, valid, nx, ny, x);
        for (int a = 0; a < nt; a++)
            total[a] += x[a];
    }
    if (coef) { /* back to physical coordinates x = hu u, y = hv v */
        double hu = 0.5 * nx * dx, hv = 0.5 * ny * dy;
        coef[0] = total[0];
        coef[1] = total[1] / hu;
        coef[2] = total[2] / hv;
        coef[3] = total[3] / (hu * hu);
        coef[4] = total[4] / (hu * hv);
        coef[5] = total[5] / (hv * hv);
    }
    return MC_OK;
}

int mc_level_mask_nonfinite(const double *z, unsigned char *valid, int n)
{
    int bad = 0;
    for (int k = 0; k < n; k++) {
        valid[k] = valid[k] && isfinite(z[k]);
        bad += !valid[k];
    }
    return bad;
}

/* ---- lateral grids ----------------------------------------------------------------------- */

int mc_level_grid_check(const mc_level_grid *g, const char *what, mc_error *err)
{
    if (g->nx < 1 || g->ny < 1)
        return mc_fail(err, MC_ERR_INPUT, "%s: %d x %d samples, both must be >= 1", what, g->nx,
                       g->ny);
    if (!(g->dx > 0 && isfinite(g->dx) && g->dy > 0 && isfinite(g->dy)))
        return mc_fail(err, MC_ERR_INPUT, "%s: spacings dx = %g m, dy = %g m must be finite "
                       "and > 0", what, g->dx, g->dy);
    if (!isfinite(g->x0) || !isfinite(g->y0))
        return mc_fail(err, MC_ERR_INPUT, "%s: offsets x0 = %g m, y0 = %g m must be finite",
                       what, g->x0, g->y0);
    return MC_OK;
}

/* Cell extent along one axis (see mc_level_grid). */
static void extent(int n, double d, double o, double *lo, double *hi)
{
    *lo = o - 0.5 * d;
    *hi = o + (n - 0.5) * d;
}

/* Samples with positions in [r, r + w) along one axis: first index and count (0 if none). */
static void axis_crop(int n, double d, double o, double r, double w, int *first, int *count)
{
    double tol = EDGE_TOL * d;
    double a = ceil((r - tol - o) / d), b = ceil((r + w - tol - o) / d); /* [a, b) */
    if (a < 0)
        a = 0;
    if (b > n)
        b = n;
    *first = (int)a;
    *count = b > a ? (int)(b - a) : 0;
}

int mc_level_crop(const mc_level_grid *g, double rx, double ry, double w, double h,
                  mc_level_grid *sub, int *i0, int *j0, mc_error *err)
{
    int rc = mc_level_grid_check(g, "crop: grid", err);
    if (rc)
        return rc;
    double xlo, xhi, ylo, yhi;
    extent(g->nx, g->dx, g->x0, &xlo, &xhi);
    extent(g->ny, g->dy, g->y0, &ylo, &yhi);
    if (!(isfinite(rx) && isfinite(ry) && isfinite(w) && isfinite(h) && w > 0 && h > 0))
        return mc_fail(err, MC_ERR_INPUT, "region x0 = %g m, y0 = %g m, width %g m, height %g m "
                       "is empty: width and height must be finite and > 0 (grid extent "
                       "x [%g, %g] m, y [%g, %g] m)", rx, ry, w, h, xlo, xhi, ylo, yhi);
    double tx = EDGE_TOL * g->dx, ty = EDGE_TOL * g->dy;
    /* the far edge may be the cell edge (x0 + (n - 1/2) dx) or, for a region aligned with the
     * samples, the sample after the last (x0 + n dx): a region that selected a map selects all
     * of it again in the map written with its offsets (surface --out) */
    const double xend = fmax(xhi, g->x0 + g->nx * g->dx), yend = fmax(yhi, g->y0 + g->ny * g->dy);
    if (rx < xlo - tx || rx + w > xend + tx || ry < ylo - ty || ry + h > yend + ty)
        return mc_fail(err, MC_ERR_INPUT, "region x [%g, %g] m, y [%g, %g] m reaches outside "
                       "the grid extent x [%g, %g] m, y [%g, %g] m", rx, rx + w, ry, ry + h,
                       xlo, xhi, ylo, yhi);
    int ni, nj;
    axis_crop(g->nx, g->dx, g->x0, rx, w, i0, &ni);
    axis_crop(g->ny, g->dy, g->y0, ry, h, j0, &nj);
    if (ni == 0 || nj == 0)
        return mc_fail(err, MC_ERR_INPUT, "region x [%g, %g] m, y [%g, %g] m holds no sample of "
                       "the grid (extent x [%g, %g] m, y [%g, %g] m, spacings %g m, %g m)", rx,
                       rx + w, ry, ry + h, xlo, xhi, ylo, yhi, g->dx, g->dy);
    sub->nx = ni;
    sub->ny = nj;
    sub->dx = g->dx;
    sub->dy = g->dy;
    sub->x0 = g->x0 + *i0 * g->dx;
    sub->y0 = g->y0 + *j0 * g->dy;
    return MC_OK;
}

void mc_level_copy_block(const double *src, const unsigned char *src_valid, int nx, int i0,
                         int j0, int sub_nx, int sub_ny, double *dst, unsigned char *dst_valid)
{
    for (int j = 0; j < sub_ny; j++) {
        size_t s = (size_t)(j0 + j) * nx + i0, d = (size_t)j * sub_nx;
        memcpy(dst + d, src + s, sizeof(double) * (size_t)sub_nx);
        if (dst_valid) {
            if (src_valid)
                memcpy(dst_valid + d, src_valid + s, (size_t)sub_nx);
            else
                memset(dst_valid + d, 1, (size_t)sub_nx);
        }
    }
}

/* Left index of the interpolation interval and the (possibly slightly extrapolating) weight. */
static void bracket(double x, int n, double d, double o, int *i, double *f)
{
    if (n == 1) {
        *i = 0;
        *f = 0.0;
        return;
    }
    double t = (x - o) / d;
    int k = (int)floor(t);
    if (k < 0)
        k = 0;
    if (k > n - 2)
        k = n - 2;
    *i = k;
    *f = t - k;
}

int mc_level_resample_linear(const double *src, const mc_level_grid *gs, double *dst,
                             const mc_level_grid *gd, mc_error *err)
{
    int rc = mc_level_grid_check(gs, "resample: source grid", err);
    if (!rc)
        rc = mc_level_grid_check(gd, "resample: destination grid", err);
    if (rc)
        return rc;
    double xlo, xhi, ylo, yhi;
    extent(gs->nx, gs->dx, gs->x0, &xlo, &xhi);
    extent(gs->ny, gs->dy, gs->y0, &ylo, &yhi);
    double dx0 = gd->x0, dx1 = gd->x0 + (gd->nx - 1) * gd->dx;
    double dy0 = gd->y0, dy1 = gd->y0 + (gd->ny - 1) * gd->dy;
    double tx = EDGE_TOL * gs->dx, ty = EDGE_TOL * gs->dy;
    if (dx0 < xlo - tx || dx1 > xhi + tx || dy0 < ylo - ty || dy1 > yhi + ty)
        return mc_fail(err, MC_ERR_INPUT, "resample: the destination samples x [%g, %g] m, "
                       "y [%g, %g] m (%d x %d at %g m x %g m) reach beyond the source extent "
                       "x [%g, %g] m, y [%g, %g] m (%d x %d at %g m x %g m)", dx0, dx1, dy0, dy1,
                       gd->nx, gd->ny, gd->dx, gd->dy, xlo, xhi, ylo, yhi, gs->nx, gs->ny,
                       gs->dx, gs->dy);
    const int nx = gs->nx;
    for (int j = 0; j < gd->ny; j++) {
        int jj;
        double fy;
        bracket(gd->y0 + j * gd->dy, gs->ny, gs->dy, gs->y0, &jj, &fy);
        const double *r0 = src + (size_t)jj * nx;
        const double *r1 = gs->ny > 1 ? r0 + nx : r0;
        for (int i = 0; i < gd->nx; i++) {
            int ii;
            double fx;
            bracket(gd->x0 + i * gd->dx, nx, gs->dx, gs->x0, &ii, &fx);
            int i1 = nx > 1 ? ii + 1 : ii;
            double a = r0[ii] + fx * (r0[i1] - r0[ii]);
            double b = r1[ii] + fx * (r1[i1] - r1[ii]);
            dst[(size_t)j * gd->nx + i] = a + fy * (b - a);
        }
    }
    return MC_OK;
}
