/* scene.h - the in-memory case: every input of one run, with SI values and defaults.
 *
 * A scene is plain data (no owned pointers), filled by case.c from an INI file plus overrides,
 * or directly by verification suites and benchmarks. mc_scene_defaults() gives every optional
 * key its documented default (docs/case-format.md); keys without a default (mesh size, load,
 * radii, ...) are left 0, which mc_scene_check() rejects until the caller sets them.
 * mc_scene_check() validates every rule a scene must satisfy however it was built, including the
 * cross-key ones (force_per_length needs periodic_y, pressure_cap > lubricant_pressure, ...).
 */
#ifndef MC_SCENE_H
#define MC_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/paths.h"
#include "core/grid.h"
#include "operator/operator.h"
#include "contact/contact.h"
#include "lube/film.h"
#include "lube/friction.h"
#include "plastic/eigen_op.h"
#include "plastic/loop.h"
#include "plastic/hardening.h"
#include "stress/stress.h"
#include "surface/surface.h"

#define MC_MAX_DEPTHS 512

typedef enum {
    MC_LOAD_FORCE,            /* total normal force, N */
    MC_LOAD_FORCE_PER_LENGTH, /* force per unit length along y, N/m (periodic_y required) */
    MC_LOAD_APPROACH,         /* rigid approach, m */
    MC_LOAD_PRESSURE_FILE     /* prescribed pressure map (no contact solve) */
} mc_load_kind;

typedef enum { MC_SPACING_LINEAR, MC_SPACING_GEOMETRIC, MC_SPACING_LIST } mc_spacing;
/* [stress] window: auto = only the loaded region plus a depth-dependent margin (stress.h) */
typedef enum { MC_STRESS_WINDOW_AUTO, MC_STRESS_WINDOW_FULL } mc_scene_stress_window;

/* [load] lubricant_pressure = auto: from the lubricant volume equilibrium ([lubrication]) */
#define MC_LUBRICANT_AUTO (-1.0)

typedef enum { MC_FILM_EHL, MC_FILM_GIVEN } mc_scene_film_source;
typedef enum { MC_CRITERION_VON_MISES, MC_CRITERION_PRESSURE_CAP } mc_yield_criterion;
typedef enum { MC_TABLE_UNIT_PA, MC_TABLE_UNIT_MPA, MC_TABLE_UNIT_GPA } mc_scene_table_unit;
/* [lubrication] lubricant_profile: the lubricant pressure over the Hertz band of the whole
 * contact (theory.md §11.4): one p_lub on the band (the paper's), or a Hertz-shaped profile */
typedef enum { MC_PROFILE_UNIFORM, MC_PROFILE_HERTZ } mc_scene_lube_profile;
/* [runin] nominal_deflection: the patch's own bowl under its nominal pressure (pipeline/runin.h) */
typedef enum { MC_DEFLECTION_REMOVE, MC_DEFLECTION_KEEP } mc_nominal_deflection;

#define MC_RUNIN_MAX 32 /* entries of [runin] forces and speeds */

/* [plasticity] layering (the key's choices follow the enum) */
typedef enum { MC_LAYERING_AUTO = 0, MC_LAYERING_UNIFORM = 1, MC_LAYERING_GRADED = 2 } mc_layering;

/* [stress] depth_max = auto: derived from the contact by the stress stage (stress.h) */
#define MC_STRESS_DEPTH_AUTO 0.0

#define MC_SCENE_KEYS_MAX 192 /* >= the rows of the key table (checked by the case reader) */

typedef struct {
    double E;  /* Young's modulus, Pa */
    double nu; /* Poisson's ratio */
    int rigid; /* 1: rigid (only body 2) */
} mc_scene_material;

