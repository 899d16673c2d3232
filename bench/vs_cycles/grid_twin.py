"""The grid medium's twin (issue 67, item 4): one density grid, written as pbrt-v4's
`uniformgrid` for Dermis and as an OpenVDB file for Blender (python3-openvdb, run by Debian's
Python: Blender 3.4's own has no pyopenvdb), with the same samples at the same places.

pbrt-v4's SampledGrid puts sample (i, j, k) of an n^3 grid at the centre of cell (i, j, k)
of its box, p0 + (i + 1/2) h with h = (p1 - p0) / n, and interpolates trilinearly, with
zero beyond the outermost samples; the VDB's index-to-world transform puts voxel (i, j, k)
there too, and Cycles interpolates its voxels trilinearly with the background (zero)
beyond the active ones. The densities vanish on the grid's two outermost layers, so that
neither convention's edge is ever reached: a smooth blob (a Gaussian of the distance to
the box's centre) modulated by a seeded noise of a few cells, like a puff of smoke.
"""

import os
import tempfile

import numpy as np


def densities(n, seed):
    """The n^3 densities, indexed [z][y][x] (x fastest when flattened, as pbrt-v4 reads them),
    in [0, about 1.5]."""
    c = (np.arange(n) + 0.5) / n * 2 - 1  # the samples' positions in [-1, 1]
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    blob = np.exp(-(x * x + y * y + z * z) / (2 * 0.35 ** 2))
    rng = np.random.default_rng(seed)
    coarse = rng.uniform(0.3, 1.7, size=(n // 4 + 2,) * 3)
    # Trilinear upsampling of the coarse noise to the grid.
    q = (np.arange(n) + 0.5) / 4
    i = np.floor(q).astype(int)
    f = q - i
    noise = np.zeros((n, n, n))
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                w = ((f if dz else 1 - f)[:, None, None] * (f if dy else 1 - f)[None, :, None] *
                     (f if dx else 1 - f)[None, None, :])
                noise += w * coarse[np.ix_(i + dz, i + dy, i + dx)]
    d = blob * noise
    d[:2, :, :] = d[-2:, :, :] = d[:, :2, :] = d[:, -2:, :] = d[:, :, :2] = d[:, :, -2:] = 0
    return d.astype(np.float32)


def pbrt_values(medium):
    """The densities as pbrt-v4 text (x fastest)."""
    d = densities(medium["n"], medium["seed"])
    return " ".join(f"{v:.6g}" for v in d.ravel())


def write_vdb(path, medium):
    """The densities as an OpenVDB FloatGrid "density", voxel (i, j, k) centred where pbrt-v4's
    sample (i, j, k) is."""
    import pyopenvdb as vdb  # noqa: PLC0415  (python3-openvdb, Debian's Python only)
    n, (lo, hi) = medium["n"], medium["box"]
    h = (hi - lo) / n
    grid = vdb.FloatGrid()
    # pyopenvdb's copyFromArray takes [x][y][z]; ours is [z][y][x].
    grid.copyFromArray(np.ascontiguousarray(densities(n, medium["seed"]).transpose(2, 1, 0)))
    grid.name = "density"
    m = np.identity(4)
    m[0, 0] = m[1, 1] = m[2, 2] = h
    m[3, :3] = lo + h / 2
    grid.transform = vdb.createLinearTransform(m)
    tmp = path + ".tmp.vdb"
    vdb.write(tmp, grids=[grid])
    os.replace(tmp, path)


def attach(medium, directory=None):
    """The medium's description with the path of its .vdb filled in ("vdb"), written if need
    be (into `directory`, default a folder of the system's temporary directory)."""
    directory = directory or os.path.join(tempfile.gettempdir(), "dermis-bench-grids")
    os.makedirs(directory, exist_ok=True)
    lo, hi = medium["box"]
    path = os.path.join(directory, f"grid-n{medium['n']}-s{medium['seed']}-box{lo:g}_{hi:g}.vdb")
    if not os.path.exists(path):
        write_vdb(path, medium)
    medium["vdb"] = path
    return medium
