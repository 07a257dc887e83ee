#!/usr/bin/env bash
# The weighted sphere at rest (H1): `hapticctrl-demo --gravity` (the 0.5 kg sphere under
# gravity, coupled to the handle) on a 1 ms core, nobody touching, for 10 minutes; the core's
# per-cycle log (hapticctrl-hmi play of a zero wrench) and the demo's per-step log go to
# OUT_DIR/raw/gravity/. bench/gravity_report.py turns them into gravity.md and gravity.json.
# The core runs in benchmark mode: on this VM a 1 ms core fails safe on a whole-VM stall every
# few seconds, which no 10-minute run survives; the stalls ridden through are counted.
#
# usage: bench/gravity_rest.sh OUT_DIR BUILD_DIR [--smoke]   (--smoke: 20 s instead of 600)
set -euo pipefail
OUT=$1 BUILD=$2
SECONDS_AT_REST=600
if [[ ${3:-} == --smoke ]]; then SECONDS_AT_REST=20; fi
RAW=$OUT/raw/gravity
rm -rf "$RAW"
mkdir -p "$RAW"
printf '0 0 0 0 0 0 0\n%s 0 0 0 0 0 0\n' "$SECONDS_AT_REST" >"$RAW/zero.seq"

source "$(dirname "$0")/processes.sh"

inst="benchgrav$$"
start_core_and_bridge "$inst" "$RAW"
port=$(port_of "$RAW/udp.out")
# The demo starts with the hmi's log: its first second (the sphere dropping onto the handle and
# the coupling ramping in) is in the record.
"$BUILD/hmi/hapticctrl-hmi" --instance "$inst" play "$RAW/zero.seq" --log "$RAW/cycles.csv" \
  >"$RAW/hmi.out" 2>&1 &
player=$!
"$BUILD/demo/hapticctrl-demo" --server "127.0.0.1:$port" --headless --no-lcm --json \
  --gravity --no-reconnect --duration $((SECONDS_AT_REST + 5)) --log "$RAW/demo.csv" \
  >"$RAW/demo.json" 2>"$RAW/demo.err" &
PIDS+=($!)
wait "$player" || true
"$BUILD/hmi/hapticctrl-hmi" --instance "$inst" status --json >"$RAW/status.json" 2>&1 || true
stop_all
