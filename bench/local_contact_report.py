#!/usr/bin/env python3
"""Local contact models' report (J2): reads OUT_DIR/raw/local/*/ (bench/local_contact.sh) and
writes OUT_DIR/local.md and local.json.

Per case (one-way delay, loss, jitter through hapticctrl-netem):
- press, for the wall and the fixed sphere rendered locally and for the sphere through the
  coupling alone (soft, --no-contacts): the stiffness felt, k_felt = (f10 - f5) / (x10 - x5) over
  the plateaus' last second, against the surface's 2000 N/m, and the penetration at 5 and 10 N
  from the rest before the push;
- jump (the wall moved 5 mm into the handle held at 5 N): the largest force step per cycle, the
  peak force and speed, the energy the port put out (positive: it gave the hand energy);
- friction (mu 0.3): the rendered tangential force over the normal one while sliding, the
  tangential force while sticking under 2 N;
- blackout (0.5 s, 5 N into the wall): the smallest force while the link was silent, the
  largest step, the speed after the link returned;
- hand (60 s of a wandering spring-damper hand pressing 3 N): the energy the port put out, the
  peak force and the cycles at the saturation.
J2's bars beside them: k_felt / k >= 0.9 (and <= 1.1), the penetration at 10 N within 10 % of
F / k, the port <= 1 mJ, no step above 1 N per ms, mu within 10 %. Only figures measured in this
run; a run whose core stopped says so.
"""
import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import coupling_report as cr  # noqa: E402  (the hmi log's readers, shared with H1's report)

K_SURFACE = 2000.0  # N/m, bench/local_contact.sh's --contact-stiffness
MU = 0.3            # the wall's friction (--friction)
SATURATED = 1 << 7  # shm::state_bits::kSaturated


def rows_in(rows, t0, t1):
    return [r for r in rows if t0 <= float(r["t_s"]) < t1]


def mean(rows, key):
    return sum(float(r[key]) for r in rows) / len(rows) if rows else None


def press(rows):
    """Stiffness felt and penetrations: rest [0.5, 1), 5 N [2.5, 3.5), 10 N [5, 6)."""
    rest, five, ten = rows_in(rows, 0.5, 1.0), rows_in(rows, 2.5, 3.5), rows_in(rows, 5.0, 6.0)
    if not (rest and five and ten):
        return {}
    x0, x5, x10 = mean(rest, "x"), mean(five, "x"), mean(ten, "x")
    f5, f10 = -mean(five, "ren_fx"), -mean(ten, "ren_fx")
    k = (f10 - f5) / (x10 - x5) if x10 != x5 else None
    return {"k_felt": k, "k_ratio": k / K_SURFACE if k else None,
            "pen5_mm": (x5 - x0) * 1e3, "pen10_mm": (x10 - x0) * 1e3, "f10_n": f10}


def largest_step(rows):
    """The largest change of the rendered force in one cycle, N per cycle."""
    step = 0.0
    for a, b in zip(rows, rows[1:]):
        gap = int(b["cycle"]) - int(a["cycle"])
        if gap > 0:
            step = max(step, math.dist([float(a[k]) for k in cr.RENDERED[:3]],
                                       [float(b[k]) for k in cr.RENDERED[:3]]) / gap)
    return step


def jump(rows):
    """From 2 s (at rest under 5 N) to the end: the jump comes at about 3 s of the play."""
    judged = rows_in(rows, 2.0, 6.0)
    if not judged:
        return {}
    return {"jump_step_n": largest_step(judged),
            "jump_peak_n": max(cr.force_of(r) for r in judged),
            "jump_speed": cr.windowed_speed(rows, 2.0, 6.0),
            "jump_energy_j": cr.port_energy(judged)}


def friction(rows):
    stuck, sliding = rows_in(rows, 1.5, 2.5), rows_in(rows, 2.6, 2.85)
    if not (stuck and sliding):
        return {}
    mu = sum(float(r["ren_fy"]) / float(r["ren_fx"]) for r in sliding if float(r["ren_fx"]))
    return {"mu": mu / len(sliding), "stuck_n": -mean(stuck, "ren_fy"),
            "stuck_speed": cr.windowed_speed(rows, 1.5, 2.5)}


def blackout(rows):
    run = cr.longest_stale_run(rows, 0.8)
    if run is None:
        return {}
    first, end = run
    held = [cr.force_of(r) for r in rows[first:end]]
    out = {"blackout_ms": float(int(rows[end - 1]["cycle"]) - int(rows[first]["cycle"]) + 1),
           "blackout_min_n": min(held), "blackout_step_n": largest_step(rows[first:])}
    if end < len(rows):
        t = float(rows[end]["t_s"])
        out["blackout_speed_after"] = cr.windowed_speed(rows, t, t + 1.0, window=20)
    return out


def hand(rows):
    if not rows:
        return {}
    return {"port_energy_j": cr.port_energy(rows), "hand_peak_n": max(cr.force_of(r) for r in rows),
            "saturated_cycles": float(sum(1 for r in rows if int(r["state_word"]) & SATURATED))}


def run_of(case_dir, part, phases):
    """One demo run's phases, or None when its core stopped or a phase is missing."""
    d = os.path.join(case_dir, part)
    logs = {p: cr.read_csv(os.path.join(d, p + ".csv")) for p in phases}
    try:
        stopped = "FAIL-SAFE" in open(os.path.join(d, "core.err")).read()
    except OSError:
        stopped = True
    status = cr.status_of(os.path.join(d, "status.json"))
    ok = all(logs.values()) and not stopped
    return (logs if ok else None), status.get("cycle_health", {}).get("would_fail_safe")


