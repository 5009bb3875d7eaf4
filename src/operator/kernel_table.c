/* kernel_table.c - kernel tables in wrap-around layout, and the tables of the Love (normal
 * displacement) kernel: free axes on the corner lattice, one periodic axis by an image sum with a
 * continued tail, two periodic axes by Ewald summation (see operator.h). */
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "kernels/kernel.h"
#include "operator/operator.h"

/* Far images in the multipole form beyond this many cell sizes: its error there is < 2e-14 of the
 * own-cell value, while the exact corner sum loses eps (r/d)^2 relative (theory.md §2.2). */
#define FAR_CELLS 32.0

/* Ewald splitting 1/r = erfc(alpha r)/r + erf(alpha r)/r with alpha = EWALD_ALPHA / max(dx, dy):
 * the real-space part is cut where erfc < 2e-17, the reciprocal part where erfc(G/2alpha) < 4e-20.
 * alpha = 0.3 ... 0.6 / d give tables equal to 3e-14 (measured); this value keeps the reciprocal
 * sum inside the first Brillouin zone but for the corner modes. */
#define EWALD_ALPHA 0.4
#define EWALD_ERFC_R 6.0
#define EWALD_ERFC_G 6.5
#define EWALD_ASPECT_MAX 1000.0 /* largest max(dx, dy) / min(dx, dy): about 2 s of table */
#define EWALD_GAUSS 8 /* Gauss-Legendre points per axis for the pixel average of erf(alpha r)/r */

int mc_table_offset(int t, int n, int len, int *used)
{
    int ok = 1, o = 0;
    if (len == n)
        o = t <= n / 2 ? t : t - n;
    else if (t < n)
        o = t;
    else if (t > len - n)
        o = t - len;
    else
        ok = 0;
    if (used)
        *used = ok;
    return o;
}

int mc_kernel_table_check(const mc_grid *g, int tx, int ty, mc_error *err)
{
    int rc = mc_grid_check(g, err);
    if (rc)
        return rc;
    int okx = g->periodic_x ? tx == g->nx : tx >= 2 * g->nx - 1;
    int oky = g->periodic_y ? ty == g->ny : ty >= 2 * g->ny - 1;
    if (!okx || !oky)
        return mc_fail(err, MC_ERR_INPUT,
                       "kernel table %d x %d does not fit grid %d x %d (periodic x %d, y %d): a "
                       "periodic axis needs length n, a free axis at least 2n - 1",
                       tx, ty, g->nx, g->ny, g->periodic_x, g->periodic_y);
    return MC_OK;
}

static int table_alloc(const mc_grid *g, int tx, int ty, mc_kernel_table *out, mc_error *err)
{
    size_t n;
    if (!mc_size_mul((size_t)tx, (size_t)ty, &n) || !(out->k = mc_zeros(n)))
        return mc_fail(err, MC_ERR_NOMEM, "kernel table %d x %d: out of memory", tx, ty);
    out->grid = *g;
    out->tx = tx;
    out->ty = ty;
    return MC_OK;
}

void mc_kernel_table_free(mc_kernel_table *t)
{
    if (!t)
        return;
    mc_free(t->k);
    t->k = NULL;
    t->tx = t->ty = 0;
}

/* Value of a table entry at the cell offsets (ox, oy) (field minus source). */
typedef double (*entry_fn)(int ox, int oy, const void *ctx);

/* k[jt tx + it] = entry(ox, oy) for every used entry of a tx x ty table of grid g, ox and oy its
 * offsets (mc_table_offset); the padding slots are left as they are. OpenMP over table rows. */
static void fill_rows(const mc_grid *g, int tx, int ty, int j0, int nj, double *k,
                      entry_fn entry, const void *ctx)
{
#pragma omp parallel for schedule(dynamic)
    for (int jt = j0; jt < j0 + nj; jt++) {
        int usedy, oy = mc_table_offset(jt, g->ny, ty, &usedy);
        for (int it = 0; it < tx && usedy; it++) {
            int usedx, ox = mc_table_offset(it, g->nx, tx, &usedx);
            if (usedx)
                k[(size_t)(jt - j0) * tx + it] = entry(ox, oy, ctx);
        }
    }
}

