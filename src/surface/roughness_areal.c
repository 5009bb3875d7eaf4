/* roughness_areal.c - ISO 25178-2 areal parameters (see roughness.h;
 * theory.md §13.5). */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "surface/roughness_internal.h"

/* Central difference of h along one axis at index a of n (stride st), or 0 when the axis has
 * no slope here. Returns 0 if the point cannot be used (a needed neighbour is missing). */
static int slope(const double *h, const unsigned char *v, size_t k, int a, int n, size_t st,
                 int periodic, double d, double *out)
{
    *out = 0.0;
    if (!periodic && n < 3)
        return 1; /* too short to tell a slope */
    if (periodic && n < 2)
        return 1;
    size_t km, kp;
    if (periodic) {
        km = a > 0 ? k - st : k + (size_t)(n - 1) * st;
        kp = a < n - 1 ? k + st : k - (size_t)(n - 1) * st;
    } else {
        if (a == 0 || a == n - 1)
            return 0;
        km = k - st;
        kp = k + st;
    }
    if (v && (!v[km] || !v[kp]))
        return 0;
    *out = (h[kp] - h[km]) / (2.0 * d);
    return 1;
}

int mc_rough_areal(const double *z, const unsigned char *valid, int nx, int ny, double dx,
                   double dy, int periodic_x, int periodic_y, mc_roughness_params *out,
                   mc_error *err)
{
    size_t n = (size_t)nx * ny, cnt = 0;
    double mean = 0;
    for (size_t k = 0; k < n; k++)
        if (!valid || valid[k]) {
            mean += z[k];
            cnt++;
        }
    if (cnt == 0)
        return mc_fail(err, MC_ERR_INPUT, "roughness: the %d x %d map has no valid point", nx,
                       ny);
    mean /= (double)cnt;
    double *h = mc_malloc(sizeof(double) * n), *work = mc_malloc(sizeof(double) * 2 * cnt);
    if (!h || !work) {
        mc_free(h);
        mc_free(work);
        return mc_fail(err, MC_ERR_NOMEM, "roughness: out of memory for %d x %d points", nx, ny);
    }
    double s1 = 0, s2 = 0, s3 = 0, s4 = 0, hi = -INFINITY, lo = INFINITY;
    size_t c = 0;
    for (size_t k = 0; k < n; k++) {
        if (valid && !valid[k]) {
            h[k] = 0.0;
            continue;
        }
        double x = z[k] - mean, x2 = x * x;
        h[k] = x;
        work[c++] = x;
        s1 += fabs(x);
        s2 += x2;
        s3 += x2 * x;
        s4 += x2 * x2;
        hi = fmax(hi, x);
        lo = fmin(lo, x);
    }
    double sq = sqrt(s2 / cnt);
    out->Sa = s1 / cnt;
    out->Sq = sq;
    out->Ssk = sq > 0 ? s3 / cnt / (sq * sq * sq) : 0.0;
    out->Sku = sq > 0 ? s4 / cnt / (sq * sq * sq * sq) : 0.0;
    out->Sp = hi;
    out->Sv = -lo;
    out->Sz = hi - lo;
    out->points = (long)cnt;

    double g2 = 0, dr = 0;
    size_t ng = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * nx + i;
            double zx, zy;
            if (valid && !valid[k])
                continue;
            if (!slope(h, valid, k, i, nx, 1, periodic_x, dx, &zx) ||
                !slope(h, valid, k, j, ny, (size_t)nx, periodic_y, dy, &zy))
                continue;
            double q = zx * zx + zy * zy;
            g2 += q;
            dr += q / (sqrt(1.0 + q) + 1.0); /* sqrt(1 + q) - 1 without cancellation */
            ng++;
        }
    out->Sdq = ng ? sqrt(g2 / ng) : 0.0;
    out->Sdr = ng ? 100.0 * dr / ng : 0.0;

    mc_material_ratio mr;
    mc_roughness_material_ratio(work, cnt, work + cnt, &mr);
    out->Sk = mr.k;
    out->Spk = mr.pk;
    out->Svk = mr.vk;
    out->Smr1 = mr.mr1;
    out->Smr2 = mr.mr2;
    mc_free(h);
    mc_free(work);
    return MC_OK;
}

int mc_roughness_material_curve(const double *z, const unsigned char *valid, size_t n, int npts,
                                double *height, mc_material_ratio *line, mc_error *err)
{
    if (npts < 2 || !z || !height)
        return mc_fail(err, MC_ERR_INPUT,
                       "material-ratio curve: %d points asked; accepted: at least 2", npts);
    size_t cnt = 0;
    double mean = 0;
    for (size_t k = 0; k < n; k++) {
        if (valid && !valid[k])
            continue;
        if (!isfinite(z[k]))
            return mc_fail(err, MC_ERR_INPUT,
                           "material-ratio curve: height %zu of %zu is not finite", k, n);
        mean += z[k];
        cnt++;
    }
    if (cnt == 0)
        return mc_fail(err, MC_ERR_INPUT, "material-ratio curve: the map has no valid point");
    mean /= (double)cnt; /* as mc_rough_areal: the same reference to the bit */
    double *h = mc_malloc(sizeof(double) * 2 * cnt);
    if (!h)
        return mc_fail(err, MC_ERR_NOMEM, "material-ratio curve: out of memory for %zu points",
                       cnt);
    for (size_t k = 0, c = 0; k < n; k++)
        if (!valid || valid[k])
            h[c++] = z[k] - mean;
    mc_material_ratio mr;
    mc_roughness_material_ratio(h, cnt, h + cnt, &mr);
    const double *s = h + cnt; /* the curve: the j-th highest at Mr = 100 (j + 1/2) / cnt */
    for (int k = 0; k < npts; k++) {
        double x = (double)k / (double)(npts - 1) * (double)cnt - 0.5; /* fractional j */
        if (x <= 0)
            height[k] = s[0];
        else if (x >= (double)(cnt - 1))
            height[k] = s[cnt - 1];
        else {
            size_t j = (size_t)x;
            double t = x - (double)j;
            height[k] = s[j] + t * (s[j + 1] - s[j]);
        }
    }
    if (line)
        *line = mr;
    mc_free(h);
    return MC_OK;
}
