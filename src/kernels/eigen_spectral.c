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

void mc_spec_coef_sparse(mc_spec_coef *k);
void mc_spec_coef_real(mc_spec_coef *k);

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
    mc_spec_coef_sparse(k);
    mc_spec_coef_real(k);
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

/* The nonzero entries of the frame matrices, for products that skip the zeros (the in-plane and
 * anti-plane blocks leave 17 of 36 entries in A, 9 in B) and split the complex arithmetic. */
static void sparse_of(const double complex M[6][6], mc_spec_sparse *s)
{
    s->n = 0;
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            if (M[i][c] != 0.0) {
                s->r[s->n] = (unsigned char)i;
                s->c[s->n] = (unsigned char)c;
                s->re[s->n] = creal(M[i][c]);
                s->im[s->n] = cimag(M[i][c]);
                s->n++;
            }
}

void mc_spec_coef_sparse(mc_spec_coef *k)
{
    sparse_of((const double complex(*)[6])k->Ap, &k->sAp);
    sparse_of((const double complex(*)[6])k->Bp, &k->sBp);
    sparse_of((const double complex(*)[6])k->Am, &k->sAm);
    sparse_of((const double complex(*)[6])k->Bm, &k->sBm);
    double complex S[6][6];
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            S[i][c] = k->Ap[i][c] + k->Am[i][c];
    sparse_of((const double complex(*)[6])S, &k->sAs);
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            S[i][c] = k->Bp[i][c] + k->Bm[i][c];
    sparse_of((const double complex(*)[6])S, &k->sBs);
}

/* y += a M x (x, y as re/im pairs) */
static inline void sp_add(double *y, double a, const mc_spec_sparse *M, const double *x)
{
    for (int n = 0; n < M->n; n++) {
        const double *xv = x + 2 * M->c[n];
        double *yv = y + 2 * M->r[n];
        const double re = M->re[n] * a, im = M->im[n] * a;
        yv[0] += re * xv[0] - im * xv[1];
        yv[1] += re * xv[1] + im * xv[0];
    }
}

/* Per layer, the scalars of its scaled thickness h (the same h repeats on uniform layers) */
typedef struct {
    double h, eh, p0, p1, ehalf, p0h2, p1h2, q0, q1;
} layer_scalars;

static void scalars(double h, layer_scalars *L)
{
    if (fabs(L->h - h) <= 1e-14 * h) /* the same thickness (the boundaries' round-off apart) */
        return;
    L->h = h;
    L->eh = exp(-h);
    L->p0 = p0(h);
    L->p1 = p1(h);
    L->ehalf = exp(-0.5 * h);
    L->p0h2 = p0(0.5 * h);
    L->p1h2 = p1(0.5 * h);
    L->q0 = q0(h);
    L->q1 = q1(h);
}

