#!/usr/bin/env bash
# The package as a machine gets it: `cmake --install` into a staging root, every systemd unit
# checked by systemd-analyze verify against the staged programs (a warning fails too), the
# sysusers file by systemd-sysusers, and each installed program answering --help.
# usage: install_test.sh BUILD_DIR
set -euo pipefail
BUILD=$1
fail() {
  echo "install test: $*" >&2
  exit 1
}
for tool in systemd-analyze systemd-sysusers; do
  command -v "$tool" >/dev/null || fail "$tool is missing (scripts/setup.sh installs systemd)"
done
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
DESTDIR=$stage cmake --install "$BUILD" >/dev/null
prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$BUILD/CMakeCache.txt")
root=$stage$prefix

for program in core udp lcm log2csv web hmi demo dds dds-listen; do
  "$root/bin/hapticctrl-$program" --help >/dev/null 2>&1 || fail "hapticctrl-$program --help failed"
done
[[ -f $root/share/hapticctrl/models/virtuose6d_class.arm ]] || fail "the arm model is not installed"
[[ -f $root/share/hapticctrl/www/index.html ]] || fail "the web page is not installed"
[[ -f $root/share/doc/hapticctrl/deployment.md ]] || fail "docs/deployment.md is not installed"

# The units name the installed paths; systemd-analyze checks that each ExecStart exists, so the
# copies it reads point into the staging root.
units=$stage/units
mkdir "$units"
for unit in "$root"/lib/systemd/system/hapticctrl-*@.service; do
  sed "s|$prefix/|$root/|g" "$unit" >"$units/$(basename "$unit")"
done
[[ $(ls "$units" | wc -l) -eq 5 ]] || fail "expected 5 units, found: $(ls "$units")"
instances=()
for unit in "$units"/*@.service; do
  instances+=("${unit%@.service}@lab.service")
done
report=$(systemd-analyze verify --man=no "${instances[@]}" 2>&1) || fail "$report"
[[ -z $report ]] || fail "systemd-analyze verify warns: $report"
grep -q "^Restart=no" "$units/hapticctrl-core@.service" ||
  fail "the core's unit must not restart a core that failed safe"

report=$(systemd-sysusers --dry-run "$root/lib/sysusers.d/hapticctrl.conf" 2>&1) || fail "$report"
echo "install test: 5 units verified, sysusers file valid, 9 programs installed under $prefix"
