"""Spectral transport from Python and the command line (issue 65): spectral=True, the scene's
Option "bool spectral", --spectral, and the warning where the scene has no spectral form."""
import subprocess
import warnings

import numpy as np
import pytest

GREY_SCENE = """LookAt 0 -4 1  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 16 "integer yresolution" 12
Sampler "zsobol" "integer pixelsamples" 64
{option}
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
Material "diffuse" "rgb reflectance" [0.6 0.3 0.2]
Shape "sphere"
"""


def test_spectral_render_from_python(dermis_module, tmp_path):
    path = tmp_path / "grey.pbrt"
    path.write_text(GREY_SCENE.format(option=""))
    scene = dermis_module.load_scene(str(path))
    rgb, rgb_stats = dermis_module.render(scene, seed=1, stats=True)
    spectral, stats = dermis_module.render(scene, seed=1, stats=True, spectral=True)
    assert not rgb_stats["spectral"] and stats["spectral"]
    assert np.isfinite(spectral).all()
    assert not np.array_equal(rgb, spectral)
    # The same picture, up to noise and the spectra's colour products: within 5 % per channel.
    assert np.allclose(spectral.mean(axis=(0, 1)), rgb.mean(axis=(0, 1)), rtol=0.05)


def test_the_scenes_option_and_the_flag_agree(dermis_module, dermis_binary, tmp_path):
    with_option = tmp_path / "option.pbrt"
    with_option.write_text(GREY_SCENE.format(option='Option "bool spectral" true'))
    plain = tmp_path / "plain.pbrt"
    plain.write_text(GREY_SCENE.format(option=""))
    a, b = tmp_path / "a.exr", tmp_path / "b.exr"
    subprocess.run([dermis_binary, "render", str(with_option), "--seed", "2", "-q", "--no-png", "-o", str(a)],
                   check=True)
    subprocess.run([dermis_binary, "render", str(plain), "--spectral", "--seed", "2", "-q", "--no-png", "-o", str(b)],
                   check=True)
    assert np.array_equal(dermis_module.read_image(str(a)), dermis_module.read_image(str(b)))
    scene = dermis_module.load_scene(str(with_option))
    assert np.array_equal(dermis_module.render(scene, seed=2), dermis_module.read_image(str(a)))


def test_a_subsurface_scene_renders_spectrally(dermis_module, sphere_scene):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        image, stats = dermis_module.render(sphere_scene, spp=1, stats=True, spectral=True)
    assert stats["spectral"]
    assert not np.array_equal(image, dermis_module.render(sphere_scene, spp=1))


def point_cloud_scene():
    from conftest import SPHERE_SCENE
    return SPHERE_SCENE.replace('"string method" "randomwalk"', '"string method" "pointcloud"')


def test_the_point_cloud_warns_what_it_does_in_rgb(dermis_module):
    scene = point_cloud_scene()
    assert "pointcloud" in scene
    with pytest.warns(UserWarning, match="the point-cloud method has no spectral form"):
        _, stats = dermis_module.render(dermis_module.load_scene(scene), spp=1, stats=True, spectral=True)
    assert stats["spectral"]


def test_the_command_line_warns_what_the_point_cloud_does_in_rgb(dermis_binary, tmp_path):
    path = tmp_path / "cloud.pbrt"
    path.write_text(point_cloud_scene())
    run = subprocess.run([dermis_binary, "render", str(path), "--spectral", "--spp", "1", "-o",
                          str(tmp_path / "cloud.exr"), "--no-png"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "warning: --spectral: the point-cloud method has no spectral form: its cloud is computed in RGB" \
        in run.stderr
