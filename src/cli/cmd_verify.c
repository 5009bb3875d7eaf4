/* cmd_verify.c - `microcontact verify [SUITE...] [--fast] [--reports DIR] [--list]` */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "harness.h"

int mc_cli_verify(int argc, char **argv)
{
    const char *reports = "reports";
    char *names[64];
    int nnames = 0, fast = 0, list = 0;
    for (int k = 0; k < argc; k++) {
        if (!strcmp(argv[k], "--fast"))
            fast = 1;
        else if (!strcmp(argv[k], "--list"))
            list = 1;
        else if (!strcmp(argv[k], "--reports") && k + 1 < argc)
            reports = argv[++k];
        else if (argv[k][0] == '-') {
            fprintf(stderr, "microcontact verify: unknown option '%s'\n"
                            "usage: microcontact verify [SUITE...] [--fast] [--reports DIR] [--list]\n",
                    argv[k]);
            return 2;
        } else if (nnames < 64)
            names[nnames++] = argv[k];
    }
    int failures = vf_run(reports, nnames, names, fast, list);
    if (failures < 0)
        return 2;
    if (!list)
        printf("verify: %s (%d failed check%s)\n", failures ? "FAIL" : "PASS", failures,
               failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
