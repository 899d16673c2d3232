#!/usr/bin/python3
"""Writes scenes/veined-marble-veins.pbrt.gz: the interior of the veined-marble demo
(scenes/veined-marble.pbrt), an `rgbgrid` medium over the Igea head's box whose absorption
draws dark, branching veins through a warm white marble (docs/materials.md, "A heterogeneous
interior"). The veins are the classic marble construction, the zero crossings of a sine
along a slanted axis displaced by turbulence (Perlin 1985, sec. 5), made sharp; the noise is
value noise on a seeded lattice. Deterministic: the same file every run.

Usage: scripts/make_veined_marble.py [OUT]   (default scenes/veined-marble-veins.pbrt.gz)"""
import gzip
import pathlib
import sys

import numpy as np

# The Igea head (scenes/meshes/igea.ply) lies in [-0.0346, 0.0346] x [-0.0497, 0.0497] x
# [-0.0496, 0.0496]; the box reaches a little past it.
P0 = np.array([-0.037, -0.052, -0.052])
P1 = -P0
RES = (44, 64, 64)  # samples along x, y, z: about 1.7 mm apart
# sigma_a / sigma_s of the body and of the veins' core per channel (the medium's "scale" is
# sigma_s; the grid holds sigma_a in units of it).
BODY = np.array([0.0030, 0.0036, 0.0046])
VEIN = np.array([1.6, 1.45, 1.2])


def value_noise(points, frequency, rng):
    """Trilinearly interpolated (smoothstep-weighted) random values on a lattice of spacing
    1/frequency, in [-1, 1]."""
    lattice = rng.uniform(-1, 1, size=(64, 64, 64))
    q = points * frequency
    i = np.floor(q).astype(int)
    f = q - i
    f = f * f * (3 - 2 * f)
    out = np.zeros(points.shape[0])
    for dx in (0, 1):
        for dy in (0, 1):
            for dz in (0, 1):
                w = (f[:, 0] if dx else 1 - f[:, 0]) * (f[:, 1] if dy else 1 - f[:, 1]) * (f[:, 2] if dz else 1 - f[:, 2])
                out += w * lattice[(i[:, 0] + dx) % 64, (i[:, 1] + dy) % 64, (i[:, 2] + dz) % 64]
    return out


def turbulence(points, base_frequency, octaves, rng):
    total, amplitude, frequency = np.zeros(points.shape[0]), 1.0, base_frequency
    for _ in range(octaves):
        total += amplitude * np.abs(value_noise(points, frequency, rng))
        amplitude *= 0.5
        frequency *= 2.0
    return total


def vein_fraction(points):
    """0 in the body, 1 in a vein's core."""
    rng = np.random.default_rng(1985)
    axis = np.array([0.55, 0.75, 0.36])
    axis /= np.linalg.norm(axis)
    t = points @ axis * 12 + 1.1 * turbulence(points, 18, 3, rng)
    stripe = np.abs(np.sin(np.pi * t))  # 0 on the veins
    main = np.clip(1 - stripe / 0.3, 0, 1) ** 1.5
    # Finer, fainter secondary veins along another direction.
    t2 = points @ np.array([-0.7, 0.2, 0.68]) * 22 + 0.9 * turbulence(points, 30, 3, rng)
    fine = 0.4 * np.clip(1 - np.abs(np.sin(np.pi * t2)) / 0.18, 0, 1) ** 1.5
    return np.clip(main + fine, 0, 1)


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else
                       pathlib.Path(__file__).resolve().parents[1] / "scenes/veined-marble-veins.pbrt.gz")
    nx, ny, nz = RES
    # pbrt-v4's grid samples sit at the cells' centres (x fastest, then y, then z).
    xs = [P0[k] + (np.arange(n) + 0.5) / n * (P1[k] - P0[k]) for k, n in enumerate(RES)]
    z, y, x = np.meshgrid(xs[2], xs[1], xs[0], indexing="ij")
    points = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    v = vein_fraction(points)[:, None]
    sigma_a = BODY * (1 - v) + VEIN * v
    values = " ".join(f"{a:.3g}" for a in sigma_a.ravel())
    text = (f"# Written by scripts/make_veined_marble.py: the veined marble's interior (rgbgrid, "
            f"{nx} x {ny} x {nz}).\n"
            f'MakeNamedMedium "veins" "string type" "rgbgrid" "float scale" 300 "float g" 0.2\n'
            f'  "point3 p0" [{P0[0]} {P0[1]} {P0[2]}] "point3 p1" [{P1[0]} {P1[1]} {P1[2]}]\n'
            f'  "integer nx" {nx} "integer ny" {ny} "integer nz" {nz}\n'
            f'  "rgb sigma_a" [ {values} ]\n')
    with gzip.GzipFile(out, "wb", mtime=0) as f:
        f.write(text.encode())
    print(f"wrote {out} ({out.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
