/* roughness_profile.c - ISO 4287 profile parameters and the ISO 13565-2 Rk family
 * (see roughness.h; theory.md §13.3-§13.4). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "surface/roughness_internal.h"

static int cmp_desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

void mc_roughness_material_ratio(const double *h, size_t n, double *work, mc_material_ratio *out)
{
    out->k = out->pk = out->vk = 0.0;
    out->mr1 = 0.0;
    out->mr2 = 100.0;
    out->c0 = out->c100 = n == 1 ? h[0] : 0.0;
    if (n == 1)
        work[0] = h[0];
    if (n < 2)
        return;
    memcpy(work, h, sizeof(double) * n);
    qsort(work, n, sizeof(double), cmp_desc); /* the material-ratio curve, highest first */
    size_t m = (size_t)llround(0.4 * (double)n);
    if (m < 1)
        m = 1;
    size_t best = 0;
    double best_drop = INFINITY;
    for (size_t k = 0; k + m < n; k++) { /* the 40 % secant of least |slope| */
        double drop = work[k] - work[k + m];
        if (drop < best_drop) {
            best_drop = drop;
            best = k;
        }
    }
    double slope = -best_drop / (100.0 * (double)m / (double)n); /* height per % */
    double mr_best = 100.0 * ((double)best + 0.5) / (double)n;
    double c0 = work[best] - slope * mr_best, c100 = c0 + 100.0 * slope;
    size_t above = 0, atleast = 0;
    double a1 = 0, a2 = 0;
    for (size_t k = 0; k < n; k++) {
        if (work[k] > c0) {
            above++;
            a1 += work[k] - c0;
        }
        if (work[k] >= c100)
            atleast++;
        else
            a2 += c100 - work[k];
    }
    double pct = 100.0 / (double)n;
    out->k = c0 - c100;
    out->c0 = c0;
    out->c100 = c100;
    out->mr1 = above * pct;
    out->mr2 = atleast * pct;
    out->pk = above ? 2.0 * a1 * pct / out->mr1 : 0.0;
    out->vk = atleast < n ? 2.0 * a2 * pct / (100.0 - out->mr2) : 0.0;
}

/* Running sums of one row's parameters. */
typedef struct {
    double ra, rq, rsk, rku, rz, rp, rv, rt, rk, rpk, rvk, mr1, mr2;
} row_sums;

/* Parameters of one roughness profile r over [i0, i1) cut into ns sampling lengths; returns 0
 * when the range holds no valid point. work: i1 - i0 doubles. */
static int row_parameters(const double *r, const unsigned char *v, int i0, int i1, int ns,
                          double *work, row_sums *acc)
{
    size_t cnt = 0;
    double s1 = 0, s2 = 0, s3 = 0, s4 = 0, hi = -INFINITY, lo = INFINITY;
    for (int i = i0; i < i1; i++) {
        if (v && !v[i])
            continue;
        double x = r[i], x2 = x * x;
        work[cnt++] = x;
        s1 += fabs(x);
        s2 += x2;
        s3 += x2 * x;
        s4 += x2 * x2;
        hi = fmax(hi, x);
        lo = fmin(lo, x);
    }
    if (cnt == 0)
        return 0;
    double rq = sqrt(s2 / cnt);
    acc->ra += s1 / cnt;
    acc->rq += rq;
    acc->rsk += rq > 0 ? s3 / cnt / (rq * rq * rq) : 0.0;
    acc->rku += rq > 0 ? s4 / cnt / (rq * rq * rq * rq) : 0.0;
    acc->rt += hi - lo;
    /* Rp, Rv: mean over the sampling lengths holding a valid point */
    long ne = i1 - i0;
    double sp = 0, sv = 0;
    int used = 0;
    for (int s = 0; s < ns; s++) {
        int a = i0 + (int)(ne * s / ns), b = i0 + (int)(ne * (s + 1) / ns);
        double p = -INFINITY, q = INFINITY;
        for (int i = a; i < b; i++)
            if (!v || v[i]) {
                p = fmax(p, r[i]);
                q = fmin(q, r[i]);
            }
        if (p >= q) {
            sp += p;
            sv -= q;
            used++;
        }
    }
    acc->rp += sp / used; /* used >= 1: some segment holds the valid point found above */
    acc->rv += sv / used;
    acc->rz += (sp + sv) / used;
    mc_material_ratio mr;
    mc_roughness_material_ratio(work, cnt, work + cnt, &mr);
    acc->rk += mr.k;
    acc->rpk += mr.pk;
    acc->rvk += mr.vk;
    acc->mr1 += mr.mr1;
    acc->mr2 += mr.mr2;
    return 1;
}