typedef struct {
    char path[MC_PATH_MAX]; /* case file the scene came from ("" if built in code) */

    mc_grid grid; /* [mesh] */

    mc_shape_spec geometry; /* [geometry] (surface.h) */

    mc_roughness_spec roughness;  /* [roughness] (surface.h): the gap's composite roughness, or
                                     body 1's surface when roughness2 is given */
    mc_roughness_spec roughness2; /* [roughness2]: body 2's surface (type none: not given) */

    mc_scene_material body1, body2; /* [body1], [body2] */

    struct { /* [load] */
        mc_load_kind kind;
        double value;                    /* N, N/m or m according to kind */
        char pressure_file[MC_PATH_MAX]; /* MC_LOAD_PRESSURE_FILE: .npy map, Pa */
        double lubricant_pressure;       /* lower bound outside solid contact, Pa (default 0) */
        double pressure_cap;             /* upper bound, Pa (default +inf: none) */
    } load;

    struct { /* [solver] */
        mc_backend backend;       /* operator backend (default fft) */
        mc_contact_method method; /* default cg */
        double tolerance;         /* relative stopping tolerance (default 1e-8) */
        int max_iterations;       /* default 2000 */
        int threads;              /* 0 = all cores */
        mc_plan_rigor plans;      /* FFTW planner rigor (operator.h; default estimate) */
        char wisdom_file[MC_PATH_MAX]; /* plans = wisdom: the wisdom file */
    } solver;

    struct { /* [stress]; the stage runs only when enabled (section present) */
        int enabled;                 /* default 0; case files: 1 when [stress] is present */
        double depth_min, depth_max; /* m (linear, geometric spacing); depth_max =
                                        MC_STRESS_DEPTH_AUTO (the default): from the contact */
        int layers;                  /* linear, geometric; default 32 */
        mc_spacing spacing;          /* MC_SPACING_LIST: use depths[] below */
        int ndepths;                 /* number of entries in depths (MC_SPACING_LIST) */
        double depths[MC_MAX_DEPTHS];
        mc_stress_kernel kernel;     /* default patch */
        double friction;             /* q_x = friction * p (sliding in +x), default 0 */
        mc_scene_stress_window window; /* default auto */
    } stress;

    struct { /* [lubrication]: the lubricant volume equilibrium (runs when enabled) */
        int enabled;                 /* case files: 1 when [lubrication] is present */
        mc_scene_film_source film;         /* ehl (formula) or given (film_thickness) */
        double film_thickness;       /* given: h_EHD, m */
        mc_film_formula formula;     /* ehl */
        double viscosity;            /* eta0, Pa s */
        double pressure_viscosity;   /* alpha (Barus), 1/Pa */
        double speed;                /* mean entrainment speed, m/s (0: from rpm) */
        double rpm, rpm2;            /* disc speeds, rad/s (rpm2 0: equal surface speeds) */
        double radius1, radius2;     /* disc radii, m */
        double macro_radius;         /* reduced radius R_x of the macro contact, m (0: unset) */
        double width;                /* contact width (face width), m (0: unset) */
        double mu_solid, mu_fluid;   /* friction coefficients of solid and fluid contact */
        mc_psi_kind psi;             /* load- or area-based solid contact ratio */
        double tolerance;            /* relative tolerance of the volume root */
        mc_scene_lube_profile profile; /* the whole contact ([geometry] shape = cylinder) */
    } lubrication;

    struct { /* [plasticity]: the elastic-plastic stage (runs when enabled) */
        int enabled;                  /* case files: 1 when [plasticity] is present */
        mc_yield_criterion criterion; /* von_mises (the paper) or pressure_cap */
        double hardness;              /* pressure_cap: the limiting pressure, Pa */
        mc_hardening_kind hardening;  /* perfect, linear, swift, table */
        double yield_stress;          /* perfect, linear: initial yield stress Y0, Pa */
        double tangent_modulus;       /* linear: E_t, Pa */
        double swift_B, swift_C, swift_n; /* swift: sigma_y = B (C + 1e6 p)^n */
        char table[MC_PATH_MAX];      /* table: CSV of (eps_p, sigma_y) */
        mc_scene_table_unit table_unit;     /* unit of sigma_y in the table */
        int both;                     /* bodies = both: body 2 is the same material */
        int load_steps;
        double relaxation;            /* omega of the outer iteration */
        double tolerance;             /* relative change of the residual displacement */
        int max_outer;
        double plastic_tolerance;     /* fixed point of the plastic strain increment */
        int max_plastic;
        mc_plastic_iteration iteration; /* joint (default) or nested (docs/theory.md §9.8) */
        int near_field;          /* > 0: local-global fixed point with this lateral reach (cells,
                                    docs/theory.md §9.7); 0: one global application per sweep */
        double dz;                    /* layer thickness, m; 0: min(dx, dy) / 2 (line: dx / 2) */
        mc_eig_stress_points stress_points; /* cell_average (default) or centre */
        mc_eig_kernel kernel;               /* cuboid (default) or spectral */
        double depth;                 /* m; 0: auto */
        double margin;                /* columns around the contact's box, m; 0: auto */
        double friction;              /* q_x = friction (p - p_lub) in solid contact */
        mc_layering layering;         /* auto (graded when depth = auto), uniform, graded */
        double fine_depth;            /* graded: fine layers down to here, m; 0: auto */
        double grading;               /* graded: largest layer thickness / its top's depth */
    } plasticity;

    struct { /* [runin]: the running-in driver, speed run-down and run-up per force */
        int enabled;                  /* case files: 1 when [runin] is present */
        int nforces;                  /* 0: [load] force alone */
        double forces[MC_RUNIN_MAX];  /* macro normal forces F_N, N, taken in this order */
        int nspeeds;
        double speeds[MC_RUNIN_MAX];  /* run-down speeds of disc 1, rad/s, strictly decreasing */
        mc_nominal_deflection deflection; /* remove (default) or keep the nominal bowl */
        int friction_in_yield;        /* 1: each run-down step's mu loads its yield check with
                                         q_x = +-mu (p - p_lub), sign of the sliding (runin.h) */
    } runin;

    struct { /* [output] */
        char dir[MC_PATH_MAX]; /* "": derive from path (mc_scene_output_dir); case files fill it */
        int vtk;               /* write field.vti */
        int x3p;               /* write an .x3p beside every surface height map .npy */
    } output;

    /* Where each key of the table (case/keys.h, by row index) was given: its line in path, -1 for
     * a --set override, 0 when not given (a default). Filled by the case reader, so that errors
     * found after parsing can name the line (mc_scene_where). */
    int key_line[MC_SCENE_KEYS_MAX];
} mc_scene;

