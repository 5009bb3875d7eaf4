/* cmd_verify.c - `microcontact verify [SUITE... | --all] [--fast] [--bless] [--reports DIR]
 *                 [--baselines DIR | --no-baselines] [--index] [--list]`
 *
 * The suites read the dossier's reference tables from $MC_PHYSICS_DIR, else tests/data/physics
 * relative to the working directory (verify/vutil.h). So that verify runs from any directory,
 * when neither is there the tables are looked for above the executable (bin/microcontact and
 * BUILD/bin/microcontact sit below the repository root) and MC_PHYSICS_DIR is set to them; when
 * they are nowhere the command says where it looked and stops (exit 3) before running a suite.
 *
 * The regression gate's baselines (verify/baseline.h) are found the same way: --baselines DIR,
 * else $MC_BASELINES_DIR, else verify/baselines in the working directory or above the
 * executable. Without them (or with --no-baselines) the run is not gated (said once); --bless
 * needs them (exit 3).
 * After the suites, DIR/index.md (the suite table and the paper-figure gallery,
 * verify/gallery.h) is rewritten from the reports found in DIR. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "gallery.h"
#include "harness.h"

#define PHYSICS_REL "tests/data/physics"
#define BASELINES_REL "verify/baselines"
#define LEVELS_UP 4 /* the executable's directory and the 3 above it are searched */

static int is_dir(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0 && S_ISDIR(sb.st_mode);
}

/* rel in the working directory, else in the executable's directory or the LEVELS_UP - 1 above
 * it: 0 with the path in out, else -1 with the executable's directory in where. */
static int find_up(const char *rel, char *out, size_t len, char *where, size_t wlen)
{
    if (is_dir(rel)) {
        snprintf(out, len, "%s", rel);
        return 0;
    }
    char exe[PATH_MAX];
    snprintf(where, wlen, "?");
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return -1;
    exe[n] = '\0';
    const char *base = strrchr(exe, '/');
    snprintf(where, wlen, "%.*s", base ? (int)(base - exe) : 0, exe);
    for (int up = 0; up < LEVELS_UP; up++) {
        char *slash = strrchr(exe, '/');
        if (!slash || slash == exe)
            break;
        *slash = '\0'; /* exe is now the directory one level further up */
        int w = snprintf(out, len, "%s/%s", exe, rel);
        if (w > 0 && (size_t)w < len && is_dir(out))
            return 0;
    }
    return -1;
}

/* 0 when the tables are found (MC_PHYSICS_DIR set if needed), else -1 with the message. */
static int locate_physics(void)
{
    const char *env = getenv("MC_PHYSICS_DIR");
    if (env && *env) {
        if (is_dir(env))
            return 0;
        fprintf(stderr, "microcontact verify: MC_PHYSICS_DIR=%s is not a directory (it should "
                        "hold the reference tables, e.g. hertz_point_axis.csv)\n",
                env);
        return -1;
    }
    char found[PATH_MAX + 64], where[PATH_MAX];
    if (find_up(PHYSICS_REL, found, sizeof found, where, sizeof where) == 0) {
        if (strcmp(found, PHYSICS_REL) != 0)
            setenv("MC_PHYSICS_DIR", found, 1);
        return 0;
    }
    fprintf(stderr,
            "microcontact verify: cannot find the reference tables (%s): looked in "
            "$MC_PHYSICS_DIR (not set), in the current directory, in the executable's "
            "directory (%s) and the %d above it; run from the repository root or set "
            "MC_PHYSICS_DIR\n",
            PHYSICS_REL, where, LEVELS_UP - 1);
    return -1;
}

/* The baselines directory into out: 0 found, 1 not found (message in msg), -1 an explicit
 * directory (option or environment) that does not exist. */
static int locate_baselines(const char *opt, char *out, size_t len, char *msg, size_t mlen)
{
    const char *env = getenv("MC_BASELINES_DIR");
    const char *given = opt ? opt : env && *env ? env : NULL;
    if (given) {
        snprintf(out, len, "%s", given);
        if (is_dir(given))
            return 0;
        snprintf(msg, mlen, "%s %s is not a directory", opt ? "--baselines" : "MC_BASELINES_DIR",
                 given);
        return -1;
    }
    char where[PATH_MAX];
    if (find_up(BASELINES_REL, out, len, where, sizeof where) == 0)
        return 0;
    snprintf(msg, mlen,
             "no baselines: looked for %s in the current directory, in the executable's "
             "directory (%s) and the %d above it, and $MC_BASELINES_DIR is not set",
             BASELINES_REL, where, LEVELS_UP - 1);
    return 1;
}

