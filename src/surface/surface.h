/* surface.h - topography: analytic shapes, synthetic roughness, height maps.
 *
 * The initial gap (topography) at zero approach is h = shape - heights, where the shape is the
 * combined gap of the two smooth bodies with its apex (h = 0) at the grid centre and heights are
 * the composite roughness, positive towards the counter body. */
#ifndef MC_SURFACE_H
#define MC_SURFACE_H

#include <stdint.h>

#include "core/error.h"
#include "core/grid.h"
#include "core/paths.h"
#include "surface/measured.h"

typedef enum { MC_SHAPE_FLAT, MC_SHAPE_SPHERE, MC_SHAPE_CYLINDER, MC_SHAPE_ELLIPSOID } mc_shape;

typedef enum {
    MC_ROUGH_NONE,
    MC_ROUGH_GAUSSIAN,    /* Gaussian heights, Gaussian autocorrelation (correlation_x/_y) */
    MC_ROUGH_SELF_AFFINE, /* self-affine (Hurst exponent) between two cut-off wavelengths */
    MC_ROUGH_FILE         /* measured/external height map (.npy or whitespace text) */
} mc_roughness_type;

/* Smooth-body shape: the combined initial gap of the two bodies, apex at the grid centre. */
typedef struct {
        mc_shape shape;
        double radius;             /* sphere, cylinder (curvature in x), m */
        double radius_x, radius_y; /* ellipsoid principal radii, m */
    } mc_shape_spec;

/* Roughness: heights up (towards the counter body) reduce the gap. */
typedef struct {
        mc_roughness_type type;
        double rq;                           /* rms height, m (gaussian, self_affine) */
        double correlation_x, correlation_y; /* gaussian: ACF exp(-(tx/lx)^2-(ty/ly)^2), m */
        double hurst;                        /* self_affine: Hurst exponent, 0 < H < 1 (0.8) */
        double rms_slope;                    /* self_affine: alternative to rq (0 = unused) */
        double lambda_long, lambda_short;    /* self_affine cut-offs, m (0: mc_scene_cutoffs) */
        uint64_t seed;                       /* generator seed (reproducible) */
        char file[MC_PATH_MAX];              /* file: height map path (relative to the case) */
        double cutoff; /* lambda_c of the roughness parameters, m; 0: ISO 4288 from Ra */
        /* file: how the map is read and prepared (surface/measured.h) */
        int format;                          /* mc_surface_format */
        int units;                           /* 0 m, 1 mm, 2 um, 3 nm */
        int verify_checksum;
        int has_region;
        double region[4];                    /* x0, y0, width, height, m */
        int detrend;                         /* mc_detrend_kind */
        int missing;                         /* mc_missing_rule */
        int resample;                        /* mc_resample_rule */
        double scale;
        int invert;
    } mc_roughness_spec;

/* ---- reproducible random numbers: xoshiro256** seeded by splitmix64 --------------------- */
/* Blackman & Vigna (2018), xoshiro256** 1.0; the four state words are four successive outputs
 * of splitmix64 started at the seed. The stream depends only on the seed (any platform). */
typedef struct {
    uint64_t s[4];
    double spare;  /* second Box-Muller value, returned by the next mc_rng_normal call */
    int has_spare; /* 1 when spare is valid */
} mc_rng;
void mc_rng_seed(mc_rng *r, uint64_t seed);
uint64_t mc_rng_next(mc_rng *r);
double mc_rng_uniform(mc_rng *r); /* [0, 1) with 53 random bits: (next >> 11) * 2^-53 */
double mc_rng_normal(mc_rng *r);  /* standard normal (Box-Muller, both values used) */

/* ---- pieces ------------------------------------------------------------------------------ */

/* Smooth-body gap at cell centres (ny*nx), m: flat 0; sphere r^2/2R; cylinder x^2/2R (axis
 * along y); ellipsoid x^2/2Rx + y^2/2Ry. Cell centres x_i = (i + 1/2 - nx/2) dx (grid.h). The
 * radii must be valid (> 0 where used). */
void mc_surface_shape(const mc_grid *g, const mc_shape_spec *s, double *h);

