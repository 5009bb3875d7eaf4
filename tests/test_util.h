/* test_util.h - shared helpers and named tolerance tiers for the unit tests.
 *
 * Tolerances are tiered and named (GSL's TEST_TOL idea): round-off (multiples of machine epsilon
 * times the problem size), solver (what a converged iterative solve recovers), discretisation
 * (derived from the mesh in each test). No bare literals in assertions.
 */
#ifndef MC_TEST_UTIL_H
#define MC_TEST_UTIL_H

#include <check.h>
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define TOL_ROUNDOFF 1e-12 /* dual backends, identities: a few hundred eps on O(1e4) terms */
#define TOL_TIGHT 1e-14    /* closed forms evaluated two ways */

/* Path of the shared physics dossier (reference CSV tables); MC_PHYSICS_DIR overrides. */
const char *test_physics_dir(void);

/* Read a numeric CSV (lines starting with '#' and one header line skipped). Returns rows, fills
 * *cols; data is malloc'ed row-major (caller frees). Fails the test on any error. */
int test_read_csv(const char *name, double **data, int *cols, char header[][32], int max_cols);

/* max |a-b| / max |b| over n values (0/0 -> 0); NaN when any difference is NaN. */
double test_rel_maxdiff(const double *a, const double *b, size_t n);

/* The larger of worst and v, NaN once either is NaN: the running worst error of a check (fmax
 * drops a NaN, and a check fed by it could not fail on one). */
double test_worst(double worst, double v);

/* Replay the fuzz target `name`'s inputs (tests/fuzz/corpus/<name>, then the optional
 * tests/fuzz/regressions/<name>): each file as exactly its bytes on the heap, so that ASan sees a
 * read past the input as libFuzzer would, through one(ctx, in, n), which runs the target (a
 * broken contract aborts: the test errors, naming the file) and says whether the input is
 * accepted. The seed corpus must exist and hold both accepted and refused inputs. */
void test_replay_target(const char *name, int (*one)(void *ctx, const uint8_t *in, size_t n),
                        void *ctx);

/* Remove dir and everything below it (the tests leave no temporary directory behind). */
void test_rm_tree(const char *dir);

/* Deterministic pseudo-random values in [-1, 1) (splitmix64), for property tests. */
void test_random_field(double *f, size_t n, unsigned long long seed);

/* A rough gap of n x n cells into h: test_random_field(seed) smoothed by 4 passes of a periodic
 * binomial filter along x and y (correlation over a few cells; periodic by construction, usable on
 * free grids too), mean removed, scaled to rms sq, negated (gap = - heights). */
void test_smooth_rough_gap(double *h, int n, double sq, unsigned long long seed);

/* A fresh empty temporary directory (mkdtemp); the path is valid until the next call (a static
 * buffer); the directory and its contents are removed when the process that made it exits. */
const char *test_tmpdir(void);

/* The same, but kept after the process exits (a file the user is told to look at). */
const char *test_tmpdir_kept(void);

#endif
