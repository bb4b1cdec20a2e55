#!/usr/bin/env bash
# Runs every fuzz target for a fixed number of executions and fails when any
# target finds a crash, a timeout or an out-of-memory input.
#
#   scripts/fuzz.sh [EXECUTIONS] [TARGET...]
#
# EXECUTIONS defaults to 100000 per target. Targets default to all of
# `cargo fuzz list`. Needs cargo-fuzz (`cargo install --locked cargo-fuzz`)
# and a nightly toolchain, or stable with RUSTC_BOOTSTRAP=1 (set below when
# no nightly is installed). Crashes land in fuzz/artifacts/<target>/; turn
# each into a fixture under tests/robustness/crashes/ (see the README there).
# Each target's log is fuzz/logs/<target>.log.
#
# The code under test is safe Rust, so the default sanitizer is `none`
# (coverage-guided only, several times faster than AddressSanitizer on this
# allocation-heavy code); set FUZZ_SANITIZER=address to run with ASan.
#
# Comparison tracing (`-sanitizer-coverage-trace-compares`) is off by default:
# on this code libFuzzer spent ~40% of each execution in the comparison
# hooks, and turning them off doubled executions per second (analyze_all:
# 1 120 -> 2 060 exec/s). Set FUZZ_TRACE_COMPARES=1 to turn them back on.
# Debug assertions and overflow checks stay on (cargo-fuzz's default).
#
# libFuzzer's -timeout is wall-clock time: on a machine loaded by other
# builds a unit that takes 0.3 s of CPU was reported as a 14 s timeout. Set
# FUZZ_TIMEOUT=60 there (default 10), and re-time any timeout artifact alone.
set -euo pipefail

runs="${1:-100000}"
shift || true
cd "$(dirname "$0")/.."

toolchain=()
if rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
    toolchain=(+nightly)
else
    export RUSTC_BOOTSTRAP=1
fi

if [ "$#" -gt 0 ]; then
    targets=("$@")
else
    mapfile -t targets < <(cargo "${toolchain[@]}" fuzz list)
fi

trace=(--no-trace-compares)
if [ "${FUZZ_TRACE_COMPARES:-0}" = 1 ]; then
    trace=()
fi

mkdir -p fuzz/logs
failed=()
for t in "${targets[@]}"; do
    mkdir -p "fuzz/corpus/$t"
    # Seed an empty corpus with the example programs and fixtures so the
    # fuzzer starts from realistic input instead of nothing.
    if [ -z "$(ls -A "fuzz/corpus/$t")" ]; then
        cp examples/* tests/robustness/seeds/* tests/robustness/crashes/* "fuzz/corpus/$t/" 2>/dev/null || true
    fi
    log="fuzz/logs/$t.log"
    echo "== $t: $runs executions (log: $log)"
    # -rss_limit_mb and -timeout turn memory blow-ups and hangs into failures;
    # -max_len 1024 keeps inputs a few blocks long, long-line cases come from the
    # robustness test.
    # FUZZ_NO_BUILD=1 runs the binary already built in fuzz/target (a
    # coverage-instrumented rebuild of lsp_messages takes over 20 minutes on
    # the loaded machine, and `cargo fuzz run` rebuilds after any source edit).
    if [ "${FUZZ_NO_BUILD:-0}" = 1 ]; then
        mkdir -p "fuzz/artifacts/$t"
        runner=("fuzz/target/x86_64-unknown-linux-gnu/release/$t" -artifact_prefix="fuzz/artifacts/$t/" "fuzz/corpus/$t")
    else
        runner=(cargo "${toolchain[@]}" fuzz run -s "${FUZZ_SANITIZER:-none}" "${trace[@]}" "$t" "fuzz/corpus/$t" --)
    fi
    if "${runner[@]}" \
        -runs="$runs" -max_len="${FUZZ_MAX_LEN:-1024}" -timeout="${FUZZ_TIMEOUT:-10}" -rss_limit_mb=2048 \
        -dict=fuzz/gcode.dict -print_final_stats=1 >"$log" 2>&1; then
        execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
        echo "   ok: $execs executions, 0 crashes"
    else
        echo "   FAILED: see $log and fuzz/artifacts/$t/"
        failed+=("$t")
    fi
done

if [ "${#failed[@]}" -gt 0 ]; then
    echo "fuzz: crashes in: ${failed[*]}" >&2
    exit 1
fi
echo "fuzz: all targets clean"
