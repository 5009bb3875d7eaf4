/* npy_compare.c - two .npy arrays of the same shape: prints max |a - b| / max |a| and whether
 * they are the same bits; exit 0 when the relative difference is <= TOL, 1 when not (or the shapes
 * differ), 2 when a file cannot be read. For tests/cli/mpi.sh (the distributed run against the
 * serial one).
 *   npy_compare A.npy B.npy TOL */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/npy.h"

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: npy_compare A.npy B.npy TOL\n");
        return 2;
    }
    double *a = NULL, *b = NULL;
    int ra, ca, rb, cb;
    mc_error err = {0};
    if (mc_npy_read(argv[1], &a, &ra, &ca, &err) != MC_OK ||
        mc_npy_read(argv[2], &b, &rb, &cb, &err) != MC_OK) {
        fprintf(stderr, "npy_compare: %s\n", err.msg);
        mc_free(a);
        return 2;
    }
    int rc = 0;
    if (ra != rb || ca != cb) {
        printf("shapes differ: %d x %d against %d x %d\n", ra, ca, rb, cb);
        rc = 1;
    } else {
        const size_t n = (size_t)ra * (size_t)ca;
        double dmax = 0, amax = 0;
        for (size_t i = 0; i < n; i++) {
            dmax = fmax(dmax, fabs(a[i] - b[i]));
            amax = fmax(amax, fabs(a[i]));
        }
        const double rel = amax > 0 ? dmax / amax : dmax;
        const int same = memcmp(a, b, n * sizeof *a) == 0;
        printf("max |a - b| / max |a| = %.3g%s\n", rel, same ? " (the same bits)" : "");
        rc = rel <= atof(argv[3]) ? 0 : 1;
    }
    mc_free(a);
    mc_free(b);
    return rc;
}
