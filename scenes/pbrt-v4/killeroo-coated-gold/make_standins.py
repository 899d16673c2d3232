#!/usr/bin/python3
"""Stand-ins for the assets of pbrt-v4's `killeroo-coated-gold` scene (mmp/pbrt-v4-scenes,
killeroos/), which are not redistributed here: files of the same names and kinds, so that
killeroo-coated-gold.pbrt parses and renders exactly as written.

  geometry/killeroo3.pbrt  one Shape "loopsubdiv" with "integer levels" [ 3 ], "point3 P"
                           and "integer indices", as the original: here the coarse closed
                           ellipsoid of ../killeroo-simple/make_standins.py (266 vertices,
                           528 triangles, the killeroo's extent x -37..37, y -40..92,
                           z -140..4 in object space: it stands on the floor at z = -140).
  textures/lines.png       a grid of lines: 64 x 64 8-bit sRGB, white (255) with a dark
                           (32) line of 4 pixels along each edge, so that the tiled floor
                           (uv 0..5) shows a 5 x 5 grid.
  spds/Au.eta.spd          gold's index of refraction and extinction coefficient as pbrt-v4
  spds/Au.k.spd            spectrum files: (wavelength nm, value) pairs. The values are
                           Palik's measurements (Handbook of Optical Constants of Solids,
                           1985), read from Dermis's own table of them
                           (src/dermis/scene/named_spectra_data.cpp, kAuEta / kAuK), the
                           same data as pbrt-v4's named spectra metal-Au-eta / metal-Au-k.

Run with Debian's python3 (numpy, OpenImageIO): /usr/bin/python3 make_standins.py
"""
import math
import os
import re

import numpy as np
import OpenImageIO as oiio

here = os.path.dirname(os.path.abspath(__file__))
for d in ("geometry", "textures", "spds"):
    os.makedirs(os.path.join(here, d), exist_ok=True)

# The killeroo: a closed ellipsoid, wound outward (counter-clockwise seen from outside).
center = (0.0, 26.0, -68.0)
radii = (37.0, 66.0, 72.0)
nu, nv = 24, 12  # segments around z, rings from pole to pole
P = [(center[0], center[1], center[2] + radii[2])]  # top pole
for j in range(1, nv):
    theta = math.pi * j / nv
    for i in range(nu):
        phi = 2 * math.pi * i / nu
        P.append(tuple(c + r * d for c, r, d in zip(center, radii, (math.sin(theta) * math.cos(phi),
                                                                         math.sin(theta) * math.sin(phi),
                                                                         math.cos(theta)))))
P.append((center[0], center[1], center[2] - radii[2]))  # bottom pole
ring = lambda j, i: 1 + (j - 1) * nu + i % nu
bottom = len(P) - 1
tris = []
for i in range(nu):
    tris.append((0, ring(1, i), ring(1, i + 1)))
    for j in range(1, nv - 1):
        a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
        tris += [(a, c, d), (a, d, b)]
    tris.append((bottom, ring(nv - 1, i + 1), ring(nv - 1, i)))


def rows(values, per_line):
    return "\n                 ".join(" ".join(values[k:k + per_line]) for k in range(0, len(values), per_line))


with open(os.path.join(here, "geometry", "killeroo3.pbrt"), "w") as f:
    f.write('Shape "loopsubdiv"\n    "integer levels" [ 3 ]\n')
    f.write('    "point3 P" [ ' + rows([f"{c:.3f}" for p in P for c in p], 9) + " ]\n")
    f.write('    "integer indices" [ ' + rows([str(v) for t in tris for v in t], 18) + " ]\n")

# The grid of lines.
s, w = 64, 4
img = np.full((s, s, 3), 255, dtype=np.uint8)
img[:w, :] = img[-w:, :] = img[:, :w] = img[:, -w:] = 32
path = os.path.join(here, "textures", "lines.png")
out = oiio.ImageOutput.create(path)
out.open(path, oiio.ImageSpec(s, s, 3, "uint8"))
out.write_image(img)
out.close()

# Gold's optical constants, from the table Dermis transcribed from Palik.
table_src = os.path.join(here, "..", "..", "..", "src", "dermis", "scene", "named_spectra_data.cpp")
text = open(table_src).read()
for name, file in (("kAuEta", "Au.eta.spd"), ("kAuK", "Au.k.spd")):
    body = re.search(r"constexpr double " + name + r"\[\] = \{(.*?)\};", text, re.S).group(1)
    values = [v for v in re.split(r"[\s,]+", body) if v]
    with open(os.path.join(here, "spds", file), "w") as f:
        f.write(f"# gold, {'index of refraction' if name == 'kAuEta' else 'extinction coefficient'}: "
                "Palik (ed.), Handbook of Optical Constants of Solids, Academic Press 1985.\n")
        f.write("# wavelength (nm)  value\n")
        for k in range(0, len(values), 2):
            f.write(f"{values[k]} {values[k + 1]}\n")
print(f"wrote geometry/killeroo3.pbrt ({len(P)} vertices, {len(tris)} triangles), textures/lines.png, "
      "spds/Au.eta.spd, spds/Au.k.spd")
