#!/bin/sh
# robustness.sh PROGRAM - results are never lost or mixed, end to end through the command line.
#
# One row per defect class of issue 15 (the classes that belong to the output directory and the
# front end); the rows that catch a defect only sometimes (concurrent runs, signals) are repeated:
#   lock_*        one run per output directory: a second run refuses at once (exit 3) naming the
#                 directory and the holder's pid; concurrent pairs leave exactly one run's set
#   signal_*      SIGINT/SIGTERM at many moments: exit 128 + signal, no staging directory left, the
#                 directory holds nothing new or one complete set, the log of a killed writer is
#                 not empty; stale staging areas of a killed run are swept, user files are not
#   nodir_*       errors found after parsing create no output directory (nor its parents) and
#                 name the case file
#   exit_*        exit codes: 0 success, 1 solver failure, 2 bad input, 3 the environment
#   cli_*         front end: --help of every command, keys SECTION, extra arguments, verify from
#                 any directory, a dangling symlink as --out, --set key= removes a key, a file
#                 that is not .npy
#   line_*        errors found after parsing name the case file and the line of the key
#   log_*         stdout is written per stage: a run killed (SIGKILL) while it computes has a log
#   phys_*        no silent physics: a lubricant load above the force, numbers beyond the solver's
#                 range, hexadecimal or infinite heights are exit 2 naming what is accepted
#   hang_*        no hangs: a doubly periodic grid of a huge cell aspect ratio is refused at once
#   warn_*        warnings a user can act on: summary.json "warnings" and stderr
#   plastic_stop_* every plastic run ends (issue 20): scenes that cannot converge end in seconds
#                 with exit 1, the load step and the reason, converged false and finite fields
# Every row prints one PASS or FAIL line; the last line is "robustness: N passed, M failed".
# ROBUST_PAIRS (default 50) and ROBUST_SIGNAL_REPS (default 2) set the repetitions.
# shellcheck disable=SC2010,SC2012,SC2045 # ls over directories that hold only names this script
# or the program chose (no blanks, no newlines)
set -u

