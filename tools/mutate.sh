#!/bin/sh
# tools/mutate.sh - mutation testing: apply each small, physically meaningful bug of
# tools/mutations.txt, one at a time, to a scratch copy of the committed tree (HEAD) and run the
# checks there; report per mutation whether it was caught, by which check, and whether only the
# bit-level baseline (a "regression:" drift) saw it.
#
#   tools/mutate.sh [ID...]              all mutations, or the ones named
#   MUTATE_CHECK="make _check" (default) the command run in the scratch copy; faster choices:
#     MUTATE_CHECK="make build/tests/run_tests && CK_DEFAULT_TIMEOUT=600 build/tests/run_tests"
#                                        (unit tests only, ~2 min)
#     MUTATE_CHECK="make all build/tests/run_tests && build/tests/run_tests && \
#                   bin/microcontact verify --fast --baselines verify/baselines --reports r"
#   MUTATE_LIST=FILE                     another mutation list (format: tools/mutations.txt)
#   MUTATE_DIR=DIR                       scratch directory (default: a new /tmp/mc_mutate.XXXXXX;
#                                        kept, with one log per mutation, mutate-<id>.log)
#   MUTATE_JOBS=N                        make -j for the builds (default 2)
# The full list with make _check takes about 20 x 10 minutes on a 2-core machine. Each mutation
# must match its file exactly once: the script stops (exit 2) on a pattern that does not.
# Exit status: 0 every mutation caught, 1 some blind, 2 a bad mutation list or set-up.
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
list=${MUTATE_LIST:-$here/tools/mutations.txt}
check=${MUTATE_CHECK:-make _check}
jobs=${MUTATE_JOBS:-2}
[ -r "$list" ] || { echo "mutate: cannot read $list" >&2; exit 2; }
dir=${MUTATE_DIR:-$(mktemp -d "${TMPDIR:-/tmp}/mc_mutate.XXXXXX")} || exit 2
mkdir -p "$dir/tree" || exit 2

# the scratch copy: the committed tree, and the build directory of this tree when there is one
# (objects newer than the extracted sources: only a mutated file is recompiled)
(cd "$here" && git archive HEAD) | tar -x -C "$dir/tree" || { echo "mutate: git archive failed" >&2; exit 2; }
if [ -d "$here/build" ]; then
    cp -pR "$here/build" "$dir/tree/" 2>/dev/null
    mkdir -p "$dir/tree/bin" && cp -p "$here/bin/microcontact" "$dir/tree/bin/" 2>/dev/null
fi
(cd "$dir/tree" && make --no-print-directory -j"$jobs" all build/tests/run_tests >"$dir/build.log" 2>&1) ||
    { echo "mutate: the unmutated tree does not build (see $dir/build.log)" >&2; exit 2; }

# field k (1-based) of a " @@ "-separated line
field() { printf '%s\n' "$1" | awk -v k="$2" 'BEGIN { FS = " @@ " } { print $k }'; }

# validate the whole list first: every text must occur exactly once in its file
n=0
while IFS= read -r line; do
    case $line in ''|'#'*) continue ;; esac
    id=$(field "$line" 1); file=$(field "$line" 3); old=$(field "$line" 4)
    [ -f "$dir/tree/$file" ] || { echo "mutate: $id: no file $file" >&2; exit 2; }
    c=$(OLD=$old perl -0ne '$n = () = /\Q$ENV{OLD}\E/g; print $n' "$dir/tree/$file")
    [ "$c" = 1 ] || { echo "mutate: $id: the text occurs $c times in $file (must be once): $old" >&2; exit 2; }
    n=$((n + 1))
done < "$list"

caught=0; blind=0; base_only=0; ran=0
printf '%-20s %-11s %-14s %s\n' mutation area result "caught by (first failing checks)"
while IFS= read -r line; do
    case $line in ''|'#'*) continue ;; esac
    id=$(field "$line" 1); area=$(field "$line" 2); file=$(field "$line" 3)
    old=$(field "$line" 4); new=$(field "$line" 5)
    if [ $# -gt 0 ]; then
        want=0; for a in "$@"; do [ "$a" = "$id" ] && want=1; done
        [ $want = 1 ] || continue
    fi
    f="$dir/tree/$file"; log="$dir/mutate-$id.log"
    cp -p "$f" "$dir/pristine" || exit 2
    OLD=$old NEW=$new perl -0pi -e 's/\Q$ENV{OLD}\E/$ENV{NEW}/' "$f"
    if cmp -s "$f" "$dir/pristine"; then echo "mutate: $id: not applied" >&2; exit 2; fi
    (cd "$dir/tree" && make --no-print-directory -j"$jobs" all build/tests/run_tests && sh -c "$check") >"$log" 2>&1
    rc=$?
    cp -p "$dir/pristine" "$f" && touch "$f"  # restored; newer than its object: rebuilt next time
    ran=$((ran + 1))
    # what failed: verification rows (FAIL suite.id), unit tests (file:line:F|E:tcase:test), the
    # case and CLI scripts (FAIL case ...), a build error
    fails=$(grep -E '^FAIL [a-z_]+\.|:[FE]:[A-Za-z_]+:[A-Za-z_0-9]+:|^FAIL case|^FAIL |error:' "$log" |
            sed -E 's/^([^ ]*:[0-9]+:[FE]:[^:]*:[^:]*):.*/\1/; s/^(FAIL [^:]*):.*/\1/' | head -4 | tr '\n' ';')
    if [ $rc = 0 ]; then
        result=blind; blind=$((blind + 1))
    elif grep -q 'error:' "$log" && ! grep -qE '^FAIL|:[FE]:' "$log"; then
        result=build-failed; caught=$((caught + 1))
    elif ! grep -E '^FAIL|:[FE]:' "$log" | grep -qv 'regression: blessed'; then
        result=baseline-only; base_only=$((base_only + 1))
    else
        result=caught; caught=$((caught + 1))
    fi
    printf '%-20s %-11s %-14s %s\n' "$id" "$area" "$result" "${fails:--}"
done < "$list"
echo "mutate: $ran of $n mutations run: $caught caught by a physics or unit check, $base_only by the baseline only, $blind blind (logs: $dir)"
[ $blind = 0 ] && [ $base_only = 0 ]
