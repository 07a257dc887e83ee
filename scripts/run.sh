#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and runs the controller.
# Until the bridges, HMI and demo client land (F4-F6), this runs hapticctrl-core with its
# simulated arm: until Ctrl-C on a terminal, or for 5 s without one, then prints its figures.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -G Ninja >/dev/null
cmake --build build -j "$(nproc)"
ARGS=(--instance "${HAPTICCTRL_INSTANCE:-demo}" --json)
if [[ ! -t 0 ]]; then
  ARGS+=(--duration 5)
fi
exec build/rt_core/hapticctrl-core "${ARGS[@]}" "$@"