static void fill_entries(const mc_grid *g, int tx, int ty, double *k, entry_fn entry,
                         const void *ctx)
{
    fill_rows(g, tx, ty, 0, ty, k, entry, ctx);
}

/* The image sum of mc_kernel_table_build at one offset. */
typedef struct {
    const mc_grid *g;
    const mc_kernel_fn *fn;
    int images, mx, my, tail;
} image_sum;

static double image_sum_entry(int ox, int oy, const void *ctx)
{
    const image_sum *c = ctx;
    const mc_grid *g = c->g;
    double s = 0.0;
    for (int l = -c->my; l <= c->my; l++)
        for (int m = -c->mx; m <= c->mx; m++)
            s += c->fn->value((ox + (double)m * g->nx) * g->dx, (oy + (double)l * g->ny) * g->dy,
                              c->fn->ctx);
    if (c->tail)
        s += c->fn->tail(ox * g->dx, oy * g->dy, g, c->images, c->fn->ctx);
    return s;
}

int mc_kernel_table_build(const mc_grid *g, int tx, int ty, const mc_kernel_fn *fn, int images,
                          mc_kernel_table *out, mc_error *err)
{
    out->k = NULL;
    if (!fn || !fn->value || images < 0)
        return mc_fail(err, MC_ERR_INPUT, "kernel table: no kernel function, or images %d < 0",
                       images);
    int rc = mc_kernel_table_check(g, tx, ty, err);
    if (rc || (rc = table_alloc(g, tx, ty, out, err)))
        return rc;
    const image_sum c = {g, fn, images, g->periodic_x ? images : 0, g->periodic_y ? images : 0,
                         fn->tail && (g->periodic_x || g->periodic_y)};
    fill_entries(g, tx, ty, out->k, image_sum_entry, &c);
    return MC_OK;
}

/* ---- the Love kernel: point form, multipoles, image-sum tails ------------------------------ */

/* Love's rectangle (half-sides a, b) at (x, y) far away, in units of mc_love_uz: the point kernel
 * 4ab/(pi r) with the pixel's second and fourth moments, i.e. the Taylor series of the average of
 * 1/|r - s| over the pixel (<s_x^2> = a^2/3, <s_x^4> = a^4/5, <s_x^2 s_y^2> = a^2 b^2/9), in the
 * plane z = 0 where r^2 = x^2 + y^2. Relative error O((a/r)^6). */
static double love_far(double x, double y, double a, double b)
{
    const double x2 = x * x, y2 = y * y, r2 = x2 + y2, ir = 1.0 / sqrt(r2), ir2 = ir * ir;
    const double ir5 = ir * ir2 * ir2, ir9 = ir5 * ir2 * ir2, a2 = a * a, b2 = b * b;
    const double d2 = (a2 * (2.0 * x2 - y2) + b2 * (2.0 * y2 - x2)) * ir5 / 6.0;
    const double dxxxx = 35.0 * x2 * x2 - 30.0 * x2 * r2 + 3.0 * r2 * r2;
    const double dyyyy = 35.0 * y2 * y2 - 30.0 * y2 * r2 + 3.0 * r2 * r2;
    const double dxxyy = 35.0 * x2 * y2 - 4.0 * r2 * r2;
    const double d4 =
        3.0 * ir9 * (a2 * a2 / 120.0 * dxxxx + b2 * b2 / 120.0 * dyyyy + a2 * b2 / 36.0 * dxxyy);
    return 4.0 * a * b / M_PI * (ir + d2 + d4);
}

/* Antiderivatives in x (u > 0 fixed) of ln(u + rho), u/rho^3 and 3u(3x^2 - 2u^2)/rho^7, with
 * rho = sqrt(u^2 + x^2): the pixel averages <J0>, <J2>, <J4> of the single-axis tail. The -x of
 * the first one is left out: it only adds the constant -2a to every difference. */
