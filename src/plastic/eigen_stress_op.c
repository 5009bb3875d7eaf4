/* eigen_stress_op.c - eigenstrain -> residual stress at the cuboid centres: the object, its
 * kernel tables and the direct backend (see eigen_op.h; Chiu 1977, 1978; Jacq et al. 2002;
 * theory.md §8.2). The fft backend is eigen_stress_fft.c.
 *
 * With M_ic(d, m) the infinite-space kernel (row i, column c, divided by 2G) of a cuboid seen at
 * the lateral offset d (cells, field minus source) and depth offset m dz, the stress of layer k
 * is, per unit 2G,
 *   sigma_i(k, x) = sum_{k',c,s} [M_ic(x - s, k - k') + r_c M_ic(x - s, k + k' + 1)] eps_c(k', s)
 *                 + sum_s L_ki(x - s) p3(s) / 2G,
 *   p3(s) / 2G   = sum_{k', c, s'} P_k'c(s - s') eps_c(k', s'),
 * r_c = -1 for the columns yz, xz (the mirror carries R eps R), M at negative m by its parity in
 * z, P = sigma_zz^(1+2)(z = 0) of source layer k', L = Love's rectangle stresses at the depth of
 * layer k. The sums over s run over the window only (p3 lives on the window).
 */
#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "kernels/eigen.h"
#include "kernels/kernel.h"
#include "plastic/eigen_internal.h"
#include "plastic/eigen_spectral_op.h"
#include "stress/stress.h"

/* ---- kernel tables --------------------------------------------------------------------------- */

typedef struct {
    double dx, dy, dz, nu;
    int k;     /* depth offset m (S1), fine layer of the observation (L) or first fine layer of
                * the source (P) */
    int k2;    /* P: the fine layer below the source's last (k + 1 when uniform) */
    int line;  /* bars along y (mc_eig_line): the bar kernels, only dj = 0 is used */
    int layer; /* periodic grids: the limit of the image sum is the layer (x periodic), else the
                * bar (y alone periodic; theory.md §8.6) */
    int average; /* S1 averaged over the observation cell near the source (s1_cell) */
} table_ctx;

/* the 21 stored pairs of the infinite-space kernel at depth offset m dz */
/* 3-point Gauss-Legendre on a cell of unit width centred on 0: nodes +-sqrt(3/5)/2, 0 and their
 * weights (the cell averages of theory.md §8.7) */
static const double GAUSS3_X[3] = {-0.38729833462074170, 0.0, 0.38729833462074170};
static const double GAUSS3_W[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

static void s1_point(const table_ctx *t, double x, double y, double z, double S[6][6])
{
    if (t->line)
        mc_eigen_stress1_bar(x, z, 0.5 * t->dx, 0.0, t->dz, t->nu, S);
    else
        mc_eigen_stress1(x, y, z, 0.5 * t->dx, 0.5 * t->dy, 0.0, t->dz, t->nu, S);
}

/* The infinite-space kernel seen by the observation cell at (di, dj) cells and depth offset k dz:
 * its value at the cell centre, or (MC_EIG_CELL_AVERAGE, the default) its average over the cell
 * by 3-point Gauss-Legendre per axis while the cell is within MC_EIG_AVERAGE_REACH cells of the
 * source (theory.md §8.7: the average makes the operator Galerkin-like and removes the unstable
 * checkerboard modes of the centre values; farther out the field is smooth and centre and
 * average differ by O((h / distance)^2) of a kernel falling like distance^-3). */
/* whether s1_cell averages the entry (di, dj) of depth offset t->k */
static int s1_averaged(const table_ctx *t, int di, int dj)
{
    const double x = di * t->dx, y = dj * t->dy;
    const double reach = MC_EIG_AVERAGE_REACH * fmax(t->dx, t->line ? t->dx : t->dy);
    return t->average && fabs(x) <= reach && fabs(y) <= reach && t->k * t->dz <= reach;
}

static void s1_cell(const table_ctx *t, int di, int dj, double S[6][6])
{
    const double x = di * t->dx, y = dj * t->dy, z = (t->k + 0.5) * t->dz;
    if (!s1_averaged(t, di, dj)) {
        s1_point(t, x, y, z, S);
        return;
    }
    const double *gp = GAUSS3_X, *gw = GAUSS3_W;
    memset(S, 0, 36 * sizeof S[0][0]);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < (t->line ? 1 : 3); b++)
            for (int c = 0; c < 3; c++) {
                double T[6][6];
                const double w = gw[a] * (t->line ? 1.0 : gw[b]) * gw[c];
                s1_point(t, x + gp[a] * t->dx, t->line ? 0.0 : y + gp[b] * t->dy,
                         z + gp[c] * t->dz, T);
                for (int i = 0; i < 6; i++)
                    for (int e = 0; e < 6; e++)
                        S[i][e] += w * T[i][e];
            }
}

static void s1_kernel(int di, int dj, const void *ctx, double *out)
{
    double S[6][6];
    s1_cell(ctx, di, dj, S);
    for (int i = 0; i < 6; i++)
        for (int c = i; c < 6; c++)
            out[mc_eig_sym(i, c)] = S[i][c];
}

static void p3_kernel(int di, int dj, const void *ctx, double *out)
{
    const table_ctx *t = ctx;
    if (t->line) {
        mc_eigen_surface_szz12_bar(di * t->dx, 0.5 * t->dx, t->k * t->dz, t->k2 * t->dz,
                                   t->nu, out);
        return;
    }
    mc_eigen_surface_szz12(di * t->dx, dj * t->dy, 0.5 * t->dx, 0.5 * t->dy, t->k * t->dz,
                           t->k2 * t->dz, t->nu, out);
}

/* the limits of the image sums on periodic grids (mc_eig_fill_images) */
static void s1_limit(int di, int dj, const void *ctx, double *out)
{
    (void)dj;
    const table_ctx *t = ctx;
    double S[6][6];
    if (t->layer) { /* constant inside the layer, 0 outside: the cell average is the centre value */
        mc_eigen_stress1_layer((t->k + 0.5) * t->dz, 0.0, t->dz, t->nu, S);
    } else { /* the sum of the (averaged) cuboid kernel along y: the (averaged) bar */
        table_ctx bar = *t;
        bar.line = 1;
        s1_cell(&bar, di, 0, S);
    }
    for (int i = 0; i < 6; i++)
        for (int c = i; c < 6; c++)
            out[mc_eig_sym(i, c)] = S[i][c];
}

static void p3_limit(int di, int dj, const void *ctx, double *out)
{
    (void)dj;
    const table_ctx *t = ctx;
    if (t->layer) { /* a laterally uniform layer leaves no surface traction */
        memset(out, 0, 6 * sizeof *out);
        return;
    }
    mc_eigen_surface_szz12_bar(di * t->dx, 0.5 * t->dx, t->k * t->dz, t->k2 * t->dz, t->nu, out);
}

