/* stress.h - subsurface stress on depth layers from surface loads (theory.md §5, §5.7).
 *
 * For each depth z_k the six stress components (tension positive, order of kernel.h: xx, yy, zz,
 * xy, yz, xz) at the cell centres (x_i, y_j, z_k) are convolutions of the surface loads with
 * influence kernels:
 *     sigma_c(z_k) = K_c^p(z_k) (*) p + K_c^qx(z_k) (*) q_x + K_c^qy(z_k) (*) q_y
 * Kernels (per unit load on one cell, offsets FIELD minus SOURCE, theory.md §3.1):
 *   patch - uniform load on the dx x dy rectangle (Love 1929; theory.md §5.3, §5.4): exact for
 *           piecewise-constant loads at every depth, including z = 0. Tables come from the corner
 *           functions of kernel.h evaluated once per corner of the offset lattice and differenced
 *           (theory.md §5.5);
 *   point - a concentrated force p dx dy at the cell centre (Boussinesq / Cerruti, 3.1, 3.2):
 *           the "minimum evaluation depth" artefact of 3.6, kept for that comparison; z > 0 only.
 * Backends as in operator.h (the direct backend's O(N^2) sums or DC-FFT over the same tables, so
 * they agree to round-off); one forward transform per load field is shared by all components and
 * layers.
 * Three speed-ups give the same results to round-off and can be switched off (mc_stress_tuning):
 * on free axes the fft backend builds one quadrant of each table and transforms it by DCT-I /
 * DST-I (the kernels' parities, stress_internal.h); loads on few cells are summed over those
 * cells only (the sparse sum) when a cost model says it is cheaper; and the pipeline stage
 * (pipeline/stage_stress.h) computes a compact load's layers only on windows around it (zeros
 * elsewhere) and takes the depth range from the contact when asked.
 * Stresses are those of the body below the surface (z >= 0) with its own Poisson ratio.
 *
 * Periodic axes (period L = n d) hold the periodic Green's function, the sum over all images:
 *   - images |k| <= M are summed exactly; the rest is the same load smeared uniformly over the
 *     strip beyond H = (M + 1/2) L (density 2b/L for y, 2a/L for x; out to a far edge of
 *     MC_STRESS_FAR_EDGE * max(Lx, Ly), where the in-plane stresses of the strip have converged to
 *     ~1e-12), corrected by the midpoint Euler-Maclaurin terms in the second and fourth derivatives
 *     along the axis (finite differences of the corner functions at H, with the pixel's own width
 *     folded in). Per axis and depth M is chosen from n and z/L so that the table changes by
 *     <= 5e-10 of its largest entry from M to 2M (M ~ 2..24, see stress_table.c); n = 1 is the
 *     exact strip (plane strain);
 *   - at depths z >= MC_STRESS_SMEAR_DEPTH * L the whole image sum along that axis is the smeared
 *     load (Poisson summation: the first omitted mode is ~(2 pi z/L) e^(-2 pi z/L); measured
 *     <= 3e-10 of the largest table entry at 4.5 L, 4e-9 at 4 L);
 *   - both axes periodic: the two 1-D rules multiply (images x images, images x strips, strips x
 *     strips). The mean (Fourier mode 0) of each table is then set exactly: sigma_zz, sigma_xz,
 *     sigma_yz keep the equilibrium values (mean sigma_zz = -mean p, mean sigma_xz = -mean q_x,
 *     mean sigma_yz = -mean q_y at every depth), while the in-plane xx, yy, xy have mean 0: their
 *     image sum converges only conditionally, and the in-plane mean stress of a periodic cell is
 *     set by the macro contact, not by the cell (theory.md §3.6). Add it outside if needed.
 */
#ifndef MC_STRESS_H
#define MC_STRESS_H

#include "core/error.h"
#include "core/grid.h"
#include "operator/operator.h"

typedef enum { MC_STRESS_PATCH, MC_STRESS_POINT } mc_stress_kernel;
enum { MC_TRACTION_P = 1, MC_TRACTION_QX = 2, MC_TRACTION_QY = 4 };

/* Far edge of the smeared strips of periodic axes, in units of max(Lx, Ly). */
#define MC_STRESS_FAR_EDGE 1e12
/* A plan on a grid with a periodic axis keeps the kernel spectra of its layers once built, up to
 * this many bytes (stress.c). */
