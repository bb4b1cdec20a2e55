#!/usr/bin/env bash
# sweep.sh DIR - compare `partscope` with the reference rs274 on every *.ngc in DIR (programs the
# suite has never seen, e.g. LinuxCNC's own nc_files/ samples: `git show HEAD:nc_files/NAME.ngc`
# from a checkout of github:LinuxCNC/linuxcnc). Not run in CI: the programs are not ours to commit.
#
# For each program, with the tool table below (the one check-status.sh uses):
#   status: rs274's exit status vs whether `partscope check --format json` reports an error;
#   motion: for programs rs274 runs cleanly, the STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED /
#           DWELL / NURBS_FEED / STRAIGHT_PROBE lines of `partscope run --emit canon` and of rs274,
#           compared with a tolerance of 1e-4 on every number.
# Environment: PARTSCOPE_BIN (default target/debug/partscope).
set -uo pipefail
dir=${1:?usage: sweep.sh DIR}
here=$(cd "$(dirname "$0")" && pwd)
bin=${PARTSCOPE_BIN:-$here/../../target/debug/partscope}
scratch=$(mktemp -d /tmp/sweep.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
printf 'T1 P1 D0.125000 Z+0.511000\nT2 P2 D0.062500 Z+0.100000\nT3 P3 D0.201000 Z+1.273000\nT99999 P123 Z+0.100000\n' > "$scratch/t.tbl"
printf 'dialect = "rs274ngc"\ntool_table = "t.tbl"\n' > "$scratch/partscope.toml"
motion_lines() {
  grep -E 'STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|DWELL|NURBS_FEED|STRAIGHT_PROBE' "$1" |
    sed -E 's/^ *[0-9]* *N[^ ]* *//'
}
status_agree=0; status_total=0; motion_agree=0; motion_total=0
for f in "$dir"/*.ngc; do
  n=$(basename "$f"); cp "$f" "$scratch/$n"
  HOME=$(mktemp -d -p "$scratch") timeout 30 rs274 -t "$scratch/t.tbl" -g "$scratch/$n" </dev/null >"$scratch/rs.out" 2>/dev/null
  rc=$?
  errors=$(timeout 60 "$bin" check --format json "$scratch/$n" 2>/dev/null | grep -c '"severity": "error"')
  status_total=$((status_total + 1))
  if { [ $rc = 0 ] && [ "$errors" = 0 ]; } || { [ $rc != 0 ] && [ "$errors" != 0 ]; }; then
    status_agree=$((status_agree + 1))
  else
    echo "status differs: $n (rs274 exit $rc, check errors $errors)"
  fi
  [ $rc = 0 ] || continue
  motion_total=$((motion_total + 1))
  timeout 60 "$bin" run --dialect rs274ngc --emit canon --tool-table "$scratch/t.tbl" "$scratch/$n" >"$scratch/ps.out" 2>/dev/null
  if python3 - "$scratch/rs.out" "$scratch/ps.out" <<'PY'
import re, sys
def lines(p):
    keep = re.compile(r"STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|DWELL|NURBS_FEED|STRAIGHT_PROBE")
    return [re.sub(r"^\s*\d*\s*N\S*\s*", "", l.strip()) for l in open(p, errors="replace") if keep.search(l)]
num = re.compile(r"-?\d+(?:\.\d+)?")
a, b = lines(sys.argv[1]), lines(sys.argv[2])
ok = len(a) == len(b) and all(
    x.split("(")[0] == y.split("(")[0]
    and len(num.findall(x)) == len(num.findall(y))
    and all(abs(float(p) - float(q)) <= 1.1e-4 for p, q in zip(num.findall(x), num.findall(y)))
    for x, y in zip(a, b))
sys.exit(0 if ok else 1)
PY
  then motion_agree=$((motion_agree + 1)); else echo "motion differs: $n"; fi
done
echo "status agrees on $status_agree of $status_total programs; motion calls agree on $motion_agree of the $motion_total rs274 runs cleanly"
