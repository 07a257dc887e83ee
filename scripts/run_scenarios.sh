# shellcheck shell=bash
# The scripted scenarios scripts/run.sh plays without a terminal (sourced by it): the operator
# pushes through hapticctrl-hmi, the client ends, and the outcome is read from its summary.
# Each takes the run's directory, the client's pid and the hmi command (with its instance), and
# returns 1 when the client printed no outcome.

# The demo has powered the arm and coupled its sphere; the operator pushes the handle along +x
# until the sphere rests against the fixed sphere.
demo_scenario() {  # run_dir client_pid hmi...
  local dir=$1 client=$2
  shift 2
  echo "== scripted scenario (no terminal): push the handle 5 N along +x"
  "$@" status
  "$@" force 5 0 0 0 0 0
  sleep 3
  "$@" status
  kill -TERM "$client" && wait "$client" || true
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

# A MuJoCo scene: the tool pushed 3 N down for 3 s; where it went and what it met.
scene_scenario() {  # run_dir client_pid hmi...
  local dir=$1 client=$2
  shift 2
  echo "== scripted scenario (no terminal): push the scene's tool 3 N down"
  "$@" force 0 0 -3 0 0 0
  sleep 3
  kill -TERM "$client" && wait "$client" || true
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
