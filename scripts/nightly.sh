#!/usr/bin/env bash
# The main job of the README: system packages, then `harness nightly`, then
# the tests too long for `cargo test` (`#[ignore]`d: the whole Jack image
# through the entry points and the whole `Main.main` run, each against the
# committed render). Exit 1 when either fails; the report is written in
# any case.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
status=0
cargo run --release --locked -p harness -- nightly "$@" || status=$?
cargo test --release --locked -p jack -- --ignored || status=1
exit "$status"
