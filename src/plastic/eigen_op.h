/* eigen_op.h - the two eigenstrain operators of the semi-analytical elastic-plastic method
 * (Jacq et al. 2002; theory.md §9.1-§8.2), each with two backends behind one
 * interface, chosen by the mc_backend of operator/operator.h (what follows is the cuboid kernel,
 * v.kernel = MC_EIG_KERNEL_CUBOID; with MC_EIG_KERNEL_SPECTRAL both objects are the spectral
 * operator of plastic/eigen_spectral_op.h behind the same calls: a volume under the whole grid, the
 * loads folded through the stress module, p3 from the fft backend only (zeros from the direct
 * one), refused with more than one MPI process; theory.md §8.10):
 *   direct - plain O(N^2) summation over the kernel tables, written for clarity: the reference;
 *   fft    - DC-FFT (zero padding along both lateral axes, Liu, Wang & Liu 2000) over the SAME
 *            tables, so the two agree to round-off.
 *
 * The volume. Under a window of the surface grid (columns i0 <= i < i0 + nx, j0 <= j < j0 + ny;
 * the plastic zone is local, so only the columns under the contact plus a margin need cells) sit
 * nz layers of cuboids dx x dy x dz; layer k spans depths [k dz, (k+1) dz], its cell centres are
 * at z = (k + 1/2) dz. Each cuboid carries a uniform eigenstrain (plastic strain).
 * Volume fields are six arrays f[c] (c in xx, yy, zz, xy, yz, xz: MC_SXX..MC_SXZ of
 * kernels/kernel.h), each nz * ny * nx values in the volume layout f[c][(k * ny + j) * nx + i],
 * (i, j) window-local. Eigenstrains are tensor components (eps_xy = gamma_xy / 2),
 * dimensionless; the six arrays may be slices of one component-major block.
 *
 * Lateral axes (theory.md §8.5, §8.6). x free with y free, y periodic with ny = 1 (a line
 * contact: every cuboid is a bar infinitely long along y, the tables hold the bar limits of
 * kernels/eigen.h and the strip limit of Love's stresses), or y periodic with any ny (a strip: the
 * whole width of a line contact across x, a length of its face along y); or both axes periodic (a
 * doubly periodic patch; with ny = 1 a line grid periodic along x). x periodic alone is refused
 * (MC_ERR_LIMIT). Along a periodic axis the volume must span the whole period (i0 = 0, nx = grid
 * nx; MC_ERR_INPUT otherwise), the tables hold the periodic kernel (image sums whose smeared rest
 * makes the period's sum exactly the bar or layer limit: a laterally uniform field gets its closed
 * form, eigen.h mc_eigen_*_layer) and the fft backend transforms over the period, unpadded.
 *
 * Objects are planned once and applied many times; apply never allocates and cannot fail; one
 * thread at a time per object (it owns its workspace); create from one thread (FFTW's planner).
 *
 * Under mpirun (core/dist.h: mc_dist_active() when create is called, any number of ranks, one
 * included) the fft backends are distributed by lateral frequency (theory.md §8.4): the lateral
 * transforms are operator/dfft.h's (each rank its rows along x, a transpose, its columns kx =
 * k0 .. k0 + nk - 1 along y; batches of up to 8 layers of a component per transpose), each rank
 * builds and keeps the spectra of its own frequencies (V, P3, Love's, E, the displacement
 * kernel: their bytes divide by P, mc_eigen_*_bytes and the estimates say so), runs the depth
 * step on them, and the results are gathered whole on every rank: the interface is the same, and
 * create, apply and destroy are then COLLECTIVE (every rank calls them alike, as the replicated
 * plastic loop does). Every grid type, the line contact's bars included. P = 1, 2, 3 give the
 * same bits (same one-line plans, FFTW_ESTIMATE, sums per frequency in an order fixed by the
 * sizes); against the serial backends round-off apart (tests/mpi/mpi_eigen.c). The direct
 * backend stays replicated.
 *
 * Cost and memory (measured on the project's 2-core machine with one thread and window = grid;
 * mc_eigen_*_bytes gives the exact figure of an object):
 *   displacement, fft: 6 nz forward transforms and one inverse at (grid + window) padding;
 *     ~50-60 bytes per volume cell (6 nz real quadrant spectra; times ~(grid/window)^2 for a
 *     window smaller than the grid); 1.1-1.5 x that transform bound;
 *   stress, fft: 6 nz forward and 6 nz inverse transforms at 2x padding plus the depth step;
 *     ~640 bytes per volume cell: kernel spectra 21 (2 nz + 1) reals per lateral frequency of a
 *     quadrant (~350), the 6 nz layer spectra (~190), p3 and Love spectra (~100); ~3.5 x the bound
 *     of 6 nz r2c + c2r pairs at 64^2 x 8 .. 256^2 x 32 (the depth step is ~2/3 of it, in
 *     blocks of up to 64 kx, its 6 x 6 products register-blocked, an AVX2 copy on x86-64);
 *   direct: O((window cells)^2 nz^2) (stress) and O(grid cells x window cells x nz) operations,
 *     ~430 (stress) and ~50 (displacement) bytes per volume cell of tables in space.
 * Periodic axes are not padded: a strip 322 + 26, a doubly periodic volume 161 + 13 bytes per
 * volume cell at 256^2 x 32. What was measured and not kept (issue 20 item 2, theory.md §8.4):
 * fewer stored depth offsets where the kernel spectra decay does not apply at the accuracy the
 * backends promise (at every lateral frequency of a 64^2 x 16 volume the depth tail stays above
 * 1e-8 of the frequency's largest value: the tables end at the window, so their spectra do not
 * decay like exp(-q z)); streaming the padded y transform by blocks of kx (the layer spectra
 * kept transformed along x only) saved 96 of the 193 bytes of the layer spectra but cost 1.7 x
 * the stress apply's CPU time (branch i20-memory-stream).
 */