if [ $# -ne 1 ] || [ ! -x "$1" ]; then
    echo "usage: $0 PROGRAM (the microcontact executable)" >&2
    exit 2
fi
PROG=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
REPO=$(cd "$(dirname "$0")/../.." && pwd)
PAIRS=${ROBUST_PAIRS:-50}
SIGREPS=${ROBUST_SIGNAL_REPS:-2}
T=$(mktemp -d "${TMPDIR:-/tmp}/mc_robust.XXXXXX") || exit 2
BG=""
cleanup() {
    for p in $BG; do kill -9 "$p" 2> /dev/null; done
    rm -rf "$T"
}
trap cleanup EXIT
trap 'exit 2' INT TERM
cd "$T" || exit 2

# Background jobs of a non-interactive shell ignore SIGINT; env restores the default so that the
# program sees the signal a terminal would send.
if env --default-signal=INT true 2> /dev/null; then
    SIGENV="env --default-signal=INT,TERM"
else
    SIGENV=""
fi

pass=0 fail=0
row() { # row NAME WHY: WHY empty = pass
    if [ -z "$2" ]; then
        pass=$((pass + 1))
        echo "PASS $1"
    else
        fail=$((fail + 1))
        echo "FAIL $1:$2"
    fi
}

# ---- fixtures --------------------------------------------------------------------------------
mesh() { printf '[mesh]\nnx = %s\nny = %s\ndx = 4 um\n[geometry]\nshape = sphere\nradius = 10 mm\n' "$1" "$1"; }
# small: a 16 x 16 Hertzian solve (milliseconds)
{ mesh 16; printf '[load]\nforce = 1 N\n[solver]\nthreads = 1\n'; } > small.ini
# pair: a few milliseconds of solve and 5 MB of results (stress volumes and VTK)
{ mesh 48; printf '[load]\nforce = 1 N\n[solver]\nthreads = 1\n[stress]\ndepth_max = 40 um\nlayers = 16\n[output]\nvtk = yes\n'; } > pair.ini
# heavy: about 1 s, of which a large part writes 140 MB of results
{ mesh 128; printf '[load]\nforce = 20 N\n[solver]\nthreads = 1\n[stress]\ndepth_max = 100 um\nlayers = 64\n[output]\nvtk = yes\n'; } > heavy.ini
# a prescribed pressure from a .npy file that is not one
{ mesh 16; printf '[load]\npressure_file = empty.npy\n'; } > p_empty.ini
{ mesh 16; printf '[load]\npressure_file = foreign.npy\n'; } > p_foreign.ini
: > empty.npy
printf 'PK\003\004 not an array\n' > foreign.npy
# a .npy whose data is truncated (header says 16 x 16, 100 values follow)
npy_header() { printf '\223NUMPY\001\000\166\000'; printf '%-117s\n' "$1"; }
{ npy_header "{'descr': '<f8', 'fortran_order': False, 'shape': (16, 16), }"; head -c 800 /dev/zero; } > truncated.npy
{ mesh 16; printf '[load]\npressure_file = truncated.npy\n'; } > p_truncated.ini

# Complete result sets of solo runs: the references every multi-run row is compared with.
"$PROG" run pair.ini --out refA > /dev/null 2>&1 || { echo "robustness: reference run failed"; exit 2; }
"$PROG" run pair.ini --out refB --set load.force=2N > /dev/null 2>&1 || { echo "robustness: reference run failed"; exit 2; }
# summary.json without its timing block (the only part that differs between equal runs)
untimed() { sed '/"timing": {/,/}/d' "$1"; }
# same_set DIR REF: DIR holds exactly REF's files with REF's contents ("" when so)
same_set() {
    w=""
    [ "$(ls -A "$1" 2> /dev/null)" = "$(ls -A "$2")" ] || { w=" files $(ls -A "$1" 2> /dev/null | tr '\n' ' ')"; echo "$w"; return; }
    for f in $(ls -A "$2"); do
        if [ "$f" = summary.json ]; then
            untimed "$1/$f" > s1; untimed "$2/$f" > s2
            cmp -s s1 s2 || w="$w $f"
        else
            cmp -s "$1/$f" "$2/$f" || w="$w $f"
        fi
    done
    [ -n "$w" ] && echo " differs from $2 in:$w"
}
# one_set DIR: DIR holds exactly refA's or refB's set
one_set() {
    a=$(same_set "$1" refA)
    [ -z "$a" ] && return
    b=$(same_set "$1" refB)
    [ -z "$b" ] && return
    echo " neither one run's set:$a /$b"
}
# fingerprint DIR: names, sizes and checksums of everything in DIR (hidden files too)
fingerprint() { (cd "$1" 2> /dev/null && ls -A | while read -r f; do echo "$f $(cksum < "$f" 2> /dev/null)"; done); }
staging_left() { ls -A "$1" 2> /dev/null | grep '^\.staging-' | tr '\n' ' '; }

# ---- 1. one run per output directory --------------------------------------------------------
# A lock held by another process (flock(1) on the directory, as a run holds it): refused at once.
mkdir held
flock -x held sleep 5 &
HOLDER=$!
BG="$BG $HOLDER"
sleep 0.3
t0=$(date +%s%N)
"$PROG" run small.ini --out held > out 2> err
st=$? t1=$(date +%s%N)
why=""
[ "$st" -eq 3 ] || why="$why exit $st, not 3;"
grep -q "held" err || why="$why message does not name the directory;"
grep -q "$HOLDER" err || why="$why message does not name the holder pid $HOLDER;"
[ $(((t1 - t0) / 1000000)) -lt 2000 ] || why="$why took $(((t1 - t0) / 1000000)) ms, not at once;"
[ -z "$(ls -A held)" ] || why="$why held/ was written: $(ls -A held | tr '\n' ' ');"
row lock_held_refuses "$why"
kill "$HOLDER" 2> /dev/null; wait "$HOLDER" 2> /dev/null

# A second run into the directory of a run that is still computing refuses at once; the first
# one finishes and its set is complete.
mkdir busy
$SIGENV "$PROG" run heavy.ini --out busy > outA 2> errA &
A=$!
# wait until the first run holds its lock (/proc/locks lists the directory's inode)
ino=$(stat -c %i busy)
n=0
while [ $n -lt 500 ] && ! grep -q ":$ino " /proc/locks 2> /dev/null; do sleep 0.01; n=$((n + 1)); done
"$PROG" run pair.ini --out busy > outB 2> errB
sB=$?
wait "$A"
sA=$?
why=""
[ "$sA" -eq 0 ] || why="$why first run exit $sA;"
[ "$sB" -eq 3 ] || why="$why second run exit $sB, not 3;"
grep -q "busy" errB || why="$why message does not name the directory;"
grep -q "$A" errB || why="$why message does not name the holder pid $A;"
[ -f busy/summary.json ] && grep -q '"value": 20' busy/summary.json || why="$why busy/ lacks the first run's summary;"
[ -z "$(staging_left busy)" ] || why="$why staging left: $(staging_left busy);"
row lock_second_run_refused "$why"
rm -rf busy

# Pairs started together into one directory (fresh for even k, holding a set for odd k): each
# exits 0 or 3 (refused, naming the lock), one at least succeeds, and the directory holds exactly
# one run's complete set.
k=0 refused=0
while [ $k -lt "$PAIRS" ]; do
    rm -rf pd
    [ $((k % 2)) -eq 1 ] && cp -r refA pd
    "$PROG" run pair.ini --out pd > oa 2> ea &
    pa=$!
    "$PROG" run pair.ini --out pd --set load.force=2N > ob 2> eb &
    pb=$!
    wait $pa; sa=$?
    wait $pb; sb=$?
    why=""
    for s in "a $sa" "b $sb"; do
        # shellcheck disable=SC2086 # "a 0" splits into the run's letter and its status
        set -- $s
        case $2 in
            0) ;;
            3) grep -q "in use by another run" "e$1" || why="$why run $1 exit 3 without naming the lock: $(cat "e$1");" ;;
            *) why="$why run $1 exit $2: $(cat "e$1");" ;;
        esac
    done
    [ "$sa" -eq 0 ] || [ "$sb" -eq 0 ] || why="$why neither run succeeded;"
    [ "$sa" -eq 3 ] || [ "$sb" -eq 3 ] && refused=$((refused + 1))
    why="$why$(one_set pd)"
    row "lock_pair_$k" "$why"
    k=$((k + 1))
done
echo "     ($refused of $PAIRS pairs met the lock: one run refused)"
rm -rf pd

