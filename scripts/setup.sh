#!/usr/bin/env bash
# Installs every Debian package hapticctrl needs to build, test, run and benchmark.
# Idempotent, non-interactive, and silent when everything is already present.
set -euo pipefail

PACKAGES=(
  # toolchain
  g++ cmake ninja-build pkg-config clang clang-format libclang-rt-14-dev
  # the test command's linker (scripts/test.sh: a link in under half of ld.bfd's time)
  lld
  # the lint's clang-tidy (bookworm's 22, from its security suite: it skips the system headers'
  # AST, under half of version 14's time, .clang-tidy)
  clang-tidy-22
  # the real-time contract check (scripts/check_realtime.py) reads the AST through libclang
  python3-clang-14
  # design-card libraries
  libeigen3-dev liblcm-dev liblcm-bin liblcm-java libglib2.0-dev libtirpc-dev rpcsvc-proto zlib1g-dev
  libbenchmark-dev libgtest-dev libgmock-dev libncurses-dev
  # program scaffolding: every program's options (program/)
  libcli11-dev
  # monitoring, analysis and benchmarks
  default-jdk-headless libjchart2d-java gnuplot-nox rt-tests stress-ng procps util-linux python3
  # the peer benchmark (H8): iceoryx, its C++ API and its broker RouDi
  iceoryx libiceoryx-posh-dev libiceoryx-hoofs-dev
  # the multi-host tests (H7): network namespaces, and a page fetched from another host
  iproute2 curl
  # the DDS bridge (H7): Cyclone DDS, its IDL compiler, and ddsperf for a look at the wire
  cyclonedds-dev cyclonedds-tools
  # the installed systemd units are checked with systemd-analyze and systemd-sysusers
  systemd
  # the web view (bridges/web): HTTP/WebSocket server, JSON, and the browser its test drives
  civetweb libcivetweb-dev nlohmann-json3-dev chromium
  # the MuJoCo client (J3): the physics engine, and the Qhull headers its CMake target names
  libmujoco-dev libqhull-dev
)
# Node.js and npm install the web page's libraries (pinned by bridges/web/package-lock.json) at
# build time and run its browser test. A Node.js from elsewhere (NodeSource ships npm inside its
# nodejs package) is used as it is: Debian's npm package would conflict with it.
if ! command -v npm >/dev/null || ! command -v node >/dev/null; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed"; then
    missing+=("$pkg")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "setup: installing ${missing[*]}" >&2
SUDO=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null; then
    SUDO=(sudo)
  else
    echo "setup: need root to install: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