/* U, V (6 complex as re/im) moved by d: V = e^{-d}(V + d U), U = e^{-d} U */
static inline void shift_by(double *U, double *V, double e, double d)
{
    for (int m = 0; m < 12; m++) {
        V[m] = e * (V[m] + d * U[m]);
        U[m] *= e;
    }
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
    const int avg = pt == MC_SPEC_AVERAGE;
    /* work: e (frame), acc (frame), as re/im pairs, 12 doubles per layer each */
    double *e = (double *)work, *acc = e + 12 * (size_t)nz;
    double M0[12] = {0}, M1[12] = {0};
    layer_scalars L = {-1.0, 0, 0, 0, 0, 0, 0, 0, 0};
    double x = 0.0, et = 1.0; /* the layer's scaled top and e^{-top} */
    for (int l = 0; l < nz; l++) {
        double complex f[6];
        mc_spec_to_frame(cq, sq, eps[l], f);
        double *el = e + 12 * l;
        for (int c = 0; c < 6; c++) {
            el[2 * c] = creal(f[c]);
            el[2 * c + 1] = cimag(f[c]);
        }
        memset(acc + 12 * l, 0, 12 * sizeof *acc);
        const double h = q * (b[l + 1] - b[l]);
        scalars(h, &L);
        const double w0 = et * L.p0, w1 = et * (x * L.p0 + L.p1);
        for (int m = 0; m < 12; m++) {
            const double r = m >= 8 ? -el[m] : el[m]; /* the mirror: yz, xz change sign */
            M0[m] += w0 * r;
            M1[m] += w1 * r;
        }
        x += h;
        et *= L.eh;
    }
    /* down: the sources above each layer and the mirror (all above), at the layer's top (average)
     * or centre */
    double U[12] = {0}, V[12] = {0}, Uc[12], Vc[12];
    x = 0.0;
    et = 1.0;
    for (int i = 0; i < nz; i++) {
        const double h = q * (b[i + 1] - b[i]);
        scalars(h, &L);
        double *ai = acc + 12 * i;
        memcpy(Uc, U, sizeof Uc);
        memcpy(Vc, V, sizeof Vc);
        double xo = x, em = et;
        if (!avg) {
            shift_by(Uc, Vc, L.ehalf, 0.5 * h);
            xo = x + 0.5 * h;
            em = et * L.ehalf;
        }
        for (int m = 0; m < 12; m++) {
            Uc[m] += em * M0[m];
            Vc[m] += em * (xo * M0[m] + M1[m]);
        }
        if (avg) { /* A (p0/h U) + B (p0/h V + p1/h U) */
            const double a = L.p0 / h, c = L.p1 / h;
            for (int m = 0; m < 12; m++)
                Vc[m] = a * Vc[m] + c * Uc[m];
            sp_add(ai, a, &k->sAp, Uc);
            sp_add(ai, 1.0, &k->sBp, Vc);
        } else {
            sp_add(ai, 1.0, &k->sAp, Uc);
            sp_add(ai, 1.0, &k->sBp, Vc);
        }
        shift_by(U, V, L.eh, h);
        const double *ei = e + 12 * i;
        for (int m = 0; m < 12; m++) {
            U[m] += L.p0 * ei[m];
            V[m] += L.p1 * ei[m];
        }
        x += h;
        et *= L.eh;
    }
    /* up: the sources below each layer, at the layer's bottom (average) or centre */
    memset(U, 0, sizeof U);
    memset(V, 0, sizeof V);
    for (int i = nz - 1; i >= 0; i--) {
        const double h = q * (b[i + 1] - b[i]);
        scalars(h, &L);
        double *ai = acc + 12 * i;
        memcpy(Uc, U, sizeof Uc);
        memcpy(Vc, V, sizeof Vc);
        if (avg) {
            const double a = L.p0 / h, c = L.p1 / h;
            for (int m = 0; m < 12; m++)
                Vc[m] = a * Vc[m] + c * Uc[m];
            sp_add(ai, a, &k->sAm, Uc);
            sp_add(ai, 1.0, &k->sBm, Vc);
        } else {
            shift_by(Uc, Vc, L.ehalf, 0.5 * h);
            sp_add(ai, 1.0, &k->sAm, Uc);
            sp_add(ai, 1.0, &k->sBm, Vc);
        }
        shift_by(U, V, L.eh, h);
        const double *ei = e + 12 * i;
        for (int m = 0; m < 12; m++) {
            U[m] += L.p0 * ei[m];
            V[m] += L.p1 * ei[m];
        }
    }
    /* at x = 0 the sums hold every layer: p3 = 2 sigma_zz of S1 on z = 0 */
    double p3[2] = {0.0, 0.0};
    for (int c = 0; c < 6; c++) {
        const double complex am = k->Am[2][c], bm = k->Bm[2][c];
        p3[0] += 2.0 * (creal(am) * U[2 * c] - cimag(am) * U[2 * c + 1] + creal(bm) * V[2 * c] -
                        cimag(bm) * V[2 * c + 1]);
        p3[1] += 2.0 * (creal(am) * U[2 * c + 1] + cimag(am) * U[2 * c] +
                        creal(bm) * V[2 * c + 1] + cimag(bm) * V[2 * c]);
    }
    /* the self terms, S3, and back to the lab frame */
    x = 0.0;
    et = 1.0;
    for (int i = 0; i < nz; i++) {
        const double h = q * (b[i + 1] - b[i]);
        scalars(h, &L);
        double sa, sb, tw0, tw1;
        if (avg) {
            sa = L.q0 / h;
            sb = L.q1 / h;
            tw0 = et * L.p0 / h;
            tw1 = et * (x * L.p0 + L.p1) / h;
        } else {
            const double c = x + 0.5 * h;
            sa = L.p0h2;
            sb = L.p1h2;
            tw0 = et * L.ehalf;
            tw1 = tw0 * c;
        }
        double *ai = acc + 12 * i;
        const double *ei = e + 12 * i;
        sp_add(ai, sa, &k->sAs, ei);
        sp_add(ai, sb, &k->sBs, ei);
        double complex f[6];
        for (int m = 0; m < 6; m++) {
            double complex s = 0.0;
            for (int c = 0; c < 6; c++)
                s += k->Minf[m][c] * (ei[2 * c] + I * ei[2 * c + 1]);
            f[m] = ai[2 * m] + I * ai[2 * m + 1] + s +
                   (tw0 * k->T0[m] + tw1 * k->T1[m]) * (p3[0] + I * p3[1]);
        }
        mc_spec_from_frame(cq, sq, f, sig[i]);
        x += h;
        et *= L.eh;
    }
    if (uz)
        *uz = k->uz0 * (p3[0] + I * p3[1]) / q;
}

