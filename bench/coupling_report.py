#!/usr/bin/env python3
"""The coupling benchmark's report (H1): reads OUT_DIR/raw/coupling/*/ (bench/coupling.sh) and
writes OUT_DIR/coupling.md, coupling.json and coupling.png (gnuplot).

Per case (one-way delay, loss, jitter through hapticctrl-netem; the demo's sphere, a free body):
- contact (2 N then 4 N along +x onto the fixed sphere): the handle's penetration past the
  contact surface under 4 N against F / K_series, K_series = 1 / (1/K_contact + 1/k) with k the
  coupling's stiffness as the core derived it, and the stiffness actually rendered, the change
  of force over the change of position between the two plateaus (1 s means),
- steps (3 N along y, released, the hand holding the handle): the handle's speed after
  settling, its displacement over 50 ms windows 1 s after each release,
- hand (a spring-damper hand wandering at random): the energy the coupling port put out, the
  time integral of the wrench the coupling rendered on the handle times the handle's twist
  (positive: the port gave the hand energy),
- blackout (0.3 s, a hand holding the handle and pressing 2 N onto the fixed sphere): the time
  to fade, from the last fresh sample (5 ms before the core flags the link stale) to the first
  cycle of the main SERVO without coupling force, the largest step of the wrench rendered on
  the handle then, the time from the first fresh sample until that wrench is back to 90 % of
  what it was before, and the handle's peak speed (20 ms windows) in the second after the link
  returned,
- the largest force rendered on the handle in any phase (the saturation is 35 N),
- beside them the sampled-data bound K_max = 2 (b + B) / (T (1 + 2 d)) for T = 1 ms, b + B the
  coupling's damping, d the measured loop in cycles (../shared/HAPTICS_REFERENCE.md).
The core runs in benchmark mode (this VM stalls every few seconds): the stalls it rode through,
each a would-be fail-safe, are counted per case. Only figures measured in this run; a case
whose core stopped says so.
"""
import csv
import glob
import json
import math
import os
import re
import subprocess
import sys

PERIOD_S = 1e-3
K_CONTACT = 2000.0  # N/m, the demo's contact stiffness (bench/coupling.sh passes it)
RADII = 0.06        # m, the demo's two spheres' radii: the handle touches at fixed x - RADII
PUSHES = (2.0, 4.0)  # N, the contact phase's two plateaus (bench/coupling.sh)


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def windowed_speeds(rows, window=50):
    """(t, speed) per row: the handle's displacement over up to `window` cycles (at least half
    of it) divided by its duration."""
    pts = [(int(r["cycle"]), float(r["t_s"]), float(r["x"]), float(r["y"]), float(r["z"]))
           for r in rows]
    out, j = [], 0
    for i in range(len(pts)):
        while pts[i][0] - pts[j][0] > window:
            j += 1
        gap = pts[i][0] - pts[j][0]
        if gap >= window // 2:
            out.append((pts[i][1], math.dist(pts[i][2:], pts[j][2:]) / (gap * PERIOD_S)))
    return out


def windowed_speed(rows, t0, t1, window=50):
    """The largest windowed speed of the rows with t0 <= t < t1."""
    inside = [r for r in rows if t0 <= float(r["t_s"]) < t1]
    return max((v for _, v in windowed_speeds(inside, window)), default=0.0)


def quaternion(r):
    return [float(r[k]) for k in ("qw", "qx", "qy", "qz")]


def angular_velocity(qa, qb, dt):
    """World-frame angular velocity taking orientation qa to qb in dt: 2 vec(qb * conj(qa)) / dt."""
    aw, ax, ay, az = qa[0], -qa[1], -qa[2], -qa[3]
    bw, bx, by, bz = qb
    w = bw * aw - bx * ax - by * ay - bz * az
    v = [bw * ax + bx * aw + by * az - bz * ay,
         bw * ay - bx * az + by * aw + bz * ax,
         bw * az + bx * ay - by * ax + bz * aw]
    sign = 1.0 if w >= 0 else -1.0  # the short way round
    return [2.0 * sign * c / dt for c in v]


