#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, runs every test.
# Under CI=true it also checks formatting and clang-tidy, and builds and runs the tests with
# AddressSanitizer+UBSan and with ThreadSanitizer.
#
# --under-load (or HAPTICCTRL_TEST_UNDER_LOAD=1): the tests run beside `stress-ng --cpu 1
# --cpu-load 50`, a busy laptop's load, to check that they judge the software and not the
# machine (J5: a test the machine disturbed is retried and says so; docs/reliability.md).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
JOBS=$(nproc)
UNDER_LOAD=${HAPTICCTRL_TEST_UNDER_LOAD:-0}
if [[ ${1:-} == --under-load ]]; then
  UNDER_LOAD=1
  shift
fi

# Each stage says when it starts, so that a slow CI run shows where its time went (budget: 45 min).
stage() { echo "== $* (at $((SECONDS / 60)) min $((SECONDS % 60)) s)"; }

scripts/setup.sh

LOAD_PID=""
stop_load() {
  if [[ -n $LOAD_PID ]]; then
    kill -TERM "$LOAD_PID" 2>/dev/null || true
    wait "$LOAD_PID" 2>/dev/null || true
  fi
}
if [[ $UNDER_LOAD == 1 ]]; then
  stress-ng --cpu 1 --cpu-load 50 --quiet &
  LOAD_PID=$!
  trap stop_load EXIT
  echo "== under load: stress-ng --cpu 1 --cpu-load 50 beside every test (pid $LOAD_PID)"
fi

