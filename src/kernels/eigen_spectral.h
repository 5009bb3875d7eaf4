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
    double U[12], V[12];   /* the running sums of the pass */
    double W0[12], W1[12]; /* the down pass's totals sum e^{-t1} P0 e, sum e^{-t1} (t1 P0 + P1) e */
    double et;             /* e^{-q top} of the next layer of the down pass */
    double p3[2];          /* after mc_spec_turn: p3 per 2G (re, im) */
    double h, eh, p0, p1, ehalf, p0h2, p1h2, q0, q1; /* the last thickness' scalars (h < 0: none) */
    double q, cq, sq;      /* |k| and the frame's direction */
} mc_spec_state;

/* a fresh state for the mode (kx, ky) (1/m) */
void mc_spec_state_init(mc_spec_state *st, double kx, double ky);
/* top, bottom: the layer's depths, m; eps (lab), sig (lab, per 2G) written (not added) */
void mc_spec_down_layer(const mc_spec_coef *k, double top, double bottom, mc_spec_point pt,
                        const double complex eps[6], mc_spec_state *st, double complex sig[6]);
/* after the last layer of the down pass; returns u_z (m) of the mode */
double complex mc_spec_turn(const mc_spec_coef *k, mc_spec_state *st);
void mc_spec_up_layer(const mc_spec_coef *k, double top, double bottom, mc_spec_point pt,
                      const double complex eps[6], mc_spec_state *st, double complex sig[6]);

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
