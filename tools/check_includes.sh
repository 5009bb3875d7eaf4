#!/usr/bin/env bash
# check_includes.sh - the arrows of docs/architecture.md, checked over the #include lines of src/.
#
# A file in src/<folder>/ may include headers of its own folder and of the folders its row below
# lists; any other project include (a folder-qualified "x/y.h", or a bare "y.h" that is not in its
# own folder) is a violation. Exit 0 when every include follows the arrows, 1 otherwise (each
# violation printed as file:line: what and why).
set -u
cd "$(dirname "$0")/.."

allowed() { # folder -> folders it may include besides itself
    case "$1" in
    core)      echo "" ;;
    kernels)   echo "core" ;;
    io)        echo "core" ;;
    reference) echo "core kernels" ;;
    operator)  echo "core kernels" ;;
    contact)   echo "core kernels operator" ;;
    stress)    echo "core kernels operator" ;;
    surface)   echo "core kernels operator io" ;;
    plastic)   echo "core kernels operator io contact stress" ;;
    lube)      echo "core kernels operator io contact stress surface" ;;
    case)      echo "core kernels reference operator io contact stress surface plastic lube" ;;
    pipeline)  echo "core kernels reference operator io contact stress surface plastic lube case" ;;
    cli)       echo "core kernels reference operator io contact stress surface plastic lube case pipeline" ;;
    *)         echo "UNKNOWN" ;;
    esac
}

bad=0
for f in src/*/*.[ch]; do
    folder=$(basename "$(dirname "$f")")
    ok=$(allowed "$folder")
    if [ "$ok" = UNKNOWN ]; then
        echo "$f: folder '$folder' has no row in tools/check_includes.sh (add it with its arrows)"
        bad=1
        continue
    fi
    while IFS=: read -r line inc; do
        inc=${inc#*\"}
        inc=${inc%%\"*}
        case "$inc" in
        */*)
            dep=${inc%%/*}
            [ "$dep" = "$folder" ] && continue
            if [ -d "src/$dep" ]; then
                case " $ok " in
                *" $dep "*) ;;
                *) echo "$f:$line: includes \"$inc\": $folder/ may not depend on $dep/"; bad=1 ;;
                esac
            else
                echo "$f:$line: includes \"$inc\": no folder src/$dep"
                bad=1
            fi
            ;;
        *)
            # the CLI is the front door of the suites and benches too (verify/, bench/)
            if [ "$folder" = cli ] && { [ -f "verify/$inc" ] || [ -f "bench/$inc" ]; }; then
                continue
            fi
            if [ ! -f "$(dirname "$f")/$inc" ]; then
                echo "$f:$line: includes \"$inc\": not in $folder/ (write it folder-qualified)"
                bad=1
            fi
            ;;
        esac
    done < <(grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" | sed 's/^\([0-9]*\):/\1:/')
done
if [ $bad -eq 0 ]; then
    echo "check_includes: every include of src/ follows the arrows"
fi
exit $bad