static double prim_log(double x, double u)
{
    return x * log(u + sqrt(u * u + x * x)) + u * asinh(x / u);
}
static double prim_r3(double x, double u) { return x / (u * sqrt(u * u + x * x)); }
static double prim_r7(double x, double u)
{
    const double rho = sqrt(u * u + x * x), rho2 = rho * rho;
    return -x * (2.0 / (u * u * u * rho) + 1.0 / (u * rho2 * rho) + 3.0 * u / (rho2 * rho2 * rho));
}

/* Tail of the image sum along ONE periodic axis, in units of mc_love_uz (see mc_kernel_fn_love):
 * x along the free axis (pixel half-width a = df/2), y along the periodic axis (n cells of dp).
 * Derivation: per image cell, sum = (1/L) int over the cell of n sinh(bD)/sinh(nbD) applied to the
 * pixel-averaged point kernel (D = d/ds, b = dp/2: the pixel's own width and the midpoint rule
 * combined), expanded to D^4; the integrals over |s| > H reduce to the end-point values.
 * The pixel average over x is a difference of the antiderivative tail_prim at x + a and x - a, so a
 * table builder evaluates it once per corner ((p - 1/2) df) and differences. */
typedef struct {
    double H, beta2, beta4, scale, a;
} tail_1d;

static tail_1d tail_1d_init(double df, double dp, int n, int images)
{
    const double L = n * dp, b = 0.5 * dp, n2 = (double)n * n;
    tail_1d t;
    t.H = (images + 0.5) * L;
    t.beta2 = (1.0 - n2) * dp * dp / 24.0;
    t.beta4 = ((1.0 - n2 * n2) / 120.0 + n2 * (n2 - 1.0) / 36.0) * b * b * b * b;
    t.scale = dp / (M_PI * L); /* c/(L 2a) with c = 4ab/pi: the average divides by 2a */
    t.a = 0.5 * df;
    return t;
}

static double tail_prim(const tail_1d *t, double X, double y)
{
    double q = 0.0;
    for (int side = -1; side <= 1; side += 2) {
        const double u = t->H + side * y;
        q += -prim_log(X, u) + t->beta2 * prim_r3(X, u) - t->beta4 * prim_r7(X, u);
    }
    return q;
}

/* The difference of the corner values; 4a restores the two -x terms left out of prim_log. */
static inline double tail_diff(const tail_1d *t, double qhi, double qlo)
{
    return t->scale * (qhi - qlo + 4.0 * t->a);
}

static double tail_one_axis(double x, double y, double df, double dp, int n, int images)
{
    const tail_1d t = tail_1d_init(df, dp, n, images);
    return tail_diff(&t, tail_prim(&t, x + t.a, y), tail_prim(&t, x - t.a, y));
}

static double corner_q(double X, double Y) { return Y / (X * sqrt(X * X + Y * Y)); }

/* Tail of the image sum over a box of (2M+1)^2 periods, in units of mc_love_uz: the integral of
 * the point kernel outside the box (minus the divergent whole-plane integral) plus the
 * second-order midpoint/pixel terms, written as corner sums over the box (divergence theorem). */
static double tail_two_axes(double x, double y, const mc_grid *g, int images)
{
    const double Lx = g->nx * g->dx, Ly = g->ny * g->dy;
    const double Hx = (images + 0.5) * Lx, Hy = (images + 0.5) * Ly;
    const double nx2 = (double)g->nx * g->nx, ny2 = (double)g->ny * g->ny;
    const double bx = (1.0 - nx2) * g->dx * g->dx / 24.0, by = (1.0 - ny2) * g->dy * g->dy / 24.0;
    const double ixx = corner_q(x + Hx, y + Hy) - corner_q(x + Hx, y - Hy) -
                       corner_q(x - Hx, y + Hy) + corner_q(x - Hx, y - Hy);
    const double iyy = corner_q(y + Hy, x + Hx) - corner_q(y - Hy, x + Hx) -
                       corner_q(y + Hy, x - Hx) + corner_q(y - Hy, x - Hx);
    /* c/A = 1/(pi nx ny) with c = dx dy/pi, A = Lx Ly */
    return (-M_PI * mc_love_uz(x, y, Hx, Hy) + bx * ixx + by * iyy) /
           (M_PI * g->nx * (double)g->ny);
}

