/* local_op.c - the near field of the residual stress operator (local_op.h; theory.md §9.7). */
#include "plastic/local_op.h"

#include <string.h>

#include "core/alloc.h"
#include "plastic/eigen_internal.h"

/* Columns of probe grid on each side of the stencil along a free axis: the probe's window is
 * the probe grid, and its surface correction S3 differs from the large window's by the traction
 * of S1 + S2 outside it, which decays as the cube of the distance (eigen_op.h); 8 columns put
 * that edge 8 + reach cells from the source. Along a periodic axis the probe's period is the
 * grid's up to PROBE_PERIOD_MAX columns (longer periods: that many; the image sums then differ
 * from the grid's by the smeared rest of the longer period, a uniform stress of order 1 /
 * PROBE_PERIOD_MAX^2 of the layer limit). Either is a preconditioner error only: the global
 * application settles the fixed point (loop.c). */
#define PROBE_PAD 4
#define PROBE_PERIOD_MAX 32

struct mc_plastic_local {
    int nz, rx, ry, rz;
    int nwx, nwy;       /* the volume's window */
    int px, py;         /* 1: the axis is periodic (the window spans it: wrap) */
    double *b;          /* blocks [k][ks - k + rz][dj + ry][di + rx][c][q], per G */
};

static size_t block_index(const mc_plastic_local *op, int k, int kk, int dj, int di)
{
    const size_t wx = 2 * (size_t)op->rx + 1, wy = 2 * (size_t)op->ry + 1,
                 wz = 2 * (size_t)op->rz + 1;
    return ((((size_t)k * wz + (size_t)kk) * wy + (size_t)(dj + op->ry)) * wx +
            (size_t)(di + op->rx)) * 36;
}

/* Probe size and reach along one axis of n columns (periodic or not). */
static void axis_probe(int n, int periodic, int reach, int *np, int *r)
{
    if (periodic) {
        *np = n < PROBE_PERIOD_MAX ? n : PROBE_PERIOD_MAX;
        *r = reach < (*np - 1) / 2 ? reach : (*np - 1) / 2;
    } else {
        *r = reach;
        *np = 2 * reach + 1 + 2 * PROBE_PAD;
    }
}

int mc_plastic_local_create(const mc_grid *g, const mc_eigen_volume *v, double nu, int reach,
                            int reach_z, mc_plastic_local **out, mc_error *err)
{
    *out = NULL;
    if (reach < 0 || reach_z < 0 || v->nz < 1 || v->nx < 1 || v->ny < 1)
        return mc_fail(err, MC_ERR_INPUT, "plastic near field: reach %d, %d; volume %d x %d x %d",
                       reach, reach_z, v->nx, v->ny, v->nz);
    mc_plastic_local *op = mc_calloc(1, sizeof *op);
    if (!op)
        return mc_fail(err, MC_ERR_NOMEM, "plastic near field: out of memory");
    op->nz = v->nz;
    op->rz = reach_z < v->nz - 1 ? reach_z : v->nz - 1;
    op->nwx = v->nx;
    op->nwy = v->ny;
    op->px = g->periodic_x;
    op->py = g->periodic_y;
    mc_grid pg = *g;
    axis_probe(g->nx, g->periodic_x, reach, &pg.nx, &op->rx);
    axis_probe(g->ny, g->periodic_y, reach, &pg.ny, &op->ry);
    if (g->periodic_y && g->ny == 1) /* bars along y: one column */
        pg.ny = 1, op->ry = 0;
    if (!g->periodic_x && op->rx > v->nx - 1) /* nothing beyond the window */
        op->rx = v->nx - 1;
    if (!g->periodic_y && op->ry > v->ny - 1)
        op->ry = v->ny - 1;
    mc_eigen_volume pv = *v; /* the same layers and evaluation under the whole probe grid */
    pv.i0 = pv.j0 = 0;
    pv.nx = pg.nx;
    pv.ny = pg.ny;
    const size_t wx = 2 * (size_t)op->rx + 1, wy = 2 * (size_t)op->ry + 1,
                 wz = 2 * (size_t)op->rz + 1;
    const size_t nb = (size_t)op->nz * wz * wy * wx * 36;
    const size_t nvp = (size_t)pg.nx * pg.ny * (size_t)v->nz;
    mc_eigen_stress *probe = NULL;
    double *field = NULL;
    int rc = MC_OK;
    if (!(op->b = mc_zeros(nb)) || !(field = mc_zeros(12 * nvp)))
        rc = mc_fail(err, MC_ERR_NOMEM, "plastic near field: out of memory");
    if (rc == MC_OK)
        rc = mc_eig_stress_create_replicated(&pg, &pv, nu, &probe, err); /* no collectives */
    if (rc != MC_OK) {
        mc_free(field);
        mc_plastic_local_destroy(&op);
        return rc;
    }
    const double *e[6];
    double *s[6];
    for (int c = 0; c < 6; c++) {
        e[c] = field + (size_t)c * nvp;
        s[c] = field + (size_t)(6 + c) * nvp;
    }
    const int cx = pg.nx / 2, cy = pg.ny / 2;
    for (int ks = 0; ks < v->nz; ks++)
        for (int q = 0; q < 6; q++) {
            double *eq = field + (size_t)q * nvp;
            const size_t src = ((size_t)ks * pg.ny + (size_t)cy) * pg.nx + (size_t)cx;
            eq[src] = 1.0;
            mc_eigen_stress_apply(probe, e, 1.0, s);
            eq[src] = 0.0;
            const int k0 = ks - op->rz < 0 ? 0 : ks - op->rz;
            const int k1 = ks + op->rz > v->nz - 1 ? v->nz - 1 : ks + op->rz;
            for (int k = k0; k <= k1; k++)
                for (int dj = -op->ry; dj <= op->ry; dj++)
                    for (int di = -op->rx; di <= op->rx; di++) {
                        const size_t at = ((size_t)k * pg.ny + (size_t)(cy + dj)) * pg.nx +
                                          (size_t)(cx + di);
                        double *blk = op->b + block_index(op, k, ks - k + op->rz, dj, di);
                        for (int c = 0; c < 6; c++)
                            blk[c * 6 + q] = s[c][at];
                    }
        }
    mc_eigen_stress_destroy(&probe);
    mc_free(field);
    *out = op;
    return MC_OK;
}

