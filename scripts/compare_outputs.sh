#!/usr/bin/env bash
# Compares two partscope binaries on every program of the project's corpora:
# `check --format json` and `run --format json` in all three dialects must be
# byte-identical (exit status included).
#
#   scripts/compare_outputs.sh BASE_BIN NEW_BIN [DIR...]
#
# Default directories: tests/, examples/ and /work/shared/corpus/linuxcnc (when
# present). Prints one line per difference and a summary; exits 1 on any.
set -u
base=${1:?usage: compare_outputs.sh BASE_BIN NEW_BIN [DIR...]}
new=${2:?usage: compare_outputs.sh BASE_BIN NEW_BIN [DIR...]}
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -eq 0 ]; then
    set -- "$root/tests" "$root/examples"
    [ -d /work/shared/corpus/linuxcnc ] && set -- "$@" /work/shared/corpus/linuxcnc
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
files=0
runs=0
diffs=0
while IFS= read -r -d '' f; do
    files=$((files + 1))
    for d in servoworks rs274ngc fanuc; do
        for cmd in check run; do
            "$base" "$cmd" --format json --dialect "$d" "$f" >"$tmp/a" 2>"$tmp/ae"
            echo "status $?" >>"$tmp/a"
            "$new" "$cmd" --format json --dialect "$d" "$f" >"$tmp/b" 2>"$tmp/be"
            echo "status $?" >>"$tmp/b"
            runs=$((runs + 1))
            if ! cmp -s "$tmp/a" "$tmp/b" || ! cmp -s "$tmp/ae" "$tmp/be"; then
                diffs=$((diffs + 1))
                echo "DIFF $cmd --dialect $d $f"
            fi
        done
    done
done < <(find "$@" -type f \( -name '*.ngc' -o -name '*.nc' -o -name '*.fnc' \
    -o -name '*.dat' -o -name '*.tap' -o -name '*.gcode' \) -print0 | sort -z)
echo "$files files, $runs comparisons (check and run × 3 dialects), $diffs differences"
[ "$diffs" -eq 0 ]
