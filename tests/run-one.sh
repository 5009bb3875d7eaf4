#!/bin/sh
# Build the unit tests (make, the library as usual) and run ONE Check suite, or one test case
# (TCase) of it:
#   tests/run-one.sh <suite> [<tcase>]     e.g. tests/run-one.sh roughness core
# <suite> is the name of tests/test_<suite>.c (suite_<suite>() there); the tcase names are the
# tcase_create() names in that file. The same without this script:
#   make build/tests/run_tests && CK_RUN_SUITE=<suite> [CK_RUN_CASE=<tcase>] build/tests/run_tests
# BUILD=<dir> (as for make) selects another build, e.g. BUILD=build/san SAN=1 OPT=-O1.
set -e
[ $# -ge 1 ] || { sed -n '2,9p' "$0" >&2; exit 2; }
b=${BUILD:-build}
make --no-print-directory -j2 BUILD="$b" "$b/tests/run_tests" >/dev/null
CK_RUN_SUITE=$1
export CK_RUN_SUITE
if [ -n "${2:-}" ]; then CK_RUN_CASE=$2; export CK_RUN_CASE; fi
CK_DEFAULT_TIMEOUT=${CK_DEFAULT_TIMEOUT:-600}
export CK_DEFAULT_TIMEOUT
exec "$b/tests/run_tests"
