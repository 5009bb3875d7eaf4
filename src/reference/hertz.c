/* hertz.c - analytic reference solutions of half-space contact (see hertz.h, theory.md §6). */
#include "reference/hertz.h"

#include <math.h>

#include <gsl/gsl_sf_ellint.h>

#include "kernels/kernel.h"

static int positive_finite(double v) { return isfinite(v) && v > 0.0; }

/* ---- Hertz point contact, SI ---------------------------------------------------------------- */

int mc_hertz_point_from_load(double R, double Estar, double P, mc_hertz_point *h, mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hertz point: NULL result");
    if (!positive_finite(R) || !positive_finite(Estar) || !positive_finite(P))
        return mc_fail(err, MC_ERR_INPUT,
                       "hertz point: need R > 0, E* > 0, P > 0 (got R=%g m, E*=%g Pa, P=%g N)", R,
                       Estar, P);
    h->R = R;
    h->Estar = Estar;
    h->load = P;
    h->a = cbrt(3.0 * P * R / (4.0 * Estar));
    h->p0 = 3.0 * P / (2.0 * M_PI * h->a * h->a);
    h->delta = h->a * h->a / R;
    return MC_OK;
}

/* B/A of the elliptical contact as a function of the eccentricity (hertz.h); rises from 1 at
 * e = 0 without bound as e -> 1. */
static double ellipse_ratio(double e)
{
    const double K = gsl_sf_ellint_Kcomp(e, GSL_PREC_DOUBLE);
    const double E = gsl_sf_ellint_Ecomp(e, GSL_PREC_DOUBLE);
    return (E / (1.0 - e * e) - K) / (K - E);
}

int mc_hertz_ellipse_from_load(double Rx, double Ry, double Estar, double P, mc_hertz_ellipse *h,
                               mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hertz ellipse: NULL result");
    if (!positive_finite(Rx) || !positive_finite(Ry) || !positive_finite(Estar) ||
        !positive_finite(P))
        return mc_fail(err, MC_ERR_INPUT,
                       "hertz ellipse: need Rx, Ry, E*, P > 0 (got %g m, %g m, %g Pa, %g N)", Rx, Ry,
                       Estar, P);
    h->Rx = Rx;
    h->Ry = Ry;
    h->Estar = Estar;
    h->load = P;
    const double rl = fmax(Rx, Ry), rs = fmin(Rx, Ry), ratio = rl / rs;
    double e = 0.0, lng, shrt;
    /* below e = 1e-4 the ratio differs from 1 by ~1e-8, where K - E loses its digits: the
     * circle's formulas are exact to that order there */
    if (ratio <= ellipse_ratio(1e-4)) {
        lng = shrt = cbrt(3.0 * P * sqrt(rl * rs) / (4.0 * Estar));
    } else {
        double lo = 1e-4, hi = 1.0 - 1e-15;
        if (!(ellipse_ratio(hi) >= ratio))
            return mc_fail(err, MC_ERR_INPUT,
                           "hertz ellipse: radius ratio %g beyond the reach of the elliptic "
                           "integrals (a line contact)",
                           ratio);
        for (int it = 0; it < 200 && hi - lo > 4e-16; it++) {
            const double mid = 0.5 * (lo + hi);
            if (ellipse_ratio(mid) < ratio)
                lo = mid;
            else
                hi = mid;
        }
        e = 0.5 * (lo + hi);
        const double K = gsl_sf_ellint_Kcomp(e, GSL_PREC_DOUBLE);
        const double E = gsl_sf_ellint_Ecomp(e, GSL_PREC_DOUBLE);
        lng = cbrt(3.0 * P * rl * (K - E) / (M_PI * Estar * e * e));
        shrt = lng * sqrt(1.0 - e * e);
    }
    h->e = e;
    h->ax = Rx >= Ry ? lng : shrt;
    h->ay = Rx >= Ry ? shrt : lng;
    h->p0 = 3.0 * P / (2.0 * M_PI * lng * shrt);
    h->delta = h->p0 * shrt * gsl_sf_ellint_Kcomp(e, GSL_PREC_DOUBLE) / Estar;
    return MC_OK;
}

