#!/usr/bin/env python3
"""The coupling in contact's report (J1): reads OUT_DIR/raw/contact/*/ (bench/contact.sh) and
writes OUT_DIR/contact.md, contact.json and contact.png (gnuplot).

Per case (wall, command mode, one-way delay, loss, jitter through hapticctrl-netem):
- push (10 N into the wall): from 1 s to 3 s, the handle's largest speed over 50 ms windows,
  the mean force felt (the force rendered on the handle along the push, against it), and the
  cycles the coupling was at the saturation;
- hand (a spring-damper hand pressing 3 N into the wall and wandering): the energy the port to
  the hand put out (the rendered wrench times the handle's twist; positive: the port gave the
  hand energy) and the peak force;
- the two-port balance at rest: the core's end out against the client's reported in, and the
  client's end out (the demo's summary) against the core's in, each in mJ above it (<= 1: J1).
J1's bars beside them: < 5 mm/s, the push +-10 %, no cycle at the saturation, each end <= the
other's in + 1 mJ, the port <= 1 mJ. Only figures measured in this run; a case whose core
stopped says so.
"""
import json
import glob
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import coupling_report as cr  # noqa: E402  (the hmi log's readers, shared with H1's report)

PUSH_N = 10.0
SATURATED = 1 << 7  # shm::state_bits::kSaturated


def demo_summary(path):
    """The demo's summary: the last JSON line it printed (when it ended)."""
    try:
        lines = [ln for ln in open(path).read().splitlines() if "channel_energy_out" in ln]
        return json.loads(lines[-1]) if lines else {}
    except (OSError, ValueError):
        return {}


def push_figures(rows):
    judged = [r for r in rows if 1.0 <= float(r["t_s"]) < 3.0]
    if not judged:
        return {}
    felt = sum(float(r["ren_fx"]) for r in judged) / len(judged)
    return {
        "push_speed": cr.windowed_speed(rows, 1.0, 3.0),
        "felt_n": -felt,
        "saturated_cycles": sum(1 for r in judged if int(r["state_word"]) & SATURATED),
    }


def analyse(case_dir):
    push = cr.read_csv(os.path.join(case_dir, "push.csv"))
    hand = cr.read_csv(os.path.join(case_dir, "hand.csv"))
    status = cr.status_of(os.path.join(case_dir, "status.json"))
    client = status.get("client", {})
    summary = demo_summary(os.path.join(case_dir, "demo.json"))
    out = cr.case_record(case_dir, status, bool(
        push and hand and "channel_energy_in" in client and summary))
    if not out["judged"]:
        return out
    out.update(push_figures(push))
    pushed = cr.status_of(os.path.join(case_dir, "status_push.json")).get("client", {})
    out.update({
        "loop_delay_ms": client.get("loop_delay_ms"),
        "k_derived": pushed.get("gains", [0])[0],
        "k_normal": pushed.get("normal_gains", [0])[0],
        "port_energy_j": cr.port_energy(hand),
        "hand_peak_n": max(cr.force_of(r) for r in hand),
        "core_excess_j": client["channel_energy_out"] - client["client_energy_in"],
        "client_excess_j": summary["channel_energy_out"] - client["channel_energy_in"],
    })
    out["meets_j1"] = bool(
        out["push_speed"] < 0.005 and abs(out["felt_n"] - PUSH_N) <= 0.1 * PUSH_N
        and out["saturated_cycles"] == 0 and out["port_energy_j"] <= 1e-3
        and out["core_excess_j"] <= 1e-3 and out["client_excess_j"] <= 1e-3)
    return out


