/* scene.h - the in-memory case: every input of one run, with SI values and defaults.
 *
 * A scene is plain data (no owned pointers), filled by case.c from an INI file plus overrides,
 * or directly by verification suites and benchmarks. mc_scene_defaults() gives every optional
 * key its documented default; mc_scene_check() validates cross-key rules.
 */
#ifndef MC_SCENE_H
#define MC_SCENE_H

#include <stdint.h>

#include "error.h"
#include "grid.h"
#include "operator.h"

#define MC_PATH_MAX 1024
#define MC_MAX_DEPTHS 512

typedef enum { MC_SHAPE_FLAT, MC_SHAPE_SPHERE, MC_SHAPE_CYLINDER, MC_SHAPE_ELLIPSOID } mc_shape;

typedef enum {
    MC_ROUGH_NONE,
    MC_ROUGH_GAUSSIAN,    /* Gaussian heights, Gaussian autocorrelation (correlation_x/_y) */
    MC_ROUGH_SELF_AFFINE, /* self-affine (Hurst exponent) between two cut-off wavelengths */
    MC_ROUGH_FILE         /* measured/external height map (.npy or whitespace text) */
} mc_roughness_type;

typedef enum {
    MC_LOAD_FORCE,            /* total normal force, N */
    MC_LOAD_FORCE_PER_LENGTH, /* force per unit length along y, N/m (periodic_y required) */
    MC_LOAD_APPROACH,         /* rigid approach, m */
    MC_LOAD_PRESSURE_FILE     /* prescribed pressure map (no contact solve) */
} mc_load_kind;

typedef enum {
    MC_METHOD_CG,        /* preconditioned constrained conjugate gradients (default, fast) */
    MC_METHOD_PK,        /* plain Polonsky & Keer (1999) */
    MC_METHOD_ACTIVE_SET /* the paper's dense active-set reference (small grids only) */
} mc_contact_method;

typedef enum { MC_SPACING_LINEAR, MC_SPACING_GEOMETRIC, MC_SPACING_LIST } mc_spacing;
typedef enum { MC_STRESS_PATCH, MC_STRESS_POINT } mc_stress_kernel;

typedef struct {
    double E;  /* Young's modulus, Pa */
    double nu; /* Poisson's ratio */
    int rigid; /* 1: rigid (only body 2) */
} mc_material;

typedef struct {
    char path[MC_PATH_MAX]; /* case file the scene came from ("" if built in code) */

    mc_grid grid; /* [mesh] */

    struct { /* [geometry]: combined initial gap of the two bodies, apex at the grid centre */
        mc_shape shape;
        double radius;             /* sphere, cylinder (curvature in x), m */
        double radius_x, radius_y; /* ellipsoid principal radii, m */
    } geometry;

    struct { /* [roughness]: heights up (towards the counter body) reduce the gap */
        mc_roughness_type type;
        double rq;                           /* rms height, m (gaussian, self_affine) */
        double correlation_x, correlation_y; /* gaussian: ACF exp(-(tx/lx)^2-(ty/ly)^2), m */
        double hurst;                        /* self_affine: Hurst exponent, 0..1 */
        double rms_slope;                    /* self_affine: alternative to rq (0 = unused) */
        double lambda_long, lambda_short;    /* self_affine cut-off wavelengths, m (0 = auto) */
        uint64_t seed;                       /* generator seed (reproducible) */
        char file[MC_PATH_MAX];              /* file: height map path (relative to the case) */
    } roughness;

    mc_material body1, body2; /* [body1], [body2] */

    struct { /* [load] */
        mc_load_kind kind;
        double value;                    /* N, N/m or m according to kind */
        char pressure_file[MC_PATH_MAX]; /* MC_LOAD_PRESSURE_FILE: .npy map, Pa */
        double lubricant_pressure;       /* lower bound outside solid contact, Pa (default 0) */
        double pressure_cap;             /* upper bound, Pa (default +inf: none) */
    } load;

    struct { /* [solver] */
        mc_backend op;            /* operator backend (default fft) */
        mc_contact_method method; /* default cg */
        double tolerance;         /* relative stopping tolerance (default 1e-8) */
        int max_iterations;       /* default 1000 */
        int threads;              /* 0 = all cores */
    } solver;

    struct { /* [stress]; the stage runs only when enabled (section present) */
        int enabled;
        double depth_min, depth_max; /* m */
        int layers;
        mc_spacing spacing;
        int ndepths;                 /* number of entries in depths (MC_SPACING_LIST) */
        double depths[MC_MAX_DEPTHS];
        mc_stress_kernel kernel;     /* default patch */
        double friction;             /* q_x = friction * p (sliding in +x), default 0 */
    } stress;

    struct { /* [output] */
        char dir[MC_PATH_MAX]; /* default "out/<case name>" */
        int vtk;               /* write field.vti */
    } output;
} mc_scene;

/* Fill every field with its documented default (shape flat, no roughness, steel bodies, ...). */
void mc_scene_defaults(mc_scene *s);

/* Cross-key validation (e.g. force_per_length needs periodic_y); MC_ERR_INPUT with a message. */
int mc_scene_check(const mc_scene *s, mc_error *err);

/* Combined modulus E* of the scene's two bodies, Pa. */
double mc_scene_estar(const mc_scene *s);

/* Resolved depth list of the stress stage (ndepths <= MC_MAX_DEPTHS); MC_ERR_INPUT if invalid. */
int mc_scene_depths(const mc_scene *s, double *depths, int *ndepths, mc_error *err);

#endif
