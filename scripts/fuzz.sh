#!/usr/bin/env bash
# Bounded fuzz run of the cargo-fuzz targets (fuzz/fuzz_targets), for the
# nightly job:
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 180 s, every target)
# Installs what it needs when missing: the nightly toolchain (rustup) and
# cargo-fuzz (crates.io, built with that toolchain). New coverage goes to fuzz/work/TARGET (not committed; the
# checked-in seeds are fuzz/corpus/TARGET). A crash is copied to
# fuzz/regressions/TARGET/, where `cargo test -p fuzz-checks` replays it
# from then on: commit it with the fix. Exit 1 when any target crashed.
# Figures (executions, coverage) are printed and kept in fuzz/work/summary.txt.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-180}
shift || true
if ! rustup toolchain list | grep -q '^nightly'; then
    rustup toolchain install nightly --profile minimal
fi
if ! command -v cargo-fuzz >/dev/null; then
    cargo +nightly install --locked cargo-fuzz
fi
if [ $# -gt 0 ]; then
    targets=("$@")
    # Only the targets named (a build of every target takes far longer).
    for t in "${targets[@]}"; do
        cargo +nightly fuzz build "$t"
    done
else
    mapfile -t targets < <(cargo +nightly fuzz list)
    cargo +nightly fuzz build
fi
crashed=0
summary=fuzz/work/summary.txt
mkdir -p fuzz/work
echo "target seconds executions exec/s coverage features crashed" > "$summary"
for t in "${targets[@]}"; do
    mkdir -p "fuzz/work/$t" "fuzz/regressions/$t"
    log="fuzz/work/$t.log"
    status=0
    cargo +nightly fuzz run "$t" "fuzz/work/$t" "fuzz/corpus/$t" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
        -print_final_stats=1 >"$log" 2>&1 || status=$?
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    last=$(grep -E '^#[0-9]+' "$log" | tail -1)
    cov=$(echo "$last" | grep -o 'cov: [0-9]*' | grep -o '[0-9]*' || echo 0)
    ft=$(echo "$last" | grep -o 'ft: [0-9]*' | grep -o '[0-9]*' || echo 0)
    found=no
    for a in fuzz/artifacts/"$t"/crash-* fuzz/artifacts/"$t"/timeout-* fuzz/artifacts/"$t"/oom-*; do
        [ -e "$a" ] || continue
        cp "$a" "fuzz/regressions/$t/"
        found=yes
    done
    if [ "$status" -ne 0 ] || [ "$found" = yes ]; then
        crashed=1
        found=yes
        echo "fuzz.sh: $t failed (exit $status), inputs in fuzz/regressions/$t/, log $log" >&2
    fi
    echo "$t $seconds $execs $rate $cov $ft $found" >> "$summary"
done
column -t "$summary"
exit "$crashed"