void mc_spec_uz_layers(const mc_spec_coef *k, double kx, double ky, int nz, const double *b,
                       double complex (*D)[6])
{
    if (kx == 0.0 && ky == 0.0) { /* the laterally constrained layer; the caller replaces it where
                                     the mode stands for a limit (eigen_spectral_op.c) */
        const double a = k->nu / (1.0 - k->nu);
        for (int l = 0; l < nz; l++) {
            const double t = b[l + 1] - b[l];
            D[l][0] = D[l][1] = -a * t;
            D[l][2] = -t;
            D[l][3] = D[l][4] = D[l][5] = 0.0;
        }
        return;
    }
    mc_spec_uzstate u;
    mc_spec_uzstate_init(&u, kx, ky, b[0]);
    for (int l = 0; l < nz; l++)
        mc_spec_uz_next(k, &u, b[l], b[l + 1], D[l]);
}

/* ---- the depth step streamed layer by layer -------------------------------------------------- */

/* The real form (eigen_spectral.h): M~[r][c] = M[r][c] d_c / d_r, d = (1, 1, 1, 1, i, i). */
static void real_form(const double complex M[6][6], double R[6][6])
{
    for (int r = 0; r < 6; r++)
        for (int c = 0; c < 6; c++) {
            const double complex d = (c >= 4 ? I : 1.0) / (r >= 4 ? I : 1.0);
            R[r][c] = creal(M[r][c] * d); /* (the imaginary part is zero: theory §8.10) */
        }
}

void mc_spec_coef_real(mc_spec_coef *k)
{
    double complex S[6][6], B[6][6], M[6][6];
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++) {
            S[i][c] = k->Ap[i][c] + k->Am[i][c];
            B[i][c] = k->Bp[i][c] + k->Bm[i][c];
            M[i][c] = k->Minf[i][c];
        }
    real_form((const double complex(*)[6])k->Ap, k->rAp);
    real_form((const double complex(*)[6])k->Bp, k->rBp);
    real_form((const double complex(*)[6])k->Am, k->rAm);
    real_form((const double complex(*)[6])k->Bm, k->rBm);
    real_form((const double complex(*)[6])S, k->rAs);
    real_form((const double complex(*)[6])B, k->rBs);
    real_form((const double complex(*)[6])M, k->rMinf);
    for (int r = 0; r < 6; r++) {
        k->rT0[r] = creal(k->T0[r] / (r >= 4 ? I : 1.0));
        k->rT1[r] = creal(k->T1[r] / (r >= 4 ? I : 1.0));
    }
}