/* the image sums of a periodic grid, or the plain table */
static void fill_table(const mc_eigen_stress *op, int k, int k2, int ncomp, const int *par,
                       mc_eig_kfn fn, mc_eig_kfn limit, double *const *q)
{
    const mc_grid *g = &op->g;
    const table_ctx ctx = {g->dx, g->dy, op->v.dz, op->nu, k, k2, mc_eig_line(g), mc_eig_per_x(g),
                           op->v.stress_points == MC_EIG_CELL_AVERAGE};
    if (!mc_eig_periodic(g)) {
        mc_eig_fill(op->qx, op->qy, op->v.nx, op->v.ny, ncomp, par, fn, &ctx, q);
        return;
    }
    const int px = mc_eig_per_x(g), py = mc_eig_per_y(g);
    const int period[2] = {px ? g->nx : 0, py ? g->ny : 0};
    const int images[2] = {px ? mc_eig_images(g->nx) : 0, py ? mc_eig_images(g->ny) : 0};
    mc_eig_fill_images(op->qx, op->qy, px ? g->nx / 2 + 1 : op->v.nx,
                       py ? g->ny / 2 + 1 : op->v.ny, ncomp, par, fn, limit, &ctx, period, images,
                       q);
}

/* Love's stresses at the observation cell (di, dj) of layer k per unit pressure on one surface
 * cell: the centre value, or the cell average near the loaded cell as s1_cell does (the S3 part
 * of the residual stress is then evaluated like S1 + S2, theory.md §8.7). */
static void love_kernel(int di, int dj, const void *ctx, double *out)
{
    const table_ctx *t = ctx;
    const double x = di * t->dx, y = dj * t->dy, z = (t->k + 0.5) * t->dz;
    const double reach = MC_EIG_AVERAGE_REACH * fmax(t->dx, t->line ? t->dx : t->dy);
    if (!t->average || fabs(x) > reach || fabs(y) > reach || t->k * t->dz > reach) {
        if (t->line) /* a strip of pressure along y */
            mc_strip_stress_p(x, z, 0.5 * t->dx, t->nu, out);
        else
            mc_rect_stress_p(x, y, z, 0.5 * t->dx, 0.5 * t->dy, t->nu, out);
        return;
    }
    const double *gp = GAUSS3_X, *gw = GAUSS3_W;
    for (int i = 0; i < 6; i++)
        out[i] = 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < (t->line ? 1 : 3); b++)
            for (int c = 0; c < 3; c++) {
                double v[6];
                const double w = gw[a] * (t->line ? 1.0 : gw[b]) * gw[c];
                if (t->line)
                    mc_strip_stress_p(x + gp[a] * t->dx, z + gp[c] * t->dz, 0.5 * t->dx, t->nu, v);
                else
                    mc_rect_stress_p(x + gp[a] * t->dx, y + gp[b] * t->dy, z + gp[c] * t->dz,
                                     0.5 * t->dx, 0.5 * t->dy, t->nu, v);
                for (int i = 0; i < 6; i++)
                    out[i] += w * v[i];
            }
}

int mc_eig_pair_par(int i, int c)
{
    return (mc_eig_odd_x(i) ^ mc_eig_odd_x(c)) | (mc_eig_odd_y(i) ^ mc_eig_odd_y(c)) << 1;
}

/* ---- the corner lattice (eigen_internal.h mc_eig_corners; theory.md §8.2) ------------------- */

static int lattice_applies(const mc_eigen_stress *op)
{
    return !mc_eig_periodic(&op->g) && !mc_eig_line(&op->g);
}

size_t mc_eig_corners_bytes(const mc_eigen_stress *op)
{
    if (!lattice_applies(op))
        return 0;
    return 2 * ((size_t)op->v.nx + 1) * ((size_t)op->v.ny + 1) * MC_EIGEN_NH * sizeof(double);
}

int mc_eig_corners_init(const mc_eigen_stress *op, mc_eig_corners *cc, mc_error *err)
{
    memset(cc, 0, sizeof *cc);
    cc->key[0] = cc->key[1] = LONG_MIN;
    if (!lattice_applies(op))
        return MC_OK;
    cc->n1x = op->v.nx + 1;
    cc->n1y = op->v.ny + 1;
    const size_t n = (size_t)cc->n1x * cc->n1y * MC_EIGEN_NH;
    if (!(cc->h[0] = mc_malloc(n * sizeof(double))) || !(cc->h[1] = mc_malloc(n * sizeof(double)))) {
        mc_eig_corners_free(cc);
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for the corner lattice");
    }
    return MC_OK;
}

void mc_eig_corners_free(mc_eig_corners *cc)
{
    mc_free(cc->h[0]);
    mc_free(cc->h[1]);
    memset(cc, 0, sizeof *cc);
}

/* The plane of corner functions at depth offset az (identified by key), kept or computed into
 * the slot that does not hold the plane `keep`. */
static const double *corner_plane(const mc_eigen_stress *op, mc_eig_corners *cc, long key,
                                  double az, long keep)
{
    for (int s = 0; s < 2; s++)
        if (cc->key[s] == key)
            return cc->h[s];
    const int s = cc->key[0] == keep ? 1 : 0;
    double *h = cc->h[s];
    const double dx = op->g.dx, dy = op->g.dy, hx = 0.5 * dx, hy = 0.5 * dy;
    const int n1x = cc->n1x, n1y = cc->n1y;
#pragma omp parallel for schedule(static)
    for (int J = 0; J < n1y; J++)
        for (int I = 0; I < n1x; I++)
            mc_eigen_corner_h(I * dx - hx, J * dy - hy, az,
                              h + ((size_t)J * n1x + I) * MC_EIGEN_NH);
    cc->key[s] = key;
    return h;
}

typedef struct {
    table_ctx t;
    const double *lo, *hi; /* the planes of the cuboid's lower and upper z corners */
    int n1x;
    int inside; /* the field point of entry (0, 0) is inside the cuboid */
} lattice_ctx;

/* The corner sum of entry (di, dj): cuboid_H's corners and signs (+1 at each lower bound: the
 * lattice point di + 1 along x, dj + 1 along y, the plane lo in z), read from the planes. */
static void lattice_sum(const lattice_ctx *c, int di, int dj, double sum[MC_EIGEN_NH])
{
    for (int n = 0; n < MC_EIGEN_NH; n++)
        sum[n] = 0.0;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                const double *h = (k ? c->hi : c->lo) +
                                  ((size_t)(dj + 1 - j) * c->n1x + (size_t)(di + 1 - i)) *
                                      MC_EIGEN_NH;
                const double s = ((i + j + k) & 1) ? -1.0 : 1.0;
                for (int n = 0; n < MC_EIGEN_NH; n++)
                    sum[n] += s * h[n];
            }
}

static void s1_lattice_kernel(int di, int dj, const void *ctx, double *out)
{
    const lattice_ctx *c = ctx;
    if (s1_averaged(&c->t, di, dj)) {
        s1_kernel(di, dj, &c->t, out);
        return;
    }
    double sum[MC_EIGEN_NH], S[6][6];
    lattice_sum(c, di, dj, sum);
    mc_eigen_stress1_sum(sum, c->t.nu, c->inside && di == 0 && dj == 0, S);
    for (int i = 0; i < 6; i++)
        for (int e = i; e < 6; e++)
            out[mc_eig_sym(i, e)] = S[i][e];
}

static void p3_lattice_kernel(int di, int dj, const void *ctx, double *out)
{
    const lattice_ctx *c = ctx;
    double sum[MC_EIGEN_NH], S[6][6];
    lattice_sum(c, di, dj, sum);
    mc_eigen_stress1_sum(sum, c->t.nu, c->inside && di == 0 && dj == 0, S);
    for (int e = 0; e < 6; e++)
        out[e] = 2.0 * S[2][e]; /* as mc_eigen_surface_szz12 */
}

