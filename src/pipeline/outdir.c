/* outdir.c - the output directory: checks, creation on commit, the one-run lock, stale staging
 * areas (see outdir.h). */
#include "pipeline/outdir.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#define RETRIES 3 /* DIR removed or replaced between mkdir, open and flock: try again */

void mc_outdir_init(mc_outdir *d)
{
    memset(d, 0, sizeof *d);
    d->fd = -1;
}

static int set_path(mc_outdir *d, const char *dir, mc_error *err)
{
    if (!dir || !*dir)
        return mc_fail(err, MC_ERR_INPUT, "output directory: empty path");
    if (snprintf(d->path, sizeof d->path, "%s", dir) >= (int)sizeof d->path)
        return mc_fail(err, MC_ERR_INPUT, "output directory '%.64s...': path too long", dir);
    return MC_OK;
}

/* Length of the next prefix of path that names a directory level, after the one of length
 * `after` (0 = the first): ends before each '/' that follows a non-'/', and at the end of path.
 * 0 when there is none. "a//b/" gives "a", "a//b", "a//b/". */
static size_t next_prefix(const char *path, size_t after)
{
    if (after > 0 && path[after] == '\0')
        return 0;
    for (size_t i = after + 1;; i++) {
        if (path[i] == '\0' || (path[i] == '/' && path[i - 1] != '/'))
            return i;
    }
}

/* ---- checks without creating anything ----------------------------------------------------- */

/* stat() of an existing name that may be a symbolic link; names a dangling link. */
static int stat_existing(const char *dir, const char *name, struct stat *sb, mc_error *err)
{
    if (!S_ISLNK(sb->st_mode))
        return MC_OK;
    if (stat(name, sb) == 0)
        return MC_OK;
    int e = errno;
    if (e == ENOENT) {
        char target[512];
        ssize_t n = readlink(name, target, sizeof target - 1);
        target[n > 0 ? n : 0] = '\0';
        return mc_fail(err, MC_ERR_ENV,
                       "output directory '%s': '%s' is a dangling symbolic link (to '%s', which "
                       "does not exist); remove the link or create its target",
                       dir, name, target);
    }
    return mc_fail(err, MC_ERR_ENV, "output directory '%s': cannot follow '%s': %s", dir, name,
                   strerror(e));
}

static int check_dir(const mc_outdir *d, int *exists, mc_error *err)
{
    char buf[MC_OUTDIR_PATH_MAX];
    memcpy(buf, d->path, sizeof buf);
    size_t have = 0; /* length of the deepest existing prefix */
    *exists = 0;
    for (size_t len = next_prefix(d->path, 0); len; len = next_prefix(d->path, len)) {
        char keep = buf[len];
        buf[len] = '\0';
        struct stat sb;
        if (lstat(buf, &sb) != 0) {
            int e = errno;
            if (e == ENOENT)
                break; /* this level and the ones below it are created on commit */
            return mc_fail(err, MC_ERR_ENV, "output directory '%s': cannot create '%s': %s",
                           d->path, buf, strerror(e));
        }
        int st = stat_existing(d->path, buf, &sb, err);
        if (st != MC_OK)
            return st;
        if (!S_ISDIR(sb.st_mode))
            return mc_fail(err, MC_ERR_ENV, "output directory '%s': cannot create '%s': %s",
                           d->path, buf, strerror(ENOTDIR));
        buf[len] = keep;
        have = len;
        *exists = d->path[len] == '\0';
    }
    /* the directory that receives new entries: DIR, or its deepest existing ancestor */
    const char *where = ".";
    if (have > 0) {
        buf[have] = '\0';
        where = buf;
    } else if (d->path[0] == '/')
        where = "/";
    if (faccessat(AT_FDCWD, where, W_OK | X_OK, AT_EACCESS) != 0) {
        int e = errno;
        if (*exists)
            return mc_fail(err, MC_ERR_ENV, "output directory '%s': not writable: %s", d->path,
                           strerror(e));
        return mc_fail(err, MC_ERR_ENV, "output directory '%s': cannot create it in '%s': %s",
                       d->path, where, strerror(e));
    }
    return MC_OK;
}

/* ---- the lock -------------------------------------------------------------------------------- */