# ---- 2. signals and leftovers ---------------------------------------------------------------
# signal_row NAME SIG WHEN PRE [retry]: start heavy.ini into sd (PRE = old: sd holds refA's set
# first), send SIG after WHEN seconds (WHEN = writing: as soon as the log says results are being
# written), then check the directory and the exit status. With "retry", a run that finished
# before the signal prints no row and sets retry=1.
signal_row() {
    name=$1 sig=$2 when=$3 pre=$4 may_retry=${5:-}
    rm -rf sd
    [ "$pre" = old ] && cp -r refA sd
    before=$(fingerprint sd)
    $SIGENV "$PROG" run heavy.ini --out sd > log 2> err &
    pid=$!
    BG="$BG $pid"
    if [ "$when" = writing ]; then
        n=0
        while [ $n -lt 1000 ] && ! grep -q "writing results" log && kill -0 $pid 2> /dev/null; do
            sleep 0.01; n=$((n + 1))
        done
    else
        sleep "$when"
    fi
    kill -s "$sig" $pid 2> /dev/null
    wait $pid
    st=$?
    why=""
    case $sig in INT) want=130 ;; TERM) want=143 ;; esac
    retry=0
    if [ "$st" -eq 0 ]; then
        n_done=$((n_done + 1))
        if [ "$when" = writing ] && [ "$may_retry" = retry ]; then
            retry=1
            return
        fi
        [ "$when" = writing ] && why="$why finished before the signal while writing (5 times);"
        [ -f sd/summary.json ] && grep -q '"value": 20' sd/summary.json || why="$why exit 0 without its summary;"
        ! ls -A sd | grep -q '^\.' || why="$why hidden files left: $(ls -A sd | grep '^\.' | tr '\n' ' ');"
    else
        if grep -q "writing results" log; then n_writing=$((n_writing + 1)); else n_solving=$((n_solving + 1)); fi
        [ "$st" -eq "$want" ] || why="$why exit $st, not $want (128 + SIG$sig);"
        # only a signal after the final renames began may find the new set committed
        if [ -e sd ] && [ "$(ls -A sd)" = "$(ls -A refA)" ] && grep -q '"value": 20' sd/summary.json; then
            n_late=$((n_late + 1))
        elif [ "$pre" = new ] && [ -e sd ]; then
            why="$why sd/ was created: $(ls -A sd | tr '\n' ' ');"
        elif [ "$(fingerprint sd)" != "$before" ]; then
            why="$why sd/ changed: $(ls -A sd 2> /dev/null | tr '\n' ' ');"
        fi
    fi
    row "$name" "$why"
}
r=0 n_done=0 n_writing=0 n_solving=0 n_late=0
while [ $r -lt "$SIGREPS" ]; do
    for when in 0.05 0.1 0.2 0.35 0.5 0.7 0.9 1.2; do
        if [ $r -eq 0 ]; then s=TERM p=new; else s=INT p=old; fi
        [ "$s" = INT ] && [ -z "$SIGENV" ] && s=TERM
        signal_row "signal_${s}_after_${when}s_$p" $s $when $p
    done
    r=$((r + 1))
done
# The write phase of heavy.ini takes a few tenths of a second; on a busy machine the signal may
# still come after it, so such a row tries up to 5 runs until one is signalled while writing.
k=0
while [ $k -lt 6 ]; do
    if [ $((k % 2)) -eq 0 ]; then s=TERM p=new; else s=INT p=old; fi
    [ "$s" = INT ] && [ -z "$SIGENV" ] && s=TERM
    try=1
    while :; do
        may=""
        [ $try -lt 5 ] && may=retry
        signal_row "signal_${s}_while_writing_${k}_$p" $s writing $p "$may"
        if [ "$retry" != 1 ] || [ $try -ge 5 ]; then break; fi
        try=$((try + 1))
    done
    k=$((k + 1))
done
echo "     (signalled runs: $n_solving stopped while solving, $n_writing while writing" \
    "(of which $n_late after their commit), $n_done had finished)"

# Stale staging areas of a killed run (SIGKILL leaves them) are swept by the next run; files
# and directories of the user that merely look alike are not.
mkdir -p st/.staging-Ab3xY9 st/.staging-user st/.staging-Q1w2E3
: > st/.staging-Ab3xY9/pressure.npy
: > st/.staging-Ab3xY9/von_mises.npy.tmp
: > st/.staging-Q1w2E3/notes.txt     # not a file of ours: this directory stays
: > st/.staging-Zz9Zz9               # a regular file: stays
"$PROG" run small.ini --out st > out 2> err
st_=$?
why=""
[ "$st_" -eq 0 ] || why="$why exit $st_;"
[ -e st/.staging-Ab3xY9 ] && why="$why stale .staging-Ab3xY9 left;"
[ -d st/.staging-user ] || why="$why user directory .staging-user removed;"
[ -f st/.staging-Q1w2E3/notes.txt ] || why="$why user file .staging-Q1w2E3/notes.txt removed;"
[ -f st/.staging-Zz9Zz9 ] || why="$why user file .staging-Zz9Zz9 removed;"
row signal_stale_staging_swept "$why"
rm -rf st

# A run killed by SIGKILL while writing leaves a staging area; the next run removes it.
rm -rf sk
"$PROG" run heavy.ini --out sk > log 2> err &
pid=$!
BG="$BG $pid"
n=0
while [ $n -lt 1000 ] && [ -z "$(staging_left sk)" ] && kill -0 $pid 2> /dev/null; do sleep 0.01; n=$((n + 1)); done
kill -9 $pid 2> /dev/null; wait $pid 2> /dev/null
left=$(staging_left sk)
"$PROG" run small.ini --out sk > out 2> err
st_=$?
why=""
[ -n "$left" ] || why="$why (setup) the killed run left no staging area to sweep;"
[ "$st_" -eq 0 ] || why="$why exit $st_;"
[ -z "$(staging_left sk)" ] || why="$why staging left: $(staging_left sk);"
row signal_sigkill_leftover_swept "$why"
rm -rf sk

