#!/bin/sh
# Runs every example case in cases/ (they are documentation: they must keep working): each must
# exit 0, write summary.json, report a converged solve (or a prescribed pressure) and raise no warning.
#   tests/cli/cases.sh PROGRAM
set -u
PROG=$1
T=$(mktemp -d "${TMPDIR:-/tmp}/mc_cases.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT INT TERM
fail=0
for c in cases/*.ini; do
    name=$(basename "$c" .ini)
    if ! "$PROG" run "$c" --out "$T/$name" > "$T/$name.log" 2>&1; then
        echo "FAIL case $c (exit status $?):"; cat "$T/$name.log"; fail=1; continue
    fi
    # a solve must converge; a prescribed pressure claims no convergence (its own state)
    if ! grep -q '"state": "converged"\|"state": "prescribed"' "$T/$name/summary.json"; then
        echo "FAIL case $c: summary.json reports neither a converged solve nor a prescribed pressure"
        fail=1; continue
    fi
    # examples are documentation: they raise no warning (summary.json "warnings", stderr)
    if ! grep -q '"warnings": \[\]' "$T/$name/summary.json" || grep -q '^microcontact: warning:' "$T/$name.log"; then
        echo "FAIL case $c: raises warnings:"; grep '^microcontact: warning:' "$T/$name.log"; fail=1; continue
    fi
    echo "PASS case $c: $(grep -E '^  time' "$T/$name.log" | sed 's/^ *//')"
done
exit $fail
