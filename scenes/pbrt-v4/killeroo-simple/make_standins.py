#!/usr/bin/python3
"""Stand-in for the asset of pbrt-v4's `killeroo-simple` scene (mmp/pbrt-v4-scenes,
killeroos/), which is not redistributed here: a file of the same name and kind, so that
killeroo-simple.pbrt parses and renders exactly as written.

  geometry/killeroo.pbrt   one Shape "loopsubdiv" with "integer levels" [ 1 ], "point3 P"
                           and "integer indices", as the original: here a closed, coarse
                           ellipsoid (11 rings of 24 and two poles: 266 vertices) of the killeroo's extent in
                           its object space (x -37..37, y -40..92, z -140..4: it stands on
                           the scene's floor), wound outward. Loop subdivision and the
                           limit projection round it off.

Run with Debian's python3: /usr/bin/python3 make_standins.py
"""
import math
import os

here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(here, "geometry"), exist_ok=True)

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
for i in range(nu):  # counter-clockwise seen from outside
    tris.append((0, ring(1, i), ring(1, i + 1)))
    for j in range(1, nv - 1):
        a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
        tris += [(a, c, d), (a, d, b)]
    tris.append((bottom, ring(nv - 1, i + 1), ring(nv - 1, i)))

def rows(values, per_line):
    return "\n                 ".join(" ".join(values[k:k + per_line]) for k in range(0, len(values), per_line))

with open(os.path.join(here, "geometry", "killeroo.pbrt"), "w") as f:
    f.write('Shape "loopsubdiv"\n    "integer levels" [ 1 ]\n')
    f.write('    "point3 P" [ ' + rows([f"{c:.3f}" for p in P for c in p], 9) + " ]\n")
    f.write('    "integer indices" [ ' + rows([str(v) for t in tris for v in t], 18) + " ]\n")
print(f"wrote geometry/killeroo.pbrt ({len(P)} vertices, {len(tris)} triangles)")
