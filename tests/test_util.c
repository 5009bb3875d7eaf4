/* test_util.c - helpers shared by the unit tests (see test_util.h). */
#define _GNU_SOURCE
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <dirent.h>
#include <ftw.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *test_physics_dir(void)
{
    const char *d = getenv("MC_PHYSICS_DIR");
    return d && *d ? d : "tests/data/physics";
}

int test_read_csv(const char *name, double **data, int *cols, char header[][32], int max_cols)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", test_physics_dir(), name);
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "cannot open reference table %s", path);
    char line[8192];
    int ncols = 0, rows = 0, cap = 64;
    double *d = malloc(sizeof(double) * (size_t)cap * (size_t)max_cols);
    ck_assert(d != NULL);
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        if (ncols == 0) { /* header */
            char *save = NULL;
            for (char *tok = strtok_r(line, ",\n", &save); tok && ncols < max_cols;
                 tok = strtok_r(NULL, ",\n", &save)) {
                if (header)
                    snprintf(header[ncols], 32, "%s", tok);
                ncols++;
            }
            continue;
        }
        if (rows == cap) {
            cap *= 2;
            d = realloc(d, sizeof(double) * (size_t)cap * (size_t)max_cols);
            ck_assert(d != NULL);
        }
        char *p = line;
        for (int c = 0; c < ncols; c++) {
            char *end;
            d[(size_t)rows * (size_t)ncols + (size_t)c] = strtod(p, &end);
            ck_assert_msg(end != p, "bad number in %s row %d col %d", path, rows, c);
            p = end;
            if (*p == ',')
                p++;
        }
        rows++;
    }
    fclose(f);
    *cols = ncols;
    *data = d;
    return rows;
}

double test_worst(double worst, double v) { return isnan(worst) || isnan(v) ? NAN : fmax(worst, v); }

double test_rel_maxdiff(const double *a, const double *b, size_t n)
{
    double md = 0, mb = 0;
    for (size_t i = 0; i < n; i++) {
        md = test_worst(md, fabs(a[i] - b[i]));
        mb = test_worst(mb, fabs(b[i]));
    }
    return mb > 0 ? md / mb : md;
}

void test_random_field(double *f, size_t n, unsigned long long seed)
{
    unsigned long long x = seed;
    for (size_t i = 0; i < n; i++) {
        unsigned long long z = (x += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        z ^= z >> 31;
        f[i] = (double)(z >> 11) * 0x1.0p-52 - 1.0;
    }
}

void test_smooth_rough_gap(double *h, int n, double sq, unsigned long long seed)
{
    const size_t nc = (size_t)n * (size_t)n;
    double *z = malloc(nc * sizeof *z), *t = malloc(nc * sizeof *t);
    ck_assert(z && t);
    test_random_field(z, nc, seed);
    for (int pass = 0; pass < 4; pass++) {
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                t[j * n + i] = 0.25 * z[j * n + (i + n - 1) % n] + 0.5 * z[j * n + i] +
                               0.25 * z[j * n + (i + 1) % n];
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                z[j * n + i] = 0.25 * t[((j + n - 1) % n) * n + i] + 0.5 * t[j * n + i] +
                               0.25 * t[((j + 1) % n) * n + i];
    }
    double mean = 0, var = 0;
    for (size_t i = 0; i < nc; i++)
        mean += z[i] / (double)nc;
    for (size_t i = 0; i < nc; i++)
        var += (z[i] - mean) * (z[i] - mean) / (double)nc;
    for (size_t i = 0; i < nc; i++)
        h[i] = -(z[i] - mean) * sq / sqrt(var);
    free(z);
    free(t);
}

/* The directories test_tmpdir made in this process, removed at its exit. Check runs each test
 * in a forked child: a directory belongs to the process that made it (a child inherits the
 * parent's list and handler, and must not remove the parent's directories). */
#define TMPDIRS_MAX 64
static struct {
    char path[64];
    pid_t pid;
} tmpdirs[TMPDIRS_MAX];
static int ntmpdirs;

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    remove(path);
    return 0;
}

static void remove_tmpdirs(void)
{
    for (int k = 0; k < ntmpdirs; k++)
        if (tmpdirs[k].pid == getpid())
            nftw(tmpdirs[k].path, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

const char *test_tmpdir_kept(void)
{
    static char path[64];
    snprintf(path, sizeof path, "/tmp/mc_test_XXXXXX");
    char *r = mkdtemp(path);
    ck_assert_msg(r != NULL, "mkdtemp failed");
    return path;
}

const char *test_tmpdir(void)
{
    static char path[64];
    snprintf(path, sizeof path, "%s", test_tmpdir_kept());
    static int registered;
    if (!registered) {
        registered = atexit(remove_tmpdirs) == 0;
    }
    if (ntmpdirs < TMPDIRS_MAX) {
        snprintf(tmpdirs[ntmpdirs].path, sizeof tmpdirs[ntmpdirs].path, "%s", path);
        tmpdirs[ntmpdirs++].pid = getpid();
    }
    return path;
}

void test_rm_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            char p[1024];
            struct stat sb;
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            if (lstat(p, &sb) == 0 && S_ISDIR(sb.st_mode))
                test_rm_tree(p);
            else
                unlink(p);
        }
        closedir(d);
    }
    rmdir(dir);
}

/* Every file of dir through one; counts accepted and refused inputs. Returns the number of files,
 * -1 if dir does not exist. */
static int replay_dir(const char *dir, int (*one)(void *, const uint8_t *, size_t), void *ctx,
                      int *accepted, int *refused)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        ck_assert_msg(f != NULL, "cannot open %s", path);
        static uint8_t buf[1 << 17];
        size_t n = fread(buf, 1, sizeof buf, f);
        ck_assert_msg(feof(f), "%s: larger than %zu bytes; seeds are small", path, sizeof buf);
        fclose(f);
        uint8_t *in = malloc(n ? n : 1);
        ck_assert_ptr_nonnull(in);
        memcpy(in, buf, n);
        if (one(ctx, in, n))
            (*accepted)++;
        else
            (*refused)++;
        free(in);
        files++;
    }
    closedir(d);
    return files;
}

void test_replay_target(const char *name, int (*one)(void *ctx, const uint8_t *in, size_t n),
                        void *ctx)
{
    char dir[512];
    int accepted = 0, refused = 0;
    snprintf(dir, sizeof dir, "tests/fuzz/corpus/%s", name);
    int seeds = replay_dir(dir, one, ctx, &accepted, &refused);
    ck_assert_msg(seeds > 0, "%s: no seed corpus", dir);
    /* a seed set that is all good or all bad would not exercise both paths */
    ck_assert_msg(accepted > 0 && refused > 0, "%s: %d accepted, %d refused", dir, accepted,
                  refused);
    snprintf(dir, sizeof dir, "tests/fuzz/regressions/%s", name);
    replay_dir(dir, one, ctx, &accepted, &refused); /* optional: absent until a crash is found */
}
