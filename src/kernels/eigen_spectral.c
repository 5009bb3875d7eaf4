/* eigen_spectral.c - the half-space eigenstrain kernel per lateral Fourier mode
 * (eigen_spectral.h; docs/theory.md §8.10).
 *
 * Derivation (theory §8.10; tools/derive_spectral.py re-derives every constant below with sympy):
 * Mura's infinite-space operator sigma = C:(Gamma:C:eps* - eps*) in 3-D Fourier space, taken
 * back to depth by residues at zeta = +-i q (S1), plus the mirror layer carrying R eps* R (S2,
 * zero shear traction and u_z on z = 0), plus the half-space stress of the remaining normal
 * traction p3 (S3). In the frame of k everything depends on t = q z: K(s) = e^{-|s|}(A + B|s|)
 * per side, integrated over the layers in closed form. */
#include "kernels/eigen_spectral.h"

#include <math.h>
#include <string.h>

void mc_spec_coef_init(double nu, mc_spec_coef *k)
{
    memset(k, 0, sizeof *k);
    const double w = 1.0 / (1.0 - nu);
    k->nu = nu;
    /* observation below the source (s > 0); frame order x'x', y'y', zz, x'y', y'z, x'z */
    k->Ap[0][0] = 0.75 * w;
    k->Ap[0][1] = 0.5 * nu * w;
    k->Ap[0][2] = -0.25 * w;
    k->Ap[0][5] = I * w;
    k->Ap[1][0] = 0.5 * nu * w;
    k->Ap[1][2] = -0.5 * nu * w;
    k->Ap[1][5] = I * nu * w;
    k->Ap[2][0] = -0.25 * w;
    k->Ap[2][1] = -0.5 * nu * w;
    k->Ap[2][2] = -0.25 * w;
    k->Ap[3][3] = 0.5;
    k->Ap[3][4] = 0.5 * I;
    k->Ap[4][3] = 0.5 * I;
    k->Ap[4][4] = -0.5;
    k->Ap[5][0] = 0.5 * I * w;
    k->Ap[5][1] = 0.5 * I * nu * w;
    k->Ap[5][5] = -0.5 * w;
    k->Bp[0][0] = -0.25 * w;
    k->Bp[0][2] = 0.25 * w;
    k->Bp[0][5] = -0.5 * I * w;
    k->Bp[2][0] = 0.25 * w;
    k->Bp[2][2] = -0.25 * w;
    k->Bp[2][5] = 0.5 * I * w;
    k->Bp[5][0] = -0.25 * I * w;
    k->Bp[5][2] = 0.25 * I * w;
    k->Bp[5][5] = 0.5 * w;
    /* observation above the source: the reflection s -> -s flips the terms odd in z (the
     * imaginary ones, which carry one z index more or less) */
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++) {
            k->Am[i][c] = conj(k->Ap[i][c]);
            k->Bm[i][c] = conj(k->Bp[i][c]);
        }
    /* inside the source layer: the laterally constrained layer (eigen_layer.c) */
    k->Minf[0][0] = k->Minf[1][1] = -w;
    k->Minf[0][1] = k->Minf[1][0] = -nu * w;
    k->Minf[3][3] = -1.0;
    /* Boussinesq per mode: a unit compressive pressure e^{i q x'} */
    k->T0[0] = -1.0;
    k->T0[1] = -2.0 * nu;
    k->T0[2] = -1.0;
    k->T1[0] = 1.0;
    k->T1[2] = -1.0;
    k->T1[5] = I;
    k->uz0 = 2.0 - 2.0 * nu;
}

void mc_spec_to_frame(double c, double s, const double complex e[6], double complex f[6])
{
    const double cc = c * c, ss = s * s, cs = c * s;
    f[0] = cc * e[0] + ss * e[1] + 2.0 * cs * e[3];
    f[1] = ss * e[0] + cc * e[1] - 2.0 * cs * e[3];
    f[2] = e[2];
    f[3] = cs * (e[1] - e[0]) + (cc - ss) * e[3];
    f[4] = c * e[4] - s * e[5];
    f[5] = c * e[5] + s * e[4];
}

void mc_spec_from_frame(double c, double s, const double complex f[6], double complex e[6])
{
    mc_spec_to_frame(c, -s, f, e);
}

