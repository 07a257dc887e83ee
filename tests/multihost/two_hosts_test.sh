#!/usr/bin/env bash
# H7, beyond one host: the project's own test hosts, made of network namespaces joined by veth
# links (created and removed here), with the real programs. "ctl" runs the core and its bridges,
# "lab" is a client's workstation and monitor, "out" a machine the bridge was not told to serve.
#  1. a remote client couples through hapticctrl-udp --bind ... --allow-remote --allow-client;
#  2. a client outside the allow-list is never answered;
#  3. LCM telemetry with ttl=1 reaches an lcm-logger on the other host, every channel;
#  4. the web view is served beyond loopback only when asked (--allow-remote);
#  5. hapticctrl-netem on the link (20 ms one way): the remote client still couples;
#  6. hapticctrl-dds: a DDS subscriber on the lab host (hapticctrl-dds-listen, ROS 2's type and
#     topic names, Cyclone DDS's default discovery) gets every topic, and its operator wrench
#     goes back through the core.
# Needs root for namespaces: exits 77 (ctest: skipped) with the reason where there is none.
# usage: two_hosts_test.sh BUILD_DIR
set -euo pipefail
BUILD=$1
fail() {
  echo "two hosts: $*" >&2
  exit 1
}
skip() {
  echo "two hosts: skipped: $*" >&2
  exit 77
}
[[ $(id -u) -eq 0 ]] || skip "network namespaces need root (CI runs as root)"
command -v ip >/dev/null || skip "the ip command (iproute2) is missing"

TAG=$$
NET=10.$((200 + TAG % 50)).$(((TAG / 50) % 250)).
CTL=hc-ctl-$TAG LAB=hc-lab-$TAG OUTSIDE=hc-out-$TAG
OUT=$(mktemp -d)
export HAPTICCTRL_RUNTIME_DIR=$OUT/runtime HAPTICCTRL_INSTANCE=twohosts$TAG
mkdir -p "$HAPTICCTRL_RUNTIME_DIR"
PIDS=()
cleanup() {
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  # Whatever still runs in a test host goes with it (a namespace lives as long as a process in it).
  for ns in "$CTL" "$LAB" "$OUTSIDE"; do
    for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
  done
  for ns in "$CTL" "$LAB" "$OUTSIDE"; do ip netns del "$ns" 2>/dev/null || true; done
  ip link del "hcb$TAG" 2>/dev/null || true
  rm -rf "$OUT"
}
trap cleanup EXIT
on() {  # namespace command...
  local ns=$1
  shift
  ip netns exec "$ns" "$@"
}

# The hosts: three namespaces on one bridge, each with its own address.
ip netns add "$CTL" 2>/dev/null || skip "ip netns add is not permitted here"
ip netns add "$LAB"
ip netns add "$OUTSIDE"
ip link add "hcb$TAG" type bridge
ip link set "hcb$TAG" up
host=1
for ns in "$CTL" "$LAB" "$OUTSIDE"; do
  ip link add "hc$host-$TAG" type veth peer name eth0 netns "$ns"
  ip link set "hc$host-$TAG" master "hcb$TAG" up
  on "$ns" ip addr add "$NET$host/24" dev eth0
  on "$ns" ip link set eth0 up
  on "$ns" ip link set lo up
  on "$ns" ip route add 224.0.0.0/4 dev eth0  # LCM's multicast leaves by the link
  host=$((host + 1))
done
CTL_IP=${NET}1 LAB_IP=${NET}2

wait_for() {  # file pattern seconds
  for _ in $(seq 1 $(($3 * 20))); do
    grep -q "$2" "$1" 2>/dev/null && return 0
    sleep 0.05
  done
  return 1
}
start() {  # namespace log command...
  local ns=$1 log=$2
  shift 2
  # Not through on(): a function in the background is a subshell, and its pid would be the one
  # recorded; `ip netns exec` execs the program, so $! is the program itself.
  ip netns exec "$ns" "$@" >"$log" 2>&1 &
  PIDS+=($!)
}

