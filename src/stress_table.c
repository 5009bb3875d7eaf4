/* stress_table.c - kernel tables of the subsurface stresses at one depth (see stress.h).
 *
 * A table entry is a sum of 1-D "stencils" along x and y applied to a 2-D function. Along an axis
 * the entry of cell offset o (field minus source) is
 *   free axis:      f(o + 1/2) - f(o - 1/2)                         (corner positions in cells)
 *   periodic axis:  sum_{|k| <= M} [f(o + kn + 1/2) - f(o + kn - 1/2)]              (images)
 *                   + (1/n) { f(o + F) - f(o - F) - [f(o + H) - f(o - H)]
 *                             - e2 [d2 f(o + H) - d2 f(o - H)] - e4 [d4 f(o + H) - d4 f(o - H)] }
 * with H = (M + 1/2) n the edge of the smeared strips, F their far edge, d2 and d4 the central
 * second and fourth differences (step one cell). The braces are the uniform load 2b/L = 1/n per
 * unit length replacing the images |k| > M, with the midpoint Euler-Maclaurin corrections: for a
 * pixel of width 2b repeated with period L = 2bn and a corner function G (the pixel's stress is
 * G(y + b) - G(y - b)),
 *   sum_{k > M} = (2b/L) [G(y - H) - G(y - F)] + (2b/L) [c2 G''(y - H) + c4 G''''(y - H)] + ...,
 *   c2 = (1 - n^2) (2b)^2/24,   c4 = b^4 [1/120 - n^2/36 + 7 n^4/360]
 * (both vanish for n = 1: the pixels tile the strip), and the images k < -M mirror it. The
 * differences replace the derivatives: e2 = c2/d^2, e4 = c4/d^4 - e2/12. The 2-D table is the
 * product of the x and y stencils applied to the corner function of kernel.h (patch kernel): the
 * images x images, images x strips and strips x strips parts of the plane.
 *
 * Evaluation streams over table rows (y offsets o, OpenMP blocks of consecutive o): a "row" is the
 * x stencil of every x entry applied to the corner function on one line Y = const (the corner
 * function evaluated once per distinct X: the corner lattice of elastic.md 3.5, plus the strip
 * points); each row is used by all table rows whose y stencil contains its Y, which for
 * consecutive o are shared (the upper corner of o is the lower corner of o + 1, the strip points
 * slide by one), so every distinct (X, Y) is evaluated once per block.
 *
 * The point kernel: its images are point forces (mc_point_stress_* times dx dy), summed directly;
 * its smeared strips are those of the patch kernel (the same loads smeared; the pixel's own width
 * changes the strips by O((d/H)^2) of their small contribution).
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "alloc.h"
#include "kernel.h"
#include "stress.h"

/* Above this many cells per period the fourth-difference correction is skipped: its round-off,
 * ~ e4/n * 16 eps |f| ~ 0.02 n^3 eps |f| (|f| <= ~30 for the logs of the corner functions), would
 * pass 1e-10 of a unit kernel, while the term it corrects is already below 1e-11 there. */
#define FOURTH_DIFF_MAX_N 128

typedef void (*stress_fn)(double X, double Y, double z, double nu, double f[MC_NSTRESS]);

static const stress_fn corner_fns[3] = {mc_rect_corner_p, mc_rect_corner_qx, mc_rect_corner_qy};
static const stress_fn point_fns[3] = {mc_point_stress_p, mc_point_stress_qx, mc_point_stress_qy};

typedef struct {
    int n, len, periodic;
    double d;      /* cell size, m */
    int olo, ohi;  /* cell offsets of the used table entries (contiguous) */
    int *index;    /* table index of offset o: index[o - olo] */
    int M;         /* images per side at depths above the smearing depth (periodic axes) */
    int J;         /* half-width of the difference stencils: 2 (d2, d4) or 1 (d2) */
    double e2, e4; /* Euler-Maclaurin coefficients of d2 and d4 */
} axis;

/* The stencil of one axis at one depth. */
typedef struct {
    int M;        /* images per side (0 on a free axis), or -1: the whole image sum smeared */
    int strips;   /* periodic: the smeared strips (and far edges) take part */
    double H;     /* strip edge, cells */
    int clo, chi; /* cells of the image lattice: corners clo - 1/2 ... chi + 1/2 */
} rule;

