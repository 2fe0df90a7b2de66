# Sourced by test.sh and nightly.sh. A headless machine has no
# XDG_RUNTIME_DIR, and Mesa's Vulkan driver (lavapipe) then prints
# "XDG_RUNTIME_DIR is invalid" for every device it opens: give it one.
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "$XDG_RUNTIME_DIR" ]; then
  export XDG_RUNTIME_DIR="${TMPDIR:-/tmp}/f316-harness-runtime-$(id -u)"
  mkdir -p -m 700 "$XDG_RUNTIME_DIR"
fi
