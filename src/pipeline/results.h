/* results.h - what a run produces: fields, summaries and timings (the output contract of
 * README.md, Outputs, in memory). Filled by pipeline.c, written by output.c, read by suites and benches.
 */
#ifndef MC_RESULTS_H
#define MC_RESULTS_H

#include "core/grid.h"
#include "operator/operator.h"
#include "contact/contact.h"
#include "surface/roughness.h"
#include "surface/surface.h"
#include "plastic/loop.h"

typedef struct {
    double vm_max, vm_max_at[3];         /* von Mises maximum, Pa, and its (x, y, z), m */
    double hydro_at_vm_max;              /* hydrostatic stress there, Pa */
    double tresca_max, tresca_max_at[3]; /* max shear (Tresca) maximum, Pa, and location */
    int layers;
    double depth_min, depth_max;         /* m */
    const char *kernel;                  /* "patch" | "point" */
    double friction;
} mc_stage_stress_summary;

/* How the stress stage computed its layers (the skips of stress.h), so that a user can see them. */
#define MC_STRESS_MAX_WINDOWS 16
typedef struct {
    int k0, k1;         /* layers k0..k1 (inclusive) */
    int i0, i1, j0, j1; /* cells computed, i0..i1 x j0..j1 (inclusive); all others hold 0 */
    int sparse;         /* 1: the sparse sum over the loaded cells; 0: the convolution over the
                         * whole window (DC-FFT, or the direct backend's O(N^2) sum) */
} mc_stage_stress_window;

typedef struct {
    int windowed;          /* 1: [stress] window = auto restricted some layer to a window */
    int nwindows;          /* groups of layers, each computed on one window */
    mc_stage_stress_window window[MC_STRESS_MAX_WINDOWS];
    long loaded_cells;     /* cells with a non-zero load */
    int depth_auto;        /* 1: depth_max = auto, derived from the contact */
    int patches;           /* connected contact patches (depth_auto) */
    double patch_radius;   /* m: radius of the largest patch (depth_auto) */
} mc_stage_stress_layout;

/* The lubricant volume equilibrium ([lubrication], lubricant_pressure = auto). */
typedef struct {
    int enabled;
    const char *film;      /* "ehl" | "given" */
    const char *formula;   /* film formula name ("" when given) */
    double h_ehd;          /* film thickness of the smooth surfaces, m */
    double entrainment;    /* mean entrainment speed u, m/s (0 when given) */
    double srr;            /* slide-to-roll ratio */
    double macro_load;     /* F_N, N */
    double load_per_length;/* w' = F_N / width, N/m (0 without the macro contact) */
    double macro_radius;   /* R_x, m (0 without) */
    double hertz_pressure; /* p_H of the macro line contact, Pa (0 without) */
    double hertz_half_width; /* b, m (0 without) */
    double nominal_pressure; /* the patch's nominal pressure F / A_nom, Pa */
    double patch_load;     /* load on the patch, N */
    double p_lub;          /* lubricant pressure, Pa */
    const char *regime;    /* "dry" | "mixed" | "full_film" */
    double volume, v_target, rel_error; /* pocket volume and its target h_EHD A_nom, m^3 */
    int solves;            /* contact solves of the root */
    int converged;
    double psi_load, psi_area, pocket_height; /* solid contact ratios; V / (A_nom - A_C), m */
    double mu;             /* mu = psi mu_solid + (1 - psi) mu_fluid */
    const char *psi_kind;  /* "load" | "area": the psi of mu */
    int whole;             /* 1: the whole contact (the grid carries the macro cylinder, the
                              nominal area is the Hertz band |x| <= b; theory.md §11.4) */
    const char *profile;   /* whole: "uniform" | "hertz", the lubricant pressure profile */
    int crowned;           /* whole and crowned ([geometry] shape = ellipsoid): the nominal area
                              is the Hertz ellipse |x/b|^2 + |y/a|^2 <= 1 */
    double hertz_half_length; /* crowned: the ellipse's semi-axis a along y, m (0 otherwise) */
    double nominal_area;   /* the volume equilibrium's nominal area, m^2 */
} mc_stage_lube_summary;

