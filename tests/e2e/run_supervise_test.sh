#!/usr/bin/env bash
# `scripts/run.sh --supervise` as an unattended demo runs it, without a terminal: the controller
# is stalled for 60 ms (SIGSTOP, as a hypervisor does) and fails safe; the supervisor must say
# why, start a new controller (powered off), and the demo must reconnect to it by itself (H5:
# run.sh used to hide the fail-safe, and the demo exited when its core went away). SIGTERM then
# stops everything, leaving no process and no socket.
# usage: run_supervise_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_supervise
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
RUN=
stop_run() {  # SIGTERM, then at most 30 s for run.sh to stop everything; its exit status
  kill -TERM "$RUN" 2>/dev/null || true
  for _ in $(seq 300); do
    kill -0 "$RUN" 2>/dev/null || break
    sleep 0.1
  done
  kill -KILL "$RUN" 2>/dev/null || true
  local status=0
  wait "$RUN" || status=$?
  RUN=
  return "$status"
}
cleanup() {
  if [[ -n $RUN ]]; then stop_run || true; fi
  rm -rf "$OUT"
}
trap cleanup EXIT
RUN_DIR=$SOURCE/build/run
until_true() {  # seconds command...: polls every 0.1 s
  local tries=$(($1 * 10))
  shift
  for _ in $(seq "$tries"); do
    "$@" && return 0
    sleep 0.1
  done
  return 1
}
said() { grep -q -- "$1" "$OUT/log"; }
status_ok() { "$BUILD/hmi/hapticctrl-hmi" --instance "$HAPTICCTRL_INSTANCE" status >/dev/null 2>&1; }

# 4 ms: at 1 ms this VM's own stalls fail the core safe every few seconds (docs/benchmark.md),
# which the supervisor would handle the same way, but the test is about our stall.
"$SOURCE/scripts/run.sh" --supervise --period-us 4000 </dev/null >"$OUT/log" 2>&1 &
RUN=$!
until_true 120 said "supervising the controller" || fail "run.sh did not start supervising"
stalled=0
for _ in 1 2 3; do  # the machine may fail a core safe by itself meanwhile: the supervisor's next
  first=$(cat "$RUN_DIR/core.pid")
  if kill -STOP "$first" 2>/dev/null; then
    stalled=1
    break
  fi
  sleep 1
done
[[ $stalled -eq 1 ]] || fail "no controller to stall"
sleep 0.06
kill -CONT "$first"
until_true 20 said "supervisor: starting controller #2" || fail "no new controller after the stall"
said "run: the controller FAILED SAFE: after cycle [0-9]*: 5 consecutive deadline misses" ||
  fail "the fail-safe's reason is not printed"
until_true 20 status_ok || fail "the new controller does not answer"
[[ $(cat "$RUN_DIR/core.pid") != "$first" ]] || fail "core.pid still names the stalled core"
until_true 20 grep -q "reconnected" "$RUN_DIR/demo.log" ||
  fail "the demo did not reconnect; its log: $(tail -n 20 "$RUN_DIR/demo.log")"
# J8: a controller restarted after a fault is powered on by the operator, never by the demo.
until_true 10 grep -q "waiting for the operator to power the arm on" "$RUN_DIR/demo.log" ||
  fail "the demo did not say it waits for the operator; its log: $(tail -n 20 "$RUN_DIR/demo.log")"
"$BUILD/hmi/hapticctrl-hmi" --instance "$HAPTICCTRL_INSTANCE" status --json |
  grep -q '"powered":false' || fail "the restarted controller was powered on by a client"
"$BUILD/hmi/hapticctrl-hmi" --instance "$HAPTICCTRL_INSTANCE" power-on >/dev/null ||
  fail "the operator's power-on was refused"
status=0
stop_run || status=$?
[[ $status -eq 130 ]] || fail "expected exit 130 (stopped by a signal), got $status"
if pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null; then
  fail "processes were left running"
fi
left=$(find "$HAPTICCTRL_RUNTIME_DIR" -mindepth 1 ! -name "hapticctrl-blackbox-$HAPTICCTRL_INSTANCE.*.csv")
[[ -z $left ]] || fail "the instance's socket or lock was left behind: $left"
echo "run_supervise_test: the supervisor restarted the controller and the demo reconnected"
