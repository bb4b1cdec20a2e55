#!/usr/bin/env bash
# regenerate.sh - rebuild the conformance goldens from the real LinuxCNC interpreter.
#
# For every programs/<name>.ngc this runs /work/shared/oracle/run_rs274.sh (LinuxCNC 2.9's
# standalone `rs274`, default options: counter stripped, stop at the first error) and writes
#   goldens/<name>.canon   canonical calls on stdout (byte-exact, counter removed)
#   goldens/<name>.stderr  rs274's error lines (empty when the program ran cleanly)
#   goldens/<name>.status  rs274's exit status as a decimal number (0 ok, 1 error)
# A programs/<name>.tbl beside the program is passed as the tool table (-t), and a
# programs/<name>.var as the parameter file (-v); without them the wrapper's defaults apply
# (LinuxCNC's sample tool table, all parameters zero).
#
# The script is idempotent: rerunning it on unchanged programs rewrites identical files, and
# goldens whose program has been deleted are removed.  Usage:
#   tests/conformance/regenerate.sh            # every program
#   tests/conformance/regenerate.sh NAME...    # only these programs (name without .ngc)
# Absolute paths of the programs directory inside rs274's messages are stripped from the
# .stderr goldens, so they read "file:NAME.ngc" wherever the checkout lives.
# Every rs274 run gets a private HOME: rs274 shares its tool table between processes through
# $HOME/.tool.mmap, so concurrent runs would otherwise corrupt each other.
# Environment: ORACLE=path/to/run_rs274.sh overrides the wrapper location.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
oracle=${ORACLE:-/work/shared/oracle/run_rs274.sh}
[ -x "$oracle" ] || { echo "regenerate.sh: $oracle not found or not executable" >&2; exit 2; }
programs=$here/programs
goldens=$here/goldens
mkdir -p "$goldens"

# rs274 keeps its tool table in a memory-mapped file $HOME/.tool.mmap that every rs274 process
# on the machine shares; concurrent runs (other engineers, parallel tests) then corrupt each
# other's tool data or die with SIGBUS.  Each run therefore gets a private HOME.
scratch=$(mktemp -d /tmp/conformance-regen.XXXXXX)
trap 'rm -rf "$scratch"' EXIT

if [ $# -gt 0 ]; then
  names=("$@")
else
  names=()
  for f in "$programs"/*.ngc; do names+=("$(basename "$f" .ngc)"); done
  # Drop goldens of programs that no longer exist so the directory mirrors programs/.
  for g in "$goldens"/*.status; do
    [ -e "$g" ] || continue
    n=$(basename "$g" .status)
    if [ ! -e "$programs/$n.ngc" ]; then
      rm -f "$goldens/$n.canon" "$goldens/$n.stderr" "$goldens/$n.status"
    fi
  done
fi

for n in "${names[@]}"; do
  ngc=$programs/$n.ngc
  [ -r "$ngc" ] || { echo "regenerate.sh: no program $ngc" >&2; exit 2; }
  args=()
  [ -e "$programs/$n.tbl" ] && args+=(-t "$programs/$n.tbl")
  [ -e "$programs/$n.var" ] && args+=(-v "$programs/$n.var")
  set +e
  rm -rf "$scratch/home"; mkdir -p "$scratch/home"
  HOME=$scratch/home "$oracle" "${args[@]}" -o "$goldens/$n.canon" "$ngc" 2> "$goldens/$n.stderr"
  rc=$?
  set -e
  if [ $rc -gt 1 ]; then
    echo "regenerate.sh: oracle failed on $n (exit $rc):" >&2
    cat "$goldens/$n.stderr" >&2
    exit 2
  fi
  # Messages such as "EOF in file:<path> seeking o-word" embed the program's absolute path;
  # strip the programs directory so goldens do not depend on where the checkout lives.
  sed -i "s|$programs/||g" "$goldens/$n.stderr"
  echo "$rc" > "$goldens/$n.status"
  printf '%-28s status %s\n' "$n" "$rc"
done
