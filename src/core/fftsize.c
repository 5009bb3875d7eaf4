/* fftsize.c - transform lengths FFTW handles fast (see fftsize.h). */
#include "core/fftsize.h"

static int is_7_smooth(int m)
{
    static const int primes[] = {2, 3, 5, 7};
    for (int k = 0; k < 4; k++)
        while (m % primes[k] == 0)
            m /= primes[k];
    return m == 1;
}

int mc_fftsize_good(int n)
{
    int m = n < 1 ? 1 : n;
    while (!is_7_smooth(m))
        m++;
    return m;
}
