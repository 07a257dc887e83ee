#!/usr/bin/env python3
"""Writes the system benchmark's report from scripts/bench.sh's raw outputs.

usage: bench/report.py OUT_DIR      (reads OUT_DIR/raw/, writes OUT_DIR/report.md,
                                     OUT_DIR/results.json and OUT_DIR/*.png with gnuplot)

Every figure stands next to the baseline measured in the same run and the ratio between them.
"""
import json
import os
import sys

from report_data import (LOADS, PERIODS, fmt, fmt_ratio, hist_stats, load_json, ns_to_us, ratio,
                         read_hist, read_samples, sample_stats, samples_at_or_beyond)
from report_peers import section as peers_section
from report_plots import write_plots


def latency_results(raw):
    results = {}
    for period in PERIODS:
        results[str(period)] = {}
        for load in LOADS:
            base = os.path.join(raw, f"lat-{period}-{load}")
            core_json = load_json(base + ".core.json")
            core = hist_stats(read_hist(base + ".core.hist"))
            cyclic_hist = read_hist(base + ".cyclictest.hist")
            cyclic = hist_stats(cyclic_hist)
            would_fail = core_json.get("would_fail_safe")
            stalls = samples_at_or_beyond(cyclic_hist, 5 * period) if cyclic["samples"] else None
            seconds = (core_json.get("cycles") or 0) * period * 1e-6
            start = core_json.get("servo_start_delay", {})
            execution = core_json.get("servo_execution", {})
            results[str(period)][load] = {
                "core": core,
                "cyclictest": cyclic,
                "ratio": {k: ratio(core.get(k), cyclic.get(k))
                          for k in ("p50_us", "p99_us", "p999_us", "max_us")},
                "misses": core_json.get("misses_total"),
                "degraded_cycles": core_json.get("degraded_cycles"),
                "cycles": core_json.get("cycles"),
                "stop_reason": core_json.get("stop_reason", "core did not report"),
                # The same window: the core rode through its would-be fail-safes.
                "samples_ratio": ratio(core["samples"], cyclic["samples"]),
                "would_fail_safe": would_fail,
                "cyclictest_stalls_5_periods": stalls,
                "fail_safes_per_stall": ratio(would_fail, stalls),
                "mean_s_between_fail_safes": (seconds / would_fail) if would_fail else None,
                "seconds": seconds,
                "rt_mode": core_json.get("rt_mode"),
                "servo_start_us": {k: ns_to_us(start, k + "_ns")
                                   for k in ("p50", "p99", "p999", "max")},
                "servo_execution_us": {k: ns_to_us(execution, k + "_ns")
                                       for k in ("p50", "p99", "p999", "max")},
            }
    return results


