#!/usr/bin/env bash
# The test command of the README: system packages, then the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
cargo test --workspace --locked "$@"
# The emulator's suites again on the compiled engine from the first step
# (HACK_VM_ENGINE picks the default engine of every Machine; the first run
# used the default, auto, whose short runs stay on the interpreter), and
# the harness's suites that run Jack programs (the CLI's child processes
# inherit the engine).
HACK_VM_ENGINE=native cargo test --locked -p hack-vm -p jack -p jack-compiler "$@"
HACK_VM_ENGINE=native cargo test --locked -p harness --lib --test bindings --test check \
    --test cli --test containment --test hardening --test jack --test selftest "$@"
