#!/usr/bin/python3
"""Writes bench/pbrt_v4/scenes/envmap.exr: a 128x128 equal-area octahedral environment map
(the only image layout pbrt-v4's `infinite` light reads; Clarberg 2008), made with numpy.

Light space has +z up (the image centre), as pbrt-v4: pixel (x, y) holds the radiance
arriving from EqualAreaSquareToSphere(((x + 0.5) / 128, (y + 0.5) / 128)), y = 0 the top
row. The map: a sky graded from a pale horizon to a blue zenith, a dark brown ground, a
warm "sun" (a smooth disc about 10 degrees across, bright enough to cast a shadow) low in
the sky, and a dimmer blue-grey patch opposite it, so that a wrong orientation or a
mirrored map shows in the comparison.

  /usr/bin/python3 -m bench.pbrt_v4.make_envmap [OUT.exr]
"""
import os
import sys

import numpy as np

RES = 128


def equal_area_square_to_sphere(u, v):
    """pbrt-v4's EqualAreaSquareToSphere (util/math.cpp), vectorised: [0,1]^2 -> S^2."""
    u = 2 * u - 1
    v = 2 * v - 1
    up, vp = np.abs(u), np.abs(v)
    sd = 1 - (up + vp)
    r = 1 - np.abs(sd)
    with np.errstate(invalid="ignore", divide="ignore"):
        phi = np.where(r == 0, 1.0, (vp - up) / np.where(r == 0, 1, r) + 1) * np.pi / 4
    z = np.copysign(1 - r * r, sd)
    cos_phi = np.copysign(np.cos(phi), u)
    sin_phi = np.copysign(np.sin(phi), v)
    s = r * np.sqrt(np.maximum(0, 2 - r * r))
    return np.stack([cos_phi * s, sin_phi * s, z], axis=-1)


def radiance(w):
    """Radiance (linear Rec.709 RGB) arriving from light-space directions w (..., 3)."""
    z = w[..., 2:3]
    horizon = np.array([0.85, 0.85, 0.90])
    zenith = np.array([0.20, 0.35, 0.75])
    t = np.clip(z, 0, 1) ** 0.6
    sky = (1 - t) * horizon + t * zenith
    ground = np.array([0.16, 0.12, 0.09]) * np.ones_like(z)
    img = np.where(z > 0, sky, ground)
    # The sun: light-space direction (-0.5, 0.6, 0.6) normalised (with the scenes'
    # `Rotate -90 1 0 0`: world (-0.5, 0.6, -0.6), up-left and toward the camera).
    for d, col, width in (((-0.5, 0.6, 0.6), (60.0, 50.0, 36.0), 0.10),
                          ((0.7, -0.6, 0.3), (0.8, 1.0, 1.6), 0.30)):
        d = np.array(d) / np.linalg.norm(d)
        ang = np.arccos(np.clip(w @ d, -1, 1))[..., None]
        img = img + np.array(col) * np.exp(-0.5 * (ang / width) ** 2 * 4) * (ang < 2 * width)
    return img


def make(path):
    import OpenImageIO as oiio
    c = (np.arange(RES) + 0.5) / RES
    v, u = np.meshgrid(c, c, indexing="ij")  # row y <-> v, column x <-> u
    img = radiance(equal_area_square_to_sphere(u, v)).astype(np.float32)
    spec = oiio.ImageSpec(RES, RES, 3, oiio.HALF)
    spec.attribute("compression", "zip")
    out = oiio.ImageOutput.create(path)
    if not out or not out.open(path, spec):
        raise SystemExit(f"cannot write {path}: {oiio.geterror()}")
    out.write_image(img)
    out.close()
    return img


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    p = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "scenes", "envmap.exr")
    img = make(p)
    print(f"wrote {p}: {RES}x{RES}, mean radiance {img.mean(axis=(0, 1))}")
