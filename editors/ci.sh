#!/usr/bin/env bash
# CI for the editor integrations (called by .ci/run with PARTSCOPE_BIN set to a built binary).
#
# Debian packages it needs, installed by .ci/run:
#   nodejs (>= 20; @vscode/vsce 3 refuses older) with npm, chromium, neovim (0.7+), unzip,
#   emacs-nox + elpa-eglot (without them the Emacs test is reported as skipped); a C compiler
#   and cargo for the tree-sitter grammar's tests (the CLI comes from crates.io).
# npm packages come from the npm registry through `npm ci` (package-lock.json is committed);
# no browser is downloaded: the preview test drives /usr/bin/chromium via playwright-core.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
passed=0
failed=0
run() {
  local name="$1"
  shift
  echo "::: editors: $name"
  if "$@"; then
    passed=$((passed + 1))
  else
    echo "::: editors: $name FAILED"
    failed=$((failed + 1))
  fi
}

# `npm test` includes the browser tests that need the server (stopped-run, html-page): they
# read PARTSCOPE_BIN from the environment and skip without it.
vscode() {
  cd "$here/vscode"
  npm ci --no-audit --no-fund
  npm run package </dev/null
  npm test
}

vsix_contents() {
  local listing missing=0
  listing="$(unzip -l "$here/vscode/partscope.vsix")"
  echo "$listing"
  for f in extension/package.json extension/language-configuration.json \
    extension/syntaxes/gcode.tmLanguage.json extension/out/extension.js \
    extension/media/preview.html extension/media/preview.js extension/media/preview.css; do
    if ! grep -qE "[[:space:]]$f\$" <<<"$listing"; then
      echo "missing from partscope.vsix: $f"
      missing=1
    fi
  done
  # The bundle must carry the language client; node_modules is not shipped.
  # grep -c reads to the end: an early exit (grep -q) would SIGPIPE unzip and trip pipefail.
  if ! unzip -p "$here/vscode/partscope.vsix" extension/out/extension.js | grep -c "LanguageClient" >/dev/null; then
    echo "extension/out/extension.js does not contain the bundled language client"
    missing=1
  fi
  return "$missing"
}

helix_toml() {
  python3 - "$here/helix/languages.toml" <<'PY'
import sys, tomllib
cfg = tomllib.load(open(sys.argv[1], "rb"))
lang = next(l for l in cfg["language"] if l["name"] == "gcode")
assert lang["language-servers"] == ["partscope"], lang
assert cfg["language-server"]["partscope"]["args"] == ["lsp"]
assert set(lang["file-types"]) == {"nc", "ngc", "tap", "cnc", "gcode", "eia", "dat", "min", "mpf", "fnc", "sw"}
grammar = next(g for g in cfg["grammar"] if g["name"] == lang["grammar"])
assert grammar["source"]["path"].endswith("/editors/tree-sitter-partscope"), grammar
print("helix languages.toml ok")
PY
}

# The tree-sitter grammar: the committed parser is what grammar.js generates, its corpus and
# highlight tests pass, the fixtures parse without error nodes but those listed in
# test/expected-errors.txt, and Neovim (when present) loads it and colours as the tests say.
# The CLI is built from crates.io once per machine (cargo install keeps it in ~/.cargo/bin),
# without its QuickJS feature (`generate` uses node): 6 CPU-minutes the first time (measured:
# 5 min 55 s user, 13 min 46 s wall on two cores shared with other builds), nothing after;
# the step itself takes about 3 s.
TREE_SITTER_CLI_VERSION=0.27.1
tree_sitter() (
  # A subshell, so that `cd` stays here; every step is checked (`run` calls this in an `if`,
  # where `set -e` does not apply).
  local dir="$here/tree-sitter-partscope" repo
  repo="$(cd "$here/.." && pwd)"
  if [[ "$(tree-sitter --version 2>/dev/null)" != "tree-sitter $TREE_SITTER_CLI_VERSION" ]]; then
    local t0=$SECONDS
    cargo install --locked --no-default-features tree-sitter-cli --version "$TREE_SITTER_CLI_VERSION" || return 1
    echo "tree-sitter CLI built in $((SECONDS - t0)) s"
  fi
  cd "$dir" || return 1
  tree-sitter generate --abi 14 || return 1
  if ! git diff --quiet -- src; then
    git diff --stat -- src
    echo "src/ differs from what grammar.js generates: run 'tree-sitter generate --abi 14' in editors/tree-sitter-partscope and commit src/"
    return 1
  fi
  # --rebuild: the CLI caches parsers by name, and a stale one may look newer than src/.
  tree-sitter test --rebuild || return 1
  python3 scripts/parse-check.py --expect test/expected-errors.txt \
    "$repo/analyzer/tests/rules" "$repo/tests/conformance" "$repo/examples" || return 1
  if command -v nvim >/dev/null && command -v cc >/dev/null; then
    test/nvim.sh || return 1
  fi
)

