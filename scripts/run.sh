#!/usr/bin/env bash
# The README's main command: installs what is missing, builds what it runs, picks the period
# this machine holds (scripts/probe_period.sh; an explicit --period-us wins), then runs the whole
# product on this machine:
#   hapticctrl-core  the controller and its simulated arm (instance $HAPTICCTRL_INSTANCE, "demo")
#   hapticctrl-udp   the client protocol on 127.0.0.1:$HAPTICCTRL_PORT (5125)
#   hapticctrl-lcm   telemetry on LCM, host-local (watch it with scripts/spy.sh)
#   hapticctrl-demo  the test client: a sphere coupled to the arm, next to a fixed sphere
#   hapticctrl-web   the 3D operator view on http://127.0.0.1:$HAPTICCTRL_WEB_PORT/ (8080)
#   hapticctrl-hmi   the operator panel, in this terminal
# Quitting the panel (q), or Ctrl-C, stops everything: the controller in its fail-safe order,
# then the others; no process is left, and the shared memory (a sealed memfd) goes with them.
# Without a terminal it plays a short scenario instead (power on, a simulated hand pushes the
# handle into the fixed sphere, read the contact force) and prints the outcome. Extra arguments go to hapticctrl-core.
#
# When the controller fails safe the panel says why and when, and R starts a new controller
# (powered off, as after any fail-safe); the bridges and the demo re-attach by themselves, and
# the demo waits for you to power the arm on (p): a controller restarted after a fault refuses a
# client's power-on until its operator's (docs/rt_core.md). This run's first controller is your
# own deliberate start (--fresh-start).
#
# --scene NAME (first, or after --supervise): a MuJoCo scene as the client instead of the demo
# (hapticctrl-mujoco with mujoco/scenes/NAME.xml: table_blocks, peg_in_hole, door_latch,
# heavy_lift; docs/mujoco.md); the handle holds the scene's tool. Without a terminal its scenario
# (an operator's hand holding the handle and its rotation) pushes the tool 3 N down for 3 s and
# prints where it went and the contact force.
#
# --supervise (first argument): keep a controller running: one that failed safe is started
# again at once (powered off), and without a terminal run.sh serves until Ctrl-C or SIGTERM
# instead of playing the scenario. For unattended demos and soak runs, never for a person at the
# arm who has not seen why it stopped (systemd's units do not restart a failed core either).
#
# Without a terminal, a controller that fails safe on a stall of this machine (its FAIL-SAFE
# line says "on a stall of the machine") at the period the probe chose starts the run again at
# the next longer period (1, 2, 4, 10 ms), at most twice, saying so in one line; a fail-safe the
# software caused, or one at a period given with --period-us, ends the run as below.
#
# One run.sh per build directory: a second one refuses at once, naming the first.
#
# Exit status: 0 the controller stopped in order; 10 + the stop reason's code when it failed
# safe (11: 5 consecutive deadline misses, 14: chronic misses, 15: arm fault, 17: velocity
# limit; docs/rt_core.md), with the reason printed; 4 the emergency stop is still latched from
# an earlier run and there is no terminal to reset it from; 1 anything else that went wrong (a
# part that did not start, with its own words; no outcome; another run.sh on this build); 130
# interrupted.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/run_scenarios.sh
source scripts/run_scenarios.sh
if [[ " $* " == *" --help "* || " $* " == *" -h "* ]]; then  # before any build or probe (J8)
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
  echo "Environment: HAPTICCTRL_INSTANCE (demo), HAPTICCTRL_PORT (5125), HAPTICCTRL_WEB_PORT" \
    "(8080), HAPTICCTRL_BUILD_DIR (build), HAPTICCTRL_RUNTIME_DIR; the core's options:" \
    "build/rt_core/hapticctrl-core --help"
  exit 0
fi
ARGS=("$@")  # as given: a run started again after a stall gets them again
SUPERVISE=0
if [[ ${1:-} == --supervise ]]; then
  SUPERVISE=1
  shift
fi
SCENE=""
if [[ ${1:-} == --scene ]]; then
  SCENE=${2:-}
  shift 2 || true
  if [[ ! -f mujoco/scenes/$SCENE.xml ]]; then
    echo "run: no scene '$SCENE': mujoco/scenes/ has" \
      "$(cd mujoco/scenes && ls ./*.xml | sed 's|^./||; s|\.xml$||' | tr '\n' ' ')" >&2
    exit 1
  fi