int mc_hertz_point_from_approach(double R, double Estar, double delta, mc_hertz_point *h,
                                 mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hertz point: NULL result");
    if (!positive_finite(R) || !positive_finite(Estar) || !positive_finite(delta))
        return mc_fail(err, MC_ERR_INPUT,
                       "hertz point: need R > 0, E* > 0, delta > 0 (got R=%g m, E*=%g Pa, "
                       "delta=%g m)",
                       R, Estar, delta);
    h->R = R;
    h->Estar = Estar;
    h->delta = delta;
    h->a = sqrt(R * delta);
    h->load = 4.0 * Estar * h->a * h->a * h->a / (3.0 * R);
    h->p0 = 3.0 * h->load / (2.0 * M_PI * h->a * h->a);
    return MC_OK;
}

double mc_hertz_point_pressure(const mc_hertz_point *h, double r)
{
    double t = r / h->a;
    return fabs(t) < 1.0 ? h->p0 * sqrt((1.0 - t) * (1.0 + t)) : 0.0;
}

double mc_hertz_point_uz(const mc_hertz_point *h, double r)
{
    double a = h->a, rr = fabs(r);
    if (rr <= a)
        return M_PI * h->p0 * (2.0 * a * a - rr * rr) / (4.0 * a * h->Estar);
    /* u_z 2 E* / (p0 a) = (2 - rho^2) asin(s) + sqrt(rho^2 - 1), s = a/r: the far field ~ 4s/3
     * is the difference of two O(rho) terms, so write it as 2 asin(s) - g(s)/s^2 with
     * g = asin(s) - s sqrt(1-s^2) = sum_k 2 c_k s^(2k+3)/(2k+3), c_k = binom(2k,k)/4^k (from
     * g' = 2 s^2/sqrt(1-s^2)); for s <= 1/2 the terms fall at least as 4^-k. */
    double s = a / rr, f;
    if (s <= 0.5) {
        double s2 = s * s, ck = 1.0, pw = s, g_s2 = 0.0;
        for (int k = 0; k < 64; k++) {
            double term = 2.0 * ck * pw / (2.0 * k + 3.0);
            g_s2 += term;
            if (term <= 1e-18 * g_s2)
                break;
            ck *= (2.0 * k + 1.0) / (2.0 * k + 2.0);
            pw *= s2;
        }
        f = 2.0 * asin(s) - g_s2;
    } else {
        double rho = rr / a;
        f = (2.0 - rho * rho) * asin(s) + sqrt((rho - 1.0) * (rho + 1.0));
    }
    return 0.5 * h->p0 * a / h->Estar * f;
}

/* ---- Hertz point contact, normalised fields ----------------------------------------------- */

void mc_hertz_point_axis(double zeta, double nu, double *sr, double *sz)
{
    double q = 1.0 / (1.0 + zeta * zeta);
    /* atan2(1, zeta) = atan(1/zeta), finite at zeta = 0 */
    *sr = -(1.0 + nu) * (1.0 - zeta * atan2(1.0, zeta)) + 0.5 * q;
    *sz = -q;
}

void mc_hertz_point_surface(double rho, double nu, double *sr, double *st, double *sz)
{
    double r = fabs(rho);
    if (r < 1.0) {
        double t = sqrt((1.0 - r) * (1.0 + r));
        /* (1/rho^2)(1 - t^3) = (1 + t + t^2)/(1 + t), since 1 - t^2 = rho^2: no cancellation */
        double k = (1.0 - 2.0 * nu) / 3.0 * (1.0 + t + t * t) / (1.0 + t);
        *sr = k - t;
        *st = -k - 2.0 * nu * t;
        *sz = -t;
    } else {
        *sr = (1.0 - 2.0 * nu) / (3.0 * r * r);
        *st = -*sr;
        *sz = 0.0;
    }
}

/* Hamilton's auxiliary quantities (theory.md §6.2), lengths / a:
 * A = r^2 + z^2 - 1, S = sqrt(A^2 + 4 z^2), M = sqrt((S+A)/2), N = sqrt((S-A)/2).
 * M^2 is Huber's u, and M N = z. The smaller of M, N is taken as z / (the larger) so that neither
 * loses digits to the cancellation S - |A| (z -> 0 inside or outside the contact circle). */
typedef struct {
    double A, S, M, N, invS;
} hamilton_aux;

static hamilton_aux hamilton_aux_at(double r2, double z)
{
    hamilton_aux h;
    h.A = r2 + z * z - 1.0;
    h.S = hypot(h.A, 2.0 * z);
    if (h.A >= 0.0) {
        h.M = sqrt(0.5 * (h.S + h.A));
        h.N = h.M > 0.0 ? z / h.M : 0.0;
    } else {
        h.N = sqrt(0.5 * (h.S - h.A));
        h.M = z / h.N;
    }
    /* S = 0 only on the contact edge at the surface; every 1/S term there is multiplied by z
     * (or by M, N, which vanish too), so 0 gives the surface limit. */
    h.invS = h.S > 0.0 ? 1.0 / h.S : 0.0;
    return h;
}