void mc_plastic_local_apply(const mc_plastic_local *op, const double *d, const double *d0,
                            const int *active, double G, int k, long j, long i, double sig[6])
{
    const long nwx = op->nwx, nwy = op->nwy;
    const size_t nvol = (size_t)op->nz * (size_t)nwx * (size_t)nwy;
    double acc[6] = {0, 0, 0, 0, 0, 0};
    const int k0 = k - op->rz < 0 ? 0 : k - op->rz;
    const int k1 = k + op->rz > op->nz - 1 ? op->nz - 1 : k + op->rz;
    for (int ks = k0; ks <= k1; ks++)
        for (int dj = -op->ry; dj <= op->ry; dj++) {
            long js = j - dj;
            if (op->py)
                js = (js % nwy + nwy) % nwy;
            else if (js < 0 || js >= nwy)
                continue;
            for (int di = -op->rx; di <= op->rx; di++) {
                long is = i - di;
                if (op->px)
                    is = (is % nwx + nwx) % nwx;
                else if (is < 0 || is >= nwx)
                    continue;
                const size_t s = ((size_t)ks * (size_t)nwy + (size_t)js) * (size_t)nwx +
                                 (size_t)is;
                const int a = active[s];
                if (a < 0)
                    continue;
                double dl[6];
                int any = 0;
                for (int q = 0; q < 6; q++) {
                    dl[q] = d[(size_t)q * nvol + s] - d0[6 * (size_t)a + (size_t)q];
                    any |= dl[q] != 0.0;
                }
                if (!any)
                    continue;
                const double *blk = op->b + block_index(op, k, ks - k + op->rz, dj, di);
                for (int c = 0; c < 6; c++) {
                    double t = 0;
                    for (int q = 0; q < 6; q++)
                        t += blk[c * 6 + q] * dl[q];
                    acc[c] += t;
                }
            }
        }
    for (int c = 0; c < 6; c++)
        sig[c] = G * acc[c];
}

void mc_plastic_local_scatter(const mc_plastic_local *op, const double r[6], const int *active,
                              int k, long j, long i, double *corr)
{
    const long nwx = op->nwx, nwy = op->nwy;
    const int k0 = k - op->rz < 0 ? 0 : k - op->rz;
    const int k1 = k + op->rz > op->nz - 1 ? op->nz - 1 : k + op->rz;
    for (int kt = k0; kt <= k1; kt++)
        for (int dj = -op->ry; dj <= op->ry; dj++) {
            long jt = j + dj;
            if (op->py)
                jt = (jt % nwy + nwy) % nwy;
            else if (jt < 0 || jt >= nwy)
                continue;
            for (int di = -op->rx; di <= op->rx; di++) {
                long it = i + di;
                if (op->px)
                    it = (it % nwx + nwx) % nwx;
                else if (it < 0 || it >= nwx)
                    continue;
                const size_t t = ((size_t)kt * (size_t)nwy + (size_t)jt) * (size_t)nwx +
                                 (size_t)it;
                const int a = active[t];
                if (a < 0)
                    continue;
                const double *blk = op->b + block_index(op, kt, k - kt + op->rz, dj, di);
                double *out = corr + 6 * (size_t)a;
                for (int c = 0; c < 6; c++) {
                    double acc = 0;
                    for (int q = 0; q < 6; q++)
                        acc += blk[c * 6 + q] * r[q];
                    out[c] += acc;
                }
            }
        }
}

size_t mc_plastic_local_bytes(const mc_plastic_local *op)
{
    if (!op)
        return 0;
    return sizeof *op + (size_t)op->nz * (2 * (size_t)op->rz + 1) * (2 * (size_t)op->ry + 1) *
                            (2 * (size_t)op->rx + 1) * 36 * sizeof(double);
}

void mc_plastic_local_destroy(mc_plastic_local **op)
{
    if (!op || !*op)
        return;
    mc_free((*op)->b);
    mc_free(*op);
    *op = NULL;
}
