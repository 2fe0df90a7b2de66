#!/usr/bin/env bash
# Mutation testing of the numeric core and of the gates: every mutant
# cargo-mutants makes of impls/reference/src/float316.rs and
# harness/src/compare.rs, each judged by its own package's tests (reference:
# all of them; harness: its library tests, as the integration tests rebuild
# the whole harness per mutant), and of the code that decides a verdict
# (`gates`: the verdict type, merge, measure, check, the report model's
# comparisons and the nightly's summary), judged by the library tests,
# tests/gates.rs, which runs the binary on faulty implementations, and the
# merge and check suites; and of the compiled VM engine (`engine`:
# impls/jack/vm/src/native, tier.rs, timing.rs), judged by hack-vm's tests
# on the compiled engine from the first step, with a fixed proptest seed
# and case count so that whether a mutant is caught does not depend on the
# seed a run draws, and without appending to the tracked regressions file.
#   scripts/mutants.sh [float316|compare|gates|engine] [K/N]    (default: all, whole)
# K/N runs every N-th mutant from the K-th (K counts from 0), so N machines
# share a file. Installs cargo-mutants from crates.io when missing. Results go
# to mutants.out/FILE[-K-N]/mutants.out/{caught,missed,timeout,unviable}.txt;
# a missed mutant must be killed by a new test or listed, with its reason, in
# docs/mutants.md. The tree is mutated in place (no copy of the 20 GB target):
# leave it alone while this runs; cargo-mutants restores each file.
set -euo pipefail
cd "$(dirname "$0")/.."

which=${1:-all}
shard=${2:-}
if ! command -v cargo-mutants >/dev/null; then
    cargo install --locked cargo-mutants@27.1.0
fi
# Neither setting changes what a test decides: without debug info a mutant
# builds in a third less time, and a failing proptest is not shrunk.
export CARGO_PROFILE_DEV_DEBUG=0 PROPTEST_MAX_SHRINK_ITERS=0

run() {
    local name=$1
    shift
    local out=mutants.out/$name
    local shard_args=()
    if [ -n "$shard" ]; then
        out=$out-${shard/\//-}
        shard_args=(--shard "$shard")
    fi
    mkdir -p "$(dirname "$out")"
    cargo mutants --in-place --output "$out" "${shard_args[@]}" "$@"
}

status=0
if [ "$which" = all ] || [ "$which" = float316 ]; then
    run float316 -p reference --file impls/reference/src/float316.rs \
        --timeout 60 --build-timeout 300 || status=$?
fi
if [ "$which" = all ] || [ "$which" = compare ]; then
    run compare -p harness --file harness/src/compare.rs \
        --timeout 90 --build-timeout 1500 --cargo-test-arg=--lib || status=$?
fi
if [ "$which" = all ] || [ "$which" = gates ]; then
    # The gates span the three harness crates; each mutant is judged by
    # the tests of all three (their libraries, harness's merge suite, and
    # the command line's integration binary, whose gates, check and
    # nightly_testfloat modules were the suites named here before they
    # became one binary with the rest of its tests).
    run gates -p harness -p harness-report -p harness-cli \
        --test-package harness --test-package harness-report --test-package harness-cli \
        --file harness/src/verdict.rs --file harness/src/merge.rs \
        --file harness-report/src/measure.rs --file harness-cli/src/commands/check.rs \
        --file harness-report/src/model.rs --file harness-cli/src/nightly/mod.rs \
        --timeout 300 --build-timeout 1500 \
        --cargo-test-arg=--lib --cargo-test-arg=--test --cargo-test-arg=integration \
        --cargo-test-arg=--test --cargo-test-arg=merge || status=$?
fi
if [ "$which" = all ] || [ "$which" = engine ]; then
    HACK_VM_ENGINE=native PROPTEST_RNG_SEED=34 PROPTEST_CASES=256 \
        PROPTEST_DISABLE_FAILURE_PERSISTENCE=1 \
        run engine -p hack-vm \
        --file 'impls/jack/vm/src/native/*.rs' --file 'impls/jack/vm/src/native/*/*.rs' \
        --file impls/jack/vm/src/tier.rs \
        --file impls/jack/vm/src/timing.rs \
        --timeout 240 --build-timeout 900 || status=$?
fi
exit "$status"
