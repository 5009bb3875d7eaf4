/* test_eigen_spectral.c - the half-space eigenstrain kernel per lateral Fourier mode
 * (src/kernels/eigen_spectral.h; docs/theory.md §8.10), against properties it must have and
 * that its construction does not impose:
 *   - the O(nz) running sums (mc_spec_depth) against the pair-by-pair closed forms;
 *   - a traction-free surface (sigma_zz = sigma_xz = sigma_yz = 0 at z = 0);
 *   - equilibrium (i k . sigma + d sigma_z / dz = 0, central differences in depth) and traction
 *     continuity across the layer faces;
 *   - the layer average against Gauss-Legendre quadrature of the point stress;
 *   - Betti: the averaged operator is Hermitian and negative semi-definite in the energy inner
 *     product (no energy-releasing mode);
 *   - reciprocity: the surface displacement of an eigenstrain layer equals the integral of the
 *     Boussinesq stress of the pressure mode over the layer (kernels independent of S1 + S2). */
#include <check.h>
#include <complex.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernels/eigen_spectral.h"
#include "test_util.h"

static const double NU = 0.3;

/* the two depth algorithms: running sums against pair sums, round-off of O(nz) terms */
#define TOL_DEPTH 1e-12
/* closed-form identities at a point: round-off of the O(1) terms */
#define TOL_IDENTITY 1e-12
/* central differences of step d in t = q z: O(d^2) of the second derivative (~1) */
#define FD_STEP 1e-4
#define TOL_FD 1e-6
/* 20-point Gauss-Legendre of a smooth integrand over one layer (h q <= 4): below 1e-13 */
#define TOL_QUAD 1e-11
/* the 15 printed digits of an O(1) stress */
#define TOL_ODE 1e-13

static double cmax6(double complex S[6][6])
{
    double m = 0.0;
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 6; c++)
            m = fmax(m, cabs(S[i][c]));
    return m;
}

/* modes and layerings: uniform fine, graded, and one thick layer */
static const double KS[][2] = {{1e6, 0.0}, {0.0, 2.5e6}, {1.2e6, -0.7e6}, {3e4, 1e4}, {4e6, 5e6}};
#define N_KS 5

static int layering(int which, double *b)
{
    const int nz = which == 2 ? 1 : 7;
    b[0] = 0.0;
    for (int l = 0; l < nz; l++) {
        double h = 0.25e-6;
        if (which == 1)
            h *= (l < 3 ? 1 : 2 * l - 3); /* 1, 1, 1, 3, 5, 7, 9 fine layers */
        if (which == 2)
            h = 1.5e-6;
        b[l + 1] = b[l] + h;
    }
    return nz;
}

/* nz layers of random complex eigenstrain (seeds a, b for the real and imaginary parts) */
static void random_layers(int nz, unsigned a, unsigned b, double complex eps[16][6])
{
    double re[6 * 16], im[6 * 16];
    test_random_field(re, 6 * (size_t)nz, a);
    test_random_field(im, 6 * (size_t)nz, b);
    for (int l = 0; l < nz; l++)
        for (int c = 0; c < 6; c++)
            eps[l][c] = re[6 * l + c] + I * im[6 * l + c];
}

/* ---- the running sums against the pairs ------------------------------------------------------- */

