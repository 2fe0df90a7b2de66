#!/usr/bin/env bash
# Wrapper for `git bisect run`: build the harness at the commit under test,
# then run `harness check ARGS...` and pass its verdict on.
#   0   good (the comparison holds)
#   1   bad (it fails; an implementation under test panicked, hung or
#       crashed; or `harness check` itself did not finish with a verdict)
#   125 skip: only when the commit does not build, or check cannot decide
#       (an implementation is unavailable here, bad arguments; exit 2 is
#       a usage error of a harness too old to have `check`)
# Example (see README, "Bisecting a numeric regression"):
#   git bisect start BAD GOOD
#   git bisect run scripts/bisect-check.sh --no-divergence ref-f316 jack --level ops
set -uo pipefail
cd "$(git rev-parse --show-toplevel)" || exit 125

if ! build_log=$(cargo build --quiet -p harness-cli 2>&1); then
  printf '%s\n' "$build_log" | tail -n 20 >&2
  echo "bisect-check: the harness does not build at $(git rev-parse --short HEAD); skipping" >&2
  exit 125
fi

"${CARGO_TARGET_DIR:-target}/debug/harness" check "$@"
status=$?
case "$status" in
  0 | 1 | 125) exit "$status" ;;
  2)
    echo "bisect-check: harness check rejected its arguments (usage error); skipping" >&2
    exit 125
    ;;
  *)
    # A harness that panics or is killed at this commit is broken by it.
    echo "bisect-check: harness check exited $status without a verdict; the commit is bad" >&2
    exit 1
    ;;
esac
