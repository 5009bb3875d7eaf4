#!/bin/sh
# The MPI build (bin/microcontact-mpi, README "Running on a cluster") under mpirun:
#  1. the distributed elastic operator against the direct sum and the serial fft operator, with
#     1, 2, 3 and 4 processes, and the same bits (hashes) for every process count (the same
#     program checks the shared reads of io/file.h: rank 0's bytes, its error, a rank short of
#     memory);
#  2. whole runs with 1, 2 and 3 processes (3: an uneven split) against the serial program: the
#     same files, pressure, gap, displacement and the stresses to <= 1e-12 relative (the one-line
#     transforms of operator/dfft.c and the row-wise sums differ from the serial program's by
#     round-off only; plain Polonsky-Keer: the solver's tier, below), the
#     contact numbers of summary.json (load, approach, area, p_max, iterations) alike; and P = 1,
#     2 and 3 the same bits: the contact solvers keep to their rank's rows and add their sums row
#     by row in row order over the ranks (contact_internal.h, core/dist.h). On the solver paths
#     cg and pk, free and periodic grids, with a pressure cap (cg's nested solve) and with a
#     lubricant (the volume equilibrium's repeated solves);
#     The elastic-plastic stage and the running-in (their volume replicated on every rank; the
#     contact solves, eigenstrain operators, elastic stress layers and return maps split): the
#     plastic fields and the plastic figures of
#     summary.json to the same 1e-12 and the same bits for P = 1, 2, 3; runin.csv the same text;
#  2b. a running-in under mpirun stopped by a signal and resumed with --resume gives the files of
#     an uninterrupted run: the signal to rank 0 alone (the ranks agree to stop at the same step),
#     and to the whole process group (mpirun ends the job; the checkpoint stays);
#  3. what cannot run distributed is refused with P > 1 (exit 2, the key named, no directory);
#  4. a grid the memory guard refuses serially under a limit runs with 2 and 3 processes under
#     the same per-process limit, gives the serial answer, and stays within the guard's figure.
#  1b. the eigenstrain operators' fft backends distributed (plastic/eigen_op.h): residual stress,
#     p3 and residual u_z against the serial operators to <= 1e-12 on every grid type, with 1, 2
#     and 3 processes, and the same bits (hashes) for every process count; and the plastic
#     loop's split (the elastic stress layers bit for bit against the whole field; a yielding
#     sphere, joint and nested, whole and windowed, against the same run built serially to
#     1e-10, every rank's rows yielding, the same hashes for P = 1, 2, 3);
#  5. the inputs are read on rank 0 alone (strace: no other rank opens the case, a surface, a data
#     file or the checkpoint), and an input that cannot be read fails as the serial run does.
#   tests/cli/mpi.sh PROGRAM MPI_PROGRAM MPI_OPERATOR_TEST NPY_COMPARE [MPI_EIGEN_TEST]
set -u
PROG=$1 MPROG=$2 OPTEST=$3 CMP=$4 EIGTEST=${5:-}
T=$(mktemp -d "${TMPDIR:-/tmp}/mc_mpi.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT INT TERM
# as root (CI) OpenMPI needs --allow-run-as-root; more processes than cores: --oversubscribe.
# One thread per process: the processes are the parallelism.
export OMP_NUM_THREADS=1
MPIRUN="mpirun --allow-run-as-root --oversubscribe"
pass=0 fail=0
ok() { echo "PASS $*"; pass=$((pass + 1)); }
bad() { echo "FAIL $*"; fail=$((fail + 1)); }

# ---- 1. the operator ------------------------------------------------------------------------
for np in 1 2 3 4; do
    if $MPIRUN -np $np "$OPTEST" > "$T/op$np.log" 2>&1; then
        ok "distributed operator, $np processes: $(tail -1 "$T/op$np.log")"
    else
        bad "distributed operator, $np processes:"; grep -v '^PASS\|^hash' "$T/op$np.log"
    fi
    grep '^hash' "$T/op$np.log" > "$T/hash$np"
done
for np in 2 3 4; do
    if [ -s "$T/hash1" ] && cmp -s "$T/hash1" "$T/hash$np"; then
        ok "distributed operator: $np processes give the same bits as 1 ($(wc -l < "$T/hash1") results)"
    else
        bad "distributed operator: $np processes do not give the bits of 1"; diff "$T/hash1" "$T/hash$np"
    fi
done

# ---- 1b. the eigenstrain operators ------------------------------------------------------------
if [ -n "$EIGTEST" ]; then
    for np in 1 2 3; do
        if $MPIRUN -np $np "$EIGTEST" > "$T/eig$np.log" 2>&1; then
            ok "distributed eigenstrain operators, $np processes: $(tail -1 "$T/eig$np.log")"
        else
            bad "distributed eigenstrain operators, $np processes:"; grep -v '^PASS\|^hash' "$T/eig$np.log"
        fi
        grep '^hash' "$T/eig$np.log" > "$T/ehash$np"
    done
    for np in 2 3; do
        if [ -s "$T/ehash1" ] && cmp -s "$T/ehash1" "$T/ehash$np"; then
            ok "distributed eigenstrain operators and plastic loop: $np processes give the bits of 1 ($(wc -l < "$T/ehash1") cases)"
        else
            bad "distributed eigenstrain operators: $np processes do not give the bits of 1"; diff "$T/ehash1" "$T/ehash$np"
        fi
    done
fi

# ---- 2. whole runs against the serial program -----------------------------------------------
# runin.csv without its seconds column (as tests/cli/robustness.sh), the one that may differ
nosec() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "seconds") s = i }
             { o = ""; for (i = 1; i <= NF; i++) if (i != s) o = o (o == "" ? "" : ",") $i; print o }' "$1"
}
# jget FILE SECTION KEY (as tests/cli/cases.sh: sections at two spaces, keys at four)
jget() {
    awk -v sec="$2" -v key="$3" '
        $0 ~ "^  \"" sec "\": [{]" { on = 1; next }
        on && /^  [}]/ { on = 0 }
        on && $0 ~ "^    \"" key "\": " { sub(/^[^:]*: /, ""); sub(/,$/, ""); print; exit }' "$1"
}
# the agreement the issue asks for: 1e-12 relative (to the largest value of a field)
TOL=1e-12
runcase() { # NAME CASE SET...: serial, then 1, 2 and 3 processes (STOL: against serial)
    name=$1 case=$2; shift 2
    "$PROG" run "$case" --out "$T/$name-s" --quiet "$@" > "$T/$name-s.log" 2>&1 ||
        { bad "$name: the serial run failed"; cat "$T/$name-s.log"; return; }
    for np in 1 2 3; do
        out="$T/$name-$np"
        if ! $MPIRUN -np $np "$MPROG" run "$case" --out "$out" --quiet "$@" > "$out.log" 2>&1; then
            bad "$name, $np processes: the run failed"; cat "$out.log"; continue
        fi
        if [ "$(cd "$T/$name-s" && ls)" != "$(cd "$out" && ls)" ]; then
            bad "$name, $np processes: other files than the serial run"; continue
        fi
        for f in pressure gap displacement von_mises stress_xz plastic_strain \
            residual_displacement residual_von_mises surface_final; do
            [ -f "$T/$name-s/$f.npy" ] || continue
            if r=$("$CMP" "$T/$name-s/$f.npy" "$out/$f.npy" "${STOL:-$TOL}"); then
                ok "$name, $np processes: $f.npy against serial: $r"
            else
                bad "$name, $np processes: $f.npy against serial: $r"
            fi
        done
        # summary.json: the serial one but for the timings ("..._s": seconds); where the
        # numbers differ in their last bits, the same keys and texts (the numbers: below)
        grep -v '_s": ' "$T/$name-s/summary.json" > "$T/$name-s.nots"
        grep -v '_s": ' "$out/summary.json" > "$out.nots"
        nonum() { sed -E 's/-?[0-9][0-9.eE+-]*//g' "$1"; }
        if cmp -s "$T/$name-s.nots" "$out.nots"; then
            ok "$name, $np processes: summary.json the serial one (timings aside)"
        elif [ "$(nonum "$T/$name-s.nots")" = "$(nonum "$out.nots")" ]; then
            ok "$name, $np processes: summary.json the serial one's keys and texts (timings aside)"
        else
            bad "$name, $np processes: summary.json differs from the serial one beyond numbers"
            diff "$T/$name-s.nots" "$out.nots" | head -20
        fi
        for k in load approach area p_max iterations converged; do
            a=$(jget "$T/$name-s/summary.json" contact $k) b=$(jget "$out/summary.json" contact $k)
            if awk -v a="$a" -v b="$b" -v t="${STOL:-$TOL}" 'BEGIN {
                    if (a == b) exit 0
                    if (a !~ /^[-+0-9.eE]+$/ || b !~ /^[-+0-9.eE]+$/) exit 1
                    d = a - b; if (d < 0) d = -d; m = a < 0 ? -a : a; exit !(d <= t * m) }'; then
                ok "$name, $np processes: contact.$k = $b (serial $a)"
            else
                bad "$name, $np processes: contact.$k = $b, serial $a"
            fi
        done
        # the plastic figures of summary.json
        [ -f "$T/$name-s/plastic_strain.npy" ] || continue
        for k in peq_max residual_max plastic_volume outer_iterations steps_done converged; do
            a=$(jget "$T/$name-s/summary.json" plastic $k) b=$(jget "$out/summary.json" plastic $k)
            if [ -n "$a" ] && awk -v a="$a" -v b="$b" -v t="${STOL:-$TOL}" 'BEGIN {
                    if (a == b) exit 0
                    if (a !~ /^[-+0-9.eE]+$/ || b !~ /^[-+0-9.eE]+$/) exit 1
                    d = a - b; if (d < 0) d = -d; m = a < 0 ? -a : a; exit !(d <= t * m) }'; then
                ok "$name, $np processes: plastic.$k = $b (serial $a)"
            else
                bad "$name, $np processes: plastic.$k = '$b', serial '$a'"
            fi
        done
    done
    for f in pressure gap displacement plastic_strain residual_displacement surface_final \
        runin.csv; do
        [ -f "$T/$name-1/$f.npy" ] || [ -f "$T/$name-1/$f" ] || continue
        case $f in *.csv) nosec "$T/$name-1/$f" > "$T/$name-1.nosec"
                          for np in 2 3; do
                              if nosec "$T/$name-$np/$f" | cmp -s - "$T/$name-1.nosec"; then
                                  ok "$name: $f the same text with 1 and $np processes (seconds aside)"
                              else
                                  bad "$name: $f differs between 1 and $np processes"
                              fi
                          done
                          continue ;;
        esac
        for np in 2 3; do
            if cmp -s "$T/$name-1/$f.npy" "$T/$name-$np/$f.npy"; then
                ok "$name: $f.npy the same bits with 1 and $np processes"
            else
                bad "$name: $f.npy differs between 1 and $np processes: $("$CMP" "$T/$name-1/$f.npy" "$T/$name-$np/$f.npy" 1)"
            fi
        done
    done
}
# the Hertz point (free grid, odd size) with a few stress layers; a rough sphere at 128^2 with
# friction in the stresses; a lubricant volume equilibrium (repeated solves, a periodic strip)
runcase hertz cases/hertz_point.ini --set stress.layers=4
runcase rough cases/rough_sphere.ini --set mesh.nx=128 --set mesh.ny=128 --set stress.layers=3 \
    --set stress.depth_max=20um
