#!/usr/bin/env bash
# The system benchmark: hapticctrl's timing against same-run baselines, idle and under load,
# written up as bench-report/report.md (+ results.json, PNG plots).
#
#  1. wake-up latency: hapticctrl-core (arm powered, so the SERVO does its full work) and
#     cyclictest side by side (same priority, period, CPU), idle and under stress-ng CPU+memory
#     load, at 1000, 250 and 100 µs, over the same window (the core in benchmark mode: its
#     would-be fail-safes against cyclictest's stalls of 5 periods or more);
#  2. SERVO start delay after the CLOCK release, against a bare futex hand-off floor;
#  3. end to end at 1 kHz: client -> hapticctrl-udp -> core -> client round trips and answer
#     jitter, against a raw UDP ping-pong on the same loopback, idle and under load;
#  4. micro-benchmarks: seqlock publish/read, XDR encode/decode, one full cycle;
#  5. the coupling over an impaired link (bench/coupling.sh, H1): per one-way delay and loss,
#     the demo's sphere through hapticctrl-netem with a scripted operator (contact, a blackout
#     while pressing, force steps, a wandering spring-damper hand), against the sampled-data
#     stiffness bound and F / K_series (coupling.md); and in contact (bench/contact.sh, J1): the
#     demo's sphere on a stiff wall (VIRTMECH 3000 and 5000 N/m, an IMPEDANCE client's 2000
#     N/m) pushed at 10 N, then a hand wandering into and along it, with the two-port balance
#     (contact.md); and the local contact models (bench/local_contact.sh, J2): per one-way delay
#     and loss, the wall and the fixed sphere the demo reports, rendered in the servo cycle
#     (stiffness felt against the coupling alone in the same run, penetration, a wall jumping
#     into the handle, mu, a blackout, a wandering hand; local.md);
#  6. the weighted sphere at rest (bench/gravity_rest.sh, H1): `hapticctrl-demo --gravity`,
#     nobody touching, 10 minutes (gravity.md);
#  7. the peers (H8): the seqlock regions against iceoryx, LCM and UDP, cross-process, in one
#     run (hapticctrl-bench-peers: latency, read and publish costs, CPU per 1000 messages, a
#     stopped and a killed reader), in report.md's section 5;
#  8. hapticctrl-mujoco on every shipped scene (bench/mujoco_scenes.sh, J3): steps per second
#     against the model's own rate, steps dropped, CPU time per step, idle and under stress-ng
#     (mujoco.md).
#
# usage: scripts/bench.sh [--out DIR] [--build DIR] [--seconds N] [--long] [--smoke]
#   default about 130 minutes (8 s per latency run, 15 s per link run, 14 coupling cases of
#   ~90 s, 48 contact cases of ~70 s, 16 local-model cases of ~110 s, 10 minutes at rest, 10
#   MuJoCo runs of 20 s);
#   --long: 60 s and 120 s latency and link runs; --smoke: 1 s runs, 1 coupling, 2 contact
#   (VIRTMECH and IMPEDANCE) and 1 local-model case with 8 s of hand motion, 20 s at rest (checks
#   the pipeline, not the machine).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=bench-report BUILD=build LAT_S=8 LINK_S=15 MIN_TIME=0.2 PINGS=20000 SMOKE=
while [[ $# -gt 0 ]]; do
  case $1 in
    --out) OUT=$2; shift 2 ;;
    --build) BUILD=$2; shift 2 ;;
    --seconds) LAT_S=$2; LINK_S=$2; shift 2 ;;
    --long) LAT_S=60 LINK_S=120 MIN_TIME=1; shift ;;
    --smoke) LAT_S=1 LINK_S=1 MIN_TIME=0.001 PINGS=300 SMOKE=--smoke; shift ;;
    *) echo "bench: unknown option $1 (see the header of $0)" >&2; exit 64 ;;
  esac
done
# Nothing here reads the terminal: a process that found one on its stdin (gnuplot pages what it
# lists when its input is a terminal) would wait there for a key (J8 walk-through: --smoke in
# a terminal waited 2 min or more).
exec </dev/null
PERIODS=(1000 250 100)
CPU=$(( $(nproc) - 1 ))
PRIO=80
RAW=$OUT/raw

scripts/setup.sh
if [[ ! -f $BUILD/build.ninja ]]; then
  cmake -S . -B "$BUILD" -G Ninja >/dev/null
