#!/bin/sh
# bad_input.sh PROGRAM - bad input, end to end through the command line.
#
# Every row runs `PROGRAM run ...` on a malformed input (case files in tests/bad_input/, binary
# .npy and text fixtures written here at test time) and asserts the output contract of DESIGN.md:
#   - exit status 2 (bad input), or 3 for the rows of the environment (ENV_ROWS: the output
#     directory cannot be created, the memory guard refuses the scene);
#   - nothing on stdout, one message on stderr (one line; two where the usage follows);
#   - the message contains every expected fragment: the file, the line where there is one, the
#     [section] key, and what is accepted;
#   - no output file anywhere: the output directory is absent or empty (no results, no staging
#     directory, no probe file) and nothing else appeared in the working directory.
# Positive controls (valid fixtures from the same generator run and exit 0) prove that the rows
# fail for the reason they test, and a solve limited to one iteration must exit 1 and still write
# its results with "converged": false.
#
# Known defects (documented in the robustness report) are listed in KNOWN_DEFECTS, one
# "row|faults" line each, faults being exactly what the row reports today: such a row is XFAIL
# while it fails in exactly that way (any other fault fails it), and fails the script (XPASS)
# once it passes, so that its line is removed with the fix.
set -u

if [ $# -ne 1 ] || [ ! -x "$1" ]; then
    echo "usage: $0 PROGRAM (the microcontact executable)" >&2
    exit 2
fi
PROG=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
CASES=$(cd "$(dirname "$0")/../bad_input" && pwd)
T=$(mktemp -d "${TMPDIR:-/tmp}/mc_bad_input.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT INT TERM

KNOWN_DEFECTS=""
# rows whose failure is the environment's (exit 3), not the input's
ENV_ROWS="out_below_file out_is_file memory_guard"

cp "$CASES"/*.ini "$T"/ && cp -r "$CASES"/surfaces "$T"/ || exit 2
cd "$T" || exit 2

# ---- fixtures ----------------------------------------------------------------------------------
# .npy 1.0: magic, version 1.0, header length 118 (little-endian uint16 0x76 0x00), the dict padded
# with spaces to 117 bytes plus '\n' (10 + 118 = 128, a multiple of 64 as NumPy writes it).
npy_header() { printf '\223NUMPY\001\000\166\000'; printf '%-117s\n' "$1"; }
# n copies of one value given as printf octal escapes (little-endian bytes)
# shellcheck disable=SC2059 # the value is a printf escape sequence by design
values() { i=0; while [ "$i" -lt "$1" ]; do printf "$2"; i=$((i + 1)); done; }
F8_ONE='\000\000\000\000\000\000\360\077'  # 1.0  = 0x3FF0000000000000
F8_NEG='\000\000\000\000\000\000\360\277'  # -1.0 = 0xBFF0000000000000
F8_NAN='\000\000\000\000\000\000\370\177'  # NaN  = 0x7FF8000000000000
F4_ONE='\000\000\200\077'                  # 1.0f = 0x3F800000
DICT16="{'descr': '<f8', 'fortran_order': False, 'shape': (16, 16), }"

{ npy_header "$DICT16"; values 256 "$F8_ONE"; } > ones.npy
{ npy_header "$DICT16"; values 100 "$F8_ONE"; } > truncated.npy
{ npy_header "{'descr': '<i8', 'fortran_order': False, 'shape': (16, 16), }"; values 256 "$F8_ONE"; } > int64.npy
{ npy_header "{'descr': '<f4', 'fortran_order': False, 'shape': (16, 16), }"; values 256 "$F4_ONE"; } > float32.npy
{ npy_header "{'descr': '<f8', 'fortran_order': False, 'shape': (8, 16), }"; values 128 "$F8_ONE"; } > shape_8x16.npy
{ npy_header "$DICT16"; values 100 "$F8_ONE"; values 1 "$F8_NEG"; values 155 "$F8_ONE"; } > negative.npy
{ npy_header "$DICT16"; values 37 "$F8_ONE"; values 1 "$F8_NAN"; values 218 "$F8_ONE"; } > nan.npy
# micro.npy: 16 x 16 heights of 1 um (1e-6 = 0x3EB0C6F7A0B5ED8D), a valid roughness map
F8_MICRO='\215\355\265\240\367\306\260\076'
{ npy_header "$DICT16"; values 256 "$F8_MICRO"; } > micro.npy
# 16 x 16 text matrices of 1e-6: valid (control), and one with "nan" on line 4 (after a comment)
line16='1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6'
nanline='1e-6 1e-6 1e-6 1e-6 1e-6 nan 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6 1e-6'
lines16() { j=0; while [ $j -lt "$1" ]; do echo "$line16"; j=$((j + 1)); done; }
{ echo "# 16 x 16 heights"; lines16 16; } > micro_16x16.txt
{ echo "# 16 x 16 heights"; lines16 2; echo "$nanline"; lines16 13; } > nan_16x16.txt
# text inputs as other tools write them: a header line of words, one of the sizes, and 'x z'
# profiles (line scans) given as a surface
{ echo "h=16 w=16"; lines16 16; } > header_words.txt
{ echo "16 16"; lines16 16; } > header_sizes.txt
printf '0 1e-6\n4e-6 2e-6\n8e-6 1e-6\n12e-6 0\n' > profile.txt
cp profile.txt profile.xyz
{ echo "h=16 w=16"; echo "0 0 1e-6"; } > header_words.xyz
# hardening tables breaking a documented rule
printf 'eps_p, sigma_y\n0, 0x10\n0.1, 1200\n' > table_hex.csv
printf '0, 2e6\n0.1, 3e6\n' > table_huge.csv  # MPa: 2e12 Pa, beyond yield_stress <= 1e12 Pa
printf '0.01, 1000\n0.1, 1200\n' > table_start.csv
echo "1 2 3" > not_wisdom.txt  # [solver] wisdom_file that is not FFTW wisdom
mkdir a_directory
: > regular_file
mkfifo a_fifo.x3p  # a FIFO without writer: an open for reading would block for ever

# ---- the harness -------------------------------------------------------------------------------
pass=0 fail=0 xfail=0
snapshot() { ls -A "$T" | grep -v -e '^stdout$' -e '^stderr$' -e '^before$' -e '^after$'; }

# row NAME OUTDIR NLINES FRAGMENT... -- ARGS...: run `PROGRAM run ARGS` and check the contract.
# OUTDIR: the directory the run would write (checked absent or empty). NLINES: stderr lines.
row() {
    name=$1 outdir=$2 nlines=$3
    shift 3
    nfrags=0
    while [ $# -gt 0 ] && [ "$1" != "--" ]; do
        nfrags=$((nfrags + 1))
        eval "frag_$nfrags=\$1"
        shift
    done
    shift
    snapshot > before
    timeout 120 "$PROG" run "$@" > stdout 2> stderr
    status=$?
    why=""
    want=2
    case " $ENV_ROWS " in *" $name "*) want=3 ;; esac
    [ "$status" -eq "$want" ] || why="$why; exit status $status, not $want"
    [ -s stdout ] && why="$why; output on stdout"
    n=$(wc -l < stderr)
    [ "$n" -eq "$nlines" ] || why="$why; $n lines on stderr, not $nlines"
    k=1
    while [ $k -le $nfrags ]; do
        eval "f=\$frag_$k"
        grep -qF -- "$f" stderr || why="$why; message lacks '$f'"
        k=$((k + 1))
    done
    if [ -e "$outdir" ]; then
        if [ ! -d "$outdir" ]; then
            [ "$outdir" = regular_file ] || why="$why; $outdir is not a directory"
            [ -s "$outdir" ] && why="$why; $outdir was written to"
        elif [ -n "$(ls -A "$outdir")" ]; then
            why="$why; $outdir is not empty: $(ls -A "$outdir" | tr '\n' ' ')"
        fi
        [ -d "$outdir" ] && rmdir "$outdir" 2> /dev/null
    fi
    snapshot > after
    cmp -s before after || why="$why; files appeared: $(diff before after | grep '^>' | tr '\n' ' ')"
    report "$name" "$why"
}

report() {
    known=""
    while IFS='|' read -r d f; do
        [ "$d" = "$1" ] && known=$f
    done << EOF
$KNOWN_DEFECTS
EOF
    if [ -z "$2" ] && [ -z "$known" ]; then
        pass=$((pass + 1))
    elif [ -z "$2" ]; then
        fail=$((fail + 1))
        echo "XPASS $1: listed in KNOWN_DEFECTS but passes now; remove its line"
    elif [ "$2" = "$known" ]; then
        xfail=$((xfail + 1))
        echo "XFAIL $1 (known defect)$2"
        sed 's/^/        stderr: /' stderr
    else
        fail=$((fail + 1))
        echo "FAIL  $1$2"
        sed 's/^/        stderr: /' stderr
    fi
}

# control NAME OUTDIR STATUS ARGS...: a valid input must exit STATUS and write summary.json.
control() {
    name=$1 outdir=$2 want=$3
    shift 3
    "$PROG" run "$@" > stdout 2> stderr
    status=$?
    why=""
    [ "$status" -eq "$want" ] || why="$why; exit status $status, not $want"
    [ -f "$outdir/summary.json" ] || why="$why; no $outdir/summary.json"
    for f in pressure.npy gap.npy displacement.npy topography.npy profile_x.csv; do
        [ -f "$outdir/$f" ] || why="$why; no $outdir/$f"
    done
    if [ "$want" -eq 1 ]; then
        grep -q '"converged": *false' "$outdir/summary.json" 2> /dev/null ||
            why="$why; summary.json lacks \"converged\": false"
        grep -qF 'did not converge' stderr || why="$why; stderr does not say 'did not converge'"
    elif [ -f "$outdir/summary.json" ]; then
        grep -q '"state": *"\(converged\|prescribed\)"' "$outdir/summary.json" ||
            why="$why; summary.json lacks \"state\": \"converged\" (or \"prescribed\")"
    fi
    ls -A "$outdir" 2> /dev/null | grep -q '^\.' &&
        why="$why; hidden files left in $outdir: $(ls -A "$outdir" | grep '^\.' | tr '\n' ' ')"
    report "$name" "$why"
    rm -rf "$outdir"
}

LEN="a length is due (m, mm, um, nm)"

# ---- positive controls: the base case and the fixture generator are valid ---------------------
control control_good          o 0 good.ini --out o
control control_pressure_npy  o 0 pressure_ok_npy.ini --out o
control control_pressure_text o 0 pressure_ok_text.ini --out o
control control_roughness_npy o 0 roughness_ok_npy.ini --out o
control control_roughness_txt o 0 roughness_ok_text.ini --out o
# a solve stopped by its iteration limit is a solver failure (1) that still writes its results
control not_converged         o 1 good.ini --out o --set solver.max_iterations=1 --set solver.method=pk

# ---- the case file ---------------------------------------------------------------------------
row missing_case_file o 1 "does_not_exist.ini" "cannot open" "No such file or directory" \
    -- does_not_exist.ini --out o
row empty_file        o 1 "empty.ini" "empty case file" -- empty.ini --out o
row case_is_directory o 1 "a_directory" "cannot read: Is a directory" -- a_directory --out o
row case_is_device    o 1 "/dev/zero" "larger than 16 MiB; not a case file" -- /dev/zero --out o
row unknown_section   o 1 "unknown_section.ini:10:" "unknown section [lod]" \
    "known sections: mesh, geometry, roughness, roughness2, body1, body2, load, solver, stress, lubrication, plasticity, output" \
    -- unknown_section.ini --out o
row unknown_key       o 1 "unknown_key.ini:4:" "[mesh] unknown key 'nz'" \
    "keys of [mesh]: nx, ny, dx, dy, periodic_x, periodic_y" -- unknown_key.ini --out o
row duplicate_key     o 1 "duplicate_key.ini:5:" "[mesh] nx given twice" "first on line 2" \
    -- duplicate_key.ini --out o
row bad_number        o 1 "bad_number.ini:4:" "[mesh] dx = four um" "'four um' is not a number" \
    "$LEN" -- bad_number.ini --out o
row bad_unit          o 1 "bad_unit.ini:4:" "[mesh] dx = 4 inch" "unknown unit 'inch'" "$LEN" \
    -- bad_unit.ini --out o
row unit_kind         o 1 "unit_kind.ini:4:" "[mesh] dx = 4 N" "unit 'N' is a force" "$LEN" \
    -- unit_kind.ini --out o
row nx_zero           o 1 "nx_zero.ini:2:" "[mesh] nx = 0" "must be an integer in 1..65536" \
    -- nx_zero.ini --out o
row dx_negative       o 1 "dx_negative.ini:4:" "[mesh] dx = -4 um" "must be a length > 0 and <= 1 m" \
    -- dx_negative.ini --out o
row nu_high           o 1 "nu_high.ini:12:" "[body1] nu = 0.6" "must be a number >= 0 and <= 0.5" \
    -- nu_high.ini --out o
row e_zero            o 1 "e_zero.ini:11:" "[body2] E = 0 GPa" "must be a pressure > 0 and <= 1e+13 Pa" \
    -- e_zero.ini --out o
row load_negative     o 1 "load_negative.ini:11:" "[load] force = -1 N" "must be a force > 0" \
    -- load_negative.ini --out o
row two_loads         o 1 "two_loads.ini:12:" "[load] approach" \
    "give exactly one of force, force_per_length, approach, pressure_file" "force is on line 11" \
    -- two_loads.ini --out o
row value_nan         o 1 "value_nan.ini:11:" "[load] force = nan N" "NaN and infinity are not accepted" \
    "a force is due (N, kN, mN)" -- value_nan.ini --out o
row missing_key       o 1 "missing_key.ini:" "[mesh] ny is required" "an integer in 1..65536" \
    -- missing_key.ini --out o
row bad_header        o 1 "bad_header.ini:1:" "section header '[mesh' lacks its closing ']'" \
    -- bad_header.ini --out o
row not_utf8          o 1 "not_utf8.ini:11:" "is not UTF-8 text (byte 0xFF at column 15)" \
    -- not_utf8.ini --out o
row continued         o 1 "continued.ini:3:" "[mesh] nx" "continues nx from line 2" \
    "takes a single value (remove the indentation)" -- continued.ini --out o
# a key that has no effect in its scene is an error, never silently ignored
row pfile_lubricant   o 1 "[load] lubricant_pressure cannot be combined with pressure_file" \
    -- pressure_ok_text.ini --out o --set load.lubricant_pressure=1MPa
row pfile_cap         o 1 "[load] pressure_cap cannot be combined with pressure_file" \
    -- pressure_ok_text.ini --out o --set load.pressure_cap=1GPa
row pfile_method      o 1 "[solver] method cannot be combined with load.pressure_file" \
    -- pressure_ok_text.ini --out o --set solver.method=pk
row pfile_tolerance   o 1 "[solver] tolerance cannot be combined with load.pressure_file" \
    -- pressure_ok_text.ini --out o --set solver.tolerance=1e-6
row radius_flat       o 1 "[geometry] radius is not used by shape = flat" \
    -- good.ini --out o --set geometry.shape=flat
# the elastic-plastic stage: x free (y free, periodic: a strip, or a line grid) or x and y periodic;
# x periodic alone is refused
control control_plastic_line o 0 plastic_line.ini --out o
control control_plastic_strip o 0 plastic_line.ini --out o --set mesh.ny=2
row plastic_periodic_x o 1 "--set mesh.periodic_x=yes" "[plasticity] with [mesh] periodic_x = yes" \
    "needs periodic_y = yes too" "accepted: x free, or x and y periodic" \
    -- good.ini --out o --set plasticity.yield_stress=1GPa --set mesh.periodic_x=yes
# the local-global fixed point is a scheme of the nested iteration (docs/theory.md §9.8)
row near_field_joint   o 1 "--set plasticity.near_field=1" "[plasticity] near_field = 1 has no effect with iteration = joint" \
    "add iteration = nested" -- good.ini --out o --set plasticity.yield_stress=1GPa --set plasticity.near_field=1
control control_near_nested o 0 good.ini --out o --set plasticity.yield_stress=1GPa \
    --set plasticity.near_field=1 --set plasticity.iteration=nested
# measured surfaces: every reader's error names the case line, the file and what is wrong
row surf_truncated    o 1 "surf_truncated.ini:5:" "[roughness] file" "surfaces/truncated.x3p" \
    "truncated or corrupt zip archive" -- surf_truncated.ini --out o
row surf_checksum     o 1 "surf_bad_checksum.ini:5:" "surfaces/bad_checksum.x3p: MD5 mismatch" \
    "set verify_checksum = no" -- surf_bad_checksum.ini --out o
row surf_no_main      o 1 "surf_no_main.ini:5:" "no main.xml in the zip archive" -- surf_no_main.ini --out o
row surf_entity       o 1 "surf_entity.ini:5:" "declares XML entities" -- surf_entity.ini --out o
row surf_size         o 1 "surf_size_mismatch.ini:5:" "sizes do not match the data" \
    -- surf_size_mismatch.ini --out o
row surf_empty        o 1 "surf_empty.ini:5:" "surfaces/empty.x3p: empty file (0 bytes)" -- surf_empty.ini --out o
row surf_absurd       o 1 "surf_absurd.ini:5:" "absurd dimensions 100000000 x 100000000" \
    -- surf_absurd.ini --out o
row surf_spacing      o 1 "surfaces/good.x3p" "16 x 16 points of 8e-07 x 1e-06 m" \
    "the mesh 16 x 16 cells of 1e-06 x 1e-06 m" "resample = linear" -- surf_good.ini --out o
control control_surf_checksum_off o 0 surf_bad_checksum.ini --out o --set roughness.verify_checksum=no \
    --set roughness.resample=linear --set mesh.dx=0.7um --set mesh.dy=0.9um
control control_surf_resample o 0 surf_good.ini --out o --set roughness.resample=linear \
    --set mesh.dx=0.7um --set mesh.dy=0.9um
row surf_resample_beyond o 1 "surfaces/good.x3p" "reach beyond the source extent" \
    -- surf_good.ini --out o --set roughness.resample=linear

# the lubricant volume equilibrium
control control_lube          o 0 lube_ok.ini --out o
row lube_auto_no_section o 1 "lube_auto_no_section.ini:10:" \
    "[load] lubricant_pressure = auto needs a [lubrication] section" -- lube_auto_no_section.ini --out o
row lube_without_auto o 1 "lube_ok.ini" "[lubrication] has no effect unless [load] lubricant_pressure = auto" \
    -- lube_ok.ini --out o --set load.lubricant_pressure=0
row lube_formula      o 1 "--set lubrication.formula=hamrock" "[lubrication] formula = hamrock" \
    "one of pan_hamrock_central, pan_hamrock_min, dowson_toyoda" -- lube_ok.ini --out o --set lubrication.formula=hamrock
row lube_viscosity    o 1 "--set lubrication.viscosity" "[lubrication] viscosity = -30 mPa*s" "must be a viscosity > 0" \
    -- lube_ok.ini --out o --set "lubrication.viscosity=-30 mPa*s"
row lube_speed_and_rpm o 1 "lube_ok.ini" "give exactly one of speed, rpm" \
    -- lube_ok.ini --out o --set lubrication.speed=2
row lube_rpm_radius   o 1 "lube_rpm_noradius.ini" "[lubrication] rpm needs radius1 and radius2" \
    -- lube_rpm_noradius.ini --out o
row lube_curved       o 1 "--set geometry.shape=sphere" "[lubrication] needs [geometry] shape = flat" \
    "cylinder (the whole line contact" "ellipsoid (the whole crowned contact" \
    -- lube_ok.ini --out o --set geometry.shape=sphere --set geometry.radius=10mm
# the whole line contact (shape = cylinder): the Hertz band of the discs on a strip
control control_whole         o 0 whole_ok.ini --out o
control control_whole_hertz   o 0 whole_ok.ini --out o --set lubrication.lubricant_profile=hertz
row whole_not_strip    o 1 "--set mesh.periodic_y=no" "needs a strip: periodic_y = yes and x free" \
    -- whole_ok.ini --out o --set mesh.periodic_y=no
row whole_radius       o 1 "--set geometry.radius=3mm" "[geometry] radius = 3 mm is not the reduced radius R_x = 2 mm" \
    "[lubrication] radius1 and radius2" -- whole_ok.ini --out o --set geometry.radius=3mm
row whole_narrow       o 1 "--set mesh.nx=64" "[mesh] the grid spans |x| <= 25.6 um, too narrow for the whole contact" \
    "b = 34.68 um" "needs nx >= 96" -- whole_ok.ini --out o --set mesh.nx=64
row whole_no_width     o 1 "[lubrication] with [geometry] shape = cylinder needs width" -- whole_ok.ini --out o --set lubrication.width=
control control_crowned       o 0 crown_ok.ini --out o
row crowned_line_film  o 1 "--set lubrication.formula=pan_hamrock_central" "is a line-contact formula" \
    "needs a point-contact one (hamrock_dowson_central or hamrock_dowson_min)" \
    -- crown_ok.ini --out o --set lubrication.formula=pan_hamrock_central
row crowned_width      o 1 "--set lubrication.width=2mm" "[lubrication] width has no effect on the whole crowned contact" \
    -- crown_ok.ini --out o --set lubrication.width=2mm
row crowned_periodic   o 1 "--set mesh.periodic_y=yes" "needs a grid free along x and y" \
    -- crown_ok.ini --out o --set mesh.periodic_y=yes
row crowned_small      o 1 "--set mesh.ny=200" "too small for the whole crowned contact" "needs nx >= 61 and ny >= 273" \
    -- crown_ok.ini --out o --set mesh.ny=200
row profile_on_patch   o 1 "--set lubrication.lubricant_profile=hertz" "[lubrication] lubricant_profile is not used by" \
    -- lube_ok.ini --out o --set lubrication.lubricant_profile=hertz
# the running-in ([runin]) and its resume
control control_runin         o 0 runin_ok.ini --out o --quiet
row runin_speeds_rise  o 1 "runin_increasing.ini:23:" "[runin] speeds = 200, 500, 1000 rpm" \
    "must be less than item 1 (200 rpm): the list is strictly decreasing" -- runin_increasing.ini --out o
row runin_first_force  o 1 "--set runin.forces=2000 N, 3000 N" \
    "[runin] forces: the first force (2000 N) must be [load] force" \
    -- runin_ok.ini --out o --set "runin.forces=2000 N, 3000 N"
row runin_given_film   o 1 "--set lubrication.film=given" "[runin] needs [lubrication] film = ehl" \
    -- runin_ok.ini --out o --set lubrication.film=given --set lubrication.film_thickness=0.5um \
    --set lubrication.viscosity= --set lubrication.pressure_viscosity= --set lubrication.rpm= \
    --set lubrication.radius1= --set lubrication.radius2= --set lubrication.width=
row runin_resume_none  o 1 "--resume: no checkpoint in 'o/checkpoint'" "run without --resume" \
    -- runin_ok.ini --out o --resume
row resume_not_runin   o 1 "--resume: good.ini has no [runin] section" -- good.ini --out o --resume
# the default output directory (out/<case name>) must not appear either
row default_out_dir   out/nx_zero 1 "nx_zero.ini:2:" "[mesh] nx = 0" -- nx_zero.ini

# ---- data files: [load] pressure_file and [roughness] file ------------------------------------
row pressure_dir       o 1 "a_directory" "cannot read: Is a directory" "[load] pressure_file" \
    -- pressure_dir.ini --out o
row pressure_missing   o 1 "does_not_exist.npy" "cannot open: No such file or directory" \
    "[load] pressure_file" -- pressure_missing.ini --out o
row pressure_truncated o 1 "truncated.npy" "truncated: header says 16 x 16 values (2048 bytes)" \
    "file has 800 bytes of data" "[load] pressure_file" -- pressure_truncated.ini --out o
row pressure_dtype     o 1 "int64.npy" "dtype '<i8' not supported; need float64 ('<f8')" \
    "[load] pressure_file" -- pressure_dtype.ini --out o
row pressure_float32   o 1 "float32.npy" "dtype '<f4' not supported; need float64 ('<f8')" \
    "[load] pressure_file" -- pressure_float32.ini --out o
row pressure_shape     o 1 "shape_8x16.npy" "shape 8 x 16, the mesh is 16 x 16 (ny x nx)" \
    "[load] pressure_file" -- pressure_shape.ini --out o
row pressure_negative  o 1 "negative.npy" "pressure -1 Pa at row 6, column 4 is negative" \
    "must be >= 0" "[load] pressure_file" -- pressure_negative.ini --out o
row pressure_nan       o 1 "nan.npy" "value [2, 5] (flat index 37) is NaN; values must be finite" \
    "[load] pressure_file" -- pressure_nan.ini --out o
row pressure_nan_text  o 1 "nan_16x16.txt:4:" "value 'nan' is not finite; values must be finite" \
    "[load] pressure_file" -- pressure_nan_text.ini --out o
row roughness_nan      o 1 "nan.npy: 1 of 256 points are missing" "row 2, column 5" \
    "set [roughness] missing = fill" "[roughness] file" -- roughness_nan.ini --out o
row roughness_nan_text o 1 "nan_16x16.txt: 1 of 256 points are missing" \
    "set [roughness] missing = fill" "[roughness] file" -- roughness_nan_text.ini --out o
row roughness_missing  o 1 "does_not_exist.txt" "cannot open: No such file or directory" \
    "[roughness] file" -- roughness_missing.ini --out o
# two measured surfaces: [roughness2] is body 2's (then [roughness] is body 1's); both maps on one
# mesh, a mismatch names both files; the rules of [roughness] hold for [roughness2]
control control_two_surfaces o 0 roughness_ok_npy.ini --out o --set roughness2.type=file \
    --set roughness2.file=micro.npy
row roughness2_alone   o 1 "--set roughness2.type" "[roughness2] (body 2's surface) needs [roughness]" \
    -- good.ini --out o --set roughness2.type=gaussian --set roughness2.rq=0.1um \
    --set roughness2.correlation_x=8um
row roughness2_grid    o 1 "roughness_ok_npy.ini" "[roughness2] file" "the two surfaces do not come onto one grid" \
    "body 2's map shape_8x16.npy: 16 x 8 points" "micro.npy: 16 x 16 points" "the mesh 16 x 16 cells" \
    -- roughness_ok_npy.ini --out o --set roughness2.type=file --set roughness2.file=shape_8x16.npy
row roughness2_scale   o 1 "--set roughness2.scale" "[roughness2] scale = 0: must not be 0" \
    -- roughness_ok_npy.ini --out o --set roughness2.type=file --set roughness2.file=micro.npy \
    --set roughness2.scale=0
row roughness2_unused  o 1 "--set roughness2.hurst" "[roughness2] hurst is not used by type = file" \
    -- roughness_ok_npy.ini --out o --set roughness2.type=file --set roughness2.file=micro.npy \
    --set roughness2.hurst=0.5
# text and profile inputs: a header is named as a header, a profile as a profile
row text_header_words  o 1 "header_words.txt:1: 'h=16 w=16' is a header line" "[roughness] file" \
    -- roughness_ok_text.ini --out o --set roughness.file=header_words.txt
row text_header_sizes  o 1 "header_sizes.txt:2: 16 values, but the first data row (line 1) has 2" \
    "if that line is a header" -- roughness_ok_text.ini --out o --set roughness.file=header_sizes.txt
row text_profile       o 1 "profile.txt: 2 columns of 4 rows" "a profile (a line scan), not a surface" \
    -- roughness_ok_text.ini --out o --set roughness.file=profile.txt
row xyz_profile        o 1 "profile.xyz:1: 2 values: 'x z' pairs are a profile" \
    -- roughness_ok_text.ini --out o --set roughness.file=profile.xyz
row xyz_header_words   o 1 "header_words.xyz:1: 'h=16 w=16' is a header line" \
    -- roughness_ok_text.ini --out o --set roughness.file=header_words.xyz
# roughness parameters that cannot be computed: a cut-off of fewer than 4 sampling intervals
row roughness_cutoff_short o 1 "--set roughness.cutoff" "[roughness] cutoff" \
    "spans fewer than 4 sampling intervals" "accepted: cutoff >= 4 dx = 1.6e-05 m" \
    -- roughness_ok_text.ini --out o --set roughness.cutoff=10um
# [solver] plans = wisdom: the file is required; one that is not FFTW wisdom is refused before
# any output (and left as it was); a fresh name is valid (the run writes the wisdom there)
row wisdom_no_file     o 1 "wisdom_no_file.ini:" "[solver] wisdom_file is required for plans = wisdom" \
    -- wisdom_no_file.ini --out o
row wisdom_not_wisdom  o 1 "wisdom_bad.ini:16:" "[solver] wisdom_file" "not_wisdom.txt is not FFTW wisdom" \
    -- wisdom_bad.ini --out o
grep -qx "1 2 3" not_wisdom.txt || { fail=$((fail + 1)); echo "FAIL  wisdom_not_wisdom: the file was changed"; }
control control_wisdom o 0 wisdom_bad.ini --out o --set solver.wisdom_file=fresh.wisdom
if head -c 6 fresh.wisdom 2> /dev/null | grep -q '^(fftw-'; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL  control_wisdom: no FFTW wisdom in fresh.wisdom"; fi
rm -f fresh.wisdom
# every documented rule, in every reader: hardening tables as the key they stand for
TAB="--set plasticity.hardening=table --set plasticity.yield_stress="
# shellcheck disable=SC2086 # $TAB is split into its options on purpose
row table_hex          o 1 "--set plasticity.table=table_hex.csv" "[plasticity] table" "table_hex.csv:2" \
    "expected a row 'eps_p, sigma_y' of two finite numbers" \
    -- plastic_line.ini --out o $TAB --set plasticity.table=table_hex.csv
# shellcheck disable=SC2086
row table_huge         o 1 "table_huge.csv:1" "must be <= 1e+12 Pa (the bound of [plasticity] yield_stress)" \
    -- plastic_line.ini --out o $TAB --set plasticity.table=table_huge.csv
# shellcheck disable=SC2086
row table_first_strain o 1 "table_start.csv:1" "the first plastic strain eps_p = 0.01 must be 0" \
    -- plastic_line.ini --out o $TAB --set plasticity.table=table_start.csv
row scale_zero         o 1 "[roughness] scale = 0: must not be 0" \
    -- surf_good.ini --out o --set roughness.scale=0 --set roughness.resample=linear --set mesh.dx=0.7um
row scale_minus_zero   o 1 "[roughness] scale = 0: must not be 0" \
    -- surf_good.ini --out o --set roughness.scale=-0 --set roughness.resample=linear --set mesh.dx=0.7um
row plastic_depth_dz   o 1 "[plasticity] depth = 5e-06 m is below dz = 1e-05 m" "accepted: depth >= dz" \
    -- plastic_line.ini --out o --set plasticity.dz=10um --set plasticity.depth=5um
# keys without effect in their scene are refused
row units_own_file     o 1 "--set roughness.units" "[roughness] units has no effect with a x3p file" \
    -- surf_good.ini --out o --set roughness.units=um
row checksum_not_x3p   o 1 "[roughness] verify_checksum has no effect with a txt file" \
    -- roughness_ok_text.ini --out o --set roughness.verify_checksum=no
row resample_mesh_file o 1 "[roughness] resample has no effect when the mesh comes from the file" \
    -- surf_good.ini --out o --set mesh.nx= --set mesh.ny= --set mesh.dx= --set roughness.resample=linear
row deflection_periodic o 1 "[runin] nominal_deflection has no effect on a grid periodic along x and y" \
    -- runin_ok.ini --out o --set runin.nominal_deflection=keep
# the systematic pass over the key table (src/case/scene_effect.c: each key x each scene class)
row window_full_periodic o 1 "--set stress.window" \
    "[stress] window = full has no effect on a grid periodic along y" "remove it" \
    -- good.ini --out o --set mesh.periodic_y=yes --set stress.window=full
row depth_max_one_layer  o 1 "--set stress.depth_max" \
    "[stress] depth_max has no effect with layers = 1 (the one layer is at depth_min)" \
    -- good.ini --out o --set stress.layers=1 --set stress.depth_max=10um
row geometric_one_layer  o 1 "--set stress.spacing" \
    "[stress] spacing = geometric has no effect with layers = 1" \
    -- good.ini --out o --set stress.layers=1 --set stress.depth_min=1um --set stress.spacing=geometric
row ellipsoid_one_row    o 1 "--set geometry.radius_y" \
    "[geometry] radius_y has no effect on a grid of one row (ny = 1" "use shape = cylinder" \
    -- good.ini --out o --set mesh.ny=1 --set geometry.shape=ellipsoid --set geometry.radius= \
    --set geometry.radius_x=10mm --set geometry.radius_y=5mm
row correlation_y_one_row o 1 "--set roughness.correlation_y" \
    "[roughness] correlation_y has no effect on a grid of one row (ny = 1" \
    -- good.ini --out o --set mesh.ny=1 --set roughness.type=gaussian --set roughness.rq=0.1um \
    --set roughness.correlation_x=8um --set roughness.correlation_y=4um
row lube_radii_macro     o 1 "lube_ok.ini:19:" \
    "[lubrication] radius1 has no effect with speed and macro_radius" \
    -- lube_ok.ini --out o --set lubrication.rpm= --set lubrication.speed=1m/s \
    --set lubrication.macro_radius=20mm
row margin_doubly_periodic o 1 "--set plasticity.margin" \
    "[plasticity] margin has no effect on a grid periodic along x and y" \
    -- plastic_line.ini --out o --set mesh.periodic_x=yes --set mesh.ny=2 --set plasticity.margin=40um
row margin_spectral      o 1 "--set plasticity.margin" \
    "[plasticity] margin has no effect with kernel = spectral" \
    -- plastic_line.ini --out o --set plasticity.kernel=spectral --set plasticity.margin=40um
row kernel_bad           o 1 "--set plasticity.kernel" "one of cuboid, spectral" \
    -- plastic_line.ini --out o --set plasticity.kernel=fourier
row fine_depth_uniform   o 1 "--set plasticity.fine_depth" \
    "[plasticity] fine_depth has no effect with layering = auto and a given depth" \
    -- plastic_line.ini --out o --set plasticity.depth=10um --set plasticity.fine_depth=4um
row grading_even         o 1 "--set plasticity.grading" "[plasticity] grading" \
    -- plastic_line.ini --out o --set plasticity.layering=graded --set plasticity.grading=1.5
# messages name what the user wrote: heights that would overflow the solve name the data file
printf '1 2 3\n4 5 6\n7 8 1e300\n' > huge_heights.txt
row huge_heights o 1 "[roughness] file: huge_heights.txt: the height 1e+300 m at row 2, column 2" \
    "not a surface height" \
    -- roughness_ok_text.ini --out o --set roughness.file=huge_heights.txt --set mesh.nx=3 --set mesh.ny=3
# [runin] lists continue on indented lines up to their maximum count
printf '  500, 200 rpm\n' > cont.txt
sed 's/^speeds = 1000, 500, 200 rpm$/speeds = 1000,/' runin_ok.ini > runin_cont.ini
cat cont.txt >> runin_cont.ini
control control_runin_continued o 0 runin_cont.ini --out o --quiet
# nothing reads forever: a device or FIFO given as any file the run reads is refused before it
# is opened, naming the file and what it should be (the case file: its size limit, above)
row surface_device     o 1 "/dev/zero: not a regular file (a character device)" \
    "a surface file must be a regular file" "[roughness] file" \
    -- surf_good.ini --out o --set roughness.file=/dev/zero --set roughness.format=x3p
row surface_fifo       o 1 "a_fifo.x3p: not a regular file (a FIFO or pipe)" "[roughness] file" \
    -- surf_good.ini --out o --set roughness.file=a_fifo.x3p
row pressure_device    o 1 "/dev/zero: not a regular file" "[load] pressure_file" \
    -- good.ini --out o --set load.force= --set load.pressure_file=/dev/zero
row table_device       o 1 "/dev/zero: not a regular file" "a hardening table must be a regular file" \
    -- plastic_line.ini --out o --set plasticity.hardening=table --set plasticity.yield_stress= \
    --set plasticity.table=/dev/zero
row wisdom_device      o 1 "/dev/zero: not a regular file" "an FFTW wisdom file must be a regular file" \
    -- wisdom_bad.ini --out o --set solver.wisdom_file=/dev/zero
# a pressure_file given by --set is relative to the current directory, not to the case file
row pressure_override  o 1 "--set load.pressure_file=nan.npy" "[load] pressure_file" \
    "give exactly one of force, force_per_length, approach, pressure_file" \
    -- good.ini --out o --set load.pressure_file=nan.npy

# ---- the output directory --------------------------------------------------------------------
row out_below_file     regular_file 1 "output directory 'regular_file/out'" \
    "cannot create 'regular_file'" "Not a directory" -- good.ini --out regular_file/out
row out_is_file        regular_file 1 "output directory 'regular_file'" "Not a directory" \
    -- good.ini --out regular_file
row out_empty          o 1 "output directory: empty path" -- good.ini --out ""
# the memory guard refuses a scene that cannot fit before allocating it (a 60000 x 60000 grid
# needs about a terabyte)
row memory_guard       o 1 "the scene needs about" "GiB available (grid 60000 x 60000)" \
    "reduce the grid" -- good.ini --out o --set mesh.nx=60000 --set mesh.ny=60000

# ---- --set overrides and options ---------------------------------------------------------------
row set_no_dot         o 1 "--set nx=3" "expected section.key=value" -- good.ini --out o --set nx=3
row set_no_equals      o 1 "--set mesh.nx" "expected section.key=value" -- good.ini --out o --set mesh.nx
row set_empty_section  o 1 "--set .nx=3" "expected section.key=value" -- good.ini --out o --set .nx=3
row set_unknown_sect   o 1 "--set mesh2.nx=3" "unknown section [mesh2]" "known sections: mesh," \
    -- good.ini --out o --set mesh2.nx=3
row set_unknown_key    o 1 "--set mesh.nz=3" "[mesh] unknown key 'nz'" "keys of [mesh]: nx, ny" \
    -- good.ini --out o --set mesh.nz=3
row set_bad_value      o 1 "--set mesh.nx=0" "[mesh] nx = 0" "must be an integer in 1..65536" \
    -- good.ini --out o --set mesh.nx=0
row set_unit_kind      o 1 "--set mesh.dx=3N" "[mesh] dx = 3N" "unit 'N' is a force" "$LEN" \
    -- good.ini --out o --set mesh.dx=3N
# an empty value removes the key: good.ini then lacks its load
row set_empty_value    o 1 "good.ini" "[load] give exactly one of force" "none is given" \
    -- good.ini --out o --set load.force=
row set_bad_choice     o 1 "--set solver.method=newton" "[solver] method = newton" \
    "must be one of cg, pk, active-set" -- good.ini --out o --set solver.method=newton
row set_unused_key     o 1 "--set geometry.radius_x=1mm" "[geometry] radius_x is not used by shape = sphere" \
    -- good.ini --out o --set geometry.radius_x=1mm
row set_missing_arg    o 2 "'--set'" "usage: microcontact run CASE.ini" -- good.ini --out o --set
row unknown_option     o 2 "unknown or incomplete option '--frobnicate'" \
    "usage: microcontact run CASE.ini [--out DIR] [--set section.key=value]..." \
    -- good.ini --out o --frobnicate
row two_case_files     o 2 "one case file only" "'good.ini' and 'nu_high.ini'" \
    -- good.ini nu_high.ini --out o
row no_case_file       o 1 "usage: microcontact run CASE.ini" -- --out o
row out_missing_arg    o 2 "unknown or incomplete option '--out'" "usage: microcontact run CASE.ini" \
    -- good.ini --out
row set_eq_bad_value   o 1 "--set mesh.ny=-3" "[mesh] ny = -3" "must be an integer in 1..65536" \
    -- --out=o good.ini --set=mesh.ny=-3
sets=""
i=0
while [ $i -lt 257 ]; do sets="$sets --set load.force=1N"; i=$((i + 1)); done
# shellcheck disable=SC2086 # $sets is split into 257 options on purpose
row set_too_many       o 1 "more than 256 --set options" -- good.ini --out o $sets
sets=$(echo "$sets" | sed 's/--set /--set=/g')
# shellcheck disable=SC2086
row set_eq_too_many    o 1 "more than 256 --set options" -- good.ini --out o $sets

total=$((pass + fail + xfail))
echo "bad_input.sh: $pass passed, $fail failed, $xfail known defects (XFAIL), $total rows"
[ "$fail" -eq 0 ]