fi
CLIENT=demo  # its logs: $RUN_DIR/$CLIENT.log and .json
[[ -n $SCENE ]] && CLIENT=mujoco
BUILD=${HAPTICCTRL_BUILD_DIR:-build}
# One run.sh per build directory (its logs and its run/ are the build's): a second one refuses
# at once, naming the first, and touches none of its files (J8: it truncated the first run's
# logs, then exited 1 on "region force ... already written").
mkdir -p "$BUILD"
exec {RUN_LOCK}>>"$BUILD/run.lock"
if ! flock -n "$RUN_LOCK"; then
  echo "run: another scripts/run.sh is running on $BUILD/ (pid $(cat "$BUILD/run.pid" 2>/dev/null ||
    echo '?')): stop it first (q or Ctrl-C there), or give this one its own" \
    "HAPTICCTRL_BUILD_DIR, HAPTICCTRL_INSTANCE, HAPTICCTRL_PORT and HAPTICCTRL_WEB_PORT" >&2
  exit 1
fi
echo $$ >"$BUILD/run.pid"
echo "run: checking the Debian packages it needs (scripts/setup.sh installs what is missing)"
scripts/setup.sh
if [[ ! -f $BUILD/build.ninja ]]; then
  echo "run: configuring $BUILD/"
  cmake -S . -B "$BUILD" -G Ninja >/dev/null
fi
# Only what runs here (tests and benchmarks are scripts/test.sh's and bench.sh's), with the build
# tool's own progress: about 2 minutes the first time on 2 vCPUs (1 min 46-55 s from an empty
# build directory, 2026-12-02), seconds after that.
echo "run: building the controller, the bridges, the panel and the demo"
cmake --build "$BUILD" -j "$(nproc)" --target hapticctrl_run

INSTANCE=${HAPTICCTRL_INSTANCE:-demo}
PORT=${HAPTICCTRL_PORT:-5125}
WEB_PORT=${HAPTICCTRL_WEB_PORT:-8080}
RUN_DIR=$BUILD/run
mkdir -p "$RUN_DIR"
HMI=("$BUILD/hmi/hapticctrl-hmi" --instance "$INSTANCE")
PIDS=()

reap_core() {  # waits for the core once and keeps its exit status in CORE_RC
  if [[ -n "${CORE_PID:-}" ]]; then
    CORE_RC=0
    wait "$CORE_PID" 2>/dev/null || CORE_RC=$?
    CORE_PID=
  fi
}

stop_all() {
  # The controller first, by the operator's stop (fail-safe order: motors inhibited, supply off,
  # client told, tasks stopped); then the processes that served it.
  # The supervisor (--supervise) starts no new controller from now on; one it started while
  # this stop was on its way is stopped on the next round.
  touch "$RUN_DIR/stopping"
  for _ in $(seq 50); do
    [[ -n "${CORE_PID:-}" ]] && kill -0 "$CORE_PID" 2>/dev/null || break
    "${HMI[@]}" stop >/dev/null 2>&1 || kill -TERM "$(cat "$RUN_DIR/core.pid")" 2>/dev/null ||
      sleep 0.1
  done
  for pid in "${PIDS[@]}"; do
    kill -TERM "$pid" 2>/dev/null || true
  done
  for pid in "${PIDS[@]}"; do
    wait "$pid" 2>/dev/null || true
  done
  reap_core
}
# On every way out: stop everything, then say how the controller ended. A controller that
# failed safe makes the run fail, with its reason, whatever the script was doing.
on_exit() {
  local status=$?
  trap - EXIT INT TERM
  stop_all
  if [[ ${CORE_RC:-0} -eq 3 ]]; then
    report_fail_safe
    again_after_stall
    local code
    code=$(sed -n 's/.*"stop_reason_code":\([0-9]*\).*/\1/p' "$RUN_DIR/core.json")
    exit $((10 + ${code:-0}))
  fi
  exit "$status"
}
trap on_exit EXIT
trap 'exit 130' INT TERM