/* Roughness heights (ny*nx), m, for the roughness spec (zeros for none).
 *
 * Synthetic surfaces use the spectral method (theory.md §14.1): standard normal white
 * noise drawn row by row from mc_rng(seed) -> FFTW r2c (FFTW_ESTIMATE) -> times sqrt(C(q)) ->
 * c2r, on the ny x nx grid (so they are periodic by construction, whatever the grid's
 * periodicity), then the mean is removed (the q = 0 mode is zeroed) and the field is scaled.
 * Wavenumbers q_x = 2 pi k / (nx dx), k = 0..nx/2, and q_y likewise with negative k above ny/2.
 *  - gaussian:    C = exp(-(q_x l_x)^2/4 - (q_y l_y)^2/4), the spectrum of the autocorrelation
 *                 R = rq^2 exp(-(t_x/l_x)^2 - (t_y/l_y)^2); l = 0 gives white noise along that
 *                 axis. Scaled to exactly rq (the rms of the returned field about its mean 0).
 *  - self_affine: C = |q|^(-2(1+H)) for q_long <= |q| <= q_short, C = q_long^(-2(1+H)) below
 *                 q_long (roll-off), 0 above q_short, q = 2 pi / lambda. lambda_long = 0 means
 *                 max(nx dx, ny dy) (no roll-off); lambda_short = 0 means 2 max(dx, dy) (the
 *                 Nyquist wavelength of the coarser axis). Scaled to exactly rq, or, when
 *                 rms_slope > 0, to that rms slope sqrt(<|grad h|^2>) computed spectrally
 *                 (Parseval: sum over all modes of |H(q)|^2 |q|^2, Nyquist modes included with
 *                 |q|^2) - then rq is ignored.
 * rq = 0 (and no rms_slope) gives zeros. The same seed and grid give a bitwise identical surface
 * on every run with the same FFTW thread count. file: the map is read with mc_heightmap_read
 * (shape checked against the mesh) and used as is.
 * Errors: MC_ERR_INPUT (bad parameters, empty spectrum band on this grid, file format or shape),
 * MC_ERR_IO (file), MC_ERR_NOMEM, MC_ERR_INTERNAL (FFTW planning failed). */
int mc_surface_roughness(const mc_grid *g, const mc_roughness_spec *s, double *heights,
                         mc_error *err);

/* mc_surface_roughness with its messages naming label ("[roughness]", "[roughness2]") instead
 * of "[roughness]". */
int mc_surface_roughness_labelled(const mc_grid *g, const mc_roughness_spec *s, const char *label,
                                  double *heights, mc_error *err);

/* What a measured file held (summary.json): format read, points missing and filled, and the
 * reader's warning ("" when none). Zeros for a synthetic surface. */
typedef struct {
    char format[16];
    long missing, filled;
    char warning[320];
} mc_surface_file_info;

/* The roughness heights of the two bodies of a contact on the mesh g (ny*nx each, m), each
 * measured outward, towards the other body (theory.md §4.11): z1 of s1 ([roughness], body 1),
 * z2 of s2 ([roughness2], body 2); the gap's roughness is z1 + z2 and the topography
 * shape - (z1 + z2). Each map is read and prepared as mc_surface_roughness does (messages name
 * "[roughness]" or "[roughness2]"), each file once. Both must come onto the mesh: a map whose
 * grid differs from it with resample = none is MC_ERR_INPUT naming both bodies (files and
 * grids, or the synthetic type) and the mesh. *which (may be NULL) is the body whose input
 * failed (1, 2; 0 on success); info1, info2 (may be NULL) what each file held. Errors as
 * mc_surface_roughness. */
int mc_surface_two_bodies(const mc_grid *g, const mc_roughness_spec *s1,
                          const mc_roughness_spec *s2, double *z1, double *z2,
                          mc_surface_file_info *info1, mc_surface_file_info *info2, int *which,
                          mc_error *err);

/* The measured-map settings of a file roughness spec. */
void mc_surface_measured_spec(const mc_roughness_spec *s, mc_measured_spec *out);

/* Whole topography: shape - roughness (ny*nx), m. Errors as mc_surface_roughness. */
int mc_surface_topography(const mc_grid *g, const mc_shape_spec *shape,
                          const mc_roughness_spec *rough, double *topo, mc_error *err);

/* Roughness statistics of a height field (for tests and reports): mean; rq = Sq and ra = Sa
 * about the mean; slopes by central differences (wrapping around periodic axes, one-sided at
 * the ends of free axes; 0 along an axis with one cell) - they under-estimate spectral slopes by
 * sin(q d)/(q d) per mode; skewness Ssk and kurtosis Sku (0 when rq = 0). */
typedef struct {
    double mean, rq, ra, rms_slope_x, rms_slope_y, skewness, kurtosis;
} mc_surface_stats;
void mc_surface_statistics(const mc_grid *g, const double *heights, mc_surface_stats *st);

#endif
