"""The study's HTML report, from synthetic data: complete, well-formed, self-contained."""

import base64
import html.parser
import math
import re

from dermis import report, repeats
from synthetic_study import make_synthetic_study


class _Collector(html.parser.HTMLParser):
    """Every tag's attributes, and the stack depth at the end (0 if tags close)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))


def _parse(text):
    p = _Collector()
    p.feed(text)
    p.close()
    return p.tags


def test_mean_stderr():
    m, se = repeats.mean_stderr([1.0, 2.0, 3.0, 4.0])
    assert m == 2.5
    assert math.isclose(se, math.sqrt(((1.5**2 + 0.5**2) * 2 / 3) / 4))
    assert repeats.mean_stderr([5.0]) == (5.0, None)
    assert repeats.format_mean_stderr(0.0123456, 0.00042) == "0.01235 ± 0.00042"


def test_tonemap_is_srgb():
    import numpy as np
    img = np.array([[[0.0, 0.5, 1.0], [2.0, -1.0, float("nan")]]], dtype=np.float32)
    out = report.tonemap(img)
    assert out.dtype == np.uint8
    assert out[0, 0].tolist() == [0, 188, 255]  # sRGB(0.5) = 0.7354
    assert out[0, 1].tolist() == [255, 0, 0]


def test_report_has_every_image_and_plot(tmp_path):
    synthetic_study = make_synthetic_study()
    path = tmp_path / "index.html"
    report.write_report(path, synthetic_study)
    text = path.read_text(encoding="utf-8")
    tags = _parse(text)
    imgs = [a for t, a in tags if t == "img"]
    n = len(synthetic_study["methods"])
    # reference, a flip pair per method, an error map per method, three plots, the mask
    assert len(imgs) == 1 + 2 * n + n + 3 + 1
    kinds = {"png": 0, "svg": 0}
    for a in imgs:
        m = re.match(r"data:image/(png|svg\+xml);base64,(.*)$", a["src"], re.S)
        assert m, a["src"][:60]
        data = base64.b64decode(m.group(2), validate=True)
        if m.group(1) == "png":
            assert data.startswith(b"\x89PNG\r\n\x1a\n")
            kinds["png"] += 1
        else:
            assert b"<svg" in data[:2000] and b"</svg>" in data[-100:]
            kinds["svg"] += 1
    assert kinds["svg"] == 3  # MSE, relMSE, MSE less the reference's variance
    # Every method's name, the table's standard errors, the command and the machine.
    for m in synthetic_study["methods"]:
        assert m["name"] in text
    assert "±" in text
    assert synthetic_study["command"] in text
    assert "Debian" in text and "abc1234" in text
    assert text.count("<table>") == text.count("</table>") >= 3


def test_report_loads_nothing_from_the_network(tmp_path):
    synthetic_study = make_synthetic_study()
    path = tmp_path / "index.html"
    report.write_report(path, synthetic_study)
    text = path.read_text(encoding="utf-8")
    for tag, attrs in _parse(text):
        for key in ("src", "href"):
            value = attrs.get(key) or ""
            assert not value.startswith(("http://", "https://", "//")), (tag, key, value[:80])
        if tag == "link":  # no external style sheets at all
            assert attrs.get("rel") != "stylesheet"
        if tag == "script":
            assert "src" not in attrs
    assert not re.search(r"""(src|href)\s*=\s*["']?\s*(https?:)?//""", text)
    assert "@import" not in text and "url(http" not in text