void mc_hertz_huber(double r, double z, double nu, double *sr, double *st, double *sz, double *trz)
{
    hamilton_aux h = hamilton_aux_at(r * r, z);
    double u = h.M * h.M;                      /* Huber's u */
    double w = h.N;                            /* z / sqrt(u) */
    double sqrtu_atan = h.M * atan2(1.0, h.M); /* sqrt(u) atan(1/sqrt(u)) */
    /* (1/r^2)(1 - w^3): from the root equation 1 - w^2 = r^2/(1+u), hence exactly
     * (1 + w + w^2) / ((1+u)(1+w)); finite and exact on the axis (3/(2(1+z^2))). */
    double k = (1.0 + w + w * w) / ((1.0 + u) * (1.0 + w));
    /* u/(u^2 + z^2) = 1/(M^2 + N^2) = 1/S, since z^2 = M^2 N^2 */
    double w3S = w * w * w * h.invS;
    double m = 1.0 - 2.0 * nu;
    *sr = m / 3.0 * k + w3S + w * ((1.0 - nu) * u / (1.0 + u) + (1.0 + nu) * sqrtu_atan - 2.0);
    /* the MINUS in front of the second term (theory.md §6.2, box at the top) */
    *st = -m / 3.0 * k - w * (2.0 * nu + (1.0 - nu) * u / (1.0 + u) - (1.0 + nu) * sqrtu_atan);
    *sz = -w3S;
    /* r z^2/(u^2+z^2) sqrt(u)/(1+u) = r M N^2 / (S (1 + M^2)) */
    *trz = -r * h.M * h.N * h.N * h.invS / (1.0 + u);
}

/* ---- near-axis evaluation of Hamilton's 1/r^2 and 1/r^4 brackets ------------------------------
 * Hamilton's Cartesian expressions divide brackets that vanish on the axis like r^2 (normal) or
 * r^4 (tangential) by those powers of r: evaluated directly they lose digits as eps/r^2 and
 * eps/r^3 (measured: 4e-4 p0 for the normal and 1e5 q0 for the tangential field at r = 1e-7 a).
 * Near the axis the brackets are therefore expanded as truncated power series in t = r^2 at fixed
 * depth z and direction (x/r, y/r): A, S, M, N are analytic in t with radius of convergence
 * 1 + z^2 (the zeros of S^2 = A^2 + 4z^2), so with t <= (1 + z^2)/16 the terms fall at least as
 * 16^-j, and the division by t^p becomes a shift of coefficients that vanish analytically. */
#define SER_N 20                 /* terms kept: 16^-(SER_N-2) is far below eps */
#define NEAR_AXIS_T (1.0 / 16.0) /* series used for t < NEAR_AXIS_T (1 + z^2) */

typedef struct {
    double c[SER_N]; /* coefficients of t^0 ... t^(SER_N-1) */
} ser;

static ser s_lin(double c0, double c1)
{
    ser r = {{0}};
    r.c[0] = c0;
    r.c[1] = c1;
    return r;
}

/* a*x + b*y */
static ser s_comb(double a, ser x, double b, ser y)
{
    ser r;
    for (int k = 0; k < SER_N; k++)
        r.c[k] = a * x.c[k] + b * y.c[k];
    return r;
}

static ser s_scale(double a, ser x)
{
    for (int k = 0; k < SER_N; k++)
        x.c[k] *= a;
    return x;
}

static ser s_addc(ser x, double v)
{
    x.c[0] += v;
    return x;
}

static ser s_mul(ser x, ser y)
{
    ser r;
    for (int k = 0; k < SER_N; k++) {
        double acc = 0.0;
        for (int i = 0; i <= k; i++)
            acc += x.c[i] * y.c[k - i];
        r.c[k] = acc;
    }
    return r;
}

/* x / y, y.c[0] != 0 */
static ser s_div(ser x, ser y)
{
    ser r;
    for (int k = 0; k < SER_N; k++) {
        double acc = x.c[k];
        for (int i = 1; i <= k; i++)
            acc -= y.c[i] * r.c[k - i];
        r.c[k] = acc / y.c[0];
    }
    return r;
}

