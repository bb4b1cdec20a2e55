#!/usr/bin/env bash
# Headless Neovim check of editors/nvim against a partscope binary:
#   editors/nvim/test.sh [path-to-partscope]
# Exits 0 only when the server published diagnostics for a sample with known errors,
# answered a hover with content, renamed a subroutine across two files and formatted a
# file as expected, and on editors/test/loop.ngc showed and ran the cycle-time lens, gave
# inlay block times, loop values on hover and a formatting with the CLI's dry run, within
# 20 s. Needs `nvim` (0.7 or later) on PATH.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin="${1:-${PARTSCOPE_BIN:-partscope}}"

if [[ "$bin" == */* && -d "$(dirname "$bin")" ]]; then
  bin="$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")"
fi
if ! command -v "$bin" >/dev/null 2>&1; then
  echo "FAIL: partscope binary '$bin' not found or not executable" >&2
  exit 1
fi
if ! command -v nvim >/dev/null 2>&1; then
  echo "FAIL: nvim not found (apt-get install neovim)" >&2
  exit 1
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$here/test/sample.ngc" "$work/sample.ngc"
cp "$here/../test/loop.ngc" "$work/loop.ngc"
# Isolate Neovim's state and the LSP log, so the log can be shown on failure.
export XDG_CONFIG_HOME="$work/config" XDG_DATA_HOME="$work/data" XDG_STATE_HOME="$work/state" XDG_CACHE_HOME="$work/cache"
export PARTSCOPE_BIN="$bin" PARTSCOPE_SAMPLE="$work/sample.ngc" PARTSCOPE_LOOP="$work/loop.ngc" PARTSCOPE_TIMEOUT_MS="${PARTSCOPE_TIMEOUT_MS:-20000}"

echo "nvim: $(nvim --version | head -n1); server: $bin lsp"
status=0
# The outer timeout only guards against a wedged nvim; run.lua enforces the 20 s budget itself.
timeout 60 nvim --headless -u NONE -i NONE -n \
  --cmd "set runtimepath^=$here" \
  -c "luafile $here/test/run.lua" </dev/null || status=$?

if [[ $status -ne 0 ]]; then
  [[ $status -eq 124 ]] && echo "FAIL: nvim did not finish within 60 s" >&2
  log="$(find "$work" -name 'lsp.log' 2>/dev/null | head -n1)"
  if [[ -n "$log" ]]; then
    echo "--- tail of $log ---" >&2
    tail -n 30 "$log" >&2
  fi
  exit 1
fi
echo "nvim: 1 passed, 0 failed"
