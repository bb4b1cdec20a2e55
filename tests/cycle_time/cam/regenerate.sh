#!/usr/bin/env bash
# Regenerates the CAM-shaped goldens: writes the programs (scripts/gen_cam_programs.py),
# runs them through the real LinuxCNC 2.9 stack (measure_cycle_time.sh, --speedup 1) on
# each machine and collects goldens.tsv. Needs linuxcnc-uspace; not run in CI (the
# goldens are committed data). About 35 minutes; run it on an otherwise idle machine.
# Usage: tests/cycle_time/cam/regenerate.sh [path/to/measure_cycle_time.sh]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
MEASURE=${1:-/work/shared/oracle/measure_cycle_time.sh}
python3 "$HERE/../../../scripts/gen_cam_programs.py"
mkdir -p "$HERE/raw"
# LinuxCNC's M2 keeps the units, the plane and the G64 P/Q tolerances, and one
# measurement run executes many programs: reset.ngc restores the start-up modes before
# each program, so a program without its own G64 (or G21) runs in the defaults.
all=()
for p in "$HERE"/programs/*.ngc; do all+=("$HERE/reset.ngc" "$p"); done
bd=()
for p in "$HERE"/programs/pocket_bd__*.ngc; do bd+=("$HERE/reset.ngc" "$p"); done

# Machine name -> options. Keep in sync with machine() in runtime/tests/plan_cam_goldens.rs.
run() {
  local name=$1 measure=$2 opts=$3; shift 3
  # shellcheck disable=SC2086
  "$measure" $opts --speedup 1 "$@" > "$HERE/raw/$name.tsv"
}
run m60 "$MEASURE" "--vel 60 --acc 800" "${all[@]}"
run mixed "$MEASURE" "--vel 100 --acc 1000 --axis Y=50,500 --axis Z=20,200" "${all[@]}"
# m60 with the block delete switch off (LinuxCNC starts with it on): the same script,
# switching it off before each run.
on=$(mktemp)
sed 's/^    ensure_mode(linuxcnc.MODE_AUTO)$/&\n    c.set_block_delete(0); c.wait_complete(2)/' "$MEASURE" > "$on"
grep -q set_block_delete "$on" || { echo "cannot patch $MEASURE for block delete" >&2; exit 1; }
chmod +x "$on"
run m60bdoff "$on" "--vel 60 --acc 800" "${bd[@]}"
rm -f "$on"

rm -f "$HERE"/raw/*_remeasured.tsv "$HERE"/raw/*_reset.tsv
"$HERE/collect.sh"
