#!/usr/bin/python3
"""Efficiency of two dermis builds on the same scenes: per-pixel variance over seeds x CPU time,
run interleaved in one session (the machine is shared and noisy: only ratios measured in one
run mean anything).

  /usr/bin/python3 -m bench.compare_efficiency OLD_DERMIS NEW_DERMIS SCENE.pbrt [SCENE ...]
      [--spp 16] [--res 96x96] [--seeds 6] [--threads 1] [--time cpu|render]

For each build and scene: --seeds renders (seeds 1..N, the two builds alternating); the
variance of each pixel over the seeds, averaged over the pixels with a non-zero mean (the
object; the background's variance is zero), and the CPU time of the process (user + system,
from the kernel: less sensitive to other load than wall time; it includes parsing and scene
preparation, so render enough samples that those are small), or with --time render the
render-stage time `dermis render` prints in milliseconds (wall time of the tiles alone: what a
change of the per-sample cost moves; builds before 2026-12-03 print 0.1 s steps).
Efficiency = 1 / (variance x time).
With --mask-dir DIR the variance is taken over the pixels an object covers fully instead (the
convention of bench/vs_cycles: silhouettes, whose noise is mostly the pixel's coverage, left
out): DIR holds coverage images (1 where the object covers a pixel, e.g. the object rendered as
a unit emitter, as bench/vs_cycles/pbrt_writer.py mask_text writes it), and a scene's is the one
whose name (without .exr) is the longest prefix of the scene file's name; pixels above 0.999.
The mean images of the two builds are compared too: |mean difference| in standard errors,
averaged over those pixels (≈ 0.8 for two unbiased builds of the same estimand; a build that
changed the image shows much more).
"""
import argparse
import os
import statistics
import tempfile

import numpy as np

from bench.harness import render
from bench.harness.exr import read_exr


def render_once(binary, scene, seed, args, out):
    """The image and the time of one render (the process's CPU time, or its printed render time)."""
    r = render.render(binary, scene, out, spp=args.spp, res=args.res, seed=seed, threads=args.threads)
    cpu = r.cpu
    if args.time == "render":
        cpu = max(render.render_stats(r.log).seconds, 1e-3)  # printed in ms
    img = read_exr(out).rgb
    os.remove(out)
    return img, cpu


def coverage(mask_dir, scene, shape):
    """The coverage image of `scene` in mask_dir (the longest prefix of its name), one channel."""
    base = os.path.basename(scene)
    names = [f[:-4] for f in os.listdir(mask_dir) if f.endswith(".exr") and base.startswith(f[:-4])]
    if not names:
        raise SystemExit(f"{mask_dir}: no coverage image for {base} (its name must begin with the image's)")
    img = read_exr(os.path.join(mask_dir, max(names, key=len) + ".exr")).rgb.mean(axis=2)
    if img.shape != shape:
        raise SystemExit(f"{base}: the coverage image is {img.shape[1]}x{img.shape[0]}, the renders "
                         f"{shape[1]}x{shape[0]}")
    return img


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", default="96x96")
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--time", choices=["cpu", "render"], default="cpu",
                    help="process CPU time (default) or the printed render-stage time")
    ap.add_argument("--mask-dir", help="coverage images: variance over the fully covered pixels only")
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="dermis-efficiency-")
    print(f"| scene | variance new/old | {'CPU' if args.time == 'cpu' else 'render time'} new/old | **efficiency new/old** | mean diff (std. errors) |")
    print("|---|---|---|---|---|")
    for scene in args.scenes:
        images = {"old": [], "new": []}
        cpu = {"old": [], "new": []}
        for seed in range(1, args.seeds + 1):
            for name, binary in (("old", args.old), ("new", args.new)) if seed % 2 else (("new", args.new),
                                                                                       ("old", args.old)):
                img, t = render_once(binary, scene, seed, args, os.path.join(work, f"{name}-{seed}.exr"))
                images[name].append(img)
                cpu[name].append(t)
        stats = {}
        for name in ("old", "new"):
            a = np.array(images[name])
            stats[name] = (a.mean(axis=0), a.var(axis=0, ddof=1))
        covered = (stats["old"][0].mean(axis=2) > 0) & (stats["new"][0].mean(axis=2) > 0)
        if args.mask_dir:
            covered = covered & (coverage(args.mask_dir, scene, covered.shape) > 0.999)
        var = {k: stats[k][1].mean(axis=2)[covered].mean() for k in stats}
        t = {k: statistics.median(cpu[k]) for k in cpu}
        se = np.sqrt((stats["old"][1] + stats["new"][1]) / args.seeds).mean(axis=2)[covered]
        z = (np.abs(stats["old"][0] - stats["new"][0]).mean(axis=2)[covered] / np.maximum(se, 1e-30)).mean()
        eff = var["old"] * t["old"] / (var["new"] * t["new"])
        print(f"| {os.path.basename(scene)} | {var['new'] / var['old']:.3f} | {t['new'] / t['old']:.3f} "
              f"| **{eff:.2f}** | {z:.2f} |", flush=True)


if __name__ == "__main__":
    main()
