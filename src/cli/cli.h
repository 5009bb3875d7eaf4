/* cli.h - the commands of the microcontact executable (each returns the process exit status:
 * 0 success, 1 solver failure, 2 bad input or usage, 3 the environment; see main.c). */
#ifndef MC_CLI_H
#define MC_CLI_H

#define MC_USAGE_RUN "usage: microcontact run CASE.ini [--out DIR] [--set section.key=value]..."
#define MC_USAGE_VERIFY "usage: microcontact verify [SUITE... | --all] [--fast] [--bless] [--reports DIR] [--baselines DIR | --no-baselines] [--index] [--list]"
#define MC_USAGE_BENCH "usage: microcontact bench [SECTION...] [--quick] [--reports DIR]"
#define MC_USAGE_KEYS "usage: microcontact keys [SECTION]"
#define MC_USAGE_SURFACE "usage: microcontact surface FILE [--set section.key=value]... [--out DIR]"

/* The exit-status paragraph shared by every --help text. */
#define MC_EXIT_STATUS_HELP                                                                        \
    "exit status: 0 success, 1 solver failure (not converged: results are still written),\n"     \
    "  2 bad input (case file, --set, data files, usage), 3 the environment (not enough memory,\n" \
    "  output directory not writable, not a directory, full or in use by another run),\n"        \
    "  128 + signal when stopped by SIGINT, SIGTERM or SIGHUP\n"

int mc_cli_run(int argc, char **argv);
int mc_cli_verify(int argc, char **argv);
int mc_cli_bench(int argc, char **argv);
int mc_cli_keys(int argc, char **argv);
int mc_cli_surface(int argc, char **argv);

/* 1 when s is -h or --help. */
int mc_cli_is_help(const char *s);

/* SIGINT, SIGTERM and SIGHUP during `run` (signals.c): blocked in every thread and received by a
 * watcher thread. A signal while no result is being written ends the process at once (nothing
 * of this run exists on disk yet: the output directory is created only by the commit); a signal
 * during a commit asks it to stop (mc_output_interrupt), and the run then ends with
 * mc_cli_signal_exit once the partial files are removed. A second signal ends the process at
 * once (the next run removes what it left). Signals ignored at start (nohup, background jobs of
 * a shell) stay ignored. Call before any thread is created. Returns 0, or -1 if the watcher could
 * not be started (signals then keep their default action). */
int mc_cli_signals_start(void);

/* The signal received so far (0 if none). */
int mc_cli_signal_caught(void);

/* End the process by signal sig, as its default action does (the shell shows 128 + sig). */
_Noreturn void mc_cli_signal_exit(int sig);

/* Set OMP_WAIT_POLICY=passive and execute the program again when the variable is unset (its
 * runtime reads it before main; wait_policy.c). Returns only when nothing was done or exec failed. */
void mc_cli_wait_policy(char **argv);

/* The default thread count of the run (thread_default.c): unless OMP_NUM_THREADS is set, the
 * cores this process may use less the other tasks running now (at least 1). Call at the start of
 * main, before any OpenMP region; the case's [solver] threads still decides when given. */
void mc_cli_thread_default(void);
int mc_cli_free_cores(void); /* that count */
/* The thread count of `verify`: every core unless OMP_NUM_THREADS is set (the count its
 * baselines were blessed with; a few results depend on it in the last bits). */
void mc_cli_thread_all(void);
/* The decision, without the machine: the count on procs cores from nsamples samples of the
 * running tasks (running[k] as mc_cli_loadavg_running returns it); the least sample counts,
 * every core when none was readable. */
int mc_cli_free_cores_from(int procs, const int *running, int nsamples);
/* The running tasks of a /proc/loadavg text (its fourth field "running/total"); -1 when malformed. */
int mc_cli_loadavg_running(const char *text);

/* bin/microcontact-mpi (mpi.c; without -DMC_MPI these do nothing and return 0 / status):
 * mc_cli_mpi_start initialises MPI and FFTW-MPI, sets the run's communicator (core/dist.h) and
 * silences the output of every rank but 0 (0, or 3 when MPI cannot start); mc_cli_mpi_end
 * finalises and returns status. mc_cli_mpi_command refuses (message, 2) a command other than
 * run when there is more than one rank, else 0. */
int mc_cli_mpi_start(int *argc, char ***argv);
int mc_cli_mpi_end(int status);
int mc_cli_mpi_command(const char *cmd);

#endif