static double love_value(double ox, double oy, const void *ctx)
{
    const mc_kernel_love_ctx *c = ctx;
    return mc_love_uz(ox, oy, c->a, c->b) / c->Estar;
}

static double love_tail(double ox, double oy, const mc_grid *g, int images, const void *ctx)
{
    const mc_kernel_love_ctx *c = ctx;
    if (g->periodic_x && g->periodic_y)
        return tail_two_axes(ox, oy, g, images) / c->Estar;
    if (g->periodic_y)
        return tail_one_axis(ox, oy, g->dx, g->dy, g->ny, images) / c->Estar;
    if (g->periodic_x)
        return tail_one_axis(oy, ox, g->dy, g->dx, g->nx, images) / c->Estar;
    return 0.0;
}

void mc_kernel_fn_love(const mc_grid *g, double Estar, mc_kernel_love_ctx *ctx, mc_kernel_fn *fn)
{
    ctx->a = 0.5 * g->dx;
    ctx->b = 0.5 * g->dy;
    ctx->Estar = Estar;
    fn->value = love_value;
    fn->tail = love_tail;
    fn->ctx = ctx;
}

/* ---- fast Love tables ---------------------------------------------------------------------- */

/* F on the corner lattice ((p - 1/2) dx, (q - 1/2) dy), p = 0..np-1, q = 0..nq-1 (theory.md §5.5):
 * each pixel value is then the four-term difference, one corner evaluation per cell. */
static double *corner_lattice_from(int np, int q0, int nq, double dx, double dy)
{
    size_t n;
    double *f = mc_size_mul((size_t)np, (size_t)nq, &n) ? mc_malloc((n ? n : 1) * sizeof *f)
                                                        : NULL;
    if (!f)
        return NULL;
#pragma omp parallel for schedule(static)
    for (int q = 0; q < nq; q++)
        for (int p = 0; p < np; p++)
            f[(size_t)q * np + p] = mc_love_corner((p - 0.5) * dx, (q0 + q - 0.5) * dy);
    return f;
}

static double *corner_lattice(int np, int nq, double dx, double dy)
{
    return corner_lattice_from(np, 0, nq, dx, dy);
}

/* Love's rectangle at offset (m, l) >= 0 cells from the lattice, in the order of mc_love_uz. */
static inline double lattice_love(const double *f, int np, int m, int l)
{
    const double *lo = f + (size_t)l * np, *hi = lo + np;
    return (hi[m + 1] - lo[m + 1] - hi[m] + lo[m]) / M_PI;
}

/* An even kernel's table entry from its values at offsets >= 0: q[|oy| stride + |ox|], or with
 * swap q[|ox| stride + |oy|] (the first axis of q is then x). */
typedef struct {
    const double *q;
    int stride, swap;
} quarter_view;

static double quarter_entry(int ox, int oy, const void *ctx)
{
    const quarter_view *c = ctx;
    const int a = abs(c->swap ? oy : ox), b = abs(c->swap ? ox : oy);
    return c->q[(size_t)b * c->stride + a];
}

/* Love's rectangle from the corner lattice (lattice_love) at offsets >= 0. */
typedef struct {
    const double *f; /* lattice rows q0 .. */
    int np, q0;
} lattice_view;

static double lattice_entry(int ox, int oy, const void *ctx)
{
    const lattice_view *c = ctx;
    return lattice_love(c->f, c->np, abs(ox), abs(oy) - c->q0);
}

/* Both axes free: the kernel is even in both offsets; only |ox| < nx, |oy| < ny are evaluated. */
static int love_free(const mc_grid *g, double *k, int tx, int ty, mc_error *err)
{
    const int np = g->nx + 1;
    double *f = corner_lattice(np, g->ny + 1, g->dx, g->dy);
    if (!f)
        return mc_fail(err, MC_ERR_NOMEM, "Love table: out of memory for the corner lattice");
    const lattice_view c = {f, np, 0};
    fill_entries(g, tx, ty, k, lattice_entry, &c);
    mc_free(f);
    return MC_OK;
}