#ifndef MC_EIGEN_OP_H
#define MC_EIGEN_OP_H

#include <stddef.h>

#include "core/error.h"
#include "core/grid.h"
#include "operator/operator.h"

/* Where the residual stress of a cell is taken (theory.md §8.7). */
typedef enum {
    MC_EIG_CELL_AVERAGE = 0, /* the default: the infinite-space part averaged over the observation
                              * cell (3-point Gauss-Legendre per axis) within
                              * MC_EIG_AVERAGE_REACH cells of the source, the centre value
                              * beyond: Galerkin-like, no unstable checkerboard mode */
    MC_EIG_CELL_CENTRE = 1   /* every value at the cell centre (collocation): the operator has
                              * energy-releasing checkerboard modes (theory.md §8.5) */
} mc_eig_stress_points;

/* The key word of each evaluation ([plasticity] stress_points, summary.json). */
static inline const char *mc_eig_stress_points_name(mc_eig_stress_points s)
{
    return s == MC_EIG_CELL_CENTRE ? "centre" : "cell_average";
}

/* The lateral discretisation of the eigenstrain (theory.md §8.10). */
typedef enum {
    MC_EIG_KERNEL_CUBOID = 0,  /* the default: uniform cuboids, their kernels tabulated in space
                                * and stored as spectra (§8.1-§8.9) */
    MC_EIG_KERNEL_SPECTRAL = 1 /* sampled trigonometric fields, the kernel evaluated per lateral
                                * mode when used (plastic/eigen_spectral_op.h): no kernel stored;
                                * a volume under the whole grid, not distributed */
} mc_eig_kernel;

/* The key word of each kernel ([plasticity] kernel, summary.json). */
static inline const char *mc_eig_kernel_name(mc_eig_kernel k)
{
    return k == MC_EIG_KERNEL_SPECTRAL ? "spectral" : "cuboid";
}

