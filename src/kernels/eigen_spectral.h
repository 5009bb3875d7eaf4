/* eigen_spectral.h - the residual stress and surface displacement of layers of eigenstrain in an
 * isotropic elastic half-space z >= 0, per LATERAL FOURIER MODE (docs/theory.md §8.10): pure
 * math, no state, no allocation.
 *
 * The spectral discretisation. A field of eigenstrain constant within layers [b_k, b_{k+1})
 * (b_0 = 0) and varying laterally as exp(i (kx x + ky y)) causes a residual stress of the same
 * lateral mode; per mode the depth problem has a closed form (Mura's infinite-space operator
 * transformed in depth by residues, the mirror layer, and the surface traction's correction).
 * In the frame of the wave vector (x' along k, q = |k|) the kernel depends on the scaled depth
 * t = q z alone: e^{-|s|} (A + B |s|) (s = t - t') plus the local term M_inf inside the layer,
 * the constant 6 x 6 matrices of mc_spec_coef. So a lateral mode costs O(nz) (running sums of
 * the exponentials, mc_spec_depth) instead of the stored kernel spectra of the cuboid operators.
 *
 * Conventions as kernels/eigen.h: z depth into the body, stresses tension positive, u_z > 0 into
 * the body, tensor strains, components xx, yy, zz, xy, yz, xz; the eigenstrain column of a shear
 * component carries both tensor entries; stresses per 2G (physical = 2 G x value).
 * Mode convention: a field f(x) = F e^{i k.x} has the coefficient F (the inverse DFT's sign).
 * Observation: MC_SPEC_CENTRE takes the stress at the layer's centre; MC_SPEC_AVERAGE averages
 * it over the layer's depth (a Galerkin form in depth: the operator's matrix is Hermitian with
 * the layers' thicknesses as weights, no energy-releasing mode). k = 0 is the laterally uniform
 * layer (kernels/eigen.h mc_eigen_stress1_layer: M_inf inside the layer, nothing outside). */
#ifndef MC_EIGEN_SPECTRAL_H
#define MC_EIGEN_SPECTRAL_H

#include <complex.h>

typedef enum { MC_SPEC_CENTRE = 0, MC_SPEC_AVERAGE = 1 } mc_spec_point;

/* The constant matrices of the k-frame kernel (per 2G; frame components x'x', y'y', zz, x'y',
 * y'z, x'z): K(s) = e^{-s} (Ap + Bp s) for s = t - t' > 0 (observation below the source),
 * e^{-|s|} (Am + Bm |s|) for s < 0, plus Minf where the observation lies in the source layer;
 * the stress of a unit compressive surface pressure e^{-t} (T0 + T1 t); u_z(0) of it uz0 / q
 * (in units of the pressure / 2G). */
typedef struct {
    int n;
    unsigned char r[36], c[36];
    double re[36], im[36];
} mc_spec_sparse; /* the nonzero entries of a frame matrix (for the running sums' products) */

typedef struct {
    double complex Ap[6][6], Bp[6][6], Am[6][6], Bm[6][6];
    double Minf[6][6];
    double complex T0[6], T1[6];
    double uz0;
    double nu;
    mc_spec_sparse sAp, sBp, sAm, sBm, sAs, sBs; /* sAs = Ap + Am, sBs = Bp + Bm (self terms) */
    /* The same matrices made real for the streamed step (theory §8.10): with the odd components
     * y'z, x'z multiplied by -i (e~ = D^-1 e, D = diag(1, 1, 1, 1, i, i)) every entry is real,
     * so a product is a real 6 x 6 one applied to the real and the imaginary parts alike. */
    double rAp[6][6], rBp[6][6], rAm[6][6], rBm[6][6], rAs[6][6], rBs[6][6], rMinf[6][6];
    double rT0[6], rT1[6];
} mc_spec_coef;

/* Fill k for Poisson ratio nu in (-1, 0.5). */
void mc_spec_coef_init(double nu, mc_spec_coef *k);

/* Rotate a lab-frame tensor (6 components) into the frame of (c, s) = (kx, ky) / q, and back. */
void mc_spec_to_frame(double c, double s, const double complex lab[6], double complex frame[6]);
void mc_spec_from_frame(double c, double s, const double complex frame[6], double complex lab[6]);

/* Reference, one pair of layers: the lab-frame response S[i][c] (stress i per unit eigenstrain
 * column c, per 2G) at the observation layer [u1, u2] to the source layer [t1, t2] (depths in m,
 * equal intervals for the self term, disjoint otherwise), mode (kx, ky) in 1/m. */