# The controller host: core, UDP bridge for the lab host only, LCM bridge at ttl=1.
start "$CTL" "$OUT/core.log" "$BUILD/rt_core/hapticctrl-core" --instance "$HAPTICCTRL_INSTANCE" \
  --period-us 4000 --benchmark-mode --rt ignore
for _ in $(seq 1 100); do
  [[ -S $HAPTICCTRL_RUNTIME_DIR/$HAPTICCTRL_INSTANCE.sock ]] && break
  sleep 0.05
done
start "$CTL" "$OUT/udp.log" "$BUILD/bridges/udp/hapticctrl-udp" --instance "$HAPTICCTRL_INSTANCE" \
  --bind "$CTL_IP" --port 0 --allow-remote --allow-client "$LAB_IP"
wait_for "$OUT/udp.log" "listening on $CTL_IP:" 5 || fail "the bridge did not listen: $(cat "$OUT/udp.log")"
PORT=$(sed -n "s/.*listening on $CTL_IP:\([0-9]*\).*/\1/p" "$OUT/udp.log" | head -n 1)

# 1. The remote client couples.
on "$LAB" "$BUILD/demo/hapticctrl-demo" --server "$CTL_IP:$PORT" --headless --no-lcm --json \
  --duration 3 >"$OUT/demo.json" 2>"$OUT/demo.err" || fail "the remote demo failed: $(cat "$OUT/demo.err")"
python3 - "$OUT/demo.json" <<'PY' || fail "the remote client did not couple: $(cat "$OUT/demo.json")"
import json, sys
d = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
assert d["steps"] > 100 and d["answers_received"] > 100 and d["powered"], d
PY
echo "two hosts: a client on $LAB_IP coupled to the controller on $CTL_IP:$PORT"

# 2. A host outside the allow-list gets no answer at all (the demo says so and gives up at the end
# of its duration).
on "$OUTSIDE" "$BUILD/demo/hapticctrl-demo" --server "$CTL_IP:$PORT" --headless --no-lcm --json \
  --duration 3 >"$OUT/outside.out" 2>&1 || true
grep -q "no answer from a hapticctrl controller at $CTL_IP:$PORT" "$OUT/outside.out" ||
  fail "the client outside the allow-list was not left unanswered: $(cat "$OUT/outside.out")"
if grep -q '"steps":[1-9]' "$OUT/outside.out"; then
  fail "a client outside the allow-list was served: $(cat "$OUT/outside.out")"
fi
echo "two hosts: a client on ${NET}3 (outside --allow-client) got no answer"

# 3. LCM telemetry at ttl=1 reaches a logger on the lab host, every channel.
URL="udpm://239.255.76.67:7667?ttl=1"
start "$LAB" "$OUT/logger.log" lcm-logger --lcm-url="$URL" "$OUT/telemetry.lcm"
sleep 0.5
start "$CTL" "$OUT/lcm.log" "$BUILD/bridges/lcm/hapticctrl-lcm" --instance "$HAPTICCTRL_INSTANCE" \
  --lcm-url "$URL" --duration 2
sleep 2.5
"$BUILD/bridges/lcm/hapticctrl-log2csv" --log "$OUT/telemetry.lcm" --out "$OUT/csv" >"$OUT/log2csv.out" 2>&1 ||
  fail "the lab host's LCM log could not be read: $(cat "$OUT/log2csv.out")"
for channel in arm_state cycle_stats coupling bridge_stats; do
  compgen -G "$OUT/csv/*.$channel.csv" >/dev/null ||
    fail "the lab host's logger never got $channel: $(ls "$OUT/csv")"
done
echo "two hosts: LCM at ttl=1 reached the lab host's lcm-logger: $(ls "$OUT/csv" | tr '\n' ' ')"

# 4. The web view: loopback unless asked; beyond it with --allow-remote.
if on "$CTL" "$BUILD/bridges/web/hapticctrl-web" --instance "$HAPTICCTRL_INSTANCE" \
  --listen "$CTL_IP:0" --duration 1 >"$OUT/web-refused.out" 2>&1; then
  fail "the web view listened beyond loopback without --allow-remote"
fi
start "$CTL" "$OUT/web.log" "$BUILD/bridges/web/hapticctrl-web" --instance "$HAPTICCTRL_INSTANCE" \
  --listen "$CTL_IP:0" --allow-remote
