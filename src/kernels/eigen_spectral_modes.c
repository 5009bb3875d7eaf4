/* eigen_spectral_modes.c - the streamed depth step on many lateral modes at once
 * (eigen_spectral.h mc_spec_modes; docs/theory.md §8.10).
 *
 * The arithmetic of mc_spec_down_layer / mc_spec_turn / mc_spec_up_layer, laid out as a structure
 * of arrays over the modes and done a chunk of modes at a time, each step a loop over the chunk
 * (the compiler's vectors; the chunk's scratch stays in the first-level cache), and a block of
 * layers per visit of the states. Every mode's operations are those of the single-mode functions
 * up to the order of the sums inside the products (tests/test_eigen_spectral.c compares). */
#include "kernels/eigen_spectral.h"

#include <math.h>
#include <string.h>

#define CHUNK 32

/* one chunk's scratch: the layer's strain in the real form of the frame, the sums seen from
 * the layer, the result */
typedef struct {
    double f[12][CHUNK], u[12][CHUNK], v[12][CHUNK], o[12][CHUNK];
} chunk_work;

static double *field(const mc_spec_modes *m, int f) { return m->st + (size_t)f * (size_t)m->n; }

static double *weight(const mc_spec_modes *m, int k) { return m->wt + (size_t)k * (size_t)m->n; }

void mc_spec_modes_clear(mc_spec_modes *m)
{
    memset(m->st, 0, (size_t)MC_SPEC_FIELDS * (size_t)m->n * sizeof *m->st);
    double *et = field(m, MC_SPEC_ET);
    for (long i = 0; i < m->n; i++)
        et[i] = 1.0;
}

void mc_spec_modes_weights(mc_spec_modes *m, long i0, long i1, double thickness, mc_spec_point pt)
{
    for (long i = i0; i < i1; i++) {
        double w[MC_SPEC_WEIGHTS];
        mc_spec_weights_of(m->q[i] * thickness, pt, w);
        for (int k = 0; k < MC_SPEC_WEIGHTS; k++)
            weight(m, k)[i] = w[k];
    }
}

/* y[r] += sum_c M[r][c] x[c] over the chunk, re and im, for the pattern of A (17 entries), B (9)
 * or the local term (5) (eigen_spectral.c prod_a, prod_b, prod_local) */
#define ROW(r, EXPR)                                                                           \
    for (int j = 0; j < 2; j++) {                                                              \
        double *restrict y_ = y[2 * (r) + j];                                                  \
        const double *restrict x0 = x[j], *restrict x1 = x[2 + j], *restrict x2 = x[4 + j],    \
                               *restrict x3 = x[6 + j], *restrict x4 = x[8 + j],               \
                               *restrict x5 = x[10 + j];                                       \
        (void)x0, (void)x1, (void)x2, (void)x3, (void)x4, (void)x5;                            \
        _Pragma("omp simd") for (int i = 0; i < n; i++) y_[i] += EXPR;                         \
    }
#define X(c) (M[r_][c] * x##c[i])

static void prod_a_chunk(const double M[6][6], double x[12][CHUNK], double y[12][CHUNK], int n)
{
    int r_ = 0;
    ROW(0, X(0) + X(1) + X(2) + X(5));
    r_ = 1;
    ROW(1, X(0) + X(2) + X(5));
    r_ = 2;
    ROW(2, X(0) + X(1) + X(2));
    r_ = 3;
    ROW(3, X(3) + X(4));
    r_ = 4;
    ROW(4, X(3) + X(4));
    r_ = 5;
    ROW(5, X(0) + X(1) + X(5));
}

static void prod_b_chunk(const double M[6][6], double x[12][CHUNK], double y[12][CHUNK], int n)
{
    int r_ = 0;
    ROW(0, X(0) + X(2) + X(5));
    r_ = 2;
    ROW(2, X(0) + X(2) + X(5));
    r_ = 5;
    ROW(5, X(0) + X(2) + X(5));
}

static void prod_local_chunk(const double M[6][6], double x[12][CHUNK], double y[12][CHUNK],
                             int n)
{
    int r_ = 0;
    ROW(0, X(0) + X(1));
    r_ = 1;
    ROW(1, X(0) + X(1));
    r_ = 3;
    ROW(3, X(3));
}
#undef X
#undef ROW