/* sqrt(x), x.c[0] > 0 */
static ser s_sqrt(ser x)
{
    ser r;
    r.c[0] = sqrt(x.c[0]);
    for (int k = 1; k < SER_N; k++) {
        double acc = x.c[k];
        for (int i = 1; i < k; i++)
            acc -= r.c[i] * r.c[k - i];
        r.c[k] = acc / (2.0 * r.c[0]);
    }
    return r;
}

/* sum_{j >= p} x_j t^(j-p): the value of x / t^p when x_0 .. x_(p-1) vanish analytically */
static double s_eval_div(ser x, int p, double t)
{
    double v = 0.0;
    for (int k = SER_N - 1; k >= p; k--)
        v = v * t + x.c[k];
    return v;
}

/* Hamilton's A, S, M, N, 1/S as series in t at depth z (N(0) = 1, M(0) = z, S(0) = 1 + z^2). */
typedef struct {
    ser t, A, S, M, N, iS;
} hamilton_ser;

static hamilton_ser hamilton_ser_at(double z)
{
    hamilton_ser h;
    ser one = s_lin(1.0, 0.0);
    h.t = s_lin(0.0, 1.0);
    h.A = s_lin(z * z - 1.0, 1.0);
    h.S = s_sqrt(s_addc(s_mul(h.A, h.A), 4.0 * z * z));
    h.N = s_sqrt(s_comb(0.5, h.S, -0.5, h.A));
    h.M = s_div(s_lin(z, 0.0), h.N); /* M N = z */
    h.iS = s_div(one, h.S);
    return h;
}

/* Near-axis quantities of the normal field: C/t and the sxy bracket / t. */
typedef struct {
    double C_t, Kxy_t;
} normal_brackets;

static normal_brackets normal_brackets_direct(const hamilton_aux *h, double t, double z, double nu)
{
    double A = h->A, S = h->S, M = h->M, N = h->N, iS = h->invS;
    double C =
        (1.0 - nu) * N * z * z - (1.0 - 2.0 * nu) / 3.0 * (N * S + 2.0 * A * N + 1.0) - nu * M * z;
    double K =
        (1.0 - 2.0 * nu) * (-N * t + 2.0 / 3.0 * N * (S + 2.0 * A) - z * (z * N + M) + 2.0 / 3.0) +
        z * (-M * t * iS - z * N + M);
    normal_brackets b = {C / t, K / t};
    return b;
}

static normal_brackets normal_brackets_series(double t, double z, double nu)
{
    hamilton_ser h = hamilton_ser_at(z);
    ser NS = s_mul(h.N, h.S), AN = s_mul(h.A, h.N);
    /* C = (1-nu) z^2 N - (1-2nu)/3 (N S + 2 A N + 1) - nu z M */
    ser C = s_comb((1.0 - nu) * z * z, h.N, -(1.0 - 2.0 * nu) / 3.0, s_comb(1.0, NS, 2.0, AN));
    C = s_addc(s_comb(1.0, C, -nu * z, h.M), -(1.0 - 2.0 * nu) / 3.0);
    /* (1-2nu)[-N t + 2/3 (N S + 2 A N) - z^2 N - z M + 2/3] + z[-M t/S - z N + M] */
    ser Nt = s_mul(h.N, h.t);
    ser b1 = s_comb(-1.0, Nt, 2.0 / 3.0, s_comb(1.0, NS, 2.0, AN));
    b1 = s_addc(s_comb(1.0, b1, -z, s_comb(z, h.N, 1.0, h.M)), 2.0 / 3.0);
    ser Mt_S = s_mul(s_mul(h.M, h.t), h.iS);
    ser b2 = s_comb(-1.0, Mt_S, 1.0, s_comb(-z, h.N, 1.0, h.M));
    ser K = s_comb(1.0 - 2.0 * nu, b1, z, b2);
    normal_brackets b = {s_eval_div(C, 1, t), s_eval_div(K, 1, t)};
    return b;
}

