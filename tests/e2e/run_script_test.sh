#!/usr/bin/env bash
# The README's main command as a user runs it without a terminal, with 5 overruns injected into the
# core 1.2 s in (extra arguments go to the core; the period is given, so that cycle 300 is inside
# the scenario whatever the timing probe would pick): scripts/run.sh must stop everything, print the
# fail-safe's reason and exit 11 (10 + "5 consecutive deadline misses"), leaving no socket (H5: it
# used to exit 0 and leave the reason in build/run/core.log).
# usage: run_script_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_script
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
status=0
"$SOURCE/scripts/run.sh" --period-us 4000 --allow-fault-injection --inject-overrun 300:5 </dev/null \
  >"$OUT/log" 2>&1 || status=$?
cat "$OUT/log"
[[ $status -eq 11 ]] || fail "expected exit 11 (a fail-safe on consecutive misses), got $status"
grep -q "^run: the controller FAILED SAFE: after cycle [0-9]*: 5 consecutive deadline misses" \
  "$OUT/log" || fail "the fail-safe's reason is not printed"
# What stays is the record of the fault: the black box, and the marker of a controller that did
# not stop in order, so that the next one started after it waits for the operator (J8).
left=$(find "$HAPTICCTRL_RUNTIME_DIR" -mindepth 1 ! -name "hapticctrl-blackbox-$HAPTICCTRL_INSTANCE.*.csv" \
  ! -name "hapticctrl-running.$HAPTICCTRL_INSTANCE")
[[ -z $left ]] || fail "the instance's socket or lock was left behind: $left"
[[ -f $HAPTICCTRL_RUNTIME_DIR/hapticctrl-running.$HAPTICCTRL_INSTANCE ]] ||
  fail "no marker of the controller that failed safe"
grep -q "black box: $HAPTICCTRL_RUNTIME_DIR/hapticctrl-blackbox-$HAPTICCTRL_INSTANCE\.[0-9]*\.csv" \
  "$OUT/log" || fail "the black box is not in the instance's runtime directory, or not said"
if pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null; then
  fail "processes were left running"
fi
echo "run_script_test: exit $status with the reason"