/* pid holding a flock on the file of sb (from /proc/locks), or -1. */
static long lock_holder(const struct stat *sb)
{
    FILE *f = fopen("/proc/locks", "r");
    if (!f)
        return -1;
    char line[256];
    long pid = -1;
    while (pid < 0 && fgets(line, sizeof line, f)) {
        /* "1: FLOCK  ADVISORY  WRITE 1234 fe:00:11011045 0 EOF"; waiters carry "->" */
        char type[16];
        long p;
        unsigned int maj, min;
        unsigned long ino;
        if (sscanf(line, "%*d: %15s %*s %*s %ld %x:%x:%lu", type, &p, &maj, &min, &ino) == 5 &&
            strcmp(type, "FLOCK") == 0 && ino == (unsigned long)sb->st_ino &&
            maj == major(sb->st_dev) && min == minor(sb->st_dev))
            pid = p;
    }
    fclose(f);
    return pid;
}

static int same_dir(const mc_outdir *d)
{
    struct stat a, b;
    return fstat(d->fd, &a) == 0 && stat(d->path, &b) == 0 && a.st_dev == b.st_dev &&
           a.st_ino == b.st_ino;
}

enum { LOCK_OK, LOCK_RETRY, LOCK_MISSING, LOCK_FAILED };

/* Open and lock DIR. LOCK_MISSING: DIR does not exist (may_be_missing); LOCK_RETRY: it vanished
 * or was replaced meanwhile. */
static int lock_dir(mc_outdir *d, int may_be_missing, mc_error *err)
{
    int fd = open(d->path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        if (e == ENOENT)
            return may_be_missing ? LOCK_MISSING : LOCK_RETRY;
        mc_fail(err, MC_ERR_ENV, "output directory '%s': cannot open: %s", d->path, strerror(e));
        return LOCK_FAILED;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        if (e == EWOULDBLOCK) {
            struct stat sb;
            long pid = fstat(fd, &sb) == 0 ? lock_holder(&sb) : -1;
            char who[48] = "pid unknown";
            if (pid > 0)
                snprintf(who, sizeof who, "pid %ld", pid);
            close(fd);
            mc_fail(err, MC_ERR_ENV,
                    "output directory '%s' is in use by another run (%s); one run per output "
                    "directory at a time: wait for it to finish or choose another --out",
                    d->path, who);
            return LOCK_FAILED;
        }
        /* no flock on this file system (EINVAL, ENOLCK, EOPNOTSUPP): go on unlocked */
    }
    d->fd = fd;
    if (!same_dir(d)) {
        mc_outdir_release(d);
        return LOCK_RETRY;
    }
    return LOCK_OK;
}

int mc_outdir_open(mc_outdir *d, const char *dir, mc_error *err)
{
    mc_outdir_release(d);
    d->nmade = 0;
    int st = set_path(d, dir, err);
    if (st != MC_OK)
        return st;
    int exists;
    for (int attempt = 0; attempt < RETRIES; attempt++) {
        if ((st = check_dir(d, &exists, err)) != MC_OK)
            return st;
        if (!exists)
            return MC_OK; /* created and locked on commit */
        int l = lock_dir(d, 1, err);
        if (l == LOCK_OK || l == LOCK_MISSING)
            return MC_OK;
        if (l == LOCK_FAILED)
            return MC_ERR_ENV;
    }
    return mc_fail(err, MC_ERR_ENV, "output directory '%s': removed or replaced while it was "
                                    "being locked", d->path);
}

/* ---- creation on commit ---------------------------------------------------------------------- */

static void remove_made(mc_outdir *d)
{
    char buf[MC_OUTDIR_PATH_MAX];
    for (int k = d->nmade - 1; k >= 0; k--) {
        memcpy(buf, d->path, d->made[k]);
        buf[d->made[k]] = '\0';
        if (rmdir(buf) != 0)
            break; /* not empty: someone else's now; so are its parents */
    }
    d->nmade = 0;
}

