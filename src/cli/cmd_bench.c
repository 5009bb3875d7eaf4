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
        if (mc_cli_is_help(argv[k])) {
            printf("%s\n\nBenchmark report in DIR/bench/report.md (default DIR: reports).\n"
                   "  --quick        smaller scenes\n"
                   "  --reports DIR  where the report goes\n"
                   "exit status: 0 all targets met, 1 a target missed, 2 usage or setup error\n",
                   MC_USAGE_BENCH);
            return 0;
        }
        if (!strcmp(argv[k], "--quick"))
            quick = 1;
        else if (!strcmp(argv[k], "--reports") && k + 1 < argc)
            reports = argv[++k];
        else {
            fprintf(stderr, "microcontact bench: unknown %s '%s'\n%s\n",
                    argv[k][0] == '-' ? "option" : "argument", argv[k], MC_USAGE_BENCH);
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