/* Cells (of the larger lateral size) from the source within which MC_EIG_CELL_AVERAGE averages. */
#define MC_EIG_AVERAGE_REACH 3

/* The volume grid under a window of the surface grid.
 *
 * Graded layers (theory.md §8.8). With group != NULL, layer k is group[k] (odd, >= 1)
 * consecutive FINE layers of thickness dz: it spans depths [f_k dz, (f_k + group[k]) dz],
 * f_k = group[0] + .. + group[k - 1], carries one eigenstrain, and its stress is evaluated at its
 * centre, the centre of its middle fine layer, z = (f_k + (group[k] - 1) / 2 + 1/2) dz. The
 * operators work on the fine lattice by superposition (a thick cuboid is the sum of its fine
 * sub-cuboids; the source repeats over them, the output is read at the middle one), so their
 * kernel tables are those of the uniform fine volume of sum(group) layers while the lateral
 * transforms, the fields and the return map scale with nz; the fft backend's depth step runs on
 * the fine lattice or, when it costs less, sums over the coarse layers' boundaries (prefix sums
 * of the fine tables: (nz + 1) nz terms per lateral frequency). group == NULL (or every entry 1)
 * is the uniform volume, with the same bits. */
typedef struct {
    int i0, j0; /* first column of the window along x and y (surface grid indices, >= 0) */
    int nx, ny; /* columns of the window along x and y (>= 1, i0 + nx <= grid nx, ...) */
    int nz;     /* layers (>= 1) */
    double dz;  /* (fine) layer thickness, m (finite, > 0) */
    mc_eig_stress_points stress_points; /* the residual stress operator's evaluation (default 0) */
    const int *group; /* NULL: uniform; else nz odd counts >= 1 of fine layers per layer (graded).
                       * Borrowed: the operators copy it; whoever holds a volume keeps it alive */
    mc_eig_kernel kernel; /* the lateral discretisation (default 0: cuboids) */
} mc_eigen_volume;

/* A sparse addend of a volume field: the plastic loop's strain increment, which is not zero on
 * the yielding cells alone. n entries, their volume indices cell[k] ascending, component c
 * (xx .. xz) of entry k at val[stride * k + c] (stride >= 6). */
typedef struct {
    long n;
    const long *cell;
    const double *val;
    int stride;
} mc_eigen_sparse;

/* The entries of s whose cells lie in first <= cell < last: k0 .. k1 - 1 (binary search). */
void mc_eigen_sparse_range(const mc_eigen_sparse *s, long first, long last, long *k0, long *k1);

/* The volume of nz layers of thickness dz under the whole surface grid g. */
static inline mc_eigen_volume mc_eigen_volume_full(const mc_grid *g, int nz, double dz)
{
    mc_eigen_volume v = {0, 0, g->nx, g->ny, nz, dz, MC_EIG_CELL_AVERAGE, NULL,
                         MC_EIG_KERNEL_CUBOID};
    return v;
}

/* Fine layers of layer k, and the first fine layer of layer k (0 <= k <= nz: k = nz gives the
 * fine layers of the whole volume). */
static inline int mc_eigen_layer_count(const mc_eigen_volume *v, int k)
{
    return v->group ? v->group[k] : 1;
}
static inline int mc_eigen_layer_first(const mc_eigen_volume *v, int k)
{
    if (!v->group)
        return k;
    int f = 0;
    for (int q = 0; q < k; q++)
        f += v->group[q];
    return f;
}
/* The fine layer at the centre of layer k (its evaluation point). */
static inline int mc_eigen_layer_centre(const mc_eigen_volume *v, int k)
{
    return mc_eigen_layer_first(v, k) + (mc_eigen_layer_count(v, k) - 1) / 2;
}
/* Depth of the centre of layer k and its thickness, m ((k + 1/2) dz and dz when uniform). */
static inline double mc_eigen_layer_depth(const mc_eigen_volume *v, int k)
{
    return (mc_eigen_layer_centre(v, k) + 0.5) * v->dz;
}
static inline double mc_eigen_layer_thickness(const mc_eigen_volume *v, int k)
{
    return mc_eigen_layer_count(v, k) * v->dz;
}
/* Depth of the bottom of the volume, m. */
static inline double mc_eigen_volume_depth(const mc_eigen_volume *v)
{
    return mc_eigen_layer_first(v, v->nz) * v->dz;
}

