/* signals.c - SIGINT, SIGTERM and SIGHUP during `microcontact run` (see cli.h).
 *
 * A handler may only do async-signal-safe work, and with OpenMP and FFTW threads a
 * process-directed signal may land on any thread. So the signals are blocked everywhere and a
 * watcher thread takes them with sigwait(), in ordinary thread context. */
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stddef.h>
#include <unistd.h>

#include "cli/cli.h"
#include "pipeline/output.h"

static sigset_t watched;
static atomic_int caught;

_Noreturn void mc_cli_signal_exit(int sig)
{
    /* die of the signal itself, so that a calling shell script stops as after Ctrl-C */
    signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    pthread_sigmask(SIG_UNBLOCK, &one, NULL);
    raise(sig);
    _exit(128 + sig);
}

static void *watch(void *arg)
{
    (void)arg;
    for (;;) {
        int sig;
        if (sigwait(&watched, &sig) != 0)
            continue;
        /* a second signal, or nothing being written: end now; else the commit stops itself */
        if (atomic_exchange(&caught, sig) != 0 || !mc_output_interrupt(1))
            mc_cli_signal_exit(sig);
    }
    return NULL;
}

int mc_cli_signals_start(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    sigemptyset(&watched);
    int n = 0;
    for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++) {
        struct sigaction old;
        if (sigaction(sigs[k], NULL, &old) == 0 && !(old.sa_flags & SA_SIGINFO) &&
            old.sa_handler == SIG_IGN)
            continue; /* ignored by whoever started us: keep it so */
        sigaddset(&watched, sigs[k]);
        n++;
    }
    if (n == 0)
        return 0;
    if (pthread_sigmask(SIG_BLOCK, &watched, NULL) != 0)
        return -1;
    pthread_attr_t attr;
    pthread_t t;
    int ok = 0;
    if (pthread_attr_init(&attr) == 0) {
        ok = pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED) == 0 &&
             pthread_create(&t, &attr, watch, NULL) == 0;
        pthread_attr_destroy(&attr);
    }
    if (!ok) {
        pthread_sigmask(SIG_UNBLOCK, &watched, NULL);
        return -1;
    }
    return 0;
}

int mc_cli_signal_caught(void)
{
    return atomic_load(&caught);
}