runcase lube cases/lubricated_equilibrium.ini
# the other solver paths: plain Polonsky-Keer on a free grid and on a periodic lubricated one
# (its approach-free load balance, the lower bound); cg with a pressure cap (the nested solve)
# Against the serial program plain Polonsky-Keer on the Hertz case is held to the solver's tier,
# not round-off: the serial program adds its sums in the blocks of core/psum.h, the MPI program
# row by row (contact_internal.h), and this unpreconditioned recurrence carries that round-off
# into iterates that stop at another point inside the stopping tolerance 1e-8 (contact.h):
# measured 7.4e-8 in the pressure, 3.4e-9 in the gap. 100 x the tolerance leaves room for the
# problem's conditioning. Between the process counts the bits must still be the same.
STOL=1e-6
runcase pk cases/hertz_point.ini --set solver.method=pk
unset STOL
runcase pk-periodic cases/lubricated_equilibrium.ini --set solver.method=pk
runcase cap cases/pressure_cap.ini
# a contact of 8.6 % of a 255 x 200 grid: cg restricted to the contact's box (contact_box.c),
# whose box-sized operator and solver are distributed over their own rows
runcase box cases/hertz_point.ini --set mesh.nx=255 --set mesh.ny=200 --set mesh.dx=5um \
    --set stress.layers=2
