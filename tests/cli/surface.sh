#!/bin/sh
# surface.sh PROGRAM - `microcontact surface FILE [--set ...] [--out DIR]` end to end.
#
# Rows:
#   - the shipped X3P (cases/data/ground_sample.x3p, 160 x 96 points of 0.8 x 1 um, 4 missing):
#     exit 2 naming the file and the rule without missing = fill; with it exit 0 and the grid,
#     spacings, missing/filled counts and every parameter printed;
#   - its roughness equals roughness.initial of cases/measured.ini's run (the same loading path:
#     Ra and Sq printed by `surface` vs summary.json, to the 6 digits printed);
#   - --out DIR writes surface.npy and surface.x3p whose heights are the same bytes (the .npy
#     payload vs bindata/data.bin of the zip), and both read back through `surface` to the same
#     parameters (detrend = none: nothing changes them);
#   - every bad file of tests/bad_input/surfaces (truncated zip, wrong checksum, missing
#     main.xml, external entities, size mismatch, empty, absurd dimensions): exit 2, nothing on
#     stdout, one line on stderr naming the file, and --out DIR not created;
#   - usage: no file, an unknown option, a --set outside [roughness]/[mesh] or of type/file:
#     exit 2; --help exit 0.
set -u
if [ $# -ne 1 ] || [ ! -x "$1" ]; then
    echo "usage: $0 PROGRAM (the microcontact executable)" >&2
    exit 2
fi
PROG=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
T=$(mktemp -d "${TMPDIR:-/tmp}/mc_surface.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT INT TERM
cd "$ROOT" || exit 2
fail=0
pass() { echo "PASS surface $1"; }
bad() { echo "FAIL surface $1"; fail=1; }

X3P=cases/data/ground_sample.x3p

# ---- the shipped file ------------------------------------------------------------------------
"$PROG" surface "$X3P" > "$T/o" 2> "$T/e"; rc=$?
if [ $rc -eq 2 ] && [ ! -s "$T/o" ] && grep -q "$X3P" "$T/e" && grep -q 'missing = fill' "$T/e" \
   && [ "$(wc -l < "$T/e")" -eq 1 ]; then pass "missing points refused (missing = error)"
else bad "missing points: exit $rc"; cat "$T/e"; fi

"$PROG" surface "$X3P" --set roughness.missing=fill > "$T/good" 2> "$T/e"; rc=$?
if [ $rc -eq 0 ] && [ ! -s "$T/e" ] \
   && grep -q '^  format  *x3p$' "$T/good" \
   && grep -q '^  file grid  *160 x 96 points' "$T/good" \
   && grep -q '^  file spacing  *dx = 0.8 um, dy = 1 um$' "$T/good" \
   && grep -q '^  missing points  *4 of 15360 (filled 4)$' "$T/good" \
   && grep -q '^  heights ' "$T/good" && grep -q '^roughness (' "$T/good"; then
    n=0
    for p in Ra Rq Rz Rp Rv Rt Rsk Rku Rk Rpk Rvk Mr1 Mr2 Sa Sq Sz Sp Sv Ssk Sku Sdq Sdr Sk Spk \
             Svk Smr1 Smr2 lambda_c; do
        grep -q "^  $p  " "$T/good" && n=$((n + 1))
    done
    if [ $n -eq 28 ]; then pass "good X3P: grid, spacing, missing, 28 parameters"
    else bad "good X3P: $n of 28 parameters printed"; fi
else bad "good X3P: exit $rc"; cat "$T/e" "$T/good"; fi

# ---- the same numbers as a run's roughness.initial -----------------------------------------------
"$PROG" run cases/measured.ini --out "$T/run" > /dev/null 2>&1 || bad "cases/measured.ini did not run"
# the [roughness] keys of cases/measured.ini that change the parameters: its cut-off
"$PROG" surface "$X3P" --set roughness.missing=fill --set roughness.cutoff=16um > "$T/same" 2> /dev/null
for p in Ra Sq; do
    want=$(awk -v p="$p" '$1 == p { print $2 }' "$T/same")
    got=$(tr ',{}' '\n\n\n' < "$T/run/summary.json" | awk -v p="\"$p\":" '
        $1 == p && !done { printf "%.6g\n", $2 * 1e6; done = 1 }')
    if [ -n "$want" ] && [ "$want" = "$got" ]; then pass "$p = $want um as the run's roughness.initial"
    else bad "$p: surface prints '$want' um, the run's roughness.initial '$got' um"; fi
done

# ---- --out -------------------------------------------------------------------------------------
"$PROG" surface "$X3P" --set roughness.missing=fill --out "$T/lev/el" > "$T/o" 2> "$T/e"; rc=$?
if [ $rc -eq 0 ] && [ -f "$T/lev/el/surface.npy" ] && [ -f "$T/lev/el/surface.x3p" ] \
   && [ "$(ls -A "$T/lev/el" | wc -l)" -eq 2 ]; then
    bytes=$((160 * 96 * 8))
    tail -c "$bytes" "$T/lev/el/surface.npy" > "$T/npy.bin"
    unzip -p "$T/lev/el/surface.x3p" bindata/data.bin > "$T/x3p.bin"
    if [ "$(wc -c < "$T/x3p.bin")" -eq "$bytes" ] && cmp -s "$T/npy.bin" "$T/x3p.bin"; then
        pass "--out: surface.npy and surface.x3p hold the same heights, byte for byte"
    else bad "--out: the heights of surface.npy and surface.x3p differ"; fi
    "$PROG" surface "$T/lev/el/surface.x3p" --set roughness.detrend=none > "$T/rx" 2> "$T/e" \
        || bad "--out: surface.x3p does not read back: $(cat "$T/e")"
    "$PROG" surface "$T/lev/el/surface.npy" --set roughness.detrend=none --set mesh.dx=0.8um \
        --set mesh.dy=1um > "$T/rn" 2> "$T/e" || bad "--out: surface.npy does not read back: $(cat "$T/e")"
    sed -n '/^roughness/,$p' "$T/good" > "$T/p0"
    sed -n '/^roughness/,$p' "$T/rx" > "$T/p1"
    sed -n '/^roughness/,$p' "$T/rn" > "$T/p2"
    if [ -s "$T/p0" ] && cmp -s "$T/p0" "$T/p1" && cmp -s "$T/p0" "$T/p2" \
       && grep -q '^  missing points  *0 of 15360' "$T/rx"; then
        pass "--out: both files read back to the same parameters"
    else bad "--out: read-back parameters differ"; diff "$T/p0" "$T/p1"; diff "$T/p0" "$T/p2"; fi
else bad "--out: exit $rc"; cat "$T/e"; ls -la "$T/lev/el" 2>&1; fi

# --out keeps the file's x/y offsets: a region that works on the original selects the same points
# of the written file, to the same parameters (before, the writer re-centred on zero)
R="roughness.region=20um, 10um, 60um, 40um"
"$PROG" surface "$X3P" --set roughness.missing=fill --set "$R" --out "$T/reg" > "$T/r0" 2> "$T/e" \
    && "$PROG" surface "$T/reg/surface.x3p" --set "$R" > "$T/r1" 2>> "$T/e" \
    && sed -n '/^roughness/,/^  sampling/p' "$T/r0" > "$T/q0" && sed -n '/^roughness/,/^  sampling/p' "$T/r1" > "$T/q1" \
    && [ -s "$T/q0" ] && cmp -s "$T/q0" "$T/q1" \
    && pass "--out keeps the offsets: the same region reads the written file" \
    || { bad "--out offsets: $(cat "$T/e")"; diff "$T/q0" "$T/q1" 2> /dev/null; }

# ---- bad files -----------------------------------------------------------------------------------
for f in tests/bad_input/surfaces/*; do
    case $f in */good.*) continue ;; esac
    "$PROG" surface "$f" --out "$T/bad/out" > "$T/o" 2> "$T/e"; rc=$?
    if [ $rc -eq 2 ] && [ ! -s "$T/o" ] && [ "$(wc -l < "$T/e")" -eq 1 ] && grep -q "$f" "$T/e" \
       && [ ! -e "$T/bad" ]; then pass "bad file $(basename "$f"): exit 2, named, nothing written"
    else bad "bad file $f: exit $rc, stderr: $(cat "$T/e")"; ls -R "$T/bad" 2>/dev/null; fi
done
"$PROG" surface "$T/absent.x3p" > "$T/o" 2> "$T/e"; rc=$?
if [ $rc -eq 2 ] && grep -q "$T/absent.x3p" "$T/e"; then pass "missing file: exit 2, named"
else bad "missing file: exit $rc"; fi

# a map without lateral scale (the .npy just written) needs the spacing: exit 2 saying how
"$PROG" surface "$T/lev/el/surface.npy" > "$T/o" 2> "$T/e"; rc=$?
if [ $rc -eq 2 ] && grep -q "$T/lev/el/surface.npy" "$T/e" && grep -q 'npy file states no lateral spacing' "$T/e" \
   && grep -q -- '--set mesh.dx=' "$T/e"; then pass "npy without spacing: exit 2, says --set mesh.dx"
else bad "npy without spacing: exit $rc"; cat "$T/e"; fi

# a run's topography.x3p ([output] x3p = yes) is a surface file too
"$PROG" run cases/measured.ini --out "$T/runx" --set output.x3p=yes > /dev/null 2>&1 \
    && "$PROG" surface "$T/runx/topography.x3p" --set roughness.detrend=none > "$T/o" 2> "$T/e" \
    && grep -q '^  file grid  *160 x 96 points' "$T/o" && grep -q '"topography.x3p"' "$T/runx/summary.json" \
    && pass "run with x3p = yes: topography.x3p reads" || { bad "run with x3p = yes"; cat "$T/e"; }

# ---- usage ---------------------------------------------------------------------------------------
usage_row() { # name, then the arguments
    name=$1; shift
    "$PROG" surface "$@" > "$T/o" 2> "$T/e"; rc=$?
    if [ $rc -eq 2 ] && [ ! -s "$T/o" ] && grep -q 'usage: microcontact surface' "$T/e"; then
        pass "usage: $name"
    else bad "usage: $name: exit $rc"; cat "$T/e"; fi
}
usage_row "no file"
usage_row "unknown option" "$X3P" --frobnicate
usage_row "two files" "$X3P" "$X3P"
usage_row "--set outside [roughness]" "$X3P" --set load.force=1
usage_row "--set roughness.file" "$X3P" --set roughness.file=x.npy
"$PROG" surface --help > "$T/o" 2>&1 && grep -q 'usage: microcontact surface' "$T/o" \
    && pass "--help" || bad "--help"
"$PROG" surface "$X3P" --set roughness.missing=fill --set roughness.units=lightyears > "$T/o" 2> "$T/e"
rc=$?
if [ $rc -eq 2 ] && grep -q 'units' "$T/e"; then pass "bad --set value: exit 2 naming the key"
else bad "bad --set value: exit $rc"; cat "$T/e"; fi
exit $fail