/* The lattice context of one table: the field point at depth zf over the cuboid [z1, z2] (fine
 * layers; the corner depths zf - z1 and zf - z2 as the per-entry kernels form them, keyed by
 * family and layer index). */
static lattice_ctx lattice_at(const mc_eigen_stress *op, mc_eig_corners *cc, const table_ctx *t,
                              long key_lo, double az_lo, long key_hi, double az_hi, int inside)
{
    lattice_ctx c = {*t, NULL, NULL, cc->n1x, inside};
    c.lo = corner_plane(op, cc, key_lo, az_lo, key_hi);
    c.hi = corner_plane(op, cc, key_hi, az_hi, key_lo);
    return c;
}

void mc_eig_s1_fill(const mc_eigen_stress *op, int m, mc_eig_corners *cc,
                    double *const q[MC_EIG_NSYM])
{
    int par[MC_EIG_NSYM];
    for (int i = 0; i < 6; i++)
        for (int c = i; c < 6; c++)
            par[mc_eig_sym(i, c)] = mc_eig_pair_par(i, c);
    if (cc && cc->h[0] && lattice_applies(op)) {
        /* the field point at (m + 1/2) dz over the fine cuboid [0, dz]: corner depths
         * zf - 0 and zf - dz; the plane of corner depth (t - 1/2) dz has key 2 t, computed as
         * (t + 1/2) dz - dz (the upper corner of offset t, the lower one of t - 1) */
        const double dz = op->v.dz;
        const table_ctx t = {op->g.dx, op->g.dy, dz, op->nu, m, m + 1, 0, 0,
                             op->v.stress_points == MC_EIG_CELL_AVERAGE};
        lattice_ctx c = lattice_at(op, cc, &t, 2L * (m + 1), (m + 1.5) * dz - dz, 2L * m,
                                   (m + 0.5) * dz - dz, m == 0);
        mc_eig_fill(op->qx, op->qy, op->v.nx, op->v.ny, MC_EIG_NSYM, par, s1_lattice_kernel, &c,
                    q);
    } else {
        fill_table(op, m, m + 1, MC_EIG_NSYM, par, s1_kernel, s1_limit, q);
    }
    /* pairs odd in z vanish at depth offset 0 (the fft backend's DST-I ignores that plane) */
    for (int i = 0; m == 0 && i < 6; i++)
        for (int c = i; c < 6; c++)
            if (mc_eig_odd_z(i) ^ mc_eig_odd_z(c))
                memset(q[mc_eig_sym(i, c)], 0, op->qlen * sizeof(double));
}

void mc_eig_p3_fill(const mc_eigen_stress *op, int k, mc_eig_corners *cc, double *const q[6])
{
    int par[6];
    for (int c = 0; c < 6; c++)
        par[c] = mc_eig_par(c);
    /* a graded layer: one cuboid of its whole thickness (theory.md §8.8) */
    const int f0 = op->first[k], f1 = op->first[k + 1];
    if (cc && cc->h[0] && lattice_applies(op)) {
        /* the field point on the surface over [f0 dz, f1 dz]: corner depths 0 - f dz, key
         * 2 f + 1 */
        const double dz = op->v.dz;
        const table_ctx t = {op->g.dx, op->g.dy, dz, op->nu, f0, f1, 0, 0, 0};
        lattice_ctx c = lattice_at(op, cc, &t, 2L * f0 + 1, 0.0 - f0 * dz, 2L * f1 + 1,
                                   0.0 - f1 * dz, f0 == 0);
        mc_eig_fill(op->qx, op->qy, op->v.nx, op->v.ny, 6, par, p3_lattice_kernel, &c, q);
        return;
    }
    fill_table(op, f0, f1, 6, par, p3_kernel, p3_limit, q);
}

void mc_eig_love_fill(const mc_eigen_stress *op, int k, double *const q[6])
{
    int par[6];
    for (int c = 0; c < 6; c++)
        par[c] = mc_eig_par(c);
    /* at the centre of layer k: the centre of its middle fine layer */
    const table_ctx ctx = {op->g.dx, op->g.dy, op->v.dz, op->nu, op->centre[k], op->centre[k] + 1,
                           mc_eig_line(&op->g), 0, op->v.stress_points == MC_EIG_CELL_AVERAGE};
    mc_eig_fill(op->qx, op->qy, op->v.nx, op->v.ny, 6, par, love_kernel, &ctx, q);
}

/* The cell average of Love's stresses on a periodic grid: the stress module's periodic table
 * holds centre values; near the loaded cell (love_kernel's reach) the average differs, so the
 * difference average - centre of every image of an entry within the reach is added (beyond it
 * the two agree to O((h / d)^2), as on free grids). */
static void love_average_periodic(mc_eigen_stress *op, int k, int ux, int uy)
{
    const mc_grid *g = &op->g;
    const int kf = op->centre[k]; /* the fine layer of the evaluation */
    const table_ctx avg = {g->dx, g->dy, op->v.dz, op->nu, kf, kf + 1, mc_eig_line(g), 0, 1};
    table_ctx ctr = avg;
    ctr.average = 0;
    const double reach = MC_EIG_AVERAGE_REACH * fmax(g->dx, mc_eig_line(g) ? g->dx : g->dy);
    if (kf * op->v.dz > reach)
        return;
    const int rx = (int)(reach / g->dx) + 1, ry = mc_eig_line(g) ? 0 : (int)(reach / g->dy) + 1;
    const int px = mc_eig_per_x(g), py = mc_eig_per_y(g);
    for (int lj = -ry; lj <= ry; lj++)
        for (int li = -rx; li <= rx; li++) {
            double a[6], b[6];
            love_kernel(li, lj, &avg, a);
            love_kernel(li, lj, &ctr, b);
            /* the quadrant entry this offset lands on, and the parity sign there */
            int wi = mc_eig_wrap(li, g->nx, px), wj = mc_eig_wrap(lj, g->ny, py);
            if (px && 2 * wi == -g->nx) /* -n/2 and n/2 are one residue of an even period */
                wi = -wi;
            if (py && 2 * wj == -g->ny)
                wj = -wj;
            const int di = wi < 0 ? -wi : wi, dj = wj < 0 ? -wj : wj;
            if (di >= ux || dj >= uy)
                continue;
            for (int c = 0; c < 6; c++) {
                const int ox = mc_eig_odd_x(c), oy = mc_eig_odd_y(c);
                if ((ox && (di == 0 || (px && 2 * di == g->nx))) ||
                    (oy && (dj == 0 || (py && 2 * dj == g->ny))))
                    continue;
                /* an offset congruent to a negative one belongs to the mirror entry, which the
                 * quadrant's parity derives from this one (the correction has the kernel's
                 * parity: the Gauss points are symmetric) */
                const double w = (wi < 0 || wj < 0) ? 0.0 : 1.0;
                op->love[(size_t)(k * 6 + c) * op->qlen + (size_t)dj * op->qx + di] +=
                    w * (a[c] - b[c]);
            }
        }
}