/* One periodic axis. Axis f is free (nf cells of df), axis p periodic (npd cells of dp); swap says
 * the periodic axis is x. The kernel is even in both offsets: the quarter of offsets (in cells)
 * 0 <= o_free < nf, 0 <= o_per <= npd/2 is computed row by row (central image on the corner
 * lattice, further images exact near and multipole far, the tail from its corner values) and
 * mirrored into the table. */
static int love_one_periodic(const mc_grid *g, double *k, int tx, int ty, mc_error *err)
{
    const int swap = g->periodic_x;
    const int nf = swap ? g->ny : g->nx, npd = swap ? g->nx : g->ny;
    const double df = swap ? g->dy : g->dx, dp = swap ? g->dx : g->dy;
    const double a = 0.5 * df, b = 0.5 * dp, L = npd * dp, far = FAR_CELLS * fmax(df, dp);
    const int hp = npd / 2 + 1, np = nf + 1;
    const tail_1d tail = tail_1d_init(df, dp, npd, MC_LOVE_IMAGES);
    double *f = corner_lattice(np, hp + 1, df, dp);
    double *quart = mc_malloc((size_t)hp * (size_t)nf * sizeof *quart);
    double *tq = mc_malloc((size_t)hp * (size_t)np * sizeof *tq);
    if (!f || !quart || !tq) {
        mc_free(f);
        mc_free(quart);
        mc_free(tq);
        return mc_fail(err, MC_ERR_NOMEM, "Love table: out of memory for the image sum");
    }
#pragma omp parallel for schedule(dynamic)
    for (int o_per = 0; o_per < hp; o_per++) {
        const double y = o_per * dp;
        double *row = quart + (size_t)o_per * nf, *trow = tq + (size_t)o_per * np;
        for (int p = 0; p < np; p++)
            trow[p] = tail_prim(&tail, (p - 0.5) * df, y);
        for (int o_free = 0; o_free < nf; o_free++)
            row[o_free] = lattice_love(f, np, o_free, o_per);
        for (int m = MC_LOVE_IMAGES; m >= 1; m--)
            for (int side = -1; side <= 1; side += 2) {
                const double yy = y + side * m * L, rest = far * far - yy * yy;
                const int near = rest < 0.0 ? 0 : (int)fmin(nf, floor(sqrt(rest) / df) + 1.0);
                for (int o_free = 0; o_free < near; o_free++)
                    row[o_free] += mc_love_uz(o_free * df, yy, a, b);
                for (int o_free = near; o_free < nf; o_free++)
                    row[o_free] += love_far(o_free * df, yy, a, b);
            }
        for (int o_free = 0; o_free < nf; o_free++)
            row[o_free] += tail_diff(&tail, trow[o_free + 1], trow[o_free]);
    }
    const quarter_view c = {quart, nf, swap};
    fill_entries(g, tx, ty, k, quarter_entry, &c);
    mc_free(f);
    mc_free(quart);
    mc_free(tq);
    return MC_OK;
}