typedef struct {
    double *fv;   /* corner function at the x points of one row, 6 per point */
    double *rows; /* row buffers, 6*tx each */
    double **lo, **up, **hp, **hm, *farp, *farm;
    double **ptr; /* pointer storage for lo, up, hp, hm */
} workspace;

struct mc_stress_tables {
    mc_grid g;
    int tx, ty;
    mc_stress_kernel kernel;
    double nu;
    double far; /* far edge of the strips, m */
    axis ax[2];
    int nthreads;
    workspace *ws;
    size_t nfv;   /* doubles of fv */
    size_t nrows; /* rows per workspace */
};

/* Images per side along a periodic axis of n cells. The strip error after the fourth-order
 * correction falls like M^-6 (M^-4 with the second-order one used for n > FOURTH_DIFF_MAX_N);
 * measured in tests/test_stress.c as the table change from M to 2M. At least 2, so that the strip
 * stencil (H - 2 cells) stays clear of the singular lines X = 0, Y = 0 at z = 0. */
static int auto_images(int n)
{
    if (n <= 1)
        return 0;
    int m = (int)ceil(48.0 / n);
    return m < 2 ? 2 : m;
}

static rule axis_rule(const axis *a, double z)
{
    rule r = {0, 0, 0.0, a->olo, a->ohi};
    if (!a->periodic)
        return r;
    r.strips = 1;
    if (a->n == 1 || z >= MC_STRESS_SMEAR_DEPTH * a->n * a->d) {
        r.M = -1;
        return r;
    }
    r.M = a->M;
    r.H = (a->M + 0.5) * a->n;
    r.clo = a->olo - a->M * a->n;
    r.chi = a->ohi + a->M * a->n;
    return r;
}

static int axis_setup(axis *a, int n, int len, int periodic, double d, int images, mc_error *err)
{
    a->n = n;
    a->len = len;
    a->periodic = periodic;
    a->d = d;
    a->olo = len;
    a->ohi = -len;
    for (int t = 0; t < len; t++) {
        int used, o = mc_table_offset(t, n, len, &used);
        if (used) {
            a->olo = o < a->olo ? o : a->olo;
            a->ohi = o > a->ohi ? o : a->ohi;
        }
    }
    if (!(a->index = mc_malloc(sizeof *a->index * (size_t)(a->ohi - a->olo + 1))))
        return mc_fail(err, MC_ERR_NOMEM, "stress tables: out of memory");
    for (int t = 0; t < len; t++) {
        int used, o = mc_table_offset(t, n, len, &used);
        if (used)
            a->index[o - a->olo] = t;
    }
    a->M = periodic ? (images > 0 ? images : auto_images(n)) : 0;
    a->J = n <= FOURTH_DIFF_MAX_N ? 2 : 1;
    const double nn = (double)n * n;
    a->e2 = (1.0 - nn) / 24.0;
    a->e4 = a->J == 2 ? (1.0 / 120.0 - nn / 36.0 + 7.0 * nn * nn / 360.0) / 16.0 - a->e2 / 12.0
                      : 0.0;
    return MC_OK;
}

/* x points of a row, in buffer order: lattice corners, strip points at +H, at -H, far +, far -. */
typedef struct {
    int nlat;    /* lattice corners (0 if none) */
    int nh;      /* strip points per side (0 if none) */
    int hp, hm;  /* first strip point at +H, -H */
    int fp, fm;  /* far points (-1 if none) */
    int total;
} xpoints;

static xpoints x_layout(const axis *a, const rule *r)
{
    xpoints p = {0, 0, 0, 0, -1, -1, 0};
    if (r->M >= 0)
        p.nlat = r->chi - r->clo + 2;
    if (r->strips && r->M >= 0)
        p.nh = a->ohi - a->olo + 1 + 2 * a->J;
    p.hp = p.nlat;
    p.hm = p.hp + p.nh;
    p.total = p.hm + p.nh;
    if (r->strips) {
        p.fp = p.total;
        p.fm = p.total + 1;
        p.total += 2;
    }
    return p;
}