START_TEST(test_depth_vs_pairs)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    double b[16];
    double worst = 0.0;
    for (int lay = 0; lay < 3; lay++) {
        const int nz = layering(lay, b);
        for (int m = 0; m < N_KS; m++)
            for (int pt = 0; pt < 2; pt++) {
                double complex eps[16][6], sig[16][6], ref[16][6] = {{0}}, work[12 * 16], uz,
                                                                  uzr = 0.0;
                random_layers(nz, 11 + (unsigned)m, 97 + (unsigned)m, eps);
                mc_spec_depth(&k, KS[m][0], KS[m][1], nz, b, (mc_spec_point)pt,
                              (const double complex(*)[6])eps, sig, &uz, work);
                double scale = 0.0;
                for (int i = 0; i < nz; i++)
                    for (int j = 0; j < nz; j++) {
                        double complex S[6][6];
                        mc_spec_pair(&k, KS[m][0], KS[m][1], b[i], b[i + 1], b[j], b[j + 1],
                                     (mc_spec_point)pt, S);
                        for (int r = 0; r < 6; r++)
                            for (int c = 0; c < 6; c++)
                                ref[i][r] += S[r][c] * eps[j][c];
                    }
                double complex Dl[16][6], uzl = 0.0;
                mc_spec_uz_layers(&k, KS[m][0], KS[m][1], nz, b, Dl);
                for (int j = 0; j < nz; j++) {
                    double complex D[6];
                    mc_spec_pair_uz(&k, KS[m][0], KS[m][1], b[j], b[j + 1], D);
                    for (int c = 0; c < 6; c++) {
                        uzr += D[c] * eps[j][c];
                        uzl += Dl[j][c] * eps[j][c];
                    }
                }
                worst = test_worst(worst, cabs(uzl - uzr) / cabs(uzr));
                for (int i = 0; i < nz; i++)
                    for (int r = 0; r < 6; r++)
                        scale = fmax(scale, cabs(ref[i][r]));
                for (int i = 0; i < nz; i++)
                    for (int r = 0; r < 6; r++)
                        worst = test_worst(worst, cabs(sig[i][r] - ref[i][r]) / scale);
                worst = test_worst(worst, cabs(uz - uzr) / cabs(uzr));
                ck_assert(scale > 0.1 && cabs(uzr) > 0.0);
            }
    }
    ck_assert_msg(worst <= TOL_DEPTH, "running sums vs pairs: %.3g", worst);
}
END_TEST

/* the two passes layer by layer (mc_spec_down_layer, mc_spec_up_layer) against mc_spec_depth */
START_TEST(test_streamed)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    double b[16];
    double worst = 0.0;
    for (int lay = 0; lay < 3; lay++) {
        const int nz = layering(lay, b);
        for (int m = 0; m < N_KS; m++)
            for (int pt = 0; pt < 2; pt++) {
                double complex eps[16][6], ref[16][6], sig[16][6], work[12 * 16], uz, uzs;
                random_layers(nz, 31 + (unsigned)m, 37 + (unsigned)m, eps);
                mc_spec_depth(&k, KS[m][0], KS[m][1], nz, b, (mc_spec_point)pt,
                              (const double complex(*)[6])eps, ref, &uz, work);
                mc_spec_state st;
                mc_spec_state_init(&st, KS[m][0], KS[m][1]);
                for (int l = 0; l < nz; l++)
                    mc_spec_down_layer(&k, b[l], b[l + 1], (mc_spec_point)pt, eps[l], &st, sig[l]);
                uzs = mc_spec_turn(&k, &st);
                for (int l = nz - 1; l >= 0; l--) {
                    double complex add[6];
                    mc_spec_up_layer(&k, b[l], b[l + 1], (mc_spec_point)pt, eps[l], &st, add);
                    for (int c = 0; c < 6; c++)
                        sig[l][c] += add[c];
                }
                double scale = 0.0;
                for (int l = 0; l < nz; l++)
                    for (int c = 0; c < 6; c++)
                        scale = fmax(scale, cabs(ref[l][c]));
                for (int l = 0; l < nz; l++)
                    for (int c = 0; c < 6; c++)
                        worst = test_worst(worst, cabs(sig[l][c] - ref[l][c]) / scale);
                worst = test_worst(worst, cabs(uzs - uz) / cabs(uz));
            }
    }
    ck_assert_msg(worst <= TOL_DEPTH, "streamed vs running sums: %.3g", worst);
}
END_TEST


/* the many-modes step (mc_spec_modes_pass, mc_spec_modes_turn) against the single-mode one, in
 * blocks of one and of two layers of a thickness, with e^{-q top} by division and by exp() */
