#!/usr/bin/env python3
"""The coupling benchmark's report (H1): reads OUT_DIR/raw/coupling/*/ (bench/coupling.sh) and
writes OUT_DIR/coupling.md, coupling.json and coupling.png (gnuplot).

Per case (one-way delay, loss, jitter through hapticctrl-netem; the demo's sphere, a free body; an
operator's 3 N force steps along y; a 0.3 s blackout):
- speed after settling: the handle's displacement over 50 ms windows, 1 s after each release,
- energy the coupling port put out: the time integral, from 1 s on, of the wrench the coupling
  rendered on the handle times the handle's velocity (positive: the port gave the hand energy),
- the stiffness the core derived for the measured loop, beside the sampled-data bound
  K_max = 2 (b + B) / (T (1 + 2 d)) for T = 1 ms, b + B the coupling's damping, d the measured
  loop in cycles (../shared/HAPTICS_REFERENCE.md); the stiffness actually rendered against an
  obstacle is not measured yet,
- time to fade after the link is lost: from the last fresh sample (5 ms before the core flags
  the link stale) to the first cycle without coupling force, and the largest force step then.
Only figures measured in this run; a case whose core failed safe on every attempt says so.
"""
import csv
import glob
import json
import math
import os
import subprocess
import sys

PERIOD_S = 1e-3


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def windowed_speed(rows, t0, t1, window=50):
    """Largest handle displacement over `window` cycles divided by its duration, t0 <= t < t1."""
    pts = [(int(r["cycle"]), float(r["x"]), float(r["y"]), float(r["z"]))
           for r in rows if t0 <= float(r["t_s"]) < t1]
    best, j = 0.0, 0
    for i in range(len(pts)):
        while pts[i][0] - pts[j][0] > window:
            j += 1
        gap = pts[i][0] - pts[j][0]
        if gap >= window // 2:
            d = math.dist(pts[i][1:], pts[j][1:])
            best = max(best, d / (gap * PERIOD_S))
    return best


def port_energy(rows):
    """Integral of (-coupling on the object) . handle velocity, in J."""
    energy = 0.0
    for a, b in zip(rows, rows[1:]):
        gap = int(b["cycle"]) - int(a["cycle"])
        if gap <= 0:
            continue
        dt = gap * PERIOD_S
        v = [(float(b[k]) - float(a[k])) / dt for k in ("x", "y", "z")]
        w = [-float(b[k]) for k in ("cpl_fx", "cpl_fy", "cpl_fz")]
        energy += sum(wi * vi for wi, vi in zip(w, v)) * dt
    return energy


def fade(rows, after_t):
    """From the last fresh sample before the longest stale run after `after_t` (the blackout;
    a lost frame or two can flag a cycle stale too) to the first cycle without coupling force."""
    runs, start = [], None
    for i, r in enumerate(rows):
        stale = float(r["t_s"]) >= after_t and int(r["state_word"]) & (1 << 5)
        if stale and start is None:
            start = i
        if not stale and start is not None:
            runs.append((i - start, start))
            start = None
    if start is not None:
        runs.append((len(rows) - start, start))
    if not runs:
        return None, None
    first = max(runs)[1]
    last_fresh = int(rows[first]["cycle"]) - 5
    start = next((i for i, r in enumerate(rows) if int(r["cycle"]) >= last_fresh), first)
    for i in range(start, len(rows)):
        f = math.hypot(*(float(rows[i][k]) for k in ("cpl_fx", "cpl_fy", "cpl_fz")))
        if f < 1e-6:
            steps = []
            for a, b in zip(rows[start:i + 1], rows[start + 1:i + 1]):
                gap = max(1, int(b["cycle"]) - int(a["cycle"]))
                d = math.dist([float(a[k]) for k in ("cpl_fx", "cpl_fy", "cpl_fz")],
                              [float(b[k]) for k in ("cpl_fx", "cpl_fy", "cpl_fz")])
                steps.append(d / gap)
            return (int(rows[i]["cycle"]) - last_fresh) * PERIOD_S * 1e3, max(steps, default=0.0)
    return None, None