/* 1 when a and b are the same volume (fields, and the layering by value). */
int mc_eigen_volume_equal(const mc_eigen_volume *a, const mc_eigen_volume *b);

/* Graded layering (theory.md §8.8): fine layers of dz down to the depth fine_depth (m, >= 0),
 * below it each layer as thick as the largest odd number of fine layers not above
 * ratio x (the depth of its top), at least 1, and never thinner than the layer above; layers
 * until the volume reaches depth (m), the last one cut to end within one dz of
 * ceil(depth / dz) dz (the fine layers of the uniform volume: the depth step costs by them). Writes the counts into group (room for max entries) and
 * returns the number of layers nz; 0 when max is too small. ratio in (0, 1]. */
int mc_eigen_grade(double dz, double depth, double fine_depth, double ratio, int *group, int max);

/* ---- eigenstrain -> surface normal residual displacement (theory.md §8.1) --------------------- */

typedef struct mc_eigen_disp mc_eigen_disp;

/* Plan u_z = D * eps for surface grid g, volume v and Poisson ratio nu in (-1, 0.5), backend b.
 * Betti reciprocity with the Boussinesq point force (Jacq et al. 2002):
 *   u_z(X) = sum over cuboids s and columns c of D_c(s - X) eps_c(s),
 * D_c = mc_eigen_surface_uz of kernels/eigen.h (a length: u_z is independent of E). The tables
 * hold D at every offset (field minus source) in cells, for each source layer and column.
 * *out is NULL on failure. MC_OK, MC_ERR_INPUT (bad grid, volume, nu or backend; a volume not
 * spanning a periodic axis), MC_ERR_LIMIT (x periodic alone, or sizes beyond int), MC_ERR_NOMEM (an allocation, or FFTW could not plan),
 * MC_ERR_INTERNAL (FFTW threads). */
int mc_eigen_disp_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                         mc_eigen_disp **out, mc_error *err);

/* uz (grid ny * nx, m, positive INTO the body: a dent is > 0) on the WHOLE surface grid, from the
 * eigenstrain eps (layout above; dimensionless). The residual displacement of a finite plastic
 * zone reaches beyond its window, so every surface cell gets its value. */
void mc_eigen_disp_apply(mc_eigen_disp *op, const double *const eps[6], double *uz);

/* Bytes held by the object (tables, spectra, workspaces). */
size_t mc_eigen_disp_bytes(const mc_eigen_disp *op);

/* What mc_eigen_disp_bytes would return for the object mc_eigen_disp_create(g, v, nu, b) would
 * build, from the sizes alone (nothing allocated or planned; the memory guard); 0 for a volume or
 * grid that create refuses. */
/* (under mpirun: rank 0's share of the distributed operator, see the header) */
size_t mc_eigen_disp_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b);
/* ... for a given arrangement (ranks as mc_eigen_stress_estimate_ranks). */
size_t mc_eigen_disp_estimate_ranks(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                    int ranks);

void mc_eigen_disp_destroy(mc_eigen_disp **op); /* frees and sets *op = NULL; NULL-safe */

/* ---- eigenstrain -> residual stress at the cuboid centres (theory.md §8.2) -------------------- */

typedef struct mc_eigen_stress mc_eigen_stress;