void mc_spec_pair(const mc_spec_coef *k, double kx, double ky, double u1, double u2, double t1,
                  double t2, mc_spec_point pt, double complex S[6][6]);

/* Reference: surface u_z (m) per unit eigenstrain column of the source layer [t1, t2]. */
void mc_spec_pair_uz(const mc_spec_coef *k, double kx, double ky, double t1, double t2,
                     double complex D[6]);

/* Reference: the stress (per 2G, lab frame) at the single depth z (m) of the source layer
 * [t1, t2] (a depth on a face plane: below it; for the checks of the boundary conditions and of
 * equilibrium). */
void mc_spec_point_stress(const mc_spec_coef *k, double kx, double ky, double z, double t1,
                          double t2, double complex S[6][6]);

/* One lateral mode, all layers at once in O(nz): eps[l][6] (lab frame) of the nz layers with
 * boundaries b[0] = 0 < b[1] < .. < b[nz] (m) -> sig[l][6] (per 2G, lab frame) and *uz (m; may
 * be NULL). sig may not alias eps. work: room for 12 nz complex values. Per mode ~130 nz
 * multiply-adds, a few exponentials per distinct layer thickness. */
void mc_spec_depth(const mc_spec_coef *k, double kx, double ky, int nz, const double *b,
                   mc_spec_point pt, const double complex (*eps)[6], double complex (*sig)[6],
                   double complex *uz, double complex *work);

/* One lateral mode, the surface displacement per unit eigenstrain column of every layer in O(nz):
 * u_z = sum_l sum_c D[l][c] eps[l][c], D[l] = mc_spec_pair_uz of layer l (m); at k = 0 the
 * laterally constrained layer. Here b[0] >= 0 may lie below the surface (a subset of layers). */
void mc_spec_uz_layers(const mc_spec_coef *k, double kx, double ky, int nz, const double *b,
                       double complex (*D)[6]);

/* ---- the depth step streamed layer by layer (the operator that keeps no layer spectra) ---------
 * Two passes over the layers per lateral mode, each layer's eigenstrain given when its turn comes:
 * down (top to bottom) mc_spec_down_layer returns the stress at layer l of the layers above it,
 * its own and the local term; then mc_spec_turn; then up (bottom to top) mc_spec_up_layer returns
 * the rest: the layers below, the mirror layers and the surface correction S3. Their sum is
 * mc_spec_depth's result to round-off. The state holds a mode's running sums (re/im pairs), the
 * totals of the down pass and the scalars of the last layer thickness. q > 0. */
typedef struct {
    double U[12], V[12];   /* the running sums of the pass (the real form of the frame, re/im) */
    double W0[12], W1[12]; /* down: the totals sum e^{-t1} P0 e, sum e^{-t1} (t1 P0 + P1) e;
                              after mc_spec_turn: the mirror layers' and S3's vectors P, Q (the
                              stress at a layer of top t is e^{-t} (al P + (al t + ga) Q)) */
    double et;             /* down: e^{-q top} of the next layer; up: e^{-q bottom} of it */
    double al, ga, sa, sb; /* the last thickness' weights: the sums seen from the layer
                              al A U + B (al V + ga U), its own sa As e + sb Bs e */
    double h, eh, p0, p1;  /* the last scaled thickness h (< 0: none), e^{-h} and the integrals */
    double q, cq, sq;      /* |k| and the frame's direction */
    double complex p3;     /* after mc_spec_turn: p3 per 2G */
} mc_spec_state;

/* a fresh state for the mode (kx, ky) (1/m) */
void mc_spec_state_init(mc_spec_state *st, double kx, double ky);
/* the same with q = |k| > 0 and the frame (cq, sq) = (kx, ky) / q given (the operator's tables) */
void mc_spec_state_init_q(mc_spec_state *st, double q, double cq, double sq);
/* top, bottom: the layer's depths, m; eps (lab), sig (lab, per 2G) written (not added) */
void mc_spec_down_layer(const mc_spec_coef *k, double top, double bottom, mc_spec_point pt,
                        const double complex eps[6], mc_spec_state *st, double complex sig[6]);
/* after the last layer of the down pass; returns u_z (m) of the mode */
double complex mc_spec_turn(const mc_spec_coef *k, mc_spec_state *st);
void mc_spec_up_layer(const mc_spec_coef *k, double top, double bottom, mc_spec_point pt,
                      const double complex eps[6], mc_spec_state *st, double complex sig[6]);