fi
cmake --build "$BUILD" -j "$(nproc)" --target hapticctrl-core hapticctrl-udp hapticctrl-hmi \
  hapticctrl-bench-link hapticctrl-netem hapticctrl-demo \
  hapticctrl-bench-handoff hapticctrl-bench-shm hapticctrl-bench-protocol hapticctrl-bench-rt-core \
  hapticctrl-bench-peers >/dev/null
rm -rf "$RAW"
mkdir -p "$RAW"

CHILDREN=()
cleanup() {
  for pid in "${CHILDREN[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT

# Load: stress-ng on every CPU plus a memory worker (the seeds' "user space heavily loaded").
start_load() {  # seconds
  stress-ng --cpu "$(nproc)" --vm 1 --vm-bytes 256M --timeout "$1s" -q &
  LOAD_PID=$!
  CHILDREN+=("$LOAD_PID")
  sleep 0.5
}
stop_load() {
  kill -TERM "$LOAD_PID" 2>/dev/null || true
  wait "$LOAD_PID" 2>/dev/null || true
}

machine() {
  local preempt=false rt=false
  if [[ -e /sys/kernel/realtime ]] || uname -v | grep -q PREEMPT_RT; then preempt=true; fi
  if chrt -f 1 true 2>/dev/null; then rt=true; fi
  local virt=none
  grep -q " hypervisor" /proc/cpuinfo && virt=vm
  printf '{"date":"%s","kernel":"%s","kernel_version":"%s","preempt_rt":%s,"cpus":%d,' \
    "$(date -u +%FT%TZ)" "$(uname -r)" "$(uname -v)" "$preempt" "$(nproc)"
  printf '"cpu_model":"%s","virtualization":"%s","sched_fifo":%s,"memlock_kib":"%s",' \
    "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')" "$virt" "$rt" \
    "$(ulimit -l)"
  printf '"loadavg":"%s","git":"%s","latency_seconds":%s,"link_seconds":%s,"bench_cpu":%d,' \
    "$(cut -d' ' -f1-3 /proc/loadavg)" "$(git rev-parse --short HEAD 2>/dev/null || echo -)" \
    "$LAT_S" "$LINK_S" "$CPU"
  printf '"load":"stress-ng --cpu %d --vm 1 --vm-bytes 256M"}\n' "$(nproc)"
}
machine >"$RAW/machine.json"

# 1 + 2: the core and cyclictest at the same priority, period and CPU, concurrently.
# The core runs in benchmark mode: a tripped miss rule is counted as a would-be fail-safe and the
# run goes on, so that both histograms cover the same seconds (a core that failed safe after 65
# cycles was once set beside 8 s of cyclictest). cyclictest's histogram reaches 5 periods, so
# that its stalls of 5 periods or more (what trips the core's rule) can be counted.
latency_run() {  # period label
  local period=$1 label=$2 base="$RAW/lat-$1-$2"
  cyclictest -q -m -t1 -a "$CPU" -p "$PRIO" --policy=fifo -i "$period" -D "$LAT_S" \
    -h $((5 * period + 1000)) >"$base.cyclictest.hist" 2>/dev/null &
  local ct=$!
  CHILDREN+=("$ct")
  "$BUILD/rt_core/hapticctrl-core" --instance "bench$$" --duration "$LAT_S" --period-us "$period" \
    --priority "$PRIO" --cpu "$CPU" --rt warn --benchmark-mode --json \
    --histogram "$base.core.hist" --state-dir "$RAW" >"$base.core.json" 2>"$base.core.err" &
  local core=$!
  CHILDREN+=("$core")
  # Powered, so that every SERVO run does the real work: law, and the simulator's integration.
  for _ in $(seq 1 100); do
    "$BUILD/hmi/hapticctrl-hmi" --instance "bench$$" status >/dev/null 2>&1 && break
    sleep 0.02
  done
  "$BUILD/hmi/hapticctrl-hmi" --instance "bench$$" --timeout-ms 1000 power-on >/dev/null 2>&1 || true
  wait "$core" || true  # a fail-safe is a result, reported as such
  wait "$ct" || true
}
for period in "${PERIODS[@]}"; do
  echo "bench: wake-up latency at $period us, idle and under load ($LAT_S s each)" >&2
  latency_run "$period" idle
  start_load $((LAT_S + 5))
  latency_run "$period" load
  stop_load
done
"$BUILD/bench/hapticctrl-bench-handoff" --iterations 3000 --cpu-a "$CPU" --cpu-b "$CPU" \
  --priority "$PRIO" >"$RAW/handoff.json"

# 3: the client link end to end at 1 kHz.
link_run() {  # label
  local label=$1 inst="benchlink$$"
  "$BUILD/rt_core/hapticctrl-core" --instance "$inst" --rt warn --priority "$PRIO" \
    --benchmark-mode --json --state-dir "$RAW" >"$RAW/link-$label.core.json" \
    2>"$RAW/link-$label.core.err" &
  local core=$!
  CHILDREN+=("$core")
  "$BUILD/bridges/udp/hapticctrl-udp" --instance "$inst" --port 0 --priority 70 \
    >"$RAW/link-$label.udp.out" 2>"$RAW/link-$label.udp.err" &
  local udp=$!
  CHILDREN+=("$udp")
  local port=""
  for _ in $(seq 1 200); do
    port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$RAW/link-$label.udp.out")
    [[ -n $port ]] && break
    sleep 0.05
  done
  local client=("$BUILD/bench/hapticctrl-bench-link")
  if chrt -f 60 true 2>/dev/null; then client=(chrt -f 60 "${client[@]}"); fi
  "${client[@]}" --port "$port" --seconds "$LINK_S" --pings "$PINGS" --json \
    --samples "$RAW/link-$label" >"$RAW/link-$label.json" || echo '{}' >"$RAW/link-$label.json"
  kill -TERM "$udp" "$core" 2>/dev/null || true
  wait "$udp" "$core" 2>/dev/null || true
}
echo "bench: client link at 1 kHz, idle and under load ($LINK_S s each)" >&2
link_run idle
start_load $((LINK_S + 10))
link_run load
stop_load

# 4: micro-benchmarks, each binary printing its own same-run ratios too.
echo "bench: micro-benchmarks" >&2
for b in shm protocol rt-core; do
  "$BUILD/bench/hapticctrl-bench-$b" --benchmark_min_time="$MIN_TIME" \
    --benchmark_out="$RAW/micro-$b.json" --benchmark_out_format=json >"$RAW/micro-$b.txt" \
    2>"$RAW/micro-$b.err"
done

# 5: the coupling over an impaired link.
echo "bench: the coupling over an impaired link (hapticctrl-netem)" >&2
bench/coupling.sh "$OUT" "$BUILD" $SMOKE
echo "bench: the coupling in contact (stiff walls, hapticctrl-netem)" >&2
bench/contact.sh "$OUT" "$BUILD" $SMOKE
echo "bench: local contact models (J2, hapticctrl-netem)" >&2
bench/local_contact.sh "$OUT" "$BUILD" $SMOKE

# 6: the weighted sphere at rest.
echo "bench: the weighted sphere at rest (hapticctrl-demo --gravity)" >&2
bench/gravity_rest.sh "$OUT" "$BUILD" $SMOKE

# 7: the peers.
echo "bench: the seqlock regions against iceoryx, LCM and UDP (hapticctrl-bench-peers)" >&2
"$BUILD/bench/hapticctrl-bench-peers" $SMOKE >"$RAW/peers.json" 2>"$RAW/peers.err" ||
  echo "bench: hapticctrl-bench-peers failed (see $RAW/peers.err)" >&2

# 8: the MuJoCo client's engine in real time.
echo "bench: hapticctrl-mujoco on the shipped scenes" >&2
bench/mujoco_scenes.sh "$OUT" "$BUILD" $SMOKE

python3 bench/report.py "$OUT"
python3 bench/coupling_report.py "$OUT" >/dev/null
python3 bench/contact_report.py "$OUT" >/dev/null
python3 bench/local_contact_report.py "$OUT" >/dev/null
python3 bench/gravity_report.py "$OUT" >/dev/null
python3 bench/mujoco_report.py "$OUT" >/dev/null
{
  echo; cat "$OUT/coupling.md"; echo; cat "$OUT/contact.md"; echo; cat "$OUT/local.md"
  echo; cat "$OUT/gravity.md"; echo; cat "$OUT/mujoco.md"
} >>"$OUT/report.md"
echo "bench: report in $OUT/report.md" >&2
