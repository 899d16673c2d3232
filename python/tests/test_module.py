"""The Python module: scenes, rendering, errors, images (issue 13)."""
import os
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import SOURCE_DIR, SPHERE_SCENE, GilProbe


def test_demo_scene_renders_from_a_path(dermis_module):
    scene = dermis_module.load_scene(os.path.join(SOURCE_DIR, "scenes", "demo.pbrt"))
    scene.resolution = (40, 30)
    image = dermis_module.render(scene, spp=1)
    assert image.shape == (30, 40, 3)
    assert image.dtype == np.float32
    assert np.isfinite(image).all() and image.mean() > 0


def test_render_equals_the_command_line_bit_for_bit(dermis_module, sphere_scene, dermis_binary, tmp_path):
    scene_file = tmp_path / "sphere.pbrt"
    scene_file.write_text(SPHERE_SCENE)
    exr = tmp_path / "sphere.exr"
    subprocess.run([dermis_binary, "render", str(scene_file), "--seed", "7", "--spp", "4", "-q", "--no-png", "-o",
                    str(exr)], check=True)
    cli = dermis_module.read_image(str(exr))
    module = dermis_module.render(sphere_scene, seed=7, spp=4)
    assert np.array_equal(cli, module)


def test_same_seed_same_image_whatever_the_threads(dermis_module, sphere_scene):
    a = dermis_module.render(sphere_scene, seed=3, spp=2, threads=1)
    b = dermis_module.render(sphere_scene, seed=3, spp=2, threads=2)
    c = dermis_module.render(sphere_scene, seed=4, spp=2, threads=2)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_inspection(dermis_module, sphere_scene):
    assert sphere_scene.resolution == (24, 18)
    assert sphere_scene.spp == 4
    assert sphere_scene.camera["fov"] == pytest.approx(40)
    materials = sphere_scene.materials
    skin = materials[sphere_scene.subsurface_materials[0]]
    assert skin["name"] == "skin" and skin["type"] == "subsurface"
    assert skin["parameters"]["method"] == "randomwalk"
    assert skin["parameters"]["mfp"] == pytest.approx((0.5, 0.25, 0.1))
    assert skin["types"]["mfp"] == "rgb"
    assert skin["location"].startswith("<string>:")


def test_a_changed_material_renders_as_the_scene_written_with_it(dermis_module, sphere_scene):
    before = dermis_module.render(sphere_scene, seed=5, spp=2)
    sphere_scene.set_material("skin", method="disk", mfp=(0.3, 0.2, 0.1))
    changed = dermis_module.render(sphere_scene, seed=5, spp=2)
    written = dermis_module.load_scene(SPHERE_SCENE.replace('"randomwalk"', '"disk"').replace(
        "[0.5 0.25 0.1]", "[0.3 0.2 0.1]"))
    assert np.array_equal(changed, dermis_module.render(written, seed=5, spp=2))
    assert not np.array_equal(before, changed)
    assert sphere_scene.materials[0]["parameters"]["method"] == "disk"
    # The same change as pbrt text.
    sphere_scene.set_material(0, '"string method" "randomwalk" "rgb mfp" [0.5 0.25 0.1]')
    assert np.array_equal(before, dermis_module.render(sphere_scene, seed=5, spp=2))


def test_integer_parameters_of_subsurface_from_python_numbers(dermis_module, sphere_scene):
    # maxpoints is an integer parameter of `subsurface` (docs/materials.md): a whole Python
    # number becomes "integer maxpoints", as the scene would write it; other numbers stay float.
    sphere_scene.set_material("skin", method="pointcloud", maxpoints=3000, epsilon=0.1)
    m = sphere_scene.materials[0]
    assert m["types"]["maxpoints"] == "integer" and m["parameters"]["maxpoints"] == 3000
    assert m["types"]["epsilon"] == "float"
    sphere_scene.set_material("skin", maxpoints=4000.0)  # a float with a whole value: integer too
    assert sphere_scene.materials[0]["types"]["maxpoints"] == "integer"
    with pytest.raises(dermis_module.SceneError, match="maxpoints"):
        sphere_scene.set_material("skin", maxpoints=3000.5)  # not a whole number: float, refused


