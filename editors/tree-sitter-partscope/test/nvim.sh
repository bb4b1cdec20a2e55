#!/usr/bin/env bash
# Loads the grammar and queries/highlights.scm into headless Neovim (0.7 or later)
# and checks every assertion of test/highlight against what Neovim captures.
# Needs nvim and a C compiler.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rtp="$(mktemp -d)"
trap 'rm -rf "$rtp"' EXIT
mkdir -p "$rtp/parser" "$rtp/queries/partscope"
cc -shared -fPIC -O1 -I "$here/src" "$here/src/parser.c" "$here/src/scanner.c" -o "$rtp/parser/partscope.so"
cp "$here/queries/highlights.scm" "$rtp/queries/partscope/"
status=0
HIGHLIGHT_DIR="$here/test/highlight" nvim --headless --clean \
  --cmd "set runtimepath^=$rtp" -c "luafile $here/test/nvim/highlights.lua" 2>&1 || status=$?
# Headless Neovim ends its last message without a line break.
echo
exit "$status"