def analyse(case_dir):
    out = json.load(open(os.path.join(case_dir, "case.json")))
    jumped, stalls_jump = run_of(case_dir, "jump", ("jump",))
    wall, stalls_wall = run_of(case_dir, "wall", ("press", "friction", "blackout", "hand"))
    sphere, stalls_sphere = run_of(case_dir, "sphere", ("press",))
    soft, stalls_soft = run_of(case_dir, "soft", ("press",))
    out["stalls_ridden"] = sum(s or 0 for s in (stalls_jump, stalls_wall, stalls_sphere,
                                                 stalls_soft))
    out["judged"] = {"jump": jumped is not None, "wall": wall is not None,
                     "sphere": sphere is not None, "soft": soft is not None}
    if wall:
        out["wall"] = {**press(wall["press"]), **friction(wall["friction"]),
                       **blackout(wall["blackout"]), **hand(wall["hand"])}
    if jumped:
        out.setdefault("wall", {}).update(jump(jumped["jump"]))
    if sphere:
        out["sphere"] = press(sphere["press"])
    if soft:
        out["soft"] = press(soft["press"])
    w = out.get("wall", {})
    needed = ("k_ratio", "pen10_mm", "port_energy_j", "jump_step_n", "jump_energy_j", "mu")
    if all(w.get(k) is not None for k in needed) and out.get("sphere", {}).get("k_ratio"):
        out["meets_j2"] = bool(
            0.9 <= w["k_ratio"] <= 1.1 and 0.9 <= out["sphere"]["k_ratio"] <= 1.1
            and abs(w["pen10_mm"] - 10.0 / K_SURFACE * 1e3) <= 0.1 * 10.0 / K_SURFACE * 1e3
            and w["port_energy_j"] <= 1e-3 and w["jump_energy_j"] <= 1e-3
            and w["jump_step_n"] <= 1.0 + 1e-6 and abs(w["mu"] - MU) <= 0.1 * MU)
    return out


def cell(d, key, spec, scale=1.0, unit=""):
    v = d.get(key) if d else None
    return "—" if v is None else f"{v * scale:{spec}}{unit}"


def row(c):
    w, s, f = c.get("wall", {}), c.get("sphere", {}), c.get("soft", {})
    head = f"| {c['delay_ms']} ms | {c['loss']:.0%} | ±{c['jitter_ms']} ms |"
    return head + " | ".join([
        f" {cell(w, 'k_ratio', '.3f')} / {cell(s, 'k_ratio', '.3f')} ({cell(f, 'k_ratio', '.3f')})",
        f"{cell(w, 'pen5_mm', '.2f')} / {cell(w, 'pen10_mm', '.2f')} mm",
        f"{cell(w, 'port_energy_j', '+.1f', 1e3)} mJ ({cell(w, 'saturated_cycles', '.0f')})",
        f"{cell(w, 'jump_step_n', '.2f')} N, {cell(w, 'jump_peak_n', '.1f')} N, "
        f"{cell(w, 'jump_speed', '.1f', 1e3)} mm/s, {cell(w, 'jump_energy_j', '+.2f', 1e3)} mJ",
        f"{cell(w, 'mu', '.3f')} ({cell(w, 'stuck_n', '.2f')} N stuck)",
        f"{cell(w, 'blackout_min_n', '.2f')} N, {cell(w, 'blackout_step_n', '.2f')} N, "
        f"{cell(w, 'blackout_speed_after', '.1f', 1e3)} mm/s",
        {True: "yes", False: "no"}.get(c.get("meets_j2"), "not judged"),
        f"{c['stalls_ridden']} |"])


def main(out):
    cases = [analyse(d) for d in sorted(glob.glob(os.path.join(out, "raw", "local", "*")))
             if os.path.exists(os.path.join(d, "case.json"))]
    cases.sort(key=lambda c: (c["delay_ms"], c["loss"]))
    json.dump(cases, open(os.path.join(out, "local.json"), "w"), indent=1)
    lines = [
        "## Local contact models (J2)",
        "",
        "The demo reports its obstacle's surface with its object state (protocol 1.3); the core",
        "renders it on the handle in the servo cycle. 1 ms core, through hapticctrl-netem. The",
        "operator played by hapticctrl-hmi. k_felt / k: the stiffness felt between 5 and 10 N",
        "over the surface's 2000 N/m, for the wall / the fixed sphere rendered locally (and the",
        "sphere through the coupling alone, --no-contacts: the baseline, same run). Penetration",
        "at 5 / 10 N from the rest (F / k: 2.5 / 5 mm). Port: the energy the port put out into a",
        "spring-damper hand pressing 3 N and wandering (cycles at the saturation). Jump: the wall",
        "moved 5 mm into the handle held at 5 N: largest step per cycle, peak force, peak speed,",
        "the port's energy. mu: sliding on the mu 0.3 wall. Blackout (0.5 s at 5 N): the",
        "smallest force held, the largest step, the speed after the return.",
        "",
        "| one way | loss | jitter | k_felt / k: wall / sphere (soft) | penetration 5 / 10 N "
        "| port out (hand) | wall jumps 5 mm | mu (0.3) | blackout | J2's bars met "
        "| VM stalls ridden through |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [row(c) for c in cases]
    lines.append("")
    open(os.path.join(out, "local.md"), "w").write("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench-report")