/* The scalars of a layer of scaled thickness h = q t for the streamed step (all 0 at h = 0):
 * w[MC_SPEC_AL], [GA] (the sums seen from the layer: al A U + B (al V + ga U)), [SA], [SB] (its
 * own: sa As + sb Bs), [H] = h, [EH] = e^{-h}, [P0], [P1] (the integrals of e^{-s}, s e^{-s}). */
enum { MC_SPEC_AL, MC_SPEC_GA, MC_SPEC_SA, MC_SPEC_SB, MC_SPEC_H, MC_SPEC_EH, MC_SPEC_P0,
       MC_SPEC_P1, MC_SPEC_WEIGHTS };
void mc_spec_weights_of(double h, mc_spec_point pt, double w[MC_SPEC_WEIGHTS]);

/* ---- the streamed step on many modes at once (eigen_spectral_modes.c) --------------------------
 * The states of n lateral modes as a structure of arrays: field f of mode i at st[f n + i], the
 * fields of mc_spec_state (U, V, W0 / P, W1 / Q, e^{-q z}); per mode q > 0 and the frame; the
 * scalars of one layer thickness per mode in wt (mc_spec_modes_weights). The caller owns every
 * array. Modes with q = 0 must stay out of the passes. */
enum { MC_SPEC_U = 0, MC_SPEC_V = 12, MC_SPEC_W0 = 18, MC_SPEC_W1 = 30, MC_SPEC_ET = 36,
       MC_SPEC_FIELDS = 37 };
/* V and W1 / Q keep only the real-form entries that the B products read or make (components
 * xx, zz and x'y', MC_SPEC_BLIVE; theory §8.10): their other entries never reach a result (V
 * and W1 enter only through B, whose columns are those three) and Q's are zero (B's rows, T1). */
enum { MC_SPEC_NBLIVE = 6 };
static const int MC_SPEC_BLIVE[MC_SPEC_NBLIVE] = {0, 1, 4, 5, 10, 11};
typedef struct {
    long n;
    double *st;                  /* MC_SPEC_FIELDS x n */
    const double *q, *cq, *sq;   /* n each */
    double *wt;                  /* MC_SPEC_WEIGHTS x n */
} mc_spec_modes;

/* every state fresh (as mc_spec_state_init) */
void mc_spec_modes_clear(mc_spec_modes *m);
/* the scalars of layer thickness t (m) for the modes i0 .. i1 - 1 */
void mc_spec_modes_weights(mc_spec_modes *m, long i0, long i1, double t, mc_spec_point pt);
/* One visit of the modes i0 .. i1 - 1 for nb layers of the thickness of wt, in the pass's order
 * (down: mc_spec_down_layer; up, after mc_spec_modes_turn: mc_spec_up_layer): layer s has its top
 * at tops[s] (m), its strain (lab) of mode i at e[s][c][i], and its stress (per 2G, lab) times
 * scale wgt[i] goes to out[s][c][i] (written, or added when add; out may be e). divide (up):
 * e^{-q top} by dividing the bottom's by e^{-q t}, which needs e^{-q depth} of the deepest mode
 * above underflow; 0 takes exp(). */
void mc_spec_modes_pass(const mc_spec_coef *k, mc_spec_modes *m, long i0, long i1, int up,
                        int nb, const double *tops, int divide,
                        const double complex *const (*e)[6], const double *wgt, double scale,
                        double complex *const (*out)[6], int add);
/* mc_spec_turn of the modes i0 .. i1 - 1: p3[i] (per 2G) and uz[i] (m), i from i0 */
void mc_spec_modes_turn(const mc_spec_coef *k, mc_spec_modes *m, long i0, long i1,
                        double complex *p3, double complex *uz);

/* The surface displacement alone, layer by layer in order from the top (the displacement
 * operator): a mode's state, then per layer D (lab, m per unit eigenstrain column). */
typedef struct {
    double q, cq, sq, et;          /* |k|, the frame, e^{-q top} of the next layer */
    double h, eh, p0, p1;          /* the last scaled thickness and its scalars */
} mc_spec_uzstate;

void mc_spec_uzstate_init(mc_spec_uzstate *u, double kx, double ky, double top);
void mc_spec_uz_next(const mc_spec_coef *k, mc_spec_uzstate *u, double top, double bottom,
                     double complex D[6]);

#endif