/* The strip part of a stencil: (1/n){f(F) - f(-F) - [hp0 - hm0] - e2 [d2] - e4 [d4]}, applied to
 * values at stride s (the strip points at offsets j = -J..J around the centre c of each side). */
static inline double strip_combine(const axis *a, const rule *r, double fp, double fm,
                                   const double *hp, const double *hm, ptrdiff_t s)
{
    double t = fp - fm;
    if (r->M >= 0) {
        t -= hp[0] - hm[0];
        const double d2 = (hp[s] - 2.0 * hp[0] + hp[-s]) - (hm[s] - 2.0 * hm[0] + hm[-s]);
        t -= a->e2 * d2;
        if (a->J == 2) {
            const double d4 = (hp[2 * s] - 4.0 * hp[s] + 6.0 * hp[0] - 4.0 * hp[-s] + hp[-2 * s]) -
                              (hm[2 * s] - 4.0 * hm[s] + 6.0 * hm[0] - 4.0 * hm[-s] + hm[-2 * s]);
            t -= a->e4 * d4;
        }
    }
    return t / a->n;
}

/* One row: g[c*tx + t] = the x stencil of the entry at table index t applied to the corner
 * function on the line Y (m). with_lattice = 0 drops the image part of the stencil (the point
 * kernel's images are added separately). Padding entries of g are left untouched (zero). */
static void make_row(const mc_stress_tables *tb, stress_fn fn, double z, const rule *rx,
                     const xpoints *px, double Y, int with_lattice, double *fv, double *g)
{
    const axis *a = &tb->ax[0];
    const double d = a->d, nu = tb->nu;
    const int tx = tb->tx;
    if (with_lattice)
        for (int q = 0; q < px->nlat; q++)
            fn((rx->clo + q - 0.5) * d, Y, z, nu, fv + 6 * q);
    for (int q = 0; q < px->nh; q++) {
        const double o = a->olo - a->J + q;
        fn((o + rx->H) * d, Y, z, nu, fv + 6 * (px->hp + q));
        fn((o - rx->H) * d, Y, z, nu, fv + 6 * (px->hm + q));
    }
    if (rx->strips) {
        fn(tb->far, Y, z, nu, fv + 6 * px->fp);
        fn(-tb->far, Y, z, nu, fv + 6 * px->fm);
    }
    const int lat = with_lattice && rx->M >= 0;
    for (int o = a->olo; o <= a->ohi; o++) {
        const int t = a->index[o - a->olo];
        for (int c = 0; c < MC_NSTRESS; c++) {
            double v = 0.0;
            if (lat)
                for (int k = -rx->M; k <= rx->M; k++) {
                    const int q = o + k * a->n - rx->clo; /* lower corner of cell o + kn */
                    v += fv[6 * (q + 1) + c] - fv[6 * q + c];
                }
            if (rx->strips) {
                const double *hp = fv + 6 * (px->hp + o - a->olo + a->J) + c;
                const double *hm = fv + 6 * (px->hm + o - a->olo + a->J) + c;
                v += strip_combine(a, rx, fv[6 * px->fp + c], fv[6 * px->fm + c], hp, hm, 6);
            }
            g[(size_t)c * tx + t] = v;
        }
    }
}

/* Rotate a window of w row pointers left by one (the first becomes the last, to be refilled). */
static void rotate(double **win, int w)
{
    double *first = win[0];
    memmove(win, win + 1, sizeof *win * (size_t)(w - 1));
    win[w - 1] = first;
}

