"""Reading a render: an EXR's channels as float64 NumPy arrays (OpenImageIO)."""
from typing import NamedTuple

import numpy as np
import OpenImageIO as oiio


class Exr(NamedTuple):
    rgb: np.ndarray  # (height, width, 3): the channels R, G, B (the first three if not so named)
    extra: dict  # the other channels by name (a render's `samples`, `error`), each (height, width)
    attrs: dict  # the header's metadata by name (Cycles' `cycles.ViewLayer.render_time`, ...)


def read_exr(path):
    """The image at path. ImageInput, not ImageBuf: ImageBuf's cache would return a file's
    first contents again when a later render writes over it."""
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise OSError(f"cannot read {path}: {oiio.geterror()}")
    try:
        spec = inp.spec()
        px = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
        if px is None:
            raise OSError(f"cannot read the pixels of {path}: {inp.geterror()}")
    finally:
        inp.close()
    px = np.asarray(px, dtype=np.float64).reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    rgb = [names.index(c) for c in "RGB"] if set("RGB") <= set(names) else [0, 1, 2]
    extra = {n: px[:, :, i] for i, n in enumerate(names) if i not in rgb}
    attrs = {a.name: a.value for a in spec.extra_attribs}
    return Exr(np.ascontiguousarray(px[:, :, rgb]), extra, attrs)
