#!/usr/bin/env bash
# Checks the toolpath key of editors/helix/config.toml without Helix: runs its shell command
# as `:sh` would, with %{buffer_name} expanded to a program and `xdg-open` replaced by a stub
# that copies the page it is given, which must hold the program's dry run.
#   editors/helix/test.sh [path-to-partscope]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin="${1:-${PARTSCOPE_BIN:-partscope}}"
bin="$(command -v "$bin")" && bin="$(realpath "$bin")" || { echo "FAIL: partscope binary not found" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin" "$work/cnc dir"
ln -s "$bin" "$work/bin/partscope"
cat >"$work/bin/xdg-open" <<STUB
#!/bin/sh
cp "\$1" "$work/opened.tmp" && mv "$work/opened.tmp" "$work/opened.html"
STUB
chmod +x "$work/bin/xdg-open"
cp "$here/../nvim/test/sample.ngc" "$work/cnc dir/sample.ngc"
command="$(python3 -c 'import sys, tomllib; print(tomllib.load(open(sys.argv[1], "rb"))["keys"]["normal"]["space"]["t"])' "$here/config.toml")"
[[ "$command" == ":sh "* ]] || { echo "FAIL: the key does not run :sh: $command" >&2; exit 1; }
script="${command#:sh }"
script="${script//%\{buffer_name\}/cnc dir/sample.ngc}"
(cd "$work" && PATH="$work/bin:$PATH" TMPDIR="$work" sh -c "$script")
for _ in $(seq 100); do
  [[ -f "$work/opened.html" ]] && break
  sleep 0.1
done
[[ -f "$work/opened.html" ]] || { echo "FAIL: the key opened no page" >&2; exit 1; }
# The sample's one drawn move: the rapid of line 3 to X0 Y0 Z5.
if ! grep -qF '"points":[[0.0,0.0,0.0],[0.0,0.0,5.0]]' "$work/opened.html"; then
  echo "FAIL: the opened page lacks the sample's dry run" >&2
  exit 1
fi
echo "helix: toolpath key ok"
