#!/usr/bin/python3
"""What the live preview costs the render: the same render (scene, samples, seed, threads)
without and with `--preview`, while a client asks for the status and the image four times a
second (as the page does), the two interleaved; the render stage's seconds ("wrote ... in X
s") of each, and their ratio per pair (the machine is shared: pairs, not totals).

Usage: python3 -m bench.preview_overhead BINARY SCENE [--reps 5] [--spp 64] [--threads 2]"""
import argparse
import re
import statistics
import subprocess
import tempfile
import threading
import time
import urllib.request


def render(binary, scene, out, spp, threads, preview):
    args = [binary, "render", scene, "--spp", str(spp), "--threads", str(threads), "-o", out, "--seed", "1"]
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
    proc.wait(timeout=3600)
    reader.join()
    m = next((re.search(r"wrote .* in ([0-9.]+) s", line) for line in lines if "wrote" in line), None)
    if not m:
        raise SystemExit("no 'wrote ... in X s' line:\n" + "".join(lines))
    return float(m[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("scene")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = f"{tmp}/out.exr"
        ratios, plain, live = [], [], []
        for i in range(a.reps):
            order = (False, True) if i % 2 == 0 else (True, False)
            t = {p: render(a.binary, a.scene, out, a.spp, a.threads, p) for p in order}
            plain.append(t[False]), live.append(t[True]), ratios.append(t[True] / t[False])
            print(f"rep {i}: without {t[False]:.3f} s, with the preview watched {t[True]:.3f} s, "
                  f"ratio {ratios[-1]:.4f}", flush=True)
    print(f"median ratio {statistics.median(ratios):.4f} (min {min(ratios):.4f}, max {max(ratios):.4f}); "
          f"median seconds {statistics.median(plain):.3f} without, {statistics.median(live):.3f} with")


if __name__ == "__main__":
    main()
