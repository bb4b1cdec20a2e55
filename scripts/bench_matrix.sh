#!/usr/bin/env bash
# Times `partscope check --format json` and `run --format json` on 500k-line
# programs of every benchmark shape in every dialect where the shape applies,
# and LinuxCNC's `rs274 -g` on the RS274/NGC ones when it is installed. Prints a
# Markdown table: best wall time of ROUNDS runs and the peak RSS of that run.
#
#   scripts/bench_matrix.sh [BIN...]        (default: target/release/partscope)
#
# Several binaries (say a base and a new build) are run interleaved, round by
# round, so they see the same machine load. Environment: LINES (500000),
# ROUNDS (5), RS274_ROUNDS (3), DIR (generated programs, /tmp/bench_matrix),
# SHAPES and DIALECTS (space-separated subsets).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -eq 0 ] && set -- "$root/target/release/partscope"
lines=${LINES:-500000}
rounds=${ROUNDS:-5}
rs_rounds=${RS274_ROUNDS:-3}
dir=${DIR:-/tmp/bench_matrix}
shapes=${SHAPES:-"g1xyz surfacing arcs drilling fusion macro"}
dialects=${DIALECTS:-"rs274ngc fanuc servoworks"}
mkdir -p "$dir"
have_rs274=$(command -v rs274 || true)
# rs274 keeps its tool table in $HOME; a private HOME keeps runs independent.
rs_home=$(mktemp -d)
timing=$(mktemp)
trap 'rm -rf "$rs_home" "$timing"' EXIT

# Best wall time (s) and its peak RSS (MB) of `rounds` runs of the command.
best() {
    local n=$1
    shift
    local b="" m="" t
    for _ in $(seq "$n"); do
        /usr/bin/time -o "$timing" -f "%e %M" "$@" >/dev/null 2>&1 </dev/null
        t=$(tail -1 "$timing")
        if [ -z "$b" ] || awk -v a="${t% *}" -v b="$b" 'BEGIN { exit !(a < b) }'; then
            b=${t% *}
            m=$(awk -v k="${t#* }" 'BEGIN { printf "%.0f", k / 1024 }')
        fi
    done
    echo "$b $m"
}

header="| shape | dialect | MB |"
rule="|---|---|---|"
for bin in "$@"; do
    name=$(basename "$bin")
    header="$header $name check s | MB | $name run s | MB |"
    rule="$rule---|---|---|---|"
done
[ -n "$have_rs274" ] && { header="$header rs274 -g s | check × rs274 | run × rs274 |"; rule="$rule---|---|---|"; }
echo "$header"
echo "$rule"

for shape in $shapes; do
    for d in $dialects; do
        # Fusion-style output is a FANUC (and LinuxCNC) post; ServoWorks has no such post.
        [ "$shape" = fusion ] && [ "$d" = servoworks ] && continue
        f="$dir/$shape.$d.$lines.nc"
        [ -s "$f" ] || python3 "$root/scripts/gen_programs.py" "$shape" --dialect "$d" --lines "$lines" >"$f"
        mb=$(awk -v s="$(stat -L -c %s "$f")" 'BEGIN { printf "%.1f", s / 1e6 }')
        row="| $shape | $d | $mb |"
        declare -A cbest=() rbest=()
        for _ in $(seq "$rounds"); do
            for bin in "$@"; do
                for cmd in check run; do
                    t=$(best 1 "$bin" "$cmd" --format json --dialect "$d" "$f")
                    key="$bin"
                    if [ "$cmd" = check ]; then cur=${cbest[$key]:-}; else cur=${rbest[$key]:-}; fi
                    if [ -z "$cur" ] || awk -v a="${t% *}" -v b="${cur% *}" 'BEGIN { exit !(a < b) }'; then
                        if [ "$cmd" = check ]; then cbest[$key]=$t; else rbest[$key]=$t; fi
                    fi
                done
            done
        done
        for bin in "$@"; do
            row="$row ${cbest[$bin]% *} | ${cbest[$bin]#* } | ${rbest[$bin]% *} | ${rbest[$bin]#* } |"
        done
        if [ -n "$have_rs274" ]; then
            if [ "$d" = rs274ngc ]; then
                rs=$(export HOME=$rs_home; best "$rs_rounds" rs274 -g "$f")
                last=${*: -1}
                c=${cbest[$last]% *}
                r=${rbest[$last]% *}
                ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.1f", a / b; else print "-" }'; }
                row="$row ${rs% *} | $(ratio "${rs% *}" "$c") | $(ratio "${rs% *}" "$r") |"
            else
                row="$row – | – | – |"
            fi
        fi
        echo "$row"
        unset cbest rbest
    done
done
