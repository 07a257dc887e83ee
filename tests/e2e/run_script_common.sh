# Sourced by the tests that run scripts/run.sh as a user does: they need the tree's own build/
# (run.sh runs that one; other builds skip, exit 77), a temporary directory OUT removed on exit,
# an instance, a runtime directory and ports of their own, and `fail MESSAGE` (prints the log).
# usage: SOURCE=... BUILD=... NAME=...; . run_script_common.sh
if [[ "$(realpath "$BUILD")" != "$(realpath "$SOURCE/build")" ]]; then
  echo "scripts/run.sh runs $SOURCE/build, not this build ($BUILD): skipped"
  exit 77
fi
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
export HAPTICCTRL_INSTANCE="$NAME$$" HAPTICCTRL_RUNTIME_DIR="$OUT/runtime"
export HAPTICCTRL_PORT=$((20000 + $$ % 20000)) HAPTICCTRL_WEB_PORT=$((40000 + $$ % 20000))
fail() {
  echo "${NAME}_test: $1" >&2
  [[ -f $OUT/log ]] && cat "$OUT/log" >&2
  exit 1
}
# True when run.sh's log LOG shows fail-safes and every one was on a measured stall of the
# machine (the FAIL-SAFE line says so, from the core's black box): an attempt the machine spoiled,
# to be tried again, not judged (J5; beside stress-ng a 4 ms core and then a 10 ms one failed
# safe on wake-ups 15 and 30 ms late, 2026-12-03).
only_machine_stalls() {
  local all stalls
  all=$(grep -c "the controller FAILED SAFE" "$1" || true)
  stalls=$(grep -c "the controller FAILED SAFE.*on a stall of the machine" "$1" || true)
  [[ $all -gt 0 && $all -eq $stalls ]]
}
# After attempt TRY (of 3) ended with STATUS: true when it is to be tried again, because it
# failed and every fail-safe in LOG was a measured stall of the machine (said, then tried again);
# after the third such attempt the test ends as skipped (ctest: SKIP_RETURN_CODE 77), saying so
# with that attempt's fail-safe lines. False when the attempt is to be judged.
machine_spoiled_attempt() {  # try status log
  if [[ $2 -eq 0 ]] || ! only_machine_stalls "$3"; then
    return 1
  fi
  if [[ $1 -ge 3 ]]; then
    echo "${NAME}_test: the machine stalled the controller in all $1 attempts: nothing could be" \
      "judged; skipped. The last attempt's fail-safes:"
    grep "the controller FAILED SAFE" "$3" || true
    exit 77
  fi
  echo "${NAME}_test: attempt $1 failed safe ($2) on stalls of the machine, trying again"
}
