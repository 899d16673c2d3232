#!/usr/bin/python3
"""Stand-ins for the assets of pbrt-v4's `sssdragon` scene (mmp/pbrt-v4-scenes, sssdragon/),
which are not redistributed here: files of the same names and kinds, so that dragon_10.pbrt,
dragon_50.pbrt and dragon_250.pbrt parse and render exactly as written.

  geometry/dragon.ply.gz   a gzip-compressed binary PLY: a lumpy blob of the dragon's size
                           (object space, ~50 units; the scene scales it by 0.02)
  geometry/meshes_0.ply    the floor: a 10 x 10 quad at z = 0 with uv in [0, 1]
  textures/envmap.exr      a small square (equal-area) sky, grey with a bright sun on one side

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

# The blob: a sphere of radius 25 with a low-frequency bump, 48 x 24 quads.
nu, nv = 48, 24
verts, faces = [], []
for j in range(nv + 1):
    theta = math.pi * j / nv
    for i in range(nu + 1):
        phi = 2 * math.pi * i / nu
        r = 25 * (1 + 0.15 * math.sin(3 * phi) * math.sin(2 * theta))
        verts.append((r * math.sin(theta) * math.cos(phi), r * math.sin(theta) * math.sin(phi), r * math.cos(theta)))
idx = lambda i, j: j * (nu + 1) + i
for j in range(nv):
    for i in range(nu):
        if j != 0:
            faces.append((idx(i, j), idx(i, j + 1), idx(i + 1, j)))
        if j != nv - 1:
            faces.append((idx(i + 1, j), idx(i, j + 1), idx(i + 1, j + 1)))
header = (f"ply\nformat binary_little_endian 1.0\ncomment stand-in for pbrt-v4-scenes sssdragon/geometry/dragon.ply.gz\n"
          f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
          f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode()
body = b"".join(struct.pack("<3f", *v) for v in verts) + b"".join(struct.pack("<B3i", 3, *f) for f in faces)
with gzip.open(os.path.join(here, "geometry", "dragon.ply.gz"), "wb") as f:
    f.write(header + body)

# The floor.
with open(os.path.join(here, "geometry", "meshes_0.ply"), "w") as f:
    f.write("ply\nformat ascii 1.0\ncomment stand-in for pbrt-v4-scenes sssdragon/geometry/meshes_0.ply\n"
            "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\n"
            "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
            "-5 -5 0 0 0\n5 -5 0 1 0\n5 5 0 1 1\n-5 5 0 0 1\n3 0 1 2\n3 0 2 3\n")

# The sky: equal-area octahedral (pbrt-v4's mapping, Clarberg 2008), grey 0.5 with a sun
# region (within 25 degrees) of radiance 20 around the world direction SUN_WORLD: beside the
# dragon as the camera sees it (perpendicular to the view, to its right in the image), 27
# degrees above the horizon. The scene's light transform (two ConcatTransforms, rotations)
# takes light space to world space; its transpose takes the sun back to light space.
SUN_WORLD = np.array([0.682, 0.731, 0.5]) / np.linalg.norm([0.682, 0.731, 0.5])
m1 = np.array([[-0.224951, 0, -0.97437], [-0.97437, 0, 0.224951], [0, 1, 0]]).T  # columns as written
m2 = np.array([[0, 0, -1], [1, 0, 0], [0, 1, 0]]).T
sun_light = (m1 @ m2).T @ SUN_WORLD


def equal_area_square_to_sphere(u, v):
    # Clarberg 2008 (pbrt-v4's EqualAreaSquareToSphere): (u, v) in [0,1]^2 -> unit vector.
    up, vp = 2 * u - 1, 2 * v - 1
    au, av = abs(up), abs(vp)
    sd = 1 - (au + av)
    r = 1 - abs(sd)
    phi = (1 if r == 0 else (av - au) / r + 1) * math.pi / 4
    z = math.copysign(1 - r * r, sd)
    cphi, sphi = math.copysign(math.cos(phi), up), math.copysign(math.sin(phi), vp)
    k = r * math.sqrt(max(0.0, 2 - r * r))
    return np.array([cphi * k, sphi * k, z])


s = 64
sky = np.full((s, s, 3), 0.5, dtype=np.float32)
for y in range(s):  # row y holds v = (y + 0.5) / s (pbrt-v4: image rows top to bottom)
    for x in range(s):
        if equal_area_square_to_sphere((x + 0.5) / s, (y + 0.5) / s) @ sun_light > math.cos(math.radians(25)):
            sky[y, x] = 20.0
path = os.path.join(here, "textures", "envmap.exr")
out = oiio.ImageOutput.create(path)
out.open(path, oiio.ImageSpec(s, s, 3, "float"))
out.write_image(sky)
out.close()
print("wrote geometry/dragon.ply.gz, geometry/meshes_0.ply, textures/envmap.exr")
