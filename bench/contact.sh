#!/usr/bin/env bash
# The coupling in contact (J1): the demo's sphere on a stiff wall in its own physics
# (--obstacle wall, 2 N.s/m), reported to the core as a contact (protocol 1.3), through
# hapticctrl-netem, for each wall, command mode, one-way delay and loss. Per case, each phase
# logged per core cycle by hapticctrl-hmi:
#   push  10 N into the wall for 3 s: the handle's speed and the felt force from 1 s on, the
#         cycles at the saturation;
#   hand  a spring-damper hand (300 N/m, 5 N.s/m) presses 3 N into the wall and wanders at random
#         (2 cm per axis, 0.2-2 Hz): the energy the port to the hand put out;
# then, with the handle at rest, the two-port balance: the core's end (hmi status: its energy in
# and out, and the client's energy in as reported) against the client's end (the demo's summary
# when it ends). VIRTMECH walls of 3000 and 5000 N/m and an IMPEDANCE client's wall of 2000 N/m
# (the wall computed in the client, its wrench inside the two-port).
# The core runs in benchmark mode (this VM stalls every few seconds): the stalls it rode through
# are counted per case. bench/contact_report.py turns OUT_DIR/raw/contact/ into contact.md,
# contact.json and contact.png.
#
# usage: bench/contact.sh OUT_DIR BUILD_DIR [--smoke] [--case MODE:K:DELAY_MS:LOSS ...]
#   --smoke  two cases (VIRTMECH 3000 N/m at 10 ms with 10 % loss, IMPEDANCE 2000 N/m at 0 ms),
#            8 s of hand motion instead of 60
#   --case   only these cases (repeatable), e.g. --case virtmech:5000:20:0.1
set -euo pipefail
OUT=$1 BUILD=$2
shift 2
RAW=$OUT/raw/contact
mkdir -p "$RAW"
CASES=()
for delay in 0 1 2 5 10 20 50 100; do
  for loss in 0 0.1; do
    CASES+=("virtmech:3000:$delay:$loss" "virtmech:5000:$delay:$loss" "impedance:2000:$delay:$loss")
  done
done
HAND_S=60
source "$(dirname "$0")/processes.sh"
cases_from_arguments bench/contact.sh "virtmech:3000:10:0.1 impedance:2000:0:0" "$@"

# Push: 10 N along +x (into the wall) from 0 to 3 s, then released.
sequence "$RAW/push.seq" "0 10 0 0 0 0 0" "3 10 0 0 0 0 0"
# Hand: 3 N into the wall while it wanders.
sequence "$RAW/hand.seq" "0 3 0 0 0 0 0" "$HAND_S 3 0 0 0 0 0"

wait_until_still() {  # instance: the handle still for 0.2 s (at most 3 s), as the tests judge
  local hmi=("$BUILD/hmi/hapticctrl-hmi" --instance "$1")
  for _ in $(seq 1 15); do
    "${hmi[@]}" status --json 2>/dev/null |
      python3 -c 'import json,sys; s=json.load(sys.stdin); v=s.get("handle_twist",[1]*3); sys.exit(0 if sum(x*x for x in v[:3])**0.5 < 1e-3 else 1)' &&
      return 0
    sleep 0.2
  done
}

case_run() {  # name mode stiffness delay_ms loss jitter_ms
  local name=$1 mode=$2 stiffness=$3 delay=$4 loss=$5 jitter=$6 dir=$RAW/$1
  rm -rf "$dir"
  mkdir -p "$dir"
  local inst="benchcon$$" demo
  start_core_and_bridge "$inst" "$dir"
  start_relay "$dir" "$delay" "$loss" "$jitter"
  "$BUILD/demo/hapticctrl-demo" --server "127.0.0.1:$RELAY_PORT" --headless --no-lcm --json \
    --no-reconnect --obstacle wall --toward x --gap 0 --contact-stiffness "$stiffness" \
    --contact-damping 2 --command "$mode" >"$dir/demo.json" 2>"$dir/demo.err" &
  demo=$!
  PIDS+=("$demo")
  wait_for_ready "$dir/demo.err"
  sleep 1  # the demo powers on and couples
  local hmi=("$BUILD/hmi/hapticctrl-hmi" --instance "$inst")
  "${hmi[@]}" play "$RAW/push.seq" --log "$dir/push.csv" >"$dir/hmi.out" 2>&1 &
  local player=$!
  sleep 2  # the coupling's gains while pushed
  "${hmi[@]}" status --json >"$dir/status_push.json" 2>&1 || true
  wait "$player" || true
  # The hand grips the handle where it is: first 3 N bring it onto the wall and hold it there
  # (an IMPEDANCE client's handle, free, floats away from its wall once released).
  "${hmi[@]}" force 3 0 0 0 0 0 >>"$dir/hmi.out" 2>&1 || true
  sleep 1
  "${hmi[@]}" play "$RAW/hand.seq" --log "$dir/hand.csv" --hand 300,5 --wander 0.02 --seed 7 \
    >>"$dir/hmi.out" 2>&1 || true
  # At rest the two ends' totals agree: each compares its output with the other's report of a
  # loop ago (docs/control.md).
  wait_until_still "$inst"
  "${hmi[@]}" status --json >"$dir/status.json" 2>&1 || true
  kill -TERM "$demo" 2>/dev/null || true
  wait "$demo" 2>/dev/null || true
  stop_all
  echo "{\"name\":\"$name\",\"mode\":\"$mode\",\"stiffness\":$stiffness,\"delay_ms\":$delay,\
\"loss\":$loss,\"jitter_ms\":$jitter,\"hand_s\":$HAND_S}" >"$dir/case.json"
}

for c in "${CASES[@]}"; do
  IFS=: read -r mode stiffness delay loss <<<"$c"
  jitter=0
  if [[ $delay -ge 2 ]]; then jitter=2; fi
  name="${mode}_k${stiffness}_d${delay}_l${loss}"
  echo "bench: contact, $mode wall of $stiffness N/m, one way ${delay} ms, loss ${loss}" >&2
  case_run "$name" "$mode" "$stiffness" "$delay" "$loss" "$jitter"
done