/* the chunk's strain (lab, complex, mode i at e[c][bin i0 + i]) into the real form of the frame */
static void chunk_frame(const mc_spec_modes *m, long i0, int n, const double complex *const e[6],
                        chunk_work *w)
{
    const double *restrict cq = m->cq + i0, *restrict sq = m->sq + i0;
    const double *restrict e0 = (const double *)(e[0] + i0);
    const double *restrict e1 = (const double *)(e[1] + i0);
    const double *restrict e2 = (const double *)(e[2] + i0);
    const double *restrict e3 = (const double *)(e[3] + i0);
    const double *restrict e4 = (const double *)(e[4] + i0);
    const double *restrict e5 = (const double *)(e[5] + i0);
    for (int j = 0; j < 2; j++) { /* re, im */
#pragma omp simd
        for (int i = 0; i < n; i++) {
            const double c = cq[i], s = sq[i], cc = c * c, ss = s * s, cs = c * s;
            const double a0 = e0[2 * i + j], a1 = e1[2 * i + j], a3 = e3[2 * i + j];
            const double a4 = e4[2 * i + j], a5 = e5[2 * i + j];
            w->f[j][i] = cc * a0 + ss * a1 + 2.0 * cs * a3;
            w->f[2 + j][i] = ss * a0 + cc * a1 - 2.0 * cs * a3;
            w->f[4 + j][i] = e2[2 * i + j];
            w->f[6 + j][i] = cs * (a1 - a0) + (cc - ss) * a3;
            /* -i f4, -i f5: re <- im, im <- -re */
            const double f4 = c * a4 - s * a5, f5 = c * a5 + s * a4;
            if (j == 0) {
                w->f[9][i] = -f4;
                w->f[11][i] = -f5;
            } else {
                w->f[8][i] = f4;
                w->f[10][i] = f5;
            }
        }
    }
}

/* the chunk's result (real form of the frame) to lab, times wgt, into out (written, or added) */
static void chunk_lab(const mc_spec_modes *m, long i0, int n, const double *wgt, double scale,
                      chunk_work *w, double complex *const out[6], int add)
{
    const double *restrict cq = m->cq + i0, *restrict sq = m->sq + i0, *restrict ww = wgt + i0;
    double *restrict o0 = (double *)(out[0] + i0), *restrict o1 = (double *)(out[1] + i0),
                     *restrict o2 = (double *)(out[2] + i0), *restrict o3 = (double *)(out[3] + i0),
                     *restrict o4 = (double *)(out[4] + i0), *restrict o5 = (double *)(out[5] + i0);
    for (int j = 0; j < 2; j++) {
#pragma omp simd
        for (int i = 0; i < n; i++) {
            /* g = D o: g4 = i o4 (re = -im o4, im = re o4); then the frame of (c, -s) */
            const double c = cq[i], s = -sq[i], cc = c * c, ss = s * s, cs = c * s;
            const double g0 = w->o[j][i], g1 = w->o[2 + j][i], g2 = w->o[4 + j][i];
            const double g3 = w->o[6 + j][i];
            const double g4 = j == 0 ? -w->o[9][i] : w->o[8][i];
            const double g5 = j == 0 ? -w->o[11][i] : w->o[10][i];
            const double f = scale * ww[i];
            const double s0 = f * (cc * g0 + ss * g1 + 2.0 * cs * g3);
            const double s1 = f * (ss * g0 + cc * g1 - 2.0 * cs * g3);
            const double s2 = f * g2;
            const double s3 = f * (cs * (g1 - g0) + (cc - ss) * g3);
            const double s4 = f * (c * g4 - s * g5), s5 = f * (c * g5 + s * g4);
            if (add) {
                o0[2 * i + j] += s0, o1[2 * i + j] += s1, o2[2 * i + j] += s2;
                o3[2 * i + j] += s3, o4[2 * i + j] += s4, o5[2 * i + j] += s5;
            } else {
                o0[2 * i + j] = s0, o1[2 * i + j] = s1, o2[2 * i + j] = s2;
                o3[2 * i + j] = s3, o4[2 * i + j] = s4, o5[2 * i + j] = s5;
            }
        }
    }
}

