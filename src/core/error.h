/* error.h - the one error path of the library.
 *
 * Every fallible library function returns an int status (MC_OK = 0) and, on failure, fills an
 * mc_error with the same code and a human-readable message. Library code never prints or exits;
 * only the CLI (src/cli/) turns an mc_error into text and an exit status.
 */
#ifndef MC_ERROR_H
#define MC_ERROR_H

#include <stddef.h>

typedef enum {
    MC_OK = 0,            /* success */
    MC_ERR_INPUT = 1,     /* bad input: case file, --set override, array or parameter (exit 2) */
    MC_ERR_IO = 2,        /* an input file could not be read (exit 2) */
    MC_ERR_NOMEM = 3,     /* an allocation failed, or the memory guard refused the scene (exit 3) */
    MC_ERR_LIMIT = 4,     /* the request exceeds what the chosen method supports (exit 2) */
    MC_ERR_NUMERIC = 5,   /* NaN/Inf or a numerical breakdown (exit 1) */
    MC_NOT_CONVERGED = 6, /* a solver stopped without meeting its tolerance (exit 1); a status */
    MC_ERR_INTERNAL = 7,  /* a broken invariant: a bug (exit 1) */
    MC_ERR_ENV = 8,       /* the environment: the output directory cannot be created or written
                           * (permissions, not a directory, disk full), or another run holds it
                           * (exit 3) */
    MC_ERR_INTERRUPTED = 9 /* a signal asked the run to stop; nothing was committed (the CLI
                            * exits 128 + signal; exit 3 when no signal is known) */
} mc_status;

#define MC_ERROR_MSG_MAX 1024

typedef struct {
    mc_status code;             /* MC_OK when no error was raised */
    char msg[MC_ERROR_MSG_MAX]; /* one line, no trailing newline */
} mc_error;

/* Raise an error: fills *err (if not NULL) and returns code. The single breakpoint for errors. */
int mc_fail(mc_error *err, mc_status code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prepend context ("file.ini:12: ") to an already raised message; returns err->code. */
int mc_error_prefix(mc_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

void mc_error_clear(mc_error *err);

/* Short stable name of a status ("input", "io", ...). */
const char *mc_status_name(mc_status code);

/* Exit status the CLI uses for a status, distinct per class:
 *   0  success (MC_OK)
 *   1  solver failure: not converged, numerical breakdown, internal error
 *   2  bad input: case file, --set, data files, limits of a method (MC_ERR_INPUT, MC_ERR_IO,
 *      MC_ERR_LIMIT)
 *   3  the environment: not enough memory (the memory guard or a failed allocation), the output
 *      directory unwritable, not a directory, full, or held by another run (MC_ERR_NOMEM,
 *      MC_ERR_ENV, MC_ERR_INTERRUPTED without a known signal)
 * A run stopped by SIGINT/SIGTERM ends with 128 + signal (the CLI's choice, not a status). */
int mc_status_exit_code(mc_status code);

/* Turn off GSL's aborting error handler (idempotent). Called by every module that uses GSL. */
void mc_gsl_quiet(void);

#endif