def core_ending(path):
    """How a core run ended, from its stderr ('FAIL-SAFE after cycle ...' or 'stopped ...')."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = [l.strip() for l in f if "FAIL-SAFE" in l or "stopped after" in l]
    except OSError:
        return "no log"
    if not lines:
        return "still running at the end"
    return lines[-1].replace("hapticctrl-core: ", "").split(" (motors")[0]


def link_results(raw):
    results = {}
    for load in LOADS:
        figures = load_json(os.path.join(raw, f"link-{load}.json"))
        ending = core_ending(os.path.join(raw, f"link-{load}.core.err"))
        core_json = load_json(os.path.join(raw, f"link-{load}.core.json"))
        client = sample_stats(read_samples(os.path.join(raw, f"link-{load}.client_rtt")))
        udp = sample_stats(read_samples(os.path.join(raw, f"link-{load}.udp_rtt")))
        results[load] = {
            "figures": figures,
            "client_rtt": client,
            "udp_rtt": udp,
            "ratio": {k: ratio(client.get(k), udp.get(k))
                      for k in ("p50_us", "p99_us", "p999_us", "max_us")},
            "core_ended": ending,
            "would_fail_safe": core_json.get("would_fail_safe"),
        }
    return results


def micro_results(raw):
    results = {}
    for name in ("shm", "protocol", "rt-core"):
        data = load_json(os.path.join(raw, f"micro-{name}.json"))
        for b in data.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration":
                continue
            scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}.get(b.get("time_unit", "ns"), 1.0)
            # "BM_WakeRoundTripFutex/min_time:1.000/real_time" -> "BM_WakeRoundTripFutex"
            results[b["name"].split("/")[0]] = b["real_time"] * scale
    return results


MICRO_PAIRS = (
    ("BM_SeqlockPublishQuietly", "BM_StructCopyBaseline"),
    ("BM_SeqlockRead", "BM_StructCopyBaseline"),
    ("BM_WakeRoundTripFutex", "BM_WakeRoundTripPipe"),
    ("BM_WakeRoundTripUdpLoopback", "BM_WakeRoundTripFutex"),
    ("BM_EncodeAnswer", "BM_CopyFrameStruct"),
    ("BM_DecodeAnswer", "BM_CopyFrameStruct"),
    ("BM_EncodeControlObject", "BM_CopyFrameStruct"),
    ("BM_DecodeControlObject", "BM_CopyFrameStruct"),
    ("BM_ControlLaw", "BM_ForwardKinematicsAndJacobian"),
    ("BM_FullCycle1ms", "BM_SimulatorStep1ms"),
)


def requirements(lat, link):
    """The seeds' performance requirements, each met or not, and by how much."""
    rows = []
    worst_exec = max((r["servo_execution_us"]["max"] or 0.0)
                     for p in lat.values() for r in p.values())
    rows.append({"requirement": "full cycle (SERVO execution) <= 500 us",
                 "measured": f"max {worst_exec:.1f} us over every period and load",
                 "met": worst_exec <= 500.0,
                 "margin": f"{500.0 - worst_exec:+.1f} us ({worst_exec / 500.0 * 100:.1f} % of the bound)"})
    starts = [(p, l, r["servo_start_us"]) for p, pr in lat.items() for l, r in pr.items()]
    worst_start = max((s["max"] or 0.0) for _, _, s in starts)
    worst_p999 = max((s["p999"] or 0.0) for _, _, s in starts)
    rows.append({"requirement": "SERVO starts <= 50 us after CLOCK wakes it",
                 "measured": f"max {worst_start:.1f} us (p99.9 at most {worst_p999:.1f} us)",
                 "met": worst_start <= 50.0,
                 "margin": f"{50.0 - worst_start:+.1f} us at the max, {50.0 - worst_p999:+.1f} us at p99.9"})
    loaded = {p: pr["load"] for p, pr in lat.items()}
    misses = {p: r["misses"] for p, r in loaded.items()}
    total = sum(m for m in misses.values() if m is not None)
    rows.append({"requirement": "no missed deadline with user space heavily loaded",
                 "measured": ", ".join(f"{p} us: {fmt(m)} misses ({r['stop_reason']})"
                                       for (p, m), r in zip(misses.items(), loaded.values())),
                 "met": all(m == 0 for m in misses.values()),
                 "margin": f"{total} misses in all"})
    lf = link["load"]["figures"]
    if lf:
        rate = lf.get("answers", 0) / max(lf.get("seconds", 1), 1e-9)
        loss = lf.get("loss_ratio", 1.0)
        met = rate >= 1000.0 / 3.0 and loss < 0.1 and not lf.get("controller_stopped", False)
        rows.append({"requirement": "client data >= 1 sample / 3 ms, < 1 in 10 lost (under load)",
                     "measured": f"{rate:.0f} samples/s, loss {loss * 100:.3f} %, "
                                 f"{lf.get('gaps_over_3ms', 'n/a')} gaps over 3 ms",
                     "met": met,
                     "margin": f"{rate / (1000.0 / 3.0):.1f}x the rate, loss {loss / 0.1 * 100:.2f} % of the bound"})
    else:
        rows.append({"requirement": "client data >= 1 sample / 3 ms, < 1 in 10 lost (under load)",
                     "measured": "no result (the link run failed)", "met": False, "margin": "n/a"})
    return rows


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def report(out, machine, lat, link, micro, handoff, reqs, plots, peers_md):
    md = ["# hapticctrl system benchmark", ""]
    md.append(f"Run {machine.get('date', '?')} at {machine.get('git', '?')}: kernel "
              f"{machine.get('kernel', '?')} ({'PREEMPT_RT' if machine.get('preempt_rt') else 'not PREEMPT_RT'}), "
              f"{machine.get('cpus', '?')} CPUs ({machine.get('cpu_model', '?')}), virtualization "
              f"{machine.get('virtualization', '?')}, SCHED_FIFO {'granted' if machine.get('sched_fifo') else 'refused'}, "
              f"RLIMIT_MEMLOCK {machine.get('memlock_kib', '?')} KiB, load average before the run "
              f"{machine.get('loadavg', '?')}. Load: `{machine.get('load', '?')}`. "
              f"{machine.get('latency_seconds', '?')} s per latency run, {machine.get('link_seconds', '?')} s per link run; "
              f"core and cyclictest on CPU {machine.get('bench_cpu', '?')} at SCHED_FIFO 80.")
    md += ["", "Every figure stands next to a baseline measured in the same run; ratios are measured / baseline.", ""]

    md += ["## The seeds' requirements", ""]
    md.append(table(["requirement", "measured", "met", "margin"],
                    [[r["requirement"], r["measured"], "met" if r["met"] else "**not met**", r["margin"]] for r in reqs]))

    md += ["", "## 1. Wake-up latency: hapticctrl-core vs cyclictest (us)", ""]
    rows = []
    for period in PERIODS:
        for load in LOADS:
            r = lat[str(period)][load]
            c, y, q = r["core"], r["cyclictest"], r["ratio"]
            rows.append([f"{period} us", load,
                         f"{fmt(c.get('p50_us'))} / {fmt(y.get('p50_us'))} ({fmt_ratio(q['p50_us'])})",
                         f"{fmt(c.get('p99_us'))} / {fmt(y.get('p99_us'))} ({fmt_ratio(q['p99_us'])})",
                         f"{fmt(c.get('p999_us'))} / {fmt(y.get('p999_us'))} ({fmt_ratio(q['p999_us'])})",
                         f"{fmt(c.get('max_us'))} / {fmt(y.get('max_us'))} ({fmt_ratio(q['max_us'])})",
                         f"{fmt(r['misses'])} of {fmt(r['cycles'])}", r["stop_reason"]])
    md.append(table(["period", "load", "p50 core / cyclictest", "p99", "p99.9", "max", "core misses", "core ended"], rows))
    md += ["", " ".join(f"![latency at {p} us]({p_png})" for p, p_png in zip(PERIODS, plots[:3])), ""]

    md += ["### Fail-safes against the machine's own stalls, over the same window", ""]
    md.append("The core ran in benchmark mode: when its miss rule (5 consecutive misses) tripped, it "
              "counted a would-be fail-safe and ran on, so both histograms cover the same seconds. "
              "A stall of 5 periods or more in cyclictest (a wake-up at least 5 periods late, beside "
              "the core on the same CPU at the same priority) is what this kernel and hypervisor do "
              "to any thread: the physical floor. A ratio near 1 says the core fails safe when the "
              "machine stalls, and only then.")
    md.append("")
    rows = []
    for period in PERIODS:
        for load in LOADS:
            r = lat[str(period)][load]
            c, y = r["core"], r["cyclictest"]
            mtbf = r["mean_s_between_fail_safes"]
            rows.append([f"{period} us", load,
                         f"{fmt(c.get('samples'))} / {fmt(y.get('samples'))} ({fmt_ratio(r['samples_ratio'])})",
                         fmt(r["would_fail_safe"]), fmt(r["cyclictest_stalls_5_periods"]),
                         fmt_ratio(r["fail_safes_per_stall"]),
                         "none in the window" if mtbf is None
                         else f"{mtbf:.1f} s" if mtbf >= 1.0 else f"{mtbf * 1000:.0f} ms"])
    md.append(table(["period", "load", "samples core / cyclictest", "would-be fail-safes",
                     "cyclictest stalls >= 5 periods", "fail-safes per stall",
                     "mean time between fail-safes"], rows))
    md.append("")

    md += ["## 2. SERVO start delay after the CLOCK release vs a bare futex hand-off (us)", ""]
    floor50 = handoff.get("p50_ns", 0) / 1000.0 if handoff else None
    floor99 = handoff.get("p99_ns", 0) / 1000.0 if handoff else None
    floormax = handoff.get("max_ns", 0) / 1000.0 if handoff else None
    md.append(f"Floor (same CPU, SCHED_FIFO, {handoff.get('samples', 0) if handoff else 0} hand-offs): "
              f"p50 {fmt(floor50)}, p99 {fmt(floor99)}, max {fmt(floormax)} us.")
    md.append("")
    rows = []
    for period in PERIODS:
        for load in LOADS:
            s = lat[str(period)][load]["servo_start_us"]
            e = lat[str(period)][load]["servo_execution_us"]
            rows.append([f"{period} us", load,
                         f"{fmt(s['p50'])} ({fmt_ratio(ratio(s['p50'], floor50))})",
                         f"{fmt(s['p99'])} ({fmt_ratio(ratio(s['p99'], floor99))})",
                         fmt(s["p999"]), f"{fmt(s['max'])} ({fmt_ratio(ratio(s['max'], floormax))})",
                         f"{fmt(e['p99'])} / {fmt(e['max'])}"])
    md.append(table(["period", "load", "start p50 (x floor)", "start p99 (x floor)", "start p99.9",
                     "start max (x floor max)", "SERVO execution p99 / max"], rows))

    md += ["", "## 3. End to end at 1 kHz: client -> hapticctrl-udp -> core -> client (us)", ""]
    rows = []
    for load in LOADS:
        r = link[load]
        c, u, q, f = r["client_rtt"], r["udp_rtt"], r["ratio"], r["figures"]
        rows.append([load,
                     f"{fmt(c.get('p50_us'))} / {fmt(u.get('p50_us'))} ({fmt_ratio(q['p50_us'])})",
                     f"{fmt(c.get('p99_us'))} / {fmt(u.get('p99_us'))} ({fmt_ratio(q['p99_us'])})",
                     f"{fmt(c.get('p999_us'))} / {fmt(u.get('p999_us'))} ({fmt_ratio(q['p999_us'])})",
                     f"{fmt(c.get('max_us'))} / {fmt(u.get('max_us'))} ({fmt_ratio(q['max_us'])})",
                     f"{fmt(f.get('gap_p99_us'))} / {fmt(f.get('gap_max_us'))}",
                     fmt(f.get("jitter_us")),
                     f"{fmt(f.get('answers'))} of {fmt(f.get('expected'))}, lost {fmt(f.get('lost'))}, late {fmt(f.get('late'))}",
                     r["core_ended"] if "FAIL-SAFE" in r["core_ended"] or f.get("controller_stopped") else "kept running",
                     fmt(r["would_fail_safe"])])
    md.append(table(["load", "RTT p50 client / raw UDP", "p99", "p99.9", "max",
                     "answer gap p99 / max", "jitter (RFC 3550)", "answers", "core",
                     "would-be fail-safes ridden through"], rows))
    md.append("")
    md.append("The client's round trip includes waiting for the next controller cycle (its floor is one "
              "period, 1000 us); the raw UDP ping-pong is the kernel's loopback floor.")
    md += ["", f"![RTT CDF]({plots[3]})", ""]

    md += ["## 4. Micro-benchmarks (ns per operation)", ""]
    rows = []
    for a, b in MICRO_PAIRS:
        if a in micro:
            rows.append([a, fmt(micro[a]), b, fmt(micro.get(b)), fmt_ratio(ratio(micro[a], micro.get(b)))])
    md.append(table(["benchmark", "ns", "same-run baseline", "ns", "ratio"], rows))
    md.append("")
    md += peers_md
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md) + "\n")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bench/report.py OUT_DIR")
    out = sys.argv[1]
    raw = os.path.join(out, "raw")
    machine = load_json(os.path.join(raw, "machine.json"))
    lat = latency_results(raw)
    link = link_results(raw)
    micro = micro_results(raw)
    handoff = load_json(os.path.join(raw, "handoff.json"))
    reqs = requirements(lat, link)
    plots = write_plots(out, raw, lat)
    peers_md, peers = peers_section(out, raw, table)
    report(out, machine, lat, link, micro, handoff, reqs, plots, peers_md)
    results = {"machine": machine, "latency": lat, "servo_start_floor": handoff, "link": link,
               "micro_ns": micro, "requirements": reqs, "plots": plots, **peers}
    with open(os.path.join(out, "results.json"), "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1, sort_keys=True)


if __name__ == "__main__":
    main()