/* Table rows for the y offsets oa..ob (a block) from streamed rows. */
static void stream_block(const mc_stress_tables *tb, stress_fn fn, double z, const rule *rx,
                         const rule *ry, const xpoints *px, int lat_rows, int with_lattice_x,
                         int oa, int ob, workspace *w, double *const k[6])
{
    const axis *ay = &tb->ax[1];
    const double dy = ay->d;
    const int tx = tb->tx, J = ay->J, W = 2 * J + 1;
    const int nlatk = (lat_rows && ry->M >= 0) ? 2 * ry->M + 1 : 0;
    const int hrows = ry->strips && ry->M >= 0;
    if (ry->strips) {
        make_row(tb, fn, z, rx, px, tb->far, 1, w->fv, w->farp);
        make_row(tb, fn, z, rx, px, -tb->far, 1, w->fv, w->farm);
    }
    for (int kk = 0; kk < nlatk; kk++) {
        const int kimg = kk - ry->M;
        make_row(tb, fn, z, rx, px, (oa + kimg * ay->n - 0.5) * dy, with_lattice_x, w->fv,
                 w->lo[kk]);
    }
    if (hrows)
        for (int j = 0; j < W - 1; j++) { /* window slots 0..W-2 hold o + j - J */
            make_row(tb, fn, z, rx, px, (oa + j - J + ry->H) * dy, 1, w->fv, w->hp[j]);
            make_row(tb, fn, z, rx, px, (oa + j - J - ry->H) * dy, 1, w->fv, w->hm[j]);
        }
    for (int o = oa; o <= ob; o++) {
        for (int kk = 0; kk < nlatk; kk++) {
            const int kimg = kk - ry->M;
            make_row(tb, fn, z, rx, px, (o + kimg * ay->n + 0.5) * dy, with_lattice_x, w->fv,
                     w->up[kk]);
        }
        if (hrows) {
            make_row(tb, fn, z, rx, px, (o + J + ry->H) * dy, 1, w->fv, w->hp[W - 1]);
            make_row(tb, fn, z, rx, px, (o + J - ry->H) * dy, 1, w->fv, w->hm[W - 1]);
        }
        const size_t t = (size_t)ay->index[o - ay->olo];
        for (int c = 0; c < MC_NSTRESS; c++) {
            double *out = k[c] + t * tx;
            const size_t off = (size_t)c * tx;
            for (int i = 0; i < tx; i++) {
                double v = 0.0;
                for (int kk = 0; kk < nlatk; kk++)
                    v += w->up[kk][off + i] - w->lo[kk][off + i];
                if (ry->strips) {
                    double hp[5], hm[5]; /* the window at this entry, centred on index J */
                    if (hrows)
                        for (int j = 0; j < W; j++) {
                            hp[j] = w->hp[j][off + i];
                            hm[j] = w->hm[j][off + i];
                        }
                    v += strip_combine(ay, ry, w->farp[off + i], w->farm[off + i], hp + J, hm + J,
                                       1);
                }
                out[i] = v;
            }
        }
        for (int kk = 0; kk < nlatk; kk++) {
            double *tmp = w->lo[kk];
            w->lo[kk] = w->up[kk];
            w->up[kk] = tmp;
        }
        if (hrows) {
            rotate(w->hp, W);
            rotate(w->hm, W);
        }
    }
}

/* The point kernel's images: k += dx dy sum over images of the point-force stresses. */
static void add_point_images(const mc_stress_tables *tb, int li, double z, const rule *rx,
                             const rule *ry, double *const k[6])
{
    const axis *ax = &tb->ax[0], *ay = &tb->ax[1];
    const double A = ax->d * ay->d, nu = tb->nu;
    const stress_fn fn = point_fns[li];
    const int tx = tb->tx;
#pragma omp parallel for schedule(dynamic) num_threads(tb->nthreads)
    for (int oy = ay->olo; oy <= ay->ohi; oy++) {
        const size_t ty_i = (size_t)ay->index[oy - ay->olo];
        for (int ox = ax->olo; ox <= ax->ohi; ox++) {
            const size_t t = ty_i * tx + (size_t)ax->index[ox - ax->olo];
            double sum[MC_NSTRESS] = {0}, s[MC_NSTRESS];
            for (int ky = -ry->M; ky <= ry->M; ky++)
                for (int kx = -rx->M; kx <= rx->M; kx++) {
                    fn((ox + kx * ax->n) * ax->d, (oy + ky * ay->n) * ay->d, z, nu, s);
                    for (int c = 0; c < MC_NSTRESS; c++)
                        sum[c] += s[c];
                }
            for (int c = 0; c < MC_NSTRESS; c++)
                k[c][t] += A * sum[c];
        }
    }
}

