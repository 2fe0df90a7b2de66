#!/usr/bin/env bash
# The test command of the README: system packages, then the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
cargo test --workspace --locked "$@"