# the elastic-plastic stage (its volume arrays whole on every rank; the contact solves split;
# the default spectral kernel's operators replicated, every rank computing the same bits): the
# rough sphere that yields at 24^2 (three load steps, 22 graded layers); and the default
# running-in at 16^2 with two forces and two speeds (8 steps, 2 of them elastic-plastic: the
# lubricant volume equilibrium's solves inside the plastic loop). Measured against serial:
# 3.9e-15 in the plastic strain (44^2 sphere), 1.1e-13 after the default running-in at 64^2;
# the same bits for P = 1, 2, 3. With kernel = cuboid the eigenstrain operators are split over
# the ranks and the joint iteration keeps to each rank's rows: the same sphere again.
runcase plastic cases/elastic_plastic.ini --set mesh.nx=24 --set mesh.ny=24
runcase plastic_cuboid cases/elastic_plastic.ini --set mesh.nx=24 --set mesh.ny=24 \
    --set plasticity.kernel=cuboid
runcase runin cases/default.ini --set mesh.nx=16 --set mesh.ny=16 --set runin.forces=1086N,2172N \
    --set runin.speeds=3000,200rpm
# the twin-disc strip (periodic y) at 192 x 24 cells of 4 um, one running-in step that yields:
# the joint iteration keeping to each rank's rows on a periodic grid (theory.md §8.4). Measured
# against serial: 3.1e-13 in the pressure, 2.1e-13 in the plastic strain; P = 1, 2, 3 the same bits.
runcase strip cases/twin_disc_whole.ini --set mesh.nx=192 --set mesh.ny=24 --set mesh.dx=4um \
    --set runin.forces=1086N --set runin.speeds=350rpm --set lubrication.rpm=350rpm \
    --set plasticity.dz=1um --set plasticity.depth=6um --set plasticity.kernel=cuboid

