#!/usr/bin/python3
"""What a grid medium costs (issue 67, item 5), at equal samples per pixel, in one run with
the renders interleaved (this machine is shared and noisy):
- a constant-density N^3 `uniformgrid` against the homogeneous medium of the same
  coefficients (asked: <= 1.5x);
- the same grid with 90 % of its cells empty (density 1 only in the lowest tenth of its
  z-slices) against it filled (asked: <= 0.5x);
- an (N/2)^3 `rgbgrid` of the homogeneous medium's colours (six floats a cell), for its
  memory and cost;
- the peak memory of loading and rendering each against the grid's own bytes (asked: <= the
  grid's bytes + 15 %): the whole process's, and what it holds beyond the homogeneous
  medium's process (the renderer itself, its film and threads), which is the grid's cost;
  and the load time.
The media fill an index-matched unit sphere lit by a sky and a distant light.

  /usr/bin/python3 -m bench.grid_media_cost [--dermis build/dermis] [--n 256] [--spp 16]
      [--res 64x64] [--repeats 3] [--out DIR]

Prints, per scene, the median render-stage time (dermis' own "in X s"), the whole process's
wall time and peak resident memory (getrusage of the child), and the ratios asked for.
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

from bench.harness import paths
from bench.harness.render import command, render_stats

HEAD = """LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Integrator "volpath" "integer maxdepth" 50
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
LightSource "distant" "point3 from" [1 2 -1] "point3 to" [0 0 0] "rgb L" [3 3 3]
"""
COEFFICIENTS = '"rgb sigma_a" [0.2 0.5 1] "rgb sigma_s" [2 1 0.5] "float g" 0.3'
SPHERE = 'Material "interface"\nMediumInterface "m" ""\nShape "sphere"\n'


def grid_scene(path, n, filled_slices):
    """An n^3 uniformgrid over a box just holding the unit sphere, density 1 in its lowest
    `filled_slices` z-slices and 0 above, written in pieces (the file is large)."""
    with open(path, "w") as f:
        f.write(HEAD)
        f.write(f'MakeNamedMedium "m" "string type" "uniformgrid" "integer nx" {n} "integer ny" {n} "integer nz" {n} '
                f'"point3 p0" [-1.01 -1.01 -1.01] "point3 p1" [1.01 1.01 1.01] {COEFFICIENTS} "float density" [')
        one, zero = " 1" * (n * n), " 0" * (n * n)
        for z in range(n):
            f.write(one if z < filled_slices else zero)
        f.write(" ]\n" + SPHERE)


def rgbgrid_scene(path, n):
    """An n^3 `rgbgrid` over the same box, sigma_a and sigma_s given per cell as the
    homogeneous medium's colours (6 floats a cell), written in pieces."""
    with open(path, "w") as f:
        f.write(HEAD)
        f.write(f'MakeNamedMedium "m" "string type" "rgbgrid" "integer nx" {n} "integer ny" {n} "integer nz" {n} '
                f'"point3 p0" [-1.01 -1.01 -1.01] "point3 p1" [1.01 1.01 1.01] "float g" 0.3')
        for name, colour in (("sigma_a", " 0.2 0.5 1"), ("sigma_s", " 2 1 0.5")):
            f.write(f' "rgb {name}" [')
            for _ in range(n):
                f.write(colour * (n * n))
            f.write(" ]")
        f.write("\n" + SPHERE)


def timed(cmd):
    """Wall time, the render stage's time and the peak RSS (bytes) of one dermis process."""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{p.stderr}")
    return wall, render_stats(p.stderr).seconds


def peak_rss(cmd):
    """Peak resident memory of cmd, in bytes: getrusage's largest child of a Python whose only
    child it is (this process's children include every render before it)."""
    probe = ("import resource,subprocess,sys;subprocess.run(sys.argv[1:],stdout=subprocess.DEVNULL,"
             "stderr=subprocess.DEVNULL,check=True);print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    out = subprocess.run(["/usr/bin/python3", "-c", probe] + cmd, text=True, stdout=subprocess.PIPE, check=True)
    return int(out.stdout.strip()) * 1024


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dermis", default=paths.DERMIS)
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", default="64x64")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="dermis-grid-cost-")
    os.makedirs(out, exist_ok=True)
    scenes = {"homogeneous": os.path.join(out, "homogeneous.pbrt"), "grid filled": os.path.join(out, "filled.pbrt"),
              "grid 90% empty": os.path.join(out, "sparse.pbrt"), "rgbgrid filled": os.path.join(out, "rgbgrid.pbrt")}
    with open(scenes["homogeneous"], "w") as f:
        f.write(HEAD + f'MakeNamedMedium "m" "string type" "homogeneous" {COEFFICIENTS}\n' + SPHERE)
    grid_scene(scenes["grid filled"], args.n, args.n)
    grid_scene(scenes["grid 90% empty"], args.n, max(1, round(args.n / 10)))
    rgb_n = args.n // 2  # six floats a cell: (n/2)^3 cells hold 3/4 of the density grid's bytes
    rgbgrid_scene(scenes["rgbgrid filled"], rgb_n)

    def cmd(name, spp):
        return command(args.dermis, scenes[name], os.path.join(out, "o.exr"), spp=spp, res=args.res)

    loads = {name: timed(cmd(name, 1))[0] for name in scenes}  # one sample: the load, mostly
    memory = {name: peak_rss(cmd(name, 1)) for name in scenes}
    times = {name: [] for name in scenes}
    for _ in range(args.repeats):
        for name in scenes:
            times[name].append(timed(cmd(name, args.spp))[1])
    median = {name: statistics.median(t) for name, t in times.items()}
    grid_bytes = {name: 4 * args.n ** 3 for name in scenes}
    grid_bytes["rgbgrid filled"] = 4 * 6 * rgb_n ** 3
    print(f"{args.n}^3 grid ({grid_bytes['grid filled'] / 2**20:.0f} MiB of floats; the rgbgrid {rgb_n}^3, "
          f"{grid_bytes['rgbgrid filled'] / 2**20:.0f} MiB), {args.spp} spp at {args.res}, "
          f"{args.repeats} interleaved repeats; scenes in {out}\n")
    print("| scene | render stage (median) | load, whole process at 1 spp | peak memory | memory / grid bytes "
          "| beyond homogeneous / grid bytes |")
    print("|---|---:|---:|---:|---:|---:|")
    for name in scenes:
        grid = name != "homogeneous"
        ratio = f"{memory[name] / grid_bytes[name]:.2f}" if grid else "-"
        beyond = f"{(memory[name] - memory['homogeneous']) / grid_bytes[name]:.3f}" if grid else "-"
        print(f"| {name} | {median[name]:.2f} s | {loads[name]:.1f} s | {memory[name] / 2**20:.0f} MiB | {ratio} "
              f"| {beyond} |")
    print(f"\nconstant grid / homogeneous: {median['grid filled'] / median['homogeneous']:.2f}x (asked <= 1.5x)")
    print(f"90% empty / filled: {median['grid 90% empty'] / median['grid filled']:.2f}x (asked <= 0.5x)")


if __name__ == "__main__":
    main()