RENDERED = ("ren_fx", "ren_fy", "ren_fz", "ren_tx", "ren_ty", "ren_tz")


def port_energy(rows):
    """Integral of the wrench the controller rendered on the handle (coupling, guards, walls;
    gravity compensation apart) times the handle's twist, in J: positive, the port gave the hand
    energy."""
    energy = 0.0
    for a, b in zip(rows, rows[1:]):
        gap = int(b["cycle"]) - int(a["cycle"])
        if gap <= 0:
            continue
        dt = gap * PERIOD_S
        v = [(float(b[k]) - float(a[k])) / dt for k in ("x", "y", "z")]
        v += angular_velocity(quaternion(a), quaternion(b), dt)
        w = [float(b[k]) for k in RENDERED]
        energy += sum(wi * vi for wi, vi in zip(w, v)) * dt
    return energy


def plateau(rows, t0, t1):
    """Mean handle x and mean force the handle renders against the push along x, t0 <= t < t1."""
    sel = [r for r in rows if t0 <= float(r["t_s"]) < t1]
    if not sel:
        return None, None
    x = sum(float(r["x"]) for r in sel) / len(sel)
    f = -sum(float(r["ren_fx"]) for r in sel) / len(sel)
    return x, f


def contact(rows, fixed_x, k_coupling):
    """Penetration under the second plateau against F / K_series; rendered stiffness."""
    x1, f1 = plateau(rows, 2.5, 3.5)
    x2, f2 = plateau(rows, 5.5, 6.5)
    if x1 is None or x2 is None or fixed_x is None or not k_coupling:
        return {}
    if abs(f1 - PUSHES[0]) > 0.1 * PUSHES[0] or abs(f2 - PUSHES[1]) > 0.1 * PUSHES[1]:
        # Not at rest against the pushes: the soft coupling of a long loop let the sphere slide
        # off the fixed one (seen at 20 ms: the handle 9.7 cm past the surface).
        return {"contact_held": False}
    k_series = 1.0 / (1.0 / K_CONTACT + 1.0 / k_coupling)
    out = {"contact_held": True, "k_series": k_series, "contact_force_n": f2,
           "penetration_mm": (x2 - (fixed_x - RADII)) * 1e3,
           "penetration_expected_mm": f2 / k_series * 1e3}
    if abs(x2 - x1) > 1e-5:
        out["k_rendered"] = (f2 - f1) / (x2 - x1)
    return out


def longest_stale_run(rows, after_t):
    """(first, end) row indices of the longest run of stale cycles after `after_t` (the
    blackout; a lost frame or two can flag a cycle stale too), or None."""
    runs, start = [], None
    for i, r in enumerate(rows):
        stale = float(r["t_s"]) >= after_t and int(r["state_word"]) & (1 << 5)
        if stale and start is None:
            start = i
        if not stale and start is not None:
            runs.append((i - start, start, i))
            start = None
    if start is not None:
        runs.append((len(rows) - start, start, len(rows)))
    if not runs:
        return None
    _, first, end = max(runs)
    return first, end


def force_of(r, keys=RENDERED[:3]):
    return math.hypot(*(float(r[k]) for k in keys))


COUPLING = ("cpl_fx", "cpl_fy", "cpl_fz")  # the coupling's force (logged on the object)


def degraded(r):
    return int(r["state_word"]) & (1 << 3)


