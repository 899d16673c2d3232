"""The scene family of the Cycles harness (issue 40): it spans what the issue asks for, and
every configuration's Dermis file loads and renders. Run by ctest (bench.vs_cycles_family)
with DERMIS=<path of the dermis binary>; Blender is not needed."""

import json
import math
import os

import numpy as np
import pytest

from bench.harness import render
from bench.harness.exr import read_exr
from bench.vs_cycles import environments, grid_twin, pbrt_writer
from bench.vs_cycles import scenes as S


def test_the_family_spans_light_scale_geometry_albedo_and_media():
    assert len(S.FAMILY_CONFIGS) >= 12
    assert {c[0] for c in S.FAMILY_CONFIGS} == {"sphere", "bust", "fin"}
    assert {c[1] for c in S.FAMILY_CONFIGS} == {"sky", "key", "both", "back"}
    assert {c[2] for c in S.FAMILY_CONFIGS} == {0.01, 0.1, 1.0}
    albedos = [a for c in S.FAMILY_CONFIGS for a in S.FAMILY_MATERIALS[c[3]]["reflectance"]]
    assert min(albedos) <= 0.3 and max(albedos) >= 0.95
    boundaries = {sc["material"].get("boundary") for sc in S.FAMILY.values() if sc["material"]["kind"] == "medium"}
    assert boundaries == {"matched", "glass"}
    # Every subsurface configuration has its walk and its disk twin, with one method each.
    methods = sorted(sc["family"]["method"] for sc in S.FAMILY.values() if sc["material"]["kind"] == "subsurface")
    assert methods == ["disk"] * len(S.FAMILY_CONFIGS) + ["walk"] * len(S.FAMILY_CONFIGS)
    # The disk twins also render the other probe method (item 2 names both), after the disk.
    for sc in S.FAMILY.values():
        if sc["family"]["method"] == "disk":
            assert list(sc["dermis"]) == ["disk burley", S.LINES_LABEL]
            assert '"string method" "sphere-lines"' in pbrt_writer.scene_text(sc, S.LINES_LABEL, S.LINES_EXTRA)


def test_scale_is_the_mean_mfp_over_the_smallest_extent():
    for sc in S.FAMILY.values():
        fam = sc["family"]
        if sc["material"]["kind"] == "subsurface":
            size = S.FAMILY_GEOMETRY[fam["geometry"]]["size"]
            assert sum(sc["material"]["mfp"]) / 3 == pytest.approx(fam["scale"] * size)