emacs_compile() {
  local work
  work="$(mktemp -d)"
  cp "$here/emacs/partscope.el" "$work/"
  emacs --batch -Q -L "$work" --eval '(setq byte-compile-error-on-warn t)' -f batch-byte-compile "$work/partscope.el"
  local rc=$?
  rm -rf "$work"
  return $rc
}

run "tree-sitter: generate, test, parse the fixtures" tree_sitter
run "vscode: npm ci, package, test" vscode
run "vscode: .vsix contents" vsix_contents
if command -v python3 >/dev/null && python3 -c 'import tomllib' 2>/dev/null; then
  run "helix: languages.toml" helix_toml
fi

# Until the server grows its `lsp` subcommand (built on another branch), a binary without it is
# reported as a skip rather than a failure; once `--help` lists `lsp`, the editor LSP tests are
# mandatory.
has_lsp() {
  "$PARTSCOPE_BIN" --help 2>&1 | grep -Eq '^[[:space:]]+lsp([[:space:]]|$)'
}
skipped=0
if [[ -n "${PARTSCOPE_BIN:-}" ]] && ! has_lsp; then
  echo "::: editors: SKIPPED the Neovim/Emacs LSP tests: '$PARTSCOPE_BIN --help' lists no 'lsp' subcommand"
  skipped=1
fi

if [[ -n "${PARTSCOPE_BIN:-}" ]] && command -v python3 >/dev/null && python3 -c 'import tomllib' 2>/dev/null; then
  run "helix: toolpath key against $PARTSCOPE_BIN" "$here/helix/test.sh" "$PARTSCOPE_BIN"
fi

if [[ -n "${PARTSCOPE_BIN:-}" && $skipped -eq 0 ]]; then
  run "nvim: LSP against $PARTSCOPE_BIN" "$here/nvim/test.sh" "$PARTSCOPE_BIN"
  if command -v emacs >/dev/null && emacs --batch -Q --eval \
    '(progn (let ((default-directory "/usr/share/emacs/site-lisp/elpa/")) (when (file-directory-p default-directory) (normal-top-level-add-subdirs-to-load-path))) (kill-emacs (if (require (quote eglot) nil t) 0 1)))' 2>/dev/null; then
    run "emacs: eglot against $PARTSCOPE_BIN" "$here/emacs/test.sh" "$PARTSCOPE_BIN"
  else
    echo "::: editors: SKIPPED the Emacs/eglot test: emacs with eglot is not installed (apt-get install emacs-nox elpa-eglot)"
    skipped=$((skipped + 1))
  fi
else
  [[ -z "${PARTSCOPE_BIN:-}" ]] && echo "::: editors: PARTSCOPE_BIN not set; skipping the Neovim and Emacs LSP tests"
  if command -v emacs >/dev/null; then
    run "emacs: byte-compile" emacs_compile
  fi
fi

echo "editors: ${passed} passed, ${failed} failed, ${skipped} skipped"
[[ $failed -eq 0 ]]
