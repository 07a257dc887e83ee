# Sourced by the benchmark scripts that start the product's processes: PIDS, stop_all (also on
# exit), start_core_and_bridge, start_relay, wait_for_ready and port_of; and the case scripts'
# cases_from_arguments and sequence. Expects BUILD.
# The case scripts' own arguments (bench/coupling.sh, contact.sh, local_contact.sh): CASES (the
# script's default list) and HAND_S (60 s) are set before; --smoke replaces the cases with the
# script's smoke cases and the hand's time with 8 s, --case CASE (repeatable) chooses cases.
# usage: cases_from_arguments SCRIPT "SMOKE CASES" "$@"
cases_from_arguments() {
  local script=$1 smoke=$2
  shift 2
  local -a only=()
  while [[ $# -gt 0 ]]; do
    case $1 in
      --smoke) read -ra CASES <<<"$smoke"; HAND_S=8 ;;
      --case) only+=("$2"); shift ;;
      *) echo "$script: unknown argument '$1'" >&2; exit 64 ;;
    esac
    shift
  done
  if [[ ${#only[@]} -gt 0 ]]; then CASES=("${only[@]}"); fi
}

sequence() {  # file, then "t fx fy fz tx ty tz" lines: a force sequence for hapticctrl-hmi play
  local file=$1
  shift
  printf '%s\n' "$@" >"$file"
}

PIDS=()
stop_all() {  # TERM every started process and wait for it
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  wait "${PIDS[@]}" 2>/dev/null || true
  PIDS=()
}
trap stop_all EXIT

port_of() {  # file: the port a program printed after "listening on 127.0.0.1:" (10 s at most)
  for _ in $(seq 1 200); do
    local p
    p=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$1")
    if [[ -n $p ]]; then echo "$p"; return 0; fi
    sleep 0.05
  done
  return 1
}

start_core_and_bridge() {  # instance dir: a 1 ms core in benchmark mode and a UDP bridge on a
  # free port (DIR/udp.out says which), their logs in DIR. Returns once the core runs: a program
  # that maps its regions at once (hapticctrl-hmi play) would otherwise find no controller
  # (bench.report.smoke's weighted sphere, 2026-12-02).
  "$BUILD/rt_core/hapticctrl-core" --instance "$1" --rt warn --priority 80 --benchmark-mode \
    --state-dir "$2" 2>"$2/core.err" &
  PIDS+=($!)
  for _ in $(seq 1 200); do
    grep -q "instance '$1' running" "$2/core.err" 2>/dev/null && break
    sleep 0.05
  done
  "$BUILD/bridges/udp/hapticctrl-udp" --instance "$1" --port 0 >"$2/udp.out" 2>"$2/udp.err" &
  PIDS+=($!)
}

start_relay() {  # dir delay_ms loss jitter_ms: hapticctrl-netem in front of the bridge that
  # start_core_and_bridge started in DIR; sets RELAY_PID and RELAY_PORT (the demo's server).
  local port
  port=$(port_of "$1/udp.out")
  "$BUILD/bench/netem/hapticctrl-netem" --to "127.0.0.1:$port" --delay-ms "$2" --loss "$3" \
    --jitter-ms "$4" --seed 7 --json >"$1/netem.out" 2>"$1/netem.err" &
  RELAY_PID=$!
  PIDS+=("$RELAY_PID")
  RELAY_PORT=$(port_of "$1/netem.out")
}

wait_for_ready() {  # file: until a program printed "ready:" there (10 s at most)
  for _ in $(seq 1 200); do
    grep -q "ready:" "$1" 2>/dev/null && return 0
    sleep 0.05
  done
}
