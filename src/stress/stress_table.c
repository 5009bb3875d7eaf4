/* stress_table.c - kernel tables of the subsurface stresses at one depth (see stress.h).
 *
 * A table entry is a 1-D "stencil" along x times one along y applied to a 2-D function. Along an
 * axis the entry of cell offset o (field minus source, in cells) is
 *   free axis:      f(o + 1/2) - f(o - 1/2)                          (corner positions)
 *   periodic axis:  sum_{|k| <= M} [f(o + kn + 1/2) - f(o + kn - 1/2)]               (images)
 *                   + (1/n) { f(o + F) - f(o - F) - [C f(o + H) - C f(o - H)] }       (strips)
 * with H = (M + 1/2) n the edge of the smeared strips, F their far edge and C f(u) =
 * f(u) + e2 d2 f(u) + e4 d4 f(u), d2 and d4 the central second and fourth differences of step s
 * cells. The braces are the load 2b/L = 1/n per unit length replacing the images |k| > M, with the
 * midpoint Euler-Maclaurin corrections: for a pixel of width 2b repeated with period L = 2bn and
 * a corner function G (the pixel's stress is G(y + b) - G(y - b)),
 *   sum_{k > M} = (2b/L) [G(y - H) - G(y - F)] + (2b/L) [c2 G''(y - H) + c4 G''''(y - H)] + ...,
 *   c2 = (1 - n^2) (2b)^2/24,   c4 = b^4 [1/120 - n^2/36 + 7 n^4/360]
 * (both vanish for n = 1: the pixels tile the strip), and the images k < -M mirror it. The
 * differences replace the derivatives: G'' = (d2 - d4/12)/h^2, G'''' = d4/h^4, h = s d. The 2-D
 * table is the product of the x and y stencils applied to the corner function of kernel.h (patch
 * kernel): the images x images, images x strips and strips x strips parts of the plane.
 *
 * Evaluation streams over lines Y = const ("rows"): a row is the x stencil of every x entry
 * applied to the corner function on that line, evaluated once per distinct X (the corner lattice
 * of theory.md §5.5 plus the strip points). Table rows are split into OpenMP blocks of consecutive
 * y offsets; a block computes each distinct Y its stencils need once (the upper corner of o is the
 * lower corner of o + 1, strip points are shared by neighbours) and adds the row, weighted, to
 * every table row of the block whose stencil holds it.
 *
 * The point kernel: its images are point forces (mc_point_stress_* times dx dy), summed directly;
 * its smeared strips are those of the patch kernel (the same loads smeared; the pixel's own width
 * changes the strips by O((d/H)^2) of their small contribution).
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/alloc.h"
#include "kernels/kernel.h"
#include "stress/stress.h"
#include "stress/stress_internal.h"

/* Table entries below which a layer's table is built on one thread: the corner functions cost
 * ~30 ns each, so a few thousand entries do not pay for waking the thread team (the memory-bound
 * loops elsewhere use the larger MC_THREADS_MIN_CELLS). */
#define TABLE_PAR_MIN 16384

/* Step of the difference stencils of the strip corrections, cells: max(1, n/DIFF_STEP_DIV). At one
 * cell the fourth difference times e4 ~ n^4/800 would amplify the round-off of the corner
 * functions (|f| up to ~30 for their logs) to ~ n^3 eps; at n/8 cells it stays ~ eps, while the
 * truncation error of the differences, O((s d/H)^4) of a correction that is itself small, is
 * negligible. */
#define DIFF_STEP_DIV 8

typedef void (*stress_fn)(double X, double Y, double z, double nu, double f[MC_NSTRESS]);

static const stress_fn corner_fns[3] = {mc_rect_corner_p, mc_rect_corner_qx, mc_rect_corner_qy};
static const stress_fn point_fns[3] = {mc_point_stress_p, mc_point_stress_qx, mc_point_stress_qy};

