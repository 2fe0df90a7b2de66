#!/usr/bin/env bash
# The GPU legs on the machine's GPU, in one short run (docs/performance.md,
# "The GPU check"): set-up, release build, the adapter wgpu chose, the three
# GPU diffs at every level (and gpu-f32 against ref-f32+fma, to name what a
# driver's contracted multiply-adds explain), the user-shader examples, the
# described scenes on both GPU legs, the speed table; a report in OUT_DIR.
#
#   scripts/gpu-check.sh [--allow-software] [--quick] OUT_DIR
#
# --allow-software (or GPU_CHECK_ALLOW_SOFTWARE=1): run on a software
#   adapter (lavapipe, llvmpipe) too; without it the check refuses one.
# --quick (or GPU_CHECK_QUICK=1): the reduced form CI runs: the GPU diffs
#   without the whole-image level and one described scene (rtdemo).
# HARNESS_BIN=PATH: use this harness binary instead of building one.
#
# OUT_DIR gets summary.md (adapter, verdicts, whole-image times), one log per
# step in logs/, the diffs' reports, the scenes' nightly report (index.html,
# report.json) and bench.json. Exit 0 when every step passed, 1 when one
# failed or diverged (the others still run), 2 on bad arguments, 3 when the
# adapter is a software one and --allow-software was not given.
set -uo pipefail
cd "$(dirname "$0")/.."

usage() {
    echo "usage: scripts/gpu-check.sh [--allow-software] [--quick] OUT_DIR" >&2
    exit 2
}
allow_software=${GPU_CHECK_ALLOW_SOFTWARE:-0}
quick=${GPU_CHECK_QUICK:-0}
out=""
for arg in "$@"; do
    case "$arg" in
        --allow-software) allow_software=1 ;;
        --quick) quick=1 ;;
        -*) usage ;;
        *) [ -z "$out" ] || usage; out=$arg ;;
    esac
done
[ -n "$out" ] || usage
mkdir -p "$out/logs" || exit 2
out=$(cd "$out" && pwd)
summary="$out/summary.md"
failed=0
started=$(date +%s)

# The summary is written as the steps go, so that a run cut short still
# says how far it got.
note() { printf '%s\n' "$*" >>"$summary"; }
: >"$summary"
note "# GPU check, $(date -u '+%Y-%m-%d %H:%M UTC')"
note ""
note "commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$( [ -n "$(git status --porcelain 2>/dev/null)" ] && echo ' (with local changes)'), $(nproc) cores$( [ "$quick" = 1 ] && echo ', quick form')"
note ""

# Run one step: `step NAME COMMAND...` logs to logs/NAME.log, records its
# time and exit status, and counts a failure. Returns the command's status.
step() {
    local name=$1
    shift
    local t0 rc
    t0=$(date +%s.%N)
    "$@" >"$out/logs/$name.log" 2>&1
    rc=$?
    local seconds
    seconds=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    if [ "$rc" -eq 0 ]; then
        echo "gpu-check: $name: ok (${seconds} s)" >&2
    else
        echo "gpu-check: $name: FAILED, exit $rc (${seconds} s; log $out/logs/$name.log)" >&2
        failed=1
    fi
    note "- \`$name\`: $( [ "$rc" -eq 0 ] && echo ok || echo "**failed (exit $rc)**"), ${seconds} s"
    return "$rc"
}

# ---- Set-up and build ----
note "## Set-up"
note ""
. scripts/headless.sh
# The set-up installs what is missing (Vulkan loader, lavapipe, Chromium for
# the report test). On a GPU machine without a network it may fail to
# install what only a GPU-less machine needs: not a failure of the check,
# whose adapter step below decides whether the GPU legs can run.
if ! step setup scripts/setup.sh; then
    failed=0
    note "  (set-up incomplete: continuing, the adapter decides)"
fi
if [ -n "${HARNESS_BIN:-}" ]; then
    bin=$HARNESS_BIN
    note "- build: skipped, HARNESS_BIN=$bin"
else
    step build cargo build --release --locked -p harness-cli || {
        note ""
        note "**FAILED**: the release build"
        exit 1
    }
    bin=target/release/harness
fi

# ---- The adapter ----
step cast "$bin" cast || true
adapter=$(sed -n 's/^gpu-f316 runs on //p' "$out/logs/cast.log" | head -n 1)
adapter_f32=$(sed -n 's/^gpu-f32 runs on //p' "$out/logs/cast.log" | head -n 1)
note ""
note "## Adapter"
note ""
if [ -z "$adapter" ] || [ -z "$adapter_f32" ]; then
    note "**no GPU adapter**: gpu-f316 or gpu-f32 did not open (see logs/cast.log)"
    grep '^gpu-' "$out/logs/cast.log" | sed 's/^/    /' >>"$summary"
    echo "gpu-check: no adapter for the GPU legs; see $out/logs/cast.log" >&2
    exit 1
fi
note "adapter: $adapter"
echo "gpu-check: adapter: $adapter" >&2
[ "$adapter" = "$adapter_f32" ] || note "gpu-f32's adapter: $adapter_f32"
case "$adapter" in
    *"[software]")
        if [ "$allow_software" != 1 ]; then
            note ""
            note "**refused**: a software adapter (pass --allow-software to run on it anyway)"
            echo "gpu-check: refusing the software adapter (--allow-software runs on it)" >&2
            exit 3
        fi
        note "(a software adapter, allowed by --allow-software: no figure here is a GPU's)"
        ;;
esac
note ""
note "## Steps"
note ""

# ---- The GPU diffs ----
if [ "$quick" = 1 ]; then
    levels=(ops sdf pixels)
    shader_level=pixels
else
    levels=(all)
    shader_level=all
