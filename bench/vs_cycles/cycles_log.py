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
