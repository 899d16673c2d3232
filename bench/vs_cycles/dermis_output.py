"""What the harness reads from `dermis render`'s log, and how it writes its picture sheets."""
import re

import numpy as np

# `dermis render` prints "... in 1.302 s (2.1 Mrays/s, 64 samples)" when the render stage ends,
RENDER_RE = re.compile(r"in ([0-9.]+) s \(([0-9.]+) Mrays/s, ([0-9]+) samples\)")
# and "time limit reached: 12..14 samples per pixel" when --time-limit stopped it.
LIMIT_RE = re.compile(r"time limit reached: ([0-9]+)\.\.([0-9]+) samples per pixel")


def write_png(img, path):
    """Linear RGB -> sRGB-encoded, clamped 8-bit PNG (as `dermis render` writes its previews)."""
    from PIL import Image
    x = np.clip(img, 0, 1)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)  # sRGB transfer (IEC 61966-2-1)
    Image.fromarray((x * 255 + 0.5).astype(np.uint8), "RGB").save(path)


def strip(pngs, out, labels=None):
    """PNG files side by side, each labelled, saved as a palette PNG (a third of the size)."""
    from PIL import Image, ImageDraw
    ims = [Image.open(p).convert("RGB") for p in pngs]
    w, h = ims[0].size
    sheet = Image.new("RGB", (w * len(ims), h))
    for i, im in enumerate(ims):
        sheet.paste(im, (i * w, 0))
    if labels:
        d = ImageDraw.Draw(sheet)
        for i, t in enumerate(labels):
            d.rectangle([i * w, 0, i * w + 6 * len(t) + 4, 12], fill=(0, 0, 0))
            d.text((i * w + 2, 0), t, fill=(255, 255, 255))
    sheet.quantize(256, dither=Image.Dither.NONE).save(out, optimize=True)