#define NSTRIP 5 /* points of the strip stencil per side, offsets j s for j = -2..2 */

typedef struct {
    int n, len, periodic;
    double d;             /* cell size, m */
    int olo, ohi;         /* cell offsets of the used table entries (contiguous) */
    int *index;           /* table index of offset o: index[o - olo] */
    int images;           /* forced images per side (> 0), or 0: automatic (depth dependent) */
    int s;                /* step of the strip stencil, cells */
    double cs[NSTRIP];    /* strip stencil: f(H + js) weights, value + Euler-Maclaurin terms */
} axis;

/* The stencil of one axis at one depth. */
typedef struct {
    int M;        /* images per side (0 on a free axis), or -1: the whole image sum smeared */
    int strips;   /* periodic: the smeared strips (and far edges) take part */
    double H;     /* strip edge, cells */
    int clo, chi; /* cells of the image lattice: corners clo - 1/2 ... chi + 1/2 */
} rule;

typedef struct {
    double *fv;  /* corner function at the x points of one row, 6 per point */
    double *row; /* one row, 6*tx */
    double *qf;  /* quadrant: corner function on one line of corners, 6 per corner (nx + 1) */
    double *qd;  /* quadrant: x differences of two lines, [2][6][nx] */
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
    size_t nfv; /* doubles of fv */
};

/* Images per side along a periodic axis of n cells at depth z (period L = n d). The strip error,
 * measured as the table change from M to 2M relative to the largest entry of the load's six
 * tables (tests/test_stress.c), follows err(M) ~ E (4/M)^TAIL_ORDER with E = TAIL_SURF/n^2 +
 * TAIL_DEPTH min(z/L, 1.5)^2 (fitted on n = 2..128, z/L = 0..4.5; the n^-2 term is the pixel
 * effect near the surface, the other the smoothness of the far field); M is the smallest with
 * err <= TAIL_TARGET, and at least 2, so that the strip stencil stays clear of the singular lines
 * X = 0, Y = 0 at z = 0. Deep tables of large periods reach the round-off floor of the corner
 * differences first (eps (z/d)^2, theory.md §5.5). */
#define TAIL_ORDER 6.6
#define TAIL_SURF 7e-7
#define TAIL_DEPTH 4e-6
#define TAIL_TARGET 5e-10
#define AUTO_IMAGES_MAX 24
static int auto_images(int n, double zl)
{
    const double q = fmin(zl, 1.5);
    const double E = TAIL_SURF / ((double)n * n) + TAIL_DEPTH * q * q;
    const int m = (int)ceil(4.0 * pow(E / TAIL_TARGET, 1.0 / TAIL_ORDER));
    return m < 2 ? 2 : (m > AUTO_IMAGES_MAX ? AUTO_IMAGES_MAX : m);
}

/* The stencil of a periodic axis with M >= 0 images per side. */
static rule images_rule(const axis *a, int M)
{
    rule r = {M, 1, (M + 0.5) * a->n, a->olo - M * a->n, a->ohi + M * a->n};
    return r;
}

static rule axis_rule(const axis *a, double z)
{
    if (!a->periodic) {
        rule r = {0, 0, 0.0, a->olo, a->ohi};
        return r;
    }
    const double zl = z / (a->n * a->d);
    if (a->n == 1 || zl >= MC_STRESS_SMEAR_DEPTH) {
        rule r = {-1, 1, 0.0, 0, 0};
        return r;
    }
    return images_rule(a, a->images > 0 ? a->images : auto_images(a->n, zl));
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
    a->images = images > 0 ? (images < 2 ? 2 : images) : 0; /* >= 2: see auto_images */
    a->s = n / DIFF_STEP_DIV > 1 ? n / DIFF_STEP_DIV : 1;
    /* c2 G'' + c4 G from differences of step h = s d: G = (d2 - d4/12)/h^2, G = d4/h^4 */
    const double nn = (double)n * n, r2 = 1.0 / ((double)a->s * a->s);
    const double e2 = (1.0 - nn) / 24.0 * r2;
    const double c4 = (1.0 / 120.0 - nn / 36.0 + 7.0 * nn * nn / 360.0) / 16.0; /* c4 / d^4 */
    const double e4 = c4 * r2 * r2 - e2 / 12.0;
    static const double d2[NSTRIP] = {0, 1, -2, 1, 0}, d4[NSTRIP] = {1, -4, 6, -4, 1};
    for (int j = 0; j < NSTRIP; j++)
        a->cs[j] = (j == NSTRIP / 2) + e2 * d2[j] + e4 * d4[j];
    return MC_OK;
}

