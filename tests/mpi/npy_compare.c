/* npy_compare.c - two .npy files written by microcontact (float64, C order, any rank): the same
 * header (shape) required; prints max |a - b| / max |a| over the values and whether they are the
 * same bits; exit 0 when the relative difference is <= TOL, 1 when not (or the headers differ),
 * 2 when a file cannot be read. For tests/cli/mpi.sh (the distributed run against the serial one).
 *   npy_compare A.npy B.npy TOL */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The whole file into *buf, its length into *len; the data offset (after the version-1 header:
 * magic, version, little-endian uint16 header length) into *off. 0, or -1 (message printed). */
static int load(const char *path, unsigned char **buf, size_t *len, size_t *off)
{
    FILE *f = fopen(path, "rb");
    if (!f || fseek(f, 0, SEEK_END) != 0) {
        fprintf(stderr, "npy_compare: cannot read %s\n", path);
        if (f)
            fclose(f);
        return -1;
    }
    long n = ftell(f);
    rewind(f);
    *buf = malloc(n > 0 ? (size_t)n : 1);
    if (n < 10 || !*buf || fread(*buf, 1, (size_t)n, f) != (size_t)n ||
        memcmp(*buf, "\223NUMPY\001", 7) != 0) {
        fprintf(stderr, "npy_compare: %s is not a version 1 .npy file\n", path);
        fclose(f);
        return -1;
    }
    fclose(f);
    *len = (size_t)n;
    *off = 10 + (size_t)(*buf)[8] + 256 * (size_t)(*buf)[9];
    int f8 = 0; /* the header (from byte 10) names the dtype */
    for (size_t i = 10; i + 5 <= *off && i + 5 <= *len; i++)
        f8 |= memcmp(*buf + i, "'<f8'", 5) == 0;
    if (*off > *len || (*len - *off) % sizeof(double) != 0 || !f8) {
        fprintf(stderr, "npy_compare: %s: not float64 data\n", path);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: npy_compare A.npy B.npy TOL\n");
        return 2;
    }
    unsigned char *a = NULL, *b = NULL;
    size_t la, lb, oa, ob;
    if (load(argv[1], &a, &la, &oa) || load(argv[2], &b, &lb, &ob)) {
        free(a);
        free(b);
        return 2;
    }
    int rc = 0;
    if (oa != ob || la != lb || memcmp(a, b, oa) != 0) {
        printf("the headers (shapes) differ\n");
        rc = 1;
    } else {
        const size_t n = (la - oa) / sizeof(double);
        double dmax = 0, amax = 0;
        for (size_t i = 0; i < n; i++) {
            double x, y;
            memcpy(&x, a + oa + i * sizeof x, sizeof x);
            memcpy(&y, b + ob + i * sizeof y, sizeof y);
            dmax = fmax(dmax, fabs(x - y));
            amax = fmax(amax, fabs(x));
            if (isnan(x) != isnan(y))
                dmax = INFINITY;
        }
        const double rel = amax > 0 ? dmax / amax : dmax;
        const int same = memcmp(a, b, la) == 0;
        printf("max |a - b| / max |a| = %.3g%s\n", rel, same ? " (the same bits)" : "");
        rc = rel <= atof(argv[3]) ? 0 : 1;
    }
    free(a);
    free(b);
    return rc;
}
