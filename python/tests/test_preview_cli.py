"""`dermis render --preview` and `--watch` on loopback: the status and the image follow the
render, a change of the scene renders it again (once per burst of saves), a scene that no
longer loads shows its error while the last image stays, and -q leaves only the URL."""
import io
import time

import numpy as np
from PIL import Image

from preview_process import PreviewProcess, long_scene


def small_scene(reflectance):
    """A diffuse sphere in 32 x 24 pixels, 8 samples: done at once."""
    return f"""LookAt 0 -4 1  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Sampler "independent" "integer pixelsamples" 8
Film "rgb" "integer xresolution" 32 "integer yresolution" 24
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
Material "diffuse" "rgb reflectance" [{reflectance} 0.3 0.2]
Shape "sphere"
"""


def centre_mean(body):
    """The mean colour of the PNG's centre (the sphere), 8-bit sRGB values."""
    img = np.asarray(Image.open(io.BytesIO(body)).convert("RGB"), float)
    h, w = img.shape[:2]
    return img[h // 2 - 3:h // 2 + 3, w // 2 - 3:w // 2 + 3].mean(axis=(0, 1))


def test_the_status_and_the_image_follow_the_render(dermis_binary, tmp_path):
    scene = tmp_path / "scene.pbrt"
    scene.write_text(long_scene(64, 48))
    with PreviewProcess(dermis_binary, [str(scene), "--threads", "1", "-o", str(tmp_path / "out.exr")]) as p:
        p.wait_for(lambda s: s["state"] == "rendering" and s["frame"] > 0, "rendering")
        image = p.get("image.png")
        first = p.status()  # its frame is at least the image's
        assert p.get("/").startswith(b"<!DOCTYPE html>")
        # Later: more samples, a frame newer than the image's, another image (a new PNG at most
        # every 0.25 s for an image this small).
        later = p.wait_for(lambda s: s["frame"] > first["frame"] and s["samples_per_pixel"] > first["samples_per_pixel"],
                           "a new frame")
        time.sleep(0.3)
        assert p.get("image.png") != image
        assert later["progress"] >= first["progress"] and later["elapsed"] > first["elapsed"]
        assert later["eta"] is not None and later["spp"] == 1000000 and later["error"] is None
        assert (later["width"], later["height"]) == (64, 48)
        for path in ("samples.png", "error.png", "image.png?exposure=-2.5"):
            assert p.status_code(path) == 200, path
        for path in ("nothing", "out.exr", "scene.pbrt", "..%2f..%2fetc%2fpasswd", "status.json?x=/etc/passwd/.."):
            assert p.status_code(path) == (200 if path.startswith("status.json") else 404), path
        assert p.interrupt() == 130  # Ctrl-C during the render: interrupted, the image written
    assert (tmp_path / "out.exr").exists()


def test_watch_renders_again_on_a_change_and_keeps_the_last_image_on_an_error(dermis_binary, tmp_path):
    scene = tmp_path / "scene.pbrt"
    scene.write_text(small_scene(0.7))
    with PreviewProcess(dermis_binary, [str(scene), "--watch", "-q", "-o", str(tmp_path / "out.exr")]) as p:
        done = p.wait_for(lambda s: s["state"] == "done" and s["render"] == 1, "the first render done")
        red = centre_mean(p.get("image.png"))

        # A burst of saves: one render more, of the last text.
        for r in (0.1, 0.05, 0.0):
            scene.write_text(small_scene(r))
            time.sleep(0.02)
        second = p.wait_for(lambda s: s["state"] == "done" and s["render"] >= 2, "rendered again")
        time.sleep(1.0)  # longer than the debounce: a second restart would show by now
        assert p.status()["render"] == 2
        dark = centre_mean(p.get("image.png"))
        assert dark[0] < 0.5 * red[0], (red, dark)  # the red sphere is now black

        # A scene that no longer loads: its error on the page, the last image kept.
        scene.write_text(small_scene(0.0) + 'Shape "spere"\n')
        broken = p.wait_for(lambda s: s["state"] == "error", "the error shown")
        assert "scene.pbrt:9:7:" in broken["error"] and "spere" in broken["error"], broken
        np.testing.assert_array_equal(centre_mean(p.get("image.png")), dark)
        assert any("spere" in line for line in p.lines)  # and in the terminal

        scene.write_text(small_scene(0.7))  # fixed
        p.wait_for(lambda s: s["state"] == "done" and s["render"] == 3 and s["error"] is None, "rendered again")
        assert p.interrupt() == 0  # the last render was written
        assert done["frame"] < second["frame"]
    # -q: nothing but the URL and the error.
    assert [line for line in p.lines if not line.startswith("preview: ") and "spere" not in line] == [], p.stderr()


def test_a_scene_that_does_not_load_ends_the_preview_without_watch(dermis_binary, tmp_path):
    scene = tmp_path / "scene.pbrt"
    scene.write_text('Shape "spere"\n')
    with PreviewProcess(dermis_binary, [str(scene), "-q"]) as p:
        assert p.proc.wait(timeout=30) == 2
    assert "scene.pbrt:1:" in p.stderr()


def test_watch_follows_a_file_the_scene_includes(dermis_binary, tmp_path):
    scene, material = tmp_path / "scene.pbrt", tmp_path / "material.pbrt"
    material.write_text('Material "diffuse" "rgb reflectance" [0.7 0.3 0.2]\n')
    scene.write_text(small_scene(0.7).replace('Material "diffuse" "rgb reflectance" [0.7 0.3 0.2]\n',
                                              'Include "material.pbrt"\n'))
    with PreviewProcess(dermis_binary, [str(scene), "--watch", "-q", "-o", str(tmp_path / "out.exr")]) as p:
        p.wait_for(lambda s: s["state"] == "done" and s["render"] == 1, "the first render done")
        red = centre_mean(p.get("image.png"))
        material.write_text('Material "diffuse" "rgb reflectance" [0 0.3 0.2]\n')
        p.wait_for(lambda s: s["state"] == "done" and s["render"] == 2, "rendered again")
        assert centre_mean(p.get("image.png"))[0] < 0.5 * red[0]
        assert p.interrupt() == 0
