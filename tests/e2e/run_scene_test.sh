#!/usr/bin/env bash
# scripts/run.sh --scene (J3) as a user runs it without a terminal: hapticctrl-mujoco on the
# peg-in-hole scene instead of the demo; the scripted 3 N push takes the peg into its hole, the
# outcome line says the contact force and the engine's steps per second, and no process is left.
# An unknown scene is refused with the list of the shipped ones, before anything starts.
# usage: run_scene_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE=$1 BUILD=$2 NAME=run_scene
# shellcheck source=run_script_common.sh
. "$(dirname "$0")/run_script_common.sh"
status=0
"$SOURCE/scripts/run.sh" --scene nothing </dev/null >"$OUT/log" 2>&1 || status=$?
[[ $status -eq 1 ]] || fail "an unknown scene: expected exit 1, got $status"
grep -q "no scene 'nothing'.*peg_in_hole" "$OUT/log" || fail "the shipped scenes are not listed"
for try in 1 2 3; do
  status=0
  "$SOURCE/scripts/run.sh" --scene peg_in_hole </dev/null >"$OUT/log" 2>&1 || status=$?
  cat "$OUT/log"
  machine_spoiled_attempt "$try" "$status" "$OUT/log" || break
done
[[ $status -eq 0 ]] || fail "expected exit 0, got $status"
grep -q "^outcome: contact force [0-9.]* N up on the tool, [0-9.]* engine steps/s" "$OUT/log" ||
  fail "no outcome line"
grep -q "the scene goes out on LCM, hapticctrl\.$HAPTICCTRL_INSTANCE\.world" "$BUILD/run/mujoco.log" ||
  fail "the scene does not go out on the instance's world channel (the web view would not draw it)"
json=$(cat "$BUILD/run/mujoco.json")
z=$(sed -n 's/.*"body_pose":\[[^,]*,[^,]*,\([^,]*\),.*/\1/p' <<<"$json")
awk -v z="$z" 'BEGIN { exit !(z < 0.005) }' ||
  fail "the peg is not in its hole (centre at z $z m; in: below 0.005)"
if pgrep -f -- "--instance $HAPTICCTRL_INSTANCE" >/dev/null || pgrep -f "hapticctrl-mujoco --model" >/dev/null; then
  fail "processes were left running"
fi
echo "run_scene_test: the peg at z $z m; $(grep '^outcome' "$OUT/log")"
