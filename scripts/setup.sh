#!/usr/bin/env bash
# Install the system packages the harness needs on a fresh Debian machine:
# the Vulkan loader and Mesa's lavapipe (the GPU leg on a machine without a
# GPU) and Chromium (the HTML report test). Idempotent and quick when
# everything is already there. Needs root (or sudo) only when installing.
set -euo pipefail

need=()
[ -e /usr/lib/x86_64-linux-gnu/libvulkan.so.1 ] || [ -n "$(ldconfig -p 2>/dev/null | grep libvulkan.so.1)" ] || need+=(libvulkan1)
ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1 || need+=(mesa-vulkan-drivers)
command -v chromium >/dev/null 2>&1 || need+=(chromium)

if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
