#!/usr/bin/env bash
# `scripts/run.sh` without a terminal after an earlier run left the emergency stop latched (J4):
# the controller starts with the stop latched, run.sh says so and how to reset it, does not
# reset it itself, and stops (exit 4) instead of running a demo that cannot power on; nothing of
# the run is left behind.
# usage: run_latched_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_latched
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
mkdir -m 0750 "$HAPTICCTRL_RUNTIME_DIR"
latch=$HAPTICCTRL_RUNTIME_DIR/hapticctrl-estop.$HAPTICCTRL_INSTANCE
echo "latched at 2026-12-04 10:00:00 UTC (core pid 1)" >"$latch"
chmod 0600 "$latch"

status=0
"$SOURCE/scripts/run.sh" --period-us 10000 </dev/null >"$OUT/log" 2>&1 || status=$?
[[ $status -eq 4 ]] || fail "run.sh exited $status, not 4"
grep -q "run: the emergency stop is still latched from an earlier run: the arm stays off until an operator resets it (r in the panel, or: .*hapticctrl-hmi --instance $HAPTICCTRL_INSTANCE reset)" "$OUT/log" ||
  fail "it did not say that the stop is latched and how to reset it"
grep -q "the emergency stop is still latched (latched at 2026-12-04 10:00:00 UTC (core pid 1))" \
  "$SOURCE/build/run/core.log" || fail "the core did not say what it found"
[[ -e $latch ]] || fail "the latch was removed: only an operator resets it"
! grep -q "outcome:" "$OUT/log" || fail "the scenario ran"
[[ ! -e $HAPTICCTRL_RUNTIME_DIR/$HAPTICCTRL_INSTANCE.sock ]] || fail "the controller was left running"
! pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null || fail "processes were left behind"
cat "$OUT/log"
echo "run_latched_test: run.sh stopped with exit 4 and said how to reset the latched stop"