/* The stress module's patch tables of load (stress/stress.h) at every layer's centre, cut to the
 * quadrants dst[(k * 6 + c) qlen] (offsets 0 .. n/2 of a periodic axis, 0 .. window - 1 of a
 * free one, zero beyond): Love's stresses on a grid with periodic axes (images and smeared
 * strips, theory.md §3.5) and the folded loads' kernels (§8.9) on any grid. The periodic tables
 * are built whole and cut; on a grid with both axes free the quadrant is built directly
 * (mc_stress_tables_quadrant, the same entries bit for bit). */
static int stress_module_tables(const mc_eigen_stress *op, int load, double *dst, mc_error *err)
{
    const mc_grid *g = &op->g;
    const mc_grid gw = {op->v.nx, op->v.ny, g->dx, g->dy, g->periodic_x, g->periodic_y};
    const int quadrant = !gw.periodic_x && !gw.periodic_y;
    const int tx = gw.periodic_x ? gw.nx : 2 * gw.nx - 1 > 1 ? 2 * gw.nx - 1 : 1;
    const int ty = gw.periodic_y ? gw.ny : 2 * gw.ny - 1 > 1 ? 2 * gw.ny - 1 : 1;
    const int ux = gw.periodic_x ? gw.nx / 2 + 1 : gw.nx, uy = gw.periodic_y ? gw.ny / 2 + 1 : gw.ny;
    mc_stress_tables *tb = NULL;
    double *tab = quadrant ? NULL : mc_malloc(6 * (size_t)tx * ty * sizeof *tab);
    int rc = quadrant || tab
                 ? mc_stress_tables_create(&gw, tx, ty, MC_STRESS_PATCH, op->nu, 0, &tb, err)
                 : mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for the stress tables");
    for (int k = 0; rc == MC_OK && k < op->v.nz; k++) {
        const double z = (op->centre[k] + 0.5) * op->v.dz;
        double *q6[6];
        for (int c = 0; c < 6; c++)
            q6[c] = dst + (size_t)(k * 6 + c) * op->qlen;
        if (quadrant) {
            rc = mc_stress_tables_quadrant(tb, load, z, op->qx, op->qy, q6, err);
            continue;
        }
        double *t6[6];
        for (int c = 0; c < 6; c++)
            t6[c] = tab + (size_t)c * tx * ty;
        rc = mc_stress_tables_build(tb, load, z, t6, err);
        for (int c = 0; rc == MC_OK && c < 6; c++) {
            /* exact zeros where the kernel is odd: offset 0, and n/2 of an even period (the
             * image sums there cancel only to round-off, which the fft path's real spectra
             * would drop and the direct sums keep) */
            const int par = mc_stress_parity(load, c), ox = par & 1, oy = par >> 1 & 1;
            for (int dj = 0; dj < op->qy; dj++)
                for (int di = 0; di < op->qx; di++) {
                    const int zero = (ox && (di == 0 || (gw.periodic_x && 2 * di == gw.nx))) ||
                                     (oy && (dj == 0 || (gw.periodic_y && 2 * dj == gw.ny)));
                    q6[c][(size_t)dj * op->qx + di] =
                        di < ux && dj < uy && !zero ? t6[c][(size_t)dj * tx + di] : 0.0;
                }
        }
    }
    mc_stress_tables_destroy(&tb);
    mc_free(tab);
    return rc ? mc_error_prefix(err, "eigen stress: ") : MC_OK;
}

/* Love's stresses on a grid with periodic axes: the stress module's periodic tables, and the
 * cell average near the source when asked. */
static int love_fill_periodic(mc_eigen_stress *op, mc_error *err)
{
    int rc = stress_module_tables(op, MC_TRACTION_P, op->love, err);
    const mc_grid *g = &op->g;
    const int ux = g->periodic_x ? op->v.nx / 2 + 1 : op->v.nx;
    const int uy = g->periodic_y ? op->v.ny / 2 + 1 : op->v.ny;
    for (int k = 0; rc == MC_OK && k < op->v.nz; k++)
        if (op->v.stress_points == MC_EIG_CELL_AVERAGE)
            love_average_periodic(op, k, ux, uy);
    return rc;
}

/* ---- direct: the O(N^2) reference ------------------------------------------------------------ */

/* Sign of a kernel of parity par (bit 0 odd in x, bit 1 odd in y) at offset (di, dj). */
static inline double par_sign(int par, int di, int dj)
{
    return (((par & 1) && di < 0) != ((par & 2) && dj < 0)) ? -1.0 : 1.0;
}

/* p3 / 2G on the window: sum over source layers and columns of P_k'c convolved with eps */
static void direct_p3(const mc_eigen_stress *op, const double *const eps[6], double *p3)
{
    const int wx = op->v.nx, wy = op->v.ny, nz = op->v.nz, qx = op->qx;
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g);
    const size_t wc = (size_t)wx * wy, ql = op->qlen;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < wy; j++)
        for (int i = 0; i < wx; i++) {
            double s = 0.0;
            for (int k = 0; k < nz; k++)
                for (int c = 0; c < 6; c++) {
                    const double *P = op->p3k + (size_t)(k * 6 + c) * ql;
                    for (int js = 0; js < wy; js++)
                        for (int is = 0; is < wx; is++) {
                            const int di = mc_eig_wrap(i - is, wx, px);
                            const int dj = mc_eig_wrap(j - js, wy, py);
                            s += par_sign(mc_eig_par(c), di, dj) *
                                 P[(size_t)(dj < 0 ? -dj : dj) * qx + (di < 0 ? -di : di)] *
                                 eps[c][k * wc + (size_t)js * wx + is];
                        }
                }
            p3[(size_t)j * wx + i] = s;
        }
}

/* The elastic stress component o of the folded loads at window cell (i, j) of layer k: the sum
 * over the grid (the window) of each load's table times the load (theory.md §8.9). */
static double direct_loads(const mc_eigen_stress *op, const double *const *loads, int k, int o,
                           int i, int j)
{
    const int wx = op->v.nx, wy = op->v.ny, qx = op->qx;
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g);
    double s = 0.0;
    for (int l = 0; l < op->nloads; l++) {
        if (!loads[l])
            continue;
        const double *K = op->lk + (size_t)((l * op->v.nz + k) * 6 + o) * op->qlen;
        const int par = op->load_par[l][o];
        for (int js = 0; js < wy; js++)
            for (int is = 0; is < wx; is++) {
                const int di = mc_eig_wrap(i - is, wx, px), dj = mc_eig_wrap(j - js, wy, py);
                s += par_sign(par, di, dj) *
                     K[(size_t)(dj < 0 ? -dj : dj) * qx + (di < 0 ? -di : di)] *
                     loads[l][(size_t)js * wx + is];
            }
    }
    return s;
}

