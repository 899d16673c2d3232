"""Pictures for the pages: linear images as 8-bit sRGB PNGs, and strips of labelled panels."""
import numpy as np


def srgb8(img):
    """Linear RGB -> sRGB-encoded (IEC 61966-2-1), clamped, 8 bits."""
    x = np.clip(img, 0, 1)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (x * 255 + 0.5).astype(np.uint8)


def write_png(img, path):
    """A linear RGB image as a PNG (as `dermis render` writes its previews)."""
    from PIL import Image
    Image.fromarray(srgb8(img), "RGB").save(path)


def strip(panels, path, labels=None):
    """PIL images of one size side by side, each labelled, saved as a palette PNG (a third of
    the size)."""
    from PIL import Image, ImageDraw
    w, h = panels[0].size
    sheet = Image.new("RGB", (w * len(panels), h))
    for i, panel in enumerate(panels):
        sheet.paste(panel, (i * w, 0))
    if labels:
        d = ImageDraw.Draw(sheet)
        for i, t in enumerate(labels):
            d.rectangle([i * w, 0, i * w + 6 * len(t) + 4, 12], fill=(0, 0, 0))
            d.text((i * w + 2, 0), t, fill=(255, 255, 255))
    sheet.quantize(256, dither=Image.Dither.NONE).save(path, optimize=True)
