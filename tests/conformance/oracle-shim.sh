#!/usr/bin/env bash
# oracle-shim.sh - accepts partscope's command line
#   run --dialect rs274ngc --emit canon [--tool-table T] [--var-file V] FILE
# and answers with the real LinuxCNC interpreter through /work/shared/oracle/run_rs274.sh.
# It exists to check the conformance harness itself: with
#   PARTSCOPE_BIN=$PWD/tests/conformance/oracle-shim.sh cargo test -p partscope --test conformance -- --nocapture
# every program and every runnable corpus test must match, so any mismatch is a harness bug.
set -u
oracle=${ORACLE:-/work/shared/oracle/run_rs274.sh}
args=()
[ "${1:-}" = run ] || { echo "oracle-shim.sh: expected 'run'" >&2; exit 2; }
shift
while [ $# -gt 1 ]; do
  case $1 in
    --dialect) [ "$2" = rs274ngc ] || { echo "oracle-shim.sh: dialect $2" >&2; exit 2; }; shift 2 ;;
    --emit) [ "$2" = canon ] || { echo "oracle-shim.sh: emit $2" >&2; exit 2; }; shift 2 ;;
    --tool-table) args+=(-t "$2"); shift 2 ;;
    --var-file) args+=(-v "$2"); shift 2 ;;
    *) echo "oracle-shim.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
# rs274 shares tool data between processes through $HOME/.tool.mmap; the harness runs
# programs in parallel, so each run needs its own HOME or the runs corrupt each other.
home=$(mktemp -d /tmp/oracle-shim.XXXXXX)
trap 'rm -rf "$home"' EXIT
HOME=$home "$oracle" "${args[@]}" "$1"