/* Nodes and weights of n-point Gauss-Legendre quadrature on [-1, 1] (Newton on P_n). */
static void gauss_legendre(int n, double *x, double *w)
{
    for (int i = 0; i < n; i++) {
        double z = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = 0.0;
            for (int k = 1; k <= n; k++) {
                const double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            const double dz = p0 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16)
                break;
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}

static double sinc(double t) { return t == 0.0 ? 1.0 : sin(t) / t; }

/* Both axes periodic: Ewald summation of the pixel kernel (units of mc_love_uz). With
 * 1/r = erfc(alpha r)/r + erf(alpha r)/r, the smooth part summed over all images is, by Poisson
 * summation, (1/(pi A)) sum_{G != 0} (2 pi/|G|) erfc(|G|/2 alpha) (dx dy) sinc(Gx a) sinc(Gy b)
 * e^{iG.x} over the reciprocal lattice G = 2 pi (k/Lx, l/Ly); at the cell offsets this is an
 * inverse DFT of the aliased sum. The short-range part is Love's rectangle minus the pixel average
 * of erf(alpha r)/r (Gauss-Legendre: the integrand is entire) at the few offsets where erfc is not
 * negligible, each added to its periodic entry. G = 0 (the divergent mean) is left out and the
 * table mean removed. */
static int love_ewald(const mc_grid *g, double *k, mc_error *err)
{
    const int nx = g->nx, ny = g->ny, hx = nx / 2 + 1;
    const double dx = g->dx, dy = g->dy, a = 0.5 * dx, b = 0.5 * dy;
    const double Lx = nx * dx, Ly = ny * dy;
    /* the real-space sum spans 2 rcut / min(dx, dy) cells along the short side: its cost grows
     * with the aspect ratio (case/scene.c refuses ratios above 1000 with the key's line) */
    if (fmax(dx, dy) / fmin(dx, dy) > EWALD_ASPECT_MAX)
        return mc_fail(err, MC_ERR_LIMIT,
                       "Ewald Love table: cell aspect ratio dy/dx = %g on a grid periodic along x "
                       "and y; at most %g (and at least 1/%g) is supported",
                       dy / dx, EWALD_ASPECT_MAX, EWALD_ASPECT_MAX);
    const double alpha = EWALD_ALPHA / fmax(dx, dy);
    const double gcut = 2.0 * alpha * EWALD_ERFC_G, rcut = EWALD_ERFC_R / alpha;
    const double kxmax = gcut * Lx / (2.0 * M_PI), kymax = gcut * Ly / (2.0 * M_PI);
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    fftw_complex *spec = mc_malloc((size_t)hx * (size_t)ny * sizeof *spec);
    if (!spec)
        return mc_fail(err, MC_ERR_NOMEM, "Ewald Love table: out of memory");
    fftw_plan plan = fftw_plan_dft_c2r_2d(ny, nx, spec, k, FFTW_ESTIMATE);
    if (!plan) {
        mc_free(spec);
        return mc_fail(err, MC_ERR_NOMEM, "Ewald Love table: FFTW could not plan %d x %d", nx, ny);
    }
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < hx; i++) {
            const int s0 = (int)ceil((-kxmax - i) / nx), s1 = (int)floor((kxmax - i) / nx);
            const int t0 = (int)ceil((-kymax - j) / ny), t1 = (int)floor((kymax - j) / ny);
            double sum = 0.0;
            for (int t = t0; t <= t1; t++)
                for (int s = s0; s <= s1; s++) {
                    const double gx = 2.0 * M_PI * (i + (double)s * nx) / Lx;
                    const double gy = 2.0 * M_PI * (j + (double)t * ny) / Ly;
                    const double gg = sqrt(gx * gx + gy * gy);
                    if (gg > 0.0 && gg <= gcut)
                        sum += erfc(gg / (2.0 * alpha)) / gg * sinc(gx * a) * sinc(gy * b);
                }
            spec[(size_t)j * hx + i][0] = sum;
            spec[(size_t)j * hx + i][1] = 0.0;
        }
    fftw_execute(plan);
    fftw_destroy_plan(plan);
    mc_free(spec);
    const size_t n = (size_t)nx * (size_t)ny;
    /* (dx dy/(pi A)) 2 pi = 2/(nx ny); FFTW's backward transform is unnormalised */
    for (size_t q = 0; q < n; q++)
        k[q] *= 2.0 / (double)n;

    double gx[EWALD_GAUSS], gw[EWALD_GAUSS];
    gauss_legendre(EWALD_GAUSS, gx, gw);
    const int mx = (int)ceil((rcut + a) / dx), my = (int)ceil((rcut + b) / dy);
    for (int oy = -my; oy <= my; oy++)
        for (int ox = -mx; ox <= mx; ox++) {
            const double x = ox * dx, y = oy * dy;
            double smooth = 0.0;
            for (int u = 0; u < EWALD_GAUSS; u++)
                for (int v = 0; v < EWALD_GAUSS; v++) {
                    const double sx = x - a * gx[u], sy = y - b * gx[v];
                    const double r = sqrt(sx * sx + sy * sy);
                    const double h = r > 0.0 ? erf(alpha * r) / r : 2.0 * alpha / sqrt(M_PI);
                    smooth += gw[u] * gw[v] * h;
                }
            const int i = ((ox % nx) + nx) % nx, j = ((oy % ny) + ny) % ny;
            k[(size_t)j * nx + i] += mc_love_uz(x, y, a, b) - smooth * a * b / M_PI;
        }
    double mean = 0.0;
    for (size_t q = 0; q < n; q++)
        mean += k[q];
    mean /= (double)n;
    for (size_t q = 0; q < n; q++)
        k[q] -= mean;
    return MC_OK;
}

