/* cmd_bench.c - `microcontact bench [SECTION...] [--quick] [--reports DIR]` */
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "cli/cli.h"
#include "harness.h"

int mc_cli_bench(int argc, char **argv)
{
    const char *reports = "reports";
    int quick = 0;
    static char only[256]; /* the sections named, comma-separated */
    for (int k = 0; k < argc; k++) {
        if (mc_cli_is_help(argv[k])) {
            printf("%s\n\nBenchmark report in DIR/bench/report.md (default DIR: reports).\n"
                   "  SECTION        run only these sections (%s)\n"
                   "  --quick        smaller scenes\n"
                   "  --reports DIR  where the report goes\n"
                   "exit status: 0 all targets met, 1 a target missed, 2 usage or setup error\n",
                   MC_USAGE_BENCH, mc_bench_section_names());
            return 0;
        }
        if (!strcmp(argv[k], "--quick"))
            quick = 1;
        else if (!strcmp(argv[k], "--reports") && k + 1 < argc)
            reports = argv[++k];
        else if (argv[k][0] != '-' && strlen(only) + strlen(argv[k]) + 2 < sizeof only) {
            if (only[0])
                strcat(only, ",");
            strcat(only, argv[k]);
            if (mc_bench_select(argv[k]) != 0) {
                fprintf(stderr, "microcontact bench: unknown section '%s' (sections: %s)\n%s\n",
                        argv[k], mc_bench_section_names(), MC_USAGE_BENCH);
                return 2;
            }
        } else {
            fprintf(stderr, "microcontact bench: unknown %s '%s'\n%s\n",
                    argv[k][0] == '-' ? "option" : "argument", argv[k], MC_USAGE_BENCH);
            return 2;
        }
    }
    if (mc_bench_select(only) != 0)
        return 2;
    int failures = vf_run_suite(&mc_bench_suite, reports, quick);
    if (failures < 0)
        return 2;
    printf("bench: %s (%d target%s missed)\n", failures ? "targets missed" : "all targets met",
           failures, failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
