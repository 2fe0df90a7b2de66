#!/usr/bin/env bash
# Wrapper for `git bisect run`: build the harness at the commit under test,
# then run `harness check ARGS...` and pass its verdict on.
#   0   good (the comparison holds)
#   1   bad (it fails)
#   125 skip: the commit does not build, or check cannot decide (an
#       implementation is unavailable, bad input, or a harness too old to
#       have `check`)
# Example (see README, "Bisecting a numeric regression"):
#   git bisect start BAD GOOD
#   git bisect run scripts/bisect-check.sh --no-divergence ref-f316 jack --level ops
set -uo pipefail
cd "$(git rev-parse --show-toplevel)" || exit 125

if ! build_log=$(cargo build --quiet -p harness 2>&1); then
  printf '%s\n' "$build_log" | tail -n 20 >&2
  echo "bisect-check: the harness does not build at $(git rev-parse --short HEAD); skipping" >&2
  exit 125
fi

"${CARGO_TARGET_DIR:-target}/debug/harness" check "$@"
status=$?
case "$status" in
  0 | 1 | 125) exit "$status" ;;
  *)
    echo "bisect-check: harness check exited $status; treating the commit as undecidable" >&2
    exit 125
    ;;
esac
