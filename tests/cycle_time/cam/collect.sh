#!/usr/bin/env bash
# Builds goldens.tsv from raw/: for each machine, raw/<machine>.tsv, then any
# raw/<machine>_remeasured.tsv, raw/<machine>_reset.tsv and raw/<machine>_added.tsv
# (programs added later) passes, a later pass's row replacing an earlier one for the same
# program (see README.md). Rows of reset.ngc and rows that did not finish ("ok") are dropped.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
{
  printf 'program\tmachine\tmotion_s\n'
  for m in m60 mixed m60bdoff; do
    files=()
    for f in "$HERE/raw/$m.tsv" "$HERE/raw/${m}_remeasured.tsv" "$HERE/raw/${m}_reset.tsv" "$HERE/raw/${m}_added.tsv"; do
      [ -f "$f" ] && files+=("$f")
    done
    [ ${#files[@]} -gt 0 ] || continue
    awk -F'\t' -v m="$m" '
      FNR > 1 && $2 == "ok" && $1 !~ /reset\.ngc$/ {
        p = $1; sub(/^.*\//, "", p); sub(/\.ngc$/, "", p)
        if (!(p in v)) order[++n] = p
        v[p] = $3
      }
      END { for (i = 1; i <= n; i++) printf "%s\t%s\t%s\n", order[i], m, v[order[i]] }' "${files[@]}" | sort
  done
} > "$HERE/goldens.tsv"
echo "wrote $HERE/goldens.tsv ($(($(wc -l < "$HERE/goldens.tsv") - 1)) rows)"
