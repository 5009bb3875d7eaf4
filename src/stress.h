/* stress.h - subsurface stress on depth layers from surface loads (elastic.md 3, 7).
 *
 * For each depth z_k the six stress components (tension positive, order of kernel.h: xx, yy, zz,
 * xy, yz, xz) at the cell centres (x_i, y_j, z_k) are convolutions of the surface loads with
 * influence kernels:
 *     sigma_c(z_k) = K_c^p(z_k) (*) p + K_c^qx(z_k) (*) q_x + K_c^qy(z_k) (*) q_y
 * Kernels (per unit load on one cell, offsets FIELD minus SOURCE, elastic.md 5.1):
 *   patch - uniform load on the dx x dy rectangle (Love 1929; elastic.md 3.3, 3.4): exact for
 *           piecewise-constant loads at every depth, including z = 0. Tables come from the corner
 *           functions of kernel.h evaluated once per corner of the offset lattice and differenced
 *           (elastic.md 3.5);
 *   point - a concentrated force p dx dy at the cell centre (Boussinesq / Cerruti, 3.1, 3.2):
 *           the "minimum evaluation depth" artefact of 3.6, kept for that comparison; z > 0 only.
 * Backends as in operator.h (direct summation or DC-FFT over the same tables, so they agree to
 * round-off); one forward transform per load field is shared by all components and layers.
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
 *     set by the macro contact, not by the cell (elastic.md 5.3). Add it outside if needed.
 */
#ifndef MC_STRESS_H
#define MC_STRESS_H

#include "error.h"
#include "grid.h"
#include "operator.h"
#include "results.h"
#include "scene.h"

enum { MC_LOAD_P = 1, MC_LOAD_QX = 2, MC_LOAD_QY = 4 };

/* Far edge of the smeared strips of periodic axes, in units of max(Lx, Ly). */
#define MC_STRESS_FAR_EDGE 1e12
/* Depth (in periods of an axis) from which the image sum along that axis is the smeared load. */
#define MC_STRESS_SMEAR_DEPTH 4.5

/* ---- kernel tables of one depth (the lower layer; used by the operator below) -------------- */

typedef struct mc_stress_tables mc_stress_tables;

/* Plan the table builder for grid g and table sizes tx, ty (as from mc_conv_table_dims: a free
 * axis >= 2n - 1, a periodic axis = n), kernel, Poisson ratio nu in (-1, 0.5]. images: images per
 * side M on periodic axes at every depth above the smearing depth (values below 2 are raised to
 * 2), or <= 0 for the automatic depth-dependent choice (tests use it to measure the tail's
 * convergence). Workspaces for mc_get_threads() threads are allocated here.
 * *out is NULL on failure. MC_OK, MC_ERR_INPUT (bad grid, sizes, kernel or nu), MC_ERR_NOMEM. */
int mc_stress_tables_create(const mc_grid *g, int tx, int ty, mc_stress_kernel kernel, double nu,
                            int images, mc_stress_tables **out, mc_error *err);

/* The six tables k[c] (c in kernel.h order, each ty*tx, caller-owned, wrap-around layout of
 * operator.h with padding slots 0) of load (one of MC_LOAD_P, MC_LOAD_QX, MC_LOAD_QY) at depth z
 * (m): stress per unit load on one cell. Never allocates; OpenMP over table rows. MC_OK, or
 * MC_ERR_INPUT for a bad load, z < 0 or not finite, or z = 0 with the point kernel. */
int mc_stress_tables_build(mc_stress_tables *tb, int load, double z, double *const k[6],
                           mc_error *err);

/* Images per side summed exactly along axis 0 (x) or 1 (y) at depth z: 0 on a free axis, -1 when
 * the whole periodic sum is smeared (n = 1, or z >= MC_STRESS_SMEAR_DEPTH L). */
int mc_stress_tables_images(const mc_stress_tables *tb, int axis, double z);

void mc_stress_tables_destroy(mc_stress_tables **tb); /* frees, sets *tb = NULL; NULL-safe */

