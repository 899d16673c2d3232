"""A run's progress lines: flushed at once, since a run of minutes is watched as it goes."""
import sys
import time


def log(msg, stream=None, clock=False):
    """One line on `stream` (default: stderr), after the time of day if `clock`."""
    if clock:
        msg = f"[{time.strftime('%H:%M:%S')}] {msg}"
    print(msg, file=stream or sys.stderr, flush=True)
