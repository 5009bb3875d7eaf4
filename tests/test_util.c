/* test_util.c - helpers shared by the unit tests (see test_util.h). */
#define _GNU_SOURCE
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

double test_rel_maxdiff(const double *a, const double *b, size_t n)
{
    double md = 0, mb = 0;
    for (size_t i = 0; i < n; i++) {
        double d = fabs(a[i] - b[i]);
        if (d > md)
            md = d;
        if (fabs(b[i]) > mb)
            mb = fabs(b[i]);
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

const char *test_tmpdir(void)
{
    static char path[256];
    snprintf(path, sizeof path, "/tmp/mc_test_XXXXXX");
    char *r = mkdtemp(path);
    ck_assert_msg(r != NULL, "mkdtemp failed");
    return path;
}
