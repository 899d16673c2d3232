#!/usr/bin/python3
"""What a grid interior costs the random walk (issue 67, item 3), in one run with the renders
interleaved (this machine is shared and noisy). A unit sphere of subsurface material (the
`dielectric` boundary, eta 1.4, given) under a sky and a distant light, filled:
- "homogeneous": with a homogeneous medium (the homogeneous walk, its pilot and guiding);
- "constant grid": with a uniformgrid of constant density 1 and the same coefficients, which
  the walk follows by null collisions (render/subsurface/heterogeneous_walk.h): the same
  picture, so both are measured against one reference (the homogeneous walk at --ref-spp);
- "veined grid, walk" and "veined grid, volumetric": a random 6^3 grid (as the tests'),
  walked, and rendered by the volumetric path tracer (the `volumetric` method), each against
  the volumetric method's reference at --ref-spp.
Efficiency = 1 / (MSE x render time), MSE over the sphere's pixels, averaged over --seeds
renders of --spp samples; ratios against the homogeneous walk and the volumetric method.

  /usr/bin/python3 -m bench.grid_interior_cost [--dermis build/dermis] [--spp 16] [--ref-spp 1024]
      [--seeds 4] [--res 64x64] [--out DIR]
"""
import argparse
import os
import random
import statistics
import subprocess
import tempfile

import numpy as np

from bench.harness import paths
from bench.harness.exr import read_exr
from bench.harness.render import command, render_stats

HEAD = """LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Integrator "volpath" "integer maxdepth" 1000
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.55 0.6]
LightSource "distant" "point3 from" [1 2 -1] "point3 to" [0 0 0] "rgb L" [3 3 3]
"""
COEFFICIENTS = '"rgb sigma_a" [0.05 0.2 0.5] "rgb sigma_s" [2 3 4] "float g" 0.3'
BOX = '"point3 p0" [-1.2 -1.2 -1.2] "point3 p1" [1.2 1.2 1.2]'


def material(interior, method=""):
    # The `dielectric` boundary, given: beside the distant light the walk's default would be
    # the diffuse one (docs/materials.md, "Which boundary"), not the volumetric method's glass.
    return (f'Material "subsurface" "string interior" "{interior}" "float eta" 1.4 "string boundary" "dielectric" '
            f'{method}\nShape "sphere"\n')


def scenes(out):
    rng = random.Random(5)
    veins = " ".join(str(0.05 if rng.random() < 0.33 else 2 * rng.random()) for _ in range(216))
    ones = " 1" * 512
    media = (f'MakeNamedMedium "hom" "string type" "homogeneous" {COEFFICIENTS}\n'
             f'MakeNamedMedium "const" "string type" "uniformgrid" {COEFFICIENTS} {BOX} '
             f'"integer nx" 8 "integer ny" 8 "integer nz" 8 "float density" [{ones}]\n'
             f'MakeNamedMedium "veins" "string type" "uniformgrid" {COEFFICIENTS} {BOX} '
             f'"integer nx" 6 "integer ny" 6 "integer nz" 6 "float density" [{veins}]\n')
    texts = {"homogeneous": material("hom"), "constant grid": material("const"),
             "veined grid, walk": material("veins"),
             "veined grid, volumetric": material("veins", '"string method" "volumetric"')}
    files = {}
    for name, body in texts.items():
        files[name] = os.path.join(out, name.replace(" ", "_").replace(",", "") + ".pbrt")
        with open(files[name], "w") as f:
            f.write(HEAD + media + body)
    return files


def render(binary, scene, out, spp, res, seed):
    p = subprocess.run(command(binary, scene, out, spp=spp, res=res, seed=seed), text=True, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE)
    if p.returncode != 0:
        raise RuntimeError(p.stderr)
    return render_stats(p.stderr).seconds, read_exr(out).rgb


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dermis", default=paths.DERMIS)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--res", default="64x64")
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="dermis-grid-interior-")
    os.makedirs(out, exist_ok=True)
    files = scenes(out)
    # A file per render, kept for inspection.
    def exr(name, seed):
        return os.path.join(out, f"{name.replace(' ', '_').replace(',', '')}-{seed}.exr")

    ref = {"homogeneous": render(args.dermis, files["homogeneous"], exr("homogeneous", "ref"), args.ref_spp, args.res,
                                 1000)[1]}
    ref["volumetric"] = render(args.dermis, files["veined grid, volumetric"], exr("volumetric", "ref"), args.ref_spp,
                               args.res, 1000)[1]
    against = {"homogeneous": "homogeneous", "constant grid": "homogeneous", "veined grid, walk": "volumetric",
               "veined grid, volumetric": "volumetric"}
    mask = ref["homogeneous"].sum(axis=2) != ref["homogeneous"].sum(axis=2)[0, 0]  # the sphere's pixels
    times = {name: [] for name in files}
    errors = {name: [] for name in files}
    for seed in range(args.seeds):
        for name, scene in files.items():  # interleaved
            t, image = render(args.dermis, scene, exr(name, seed + 1), args.spp, args.res, seed + 1)
            times[name].append(t)
            errors[name].append(float(np.mean((image - ref[against[name]])[mask] ** 2)))
    print(f"{args.spp} spp at {args.res}, {args.seeds} seeds, references at {args.ref_spp} spp; scenes in {out}\n")
    print("| scene | render time (median) | MSE (mean) | efficiency 1/(MSE t) | against |")
    print("|---|---:|---:|---:|---|")
    eff = {}
    for name in files:
        t, mse = statistics.median(times[name]), statistics.mean(errors[name])
        eff[name] = 1 / (mse * t)
        print(f"| {name} | {t:.2f} s | {mse:.3e} | {eff[name]:.3g} | {against[name]} reference |")
    print(f"\nconstant grid / homogeneous: time {statistics.median(times['constant grid']) / statistics.median(times['homogeneous']):.2f}x, "
          f"efficiency {eff['constant grid'] / eff['homogeneous']:.2f}x")
    print(f"veined walk / volumetric: time "
          f"{statistics.median(times['veined grid, walk']) / statistics.median(times['veined grid, volumetric']):.2f}x, "
          f"efficiency {eff['veined grid, walk'] / eff['veined grid, volumetric']:.2f}x")


if __name__ == "__main__":
    main()