# ---- 3. nothing created on failure -----------------------------------------------------------
# nodir NAME STATUS FRAGMENT ARGS...: the run fails with STATUS, names the case file (FRAGMENT)
# and creates neither nd/ nor nd/a/.
nodir() {
    name=$1 want=$2 frag=$3
    shift 3
    rm -rf nd
    "$PROG" run "$@" --out nd/a/b > out 2> err
    st=$?
    why=""
    [ "$st" -eq "$want" ] || why="$why exit $st, not $want;"
    [ -e nd ] && why="$why nd/ was created: $(find nd | tr '\n' ' ');"
    grep -q "$frag" err || why="$why message does not name $frag: $(cat err);"
    row "$name" "$why"
    rm -rf nd
}
nodir nodir_bad_data_file 2 p_truncated.ini p_truncated.ini
nodir nodir_memory_guard 3 small.ini small.ini --set mesh.nx=60000 --set mesh.ny=60000
nodir nodir_infeasible_cap 2 small.ini small.ini --set load.pressure_cap=1MPa --set load.force=100N
nodir nodir_point_kernel_zero_depth 2 small.ini small.ini --set stress.kernel=point --set stress.depth_max=20um
# a write that fails (file size limit: EFBIG, as a full disk gives ENOSPC) removes what it created
rm -rf nd
(trap '' XFSZ; ulimit -f 64; exec "$PROG" run pair.ini --out nd/a/b > out 2> err)
st=$?
why=""
[ "$st" -eq 3 ] || why="$why exit $st, not 3;"
[ -e nd ] && why="$why nd/ left behind: $(find nd | tr '\n' ' ');"
grep -q "File too large" err || why="$why message lacks the reason: $(cat err);"
row nodir_write_fails "$why"
rm -rf nd

# ---- 7. exit codes ---------------------------------------------------------------------------
# exitrow NAME STATUS ARGS...
exitrow() {
    name=$1 want=$2
    shift 2
    rm -rf eo
    "$PROG" "$@" > out 2> err
    st=$?
    if [ "$st" -eq "$want" ]; then row "$name" ""; else row "$name" " exit $st, not $want: $(head -c 300 err)"; fi
    rm -rf eo
}
exitrow exit0_success 0 run small.ini --out eo
exitrow exit1_not_converged 1 run small.ini --out eo --set solver.max_iterations=1 --set solver.method=pk
exitrow exit2_bad_input 2 run small.ini --out eo --set mesh.nx=0
exitrow exit2_missing_case 2 run does_not_exist.ini --out eo
exitrow exit3_memory_guard 3 run small.ini --out eo --set mesh.nx=60000 --set mesh.ny=60000
: > a_file
exitrow exit3_out_below_file 3 run small.ini --out a_file/out
exitrow exit3_out_is_file 3 run small.ini --out a_file
"$PROG" --help > out 2>&1
why=""
for f in "0 success" "1 solver" "2 bad input" "3 the environment"; do
    grep -q "$f" out || why="$why --help lacks '$f';"
done
row exit_codes_documented "$why"

# ---- 8. front end ----------------------------------------------------------------------------
for c in run verify bench keys; do
    "$PROG" $c --help > out 2> err
    st=$?
    why=""
    [ "$st" -eq 0 ] || why="$why exit $st;"
    grep -q "usage: microcontact $c" out || why="$why no usage on stdout;"
    [ -s err ] && why="$why stderr: $(cat err);"
    row "cli_${c}_help" "$why"
done
"$PROG" keys mesh > out 2> err
st=$?
why=""
[ "$st" -eq 0 ] || why="$why exit $st;"
grep -q "nx" out || why="$why lacks nx;"
grep -q "<!--" out && why="$why holds an HTML comment;"
grep -q "|---" out && why="$why holds a Markdown table;"
grep -qi "geometry\|radius" out && why="$why shows other sections;"
row cli_keys_section "$why"
"$PROG" keys nosuch > out 2> err
st=$?
why=""
[ "$st" -eq 2 ] || why="$why exit $st, not 2;"
grep -q "mesh" err || why="$why does not list the sections;"
row cli_keys_unknown_section "$why"
for args in "keys mesh load" "help extra" "--version extra" "bench --quick extra" "run small.ini --out eo extra"; do
    rm -rf eo
    # shellcheck disable=SC2086 # split on purpose
    "$PROG" $args > out 2> err
    st=$?
    why=""
    [ "$st" -eq 2 ] || why="$why exit $st, not 2;"
    grep -q "usage" err || why="$why no usage on stderr;"
    [ -e eo ] && why="$why eo/ created;"
    row "cli_extra_args_$(echo "$args" | tr ' -' '_')" "$why"
done
rm -rf eo
# verify from a directory that is not the repository: an executable inside the repository finds
# the reference tables above itself; one elsewhere says where it looked (exit 3, no suite run)
mkdir elsewhere
(cd elsewhere && env -u MC_PHYSICS_DIR "$PROG" verify hertz_line --fast --reports rep > out 2> err)
st=$?
why=""
case $PROG in
    "$REPO"/*)
        [ "$st" -eq 0 ] || why="$why exit $st: $(grep -h 'cannot\|FAIL' elsewhere/err elsewhere/out elsewhere/rep/*/report.md 2> /dev/null | head -3);" ;;
    *)
        [ "$st" -eq 3 ] || why="$why exit $st, not 3 (the executable is outside the repository);"
        grep -q "looked in" elsewhere/err || why="$why message does not say where it looked: $(cat elsewhere/err);" ;;