/* ---- scalar integrals of e^{-s} (h >= 0; series where the closed forms cancel) --------------- */

#define SERIES_BELOW 0.5
#define SERIES_TERMS 24 /* 0.5^26 / 24! ~ 2e-32 */

/* int_0^h e^{-s} ds */
static double p0(double h) { return -expm1(-h); }

/* int_0^h s e^{-s} ds = 1 - (1 + h) e^{-h} */
static double p1(double h)
{
    if (h >= SERIES_BELOW)
        return -expm1(-h) - h * exp(-h);
    double term = h * h / 2.0, sum = 0.0; /* (-1)^n h^{n+2} / (n! (n + 2)) */
    double pw = h * h, fact = 1.0;
    for (int n = 0; n < SERIES_TERMS; n++) {
        term = pw / (fact * (n + 2));
        sum += (n & 1) ? -term : term;
        pw *= h;
        fact *= n + 1;
    }
    return sum;
}

/* int_0^h (h - s) e^{-s} ds = h - 1 + e^{-h} */
static double q0(double h)
{
    if (h >= SERIES_BELOW)
        return h + expm1(-h);
    double sum = 0.0, pw = h * h, fact = 2.0; /* (-1)^n h^{n+2} / (n + 2)! */
    for (int n = 0; n < SERIES_TERMS; n++) {
        const double term = pw / fact;
        sum += (n & 1) ? -term : term;
        pw *= h;
        fact *= n + 3;
    }
    return sum;
}

/* int_0^h (h - s) s e^{-s} ds = h p1(h) - (2 - (2 + 2h + h^2) e^{-h}) */
static double q1(double h)
{
    if (h >= SERIES_BELOW)
        return h * p1(h) - (2.0 - (2.0 + 2.0 * h + h * h) * exp(-h));
    double sum = 0.0, pw = h * h * h, fact = 1.0; /* (-1)^n h^{n+3} / (n! (n+2)(n+3)) */
    for (int n = 0; n < SERIES_TERMS; n++) {
        const double term = pw / (fact * (n + 2) * (n + 3));
        sum += (n & 1) ? -term : term;
        pw *= h;
        fact *= n + 1;
    }
    return sum;
}

/* ---- small complex linear algebra ------------------------------------------------------------- */

/* y += a M x (6 x 6) */
static void mv_add(double complex y[6], double a, const double complex M[6][6],
                   const double complex x[6])
{
    for (int i = 0; i < 6; i++) {
        double complex s = 0.0;
        for (int c = 0; c < 6; c++)
            s += M[i][c] * x[c];
        y[i] += a * s;
    }
}

static void mv_add_real(double complex y[6], double a, const double M[6][6],
                        const double complex x[6])
{
    for (int i = 0; i < 6; i++) {
        double complex s = 0.0;
        for (int c = 0; c < 6; c++)
            s += M[i][c] * x[c];
        y[i] += a * s;
    }
}

/* M += a N */
static void m_add(double complex M[6][6], double complex a, const double complex N[6][6])
{
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            M[i][c] += a * N[i][c];
}

/* The mirror's R eps R: the columns yz, xz change sign (also in the k frame: R acts on z). */
static void mirror(double complex e[6])
{
    e[4] = -e[4];
    e[5] = -e[5];
}

/* ---- the reference: one pair of layers ------------------------------------------------------- */

/* Weights of A and B for a source of scaled width w whose near edge lies gap >= 0 from the
 * observation: the point (h = 0) or the average over an observation layer of width h on the far
 * side of the gap. */
static void cross_weights(double gap, double w, double h, double *wa, double *wb)
{
    const double e = exp(-gap);
    if (h <= 0.0) {
        *wa = e * p0(w);
        *wb = e * (gap * p0(w) + p1(w));
        return;
    }
    *wa = e * p0(h) * p0(w) / h;
    *wb = e * (gap * p0(h) * p0(w) + p1(h) * p0(w) + p0(h) * p1(w)) / h;
}

/* The frame matrix (per 2G) at the scaled observation [o1, o2] (o2 = o1: a point) of the scaled
 * source [t1, t2]: S1 + S2 + S3. */
