#!/usr/bin/env bash
# The README's main command as a user runs it without a terminal, with 5 overruns injected into
# the core (extra arguments go to the core): scripts/run.sh must stop everything, print the
# fail-safe's reason and exit 11 (10 + "5 consecutive deadline misses"), leaving no socket
# (H5: it used to exit 0 and leave the reason in build/run/core.log).
# usage: run_script_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2
if [[ "$(realpath "$BUILD")" != "$(realpath "$SOURCE/build")" ]]; then
  echo "scripts/run.sh runs $SOURCE/build, not this build ($BUILD): skipped"
  exit 77
fi
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
export HAPTICCTRL_INSTANCE="runtest$$" HAPTICCTRL_RUNTIME_DIR="$OUT/run"
export HAPTICCTRL_PORT=$((20000 + $$ % 20000)) HAPTICCTRL_WEB_PORT=$((40000 + $$ % 20000))
status=0
"$SOURCE/scripts/run.sh" --allow-fault-injection --inject-overrun 1500:5 </dev/null \
  >"$OUT/log" 2>&1 || status=$?
cat "$OUT/log"
fail() { echo "run_script_test: $1" >&2; exit 1; }
[[ $status -eq 11 ]] || fail "expected exit 11 (a fail-safe on consecutive misses), got $status"
grep -q "^run: the controller FAILED SAFE: after cycle [0-9]*: 5 consecutive deadline misses" \
  "$OUT/log" || fail "the fail-safe's reason is not printed"
[[ -z "$(ls -A "$HAPTICCTRL_RUNTIME_DIR")" ]] || fail "the instance's socket or lock was left behind"
if pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null; then
  fail "processes were left running"
fi
echo "run_script_test: exit $status with the reason"
