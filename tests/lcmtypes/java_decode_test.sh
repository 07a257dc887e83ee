#!/usr/bin/env bash
# The Java jar (lcm-spy's types) decodes a log written by the C++ side.
# usage: java_decode_test.sh WRITER JAR SOURCE_DIR
set -euo pipefail
writer=$1 jar=$2 src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$writer" "$work/run.lcmlog"
cp=/usr/share/java/lcm.jar:$jar
javac -nowarn -cp "$cp" -d "$work" "$src/tests/lcmtypes/DecodeLog.java"
out=$(java -cp "$cp:$work" DecodeLog "$work/run.lcmlog")
echo "$out"
expected='arm_states=5 undecodable=1 last_x=0.5 histogram_bin5=120 last_event=fail-safe: 5 consecutive deadline misses, "black box" written'
[[ "$out" == "$expected" ]] || { echo "expected: $expected" >&2; exit 1; }
