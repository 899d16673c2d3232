#!/usr/bin/python3
"""Runs `dermis` on every case of the hostile corpus (generate.py) and checks each:
no signal, the exit status the case expects (0 or 2), a message on stderr for every
refusal, `file:line:col: error:` in every scene error, a short message (no 10 MB echo),
no output file after a refusal, an image after a success, and no case slower than
--slow seconds. Cases run in a small thread pool. Exit 0 when every case passes.

Usage: run.py --binary build/dermis --work DIR [--jobs 3] [--only SUBSTRING]"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import re
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(HERE))
import generate  # noqa: E402

SCENE_ERROR = re.compile(r"\S+:\d+:\d+: error: ")
MAX_MESSAGE = 8192  # bytes of stderr a refusal may print


def listing(d):
    return sorted(str(p.relative_to(d)) for p in d.rglob("*"))


def run_case(binary, d, timeout, slow):
    meta = json.loads((d / "case.json").read_text())
    out = d / "out"
    before = listing(out)
    start = time.monotonic()
    try:
        p = subprocess.run([binary] + meta["args"], cwd=d, stdin=subprocess.DEVNULL, capture_output=True,
                           timeout=timeout)
        rc, err = p.returncode, p.stderr.decode(errors="replace")
    except subprocess.TimeoutExpired as e:
        rc, err = None, (e.stderr or b"").decode(errors="replace")
    took = time.monotonic() - start
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
        problems.append(f"took {took:.1f} s (more than {slow} s)")
    return d.name, rc, took, err, problems, meta


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--jobs", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=30, help="seconds before a case is killed as a hang")
    ap.add_argument("--slow", type=float, default=10, help="seconds a case may take")
    ap.add_argument("--only", default="", help="run the cases whose name contains this")
    a = ap.parse_args()
    binary = os.path.abspath(a.binary)
    cases_dir = pathlib.Path(a.work) / "cases"
    n = generate.write(cases_dir)
    dirs = sorted(d for d in cases_dir.iterdir() if a.only in d.name)
    start = time.monotonic()
    results = []
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for r in pool.map(lambda d: run_case(binary, d, a.timeout, a.slow), dirs):
            results.append(r)
    failed = [r for r in results if r[4]]
    for name, rc, took, err, problems, meta in failed:
        print(f"FAIL {name} (exit {rc}, {took:.1f} s): {'; '.join(problems)}")
        print("     args:", " ".join(meta["args"]))
        print("     stderr:", err.strip()[:300].replace("\n", "\n             "))
    refused = sum(1 for r in results if r[1] == 2)
    rendered = sum(1 for r in results if r[1] == 0)
    slowest = max(results, key=lambda r: r[2]) if results else None
    print(f"hostile corpus: {len(results)} of {n} cases run in {time.monotonic() - start:.1f} s, "
          f"{refused} refused with exit 2, {rendered} rendered, {len(failed)} failed"
          + (f"; slowest {slowest[0]} {slowest[2]:.1f} s" if slowest else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