/* The elastic-plastic stage ([plasticity]). */
typedef struct {
    int enabled;
    int converged;             /* every load step converged (1 also for the elastic shortcut) */
    const char *criterion;     /* "von_mises" | "pressure_cap" */
    const char *hardening;     /* "perfect" | "linear" | "swift" | "table" ("" for a cap) */
    const char *stress_points; /* "cell_average" | "centre" (NULL for a cap) */
    const char *kernel;        /* "cuboid" | "spectral" (NULL for a cap) */
    const char *iteration;     /* "joint" | "nested" (NULL for a cap; plastic/loop.h) */
    double yield_initial;      /* sigma_y(0), Pa (von_mises) */
    double vm_elastic_max;     /* largest von Mises stress of the elastic solve at full load, Pa */
    int elastic_shortcut;      /* 1: nothing yields at full load, no plastic loop was run */
    int load_steps, steps_done, outer_iterations;
    double peq_max, peq_max_at[3]; /* largest accumulated plastic strain and its cell, m */
    double plastic_volume;     /* m^3 of cells that yielded */
    double residual_max;       /* largest residual displacement (into the body), m */
    double depth, dz;          /* plastic volume's depth and layer thickness, m */
    int nz, depth_auto;
    const char *layering;      /* "uniform" | "graded" (NULL for a cap) */
    int *group;                /* graded: nz counts of dz per layer (owned; eigen_op.h); NULL:
                                  uniform */
    int i0, j0, wnx, wny;      /* columns carrying plastic cells (window of the surface grid) */
    long volume_cells;         /* nz wnx wny */
    mc_plastic_step *steps;    /* steps_done records (owned) */
    /* where and why a run that did not converge stopped (plastic/loop.h, theory §9.5); the
     * fields are those of its last iterate. summary.json plastic.stop */
    int stop_step;             /* load step of the loop, from 1 (0: the run did not stop) */
    double stop_load;          /* load of the increment it stopped in, N */
    const char *stop_reason;   /* mc_plastic_stop_text (static) */
    int stop_runin_step;       /* running-in step, from 1 (0: not a running-in) */
} mc_stage_plastic_summary;

/* One step of the running-in ([runin], pipeline/runin.h): a row of runin.csv. */
typedef struct {
    int force_index;         /* into [runin] forces, from 0 */
    int up;                  /* 0: run-down (elastic-plastic), 1: run-up (elastic) */
    double force;            /* macro normal force F_N, N */
    double speed;            /* disc 1, rad/s */
    double entrainment;      /* mean entrainment speed u, m/s */
    double h_ehd, p_lub;     /* film of the smooth discs, m; lubricant pressure, Pa */
    double psi_load, psi_area, pocket_height, mu; /* pocket height in m */
    int regime;              /* lube/volume.h mc_lube_regime */
    double ra, rq, rz, sa, sq; /* of the surface after the step (ISO, as roughness.initial), m */
    double rpk, rk, rvk, mr1, mr2; /* its ISO 13565-2 family (mean over the rows), m and % */
    double sp, spk, sk, svk, smr1, smr2; /* its highest peak and areal material ratio
                                            (ISO 25178-2), m and % */
    double residual_max;     /* largest residual displacement of body 1 so far, m */
    int plastic;             /* the step ran the plastic loop (something yielded) */
    int converged;           /* every solve of the step converged */
    int solves;              /* contact solves of the step */
    int roots;               /* volume equilibria of the step */
    double root_error;       /* |V - V*| / V* of its last equilibrium */
    double seconds;          /* wall time of the step */
} mc_runin_row;

typedef struct {
    int enabled;
    int nforces, nspeeds, nsteps; /* nsteps = 2 nforces nspeeds, in run order */
    int done;                     /* rows filled (all of them unless the run stopped) */
    int resumed_from;             /* steps taken from a checkpoint (0: none) */
    mc_runin_row *rows;           /* nsteps (owned) */
    double *hysteresis;           /* nforces: integral of mu_down - mu_up over log10 speed (owned) */
    const char *deflection;       /* "remove" | "keep" */
} mc_runin_summary;

