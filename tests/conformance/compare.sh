#!/usr/bin/env bash
# compare.sh - show how partscope's canonical output for one RS274/NGC program differs from
# LinuxCNC's rs274.
#
# Usage: tests/conformance/compare.sh [-t TOOL.tbl] [-v PARAMS.var] [-w] FILE.ngc
#   -t FILE  tool table (default: FILE's sibling NAME.tbl if present, else rs274's default)
#   -v FILE  parameter file (default: sibling NAME.var if present, else all parameters zero)
#   -w       compare motion only: keep STRAIGHT_TRAVERSE/STRAIGHT_FEED/ARC_FEED/DWELL lines,
#            drop the N..... field and print -0.0000 as 0.0000
# Prints a unified diff (--- rs274, +++ partscope) of stdout, then of stderr, then both exit
# statuses; exits 0 when everything is identical and 1 otherwise.
# Environment: PARTSCOPE=binary to test (default: target/debug/partscope of this checkout,
#              built with `cargo build -p partscope` when missing);
#              ORACLE=path to run_rs274.sh (default /work/shared/oracle/run_rs274.sh).
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
oracle=${ORACLE:-/work/shared/oracle/run_rs274.sh}
tbl=""; var=""; motion=0
while getopts "t:v:wh" opt; do
  case $opt in
    t) tbl=$OPTARG ;; v) var=$OPTARG ;; w) motion=1 ;;
    *) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
  esac
done
shift $((OPTIND-1))
[ $# -eq 1 ] || { sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
ngc=$(readlink -f "$1")
[ -r "$ngc" ] || { echo "compare.sh: cannot read $1" >&2; exit 2; }
base=${ngc%.ngc}
[ -z "$tbl" ] && [ -e "$base.tbl" ] && tbl=$base.tbl
[ -z "$var" ] && [ -e "$base.var" ] && var=$base.var

bin=${PARTSCOPE:-$root/target/debug/partscope}
if [ ! -x "$bin" ]; then
  (cd "$root" && cargo build -q -p partscope) || exit 2
fi

work=$(mktemp -d /tmp/compare.XXXXXX)
trap 'rm -rf "$work"' EXIT
oargs=(); pargs=()
[ -n "$tbl" ] && { oargs+=(-t "$tbl"); pargs+=(--tool-table "$(readlink -f "$tbl")"); }
if [ -n "$var" ]; then
  # Both interpreters get scratch copies: rs274 rewrites its parameter file on exit.
  cp "$var" "$work/ours.var"
  oargs+=(-v "$var"); pargs+=(--var-file "$work/ours.var")
fi
# A private HOME keeps rs274's shared $HOME/.tool.mmap away from concurrent rs274 runs.
mkdir -p "$work/home"
HOME=$work/home "$oracle" "${oargs[@]}" "$ngc" > "$work/rs274.out" 2> "$work/rs274.err"
rs=$?
(cd "$(dirname "$ngc")" && timeout 10 "$bin" run --dialect rs274ngc --emit canon "${pargs[@]}" "$ngc") \
  > "$work/partscope.out" 2> "$work/partscope.err" < /dev/null
ps=$?

if [ $motion -eq 1 ]; then
  for f in rs274 partscope; do
    grep -E '(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|DWELL)\(' "$work/$f.out" \
      | sed -E 's/^ *N[^ ]* +//; s/-0\.0000/0.0000/g' > "$work/$f.motion"
    mv "$work/$f.motion" "$work/$f.out"
  done
fi

same=0
echo "== stdout"
diff -u --label rs274 --label partscope "$work/rs274.out" "$work/partscope.out" && echo "(identical)" || same=1
echo "== stderr"
diff -u --label rs274 --label partscope "$work/rs274.err" "$work/partscope.err" && echo "(identical)" || same=1
echo "== exit status: rs274 $rs, partscope $ps"
[ "$rs" -eq "$ps" ] || same=1
exit $same
