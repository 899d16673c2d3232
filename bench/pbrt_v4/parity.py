#!/usr/bin/python3
"""pbrt-v4's means of the parity scenes (bench/pbrt_v4/parity/*.pbrt), for the test that holds
Dermis --spectral to them (src/dermis/render/spectral_pbrt_v4_parity_test.cpp).

  /usr/bin/python3 -m bench.pbrt_v4.parity --pbrt /path/to/pbrt [--spp 2048] [--seeds 8]

pbrt-v4 is not part of Dermis: build it yourself, outside the repository. Each scene is
rendered --seeds times (seeds 1..K) at --spp; per channel the image's mean and its standard
error, pooled from the per-pixel variance over the seeds (bench/pbrt_v4/compare.py
pooled_mean_se). Prints the C++ table the test holds, with the pbrt-v4 binary's version.
"""
import argparse
import glob
import os
import subprocess
import tempfile

import numpy as np

from bench.harness.exr import read_exr
from bench.pbrt_v4.compare import pooled_mean_se

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "parity")


def render(pbrt, scene, spp, seed, out):
    subprocess.run(["nice", "-n", "19", pbrt, "--quiet", "--nthreads", "2", "--spp", str(spp), "--seed", str(seed),
                    "--outfile", out, scene], check=True)
    return read_exr(out).rgb


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pbrt", default=os.environ.get("PBRT_V4"), required=os.environ.get("PBRT_V4") is None)
    ap.add_argument("--spp", type=int, default=2048)
    ap.add_argument("--seeds", type=int, default=8)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for scene in sorted(glob.glob(os.path.join(HERE, "*.pbrt"))):
            name = os.path.splitext(os.path.basename(scene))[0]
            imgs = np.stack([render(args.pbrt, scene, args.spp, s, os.path.join(tmp, f"{name}-{s}.exr"))
                             for s in range(1, args.seeds + 1)])
            mean, se = pooled_mean_se(imgs)
            print(f'    {{"{name}", {{{mean[0]:.6f}, {mean[1]:.6f}, {mean[2]:.6f}}}, '
                  f'{{{se[0]:.6f}, {se[1]:.6f}, {se[2]:.6f}}}}},')


if __name__ == "__main__":
    main()