START_TEST(test_modes)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    enum { NM = N_KS + 1 }; /* mode 0: k = 0, kept out of the passes as the operator does */
    double b[16], mq[3 * NM], st[MC_SPEC_FIELDS * NM], wt[MC_SPEC_WEIGHTS * NM], wgt[NM];
    for (int m = 0; m < NM; m++) {
        const double kx = m ? KS[m - 1][0] : 0.0, ky = m ? KS[m - 1][1] : 0.0, q = hypot(kx, ky);
        mq[m] = q;
        mq[NM + m] = q > 0 ? kx / q : 1.0;
        mq[2 * NM + m] = q > 0 ? ky / q : 0.0;
        wgt[m] = 0.5 + 0.1 * m;
    }
    double worst = 0.0;
    for (int lay = 0; lay < 3; lay++)
        for (int pt = 0; pt < 2; pt++)
            for (int variant = 0; variant < 4; variant++) {
                const int block = variant & 1 ? 2 : 1, divide = variant < 2;
                const int nz = layering(lay, b);
                double complex eps[NM][16][6], ref[NM][16][6], p3r[NM], uzr[NM];
                for (int m = 1; m < NM; m++) { /* the reference, mode by mode */
                    random_layers(nz, 41 + (unsigned)m, 43 + (unsigned)m, eps[m]);
                    mc_spec_state s;
                    mc_spec_state_init(&s, KS[m - 1][0], KS[m - 1][1]);
                    for (int l = 0; l < nz; l++)
                        mc_spec_down_layer(&k, b[l], b[l + 1], (mc_spec_point)pt, eps[m][l], &s,
                                           ref[m][l]);
                    uzr[m] = mc_spec_turn(&k, &s);
                    p3r[m] = s.p3;
                    for (int l = nz - 1; l >= 0; l--) {
                        double complex add[6];
                        mc_spec_up_layer(&k, b[l], b[l + 1], (mc_spec_point)pt, eps[m][l], &s,
                                         add);
                        for (int c = 0; c < 6; c++)
                            ref[m][l][c] += add[c];
                    }
                }
                mc_spec_modes sm = {NM, st, mq, mq + NM, mq + 2 * NM, wt};
                mc_spec_modes_clear(&sm);
                /* layer l, component c of mode m at in[l][c][m]; results likewise */
                double complex in[16][6][NM], dn[16][6][NM], up[16][6][NM], p3[NM], uz[NM];
                for (int l = 0; l < nz; l++)
                    for (int c = 0; c < 6; c++)
                        for (int m = 0; m < NM; m++)
                            in[l][c][m] = m ? eps[m][l][c] : 0.0;
                for (int pass = 0; pass < 2; pass++) {
                    for (int n = 0; n < nz;) {
                        const int l0 = pass ? nz - 1 - n : n, dir = pass ? -1 : 1;
                        const double t = b[l0 + 1] - b[l0];
                        int nb = 1;
                        while (nb < block && n + nb < nz &&
                               fabs(b[l0 + dir * nb + 1] - b[l0 + dir * nb] - t) <= 1e-12 * t)
                            nb++;
                        double tops[2];
                        const double complex *e[2][6];
                        double complex *o[2][6];
                        for (int s = 0; s < nb; s++) {
                            const int l = l0 + dir * s;
                            tops[s] = b[l];
                            for (int c = 0; c < 6; c++) {
                                e[s][c] = in[l][c];
                                o[s][c] = pass ? up[l][c] : dn[l][c];
                            }
                        }
                        mc_spec_modes_weights(&sm, 1, NM, t, (mc_spec_point)pt);
                        mc_spec_modes_pass(&k, &sm, 1, NM, pass, nb, tops, divide,
                                           (const double complex *const(*)[6])e, wgt, 2.0,
                                           (double complex *const(*)[6])o, 0);
                        n += nb;
                    }
                    if (!pass)
                        mc_spec_modes_turn(&k, &sm, 1, NM, p3, uz);
                }
                for (int m = 1; m < NM; m++) {
                    double scale = 0.0;
                    for (int l = 0; l < nz; l++)
                        for (int c = 0; c < 6; c++)
                            scale = fmax(scale, cabs(ref[m][l][c]));
                    for (int l = 0; l < nz; l++)
                        for (int c = 0; c < 6; c++) {
                            const double complex got = (dn[l][c][m] + up[l][c][m]) / (2.0 * wgt[m]);
                            worst = test_worst(worst, cabs(got - ref[m][l][c]) / scale);
                        }
                    worst = test_worst(worst, cabs(uz[m] - uzr[m]) / cabs(uzr[m]));
                    worst = test_worst(worst, cabs(p3[m] - p3r[m]) / cabs(p3r[m]));
                }
            }
    ck_assert_msg(worst <= TOL_DEPTH, "many modes vs one: %.3g", worst);
}
END_TEST