/* Plan sigma_r = S * eps at every cuboid centre of volume v (grid g, nu in (-1, 0.5), backend b):
 *   sigma_r = S1 + S2 + S3   (Chiu 1977, 1978; Jacq et al. 2002)
 *   S1: each cuboid in an infinite space (kernels/eigen.h mc_eigen_stress1);
 *   S2: its mirror cuboid z -> -z carrying R eps R, R = diag(1, 1, -1) (columns yz, xz change
 *       sign); S1 + S2 has zero shear traction and zero u_z on z = 0;
 *   S3: the half-space stress (Love's rectangles, mc_rect_stress_p) of the surface pressure
 *       p3 = sigma_zz^(1+2)(x, y, 0) (mc_eigen_surface_szz12), which cancels the normal traction.
 * S1 depends on the depth offset z_obs - z_src, S2 is S1 seen from the mirror layer: both are
 * the infinite-space kernel at depth offsets (k - k') dz and (k + k' + 1) dz, so one family of
 * tables at offsets m dz, m = 0 .. 2 nz - 1, serves every (observation, source) layer pair
 * (negative offsets by the kernel's parity in z). The 6 x 6 kernel is symmetric up to the shear
 * weights (sigma_c per eps_i = (w_i / w_c) sigma_i per eps_c, w = 1, 1, 1, 2, 2, 2: the major
 * symmetry of C:Gamma:C), so 21 of the 36 tables are kept.
 * p3 is formed on the window's columns only (the volume's surface footprint): outside the window
 * the surface is left with the small traction of S1 + S2 there, which decays like the cube of
 * the inverse distance from the plastic cells; give the volume a margin around the plastic zone.
 * Returns as mc_eigen_disp_create. */
int mc_eigen_stress_create(const mc_grid *g, const mc_eigen_volume *v, double nu, mc_backend b,
                           mc_eigen_stress **out, mc_error *err);

/* sig[c] (c in xx .. xz, each nz * ny * nx, volume layout above, Pa, tension positive): the
 * residual stress at the cuboid centres from the eigenstrain eps, for shear modulus G > 0 (Pa).
 * Inside a cuboid the stress includes -C:eps* of the cuboid itself. */
void mc_eigen_stress_apply(mc_eigen_stress *op, const double *const eps[6], double G,
                           double *const sig[6]);

/* Surface loads folded into the operator (theory.md §8.9). After mc_eigen_stress_loads(op,
 * loads), loads = MC_TRACTION_P, optionally | MC_TRACTION_QX (stress/stress.h),
 * mc_eigen_stress_apply_loaded adds to the residual stress the elastic stresses of those surface
 * tractions at the cuboid centres: the stress module's patch kernel at the layers' centres
 * (mc_eigen_layer_depth), i.e. what mc_stress_field of such a plan gives, to round-off, through
 * the operator's own inverse transforms (one set for both fields instead of two). The plastic
 * loop's elastic stresses go this way. Only for a volume under the whole grid (the loads live on
 * the grid, the transforms on the volume's window): MC_ERR_INPUT for a smaller window, another
 * load, or loads already folded; MC_ERR_NOMEM. Collective under mpirun. The tables cost 6 nz
 * quadrants per load, as Love's (mc_eigen_stress_parts part 3 counts them). */
int mc_eigen_stress_loads(mc_eigen_stress *op, int loads, mc_error *err);

/* The loads folded into op (0: none). */
int mc_eigen_stress_loads_of(const mc_eigen_stress *op);

/* sig = S eps + the elastic stresses of the folded loads: eps NULL is a zero eigenstrain (the
 * loads' stresses alone: no forward transform, p3 = 0); p and qx (grid ny * nx, Pa; NULL counts as
 * zero, qx only when folded) are the pressure (positive pushing) and the shear traction along x, as
 * mc_stress_field takes them. Collective under mpirun. */
void mc_eigen_stress_apply_loaded(mc_eigen_stress *op, const double *const eps[6], double G,
                                  const double *p, const double *qx, double *const sig[6]);

