#!/usr/bin/python3
"""Spectral transport against RGB on the vs-Cycles family (issue 65, item 5): for each of the
family's scenes (bench/vs_cycles/scenes.py FAMILY) and its first Dermis variant (the default
walk, the disk probes, the volumetric path tracer on the media), the efficiency of
`dermis render --spectral` against `dermis render`, each against its own mean: per-pixel
variance over seeds x CPU time, the two modes interleaved (bench/compare_efficiency.py).
Blender is not needed: only Dermis renders.

  /usr/bin/python3 -m bench.spectral_cost [--dermis build/dermis] [--spp 16] [--res 64x48]
      [--seeds 6] [--only walk,disk] [--out DIR]

Prints compare_efficiency's table (new = spectral, old = RGB): variance ratio, CPU-time ratio
(the cost per sample), efficiency ratio, and the mean difference in standard errors (large:
the two modes' pictures differ in colour, as they should where light meets colour twice).
"""
import argparse
import os
import subprocess
import sys
import tempfile

from bench.harness import paths
from bench.vs_cycles import pbrt_writer
from bench.vs_cycles import scenes as S


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dermis", default=paths.DERMIS)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", default="64x48")
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--only", default="", help="comma-separated substrings of the scene names to keep")
    ap.add_argument("--out", default="", help="folder for the scene files (default: a temporary one)")
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="dermis-spectral-cost-")
    os.makedirs(out, exist_ok=True)
    keep = [k for k in args.only.split(",") if k]
    files = []
    for name in S.FAMILY:
        if keep and not any(k in name for k in keep):
            continue
        sc = S.SCENES[name]
        label, extra = next(iter(sc["dermis"].items()))
        path = os.path.join(out, f"{name}.pbrt")
        with open(path, "w") as f:
            f.write(pbrt_writer.scene_text(sc, label, extra))
        files.append(path)
    # The spectral mode as a second binary: the same one with --spectral appended.
    wrapper = os.path.join(out, "dermis-spectral")
    with open(wrapper, "w") as f:
        f.write(f'#!/bin/sh\nexec "{os.path.abspath(args.dermis)}" "$@" --spectral\n')
    os.chmod(wrapper, 0o755)
    print(f"scenes in {out}; new = --spectral, old = RGB", flush=True)
    sys.exit(subprocess.call([sys.executable, "-m", "bench.compare_efficiency", args.dermis, wrapper, *files,
                              "--spp", str(args.spp), "--res", args.res, "--seeds", str(args.seeds)]))


if __name__ == "__main__":
    main()