# Line tables only (-g1): enough for every backtrace and sanitizer report, and it halves the
# compile time of a test file (codec_test.cpp 8.1 s with -g, 4.3 s with -g1; servo_law_test.cpp
# 10.1 s and 6.7 s, measured 2026-12-02), which is most of the time of the three builds.
LINES_ONLY=(-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG")
# LLVM's linker: about 410 executables are linked in the four builds, each in well under half of
# ld.bfd's time (an ASan test program 0.35 s against 0.87 s, the core 0.31 against 0.87; all 174
# programs of the plain build 44.9 CPU-s against 72.4; 2026-12-07).
LLD=(-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld
  -DCMAKE_MODULE_LINKER_FLAGS=-fuse-ld=lld)

configure_build() {  # dir, extra cmake args...
  local dir=$1
  shift
  cmake -S "$ROOT" -B "$dir" -G Ninja -DHAPTICCTRL_WERROR=ON "${LINES_ONLY[@]}" "${LLD[@]}" "$@" \
    >/dev/null
  cmake --build "$dir" -j "$JOBS"
}

run_tests() {  # dir, ctest label regex, ctest attempts[, label regex left out]
  local dir=$1 labels=$2 attempts=$3 left_out=(${4:+-LE "$4"})
  stage "tests of $dir"
  local runner=()
  # Sanitizer runtimes of GCC 12 cannot map their shadow with high mmap randomisation.
  if [[ -r /proc/sys/vm/mmap_rnd_bits && $(cat /proc/sys/vm/mmap_rnd_bits) -gt 28 ]]; then
    runner=(setarch "$(uname -m)" -R)
  fi
  if ! (cd "$dir" && "${runner[@]}" ctest --output-on-failure -j "$JOBS" -L "$labels" \
    "${left_out[@]}" --timeout 600 --repeat until-pass:"$attempts"); then
    # A long log is often read from its end: say there why each failed test failed.
    python3 "$ROOT/scripts/why_tests_failed.py" "$dir"
    return 1
  fi
}

# CI's other work (the sanitizer and fuzz builds, clang-tidy) runs beside the test stages, at
# SCHED_IDLE: the tests wait on their cycles and leave the CPU about 95 % idle (the plain
# tests' 7.7 min, vmstat, 2026-12-04), the builds and clang-tidy are CPU-bound (clang-tidy 17
# min on both cores). One after the other they took CI to 57-60 min against its 45; beside the
# tests they get only the CPU the tests leave, and a test's thread that wakes preempts them.
BACKGROUND_PID=""
LOGS=""
as_minutes() { printf '%d:%02d' $(($1 / 60)) $(($1 % 60)); }  # seconds as minutes:seconds
background_step() {  # name, command...: runs it, its output in $LOGS/name.log, its status in .rc
  local name=$1 start=$SECONDS
  shift
  "$@" >"$LOGS/$name.log" 2>&1
  echo $? >"$LOGS/$name.rc"
  echo "ran from $(as_minutes "$start") to $(as_minutes "$SECONDS")" >"$LOGS/$name.when"
}

# The sanitizer builds use clang: its front end, where the tests' compile time goes (parsing and
# templates, 80 % of servo_law_surface_test.cpp), took 5.6-16.0 s per test file against GCC's
# 10.2-24.0 s (ASan+UBSan -O1, three of the longest, 2026-12-07).
build_asan() {
  # Asserts on (EIGEN_NO_MALLOC), -O1: Eigen still fast enough.
  CC=clang CXX=clang++ configure_build build-asan -DHAPTICCTRL_SANITIZER=address,undefined \
    -DHAPTICCTRL_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DCMAKE_C_FLAGS_DEBUG="-O1 -g1"
}

build_tsan() {
  CC=clang CXX=clang++ configure_build build-tsan -DHAPTICCTRL_SANITIZER=thread \
    -DHAPTICCTRL_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
}

FUZZERS=(decoder arm-model config lcm-hmi web dds-input)  # the decoder first (fuzz_one's share)
build_fuzz() {
  CC=clang CXX=clang++ cmake -S "$ROOT" -B build-fuzz -G Ninja -DHAPTICCTRL_WERROR=ON \
    -DHAPTICCTRL_BUILD_FUZZ=ON -DHAPTICCTRL_BUILD_TESTS=OFF -DHAPTICCTRL_BUILD_BENCH=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "${LINES_ONLY[@]}" "${LLD[@]}" >/dev/null
  cmake --build build-fuzz -j "$JOBS" --target "${FUZZERS[@]/#/hapticctrl-fuzz-}"
}

fuzz_one() {  # name: fuzzes it for its share of FUZZ_SECONDS; its log's end if it crashed
  local name=$1 share=8 seconds corpus log
  # The protocol decoder faces the network: half of the time budget; the others an eighth each.
  [[ $name == decoder ]] && share=2
  seconds=$(( ${FUZZ_SECONDS:-90} / share ))
  corpus=$(mktemp -d)  # new inputs stay out of the repository's seed corpus
  log=$(mktemp)
  if ! "build-fuzz/tests/fuzz/hapticctrl-fuzz-$name" -max_total_time="$seconds" \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=build-fuzz/ \
    "$corpus" "tests/fuzz/corpus/$name" >"$log" 2>&1; then
    tail -n 60 "$log"
    echo "fuzzing $name found a crash (reproducer: the crash-* file above)" >&2
    return 1
  fi
  echo "$name: $(grep -E "^stat::number_of_executed_units" "$log") in $seconds s"
  rm -rf "$log" "$corpus"
}

fuzz_all() {  # the decoder on one core, the others one after the other on the other: half the time
  local decoder_pid status=0 name
  fuzz_one decoder &
  decoder_pid=$!
  for name in "${FUZZERS[@]:1}"; do
    fuzz_one "$name" || status=1
  done
  wait "$decoder_pid" || status=1
  echo "fuzzed ${#FUZZERS[@]} targets for ${FUZZ_SECONDS:-90} s"
  return $status
}

start_background() {
  LOGS=$(mktemp -d)
  (
    set +e
    # Lowering one's own policy needs no privilege; where it is refused, the lowest nice.
    chrt --idle -p 0 "$BASHPID" 2>/dev/null || renice -n 19 -p "$BASHPID" >/dev/null
    background_step build-asan build_asan
    background_step build-tsan build_tsan
    background_step lint scripts/lint.sh build
    background_step build-fuzz build_fuzz
    # The fuzzers' budget is wall time: beside the sanitizer tests they get the CPU those leave
    # (most of it), where at the end they held CI up for a minute more.
    [[ $(cat "$LOGS/build-fuzz.rc") == 0 ]] && background_step fuzz fuzz_all
  ) &
  BACKGROUND_PID=$!
}

wait_for() {  # name: until the background ran it (it ends, so this does); its log if it failed
  local name=$1
  while [[ ! -f $LOGS/$name.rc ]] && kill -0 "$BACKGROUND_PID" 2>/dev/null; do
    sleep 2
  done
  if [[ $(cat "$LOGS/$name.rc" 2>/dev/null) != 0 ]]; then
    tail -n 120 "$LOGS/$name.log"
    echo "$name failed (its log's end above)" >&2
    return 1
  fi
  stage "$name done, $(cat "$LOGS/$name.when"): $(tail -n 1 "$LOGS/$name.log")"
}

kill_tree() {  # pid: it and every process under it (a build's compilers, clang-tidy's workers)
  local child
  for child in $(pgrep -P "$1"); do
    kill_tree "$child"
  done
  kill -TERM "$1" 2>/dev/null || true
}

stop_background() {  # on any exit: nothing of the background outlives the script
  if [[ -n $BACKGROUND_PID ]]; then
    kill_tree "$BACKGROUND_PID"
    wait "$BACKGROUND_PID" 2>/dev/null || true
  fi
  [[ -z $LOGS ]] || rm -rf "$LOGS"
}

stage "build and test (RelWithDebInfo)"
configure_build build
CI_RUN=false
if [[ "${CI:-}" == "true" ]]; then
  CI_RUN=true
  trap 'stop_background; stop_load' EXIT
  start_background
fi
# Two attempts: on these 2 vCPUs without a real-time kernel a whole-VM stall of 50 ms or more
# now and then fails a timing-bound integration test of the plain build too (2026-12-02, a full
# run: the demo's core failed safe on 5 missed 10 ms deadlines, and two H1 cases measured a 1 ms
# link at 2.8 ms with 0.75 ms jitter and missed "still" by 10 %; the 1 ms case passed 14 times
# out of 14 alone). A functional failure fails both attempts.
run_tests build 'unit|sim|integration|bench' 2

if [[ $CI_RUN == true ]]; then
  # Sanitizer builds: a multi-process test whose instrumented core missed 5 deadlines in a row
  # on these 2 vCPUs (seen 2026-11-24, never in the plain build, which runs each test once) gets
  # up to 3 attempts; a functional failure still fails every attempt.
  wait_for build-asan
  run_tests build-asan 'unit|sim|integration' 3
  wait_for build-tsan
  # Not the browser tests: TSan sees the web bridge's threads raced by its own tests' pages
  # (WebServerTest, WebBridgeProcess), and Chromium drawing for 85 s took CPU from the background.
  run_tests build-tsan 'unit|sim|integration' 3 browser
  wait_for lint
  wait_for build-fuzz
  # The decoder, the arm model, the option parsers, LCM HMI input and web page input (libFuzzer).
  wait_for fuzz
fi
stage "all tests passed"