def test_scene_errors_carry_file_line_column(dermis_module, sphere_scene, tmp_path):
    bad = tmp_path / "bad.pbrt"
    bad.write_text('WorldBegin\nShape "sphere" "float radius" "one"\n')
    with pytest.raises(dermis_module.SceneError, match=r"bad\.pbrt:2:\d+: error:"):
        dermis_module.load_scene(str(bad))
    assert issubclass(dermis_module.SceneError, ValueError)
    with pytest.raises(dermis_module.SceneError, match=r"<set_material>:1:\d+: error:.*method"):
        sphere_scene.set_material("skin", method="nonsense")
    assert sphere_scene.materials[0]["parameters"]["method"] == "randomwalk"  # unchanged
    with pytest.raises(KeyError, match="skin"):
        sphere_scene.set_material("nope", method="disk")
    with pytest.raises(dermis_module.SceneError, match="nothing.pbrt"):
        dermis_module.load_scene(str(tmp_path / "nothing.pbrt"))
    with pytest.raises(ValueError, match="spp"):
        dermis_module.render(sphere_scene, spp=0)
    with pytest.raises(ValueError, match="sampler"):
        dermis_module.render(sphere_scene, sampler="halton")


def test_warnings_are_python_warnings(dermis_module, sphere_scene):
    with pytest.warns(UserWarning, match="nonsense"):
        sphere_scene.set_material("skin", nonsense=1.0)


def test_progress_and_stats(dermis_module, sphere_scene):
    calls = []
    image, stats = dermis_module.render(sphere_scene, spp=3, progress=lambda done, total: calls.append((done, total)),
                                        stats=True)
    assert calls and calls[-1] == (24 * 18 * 3, 24 * 18 * 3)
    assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))
    assert stats["samples"] == 24 * 18 * 3 and stats["min_spp"] == stats["max_spp"] == 3
    assert stats["seconds"] > 0 and stats["cpu_seconds"] > 0 and stats["rays"] > 0
    assert not stats["interrupted"] and not stats["time_limited"]
    # The subsurface pilot measured the walk's strategies on the sphere.
    (choice,) = stats["subsurface_choices"]
    assert choice["material"] == 0 and choice["pixels"] >= 32 and choice["gain"] >= 1
    assert "randomwalk" in choice["description"]


def test_adaptive_sampling_equals_the_command_line_and_reports_its_maps(dermis_module, sphere_scene, dermis_binary,
                                                                        tmp_path):
    # A threshold at which some pixels stop early and some reach the maximum (at 0.03 every
    # pixel of this sphere stops by 48 samples since its walks also guide toward its far side).
    scene_file = tmp_path / "sphere.pbrt"
    scene_file.write_text(SPHERE_SCENE)
    exr = tmp_path / "sphere.exr"
    subprocess.run([dermis_binary, "render", str(scene_file), "--seed", "7", "--spp", "64", "--noise-threshold", "0.02",
                    "-q", "--no-png", "-o", str(exr)], check=True)
    calls = []
    image, stats = dermis_module.render(sphere_scene, seed=7, spp=64, noise_threshold=0.02, stats=True,
                                        progress=lambda done, total: calls.append((done, total)))
    assert np.array_equal(dermis_module.read_image(str(exr)), image)
    counts, error = stats["sample_counts"], stats["noise_error"]
    assert counts.shape == error.shape == (18, 24)
    assert counts.min() == 16 and counts.max() == 64 and stats["samples"] == counts.sum()
    assert (error[counts < 64] <= 0.02).all()
    assert 0 < stats["converged_pixels"] < 24 * 18
    assert stats["pixel_rays"].shape == (18, 24) and (stats["pixel_rays"] >= counts).all()
    assert calls[-1] == (24 * 18 * 64, 24 * 18 * 64)
    with pytest.raises(ValueError, match="noise_threshold"):
        dermis_module.render(sphere_scene, noise_threshold=-1)
    with pytest.raises(ValueError, match="min_spp"):
        dermis_module.render(sphere_scene, noise_threshold=0.1, min_spp=0)