static void frame_pair(const mc_spec_coef *k, double o1, double o2, double t1, double t2,
                       double complex S[6][6])
{
    memset(S, 0, 36 * sizeof S[0][0]);
    const double w = t2 - t1, h = o2 - o1;
    double wa, wb;
    /* S1 */
    if (h > 0.0 && o1 == t1 && o2 == t2) { /* the self term, averaged */
        m_add(S, q0(h) / h, k->Ap);
        m_add(S, q0(h) / h, k->Am);
        m_add(S, q1(h) / h, k->Bp);
        m_add(S, q1(h) / h, k->Bm);
        for (int i = 0; i < 6; i++)
            for (int c = 0; c < 6; c++)
                S[i][c] += k->Minf[i][c];
    } else if (o1 >= t2) { /* below */
        cross_weights(o1 - t2, w, h, &wa, &wb);
        m_add(S, wa, k->Ap);
        m_add(S, wb, k->Bp);
    } else if (o2 <= t1 && !(h == 0.0 && o1 == t1)) { /* above (a point on the top face is in) */
        cross_weights(t1 - o2, w, h, &wa, &wb);
        m_add(S, wa, k->Am);
        m_add(S, wb, k->Bm);
    } else { /* a point inside: the parts of the layer above and below it */
        cross_weights(0.0, o1 - t1, 0.0, &wa, &wb);
        m_add(S, wa, k->Ap);
        m_add(S, wb, k->Bp);
        cross_weights(0.0, t2 - o1, 0.0, &wa, &wb);
        m_add(S, wa, k->Am);
        m_add(S, wb, k->Bm);
        for (int i = 0; i < 6; i++)
            for (int c = 0; c < 6; c++)
                S[i][c] += k->Minf[i][c];
    }
    /* S2: the mirror layer [-t2, -t1] lies above every observation point */
    cross_weights(o1 + t1, w, h, &wa, &wb);
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++) {
            const double r = c >= 4 ? -1.0 : 1.0;
            S[i][c] += r * (wa * k->Ap[i][c] + wb * k->Bp[i][c]);
        }
    /* S3: p3 = sigma_zz of S1 + S2 on z = 0, twice S1's (the mirror doubles it) */
    cross_weights(t1, w, 0.0, &wa, &wb);
    double complex p3[6], tw0, tw1;
    for (int c = 0; c < 6; c++)
        p3[c] = 2.0 * (wa * k->Am[2][c] + wb * k->Bm[2][c]);
    if (h > 0.0) {
        tw0 = exp(-o1) * p0(h) / h;
        tw1 = exp(-o1) * (o1 * p0(h) + p1(h)) / h;
    } else {
        tw0 = exp(-o1);
        tw1 = exp(-o1) * o1;
    }
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            S[i][c] += (tw0 * k->T0[i] + tw1 * k->T1[i]) * p3[c];
}

/* Lab frame of a frame matrix: S_lab = R^T S R, column by column through the rotations. */
static void lab_matrix(double c, double s, double complex F[6][6], double complex S[6][6])
{
    double complex col[6], fcol[6], out[6], unit[6];
    for (int j = 0; j < 6; j++) {
        memset(unit, 0, sizeof unit);
        unit[j] = 1.0;
        mc_spec_to_frame(c, s, unit, col);
        for (int i = 0; i < 6; i++) {
            fcol[i] = 0.0;
            for (int m = 0; m < 6; m++)
                fcol[i] += F[i][m] * col[m];
        }
        mc_spec_from_frame(c, s, fcol, out);
        for (int i = 0; i < 6; i++)
            S[i][j] = out[i];
    }
}

static void layer_limit(double u1, double u2, double t1, double t2, const mc_spec_coef *k,
                        double complex S[6][6])
{
    memset(S, 0, 36 * sizeof S[0][0]);
    const double mid = 0.5 * (u1 + u2);
    if (mid >= t1 && mid < t2)
        for (int i = 0; i < 6; i++)
            for (int c = 0; c < 6; c++)
                S[i][c] = k->Minf[i][c];
}