#define MC_STRESS_CACHE_BYTES ((size_t)256 << 20)

/* Bytes of the kernel spectra a plan on grid g keeps per layer and load (its cache, stress.c): six
 * arrays, real quadrants of the symmetric engine on free axes (fft), the compact parity form of
 * the general engine's spectra with a periodic axis on one process (a quarter of the half
 * spectrum), the half spectrum itself under mpirun. */
double mc_stress_cache_layer_bytes(const mc_grid *g);

/* Depth (in periods of an axis) from which the image sum along that axis is the smeared load. */
#define MC_STRESS_SMEAR_DEPTH 4.5

/* ---- kernel tables of one depth (the lower layer; used by the operator below) -------------- */

typedef struct mc_stress_tables mc_stress_tables;

/* Plan the table builder for grid g and table sizes tx, ty (as from mc_conv_table_dims: a free
 * axis >= 2n - 1, a periodic axis = n), kernel, Poisson ratio nu in (-1, 0.5]. images: images per
 * side M on periodic axes at every depth above the smearing depth (values below 2 are raised to
 * 2), or <= 0 for the automatic depth-dependent choice (tests use it to measure the tail's
 * convergence). Workspaces for mc_threads_count() threads are allocated here.
 * *out is NULL on failure. MC_OK, MC_ERR_INPUT (bad grid, sizes, kernel or nu), MC_ERR_NOMEM. */
int mc_stress_tables_create(const mc_grid *g, int tx, int ty, mc_stress_kernel kernel, double nu,
                            int images, mc_stress_tables **out, mc_error *err);

/* The six tables k[c] (c in kernel.h order, each ty*tx, caller-owned, wrap-around layout of
 * operator.h with padding slots 0) of load (one of MC_TRACTION_P, MC_TRACTION_QX, MC_TRACTION_QY)
 * at depth z (m): stress per unit load on one cell. Never allocates; OpenMP over table rows. MC_OK, or
 * MC_ERR_INPUT for a bad load, z < 0 or not finite, or z = 0 with the point kernel. */
int mc_stress_tables_build(mc_stress_tables *tb, int load, double z, double *const k[6],
                           mc_error *err);

/* Parity of table c (kernel.h order) of load (MC_TRACTION_P, _QX or _QY): bit 0 set when the
 * kernel is odd in the x offset, bit 1 when odd in the y offset (kernel.h, theory.md §5.3, §5.4); -1 for a
 * bad load or component. */
int mc_stress_parity(int load, int c);

/* The quadrant of the six tables of load at depth z, for a grid whose axes are both free:
 * q[c][j*qx + i] = the table entry at the offset (i, j) cells, 0 <= i < qx, 0 <= j < qy; 0 for
 * offsets i >= nx or j >= ny; along an axis where table c is odd the entry at offset 0 is exactly 0.
 * Every other entry is bit for bit that of mc_stress_tables_build (the same corner differences in
 * the same order): the other quadrants follow by parity, so this costs (nx+1)(ny+1) corner
 * evaluations instead of (2nx)(2ny). Never allocates; OpenMP over rows. MC_OK, or MC_ERR_INPUT
 * (periodic axis, qx or qy < 1, bad load or depth as mc_stress_tables_build). */
int mc_stress_tables_quadrant(mc_stress_tables *tb, int load, double z, int qx, int qy,
                              double *const q[6], mc_error *err);

/* Images per side summed exactly along axis 0 (x) or 1 (y) at depth z: 0 on a free axis, -1 when
 * the whole periodic sum is smeared (n = 1, or z >= MC_STRESS_SMEAR_DEPTH L). */
int mc_stress_tables_images(const mc_stress_tables *tb, int axis, double z);

void mc_stress_tables_destroy(mc_stress_tables **tb); /* frees, sets *tb = NULL; NULL-safe */

/* ---- the stress operator, planned once for a grid and a set of layers: mc_stress_plan -------- */

