#!/usr/bin/env bash
# The main job of the README: system packages, then `harness nightly`.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
cargo run --release --locked -p harness -- nightly "$@"