def blackout(rows, after_t):
    """Fade time and largest step from the last fresh sample; re-coupling time and peak speed
    after the link returns."""
    run = longest_stale_run(rows, after_t)
    if run is None:
        return {}
    first, end = run
    out = {}
    last_fresh = int(rows[first]["cycle"]) - 5
    start = next((i for i, r in enumerate(rows) if int(r["cycle"]) >= last_fresh), first)
    before = [force_of(r) for r in rows[max(0, start - 200):start] if not degraded(r)]
    held = sum(before) / len(before) if before else 0.0
    out["force_before_n"] = held
    for i in range(start, end):
        if force_of(rows[i], COUPLING) < 1e-6 and not degraded(rows[i]):
            steps = [math.dist([float(a[k]) for k in RENDERED[:3]],
                               [float(b[k]) for k in RENDERED[:3]])
                     / max(1, int(b["cycle"]) - int(a["cycle"]))
                     for a, b in zip(rows[start:i + 1], rows[start + 1:i + 1])
                     if not degraded(a) and not degraded(b)]
            out["fade_ms"] = (int(rows[i]["cycle"]) - last_fresh) * PERIOD_S * 1e3
            out["fade_largest_step_n"] = max(steps, default=0.0)
            break
    if end < len(rows):
        back = next((r for r in rows[end:] if force_of(r) >= 0.9 * held), None)
        if back is not None and held > 0.1:
            out["recouple_ms"] = (int(back["cycle"]) - int(rows[end]["cycle"])) * PERIOD_S * 1e3
        t_back = float(rows[end]["t_s"])
        out["speed_after_return"] = windowed_speed(rows, t_back, t_back + 1.0, window=20)
    return out


def fixed_sphere_x(demo_err):
    """The fixed sphere's centre x, as the demo printed it at start."""
    try:
        text = open(demo_err).read()
    except OSError:
        return None
    m = re.search(r"fixed sphere at \(([-+0-9.eE]+) ", text)
    return float(m.group(1)) if m else None


def status_of(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return {}


def case_record(case_dir, status, complete):
    """The case as the script wrote it, whether it can be judged (complete, and the core never
    failed safe) and the VM stalls the core rode through (also bench/contact_report.py)."""
    out = json.load(open(os.path.join(case_dir, "case.json")))
    out["judged"] = complete and "FAIL-SAFE" not in open(os.path.join(case_dir, "core.err")).read()
    out["stalls_ridden"] = status.get("cycle_health", {}).get("would_fail_safe")
    return out


def analyse(case_dir):
    phases = {name: read_csv(os.path.join(case_dir, name + ".csv"))
              for name in ("contact", "steps", "hand", "blackout")}
    status = status_of(os.path.join(case_dir, "status.json"))
    client = status.get("client", {})
    out = case_record(case_dir, status, all(phases.values()))
    if not out["judged"]:
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
        "speed_after_settling": max(windowed_speed(phases["steps"], 4.5, 5.5),
                                    windowed_speed(phases["steps"], 8.5, 9.5)),
        "hand_s": float(phases["hand"][-1]["t_s"]),
        "peak_force_n": max(force_of(r) for name in ("contact", "blackout", "steps", "hand")
                            for r in phases[name]),
        "port_energy_j": port_energy(phases["hand"]),
        "channel_energy_out_j": client.get("channel_energy_out"),
    })
    k_contact_phase = (status_of(os.path.join(case_dir, "status_contact.json"))
                       .get("client", {}).get("gains", [0])[0])
    out.update(contact(phases["contact"], fixed_sphere_x(os.path.join(case_dir, "demo.err")),
                       k_contact_phase))
    out.update(blackout(phases["blackout"], 0.8))
    return out


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def contact_cells(c):
    if not c.get("contact_held", False):
        return "the sphere slid off the fixed one: not at rest against the pushes | | |"
    return (f"{fmt(c.get('k_rendered'), '.0f')} N/m | {fmt(c.get('k_series'), '.0f')} N/m | "
            f"{fmt(c.get('penetration_mm'), '.2f')} mm "
            f"({fmt(c.get('penetration_expected_mm'), '.2f')} mm) |")


def row_head(c):
    return f"| {c['delay_ms']} ms | {c['loss']:.0%} | ±{c['jitter_ms']} ms |"


