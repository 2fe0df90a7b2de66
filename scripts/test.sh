#!/usr/bin/env bash
# The test command of the README: system packages, then the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/headless.sh
scripts/setup.sh
# The GPU suites compile many large kernels once each and run them on small
# inputs. On lavapipe (a machine without a GPU) LLVM's optimisation passes
# are most of that time: the kernel suite takes 166 s with a cold shader
# cache and 44 s without them. The kernels compute the same words either
# way, which these very tests check bit for bit against the reference. A
# value the caller set is kept.
export GALLIVM_PERF="${GALLIVM_PERF:-nopt}"
cargo test --workspace --locked "$@"

# The emulator's suites again on the compiled engine from the first step
# (HACK_VM_ENGINE picks the default engine of every Machine; the first run
# used the default, auto, whose short runs stay on the interpreter), and
# the harness's suites that run Jack programs (the CLI's child processes
# inherit the engine). The test binaries are the ones the first run built:
# cargo is asked for their paths with the same package selection, so
# nothing is built again (a narrower selection would resolve features
# differently and rebuild much of the workspace).
# An entry is "PACKAGE BINARY", then, after a "|", the test filters that
# pick its share of a binary (the emulator's and the command line's
# integration tests are one binary each, a module per file; `check::` would
# also match `gpu_check::`); a binary runs under the first entry it
# matches. Not the emulator's proptests: they give every machine its engine
# themselves and run each case on both, so a second pass would only draw
# more cases at the price of the first (70 s).
native=(
    "hack-vm integration|--skip proptests::" "hack-vm *" "jack *" "jack-compiler *"
    "harness lib" "harness jack" "harness selftest"
    "harness-cli integration|bindings:: check:: cli:: containment:: hardening:: --skip gpu_check::"
)
binaries=$(cargo test --workspace --locked --no-run --message-format=json "$@" 2>/dev/null |
    python3 -c '
import json, os, sys
for line in sys.stdin:
    m = json.loads(line)
    exe = m.get("executable")
    if m.get("reason") != "compiler-artifact" or not exe or not m.get("profile", {}).get("test"):
        continue
    kind = m["target"]["kind"][0]
    if kind not in ("lib", "test"):
        continue
    name = m["target"]["name"] if kind == "test" else "lib"
    # path+file:///DIR#NAME@VERSION, or path+file:///DIR#VERSION when the
    # folder is named as the package.
    url, _, fragment = m["package_id"].partition("#")
    package = fragment.split("@")[0] if "@" in fragment else url.rstrip("/").rsplit("/", 1)[-1]
    print(package, name, os.path.dirname(m["manifest_path"]), exe, sep="\t")
')
declare -A found=()
while IFS=$'\t' read -r package name dir exe; do
    for wanted in "${native[@]}"; do
        pattern=${wanted%%|*}
        filters=()
        [[ "$wanted" == *"|"* ]] && read -ra filters <<<"${wanted#*|}"
        # shellcheck disable=SC2053  # the pattern's * is meant
        if [[ "$package $name" == $pattern ]]; then
            echo "     Running $exe ${filters[*]} (HACK_VM_ENGINE=native)"
            (cd "$dir" && HACK_VM_ENGINE=native "$exe" "${filters[@]}")
            found[$wanted]=1
            break
        fi
    done
done <<<"$binaries"
# Every suite named above must have been found and run.
for wanted in "${native[@]}"; do
    if [ -z "${found[$wanted]:-}" ]; then
        echo "test.sh: no test binary for \"$wanted\" on the compiled engine" >&2
        exit 1
    fi
done
