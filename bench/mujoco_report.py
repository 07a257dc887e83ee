#!/usr/bin/env python3
"""hapticctrl-mujoco on the shipped scenes (J3): reads OUT_DIR/raw/mujoco/ (bench/mujoco_scenes.sh)
and writes OUT_DIR/mujoco.md and mujoco.json: per scene and load, the engine's steps per second
against the model's own rate (real time is the baseline: a ratio of 1.000), the steps dropped
after stalls, the catch-ups, the CPU time per step, MuJoCo's instability resets and the stalls
the core rode through. Only figures measured in this run."""
import json
import os
import sys


def analyse(raw):
    rows = []
    for entry in sorted(os.listdir(raw)):
        scene, load = entry.rsplit(".", 1)
        path = os.path.join(raw, entry, "summary.json")
        try:
            with open(path) as f:
                s = json.loads(f.read().strip().splitlines()[-1])
        except (OSError, ValueError, IndexError):
            rows.append({"scene": scene, "load": load, "error": "no summary"})
            continue
        stalls = None
        try:
            with open(os.path.join(raw, entry, "status.json")) as f:
                stalls = json.load(f)["cycle_health"]["would_fail_safe"]
        except (OSError, ValueError, KeyError):
            pass
        rows.append({
            "scene": scene, "load": load, "steps": s["steps"],
            "steps_per_second": s["steps_per_second"],
            "model_steps_per_second": s["model_steps_per_second"],
            "ratio": s["steps_per_second"] / s["model_steps_per_second"],
            "dropped": s["steps_dropped"], "paused": s["steps_paused"],
            "catch_ups": s["catch_ups"], "cpu_us_mean": s["cpu_us_per_step_mean"],
            "cpu_us_max": s["cpu_us_per_step_max"], "instabilities": s["instabilities"],
            "contact_reports": s["contact_reports"], "core_stalls": stalls})
    return rows


def markdown(rows):
    out = ["## hapticctrl-mujoco: the shipped scenes in real time (J3)", "",
           "Per scene, coupled to a 1 ms core through the UDP bridge, the body pushed 3 N down "
           "from the second second; idle and beside stress-ng --cpu on every CPU. Ratio: steps "
           "per second over the model's own rate (1.000 is real time).", "",
           "| scene | load | steps/s | ratio | dropped | catch-ups | CPU/step mean | largest | "
           "resets | core stalls |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "error" in r:
            out.append(f"| {r['scene']} | {r['load']} | {r['error']} | | | | | | | |")
            continue
        out.append(
            f"| {r['scene']} | {r['load']} | {r['steps_per_second']:.1f} | {r['ratio']:.3f} | "
            f"{r['dropped']} | {r['catch_ups']} | {r['cpu_us_mean']:.1f} µs | "
            f"{r['cpu_us_max']:.0f} µs | {r['instabilities']} | {r['core_stalls']} |")
    return "\n".join(out) + "\n"


def main():
    out = sys.argv[1]
    rows = analyse(os.path.join(out, "raw", "mujoco"))
    with open(os.path.join(out, "mujoco.json"), "w") as f:
        json.dump(rows, f, indent=1)
    text = markdown(rows)
    with open(os.path.join(out, "mujoco.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