static void direct_apply(mc_eigen_stress *op, const double *const eps[6], double G,
                         const double *const *loads, double *const sig[6])
{
    const int wx = op->v.nx, wy = op->v.ny, nz = op->v.nz, qx = op->qx;
    const int px = mc_eig_per_x(&op->g), py = mc_eig_per_y(&op->g);
    const size_t wc = (size_t)wx * wy, ql = op->qlen;
    if (eps)
        direct_p3(op, eps, op->work);
    else
        memset(op->work, 0, wc * sizeof *op->work);
    for (size_t s = 0; s < wc; s++)
        op->p3[s] = 2.0 * G * op->work[s];
#pragma omp parallel for schedule(dynamic, 1)
    for (int row = 0; row < nz * wy; row++) {
        const int k = row / wy, j = row % wy;
        for (int i = 0; i < wx; i++) {
            double acc[6] = {0.0};
            const int kf = op->centre[k]; /* the observation's fine layer */
            for (int kp = 0; kp < nz && eps; kp++) {
                const int f0 = op->first[kp], f1 = op->first[kp + 1]; /* the source's fine layers */
                for (int js = 0; js < wy; js++)
                    for (int is = 0; is < wx; is++) {
                        const int di = mc_eig_wrap(i - is, wx, px);
                        const int dj = mc_eig_wrap(j - js, wy, py);
                        const size_t at = (size_t)(dj < 0 ? -dj : dj) * qx + (di < 0 ? -di : di);
                        for (int c = 0; c < 6; c++) {
                            const double e = eps[c][kp * wc + (size_t)js * wx + is];
                            if (e == 0.0)
                                continue;
                            const double rc = mc_eig_odd_z(c) ? -1.0 : 1.0;
                            for (int o = 0; o < 6; o++) {
                                const int n = mc_eig_sym(o, c);
                                const int par = mc_eig_pair_par(o, c);
                                /* a graded source: the sum of its fine sub-cuboids */
                                double t = 0.0;
                                for (int q = f0; q < f1; q++) {
                                    const int m1 = kf >= q ? kf - q : q - kf, m2 = kf + q + 1;
                                    /* S1 below the source (k < k') by the parity in z */
                                    const double z1 =
                                        (kf < q && (mc_eig_odd_z(o) ^ mc_eig_odd_z(c))) ? -1.0
                                                                                        : 1.0;
                                    const double t1 =
                                        op->s1[(size_t)(m1 * MC_EIG_NSYM + n) * ql + at];
                                    const double t2 =
                                        op->s1[(size_t)(m2 * MC_EIG_NSYM + n) * ql + at];
                                    t += z1 * t1 + rc * t2;
                                }
                                acc[o] += mc_eig_sym_factor(o, c) * par_sign(par, di, dj) * t * e;
                            }
                        }
                    }
            }
            /* S3: Love's stresses of the window p3 at this depth */
            for (int o = 0; o < 6; o++) {
                const double *L = op->love + (size_t)(k * 6 + o) * ql;
                const int par = mc_eig_par(o);
                double s3 = 0.0;
                for (int js = 0; js < wy; js++)
                    for (int is = 0; is < wx; is++) {
                        const int di = mc_eig_wrap(i - is, wx, px);
                        const int dj = mc_eig_wrap(j - js, wy, py);
                        s3 += par_sign(par, di, dj) *
                              L[(size_t)(dj < 0 ? -dj : dj) * qx + (di < 0 ? -di : di)] *
                              op->work[(size_t)js * wx + is];
                    }
                sig[o][(size_t)k * wc + (size_t)j * wx + i] =
                    2.0 * G * (acc[o] + s3) + (loads ? direct_loads(op, loads, k, o, i, j) : 0.0);
            }
        }
    }
}

/* ---- the backend table and the object ------------------------------------------------------- */

struct mc_eig_stress_ops {
    const char *name;
    mc_backend id;
    void (*size)(mc_eigen_stress *op);                 /* qx, qy */
    int (*prepare)(mc_eigen_stress *op, mc_error *err); /* tables and workspaces */
    void (*apply)(mc_eigen_stress *op, const double *const eps[6], double G,
                  const double *const *loads, double *const sig[6]);
    int (*loads)(mc_eigen_stress *op, mc_error *err);  /* op->lk's tables as the apply uses them */
    void (*release)(mc_eigen_stress *op);              /* what prepare took; NULL-safe */
};

static void direct_size(mc_eigen_stress *op)
{
    /* a periodic axis: offsets 0 .. n/2 of the periodic kernel */
    op->qx = mc_eig_per_x(&op->g) ? op->g.nx / 2 + 1 : op->v.nx;
    op->qy = mc_eig_per_y(&op->g) ? op->g.ny / 2 + 1 : op->v.ny;
}

/* the tables in space: S1 at depth offsets 0 .. 2 nzf - 1 of the fine lattice and p3 per source
 * layer */
static int direct_prepare(mc_eigen_stress *op, mc_error *err)
{
    const int nz = op->v.nz, nzf = op->nzf;
    const size_t ql = op->qlen, n1 = 2 * (size_t)nzf * MC_EIG_NSYM * ql, n2 = 6 * (size_t)nz * ql;
    if (!(op->s1 = mc_malloc(n1 * sizeof *op->s1)) || !(op->p3k = mc_malloc(n2 * sizeof *op->p3k)))
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for %zu tables",
                       (n1 + n2) / ql);
    op->part[0] += n1 * sizeof(double);
    op->part[2] += n2 * sizeof(double);
    mc_eig_corners cc;
    int rc = mc_eig_corners_init(op, &cc, err);
    if (rc)
        return rc;
    for (int m = 0; m < 2 * nzf; m++) {
        double *q[MC_EIG_NSYM];
        for (int n = 0; n < MC_EIG_NSYM; n++)
            q[n] = op->s1 + (size_t)(m * MC_EIG_NSYM + n) * ql;
        mc_eig_s1_fill(op, m, &cc, q);
    }
    for (int k = 0; k < nz; k++) {
        double *q[6];
        for (int c = 0; c < 6; c++)
            q[c] = op->p3k + (size_t)(k * 6 + c) * ql;
        mc_eig_p3_fill(op, k, &cc, q);
    }
    mc_eig_corners_free(&cc);
    return MC_OK;
}

static void direct_release(mc_eigen_stress *op)
{
    mc_free(op->s1);
    mc_free(op->p3k);
    op->s1 = op->p3k = NULL;
}

/* the direct backend sums the tables in space as they are */
static int direct_loads_prepare(mc_eigen_stress *op, mc_error *err)
{
    (void)op;
    (void)err;
    return MC_OK;
}

static const struct mc_eig_stress_ops backends[] = {
    {"fft", MC_BACKEND_FFT, mc_eig_stress_fft_size, mc_eig_stress_fft_prepare,
     mc_eig_stress_fft_apply, mc_eig_stress_fft_loads, mc_eig_stress_fft_free},
    {"direct", MC_BACKEND_DIRECT, direct_size, direct_prepare, direct_apply, direct_loads_prepare,
     direct_release},
};

void mc_eigen_stress_destroy(mc_eigen_stress **op)
{
    if (!op || !*op)
        return;
    if ((*op)->ops && !(*op)->spec)
        (*op)->ops->release(*op);
    mc_eigen_spectral_destroy(&(*op)->spec);
    mc_stress_destroy(&(*op)->lplan);
    mc_free((*op)->lay6);
    mc_free((*op)->love);
    mc_free((*op)->lk);
    mc_free((*op)->p3);
    mc_free((*op)->work);
    mc_free((*op)->group);
    mc_free((*op)->first);
    mc_free(*op);
    *op = NULL;
}

int mc_eigen_stress_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                           mc_eigen_stress **out, mc_error *err)
{
    return mc_eig_stress_create_depth(g, v, nu, b, MC_EIG_DEPTH_AUTO, out, err);
}

static int create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                  int depth, int replicated, mc_eigen_stress **out, mc_error *err);

int mc_eig_stress_create_depth(const mc_grid *g, const mc_eigen_volume *v, double nu,
                               mc_backend b, int depth, mc_eigen_stress **out, mc_error *err)
{
    return create(g, v, nu, b, depth, 0, out, err);
}

