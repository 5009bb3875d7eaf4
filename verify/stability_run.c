/* stability_run.c - runs the `stability` suite's jobs in forked children (see stability_run.h).
 *
 * A child runs one scene, writes its fixed-size record into a pipe and leaves with _exit; an
 * alarm bounds its run time. The parent reaps children as they finish: a signal is a crash (or,
 * SIGALRM, a time-out), a short record is a lost run; either becomes a failed check in the suite
 * instead of ending it. The record is far below the pipe's capacity, so a child never blocks on
 * its write and the parent reads it after the reap. */
#include "stability_run.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pipeline/pipeline.h"

#define MAX_WORKERS 2 /* the suite shares a 2-core machine; children run one thread each */

typedef struct {
    pid_t pid;
    int fd, job;
    double t0;
} st_slot;

static void start(st_job *job, int k, st_slot *slot)
{
    int fds[2];
    slot->pid = -1;
    slot->job = k;
    if (pipe(fds) != 0) {
        job->rec.outcome = ST_LOST;
        snprintf(job->rec.msg, sizeof job->rec.msg, "pipe: %s", strerror(errno));
        return;
    }
    fflush(NULL); /* nothing buffered may be written twice */
    slot->t0 = mc_clock();
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        job->rec.outcome = ST_LOST;
        snprintf(job->rec.msg, sizeof job->rec.msg, "fork: %s", strerror(errno));
        return;
    }
    if (pid == 0) {
        close(fds[0]);
        alarm((unsigned)job->timeout);
        st_record rec;
        memset(&rec, 0, sizeof rec);
        rec.outcome = ST_DONE;
        st_child_run(job->scene, job->combo, &rec);
        const char *b = (const char *)&rec;
        size_t left = sizeof rec;
        while (left > 0) {
            ssize_t w = write(fds[1], b, left);
            if (w < 0 && errno == EINTR)
                continue;
            if (w <= 0)
                _exit(3);
            b += w;
            left -= (size_t)w;
        }
        _exit(0);
    }
    close(fds[1]);
    slot->pid = pid;
    slot->fd = fds[0];
}

static void finish(st_job *job, const st_slot *slot, int wstatus)
{
    st_record rec;
    memset(&rec, 0, sizeof rec);
    size_t got = 0;
    while (got < sizeof rec) {
        ssize_t r = read(slot->fd, (char *)&rec + got, sizeof rec - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        got += (size_t)r;
    }
    close(slot->fd);
    job->wall_s = mc_clock() - slot->t0;
    if (WIFSIGNALED(wstatus)) {
        int sig = WTERMSIG(wstatus);
        memset(&job->rec, 0, sizeof job->rec);
        job->rec.outcome = sig == SIGALRM ? ST_TIMEOUT : ST_CRASH;
        if (sig == SIGALRM)
            snprintf(job->rec.msg, sizeof job->rec.msg, "no result within the limit of %d s",
                     job->timeout);
        else
            snprintf(job->rec.msg, sizeof job->rec.msg, "killed by signal %d (%s)", sig,
                     strsignal(sig));
        return;
    }
    if (got != sizeof rec || !WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0) {
        memset(&job->rec, 0, sizeof job->rec);
        job->rec.outcome = ST_LOST;
        snprintf(job->rec.msg, sizeof job->rec.msg,
                 "the child exited with status %d after passing %zu of %zu record bytes",
                 WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1, got, sizeof rec);
        return;
    }
    job->rec = rec;
}

int st_run_jobs(st_job *jobs, int njobs)
{
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    int workers = ncpu >= MAX_WORKERS ? MAX_WORKERS : 1;
    /* longest time limit first, so the long runs overlap the many short ones */
    int *order = malloc((size_t)(njobs > 0 ? njobs : 1) * sizeof *order);
    if (!order)
        return 0;
    int m = 0;
    for (int t = 1 << 30; m < njobs;) {
        int next = 0;
        for (int k = 0; k < njobs; k++) {
            if (jobs[k].timeout == t)
                order[m++] = k;
            else if (jobs[k].timeout < t && jobs[k].timeout > next)
                next = jobs[k].timeout;
        }
        t = next;
        if (t <= 0)
            break;
    }
    for (int k = 0; k < njobs && m < njobs; k++) /* (time limits <= 0: run anyway) */
        if (jobs[k].timeout <= 0)
            order[m++] = k;

    st_slot slot[MAX_WORKERS];
    int running = 0, next = 0;
    while (next < njobs || running > 0) {
        while (running < workers && next < njobs) {
            int k = order[next++];
            start(&jobs[k], k, &slot[running]);
            if (slot[running].pid > 0)
                running++;
        }
        if (running == 0)
            continue;
        int wstatus;
        pid_t pid = waitpid(-1, &wstatus, 0);
        if (pid < 0) {
            if (errno == EINTR)
                continue;
            for (int s = 0; s < running; s++) { /* ECHILD: our children are gone */
                st_job *j = &jobs[slot[s].job];
                close(slot[s].fd);
                memset(&j->rec, 0, sizeof j->rec);
                j->rec.outcome = ST_LOST;
                snprintf(j->rec.msg, sizeof j->rec.msg, "waitpid: %s", strerror(errno));
            }
            running = 0;
            continue;
        }
        for (int s = 0; s < running; s++) {
            if (slot[s].pid != pid)
                continue;
            finish(&jobs[slot[s].job], &slot[s], wstatus);
            slot[s] = slot[--running];
            break;
        }
    }
    free(order);
    return workers;
}