static int make_dirs(mc_outdir *d, mc_error *err)
{
    char buf[MC_OUTDIR_PATH_MAX];
    memcpy(buf, d->path, sizeof buf);
    for (size_t len = next_prefix(d->path, 0); len; len = next_prefix(d->path, len)) {
        char keep = buf[len];
        buf[len] = '\0';
        int e = 0;
        if (mkdir(buf, 0777) == 0) {
            if (d->nmade < MC_OUTDIR_MAX_MADE)
                d->made[d->nmade++] = len;
        } else {
            e = errno;
            struct stat sb;
            if (e == EEXIST) {
                if (lstat(buf, &sb) != 0) {
                    e = errno;
                } else {
                    int lst = stat_existing(d->path, buf, &sb, err);
                    if (lst != MC_OK) {
                        remove_made(d);
                        return lst;
                    }
                    e = S_ISDIR(sb.st_mode) ? 0 : ENOTDIR;
                }
            }
        }
        if (e) {
            remove_made(d);
            return mc_fail(err, MC_ERR_ENV, "output directory '%s': cannot create '%s': %s",
                           d->path, buf, strerror(e));
        }
        buf[len] = keep;
    }
    return MC_OK;
}

int mc_outdir_acquire(mc_outdir *d, mc_error *err)
{
    if (!d->path[0])
        return mc_fail(err, MC_ERR_INPUT, "output directory: empty path");
    for (int attempt = 0; attempt < RETRIES; attempt++) {
        if (d->fd >= 0) {
            if (same_dir(d))
                return MC_OK;
            mc_outdir_release(d); /* DIR was removed or replaced while the run computed */
        }
        int st = make_dirs(d, err);
        if (st != MC_OK)
            return st;
        int l = lock_dir(d, 0, err);
        if (l == LOCK_OK)
            return MC_OK;
        if (l == LOCK_FAILED) {
            /* what this run created may already hold the other run's files: leave it */
            d->nmade = 0;
            return MC_ERR_ENV;
        }
    }
    remove_made(d);
    return mc_fail(err, MC_ERR_ENV, "output directory '%s': removed or replaced while it was "
                                    "being created", d->path);
}

void mc_outdir_rollback(mc_outdir *d)
{
    if (d->fd >= 0)
        remove_made(d);
}

void mc_outdir_release(mc_outdir *d)
{
    if (d->fd >= 0)
        close(d->fd);
    d->fd = -1;
}

/* ---- stale staging areas --------------------------------------------------------------------- */

/* name is prefix followed by exactly 6 letters or digits (mkdtemp's XXXXXX) */
static int our_temp_name(const char *name, const char *prefix)
{
    size_t n = strlen(prefix);
    if (strncmp(name, prefix, n) != 0 || strlen(name) != n + 6)
        return 0;
    for (size_t k = n; k < n + 6; k++)
        if (!isalnum((unsigned char)name[k]))
            return 0;
    return 1;
}

static int result_name(const char *name, const char *const *names, int n)
{
    for (int k = 0; k < n; k++) {
        size_t len = strlen(names[k]);
        if (strncmp(name, names[k], len) == 0 &&
            (name[len] == '\0' || strcmp(name + len, ".tmp") == 0))
            return 1;
    }
    return 0;
}

static void sweep_stage(const char *stage, const char *const *names, int n)
{
    DIR *s = opendir(stage);
    if (!s)
        return;
    char path[MC_OUTDIR_PATH_MAX];
    struct dirent *e;
    while ((e = readdir(s)) != NULL) {
        struct stat sb;
        if (!result_name(e->d_name, names, n) ||
            snprintf(path, sizeof path, "%s/%s", stage, e->d_name) >= (int)sizeof path)
            continue;
        if (lstat(path, &sb) == 0 && S_ISREG(sb.st_mode))
            unlink(path);
    }
    closedir(s);
    rmdir(stage); /* fails, and keeps the directory, when anything else is in it */
}

void mc_outdir_sweep(const mc_outdir *d, const char *const *names, int n)
{
    if (d->fd < 0)
        return;
    DIR *dir = opendir(d->path);
    if (!dir)
        return;
    char path[MC_OUTDIR_PATH_MAX];
    struct dirent *e;
    while ((e = readdir(dir)) != NULL) {
        int stage = our_temp_name(e->d_name, ".staging-");
        int probe = our_temp_name(e->d_name, ".mc-probe-");
        struct stat sb;
        if ((!stage && !probe) ||
            snprintf(path, sizeof path, "%s/%s", d->path, e->d_name) >= (int)sizeof path ||
            lstat(path, &sb) != 0)
            continue;
        if (stage && S_ISDIR(sb.st_mode))
            sweep_stage(path, names, n);
        else if (probe && S_ISREG(sb.st_mode))
            unlink(path);
    }
    closedir(dir);
}
