/* threads.c - the thread count of a run (threads.h). */
#include <fftw3.h>
#include <omp.h>

#include "core/threads.h"

static int n_threads;       /* 0: not set: the OpenMP default (OMP_NUM_THREADS or all cores) */
static int omp_default;     /* omp_get_max_threads() before we first changed it */
static int fftw_threads_on; /* fftw_init_threads has succeeded */

static void apply(int n)
{
    if (!omp_default)
        omp_default = omp_get_max_threads();
    n_threads = n > 0 ? n : 0;
    omp_set_num_threads(mc_threads_count());
}

void mc_threads_begin(int n, mc_threads_scope *scope)
{
    scope->previous = n_threads;
    apply(n);
}

void mc_threads_end(const mc_threads_scope *scope)
{
    apply(scope->previous);
}

int mc_threads_count(void)
{
    if (n_threads > 0)
        return n_threads;
    return omp_default ? omp_default : omp_get_max_threads();
}

int mc_fftw_prepare(mc_error *err)
{
    if (!fftw_threads_on) {
        if (!fftw_init_threads())
            return mc_fail(err, MC_ERR_INTERNAL, "FFTW could not initialise its threads");
        fftw_threads_on = 1;
    }
    fftw_plan_with_nthreads(mc_threads_count());
    return MC_OK;
}
