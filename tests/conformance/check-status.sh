#!/usr/bin/env bash
# check-status.sh - does `partscope check --format json` report an error exactly on the
# programs rs274 rejects (goldens/NAME.status 1) and on none it runs cleanly (status 0)?
#
# Each program is checked in a scratch directory with a partscope.toml naming its tool table
# (its own NAME.tbl, else the table rs274 reads by default) and its NAME.var, the same inputs
# regenerate.sh gives rs274.  Prints every disagreement and a count; exits 1 on any.
# Environment: PARTSCOPE_BIN=path picks the binary (default: target/debug/partscope).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${PARTSCOPE_BIN:-$here/../../target/debug/partscope}
scratch=$(mktemp -d /tmp/check-status.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
agree=0; disagree=0
for ngc in "$here"/programs/*.ngc; do
  n=$(basename "$ngc" .ngc)
  d=$scratch/$n; mkdir -p "$d"; cp "$ngc" "$d/"
  {
    echo 'dialect = "rs274ngc"'
    if [ -e "$here/programs/$n.tbl" ]; then
      cp "$here/programs/$n.tbl" "$d/"; echo "tool_table = \"$n.tbl\""
    else
      printf 'T1 P1 D0.125000 Z+0.511000\nT2 P2 D0.062500 Z+0.100000\nT3 P3 D0.201000 Z+1.273000\nT99999 P123 Z+0.100000\n' > "$d/default.tbl"
      echo 'tool_table = "default.tbl"'
    fi
    if [ -e "$here/programs/$n.var" ]; then cp "$here/programs/$n.var" "$d/"; echo "var_file = \"$n.var\""; fi
  } > "$d/partscope.toml"
  errors=$("$bin" check --format json "$d/$n.ngc" 2>/dev/null | grep -c '"severity": "error"')
  status=$(cat "$here/goldens/$n.status")
  if { [ "$status" = 0 ] && [ "$errors" = 0 ]; } || { [ "$status" = 1 ] && [ "$errors" != 0 ]; }; then
    agree=$((agree + 1))
  else
    disagree=$((disagree + 1)); echo "disagree: $n (rs274 status $status, $errors errors)"
  fi
done
echo "check --format json agrees with rs274 on $agree programs, disagrees on $disagree"
[ "$disagree" = 0 ]