void mc_hertz_hamilton_normal(double x, double y, double z, double nu, double s[6])
{
    double r = hypot(x, y);
    if (r == 0.0) {
        mc_hertz_point_axis(z, nu, &s[MC_SXX], &s[MC_SZZ]);
        s[MC_SYY] = s[MC_SXX];
        s[MC_SXY] = s[MC_SYZ] = s[MC_SXZ] = 0.0;
        return;
    }
    double t = r * r, cx = x / r, cy = y / r, c2 = cx * cx, s2 = cy * cy;
    hamilton_aux h = hamilton_aux_at(t, z);
    double M = h.M, N = h.N, iS = h.invS;
    normal_brackets b = t < NEAR_AXIS_T * (1.0 + z * z) ? normal_brackets_series(t, z, nu)
                                                        : normal_brackets_direct(&h, t, z, nu);
    double phi = atan2(1.0, M); /* atan(1/M), pi/2 at M = 0 */
    double G = M * M - N * N + z * M - N;
    double H = 2.0 * M * N + M + z * N;
    double GH = G * G + H * H;
    double zH = GH > 0.0 ? z * H / GH : 0.0; /* GH = 0 only on the contact edge at z = 0 */

    s[MC_SXX] =
        (1.0 + nu) * z * phi + (s2 - c2) * b.C_t - N * (c2 + 2.0 * nu * s2) - M * c2 * z * iS;
    s[MC_SYY] =
        (1.0 + nu) * z * phi + (c2 - s2) * b.C_t - N * (s2 + 2.0 * nu * c2) - M * s2 * z * iS;
    s[MC_SZZ] = -N + z * M * iS;
    s[MC_SXY] = cx * cy * b.Kxy_t;
    s[MC_SXZ] = -z * x * (N * iS - zH);
    s[MC_SYZ] = -z * y * (N * iS - zH);
}

/* The tangential field written as (theory.md §6.2 with x^2 = c2 t, y^2 = s2 t):
 *   sxx = x(-(nu/4+1) phi + Kxx/t^2)     syy = x(-(3nu/4) phi + Kyy/t^2)    szz = x Kzz/t
 *   sxy = y((nu/2-1) phi/2 + Kxy/t^2)    sxz = (3/2) z phi + Kxz/t          syz = cx cy Kyz/t */
typedef struct {
    double xx, yy, zz, xy, xz, yz; /* Kxx/t^2, Kyy/t^2, Kzz/t, Kxy/t^2, Kxz/t, Kyz/t */
} tangential_brackets;

static tangential_brackets tangential_brackets_direct(const hamilton_aux *h, double t, double z,
                                                      double nu, double c2, double s2)
{
    double A = h->A, S = h->S, M = h->M, N = h->N, iS = h->invS, z2 = z * z;
    double m = 1.0 - 2.0 * nu;
    double f = 1.5 - 2.0 * c2, hx = 0.5 - 2.0 * c2, hy = 0.5 - 2.0 * s2;
    double it = 1.0 / t, it2 = it * it;
    tangential_brackets k;
    k.xx = (M * (f * (nu * S - 2.0 * nu * A + z2) + c2 * t * z2 * iS + 1.75 * nu * t -
                 2.0 * nu * c2 * t + t) +
            z * N *
                (f * (-m * S / 6.0 - m * A / 3.0 - 0.5 * (z2 + 3.0)) + c2 * t * iS - 0.25 * nu * t -
                 1.75 * t) +
            4.0 * z * m * f / 3.0) *
           it2;
    k.yy = (M * (hy * (nu * (S - 2.0 * A + t) + z2) + s2 * t * z2 * iS + 0.75 * nu * t) +
            z * N *
                (hy * (-m * S / 6.0 - m * A / 3.0 - 0.5 * z2 - 1.5) + s2 * t * iS - 0.75 * nu * t -
                 0.25 * t) +
            4.0 * z * m * hy / 3.0) *
           it2;
    k.zz = 0.5 * z * N * (1.0 - (t + z2 + 1.0) * iS) * it;
    k.xy = (M * (c2 * t * z2 * iS + nu * ((S - 2.0 * A) * hx - 2.0 * c2 * t + 0.25 * t) + 0.5 * t +
                 z2 * hx) +
            z * N *
                (hx * (-m * (S / 6.0 + A / 3.0) - 0.5 * z2 - 1.5 - 0.5 * t) + 0.25 * nu * t +
                 c2 * t * iS - 0.5 * s2 * t - 1.5 * c2 * t) +
            4.0 * z * m * hx / 3.0) *
           it2;
    k.xz = (z * M * (1.0 + c2 - c2 * t * iS) +
            N * (-0.75 * (S + 2.0 * A) + z2 - 0.75 - 0.25 * t + 0.5 * z2 * hx)) *
           it;
    k.yz =
        0.5 * z *
        (M * (0.5 + (0.5 * z2 - 1.5 - 0.5 * t) * iS) + 0.5 * z * N * (-3.0 + (5.0 + z2 + t) * iS)) *
        it;
    return k;
}