/* y += M x on re/im pairs, for the pattern of A (the in-plane block x'x', y'y', zz, x'z and the
 * anti-plane block x'y', y'z: 17 entries), of B (rows and columns x'x', zz, x'z: 9) and of the
 * local term (x'x', y'y' and x'y': 5). The patterns hold every entry that is not zero (a check in
 * tests/test_eigen_spectral.c). */
#define PAIR(r, c) y[2 * r] += M[r][c] * x[2 * c], y[2 * r + 1] += M[r][c] * x[2 * c + 1]
static inline void prod_a(const double M[6][6], const double *restrict x, double *restrict y)
{
    PAIR(0, 0), PAIR(0, 1), PAIR(0, 2), PAIR(0, 5);
    PAIR(1, 0), PAIR(1, 2), PAIR(1, 5);
    PAIR(2, 0), PAIR(2, 1), PAIR(2, 2);
    PAIR(3, 3), PAIR(3, 4), PAIR(4, 3), PAIR(4, 4);
    PAIR(5, 0), PAIR(5, 1), PAIR(5, 5);
}

static inline void prod_b(const double M[6][6], const double *restrict x, double *restrict y)
{
    PAIR(0, 0), PAIR(0, 2), PAIR(0, 5);
    PAIR(2, 0), PAIR(2, 2), PAIR(2, 5);
    PAIR(5, 0), PAIR(5, 2), PAIR(5, 5);
}

static inline void prod_local(const double M[6][6], const double *restrict x, double *restrict y)
{
    PAIR(0, 0), PAIR(0, 1), PAIR(1, 0), PAIR(1, 1), PAIR(3, 3);
}
#undef PAIR

/* lab (complex) -> the real form of the frame, as re/im pairs */
static inline void frame_real(double c, double s, const double complex e[6], double f[12])
{
    const double cc = c * c, ss = s * s, cs = c * s;
    const double complex f0 = cc * e[0] + ss * e[1] + 2.0 * cs * e[3];
    const double complex f1 = ss * e[0] + cc * e[1] - 2.0 * cs * e[3];
    const double complex f3 = cs * (e[1] - e[0]) + (cc - ss) * e[3];
    const double complex f4 = c * e[4] - s * e[5], f5 = c * e[5] + s * e[4];
    f[0] = creal(f0), f[1] = cimag(f0);
    f[2] = creal(f1), f[3] = cimag(f1);
    f[4] = creal(e[2]), f[5] = cimag(e[2]);
    f[6] = creal(f3), f[7] = cimag(f3);
    f[8] = cimag(f4), f[9] = -creal(f4); /* -i f4 */
    f[10] = cimag(f5), f[11] = -creal(f5);
}

/* the real form of the frame -> lab (mc_spec_from_frame of D f) */
static inline void lab_real(double c, double s, const double f[12], double complex e[6])
{
    double complex g[6];
    for (int m = 0; m < 4; m++)
        g[m] = f[2 * m] + I * f[2 * m + 1];
    g[4] = -f[9] + I * f[8]; /* i f~4 */
    g[5] = -f[11] + I * f[10];
    mc_spec_from_frame(c, s, g, e);
}

void mc_spec_state_init_q(mc_spec_state *st, double q, double cq, double sq)
{
    memset(st, 0, sizeof *st);
    st->et = 1.0;
    st->h = -1.0;
    st->q = q;
    st->cq = cq;
    st->sq = sq;
}

void mc_spec_state_init(mc_spec_state *st, double kx, double ky)
{
    const double q = hypot(kx, ky);
    mc_spec_state_init_q(st, q, q > 0.0 ? kx / q : 1.0, q > 0.0 ? ky / q : 0.0);
}