esac
row cli_verify_any_directory "$why"
rm -rf elsewhere
# a dangling symlink as --out is named as such
ln -s does/not/exist lnk
"$PROG" run small.ini --out lnk > out 2> err
st=$?
why=""
[ "$st" -eq 3 ] || why="$why exit $st, not 3;"
grep -q "dangling" err || why="$why message does not say dangling: $(cat err);"
[ -e does ] && why="$why the link target was created;"
row cli_out_dangling_symlink "$why"
rm -f lnk
# --set section.key= removes the key: switch from force to approach without editing the file
"$PROG" run small.ini --out eo --set load.force= --set load.approach=0.1um > out 2> err
st=$?
why=""
[ "$st" -eq 0 ] || why="$why exit $st: $(cat err);"
grep -q '"kind": "approach"' eo/summary.json 2> /dev/null || why="$why summary lacks the approach load;"
row cli_set_empty_removes_key "$why"
rm -rf eo
# a 0-byte or foreign file given as .npy: "not a .npy file"
for f in empty foreign; do
    "$PROG" run p_$f.ini --out eo > out 2> err
    st=$?
    why=""
    [ "$st" -eq 2 ] || why="$why exit $st, not 2;"
    grep -q "not a .npy file" err || why="$why message: $(cat err);"
    [ -e eo ] && why="$why eo/ created;"
    row "cli_npy_$f" "$why"
    rm -rf eo
done

# ---- 3b. errors after parsing name the key's line --------------------------------------------
# lines: a case whose keys stand on known lines (load on 9, pressure_cap 10, kernel 12, nx 2)
{ mesh 16; printf '[load]\nforce = 1 N\npressure_cap = 1 MPa\n[stress]\nkernel = point\n'
  printf 'depth_max = 20 um\n'; } > lines.ini
{ mesh 16; printf '[load]\npressure_file = truncated.npy\n'; } > lines_p.ini
# lineof NAME WANT STATUS ARGS...: the run fails with STATUS and its message holds WANT
lineof() {
    name=$1 want=$2 st_want=$3
    shift 3
    rm -rf lo
    "$PROG" run "$@" --out lo > out 2> err
    st=$?
    why=""
    [ "$st" -eq "$st_want" ] || why="$why exit $st, not $st_want;"
    grep -qF "$want" err || why="$why message lacks '$want': $(cat err);"
    row "$name" "$why"
    rm -rf lo
}
lineof line_infeasible_cap "lines.ini:10: [load] pressure_cap" 2 lines.ini --set stress.depth_max=
lineof line_point_kernel_zero_depth "lines.ini:12: [stress] kernel" 2 lines.ini \
    --set load.pressure_cap=
lineof line_bad_data_file "lines_p.ini:9: [load] pressure_file" 2 lines_p.ini
{ mesh 60000; printf '[load]\nforce = 1 N\n'; } > lines_m.ini
lineof line_memory_guard "lines_m.ini:2: [mesh] nx" 3 lines_m.ini
lineof line_override_named "lines.ini: --set load.pressure_cap: [load] pressure_cap" 2 lines.ini \
    --set load.pressure_cap=2MPa

# ---- 2b. a log per stage ---------------------------------------------------------------------
# SIGKILL while the run computes (a solve of about 1.5 s, once its grid line is out): its log is
# not empty
rm -rf lk
"$PROG" run heavy.ini --out lk --set stress.layers=128 > log 2> err &
pid=$!
BG="$BG $pid"
# wait until the grid line is in the log file while the run still computes (unflushed stdout
# would show nothing before the end: the run then ends first and the row fails)
n=0
while [ $n -lt 2000 ] && ! grep -q "cells" log && kill -0 $pid 2> /dev/null; do
    sleep 0.01; n=$((n + 1))
done
alive=0
kill -0 $pid 2> /dev/null && alive=1
kill -9 $pid 2> /dev/null
wait $pid 2> /dev/null
why=""
[ "$alive" -eq 1 ] || why="$why (setup) the run had ended before the signal;"
[ -s log ] || why="$why the log of the killed run is empty;"
grep -q "cells" log || why="$why the log lacks the grid line: $(cat log);"
row log_sigkill_while_computing "$why"
rm -rf lk

# ---- 4b. no silent physics -------------------------------------------------------------------
# phys NAME FRAGMENT ARGS...: exit 2, the message holds FRAGMENT, no output directory
phys() {
    name=$1 frag=$2
    shift 2
    rm -rf po
    timeout 60 "$PROG" run "$@" --out po > out 2> err
    st=$?
    why=""
    [ "$st" -eq 2 ] || why="$why exit $st, not 2: $(head -c 300 err);"
    grep -qF -- "$frag" err || why="$why message lacks '$frag': $(cat err);"
    [ -e po ] && why="$why po/ created;"
    row "$name" "$why"
    rm -rf po
}
# 1 GPa over the (64 um)^2 grid carries 4.096 N: more than the 1 N asked for
phys phys_lubricant_load_above_force "carries 4.096 N, more than the requested force 1 N" \
    small.ini --set load.lubricant_pressure=1GPa
phys phys_lubricant_per_length "more than the requested force_per_length" small.ini \
    --set load.force= --set load.force_per_length=1N/m --set mesh.periodic_y=yes \
    --set geometry.shape=cylinder --set load.lubricant_pressure=1GPa
phys phys_force_overflow "accepted: force <=" small.ini --set load.force=1e300N
phys phys_modulus_tiny "accepted: force <=" small.ini --set body1.E=1e-300Pa --set body2.E=1e-300Pa
phys phys_dx_tiny "must be >= 1e-150 m" small.ini --set mesh.dx=1e-300m
phys phys_approach_overflow "accepted: approach <=" small.ini --set load.force= \
    --set load.approach=1e300m
printf '[mesh]\nnx = 2\nny = 2\ndx = 4 um\n[roughness]\ntype = file\nfile = %s\nmissing = fill\n' \
    hex.txt > hex.ini