int mc_eig_stress_create_replicated(const mc_grid *g, const mc_eigen_volume *v, double nu,
                                    mc_eigen_stress **out, mc_error *err)
{
    return create(g, v, nu, MC_BACKEND_FFT, MC_EIG_DEPTH_AUTO, 1, out, err);
}

/* The spectral kernel (theory.md §8.10): the whole operator is an mc_eigen_spectral; p3 is not
 * kept (zeros). Under mpirun every rank holds the whole object and computes the same bits
 * (one-thread FFTW_ESTIMATE plans): replicated, not split (docs/architecture.md "MPI"). */
static int create_spectral(mc_eigen_stress *op, mc_eigen_stress **out, mc_error *err)
{
    const size_t wc = (size_t)op->v.nx * op->v.ny;
    op->p3 = mc_zeros(wc);
    int rc = op->p3 ? mc_eigen_spectral_create(&op->g, &op->v, op->nu, op->ops->id, &op->spec, err)
                    : mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory");
    if (rc) {
        mc_eigen_stress_destroy(&op);
        return rc;
    }
    op->part[1] = mc_eigen_spectral_bytes(op->spec);
    op->part[4] = sizeof *op + wc * sizeof(double) + (2 * (size_t)op->v.nz + 1) * sizeof(int);
    *out = op;
    return MC_OK;
}

static int create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                  int depth, int replicated, mc_eigen_stress **out, mc_error *err)
{
    *out = NULL;
    int rc = mc_eig_check(g, v, nu, b, "eigen stress", err);
    if (rc)
        return rc;
    mc_eigen_stress *op = mc_calloc(1, sizeof *op);
    if (!op)
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory");
    op->g = *g;
    op->v = *v;
    op->nu = nu;
    op->depth = depth;
    op->replicated = replicated;
    /* the layering: the object's copy of the groups, the first fine layer of each layer (and
     * the count at nz) and the fine layer of each layer's centre */
    op->first = mc_malloc((2 * (size_t)v->nz + 1) * sizeof *op->first);
    if (!op->first || (v->group && !(op->group = mc_malloc((size_t)v->nz * sizeof *op->group)))) {
        mc_eigen_stress_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory");
    }
    if (v->group) {
        memcpy(op->group, v->group, (size_t)v->nz * sizeof *op->group);
        op->v.group = op->group;
    }
    op->centre = op->first + v->nz + 1;
    for (int k = 0; k <= v->nz; k++)
        op->first[k] = k == 0 ? 0 : op->first[k - 1] + mc_eigen_layer_count(v, k - 1);
    for (int k = 0; k < v->nz; k++)
        op->centre[k] = mc_eigen_layer_centre(v, k);
    op->nzf = op->first[v->nz];
    for (size_t r = 0; r < sizeof backends / sizeof backends[0]; r++)
        if (backends[r].id == b)
            op->ops = &backends[r];
    if (v->kernel == MC_EIG_KERNEL_SPECTRAL)
        return create_spectral(op, out, err);
    op->ops->size(op);
    op->qlen = ((size_t)op->qx * op->qy + 7) / 8 * 8;
    const size_t wc = (size_t)v->nx * v->ny, nl = 6 * (size_t)v->nz * op->qlen;
    op->love = mc_malloc(nl * sizeof *op->love);
    op->p3 = mc_zeros(wc);
    op->work = mc_zeros(wc);
    if (!op->love || !op->p3 || !op->work) {
        mc_eigen_stress_destroy(&op);
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for its tables");
    }
    op->part[3] = nl * sizeof(double);
    op->part[4] = sizeof *op + 2 * wc * sizeof(double) + (2 * (size_t)v->nz + 1) * sizeof(int);
    for (int k = 0; k < v->nz && !mc_eig_periodic(g); k++) {
        double *q[6];
        for (int i = 0; i < 6; i++)
            q[i] = op->love + (size_t)(k * 6 + i) * op->qlen;
        mc_eig_love_fill(op, k, q);
    }
    if ((mc_eig_periodic(g) && (rc = love_fill_periodic(op, err))) ||
        (rc = op->ops->prepare(op, err))) {
        mc_eigen_stress_destroy(&op);
        return rc;
    }
    *out = op;
    return MC_OK;
}

void mc_eigen_stress_apply(mc_eigen_stress *op, const double *const eps[6], double G,
                           double *const sig[6])
{
    op->fwd = NULL;
    if (op->spec)
        mc_eigen_spectral_apply(op->spec, eps, G, sig, NULL);
    else
        op->ops->apply(op, eps, G, NULL, sig);
}

/* ---- the forward transforms shared with the displacement operator ---------------------------- */

void mc_eig_stress_forward_visit(mc_eigen_stress *op, const double *const eps[6],
                                 const mc_eig_forward_visit *visit)
{
    for (int c = 0; c < 6; c++)
        op->fwd_eps[c] = eps[c];
    op->fwd = op->fwd_eps;
    if (op->ops->id == MC_BACKEND_FFT && !op->spec)
        mc_eig_stress_fft_forward(op, eps, visit);
}

void mc_eigen_stress_forward(mc_eigen_stress *op, const double *const eps[6])
{
    mc_eig_stress_forward_visit(op, eps, NULL);
}

int mc_eigen_stress_forwarded(const mc_eigen_stress *op) { return op->fwd != NULL; }

int mc_eigen_stress_keep_rows(mc_eigen_stress *op, int on, int *r0, int *nr)
{
    const int dist = op->ops->id == MC_BACKEND_FFT && !op->spec && mc_eig_stress_fft_rows(op, r0, nr);
    if (!dist) {
        *r0 = 0;
        *nr = op->v.ny;
    }
    op->keep_rows = dist && on;
    return dist;
}

/* ---- surface loads folded in (theory.md §8.9) ---------------------------------------------- */

/* the loads that can be folded, in the order of op->lk */
static const int FOLDABLE[2] = {MC_TRACTION_P, MC_TRACTION_QX};

static int whole_window(const mc_eigen_stress *op)
{
    return op->v.i0 == 0 && op->v.j0 == 0 && op->v.nx == op->g.nx && op->v.ny == op->g.ny;
}

/* The spectral kernel folds the loads through the stress module (theory.md §8.10): its plan of
 * the patch stresses at the layer centres, each layer computed into a grid-sized scratch and
 * added to the residual stress, so that the loop's sweep reads one array as with the cuboid
 * operators' folding, and no elastic stress array of the volume exists. Free axes keep no
 * kernel spectra (the tables are built per layer and call); periodic axes keep them (stress.h). */
/* The kernel spectra of every layer the plan would keep (6 per layer and load: quadrants on free
 * axes, half spectra on periodic ones), bytes. Free axes keep them (repeated) while they stay
 * within SPECTRAL_LOADS_CACHE: rebuilding the tables per layer and call cost 2.7x the time of a
 * small run (44^2 x 13 sphere 1.24 -> 3.35 s), and at large sizes their memory is what the
 * spectral kernel is for (256^2 x 32: 101 MB, 48 bytes per volume cell). */
#define SPECTRAL_LOADS_CACHE ((double)(64 << 20))

static double spectral_loads_cache(const mc_grid *g, int nz, int nloads)
{
    return (double)nz * nloads * mc_stress_cache_layer_bytes(g);
}