/* u = al U, v = al V + ga U of the modes i0 .. i0 + n - 1 (v on the entries B reads) */
static void chunk_seen(const mc_spec_modes *m, long i0, int n, chunk_work *w)
{
    const double *restrict al = weight(m, MC_SPEC_AL) + i0;
    const double *restrict ga = weight(m, MC_SPEC_GA) + i0;
    for (int c = 0; c < 12; c++) {
        const double *restrict U = field(m, MC_SPEC_U + c) + i0;
#pragma omp simd
        for (int i = 0; i < n; i++) {
            w->u[c][i] = al[i] * U[i];
            w->o[c][i] = 0.0;
        }
    }
    for (int k = 0; k < MC_SPEC_NBLIVE; k++) {
        const int c = MC_SPEC_BLIVE[k];
        const double *restrict U = field(m, MC_SPEC_U + c) + i0;
        const double *restrict V = field(m, MC_SPEC_V + k) + i0;
#pragma omp simd
        for (int i = 0; i < n; i++)
            w->v[c][i] = al[i] * V[i] + ga[i] * U[i];
    }
}

/* past the layer: V = e^{-h} (V + h U) + p1 f (its live entries, from the old U), then
 * U = e^{-h} U + p0 f */
static void chunk_advance(const mc_spec_modes *m, long i0, int n, chunk_work *w)
{
    const double *restrict eh = weight(m, MC_SPEC_EH) + i0, *restrict h = weight(m, MC_SPEC_H) + i0,
                           *restrict p0 = weight(m, MC_SPEC_P0) + i0,
                           *restrict p1 = weight(m, MC_SPEC_P1) + i0;
    for (int k = 0; k < MC_SPEC_NBLIVE; k++) {
        const int c = MC_SPEC_BLIVE[k];
        const double *restrict U = field(m, MC_SPEC_U + c) + i0;
        double *restrict V = field(m, MC_SPEC_V + k) + i0;
        const double *restrict f = w->f[c];
#pragma omp simd
        for (int i = 0; i < n; i++)
            V[i] = eh[i] * (V[i] + h[i] * U[i]) + p1[i] * f[i];
    }
    for (int c = 0; c < 12; c++) {
        double *restrict U = field(m, MC_SPEC_U + c) + i0;
        const double *restrict f = w->f[c];
#pragma omp simd
        for (int i = 0; i < n; i++)
            U[i] = eh[i] * U[i] + p0[i] * f[i];
    }
}

static void chunk_down(const mc_spec_coef *k, mc_spec_modes *m, long i0, int n, double top,
                       const double complex *const e[6], const double *wgt, double scale,
                       double complex *const out[6], int add, chunk_work *w)
{
    chunk_frame(m, i0, n, e, w);
    chunk_seen(m, i0, n, w);
    prod_a_chunk(k->rAp, w->u, w->o, n); /* the layers above */
    prod_b_chunk(k->rBp, w->v, w->o, n);
    const double *restrict sa = weight(m, MC_SPEC_SA) + i0;
    const double *restrict sb = weight(m, MC_SPEC_SB) + i0;
    for (int c = 0; c < 12; c++) { /* its own: As (sa f) + Bs (sb f) + Minf f */
#pragma omp simd
        for (int i = 0; i < n; i++) {
            w->u[c][i] = sa[i] * w->f[c][i];
            w->v[c][i] = sb[i] * w->f[c][i];
        }
    }
    prod_a_chunk(k->rAs, w->u, w->o, n);
    prod_b_chunk(k->rBs, w->v, w->o, n);
    prod_local_chunk(k->rMinf, w->f, w->o, n);
    chunk_lab(m, i0, n, wgt, scale, w, out, add);
    /* the totals seen from the surface: e^{-x} p0 f and e^{-x} (x p0 + p1) f, x = q top */
    double *restrict et = field(m, MC_SPEC_ET) + i0;
    const double *restrict q = m->q + i0, *restrict p0 = weight(m, MC_SPEC_P0) + i0,
                           *restrict p1 = weight(m, MC_SPEC_P1) + i0;
    double w0[CHUNK], w1[CHUNK];
#pragma omp simd
    for (int i = 0; i < n; i++) {
        w0[i] = et[i] * p0[i];
        w1[i] = et[i] * (q[i] * top * p0[i] + p1[i]);
    }
    for (int c = 0; c < 12; c++) {
        double *restrict W0 = field(m, MC_SPEC_W0 + c) + i0;
#pragma omp simd
        for (int i = 0; i < n; i++)
            W0[i] += w0[i] * w->f[c][i];
    }
    for (int b = 0; b < MC_SPEC_NBLIVE; b++) {
        const int c = MC_SPEC_BLIVE[b];
        double *restrict W1 = field(m, MC_SPEC_W1 + b) + i0;
#pragma omp simd
        for (int i = 0; i < n; i++)
            W1[i] += w1[i] * w->f[c][i];
    }
    chunk_advance(m, i0, n, w);
    const double *restrict eh = weight(m, MC_SPEC_EH) + i0;
#pragma omp simd
    for (int i = 0; i < n; i++)
        et[i] *= eh[i];
}