def main(out):
    cases = [analyse(d) for d in sorted(glob.glob(os.path.join(out, "raw", "coupling", "*")))
             if os.path.exists(os.path.join(d, "case.json"))]
    cases.sort(key=lambda c: (c["delay_ms"], c["loss"]))
    json.dump(cases, open(os.path.join(out, "coupling.json"), "w"), indent=1)
    lost = "the core stopped: not judged |"
    lines = [
        "## Coupling over an impaired link (H1)",
        "",
        "The demo's 0.5 kg sphere (a free body) through hapticctrl-netem, 1 ms core; the operator",
        "played by hapticctrl-hmi: 2 N then 4 N onto the fixed sphere (contact); a spring-damper",
        "hand (300 N/m, 5 N.s/m) pressing 2 N onto it through a 0.3 s blackout; 3 N steps along y",
        "and releases, the hand holding the handle (settling); the hand wandering 2 cm at 0.2-2 Hz",
        "(port energy). K_max = 2(b+B)/(T(1+2d)) with T = 1 ms, b+B the coupling's damping, d the",
        "measured loop in cycles; K_series = 1/(1/K_contact + 1/k), K_contact =",
        f"{K_CONTACT:.0f} N/m.",
        "",
        "| one way | loss | jitter | loop | k derived | K_max | k rendered | K_series "
        "| penetration at 4 N (expected) | speed after settling | port energy out (hand) "
        "| peak force | VM stalls ridden through |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in cases:
        if not c["judged"]:
            lines.append(row_head(c) + f" {lost}" + " |" * 8 + f" {fmt(c['stalls_ridden'], 'd')} |")
            continue
        lines.append(
            row_head(c) + f" {fmt(c['loop_delay_ms'], '.1f')} ms | "
            f"{fmt(c['k_derived'], '.0f')} N/m | {fmt(c['k_max_bound'], '.0f')} N/m | "
            + contact_cells(c) + f" {fmt(c['speed_after_settling'] * 1e3, '.1f')} mm/s | "
            f"{fmt(c['port_energy_j'] * 1e3, '.2f')} mJ in {c['hand_s']:.0f} s | "
            f"{fmt(c['peak_force_n'], '.1f')} N | "
            f"{fmt(c['stalls_ridden'], 'd')} |")
    lines += [
        "",
        "| one way | loss | jitter | force held | fade after loss | largest step while fading "
        "| force back to 90 % after the link returns | peak speed in the second after |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for c in cases:
        if not c["judged"]:
            lines.append(row_head(c) + f" {lost}" + " |" * 4)
            continue
        speed = c.get("speed_after_return")
        lines.append(
            row_head(c) + f" {fmt(c.get('force_before_n'), '.2f')} N | "
            f"{fmt(c.get('fade_ms'), '.0f')} ms | "
            f"{fmt(c.get('fade_largest_step_n'), '.2f')} N/ms | "
            f"{fmt(c.get('recouple_ms'), '.0f')} ms | "
            f"{fmt(None if speed is None else speed * 1e3, '.1f')} mm/s |")
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
            f.write(f"{max(c['loop_delay_ms'], 0.1)} {c['k_derived']} {c['k_max_bound'] or 0} "
                    f"{c.get('k_rendered') or 'NaN'}\n")
    script = "\n".join([
        "set terminal png size 900,500 noenhanced",
        f"set output '{os.path.join(out, 'coupling.png')}'",
        "set title 'Coupling stiffness against the measured loop delay'",
        "set xlabel 'coupling loop delay (ms)'", "set ylabel 'stiffness (N/m)'",
        "set logscale xy", "set grid", "set key top right",
        f"plot '{data}' using 1:3 with linespoints title 'K_max = 2(b+B)/(T(1+2d))', "
        f"'{data}' using 1:2 with points pt 7 title 'k derived', "
        f"'{data}' using 1:4 with points pt 5 title 'k rendered against the fixed sphere (in series with K_contact)'",
    ])
    subprocess.run(["gnuplot"], input=script, text=True, check=False)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench-report")