def row(c):
    head = (f"| {c['mode']} | {c['stiffness']} N/m | {c['delay_ms']} ms | {c['loss']:.0%} "
            f"| ±{c['jitter_ms']} ms |")
    if not c["judged"]:
        return head + " the core stopped or a phase is missing: not judged |" + " |" * 8 + \
            f" {cr.fmt(c['stalls_ridden'], 'd')} |"
    return head + (
        f" {cr.fmt(c['loop_delay_ms'], '.1f')} ms | {c['k_derived']:.0f} + {c['k_normal']:.0f} N/m"
        f" | {c['push_speed'] * 1e3:.2f} mm/s | {c['felt_n']:.2f} N | {c['saturated_cycles']} "
        f"| {c['port_energy_j'] * 1e3:.1f} mJ in {c['hand_s']} s | {c['hand_peak_n']:.1f} N "
        f"| {c['core_excess_j'] * 1e3:+.2f} mJ | {c['client_excess_j'] * 1e3:+.2f} mJ "
        f"| {'yes' if c['meets_j1'] else 'no'} | {cr.fmt(c['stalls_ridden'], 'd')} |")


def main(out):
    cases = [analyse(d) for d in sorted(glob.glob(os.path.join(out, "raw", "contact", "*")))
             if os.path.exists(os.path.join(d, "case.json"))]
    cases.sort(key=lambda c: (c["mode"], c["stiffness"], c["delay_ms"], c["loss"]))
    json.dump(cases, open(os.path.join(out, "contact.json"), "w"), indent=1)
    lines = [
        "## The coupling in contact (J1)",
        "",
        "The demo's sphere on a wall in its own physics (2 N.s/m), reported to the core as a",
        "contact (protocol 1.3), through hapticctrl-netem, 1 ms core. VIRTMECH: the sphere",
        "coupled to the handle; IMPEDANCE: the wall computed in the client, its wrench inside the",
        "two-port. The operator played by hapticctrl-hmi: 10 N into the wall (judged from 1 s to",
        "3 s), then a spring-damper hand (300 N/m, 5 N.s/m) pressing 3 N into it and wandering",
        "2 cm at 0.2-2 Hz. k: the coupling's derived stiffness + the contact's along its normal,",
        "while pushed (VIRTMECH).",
        "Balance at rest: each end's energy out above the other's in (J1: <= 1 mJ).",
        "",
        "| mode | wall | one way | loss | jitter | loop | k | speed pushed | felt (10 N) "
        "| cycles saturated | port out (hand) | hand's peak | core's end over | client's end over "
        "| J1's bars met | VM stalls ridden through |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [row(c) for c in cases]
    lines += ["", "![speed and felt force against delay](contact.png)", ""]
    open(os.path.join(out, "contact.md"), "w").write("\n".join(lines))
    plot(out, cases)
    print("\n".join(lines))


def plot(out, cases):
    judged = [c for c in cases if c["judged"]]
    if not judged:
        return
    series = []
    for mode, k in sorted({(c["mode"], c["stiffness"]) for c in judged}):
        data = os.path.join(out, "raw", "contact", f"{mode}_{k}.dat")
        with open(data, "w") as f:
            for c in judged:
                if (c["mode"], c["stiffness"]) == (mode, k):
                    f.write(f"{max(c['delay_ms'], 0.5)} {c['push_speed'] * 1e3} {c['felt_n']}\n")
        series.append((f"{mode} {k} N/m", data))
    plots = ", ".join(f"'{d}' using 1:2 with points pt 7 title 'speed pushed, {t}'"
                      for t, d in series)
    plots += ", " + ", ".join(f"'{d}' using 1:3 axes x1y2 with points pt 5 title 'felt, {t}'"
                              for t, d in series)
    script = "\n".join([
        "set terminal png size 900,500 noenhanced",
        f"set output '{os.path.join(out, 'contact.png')}'",
        "set title 'Pushed 10 N into a stiff wall: handle speed and felt force against delay'",
        "set xlabel 'one-way delay (ms; 0 plotted at 0.5)'", "set ylabel 'speed (mm/s)'",
        "set y2label 'felt force (N)'", "set y2tics", "set y2range [0:20]",
        "set xrange [0.3:150]", "set logscale xy", "set grid", "set key top left",
        "set arrow from graph 0, first 5 to graph 1, first 5 nohead dt 2",
        f"plot {plots}",
    ])
    subprocess.run(["gnuplot"], input=script, text=True, check=False)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench-report")