# ---- 2b. a running-in stopped under mpirun and resumed ----------------------------------------
# The default running-in at 16^2 (36 steps, 8 elastic-plastic; about 1.5 s with 2 processes),
# uninterrupted with 2 processes, then stopped once its first checkpoint is there and resumed
# with mpirun -np 2 ... --resume: the files of the uninterrupted run, bit for bit (runin.csv but
# for its seconds), and the serial run's to 1e-12. WHO = rank0: SIGTERM to rank 0 alone (the
# ranks agree to stop at the next step boundary or outer iteration, runin.c: rank 0 says how to
# resume); WHO = rank1: to rank 1 alone (the same; without the agreement rank 0 would wait in
# the next step's collectives for ever); WHO = group: SIGTERM to mpirun and every rank at once
# (mpirun ends the job).
RI="cases/default.ini --set mesh.nx=16 --set mesh.ny=16"
"$PROG" run $RI --out "$T/ri-s" --quiet > "$T/ri-s.log" 2>&1 || { bad "resume: the serial run failed"; cat "$T/ri-s.log"; }
$MPIRUN -np 2 "$MPROG" run $RI --out "$T/ri-u" --quiet > "$T/ri-u.log" 2>&1 ||
    { bad "resume: the uninterrupted 2-process run failed"; cat "$T/ri-u.log"; }
stop_resume() { # WHO
    who=$1 out="$T/ri-$1"
    # (a deadlock, ranks that do not agree, ends red after 120 s)
    timeout -s KILL 120 $MPIRUN -np 2 "$MPROG" run $RI --out "$out" > "$out.log" 2> "$out.err" &
    bg=$!
    n=0
    while [ $n -lt 3000 ] && [ ! -f "$out/checkpoint/state.bin" ] && kill -0 $bg 2> /dev/null; do
        sleep 0.01; n=$((n + 1))
    done
    # mpirun is timeout's child, the ranks mpirun's (each in a process group of its own)
    mpid=$(pgrep -P $bg) ranks=""
    [ -n "$mpid" ] && ranks=$(pgrep -P "$mpid")
    case $who in
    rank*)
        for c in $ranks; do
            if tr '\0' '\n' < "/proc/$c/environ" 2> /dev/null |
                grep -qx "OMPI_COMM_WORLD_RANK=${who#rank}"; then
                kill -TERM "$c"
            fi
        done ;;
    *) kill -TERM $mpid $ranks ;; # as a terminal's Ctrl-C would: mpirun and every rank at once
    esac
    wait $bg
    why=""
    [ -e "$out/summary.json" ] && why="$why it ended before the signal (or committed results);"
    [ -f "$out/checkpoint/state.bin" ] || why="$why no checkpoint;"
    if [ "$who" != group ]; then # rank 0 speaks, whichever rank the signal reached
        grep -q "stopped by .* after [0-9]* of 36 steps" "$out.err" &&
            grep -q "continue with:" "$out.err" ||
            why="$why no stop message or resume hint: $(tail -3 "$out.err" | tr '\n' ' ');"
    fi
    if [ -n "$why" ]; then bad "resume ($who): stopped:$why"; return; fi
    if ! $MPIRUN -np 2 "$MPROG" run $RI --out "$out" --resume --quiet > "$out.log" 2> "$out.err"; then
        bad "resume ($who): mpirun -np 2 --resume failed"; cat "$out.err"; return
    fi
    from=$(jget "$out/summary.json" runin resumed_from)
    [ "${from:-0}" -gt 0 ] || why="$why resumed_from '$from';"
    [ -e "$out/checkpoint" ] && why="$why the checkpoint is left;"
    [ "$(nosec "$out/runin.csv")" = "$(nosec "$T/ri-u/runin.csv")" ] || why="$why runin.csv differs;"
    for f in pressure.npy gap.npy displacement.npy surface_final.npy plastic_strain.npy \
        residual_displacement.npy residual_von_mises.npy material_ratio.csv runin.gp; do
        cmp -s "$out/$f" "$T/ri-u/$f" || why="$why $f differs;"
    done
    for f in pressure gap plastic_strain residual_displacement surface_final; do
        "$CMP" "$T/ri-s/$f.npy" "$out/$f.npy" "$TOL" > /dev/null || why="$why $f.npy against serial: $("$CMP" "$T/ri-s/$f.npy" "$out/$f.npy" "$TOL");"
    done
    if [ -z "$why" ]; then
        ok "resume ($who): stopped after step $from of 36, resumed with 2 processes: the uninterrupted run's files, serial to $TOL"
    else
        bad "resume ($who):$why"
    fi
}
stop_resume rank0
stop_resume rank1
stop_resume group

