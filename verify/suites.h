/* suites.h - the suite entry points (one file each in verify/). */
#ifndef MC_VERIFY_SUITES_H
#define MC_VERIFY_SUITES_H

#include "harness.h"

int vf_suite_hertz_point(vf_ctx *ctx, int fast);
int vf_suite_hertz_line(vf_ctx *ctx, int fast);

#endif
