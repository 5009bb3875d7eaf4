#!/bin/sh
# prefixes.sh - one prefix per folder (docs/architecture.md §7): lists the public names of src/
# per folder by their prefix mc_<word> (functions and data exported by the folder's objects, nm;
# typedef names of its headers) and fails when a prefix is used by two folders, outside the
# exceptions below.
#   tools/prefixes.sh [BUILD]      BUILD: the build directory with the objects (default build)
#   tools/prefixes.sh -l [BUILD]   also print every folder's prefixes with their counts
# Exit 0: every prefix belongs to one folder (or is a listed exception); 1: a prefix is shared
# (each printed with the folders and names); 2: no objects (build first: make all).
set -u
cd "$(dirname "$0")/.."
list=0
[ "${1:-}" = -l ] && { list=1; shift; }
b=${1:-build}
ls "$b"/src/*/*.o >/dev/null 2>&1 || { echo "prefixes: no objects in $b/src (make all first)" >&2; exit 2; }

# Known exceptions, with the reason; a listed prefix may be shared by exactly these folders.
#   mc_surface: io/ (the surface-file readers, surface_file.h) and surface/ (shapes, topography,
#     roughness statistics): 134 uses in 25 files, left for a rename of its own.
#   mc_eigen: kernels/ (the cuboid eigenstrain functions, eigen.h) and plastic/ (the eigenstrain
#     operators built on them, eigen_op.h): plastic/ is being changed on other branches.
exceptions="mc_surface:io,surface mc_eigen:kernels,plastic"

tab=$(mktemp "${TMPDIR:-/tmp}/mc_prefixes.XXXXXX") || exit 2
trap 'rm -f "$tab"' EXIT INT TERM
for d in src/*/; do
    f=$(basename "$d")
    {
        for o in "$b/src/$f"/*.o; do
            [ -f "$o" ] && nm -g --defined-only "$o" | awk '$2 ~ /^[TDBRC]$/ { print $3 }'
        done
        # typedef names: "} mc_x;" closing a typedef'd struct/enum, or "typedef ... mc_x;"
        cat "$d"*.h 2>/dev/null | sed -n -E 's/^[}] *(mc_[A-Za-z0-9_]+);.*/\1/p; s/^typedef .*[ *](mc_[A-Za-z0-9_]+);.*/\1/p'
    } | grep '^mc_' | sort -u | awk -v f="$f" '{ p = $1; sub(/^mc_/, "", p); sub(/_.*/, "", p); print f, "mc_" p, $1 }'
done > "$tab"

if [ $list = 1 ]; then
    awk '{ n[$1 " " $2]++ } END { for (k in n) print k, n[k] }' "$tab" | sort -k1,1 -k3,3nr |
        awk '$1 != last { if (NR > 1) printf "\n"; printf "%s:", $1; last = $1 } { printf " %s (%d)", $2, $3 } END { print "" }'
fi

bad=0
for p in $(awk '{ print $2 }' "$tab" | sort -u); do
    folders=$(awk -v p="$p" '$2 == p { print $1 }' "$tab" | sort -u | paste -sd, -)
    case $folders in *,*) ;; *) continue ;; esac
    if printf '%s\n' $exceptions | grep -qx "$p:$folders"; then
        [ $list = 1 ] && echo "exception: $p in $folders"
        continue
    fi
    echo "prefixes: $p is used by the folders $folders:"
    awk -v p="$p" '$2 == p { printf "  %s: %s\n", $1, $3 }' "$tab"
    bad=1
done
[ $bad = 0 ] && [ $list = 1 ] && echo "prefixes: every other prefix belongs to one folder"
exit $bad