# ---- 2c. the transposes: shared memory on one machine, FFTW-MPI's on request -------------------
# operator/dfft.h: on one machine the transposes copy straight out of the other ranks' shared
# buffers; MC_TRANSPOSES=fftw takes FFTW-MPI's (what runs across machines). Both move the same
# values: the same bits in every output, and the run's MPI line says which it used. A value
# other than auto or fftw is refused (exit 2, the variable named, nothing written).
TR="--set mesh.nx=96 --set mesh.ny=80"
$MPIRUN -np 2 "$MPROG" run cases/rough_sphere.ini --out "$T/tr-shm" $TR > "$T/tr-shm.log" 2>&1 &&
    MC_TRANSPOSES=fftw $MPIRUN -x MC_TRANSPOSES -np 2 "$MPROG" run cases/rough_sphere.ini \
        --out "$T/tr-fftw" $TR > "$T/tr-fftw.log" 2>&1
rc=$?
if [ $rc -ne 0 ]; then
    bad "transposes: the runs failed (exit $rc)"; tail -5 "$T/tr-shm.log" "$T/tr-fftw.log"
else
    grep -q "transposes through shared memory" "$T/tr-shm.log" &&
        grep -q "transposes by FFTW-MPI" "$T/tr-fftw.log" &&
        ok "transposes: the MPI line names them (shared memory; FFTW-MPI with MC_TRANSPOSES=fftw)" ||
        bad "transposes: the MPI lines do not name shared memory and FFTW-MPI"
    same=1
    for f in "$T"/tr-shm/*.npy; do
        cmp -s "$f" "$T/tr-fftw/$(basename "$f")" || { same=0; echo "differs: $(basename "$f")"; }
    done
    [ $same = 1 ] && ok "transposes: shared memory and FFTW-MPI's give the same bits ($(ls "$T"/tr-shm/*.npy | wc -l) arrays)" ||
        bad "transposes: shared memory and FFTW-MPI's differ"
fi
MC_TRANSPOSES=bogus $MPIRUN -x MC_TRANSPOSES -np 2 "$MPROG" run cases/hertz_point.ini \
    --out "$T/tr-bad" > "$T/tr-bad.log" 2>&1
rc=$?
if [ $rc -eq 2 ] && grep -q "MC_TRANSPOSES=bogus" "$T/tr-bad.log" && [ ! -e "$T/tr-bad" ]; then
    ok "transposes: MC_TRANSPOSES=bogus refused (exit 2, named, nothing written)"
else
    bad "transposes: MC_TRANSPOSES=bogus: exit $rc"; cat "$T/tr-bad.log"
fi

# ---- 3. refused with more than one process ----------------------------------------------------
refused() { # NAME WANT CASE SET...: exit ${CODE:-2}, the message naming WANT, no output directory
    name=$1 want=$2 case=$3 code=${CODE:-2}; shift 3
    $MPIRUN -np 2 "$MPROG" run "$case" --out "$T/$name" "$@" > "$T/$name.log" 2>&1
    rc=$?
    if [ $rc -eq "$code" ] && grep -q -- "$want" "$T/$name.log" && [ ! -e "$T/$name" ]; then
        ok "refused with 2 processes: $name ($(grep -m1 error "$T/$name.log"))"
    else
        bad "$name with 2 processes: exit $rc (want $code, a message naming '$want', no directory)"
        cat "$T/$name.log"
    fi
}
refused plans '\[solver\] plans' cases/hertz_point.ini --set solver.plans=measure
# the memory guard decides for all processes alike (rank 0's available memory): exit 3 on all
export MC_MEMORY_LIMIT=1000
CODE=3
refused memory 'needs about' cases/hertz_point.ini
unset MC_MEMORY_LIMIT CODE

# ---- 4. memory that divides: refused serially under a limit, run with 2 and 3 processes -------
# The memory guard's figure is per process (pipeline/memguard.c: the operators' slabs and the
# contact solvers' work arrays 1/P, the rest replicated). The Hertz point of bench mpi at 768^2
# (no stress layers) under a limit halfway between its serial and its 2-process figure: the
# serial program refuses it (exit 3, no directory); the MPI program runs it under the same
# per-process limit with 2 and with 3 processes and gives the serial answer of the control (the
# same case without a limit) to the 1e-12 of part 2. And the guard's figure bounds the measured
# peak of rank 0 (VmHWM; the rank with the most rows): 114 MiB against 127.5 with 2 processes,
# 97 against 105.3 with 3 when measured; with the solvers' work arrays whole on every rank (before
# they were split) the peaks were 129 and 119, above the figures. The figures come from the
# guard's own message ("needs about ... (X MiB) ... (Y MiB each with 2)").
printf '[mesh]\nnx = 768\nny = 768\ndx = 0.72890625um\n[geometry]\nshape = sphere\nradius = 10mm\n[body1]\nE = 210GPa\nnu = 0.3\n[body2]\nE = 210GPa\nnu = 0.3\n[load]\nforce = 100N\n' > "$T/demo.ini"
figure() { sed -n "s/.*needs about [0-9.]* GiB (\([0-9.]*\) MiB).*/\1/p" "$1"; }
MC_MEMORY_LIMIT=1 "$PROG" run "$T/demo.ini" --out "$T/demo-probe" > "$T/demo-probe.log" 2>&1
MC_MEMORY_LIMIT=1 $MPIRUN -x MC_MEMORY_LIMIT -np 3 "$MPROG" run "$T/demo.ini" --out "$T/demo-probe" \
    > "$T/demo-probe3.log" 2>&1
