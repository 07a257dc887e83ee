#!/usr/bin/env python3
"""The weighted sphere at rest (H1): reads OUT_DIR/raw/gravity/ (bench/gravity_rest.sh) and
writes OUT_DIR/gravity.md and gravity.json.

- when the handle and the sphere came to rest: the last time their speed was above 0.1 m/s
  (handle: displacement over 50 ms windows of the core's per-cycle log; sphere: the demo's
  velocity), and the largest speed of each after 3 s;
- coupling on/off chatter: changes of the coupled bit between cycles of the main SERVO on fresh
  client data (a degraded cycle never couples; a stale link is not chatter);
- where the handle rested, how far it crept after 3 s, the weight it carried (mean of the last
  2 s of the wrench rendered on it), and the stalls the core rode through.
Only figures measured in this run.
"""
import json
import math
import os
import sys

from coupling_report import read_csv, status_of, windowed_speeds

COUPLED, DEGRADED, STALE = 1 << 4, 1 << 3, 1 << 5


def chatter(rows):
    """Coupled-bit changes after the coupling first engaged, main SERVO on fresh data only."""
    n, prev, engaged = 0, None, False
    for r in rows:
        word = int(r["state_word"])
        if engaged and not (word | prev) & (DEGRADED | STALE):
            n += (word & COUPLED) != (prev & COUPLED)
        engaged = engaged or bool(word & COUPLED)
        prev = word
    return n


def analyse(raw):
    rows = read_csv(os.path.join(raw, "cycles.csv"))
    demo = read_csv(os.path.join(raw, "demo.csv"))
    status = status_of(os.path.join(raw, "status.json"))
    stopped = not rows or "FAIL-SAFE" in open(os.path.join(raw, "core.err")).read()
    out = {"judged": not stopped,
           "stalls_ridden": status.get("cycle_health", {}).get("would_fail_safe")}
    if stopped:
        return out
    handle = windowed_speeds(rows)
    sphere = [(float(r["t_s"]), math.sqrt(sum(float(r[k]) ** 2 for k in ("vx", "vy", "vz"))))
              for r in demo]
    settled = next((r for r in rows if float(r["t_s"]) >= 3.0), rows[-1])
    last_two = [r for r in rows if int(r["cycle"]) > int(rows[-1]["cycle"]) - 2000]
    start = [float(settled[k]) for k in ("x", "y", "z")]
    end = [float(rows[-1][k]) for k in ("x", "y", "z")]
    out.update({
        "seconds": float(rows[-1]["t_s"]),
        "handle_last_above_0p1_s": max((t for t, v in handle if v > 0.1), default=None),
        "sphere_last_above_0p1_s": max((t for t, v in sphere if v > 0.1), default=None),
        "handle_peak_after_3s": max((v for t, v in handle if t > 3.0), default=None),
        "sphere_peak_after_3s": max((v for t, v in sphere if t > 3.0), default=None),
        "chatter": chatter(rows),
        "rest_z": end[2],
        "creep_mm": math.dist(start, end) * 1e3,
        "weight_n": -sum(float(r["ren_fz"]) for r in last_two) / len(last_two),
    })
    return out


def fmt(v, spec, unit=""):
    return "—" if v is None else format(v, spec) + unit


def main(out):
    r = analyse(os.path.join(out, "raw", "gravity"))
    json.dump(r, open(os.path.join(out, "gravity.json"), "w"), indent=1)
    lines = ["## The weighted sphere at rest (H1)", ""]
    if not r["judged"]:
        lines.append("The core stopped during the run: not judged.")
    else:
        lines += [
            f"`hapticctrl-demo --gravity` (0.5 kg) on a 1 ms core for {r['seconds']:.0f} s, nobody "
            f"touching; the core rode through {fmt(r['stalls_ridden'], 'd')} VM stalls "
            "(benchmark mode).",
            "",
            "| last above 0.1 m/s (handle / sphere) | peak after 3 s (handle / sphere) "
            "| coupling on/off chatter | rest height | creep | weight on the handle |",
            "|---|---|---|---|---|---|",
            f"| {fmt(r['handle_last_above_0p1_s'], '.2f', ' s')} / "
            f"{fmt(r['sphere_last_above_0p1_s'], '.2f', ' s')} "
            f"| {fmt(r['handle_peak_after_3s'] and r['handle_peak_after_3s'] * 1e3, '.1f', ' mm/s')} / "
            f"{fmt(r['sphere_peak_after_3s'] and r['sphere_peak_after_3s'] * 1e3, '.1f', ' mm/s')} "
            f"| {r['chatter']} | z {r['rest_z'] * 1e3:.1f} mm | {r['creep_mm']:.1f} mm "
            f"| {r['weight_n']:.2f} N |",
            "",
            "'—': never above 0.1 m/s. Creep: how far the handle moved from 3 s to the end.",
        ]
    text = "\n".join(lines) + "\n"
    open(os.path.join(out, "gravity.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench-report")
