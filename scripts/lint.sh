#!/usr/bin/env bash
# The dependency rules (docs/architecture.md), the real-time contract (scripts/check_realtime.py,
# which first proves on planted violations that it finds them), clang-format (check only) and
# clang-tidy over the project's own sources.
# Usage: scripts/lint.sh [build-dir-with-compile_commands.json]  (--fix to reformat in place)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build
FIX=0
for arg in "$@"; do
  case $arg in
    --fix) FIX=1 ;;
    *) BUILD=$arg ;;
  esac
done

scripts/check_architecture.py .

mapfile -t SOURCES < <(git ls-files '*.cpp' '*.hpp' '*.h' | grep -v '^lcmtypes/generated/')
if [[ $FIX -eq 1 ]]; then
  clang-format -i "${SOURCES[@]}"
else
  clang-format --dry-run --Werror "${SOURCES[@]}"
fi

mapfile -t UNITS < <(git ls-files '*.cpp')
[[ -f $BUILD/compile_commands.json ]] || { echo "lint: no $BUILD/compile_commands.json" >&2; exit 1; }
# .clang-tidy is written for clang-tidy-22 (scripts/setup.sh installs it); run-clang-tidy
# parallelises.
if ! command -v run-clang-tidy-22 >/dev/null; then
  echo "lint: run-clang-tidy-22 not found (scripts/setup.sh installs clang-tidy-22)" >&2
  exit 1
fi
TIDY_LOG=/tmp/hapticctrl-tidy.log
if ! run-clang-tidy-22 -quiet -p "$BUILD" -j "$(nproc)" "${UNITS[@]/#/$PWD/}" \
  >"$TIDY_LOG" 2>&1; then
  grep -E "error:|warning:" "$TIDY_LOG" | sort -u | head -50
  exit 1
fi
scripts/check_realtime.py --self-test >/dev/null
scripts/check_realtime.py --build "$BUILD" .
echo "lint: clean (${#SOURCES[@]} files formatted, ${#UNITS[@]} units tidy, the real-time contract kept)"
