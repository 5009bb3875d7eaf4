/* baseline.h - the regression gate's blessed values: verify/baselines/<suite>.json (the full
 * variant) and <suite>.fast.json (the fast variant of `make check`), one entry per check id.
 *
 * A baseline holds, per check id, the blessed value and its regression tolerances: a run passes
 * the gate on that id when |new - blessed| <= tol (absolute, in the unit of the quantity). This
 * is separate from the physics tolerance against the reference: a number may move inside its
 * physics tolerance (a solver change, a different stopping point) and the gate still catches it.
 *
 * Two tolerances per entry. "tol" applies on the configuration the baseline was blessed on (the
 * same OpenMP thread count, FFTW build and CPU model, recorded in the file): there the suites
 * repeat bit for bit, so tol is round-off. "tol_other" applies on any other configuration, where
 * FFTW plans (codelets) and the order of threaded sums change the last digits, and an iterative
 * solve may stop one iteration earlier or later.
 *
 * File format (JSON, one line per check so that a re-bless gives a readable git diff):
 *   {"suite": "hertz_point", "variant": "fast", "threads": 2, "fftw": "fftw-3.3.10-...",
 *    "cpu": "...",
 *    "checks": {
 *     "pmax_N10": {"value": 1.234e9, "tol": 1.2e-3, "tol_other": 1.2, "tier": "plan"},
 *     ...}}
 * "value" is null for a non-finite blessed value (it then matches a non-finite new value only);
 * the tolerances are null for a row that is recorded but not gated (tier "none": a run time);
 * a missing "tol_other" means "tol". The tolerances follow from the tier (vf_tier_tol) each time
 * a check is blessed. The tier is the one its suite declares (vf_regress, or the registry's
 * patterns: harness.h vf_suite_tiers), else the one already in the file, else vf_tier_auto's
 * choice; so a tier changed by hand in the file survives re-blessing, and tolerances set by hand
 * survive when the tier is "fixed".
 *
 * Front-end code (like the harness): may allocate with malloc, never prints.
 */
#ifndef MC_VERIFY_BASELINE_H
#define MC_VERIFY_BASELINE_H

#include <stddef.h>

/* Regression tiers; the numbers are in baseline.c, justified there. "same" is the blessing
 * configuration, "other" any other (see above). */
typedef enum {
    VF_TIER_AUTO = 0, /* chosen from the row when it is blessed (vf_tier_auto) */
    VF_TIER_EXACT,    /* counts of violations, flags, cell counts: exact everywhere */
    VF_TIER_ITER,     /* iteration counts: exact on the same configuration, +-1 on another
                       * (its last digits can move the stopping iteration by one) */
    VF_TIER_ROUNDOFF, /* closed forms and serial sums that no FFT or thread touches: round-off
                       * everywhere */
    VF_TIER_PLAN,     /* floating values through FFTs, threaded sums or iterative solves (the
                       * default): round-off on the same configuration, wider on another */
    VF_TIER_NOISE,    /* a value that is itself noise on another configuration: the residual
                       * where an iterative solve stopped, a round-off difference, the
                       * difference of two converged solves; round-off on the same one */
    VF_TIER_NONE,     /* recorded, not gated (run times, machine-dependent values) */
    VF_TIER_FIXED     /* the tolerances in the file were set by hand: a re-bless keeps them */
} vf_tier;

typedef struct {
    char id[64];
    double value;     /* blessed value; NAN when the blessed value was not finite */
    double tol;       /* regression tolerance on the blessing configuration, absolute; NAN: not
                       * gated (tier none) */
    double tol_other; /* on any other configuration */
    vf_tier tier;     /* the tier the tolerances came from */
    int seen;         /* set by the caller when a run produced this id */
} vf_blessed;

/* The configuration a run is on (what makes the suites repeat bit for bit). */
typedef struct {
    int threads;    /* OpenMP threads */
    char fftw[64];  /* FFTW's version string (it names the SIMD codelets compiled in) */
    char cpu[128];  /* CPU model (FFTW picks codelets by what the CPU offers) */
} vf_config;

typedef struct {
    char suite[64];
    int fast;      /* 1: the fast variant */
    vf_config config; /* the configuration it was blessed on */
    int n, cap;
    vf_blessed *v;
} vf_baseline;

/* The configuration of this process: omp_get_max_threads(), fftw_version, the first "model name"
 * of /proc/cpuinfo ("" when unknown). */
void vf_config_current(vf_config *c);

/* 1 when a and b are the same configuration. */
int vf_config_same(const vf_config *a, const vf_config *b);

/* Path of the baseline file of suite in dir: "<dir>/<suite>.json" or "<dir>/<suite>.fast.json".
 * Returns 0, or -1 if it does not fit in len. */
int vf_baseline_path(char *buf, size_t len, const char *dir, const char *suite, int fast);

/* Read a baseline file into *b (zeroed first; free with vf_baseline_free). Returns 0, 1 when the
 * file does not exist (b is empty: the suite is not gated yet), or -1 when it cannot be read or
 * is malformed (message in msg). */
int vf_baseline_load(const char *path, vf_baseline *b, char *msg, size_t msglen);

/* Write b to path (through a temporary file, renamed). Returns 0 or -1 (message in msg). */
int vf_baseline_save(const char *path, const vf_baseline *b, char *msg, size_t msglen);

/* The entry of id, or NULL. hint: the index where it is expected (rows come in the same order
 * from run to run), or -1. */
vf_blessed *vf_baseline_find(vf_baseline *b, const char *id, int hint);

/* Append an entry; returns it, or NULL when out of memory. */
vf_blessed *vf_baseline_add(vf_baseline *b, const char *id, double value, double tol,
                            double tol_other, vf_tier tier);

void vf_baseline_free(vf_baseline *b);

/* Regression tolerance of tier for a blessed value v, on the blessing configuration (other = 0)
 * or another (other = 1). err is the physics tolerance of a check whose value is itself an error
 * that must stay small (VF_MAX, or VF_ABS against 0), in the unit of the value; 0 for a quantity
 * compared with a reference (or an information row): a relative tolerance means nothing for an
 * error near round-off, so such rows get a floor of a fraction of what the physics allows.
 * NAN for VF_TIER_NONE (not gated) and VF_TIER_FIXED (the tolerances are the file's). */
double vf_tier_tol(vf_tier tier, double v, double err, int other);

/* The tier chosen for a row that declares none: EXACT for an integer value (below 2^31) of a row
 * that can hold a count (counts = 1: an information row, or a check that is not relative and
 * whose expected value and tolerance are integers), and among those ITER when the id names
 * iterations ("iter" in its last dot-separated part); PLAN otherwise. (Quantities are not used:
 * descriptions of flags mention iteration counts.) */
vf_tier vf_tier_auto(const char *id, double v, int counts);

const char *vf_tier_name(vf_tier tier);

/* The tier named s ("exact", "iter", ...), or VF_TIER_AUTO for an unknown name. */
vf_tier vf_tier_from_name(const char *s);

/* 1 when value passes the gate of blessed value e->value with the tolerance tol (NAN: not
 * gated, always 1); non-finite values match non-finite blessed values only. */
int vf_blessed_ok(const vf_blessed *e, double tol, double value);

#endif