int mc_kernel_table_love(const mc_grid *g, int tx, int ty, double Estar, mc_kernel_table *out,
                         mc_error *err)
{
    out->k = NULL;
    if (!(isfinite(Estar) && Estar > 0.0))
        return mc_fail(err, MC_ERR_INPUT, "Love table: E* = %g Pa must be finite and > 0", Estar);
    int rc = mc_kernel_table_check(g, tx, ty, err);
    if (rc || (rc = table_alloc(g, tx, ty, out, err)))
        return rc;
    if (g->periodic_x && g->periodic_y)
        rc = love_ewald(g, out->k, err);
    else if (g->periodic_x || g->periodic_y)
        rc = love_one_periodic(g, out->k, tx, ty, err);
    else
        rc = love_free(g, out->k, tx, ty, err);
    if (rc) {
        mc_kernel_table_free(out);
        return rc;
    }
    const size_t n = (size_t)tx * (size_t)ty;
    for (size_t q = 0; q < n; q++)
        out->k[q] /= Estar;
    return MC_OK;
}

int mc_kernel_table_love_rows(const mc_grid *g, int tx, int ty, double Estar, int j0, int nj,
                              double *rows, mc_error *err)
{
    if (!(isfinite(Estar) && Estar > 0.0))
        return mc_fail(err, MC_ERR_INPUT, "Love table: E* = %g Pa must be finite and > 0", Estar);
    int rc = mc_kernel_table_check(g, tx, ty, err);
    if (rc)
        return rc;
    if (j0 < 0 || nj < 0 || j0 + nj > ty)
        return mc_fail(err, MC_ERR_INTERNAL, "Love table: rows %d .. %d outside 0 .. %d", j0,
                       j0 + nj - 1, ty - 1);
    const size_t n = (size_t)nj * (size_t)tx;
    memset(rows, 0, n * sizeof *rows);
    if (g->periodic_x || g->periodic_y) { /* the whole table, its rows kept */
        mc_kernel_table t;
        if ((rc = mc_kernel_table_love(g, tx, ty, Estar, &t, err)))
            return rc;
        memcpy(rows, t.k + (size_t)j0 * tx, n * sizeof *rows);
        mc_kernel_table_free(&t);
        return MC_OK;
    }
    /* free axes: the corner lattice's rows these table rows read (|oy| and |oy| + 1) */
    int qlo = g->ny, qhi = -1;
    for (int jt = j0; jt < j0 + nj; jt++) {
        int used, oy = abs(mc_table_offset(jt, g->ny, ty, &used));
        if (used) {
            qlo = oy < qlo ? oy : qlo;
            qhi = oy > qhi ? oy : qhi;
        }
    }
    if (qhi < 0)
        return MC_OK; /* only padding rows */
    const int np = g->nx + 1;
    double *f = corner_lattice_from(np, qlo, qhi - qlo + 2, g->dx, g->dy);
    if (!f)
        return mc_fail(err, MC_ERR_NOMEM, "Love table: out of memory for the corner lattice");
    const lattice_view c = {f, np, qlo};
    fill_rows(g, tx, ty, j0, nj, rows, lattice_entry, &c);
    mc_free(f);
    for (size_t q = 0; q < n; q++)
        rows[q] /= Estar;
    return MC_OK;
}
