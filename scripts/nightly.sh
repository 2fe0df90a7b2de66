#!/usr/bin/env bash
# The main job of the README: system packages, then `harness nightly`, then
# the tests too long for `cargo test` (`#[ignore]`d: the whole `Main.main`
# run against the committed render, on both engines and bound to the
# tracer; the generated seed program's Main.main against the same), then a bounded fuzz run of every target (`scripts/fuzz.sh`,
# FUZZ_SECONDS per target, default 60). Exit 1 when any of them fails; the
# report is written in any case.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
status=0
cargo run --release --locked -p harness-cli -- nightly "$@" || status=$?
cargo test --release --locked -p jack -- --ignored || status=1
cargo test --release --locked -p scene-jack -- --ignored || status=1
scripts/fuzz.sh "${FUZZ_SECONDS:-60}" || status=1
exit "$status"