void mc_spec_weights_of(double h, mc_spec_point pt, double w[MC_SPEC_WEIGHTS])
{
    memset(w, 0, MC_SPEC_WEIGHTS * sizeof *w);
    if (!(h > 0.0))
        return;
    layer_scalars L = {-1.0, 0, 0, 0, 0, 0, 0, 0, 0};
    scalars(h, &L);
    w[MC_SPEC_H] = h, w[MC_SPEC_EH] = L.eh, w[MC_SPEC_P0] = L.p0, w[MC_SPEC_P1] = L.p1;
    if (pt == MC_SPEC_AVERAGE) { /* A (p0/h U) + B (p0/h V + p1/h U); q0/h As + q1/h Bs */
        w[MC_SPEC_AL] = L.p0 / h, w[MC_SPEC_GA] = L.p1 / h;
        w[MC_SPEC_SA] = L.q0 / h, w[MC_SPEC_SB] = L.q1 / h;
    } else { /* the sums moved by h/2 to the centre: e^{-h/2} (U, V + h/2 U) */
        w[MC_SPEC_AL] = L.ehalf, w[MC_SPEC_GA] = L.ehalf * 0.5 * h;
        w[MC_SPEC_SA] = L.p0h2, w[MC_SPEC_SB] = L.p1h2;
    }
}

/* the state's weights of thickness h (cached: uniform layers repeat it) */
static void state_scalars(mc_spec_state *st, double h, mc_spec_point pt)
{
    if (fabs(st->h - h) <= 1e-14 * h)
        return;
    double w[MC_SPEC_WEIGHTS];
    mc_spec_weights_of(h, pt, w);
    st->h = h, st->eh = w[MC_SPEC_EH], st->p0 = w[MC_SPEC_P0], st->p1 = w[MC_SPEC_P1];
    st->al = w[MC_SPEC_AL], st->ga = w[MC_SPEC_GA], st->sa = w[MC_SPEC_SA], st->sb = w[MC_SPEC_SB];
}

/* out = A (al U) + B (al V + ga U) of the state's sums */
static inline void observe(const double A[6][6], const double B[6][6], const mc_spec_state *st,
                           double *restrict out)
{
    double u[12], v[12];
    for (int m = 0; m < 12; m++) {
        u[m] = st->al * st->U[m];
        v[m] = st->al * st->V[m] + st->ga * st->U[m];
    }
    prod_a(A, u, out);
    prod_b(B, v, out);
}

/* past a layer of scaled thickness h: U = e^{-h} U + p0 e, V = e^{-h} (V + h U) + p1 e */
static inline void advance(mc_spec_state *st, const double *e)
{
    for (int m = 0; m < 12; m++) {
        st->V[m] = st->eh * (st->V[m] + st->h * st->U[m]) + st->p1 * e[m];
        st->U[m] = st->eh * st->U[m] + st->p0 * e[m];
    }
}

void mc_spec_down_layer(const mc_spec_coef *k, double top, double bottom, mc_spec_point pt,
                        const double complex eps[6], mc_spec_state *st, double complex sig[6])
{
    const double q = st->q, x = q * top;
    state_scalars(st, q * (bottom - top), pt);
    double e[12], out[12] = {0}, es[12], eb[12];
    frame_real(st->cq, st->sq, eps, e);
    observe(k->rAp, k->rBp, st, out); /* the layers above */
    for (int m = 0; m < 12; m++) {
        es[m] = st->sa * e[m];
        eb[m] = st->sb * e[m];
    }
    prod_a(k->rAs, es, out); /* its own */
    prod_b(k->rBs, eb, out);
    prod_local(k->rMinf, e, out);
    lab_real(st->cq, st->sq, out, sig);
    const double w0 = st->et * st->p0, w1 = st->et * (x * st->p0 + st->p1);
    for (int m = 0; m < 12; m++) { /* the totals */
        st->W0[m] += w0 * e[m];
        st->W1[m] += w1 * e[m];
    }
    advance(st, e);
    st->et *= st->eh;
}

