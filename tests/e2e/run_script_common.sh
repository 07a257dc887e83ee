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