static tangential_brackets tangential_brackets_series(double t, double z, double nu, double c2,
                                                      double s2)
{
    hamilton_ser h = hamilton_ser_at(z);
    double z2 = z * z, m = 1.0 - 2.0 * nu;
    double f = 1.5 - 2.0 * c2, hx = 0.5 - 2.0 * c2, hy = 0.5 - 2.0 * s2;
    ser t_S = s_mul(h.t, h.iS); /* t/S */
    ser zN = s_scale(z, h.N);
    ser zM = s_scale(z, h.M);
    /* m S/6 + m A/3 */
    ser mSA = s_comb(m / 6.0, h.S, m / 3.0, h.A);
    tangential_brackets k;
    ser b1, b2, K;

    /* Kxx = M[f(nu S - 2 nu A + z^2) + c2 z^2 t/S + (7nu/4 - 2 nu c2 + 1) t]
     *     + z N[f(-(m S/6 + m A/3) - (z^2+3)/2) + c2 t/S - (nu/4 + 7/4) t] + 4 z m f/3 */
    b1 = s_addc(s_comb(f * nu, h.S, -2.0 * f * nu, h.A), f * z2);
    b1 = s_comb(1.0, b1, c2 * z2, t_S);
    b1 = s_comb(1.0, b1, 1.75 * nu - 2.0 * nu * c2 + 1.0, h.t);
    b2 = s_addc(s_comb(-f, mSA, c2, t_S), -0.5 * f * (z2 + 3.0));
    b2 = s_comb(1.0, b2, -(0.25 * nu + 1.75), h.t);
    K = s_addc(s_comb(1.0, s_mul(h.M, b1), 1.0, s_mul(zN, b2)), 4.0 * z * m * f / 3.0);
    k.xx = s_eval_div(K, 2, t);

    /* Kyy = M[hy(nu(S - 2A + t) + z^2) + s2 z^2 t/S + (3nu/4) t]
     *     + z N[hy(-(m S/6 + m A/3) - z^2/2 - 3/2) + s2 t/S - (3nu/4 + 1/4) t] + 4 z m hy/3 */
    b1 = s_comb(hy * nu, h.S, -2.0 * hy * nu, h.A);
    b1 = s_addc(s_comb(1.0, b1, hy * nu + 0.75 * nu, h.t), hy * z2);
    b1 = s_comb(1.0, b1, s2 * z2, t_S);
    b2 = s_addc(s_comb(-hy, mSA, s2, t_S), hy * (-0.5 * z2 - 1.5));
    b2 = s_comb(1.0, b2, -(0.75 * nu + 0.25), h.t);
    K = s_addc(s_comb(1.0, s_mul(h.M, b1), 1.0, s_mul(zN, b2)), 4.0 * z * m * hy / 3.0);
    k.yy = s_eval_div(K, 2, t);

    /* Kzz = (z N/2)(1 - (t + z^2 + 1)/S) */
    b1 = s_addc(s_scale(-1.0, s_mul(s_addc(h.t, z2 + 1.0), h.iS)), 1.0);
    K = s_scale(0.5, s_mul(zN, b1));
    k.zz = s_eval_div(K, 1, t);

    /* Kxy = M[c2 z^2 t/S + nu((S - 2A) hx) + (-2 nu c2 + nu/4 + 1/2) t + z^2 hx]
     *     + z N[-hx (m S/6 + m A/3) + (nu/4 - hx/2 - s2/2 - 3 c2/2) t + c2 t/S - hx (z^2/2 + 3/2)]
     *     + 4 z m hx/3 */
    b1 = s_addc(s_comb(nu * hx, h.S, -2.0 * nu * hx, h.A), z2 * hx);
    b1 = s_comb(1.0, b1, c2 * z2, t_S);
    b1 = s_comb(1.0, b1, -2.0 * nu * c2 + 0.25 * nu + 0.5, h.t);
    b2 = s_addc(s_comb(-hx, mSA, c2, t_S), -hx * (0.5 * z2 + 1.5));
    b2 = s_comb(1.0, b2, 0.25 * nu - 0.5 * hx - 0.5 * s2 - 1.5 * c2, h.t);
    K = s_addc(s_comb(1.0, s_mul(h.M, b1), 1.0, s_mul(zN, b2)), 4.0 * z * m * hx / 3.0);
    k.xy = s_eval_div(K, 2, t);

    /* Kxz = z M (1 + c2 - c2 t/S) + N(-(3/4)(S + 2A) - t/4 + z^2 - 3/4 + z^2 hx/2) */
    b1 = s_addc(s_scale(-c2, t_S), 1.0 + c2);
    b2 = s_comb(-0.75, s_comb(1.0, h.S, 2.0, h.A), -0.25, h.t);
    b2 = s_addc(b2, z2 - 0.75 + 0.5 * z2 * hx);
    K = s_comb(1.0, s_mul(zM, b1), 1.0, s_mul(h.N, b2));
    k.xz = s_eval_div(K, 1, t);

    /* Kyz = (z/2)[M(1/2 + (z^2/2 - 3/2 - t/2)/S) + (z N/2)(-3 + (5 + z^2 + t)/S)] */
    b1 = s_addc(s_mul(s_addc(s_scale(-0.5, h.t), 0.5 * z2 - 1.5), h.iS), 0.5);
    b2 = s_addc(s_mul(s_addc(h.t, 5.0 + z2), h.iS), -3.0);
    K = s_comb(0.5 * z, s_mul(h.M, b1), 0.25 * z, s_mul(zN, b2));
    k.yz = s_eval_div(K, 1, t);
    return k;
}

