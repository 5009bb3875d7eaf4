/* error.c - the one error path (see error.h). */
#include "core/error.h"

#include <gsl/gsl_errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int mc_fail(mc_error *err, mc_status code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
    }
    return (int)code;
}

int mc_error_prefix(mc_error *err, const char *fmt, ...)
{
    if (!err)
        return MC_ERR_INTERNAL;
    char head[MC_ERROR_MSG_MAX], old[MC_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    memcpy(old, err->msg, sizeof old);
    if (snprintf(err->msg, sizeof err->msg, "%s%s", head, old) >= (int)sizeof err->msg)
        err->msg[sizeof err->msg - 1] = '\0'; /* truncated: the context head is kept */
    return (int)err->code;
}

void mc_error_clear(mc_error *err)
{
    if (err) {
        err->code = MC_OK;
        err->msg[0] = '\0';
    }
}

const char *mc_status_name(mc_status code)
{
    switch (code) {
    case MC_OK: return "ok";
    case MC_ERR_INPUT: return "input";
    case MC_ERR_IO: return "io";
    case MC_ERR_NOMEM: return "memory";
    case MC_ERR_LIMIT: return "limit";
    case MC_ERR_NUMERIC: return "numeric";
    case MC_NOT_CONVERGED: return "not-converged";
    case MC_ERR_INTERNAL: return "internal";
    case MC_ERR_ENV: return "environment";
    case MC_ERR_INTERRUPTED: return "interrupted";
    }
    return "unknown";
}

int mc_status_exit_code(mc_status code)
{
    switch (code) {
    case MC_OK: return 0;
    case MC_ERR_INPUT:
    case MC_ERR_IO:
    case MC_ERR_LIMIT: return 2;
    case MC_ERR_NOMEM:
    case MC_ERR_ENV:
    case MC_ERR_INTERRUPTED: return 3;
    case MC_ERR_NUMERIC:
    case MC_NOT_CONVERGED:
    case MC_ERR_INTERNAL: return 1;
    }
    return 1;
}

void mc_gsl_quiet(void)
{
    /* GSL's default handler calls abort(); we check every return code instead. */
    static int done;
    if (!done) {
        gsl_set_error_handler_off();
        done = 1;
    }
}