printf '[load]\nforce = 1 mN\n' >> hex.ini
printf '0 0x10\n0 0\n' > hex.txt
phys phys_height_hex "hex.txt:1: '0x10' is not a number" hex.ini
printf '0 0\n0 inf\n' > inf.txt
phys phys_height_inf "inf.txt:2: 'inf' is not a number" hex.ini --set roughness.file=inf.txt
printf '0 0\n0 1e999\n' > big.txt
phys phys_height_overflow "big.txt:2: value '1e999' is not finite" hex.ini --set roughness.file=big.txt

# ---- 5. no hangs -----------------------------------------------------------------------------
# plastic layers: depth / dz is a loop count set by values (dz = 1 pm took hours, or died out of
# memory): dz below min(dx, dy)/16 and more than 1024 layers are refused
{ mesh 16; printf '[load]\nforce = 1 N\n[plasticity]\nyield_stress = 1 GPa\n'; } > plastic.ini
phys hang_plastic_dz_tiny "must be >= min(dx, dy) / 16" plastic.ini --set plasticity.dz=1e-12m
phys hang_plastic_layers "accepted: depth <= 1024 dz" plastic.ini --set plasticity.dz=1um \
    --set plasticity.depth=2mm
# dy/dx = 1e5 on a doubly periodic grid took minutes in the Ewald table: refused at once
t0=$(date +%s%N)
phys hang_ewald_aspect_ratio "at most 1000" small.ini --set mesh.periodic_x=yes \
    --set mesh.periodic_y=yes --set mesh.dx=0.01um --set mesh.dy=1mm --set geometry.shape=flat \
    --set geometry.radius=
t1=$(date +%s%N)
why=""
[ $(((t1 - t0) / 1000000)) -lt 2000 ] || why=" took $(((t1 - t0) / 1000000)) ms, not at once"
row hang_ewald_aspect_ratio_time "$why"
# the largest accepted ratio (1000) ends in seconds
{ printf '[mesh]\nnx = 16\nny = 16\ndx = 0.01 um\ndy = 10 um\nperiodic_x = yes\nperiodic_y = yes\n'
  printf '[roughness]\ntype = gaussian\nrq = 0.01 um\ncorrelation_x = 0.05 um\n'
  printf 'correlation_y = 50 um\n[load]\nforce = 0.001 mN\n[solver]\nthreads = 1\n'; } > aspect.ini
t0=$(date +%s%N)
timeout 60 "$PROG" run aspect.ini --out ao > out 2> err
st=$? t1=$(date +%s%N)
why=""
[ "$st" -eq 0 ] || why="$why exit $st: $(head -c 300 err);"
[ $(((t1 - t0) / 1000000)) -lt 20000 ] || why="$why took $(((t1 - t0) / 1000000)) ms;"
row hang_ewald_aspect_limit_runs "$why"
rm -rf ao

# ---- 6. warnings -----------------------------------------------------------------------------
# warn NAME ARGS... -- CODES: exit 0; summary.json "warnings" holds exactly CODES (in order), and
# stderr one "microcontact: warning:" line per warning
warn() {
    name=$1
    shift
    args=""
    while [ "$1" != "--" ]; do args="$args $1"; shift; done
    shift
    rm -rf wo
    # shellcheck disable=SC2086 # split on purpose
    "$PROG" run $args --out wo > out 2> err
    st=$?
    why=""
    [ "$st" -eq 0 ] || why="$why exit $st: $(head -c 300 err);"
    got=$(tr -d ' \n' < wo/summary.json 2> /dev/null | grep -o '"warnings":\[[^]]*\]' |
          grep -o '"code":"[a-z_]*"' | sed 's/"code":"//; s/"//' | tr '\n' ' ' | sed 's/ $//')
    grep -q '"warnings"' wo/summary.json 2> /dev/null || why="$why summary.json has no warnings list;"
    [ "$got" = "$*" ] || why="$why codes '$got', not '$*';"
    n=$(grep -c '^microcontact: warning: ' err)
    [ "$n" -eq "$#" ] || why="$why $n warning lines on stderr, not $#;"
    row "$name" "$why"
    rm -rf wo
}
# a Hertzian contact of radius 19 um on 1 um cells well inside a 64 um grid: none
{ mesh 64 | sed 's/4 um/1 um/'; printf '[load]\nforce = 0.1 N\n[solver]\nthreads = 1\n'; } > clean.ini
[ "$(grep -c 'dx = 1 um' clean.ini)" -eq 1 ] || echo "robustness: clean.ini fixture broken"
warn warn_none clean.ini --
warn warn_edge_ratio_coarse small.ini -- contact_at_edge contact_ratio_high coarse_contact
warn warn_coarse clean.ini --set load.force=0.1mN -- coarse_contact
warn warn_pressure_above_moduli clean.ini --set body1.E=1MPa --set body2.E=1MPa \
    --set load.force=10mN -- contact_at_edge contact_ratio_high pressure_above_moduli
# a flat rough patch under a nominal load touches its edges by nature: no contact_at_edge
{ mesh 32 | sed 's/shape = sphere/shape = flat/; /radius/d'
  printf '[roughness]\ntype = gaussian\nrq = 0.2 um\ncorrelation_x = 20 um\ncorrelation_y = 20 um\n'
  printf 'cutoff = 16 um\n[load]\nforce = 1 N\n[solver]\nthreads = 1\n'; } > patch.ini
warn warn_flat_patch_no_edge patch.ini --

