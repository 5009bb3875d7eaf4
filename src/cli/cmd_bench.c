/* cmd_bench.c - `microcontact bench [--quick] [--reports DIR]` */
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "cli/cli.h"
#include "harness.h"

int mc_cli_bench(int argc, char **argv)
{
    const char *reports = "reports";
    int quick = 0;
    for (int k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--quick"))
            quick = 1;
        else if (!strcmp(argv[k], "--reports") && k + 1 < argc)
            reports = argv[++k];
        else {
            fprintf(stderr, "microcontact bench: unknown option '%s'\n"
                            "usage: microcontact bench [--quick] [--reports DIR]\n",
                    argv[k]);
            return 2;
        }
    }
    int failures = vf_run_suite(&mc_bench_suite, reports, quick);
    if (failures < 0)
        return 2;
    printf("bench: %s (%d target%s missed)\n", failures ? "targets missed" : "all targets met",
           failures, failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