static int spectral_loads_repeated(const mc_grid *g, int nz, int nloads)
{
    return spectral_loads_cache(g, nz, nloads) <= SPECTRAL_LOADS_CACHE;
}

static size_t spectral_loads_bytes(const mc_grid *g, int nz, int nloads)
{
    const int px = g->periodic_x, py = g->periodic_y;
    const double tx = px ? g->nx : mc_fftsize_good(2 * g->nx - 1);
    const double ty = py ? g->ny : mc_fftsize_good(2 * g->ny - 1);
    const double spec = 16 * ty * (tx / 2 + 1), cells = (double)g->nx * g->ny;
    double b = nloads * 7 * spec + 6 * 8 * tx * ty + 4 * cells + 6 * 8 * cells;
    const double cache = spectral_loads_cache(g, nz, nloads);
    if ((px || py || spectral_loads_repeated(g, nz, nloads)) &&
        cache <= (double)MC_STRESS_CACHE_BYTES)
        b += cache;
    return (size_t)b;
}

static int spectral_loads(mc_eigen_stress *op, int loads, mc_error *err)
{
    double *depths = mc_zeros((size_t)op->v.nz);
    if (!depths)
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory");
    for (int k = 0; k < op->v.nz; k++)
        depths[k] = mc_eigen_layer_depth(&op->v, k);
    const mc_stress_options so = {.kernel = MC_STRESS_PATCH,
                                  .nu = op->nu,
                                  .nlayers = op->v.nz,
                                  .depths = depths,
                                  .backend = op->ops->id,
                                  .loads = loads,
                                  .repeated = spectral_loads_repeated(
                                      &op->g, op->v.nz, 1 + ((loads & MC_TRACTION_QX) != 0))};
    int rc = mc_stress_create(&op->g, &so, &op->lplan, err);
    mc_free(depths);
    if (rc == MC_OK && !(op->lay6 = mc_malloc(6 * (size_t)op->g.nx * op->g.ny * sizeof(double))))
        rc = mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for the loads' layer");
    if (rc != MC_OK) {
        mc_stress_destroy(&op->lplan);
        return rc;
    }
    int n = 0;
    for (int l = 0; l < 2; l++)
        if (loads & FOLDABLE[l])
            op->load_id[n++] = FOLDABLE[l];
    op->nloads = n;
    op->part[3] += spectral_loads_bytes(&op->g, op->v.nz, n);
    return MC_OK;
}

/* The loads' spectra added to the up pass's (theory §8.10): the hook of mc_eigen_spectral */
static int loads_hook(void *ctx, int layer, double *const spec[6])
{
    mc_eigen_stress *op = ctx;
    mc_error e = {0};
    return mc_stress_add_spectra(op->lplan, layer, spec, &e) != MC_OK;
}

/* How an apply adds the folded loads (spectral kernel), decided once per apply by loads_begin */
enum { LOADS_NONE, LOADS_FAILED, LOADS_AFTER, LOADS_FUSED };

/* Prepares the loads' plan once (p or q_x of the operator's load ids) and, when may_fuse and its
 * spectra fit the spectral operator's transform (fft, the same padded size, the loads not summed
 * cell by cell), sets the hook that adds them in the up pass (LOADS_FUSED: one inverse transform
 * per layer and component for both, 6 nz fewer per apply); else LOADS_AFTER (loads_end adds them
 * layer by layer), LOADS_FAILED (a plan that refuses the loads: a caller's slip) or LOADS_NONE. */
static int loads_begin(mc_eigen_stress *op, const double *p, const double *qx, int may_fuse)
{
    if (!op->nloads)
        return LOADS_NONE;
    const double *loads[2] = {NULL, NULL};
    for (int l = 0; l < op->nloads; l++)
        loads[l] = op->load_id[l] == MC_TRACTION_P ? p : qx;
    mc_error e = {0};
    if (mc_stress_prepare(op->lplan, loads[0], op->nloads > 1 ? loads[1] : NULL, NULL, &e) !=
        MC_OK)
        return LOADS_FAILED;
    int px, py, tx, ty;
    if (!may_fuse || !mc_eigen_spectral_padded(op->spec, &px, &py) ||
        !mc_stress_spectra_size(op->lplan, &tx, &ty) || tx != px || ty != py)
        return LOADS_AFTER;
    mc_eigen_spectral_set_hook(op->spec, loads_hook, op);
    return LOADS_FUSED;
}

/* After the apply's passes: the hook cleared, and sig += the loads' stresses layer by layer
 * where the passes did not add them (NaN where the plan refused them) */
static void loads_end(mc_eigen_stress *op, int how, double *const sig[6])
{
    mc_eigen_spectral_set_hook(op->spec, NULL, NULL);
    if (how == LOADS_NONE || how == LOADS_FUSED)
        return;
    const size_t cells = (size_t)op->g.nx * op->g.ny;
    double *s[6];
    for (int c = 0; c < 6; c++)
        s[c] = op->lay6 + c * cells;
    mc_error e = {0};
    for (int k = 0; k < op->v.nz; k++) {
        if (how == LOADS_FAILED || mc_stress_compute(op->lplan, k, s, &e) != MC_OK) {
            for (int c = 0; c < 6; c++)
                for (size_t i = 0; i < cells; i++)
                    sig[c][k * cells + i] = NAN;
            continue;
        }
        for (int c = 0; c < 6; c++) {
            double *restrict o = sig[c] + k * cells;
            const double *restrict a = s[c];
#pragma omp parallel for schedule(static) if (cells > MC_THREADS_MIN_LOOP)
            for (size_t i = 0; i < cells; i++)
                o[i] += a[i];
        }
    }
}

int mc_eigen_stress_loads(mc_eigen_stress *op, int loads, mc_error *err)
{
    if (op->nloads > 0)
        return mc_fail(err, MC_ERR_INPUT, "eigen stress: surface loads are folded in already");
    if (!(loads & MC_TRACTION_P) || (loads & ~(MC_TRACTION_P | MC_TRACTION_QX)))
        return mc_fail(err, MC_ERR_INPUT,
                       "eigen stress: surface loads %d: the pressure, and at most q_x besides",
                       loads);
    if (!whole_window(op))
        return mc_fail(err, MC_ERR_INPUT,
                       "eigen stress: surface loads need the volume under the whole grid (window "
                       "%d x %d at (%d, %d) of %d x %d)",
                       op->v.nx, op->v.ny, op->v.i0, op->v.j0, op->g.nx, op->g.ny);
    if (op->spec)
        return spectral_loads(op, loads, err);
    int n = 0;
    for (int l = 0; l < 2; l++)
        if (loads & FOLDABLE[l])
            op->load_id[n++] = FOLDABLE[l];
    const size_t nl = (size_t)n * 6 * op->v.nz * op->qlen;
    if (!(op->lk = mc_malloc(nl * sizeof *op->lk)))
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for the loads' tables");
    int rc = MC_OK;
    for (int l = 0; l < n && rc == MC_OK; l++) {
        for (int c = 0; c < 6; c++)
            op->load_par[l][c] = mc_stress_parity(op->load_id[l], c);
        rc = stress_module_tables(op, op->load_id[l], op->lk + (size_t)l * 6 * op->v.nz * op->qlen,
                                  err);
    }
    op->nloads = n;
    if (rc == MC_OK)
        rc = op->ops->loads(op, err);
    if (rc != MC_OK) {
        mc_free(op->lk);
        op->lk = NULL;
        op->nloads = 0;
        return rc;
    }
    if (op->ops->id == MC_BACKEND_DIRECT)
        op->part[3] += nl * sizeof(double);
    return MC_OK;
}