e1=$(figure "$T/demo-probe.log") e3=$(figure "$T/demo-probe3.log")
e2=$(sed -n 's/.*(\([0-9.]*\) MiB each with 2).*/\1/p' "$T/demo-probe.log")
if [ -z "$e1" ] || [ -z "$e2" ] || [ -z "$e3" ] ||
    ! awk -v a="$e1" -v b="$e2" -v c="$e3" 'BEGIN { exit !(c < b && b < a) }'; then
    bad "memory demo: no falling serial, 2- and 3-process figures in the guard's messages"
    cat "$T/demo-probe.log" "$T/demo-probe3.log"
else
    limit=$(awk -v a="$e1" -v b="$e2" 'BEGIN { printf "%.0f", 0.5 * (a + b) * 1048576 }')
    MC_MEMORY_LIMIT=$limit "$PROG" run "$T/demo.ini" --out "$T/demo-s" --quiet > "$T/demo-s.log" 2>&1
    rc=$?
    if [ $rc -eq 3 ] && grep -q "needs about" "$T/demo-s.log" && [ ! -e "$T/demo-s" ]; then
        ok "memory demo: serial needs $e1 MiB, refused under a limit of $limit bytes"
    else
        bad "memory demo: serial under $limit bytes: exit $rc (want 3, refused)"; cat "$T/demo-s.log"
    fi
    "$PROG" run "$T/demo.ini" --out "$T/demo-c" --quiet > "$T/demo-c.log" 2>&1 ||
        bad "memory demo: the control (serial, no limit) failed"
    for np in 2 3; do
        [ $np -eq 2 ] && e=$e2 || e=$e3
        if MC_MEMORY_LIMIT=$limit $MPIRUN -x MC_MEMORY_LIMIT -np $np "$MPROG" run "$T/demo.ini" \
            --out "$T/demo-$np" --quiet > "$T/demo-$np.log" 2>&1; then
            ok "memory demo: $np processes (the guard: $e MiB each) run under the same limit"
        else
            bad "memory demo: $np processes under $limit bytes failed"; cat "$T/demo-$np.log"
            continue
        fi
        for f in pressure gap displacement; do
            if r=$("$CMP" "$T/demo-c/$f.npy" "$T/demo-$np/$f.npy" "$TOL"); then
                ok "memory demo, $np processes: $f.npy against the serial control: $r"
            else
                bad "memory demo, $np processes: $f.npy against the serial control: $r"
            fi
        done
        peak=$(sed -n 's/.*peak memory \([0-9]*\) MiB.*/\1/p' "$T/demo-$np.log")
        if [ -n "$peak" ] && awk -v m="$peak" -v e="$e" 'BEGIN { exit !(m <= e) }'; then
            ok "memory demo, $np processes: rank 0's peak $peak MiB within the guard's $e MiB"
        else
            bad "memory demo, $np processes: rank 0's peak '$peak' MiB above the guard's $e MiB"
        fi
    done
fi
if $MPIRUN -np 2 "$MPROG" verify --list > "$T/verify.log" 2>&1; then
    bad "verify with 2 processes was not refused"
elif grep -q "only 'run' is distributed" "$T/verify.log"; then
    ok "refused with 2 processes: verify"
else
    bad "verify with 2 processes: no message"; cat "$T/verify.log"
fi

