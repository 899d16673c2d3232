"""The family's HDR environments (issue 66), made procedurally so that no file is downloaded:
each is one function of the world direction (z up, as the scenes), written twice from it:
pbrt-v4's equal-area square for Dermis (`LightSource "infinite" "string filename"`, the
octahedral map of pbrt-v4's EqualAreaSquareToSphere, Clarberg 2008) and lat-long for
Blender's Environment Texture (Cycles' equirectangular mapping: u = 1/2 - atan2(y, x) / 2 pi
from the left, v = acos(z) / pi from the top row). `check` renders both in the two renderers'
conventions and compares them (bench/vs_cycles/run.py --check-environments).

- `outdoor`: a clear sky (brighter toward the horizon), a dark ground below it, and a sun of
  2 degrees' radius, its edge softened over a quarter degree, 40 degrees high;
- `studio`: a dark surround and three soft boxes: a large key, a dim fill low on the other
  side and a narrow bright rim light behind the object.

Radiance in the family's units (its uniform sky is about 0.08): the sun's irradiance on a
surface facing it is about four times the sky's, the key soft box's about three times.
"""

import math
import os
import tempfile

import numpy as np

EQUAL_AREA_SIZE = 1024  # pbrt-v4's square: 1024 x 1024 (a pixel is 1.2e-5 sr; the sun covers about 320)
LATLONG_SIZE = (2048, 1024)  # Blender's lat-long: 2048 x 1024
VERSION = 1  # bumped whenever a map's function changes (part of the file names)


def _direction(azimuth_deg, elevation_deg):
    a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
    return np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])


def _smooth_edge(x, width):
    """1 well inside (x << 0), 0 outside (x >= width), a smoothstep between."""
    t = np.clip(x / width, 0.0, 1.0)
    return 1.0 - t * t * (3.0 - 2.0 * t)


SUN_DIRECTION = _direction(-150.0, 40.0)
SUN_RADIUS = math.radians(2.0)
SUN_EDGE = math.radians(0.25)


def outdoor(d):
    """Radiance (N x 3) for unit directions d (N x 3)."""
    z = d[:, 2]
    zenith, horizon = np.array([0.045, 0.065, 0.11]), np.array([0.10, 0.11, 0.12])
    t = np.clip(z, 0.0, 1.0)[:, None] ** 0.5
    sky = horizon * (1 - t) + zenith * t
    ground = np.array([0.030, 0.027, 0.022])
    # Below the horizon the ground, above it the sky, blended over the first half degree.
    w = np.clip(z / math.sin(math.radians(0.5)), 0.0, 1.0)[:, None]
    out = ground * (1 - w) + sky * w
    angle = np.arccos(np.clip(d @ SUN_DIRECTION, -1.0, 1.0))
    sun = _smooth_edge(angle - (SUN_RADIUS - SUN_EDGE / 2), SUN_EDGE)[:, None]
    # The sun's irradiance at normal incidence is about 1.2 (the sky's about 0.3): L pi r^2.
    return out + sun * (1.2 / (math.pi * SUN_RADIUS ** 2)) * np.array([1.0, 0.93, 0.82])


# Soft boxes: (azimuth, elevation, half-width, half-height in degrees, radiance).
SOFT_BOXES = [
    (-170.0, 35.0, 16.0, 11.0, [2.0, 1.9, 1.75]),  # key: about 0.2 sr
    (-75.0, 5.0, 20.0, 14.0, [0.25, 0.26, 0.28]),  # fill, low on the other side
    (40.0, 20.0, 4.0, 22.0, [3.0, 3.0, 3.0]),  # rim, a narrow strip behind
]
SOFT_EDGE_DEG = 1.0


def studio(d):
    out = np.tile(np.array([0.004, 0.004, 0.005]), (d.shape[0], 1))
    az = np.degrees(np.arctan2(d[:, 1], d[:, 0]))
    el = np.degrees(np.arcsin(np.clip(d[:, 2], -1.0, 1.0)))
    for a0, e0, hw, hh, L in SOFT_BOXES:
        da = (az - a0 + 180.0) % 360.0 - 180.0
        inside = (_smooth_edge(np.abs(da) * np.cos(np.radians(el)) - hw, SOFT_EDGE_DEG) *
                  _smooth_edge(np.abs(el - e0) - hh, SOFT_EDGE_DEG))
        out = out + inside[:, None] * np.array(L)
    return out


ENVIRONMENTS = {"outdoor": outdoor, "studio": studio}


def equal_area_directions(n):
    """Unit directions at the pixel centres of pbrt-v4's n x n equal-area square (row 0 at the
    top: v = (row + 1/2) / n), as its EqualAreaSquareToSphere."""
    c = (np.arange(n) + 0.5) / n
    u, v = np.meshgrid(2 * c - 1, 2 * c - 1)  # u along columns, v along rows
    au, av = np.abs(u), np.abs(v)
    signed = 1 - (au + av)
    r = 1 - np.abs(signed)
    phi = np.where(r == 0, 1.0, (av - au) / np.where(r == 0, 1.0, r) + 1) * (math.pi / 4)
    z = np.copysign(1 - r * r, signed)
    s = r * np.sqrt(np.clip(2 - r * r, 0.0, None))
    x = np.copysign(np.cos(phi), u) * s
    y = np.copysign(np.sin(phi), v) * s
    return np.stack([x, y, z], axis=-1).reshape(-1, 3)


def latlong_directions(width, height):
    """Unit directions at the pixel centres of Cycles' equirectangular map (row 0 at the top)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    phi = 2 * math.pi * (0.5 - u)
    theta = math.pi * v
    p, t = np.meshgrid(phi, theta)
    return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)


def _write_exr(path, pixels):
    import OpenImageIO as oiio  # noqa: PLC0415  (only where a map is written)
    h, w, _ = pixels.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, 3, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, 3), np.ascontiguousarray(pixels, dtype=np.float32))
    tmp = path + ".tmp.exr"
    if not buf.write(tmp):
        raise RuntimeError(f"cannot write {path}: {buf.geterror()}")
    os.replace(tmp, path)


def default_directory():
    return os.path.join(tempfile.gettempdir(), "dermis-bench-environments")


def files(name, directory=None):
    """(equal-area path, lat-long path) of environment `name`, written into `directory` (default
    default_directory()) unless already there."""
    directory = directory or default_directory()
    os.makedirs(directory, exist_ok=True)
    f = ENVIRONMENTS[name]
    square = os.path.join(directory, f"env-{name}-v{VERSION}-equal-area.exr")
    latlong = os.path.join(directory, f"env-{name}-v{VERSION}-latlong.exr")
    if not os.path.exists(square):
        n = EQUAL_AREA_SIZE
        _write_exr(square, f(equal_area_directions(n)).reshape(n, n, 3))
    if not os.path.exists(latlong):
        w, h = LATLONG_SIZE
        _write_exr(latlong, f(latlong_directions(w, h)).reshape(h, w, 3))
    return square, latlong


def attach(env, directory=None):
    """The environment description of a scene (dict(name=...)) with the paths of its two maps
    filled in ("equal_area", "latlong"), written if need be; a directory already given in it
    ("directory") wins."""
    square, latlong = files(env["name"], env.get("directory") or directory)
    env.update(equal_area=square, latlong=latlong)
    return env