report_fail_safe() {  # the last fail-safe of core.log, on the terminal
  echo "run: the controller FAILED SAFE: $(grep 'FAIL-SAFE' "$RUN_DIR/core.log" | tail -n 1 |
    sed 's/^hapticctrl-core: FAIL-SAFE //')" >&2
}

# J5: the probe measures 2 s, and this VM stalls for 5-60 ms now and then (docs/rt_core.md).
# Starts the whole run again (never returns) at the next longer period when the last fail-safe
# was a stall of the machine, the period was the probe's, there is no terminal and fewer than
# two such starts happened; returns otherwise.
again_after_stall() {
  local restarts=${HAPTICCTRL_RUN_RESTARTS:-0} next
  [[ -n ${PROBED_PERIOD:-} && $SUPERVISE -eq 0 && $restarts -lt 2 ]] || return 0
  [[ -t 0 && -t 1 ]] && return 0  # the panel said it, and R starts a new controller
  grep 'FAIL-SAFE' "$RUN_DIR/core.log" | tail -n 1 | grep -q 'on a stall of the machine' ||
    return 0
  case $PROBED_PERIOD in
    1000) next=2000 ;;
    2000) next=4000 ;;
    4000) next=10000 ;;
    *) return 0 ;;
  esac
  echo "run: that was a stall of this machine, not of the controller: starting again at" \
    "$((next / 1000)) ms (again $((restarts + 1)) of 2)" >&2
  exec {RUN_LOCK}>&-  # the run lock: the run started again takes it anew
  HAPTICCTRL_RUN_RESTARTS=$((restarts + 1)) HAPTICCTRL_RUN_PERIOD_US=$next exec "$0" "${ARGS[@]}"
}

# The last fail-safe's reason, without its cycle and the steps taken ("5 consecutive deadline
# misses").
fail_safe_reason() {
  grep 'FAIL-SAFE' "$RUN_DIR/core.log" | tail -n 1 |
    sed 's/.*FAIL-SAFE after cycle [0-9]*: //; s/ (motors inhibited.*//'
}