/* Fill every field with its documented default: shape flat, no roughness (seed 1, hurst 0.8),
 * steel bodies (E = 210 GPa, nu = 0.3), no pressure cap (+inf), fft + cg, tolerance 1e-8, 2000
 * iterations, stress disabled (32 linear layers from 0 to depth_max = auto, window auto), output
 * dir "". */
void mc_scene_defaults(mc_scene *s);

/* Validate the scene: grid, shape radii, roughness parameters, materials, a load (> 0 or a file),
 * force_per_length => periodic_y, pressure_cap > lubricant_pressure >= 0, solver settings, and,
 * when stress is enabled, its depths (depth_max > depth_min >= 0 unless auto, geometric =>
 * depth_min > 0, lists strictly increasing) and window. MC_OK or MC_ERR_INPUT with a message
 * "[section] key ...". */
int mc_scene_check(const mc_scene *s, mc_error *err);

/* Same, and on failure names the key at fault (*section, *key: static strings; either pointer
 * may be NULL), so that the case reader can point at the line that set it. */
int mc_scene_check_key(const mc_scene *s, mc_error *err, const char **section, const char **key);

/* The place of key [section] name for a message about it, into buf: "case.ini:12: " (given on line
 * 12), "case.ini: --set load.force: " (given by an override), "case.ini: " (a default, or a scene
 * built in code: "<scene>: " without path). Always NUL-terminated. */
void mc_scene_where(const mc_scene *s, const char *section, const char *name, char *buf,
                    size_t len);

/* Combined modulus E* of the scene's two bodies, Pa (kernel.h mc_combined_modulus). */
double mc_scene_estar(const mc_scene *s);

/* Resolved depth list of the stress stage, m (depths must hold MC_MAX_DEPTHS): linear
 * z_k = depth_min + k (depth_max - depth_min)/(layers - 1) (layers = 1: depth_min alone);
 * geometric z_k = depth_min (depth_max/depth_min)^(k/(layers - 1)); list: as given. The ends are
 * exact. MC_ERR_INPUT (as mc_scene_check) if the stress settings are invalid, or if depth_max is
 * auto (which only the stress stage resolves, from the contact patches: mc_stage_stress). */
int mc_scene_depths(const mc_scene *s, double *depths, int *ndepths, mc_error *err);

/* Effective self-affine cut-off wavelengths, m: the scene's values, or for 0 the defaults
 * lambda_long = max(nx dx, ny dy) and lambda_short = 2 max(dx, dy). */
void mc_scene_cutoffs(const mc_scene *s, double *lambda_long, double *lambda_short);
/* The same for the roughness spec r of the scene ([roughness] or [roughness2]). */
void mc_scene_spec_cutoffs(const mc_scene *s, const mc_roughness_spec *r, double *lambda_long,
                           double *lambda_short);

/* Output directory: s->output.dir, or when it is "" "out/<file name of s->path without .ini>"
 * ("out/scene" when path is "" too). MC_ERR_INPUT if it does not fit in len bytes. */
int mc_scene_output_dir(const mc_scene *s, char *buf, size_t len, mc_error *err);

#endif
