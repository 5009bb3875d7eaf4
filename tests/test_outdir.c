/* test_outdir.c - the output directory of a run (outdir.c, output.c): nothing created before
 * the commit nor left after a failed one, one run per directory (flock), stale staging areas
 * swept without touching the user's files, interruption, the exit-code classes (error.c). */
#include <check.h>
#include <dirent.h>
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/alloc.h"
#include "kernels/kernel.h"
#include "pipeline/output.h"
#include "pipeline/results.h"
#include "test_util.h"

enum { NX = 24, NY = 16, NL = 8 };

/* ---- fixtures ----------------------------------------------------------------------------- */

static void make_results(mc_results *r, int nlayers)
{
    memset(r, 0, sizeof *r);
    mc_grid g = {NX, NY, 1e-6, 1e-6, 0, 0};
    r->grid = g;
    size_t n = NX * NY;
    double **f[] = {&r->topography, &r->pressure, &r->gap, &r->displacement};
    for (int k = 0; k < 4; k++) {
        *f[k] = mc_zeros(n);
        ck_assert_ptr_nonnull(*f[k]);
        test_random_field(*f[k], n, 7 + (unsigned long long)k);
    }
    r->contact.solver = "cg";
    if (nlayers == 0)
        return;
    r->nlayers = nlayers;
    r->depths = mc_zeros((size_t)nlayers);
    for (int k = 0; k < nlayers; k++)
        r->depths[k] = 1e-6 * (k + 1);
    double **v[] = {&r->von_mises, &r->hydrostatic, &r->tresca};
    for (int k = 0; k < 3; k++)
        *v[k] = mc_zeros(n * (size_t)nlayers);
    for (int s = 0; s < MC_NSTRESS; s++)
        r->stress[s] = mc_zeros(n * (size_t)nlayers);
}

static void make_scene(mc_scene *s)
{
    memset(s, 0, sizeof *s);
    snprintf(s->path, sizeof s->path, "case.ini");
    s->body1.E = s->body2.E = 210e9;
    s->body1.nu = s->body2.nu = 0.3;
    s->load.kind = MC_LOAD_FORCE;
    s->load.value = 1.0;
    s->output.vtk = 1;
}

static char *path_in(const char *dir, const char *name)
{
    static char p[8][1024];
    static int k;
    k = (k + 1) % 8;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static int exists(const char *path)
{
    struct stat sb;
    return lstat(path, &sb) == 0;
}

static void touch(const char *path)
{
    FILE *f = fopen(path, "w");
    ck_assert_msg(f != NULL, "%s", path);
    fputs("x\n", f);
    fclose(f);
}

/* Every name under dir, recursively, with the size of each file: any change shows. */
static void tree(const char *dir, const char *rel, char *out, size_t len)
{
    struct dirent **e;
    int n = scandir(dir, &e, NULL, alphasort);
    if (n < 0)
        return;
    for (int k = 0; k < n; k++) {
        const char *nm = e[k]->d_name;
        if (strcmp(nm, ".") && strcmp(nm, "..")) {
            char p[1024], r[1024];
            struct stat sb;
            snprintf(p, sizeof p, "%s/%s", dir, nm);
            snprintf(r, sizeof r, "%s%s", rel, nm);
            lstat(p, &sb);
            size_t used = strlen(out);
            snprintf(out + used, len - used, "%s %lld\n", r, (long long)sb.st_size);
            if (S_ISDIR(sb.st_mode)) {
                strncat(r, "/", sizeof r - strlen(r) - 1);
                tree(p, r, out, len);
            }
        }
        free(e[k]);
    }
    free(e);
}

static char *snapshot(const char *dir)
{
    char *out = calloc(1, 1 << 16);
    tree(dir, "", out, 1 << 16);
    return out;
}

/* ---- exit codes ---------------------------------------------------------------------------- */

START_TEST(test_exit_codes)
{
    /* issue 15: 0 success, 1 solver failure, 2 bad input, 3 the environment - one class each */
    static const struct {
        mc_status code;
        int exit;
    } want[] = {{MC_OK, 0},           {MC_ERR_NUMERIC, 1}, {MC_NOT_CONVERGED, 1},
                {MC_ERR_INTERNAL, 1}, {MC_ERR_INPUT, 2},   {MC_ERR_IO, 2},
                {MC_ERR_LIMIT, 2},    {MC_ERR_NOMEM, 3},   {MC_ERR_ENV, 3},
                {MC_ERR_INTERRUPTED, 3}};
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        ck_assert_int_eq(mc_status_exit_code(want[k].code), want[k].exit);
        ck_assert_str_ne(mc_status_name(want[k].code), "unknown");
    }
    /* the numbers of the codes that existed before stay */
    ck_assert_int_eq(MC_ERR_IO, 2);
    ck_assert_int_eq(MC_ERR_NOMEM, 3);
    ck_assert_int_eq(MC_ERR_INTERNAL, 7);
}
END_TEST

