#!/bin/sh
# Build and run ONE Check suite against an explicit list of library sources, without building the
# whole library (lets several people work on different modules at once).
#   tests/run-one.sh <suite> [src/x.c ...]      e.g. tests/run-one.sh kernel src/kernel.c
# Always links src/error.c and src/alloc.c; suite <name> lives in tests/test_<name>.c.
set -e
name=$1; shift
out=build/one/$name
mkdir -p "$out"
echo "SUITE($name)" > "$out/suites.inc"
${CC:-gcc} -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -O2 -g -fopenmp \
  -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes ${EXTRA_CFLAGS:-} \
  -Isrc -Itests -Iverify -I"$out" tests/run_tests.c tests/test_util.c "tests/test_$name.c" \
  src/error.c src/alloc.c "$@" -o "$out/run" \
  -lcheck_pic -lsubunit -lrt -lpthread -linih -ljansson -lgsl -lgslcblas -lfftw3_omp -lfftw3 -lm
exec "$out/run"