static void chunk_up(const mc_spec_coef *k, mc_spec_modes *m, long i0, int n, double top,
                     int divide, const double complex *const e[6], const double *wgt,
                     double scale, double complex *const out[6], int add, chunk_work *w)
{
    chunk_frame(m, i0, n, e, w);
    chunk_seen(m, i0, n, w);
    prod_a_chunk(k->rAm, w->u, w->o, n); /* the layers below */
    prod_b_chunk(k->rBm, w->v, w->o, n);
    /* e^{-x} at the layer's top: the bottom's divided by e^{-h}, or exp() where the volume's
     * e^{-q depth} could underflow (divide 0) */
    double *restrict et = field(m, MC_SPEC_ET) + i0;
    const double *restrict q = m->q + i0, *restrict eh = weight(m, MC_SPEC_EH) + i0,
                           *restrict al = weight(m, MC_SPEC_AL) + i0,
                           *restrict ga = weight(m, MC_SPEC_GA) + i0;
    if (divide) {
#pragma omp simd
        for (int i = 0; i < n; i++)
            et[i] /= eh[i];
    } else {
        for (int i = 0; i < n; i++)
            et[i] = exp(-q[i] * top);
    }
    double wp[CHUNK], wq[CHUNK];
#pragma omp simd
    for (int i = 0; i < n; i++) {
        wp[i] = et[i] * al[i];
        wq[i] = et[i] * (al[i] * (q[i] * top) + ga[i]);
    }
    /* the mirror layers and S3: e^{-x} (al P + (al x + ga) Q), Q on its live entries */
    for (int c = 0, b = 0; c < 12; c++) {
        const double *restrict P = field(m, MC_SPEC_W0 + c) + i0;
        if (b < MC_SPEC_NBLIVE && MC_SPEC_BLIVE[b] == c) {
            const double *restrict Q = field(m, MC_SPEC_W1 + b++) + i0;
#pragma omp simd
            for (int i = 0; i < n; i++)
                w->o[c][i] += wp[i] * P[i] + wq[i] * Q[i];
        } else {
#pragma omp simd
            for (int i = 0; i < n; i++)
                w->o[c][i] += wp[i] * P[i];
        }
    }
    chunk_lab(m, i0, n, wgt, scale, w, out, add);
    chunk_advance(m, i0, n, w);
}

/* Built for AVX2 as well where the compiler can (GCC's function clones, picked at load time):
 * the chunk loops are the same IEEE operations in the same order on wider vectors, so the
 * results keep their bits (no contraction into FMA: ISO C mode). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&                           \
    !defined(__SANITIZE_ADDRESS__)
#define MODES_CLONES __attribute__((flatten, target_clones("avx2", "default")))
#else
#define MODES_CLONES
#endif

MODES_CLONES
void mc_spec_modes_pass(const mc_spec_coef *k, mc_spec_modes *m, long i0, long i1, int up,
                        int nb, const double *tops, int divide,
                        const double complex *const (*e)[6], const double *wgt, double scale,
                        double complex *const (*out)[6], int add)
{
    chunk_work w;
    for (long c0 = i0; c0 < i1; c0 += CHUNK) {
        const int n = (int)(i1 - c0 < CHUNK ? i1 - c0 : CHUNK);
        for (int s = 0; s < nb; s++) {
            if (up)
                chunk_up(k, m, c0, n, tops[s], divide, e[s], wgt, scale, out[s], add, &w);
            else
                chunk_down(k, m, c0, n, tops[s], e[s], wgt, scale, out[s], add, &w);
        }
    }
}

/* mc_spec_turn on a chunk of modes (the same operations; the products' sums in the chunk
 * order): P, Q into the W0, W1 fields, the sums U, V cleared, p3 and u_z of each mode */