# Runs the controller (its pid in core.pid); under --supervise starts it again after each
# fail-safe, by these rules (J4: it restarted a core that failed safe at every start 19 times in
# 15 s, forever): it waits 0.5 s, then twice as long after each fail-safe that followed soon
# (up to 8 s; 0.5 s again after a controller that ran a minute); it starts at most 5 in any
# 60 s; and it gives up when a controller fails safe within 3 s of its start for the same reason
# as the one before (a stall of the machine says how late the clock woke, so stalls never look
# alike): a start that fails the same way every time is a fault to fix, not to retry. Giving up
# says why and ends the run with the fail-safe's exit code. Returns the last controller's exit
# status.
run_core() {  # fresh (1: this run's first controller, started by its operator), core options...
  local fresh=$1 starts=0 rc delay=0.5 started ran reason last_reason="" stamp
  shift
  local -a recent=() first=()
  # The run's first controller is its operator's deliberate start; a restart (the supervisor's,
  # or R in the panel) after a fault refuses a client's power-on until the operator powers the
  # arm on (p in the panel): J8, IEC 60204-1 7.5.
  [[ $fresh -eq 1 ]] && first=(--fresh-start)
  while true; do
    started=$SECONDS
    "$BUILD/rt_core/hapticctrl-core" --instance "$INSTANCE" --json "${first[@]}" "$@" \
      >"$RUN_DIR/core.json" 2>>"$RUN_DIR/core.log" &
    first=()
    echo $! >"$RUN_DIR/core.pid"
    rc=0
    wait $! || rc=$?
    starts=$((starts + 1))
    if [[ $rc -ne 3 || $SUPERVISE -eq 0 || -e "$RUN_DIR/stopping" ]]; then
      return "$rc"
    fi
    report_fail_safe
    ran=$((SECONDS - started))
    reason=$(fail_safe_reason)
    if [[ $ran -lt 3 && $reason == "$last_reason" ]]; then
      echo "run: supervisor: the controller failed safe at its start twice in a row ($reason):" \
        "not starting it again" >&2
      return "$rc"
    fi
    last_reason=$reason
    local -a kept=()
    for stamp in "${recent[@]}" "$SECONDS"; do
      [[ $((SECONDS - stamp)) -lt 60 ]] && kept+=("$stamp")
    done
    recent=("${kept[@]}")
    if [[ ${#recent[@]} -ge 5 ]]; then
      echo "run: supervisor: ${#recent[@]} fail-safes within 60 s: not starting it again" >&2
      return "$rc"
    fi
    [[ $ran -ge 60 ]] && delay=0.5
    echo "run: supervisor: starting controller #$((starts + 1)) in $delay s (powered off, until" \
      "an operator powers it on: p in the panel, or ${HMI[*]} power-on)" >&2
    sleep "$delay"
    delay=$(awk -v d="$delay" 'BEGIN { print (d * 2 > 8 ? 8 : d * 2) }')
    [[ -e "$RUN_DIR/stopping" ]] && return "$rc"
  done
}

# A process that did not start: its own words, not only that it failed (J8).
did_not_start() {  # name log
  echo "run: $1 did not start; it said:" >&2
  tail -n 5 "$2" | sed 's/^/  /' >&2
  exit 1
}

FRESH=1
start_core() {
  run_core "$FRESH" "$@" &
  FRESH=0
  CORE_PID=$!
  for _ in $(seq 100); do
    "${HMI[@]}" status >/dev/null 2>&1 && return 0
    kill -0 "$CORE_PID" 2>/dev/null || did_not_start hapticctrl-core "$RUN_DIR/core.log"
    sleep 0.05
  done
}

: >"$RUN_DIR/core.log"
rm -f "$RUN_DIR/stopping"
# The period: an explicit --period-us always wins; else the shortest this machine holds.
PERIOD_ARGS=()
PROBED_PERIOD=
if [[ " $* " != *" --period-us "* ]]; then
  if [[ -n ${HAPTICCTRL_RUN_PERIOD_US:-} ]]; then
    PROBED_PERIOD=$HAPTICCTRL_RUN_PERIOD_US  # a start again after a stall (again_after_stall)
  else
    PROBED_PERIOD=$(scripts/probe_period.sh "$RUN_DIR" 2>/dev/null)
    echo "run: $(cat "$RUN_DIR/probe.txt")"
  fi
  PERIOD_ARGS=(--period-us "$PROBED_PERIOD")
fi
PERIOD_TEXT=${PERIOD_ARGS[1]:+, period $((PERIOD_ARGS[1] / 1000)) ms}
echo "run: starting the controller (instance $INSTANCE$PERIOD_TEXT; its log: $RUN_DIR/core.log)"
start_core "${PERIOD_ARGS[@]}" "$@"
# An emergency stop latched in an earlier run and never reset outlives its controller
# (docs/rt_core.md): the arm stays off until an operator resets it, never a script.
for _ in $(seq 40); do
  grep -q "running, period" "$RUN_DIR/core.log" && break
  sleep 0.05
done
if grep -q "the emergency stop is still latched" "$RUN_DIR/core.log"; then
  echo "run: the emergency stop is still latched from an earlier run: the arm stays off until" \
    "an operator resets it (r in the panel, or: ${HMI[*]} reset)" >&2
  if ! [[ -t 0 && -t 1 ]] && [[ $SUPERVISE -eq 0 ]]; then
    echo "run: without a terminal nobody resets it here: stopping (exit 4)" >&2
    exit 4
  fi
fi
echo "run: starting the UDP bridge, the LCM bridge, the web view and the $CLIENT client"
"$BUILD/bridges/udp/hapticctrl-udp" --instance "$INSTANCE" --port "$PORT" >"$RUN_DIR/udp.log" 2>&1 &
PIDS+=($!)
# The web page watches, and its emergency stop always acts. With HAPTICCTRL_WEB_CONTROL=1 (and
# a terminal) the page is the operator panel instead of this terminal: the LCM bridge then takes
# the force region (one writer per region) and both bridges accept the page's power and force.
REMOTE=()
if [[ "${HAPTICCTRL_WEB_CONTROL:-0}" == 1 && -t 0 && -t 1 ]]; then
  REMOTE=(--allow-remote-commands)
fi
"$BUILD/bridges/lcm/hapticctrl-lcm" --instance "$INSTANCE" "${REMOTE[@]}" 2>"$RUN_DIR/lcm.log" &
PIDS+=($!)
"$BUILD/bridges/web/hapticctrl-web" --instance "$INSTANCE" --listen "127.0.0.1:$WEB_PORT" \
  "${REMOTE[@]}" 2>"$RUN_DIR/web.log" &
PIDS+=($!)
if [[ -n $SCENE ]]; then
  "$BUILD/mujoco/hapticctrl-mujoco" --model "mujoco/scenes/$SCENE.xml" --server "127.0.0.1:$PORT" \
    --instance "$INSTANCE" --headless --json >"$RUN_DIR/mujoco.json" 2>"$RUN_DIR/mujoco.log" &
else
  "$BUILD/demo/hapticctrl-demo" --server "127.0.0.1:$PORT" --instance "$INSTANCE" --headless \
    --json --log "$RUN_DIR/demo.csv" >"$RUN_DIR/demo.json" 2>"$RUN_DIR/demo.log" &
fi
DEMO_PID=$!
PIDS+=("$DEMO_PID")
for _ in $(seq 100); do
  grep -q "ready:" "$RUN_DIR/$CLIENT.log" 2>/dev/null && break
  sleep 0.05
done

sleep 0.3
# A bridge that could not start (its port taken, say) ends the run with its reason: without it
# the scenario ran unconnected and exited 0 (J8).
for part in "udp:${PIDS[0]}" "lcm:${PIDS[1]}"; do
  kill -0 "${part#*:}" 2>/dev/null || did_not_start "hapticctrl-${part%%:*}" "$RUN_DIR/${part%%:*}.log"
done
if ! grep -q "ready:" "$RUN_DIR/$CLIENT.log"; then
  kill -0 "$DEMO_PID" 2>/dev/null || did_not_start "hapticctrl-$CLIENT" "$RUN_DIR/$CLIENT.log"
fi
if grep -q "listening on" "$RUN_DIR/web.log"; then
  echo "run: operator view on http://127.0.0.1:$WEB_PORT/ (from another machine: ssh -L $WEB_PORT:127.0.0.1:$WEB_PORT)"
else
  echo "run: the web view did not start: $(cat "$RUN_DIR/web.log")" >&2
fi

if [[ ${#REMOTE[@]} -gt 0 ]]; then
  echo "run: the web page is the operator panel; Ctrl-C stops everything"
  reap_core
  exit 0
fi
if [[ -t 0 && -t 1 ]]; then
  # R in the panel, once the controller has ended: a new one (powered off), the same panel.
  # Under --supervise the supervisor starts it, and the panel re-attaches by itself.
  OFFER=(--offer-restart)
  [[ $SUPERVISE -eq 1 ]] && OFFER=()
  while true; do
    panel=0
    "${HMI[@]}" "${OFFER[@]}" || panel=$?
    [[ $panel -eq 75 ]] || break
    reap_core
    [[ $CORE_RC -eq 3 ]] && report_fail_safe
    echo "run: starting a new controller (powered off; a client may power it on once you have: p)"
    start_core "${PERIOD_ARGS[@]}" "$@"
  done
  exit 0  # stop_all (EXIT) stops the controller and the rest
fi
if [[ $SUPERVISE -eq 1 ]]; then
  echo "run: supervising the controller (a fail-safe starts a new one); Ctrl-C stops everything"
  reap_core
  exit 0
fi

# No terminal: a short scripted scenario (scripts/run_scenarios.sh), its outcome, then the
# controller's end.
OUTCOME=0
if [[ -n $SCENE ]]; then
  scene_scenario "$RUN_DIR" "$DEMO_PID" "${HMI[@]}" || OUTCOME=$?
else
  demo_scenario "$RUN_DIR" "$DEMO_PID" "${HMI[@]}" || OUTCOME=$?
fi
"${HMI[@]}" stop
reap_core
[[ -n $SCENE ]] || cat "$RUN_DIR/core.log"
echo "core figures: $(cat "$RUN_DIR/core.json")"
if [[ -n $SCENE ]]; then
  echo "logs in $RUN_DIR/"
else
  echo "logs in $RUN_DIR/ (demo.csv: the scene per step)"
fi
exit "$OUTCOME"
