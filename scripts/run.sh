#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and runs the controller: the core
# with its simulated arm, the UDP bridge on 127.0.0.1:5125 (HAPTICCTRL_PORT) that clients
# (hapticctrl::client, virtOpen("udpxdr://127.0.0.1:5125")) connect to, and the LCM bridge
# (telemetry on hapticctrl.<instance>.*, host-local; watch with scripts/spy.sh). Runs until
# Ctrl-C on a terminal, or for 5 s without one, then prints the core's figures. The demo client
# and the HMI join with F6.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -G Ninja >/dev/null
cmake --build build -j "$(nproc)"
INSTANCE=${HAPTICCTRL_INSTANCE:-demo}
ARGS=(--instance "$INSTANCE" --json)
if [[ ! -t 0 ]]; then
  ARGS+=(--duration 5)
fi
build/bridges/udp/hapticctrl-udp --instance "$INSTANCE" --port "${HAPTICCTRL_PORT:-5125}" &
BRIDGES=($!)
build/bridges/lcm/hapticctrl-lcm --instance "$INSTANCE" &
BRIDGES+=($!)
trap 'kill -TERM "${BRIDGES[@]}" 2>/dev/null || true; wait "${BRIDGES[@]}" 2>/dev/null || true' EXIT
build/rt_core/hapticctrl-core "${ARGS[@]}" "$@"
