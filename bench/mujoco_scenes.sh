#!/usr/bin/env bash
# hapticctrl-mujoco on every shipped scene (J3): does the engine keep real time on this machine,
# and what does a step cost? Per scene, a run coupled to a 1 ms core (benchmark mode) through the
# UDP bridge, idle and then beside stress-ng --cpu on every CPU (a user's busy laptop); the
# operator pushes the held body 3 N down from the second second on (a contact for every scene).
# The summaries go to OUT_DIR/raw/mujoco/; bench/mujoco_report.py writes mujoco.md and
# mujoco.json: steps per second against the model's own rate (the baseline: what real time is),
# steps dropped after stalls, CPU time per step (mean, largest).
#
# usage: bench/mujoco_scenes.sh OUT_DIR BUILD_DIR [--smoke]   (--smoke: 3 s runs, no load)
set -euo pipefail
OUT=$1 BUILD=$2
RUN_S=20
LOADS=(idle load)
if [[ ${3:-} == --smoke ]]; then RUN_S=3 LOADS=(idle); fi
RAW=$OUT/raw/mujoco
rm -rf "$RAW"
mkdir -p "$RAW"

source "$(dirname "$0")/processes.sh"

for load in "${LOADS[@]}"; do
  for scene in mujoco/scenes/*.xml; do
    name=$(basename "$scene" .xml)
    dir=$RAW/$name.$load
    mkdir -p "$dir"
    inst="benchmj$$"
    start_core_and_bridge "$inst" "$dir"
    port=$(port_of "$dir/udp.out")
    if [[ $load == load ]]; then
      stress-ng --cpu "$(nproc)" --timeout "$((RUN_S + 5))s" >/dev/null 2>&1 &
      PIDS+=($!)
    fi
    "$BUILD/mujoco/hapticctrl-mujoco" --model "$scene" --server "127.0.0.1:$port" --headless \
      --json --duration "$RUN_S" >"$dir/summary.json" 2>"$dir/mujoco.err" &
    client=$!
    wait_for_ready "$dir/mujoco.err"
    sleep 1
    "$BUILD/hmi/hapticctrl-hmi" --instance "$inst" force 0 0 -3 0 0 0 >/dev/null 2>&1 || true
    wait "$client" || echo "bench: hapticctrl-mujoco on $name ($load) ended badly" >&2
    "$BUILD/hmi/hapticctrl-hmi" --instance "$inst" status --json >"$dir/status.json" 2>&1 || true
    stop_all
  done
done
