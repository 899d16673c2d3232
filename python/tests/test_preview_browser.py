"""The live preview in a real browser: `dermis render SCENE --preview 0` serves its page,
headless Chromium loads it, polls the status and draws the finished image.

Skipped when Chromium is not installed (it is optional: scripts/install-bench-deps.sh
installs Debian's `chromium`).
"""

import io
import re
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

from preview_process import PreviewProcess


# A diffuse sphere under a uniform grey sky: renders in well under a second.
SCENE = """LookAt 0 -4 1  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Sampler "independent" "integer pixelsamples" 16
Film "rgb" "integer xresolution" 160 "integer yresolution" 120 "string filename" "out.exr"
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
Material "diffuse" "rgb reflectance" [0.7 0.3 0.2]
Shape "sphere"
"""


def _chromium():
    """Helper: the Chromium executable, or a skip."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    pytest.skip("headless Chromium is not installed: run scripts/install-bench-deps.sh "
                "(or apt-get install --no-install-recommends chromium)")


def _image_area(shot, background=(43, 43, 43)):
    """Helper: the part of the screenshot where the page drew the image, 2 pixels in from its
    edges (where it blends into the background). The page's image area is exactly #2b2b2b and
    "fit" keeps the image 8 px inside it: its rows are those whose left pixel is background,
    the image the bounding box of what differs from the background there."""
    rows = np.flatnonzero((shot[:, 2] == background).all(axis=1))
    assert len(rows), "no #2b2b2b image area in the screenshot"
    area = shot[rows[0]:rows[-1] + 1]
    ys, xs = np.nonzero((np.abs(area - background) > 2).any(axis=2))
    assert len(ys), "nothing drawn in the image area"
    return area[ys.min() + 2:ys.max() - 1, xs.min() + 2:xs.max() - 1]


def test_preview_page_draws_the_finished_image(dermis_binary, tmp_path):
    chromium = _chromium()
    scene = tmp_path / "scene.pbrt"
    scene.write_text(SCENE)
    with PreviewProcess(dermis_binary, [str(scene), "-q", "-o", str(tmp_path / "out.exr")]) as p:
        status = p.wait_for(lambda s: s["state"] == "done", "done")
        assert (status["width"], status["height"]) == (160, 120), status
        png = np.asarray(Image.open(io.BytesIO(p.get("image.png?exposure=0"))).convert("RGB"), float)
        assert png.shape == (120, 160, 3)
        assert png.mean() > 30, png.mean()  # lit: the comparison below means something

        # One Chromium run: the screenshot, and the DOM after the script ran. (Headless
        # Chromium lays the page out in a shorter window, then enlarges it for the screenshot:
        # the image is found in the screenshot itself, not from the DOM.)
        shot = tmp_path / "shot.png"
        r = subprocess.run([chromium, "--headless", "--disable-gpu", "--no-sandbox", "--hide-scrollbars",
                            f"--user-data-dir={tmp_path / 'profile'}", "--window-size=1280,800",
                            "--virtual-time-budget=4000", f"--screenshot={shot}", "--dump-dom", p.url],
                           capture_output=True, text=True, timeout=90)
        assert r.returncode == 0, r.stderr[-2000:]
        canvas = re.search(r'<canvas[^>]*id="view"[^>]*>', r.stdout)
        assert canvas, r.stdout[-2000:]
        assert f'data-frame="{status["frame"]}"' in canvas[0], canvas[0]  # the last frame is drawn
        assert 'data-view="image"' in canvas[0] and 'data-exposure="0.0"' in canvas[0], canvas[0]

        crop = _image_area(np.asarray(Image.open(shot).convert("RGB"), float))
        assert crop.shape[0] > 300 and crop.shape[1] > 400, crop.shape  # "fit": most of the window
        # 15 %: the browser enlarges the image (nearest neighbour, a non-integer factor, so some
        # rows and columns are repeated more than others) and may colour-manage the PNG; this
        # checks that the right image is drawn, lit and unclipped, not statistics.
        # Per channel (which implies the mean over all of them): a swapped channel shows too.
        np.testing.assert_allclose(crop.mean(axis=(0, 1)), png.mean(axis=(0, 1)), rtol=0.15)

        # After the render the preview serves until Ctrl-C, which ends it.
        assert p.interrupt() == 0
