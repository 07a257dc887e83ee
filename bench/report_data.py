"""The system benchmark's raw outputs read back, and the figures' formatting (bench/report.py)."""
import json
import math

PERIODS = (1000, 250, 100)
LOADS = ("idle", "load")


def load_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read().strip()
        return json.loads(text) if text else {}
    except (OSError, ValueError):
        return {}


def read_hist(path):
    """A cyclictest-format histogram: 'bin count' lines (1 us bins), '# Max Latencies' etc."""
    bins, overflows, maximum = [], 0, None
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                parts = line.split()
                if not parts:
                    continue
                if parts[0][0].isdigit() and len(parts) >= 2:
                    bins.append((int(parts[0]), int(parts[1])))
                elif "Max Latencies" in line:
                    maximum = int(parts[-1])
                elif "Histogram Overflows" in line:
                    overflows = int(parts[-1])
    except OSError:
        pass
    return {"bins": bins, "overflows": overflows, "max": maximum}


def hist_stats(h):
    """p50/p99/p99.9 (upper bin edge, us), max and sample count of a histogram."""
    total = sum(c for _, c in h["bins"]) + h["overflows"]
    out = {"samples": total, "max_us": h["max"]}
    for name, q in (("p50_us", 0.5), ("p99_us", 0.99), ("p999_us", 0.999)):
        want, seen, value = q * total, 0, h["max"]
        for us, count in h["bins"]:
            seen += count
            if total and seen >= want:
                value = us + 1
                break
        out[name] = value
    return out


def sample_stats(values):
    values = sorted(values)
    if not values:
        return {"samples": 0}

    def at(q):
        return values[min(len(values) - 1, int(q * len(values)))]

    return {"samples": len(values), "p50_us": at(0.5), "p99_us": at(0.99),
            "p999_us": at(0.999), "max_us": values[-1]}


def read_samples(path):
    try:
        with open(path, encoding="utf-8") as f:
            return [float(line) for line in f if line.strip()]
    except (OSError, ValueError):
        return []


def ratio(a, b):
    if a is None or b is None or not b:
        return None
    return a / b


def fmt(v, digits=1):
    if v is None:
        return "n/a"
    if isinstance(v, float) and (math.isnan(v) or math.isinf(v)):
        return "n/a"
    return f"{v:.{digits}f}" if isinstance(v, float) else str(v)


def samples_at_or_beyond(h, us):
    """Samples of a histogram at `us` or later (overflows are beyond every bin)."""
    return sum(c for b, c in h["bins"] if b >= us) + h["overflows"]


def fmt_ratio(v):
    return "n/a" if v is None else f"{v:.2f}x"


def ns_to_us(summary, key):
    v = summary.get(key)
    return None if v is None else v / 1000.0