# ---- 4. running-in: checkpoints, SIGINT and --resume ----------------------------------------
# A small elastic-plastic running-in (two forces, six speeds: 24 steps of a few tenths of a
# second). runin_resume_*: stopped by SIGINT while it runs, it exits 130, keeps its checkpoint,
# commits no result and says how to continue; resumed, it ends with the uninterrupted run's
# runin.csv (but for its seconds column) and fields, bit for bit; the checkpoint is gone then.
{ printf '[mesh]\nnx = 32\nny = 32\ndx = 0.8 um\n[roughness]\ntype = gaussian\nrq = 0.3 um\n'
  printf 'correlation_x = 4 um\ncorrelation_y = 24 um\nseed = 2\n[load]\nforce = 1086 N\n'
  printf 'lubricant_pressure = auto\n[lubrication]\nviscosity = 30 mPa*s\npressure_viscosity = 2e-8\n'
  printf 'rpm = 3000 rpm\nradius1 = 40 mm\nradius2 = 40 mm\nwidth = 10 mm\n[solver]\nthreads = 1\n'
  printf '[plasticity]\nhardening = swift\nswift_B = 1280 MPa\nswift_C = 4\nswift_n = 0.095\n'
  printf 'bodies = both\nload_steps = 1\ndz = 0.4 um\ndepth = 2 um\nplastic_tolerance = 1e-5\n'
  printf '[runin]\nforces = 1086 N, 2172 N\nspeeds = 3000, 1000, 700, 500, 350, 200 rpm\n'; } > runin.ini
# runin.csv without its seconds column (found by its name in the header), the one that may differ
nosec() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "seconds") s = i }
             { o = ""; for (i = 1; i <= NF; i++) if (i != s) o = o (o == "" ? "" : ",") $i; print o }' "$1"
}
"$PROG" run runin.ini --out rref --quiet > /dev/null 2>&1 || { echo "robustness: running-in reference failed"; exit 2; }
why=""
[ -e rref/checkpoint ] && why="$why the checkpoint of a finished run is left;"
for f in runin.csv runin.gp surface_initial.npy surface_final.npy material_ratio.csv; do
    [ -f "rref/$f" ] || why="$why no $f;"
done
row runin_outputs "$why"
# runin_resume SIG STEP: stop after STEP steps were reported, then resume
runin_resume() {
    sig=$1 step=$2
    rm -rf rs; : > err
    $SIGENV "$PROG" run runin.ini --out rs > log 2> err &
    pid=$!
    BG="$BG $pid"
    n=0
    while [ $n -lt 3000 ] && ! grep -q "^step  *$step/" err && kill -0 $pid 2> /dev/null; do
        sleep 0.01; n=$((n + 1))
    done
    kill -s "$sig" $pid 2> /dev/null
    wait $pid
    st=$?
    why=""
    case $sig in INT) want=130 ;; TERM) want=143 ;; esac
    [ "$st" -eq "$want" ] || why="$why exit $st, not $want;"
    grep -q "continue with:" err && grep -q -- "--out rs --resume" err || why="$why no resume hint: $(tail -3 err | tr '\n' ' ');"
    [ -f rs/checkpoint/state.bin ] || why="$why no checkpoint;"
    [ -e rs/summary.json ] && why="$why results were committed;"
    "$PROG" run runin.ini --out rs --resume --quiet > log 2> err
    st=$?
    [ "$st" -eq 0 ] || why="$why resume: exit $st: $(cat err);"
    [ -s err ] && why="$why resume --quiet wrote to stderr: $(cat err);"
    [ "$(nosec rs/runin.csv)" = "$(nosec rref/runin.csv)" ] || why="$why runin.csv differs;"
    for f in pressure.npy gap.npy surface_final.npy plastic_strain.npy residual_displacement.npy \
             material_ratio.csv runin.gp; do
        cmp -s "rs/$f" "rref/$f" || why="$why $f differs;"
    done
    [ -e rs/checkpoint ] && why="$why the checkpoint is left after the resumed run;"
    row "runin_resume_${sig}_after_step_$step" "$why"
}
if [ -n "$SIGENV" ]; then runin_resume INT 3; else runin_resume TERM 3; fi
runin_resume TERM 9
# the progress lines: one per step on stderr, none with --quiet
rm -rf rp
"$PROG" run runin.ini --out rp > log 2> err
why=""
[ "$(grep -c '^step  *[0-9]*/24 ' err)" -eq 24 ] || why="$why $(grep -c '^step' err) progress lines, not 24;"
grep -q 'elapsed' err && grep -q 'left' err || why="$why progress lines lack elapsed / left;"
row runin_progress_lines "$why"
# a resume with other --set values (another case) is refused and keeps the checkpoint
rm -rf rs; : > err
$SIGENV "$PROG" run runin.ini --out rs > log 2> err &
pid=$!
BG="$BG $pid"
n=0
while [ $n -lt 3000 ] && ! grep -q "^step  *2/" err && kill -0 $pid 2> /dev/null; do sleep 0.01; n=$((n + 1)); done
kill -s TERM $pid 2> /dev/null
wait $pid
"$PROG" run runin.ini --out rs --resume --set lubrication.mu_solid=0.13 > log 2> err
st=$?
why=""
[ "$st" -eq 2 ] || why="$why exit $st, not 2;"
grep -q "belongs to another case" err || why="$why message: $(cat err);"
[ -f rs/checkpoint/state.bin ] || why="$why the checkpoint was removed;"
row runin_resume_other_case "$why"
rm -rf rs rp rref

