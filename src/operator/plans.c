/* plans.c - planner rigor of the repeated transforms and stored FFTW wisdom (see operator.h,
 * "planner rigor and stored wisdom").
 *
 * FFTW keeps its wisdom per process, and its estimate planner reuses wisdom of more rigorous
 * plans: a process that measured once would plan differently afterwards. So a scope that
 * measured (or imported) forgets all wisdom at its end, and estimate plans stay the same plan,
 * hence the same round-off, on every run.
 */
#include <fftw3.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/fileguard.h"
#include "core/threads.h"
#include "operator/operator.h"

static mc_plan_rigor rigor = MC_PLANS_ESTIMATE;

unsigned mc_fft_plan_flags(void)
{
    return rigor == MC_PLANS_ESTIMATE ? FFTW_ESTIMATE : FFTW_MEASURE;
}

mc_plan_rigor mc_fft_plan_rigor(void) { return rigor; }

const char *mc_plan_rigor_name(mc_plan_rigor r)
{
    switch (r) {
    case MC_PLANS_ESTIMATE: return "estimate";
    case MC_PLANS_MEASURE: return "measure";
    case MC_PLANS_WISDOM: return "wisdom";
    }
    return "?";
}

int mc_fft_plans_begin(mc_plan_rigor r, const char *wisdom_file, mc_fft_plans_scope *scope,
                       mc_error *err)
{
    memset(scope, 0, sizeof *scope);
    scope->previous = rigor;
    if (r != MC_PLANS_ESTIMATE && r != MC_PLANS_MEASURE && r != MC_PLANS_WISDOM)
        return mc_fail(err, MC_ERR_INPUT, "unknown planner rigor %d (estimate, measure, wisdom)",
                       (int)r);
    if (r == MC_PLANS_WISDOM) {
        if (!wisdom_file || !*wisdom_file)
            return mc_fail(err, MC_ERR_INPUT, "plans = wisdom needs a wisdom_file");
        if (strlen(wisdom_file) >= sizeof scope->file)
            return mc_fail(err, MC_ERR_INPUT, "wisdom_file: path too long");
        /* FFTW's threads first: wisdom imported before fftw_init_threads would not be matched
         * by the threaded planner */
        int rc = mc_fftw_prepare(err);
        if (rc != MC_OK)
            return rc;
        /* FFTW reads the file itself, to its end: a device or FIFO is refused first */
        rc = mc_file_guard(wisdom_file, MC_FILE_MAX_WISDOM, "an FFTW wisdom file", err);
        if (rc != MC_OK)
            return rc;
        if (access(wisdom_file, F_OK) == 0 && !fftw_import_wisdom_from_filename(wisdom_file)) {
            fftw_forget_wisdom(); /* a partial import must not outlive the refusal */
            return mc_fail(err, MC_ERR_INPUT,
                           "%s is not FFTW wisdom (remove it, and the next run stores new "
                           "wisdom there)",
                           wisdom_file);
        }
        strcpy(scope->file, wisdom_file);
    }
    scope->active = r != MC_PLANS_ESTIMATE;
    rigor = r;
    return MC_OK;
}

int mc_fft_plans_end(const mc_fft_plans_scope *scope, mc_error *err)
{
    int rc = MC_OK;
    if (scope->file[0]) { /* atomically: a temporary file beside it, renamed over it */
        char tmp[sizeof scope->file + 32];
        snprintf(tmp, sizeof tmp, "%s.tmp%ld", scope->file, (long)getpid());
        if (!fftw_export_wisdom_to_filename(tmp) || rename(tmp, scope->file) != 0) {
            unlink(tmp);
            rc = mc_fail(err, MC_ERR_ENV, "cannot write the FFTW wisdom to %s", scope->file);
        }
    }
    if (scope->active)
        fftw_forget_wisdom();
    rigor = scope->previous;
    return rc;
}
