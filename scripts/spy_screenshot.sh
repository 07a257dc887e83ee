#!/usr/bin/env bash
# Regenerates docs/lcm-spy.png: runs the controller (core + LCM bridge) for a few seconds, starts
# lcm-spy on a virtual X display (Xvfb) and captures it. Installs xvfb and imagemagick
# when missing (documentation tooling, not needed to build or test).
#
# usage: scripts/spy_screenshot.sh [--build DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build
[[ ${1:-} == --build ]] && BUILD=$2
need=()
for pkg in xvfb imagemagick; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed" || need+=("$pkg")
done
if [[ ${#need[@]} -gt 0 ]]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >/dev/null
fi
scripts/setup.sh
cmake -S . -B "$BUILD" -G Ninja >/dev/null
cmake --build "$BUILD" --target hapticctrl-core hapticctrl-lcm hapticctrl_lcmtypes_jar
INSTANCE=spy$$
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true' EXIT
"$BUILD/rt_core/hapticctrl-core" --instance "$INSTANCE" --rt warn >/dev/null 2>&1 &
pids+=($!)
"$BUILD/bridges/lcm/hapticctrl-lcm" --instance "$INSTANCE" --allow-remote-commands >/dev/null 2>&1 &
pids+=($!)
Xvfb :77 -screen 0 1280x800x24 >/dev/null 2>&1 &
pids+=($!)
sleep 1
DISPLAY=:77 scripts/spy.sh --build "$BUILD" >/dev/null 2>&1 &
pids+=($!)
sleep 2
sleep 6
DISPLAY=:77 import -window root docs/lcm-spy.png
echo "docs/lcm-spy.png written"
