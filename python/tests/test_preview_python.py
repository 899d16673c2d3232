"""dermis.render(..., preview=True): the page is served while the render runs (the URL on
sys.stderr and in the stats), and stops when render() returns."""
import io
import json
import re
import sys
import urllib.error
import urllib.request

import pytest


def test_render_serves_a_preview_while_it_runs(sphere_scene, dermis_module, monkeypatch):
    err = io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    seen = []

    def progress(done, total):  # on the calling thread, during the render and once at its end
        m = re.search(r"preview: (http://127\.0\.0\.1:\d+/)", err.getvalue())
        if m and not seen:
            with urllib.request.urlopen(m[1] + "status.json", timeout=10) as r:
                seen.append(json.load(r))
            with urllib.request.urlopen(m[1] + "image.png", timeout=10) as r:
                seen.append(r.read())

    image, stats = dermis_module.render(sphere_scene, spp=64, threads=1, progress=progress, stats=True,
                                        preview=True)
    assert seen, err.getvalue()
    assert seen[0]["state"] in ("rendering", "done") and seen[0]["width"] == image.shape[1], seen[0]
    assert seen[1][1:4] == b"PNG"
    assert f"preview: {stats['preview_url']}" in err.getvalue()
    with pytest.raises(urllib.error.URLError):  # gone with the render
        urllib.request.urlopen(stats["preview_url"] + "status.json", timeout=2)
    with pytest.raises(ValueError):
        dermis_module.render(sphere_scene, spp=1, preview=70000)