int mc_rough_profiles(const double *z, const unsigned char *valid, int nx, int ny, double dx,
                      double lc, int periodic, int filter, mc_roughness_params *out,
                      mc_error *err)
{
    size_t n = (size_t)nx * ny;
    double *r = mc_malloc(sizeof(double) * n), *work = mc_malloc(sizeof(double) * 2 * nx);
    if (!r || !work) {
        mc_free(r);
        mc_free(work);
        return mc_fail(err, MC_ERR_NOMEM, "roughness: out of memory for %d x %d points", nx, ny);
    }
    int i0 = 0, i1 = nx;
    if (filter) {
        int rc = mc_roughness_mean_line(z, valid, nx, ny, dx, lc, periodic, r, err);
        if (rc) {
            mc_free(r);
            mc_free(work);
            return rc;
        }
        for (size_t k = 0; k < n; k++)
            r[k] = (valid && !valid[k]) ? 0.0 : z[k] - r[k];
        if (!periodic) { /* ends without the whole kernel are discarded (ISO 16610-21) */
            int K = mc_roughness_filter_halfwidth(dx, lc);
            if (2 * K < nx) {
                i0 = K;
                i1 = nx - K;
            }
        }
    } else {
        for (int j = 0; j < ny; j++) { /* the row's mean line is its mean */
            const double *zr = z + (size_t)j * nx;
            const unsigned char *vr = valid ? valid + (size_t)j * nx : NULL;
            double s = 0;
            int c = 0;
            for (int i = 0; i < nx; i++)
                if (!vr || vr[i]) {
                    s += zr[i];
                    c++;
                }
            double mean = c ? s / c : 0.0;
            for (int i = 0; i < nx; i++)
                r[(size_t)j * nx + i] = (!vr || vr[i]) ? zr[i] - mean : 0.0;
        }
    }
    double le = (i1 - i0) * dx;
    int ns = (int)floor(le / lc + 1e-9);
    if (ns < 1)
        ns = 1;
    if (ns > i1 - i0)
        ns = i1 - i0;
    row_sums acc;
    memset(&acc, 0, sizeof acc);
    int rows = 0;
    for (int j = 0; j < ny; j++)
        rows += row_parameters(r + (size_t)j * nx, valid ? valid + (size_t)j * nx : NULL, i0,
                               i1, ns, work, &acc);
    double inv = rows ? 1.0 / rows : 0.0;
    out->Ra = acc.ra * inv;
    out->Rq = acc.rq * inv;
    out->Rsk = acc.rsk * inv;
    out->Rku = acc.rku * inv;
    out->Rp = acc.rp * inv;
    out->Rv = acc.rv * inv;
    out->Rz = acc.rz * inv;
    out->Rt = acc.rt * inv;
    out->Rk = acc.rk * inv;
    out->Rpk = acc.rpk * inv;
    out->Rvk = acc.rvk * inv;
    out->Mr1 = acc.mr1 * inv;
    out->Mr2 = rows ? acc.mr2 * inv : 100.0;
    out->evaluation_length = le;
    out->n_sampling = ns;
    out->rows = rows;
    out->filtered = filter != 0;
    mc_free(r);
    mc_free(work);
    return MC_OK;
}
