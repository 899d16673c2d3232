"""Cycles' render times from its own log, to the microsecond.

The EXR stamp `cycles.ViewLayer.render_time` is written by Cycles'
time_human_readable_from_seconds (intern/cycles/util/time.cpp), which keeps
`(int)(seconds * 100) % 100` hundredths: it truncates to 10 ms. The family's renders take
20-200 ms, so the stamp reads Cycles 5 ms faster on average, up to a quarter of a 16-spp
render. Blender run with `--debug-cycles --verbose 2` logs the same two clocks unrounded
(session.cpp: "Total render time: T", "Render time (without synchronization): R"), once
per render, in the order the renders ran.
"""
import re

# The flags that make Blender log them (they turn on Cycles' logging, nothing else).
BLENDER_FLAGS = ["--debug-cycles", "--verbose", "2"]

_TOTAL_RE = re.compile(r"Total render time: ([0-9.eE+-]+)")
_RENDER_RE = re.compile(r"Render time \(without synchronization\): ([0-9.eE+-]+)")


def render_times(log_text):
    """[(render seconds, total seconds)] per render, in order, from Blender's stderr."""
    totals = [float(x) for x in _TOTAL_RE.findall(log_text)]
    renders = [float(x) for x in _RENDER_RE.findall(log_text)]
    if len(totals) != len(renders):
        raise ValueError(f"Cycles' log has {len(totals)} total and {len(renders)} render times")
    return list(zip(renders, totals))


def agrees_with_stamp(seconds, stamp_seconds):
    """Whether a logged time is the one behind an EXR stamp, which truncates it to
    hundredths (within a float's rounding): the check that log lines and renders pair up."""
    return -1e-4 < seconds - stamp_seconds < 0.0101


def main():
    """Per scene of a run.py output folder: Cycles' median render time per sample count as
    logged and as stamped, and their ratio (what the stamp's truncation took off)."""
    import json
    import math
    import os
    import statistics
    import sys

    from bench.harness.exr import read_exr

    if len(sys.argv) != 2:
        sys.exit("usage: python3 -m bench.vs_cycles.cycles_log RUN_FOLDER   (run.py's --out)")
    root = sys.argv[1]
    for name in sorted(os.listdir(root)):
        folder = os.path.join(root, name)
        if not os.path.exists(os.path.join(folder, "cycles-log.txt")):
            continue
        renders = json.load(open(os.path.join(folder, "cycles-result.json")))["renders"]
        logged = render_times(open(os.path.join(folder, "cycles-log.txt")).read())
        by_spp = {}
        for r, (seconds, _) in zip(renders, logged):
            if "time_limit" in r and r["time_limit"]:
                continue  # a reference
            stamp = read_exr(r["out"]).attrs["cycles.ViewLayer.render_time"]
            minutes, secs = stamp.split(":")[-2:]
            by_spp.setdefault(r["spp"], []).append((seconds, 60 * int(minutes) + float(secs)))
        ratios, cells = [], []
        for spp, pairs in sorted(by_spp.items()):
            t, s = statistics.median(p[0] for p in pairs), statistics.median(p[1] for p in pairs)
            ratios.append(t / s)
            cells.append(f"{spp} spp {t:.4f} s / stamp {s:.2f} s = {t / s:.3f}")
        if ratios:
            gm = math.exp(sum(map(math.log, ratios)) / len(ratios))
            print(f"{name}: " + "; ".join(cells) + f"; geometric mean {gm:.3f}")


if __name__ == "__main__":
    main()