fi
# `diff A B` at each level B answers: exit 0 agreement, 1 divergence, 3 not
# compared (gpu-f32 computes no Float316 operation, and a level asked for and
# not answered is not compared, so it is not asked for ops).
diff_pair() {
    local a=$1 b=$2 level
    for level in "${levels[@]}"; do
        if [ "$b" = gpu-f32 ] && [ "$level" = ops ]; then
            continue
        fi
        "$bin" diff "$a" "$b" --level "$level" --report "$out/diff-$a-$b/$level" || return $?
    done
}
for pair in "ref-f316 gpu-f316" "ref-f32 gpu-f32" "ref-f64 gpu-f32" "ref-f32+fma gpu-f32"; do
    set -- $pair
    step "diff-$1-$2" diff_pair "$1" "$2" || true
done

# ---- The user-shader examples ----
step shaders "$bin" --cast examples/shaders/harness.toml diff ref-f64 seed-shadertoy seed-wgsl \
    --level "$shader_level" || true

# ---- The described scenes on both GPU legs (the nightly's scene step) ----
if [ "$quick" = 1 ]; then
    scenes=(vectors/scenes/rtdemo.json)
else
    scenes=(vectors/scenes/*.json)
fi
scene_args=()
for s in "${scenes[@]}"; do scene_args+=(--scene "$s"); done
step scenes "$bin" nightly --steps scenes --impls gpu-f32,gpu-f316 \
    "${scene_args[@]}" --out "$out/scenes" || true

# ---- Speed ----
step bench "$bin" bench ref-f64 ref-f32 ref-f316 gpu-f32 gpu-f316 --json "$out/bench.json" || true
for leg in gpu-f32 gpu-f316; do
    if ! grep -q "^$leg " "$out/logs/bench.log"; then
        note "  **bench has no row for $leg** (see logs/bench.log)"
        failed=1
    fi
done

# ---- Verdicts ----
note ""
note "## Verdicts"
note ""
for log in "$out"/logs/diff-*.log "$out/logs/shaders.log"; do
    [ -e "$log" ] || continue
    note "### $(basename "$log" .log)"
    note ""
    note '```'
    grep -E '^level |policy|figures:|divergen|does not support|error' "$log" >>"$summary"
    note '```'
    note ""
done
note "### scenes"
note ""
note '```'
grep -E '^nightly: ' "$out/logs/scenes.log" >>"$summary"
note '```'
note ""

# ---- What contracted multiply-adds explain ----
# The largest difference in f32 ulps at a level, from a diff log.
ulps() {
    awk -v level="$2" '
        /^level / { current = $2; sub(":", "", current) }
        current == level && /figures:/ {
            if (match($0, /max [0-9.e+-]+ ulps/)) { v = substr($0, RSTART + 4, RLENGTH - 9); print v; exit }
            print "-"; exit
        }' "$1"
}
note "## gpu-f32 against ref-f32 and ref-f32+fma"
note ""
note "| level | operations it exercises | max ulps against ref-f32 | against ref-f32+fma | reading |"
note "|---|---|---:|---:|---|"
for level in sdf pixels; do
    plain=$(ulps "$out/logs/diff-ref-f32-gpu-f32.log" "$level")
    fused=$(ulps "$out/logs/diff-ref-f32+fma-gpu-f32.log" "$level")
    case $level in
        sdf) ops="the scene's distance and colour: sub, mul, add (the lengths' sums of squares), sqrt, floor" ;;
        pixels) ops="the whole pixel: the above, and the dot products, normalize's div, pow, the multiply-adds of marching, normal and light" ;;
    esac
    reading=$(awk -v p="${plain:--}" -v f="${fused:--}" 'BEGIN {
        if (p == "-" || f == "-") print "not measured";
        else if (p + 0 == 0) print "bit for bit with ref-f32: nothing contracted or approximated here";
        else if (f + 0 == 0) print "explained: the driver contracts multiply-adds (ref-f32+fma agrees bit for bit)";
        else if (f + 0 < p + 0) print "partly explained by contraction; the rest is another operation (div, sqrt or pow less accurate than IEEE, as WGSL allows)";
        else print "not explained by contraction: another operation differs (div, sqrt or pow less accurate than IEEE, as WGSL allows)";
    }')
    note "| $level | $ops | ${plain:--} | ${fused:--} | $reading |"
done
note ""

# ---- Whole-image times ----
note "## Whole-image times"
note ""
note "\`harness bench\` (set-up apart):"
note ""
note '```'
sed -n '/^implementation /,$p' "$out/logs/bench.log" >>"$summary"
note '```'
note ""
if command -v python3 >/dev/null && [ -e "$out/scenes/report.json" ]; then
    note "Described scenes (render after set-up; set-up is generating and compiling the kernels):"
    note ""
    python3 - "$out/scenes/report.json" >>"$summary" <<'EOF'
import json, sys
rows = json.load(open(sys.argv[1])).get("scenes", [])
print("| scene | implementation | set-up s | image s |")
print("|---|---|---:|---:|")
for row in rows:
    for c in row["costs"]:
        print(f"| {row['name']} | {c['implementation']} | {c['setup_s']:.2f} | {c['render_s']:.3f} |")
EOF
else
    note "Described scenes: see scenes/report.json (python3 is needed to tabulate it here)."
fi
note ""
seconds=$(($(date +%s) - started))
if [ "$failed" = 0 ]; then
    note "**passed** in ${seconds} s"
    echo "gpu-check: passed in ${seconds} s; summary $summary" >&2
else
    note "**FAILED** in ${seconds} s (a step above failed or diverged)"
    echo "gpu-check: FAILED in ${seconds} s; summary $summary" >&2
fi
exit "$failed"