# ---- 5. the inputs read on rank 0 alone ------------------------------------------------------
# Under mpirun rank 0 alone opens each input and every rank receives its bytes, or its error
# (io/file.c, pipeline/checkpoint.c over mc_dist_share_read of core/dist.h): the case file (a
# pipe too), the surfaces, the data files (hardening tables, pressure maps), the checkpoint on
# --resume. An input only rank 0 can see cannot be staged on one machine; instead each rank runs
# under strace and its file system calls (open, stat, access, ...: strace's %file class) are
# searched for the inputs' names: rank 0 must name each, no other rank any (nor the output
# directory, rank 0's). And an input that cannot be read fails on every rank alike: the serial
# program's exit code and its message naming the file, said once (rank 0 speaks), never a hang
# (a rank that went on alone would wait for ever in the next collective: timeout).
TAB="--set mesh.nx=24 --set mesh.ny=24 --set plasticity.hardening=table
     --set plasticity.yield_stress= --set plasticity.tangent_modulus="
if command -v strace > /dev/null 2>&1; then
    traced() { # NAME NP FILES CASE ARG...: mpirun -np NP under strace, rank r's calls in $T/NAME.tr.r
        name=$1 np=$2 files=$3; shift 3
        rm -f "$T/$name.tr."*
        if ! timeout -s KILL 180 $MPIRUN -np "$np" sh -c \
            'exec strace -qq -f -e trace=%file -o "$0.$OMPI_COMM_WORLD_RANK" "$@"' "$T/$name.tr" \
            "$MPROG" run "$@" > "$T/$name.log" 2>&1; then
            bad "inputs ($name, $np processes): the run failed"; cat "$T/$name.log"; return 1
        fi
        why=""
        for r in $(seq 0 $((np - 1))); do
            [ -s "$T/$name.tr.$r" ] || { why="$why no trace of rank $r;"; continue; }
            for f in $files; do # (execve's arguments name them too: not a read)
                k=$(grep -v ' execve(' "$T/$name.tr.$r" | grep -cF -- "$f")
                if [ "$r" -eq 0 ] && [ "$k" -eq 0 ]; then why="$why rank 0 never opened $f;"; fi
                if [ "$r" -gt 0 ] && [ "$k" -gt 0 ]; then
                    why="$why rank $r named $f $k times: $(grep -v ' execve(' "$T/$name.tr.$r" | grep -m1 -F -- "$f");"
                fi
            done
        done
        if [ -z "$why" ]; then
            ok "inputs ($name, $np processes): rank 0 alone opened $(echo $files | sed 's|[^ ]*/||g')"
        else
            bad "inputs ($name, $np processes):$why"; return 1
        fi
    }
    samebits() { # NAME A B: pressure.npy of two runs, the same bits
        if cmp -s "$2/pressure.npy" "$3/pressure.npy"; then
            ok "inputs ($1): pressure.npy the same bits as $(basename "$2")"
        else
            bad "inputs ($1): pressure.npy differs from $(basename "$2")"
        fi
    }
    # a measured X3P surface (libzip over rank 0's bytes), with 2 and 3 processes
    "$PROG" run cases/measured.ini --out "$T/in-x3p-s" --quiet > "$T/in-x3p-s.log" 2>&1 ||
        bad "inputs: the serial measured run failed"
    for np in 2 3; do
        traced in-x3p-$np $np "cases/measured.ini cases/data/ground_sample.x3p $T/in-x3p-$np" \
            cases/measured.ini --out "$T/in-x3p-$np" --quiet || continue
        if r=$("$CMP" "$T/in-x3p-s/pressure.npy" "$T/in-x3p-$np/pressure.npy" "$TOL"); then
            ok "inputs (x3p, $np processes): pressure.npy against serial: $r"
        else
            bad "inputs (x3p, $np processes): pressure.npy against serial: $r"
        fi
    done
    samebits x3p "$T/in-x3p-2" "$T/in-x3p-3"
    # a prescribed pressure map (text), and a hardening table of the elastic-plastic stage
    traced in-map 2 "cases/prescribed_pressure.ini cases/data/hertz_pressure.txt $T/in-map" \
        cases/prescribed_pressure.ini --out "$T/in-map" --quiet --set stress.layers=2
    printf 'eps_p, sigma_y_MPa\n0, 1000\n0.05, 1400\n0.5, 1600\n' > "$T/flow.csv"
    "$PROG" run cases/elastic_plastic.ini --out "$T/in-tab-s" --quiet $TAB \
        --set plasticity.table="$T/flow.csv" > "$T/in-tab-s.log" 2>&1 || bad "inputs: the serial table run failed"
    for np in 2 3; do
        traced in-tab-$np $np "cases/elastic_plastic.ini $T/flow.csv $T/in-tab-$np" cases/elastic_plastic.ini \
            --out "$T/in-tab-$np" --quiet $TAB --set plasticity.table="$T/flow.csv" || continue
        if r=$("$CMP" "$T/in-tab-s/plastic_strain.npy" "$T/in-tab-$np/plastic_strain.npy" "$TOL"); then
            ok "inputs (table, $np processes): plastic_strain.npy against serial: $r"
        else
            bad "inputs (table, $np processes): plastic_strain.npy against serial: $r"
        fi
    done
    samebits table "$T/in-tab-2" "$T/in-tab-3"
    # the case file through a pipe: mpirun hands its standard input to rank 0 alone
    "$PROG" run cases/hertz_point.ini --out "$T/in-pipe-s" --quiet > /dev/null 2>&1
    for np in 2 3; do
        if timeout -s KILL 120 $MPIRUN -np $np "$MPROG" run /dev/stdin --out "$T/in-pipe-$np" --quiet \
            < cases/hertz_point.ini > "$T/in-pipe-$np.log" 2>&1; then
            if r=$("$CMP" "$T/in-pipe-s/pressure.npy" "$T/in-pipe-$np/pressure.npy" "$TOL"); then
                ok "inputs (the case on standard input, $np processes): pressure.npy against serial: $r"
            else
                bad "inputs (the case on standard input, $np processes): $r"
            fi
        else
            bad "inputs (the case on standard input, $np processes): exit $?"; cat "$T/in-pipe-$np.log"
        fi
    done
    # the checkpoint on --resume: a serial running-in stopped after its first checkpoint, resumed
    # with 2 processes (only rank 0 sees DIR/checkpoint)
    RI="cases/default.ini --set mesh.nx=16 --set mesh.ny=16"
    "$PROG" run $RI --out "$T/in-ck" > "$T/in-ck-s.log" 2>&1 &
    bg=$! n=0
    while [ $n -lt 3000 ] && [ ! -f "$T/in-ck/checkpoint/state.bin" ] && kill -0 $bg 2> /dev/null; do
        sleep 0.01; n=$((n + 1))
    done
    kill -TERM $bg 2> /dev/null; { wait $bg; } 2> /dev/null
    if [ ! -f "$T/in-ck/checkpoint/state.bin" ] || [ -e "$T/in-ck/summary.json" ]; then
        bad "inputs (checkpoint): the serial running-in left no checkpoint"; cat "$T/in-ck-s.log"
    elif traced in-ck 2 "cases/default.ini $T/in-ck/checkpoint/state.bin $T/in-ck" $RI \
        --out "$T/in-ck" --quiet --resume; then
        from=$(jget "$T/in-ck/summary.json" runin resumed_from)
        if [ "${from:-0}" -gt 0 ]; then
            ok "inputs (checkpoint): resumed from step $from with 2 processes"
        else
            bad "inputs (checkpoint): resumed_from '$from'"
        fi
    fi
