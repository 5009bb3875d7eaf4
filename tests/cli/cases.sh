#!/bin/sh
# Runs every example case in cases/ (they are documentation: they must keep working): each must
# exit 0, write summary.json, report a converged solve (or a prescribed pressure) and raise no
# warning; and a few numbers of each summary.json are compared with values computed here, from the
# case's own parameters, by closed forms (Hertz, Pan-Hamrock) or definitions (load balance, volume
# target, friction mix), independently of the program (awk, no external JSON tool).
#   tests/cli/cases.sh PROGRAM
set -u
PROG=$1
T=$(mktemp -d "${TMPDIR:-/tmp}/mc_cases.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT INT TERM
fail=0

# jget FILE SECTION KEY: the number at "SECTION": { ... "KEY": value } of a summary.json (the
# writer's layout: sections at two spaces, their keys at four)
jget() {
    awk -v sec="$2" -v key="$3" '
        $0 ~ "^  \"" sec "\": [{]" { on = 1; next }
        on && /^  [}]/ { on = 0 }
        on && $0 ~ "^    \"" key "\": " { sub(/^[^:]*: /, ""); sub(/,$/, ""); print; exit }' "$1"
}

# near CASE NAME GOT WANT RELTOL: |GOT - WANT| <= RELTOL |WANT| (a missing or non-numeric value,
# NaN included, fails)
near() {
    if awk -v g="$3" -v w="$4" -v t="$5" 'BEGIN {
            if (g !~ /^[-+0-9.eE]+$/ || w !~ /^[-+0-9.eE]+$/) exit 1
            d = g - w; if (d < 0) d = -d; a = w < 0 ? -w : w
            exit !(d <= t * a) }'; then
        echo "  ok   $1 $2 = $3 (expected $4, rel. tol. $5)"
    else
        echo "FAIL case $1: $2 = $3, expected $4 (rel. tol. $5)"; numfail=1
    fi
}

# calc EXPR: awk arithmetic to 17 digits
calc() { awk "BEGIN { printf \"%.17g\", $1 }"; }