typedef struct {
    mc_stress_kernel kernel; /* MC_STRESS_PATCH (default) or MC_STRESS_POINT */
    double nu;               /* Poisson's ratio of the stressed body, in (-1, 0.5] */
    int nlayers;             /* >= 1 */
    const double *depths;    /* nlayers finite depths z >= 0, m (copied); point kernel: z > 0 */
    mc_backend backend;
    int loads;               /* the load fields that will be given: MC_TRACTION_P | _QX | _QY */
    int repeated;            /* 1: the plan will compute its layers many times (the plastic
                              * loop): keep the kernel spectra of every layer once built when
                              * they fit MC_STRESS_CACHE_BYTES (stress.c says what it saves),
                              * under mpirun those of the rank's own block of layers (the ones
                              * mc_stress_field_split computes there); 0: only where their
                              * tables are costly (a periodic axis), every layer */
} mc_stress_options;

typedef struct mc_stress_plan mc_stress_plan;

/* A speed-up that can be switched off (to measure what it saves, or to compare against). */
typedef enum { MC_STRESS_AUTO = 0, MC_STRESS_OFF = 1, MC_STRESS_ON = 2 } mc_stress_switch;

/* The speed-ups of the operator and the stage; all results agree with the plain computation to
 * round-off (tests/test_stress.c), except the window's zeros outside it (see mc_stage_stress).
 * A zeroed struct (or NULL) is "everything automatic".
 *   symmetric - fft backend, both axes free: kernel tables of one quadrant
 *               (mc_stress_tables_quadrant) and their spectra by real-to-real transforms of a
 *               quarter of the size (stress_internal.h), products straight from those; padded
 *               length 2m per axis, m the smallest 7-smooth >= max(n, 2). AUTO = ON where it
 *               applies; OFF: full tables and r2c (the engine of operator.h).
 *   sparse    - the sparse sum over the loaded cells only: 6 n_L N multiply-adds per load and
 *               layer from the real-space tables (no kernel transforms). AUTO: the cost model of
 *               mc_stress_cost picks it when it is cheaper than the transforms; ON: always (any
 *               backend); OFF: never.
 *   window    - the stage only (mc_stage_stress_tuned): AUTO follows the scene's [stress] window
 *               key; OFF computes every layer on the whole grid; ON windows regardless. */
typedef struct {
    mc_stress_switch symmetric;
    mc_stress_switch sparse;
    mc_stress_switch window;
} mc_stress_tuning;

/* Cost model of the automatic choice, seconds per layer on one thread of this machine (a 2-core
 * x86-64; the constants are in stress.c with their measurements):
 *   *full_s   the convolution over the whole grid: on the fft backend 6 nterms kernel transforms
 *             (r2r of the quadrant, or r2c of the full table), 6 pruned inverse transforms,
 *             6 nterms spectrum products, and the load transforms spread over the plan's layers;
 *             on the direct backend the dense O(N^2) sum;
 *   *sparse_s the sparse sum over nloaded cells: 6 nterms nloaded nx ny multiply-adds.
 * Table builds are common to both and left out. */
void mc_stress_cost(const mc_stress_plan *plan, long nloaded, int nterms, double *full_s,
                    double *sparse_s);

/* Plan the transforms and workspaces for grid g: the transform engine (the symmetric one of
 * stress_internal.h for the fft backend on free axes, else operator.h's), the table builder, the
 * kernel arrays of every announced load (6 quadrants or spectra each) and the load spectra, the
 * list of loaded cells; nothing is allocated afterwards. *out is NULL on failure. MC_OK,
 * MC_ERR_INPUT for bad options (no load announced, nlayers < 1, bad depth, nu or kernel, a bad
 * tuning switch), MC_ERR_LIMIT (more than INT_MAX cells), MC_ERR_NOMEM, or what mc_conv_create
 * returns. */
int mc_stress_create(const mc_grid *g, const mc_stress_options *opt, mc_stress_plan **out,
                     mc_error *err);

/* mc_stress_create with the speed-ups of tune (NULL: all automatic, as mc_stress_create). */
int mc_stress_create_tuned(const mc_grid *g, const mc_stress_options *opt,
                           const mc_stress_tuning *tune, mc_stress_plan **out, mc_error *err);