/* The real form of the frame matrices (mc_spec_coef r*): real, with every entry that is not zero
 * inside the patterns the products unroll (A: 17 entries, B: 9, the local term: 5). */
START_TEST(test_real_form_patterns)
{
    static const char PA[6][7] = {"111001", "101001", "111000", "000110", "000110", "110001"};
    static const char PB[6][7] = {"101001", "000000", "101001", "000000", "000000", "101001"};
    static const char PL[6][7] = {"110000", "110000", "000000", "000100", "000000", "000000"};
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    const double(*A[])[6] = {k.rAp, k.rAm, k.rAs}, (*B[])[6] = {k.rBp, k.rBm, k.rBs};
    int outside = 0;
    double worst = 0.0;
    for (int r = 0; r < 6; r++)
        for (int c = 0; c < 6; c++) {
            for (int j = 0; j < 3; j++) {
                outside += PA[r][c] == '0' && A[j][r][c] != 0.0;
                outside += PB[r][c] == '0' && B[j][r][c] != 0.0;
            }
            outside += PL[r][c] == '0' && k.rMinf[r][c] != 0.0;
            /* D^-1 M D is real: its entries are the complex ones times +-1 or +-i */
            const double complex d = (c >= 4 ? I : 1.0) / (r >= 4 ? I : 1.0);
            worst = fmax(worst, fabs(cimag(k.Ap[r][c] * d)) + fabs(cimag(k.Bp[r][c] * d)));
            worst = fmax(worst, fabs(creal(k.Ap[r][c] * d) - k.rAp[r][c]));
        }
    ck_assert_msg(outside == 0, "%d entries outside the unrolled patterns", outside);
    ck_assert_msg(worst == 0.0, "the real form is not real: %.3g", worst);
}
END_TEST

/* ---- boundary conditions, equilibrium, continuity --------------------------------------------- */

START_TEST(test_surface_free)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    const double layers[][2] = {{0.0, 0.5e-6}, {0.3e-6, 0.9e-6}, {1e-6, 4e-6}};
    double worst = 0.0;
    for (int m = 0; m < N_KS; m++)
        for (int l = 0; l < 3; l++) {
            double complex S[6][6], In[6][6];
            mc_spec_point_stress(&k, KS[m][0], KS[m][1], 0.0, layers[l][0], layers[l][1], S);
            /* the scale: the stress inside the layer */
            mc_spec_point_stress(&k, KS[m][0], KS[m][1], 0.5 * (layers[l][0] + layers[l][1]),
                                 layers[l][0], layers[l][1], In);
            for (int c = 0; c < 6; c++) {
                worst = test_worst(worst, cabs(S[2][c]) / cmax6(In));
                worst = test_worst(worst, cabs(S[4][c]) / cmax6(In));
                worst = test_worst(worst, cabs(S[5][c]) / cmax6(In));
            }
        }
    ck_assert_msg(worst <= TOL_IDENTITY, "surface traction %.3g", worst);
}
END_TEST

/* sigma_zj(z) for the lab rows zz (2), yz (4), xz (5) */
static void traction(const mc_spec_coef *k, const double *kv, double z, double t1, double t2,
                     double complex S[6][6])
{
    mc_spec_point_stress(k, kv[0], kv[1], z, t1, t2, S);
}

