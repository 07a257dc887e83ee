#!/usr/bin/env bash
# scripts/run.sh tells the truth on the terminal (J8): --help answers before any build or probe;
# a second run.sh on the same build refuses at once, naming the first, and leaves its files
# alone; a bridge that cannot start (its UDP port taken) ends the run non-zero with the bridge's
# own words instead of playing the scenario unconnected.
# usage: run_truth_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_truth
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
FIRST=
cleanup() {
  if [[ -n $FIRST ]]; then
    kill -TERM "$FIRST" 2>/dev/null || true
    wait "$FIRST" 2>/dev/null || true
  fi
  [[ -n ${HOLDER:-} ]] && kill "$HOLDER" 2>/dev/null || true
  rm -rf "$OUT"
}
trap cleanup EXIT

# --help: the header, at once, nothing built or probed.
start=$EPOCHREALTIME
"$SOURCE/scripts/run.sh" --help >"$OUT/help" 2>&1 || fail "--help exited non-zero"
took=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }')
grep -q "The README's main command" "$OUT/help" || fail "--help printed: $(cat "$OUT/help")"
grep -q "Exit status:" "$OUT/help" || fail "--help leaves out the exit status"
! grep -q "run: building\|run: timing probe\|run: checking" "$OUT/help" || fail "--help built or probed"
awk -v t="$took" 'BEGIN { exit !(t < 2) }' || fail "--help took $took s"

# A UDP port already taken: the bridge's own words, exit 1, no scenario.
python3 -c "
import socket, time, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.bind(('127.0.0.1', int(sys.argv[1])))
time.sleep(120)" "$HAPTICCTRL_PORT" &
HOLDER=$!
sleep 0.3
status=0
"$SOURCE/scripts/run.sh" --period-us 10000 </dev/null >"$OUT/log" 2>&1 || status=$?
kill "$HOLDER" 2>/dev/null || true
HOLDER=
[[ $status -eq 1 ]] || fail "with its port taken run.sh exited $status, not 1"
grep -q "run: hapticctrl-udp did not start; it said:" "$OUT/log" || fail "the bridge's failure is not said"
grep -qi "address already in use" "$OUT/log" || fail "the bridge's own words are missing"
! grep -q "outcome:\|scripted scenario" "$OUT/log" || fail "the scenario ran unconnected"

# A second run.sh while one runs: refused at once, naming the first; the first's log untouched.
"$SOURCE/scripts/run.sh" --supervise --period-us 10000 </dev/null >"$OUT/first" 2>&1 &
FIRST=$!
for _ in $(seq 600); do
  grep -q "supervising the controller" "$OUT/first" && break
  sleep 0.1
done
grep -q "supervising the controller" "$OUT/first" || fail "the first run did not start: $(cat "$OUT/first")"
before=$(stat -c %s "$SOURCE/build/run/core.log")
status=0
start=$EPOCHREALTIME
HAPTICCTRL_INSTANCE=${HAPTICCTRL_INSTANCE}b "$SOURCE/scripts/run.sh" </dev/null >"$OUT/second" 2>&1 || status=$?
took=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }')
[[ $status -eq 1 ]] || fail "the second run.sh exited $status, not 1: $(cat "$OUT/second")"
grep -q "run: another scripts/run.sh is running on build/ (pid $FIRST)" "$OUT/second" ||
  fail "the second run.sh did not name the first: $(cat "$OUT/second")"
awk -v t="$took" 'BEGIN { exit !(t < 2) }' || fail "the refusal took $took s"
[[ $(stat -c %s "$SOURCE/build/run/core.log") -eq $before ]] || fail "the first run's log was touched"
kill -0 "$FIRST" || fail "the first run ended"
echo "run_truth_test: --help at once, a taken port said with exit 1, a second run refused in $took s"
