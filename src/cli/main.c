/* main.c - the microcontact command line: the only code that prints and chooses exit codes.
 *
 *   microcontact run CASE.ini [--out DIR] [--set section.key=value]...
 *   microcontact verify [SUITE...] [--fast] [--reports DIR] [--list]
 *   microcontact bench [--quick] [--reports DIR]
 *   microcontact keys        the case-file reference (Markdown)
 *   microcontact help | --help | --version
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "case/case.h"
#include "cli/cli.h"

#define MC_VERSION "0.1.0"

static void usage(FILE *f)
{
    fprintf(f,
            "microcontact %s - elastic half-space micro-contact (Mevissen et al. 2025)\n\n"
            "usage:\n"
            "  microcontact run CASE.ini [--out DIR] [--set section.key=value]...\n"
            "        solve the scene of CASE.ini; results (summary.json, *.npy, *.csv) go to DIR\n"
            "        (default: [output] dir of the case, else out/<case name>)\n"
            "  microcontact verify [SUITE...] [--fast] [--reports DIR] [--list]\n"
            "        run verification suites (all by default); reports in DIR/<suite>/report.md\n"
            "  microcontact bench [--quick] [--reports DIR]\n"
            "        benchmark report in DIR/bench/report.md\n"
            "  microcontact keys\n"
            "        print the case-file reference (also in docs/case-format.md)\n"
            "  microcontact help | --help | --version\n\n"
            "exit status: 0 success, 1 solver failure (e.g. not converged), 2 bad input\n"
            "case-file reference: docs/case-format.md or `microcontact keys`\n",
            MC_VERSION);
}

static int cmd_keys(void)
{
    char *md = mc_case_reference_markdown();
    if (!md) {
        fprintf(stderr, "microcontact: out of memory\n");
        return 1;
    }
    fputs(md, stdout);
    mc_free(md);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        printf("microcontact %s\n", MC_VERSION);
        return 0;
    }
    if (!strcmp(cmd, "run"))
        return mc_cli_run(argc - 2, argv + 2);
    if (!strcmp(cmd, "verify"))
        return mc_cli_verify(argc - 2, argv + 2);
    if (!strcmp(cmd, "bench"))
        return mc_cli_bench(argc - 2, argv + 2);
    if (!strcmp(cmd, "keys"))
        return cmd_keys();
    fprintf(stderr, "microcontact: unknown command '%s'\n\n", cmd);
    usage(stderr);
    return 2;
}
