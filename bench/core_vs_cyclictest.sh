#!/usr/bin/env bash
# Wake-up latency of hapticctrl-core against cyclictest run concurrently at the same priority,
# period and CPU, idle and (if stress-ng exists) under CPU+memory load; and the core's SERVO
# start delay against a bare two-thread futex hand-off floor measured in the same run. The core
# runs in benchmark mode, as in scripts/bench.sh: a tripped miss rule is counted as a would-be
# fail-safe and the run goes on, so that both histograms cover the same seconds.
#
# usage: bench/core_vs_cyclictest.sh [--build DIR] [--seconds N] [--period-us P] [--cpu C]
#                                    [--priority P] [--no-load]
set -euo pipefail
BUILD=build SECONDS_RUN=10 PERIOD=1000 CPU=$(( $(nproc) - 1 )) PRIO=80 LOAD=1
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) BUILD=$2; shift 2 ;;
    --seconds) SECONDS_RUN=$2; shift 2 ;;
    --period-us) PERIOD=$2; shift 2 ;;
    --cpu) CPU=$2; shift 2 ;;
    --priority) PRIO=$2; shift 2 ;;
    --no-load) LOAD=0; shift ;;
    *) echo "unknown option $1" >&2; exit 64 ;;
  esac
done
CORE=$BUILD/rt_core/hapticctrl-core
HANDOFF=$BUILD/bench/hapticctrl-bench-handoff
command -v cyclictest >/dev/null || { echo "cyclictest missing (scripts/setup.sh installs rt-tests)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# p50/p99/p99.9/max (µs) from a cyclictest-format histogram on stdin.
percentiles() {
  awk -f "$(dirname "$0")/../scripts/cyclictest_percentiles.awk"
}

run_pair() {  # label
  local label=$1 inst="bench$$"
  cyclictest -q -m -t1 -a "$CPU" -p "$PRIO" --policy=fifo -i "$PERIOD" -D "$SECONDS_RUN" -h 10000 \
    >"$TMP/cyclictest.hist" 2>/dev/null &
  local ct=$!
  "$CORE" --instance "$inst" --duration "$SECONDS_RUN" --period-us "$PERIOD" --priority "$PRIO" \
    --cpu "$CPU" --rt ignore --benchmark-mode --json --histogram "$TMP/core.hist" \
    --state-dir "$TMP" >"$TMP/core.json" 2>"$TMP/core.err" || true
  wait "$ct" || true
  read -r c50 c99 c999 cmax < <(percentiles <"$TMP/cyclictest.hist")
  read -r h50 h99 h999 hmax < <(percentiles <"$TMP/core.hist")
  local misses
  misses=$(grep -o '"misses_total":[0-9]*' "$TMP/core.json" | cut -d: -f2)
  local reason would
  reason=$(grep -o '"stop_reason":"[^"]*"' "$TMP/core.json" | cut -d'"' -f4)
  would=$(grep -o '"would_fail_safe":[0-9]*' "$TMP/core.json" | cut -d: -f2)
  printf "%-6s %-10s %8s %8s %8s %8s   misses (core stop: %s)\n" "$label" "" p50 p99 p99.9 max "$reason"
  printf "%-6s %-10s %8d %8d %8d %8d   %s\n" "" cyclictest "$c50" "$c99" "$c999" "$cmax" "-"
  printf "%-6s %-10s %8d %8d %8d %8d   %s (would-be fail-safes: %s)\n" "" core "$h50" "$h99" \
    "$h999" "$hmax" "$misses" "$would"
  awk -v a="$h50" -v b="$c50" -v c="$h99" -v d="$c99" -v e="$h999" -v f="$c999" -v g="$hmax" -v h="$cmax" \
    'function r(x,y){ return y > 0 ? sprintf("%.2f", x / y) : "n/a" }
     BEGIN { printf "%-6s %-10s %8s %8s %8s %8s\n", "", "ratio", r(a,b), r(c,d), r(e,f), r(g,h) }'
  grep -o '"servo_start_delay":{[^}]*}' "$TMP/core.json" >"$TMP/start.json" || true
}

echo "# wake-up latency, µs (1 µs bins); period ${PERIOD} µs, ${SECONDS_RUN} s, CPU ${CPU}, priority ${PRIO}"
echo "# kernel $(uname -r) $(uname -v | grep -o 'PREEMPT[_A-Z]*' | head -1), $(nproc) CPUs"
run_pair idle
start_idle=$(cat "$TMP/start.json")
if [[ $LOAD -eq 1 ]] && command -v stress-ng >/dev/null; then
  stress-ng --cpu "$(nproc)" --vm 1 --vm-bytes 256M --timeout "$((SECONDS_RUN + 2))s" -q &
  STRESS=$!
  sleep 1
  run_pair load
  wait "$STRESS" || true
fi

echo
echo "# SERVO start delay after CLOCK release vs bare futex hand-off (same CPU), µs"
floor=$("$HANDOFF" --iterations 3000 --cpu-a "$CPU" --cpu-b "$CPU" --priority "$PRIO")
f50=$(grep -o '"p50_ns":[0-9]*' <<<"$floor" | cut -d: -f2)
f99=$(grep -o '"p99_ns":[0-9]*' <<<"$floor" | cut -d: -f2)
s50=$(grep -o '"p50_ns":[0-9]*' <<<"$start_idle" | cut -d: -f2)
s99=$(grep -o '"p99_ns":[0-9]*' <<<"$start_idle" | cut -d: -f2)
awk -v s50="$s50" -v s99="$s99" -v f50="$f50" -v f99="$f99" 'BEGIN {
  printf "%-22s %8s %8s\n", "", "p50", "p99"
  printf "%-22s %8.1f %8.1f\n", "core SERVO start", s50 / 1000, s99 / 1000
  printf "%-22s %8.1f %8.1f\n", "futex hand-off floor", f50 / 1000, f99 / 1000
  printf "%-22s %8.2f %8.2f\n", "ratio", (f50 > 0 ? s50 / f50 : 0), (f99 > 0 ? s99 / f99 : 0) }'
