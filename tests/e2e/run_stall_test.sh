#!/usr/bin/env bash
# J5: the README's main command without a terminal, when a stall of the machine fails its
# controller safe. The stall is a SIGSTOP of 60 ms of the running core (to the core exactly what
# a VM stall is: its clock wakes 60 ms late), at the 1 ms a probe could have chosen
# (HAPTICCTRL_RUN_PERIOD_US stands for the probe's choice). scripts/run.sh must say it was a
# stall, start again at 2 ms, and reach the demo's outcome with exit 0.
# usage: run_stall_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_stall
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
# One attempt: run.sh at 1 ms, its core stopped for 60 ms once the scenario runs. Its status.
attempt() {
  rm -f "$BUILD/run/core.pid"
  local status=0 run core=
  HAPTICCTRL_RUN_PERIOD_US=1000 "$SOURCE/scripts/run.sh" </dev/null >"$OUT/log" 2>&1 &
  run=$!
  for _ in $(seq 600); do  # the build is there: the core starts within seconds (bounded: 60 s)
    [[ -s $BUILD/run/core.pid ]] && core=$(cat "$BUILD/run/core.pid")
    grep -q "scripted scenario" "$OUT/log" 2>/dev/null && break
    sleep 0.1
  done
  [[ -n $core ]] || fail "no controller started"
  # core.pid is the core's own pid (run.sh's run_core); it may have failed safe already.
  kill -STOP "$core" 2>/dev/null && sleep 0.06 && kill -CONT "$core"
  wait "$run" || status=$?
  cat "$OUT/log"
  return "$status"
}
# Our stop is a stall the core must be told; the machine's own stalls may fail the later starts
# too: such an attempt (every fail-safe a measured stall) is tried again, up to 3.
for try in 1 2 3; do
  status=0
  attempt || status=$?
  grep -q "on a stall of the machine (the clock woke" "$OUT/log" ||
    fail "the fail-safe was not told a stall of the machine (did the 60 ms stop reach the core?)"
  grep -q "^run: that was a stall of this machine, not of the controller: starting again at 2 ms (again 1 of 2)" \
    "$OUT/log" || fail "run.sh did not start again at 2 ms"
  machine_spoiled_attempt "$try" "$status" "$OUT/log" || break
done
[[ $status -eq 0 ]] || fail "expected exit 0 after starting again, got $status"
grep -q "^outcome: contact force" "$OUT/log" || fail "the demo's outcome is missing"
if pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null; then
  fail "processes were left running"
fi
echo "run_stall_test: a stall failed the 1 ms controller safe; run.sh started again at 2 ms and" \
  "reached the outcome"