START_TEST(test_equilibrium)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    const double t1 = 0.4e-6, t2 = 1.1e-6;
    double worst = 0.0, worst_jump = 0.0;
    for (int m = 0; m < N_KS; m++) {
        const double *kv = KS[m], q = hypot(kv[0], kv[1]), d = FD_STEP / q;
        const double zs[] = {0.2e-6, 0.7e-6, 1.6e-6, 3e-6}; /* above, inside, below */
        for (int p = 0; p < 4; p++) {
            double complex S[6][6], Sp[6][6], Sm[6][6];
            traction(&k, kv, zs[p], t1, t2, S);
            traction(&k, kv, zs[p] + d, t1, t2, Sp);
            traction(&k, kv, zs[p] - d, t1, t2, Sm);
            const double scale = cmax6(S) * q + 1e-300;
            /* rows of sigma_j. : x (xx, xy, xz), y (xy, yy, yz), z (xz, yz, zz) */
            const int rx[3] = {0, 3, 5}, ry[3] = {3, 1, 4}, rz[3] = {5, 4, 2};
            for (int j = 0; j < 3; j++)
                for (int c = 0; c < 6; c++) {
                    const double complex div = I * kv[0] * S[rx[j]][c] + I * kv[1] * S[ry[j]][c] +
                                               (Sp[rz[j]][c] - Sm[rz[j]][c]) / (2.0 * d);
                    worst = test_worst(worst, cabs(div) / scale);
                }
        }
        /* traction continuity across both faces */
        const double faces[2] = {t1, t2};
        for (int f = 0; f < 2; f++) {
            double complex A[6][6], B[6][6];
            traction(&k, kv, faces[f] * (1.0 - 1e-15), t1, t2, A);
            traction(&k, kv, faces[f], t1, t2, B);
            for (int c = 0; c < 6; c++)
                for (int r = 2; r < 6; r += (r == 2 ? 2 : 1))
                    worst_jump = test_worst(worst_jump, cabs(A[r][c] - B[r][c]) / cmax6(B));
        }
    }
    ck_assert_msg(worst <= TOL_FD, "equilibrium %.3g", worst);
    ck_assert_msg(worst_jump <= 1e-9, "traction jump %.3g", worst_jump);
}
END_TEST

/* ---- the layer average against quadrature ----------------------------------------------------- */

START_TEST(test_average_quadrature)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(20);
    const double lay[][4] = {/* observation, source */
                             {0.0, 0.5e-6, 0.0, 0.5e-6},
                             {1e-6, 1.5e-6, 1e-6, 1.5e-6},
                             {1.5e-6, 2.5e-6, 0.25e-6, 0.75e-6},
                             {0.0, 0.25e-6, 0.5e-6, 2e-6}};
    double worst = 0.0;
    for (int m = 0; m < N_KS; m++)
        for (int l = 0; l < 4; l++) {
            double complex A[6][6], Q[6][6] = {{0}};
            mc_spec_pair(&k, KS[m][0], KS[m][1], lay[l][0], lay[l][1], lay[l][2], lay[l][3],
                         MC_SPEC_AVERAGE, A);
            for (size_t g = 0; g < 20; g++) {
                double x, w;
                gsl_integration_glfixed_point(lay[l][0], lay[l][1], g, &x, &w, gl);
                double complex S[6][6];
                mc_spec_point_stress(&k, KS[m][0], KS[m][1], x, lay[l][2], lay[l][3], S);
                for (int r = 0; r < 6; r++)
                    for (int c = 0; c < 6; c++)
                        Q[r][c] += w * S[r][c] / (lay[l][1] - lay[l][0]);
            }
            for (int r = 0; r < 6; r++)
                for (int c = 0; c < 6; c++)
                    worst = test_worst(worst, cabs(A[r][c] - Q[r][c]) / cmax6(Q));
        }
    gsl_integration_glfixed_table_free(gl);
    ck_assert_msg(worst <= TOL_QUAD, "layer average vs quadrature %.3g", worst);
}
END_TEST

/* ---- Betti ------------------------------------------------------------------------------------ */