/* ---- nothing created before the commit, nothing left after a failed one --------------------- */

START_TEST(test_created_on_commit)
{
    const char *tmp = test_tmpdir();
    char dir[600];
    snprintf(dir, sizeof dir, "%s/a/b//c/", tmp);
    mc_error err = {0};
    ck_assert_msg(mc_output_prepare(dir, &err) == MC_OK, "%s", err.msg);
    mc_outdir od;
    ck_assert_msg(mc_output_open(&od, dir, &err) == MC_OK, "%s", err.msg);
    ck_assert_msg(!exists(path_in(tmp, "a")), "open created the directory");
    ck_assert_int_eq(od.fd, -1); /* nothing to lock yet */

    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s);
    ck_assert_msg(mc_output_commit(&od, &s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(od.fd >= 0); /* the commit locked what it created */
    mc_output_close(&od);
    ck_assert(exists(path_in(tmp, "a/b/c/summary.json")));
    ck_assert(exists(path_in(tmp, "a/b/c/pressure.npy")));
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

START_TEST(test_rollback_on_failure)
{
    /* Every injected allocation failure during a commit into a new nested directory leaves the
     * parent exactly as it was: the directories the commit created are removed again. */
    const char *tmp = test_tmpdir();
    char dir[600];
    snprintf(dir, sizeof dir, "%s/x/y", tmp);
    mc_results r;
    mc_scene s;
    make_results(&r, 2);
    make_scene(&s);
    int failures = 0;
    for (long n = 1;; n++) {
        mc_error e = {0};
        mc_alloc_fail_at(n);
        int st = mc_output_write(dir, &s, &r, &e);
        mc_alloc_fail_at(0);
        if (st == MC_OK)
            break;
        failures++;
        ck_assert_msg(st == MC_ERR_NOMEM, "n = %ld: %s", n, e.msg);
        ck_assert_msg(!exists(path_in(tmp, "x")), "n = %ld left %s/x", n, tmp);
        ck_assert_int_lt(n, 100000);
    }
    ck_assert_int_gt(failures, 0);
    ck_assert(exists(path_in(dir, "summary.json")));
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

/* Run one write in a child whose file size limit makes every write beyond `limit` bytes fail
 * with EFBIG (SIGXFSZ ignored), as a full disk fails with ENOSPC. Returns the status code. */
static int write_limited(const char *dir, rlim_t limit, char *msg, size_t msglen)
{
    int pipefd[2];
    ck_assert_int_eq(pipe(pipefd), 0);
    pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        close(pipefd[0]);
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {limit, limit};
        setrlimit(RLIMIT_FSIZE, &rl);
        mc_results r;
        mc_scene s;
        make_results(&r, NL);
        make_scene(&s);
        mc_error e = {0};
        int st = mc_output_write(dir, &s, &r, &e);
        ssize_t w = write(pipefd[1], e.msg, strlen(e.msg));
        (void)w;
        _exit(st);
    }
    close(pipefd[1]);
    ssize_t n = read(pipefd[0], msg, msglen - 1);
    msg[n > 0 ? n : 0] = '\0';
    close(pipefd[0]);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert(WIFEXITED(status));
    return WEXITSTATUS(status);
}

START_TEST(test_disk_full)
{
    /* a write that fails is the environment (exit 3), DIR keeps its earlier set, a new DIR is
     * removed again; a limit of 64 kB passes every file but stress.vtr (9 volumes of 24 kB) */
    const char *tmp = test_tmpdir();
    char dir[600], msg[1024];
    snprintf(dir, sizeof dir, "%s/new/out", tmp);
    ck_assert_int_eq(write_limited(dir, 64 * 1024, msg, sizeof msg), MC_ERR_ENV);
    ck_assert_msg(strstr(msg, "File too large"), "%s", msg);
    ck_assert_msg(!exists(path_in(tmp, "new")), "a failed write left %s/new", tmp);

    snprintf(dir, sizeof dir, "%s/old", tmp);
    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s);
    mc_error err = {0};
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    char *before = snapshot(dir);
    ck_assert_int_eq(write_limited(dir, 64 * 1024, msg, sizeof msg), MC_ERR_ENV);
    char *after = snapshot(dir);
    ck_assert_str_eq(after, before);
    free(before);
    free(after);
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

/* ---- one run per directory ----------------------------------------------------------------- */

START_TEST(test_lock)
{
    const char *tmp = test_tmpdir();
    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s);
    mc_error err = {0};
    /* an existing directory is held from open on: a second run is refused at once, naming the
     * directory and the holder's pid (this process: flock conflicts between descriptors) */
    mc_outdir a;
    ck_assert_int_eq(mc_output_open(&a, tmp, &err), MC_OK);
    ck_assert(a.fd >= 0);
    char *before = snapshot(tmp);
    ck_assert_int_eq(mc_output_write(tmp, &s, &r, &err), MC_ERR_ENV);
    char pid[32];
    snprintf(pid, sizeof pid, "pid %ld", (long)getpid());
    ck_assert_msg(strstr(err.msg, tmp) && strstr(err.msg, "in use by another run") &&
                      strstr(err.msg, pid),
                  "%s", err.msg);
    ck_assert_int_eq(mc_output_prepare(tmp, &err), MC_ERR_ENV);
    char *after = snapshot(tmp);
    ck_assert_str_eq(after, before);
    free(after);
    ck_assert_msg(mc_output_commit(&a, &s, &r, &err) == MC_OK, "%s", err.msg);
    mc_output_close(&a);
    ck_assert_msg(mc_output_write(tmp, &s, &r, &err) == MC_OK, "%s", err.msg);

    /* a directory that does not exist yet is locked by the first commit that creates it */
    char dir[600];
    snprintf(dir, sizeof dir, "%s/fresh", tmp);
    mc_outdir b, c;
    ck_assert_int_eq(mc_output_open(&b, dir, &err), MC_OK);
    ck_assert_int_eq(mc_output_open(&c, dir, &err), MC_OK);
    ck_assert_int_eq(mc_output_commit(&b, &s, &r, &err), MC_OK);
    ck_assert_int_eq(mc_output_commit(&c, &s, &r, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, "in use by another run"), "%s", err.msg);
    ck_assert(exists(path_in(dir, "summary.json"))); /* the refused run removed nothing */
    mc_output_close(&b);
    ck_assert_int_eq(mc_output_commit(&c, &s, &r, &err), MC_OK);
    mc_output_close(&c);
    free(before);
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

/* ---- stale staging areas -------------------------------------------------------------------- */

START_TEST(test_sweep)
{
    const char *dir = test_tmpdir();
    /* ours: a staging area of a killed run and a probe file of an earlier version */
    ck_assert_int_eq(mkdir(path_in(dir, ".staging-Ab3xY9"), 0777), 0);
    touch(path_in(dir, ".staging-Ab3xY9/pressure.npy"));
    touch(path_in(dir, ".staging-Ab3xY9/von_mises.npy.tmp"));
    touch(path_in(dir, ".mc-probe-Qw12Er"));
    /* the user's: names that merely look alike, and a foreign file inside a staging area */
    ck_assert_int_eq(mkdir(path_in(dir, ".staging-user"), 0777), 0);
    ck_assert_int_eq(mkdir(path_in(dir, ".staging-Q1w2E3"), 0777), 0);
    touch(path_in(dir, ".staging-Q1w2E3/notes.txt"));
    touch(path_in(dir, ".staging-Q1w2E3/gap.npy"));
    touch(path_in(dir, ".staging-Zz9Zz9"));
    ck_assert_int_eq(mkdir(path_in(dir, ".staging-Zz9Zz8"), 0777), 0);
    ck_assert_int_eq(symlink("../elsewhere", path_in(dir, ".staging-Ln9Ln9")), 0);
    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s);
    mc_error err = {0};
    ck_assert_msg(mc_output_write(dir, &s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(!exists(path_in(dir, ".staging-Ab3xY9")));
    ck_assert(!exists(path_in(dir, ".mc-probe-Qw12Er")));
    ck_assert(!exists(path_in(dir, ".staging-Zz9Zz8"))); /* an empty one of ours */
    ck_assert(exists(path_in(dir, ".staging-user")));
    ck_assert(exists(path_in(dir, ".staging-Q1w2E3/notes.txt")));
    ck_assert(!exists(path_in(dir, ".staging-Q1w2E3/gap.npy")));
    ck_assert(exists(path_in(dir, ".staging-Zz9Zz9")));
    ck_assert(exists(path_in(dir, ".staging-Ln9Ln9")));
    mc_results_free(&r);
    test_rm_tree(dir);
}
END_TEST

/* ---- interruption --------------------------------------------------------------------------- */

START_TEST(test_interrupt_before)
{
    const char *tmp = test_tmpdir();
    char dir[600];
    snprintf(dir, sizeof dir, "%s/new", tmp);
    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s);
    mc_error err = {0};
    ck_assert_int_eq(mc_output_interrupt(1), 0); /* no commit is running */
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_ERR_INTERRUPTED);
    ck_assert(!exists(dir));
    ck_assert_int_eq(mc_output_write(tmp, &s, &r, &err), MC_ERR_INTERRUPTED);
    char *l = snapshot(tmp);
    ck_assert_str_eq(l, "");
    free(l);
    ck_assert_int_eq(mc_output_interrupt(0), 0);
    ck_assert_int_eq(mc_output_write(dir, &s, &r, &err), MC_OK);
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

static void *interrupter(void *arg)
{
    (void)arg;
    while (!mc_output_interrupt(0)) /* poll (clearing an unset request) until a commit runs */
        ;
    mc_output_interrupt(1);
    return NULL;
}

START_TEST(test_interrupt_during)
{
    /* A request that arrives while a commit runs stops it (or lets it finish if it reached its
     * renames): DIR holds the old set or the complete new one, and no staging area. */
    const char *dir = test_tmpdir();
    mc_results r, old;
    mc_scene s;
    make_results(&old, 0);
    make_results(&r, 200); /* 17 files, 13 MB: the request lands while they are written */
    make_scene(&s);
    mc_error err = {0};
    ck_assert_int_eq(mc_output_write(dir, &s, &old, &err), MC_OK);
    char *before = snapshot(dir);
    int stopped = 0;
    for (int k = 0; k < 20; k++) {
        mc_output_interrupt(0);
        pthread_t t;
        ck_assert_int_eq(pthread_create(&t, NULL, interrupter, NULL), 0);
        int st = mc_output_write(dir, &s, &r, &err);
        pthread_join(t, NULL);
        char *after = snapshot(dir);
        if (st == MC_ERR_INTERRUPTED) {
            stopped++;
            ck_assert_str_eq(after, before);
        } else {
            ck_assert_msg(st == MC_OK, "%s", err.msg);
            ck_assert(exists(path_in(dir, "stress.vtr")));
            ck_assert(!strstr(after, ".staging-"));
            mc_output_interrupt(0);
            ck_assert_int_eq(mc_output_write(dir, &s, &old, &err), MC_OK);
            free(before);
            before = snapshot(dir);
        }
        free(after);
    }
    mc_output_interrupt(0);
    ck_assert_int_gt(stopped, 0); /* at least one of 20 requests came before the renames */
    free(before);
    mc_results_free(&r);
    mc_results_free(&old);
    test_rm_tree(dir);
}
END_TEST

/* ---- symbolic links and non-directories ---------------------------------------------------- */

START_TEST(test_links)
{
    const char *tmp = test_tmpdir();
    mc_error err = {0};
    char link[600], target[600];
    snprintf(link, sizeof link, "%s/out", tmp);
    ck_assert_int_eq(symlink("missing/dir", link), 0);
    ck_assert_int_eq(mc_output_prepare(link, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, "dangling symbolic link") && strstr(err.msg, "missing/dir"),
                  "%s", err.msg);
    char below[700];
    snprintf(below, sizeof below, "%s/sub", link);
    ck_assert_int_eq(mc_output_prepare(below, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, "dangling symbolic link"), "%s", err.msg);
    mc_results r;
    mc_scene s;
    make_results(&r, 0);
    make_scene(&s);
    ck_assert_int_eq(mc_output_write(link, &s, &r, &err), MC_ERR_ENV);
    ck_assert(!exists(path_in(tmp, "missing"))); /* the link's target was not created */
    /* a link to a directory is followed */
    ck_assert_int_eq(unlink(link), 0);
    snprintf(target, sizeof target, "%s/real", tmp);
    ck_assert_int_eq(mkdir(target, 0777), 0);
    ck_assert_int_eq(symlink("real", link), 0);
    ck_assert_msg(mc_output_write(link, &s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(exists(path_in(target, "summary.json")));
    /* a regular file where a directory level is due */
    char file[600], under[700];
    snprintf(file, sizeof file, "%s/file", tmp);
    touch(file);
    snprintf(under, sizeof under, "%s/x", file);
    ck_assert_int_eq(mc_output_prepare(under, &err), MC_ERR_ENV);
    ck_assert_msg(strstr(err.msg, "Not a directory"), "%s", err.msg);
    ck_assert_int_eq(mc_output_prepare(file, &err), MC_ERR_ENV);
    ck_assert_int_eq(mc_output_prepare("", &err), MC_ERR_INPUT);
    mc_results_free(&r);
    test_rm_tree(tmp);
}
END_TEST

Suite *suite_outdir(void);
Suite *suite_outdir(void)
{
    Suite *s = suite_create("outdir");
    TCase *tc = tcase_create("outdir");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_exit_codes);
    tcase_add_test(tc, test_created_on_commit);
    tcase_add_test(tc, test_rollback_on_failure);
    tcase_add_test(tc, test_disk_full);
    tcase_add_test(tc, test_lock);
    tcase_add_test(tc, test_sweep);
    tcase_add_test(tc, test_interrupt_before);
    tcase_add_test(tc, test_interrupt_during);
    tcase_add_test(tc, test_links);
    suite_add_tcase(s, tc);
    return s;
}
