#!/usr/bin/env bash
# `scripts/run.sh --supervise` with a controller that fails safe at every start (J4: the
# supervisor restarted such a core 19 times in 15 s, forever, each leaving a black box): it must
# give up within 10 s, say why, and end the run with the fail-safe's exit code (11: consecutive
# misses), leaving no process and no socket. Each core here overruns 5 cycles 0.2 s after its
# start (--inject-overrun goes to every core the supervisor starts).
# usage: run_supervise_gives_up_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_gives_up
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
status=0
started=$SECONDS
timeout 60 "$SOURCE/scripts/run.sh" --supervise --period-us 4000 --allow-fault-injection \
  --inject-overrun 50:5 </dev/null >"$OUT/log" 2>&1 || status=$?
took=$((SECONDS - started))
cat "$OUT/log"
[[ $status -eq 11 ]] || fail "expected exit 11 (the fail-safe's), got $status"
grep -q "run: supervisor: starting controller #2 in 0.5 s (powered off, until an operator powers it on" "$OUT/log" ||
  fail "the first fail-safe was not restarted after 0.5 s"
grep -q "run: supervisor: the controller failed safe at its start twice in a row (5 consecutive deadline misses): not starting it again" \
  "$OUT/log" || fail "it did not give up with the reason"
! grep -q "starting controller #3" "$OUT/log" || fail "a third controller was started"
# The build check and the probe-free start take 1-3 s here; the two controllers about 1 s.
[[ $took -le 10 ]] || fail "it gave up after $took s (at most 10)"
# What stays is the record of the fault: the black box, and the marker of a controller that did
# not stop in order, so that the next one started after it waits for the operator (J8).
left=$(find "$HAPTICCTRL_RUNTIME_DIR" -mindepth 1 ! -name "hapticctrl-blackbox-$HAPTICCTRL_INSTANCE.*.csv" \
  ! -name "hapticctrl-running.$HAPTICCTRL_INSTANCE")
[[ -z $left ]] || fail "the instance's socket or lock was left behind: $left"
[[ -f $HAPTICCTRL_RUNTIME_DIR/hapticctrl-running.$HAPTICCTRL_INSTANCE ]] ||
  fail "no marker of the controller that failed safe"
! pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null || fail "processes were left running"
echo "run_supervise_gives_up_test: gave up after $took s with the reason, exit $status"