static void chunk_turn(const mc_spec_coef *k, mc_spec_modes *m, long i0, int n, double complex *p3,
                       double complex *uz, chunk_work *w)
{
    double pr[2][CHUNK];
    for (int j = 0; j < 2; j++) { /* p3 = 2 sigma_zz of S1 on z = 0 (the A and B rows zz) */
        for (int i = 0; i < n; i++)
            pr[j][i] = 0.0;
        for (int c = 0, b = 0; c < 6; c++) {
            const double *restrict W0 = field(m, MC_SPEC_W0 + 2 * c + j) + i0;
            const int live = b < MC_SPEC_NBLIVE && MC_SPEC_BLIVE[b] == 2 * c;
            const double *restrict W1 = live ? field(m, MC_SPEC_W1 + b + j) + i0 : NULL;
            b += live ? 2 : 0;
            const double a0 = k->rAm[2][c], b0 = k->rBm[2][c];
            if (W1) {
#pragma omp simd
                for (int i = 0; i < n; i++)
                    pr[j][i] += 2.0 * (a0 * W0[i] + b0 * W1[i]);
            } else {
#pragma omp simd
                for (int i = 0; i < n; i++)
                    pr[j][i] += 2.0 * (a0 * W0[i] + b0 * 0.0);
            }
        }
    }
    /* the mirror: R W (entries of y'z, x'z flipped) into u (of W0) and v (of W1, live) */
    for (int c = 0; c < 12; c++) {
        const double *restrict W0 = field(m, MC_SPEC_W0 + c) + i0;
        const double sg = c >= 8 ? -1.0 : 1.0;
#pragma omp simd
        for (int i = 0; i < n; i++) {
            w->u[c][i] = sg * W0[i];
            w->o[c][i] = 0.0; /* P */
            w->f[c][i] = 0.0; /* Q */
        }
    }
    for (int b = 0; b < MC_SPEC_NBLIVE; b++) {
        const int c = MC_SPEC_BLIVE[b];
        const double *restrict W1 = field(m, MC_SPEC_W1 + b) + i0;
        const double sg = c >= 8 ? -1.0 : 1.0;
#pragma omp simd
        for (int i = 0; i < n; i++)
            w->v[c][i] = sg * W1[i];
    }
    prod_a_chunk(k->rAp, w->u, w->o, n); /* P = Ap R W0 + Bp R W1 + T0 p3 */
    prod_b_chunk(k->rBp, w->v, w->o, n);
    prod_b_chunk(k->rBp, w->u, w->f, n); /* Q = Bp R W0 + T1 p3 */
    for (int c = 0; c < 6; c++)
        for (int j = 0; j < 2; j++) {
            const double t0 = k->rT0[c], t1 = k->rT1[c];
#pragma omp simd
            for (int i = 0; i < n; i++) {
                w->o[2 * c + j][i] += t0 * pr[j][i];
                w->f[2 * c + j][i] += t1 * pr[j][i];
            }
        }
    for (int c = 0; c < 12; c++) {
        double *restrict W0 = field(m, MC_SPEC_W0 + c) + i0;
        double *restrict U = field(m, MC_SPEC_U + c) + i0;
#pragma omp simd
        for (int i = 0; i < n; i++) {
            W0[i] = w->o[c][i];
            U[i] = 0.0;
        }
    }
    for (int b = 0; b < MC_SPEC_NBLIVE; b++) {
        double *restrict W1 = field(m, MC_SPEC_W1 + b) + i0;
        double *restrict V = field(m, MC_SPEC_V + b) + i0;
        const double *restrict Q = w->f[MC_SPEC_BLIVE[b]];
#pragma omp simd
        for (int i = 0; i < n; i++) {
            W1[i] = Q[i];
            V[i] = 0.0;
        }
    }
    const double *restrict q = m->q + i0;
    for (int i = 0; i < n; i++) {
        p3[i] = pr[0][i] + I * pr[1][i];
        uz[i] = k->uz0 * p3[i] / q[i];
    }
}

MODES_CLONES
void mc_spec_modes_turn(const mc_spec_coef *k, mc_spec_modes *m, long i0, long i1,
                        double complex *p3, double complex *uz)
{
    chunk_work w;
    for (long c0 = i0; c0 < i1; c0 += CHUNK) {
        const int n = (int)(i1 - c0 < CHUNK ? i1 - c0 : CHUNK);
        chunk_turn(k, m, c0, n, p3 + c0, uz + c0, &w);
    }
}