START_TEST(test_betti)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    double b[16];
    const int nz = layering(1, b), n = 6 * nz;
    const double wgt[6] = {1, 1, 1, 2, 2, 2}; /* sigma : eps with the shear columns' both entries */
    double worst_herm = 0.0, lowest = 0.0, largest = 0.0;
    gsl_matrix_complex *H = gsl_matrix_complex_alloc((size_t)n, (size_t)n);
    gsl_vector *ev = gsl_vector_alloc((size_t)n);
    gsl_eigen_herm_workspace *ws = gsl_eigen_herm_alloc((size_t)n);
    for (int m = 0; m < N_KS; m++) {
        /* W = -sum_i h_i conj(eps_i) . wgt . sigma_i: H[(i, r), (j, c)] */
        for (int i = 0; i < nz; i++)
            for (int j = 0; j < nz; j++) {
                double complex S[6][6];
                mc_spec_pair(&k, KS[m][0], KS[m][1], b[i], b[i + 1], b[j], b[j + 1],
                             MC_SPEC_AVERAGE, S);
                for (int r = 0; r < 6; r++)
                    for (int c = 0; c < 6; c++) {
                        const double complex v = -(b[i + 1] - b[i]) / b[nz] * wgt[r] * S[r][c];
                        gsl_matrix_complex_set(H, (size_t)(6 * i + r), (size_t)(6 * j + c),
                                               gsl_complex_rect(creal(v), cimag(v)));
                    }
            }
        double big = 0.0;
        for (int a = 0; a < n; a++)
            for (int c = 0; c < n; c++) {
                const gsl_complex x = gsl_matrix_complex_get(H, (size_t)a, (size_t)c);
                big = fmax(big, hypot(GSL_REAL(x), GSL_IMAG(x)));
            }
        for (int a = 0; a < n; a++)
            for (int c = 0; c < n; c++) {
                const gsl_complex x = gsl_matrix_complex_get(H, (size_t)a, (size_t)c);
                const gsl_complex y = gsl_matrix_complex_get(H, (size_t)c, (size_t)a);
                worst_herm = test_worst(worst_herm, hypot(GSL_REAL(x) - GSL_REAL(y),
                                                          GSL_IMAG(x) + GSL_IMAG(y)) / big);
            }
        gsl_eigen_herm(H, ev, ws); /* destroys H */
        for (int a = 0; a < n; a++) {
            lowest = fmin(lowest, gsl_vector_get(ev, (size_t)a) / big);
            largest = fmax(largest, gsl_vector_get(ev, (size_t)a) / big);
        }
    }
    gsl_eigen_herm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_complex_free(H);
    ck_assert_msg(worst_herm <= TOL_IDENTITY, "averaged operator not Hermitian: %.3g", worst_herm);
    ck_assert_msg(lowest >= -TOL_IDENTITY, "energy-releasing mode: lowest %.3g", lowest);
    ck_assert(largest > 0.1);
}
END_TEST

/* ---- reciprocity: u_z against the Boussinesq stress of the pressure mode ---------------------- */

START_TEST(test_reciprocity)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(30);
    const double G = 0.5; /* stresses per 2G: the pressure response per unit force, 2G = 1 */
    double worst = 0.0;
    for (int m = 0; m < N_KS; m++) {
        const double kx = KS[m][0], ky = KS[m][1], q = hypot(kx, ky);
        const double t1 = 0.3e-6, t2 = 0.3e-6 + 2.0 / q;
        double complex D[6], R[6] = {0};
        mc_spec_pair_uz(&k, kx, ky, t1, t2, D);
        /* Betti: u_z(k) = int sigma^B(-k, z) : eps* dz, sigma^B the stress of a unit compressive
         * point force (its lateral transform: the pressure mode), here per unit stress 2G */
        for (size_t g = 0; g < 30; g++) {
            double z, w;
            gsl_integration_glfixed_point(t1, t2, g, &z, &w, gl);
            double complex f[6], lab[6];
            const double t = q * z;
            for (int r = 0; r < 6; r++)
                f[r] = exp(-t) * (k.T0[r] + k.T1[r] * t);
            mc_spec_from_frame(-kx / q, -ky / q, f, lab);
            const double wgt[6] = {1, 1, 1, 2, 2, 2};
            for (int c = 0; c < 6; c++)
                R[c] += w * wgt[c] * lab[c] / (2.0 * G);
        }
        double big = 0.0;
        for (int c = 0; c < 6; c++)
            big = fmax(big, cabs(R[c]));
        for (int c = 0; c < 6; c++)
            worst = test_worst(worst, cabs(D[c] - R[c]) / big);
    }
    gsl_integration_glfixed_table_free(gl);
    ck_assert_msg(worst <= TOL_QUAD, "u_z against Betti with the pressure mode %.3g", worst);
}
END_TEST

/* ---- an independent solution: plane strain, region by region -------------------------------- */