static void help(void)
{
    printf("%s\n\nRun the verification suites (all by default, or the SUITEs named);\n"
           "each writes DIR/<suite>/report.md, its data and figures (default DIR: reports),\n"
           "and DIR/index.md lists every suite found in DIR with the paper-figure gallery.\n"
           "  --all            every suite (the same as naming none; not with SUITE)\n"
           "  --fast           the fast variant of each suite (as in make check)\n"
           "  --reports DIR    where the reports go\n"
           "  --bless          rewrite the baselines of the suites run (SUITE... or --all)\n"
           "                   from this run and print the diff; refused for a suite with a\n"
           "                   failing check. Fast and full variants have separate baselines\n"
           "                   (<suite>.fast.json, <suite>.json)\n"
           "  --baselines DIR  the baselines (default $MC_BASELINES_DIR, else %s in\n"
           "                   the current directory or above the executable)\n"
           "  --no-baselines   no regression gate (e.g. while changing a solver on purpose)\n"
           "  --index          run nothing: rewrite DIR/index.md from the reports in DIR\n"
           "                   (e.g. after redrawing a figure with gnuplot)\n"
           "  --list           list the suites\n"
           "Every gated run compares each check with its blessed value: a drift beyond the\n"
           "check's regression tolerance fails it and names the check, the blessed and the\n"
           "new value; a suite without its baseline file fails (--bless creates it).\n"
           "Reference tables: $MC_PHYSICS_DIR, else ./%s, else %s above\n"
           "the executable.\n"
           "exit status: 0 every check passed, 1 a check failed (or drifted, or a bless was\n"
           "refused), 2 usage or a malformed baseline file, 3 the reference tables, the\n"
           "--baselines directory or the baselines to bless are missing\n",
           MC_USAGE_VERIFY, BASELINES_REL, PHYSICS_REL, PHYSICS_REL);
}

static int usage_error(const char *msg, const char *arg)
{
    fprintf(stderr, "microcontact verify: %s%s%s%s\n%s\n", msg, arg ? " '" : "", arg ? arg : "",
            arg ? "'" : "", MC_USAGE_VERIFY);
    return 2;
}

int mc_cli_verify(int argc, char **argv)
{
    const char *reports = "reports", *baselines_opt = NULL;
    char *names[64];
    int nnames = 0, fast = 0, list = 0, all = 0, bless = 0, no_gate = 0, index_only = 0;
    for (int k = 0; k < argc; k++) {
        if (mc_cli_is_help(argv[k])) {
            help();
            return 0;
        }
        if (!strcmp(argv[k], "--fast"))
            fast = 1;
        else if (!strcmp(argv[k], "--list"))
            list = 1;
        else if (!strcmp(argv[k], "--all"))
            all = 1;
        else if (!strcmp(argv[k], "--bless"))
            bless = 1;
        else if (!strcmp(argv[k], "--no-baselines"))
            no_gate = 1;
        else if (!strcmp(argv[k], "--index"))
            index_only = 1;
        else if (!strcmp(argv[k], "--reports") && k + 1 < argc)
            reports = argv[++k];
        else if (!strcmp(argv[k], "--baselines") && k + 1 < argc)
            baselines_opt = argv[++k];
        else if (argv[k][0] == '-')
            return usage_error("unknown or incomplete option", argv[k]);
        else if (nnames < 64)
            names[nnames++] = argv[k];
        else
            return usage_error("more than 64 suites named", NULL);
    }
    if (all && nnames)
        return usage_error("--all runs every suite: do not name suites with it", NULL);
    if (no_gate && (bless || baselines_opt))
        return usage_error("--no-baselines runs without the regression gate: not with --bless or "
                           "--baselines",
                           NULL);
    if (bless && !all && !nnames)
        return usage_error("--bless rewrites baselines deliberately: name the suites (SUITE...) "
                           "or give --all",
                           NULL);
    if (list)
        return vf_run(reports, 0, NULL, 0, 1);
    char gmsg[512];
    if (index_only) {
        if (nnames || all || bless)
            return usage_error("--index runs no suite: not with SUITE, --all or --bless", NULL);
        if (vf_gallery_write(reports, gmsg, sizeof gmsg) != 0) {
            fprintf(stderr, "microcontact verify: %s\n", gmsg);
            return 3;
        }
        printf("verify: %s/index.md (suite table and figure gallery)\n", reports);
        return 0;
    }
    if (locate_physics() != 0)
        return 3;
    char base[PATH_MAX + 64], msg[PATH_MAX + 256];
    int found = no_gate ? 1 : locate_baselines(baselines_opt, base, sizeof base, msg, sizeof msg);
    if (no_gate)
        snprintf(msg, sizeof msg, "--no-baselines");
    if (found < 0 || (found > 0 && bless)) {
        fprintf(stderr, "microcontact verify: %s%s\n", msg,
                bless ? "; --bless needs the baselines directory (--baselines DIR)" : "");
        return 3;
    }
    if (found > 0)
        printf("verify: %s; the regression gate is off\n", msg);
    vf_options opt = {.reports_dir = reports,
                      .baselines = found == 0 ? base : NULL,
                      .fast = fast,
                      .bless = bless};
    int failures = vf_run_opts(&opt, nnames, names);
    if (failures < 0)
        return 2;
    if (vf_gallery_write(reports, gmsg, sizeof gmsg) != 0) {
        fprintf(stderr, "microcontact verify: %s\n", gmsg);
        failures++;
    } else
        printf("verify: %s/index.md (suite table and figure gallery)\n", reports);
    printf("verify: %s (%d failed check%s)\n", failures ? "FAIL" : "PASS", failures,
           failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
