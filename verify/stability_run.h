/* stability_run.h - the `stability` suite's runs in forked children (stability_run.c) and the
 * record a child passes back to the suite (stability.c). Private to the suite. */
#ifndef MC_VERIFY_STABILITY_RUN_H
#define MC_VERIFY_STABILITY_RUN_H

/* How a child ended (set by the parent). */
typedef enum {
    ST_DONE = 0, /* the child ran the scene and passed its record back */
    ST_CRASH,    /* killed by a signal other than the time limit */
    ST_TIMEOUT,  /* killed by the time limit (SIGALRM) */
    ST_LOST      /* exited without a complete record (or could not be started) */
} st_outcome;

/* One run's result: plain data, written through a pipe by the child. */
typedef struct {
    int outcome;       /* st_outcome */
    int status;        /* mc_pipeline_run's return */
    char msg[256];     /* its message (error, not converged), or the crash description */
    char measure_msg[160]; /* non-empty when the suite's own measures could not be computed */
    int converged, iterations, capped;
    double residual, load, p_max, contact_ratio, approach;
    double time_s;     /* mc_pipeline_run wall time in the child */
    /* measures from the output arrays (stability.c, measure()) */
    long nonfinite;    /* NaN/Inf count over p, gap, u, h and the summary */
    int force, lub_all;
    double W;          /* force control: the imposed load, N */
    double scale;      /* gap scale s, m */
    double compl;      /* complementarity violation / s on g = h + K p - approach */
    double load_err;   /* |A sum p - W| / W (lub_all: solid load / W) */
    double kkt;        /* max(compl, load_err) */
    double kkt_floor;  /* round-off floor of kkt */
    double bounds;     /* bound violation / p_max */
    double gapid;      /* gap identity and u = K p, relative */
    double summary_err;/* summary load, p_max, area against the arrays, relative */
    long ncontact;     /* cells with p > p_lub */
    int stress_run;    /* the stress stage ran */
    long stress_nonfinite;
    double stress_z0;  /* depth of the first layer */
    double szz_err;    /* max |sigma_zz(z0) + p| / p_max */
} st_record;

typedef struct {
    int scene, combo;  /* indices into the suite's tables */
    int timeout;       /* s */
    double wall_s;     /* fork to reap, s */
    st_record rec;
} st_job;

/* Child side (stability.c): build and run job's scene, fill rec. */
void st_child_run(int scene, int combo, st_record *rec);

/* Run every job in a forked child, up to min(2, online CPUs) at a time, longest time limit first;
 * fills each job's rec and wall_s. Returns the number of concurrent workers used. */
int st_run_jobs(st_job *jobs, int njobs);

#endif