typedef struct {
    /* seconds: the whole run; kernel tables, spectra and plans of the operator; the contact solve
     * (with its coarse-grid start and the plans it makes for the contact's box); the stress stage */
    double total_s, setup_s, contact_s, stress_s;
    /* of these, seconds in MPI communication on this process (core/dist.h; 0 serially): printed
     * by the MPI executable, not written to summary.json (the same file as a serial run's) */
    double comm_s;
    /* the contact stage's CPU seconds on this process, and those in MPI communication (the
     * work a rank did, which the machine's load does not inflate); printed by the MPI
     * executable only */
    double contact_cpu_s, contact_comm_cpu_s;
} mc_timing;

/* A warning a user can act on (pipeline/warnings.h): a stable code and one line of text. */
#define MC_WARNINGS_MAX 8
typedef struct {
    const char *code; /* static: "contact_at_edge", "contact_ratio_high", ... */
    char message[640];
} mc_warning;

typedef struct {
    mc_grid grid;
    /* surface fields, ny*nx each (owned) */
    double *topography;   /* initial gap h (shape minus roughness), m */
    double *pressure;     /* Pa */
    double *gap;          /* h + u - approach, m */
    double *displacement; /* combined elastic normal displacement, positive into the bodies, m */
    mc_contact_summary contact;

    /* stress stage (NULL / 0 when not run): layers*ny*nx volumes, component order of kernel.h */
    int nlayers;
    double *depths;              /* nlayers, m */
    double *stress[6];           /* xx, yy, zz, xy, yz, xz; Pa */
    double *von_mises, *hydrostatic, *tresca;
    mc_stage_stress_summary stress_summary;
    mc_stage_stress_layout stress_layout;

    mc_stage_lube_summary lube;
    double *lube_profile; /* ny*nx: the whole contact's lubricant pressure profile w (lube/
                             volume.h), NULL for a patch (stage_lube.h mc_stage_lube_profile) */

    /* elastic-plastic stage (NULL / 0 when not run) */
    mc_stage_plastic_summary plastic;
    double *residual_displacement; /* ny*nx, m, positive into the body */
    double *topography_final;      /* ny*nx, m: the unloaded gap the next load sees */
    double *plastic_strain;        /* nz*ny*nx accumulated equivalent plastic strain */
    double *residual_von_mises;    /* nz*ny*nx von Mises of the residual stress, Pa */

    /* ISO roughness parameters of the roughness heights (not the shape) before the run */
    int has_roughness;
    mc_roughness_params roughness_initial;
    long surface_missing, surface_filled; /* [roughness] file: points not measured, filled */
    char surface_format[16];              /* [roughness] file: the format read */

    /* running-in (NULL / 0 when not run): the composite surface heights (m, up towards the
     * counter body, ny*nx) before and after; the ISO parameters of the final surface (also of
     * the elastic-plastic stage: of shape - topography_final, pipeline.c) */
    mc_runin_summary runin;
    double *surface_initial, *surface_final;
    int has_roughness_final;
    mc_roughness_params roughness_final;

    /* two surfaces ([roughness2], pipeline/bodies.h; NULL / 0 without): index 0 body 1, 1 body 2.
     * Each body's roughness heights, outward towards the other body (m, ny*nx), before, and
     * where the results hold a final surface (elastic-plastic stage, running-in) after: the
     * initial heights minus the body's own residual dent; their ISO parameters (the options of
     * roughness_initial, each with its own section's cutoff); what each file held */
    int two_bodies;
    double *body_initial[2], *body_final[2];
    mc_roughness_params body_roughness_initial[2], body_roughness_final[2];
    int body_has_final;
    int body_dents[2]; /* the body takes the residual displacement (body 1 with [plasticity],
                          body 2 with bodies = both) */
    mc_surface_file_info body_file[2];

    mc_timing timing;
    unsigned long long roughness_seed;

    /* warnings of a solve that succeeded (pipeline/warnings.h); summary.json "warnings" */
    int nwarnings;
    mc_warning warnings[MC_WARNINGS_MAX];
} mc_results;

/* Free every owned array and zero the struct (safe on a zeroed or half-filled struct). */
void mc_results_free(mc_results *r);

/* The stress members (nlayers, depths, stress, von_mises, hydrostatic, tresca, stress_summary,
 * stress_layout): free and zero them in r; or move them from `from` into `to`, replacing (and
 * freeing) what `to` held, and leaving them zero in `from`. */
void mc_results_free_stress(mc_results *r);
void mc_results_move_stress(mc_results *to, mc_results *from);

#endif
