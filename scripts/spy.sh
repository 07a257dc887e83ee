#!/usr/bin/env bash
# Starts lcm-spy with the project's type jar, so every hapticctrl channel decodes field by field.
# (Debian's /usr/bin/lcm-spy passes -Xincgc, which Java 17 rejects: the class is started
# directly. The chart view needs libjchart2d-java.)
#
# usage: scripts/spy.sh [--build DIR] [--lcm-url URL]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build
URL='udpm://239.255.76.67:7667?ttl=0'
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) BUILD=$2; shift 2 ;;
    --lcm-url) URL=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 64 ;;
  esac
done
JAR=$BUILD/lcmtypes/hapticctrl_lcmtypes.jar
if [[ ! -f $JAR ]]; then
  scripts/setup.sh
  cmake -S . -B "$BUILD" -G Ninja >/dev/null
  cmake --build "$BUILD" --target hapticctrl_lcmtypes_jar
fi
exec java -Djava.net.preferIPv4Stack=true \
  -cp "/usr/share/java/lcm.jar:/usr/share/java/jchart2d.jar:$JAR" lcm.spy.Spy --lcm-url="$URL"
