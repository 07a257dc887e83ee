#!/usr/bin/env bash
# The coupling benchmark (H1): the demo's sphere (0.5 kg, a free body) coupled to the arm through
# hapticctrl-netem, for each one-way delay and loss rate, with a scripted operator played by
# hapticctrl-hmi in four phases, each logged per core cycle:
#   contact  pushes the handle, and the sphere, onto the fixed sphere (+x) with 2 N then 4 N:
#            the penetration and the stiffness rendered, against F/K_series;
#   blackout a hand (300 N/m, 5 N.s/m) holds the handle and presses 2 N onto the fixed sphere
#            while the relay drops everything for 0.3 s (SIGUSR1): the fade, the re-coupling
#            and the handle's speed after the link returns;
#   steps    the hand holds the handle while the operator pushes 3 N along y and releases:
#            the handle's speed after settling;
#   hand     the hand grips the handle and wanders at random (2 cm per axis, 0.2-2 Hz): the
#            energy the coupling port puts out.
# Per case also the measured link and loop (hmi status). The demo reports no contacts
# (--no-contacts): this is the coupling alone, H1's case; the contacts the demo reports are
# rendered in the servo cycle (J2), measured by bench/local_contact.sh. The core runs in benchmark mode: this
# VM stalls the whole machine for 5-50 ms every few seconds (../shared/PITFALLS.md), which fails
# a 1 ms core safe long before a case's ~90 s are over; the simulated arm pauses through a stall
# and the core counts it as a would-be fail-safe, reported per case.
# bench/coupling_report.py turns them into coupling.md, coupling.json and coupling.png beside
# the main report.
#
# usage: bench/coupling.sh OUT_DIR BUILD_DIR [--smoke] [--case DELAY_MS:LOSS ...]
#   --smoke  one case (10 ms with 10 % loss), 8 s of hand motion instead of 60
#   --case   only these cases (repeatable), e.g. --case 20:0 --case 50:0.1
set -euo pipefail
OUT=$1 BUILD=$2
shift 2
RAW=$OUT/raw/coupling
mkdir -p "$RAW"
CASES=()
for delay in 0 1 2 5 10 20 50; do
  for loss in 0 0.1; do CASES+=("$delay:$loss"); done
done
HAND_S=60
source "$(dirname "$0")/processes.sh"
cases_from_arguments bench/coupling.sh "10:0.1" "$@"

# Contact: 2 N along +x from 0.5 s, 4 N from 3.5 s, released at 6.5 s; ends at 8 s.
sequence "$RAW/contact.seq" "0 0 0 0 0 0 0" "0.5 0 0 0 0 0 0" "0.501 2 0 0 0 0 0" \
  "3.5 2 0 0 0 0 0" "3.501 4 0 0 0 0 0" "6.5 4 0 0 0 0 0" "6.501 0 0 0 0 0 0" "8 0 0 0 0 0 0"
# Steps (the hand holding): nothing for 1.5 s, +3 N along y for 2 s, release, -3 N for 2 s,
# release; ends at 9.5 s.
sequence "$RAW/steps.seq" "0 0 0 0 0 0 0" "1.5 0 0 0 0 0 0" "1.501 0 3 0 0 0 0" \
  "3.5 0 3 0 0 0 0" "3.501 0 0 0 0 0 0" "5.5 0 0 0 0 0 0" "5.501 0 -3 0 0 0 0" \
  "7.5 0 -3 0 0 0 0" "7.501 0 0 0 0 0 0" "9.5 0 0 0 0 0 0"
# Blackout: 2 N along +x from 0.3 s to the end at 2.5 s (the link is cut from 1.2 to 1.5 s).
sequence "$RAW/press.seq" "0 0 0 0 0 0 0" "0.3 0 0 0 0 0 0" "0.301 2 0 0 0 0 0" \
  "2.5 2 0 0 0 0 0"
# Hand: no wrench of its own.
sequence "$RAW/hand.seq" "0 0 0 0 0 0 0" "$HAND_S 0 0 0 0 0 0"

case_run() {  # name delay_ms loss jitter_ms
  local name=$1 delay=$2 loss=$3 jitter=$4 dir=$RAW/$1
  rm -rf "$dir"
  mkdir -p "$dir"
  local inst="benchcpl$$"
  start_core_and_bridge "$inst" "$dir"
  start_relay "$dir" "$delay" "$loss" "$jitter"
  "$BUILD/demo/hapticctrl-demo" --server "127.0.0.1:$RELAY_PORT" --headless --no-lcm \
    --contact-stiffness 2000 --no-contacts --json --no-reconnect --log "$dir/demo.csv" \
    >"$dir/demo.json" 2>"$dir/demo.err" &
  PIDS+=($!)
  wait_for_ready "$dir/demo.err"
  sleep 0.3  # the demo powers on and couples
  local hmi=("$BUILD/hmi/hapticctrl-hmi" --instance "$inst")
  "${hmi[@]}" play "$RAW/contact.seq" --log "$dir/contact.csv" >"$dir/hmi.out" 2>&1 || true
  "${hmi[@]}" status --json >"$dir/status_contact.json" 2>&1 || true
  "${hmi[@]}" play "$RAW/press.seq" --log "$dir/blackout.csv" --hand 300,5 \
    >>"$dir/hmi.out" 2>&1 &
  local player=$!
  sleep 1.2
  kill -USR1 "$RELAY_PID"  # blackout on
  sleep 0.3
  kill -USR1 "$RELAY_PID"  # and off
  wait "$player" || true
  "${hmi[@]}" play "$RAW/steps.seq" --log "$dir/steps.csv" --hand 300,5 >>"$dir/hmi.out" 2>&1 ||
    true
  "${hmi[@]}" play "$RAW/hand.seq" --log "$dir/hand.csv" --hand 300,5 --wander 0.02 --seed 7 \
    >>"$dir/hmi.out" 2>&1 || true
  "${hmi[@]}" status --json >"$dir/status.json" 2>&1 || true
  stop_all
  echo "{\"name\":\"$name\",\"delay_ms\":$delay,\"loss\":$loss,\"jitter_ms\":$jitter}" \
    >"$dir/case.json"
}

for c in "${CASES[@]}"; do
  delay=${c%%:*} loss=${c##*:}
  jitter=0
  if [[ $delay -ge 2 ]]; then jitter=2; fi
  name="d${delay}_l${loss}"
  echo "bench: coupling, one way ${delay} ms, loss ${loss}, jitter +-${jitter} ms" >&2
  case_run "$name" "$delay" "$loss" "$jitter"
done
