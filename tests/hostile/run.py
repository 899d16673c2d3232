#!/usr/bin/python3
"""Runs `dermis` on every case of the hostile corpus (generate.py) and checks each:
no signal, the exit status the case expects (0 or 2), a message on stderr for every
refusal, `file:line:col: error:` in every scene error, a short message (no 10 MB echo),
no output file after a refusal, an image after a success, and no case using more than
--slow seconds of CPU (a hang: more than --timeout seconds on the clock). Cases run in a small thread pool. Exit 0 when every case passes.
`--shard I/N` runs every N-th case from the I-th (ctest runs N shards side by side).

Usage: run.py --binary build/dermis --work DIR [--jobs 3] [--only SUBSTRING] [--shard I/N]"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import threading
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(HERE))
import generate  # noqa: E402

SCENE_ERROR = re.compile(r"\S+:\d+:\d+: error: ")
MAX_MESSAGE = 8192  # bytes of stderr a refusal may print


def listing(d):
    return sorted(str(p.relative_to(d)) for p in d.rglob("*"))


def run(args, cwd, timeout):
    """Runs args; returns (exit status or None when killed as a hang, stderr, CPU seconds of
    the process). CPU time, not wall time, is what --slow bounds: a loaded machine makes
    every case slow on the clock, only a pathological input makes one cost CPU."""
    with tempfile.TemporaryFile() as err:
        p = subprocess.Popen(args, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err)
        killed = threading.Event()

        def kill():
            killed.set()
            p.kill()
        timer = threading.Timer(timeout, kill)
        timer.start()
        _, status, usage = os.wait4(p.pid, 0)
        timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
        err.seek(0)
        text = err.read().decode(errors="replace")
    return (None if killed.is_set() else p.returncode), text, usage.ru_utime + usage.ru_stime


def run_case(binary, d, timeout, slow):
    meta = json.loads((d / "case.json").read_text())
    out = d / "out"
    before = listing(out)
    rc, err, took = run([binary] + meta["args"], d, timeout)
    problems = []
    if rc is None:
        problems.append(f"hang: killed after {timeout} s")
    elif rc < 0:
        problems.append(f"crash: signal {-rc}")
    elif rc != meta["expect"]:
        problems.append(f"exit status {rc}, expected {meta['expect']}")
    if rc == 2 and not err.strip():
        problems.append("refused with no message on stderr")
    if rc == 2 and meta["kind"] == "scene" and not SCENE_ERROR.search(err):
        problems.append("scene error without file:line:col: error:")
    if re.search(r"\d{100}", err):
        problems.append("a number of 100+ digits in the message")
    if len(err) > MAX_MESSAGE:
        problems.append(f"{len(err)} bytes on stderr (input echoed?)")
    if rc != 0 and listing(out) != before:
        problems.append(f"output written on error: {sorted(set(listing(out)) - set(before))}")
    if rc == 0 and meta["expect"] == 0 and not (out / "image.exr").exists():
        problems.append("exit 0 but no image written")
    if took > slow and rc is not None:
        problems.append(f"took {took:.1f} s of CPU (more than {slow} s)")
    return d.name, rc, took, err, problems, meta


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--jobs", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=60, help="seconds (wall) before a case is killed as a hang")
    ap.add_argument("--slow", type=float, default=10, help="seconds of CPU a case may take")
    ap.add_argument("--only", default="", help="run the cases whose name contains this")
    ap.add_argument("--shard", default="0/1", help="I/N: run shard I (from 0) of N")
    a = ap.parse_args()
    try:
        index, count = (int(v) for v in a.shard.split("/"))
        assert 0 <= index < count
    except (ValueError, AssertionError):
        ap.error(f"--shard must be I/N with 0 <= I < N, got {a.shard!r}")
    binary = os.path.abspath(a.binary)
    cases_dir = pathlib.Path(a.work) / "cases"
    names = {name for name in generate.shard(index, count) if a.only in name}
    n = generate.write(cases_dir, names)
    dirs = sorted(d for d in cases_dir.iterdir())
    start = time.monotonic()
    results = []
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for r in pool.map(lambda d: run_case(binary, d, a.timeout, a.slow), dirs):
            results.append(r)
    failed = [r for r in results if r[4]]
    for name, rc, took, err, problems, meta in failed:
        print(f"FAIL {name} (exit {rc}, {took:.1f} CPU-s): {'; '.join(problems)}")
        print("     args:", " ".join(meta["args"]))
        print("     stderr:", err.strip()[:300].replace("\n", "\n             "))
    refused = sum(1 for r in results if r[1] == 2)
    rendered = sum(1 for r in results if r[1] == 0)
    slowest = max(results, key=lambda r: r[2]) if results else None
    print(f"hostile corpus{'' if count == 1 else f' shard {index}/{count}'}: {len(results)} of {n} cases run in {time.monotonic() - start:.1f} s, "
          f"{refused} refused with exit 2, {rendered} rendered, {len(failed)} failed"
          + (f"; {sum(r[2] for r in results):.1f} CPU-s in all, the most {slowest[0]} {slowest[2]:.1f} CPU-s"
             if slowest else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
