#!/usr/bin/env bash
# Runs two partscope binaries over every program corpus the project has and reports
# where their outputs differ: `check --format json` and `run --format json` in each
# dialect, and `run --emit canon` in rs274ngc (stdout, stderr and exit status of each).
# Used to show that a refactoring leaves behaviour byte-identical.
#
# Usage: scripts/compare_outputs.sh BASE_BIN NEW_BIN [FILE...]
#   Without FILEs it walks tests/, examples/, analyzer/tests/, runtime/tests/,
#   server/tests/ and /work/shared/corpus/linuxcnc/ (CORPUS_EXTRA adds more roots) for
#   .ngc .nc .fnc .sw .dat programs. A sibling NAME.tbl / NAME.var is passed to `run`
#   as --tool-table / --var-file (the var file as a fresh copy for each run).
# Prints one line per difference and a summary; exits 1 when anything differs.
set -u
base=$(readlink -f "$1")
new=$(readlink -f "$2")
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

files=()
if [ $# -gt 0 ]; then
  for f in "$@"; do files+=("$(readlink -f "$f")"); done
else
  roots=()
  for d in tests examples analyzer/tests runtime/tests server/tests; do
    [ -d "$root/$d" ] && roots+=("$root/$d")
  done
  for d in /work/shared/corpus/linuxcnc ${CORPUS_EXTRA:-}; do
    [ -d "$d" ] && roots+=("$d")
  done
  while IFS= read -r f; do files+=("$f"); done < <(
    find "${roots[@]}" -type f \( -iname '*.ngc' -o -iname '*.nc' -o -iname '*.fnc' \
      -o -iname '*.sw' -o -iname '*.dat' \) | LC_ALL=C sort)
fi

runs=0
diffs=0
# one NAME BIN ARGS...: runs BIN with ARGS in the program's directory, output to NAME.*
one() {
  local name=$1 bin=$2
  shift 2
  (cd "$dir" && timeout 60 "$bin" "$@" >"$work/$name.out" 2>"$work/$name.err")
  echo $? >"$work/$name.rc"
}
# case LABEL ARGS...: runs both binaries and compares the three outputs.
case_() {
  local label=$1
  shift
  local args=("$@")
  if [ -n "$var" ]; then
    cp "$var" "$work/a.var"
    cp "$var" "$work/b.var"
  fi
  one a "$base" "${args[@]}" ${var:+--var-file "$work/a.var"}
  one b "$new" "${args[@]}" ${var:+--var-file "$work/b.var"}
  runs=$((runs + 1))
  local part
  for part in out err rc; do
    if ! cmp -s "$work/a.$part" "$work/b.$part"; then
      diffs=$((diffs + 1))
      echo "DIFF [$part] $label: $f"
      break
    fi
  done
}

for f in "${files[@]}"; do
  dir=$(dirname "$f")
  stem=${f%.*}
  tbl=()
  [ -e "$stem.tbl" ] && tbl=(--tool-table "$stem.tbl")
  var=""
  [ -e "$stem.var" ] && var=$stem.var
  for d in servoworks rs274ngc fanuc; do
    saved_var=$var
    var=""
    case_ "check $d" check --format json --dialect "$d" "$f"
    var=$saved_var
    case_ "run $d" run --format json --dialect "$d" "${tbl[@]}" "$f"
    if [ "$d" = rs274ngc ]; then
      case_ "canon $d" run --emit canon --dialect "$d" "${tbl[@]}" "$f"
    fi
  done
done

echo "${#files[@]} files, $runs runs per binary, $diffs differences"
[ "$diffs" -eq 0 ]