/* Fully periodic: the mean (Fourier mode 0) of each table, set exactly (stress.h). */
static void set_means(const mc_stress_tables *tb, int li, double *const k[6])
{
    const size_t n = (size_t)tb->tx * tb->ty;
    const double inv = 1.0 / (double)n;
    /* the equilibrium mean of each component under a unit load on one cell of n */
    double exact[MC_NSTRESS] = {0};
    exact[li == 0 ? MC_SZZ : (li == 1 ? MC_SXZ : MC_SYZ)] = -inv;
    for (int c = 0; c < MC_NSTRESS; c++) {
        double s = 0.0;
        for (size_t i = 0; i < n; i++)
            s += k[c][i];
        const double shift = exact[c] - s * inv;
        for (size_t i = 0; i < n; i++)
            k[c][i] += shift;
    }
}

static int load_index(int load)
{
    return load == MC_LOAD_P ? 0 : load == MC_LOAD_QX ? 1 : load == MC_LOAD_QY ? 2 : -1;
}

int mc_stress_tables_build(mc_stress_tables *tb, int load, double z, double *const k[6],
                           mc_error *err)
{
    const int li = load_index(load);
    if (li < 0)
        return mc_fail(err, MC_ERR_INPUT, "stress tables: load %d is not one of p, qx, qy", load);
    if (!(isfinite(z) && z >= 0.0))
        return mc_fail(err, MC_ERR_INPUT, "stress tables: depth z = %g m must be finite and >= 0",
                       z);
    if (tb->kernel == MC_STRESS_POINT && z == 0.0)
        return mc_fail(err, MC_ERR_INPUT,
                       "stress tables: the point kernel is singular at z = 0 (use the patch "
                       "kernel, or a depth > 0)");
    const axis *ax = &tb->ax[0], *ay = &tb->ax[1];
    const rule rx = axis_rule(ax, z), ry = axis_rule(ay, z);
    const xpoints px = x_layout(ax, &rx);
    const int point = tb->kernel == MC_STRESS_POINT;
    /* the point kernel takes only the strips from the corner functions: image rows along y carry
     * the x strips alone, and vanish on a free x axis */
    const int lat_rows = !point || rx.strips;
    const int stream = lat_rows || ry.strips;
    const int tx = tb->tx;

    for (int t = 0; t < tb->ty; t++) { /* padding rows of a free y axis, and all rows if no stream */
        int used;
        mc_table_offset(t, ay->n, ay->len, &used);
        if (!used || !stream)
            for (int c = 0; c < MC_NSTRESS; c++)
                memset(k[c] + (size_t)t * tx, 0, sizeof(double) * (size_t)tx);
    }
    if (stream) {
        const int nO = ay->ohi - ay->olo + 1;
        const int nb = nO < tb->nthreads ? nO : tb->nthreads;
#pragma omp parallel for schedule(static) num_threads(tb->nthreads)
        for (int b = 0; b < nb; b++) {
            const int oa = ay->olo + (int)((long)nO * b / nb);
            const int ob = ay->olo + (int)((long)nO * (b + 1) / nb) - 1;
            stream_block(tb, corner_fns[li], z, &rx, &ry, &px, lat_rows, !point, oa, ob,
                         &tb->ws[omp_get_thread_num()], k);
        }
    }
    if (point && rx.M >= 0 && ry.M >= 0)
        add_point_images(tb, li, z, &rx, &ry, k);
    if (ax->periodic && ay->periodic)
        set_means(tb, li, k);
    return MC_OK;
}

int mc_stress_tables_images(const mc_stress_tables *tb, int axis_id, double z)
{
    return axis_rule(&tb->ax[axis_id ? 1 : 0], z).M;
}

static void workspace_free(workspace *w)
{
    mc_free(w->fv);
    mc_free(w->rows);
    mc_free(w->ptr);
}

void mc_stress_tables_destroy(mc_stress_tables **tbp)
{
    if (!tbp || !*tbp)
        return;
    mc_stress_tables *tb = *tbp;
    if (tb->ws)
        for (int i = 0; i < tb->nthreads; i++)
            workspace_free(&tb->ws[i]);
    mc_free(tb->ws);
    mc_free(tb->ax[0].index);
    mc_free(tb->ax[1].index);
    mc_free(tb);
    *tbp = NULL;
}

