"""The peer benchmark's section of the report (H8): hapticctrl's seqlock regions side by side
with iceoryx, LCM, UDP and DDS (the middleware of hapticctrl-dds, H7), from OUT_DIR/raw/peers.json (hapticctrl-bench-peers), with every figure
as a ratio against the best peer in the same run, and the latency distributions' plot."""
import os

from report_data import fmt, load_json
from report_plots import has_pngcairo, run_gnuplot

# Each column: its title, how to read it from a case, and whether smaller is better (all are).
COLUMNS = (
    ("latency p50 (us)", lambda c: c["latency_us"]["p50"]),
    ("p99", lambda c: c["latency_us"]["p99"]),
    ("p99.9", lambda c: c["latency_us"]["p999"]),
    ("max", lambda c: c["latency_us"]["max"]),
    ("read (ns)", lambda c: c["read_ns"]["p50"]),
    ("publish (ns)", lambda c: c["publish_ns"]["p50"]),
    ("CPU us / 1000 msgs at 1 kHz (writer + reader)",
     lambda c: c["cpu_us_per_1000"]["1000"]["writer"] + c["cpu_us_per_1000"]["1000"]["reader"]),
    ("at 10 kHz", lambda c: c["cpu_us_per_1000"]["10000"]["writer"] + c["cpu_us_per_1000"]["10000"]["reader"]),
    ("publish max, reader stopped (us)", lambda c: c["stall"]["stopped"]["publish_max_us"]),
    ("reader killed (us)", lambda c: c["stall"]["killed"]["publish_max_us"]),
)


def cases_of(raw):
    doc = load_json(os.path.join(raw, "peers.json"))
    return doc, [c for c in doc.get("cases", []) if not c.get("error")]


def name_of(case):
    return f"{case['transport']} ({case['mode']})"


def table_rows(cases):
    rows = []
    best = [min((get(c) for c in cases), default=0) for _, get in COLUMNS]
    for c in cases:
        row = [name_of(c)]
        for (_, get), b in zip(COLUMNS, best):
            v = get(c)
            ratio = "best" if v == b else (f"{v / b:.1f}x" if b > 0 else "-")
            row.append(f"{fmt(v, 2 if v < 10 else 1)} ({ratio})")
        rows.append(row)
    return rows


def write_plot(out, raw, cases):
    png = "peers-latency.png"
    series = []
    for i, c in enumerate(cases):
        dat = os.path.join(raw, f"plot-peers-{i}.dat")
        with open(dat, "w", encoding="utf-8") as f:
            for q, us in c.get("cdf_us", []):
                f.write(f"{max(us, 0.01)} {q}\n")
        series.append((dat, name_of(c)))
    script = [
        "set terminal pngcairo size 900,500" if has_pngcairo() else "set terminal png size 900,500",
        f"set output '{os.path.join(out, png)}'",
        "set title 'Publish -> observed latency, cross-process, 1 kHz (CDF)'",
        "set xlabel 'latency (us)'", "set ylabel 'share of messages'", "set logscale x",
        "set key bottom right", "set grid",
    ]
    if series:
        script.append("plot " + ", ".join(f"'{d}' using 1:2 with linespoints title '{t}'" for d, t in series))
    else:
        script += ["set label 'no samples' at graph 0.5,0.5 center", "plot 1 notitle"]
    run_gnuplot(script)
    return png


def dds_added(cases):
    """What the DDS path (hapticctrl-dds's Cyclone DDS, sensor-data QoS) adds against the
    telemetry bus (LCM) and the client protocol's transport (UDP), woken readers all."""
    woken = {c["transport"]: c["latency_us"] for c in cases if c["mode"] == "wake"}
    if "dds" not in woken:
        return []
    d = woken["dds"]
    against = [f"{d[q] - woken[peer][q]:+.1f} us at {label} against {peer.upper()}"
               for peer in ("lcm", "udp") if peer in woken for q, label in (("p50", "p50"), ("p99", "p99"))]
    return ["", f"The DDS path (H7, hapticctrl-dds's middleware: Cyclone DDS, ROS 2's sensor-data QoS) "
                f"adds, message for message in this run: " + ", ".join(against) + "."]


def section(out, raw, table):
    """The report's lines, and what results.json keeps."""
    doc, cases = cases_of(raw)
    failed = [c for c in doc.get("cases", []) if c.get("error")]
    md = ["", "## 5. Side by side with the peers: seqlock regions, iceoryx, LCM, UDP, DDS", ""]
    if not doc:
        return md + ["Not run (no raw/peers.json).", ""], {}
    md.append(f"One run of `hapticctrl-bench-peers`: writer on CPU {doc.get('writer_cpu')}, reader on "
              f"CPU {doc.get('reader_cpu')}, the writer and a woken reader at SCHED_FIFO {doc.get('priority')}, "
              f"a polling reader at SCHED_OTHER (it spins; at SCHED_FIFO, RT throttling took 50 ms of each "
              f"second from it); "
              f"the payload is a VP sample; latency runs of {doc.get('messages')} messages at 1 kHz, "
              f"median of {doc.get('repeats')} runs; costs net of one clock read "
              f"({doc.get('clock_read_ns')} ns). Each figure: (ratio to the best peer in this run).")
    md += ["", table(["transport (read)"] + [t for t, _ in COLUMNS], table_rows(cases)), ""]
    md.append("Failed publishes in the stall runs: " + ", ".join(
        f"{name_of(c)} {c['stall']['failed_publishes']}" for c in cases) + ".")
    for c in failed:
        md.append(f"- {c['transport']}: not measured: {c['error']}")
    md += dds_added(cases)
    png = write_plot(out, raw, cases)
    md += ["", f"![latency distributions]({png})", ""]
    return md, {"peers": doc, "peers_plot": png}
