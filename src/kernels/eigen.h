/* eigen.h - influence functions of a cuboid of uniform eigenstrain (plastic strain) in an
 * isotropic elastic half-space z >= 0: pure math, no state, no allocation.
 *
 * Conventions (theory.md §1, as kernel.h): z is depth into the body; stresses
 * tension positive; u_z > 0 into the body; tensor (not engineering) strains; component order
 * xx, yy, zz, xy, yz, xz (MC_SXX..MC_SXZ of kernel.h) for stresses AND eigenstrains.
 *
 * Eigenstrain columns. Every function returns the response per unit eigenstrain component c,
 * where the unit eigenstrain of a shear column c = xy (yz, xz) has BOTH tensor entries
 * eps*_xy = eps*_yx = 1 (etc.). The response to a general uniform eps* in the cuboid is therefore
 * the plain sum over c = 0..5 of (column c) * eps*_c with eps*_c the six tensor components; no
 * factor 2 is needed by the caller (it is inside the shear columns).
 *
 * Stress normalisation. Stress outputs are dimensionless: the physical stress (Pa) is
 * sigma_i = 2 G * sum_c S[i][c] eps*_c, G = E / (2 (1 + nu)) the shear modulus. Lengths may be in
 * any unit (m, or cell units): D scales with length, S is scale invariant.
 *
 * Validity. nu in (-1, 0.5). Stress field points may lie on a face plane of a cuboid: the face
 * belongs to the cuboid when it is a lower face (x = -hx, y = -hy, z = z1) and not when it is an
 * upper face (the half-open cuboid [-hx, hx) x [-hy, hy) x [z1, z2)); the traction sigma.n is the
 * same from both sides, the other components jump by the eigenstrain step. Stress field points
 * with two coordinates on face planes at once (an edge of the cuboid or of its mirror, or the
 * line extending one) are not allowed: the stress is log-singular on an edge and the corner terms
 * overflow on its extension (inf or NaN). The cell-centred lattice (field points at cell centres,
 * faces at half-cell offsets, so x and y are never on a face plane; top layer z1 = 0, also
 * observed at z = 0) never meets such a line.
 *
 * Accuracy. Values are corner sums of terms that do not decay with the distance d, while the
 * field decays like (h/d)^3 (h the box size): the absolute error stays at round-off of the
 * near-field values (S: ~3e-16; D: ~1e-15 h ln(d/h) ... 1e-12 h at d = 1000 h), the relative
 * error grows like eps (d/h)^3: measured 1e-12 at d = 10 h, 2e-9 at 100 h, 6e-6 at 1000 h.
 */
#ifndef MC_EIGEN_H
#define MC_EIGEN_H

/* Surface normal displacement per unit eigenstrain (Betti reciprocity; Jacq et al. 2002;
 * theory.md §8.1). Cuboid [x1,x2] x [y1,y2] x [z1,z2], coordinates relative to
 * the observation point X on the surface (SOURCE minus FIELD), 0 <= z1 < z2, x1 < x2, y1 < y2.
 * Output D[6] (length unit of the inputs) in the column convention above:
 *   u_z(X) = sum_c D[c] eps*_c,  D[diag] = D_ii,  D[xy] = D_xy + D_yx = 2 D_xy (etc.),
 *   D_ij = integral_box sigma^B_ij dV = lambda delta_ij tr J + G (J_ij + J_ji)  (per unit force),
 * sigma^B the Boussinesq stress of a unit compressive point force at X. D depends on nu and the
 * geometry only (not on E). Reflecting the box about X in x (in y) multiplies D[c] by -1 to the
 * number of x (y) indices of c: xx, yy, zz even, xy odd in x and in y, xz odd in x, yz odd in y.
 * X may lie on any face plane or edge line of the box (the kernel stays finite and continuous
 * there), but must not be one of its corners (possible only when z1 = 0). */
void mc_eigen_surface_uz(double x1, double x2, double y1, double y2, double z1, double z2,
                         double nu, double D[6]);

/* Residual stress of the cuboid |x'| <= hx, |y'| <= hy, z1 <= z' <= z2 (0 <= z1 < z2) in the
 * half-space WITHOUT the surface-normal-traction correction S3, i.e. S1 + S2 (Chiu 1977, 1978;
 * Mura 1987; theory.md §8.2):
 *   S1 = the cuboid in an infinite space (includes -C:eps* inside the cuboid),
 *   S2 = the mirror cuboid z' -> -z' carrying R eps* R, R = diag(1, 1, -1) (shear columns yz, xz
 *        change sign), which makes sigma_xz = sigma_yz = 0 and u_z = 0 on z = 0.
 * Field point (x, y, z), z >= 0, relative to the cuboid's lateral centre (FIELD minus SOURCE).
 * Output S[i][c]: stress component i (rows xx..xz) per unit eigenstrain component c (columns, see
 * above), divided by 2G. The full residual stress adds the half-space stress of the surface
 * pressure p3 = 2G * sum_c s[c] eps*_c from mc_eigen_surface_szz12 (mc_rect_stress_p per cell). */