else
    echo "SKIP inputs read on rank 0: strace is not installed (make deps installs it)"
fi
# inputs that cannot be read: the serial program's exit code and message (the microcontact lines
# of stderr; mpirun adds its own), once, within the timeout, and no output directory
printf 'eps_p, sigma_y\n0, 1000\n0.1, 0x10\n' > "$T/bad.csv"
mkdir -p "$T/a_dir.x3p"
unreadable() { # NAME CASE ARG...
    name=$1; shift
    "$PROG" run "$@" --out "$T/un-$name-s" > /dev/null 2> "$T/un-$name-s.err"
    want=$?
    grep '^microcontact' "$T/un-$name-s.err" > "$T/un-$name-s.msg"
    for np in 2 3; do
        timeout -s KILL 120 $MPIRUN -np $np "$MPROG" run "$@" --out "$T/un-$name-$np" \
            > /dev/null 2> "$T/un-$name-$np.err"
        rc=$?
        grep '^microcontact' "$T/un-$name-$np.err" > "$T/un-$name-$np.msg"
        if [ $want -ne 0 ] && [ $rc -eq $want ] && [ -s "$T/un-$name-s.msg" ] &&
            cmp -s "$T/un-$name-s.msg" "$T/un-$name-$np.msg" && [ ! -e "$T/un-$name-$np" ] &&
            [ "$(grep -c error "$T/un-$name-$np.msg")" -eq 1 ]; then
            ok "unreadable input ($name, $np processes): exit $rc as serial: $(cat "$T/un-$name-$np.msg")"
        else
            bad "unreadable input ($name, $np processes): exit $rc (serial $want), the messages:"
            cat "$T/un-$name-s.msg" "$T/un-$name-$np.err"
        fi
    done
}
unreadable case "$T/no_such_case.ini"
unreadable surface cases/measured.ini --set roughness.file="$T/no_such_surface.x3p"
unreadable directory cases/measured.ini --set roughness.file="$T/a_dir.x3p"
unreadable table cases/elastic_plastic.ini $TAB --set plasticity.table="$T/bad.csv"
unreadable map cases/prescribed_pressure.ini --set load.pressure_file="$T/no_such_map.txt"

echo "mpi: $pass passed, $fail failed"
[ $fail -eq 0 ]
