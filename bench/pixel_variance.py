#!/usr/bin/python3
"""Per-pixel variance and mean of one dermis build on scene variants, by channel: where a
scene's noise is (which light, which scattering orders, which channel), measured by
rendering each variant over seeds.

  /usr/bin/python3 -m bench.pixel_variance DERMIS SCENE.pbrt [SCENE ...] [--spp 32]
      [--res 96x96] [--seeds 8] [--threads 2] [--mask-from SCENE.pbrt]

Each scene is rendered with seeds 1..N; the variance of each pixel over the seeds (of the
N images of --spp samples each) and its mean are averaged over the pixels of the mask, per
channel and over R, G, B. The mask: the pixels with a non-zero mean in the first scene, or in
--mask-from (e.g. a variant with the environment light off, whose background is black: the
object's pixels). Also printed: the share of the summed variance held by the 1 % and 10 %
noisiest pixels, and the render-stage time (median over the seeds, as `dermis render` prints
it in milliseconds). Variants are plain scene files: write them with sed (a Integrator
"maxdepth" of 1, 2, 4 splits the noise by scattering order; a light's L set to 0 splits it
by light).
"""
import argparse
import os
import statistics
import tempfile

import numpy as np

from bench.harness import render
from bench.harness.exr import read_exr


def render_once(binary, scene, seed, args, out):
    """The image of one render and its printed render time (NaN if none)."""
    r = render.render(binary, scene, out, spp=args.spp, res=args.res, seed=seed, threads=args.threads)
    stats = render.render_stats(r.log)
    img = read_exr(out).rgb
    os.remove(out)
    return img, stats.seconds if stats else float("nan")


def images(binary, scene, args, out):
    runs = [render_once(binary, scene, s, args, out) for s in range(1, args.seeds + 1)]
    return np.array([r[0] for r in runs]), statistics.median(r[1] for r in runs)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dermis")
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--res", default="96x96")
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--mask-from")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "image.exr")
        mask_scene = args.mask_from or args.scenes[0]
        mask_images, _ = images(args.dermis, mask_scene, args, out)
        mask = mask_images.mean(0).sum(-1) > 0
        print(f"mask: {int(mask.sum())} pixels (non-zero mean in {os.path.basename(mask_scene)}); "
              f"{args.seeds} seeds x {args.spp} spp, {args.res}")
        print(f"{'scene':28s} {'variance':>10s} {'R':>10s} {'G':>10s} {'B':>10s} {'mean':>8s} {'R':>8s} {'G':>8s} "
              f"{'B':>8s} {'top1%':>6s} {'top10%':>6s} {'time s':>7s}")
        for scene in args.scenes:
            a, seconds = images(args.dermis, scene, args, out)
            var = a.var(0, ddof=1)[mask]  # pixels x channels
            mean = a.mean(0)[mask]
            per_pixel = np.sort(var.mean(-1))[::-1]
            top = [per_pixel[:max(1, int(len(per_pixel) * f))].sum() / per_pixel.sum() for f in (0.01, 0.1)]
            vc, mc = var.mean(0), mean.mean(0)
            print(f"{os.path.basename(scene):28s} {var.mean():10.3e} {vc[0]:10.3e} {vc[1]:10.3e} {vc[2]:10.3e} "
                  f"{mean.mean():8.4f} {mc[0]:8.4f} {mc[1]:8.4f} {mc[2]:8.4f} {top[0]:6.3f} {top[1]:6.3f} "
                  f"{seconds:7.3f}", flush=True)


if __name__ == "__main__":
    main()
