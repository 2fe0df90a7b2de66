#!/usr/bin/env bash
# The test command of the README: system packages, then the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
cargo test --workspace --locked "$@"
# The emulator's suites again on the compiled engine from the first step
# (HACK_VM_ENGINE picks the default engine of every Machine; the first run
# used the default, auto, whose short runs stay on the interpreter).
HACK_VM_ENGINE=native cargo test --locked -p hack-vm -p jack -p jack-compiler "$@"
