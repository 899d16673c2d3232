#!/usr/bin/python3
"""Wall time of two dermis builds on the same scenes, run alternately in one session (the
machine is shared and noisy: only the ratio in one run means anything).

  /usr/bin/python3 -m bench.compare_builds OLD_DERMIS NEW_DERMIS [--reps 3] [--scale K]

Each scene is rendered --reps times by each build, alternating; the median wall time of
the whole process (parse, preparation, render) is reported, and new / old.
"""
import argparse
import statistics

from bench.harness import render
from bench.harness.paths import ROOT

SCENES = [("scenes/demo.pbrt", 16, "160x120"), ("scenes/bench/bust-walk-mis.pbrt", 16, "128x128"),
          ("scenes/bench/sphere-walk-diffuse-mis.pbrt", 32, "128x128"), ("scenes/bench/bust-disk.pbrt", 16, "128x128"),
          ("scenes/bench/sphere-volumetric.pbrt", 8, "128x128")]

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("old")
ap.add_argument("new")
ap.add_argument("--reps", type=int, default=3)
ap.add_argument("--scale", type=int, default=1, help="each scene's samples per pixel times K (longer renders, less noise)")
args = ap.parse_args()
for scene, spp, res in SCENES:
    times = {args.old: [], args.new: []}
    for _ in range(args.reps):
        for binary in (args.old, args.new):
            r = render.render(binary, scene, "/tmp/dermis_compare_builds.exr", cwd=ROOT, spp=spp * args.scale, res=res)
            times[binary].append(r.wall)
    old, new = statistics.median(times[args.old]), statistics.median(times[args.new])
    print(f"{scene:45s} spp {spp * args.scale:3d} {res}: old {old:.2f} s, new {new:.2f} s, new/old {new / old:.3f}", flush=True)