/* Row buffers for the largest stencils (the shallow-depth rules); zeroed, so padding entries of
 * every row stay 0. */
static int workspace_alloc(mc_stress_tables *tb, workspace *w)
{
    const axis *ay = &tb->ax[1];
    const int nlat = 2 * ay->M + 1, W = 2 * ay->J + 1;
    const size_t rowlen = (size_t)MC_NSTRESS * tb->tx;
    size_t nrows = 2 * (size_t)nlat + 2 * (size_t)W + 2, total;
    if (!mc_size_mul(nrows, rowlen, &total))
        return MC_ERR_NOMEM;
    w->fv = mc_zeros(tb->nfv);
    w->rows = mc_zeros(total);
    w->ptr = mc_calloc(2 * (size_t)nlat + 2 * (size_t)W, sizeof *w->ptr);
    if (!w->fv || !w->rows || !w->ptr)
        return MC_ERR_NOMEM;
    w->lo = w->ptr;
    w->up = w->lo + nlat;
    w->hp = w->up + nlat;
    w->hm = w->hp + W;
    double *r = w->rows;
    for (int i = 0; i < 2 * nlat + 2 * W; i++, r += rowlen)
        w->ptr[i] = r;
    w->farp = r;
    w->farm = r + rowlen;
    return MC_OK;
}

int mc_stress_tables_create(const mc_grid *g, int tx, int ty, mc_stress_kernel kernel, double nu,
                            int images, mc_stress_tables **out, mc_error *err)
{
    *out = NULL;
    int rc = mc_grid_check(g, err);
    if (rc)
        return rc;
    const int okx = g->periodic_x ? tx == g->nx : tx >= 2 * g->nx - 1;
    const int oky = g->periodic_y ? ty == g->ny : ty >= 2 * g->ny - 1;
    if (!okx || !oky)
        return mc_fail(err, MC_ERR_INPUT,
                       "stress tables %d x %d do not fit grid %d x %d (periodic x %d, y %d)", tx,
                       ty, g->nx, g->ny, g->periodic_x, g->periodic_y);
    if (kernel != MC_STRESS_PATCH && kernel != MC_STRESS_POINT)
        return mc_fail(err, MC_ERR_INPUT, "stress tables: unknown kernel %d", (int)kernel);
    if (!(nu > -1.0 && nu <= 0.5))
        return mc_fail(err, MC_ERR_INPUT, "stress tables: Poisson ratio %g not in (-1, 0.5]", nu);
    mc_stress_tables *tb = mc_calloc(1, sizeof *tb);
    if (!tb)
        return mc_fail(err, MC_ERR_NOMEM, "stress tables: out of memory");
    tb->g = *g;
    tb->tx = tx;
    tb->ty = ty;
    tb->kernel = kernel;
    tb->nu = nu;
    tb->far = MC_STRESS_FAR_EDGE * fmax(g->nx * g->dx, g->ny * g->dy);
    tb->nthreads = mc_get_threads();
    if ((rc = axis_setup(&tb->ax[0], g->nx, tx, g->periodic_x, g->dx, images, err)) ||
        (rc = axis_setup(&tb->ax[1], g->ny, ty, g->periodic_y, g->dy, images, err))) {
        mc_stress_tables_destroy(&tb);
        return rc;
    }
    const rule r0 = axis_rule(&tb->ax[0], 0.0);
    tb->nfv = (size_t)MC_NSTRESS * (size_t)x_layout(&tb->ax[0], &r0).total;
    if (!(tb->ws = mc_calloc((size_t)tb->nthreads, sizeof *tb->ws))) {
        mc_stress_tables_destroy(&tb);
        return mc_fail(err, MC_ERR_NOMEM, "stress tables: out of memory");
    }
    for (int i = 0; i < tb->nthreads; i++)
        if (workspace_alloc(tb, &tb->ws[i]) != MC_OK) {
            mc_stress_tables_destroy(&tb);
            return mc_fail(err, MC_ERR_NOMEM,
                           "stress tables %d x %d: out of memory for the row workspaces", tx, ty);
        }
    *out = tb;
    return MC_OK;
}
