#!/usr/bin/env bash
# The coupling benchmark (H1): the demo's sphere (0.5 kg, a free body) coupled to the arm through
# hapticctrl-netem, for each one-way delay and loss rate, with a scripted operator (force steps
# of 3 N along y, played by hapticctrl-hmi) and a 0.3 s blackout. Per case: the core's per-cycle
# log (hmi play) and the demo's per-step log, the measured link and loop (hmi status), a retry
# count when the 1 ms core failed safe on a VM stall. bench/coupling_report.py turns them into
# coupling.md, coupling.json and coupling.png beside the main report.
#
# usage: bench/coupling.sh OUT_DIR BUILD_DIR [--smoke]
set -euo pipefail
OUT=$1 BUILD=$2
SMOKE=${3:-}
RAW=$OUT/raw/coupling
mkdir -p "$RAW"
DELAYS=(0 1 2 5 10 20 50)
LOSSES=(0 0.1)
ATTEMPTS=5
if [[ $SMOKE == --smoke ]]; then
  DELAYS=(1 10)
  LOSSES=(0.1)
  ATTEMPTS=2  # the smoke run checks the pipeline; a case lost to VM stalls is reported as such
fi

# The operator: nothing for 1.5 s, +3 N along y for 2 s, release,
# -3 N for 2 s, release; the sequence ends at 11 s. The relay blacks out at 10.5 s for 0.3 s
# (counted from its own start, about 1 s before the sequence).
SEQ=$RAW/steps.seq
cat >"$SEQ" <<'SEQUENCE'
# t fx fy fz tx ty tz
0 0 0 0 0 0 0
1.5 0 0 0 0 0 0
1.501 0 3 0 0 0 0
3.5 0 3 0 0 0 0
3.501 0 0 0 0 0 0
5.5 0 0 0 0 0 0
5.501 0 -3 0 0 0 0
7.5 0 -3 0 0 0 0
7.501 0 0 0 0 0 0
11 0 0 0 0 0 0
SEQUENCE

PIDS=()
stop_all() {
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  wait "${PIDS[@]}" 2>/dev/null || true
  PIDS=()
}
trap stop_all EXIT

port_of() {  # file: the port a program printed after "listening on 127.0.0.1:"
  for _ in $(seq 1 200); do
    local p
    p=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$1")
    if [[ -n $p ]]; then echo "$p"; return 0; fi
    sleep 0.05
  done
  return 1
}

case_run() {  # name delay_ms loss jitter_ms
  local name=$1 delay=$2 loss=$3 jitter=$4 dir=$RAW/$1 attempt lost=0
  for attempt in $(seq 1 $ATTEMPTS); do
    rm -rf "$dir"
    mkdir -p "$dir"
    local inst="benchcpl$$"
    "$BUILD/rt_core/hapticctrl-core" --instance "$inst" --rt warn --priority 80 \
      --blackbox-dir "$dir" 2>"$dir/core.err" &
    PIDS+=($!)
    "$BUILD/bridges/udp/hapticctrl-udp" --instance "$inst" --port 0 >"$dir/udp.out" \
      2>"$dir/udp.err" &
    PIDS+=($!)
    local port relay
    port=$(port_of "$dir/udp.out")
    "$BUILD/bench/netem/hapticctrl-netem" --to "127.0.0.1:$port" --delay-ms "$delay" \
      --loss "$loss" --jitter-ms "$jitter" --blackout 10.5:0.3 --seed 7 --json \
      >"$dir/netem.out" 2>"$dir/netem.err" &
    PIDS+=($!)
    relay=$(port_of "$dir/netem.out")
    "$BUILD/client/demo/hapticctrl-demo" --server "127.0.0.1:$relay" --headless --no-lcm \
      --json --no-reconnect --log "$dir/demo.csv" >"$dir/demo.json" 2>"$dir/demo.err" &
    PIDS+=($!)
    for _ in $(seq 1 200); do
      grep -q "ready:" "$dir/demo.err" 2>/dev/null && break
      sleep 0.05
    done
    sleep 0.3  # the demo powers on and couples
    "$BUILD/hmi/hapticctrl-hmi" --instance "$inst" play "$SEQ" --log "$dir/cycles.csv" \
      >"$dir/hmi.out" 2>&1 || true
    "$BUILD/hmi/hapticctrl-hmi" --instance "$inst" status --json >"$dir/status.json" 2>&1 || true
    stop_all
    if ! grep -q "FAIL-SAFE" "$dir/core.err"; then
      break
    fi
    lost=$((lost + 1))
    echo "bench: coupling $name: the core failed safe (VM stall), attempt $attempt" >&2
  done
  echo "{\"name\":\"$name\",\"delay_ms\":$delay,\"loss\":$loss,\"jitter_ms\":$jitter,\"attempts_lost\":$lost}" \
    >"$dir/case.json"
}

for delay in "${DELAYS[@]}"; do
  for loss in "${LOSSES[@]}"; do
    jitter=0
    if [[ $delay -ge 2 ]]; then jitter=2; fi
    name="d${delay}_l${loss}"
    echo "bench: coupling, one way ${delay} ms, loss ${loss}, jitter +-${jitter} ms" >&2
    case_run "$name" "$delay" "$loss" "$jitter"
  done
done
