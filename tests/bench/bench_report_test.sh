#!/usr/bin/env bash
# Smoke test of the system benchmark (label bench): scripts/bench.sh --smoke (1 s runs) must
# produce a well-formed report, results.json and PNG plots. No timing thresholds here: the
# figures are the report's business.
# usage: bench_report_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
BUILD=$1 SOURCE=$2
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
# In a terminal, as a user runs it (a pseudo-terminal of 24 rows from script(1)): nothing may
# wait on it (J8: --smoke in a terminal once waited 2 min or more for gnuplot's pager).
printf -v run '%q ' "$SOURCE/scripts/bench.sh" --smoke --build "$BUILD" --out "$OUT"
timeout 540 script -qec "stty rows 24 cols 80; $run >$(printf %q "$OUT/bench.log") 2>&1" /dev/null </dev/null ||
  { echo "bench.sh --smoke in a terminal failed or waited (status $?)"; cat "$OUT/bench.log"; exit 1; }
python3 - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
report = open(os.path.join(out, "report.md"), encoding="utf-8").read()
for heading in ("## The seeds' requirements", "## 1. Wake-up latency", "## 2. SERVO start delay",
                "## 3. End to end at 1 kHz", "## 4. Micro-benchmarks",
                "## 5. Side by side with the peers",
                "## Coupling over an impaired link (H1)", "## The coupling in contact (J1)",
                "## Local contact models (J2)",
                "## The weighted sphere at rest (H1)"):
    assert heading in report, f"report.md lacks '{heading}'"
assert "The DDS path (H7" in report and "against LCM" in report and "against UDP" in report
for period in (1000, 250, 100):
    assert report.count(f"| {period} us | ") >= 4, f"report.md lacks the {period} us rows"
r = json.load(open(os.path.join(out, "results.json"), encoding="utf-8"))
for key in ("machine", "latency", "servo_start_floor", "link", "micro_ns", "requirements", "plots"):
    assert key in r, f"results.json lacks {key}"
assert r["machine"]["cpus"] >= 1 and "kernel" in r["machine"]
for period in ("1000", "250", "100"):
    for load in ("idle", "load"):
        run = r["latency"][period][load]
        assert run["core"]["samples"] > 0, f"no core samples at {period} us {load}"
        assert run["cyclictest"]["samples"] > 0, f"no cyclictest samples at {period} us {load}"
        assert run["cycles"] is not None, f"the core reported nothing at {period} us {load}"
        # Benchmark mode: the core covers cyclictest's window whatever it rode through (a core
        # that failed safe after 65 cycles was once compared with 8 s of cyclictest). Stalls of
        # this VM skip some of the core's slots (cyclictest samples each one late): 0.75 leaves
        # room for a 250 ms stall in a 1 s smoke run.
        assert run["would_fail_safe"] is not None, f"no would-be fail-safe count at {period} us {load}"
        assert run["samples_ratio"] >= 0.75, (period, load, run["core"], run["cyclictest"])
        assert run["cyclictest_stalls_5_periods"] is not None
for load in ("idle", "load"):
    link = r["link"][load]
    # A core that fails safe on a noisy machine is a result the report states, not a defect.
    if "FAIL-SAFE" not in link["core_ended"]:
        assert link["figures"].get("answers", 0) > 0, f"no answers in the {load} link run"
        assert link["client_rtt"]["samples"] > 0 and link["udp_rtt"]["samples"] > 0
assert r["servo_start_floor"].get("samples", 0) > 0
for name in ("BM_SeqlockRead", "BM_EncodeAnswer", "BM_DecodeAnswer", "BM_FullCycle1ms"):
    assert r["micro_ns"].get(name, 0) > 0, f"micro-benchmark {name} missing"
