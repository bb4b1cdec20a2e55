#!/usr/bin/env bash
# Regenerates goldens.tsv by running the programs in programs/ through the real
# LinuxCNC 2.9 trajectory planner (measure_cycle_time.sh) on each validation machine.
# Real time (--speedup 1) is used because faster runs can starve the motion queue.
# Takes about 6 minutes. Run it on an otherwise idle machine: LinuxCNC runs without
# real-time scheduling here, and under heavy load (load average above the number of
# cores) the task queues moves late, which makes a few blended corners 1-3 ms slower.
# Usage: tests/cycle_time/regenerate.sh [path/to/measure_cycle_time.sh]
set -euo pipefail
load=$(cut -d' ' -f1 /proc/loadavg)
if awk -v l="$load" -v n="$(nproc)" 'BEGIN { exit !(l > n) }'; then
  echo "regenerate.sh: warning: load average $load exceeds $(nproc) cores; results may be slow by a few ms" >&2
fi
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
# An inch machine (4 in/s, 40 in/s²); the test reads its generated INI with
# MachineProfile::from_linuxcnc_ini, so that file is kept (paths made relative).
keep=$(mktemp -d)
inch=(line_x20_f3000 corner090_g64 inch_square_g64 arc_r5_f1200_full poly_zigzag_g64p005 rapid_xyz)
inch_paths=()
for n in "${inch[@]}"; do inch_paths+=("$HERE/programs/$n.ngc"); done
run inch "--units inch --vel 4 --acc 40 --keep $keep" "${inch_paths[@]}"
mkdir -p "$HERE/machines"
sed "s|$keep|.|g" "$keep/sim.ini" > "$HERE/machines/inch.ini"
rm -rf "$keep"

{
  printf 'program\tmachine\tmotion_s\n'
  for m in m100 m60 mixed rot inch; do
    awk -F'\t' -v m="$m" 'NR > 1 && $2 == "ok" { sub(/^.*\//, "", $1); sub(/\.ngc$/, "", $1); printf "%s\t%s\t%s\n", $1, m, $3 }' "$HERE/raw/$m.tsv"
  done
} > "$HERE/goldens.tsv"
echo "wrote $HERE/goldens.tsv"