void mc_spec_pair(const mc_spec_coef *k, double kx, double ky, double u1, double u2, double t1,
                  double t2, mc_spec_point pt, double complex S[6][6])
{
    const double q = hypot(kx, ky);
    if (q == 0.0) {
        layer_limit(u1, u2, t1, t2, k, S);
        return;
    }
    double complex F[6][6];
    if (pt == MC_SPEC_AVERAGE) {
        frame_pair(k, q * u1, q * u2, q * t1, q * t2, F);
    } else {
        const double c = 0.5 * q * (u1 + u2);
        frame_pair(k, c, c, q * t1, q * t2, F);
    }
    lab_matrix(kx / q, ky / q, F, S);
}

void mc_spec_point_stress(const mc_spec_coef *k, double kx, double ky, double z, double t1,
                          double t2, double complex S[6][6])
{
    const double q = hypot(kx, ky);
    if (q == 0.0) {
        layer_limit(z, z, t1, t2, k, S);
        return;
    }
    double complex F[6][6];
    frame_pair(k, q * z, q * z, q * t1, q * t2, F);
    lab_matrix(kx / q, ky / q, F, S);
}

void mc_spec_pair_uz(const mc_spec_coef *k, double kx, double ky, double t1, double t2,
                     double complex D[6])
{
    const double q = hypot(kx, ky);
    if (q == 0.0) { /* the layer (eigen_layer.c) */
        const double t = t2 - t1, a = k->nu / (1.0 - k->nu);
        D[0] = D[1] = -a * t;
        D[2] = -t;
        D[3] = D[4] = D[5] = 0.0;
        return;
    }
    double wa, wb;
    cross_weights(q * t1, q * (t2 - t1), 0.0, &wa, &wb);
    double complex row[6], unit[6], f[6];
    for (int c = 0; c < 6; c++)
        row[c] = 2.0 * (wa * k->Am[2][c] + wb * k->Bm[2][c]) * k->uz0 / q;
    const double cq = kx / q, sq = ky / q;
    for (int j = 0; j < 6; j++) { /* D_lab[j] = row . frame(unit j) */
        memset(unit, 0, sizeof unit);
        unit[j] = 1.0;
        mc_spec_to_frame(cq, sq, unit, f);
        D[j] = 0.0;
        for (int c = 0; c < 6; c++)
            D[j] += row[c] * f[c];
    }
}

/* ---- the fast depth step: running sums ------------------------------------------------------- */

/* Move sums U, V of e^{-(x - x_j)} P0 and e^{-(x - x_j)}((x - x_j) P0 + P1) by d >= 0. */
static void shift(double complex U[6], double complex V[6], double d)
{
    const double e = exp(-d);
    for (int c = 0; c < 6; c++) {
        V[c] = e * (V[c] + d * U[c]);
        U[c] *= e;
    }
}

/* out += A (a U) + B (b V + c U) */
static void apply_ab(double complex out[6], const double complex A[6][6],
                     const double complex B[6][6], double a, double b, double c,
                     const double complex U[6], const double complex V[6])
{
    double complex u[6], v[6];
    for (int m = 0; m < 6; m++) {
        u[m] = a * U[m];
        v[m] = b * V[m] + c * U[m];
    }
    mv_add(out, 1.0, A, u);
    mv_add(out, 1.0, B, v);
}