assert len(r["requirements"]) == 4 and all(isinstance(q["met"], bool) for q in r["requirements"])
cases = json.load(open(os.path.join(out, "coupling.json"), encoding="utf-8"))
assert len(cases) == 1, f"the smoke run has one coupling case, not {len(cases)}"
for c in cases:
    # The core runs in benchmark mode: every case is judged, with the stalls it rode through.
    assert c["judged"], c
    assert c["stalls_ridden"] is not None and c["loop_delay_ms"] > 0 and c["k_derived"] > 0, c
    for key in ("speed_after_settling", "port_energy_j", "contact_held", "fade_ms",
                "recouple_ms", "speed_after_return"):
        assert c.get(key) is not None, (key, c)
    assert not c["contact_held"] or c["k_rendered"] > 0 and c["penetration_mm"] > 0, c
# The coupling in contact (J1): both smoke cases judged, every figure measured, and the plot.
walls = json.load(open(os.path.join(out, "contact.json"), encoding="utf-8"))
assert sorted((c["mode"], c["stiffness"]) for c in walls) == [("impedance", 2000),
                                                                ("virtmech", 3000)], walls
for c in walls:
    assert c["judged"], c
    for key in ("push_speed", "felt_n", "saturated_cycles", "port_energy_j", "core_excess_j",
                "client_excess_j", "meets_j1", "stalls_ridden"):
        assert c.get(key) is not None, (key, c)
# Local contact models (J2): the smoke case, every run judged and every figure measured.
local = json.load(open(os.path.join(out, "local.json"), encoding="utf-8"))
assert [c["delay_ms"] for c in local] == [100], local
for c in local:
    assert all(c["judged"].values()), c
    for key in ("k_ratio", "pen10_mm", "jump_step_n", "jump_energy_j", "mu", "blackout_min_n",
                "port_energy_j", "saturated_cycles"):
        assert c["wall"].get(key) is not None, (key, c)
    assert c["sphere"]["k_ratio"] is not None and c["soft"]["k_ratio"] is not None, c
    assert c.get("meets_j2") is not None, c
with open(os.path.join(out, "contact.png"), "rb") as f:
    assert f.read(8) == b"\x89PNG\r\n\x1a\n", "contact.png is not a PNG"
# The peers (H8): every transport and read mode measured in the same run, none left out.
peers = r["peers"]["cases"]
names = sorted((c["transport"], c["mode"]) for c in peers)
assert names == [("dds", "wake"), ("iceoryx", "poll"), ("iceoryx", "wake"), ("lcm", "wake"),
                 ("seqlock", "poll"), ("seqlock", "wake"), ("udp", "wake")], names
for c in peers:
    assert not c["error"], c
    # "delivered" is the share of messages a reader observed as the newest: a reader woken late
    # finds several and keeps the newest (CI, 2026-12-02: LCM woken 88 % on a loaded machine).
    # How much is a measurement the report states; the smoke run asserts only that it was made.
    assert c["latency_us"]["p50"] > 0 and c["latency_us"]["delivered"] > 0, c
    assert c["publish_ns"]["p50"] > 0 and c["read_ns"]["p50"] > 0, c
    assert c["cpu_us_per_1000"]["10000"]["messages"] > 0, c
    assert c["stall"]["stopped"]["publishes"] > 0 and c["stall"]["killed"]["publishes"] > 0, c
assert os.path.getsize(os.path.join(out, r["peers_plot"])) > 0
rest = json.load(open(os.path.join(out, "gravity.json"), encoding="utf-8"))
assert rest["judged"] and rest["seconds"] > 15 and rest["stalls_ridden"] is not None, rest
assert rest["chatter"] is not None and rest["weight_n"] > 0, rest
engine = json.load(open(os.path.join(out, "mujoco.json"), encoding="utf-8"))
assert len(engine) >= 5 and all("error" not in e for e in engine), engine
assert all(e["steps"] > 0 and e["cpu_us_mean"] > 0 for e in engine), engine
assert "hapticctrl-mujoco: the shipped scenes" in report, "report.md lacks the MuJoCo section"
assert len(r["plots"]) == 4
for png in r["plots"]:
    with open(os.path.join(out, png), "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n", f"{png} is not a PNG"
print("bench report: well-formed")
PY
