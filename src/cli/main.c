/* main.c - the microcontact command line: the only code that prints and chooses exit codes.
 *
 *   microcontact run CASE.ini [--out DIR] [--set section.key=value]...
 *   microcontact verify [SUITE... | --all] [--fast] [--bless] [--reports DIR] [--list]
 *   microcontact bench [SECTION...] [--quick] [--reports DIR]
 *   microcontact keys [SECTION]
 *   microcontact surface FILE [--set section.key=value]... [--out DIR]
 *   microcontact help | --help | --version
 * Every command takes -h/--help (usage on stdout, exit 0) and refuses arguments it does not
 * know with its usage on stderr (exit 2). Exit statuses: see MC_EXIT_STATUS_HELP in cli.h.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

#define MC_VERSION "0.1.0"

int mc_cli_is_help(const char *s)
{
    return !strcmp(s, "-h") || !strcmp(s, "--help");
}

static void usage(FILE *f)
{
    fprintf(f,
            "microcontact %s - elastic half-space micro-contact (Mevissen et al. 2025)\n\n"
            "usage:\n"
            "  microcontact run CASE.ini [--out DIR] [--set section.key=value]...\n"
            "        solve the scene of CASE.ini; results (summary.json, *.npy, *.csv) go to DIR\n"
            "        (default: [output] dir of the case, else out/<case name>); one run per\n"
            "        output directory at a time\n"
            "  microcontact verify [SUITE... | --all] [--fast] [--bless] [--reports DIR] [--list]\n"
            "        run verification suites (all by default); reports in DIR/<suite>/report.md\n"
            "  microcontact bench [SECTION...] [--quick] [--reports DIR]\n"
            "        benchmark report in DIR/bench/report.md\n"
            "  microcontact keys [SECTION]\n"
            "        print the case-file reference (also in docs/case-format.md), or one section\n"
            "  microcontact surface FILE [--set section.key=value]... [--out DIR]\n"
            "        check a surface file before a run: format, grid, missing points, heights,\n"
            "        roughness parameters; --out writes it levelled as surface.npy and .x3p\n"
            "  microcontact help | --help | --version\n\n"
            "microcontact COMMAND --help describes a command.\n\n"
            "%s\n"
            "case-file reference: docs/case-format.md or `microcontact keys`\n",
            MC_VERSION, MC_EXIT_STATUS_HELP);
}

/* help and --version take no argument */
static int no_arguments(int argc, char **argv)
{
    if (argc <= 2)
        return 0;
    fprintf(stderr, "microcontact %s: unexpected argument '%s'\n\n", argv[1], argv[2]);
    usage(stderr);
    return 2;
}

static int dispatch(int argc, char **argv);

int main(int argc, char **argv)
{
    mc_cli_wait_policy(argv); /* before any OpenMP: may execute the program again */
    int rc = mc_cli_mpi_start(&argc, &argv); /* bin/microcontact-mpi only (mpi.c) */
    if (rc)
        return rc;
    /* after the ranks started: they count as running tasks. verify gates on baselines at the
     * last bits, and FFTW's threaded transforms differ in them on some thread counts
     * (lubricant_bc on 3 threads: docs/architecture.md "Threads"): it runs on every core, as
     * `make bless` did, whatever the load */
    if (argc >= 2 && !strcmp(argv[1], "verify"))
        mc_cli_thread_all();
    else
        mc_cli_thread_default();
    if (argc >= 2 && (rc = mc_cli_mpi_command(argv[1])))
        return mc_cli_mpi_end(rc);
    return mc_cli_mpi_end(dispatch(argc, argv));
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "help") || mc_cli_is_help(cmd)) {
        if (no_arguments(argc, argv))
            return 2;
        usage(stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        if (no_arguments(argc, argv))
            return 2;
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
        return mc_cli_keys(argc - 2, argv + 2);
    if (!strcmp(cmd, "surface"))
        return mc_cli_surface(argc - 2, argv + 2);
    fprintf(stderr, "microcontact: unknown command '%s'\n\n", cmd);
    usage(stderr);
    return 2;
}
