#!/usr/bin/env bash
# Regenerates goldens.tsv by running every program in programs/ through the real
# LinuxCNC 2.9 trajectory planner (measure_cycle_time.sh) on each validation machine.
# Real time (--speedup 1) is used because faster runs can starve the motion queue.
# Usage: tests/cycle_time/regenerate.sh [path/to/measure_cycle_time.sh]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
MEASURE=${1:-/work/shared/oracle/measure_cycle_time.sh}
python3 "$HERE/gen_programs.py"
mkdir -p "$HERE/raw"

# Machine name -> measure_cycle_time.sh options. Keep in sync with MACHINES in
# runtime/tests/plan_goldens.rs.
declare -A MACHINES=(
  [m100]="--vel 100 --acc 1000"
  [m60]="--vel 60 --acc 800"
  [mixed]="--vel 100 --acc 1000 --axis Y=50,500 --axis Z=20,200"
)
for m in m100 m60 mixed; do
  # shellcheck disable=SC2086
  "$MEASURE" ${MACHINES[$m]} --speedup 1 "$HERE"/programs/*.ngc > "$HERE/raw/$m.tsv"
done

{
  printf 'program\tmachine\tmotion_s\n'
  for m in m100 m60 mixed; do
    awk -F'\t' -v m="$m" 'NR > 1 && $2 == "ok" { sub(/^.*\//, "", $1); sub(/\.ngc$/, "", $1); printf "%s\t%s\t%s\n", $1, m, $3 }' "$HERE/raw/$m.tsv"
  done
} > "$HERE/goldens.tsv"
echo "wrote $HERE/goldens.tsv"