void mc_hertz_hamilton_tangential(double x, double y, double z, double nu, double s[6])
{
    double r = hypot(x, y);
    if (r == 0.0) {
        s[MC_SXX] = s[MC_SYY] = s[MC_SZZ] = s[MC_SXY] = s[MC_SYZ] = 0.0;
        s[MC_SXZ] = -1.0 + 1.5 * z * atan2(1.0, z) - z * z / (2.0 * (1.0 + z * z));
        return;
    }
    double t = r * r, cx = x / r, cy = y / r, c2 = cx * cx, s2 = cy * cy;
    hamilton_aux h = hamilton_aux_at(t, z);
    tangential_brackets k = t < NEAR_AXIS_T * (1.0 + z * z)
                                ? tangential_brackets_series(t, z, nu, c2, s2)
                                : tangential_brackets_direct(&h, t, z, nu, c2, s2);
    double phi = atan2(1.0, h.M);
    s[MC_SXX] = x * (-(0.25 * nu + 1.0) * phi + k.xx);
    s[MC_SYY] = x * (-0.75 * nu * phi + k.yy);
    s[MC_SZZ] = x * k.zz;
    s[MC_SXY] = y * (0.5 * (0.5 * nu - 1.0) * phi + k.xy);
    s[MC_SXZ] = 1.5 * z * phi + k.xz;
    s[MC_SYZ] = cx * cy * k.yz;
}

void mc_hertz_point_sliding(double x, double y, double z, double nu, double mu, double s[6])
{
    double t[6];
    mc_hertz_hamilton_normal(x, y, z, nu, s);
    mc_hertz_hamilton_tangential(x, y, z, nu, t);
    for (int c = 0; c < MC_NSTRESS; c++)
        s[c] += mu * t[c];
}

/* ---- Hertz line contact, SI ----------------------------------------------------------------- */

int mc_hertz_line_from_load(double R, double Estar, double load, mc_hertz_line *h, mc_error *err)
{
    if (!h)
        return mc_fail(err, MC_ERR_INPUT, "hertz line: NULL result");
    if (!positive_finite(R) || !positive_finite(Estar) || !positive_finite(load))
        return mc_fail(err, MC_ERR_INPUT,
                       "hertz line: need R > 0, E* > 0, P' > 0 (got R=%g m, E*=%g Pa, "
                       "P'=%g N/m)",
                       R, Estar, load);
    h->R = R;
    h->Estar = Estar;
    h->load = load;
    h->b = sqrt(4.0 * load * R / (M_PI * Estar));
    h->p0 = 2.0 * load / (M_PI * h->b);
    return MC_OK;
}

double mc_hertz_line_pressure(const mc_hertz_line *h, double x)
{
    double t = x / h->b;
    return fabs(t) < 1.0 ? h->p0 * sqrt((1.0 - t) * (1.0 + t)) : 0.0;
}

/* ---- Hertz line contact, normalised fields -------------------------------------------------- */

