#!/bin/bash
# Times the egocentric map's rotation of two versions of lib/terrain side by side in one
# process (see rotation_main.cpp), for a full 150x150 map and one 37 % known (the demo's
# share). A benchmark to run on purpose, not a test.
#
#   tests/perf/terrain/side_by_side/rotation.sh REV_A [REV_B] [PAIRS]
#
# REV_A and REV_B are git revisions; REV_B defaults to the working tree. PAIRS defaults to
# 1000. B/A below 1: B is faster. Needs g++ and Eigen (tools/install-deps).
set -euo pipefail

if [[ $# -lt 1 || $# -gt 3 ]]; then
    echo "usage: $0 REV_A [REV_B|worktree] [PAIRS]" >&2
    exit 2
fi
here="$(cd "$(dirname "$0")" && pwd)"
root="$(git -C "$here" rev-parse --show-toplevel)"
rev_a="$1"
rev_b="${2:-worktree}"
pairs="${3:-1000}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# lib/terrain of a revision (or of the working tree) into $work/$2.
export_library() {
    mkdir -p "$work/$2"
    if [[ "$1" == worktree ]]; then
        cp -r "$root/lib/terrain" "$work/$2/"
    else
        git -C "$root" rev-parse --verify --quiet "$1^{commit}" >/dev/null ||
            { echo "rotation.sh: no such revision: $1" >&2; exit 2; }
        git -C "$root" archive "$1" lib/terrain | tar -x -C "$work/$2" --strip-components=1
    fi
}

flags=(-O3 -DNDEBUG -std=c++20 -isystem /usr/include/eigen3 -Wno-psabi)
for v in A B; do
    rev="$rev_a"; [[ $v == B ]] && rev="$rev_b"
    export_library "$rev" "$v"
    src="$work/$v/terrain"
    objects=()
    # Every source of the library, its subfolders (src/kernels) included.
    while IFS= read -r f; do
        o="$work/$v/$(basename "$f" .cpp).o"
        g++ "${flags[@]}" -Dugv=ugv$v -I"$src/include" -I"$src/src" -c "$f" -o "$o"
        objects+=("$o")
    done < <(find "$src/src" -name '*.cpp' | sort)
    ar rcs "$work/libterrain$v.a" "${objects[@]}"
    g++ "${flags[@]}" -Dugv=ugv$v -I"$src/include" -c "$here/rotation_driver.cpp" -o "$work/driver$v.o"
done
g++ "${flags[@]}" "$here/rotation_main.cpp" "$work/driverA.o" "$work/driverB.o" \
    "$work/libterrainA.a" "$work/libterrainB.a" -o "$work/rotation_side_by_side"

echo "A = $rev_a, B = $rev_b"
"$work/rotation_side_by_side" 150 0 "$pairs"
"$work/rotation_side_by_side" 150 14.5 "$pairs"
