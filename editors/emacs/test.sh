#!/usr/bin/env bash
# Batch-Emacs check of editors/emacs/partscope.el with eglot against a partscope binary:
#   editors/emacs/test.sh [path-to-partscope]
# Byte-compiles partscope.el with warnings as errors, then requires diagnostics and a hover
# from the server, and on editors/test/loop.ngc the lens's breakdown, inlay block times,
# loop values on hover, formatting and rename, within 20 s. Needs emacs (27+) and eglot (built in from 29; elpa-eglot).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin="${1:-${PARTSCOPE_BIN:-partscope}}"
if [[ "$bin" == */* && -d "$(dirname "$bin")" ]]; then
  bin="$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")"
fi
command -v emacs >/dev/null || { echo "FAIL: emacs not found (apt-get install emacs-nox elpa-eglot)" >&2; exit 1; }
command -v "$bin" >/dev/null || { echo "FAIL: partscope binary '$bin' not found" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$here/partscope.el" "$work/"
emacs --batch -Q -L "$work" --eval '(setq byte-compile-error-on-warn t)' -f batch-byte-compile "$work/partscope.el"
cp "$here/../nvim/test/sample.ngc" "$work/sample.ngc"
cp "$here/../test/loop.ngc" "$work/loop.ngc"
export PARTSCOPE_BIN="$bin" PARTSCOPE_SAMPLE="$work/sample.ngc" PARTSCOPE_LOOP="$work/loop.ngc" HOME="$work"
timeout 60 emacs --batch -Q -L "$work" -l "$here/test/eglot-test.el"
echo "emacs: 1 passed, 0 failed"
