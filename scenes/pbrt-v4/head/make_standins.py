#!/usr/bin/python3
"""Stand-ins for the assets of pbrt-v4's `head` scene (mmp/pbrt-v4-scenes, head/), which
are not redistributed here: files of the same names and kinds, so that head.pbrt parses
and renders exactly as written.

  geometry/head.ply              an ellipsoid head-sized (metres) with uv and normals
  textures/head_albedomap.png    a skin albedo map: warm on the left half of u, cool on
                                 the right (a test checks both reach the picture)
  textures/doge2_equiarea.exr    a small square sky map

Run with Debian's python3 (numpy, OpenImageIO): /usr/bin/python3 make_standins.py
"""
import math
import os

import numpy as np
import OpenImageIO as oiio

here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "geometry"), exist_ok=True)
os.makedirs(os.path.join(here, "textures"), exist_ok=True)

# The ellipsoid: centred where the camera of head.pbrt looks, 0.6 m in front of it.
center = np.array([0.044, -0.077, -0.011])
radii = np.array([0.09, 0.11, 0.10])
nu, nv = 48, 24
verts, faces = [], []
for j in range(nv + 1):
    theta = math.pi * j / nv
    for i in range(nu + 1):
        phi = 2 * math.pi * i / nu
        d = np.array([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)])
        p = center + radii * d
        n = d / radii
        n /= np.linalg.norm(n)
        verts.append((*p, *n, i / nu, 1 - j / nv))
idx = lambda i, j: j * (nu + 1) + i
for j in range(nv):
    for i in range(nu):
        if j != 0:
            faces.append((idx(i, j), idx(i, j + 1), idx(i + 1, j)))
        if j != nv - 1:
            faces.append((idx(i + 1, j), idx(i, j + 1), idx(i + 1, j + 1)))
with open(os.path.join(here, "geometry", "head.ply"), "w") as f:
    f.write("ply\nformat ascii 1.0\ncomment stand-in for pbrt-v4-scenes head/geometry/head.ply\n")
    f.write(f"element vertex {len(verts)}\n")
    for name in ("x", "y", "z", "nx", "ny", "nz", "u", "v"):
        f.write(f"property float {name}\n")
    f.write(f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    for v in verts:
        f.write(" ".join(f"{c:.6g}" for c in v) + "\n")
    for t in faces:
        f.write(f"3 {t[0]} {t[1]} {t[2]}\n")

# The albedo map (sRGB 8-bit, as pbrt-v4 reads PNGs).
w = h = 64
img = np.zeros((h, w, 3), dtype=np.uint8)
img[:, : w // 2] = (224, 150, 120)  # warm skin
img[:, w // 2 :] = (120, 150, 224)  # cool
out = oiio.ImageOutput.create(os.path.join(here, "textures", "head_albedomap.png"))
out.open(os.path.join(here, "textures", "head_albedomap.png"), oiio.ImageSpec(w, h, 3, "uint8"))
out.write_image(img)
out.close()

# The sky: square, as pbrt-v4's equal-area maps are; grey, brighter towards one side.
s = 16
sky = np.zeros((s, s, 3), dtype=np.float32)
for y in range(s):
    for x in range(s):
        sky[y, x] = 0.5 + x / s  # grey: every hue in the picture comes from the head
path = os.path.join(here, "textures", "doge2_equiarea.exr")
out = oiio.ImageOutput.create(path)
out.open(path, oiio.ImageSpec(s, s, 3, "float"))
out.write_image(sky)
out.close()
print("wrote geometry/head.ply, textures/head_albedomap.png, textures/doge2_equiarea.exr")
