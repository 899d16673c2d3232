#!/usr/bin/python3
"""Checks the family's two HDR environments (environments.py) against each other as the two
renderers see them: Dermis renders the equal-area map, Cycles the lat-long one, from a camera
at the origin (90 degree field of view) looking toward the sun or the key soft box, across,
behind and up; each background pixel at least 3 degrees from the horizon (where the ground
meets the sky in half a degree) is compared. Prints per environment and view the mean ratio
Dermis / Cycles and the median and 99th-percentile relative difference of those pixels, and
exits 1 when a view's mean ratio is off by more than 1 % or its median difference exceeds 1 %.

  /usr/bin/python3 -m bench.vs_cycles.check_environments [--dermis build/dermis]
      [--blender blender] [--res 96] [--spp 256] [--out DIR]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from bench.harness import paths
from bench.harness.exr import read_exr
from bench.harness.render import command
from bench.vs_cycles import environments, pbrt_writer

HERE = os.path.dirname(os.path.abspath(__file__))
# (label, azimuth, elevation) of the camera's view direction, degrees.
VIEWS = [("toward the light", -160.0, 35.0), ("across", -70.0, 20.0), ("behind", 40.0, 25.0), ("up", 0.0, 80.0)]
HORIZON_MARGIN = math.radians(3.0)


def view_scene(env, label, azimuth, elevation, res):
    a, e = math.radians(azimuth), math.radians(elevation)
    target = [math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)]
    up = [0.0, 0.0, 1.0] if elevation < 70 else [1.0, 0.0, 0.0]
    return dict(name=f"env-{env}-{label.replace(' ', '-')}", res=[res, res], sky=None, max_depth=1, lights=[],
                shape=None, material=None, environment=dict(name=env),
                camera=dict(eye=[0.0, 0.0, 0.0], target=target, up=up, fov=90.0))


def pixel_elevations(sc):
    """The elevation of each pixel centre's direction (the harness' camera in both renderers)."""
    cam, (w, h) = sc["camera"], sc["res"]
    f = np.array(cam["target"]) - np.array(cam["eye"])
    f /= np.linalg.norm(f)
    right = np.cross(f, cam["up"])
    right /= np.linalg.norm(right)
    up = np.cross(right, f)
    t = math.tan(math.radians(cam["fov"]) / 2)
    x = (2 * (np.arange(w) + 0.5) / w - 1) * t * (w / h if w >= h else 1)
    y = (1 - 2 * (np.arange(h) + 0.5) / h) * t * (h / w if h > w else 1)
    X, Y = np.meshgrid(x, y)
    d = f + X[..., None] * right + Y[..., None] * up
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return np.arcsin(np.clip(d[..., 2], -1, 1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dermis", default=paths.DERMIS)
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--res", type=int, default=96)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="dermis-env-check-")
    os.makedirs(out, exist_ok=True)
    scenes, renders = [], []
    for env in environments.ENVIRONMENTS:
        for label, az, el in VIEWS:
            sc = view_scene(env, label, az, el, args.res)
            environments.attach(sc["environment"], out)
            scenes.append(sc)
            text = pbrt_writer.header(sc, f"environment {env}, looking {label}", args.spp) + pbrt_writer.lights(sc)
            pbrt = os.path.join(out, sc["name"] + ".pbrt")
            with open(pbrt, "w") as f:
                f.write(text)
            p = subprocess.run(command(args.dermis, pbrt, os.path.join(out, sc["name"] + "-dermis.exr"), spp=args.spp),
                               capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit(f"dermis failed on {pbrt}:\n{p.stderr}")
    # One Blender process per view (blender_scene.py builds one scene per job).
    for sc in scenes:
        job = dict(scene=sc, threads=2, root=paths.ROOT, result=os.path.join(out, sc["name"] + "-result.json"),
                   renders=[dict(out=os.path.join(out, sc["name"] + "-cycles.exr"), spp=args.spp, seed=1)])
        jpath = os.path.join(out, sc["name"] + "-job.json")
        with open(jpath, "w") as f:
            json.dump(job, f)
        p = subprocess.run([args.blender, "-b", "--factory-startup", "--python", os.path.join(HERE, "blender_scene.py"),
                            "--", jpath], capture_output=True, text=True)
        if p.returncode != 0 or not os.path.exists(job["result"]):
            sys.exit(f"blender failed on {jpath}:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    failed = False
    print(f"{args.res}x{args.res} px, {args.spp} spp; files in {out}\n")
    print("| environment | view | pixels | mean Dermis / Cycles | median rel. diff | 99th pct rel. diff |")
    print("|---|---|---:|---:|---:|---:|")
    for sc in scenes:
        d = read_exr(os.path.join(out, sc["name"] + "-dermis.exr")).rgb
        c = read_exr(os.path.join(out, sc["name"] + "-cycles.exr")).rgb
        mask = np.abs(pixel_elevations(sc)) > HORIZON_MARGIN
        ld, lc = d.mean(axis=2)[mask], c.mean(axis=2)[mask]
        rel = np.abs(ld - lc) / np.maximum(lc, 1e-4)
        ratio = ld.mean() / lc.mean()
        med, p99 = float(np.median(rel)), float(np.percentile(rel, 99))
        failed = failed or abs(ratio - 1) > 0.01 or med > 0.01
        print(f"| {sc['environment']['name']} | {sc['name'].split('-', 2)[2].replace('-', ' ')} | {int(mask.sum())} | "
              f"{ratio:.4f} | {med:.4f} | {p99:.4f} |")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