def analyse(case_dir):
    case = json.load(open(os.path.join(case_dir, "case.json")))
    rows = read_csv(os.path.join(case_dir, "cycles.csv"))
    try:
        status = json.load(open(os.path.join(case_dir, "status.json")))
        client = status.get("client", {})
    except (OSError, ValueError):
        client = {}
    failed = not rows or "FAIL-SAFE" in open(os.path.join(case_dir, "core.err")).read()
    out = dict(case)
    out["judged"] = not failed
    if failed:
        return out
    gains = client.get("gains", [0, 0, 0, 0])
    loop_ms = client.get("loop_delay_ms", 0.0)
    d = loop_ms * 1e-3 / PERIOD_S
    b = gains[1]
    out.update({
        "loop_delay_ms": loop_ms,
        "link_delay_ms": client.get("link_delay_ms"),
        "link_loss_measured": client.get("link_loss"),
        "k_derived": gains[0],
        "b_derived": b,
        "k_max_bound": 2 * b / (PERIOD_S * (1 + 2 * d)) if b > 0 else None,
        "speed_after_settling": max(windowed_speed(rows, 4.5, 5.5), windowed_speed(rows, 8.5, 9.4)),
        "port_energy_j": port_energy([r for r in rows if float(r["t_s"]) >= 1.0]),
        "channel_energy_out_j": client.get("channel_energy_out"),
    })
    out["fade_ms"], out["fade_largest_step_n"] = fade(rows, 9.0)
    return out


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def main(out):
    cases = [analyse(d) for d in sorted(glob.glob(os.path.join(out, "raw", "coupling", "*")))
             if os.path.exists(os.path.join(d, "case.json"))]
    cases.sort(key=lambda c: (c["delay_ms"], c["loss"]))
    json.dump(cases, open(os.path.join(out, "coupling.json"), "w"), indent=1)
    lines = [
        "## Coupling over an impaired link (H1)",
        "",
        "The demo's 0.5 kg sphere (a free body) through hapticctrl-netem, 1 ms core, an operator's 3 N",
        "steps along y (hapticctrl-hmi play), a 0.3 s blackout. K_max = 2(b+B)/(T(1+2d)) with",
        "T = 1 ms, b+B the coupling's damping, d the measured loop in cycles.",
        "",
        "| one way | loss | jitter | loop | k derived | K_max | speed after settling "
        "| port energy out | fade after loss | largest step while fading | VM-stall retries |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in cases:
        if not c["judged"]:
            lines.append(f"| {c['delay_ms']} ms | {c['loss']:.0%} | ±{c['jitter_ms']} ms | "
                         f"the core failed safe on VM stalls in every attempt: not judged |"
                         + " |" * 7 + f" {c['attempts_lost']} |")
            continue
        lines.append(
            f"| {c['delay_ms']} ms | {c['loss']:.0%} | ±{c['jitter_ms']} ms | "
            f"{fmt(c['loop_delay_ms'], '.1f')} ms | {fmt(c['k_derived'], '.0f')} N/m | "
            f"{fmt(c['k_max_bound'], '.0f')} N/m | "
            f"{fmt(c['speed_after_settling'] * 1e3, '.1f')} mm/s | "
            f"{fmt(c['port_energy_j'] * 1e3, '.1f')} mJ | {fmt(c['fade_ms'], '.0f')} ms | "
            f"{fmt(c['fade_largest_step_n'], '.2f')} N | {c['attempts_lost']} |")
    lines += ["", "![stiffness against delay](coupling.png)", ""]
    open(os.path.join(out, "coupling.md"), "w").write("\n".join(lines))
    plot(out, cases)
    print("\n".join(lines))


def plot(out, cases):
    judged = [c for c in cases if c["judged"] and c.get("k_derived")]
    if not judged:
        return
    data = os.path.join(out, "raw", "coupling", "stiffness.dat")
    with open(data, "w") as f:
        for c in judged:
            f.write(f"{max(c['loop_delay_ms'], 0.1)} {c['k_derived']} {c['k_max_bound'] or 0}\n")
    script = "\n".join([
        "set terminal png size 900,500 noenhanced",
        f"set output '{os.path.join(out, 'coupling.png')}'",
        "set title 'Coupling stiffness against the measured loop delay'",
        "set xlabel 'coupling loop delay (ms)'", "set ylabel 'stiffness (N/m)'",
        "set logscale xy", "set grid", "set key top right",
        f"plot '{data}' using 1:3 with linespoints title 'K_max = 2(b+B)/(T(1+2d))', "
        f"'{data}' using 1:2 with points pt 7 title 'k derived'",
    ])
    subprocess.run(["gnuplot"], input=script, text=True, check=False)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench-report")
