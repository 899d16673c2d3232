"""The report in a real browser: headless Chromium loads it, runs its script, and draws it.

Skipped when Chromium is not installed (it is optional: scripts/install-bench-deps.sh
installs Debian's `chromium`).
"""

import html.parser
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

from dermis import report
from synthetic_study import make_synthetic_study


def _chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    pytest.skip("headless Chromium is not installed: run scripts/install-bench-deps.sh "
                "(or apt-get install --no-install-recommends chromium)")


def _run(chromium, tmp_path, *args):
    cmd = [chromium, "--headless", "--disable-gpu", "--no-sandbox", "--hide-scrollbars",
           f"--user-data-dir={tmp_path / 'profile'}", "--window-size=1400,1000", *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=90)
    assert p.returncode == 0, p.stderr[-2000:]
    return p.stdout


class _Images(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.imgs, self.status = [], None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img":
            self.imgs.append(a)
        if a.get("id") == "status":
            self.status = a


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    """One Chromium run on a synthetic report: the DOM after its script ran (--dump-dom)
    and a 1400 x 1000 screenshot."""
    chromium = _chromium()
    tmp_path = tmp_path_factory.mktemp("browser")
    page = tmp_path / "index.html"
    report.write_report(page, make_synthetic_study())
    shot = tmp_path / "shot.png"
    dom = _run(chromium, tmp_path, f"--screenshot={shot}", "--dump-dom", page.as_uri())
    return dom, shot


def test_browser_decodes_every_image(browser):
    """Every <img> (images and plots) has a natural width, and the status line counts
    them all as decoded."""
    p = _Images()
    p.feed(browser[0])
    assert len(p.imgs) >= 8
    widths = [int(a.get("data-natural-width", "0")) for a in p.imgs]
    assert all(w > 0 for w in widths), widths
    assert p.status is not None and p.status.get("data-loaded") == f"{len(p.imgs)}/{len(p.imgs)}", p.status


def test_browser_screenshot_is_not_blank(browser):
    img = np.asarray(Image.open(browser[1]).convert("RGB"))
    assert img.shape[:2] == (1000, 1400)
    packed = (img[..., 0].astype(np.uint32) << 16) | (img[..., 1].astype(np.uint32) << 8) | img[..., 2]
    colours = np.unique(packed)
    assert len(colours) > 500, len(colours)  # the noisy images, not just text on a background
    # The images' black-framed panels and their content: well away from a uniform page.
    assert img.std() > 30
