# shellcheck shell=bash
# The scripted scenarios scripts/run.sh plays without a terminal (sourced by it): the operator
# pushes through hapticctrl-hmi, the client ends, and the outcome is read from its summary.
# Each takes the run's directory, the client's pid and the hmi command (with its instance), and
# returns 1 when the client printed no outcome.

# The operator's hand: it pushes with `push` (a wrench sequence's line),
# its wrist holding the handle's rotation (2 N.m/rad, 0.05 N.m.s/rad) and its arm following the
# push (no stiffness towards where it started, 5 N.s/m on its speed), from 0.5 s on for `hold`
# seconds; in the background (its pid in HAND_PID). A pure force on a handle nobody held let a
# contact turn the handle with the object: the demo's sphere rolled off the fixed one at a 10 ms
# core, and the peg sat tilted on its hole's rim (docs/mujoco.md).
hand_pushes() {  # run_dir "fx fy fz tx ty tz" hold_s hmi...
  local dir=$1 push=$2 hold=$3
  shift 3
  printf '0 0 0 0 0 0 0\n0.5 %s\n%s %s\n' "$push" "$hold" "$push" >"$dir/push.seq"
  "$@" play "$dir/push.seq" --hand 0,5,2,0.05 --log "$dir/hand.csv" &
  HAND_PID=$!
}

# The demo has powered the arm and coupled its sphere; the operator's hand pushes the handle
# along +x until the sphere rests against the fixed sphere.
demo_scenario() {  # run_dir client_pid hmi...
  local dir=$1 client=$2
  shift 2
  echo "== scripted scenario (no terminal): a hand pushes the handle 5 N along +x"
  "$@" status
  hand_pushes "$dir" "5 0 0 0 0 0" 4 "$@"
  sleep 3.5
  "$@" status
  kill -TERM "$client" && wait "$client" || true
  wait "$HAND_PID" || true
  "$@" zero-force >/dev/null
  tail -n 2 "$dir/demo.log"
  local outcome
  outcome=$(awk -v operator=5 'match($0, /"contact_force":\[[^]]*\]/) {
      split(substr($0, RSTART + 17, RLENGTH - 18), f, ",")
      printf "outcome: contact force %.3f N for an operator force of %.1f N (%.1f %%)\n",
             -f[1], operator, 100 * -f[1] / operator
    }' "$dir/demo.json")
  echo "${outcome:-run: no outcome: the demo printed no contact force (its log: $dir/demo.log)}"
  [[ -n $outcome ]]
}

# A MuJoCo scene: the operator's hand pushes the tool 3 N down for 3 s; where it went and what
# it met.
scene_scenario() {  # run_dir client_pid hmi...
  local dir=$1 client=$2
  shift 2
  echo "== scripted scenario (no terminal): a hand pushes the scene's tool 3 N down"
  hand_pushes "$dir" "0 0 -3 0 0 0" 4 "$@"
  sleep 3.5
  kill -TERM "$client" && wait "$client" || true
  wait "$HAND_PID" || true
  "$@" zero-force >/dev/null
  tail -n 2 "$dir/mujoco.log"
  local outcome
  outcome=$(awk 'match($0, /"contact_force":\[[^]]*\]/) {
      split(substr($0, RSTART + 17, RLENGTH - 18), f, ",")
      match($0, /"steps_per_second":[0-9.]+/); rate = substr($0, RSTART + 19, RLENGTH - 19)
      printf "outcome: contact force %.3f N up on the tool, %s engine steps/s\n", f[3], rate
    }' "$dir/mujoco.json")
  echo "${outcome:-run: no outcome: hapticctrl-mujoco printed no summary ($dir/mujoco.log)}"
  [[ -n $outcome ]]
}