void mc_eigen_stress12(double x, double y, double z, double hx, double hy, double z1, double z2,
                       double nu, double S[6][6]);

/* S1 alone: the same cuboid and conventions in an infinite space (no mirror), any z. */
void mc_eigen_stress1(double x, double y, double z, double hx, double hy, double z1, double z2,
                      double nu, double S[6][6]);

/* ---- corner sums, for tables of many cuboids (docs/theory.md §8.2) ------------------------------
 *
 * Every value of mc_eigen_stress1 is Chiu's formula applied to a signed sum, over the cuboid's 8
 * corners, of MC_EIGEN_NH corner functions of the offset a = field point - corner (sign +1 per
 * axis at the LOWER bound of the cuboid). Cuboids of one lattice seen from lattice points share
 * their corners: a table of n cells needs about n corner evaluations instead of 8 n (the
 * residual stress operator's tables, plastic/eigen_stress_op.c). */
#define MC_EIGEN_NH 21

/* The corner functions at the offset (ax, ay, az), not all 0 (h: MC_EIGEN_NH values). */
void mc_eigen_corner_h(double ax, double ay, double az, double h[MC_EIGEN_NH]);

/* S of mc_eigen_stress1 from the corner sum; inside: 1 when the field point is inside the
 * cuboid (half-open, lower faces included: then -C:eps* / (2G) is added). */
void mc_eigen_stress1_sum(const double sum[MC_EIGEN_NH], double nu, int inside, double S[6][6]);

/* sigma_zz of S1 + S2 on the surface z = 0 at (x, y) relative to the cuboid's lateral centre, per
 * unit eigenstrain component c, divided by 2G (the "p3" of theory.md §8.2: a tensile value is a
 * positive pushing pressure p3 = 2G sum_c s[c] eps*_c that the S3 term must carry). By the mirror
 * symmetry it equals 2 sigma_zz^S1(x, y, 0). Equal to row MC_SZZ of mc_eigen_stress12 at z = 0. */
void mc_eigen_surface_szz12(double x, double y, double hx, double hy, double z1, double z2,
                            double nu, double s[6]);

/* ---- the bar limit: a cuboid infinitely long along y (plane strain; docs/theory.md §8.5) -------
 *
 * A y-uniform eigenstrain field is a sum of bars |y'| < infinity; each function below is the limit
 * of its cuboid counterpart above as the y half-length tends to infinity, observed at any y (the
 * field does not depend on y), in closed form (the corner functions' y-corner difference expanded
 * for large length; no large number is formed, so no cancellation). The limit is finite: S1 and S2
 * decay like the inverse cube of the distance from a cuboid and u_z like its inverse square, so
 * the sum over a row of cuboids converges. Columns and rows odd in y (xy, yz) vanish (pairs that
 * couple an odd-in-y row with an even-in-y column), as does the yy row's total strain: the bar's
 * total eps_yy is 0 (plane strain; the eps*_yy column acts through the other components).
 * The surface displacement of a bar decays like 1/x^2 or faster (the field of an eigenstrain
 * bar is a force dipole): unlike the 2-D displacement of a line load it has no arbitrary
 * constant. Arguments as the cuboid functions with the y extent dropped. */
void mc_eigen_surface_uz_bar(double x1, double x2, double z1, double z2, double nu, double D[6]);
void mc_eigen_stress1_bar(double x, double z, double hx, double z1, double z2, double nu,
                          double S[6][6]);
void mc_eigen_stress12_bar(double x, double z, double hx, double z1, double z2, double nu,
                           double S[6][6]);
void mc_eigen_surface_szz12_bar(double x, double hx, double z1, double z2, double nu, double s[6]);

/* ---- the layer limit: a layer unbounded in x and y (docs/theory.md §8.6) -------------------------
 *
 * The sum of the cuboid kernels over every lateral position, i.e. the Fourier mode k = 0 of a doubly
 * periodic eigenstrain field, in closed form (eigen_layer.c): in-plane total strains 0 and
 * sigma_zz = sigma_xz = sigma_yz = 0. S1 of the layer z1 <= z' < z2 seen at depth z: the local stress
 * -C:eps* restricted to the in-plane rows inside the layer, 0 outside; S2 (the mirror layer lies
 * above the surface) and the surface traction p3 are 0. The surface displacement (a length, u_z > 0
 * into the body) per unit eigenstrain: -(z2 - z1) [eps*_zz + nu/(1 - nu)(eps*_xx + eps*_yy)]. Unlike
 * the sum over a growing finite patch (whose rim forces do not fade, theory.md §8.1), this is the
 * periodic field's own mean: the sum of D over a patch converges only conditionally. */
void mc_eigen_stress1_layer(double z, double z1, double z2, double nu, double S[6][6]);
void mc_eigen_surface_uz_layer(double z1, double z2, double nu, double D[6]);

#endif
