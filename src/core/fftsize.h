/* fftsize.h - transform lengths FFTW handles fast. */
#ifndef MC_FFTSIZE_H
#define MC_FFTSIZE_H

/* Smallest m >= n (n >= 1) whose prime factors are all in {2, 3, 5, 7}. */
int mc_fftsize_good(int n);

#endif
