#!/usr/bin/env bash
# The client link end to end: hapticctrl-core (simulated arm) + hapticctrl-udp + the client
# library, measured by hapticctrl-bench-link against a raw UDP ping-pong in the same run; idle,
# then (unless --no-load) under stress-ng CPU + memory + I/O load on every CPU.
#
# --load cpu: stress-ng --cpu on every CPU (user-space load; the seeds' "user space heavily
#             loaded"); --load full: also --vm and --io (kernel-heavy load, which stalls this
#             non-PREEMPT_RT VM for milliseconds).
# The core runs in benchmark mode, as in scripts/bench.sh: a stall that trips a miss rule is
# counted as a would-be fail-safe and said at the end, and the measurement goes on (a plain core
# failed safe before the client's first frame in CI, 2026-12-06, and the run measured nothing).
#
# usage: bench/client_link.sh [--build DIR] [--seconds N] [--period-us P] [--load cpu|full|none]
#                             [--json]
set -euo pipefail
BUILD=build SECONDS_RUN=60 PERIOD=1000 LOAD=cpu JSON=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) BUILD=$2; shift 2 ;;
    --seconds) SECONDS_RUN=$2; shift 2 ;;
    --period-us) PERIOD=$2; shift 2 ;;
    --load) LOAD=$2; shift 2 ;;
    --json) JSON=(--json); shift ;;
    *) echo "unknown option $1" >&2; exit 64 ;;
  esac
done
TMP=$(mktemp -d)
INSTANCE="linkbench$$"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$TMP"
}
trap cleanup EXIT

# Core at SCHED_FIFO 80 when allowed (warns otherwise), bridge just below it.
"$BUILD/rt_core/hapticctrl-core" --instance "$INSTANCE" --period-us "$PERIOD" --rt warn \
  --priority 80 --benchmark-mode --json --state-dir "$TMP" >"$TMP/core.json" 2>"$TMP/core.err" &
pids+=($!)
"$BUILD/bridges/udp/hapticctrl-udp" --instance "$INSTANCE" --port 0 --priority 70 \
  >"$TMP/udp.out" 2>"$TMP/udp.err" &
pids+=($!)
for _ in $(seq 1 200); do
  grep -q "listening on" "$TMP/udp.out" 2>/dev/null && break
  sleep 0.05
done
PORT=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$TMP/udp.out")
[[ -n "$PORT" ]] || { cat "$TMP/udp.err" >&2; exit 1; }

# The client too runs at SCHED_FIFO (60) when allowed, like a haptic application's loop; the
# raw UDP baseline runs in the same process, so both sides of the ratio get the same treatment.
CLIENT=("$BUILD/bench/hapticctrl-bench-link")
if chrt -f 60 true 2>/dev/null; then CLIENT=(chrt -f 60 "${CLIENT[@]}"); fi

echo "== idle"
"${CLIENT[@]}" --port "$PORT" --seconds "$SECONDS_RUN" "${JSON[@]}"
if [[ $LOAD != none ]] && command -v stress-ng >/dev/null; then
  STRESS=(--cpu "$(nproc)")
  [[ $LOAD == full ]] && STRESS+=(--vm 1 --vm-bytes 256M --io 1)
  echo "== under stress-ng ${STRESS[*]}"
  stress-ng "${STRESS[@]}" --timeout "$((SECONDS_RUN + 10))s" >/dev/null 2>&1 &
  pids+=($!)
  sleep 1
  "${CLIENT[@]}" --port "$PORT" --seconds "$SECONDS_RUN" "${JSON[@]}"
fi
if ! kill -0 "${pids[0]}" 2>/dev/null; then
  echo "note: the core stopped during the run:" >&2
  cat "$TMP/core.err" >&2
else
  kill -TERM "${pids[0]}" && wait "${pids[0]}" || true
fi
would=$(grep -o '"would_fail_safe":[0-9]*' "$TMP/core.json" | cut -d: -f2 || true)
note="core: would-be fail-safes (machine stalls that tripped a miss rule): ${would:-unknown}"
if [[ ${#JSON[@]} -gt 0 ]]; then echo "$note" >&2; else echo "$note"; fi