# ---- 10. every plastic run ends (issue 20; docs/theory.md §9.5) -------------------------------
# finite_npy FILE: no NaN or Inf among its float64 values (the exponent bits all set)
finite_npy() {
    hl=$(od -An -tu2 -j8 -N2 "$1" | tr -d ' ')
    ! od -An -v -tx8 -j $((10 + hl)) "$1" | tr -s ' ' '\n' | grep -qi '^[7f]ff'
}
# plastic_stop NAME SECONDS CASE [FIELDS...]: a plastic scene that cannot converge ends within
# SECONDS with exit 1, a message that names the load step and the reason, summary.json with
# plastic "converged": false and plastic.stop, and its fields written and finite
# A build with AddressSanitizer (make check-sanitize) runs the plastic loops about 5x slower: its
# time limits scale by SLOW (the bound stays a bound, of that build).
if grep -qa __asan_init "$PROG"; then SLOW=5; else SLOW=1; fi
plastic_stop() {
    name=$1 secs=$(($2 * SLOW)) case=$3
    shift 3
    rm -rf po
    t0=$(date +%s)
    timeout $((secs * 3)) "$PROG" run "$case" --out po > out 2> err
    st=$? t1=$(date +%s)
    why=""
    [ $((t1 - t0)) -le "$secs" ] || why="$why took $((t1 - t0)) s (more than $secs s);"
    [ "$st" -eq 1 ] || why="$why exit $st, not 1: $(tail -c 300 err);"
    grep -q "load step [0-9]* of [0-9]*" err || why="$why the message names no load step: $(tail -c 300 err);"
    grep -q "the results are those of the last iterate" err || why="$why the message gives no reason: $(tail -c 300 err);"
    case $case in runin*) grep -q "running-in step [0-9]* of" err || why="$why the message names no running-in step;" ;; esac
    if [ -f po/summary.json ]; then
        sed -n '/"plastic": {/,/^  }/p' po/summary.json > plastic.json
        grep -q '"converged": false' plastic.json || why="$why plastic converged is not false;"
        grep -q '"stop": {' plastic.json && grep -q '"reason": "[a-z]' plastic.json &&
            grep -q '"load_step": [1-9]' plastic.json || why="$why no plastic.stop with step and reason;"
        for f in pressure gap residual_displacement topography_final plastic_strain residual_von_mises "$@"; do
            if [ ! -s "po/$f.npy" ]; then why="$why no $f.npy;"
            elif ! finite_npy "po/$f.npy"; then why="$why $f.npy not finite;"; fi
        done
    else
        why="$why no summary.json;"
    fi
    row "$name" "$why"
    rm -rf po
}
# a flat patch at 10 GPa with Y = 100 MPa: far beyond what the perfectly plastic body carries
# (issue 20's 1 GPa patch: before, 98 s on 8 x 8, then exit 1 and nothing written; with the cell
# averages of theory §8.7 that scene converges in 0.9 s, so the row loads ten times more; with
# the warm start and dry Anderson mixing of theory §9.6 it converges even at 100 GPa, so the row
# caps the outer iteration at 2: the stop's contract, results with converged false, is what it
# checks)
{ printf '[mesh]\nnx = 8\nny = 8\ndx = 1 um\n[load]\nforce = 0.64 N\n[solver]\nthreads = 1\n'
  printf '[plasticity]\nhardening = perfect\nyield_stress = 100 MPa\nmax_outer = 2\n'; } > flat_overload.ini
plastic_stop plastic_stop_flat_overload 30 flat_overload.ini
# the Swift sphere with C = 1e9 (nearly perfectly plastic at 358 MPa) on 20 x 20 in 3 load steps:
# the outer iteration cycles with a growing change (before: 266 s, every step at its cap); with
# the warm start and Anderson mixing of theory §9.6 it converges, so max_outer = 2 keeps a stop
{ printf '[mesh]\nnx = 20\nny = 20\ndx = 6 um\n[geometry]\nshape = sphere\nradius = 5 mm\n'
  printf '[body2]\nrigid = yes\n[load]\nforce = 5 N\n[solver]\nthreads = 1\n'
  printf '[plasticity]\nhardening = swift\nswift_B = 50 MPa\nswift_C = 1e9\nswift_n = 0.095\n'
  printf 'load_steps = 3\nmax_outer = 2\n'; } > swift_c1e9.ini
plastic_stop plastic_stop_swift_c1e9 30 swift_c1e9.ini
# the running-in of cases/default.ini on 32 x 32, perfectly plastic at 40 MPa: the fixed point
# stalls at its cap (before: 3000 sweeps in every elastic-plastic step, 18 of them). The row keeps
# the scene it was made on, the 10 mm track (p_H 447 MPa) with 3 um of 0.4 um layers, at 50 MPa
# until the elastic stresses were folded into the residual stress operator (theory §8.9): that
# moved the round-off of this ill-posed scene, and at 50 MPa it stalled at the 18th step instead
# of the 6th (15.7 s; 36 s under the sanitizers). At 40 MPa it stalls at the 5th step (1.6 s;
# with the spectral kernel, the default since session 33, at the 5th step after 275 joint
# evaluations, the budget max_outer x max_plastic: 15 s, 82 s under the sanitizers)
sed -e 's/^n\([xy]\) = 64/n\1 = 32/' -e 's/^hardening = swift/hardening = perfect\nyield_stress = 40 MPa/' \
    -e '/^swift_/d' -e '/^dir = /d' -e 's/^width = .*/width = 10 mm/' -e 's/^dz = .*/dz = 0.4 um/' \
    -e 's/^depth = .*/depth = 3 um/' "$REPO/cases/default.ini" > runin_y40.ini
printf '[solver]\nthreads = 1\n' >> runin_y40.ini
plastic_stop plastic_stop_runin_y40 30 runin_y40.ini surface_final

echo "robustness: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