void mc_spec_depth(const mc_spec_coef *k, double kx, double ky, int nz, const double *b,
                   mc_spec_point pt, const double complex (*eps)[6], double complex (*sig)[6],
                   double complex *uz, double complex *work)
{
    const double q = hypot(kx, ky);
    if (q == 0.0) { /* the layer: local stresses, u_z the sum of the layers' heaves */
        const double a = k->nu / (1.0 - k->nu);
        double complex u = 0.0;
        for (int l = 0; l < nz; l++) {
            memset(sig[l], 0, sizeof sig[l]);
            mv_add_real(sig[l], 1.0, k->Minf, eps[l]);
            u -= (b[l + 1] - b[l]) * (eps[l][2] + a * (eps[l][0] + eps[l][1]));
        }
        if (uz)
            *uz = u;
        return;
    }
    const double cq = kx / q, sq = ky / q;
    double complex(*e)[6] = (double complex(*)[6])work;
    double complex(*acc)[6] = (double complex(*)[6])(work + 6 * (size_t)nz);
    double complex M0[6] = {0}, M1[6] = {0};
    for (int l = 0; l < nz; l++) {
        mc_spec_to_frame(cq, sq, eps[l], e[l]);
        memset(acc[l], 0, sizeof acc[l]);
        const double t1 = q * b[l], w = q * (b[l + 1] - b[l]), et = exp(-t1);
        double complex r[6];
        memcpy(r, e[l], sizeof r);
        mirror(r);
        for (int c = 0; c < 6; c++) {
            M0[c] += et * p0(w) * r[c];
            M1[c] += et * (t1 * p0(w) + p1(w)) * r[c];
        }
    }
    const int avg = pt == MC_SPEC_AVERAGE;
    /* down: the sources above each layer, and the mirror (all above); at x = top of layer i */
    double complex U[6] = {0}, V[6] = {0}, Uc[6], Vc[6];
    for (int i = 0; i < nz; i++) {
        const double x = q * b[i], h = q * (b[i + 1] - b[i]);
        const double xo = avg ? x : x + 0.5 * h; /* where the sums are taken */
        memcpy(Uc, U, sizeof Uc);
        memcpy(Vc, V, sizeof Vc);
        if (!avg)
            shift(Uc, Vc, 0.5 * h);
        const double em = exp(-xo);
        for (int c = 0; c < 6; c++) {
            Uc[c] += em * M0[c];
            Vc[c] += em * (xo * M0[c] + M1[c]);
        }
        if (avg)
            apply_ab(acc[i], k->Ap, k->Bp, p0(h) / h, p0(h) / h, p1(h) / h, Uc, Vc);
        else
            apply_ab(acc[i], k->Ap, k->Bp, 1.0, 1.0, 0.0, Uc, Vc);
        shift(U, V, h);
        for (int c = 0; c < 6; c++) {
            U[c] += p0(h) * e[i][c];
            V[c] += p1(h) * e[i][c];
        }
    }
    /* up: the sources below each layer; at x = bottom of layer i */
    memset(U, 0, sizeof U);
    memset(V, 0, sizeof V);
    for (int i = nz - 1; i >= 0; i--) {
        const double h = q * (b[i + 1] - b[i]);
        memcpy(Uc, U, sizeof Uc);
        memcpy(Vc, V, sizeof Vc);
        if (avg) {
            apply_ab(acc[i], k->Am, k->Bm, p0(h) / h, p0(h) / h, p1(h) / h, Uc, Vc);
        } else {
            shift(Uc, Vc, 0.5 * h);
            apply_ab(acc[i], k->Am, k->Bm, 1.0, 1.0, 0.0, Uc, Vc);
        }
        shift(U, V, h);
        for (int c = 0; c < 6; c++) {
            U[c] += p0(h) * e[i][c];
            V[c] += p1(h) * e[i][c];
        }
    }
    /* at x = 0 the sums hold every layer: p3 */
    double complex p3 = 0.0;
    for (int c = 0; c < 6; c++)
        p3 += 2.0 * (k->Am[2][c] * U[c] + k->Bm[2][c] * V[c]);
    /* the self terms, S3, and back to the lab frame */
    for (int i = 0; i < nz; i++) {
        const double x = q * b[i], h = q * (b[i + 1] - b[i]);
        double sa, sb, tw0, tw1;
        if (avg) {
            sa = q0(h) / h;
            sb = q1(h) / h;
            tw0 = exp(-x) * p0(h) / h;
            tw1 = exp(-x) * (x * p0(h) + p1(h)) / h;
        } else {
            const double c = x + 0.5 * h;
            sa = p0(0.5 * h);
            sb = p1(0.5 * h);
            tw0 = exp(-c);
            tw1 = exp(-c) * c;
        }
        mv_add(acc[i], sa, k->Ap, e[i]);
        mv_add(acc[i], sa, k->Am, e[i]);
        mv_add(acc[i], sb, k->Bp, e[i]);
        mv_add(acc[i], sb, k->Bm, e[i]);
        mv_add_real(acc[i], 1.0, k->Minf, e[i]);
        for (int m = 0; m < 6; m++)
            acc[i][m] += (tw0 * k->T0[m] + tw1 * k->T1[m]) * p3;
        mc_spec_from_frame(cq, sq, acc[i], sig[i]);
    }
    if (uz)
        *uz = k->uz0 * p3 / q;
}
