#!/usr/bin/env bash
# A newcomer's first `scripts/run.sh`, without a terminal (H6): a line for each step within 10 s
# of the start (packages, build with the build tool's own progress, the timing probe and the
# period it chose, each process started), the controller at that period, and the scenario's
# outcome line. With HAPTICCTRL_FIRST_RUN_CLEAN=1 it builds into a new, empty build directory
# as a fresh clone does (about 2 minutes on 2 vCPUs); CI runs it on the tree's build/ (the same
# steps, the build then has nothing to do) to keep within its time budget.
# usage: run_first_run_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=first_run
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
RUN_DIR=$SOURCE/build/run
if [[ ${HAPTICCTRL_FIRST_RUN_CLEAN:-0} == 1 ]]; then
  export HAPTICCTRL_BUILD_DIR="$OUT/build"
  RUN_DIR=$HAPTICCTRL_BUILD_DIR/run
fi

# Each line with the seconds since the start.
attempt() {
  local start=$EPOCHREALTIME status=0
  { "$SOURCE/scripts/run.sh" </dev/null 2>&1 || echo "exit status $?"; } |
    while IFS= read -r line; do
      awk -v now="$EPOCHREALTIME" -v start="$start" -v line="$line" \
        'BEGIN { printf "%6.1f %s\n", now - start, line }'
    done >"$OUT/log"
  grep -q "^ *[0-9.]* exit status" "$OUT/log" && status=$(sed -n 's/.* exit status //p' "$OUT/log")
  return "$status"
}
# A fail-safe on a stall of this VM longer than the probe saw is the machine's (H6 asks for 9 of
# 10 runs without one, docs in the README): an attempt whose every fail-safe was a measured stall
# of the machine is tried again, up to 3 attempts; any other failure fails the test.
for try in 1 2 3; do
  status=0
  attempt || status=$?
  machine_spoiled_attempt "$try" "$status" "$OUT/log" || break
done
[[ $status -eq 0 ]] || fail "run.sh exited $status"
cat "$OUT/log"

first=$(head -n 1 "$OUT/log" | awk '{print $1}')
awk -v t="$first" 'BEGIN { exit !(t <= 10) }' || fail "the first line came after $first s"
previous=0
for step in "run: checking the Debian packages" "run: building the controller" \
  "run: timing probe: a SCHED_" "run: starting the controller (instance" \
  "run: starting the UDP bridge" "outcome: contact force"; do
  at=$(grep -n -m1 -- "$step" "$OUT/log" | cut -d: -f1 || true)
  [[ -n $at ]] || fail "no line '$step'"
  ((at > previous)) || fail "'$step' out of order"
  previous=$at
done
chosen=$(sed -n 's/.*the controller runs at \([0-9]*\) ms.*/\1/p' "$OUT/log" | head -n 1)
[[ -n $chosen ]] || fail "the probe did not say which period it chose"
# After a fail-safe on a stall, run.sh starts again at a longer period (J5): the last one counts.
again=$(sed -n 's/.*starting again at \([0-9]*\) ms.*/\1/p' "$OUT/log" | tail -n 1)
chosen=${again:-$chosen}
grep -q "period $chosen ms" "$OUT/log" || fail "the controller was not started at $chosen ms"
grep -q "\"period_ns\":$((chosen * 1000000))" "$RUN_DIR/core.json" ||
  fail "the controller did not run at $chosen ms: $(cat "$RUN_DIR/core.json")"
[[ -s $RUN_DIR/probe.hist && -s $RUN_DIR/probe.txt ]] || fail "the probe's figures are not in $RUN_DIR"
echo "first_run_test: progress from ${first} s, period $chosen ms, outcome printed"