/* McEwen's m, n (theory.md §6.3): m^2 = (Q + B)/2, n^2 = (Q - B)/2, Q = sqrt(B^2 + 4x^2z^2),
 * B = 1 - x^2 + z^2; m n = |x| z, so the smaller one is formed as |x| z / (the larger) to avoid
 * the cancellation Q - |B|. sign(n) = sign(x). */
static void mcewen_mn(double x, double z, double *m, double *n)
{
    double B = 1.0 - x * x + z * z;
    double Q = hypot(B, 2.0 * x * z);
    double mm, nn;
    if (B >= 0.0) {
        mm = sqrt(0.5 * (Q + B));
        nn = mm > 0.0 ? fabs(x) * z / mm : 0.0;
    } else {
        nn = sqrt(0.5 * (Q - B));
        mm = fabs(x) * z / nn;
    }
    *m = mm;
    *n = x < 0.0 ? -nn : nn;
}

static void plane_strain_fill(double sxx, double szz, double sxz, double nu, double s[6])
{
    s[MC_SXX] = sxx;
    s[MC_SZZ] = szz;
    s[MC_SXZ] = sxz;
    s[MC_SYY] = nu * (sxx + szz);
    s[MC_SXY] = s[MC_SYZ] = 0.0;
}

void mc_mcewen_normal(double x, double z, double nu, double s[6])
{
    double m, n;
    mcewen_mn(x, z, &m, &n);
    double d = m * m + n * n;
    /* d = 0 only at the contact edge on the surface, where the fractions are multiplied by m
     * or n = 0 and the stresses tend to 0 */
    double id = d > 0.0 ? 1.0 / d : 0.0;
    double sxx = -(m * (1.0 + (z * z + n * n) * id) - 2.0 * z);
    double szz = -m * (1.0 - (z * z + n * n) * id);
    double sxz = -n * (m * m - z * z) * id;
    plane_strain_fill(sxx, szz, sxz, nu, s);
}

void mc_mcewen_tangential(double x, double z, double nu, double s[6])
{
    double m, n;
    mcewen_mn(x, z, &m, &n);
    double d = m * m + n * n;
    double id = d > 0.0 ? 1.0 / d : 0.0;
    double sxx = n * (2.0 - (z * z - m * m) * id) - 2.0 * x;
    double szz = -n * (m * m - z * z) * id;
    double sxz = -(m * (1.0 + (z * z + n * n) * id) - 2.0 * z);
    plane_strain_fill(sxx, szz, sxz, nu, s);
}

void mc_hertz_line_sliding(double x, double z, double nu, double mu, double s[6])
{
    double t[6];
    mc_mcewen_normal(x, z, nu, s);
    mc_mcewen_tangential(x, z, nu, t);
    for (int c = 0; c < MC_NSTRESS; c++)
        s[c] += mu * t[c];
}

/* ---- plane-strain line loads ----------------------------------------------------------------- */

void mc_flamant_strip_uniform(double x, double z, double a, double nu, double s[6])
{
    /* Integrating Flamant over the strip with x - xi = z tan(theta) turns the kernels into
     * cos^2, sin^2 and sin cos of theta, hence these angle forms. */
    double tp = atan2(x + a, z), tm = atan2(x - a, z);
    double dt = tp - tm;
    double ds = 0.5 * (sin(2.0 * tp) - sin(2.0 * tm));
    double sxx = -(dt - ds) / M_PI;
    double szz = -(dt + ds) / M_PI;
    double sxz = (cos(2.0 * tp) - cos(2.0 * tm)) / (2.0 * M_PI);
    plane_strain_fill(sxx, szz, sxz, nu, s);
}

void mc_flamant_normal(double x, double z, double nu, double s[6])
{
    double r2 = x * x + z * z;
    double c = -2.0 / (M_PI * r2 * r2);
    plane_strain_fill(c * x * x * z, c * z * z * z, c * x * z * z, nu, s);
}

void mc_flamant_tangential(double x, double z, double nu, double s[6])
{
    double r2 = x * x + z * z;
    double c = -2.0 / (M_PI * r2 * r2);
    plane_strain_fill(c * x * x * x, c * x * z * z, c * x * x * z, nu, s);
}

void mc_flamant_antiplane(double x, double z, double s[6])
{
    double c = -1.0 / (M_PI * (x * x + z * z));
    s[MC_SXX] = s[MC_SYY] = s[MC_SZZ] = s[MC_SXZ] = 0.0;
    s[MC_SYZ] = c * z;
    s[MC_SXY] = c * x;
}