/* All layers: s[c] (c < 6) are caller arrays of nlayers*ny*nx values (volume layout
 * f[(k*ny + j)*nx + i]), in the unit of the loads (Pa). Loads (ny*nx, Pa) that are NULL count as
 * zero; a load not announced in opt.loads must be NULL (MC_ERR_INPUT). The cells where a given
 * load is non-zero are found once, and the path chosen once (mc_stress_tuning.sparse): either each
 * given load is transformed once and per layer the tables of the given loads are built and
 * transformed, then each component is one product-and-inverse-transform with one term per given
 * load; or per layer the tables are built and summed over the loaded cells (the sparse sum).
 * Never allocates beyond the plan's workspaces. Not reentrant per plan. */
int mc_stress_field(mc_stress_plan *plan, const double *p, const double *qx, const double *qy,
                    double *const s[6], mc_error *err);

/* mc_stress_field one layer at a time, for a caller that needs each layer once and not the
 * volume: layer k (k = 0 .. nlayers - 1 in order) is computed into s[c] (ny*nx values each) and
 * handed to visit(ctx, k, s), whose non-zero return stops the sweep and is returned. The same
 * bits as mc_stress_field's layer k (the loads prepared once, the same compute). */
int mc_stress_field_layers(mc_stress_plan *plan, const double *p, const double *qx,
                           const double *qy, double *const s[6],
                           int (*visit)(void *ctx, int k, double *const s[6]), void *ctx,
                           mc_error *err);

/* mc_stress_field with its layers split over the ranks of the run (core/dist.h): each rank
 * computes its contiguous block of layers (mc_dist_share) and receives the others', so that s is
 * whole on every rank, the same bits as mc_stress_field's on one process. Collective: every rank
 * calls it with the same plan and loads; a failure on one rank fails all (the others with a
 * message naming the status). Without a communicator it is mc_stress_field. MC_ERR_LIMIT when
 * the volume exceeds MPI's int counts. */
int mc_stress_field_split(mc_stress_plan *plan, const double *p, const double *qx,
                          const double *qy, double *const s[6], mc_error *err);

/* One layer k (0 <= k < nlayers): s[c] are ny*nx arrays; loads as in mc_stress_field (transformed
 * on every call). */
int mc_stress_layer(mc_stress_plan *plan, int k, const double *p, const double *qx,
                    const double *qy, double *const s[6], mc_error *err);

/* The layers of one set of loads, the loads transformed once: mc_stress_prepare takes them (as
 * mc_stress_field; they must stay alive until the last mc_stress_compute), finds the loaded cells,
 * chooses the path and transforms the loads if the path needs it; mc_stress_compute gives layer k
 * into s[c] (ny*nx each), the bits of mc_stress_layer. */
int mc_stress_prepare(mc_stress_plan *plan, const double *p, const double *qx, const double *qy,
                      mc_error *err);
int mc_stress_compute(mc_stress_plan *plan, int k, double *const s[6], mc_error *err);

/* After mc_stress_prepare, layer k's six stresses as half spectra instead of fields, for a caller
 * that adds spectra of its own before one inverse transform (the spectral eigenstrain operator,
 * docs/theory.md §8.10): mc_stress_spectra_size says whether the prepared plan can (the
 * symmetric engine, the loads not summed cell by cell) and the transform's size tx x ty;
 * mc_stress_add_spectra then adds layer k's spectra to spec[c] (ty rows of tx/2 + 1 complex
 * values, normalised: FFTW's unnormalised c2r of them gives the stresses). */
int mc_stress_spectra_size(const mc_stress_plan *plan, int *tx, int *ty);
int mc_stress_add_spectra(mc_stress_plan *plan, int k, double *const spec[6], mc_error *err);

/* Cumulative wall-clock seconds spent by mc_stress_field / mc_stress_layer of a plan since its
 * creation. */
typedef struct {
    double loads;   /* forward transforms of the loads (and the scan for loaded cells) */
    double tables;  /* kernel table builds (full, or quadrants on the symmetric path) */
    double kernels; /* kernel transforms (fft: r2c, symmetric: r2r; direct: copies) */
    double apply;   /* products and inverse transforms (fft), or the sparse sums */
    long layers;    /* layers computed */
    long sparse_layers; /* of which by the sparse sum over the loaded cells */
    int symmetric;  /* 1: the plan runs the symmetric engine */
} mc_stress_timing;

void mc_stress_timing_get(const mc_stress_plan *plan, mc_stress_timing *t);

void mc_stress_destroy(mc_stress_plan **plan); /* frees, sets *plan = NULL; NULL-safe */

#endif
