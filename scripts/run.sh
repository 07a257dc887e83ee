#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and runs the main job.
# (Until the full demo exists this runs what the tree has: see README "Status".)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -G Ninja >/dev/null
cmake --build build -j "$(nproc)"
exec build/bench/hapticctrl-bench-shm --benchmark_min_time=0.2