double complex mc_spec_turn(const mc_spec_coef *k, mc_spec_state *st)
{
    /* p3 = 2 sigma_zz of S1 on z = 0 (row zz is even: the real form's row is its own) */
    double p3[2] = {0.0, 0.0};
    for (int c = 0; c < 6; c++)
        for (int j = 0; j < 2; j++)
            p3[j] += 2.0 * (k->rAm[2][c] * st->W0[2 * c + j] + k->rBm[2][c] * st->W1[2 * c + j]);
    /* the mirror layers (R W: y'z, x'z flipped) and S3, as seen from a layer of top t:
     * e^{-t} (al P + (al t + ga) Q), P = Ap R W0 + Bp R W1 + T0 p3, Q = Bp R W0 + T1 p3 */
    double r0[12], r1[12], P[12] = {0}, Q[12] = {0};
    for (int m = 0; m < 12; m++) {
        r0[m] = m >= 8 ? -st->W0[m] : st->W0[m];
        r1[m] = m >= 8 ? -st->W1[m] : st->W1[m];
    }
    prod_a(k->rAp, r0, P);
    prod_b(k->rBp, r1, P);
    prod_b(k->rBp, r0, Q);
    for (int c = 0; c < 6; c++)
        for (int j = 0; j < 2; j++) {
            P[2 * c + j] += k->rT0[c] * p3[j];
            Q[2 * c + j] += k->rT1[c] * p3[j];
        }
    memcpy(st->W0, P, sizeof P);
    memcpy(st->W1, Q, sizeof Q);
    st->p3 = p3[0] + I * p3[1];
    memset(st->U, 0, sizeof st->U);
    memset(st->V, 0, sizeof st->V);
    return k->uz0 * st->p3 / st->q;
}

/* below this e^{-q z} the up pass takes e^{-q top} from exp() instead of dividing by e^{-h} */
#define ET_DIVIDE_ABOVE 1e-200

void mc_spec_up_layer(const mc_spec_coef *k, double top, double bottom, mc_spec_point pt,
                      const double complex eps[6], mc_spec_state *st, double complex sig[6])
{
    const double q = st->q, x = q * top;
    state_scalars(st, q * (bottom - top), pt);
    /* e^{-x}: the bottom's e^{-q bottom} (after the down pass: the volume's) divided by e^{-h} */
    const double em = st->et > ET_DIVIDE_ABOVE ? st->et / st->eh : exp(-x);
    st->et = em;
    double e[12], out[12] = {0};
    frame_real(st->cq, st->sq, eps, e);
    observe(k->rAm, k->rBm, st, out); /* the layers below */
    const double wp = em * st->al, wq = em * (st->al * x + st->ga);
    for (int m = 0; m < 12; m++) /* the mirror layers and S3 */
        out[m] += wp * st->W0[m] + wq * st->W1[m];
    lab_real(st->cq, st->sq, out, sig);
    advance(st, e);
}

/* ---- the surface displacement, layer by layer ---------------------------------------------- */

void mc_spec_uzstate_init(mc_spec_uzstate *u, double kx, double ky, double top)
{
    memset(u, 0, sizeof *u);
    u->q = hypot(kx, ky);
    u->cq = u->q > 0.0 ? kx / u->q : 1.0;
    u->sq = u->q > 0.0 ? ky / u->q : 0.0;
    u->et = exp(-u->q * top);
    u->h = -1.0;
}

void mc_spec_uz_next(const mc_spec_coef *k, mc_spec_uzstate *u, double top, double bottom,
                     double complex D[6])
{
    const double q = u->q, x = q * top, h = q * (bottom - top);
    if (!(fabs(u->h - h) <= 1e-14 * h)) {
        u->h = h;
        u->eh = exp(-h);
        u->p0 = p0(h);
        u->p1 = p1(h);
    }
    const double wa = u->et * u->p0, wb = u->et * (x * u->p0 + u->p1), f = 2.0 * k->uz0 / q;
    const double c = u->cq, s = u->sq, cc = c * c, ss = s * s, cs = c * s;
    double complex v[6];
    for (int m = 0; m < 6; m++)
        v[m] = f * (wa * k->Am[2][m] + wb * k->Bm[2][m]);
    D[0] = cc * v[0] + ss * v[1] - cs * v[3];
    D[1] = ss * v[0] + cc * v[1] + cs * v[3];
    D[2] = v[2];
    D[3] = 2.0 * cs * (v[0] - v[1]) + (cc - ss) * v[3];
    D[4] = c * v[4] + s * v[5];
    D[5] = c * v[5] - s * v[4];
    u->et *= u->eh;
}