/* A field given as a dense part and a sparse addend (mc_eigen_sparse; inc NULL or without
 * entries: eps alone): the operators read eps + inc value by value as they read their input, so
 * the results are the bits of applying the summed field and the caller holds no volume array of
 * the sum (the plastic loop's eps_p + d eps_p, theory.md §9.9). Only the spectral kernel's
 * objects on one process take it (mc_eigen_stress_takes_sum, mc_eigen_disp_takes_sum: 1); the
 * calls return MC_ERR_LIMIT and write nothing for the others. As mc_eigen_stress_apply_loaded and
 * mc_eigen_disp_apply otherwise. */
int mc_eigen_stress_takes_sum(const mc_eigen_stress *op);
int mc_eigen_stress_apply_sum(mc_eigen_stress *op, const double *const eps[6],
                              const mc_eigen_sparse *inc, double G, const double *p,
                              const double *qx, double *const sig[6]);
int mc_eigen_disp_takes_sum(const mc_eigen_disp *op);
int mc_eigen_disp_apply_sum(mc_eigen_disp *op, const double *const eps[6],
                            const mc_eigen_sparse *inc, double *uz);

/* The sum's apply in two halves around the contact solve (the spectral kernel's objects; others
 * MC_ERR_LIMIT): begin_sum writes u_z (grid, m) of eps + inc and a part of its stresses into sig,
 * end_sum adds the rest and the folded loads' stresses of p and qx, so that sig is then what
 * mc_eigen_stress_apply_sum gives, with the same bits. The joint iteration takes u_z from the
 * stress operator this way instead of a displacement apply (theory §9.9). eps and inc must not
 * change in between, nor op be applied otherwise. */
int mc_eigen_stress_begin_sum(mc_eigen_stress *op, const double *const eps[6],
                              const mc_eigen_sparse *inc, double G, double *const sig[6],
                              double *uz);
int mc_eigen_stress_end_sum(mc_eigen_stress *op, const double *const eps[6],
                            const mc_eigen_sparse *inc, double G, const double *p,
                            const double *qx, double *const sig[6]);

/* The forward transforms of one strain field shared by both operators (theory.md §8.9): the
 * joint iteration needs u_z and the stresses of the same eps in one evaluation, with the contact
 * solve between them. mc_eigen_stress_forward(op, eps) transforms eps into the stress operator's
 * layer spectra (the direct backend only remembers eps); mc_eigen_disp_apply_shared makes that
 * forward and takes u_z from the spectra as they are made, and mc_eigen_stress_apply_forwarded(op, G, p, qx, sig) finishes the
 * stress of that eps (as mc_eigen_stress_apply_loaded, without its forward transforms). eps must
 * not change in between; any other apply of op forgets the forward (mc_eigen_stress_forwarded
 * then 0, and apply_forwarded gives the loads' stresses alone). Collective under mpirun. */
void mc_eigen_stress_forward(mc_eigen_stress *op, const double *const eps[6]);
int mc_eigen_stress_forwarded(const mc_eigen_stress *op);

/* Distributed operators (the fft backend under mpirun, theory.md §8.4): on = 1 makes the applies
 * that follow write the stresses on this rank's rows of the window alone (*r0 .. *r0 + *nr - 1
 * of v.ny, in every layer: the rows its forward transforms read), without gathering them, and
 * leave the other rows of sig untouched; on = 0 (the default) gathers them whole on every rank.
 * Returns 1 when the operator is distributed; 0 when it is not (nothing is set; *r0 = 0,
 * *nr = v.ny). p3 (mc_eigen_stress_p3) stays whole. */
int mc_eigen_stress_keep_rows(mc_eigen_stress *op, int on, int *r0, int *nr);
void mc_eigen_stress_apply_forwarded(mc_eigen_stress *op, double G, const double *p,
                                     const double *qx, double *const sig[6]);