/* x points of a row, in buffer order: lattice corners, strip points at +H, at -H, far +, far -. */
typedef struct {
    int nlat;   /* lattice corners (0 if none) */
    int nh;     /* strip points per side (0 if none): offsets olo - 2s ... ohi + 2s */
    int hp, hm; /* first strip point at +H, -H */
    int fp, fm; /* far points (-1 if none) */
    int total;
} xpoints;

static xpoints x_layout(const axis *a, const rule *r)
{
    xpoints p = {0, 0, 0, 0, -1, -1, 0};
    if (r->M >= 0)
        p.nlat = r->chi - r->clo + 2;
    if (r->strips && r->M >= 0)
        p.nh = a->ohi - a->olo + 1 + (NSTRIP - 1) * a->s;
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

/* One row: g[c*tx + t] = the x stencil of the entry at table index t applied to the corner
 * function on the line Y (m). with_lattice = 0 drops the image part of the stencil (the point
 * kernel's images are added separately). Padding entries of g are left untouched (zero). */
static void make_row(const mc_stress_tables *tb, stress_fn fn, double z, const rule *rx,
                     const xpoints *px, double Y, int with_lattice, double *fv, double *g)
{
    const axis *a = &tb->ax[0];
    const double d = a->d, nu = tb->nu;
    const int tx = tb->tx, s = a->s, h = NSTRIP / 2;
    if (with_lattice)
        for (int q = 0; q < px->nlat; q++)
            fn((rx->clo + q - 0.5) * d, Y, z, nu, fv + 6 * q);
    for (int q = 0; q < px->nh; q++) {
        const double u = a->olo - h * s + q;
        fn((u + rx->H) * d, Y, z, nu, fv + 6 * (px->hp + q));
        fn((u - rx->H) * d, Y, z, nu, fv + 6 * (px->hm + q));
    }
    if (rx->strips) {
        fn(tb->far, Y, z, nu, fv + 6 * px->fp);
        fn(-tb->far, Y, z, nu, fv + 6 * px->fm);
    }
    const int lat = with_lattice && rx->M >= 0, hstrip = rx->strips && rx->M >= 0;
    const double w = 1.0 / a->n; /* smeared load per unit length: 2a/L */
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
                double st = fv[6 * px->fp + c] - fv[6 * px->fm + c];
                if (hstrip)
                    for (int j = 0; j < NSTRIP; j++) {
                        const int q = o - a->olo + j * s; /* offset o + (j - h) s */
                        st -= a->cs[j] * (fv[6 * (px->hp + q) + c] - fv[6 * (px->hm + q) + c]);
                    }
                v += w * st;
            }
            g[(size_t)c * tx + t] = v;
        }
    }
}

/* k rows of offset o += wgt * g */
static inline void add_row(const mc_stress_tables *tb, double *const k[6], int o, double wgt,
                           const double *g)
{
    const axis *ay = &tb->ax[1];
    const int tx = tb->tx;
    const size_t t = (size_t)ay->index[o - ay->olo] * tx;
    for (int c = 0; c < MC_NSTRESS; c++) {
        double *out = k[c] + t;
        const double *in = g + (size_t)c * tx;
        for (int i = 0; i < tx; i++)
            out[i] += wgt * in[i];
    }
}