wait_for "$OUT/web.log" "listening on http://$CTL_IP:" 5 || fail "the web view did not listen: $(cat "$OUT/web.log")"
WEB=$(grep -o "http://$CTL_IP:[0-9]*" "$OUT/web.log" | head -n 1)
on "$LAB" curl -sf -m 5 "$WEB/" >"$OUT/page.html" || fail "the lab host could not load $WEB/"
grep -qi "<html" "$OUT/page.html" || fail "the lab host got no page from $WEB/"
echo "two hosts: the web view at $WEB served the lab host, and only with --allow-remote"

# 5. hapticctrl-netem on the link (20 ms each way), on the lab host in front of its client: the
# bridge sees the lab host's address, so the allow-list still serves it.
start "$LAB" "$OUT/netem.log" "$BUILD/bench/netem/hapticctrl-netem" --listen 127.0.0.1:0 \
  --to "$CTL_IP:$PORT" --delay-ms 20 --allow-remote
wait_for "$OUT/netem.log" "listening on 127.0.0.1:" 5 || fail "netem did not listen: $(cat "$OUT/netem.log")"
RELAY=$(sed -n "s/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p" "$OUT/netem.log" | head -n 1)
on "$LAB" "$BUILD/demo/hapticctrl-demo" --server "127.0.0.1:$RELAY" --headless --no-lcm --json \
  --duration 3 >"$OUT/delayed.json" 2>"$OUT/delayed.err" ||
  fail "the demo through netem failed: $(cat "$OUT/delayed.err")"
python3 - "$OUT/delayed.json" <<'PY' || fail "no coupling over the delayed link: $(cat "$OUT/delayed.json")"
import json, sys
d = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
assert d["steps"] > 50 and d["rtt_mean_us"] > 40000, d
PY
echo "two hosts: the remote client coupled through hapticctrl-netem (20 ms each way)"
# 6. DDS across hosts, in ROS 2's default domain, with Cyclone DDS's default configuration (each
# host's one interface, multicast discovery), as two ROS 2 machines would be set up.
unset CYCLONEDDS_URI ROS_DOMAIN_ID
start "$CTL" "$OUT/dds.log" "$BUILD/bridges/dds/hapticctrl-dds" --instance "$HAPTICCTRL_INSTANCE" \
  --namespace /lab/arm --allow-remote-commands --json
on "$LAB" "$BUILD/bridges/dds/hapticctrl-dds-listen" --namespace /lab/arm --duration 4 \
  --wrench 3,0,0,0,0,0 >"$OUT/dds.json" 2>"$OUT/dds-listen.err" ||
  fail "the lab host's DDS listener failed: $(cat "$OUT/dds-listen.err")"
python3 - "$OUT/dds.json" <<'PY' || fail "DDS did not cross hosts: $(cat "$OUT/dds.json") $(cat "$OUT/dds.log")"
import json, sys
d = json.loads(open(sys.argv[1]).read())
types = {"handle_pose": "geometry_msgs::msg::dds_::PoseStamped_",
         "rendered_wrench": "geometry_msgs::msg::dds_::WrenchStamped_",
         "operator_wrench": "geometry_msgs::msg::dds_::WrenchStamped_",
         "joint_states": "sensor_msgs::msg::dds_::JointState_",
         "diagnostics": "diagnostic_msgs::msg::dds_::DiagnosticArray_"}
for topic, t in types.items():
    assert d[topic + "_type"] == t and d[topic + "_count"] > 0, (topic, d)
assert d["handle_pose_count"] > 100 and d["joint_states_rate_hz"] > 50, d
assert abs(d["operator"][0] - 3.0) < 1e-6, d["operator"]
PY
echo "two hosts: a DDS subscriber on $LAB_IP got every ROS 2 topic of the controller on $CTL_IP" \
  "($(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print("pose %d at %.0f Hz, age p50 %.0f us" % (d["handle_pose_count"], d["handle_pose_rate_hz"], d["handle_pose_age_p50_us"]))' "$OUT/dds.json")), and its wrench came back"
echo "two hosts: ok"