/* The spectral kernel's displacement object dop takes the workspaces of its stress object sop
 * (eigen_spectral_op.h mc_eigen_spectral_borrow: 8 bytes per volume cell at 256^2 x 32 free):
 * 1 when done (dop and sop are then applied one at a time, and sop destroyed after dop; the
 * plastic operators do both), 0 for objects that do not fit (other kernels, the direct backend,
 * another volume). */
int mc_eigen_disp_borrow(mc_eigen_disp *dop, mc_eigen_stress *sop);

/* 1 when dop can read the layer spectra of sop's forward (fft backends of one volume under the
 * whole grid, the same transform sizes and, distributed, the same columns). */
int mc_eigen_disp_shares(const mc_eigen_disp *dop, const mc_eigen_stress *sop);

/* u_z of eps as mc_eigen_disp_apply, and mc_eigen_stress_forward(sop, eps): when dop shares
 * sop's transforms, u_z is summed from sop's layer spectra as sop's forward makes them (no
 * transform of its own; the same values to round-off), else by dop's own transforms. Either way
 * mc_eigen_stress_apply_forwarded(sop, ...) may follow. Collective under mpirun. */
void mc_eigen_disp_apply_shared(mc_eigen_disp *dop, mc_eigen_stress *sop,
                                const double *const eps[6], double *uz);

/* Bytes that mc_eigen_stress_loads(op, loads) would add to the operator mc_eigen_stress_create(g,
 * v, b) builds, ranks as mc_eigen_stress_estimate_ranks (the memory guard). */
size_t mc_eigen_stress_loads_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                      int ranks, int loads);

/* p3 (Pa, window ny * nx) of the last mc_eigen_stress_apply: the surface normal traction of
 * S1 + S2 that S3 cancels (a tensile sigma_zz is a positive pushing pressure); zeros before the
 * first apply. Exposed for checks (the Boussinesq displacement of p3 is the residual u_z). */
void mc_eigen_stress_p3(const mc_eigen_stress *op, double *p3);

/* Bytes held by the object (tables, spectra, workspaces). */
size_t mc_eigen_stress_bytes(const mc_eigen_stress *op);

/* The bytes of mc_eigen_stress_bytes by part (bench plastic, the memory guard):
 *   [0] the S1 + S2 kernel: fft, its spectra (21 reals per depth frequency and lateral frequency
 *       of a quadrant); direct, its tables at 2 nz depth offsets;
 *   [1] fft: the 6 nz layer spectra and the p3 spectrum (0 direct);
 *   [2] the p3 kernel (6 nz quadrants: spectra or tables);
 *   [3] Love's stresses per unit pressure (6 nz quadrants);
 *   [4] the rest: workspaces, p3 on the window, the object. */
#define MC_EIGEN_STRESS_PARTS 5
void mc_eigen_stress_parts(const mc_eigen_stress *op, size_t parts[MC_EIGEN_STRESS_PARTS]);

/* The parts above (their sum: what mc_eigen_stress_bytes would return) of the object that
 * mc_eigen_stress_create(g, v, nu, b) would build, computed from the sizes alone (nothing is
 * allocated, no FFTW planning; for the memory guard). All zero for a volume or grid that create
 * refuses. */
void mc_eigen_stress_estimate(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                              size_t parts[MC_EIGEN_STRESS_PARTS]);

/* The same for a given arrangement: ranks = 0 the serial operator, ranks >= 1 rank 0's share of
 * the operator distributed over that many ranks (it holds the most frequencies).
 * mc_eigen_stress_estimate is this with the run's: mc_dist_active() ? mc_dist_size() : 0. */
void mc_eigen_stress_estimate_ranks(const mc_grid *g, const mc_eigen_volume *v, mc_backend b,
                                    int ranks, size_t parts[MC_EIGEN_STRESS_PARTS]);

void mc_eigen_stress_destroy(mc_eigen_stress **op); /* frees and sets *op = NULL; NULL-safe */

#endif
