/* cmd_verify.c - `microcontact verify [SUITE...] [--fast] [--reports DIR] [--list]`
 *
 * The suites read the dossier's reference tables from $MC_PHYSICS_DIR, else tests/data/physics
 * relative to the working directory (verify/vutil.h). So that verify runs from any directory,
 * when neither is there the tables are looked for above the executable (bin/microcontact and
 * BUILD/bin/microcontact sit below the repository root) and MC_PHYSICS_DIR is set to them; when
 * they are nowhere the command says where it looked and stops (exit 3) before running a suite. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "harness.h"

#define PHYSICS_REL "tests/data/physics"
#define LEVELS_UP 4 /* the executable's directory and the 3 above it are searched */

static int is_dir(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0 && S_ISDIR(sb.st_mode);
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
    if (is_dir(PHYSICS_REL))
        return 0;
    char exe[PATH_MAX], cand[PATH_MAX + sizeof PHYSICS_REL + 1], where[PATH_MAX] = "?";
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        const char *base = strrchr(exe, '/');
        snprintf(where, sizeof where, "%.*s", base ? (int)(base - exe) : 0, exe);
        for (int up = 0; up < LEVELS_UP; up++) {
            char *slash = strrchr(exe, '/');
            if (!slash || slash == exe)
                break;
            *slash = '\0'; /* exe is now the directory one level further up */
            snprintf(cand, sizeof cand, "%s/%s", exe, PHYSICS_REL);
            if (is_dir(cand)) {
                setenv("MC_PHYSICS_DIR", cand, 1);
                return 0;
            }
        }
    }
    fprintf(stderr,
            "microcontact verify: cannot find the reference tables (%s): looked in "
            "$MC_PHYSICS_DIR (not set), in the current directory, in the executable's "
            "directory (%s) and the %d above it; run from the repository root or set "
            "MC_PHYSICS_DIR\n",
            PHYSICS_REL, where, LEVELS_UP - 1);
    return -1;
}

int mc_cli_verify(int argc, char **argv)
{
    const char *reports = "reports";
    char *names[64];
    int nnames = 0, fast = 0, list = 0;
    for (int k = 0; k < argc; k++) {
        if (mc_cli_is_help(argv[k])) {
            printf("%s\n\nRun the verification suites (all by default, or the SUITEs named);\n"
                   "each writes DIR/<suite>/report.md (default DIR: reports).\n"
                   "  --fast         the fast variant of each suite (as in make check)\n"
                   "  --reports DIR  where the reports go\n"
                   "  --list         list the suites\n"
                   "Reference tables: $MC_PHYSICS_DIR, else ./%s, else %s above\n"
                   "the executable.\n"
                   "exit status: 0 every check passed, 1 a check failed, 2 usage, 3 the "
                   "reference tables are missing\n",
                   MC_USAGE_VERIFY, PHYSICS_REL, PHYSICS_REL);
            return 0;
        }
        if (!strcmp(argv[k], "--fast"))
            fast = 1;
        else if (!strcmp(argv[k], "--list"))
            list = 1;
        else if (!strcmp(argv[k], "--reports") && k + 1 < argc)
            reports = argv[++k];
        else if (argv[k][0] == '-') {
            fprintf(stderr, "microcontact verify: unknown or incomplete option '%s'\n%s\n",
                    argv[k], MC_USAGE_VERIFY);
            return 2;
        } else if (nnames < 64)
            names[nnames++] = argv[k];
        else {
            fprintf(stderr, "microcontact verify: more than 64 suites named\n%s\n",
                    MC_USAGE_VERIFY);
            return 2;
        }
    }
    if (!list && locate_physics() != 0)
        return 3;
    int failures = vf_run(reports, nnames, names, fast, list);
    if (failures < 0)
        return 2;
    if (!list)
        printf("verify: %s (%d failed check%s)\n", failures ? "FAIL" : "PASS", failures,
               failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