/* Table rows of the y offsets oa..ob (a block): each streamed row is computed once and added to
 * every row of the block whose y stencil holds its Y. */
static void stream_block(const mc_stress_tables *tb, stress_fn fn, double z, const rule *rx,
                         const rule *ry, const xpoints *px, int lat_rows, int with_lattice_x,
                         int oa, int ob, workspace *ws, double *const k[6])
{
    const axis *ay = &tb->ax[1];
    const double dy = ay->d;
    const int tx = tb->tx, n = ay->n, s = ay->s, h = NSTRIP / 2;
    for (int o = oa; o <= ob; o++)
        for (int c = 0; c < MC_NSTRESS; c++)
            memset(k[c] + (size_t)ay->index[o - ay->olo] * tx, 0, sizeof(double) * (size_t)tx);
    if (ry->strips) {
        const double w = 1.0 / n;
        for (int side = 1; side >= -1; side -= 2) {
            make_row(tb, fn, z, rx, px, side * tb->far, 1, ws->fv, ws->row);
            for (int o = oa; o <= ob; o++)
                add_row(tb, k, o, side * w, ws->row);
            if (ry->M < 0)
                continue;
            /* strip points u + side H, u = o + (j - h) s */
            for (int u = oa - h * s; u <= ob + h * s; u++) {
                make_row(tb, fn, z, rx, px, (u + side * ry->H) * dy, 1, ws->fv, ws->row);
                for (int j = 0; j < NSTRIP; j++) {
                    const int o = u - (j - h) * s;
                    if (o >= oa && o <= ob && ay->cs[j] != 0.0)
                        add_row(tb, k, o, -side * w * ay->cs[j], ws->row);
                }
            }
        }
    }
    if (lat_rows && ry->M >= 0)
        for (int kimg = -ry->M; kimg <= ry->M; kimg++)
            /* corner c - 1/2 (c = o + kn) is the lower corner of cell c and the upper of c - 1 */
            for (int c = oa + kimg * n; c <= ob + kimg * n + 1; c++) {
                make_row(tb, fn, z, rx, px, (c - 0.5) * dy, with_lattice_x, ws->fv, ws->row);
                const int o = c - kimg * n;
                if (o <= ob)
                    add_row(tb, k, o, -1.0, ws->row);
                if (o - 1 >= oa)
                    add_row(tb, k, o - 1, 1.0, ws->row);
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
    const size_t work = (size_t)(ay->ohi - ay->olo + 1) * (size_t)(ax->ohi - ax->olo + 1);
#pragma omp parallel for schedule(dynamic) num_threads(tb->nthreads) if (work > TABLE_PAR_MIN)
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

/* Tables with a periodic axis made exactly even or odd in each offset (their parity,
 * mc_stress_parity): the entry at o and the one at -o (index t and (len - t) mod len, on both
 * kinds of axis) averaged with the parity's sign. The kernel has that symmetry, but an image sum
 * truncated at M images per side is not symmetric at the offset n/2 of an even period (its images
 * run from -M to M on one side, -M - 1 to M - 1 on the other): the average halves that tail's
 * asymmetry, and the tables' spectra become exactly real or imaginary and even or odd in ky, so
 * that the plan keeps a quarter of them (stress.c compact_spectrum; theory.md §9.9). */
static void make_symmetric(const mc_stress_tables *tb, int load, double *const k[6])
{
    const int tx = tb->tx, ty = tb->ty;
    for (int c = 0; c < MC_NSTRESS; c++) {
        const int par = mc_stress_parity(load, c);
        const double sx = (par & 1) ? -1.0 : 1.0, sy = (par & 2) ? -1.0 : 1.0;
        double *a = k[c];
        for (int u = 0; u < ty; u++) {
            const int um = (ty - u) % ty;
            if (um < u)
                continue; /* (done with its mirror) */
            for (int t = 0; t < tx; t++) {
                const int tm = (tx - t) % tx;
                if (um == u && tm < t)
                    continue;
                const size_t i00 = (size_t)u * tx + t, i10 = (size_t)u * tx + tm,
                             i01 = (size_t)um * tx + t, i11 = (size_t)um * tx + tm;
                const double v = 0.25 * (a[i00] + sx * a[i10] + sy * a[i01] + sx * sy * a[i11]);
                a[i00] = v;
                a[i10] = sx * v;
                a[i01] = sy * v;
                a[i11] = sx * sy * v;
            }
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
    return load == MC_TRACTION_P    ? 0
           : load == MC_TRACTION_QX ? 1
           : load == MC_TRACTION_QY ? 2
                                    : -1;
}

int mc_stress_check_depth(mc_stress_kernel kernel, double z, const char *what, mc_error *err)
{
    if (!(isfinite(z) && z >= 0.0))
        return mc_fail(err, MC_ERR_INPUT, "%s: depth z = %g m must be finite and >= 0", what, z);
    if (kernel == MC_STRESS_POINT && z == 0.0)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: the point kernel is singular at z = 0 (use the patch kernel, or a "
                       "depth > 0)",
                       what);
    return MC_OK;
}

/* The index of load (p, q_x, q_y: 0, 1, 2) after checking it and the depth z for the tables of
 * tb; MC_ERR_INPUT (messages prefixed by what) for a bad load or depth. */
static int check_layer(const mc_stress_tables *tb, int load, double z, const char *what, int *li,
                       mc_error *err)
{
    *li = load_index(load);
    if (*li < 0)
        return mc_fail(err, MC_ERR_INPUT, "%s: load %d is not one of p, qx, qy", what, load);
    return mc_stress_check_depth(tb->kernel, z, what, err);
}

int mc_stress_tables_build(mc_stress_tables *tb, int load, double z, double *const k[6],
                           mc_error *err)
{
    int li, rc = check_layer(tb, load, z, "stress tables", &li, err);
    if (rc)
        return rc;
    const axis *ax = &tb->ax[0], *ay = &tb->ax[1];
    const rule rx = axis_rule(ax, z), ry = axis_rule(ay, z);
    const xpoints px = x_layout(ax, &rx);
    const int point = tb->kernel == MC_STRESS_POINT;
    /* the point kernel takes only the strips from the corner functions: image rows along y carry
     * the x strips alone, and vanish on a free x axis */
    const int lat_rows = !point || rx.strips;
    const int stream = lat_rows || ry.strips;
    const int tx = tb->tx;

    /* padding rows of a free y axis, and all rows when nothing is streamed */
    for (int t = 0; t < tb->ty; t++) {
        int used;
        mc_table_offset(t, ay->n, ay->len, &used);
        if (!used || !stream)
            for (int c = 0; c < MC_NSTRESS; c++)
                memset(k[c] + (size_t)t * tx, 0, sizeof(double) * (size_t)tx);
    }
    if (stream) {
        const int nO = ay->ohi - ay->olo + 1;
        const int nb = nO < tb->nthreads ? nO : tb->nthreads;
        const size_t work = (size_t)nO * (size_t)(tb->ax[0].ohi - tb->ax[0].olo + 1);
#pragma omp parallel for schedule(static) num_threads(tb->nthreads) if (work > TABLE_PAR_MIN)
        for (int b = 0; b < nb; b++) {
            const int oa = ay->olo + (int)((long)nO * b / nb);
            const int ob = ay->olo + (int)((long)nO * (b + 1) / nb) - 1;
            stream_block(tb, corner_fns[li], z, &rx, &ry, &px, lat_rows, !point, oa, ob,
                         &tb->ws[omp_get_thread_num()], k);
        }
    }
    if (point && rx.M >= 0 && ry.M >= 0)
        add_point_images(tb, li, z, &rx, &ry, k);
    if (ax->periodic || ay->periodic)
        make_symmetric(tb, load, k);
    if (ax->periodic && ay->periodic)
        set_means(tb, li, k);
    return MC_OK;
}

/* ---- quadrant tables (free axes) -------------------------------------------------------------- */

/* Odd flags of the tables (bit 0: odd in the x offset, bit 1: odd in the y offset), kernel.h's
 * parities: p: xx, yy, zz ee, xy oo, yz eo, xz oe; qx: xx, yy, zz oe, xy eo, yz oo, xz ee; qy: qx
 * with the axes exchanged. */
static const int parities[3][MC_NSTRESS] = {
    {0, 0, 0, 3, 2, 1},
    {1, 1, 1, 2, 3, 0},
    {2, 2, 2, 1, 0, 3},
};

int mc_stress_parity(int load, int c)
{
    const int li = load_index(load);
    return li < 0 || c < 0 || c >= MC_NSTRESS ? -1 : parities[li][c];
}

/* Quadrant rows ja..jb (a block of one thread) of the patch kernel: entry (i, j) = D_{j+1}[i] -
 * D_j[i] with D_j[i] = f(X_{i+1}, Y_j) - f(X_i, Y_j) and corners X_i = (i - 1/2) dx, Y_j =
 * (j - 1/2) dy: the same differences, in the same order, as the streamed full table, so both
 * agree bit for bit. */
static void quadrant_block(const mc_stress_tables *tb, stress_fn fn, double z, int nxq, int ja,
                           int jb, int qx, workspace *ws, double *const q[6])
{
    const double dx = tb->ax[0].d, dy = tb->ax[1].d, nu = tb->nu;
    double *d[2] = {ws->qd, ws->qd + (size_t)MC_NSTRESS * nxq};
    for (int j = ja; j <= jb + 1; j++) {
        const double Y = (j - 0.5) * dy;
        for (int i = 0; i <= nxq; i++)
            fn((i - 0.5) * dx, Y, z, nu, ws->qf + 6 * i);
        double *cur = d[j & 1];
        for (int c = 0; c < MC_NSTRESS; c++)
            for (int i = 0; i < nxq; i++)
                cur[(size_t)c * nxq + i] = ws->qf[6 * (i + 1) + c] - ws->qf[6 * i + c];
        if (j == ja)
            continue;
        const double *prev = d[(j - 1) & 1];
        for (int c = 0; c < MC_NSTRESS; c++) {
            double *row = q[c] + (size_t)(j - 1) * qx;
            for (int i = 0; i < nxq; i++)
                row[i] = cur[(size_t)c * nxq + i] - prev[(size_t)c * nxq + i];
        }
    }
}

int mc_stress_tables_quadrant(mc_stress_tables *tb, int load, double z, int qx, int qy,
                              double *const q[6], mc_error *err)
{
    int li, rc = check_layer(tb, load, z, "stress quadrant", &li, err);
    if (rc)
        return rc;
    if (tb->ax[0].periodic || tb->ax[1].periodic || qx < 1 || qy < 1)
        return mc_fail(err, MC_ERR_INPUT,
                       "stress quadrant %d x %d: needs free axes and sizes >= 1 (periodic x %d, "
                       "y %d)",
                       qx, qy, tb->ax[0].periodic, tb->ax[1].periodic);
    const int nxq = qx < tb->g.nx ? qx : tb->g.nx, nyq = qy < tb->g.ny ? qy : tb->g.ny;
    /* the slots beyond the grid's offsets are never reached by an output: 0 */
    for (int c = 0; c < MC_NSTRESS; c++)
        for (int j = 0; j < qy; j++) {
            double *row = q[c] + (size_t)j * qx;
            if (j < nyq)
                memset(row + nxq, 0, sizeof(double) * (size_t)(qx - nxq));
            else
                memset(row, 0, sizeof(double) * (size_t)qx);
        }
    if (tb->kernel == MC_STRESS_POINT) {
        const double A = tb->ax[0].d * tb->ax[1].d, nu = tb->nu;
#pragma omp parallel for schedule(static) num_threads(tb->nthreads) \
    if ((size_t)nyq * (size_t)nxq > TABLE_PAR_MIN)
        for (int j = 0; j < nyq; j++)
            for (int i = 0; i < nxq; i++) {
                double s[MC_NSTRESS];
                point_fns[li](i * tb->ax[0].d, j * tb->ax[1].d, z, nu, s);
                for (int c = 0; c < MC_NSTRESS; c++) /* 0 + : as the full table's sum (no -0) */
                    q[c][(size_t)j * qx + i] = 0.0 + A * s[c];
            }
    } else {
        const int nb = nyq < tb->nthreads ? nyq : tb->nthreads;
#pragma omp parallel for schedule(static) num_threads(tb->nthreads) \
    if ((size_t)nyq * (size_t)nxq > TABLE_PAR_MIN)
        for (int b = 0; b < nb; b++) {
            const int ja = (int)((long)nyq * b / nb), jb = (int)((long)nyq * (b + 1) / nb) - 1;
            quadrant_block(tb, corner_fns[li], z, nxq, ja, jb, qx, &tb->ws[omp_get_thread_num()],
                           q);
        }
    }
    /* an odd kernel vanishes at offset 0 along its odd axis: exactly, by parity */
    for (int c = 0; c < MC_NSTRESS; c++) {
        if (parities[li][c] & 1)
            for (int j = 0; j < nyq; j++)
                q[c][(size_t)j * qx] = 0.0;
        if (parities[li][c] & 2)
            memset(q[c], 0, sizeof(double) * (size_t)nxq);
    }
    return MC_OK;
}

int mc_stress_tables_images(const mc_stress_tables *tb, int axis_id, double z)
{
    return axis_rule(&tb->ax[axis_id ? 1 : 0], z).M;
}

static void workspace_free(workspace *w)
{
    mc_free(w->fv);
    mc_free(w->row);
    mc_free(w->qf);
    mc_free(w->qd);
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

/* One row buffer, zeroed: padding entries of every row stay 0. */
static int workspace_alloc(mc_stress_tables *tb, workspace *w)
{
    const size_t nx = (size_t)tb->g.nx;
    w->fv = mc_zeros(tb->nfv);
    w->row = mc_zeros((size_t)MC_NSTRESS * tb->tx);
    w->qf = mc_zeros((size_t)MC_NSTRESS * (nx + 1));
    w->qd = mc_zeros((size_t)2 * MC_NSTRESS * nx);
    return w->fv && w->row && w->qf && w->qd ? MC_OK : MC_ERR_NOMEM;
}

int mc_stress_tables_create(const mc_grid *g, int tx, int ty, mc_stress_kernel kernel, double nu,
                            int images, mc_stress_tables **out, mc_error *err)
{
    *out = NULL;
    int rc = mc_kernel_table_check(g, tx, ty, err);
    if (rc)
        return rc;
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
    tb->nthreads = mc_threads_count();
    if ((rc = axis_setup(&tb->ax[0], g->nx, tx, g->periodic_x, g->dx, images, err)) ||
        (rc = axis_setup(&tb->ax[1], g->ny, ty, g->periodic_y, g->dy, images, err))) {
        mc_stress_tables_destroy(&tb);
        return rc;
    }
    const axis *ax = &tb->ax[0];
    const rule rmax = ax->periodic ? images_rule(ax, ax->images > 0 ? ax->images : AUTO_IMAGES_MAX)
                                   : axis_rule(ax, 0.0); /* the largest x stencil */
    tb->nfv = (size_t)MC_NSTRESS * (size_t)x_layout(ax, &rmax).total;
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
