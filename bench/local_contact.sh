#!/usr/bin/env bash
# Local contact models (J2): the demo reports its obstacle's surface with its object state and
# the core renders it on the handle in the servo cycle. Per one-way delay and loss through
# hapticctrl-netem, three runs of the demo:
#   jump    a 2000 N/m wall (2 N.s/m) with the sphere resting on it, pushed 5 N by the operator
#           (hapticctrl-hmi, logged per core cycle); at 4.5 s of the demo's time its script
#           moves the wall 5 mm into the handle: the largest force step, the peak speed, the
#           port's energy (its own run: the depth held back stays until the hand moves);
#   wall    the same wall (mu 0.3), in phases:
#     press     rest, 5 N, 10 N: the stiffness felt (the 5 N between the plateaus over the
#               handle's travel) and the penetration at 5 and 10 N from the rest;
#     friction  10 N into it, 2 N along it (sticks), 3.3 N (slides): mu rendered;
#     blackout  5 N into it while the relay drops everything for 0.5 s: the force held, the
#               largest step, the speed after the link returns;
#     hand      a spring-damper hand (300 N/m, 5 N.s/m) pressing 3 N and wandering (2 cm per
#               axis, 0.2-2 Hz) for 60 s: the energy the port to the hand put out, the cycles at
#               the saturation;
#   sphere  the fixed sphere (2000 N/m), pressed as above: the stiffness felt;
#   soft    the same without contact reports (--no-contacts): the coupling alone, today's
#           baseline in the same run.
# The core runs in benchmark mode (this VM stalls every few seconds): the stalls it rode
# through are counted per case. bench/local_contact_report.py turns OUT_DIR/raw/local/ into
# local.md and local.json.
#
# usage: bench/local_contact.sh OUT_DIR BUILD_DIR [--smoke] [--case DELAY_MS:LOSS ...]
#   --smoke  one case (100 ms with 10 % loss), 8 s of hand motion instead of 60
#   --case   only these cases (repeatable), e.g. --case 20:0.1
set -euo pipefail
OUT=$1 BUILD=$2
shift 2
RAW=$OUT/raw/local
mkdir -p "$RAW"
CASES=()
for delay in 0 1 2 5 10 20 50 100; do
  for loss in 0 0.1; do CASES+=("$delay:$loss"); done
done
HAND_S=60
source "$(dirname "$0")/processes.sh"
cases_from_arguments bench/local_contact.sh "100:0.1" "$@"

sequence "$RAW/jump.seq" "0 5 0 0 0 0 0" "6 5 0 0 0 0 0"
echo "4.5 obstacle -0.005 0 0" >"$RAW/jump.script"
# Press: nothing for 1 s, 5 N from 1 s, 10 N from 3.5 s, released at 6 s; ends at 6.5 s.
sequence "$RAW/press.seq" "0 0 0 0 0 0 0" "1 0 0 0 0 0 0" "1.001 5 0 0 0 0 0" \
  "3.5 5 0 0 0 0 0" "3.501 10 0 0 0 0 0" "6 10 0 0 0 0 0" "6.001 0 0 0 0 0 0" "6.5 0 0 0 0 0 0"
# Friction (mu 0.3): 10 N into it, 2 N along it from 1 s, 3.3 N from 2.5 s, released at 2.85 s.
sequence "$RAW/friction.seq" "0 10 0 0 0 0 0" "1 10 0 0 0 0 0" "1.001 10 2 0 0 0 0" \
  "2.5 10 2 0 0 0 0" "2.501 10 3.3 0 0 0 0" "2.85 10 3.3 0 0 0 0" "2.851 0 0 0 0 0 0" \
  "3.2 0 0 0 0 0 0"
# Blackout: 5 N into it for 3 s, the link cut from about 1.2 s to 1.7 s.
sequence "$RAW/blackout.seq" "0 5 0 0 0 0 0" "3 5 0 0 0 0 0"
sequence "$RAW/hand.seq" "0 3 0 0 0 0 0" "$HAND_S 3 0 0 0 0 0"

