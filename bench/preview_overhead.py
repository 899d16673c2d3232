#!/usr/bin/python3
"""What the live preview costs the render: the same render (scene, samples, seed, threads)
without and with `--preview`, while a client asks for the status and the image four times a
second (as the page does), the two interleaved; the render stage's seconds ("wrote ... in X
s") of each and the process's CPU seconds (the server's included), and their ratios per
pair (the machine is shared: pairs, not totals), with the median's 95 % interval
(bootstrap over the pairs).

Then the preview's direct cost, measured on the threads that pay it (the render prints
it: the server's threads' CPU seconds, and the render threads' in LiveImage::copy_tile),
as a share of the render's capacity (its seconds x its threads). A shared machine's noise
scales the cost and the capacity alike, so this share is steady where the ratios are not;
what it leaves out (caches, the client's own CPU) the ratios bound.

Usage: python3 -m bench.preview_overhead BINARY SCENE [--reps 5] [--spp 64] [--threads 2] [--res WxH]
       [--no-client]"""
import argparse
import os
import random
import re
import statistics
import subprocess
import tempfile
import threading
import time
import urllib.request


def render(binary, scene, out, spp, threads, preview, res=None, client=True):
    args = [binary, "render", scene, "--spp", str(spp), "--threads", str(threads), "-o", out, "--seed", "1"]
    if res:
        args += ["--res", res]
    if preview:
        args += ["--preview", "0"]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines, stop = [], threading.Event()

    def watch():  # the page's requests: status and image, 4 per second
        url = None
        for line in proc.stderr:
            lines.append(line)
            m = re.search(r"preview: (\S+)", line)
            if m and url is None:
                url = m[1]
                if client:
                    threading.Thread(target=poll, args=(url,), daemon=True).start()
            if "wrote" in line:
                stop.set()
                if preview:
                    proc.send_signal(2)  # the preview serves until Ctrl-C

    def poll(url):
        while not stop.is_set():
            for path in ("status.json", "image.png?exposure=0.0"):
                try:
                    urllib.request.urlopen(url + path, timeout=5).read()
                except OSError:
                    pass
            time.sleep(0.25)

    reader = threading.Thread(target=watch)
    reader.start()
    _, _, usage = os.wait4(proc.pid, 0)  # the process's CPU time: the render's and the server's
    proc.returncode = 0
    reader.join()
    m = next((re.search(r"wrote .* in ([0-9.]+) s", line) for line in lines if "wrote" in line), None)
    if not m:
        raise SystemExit("no 'wrote ... in X s' line:\n" + "".join(lines))
    cost = None
    if preview:
        c = next((re.search(r"preview so far: (\d+) requests answered in ([0-9.]+) CPU s; ([0-9.]+) CPU s copying", line)
                  for line in lines if "preview so far" in line), None)
        if not c:
            raise SystemExit("no 'the preview so far' line:\n" + "".join(lines))
        cost = (int(c[1]), float(c[2]), float(c[3]))
    return float(m[1]), usage.ru_utime + usage.ru_stime, cost


def median_interval(values, draws=2000, seed=1):
    """The median's 95 % bootstrap interval."""
    rng = random.Random(seed)
    medians = sorted(statistics.median(rng.choices(values, k=len(values))) for _ in range(draws))
    return medians[int(0.025 * draws)], medians[int(0.975 * draws) - 1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("scene")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--res", help="WIDTHxHEIGHT, overriding the scene's")
    ap.add_argument("--no-client", action="store_true", help="the preview served, nobody asking (its cost alone)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = f"{tmp}/out.exr"
        ratios, cpu_ratios, shares = [], [], []
        for i in range(a.reps):
            order = (False, True) if i % 2 == 0 else (True, False)
            t = {p: render(a.binary, a.scene, out, a.spp, a.threads, p, a.res, not a.no_client) for p in order}
            ratios.append(t[True][0] / t[False][0])
            cpu_ratios.append(t[True][1] / t[False][1])
            requests, server_cpu, copy_cpu = t[True][2]
            shares.append((server_cpu + copy_cpu) / (t[True][0] * a.threads))
            print(f"rep {i}: render seconds without {t[False][0]:.3f}, with the preview watched {t[True][0]:.3f} "
                  f"(ratio {ratios[-1]:.4f}); process CPU seconds {t[False][1]:.2f}, {t[True][1]:.2f} "
                  f"(ratio {cpu_ratios[-1]:.4f}); the preview: {requests} requests, {server_cpu:.3f} CPU s serving, "
                  f"{copy_cpu:.3f} CPU s copying tiles: {100 * shares[-1]:.2f} % of the render's capacity", flush=True)
    for name, r in (("render seconds", ratios), ("process CPU seconds", cpu_ratios)):
        lo, hi = median_interval(r)
        print(f"{name}: median ratio with/without {statistics.median(r):.4f} (95 % interval {lo:.4f} - {hi:.4f}; "
              f"min {min(r):.4f}, max {max(r):.4f})")
    print(f"the preview's direct cost: median {100 * statistics.median(shares):.2f} % of the render's capacity "
          f"(min {100 * min(shares):.2f} %, max {100 * max(shares):.2f} %)")


if __name__ == "__main__":
    main()
