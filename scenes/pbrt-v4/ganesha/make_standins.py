#!/usr/bin/python3
"""Stand-ins for the assets of pbrt-v4's `ganesha` scene (mmp/pbrt-v4-scenes, ganesha/),
which are not redistributed here: files of the same names and kinds, so that ganesha.pbrt
parses and renders exactly as written.

  geometry/ganesha.ply.gz  a gzip-compressed binary PLY with normals and uv: an ellipsoid
                           standing on the scene's floor (y = -42) where the camera looks
                           (x 328, z 0), about as large as the statue in the picture
  textures/ganesha.png     its colour map: warm on the upper half (v), cool on the lower
                           (a test checks both reach the picture)
  textures/sky.exr         a small square (equal-area) sky, grey

Run with Debian's python3 (numpy, OpenImageIO): /usr/bin/python3 make_standins.py
"""
import gzip
import math
import os
import struct

import numpy as np
import OpenImageIO as oiio

here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "geometry"), exist_ok=True)
os.makedirs(os.path.join(here, "textures"), exist_ok=True)

center = np.array([328.0, 10.0, 0.0])
radii = np.array([45.0, 52.0, 35.0])
nu, nv = 64, 32
verts, faces = [], []
for j in range(nv + 1):
    theta = math.pi * j / nv
    for i in range(nu + 1):
        phi = 2 * math.pi * i / nu
        # The ellipsoid's axis along y (up in the picture); u runs around it.
        d = np.array([math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)])
        n = d / radii
        n /= np.linalg.norm(n)
        verts.append((*(center + radii * d), *n, i / nu, 1 - j / nv))
idx = lambda i, j: j * (nu + 1) + i
for j in range(nv):
    for i in range(nu):  # wound so that cross(p1 - p0, p2 - p0) points outward
        if j != 0:
            faces.append((idx(i, j), idx(i + 1, j), idx(i, j + 1)))
        if j != nv - 1:
            faces.append((idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)))
header = ("ply\nformat binary_little_endian 1.0\ncomment stand-in for pbrt-v4-scenes ganesha/geometry/ganesha.ply.gz\n"
          f"element vertex {len(verts)}\n" + "".join(f"property float {p}\n" for p in ("x", "y", "z", "nx", "ny", "nz", "u", "v")) +
          f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode()
body = b"".join(struct.pack("<8f", *v) for v in verts) + b"".join(struct.pack("<B3i", 3, *f) for f in faces)
with open(os.path.join(here, "geometry", "ganesha.ply.gz"), "wb") as raw:
    with gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as f:  # mtime 0: the same bytes every run
        f.write(header + body)

w = h = 64
img = np.zeros((h, w, 3), dtype=np.uint8)
img[: h // 2] = (224, 150, 100)  # warm on the upper half (v > 1/2: the top of the statue)
img[h // 2 :] = (100, 150, 224)  # cool on the lower half
path = os.path.join(here, "textures", "ganesha.png")
out = oiio.ImageOutput.create(path)
out.open(path, oiio.ImageSpec(w, h, 3, "uint8"))
out.write_image(img)
out.close()

s = 16
sky = np.full((s, s, 3), 1.0, dtype=np.float32)  # grey: every hue in the picture comes from the statue
path = os.path.join(here, "textures", "sky.exr")
out = oiio.ImageOutput.create(path)
out.open(path, oiio.ImageSpec(s, s, 3, "float"))
out.write_image(sky)
out.close()
print("wrote geometry/ganesha.ply.gz, textures/ganesha.png, textures/sky.exr")