def test_time_limit_keeps_the_samples_taken(dermis_module, sphere_scene):
    sphere_scene.resolution = (96, 72)
    image, stats = dermis_module.render(sphere_scene, spp=1 << 20, time_limit=0.3, stats=True)
    assert stats["time_limited"] and 1 <= stats["min_spp"] < 1 << 20
    assert stats["max_spp"] - stats["min_spp"] <= 16  # passes keep pixels even
    assert np.isfinite(image).all()


def test_ctrl_c_raises_render_interrupted_with_the_partial_image(dermis_module, sphere_scene):
    sphere_scene.resolution = (96, 72)
    # A real SIGINT at the render's first progress report: it lands in the render loop on
    # any machine. Unheeded, the render would run to its time limit and return normally.
    def interrupt(done, total):
        os.kill(os.getpid(), signal.SIGINT)
    with pytest.raises(dermis_module.RenderInterrupted) as info:
        dermis_module.render(sphere_scene, spp=1 << 20, time_limit=300, progress=interrupt)
    assert isinstance(info.value, KeyboardInterrupt)
    assert info.value.image.shape == (72, 96, 3)
    assert info.value.stats["interrupted"] and info.value.stats["min_spp"] >= 0
    assert np.isfinite(info.value.image).all()


def test_an_exception_in_progress_stops_the_render(dermis_module, sphere_scene):
    def fail(done, total):
        raise RuntimeError("stop here")
    sphere_scene.resolution = (96, 72)
    start = time.monotonic()
    with pytest.raises(RuntimeError, match="stop here"):
        dermis_module.render(sphere_scene, spp=1 << 20, progress=fail)
    assert time.monotonic() - start < 30


def test_render_releases_the_gil(dermis_module, sphere_scene):
    """The GIL is free while the render works (conftest.GilProbe): the probe's helper runs its
    steps during the render, whose progress callback then stops it. A render that kept the GIL
    would run to its time limit without the helper's exception."""
    sphere_scene.resolution = (96, 72)

    class HelperRan(Exception):
        pass

    with GilProbe() as probe:
        def progress(done, total):
            probe.started.set()
            if probe.finished.is_set():
                raise HelperRan()
        with pytest.raises(HelperRan):
            dermis_module.render(sphere_scene, spp=1 << 20, time_limit=300, threads=1, progress=progress)
    with pytest.raises(ValueError):
        sphere_scene.resolution = (0, 10)


def test_compare_and_error_map(dermis_module):
    rng = np.random.default_rng(1)
    b = rng.random((8, 10, 3), dtype=np.float32)
    a = b + np.float32(0.1)
    c = dermis_module.compare(a, b)
    assert c["rmse"] == pytest.approx(0.1, rel=1e-5)
    assert c["relmse"] == pytest.approx(np.mean(0.01 / (b.astype(np.float64) ** 2 + 0.01)), rel=1e-4)
    assert dermis_module.compare(b, b)["rmse"] == 0
    emap, scale = dermis_module.error_map(a, b)
    assert emap.shape == b.shape and scale > 0
    with pytest.raises(ValueError):
        dermis_module.compare(a, b[:4])


def test_subsurface_mask(dermis_module, sphere_scene):
    mask = dermis_module.subsurface_mask(sphere_scene)
    assert mask.shape == (18, 24) and mask.dtype == bool
    assert mask[9, 12] and not mask[0, 0]


def test_images_round_trip(dermis_module, tmp_path):
    image = np.linspace(0, 2, 6 * 4 * 3, dtype=np.float32).reshape(6, 4, 3)
    dermis_module.write_image(str(tmp_path / "x.exr"), image)
    assert np.array_equal(dermis_module.read_image(str(tmp_path / "x.exr")), image)


def test_help_says_what_each_argument_means(dermis_module):
    doc = dermis_module.render.__doc__
    for word in ("spp", "seed", "threads", "time_limit", "progress", "RenderInterrupted"):
        assert word in doc
    assert "set_material" in dermis_module.Scene.set_material.__doc__