start_demo() {  # dir, then the demo's scene options: through the relay that start_relay started
  local dir=$1
  shift
  "$BUILD/demo/hapticctrl-demo" --server "127.0.0.1:$RELAY_PORT" --headless --no-lcm --json \
    --no-reconnect --toward x --gap 0 --contact-stiffness 2000 "$@" >"$dir/demo.json" \
    2>"$dir/demo.err" &
  PIDS+=($!)
  wait_for_ready "$dir/demo.err"
  sleep 1  # the demo powers on and couples
}

stack_run() {  # dir delay loss jitter, then the demo's options: one core, bridge, relay, demo
  local dir=$1 delay=$2 loss=$3 jitter=$4
  shift 4
  mkdir -p "$dir"
  start_core_and_bridge "$INST" "$dir"
  start_relay "$dir" "$delay" "$loss" "$jitter"
  start_demo "$dir" "$@"
}

wall_run() {  # dir delay loss jitter
  local dir=$1
  local hmi=("$BUILD/hmi/hapticctrl-hmi" --instance "$INST")
  stack_run "$@" --obstacle wall --contact-damping 2 --friction 0.3
  "${hmi[@]}" play "$RAW/press.seq" --log "$dir/press.csv" >"$dir/hmi.out" 2>&1 || true
  "${hmi[@]}" play "$RAW/friction.seq" --log "$dir/friction.csv" >>"$dir/hmi.out" 2>&1 || true
  "${hmi[@]}" play "$RAW/blackout.seq" --log "$dir/blackout.csv" >>"$dir/hmi.out" 2>&1 &
  local player=$!
  sleep 1.2
  kill -USR1 "$RELAY_PID"  # blackout on
  sleep 0.5
  kill -USR1 "$RELAY_PID"  # and off
  wait "$player" || true
  "${hmi[@]}" force 3 0 0 0 0 0 >>"$dir/hmi.out" 2>&1 || true
  sleep 1
  "${hmi[@]}" play "$RAW/hand.seq" --log "$dir/hand.csv" --hand 300,5 --wander 0.02 --seed 7 \
    >>"$dir/hmi.out" 2>&1 || true
  "${hmi[@]}" status --json >"$dir/status.json" 2>&1 || true
  stop_all
}

one_phase_run() {  # phase dir delay loss jitter, then the demo's options: one phase alone
  local phase=$1 dir=$2
  shift
  local hmi=("$BUILD/hmi/hapticctrl-hmi" --instance "$INST")
  stack_run "$@"
  "${hmi[@]}" play "$RAW/$phase.seq" --log "$dir/$phase.csv" >"$dir/hmi.out" 2>&1 || true
  "${hmi[@]}" status --json >"$dir/status.json" 2>&1 || true
  stop_all
}

INST="benchlocal$$"
for c in "${CASES[@]}"; do
  delay=${c%%:*} loss=${c##*:}
  jitter=0
  if [[ $delay -ge 2 ]]; then jitter=2; fi
  name="d${delay}_l${loss}"
  dir=$RAW/$name
  rm -rf "$dir"
  echo "bench: local contact models, one way ${delay} ms, loss ${loss}, jitter +-${jitter} ms" >&2
  one_phase_run jump "$dir/jump" "$delay" "$loss" "$jitter" --obstacle wall --contact-damping 2 \
    --script "$RAW/jump.script"
  wall_run "$dir/wall" "$delay" "$loss" "$jitter"
  one_phase_run press "$dir/sphere" "$delay" "$loss" "$jitter"
  one_phase_run press "$dir/soft" "$delay" "$loss" "$jitter" --no-contacts
  echo "{\"name\":\"$name\",\"delay_ms\":$delay,\"loss\":$loss,\"jitter_ms\":$jitter,\
\"hand_s\":$HAND_S}" >"$dir/case.json"
done
