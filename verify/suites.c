/* suites.c - the registry of verification suites, in report order. */
#include "harness.h"
#include "suites.h"

static const vf_suite all[] = {
    {"hertz_point", "Hertz point contact: sphere on flat (two materials)", vf_suite_hertz_point},
    {"hertz_line", "Hertz line contact: cylinder periodic in y (plane strain)", vf_suite_hertz_line},
};

const vf_suite *vf_suites(int *count)
{
    *count = (int)(sizeof all / sizeof all[0]);
    return all;
}