def test_the_ellipsoid_is_closed_and_faces_outward():
    verts, faces = S.ellipsoid_mesh([1.0, 2.0, 3.0], [25.0, 3.0, 18.0], 16, 8)
    edges = {}
    for f in faces:
        a, b, c = (verts[i] for i in f)
        n = [(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
             (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
             (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])]
        centroid = [(a[k] + b[k] + c[k]) / 3 - [1.0, 2.0, 3.0][k] for k in range(3)]
        assert sum(x * y for x, y in zip(n, centroid)) > 0
        for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
            edges[e] = edges.get(e, 0) + 1
    # Closed and consistently wound: every directed edge once, its reverse once.
    assert all(n == 1 and edges.get((b, a)) == 1 for (a, b), n in edges.items())


def renders_without_warning(sc, tmp_path):
    """Every Dermis variant of scene description sc renders (16x12, 1 spp) with no warning."""
    dermis = os.environ.get("DERMIS")
    if not dermis:
        pytest.skip("DERMIS (the dermis binary) not set")
    for i, (label, extra) in enumerate(sc["dermis"].items()):
        path = tmp_path / f"{i}.pbrt"
        path.write_text(pbrt_writer.scene_text(sc, label, extra))
        out = tmp_path / f"{i}.exr"
        p = render.render(dermis, str(path), str(out), timeout=120, spp=1, res="16x12", threads=1)
        assert "warning" not in p.log, p.log
        assert out.exists()


@pytest.mark.parametrize("name", sorted(S.FAMILY))
def test_every_configuration_renders_in_dermis(name, tmp_path):
    renders_without_warning(S.FAMILY[name], tmp_path)


def test_the_held_out_configurations_are_not_in_the_family_and_render(tmp_path):
    from bench.vs_cycles import heldout
    family = {tuple(c) for c in S.FAMILY_CONFIGS}
    assert not family & {tuple(c) for c in S.HELDOUT_CONFIGS}
    assert not set(S.HELDOUT_MATERIALS) & set(S.FAMILY_MATERIALS)
    assert not set(S.HELDOUT) & set(S.FAMILY)
    # Each has its walk and its disk twin (run.py --set heldout), and heldout.py writes the walks.
    methods = sorted(sc["family"]["method"] for sc in S.HELDOUT.values())
    assert methods == ["disk"] * len(S.HELDOUT_CONFIGS) + ["walk"] * len(S.HELDOUT_CONFIGS)
    texts = heldout.heldout_scenes()
    assert sorted(texts) == sorted(n for n in S.HELDOUT if n.endswith("-walk"))
    for name, sc in sorted(S.HELDOUT.items()):
        renders_without_warning(sc, tmp_path)


def test_the_textured_configurations_are_new_and_render(tmp_path):
    """A checkerboard reflectance (run.py --set textured): configurations of neither the
    family nor the held-out set, walk and disk twin each, the texture in the Dermis text,
    the other squares' Cycles radius from their own reflectance."""
    assert not {tuple(c) for c in S.TEXTURED_CONFIGS} & {tuple(c) for c in S.FAMILY_CONFIGS + S.HELDOUT_CONFIGS}
    methods = sorted(sc["family"]["method"] for sc in S.TEXTURED.values())
    assert methods == ["disk"] * len(S.TEXTURED_CONFIGS) + ["walk"] * len(S.TEXTURED_CONFIGS)
    for name, sc in sorted(S.TEXTURED.items()):
        m = sc["material"]
        assert m["checker"]["reflectance"] == [S.TEXTURED_CHECKER * a for a in m["reflectance"]]
        for label, extra in sc["dermis"].items():
            text = pbrt_writer.scene_text(sc, label, extra)
            assert '"texture reflectance" "reflectance"' in text and '"checkerboard" "integer dimension" 3' in text
        other = S.cycles_radius(dict(m, reflectance=m["checker"]["reflectance"]))
        assert all(r != o for r, o in zip(S.cycles_radius(m), other)), name
        renders_without_warning(sc, tmp_path)


def test_the_close_ups_are_the_family_framed_close_and_render(tmp_path):
    """run.py --set closeup: each family configuration again, walk and disk twin, with the
    same material and lights and the same camera but for a narrower field of view."""
    assert len(S.CLOSEUP) == 2 * len(S.FAMILY_CONFIGS)
    for name, sc in sorted(S.CLOSEUP.items()):
        twin = S.FAMILY["f" + name[1:]]
        assert sc["material"] == twin["material"] and sc["lights"] == twin["lights"] and sc["sky"] == twin["sky"]
        assert sc["dermis"] == twin["dermis"]
        geometry = sc["family"]["geometry"]
        assert sc["camera"] == dict(twin["camera"], fov=S.CLOSEUP_FOV[geometry])
        assert sc["camera"]["fov"] < twin["camera"]["fov"]
        renders_without_warning(sc, tmp_path)


def test_the_random_walk_twins_enter_as_cycles_3_4_does():
    """Cycles 3.4's Random Walk enters along a cosine lobe: its Dermis twin says so; the
    Christensen-Burley twins (profile methods) have no entry direction to set."""
    for name, sc in S.SCENES.items():
        m = sc["material"]
        if m["kind"] != "subsurface":
            continue
        for label, extra in sc["dermis"].items():
            text = pbrt_writer.scene_text(sc, label, extra)
            assert ('"string entry" "lambertian"' in text) == (m["method"] == "randomwalk"), (name, label)


def test_the_highlight_scene_shows_only_the_quad_lights_mirror_image(tmp_path):
    """run.py's third convention leaves out the pixels where the object shows a light's
    mirror image: pbrt_writer.highlight_text renders the object as a smooth mirror with its
    boundary's Fresnel reflectance under the quad lights alone. None without a quad light or
    a reflecting boundary; on the key-lit sphere, a few pixels of the object light up, and
    they are the brightest of the scene's own reference."""
    assert pbrt_writer.highlight_text(S.FAMILY["f02-sphere-sky-0.1-milk-walk"], 16) is None  # the sky alone
    assert pbrt_writer.highlight_text(S.FAMILY["f13-medium-matched"], 16) is None  # no boundary
    sc = S.FAMILY["f03-sphere-key-0.1-jade-walk"]
    text = pbrt_writer.highlight_text(sc, 256)
    assert 'LightSource "infinite"' not in text and '"conductor" "rgb eta" [ 1.4 1.4 1.4 ] "rgb k" [ 0 0 0 ]' in text
    dermis = os.environ.get("DERMIS")
    if not dermis:
        pytest.skip("DERMIS (the dermis binary) not set")

    def brightest_channel(name, body, spp):
        path = tmp_path / f"{name}.pbrt"
        path.write_text(body)
        out = tmp_path / f"{name}.exr"
        render.render(dermis, str(path), str(out), timeout=120, spp=spp, res="64x48", threads=1)
        return read_exr(str(out)).rgb.max(axis=2)

    covered = brightest_channel("mask", pbrt_writer.mask_text(sc), 16) > 0.999
    lit = brightest_channel("highlights", text, 256) > 0
    assert covered.sum() > 500 and 0 < (lit & covered).sum() < 0.02 * covered.sum()
    scene = brightest_channel("scene", pbrt_writer.scene_text(sc, *next(iter(sc["dermis"].items()))), 64)
    assert scene[lit & covered].max() >= scene[covered].max()  # the brightest pixel is a highlight


def test_the_lighting_axis_spans_environments_and_area_light_sizes(tmp_path):
    """run.py --set lighting (issue 66): each lighting on one configuration per geometry (walk
    and disk twins) and on the three media; an HDR environment alone or an area light alone;
    the area lights subtend their solid angle at the object (the exact solid angle of a
    square on its axis, by quadrature) and give the same irradiance; and the scenes render."""
    # The family's geometries and materials under the new lights: each is a family configuration's.
    assert {tuple(c) for c in S.LIGHTING_CONFIGS} <= {(g, s, m) for g, _, s, m in S.FAMILY_CONFIGS}
    by_lighting = {}
    for name, sc in S.LIGHTING.items():
        by_lighting.setdefault(sc["family"]["balance"], []).append(name)
        if sc["family"]["balance"] in S.HDR_LIGHTINGS:
            assert sc["sky"] is None and sc["lights"] == [] and sc["environment"]["name"] in environments.ENVIRONMENTS
            continue
        assert sc["sky"] is None and "environment" not in sc and len(sc["lights"]) == 1
        corners = np.array(sc["lights"][0]["corners"])
        centre, side = corners.mean(axis=0), np.linalg.norm(corners[1] - corners[0])
        # Solid angle at the origin by a midpoint rule over the square (200 x 200 cells).
        u, v = (corners[1] - corners[0]) / side, (corners[3] - corners[0]) / side
        t = (np.arange(200) + 0.5) / 200 * side
        p = corners[0] + t[:, None, None] * u + t[None, :, None] * v
        r = np.linalg.norm(p, axis=-1)
        n = np.cross(u, v)
        omega = float((np.abs(p @ n) / r ** 3).sum() * (side / 200) ** 2)
        expected = S.AREA_LIGHTINGS[sc["family"]["balance"]]
        assert abs(omega / expected - 1) < 0.01, (name, omega)
        assert abs(max(sc["lights"][0]["radiance"]) * expected - S.AREA_IRRADIANCE) < 1e-9
        assert np.linalg.norm(centre) > 2 * side or expected > 0.1  # far from the object but for the largest
    assert sorted(by_lighting) == sorted(S.LIGHTINGS)
    assert all(len(v) == 2 * len(S.LIGHTING_CONFIGS) + len(S.LIGHTING_MEDIA) for v in by_lighting.values())
    for name in ("l01-sphere-hdr-outdoor-0.1-skin-walk", "l20-medium-glass-hdr-studio", "l27-medium-dense-area-0.05",
                 "l15-fin-area-0.2-1-milk-disk"):
        sc = json.loads(json.dumps(S.LIGHTING[name]))
        if "environment" in sc:
            sc["environment"]["directory"] = str(tmp_path / "environments")
        renders_without_warning(sc, tmp_path)


def test_the_environments_two_maps_are_one_function_of_direction():
    """environments.py: the equal-area square and the lat-long map of each environment hold the
    same light (their integrals over the sphere within 0.1 %), the sun where it is in both, and
    the equal-area directions are pbrt-v4's (unit, the upper hemisphere in the central diamond)."""
    for name, f in environments.ENVIRONMENTS.items():
        n = environments.EQUAL_AREA_SIZE
        d = environments.equal_area_directions(n)
        assert np.allclose(np.linalg.norm(d, axis=1), 1)
        c = (np.arange(n) + 0.5) / n * 2 - 1
        l1 = (np.abs(c)[None, :] + np.abs(c)[:, None]).ravel()
        assert np.all(d[l1 < 1, 2] > 0) and np.all(d[l1 > 1, 2] < 0)
        square = f(d).sum(axis=0) * 4 * math.pi / n ** 2
        w, h = environments.LATLONG_SIZE
        theta = (np.arange(h) + 0.5) / h * math.pi
        solid = (2 * math.pi / w) * (math.pi / h) * np.repeat(np.sin(theta), w)
        latlong = (f(environments.latlong_directions(w, h)) * solid[:, None]).sum(axis=0)
        assert np.allclose(square, latlong, rtol=1e-3), (name, square, latlong)
    sun = environments.SUN_DIRECTION
    phi, theta = math.atan2(sun[1], sun[0]), math.acos(sun[2])
    u, v = 0.5 - phi / (2 * math.pi), theta / math.pi  # Cycles' equirectangular mapping
    d = environments.latlong_directions(1024, 512).reshape(512, 1024, 3)[int(v * 512), int(u * 1024)]
    assert math.degrees(math.acos(min(1.0, float(d @ sun)))) < 0.5


def test_the_grid_twin_puts_its_samples_where_pbrt_v4_does(tmp_path):
    """grid_twin.py (run.py --scenes medium-grid): the densities vanish on the two outer layers
    (neither renderer's edge convention is reached), pbrt-v4's text holds n^3 of them x fastest,
    the Dermis scene renders, and, where python3-openvdb is installed, the .vdb holds the same
    value at the same world position as pbrt-v4's sample."""
    m = S.SCENES["medium-grid"]["material"]
    d = grid_twin.densities(m["n"], m["seed"])
    n = m["n"]
    assert d.shape == (n, n, n) and d.max() > 0.5
    inner = d[2:-2, 2:-2, 2:-2]
    assert d.sum() == inner.sum()
    values = [float(v) for v in grid_twin.pbrt_values(m).split()]
    assert len(values) == n ** 3 and abs(values[3 + n * (5 + n * 7)] - d[7, 5, 3]) < 1e-5
    renders_without_warning(S.SCENES["medium-grid"], tmp_path)
    vdb = pytest.importorskip("pyopenvdb")
    twin = grid_twin.attach(dict(m), str(tmp_path))
    grid = vdb.read(twin["vdb"], "density")
    lo, hi = m["box"]
    h = (hi - lo) / n
    i, j, k = 14, 17, 12  # x, y, z
    assert abs(grid.getConstAccessor().getValue((i, j, k)) - d[k, j, i]) < 1e-6
    world = grid.transform.indexToWorld((i, j, k))
    assert np.allclose(world, [lo + (i + 0.5) * h, lo + (j + 0.5) * h, lo + (k + 0.5) * h])
