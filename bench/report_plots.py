"""The system benchmark's plots, drawn with gnuplot (bench/report.py)."""
import os
import subprocess

from report_data import LOADS, PERIODS, read_hist, read_samples


def write_plots(out, raw, lat):
    """Latency histograms (core vs cyclictest, log scale) and the RTT CDF against UDP."""
    plots = []
    for period in PERIODS:
        series = []
        for load in LOADS:
            for who, suffix in (("core", "core.hist"), ("cyclictest", "cyclictest.hist")):
                h = read_hist(os.path.join(raw, f"lat-{period}-{load}.{suffix}"))
                dat = os.path.join(raw, f"plot-lat-{period}-{load}-{who}.dat")
                with open(dat, "w", encoding="utf-8") as f:
                    for us, count in h["bins"]:
                        if count:
                            f.write(f"{us + 0.5} {count}\n")
                if os.path.getsize(dat):
                    series.append((dat, f"{who} {load}"))
        png = f"latency-{period}us.png"
        script = [
            "set terminal pngcairo size 900,500" if has_pngcairo() else "set terminal png size 900,500",
            f"set output '{os.path.join(out, png)}'",
            f"set title 'Wake-up latency at {period} us: hapticctrl-core vs cyclictest'",
            "set xlabel 'latency (us)'", "set ylabel 'cycles'", "set logscale y", "set logscale x",
            "set yrange [0.5:*]",
            "set grid",
        ]
        if series:
            script.append("plot " + ", ".join(f"'{d}' using 1:2 with steps title '{t}'" for d, t in series))
        else:
            script.append("set label 'no samples' at graph 0.5,0.5 center")
            script.append("plot 1 notitle")
        run_gnuplot(script)
        plots.append(png)
    series = []
    for load in LOADS:
        for who, suffix in (("client via bridge+core", "client_rtt"), ("raw UDP", "udp_rtt")):
            values = sorted(read_samples(os.path.join(raw, f"link-{load}.{suffix}")))
            dat = os.path.join(raw, f"plot-cdf-{load}-{suffix}.dat")
            with open(dat, "w", encoding="utf-8") as f:
                step = max(1, len(values) // 2000)
                for i in range(0, len(values), step):
                    f.write(f"{values[i]} {(i + 1) / len(values)}\n")
            if values:
                series.append((dat, f"{who}, {load}"))
    script = [
        "set terminal pngcairo size 900,500" if has_pngcairo() else "set terminal png size 900,500",
        f"set output '{os.path.join(out, 'rtt-cdf.png')}'",
        "set title 'Round trip at 1 kHz: client through hapticctrl-udp and the core vs raw UDP'",
        "set xlabel 'round-trip time (us)'", "set ylabel 'fraction of samples'", "set logscale x",
        "set key bottom right", "set grid", "set yrange [0:1]",
    ]
    if series:
        script.append("plot " + ", ".join(f"'{d}' using 1:2 with lines title '{t}'" for d, t in series))
    else:
        script.append("plot 1 notitle")
    run_gnuplot(script)
    plots.append("rtt-cdf.png")
    return plots


_PNGCAIRO = None


def has_pngcairo():
    global _PNGCAIRO
    if _PNGCAIRO is None:
        # Never the caller's terminal as its input: gnuplot pages the list there (J8).
        r = subprocess.run(["gnuplot", "-e", "set terminal"], capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, check=False)
        _PNGCAIRO = "pngcairo" in (r.stdout + r.stderr)
    return _PNGCAIRO


def run_gnuplot(lines):
    subprocess.run(["gnuplot"], input="\n".join(lines) + "\n", text=True, check=True)