# physics CASE SUMMARY: the numbers of each example against values computed here
physics() {
    n=$1; f=$2; numfail=0
    kind=$(awk '/^  "load": [{]/ { on = 1 } on && /"kind"/ { gsub(/[",]/, ""); print $2; exit }' "$f")
    if grep -q '^  "lubrication": [{]' "$f" && [ "$(jget "$f" lubrication contact)" = '"whole"' ]; then
        # the whole line contact (theory 11.4): the strip carries w' = F_N / width per length,
        # b = sqrt(8 w' R_x / (pi E')) with E' = E / (1 - nu^2) (two steels)
        wp=$(jget "$f" lubrication load_per_length)
        near "$n" contact.load "$(jget "$f" contact load)" "$(jget "$f" lubrication patch_load)" 1e-6
        near "$n" lubrication.patch_load "$(jget "$f" lubrication patch_load)" \
            "$(calc "$wp * $(jget "$f" mesh ny) * $(jget "$f" mesh dy)")" 1e-12
        near "$n" lubrication.hertz_half_width "$(jget "$f" lubrication hertz_half_width)" \
            "$(calc "sqrt(8 * $wp * $(jget "$f" lubrication macro_radius) / (3.141592653589793 * 210e9 / (1 - 0.09)))")" 1e-9
    elif grep -q '^  "lubrication": [{]' "$f" && [ -n "$(jget "$f" lubrication patch_load)" ]; then
        # a lubricated patch carries the macro contact's Hertz pressure over its area
        near "$n" contact.load "$(jget "$f" contact load)" "$(jget "$f" lubrication patch_load)" 1e-6
        near "$n" lubrication.patch_load "$(jget "$f" lubrication patch_load)" \
            "$(calc "$(jget "$f" lubrication hertz_pressure) * $(jget "$f" mesh nx) * $(jget "$f" mesh ny) * $(jget "$f" mesh dx) * $(jget "$f" mesh dy)")" 1e-9
    elif [ "$kind" = force ]; then
        near "$n" contact.load "$(jget "$f" contact load)" "$(jget "$f" load value)" 1e-6
    fi
    case $n in
    hertz_point|pressure_cap|prescribed_pressure)
        # Hertz, steel on steel, R = 10 mm, F = 100 N: E* = E / (2 (1 - nu^2)),
        # a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2), approach a^2 / R
        es=$(calc "210e9 / (2 * (1 - 0.09))"); a=$(calc "exp(log(3 * 100 * 0.01 / (4 * $es)) / 3)")
        p0=$(calc "3 * 100 / (2 * 3.141592653589793 * $a * $a)")
        if [ "$n" = pressure_cap ]; then
            near "$n" contact.p_max "$(jget "$f" contact p_max)" 1.2e9 1e-9
            cc=$(jget "$f" contact capped_cells)
            [ "${cc:-0}" -gt 0 ] && echo "  ok   $n capped_cells = $cc > 0" ||
                { echo "FAIL case $n: no capped cell (Hertz p0 $p0 is above the 1.2 GPa cap)"; numfail=1; }
        else # 46 cells per contact radius: discretisation well below 0.5 %
            near "$n" contact.p_max "$(jget "$f" contact p_max)" "$p0" 5e-3
            near "$n" contact.approach "$(jget "$f" contact approach)" "$(calc "$a * $a / 0.01")" 5e-3
            near "$n" contact.area "$(jget "$f" contact area)" "$(calc "3.141592653589793 * $a * $a")" 3e-2
        fi ;;
    line_contact)
        # Hertz line, w = 100 N/mm, R = 10 mm: b = sqrt(4 w R / (pi E*)), p0 = 2 w / (pi b);
        # contact.area over dy = 1.3 um is the width 2b (80 cells per half-width)
        es=$(calc "210e9 / (2 * (1 - 0.09))"); b=$(calc "sqrt(4 * 1e5 * 0.01 / (3.141592653589793 * $es))")
        near "$n" contact.p_max "$(jget "$f" contact p_max)" "$(calc "2 * 1e5 / (3.141592653589793 * $b)")" 5e-3
        near "$n" "contact.area/dy" "$(calc "$(jget "$f" contact area) / 1.3e-6")" "$(calc "2 * $b")" 2e-2 ;;
    lubricated)
        # p >= p_lub = 300 MPa everywhere, so the peak is above it; solid contact is partial
        awk -v p="$(jget "$f" contact p_max)" 'BEGIN { exit !(p > 300e6) }' &&
            echo "  ok   $n contact.p_max > p_lub" || { echo "FAIL case $n: p_max <= p_lub"; numfail=1; }
        near "$n" "contact_ratio in (0, 1)" "$(jget "$f" contact contact_ratio)" 0.5 0.9999 ;;
    default|twin_disc_whole)
        # the running-in of three forces x speeds ends: every step done
        near "$n" runin.done "$(jget "$f" runin done)" "$(jget "$f" runin steps)" 0 ;;
    lubricated_equilibrium)
        # Pan-Hamrock central film (Pan & Hamrock 1989): H = 2.922 U^0.692 G^0.470 W'^-0.166,
        # E' = E / (1 - nu^2) (steel), R_x = 20 mm, u = 2 pi 500 / 60 0.04 m/s, w' = 1086 N / 10 mm;
        # macro Hertz b = sqrt(8 w' R_x / (pi E')); V* = h A_nom (64 x 0.8 um)^2; mu by psi_load
        ep=$(calc "210e9 / (1 - 0.09)"); u=$(calc "2 * 3.141592653589793 * 500 / 60 * 0.04")
        h=$(calc "2.922 * exp(0.692 * log(0.03 * $u / ($ep * 0.02)) + 0.470 * log(2e-8 * $ep) - 0.166 * log(108600 / ($ep * 0.02))) * 0.02")
        near "$n" lubrication.h_ehd "$(jget "$f" lubrication h_ehd)" "$h" 1e-9
        near "$n" lubrication.entrainment_speed "$(jget "$f" lubrication entrainment_speed)" "$u" 1e-12
        near "$n" lubrication.hertz_half_width "$(jget "$f" lubrication hertz_half_width)" \
            "$(calc "sqrt(8 * 108600 * 0.02 / (3.141592653589793 * $ep))")" 1e-9
        near "$n" lubrication.volume_target "$(jget "$f" lubrication volume_target)" "$(calc "$h * (51.2e-6)^2")" 1e-9
        near "$n" lubrication.volume "$(jget "$f" lubrication volume)" "$(jget "$f" lubrication volume_target)" 2e-6
        psi=$(jget "$f" lubrication psi_load)
        near "$n" lubrication.mu "$(jget "$f" lubrication mu)" "$(calc "$psi * 0.12 + (1 - $psi) * 0.03")" 1e-12 ;;
    *)  # rough cases: part of the surface touches
        near "$n" "contact_ratio in (0, 1)" "$(jget "$f" contact contact_ratio)" 0.5 0.9999 ;;
    esac
    return $numfail
}

for c in ${CASES:-cases/*.ini}; do  # CASES="cases/a.ini ...": some only
    name=$(basename "$c" .ini)
    # a case too large for make check runs shortened: its whole grid across x (the Hertz band of
    # the largest force must fit), a few rows, one force and two speeds
    set --
    case $name in
    twin_disc_whole) set -- --set mesh.ny=4 --set "runin.forces=1086 N" --set "runin.speeds=3000, 1000 rpm" ;;
    esac
    if ! "$PROG" run "$c" --out "$T/$name" "$@" > "$T/$name.log" 2>&1; then
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
    if ! physics "$name" "$T/$name/summary.json"; then
        fail=1; continue
    fi
    echo "PASS case $c: $(grep -E '^  time' "$T/$name.log" | sed 's/^ *//')"
done
exit $fail
