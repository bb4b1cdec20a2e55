#!/usr/bin/env bash
# Regenerates goldens.tsv by running the programs in programs/ through the real
# LinuxCNC 2.9 trajectory planner (measure_cycle_time.sh) on each validation machine.
# Real time (--speedup 1) is used because faster runs can starve the motion queue.
# Takes about 6 minutes.
# Usage: tests/cycle_time/regenerate.sh [path/to/measure_cycle_time.sh]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
MEASURE=${1:-/work/shared/oracle/measure_cycle_time.sh}
python3 "$HERE/gen_programs.py"
mkdir -p "$HERE/raw"

# rot_* programs move the A axis and run on the XYZA machine only.
xyz=()
rot=()
for p in "$HERE"/programs/*.ngc; do
  case $(basename "$p") in rot_*) rot+=("$p") ;; *) xyz+=("$p") ;; esac
done

# Machine name -> measure_cycle_time.sh options. Keep in sync with machine() in
# runtime/tests/plan_goldens.rs.
run() {
  local name=$1 opts=$2; shift 2
  # shellcheck disable=SC2086
  "$MEASURE" $opts --speedup 1 "$@" > "$HERE/raw/$name.tsv"
}
run m100 "--vel 100 --acc 1000" "${xyz[@]}"
run m60 "--vel 60 --acc 800" "${xyz[@]}"
run mixed "--vel 100 --acc 1000 --axis Y=50,500 --axis Z=20,200" "${xyz[@]}"
run rot "--coords XYZA --vel 100 --acc 1000" "${rot[@]}"

{
  printf 'program\tmachine\tmotion_s\n'
  for m in m100 m60 mixed rot; do
    awk -F'\t' -v m="$m" 'NR > 1 && $2 == "ok" { sub(/^.*\//, "", $1); sub(/\.ngc$/, "", $1); printf "%s\t%s\t%s\n", $1, m, $3 }' "$HERE/raw/$m.tsv"
  done
} > "$HERE/goldens.tsv"
echo "wrote $HERE/goldens.tsv"