int mc_eigen_stress_loads_of(const mc_eigen_stress *op)
{
    int loads = 0;
    for (int l = 0; l < op->nloads; l++)
        loads |= op->load_id[l];
    return loads;
}

static void apply_loads(mc_eigen_stress *op, const double *const eps[6],
                        const mc_eigen_sparse *inc, double G, const double *p, const double *qx,
                        double *const sig[6])
{
    if (op->spec) { /* the residual stress, then (or in its up pass) the loads' */
        const size_t n = (size_t)op->v.nx * op->v.ny * op->v.nz;
        const int how = loads_begin(op, p, qx, eps != NULL);
        if (eps)
            mc_eigen_spectral_apply_sum(op->spec, eps, inc, G, sig, NULL);
        else
            for (int c = 0; c < 6; c++)
                memset(sig[c], 0, n * sizeof *sig[c]);
        loads_end(op, how, sig);
    } else {
        const double *loads[2] = {NULL, NULL};
        for (int l = 0; l < op->nloads; l++)
            loads[l] = op->load_id[l] == MC_TRACTION_P ? p : qx;
        op->ops->apply(op, eps, G, op->nloads ? loads : NULL, sig);
    }
    op->fwd = NULL;
}

void mc_eigen_stress_apply_loaded(mc_eigen_stress *op, const double *const eps[6], double G,
                                  const double *p, const double *qx, double *const sig[6])
{
    op->fwd = NULL;
    apply_loads(op, eps, NULL, G, p, qx, sig);
}

int mc_eigen_stress_takes_sum(const mc_eigen_stress *op) { return op->spec != NULL; }

int mc_eigen_stress_apply_sum(mc_eigen_stress *op, const double *const eps[6],
                              const mc_eigen_sparse *inc, double G, const double *p,
                              const double *qx, double *const sig[6])
{
    if (!op->spec)
        return MC_ERR_LIMIT;
    op->fwd = NULL;
    apply_loads(op, eps, inc, G, p, qx, sig);
    return MC_OK;
}

int mc_eigen_stress_begin_sum(mc_eigen_stress *op, const double *const eps[6],
                              const mc_eigen_sparse *inc, double G, double *const sig[6],
                              double *uz)
{
    if (!op->spec)
        return MC_ERR_LIMIT;
    op->fwd = NULL;
    mc_eigen_spectral_begin_sum(op->spec, eps, inc, G, sig, uz);
    return MC_OK;
}

int mc_eigen_stress_end_sum(mc_eigen_stress *op, const double *const eps[6],
                            const mc_eigen_sparse *inc, double G, const double *p,
                            const double *qx, double *const sig[6])
{
    if (!op->spec)
        return MC_ERR_LIMIT;
    const int how = loads_begin(op, p, qx, 1);
    mc_eigen_spectral_end_sum(op->spec, eps, inc, G, sig);
    loads_end(op, how, sig);
    return MC_OK;
}

void mc_eigen_stress_apply_forwarded(mc_eigen_stress *op, double G, const double *p,
                                     const double *qx, double *const sig[6])
{
    apply_loads(op, op->fwd, NULL, G, p, qx, sig); /* fwd NULL: the loads alone */
}

void mc_eigen_stress_p3(const mc_eigen_stress *op, double *p3)
{
    if (op->spec) {
        mc_eigen_spectral_p3(op->spec, p3);
        return;
    }
    memcpy(p3, op->p3, (size_t)op->v.nx * op->v.ny * sizeof *p3);
}

size_t mc_eigen_stress_bytes(const mc_eigen_stress *op)
{
    size_t b = 0;
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        b += op->part[k];
    return b;
}

void mc_eigen_stress_parts(const mc_eigen_stress *op, size_t parts[MC_EIGEN_STRESS_PARTS])
{
    memcpy(parts, op->part, sizeof op->part);
}

void mc_eigen_stress_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                              size_t parts[MC_EIGEN_STRESS_PARTS])
{
    mc_eigen_stress_estimate_ranks(g, v, b, mc_dist_active() ? mc_dist_size() : 0, parts);
}

/* The shell that create fills before its allocations (sizes only); 0 for a volume or grid that
 * create refuses. */
static int shell(const mc_grid *g, const mc_eigen_volume *v, mc_backend b, mc_eigen_stress *op)
{
    mc_error err = {0};
    if (mc_eig_check(g, v, 0.3, b, "eigen stress", &err) != MC_OK)
        return 0;
    memset(op, 0, sizeof *op);
    op->g = *g;
    op->v = *v;
    op->depth = MC_EIG_DEPTH_AUTO;
    for (int k = 0; k < v->nz; k++)
        op->nzf += mc_eigen_layer_count(v, k);
    for (size_t r = 0; r < sizeof backends / sizeof backends[0]; r++)
        if (backends[r].id == b)
            op->ops = &backends[r];
    op->ops->size(op);
    op->qlen = ((size_t)op->qx * op->qy + 7) / 8 * 8;
    return 1;
}

size_t mc_eigen_stress_loads_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                      int ranks, int loads)
{
    mc_eigen_stress op;
    if (!(loads & MC_TRACTION_P) || !shell(g, v, b, &op) || !whole_window(&op))
        return 0;
    if (v->kernel == MC_EIG_KERNEL_SPECTRAL)
        return spectral_loads_bytes(g, v->nz, 1 + ((loads & MC_TRACTION_QX) != 0));
    const int n = 1 + ((loads & MC_TRACTION_QX) != 0);
    return b == MC_BACKEND_FFT ? mc_eig_stress_fft_loads_bytes(&op, ranks, n)
                               : (size_t)n * 6 * v->nz * op.qlen * sizeof(double);
}

void mc_eigen_stress_estimate_ranks(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                    int ranks, size_t parts[MC_EIGEN_STRESS_PARTS])
{
    memset(parts, 0, MC_EIGEN_STRESS_PARTS * sizeof *parts);
    mc_eigen_stress op;
    if (!shell(g, v, b, &op))
        return;
    if (v->kernel == MC_EIG_KERNEL_SPECTRAL) { /* create_spectral's parts */
        parts[1] = mc_eigen_spectral_estimate(g, v, b);
        parts[4] = parts[1] ? sizeof op + (size_t)v->nx * v->ny * sizeof(double) +
                                  (2 * (size_t)v->nz + 1) * sizeof(int)
                            : 0;
        return;
    }
    const size_t wc = (size_t)v->nx * v->ny, nl = 6 * (size_t)v->nz * op.qlen;
    parts[3] = nl * sizeof(double);
    parts[4] = sizeof op + 2 * wc * sizeof(double) + (2 * (size_t)v->nz + 1) * sizeof(int);
    if (b == MC_BACKEND_FFT) {
        mc_eig_stress_fft_estimate(&op, ranks, parts);
    } else {
        parts[0] = 2 * (size_t)op.nzf * MC_EIG_NSYM * op.qlen * sizeof(double);
        parts[2] = 6 * (size_t)v->nz * op.qlen * sizeof(double);
    }
}
