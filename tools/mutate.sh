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
#   MUTATE_FOCUS=1                       run only each mutation's focus checks (field 7 of its
#                                        line: unit:<Check suite> and verify:<suite> words; a
#                                        mutation without them runs MUTATE_CHECK): make check
#                                        runs every one of them, so caught here is caught there;
#                                        blind here is then re-run with the whole check
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
if [ -d "$here/build" ] && (cd "$here" && git diff --quiet HEAD -- src tests verify bench tools Makefile); then
    # the build is of HEAD's sources: date the extracted files back so that it is reused
    find "$dir/tree" -type f -exec touch -d '2000-01-01' {} +
    cp -pR "$here/build" "$dir/tree/" 2>/dev/null
    mkdir -p "$dir/tree/bin" && cp -p "$here/bin/microcontact" "$dir/tree/bin/" 2>/dev/null
fi
(cd "$dir/tree" && make --no-print-directory -j"$jobs" all build/tests/run_tests >"$dir/build.log" 2>&1) ||
    { echo "mutate: the unmutated tree does not build (see $dir/build.log)" >&2; exit 2; }

# field k (1-based) of a " @@ "-separated line
field() { printf '%s\n' "$1" | awk -v k="$2" 'BEGIN { FS = " @@ " } { print $k }'; }

# physics_fails LOG: the failures in LOG that are not a drift from the baseline alone. A verify
# row prints "FAIL suite.id: ... (reference R, <kind> E, tolerance T)" and, when it also drifted,
# " - regression: blessed ..."; its check failed when E > T (or E is not a number); an
# information row ("information, not a check") fails only by drifting. Every other failure (a
# unit test, a case or CLI script, a missing row) counts.
physics_fails() {
    grep -E '^FAIL|^MISSING|:[FE]:' "$1" | awk '
        /information, not a check/ { next }
        /^FAIL [a-z_0-9]+\./ && / - regression: / {
            if (match($0, /, (rel\. error|abs\. error|value) [^,]*, tolerance [^)]*\)/)) {
                t = substr($0, RSTART, RLENGTH); sub(/^, (rel\. error|abs\. error|value) /, "", t)
                e = t; sub(/,.*/, "", e); tol = t; sub(/.*tolerance /, "", tol); sub(/\).*/, "", tol)
                if (e ~ /^[-+0-9.eE]+$/ && tol ~ /^[-+0-9.eE]+$/ && e + 0 <= tol + 0) next
            }
        }
        { n++ } END { print n + 0 }'
}

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
    old=$(field "$line" 4); new=$(field "$line" 5); focus=$(field "$line" 7)
    run=$check
    if [ "${MUTATE_FOCUS:-0}" = 1 ] && [ -n "$focus" ]; then
        run=true; vs=""
        for w in $focus; do
            case $w in
            unit:*) run="$run && CK_DEFAULT_TIMEOUT=600 CK_RUN_SUITE=${w#unit:} build/tests/run_tests" ;;
            verify:*) vs="$vs ${w#verify:}" ;;
            *) echo "mutate: $id: focus word '$w' is not unit:<suite> or verify:<suite>" >&2; exit 2 ;;
            esac
        done
        [ -n "$vs" ] && run="$run && bin/microcontact verify --fast --baselines verify/baselines --reports $dir/reports-$id$vs"
    fi
    if [ $# -gt 0 ]; then
        want=0; for a in "$@"; do [ "$a" = "$id" ] && want=1; done
        [ $want = 1 ] || continue
    fi
    f="$dir/tree/$file"; log="$dir/mutate-$id.log"
    cp -p "$f" "$dir/pristine" || exit 2
    OLD=$old NEW=$new perl -0pi -e 's/\Q$ENV{OLD}\E/$ENV{NEW}/' "$f"
    if cmp -s "$f" "$dir/pristine"; then echo "mutate: $id: not applied" >&2; exit 2; fi
    (cd "$dir/tree" && make --no-print-directory -j"$jobs" all build/tests/run_tests && sh -c "$run") < /dev/null >"$log" 2>&1
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
    elif [ "$(physics_fails "$log")" = 0 ]; then
        result=baseline-only; base_only=$((base_only + 1))
    else
        result=caught; caught=$((caught + 1))
    fi
    printf '%-20s %-11s %-14s %s\n' "$id" "$area" "$result" "${fails:--}"
done < "$list"
echo "mutate: $ran of $n mutations run: $caught caught by a physics or unit check, $base_only by the baseline only, $blind blind (logs: $dir)"
[ $blind = 0 ] && [ $base_only = 0 ]
