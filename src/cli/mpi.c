/* mpi.c - the MPI front door of bin/microcontact-mpi, a build with -DMC_MPI (README "Running on
 * a cluster"): MPI and FFTW-MPI are started and stopped here, the run's communicator is handed to
 * the numerics (core/dist.h), and only rank 0 speaks (the other ranks' stdout and stderr go to
 * /dev/null: every rank computes the same numbers and meets the same errors). */
#include <signal.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "core/dist.h"
#include "core/error.h"
#include "core/threads.h"
#include "operator/dfft.h"

#ifdef MC_MPI
#include <fftw3-mpi.h>
#include <mpi.h>

/* The threads MPI starts (its progress and PMIx threads) must not take the signals `run` waits
 * for (signals.c): a process-directed SIGINT or SIGTERM landing on one of them would end the
 * process at once (their default action) instead of stopping the running-in at a step boundary.
 * So they are blocked while MPI starts (a thread inherits its creator's mask) and the main
 * thread's mask is restored afterwards. */
static int start(int *argc, char ***argv);

int mc_cli_mpi_start(int *argc, char ***argv)
{
    sigset_t sigs, old;
    sigemptyset(&sigs);
    sigaddset(&sigs, SIGINT);
    sigaddset(&sigs, SIGTERM);
    sigaddset(&sigs, SIGHUP);
    const int masked = pthread_sigmask(SIG_BLOCK, &sigs, &old) == 0;
    int rc = start(argc, argv);
    if (masked)
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc;
}

static int start(int *argc, char ***argv)
{
    int provided;
    /* MPI is called from the main thread only (OpenMP loops never communicate) */
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        fprintf(stderr, "microcontact: error: MPI could not be initialised\n");
        return 3;
    }
    mc_error err = {0};
    if (mc_fftw_prepare(&err) != MC_OK) { /* FFTW's threads before FFTW-MPI */
        fprintf(stderr, "microcontact: error: %s\n", err.msg);
        MPI_Finalize();
        return 3;
    }
    fftw_mpi_init();
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > MC_DIST_MAX_RANKS) { /* the row-split sums' static tables (core/dist.h) */
        fprintf(stderr, "microcontact: error: %d MPI processes: at most %d are supported\n", size,
                MC_DIST_MAX_RANKS);
        fftw_mpi_cleanup();
        MPI_Finalize();
        return 3;
    }
    mc_dist_set(MPI_COMM_WORLD);
    if (mc_dist_rank() != 0) {
        if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
            return mc_cli_mpi_end(3);
    }
    /* MC_TRANSPOSES=fftw: FFTW-MPI's transposes on one machine too (to compare; operator/dfft.h);
     * unset or auto: through shared memory where the ranks share one */
    const char *tr = getenv("MC_TRANSPOSES");
    if (tr && strcmp(tr, "auto") && strcmp(tr, "fftw")) {
        fprintf(stderr, "microcontact: error: MC_TRANSPOSES=%s in the environment: accepted are "
                        "auto (the default: through shared memory when the processes share one "
                        "machine) and fftw (FFTW-MPI's transposes)\n", tr);
        return mc_cli_mpi_end(2);
    }
    mc_dfft_shared_transposes(!(tr && !strcmp(tr, "fftw")));
    return 0;
}

int mc_cli_mpi_end(int status)
{
    mc_dist_set(MPI_COMM_NULL);
    fftw_mpi_cleanup();
    MPI_Finalize();
    return status;
}
#else
int mc_cli_mpi_start(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

int mc_cli_mpi_end(int status) { return status; }
#endif

int mc_cli_mpi_command(const char *cmd)
{
    const int ranks = mc_dist_size();
    if (ranks <= 1 || !strcmp(cmd, "run"))
        return 0;
    fprintf(stderr,
            "microcontact: error: '%s' with %d MPI processes: only 'run' is distributed; run "
            "'%s' with one process (mpirun -np 1, or bin/microcontact)\n",
            cmd, ranks, cmd);
    return 2;
}