/* ---- the stress operator ------------------------------------------------------------------- */

typedef struct {
    mc_stress_kernel kernel; /* MC_STRESS_PATCH (default) or MC_STRESS_POINT */
    double nu;               /* Poisson's ratio of the stressed body, in (-1, 0.5] */
    int nlayers;             /* >= 1 */
    const double *depths;    /* nlayers finite depths z >= 0, m (copied); point kernel: z > 0 */
    mc_backend backend;
    int loads;               /* which load fields will be given: MC_LOAD_P | MC_LOAD_QX | ... */
} mc_stress_options;

typedef struct mc_stress_op mc_stress_op;

/* Plan the transforms and workspaces for grid g: the transform engine (operator.h), one set of six
 * tables, the kernel spectra of every announced load and the load spectra; nothing is allocated
 * afterwards. *out is NULL on failure. MC_OK, MC_ERR_INPUT for bad options (no load announced,
 * nlayers < 1, bad depth, nu or kernel), MC_ERR_NOMEM, or what mc_conv_create returns. */
int mc_stress_create(const mc_grid *g, const mc_stress_options *opt, mc_stress_op **out,
                     mc_error *err);

/* All layers: s[c] (c < 6) are caller arrays of nlayers*ny*nx values (volume layout
 * f[(k*ny + j)*nx + i]), in the unit of the loads (Pa). Loads (ny*nx, Pa) that are NULL count as
 * zero; a load not announced in opt.loads must be NULL (MC_ERR_INPUT). Each given load is
 * transformed once; per layer the tables of the given loads are built and transformed, then each
 * component is one mc_conv_apply with one term per given load. Never allocates beyond the plan's
 * workspaces. Not reentrant per op. */
int mc_stress_field(mc_stress_op *op, const double *p, const double *qx, const double *qy,
                    double *const s[6], mc_error *err);

/* One layer k (0 <= k < nlayers): s[c] are ny*nx arrays; loads as in mc_stress_field (transformed
 * on every call). */
int mc_stress_layer(mc_stress_op *op, int k, const double *p, const double *qx, const double *qy,
                    double *const s[6], mc_error *err);

/* Cumulative wall-clock seconds spent by mc_stress_field / mc_stress_layer of op since create. */
typedef struct {
    double loads;   /* forward transforms of the loads */
    double tables;  /* kernel table builds */
    double kernels; /* kernel transforms (fft: r2c; direct: copies) */
    double apply;   /* products and inverse transforms (fft), or the direct sums */
    long layers;    /* layers computed */
} mc_stress_timing;

void mc_stress_timing_get(const mc_stress_op *op, mc_stress_timing *t);

void mc_stress_destroy(mc_stress_op **op); /* frees, sets *op = NULL; NULL-safe */

/* ---- the pipeline stage -------------------------------------------------------------------- */

/* Stresses of the scene's [stress] section under the contact result: depths from mc_scene_depths;
 * loads p = res->pressure and, when friction > 0, the traction q_x = friction * p on the lower
 * body (body 1, z >= 0) in +x: the counter body slides in +x relative to it (elastic.md 0);
 * Poisson ratio of body 1 (the stresses are body 1's; for body 2 mirror the problem); kernel from
 * the scene; backend scene->solver.op; the grid of res (that of the pressure). Fills res->nlayers, depths, stress[6], von_mises, hydrostatic, tresca
 * (invariants.h) and stress_summary (maxima of von Mises and Tresca, first found in volume order,
 * with their cell-centre (x, y, z); the hydrostatic stress at the von Mises maximum). Stress
 * members already present in res are replaced. On failure res's stress members are unchanged.
 * Does not set res->timing.stress_s (the caller times the stage). MC_OK, MC_ERR_INPUT (bad stress
 * settings, no pressure field), MC_ERR_NOMEM, or what mc_stress_create returns. */
int mc_stress_stage(const mc_scene *sc, mc_results *res, mc_error *err);

#endif