/* tools/check_spectral_ode.py: the half-space with a layer [0.4, 1.1] (q = 1) of eigenstrain
 * column c varying as e^{i x}, solved region by region (homogeneous solutions of the Navier
 * equations, the particular one of a constant eigenstress, continuity of u and of the traction at
 * the faces, a free surface, decay) with sympy, 15 digits: sigma_xx, sigma_yy, sigma_zz, sigma_xz
 * per 2G at z = 0.2 (above), 0.75 (inside), 1.6 (below). A derivation that shares nothing with
 * the residues of eigen_spectral.c. */
static const struct {
    int col;
    double z;
    double s[4][2];
} ODE[] = {
    {0, 0.20, {{0.618739026383293, 0}, {0.181920336899358, 0}, {-0.012337903385434, 0}, {0, -0.123266989750154}}},
    {0, 0.75, {{-0.7345578319464, 0}, {-0.248006619853985, 0}, {-0.092130900900217, 0}, {0, 0.005963147560597}}},
    {0, 1.60, {{0.247190763605042, 0}, {0.088510739943311, 0}, {0.047845036205996, 0}, {0, 0.099672863699523}}},
    {1, 0.20, {{0.242247575420018, 0}, {0.071043388215432, 0}, {-0.005436281368578, 0}, {0, -0.052798540178866}}},
    {1, 0.75, {{-0.250773594608419, 0}, {-1.38758295921175, 0}, {-0.041169602764073, 0}, {0, -0.017078528899867}}},
    {1, 1.60, {{0.06250939150737, 0}, {0.01751908384205, 0}, {-0.004112445367202, 0}, {0, 0.033310918437286}}},
    {2, 0.20, {{0.188752891683434, 0}, {0.054890957152083, 0}, {-0.005783034509825, 0}, {0, -0.052728144179399}}},
    {2, 0.75, {{-0.101354150081664, 0}, {-0.043936577518507, 0}, {-0.045101108313361, 0}, {0, -0.062891577226821}}},
    {2, 1.60, {{-0.038826125247143, 0}, {-0.030113793803143, 0}, {-0.061553187430001, 0}, {0, 0.011363531091429}}},
    {5, 0.20, {{0, -0.429986134699859}, {0, -0.127029379747275}, {0, 0.006554868875609}, {-0.070538845570756, 0}}},
    {5, 0.75, {{0, -0.021149544302641}, {0, 0.028623108290866}, {0, 0.116559905272194}, {-0.283489320071939, 0}}},
    {5, 1.60, {{0, 0.233274785774611}, {0, 0.143092421511058}, {0, 0.243699952595582}, {0.005212583410485, 0}}},
};

START_TEST(test_against_region_solution)
{
    mc_spec_coef k;
    mc_spec_coef_init(NU, &k);
    const int rows[4] = {0, 1, 2, 5};
    double worst = 0.0;
    for (size_t t = 0; t < sizeof ODE / sizeof ODE[0]; t++) {
        double complex S[6][6];
        mc_spec_point_stress(&k, 1.0, 0.0, ODE[t].z, 0.4, 1.1, S);
        for (int r = 0; r < 4; r++) {
            const double complex want = ODE[t].s[r][0] + I * ODE[t].s[r][1];
            worst = test_worst(worst, cabs(S[rows[r]][ODE[t].col] - want));
        }
    }
    ck_assert_msg(worst <= TOL_ODE, "against the region-by-region solution: %.3g", worst);
}
END_TEST

Suite *suite_eigen_spectral(void);
Suite *suite_eigen_spectral(void)
{
    Suite *s = suite_create("eigen_spectral");
    TCase *tc = tcase_create("kernel");
    tcase_add_test(tc, test_depth_vs_pairs);
    tcase_add_test(tc, test_streamed);
    tcase_add_test(tc, test_modes);
    tcase_add_test(tc, test_real_form_patterns);
    tcase_add_test(tc, test_against_region_solution);
    tcase_add_test(tc, test_surface_free);
    tcase_add_test(tc, test_equilibrium);
    tcase_add_test(tc, test_average_quadrature);
    tcase_add_test(tc, test_betti);
    tcase_add_test(tc, test_reciprocity);
    suite_add_tcase(s, tc);
    return s;
}
