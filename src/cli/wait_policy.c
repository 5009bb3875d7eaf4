/* wait_policy.c - OpenMP worker threads that sleep, not spin, while they wait, in every run
 * started directly (docs/architecture.md "Threads").
 *
 * libgomp reads OMP_WAIT_POLICY once, in its own library constructor, before main: setting it
 * from main is too late. So when the variable is unset the program sets it to passive and
 * executes itself again (same arguments, same open files); a user's explicit value is kept.
 * Why: with spinning waits, two threads on a machine where another process holds one core were
 * 0.73 / 0.90 / 1.8x CONTACT at N = 256 / 512 / 1024 against 3.2 / 5.9 / 8.4x on a quiet
 * machine, 4-6x slower than one thread of its own (measured); sleeping waits cost a few
 * microseconds per barrier on a quiet machine and remove that collapse (bench section threads).
 * If the re-execution fails the run goes on with the runtime's default. */
#define _GNU_SOURCE
#include <stdlib.h>
#include <unistd.h>

#include "cli/cli.h"

void mc_cli_wait_policy(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("MC_NO_REEXEC"))
        return;
    if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0)
        return;
    execv("/proc/self/exe", argv);
    /* not reached unless exec failed: keep going with the default policy of this process */
}
