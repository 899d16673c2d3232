"""The study end to end on a tiny scene: renders, errors, report and files; and the
`dermis study` subcommand that runs it."""

import json
import math
import subprocess

import pytest

import dermis
from dermis import study

# A subsurface sphere on a floor, a sky and an area light, in 48 x 36 pixels.
TINY_SCENE = """LookAt 0 -4 1.2  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 48 "integer yresolution" 36
Sampler "zsobol" "integer pixelsamples" 4
Integrator "volpath" "integer maxdepth" 64
WorldBegin
LightSource "infinite" "rgb L" [0.3 0.35 0.4]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [10 9 8]
  Translate 2 -2 3
  Shape "sphere" "float radius" 0.5
AttributeEnd
AttributeBegin
  Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.4 0.2 0.1] "float eta" 1.33
  Shape "sphere" "float radius" 1
AttributeEnd
AttributeBegin
  Material "diffuse" "rgb reflectance" [0.4 0.4 0.4]
  Shape "trianglemesh" "point3 P" [-9 -9 -1  9 -9 -1  9 9 -1  -9 9 -1] "integer indices" [0 1 2 0 2 3]
AttributeEnd
"""


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "tiny.pbrt"
    path.write_text(TINY_SCENE)
    return path


@pytest.fixture(scope="module")
def wall_study(tiny, tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    rc = study.main([str(tiny), "--methods", "disk,randomwalk:walksampling=mis", "--time", "0.3", "--budgets", "0.15",
                     "--repeats", "2", "--reference-time", "1", "--threads", "2", "--out", str(out)])
    assert rc == 0
    return out


def test_study_writes_report_and_numbers(wall_study):
    for name in ("index.html", "study.json", "reference.exr", "disk.exr", "randomwalk_walksampling_mis.exr"):
        assert (wall_study / name).is_file(), name
    data = json.loads((wall_study / "study.json").read_text())
    assert data["budgets"] == [0.15, 0.3] and data["repeats"] == 2 and data["cost"] == "wall"
    assert [m["name"] for m in data["methods"]] == ["disk", "randomwalk:walksampling=mis"]
    assert data["methods"][1]["params"] == {"walksampling": "mis"}
    assert 0 < data["mask_pixels"] < 48 * 36
    for m in data["methods"]:
        runs = m["runs"]
        assert len(runs) == 4
        assert len({r["seed"] for r in runs}) == 4  # independent repeats
        for r in runs:
            assert 0 < r["rmse"] < 1 and 0 < r["relmse"] < 1 and math.isfinite(r["mask_rmse"])
            # Equal wall time: the renderer stops at the first pass boundary past the limit, not
            # before (how far past depends on the machine's speed: no bound here).
            assert r["seconds"] >= 0.8 * r["budget"], r
    ref = data["reference"]
    # disk and the walk both solve the diffuse boundary's model: the reference is its walk.
    assert ref["noise_rmse"] > 0 and "randomwalk:boundary=diffuse" in ref["label"]
    assert data["models"]["reference"] == "diffuse"
    assert [m["same_as_reference"] for m in data["models"]["methods"]] == [True, True]
    text = (wall_study / "index.html").read_text()
    assert text.count("<img ") == 1 + 2 * 2 + 2 + 4 + 1  # 4 plots: MSE, relMSE, MSE - ref. var., noise/bias
    run = data["methods"][0]["runs"][0]
    assert math.isclose(run["mse_corr"], run["rmse"] ** 2 - ref["noise_rmse"] ** 2)
    assert "randomwalk:walksampling=mis" in text and "--reference-time 1" in text


def test_study_masked_errors_match_compare(wall_study):
    """The object errors are dermis.compare over the mask's pixels: check one by hand."""
    data = json.loads((wall_study / "study.json").read_text())
    ref = dermis.read_image(str(wall_study / "reference.exr"))
    img = dermis.read_image(str(wall_study / "disk.exr"))
    scene = dermis.load_scene(data["scene"])
    mask = dermis.subsurface_mask(scene)
    # The sphere only: the centre is on it, the bottom corners see the (diffuse) floor.
    assert mask[18, 24] and not mask[-1, 0] and not mask[-1, -1]
    run = next(r for r in data["methods"][0]["runs"] if r["budget"] == 0.3 and r["repeat"] == 0)
    d = (img[mask].astype(float) - ref[mask]) ** 2
    assert math.isclose(run["mask_rmse"], math.sqrt(d.mean()), rel_tol=1e-4)
    assert math.isclose(run["mask_relmse"], (d / (ref[mask].astype(float) ** 2 + 0.01)).mean(), rel_tol=1e-4)


def test_study_equal_cpu_time_with_given_reference(wall_study, tiny, tmp_path):
    rc = study.main([str(tiny), "--methods", "disk", "--time", "0.4", "--budgets", "0.4", "--repeats", "2",
                     "--cpu-time", "--threads", "1", "--reference", str(wall_study / "reference.exr"),
                     "--out", str(tmp_path)])
    assert rc == 0
    data = json.loads((tmp_path / "study.json").read_text())
    assert data["cost"] == "cpu" and data["reference"]["noise_rmse"] is None
    assert "mse_corr" not in data["methods"][0]["runs"][0]  # a given reference: its noise is unknown
    assert (tmp_path / "index.html").read_text().count("image/svg+xml") == 3  # MSE, relMSE, noise/bias
    st = data["methods"][0]["by_budget"][0]
    assert st["bias2_less_reference_variance"] is False and st["variance"] > 0  # bias2 holds Var R
    for r in data["methods"][0]["runs"]:
        # The sample count comes from the measured cost per sample: CPU time near the budget.
        assert 0.4 / 3 < r["cpu_seconds"] < 0.4 * 3, r
        assert r["min_spp"] == r["max_spp"]


def test_study_bad_input_is_status_2(tiny, tmp_path, capsys):
    assert study.main([str(tiny), "--methods", "no-such-method", "--time", "0.1", "--reference-time", "0.1",
                       "--out", str(tmp_path)]) == 2
    assert "error" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        study.main([str(tiny), "--methods", "disk"])  # no --time
    assert e.value.code == 2


def test_dermis_study_subcommand(dermis_binary, tiny):
    p = subprocess.run([dermis_binary, "study", "--help"], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert "--methods" in p.stdout
    assert p.stdout.splitlines()[0].startswith("usage: dermis study "), p.stdout.splitlines()[0]
    p = subprocess.run([dermis_binary, "study", str(tiny)], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "--methods" in p.stderr


def test_out_and_o_name_the_same_folder(tiny):
    # `-o` as in `dermis render` (issue 39).
    assert study.parse_args([str(tiny), "--methods", "disk", "--time", "1", "-o", "a"]).out == "a"
    assert study.parse_args([str(tiny), "--methods", "disk", "--time", "1", "--out", "b"]).out == "b"


def test_method_specs_with_labels():
    m = study.Method("mis + backward=randomwalk:walksampling=mis:backwardguiding=true:mfp=1/2/3")
    assert (m.label, m.method) == ("mis + backward", "randomwalk")
    assert m.params == {"walksampling": "mis", "backwardguiding": True, "mfp": (1.0, 2.0, 3.0)}
    m = study.Method("randomwalk:boundary=diffuse")
    assert (m.label, m.method, m.params) == ("randomwalk:boundary=diffuse", "randomwalk", {"boundary": "diffuse"})
    for bad in ("=disk", "label=", "label=:walksampling=mis", "disk:walksampling"):
        with pytest.raises(ValueError):
            study.Method(bad)


def test_each_method_renders_the_scene_written_with_its_overrides(tiny):
    """A method's parameters override the scene's for that method only: its scene renders
    bit for bit as the scene written with them, and the next method does not inherit them."""
    args = study.parse_args([str(tiny), "--methods", "diffuse walk=randomwalk:boundary=diffuse:g=0.5,plain=randomwalk",
                             "--time", "1"])
    assert [m.label for m in args.methods] == ["diffuse walk", "plain"]
    s = study.Study(args)
    written = {
        "diffuse walk": '"string method" "randomwalk" "string boundary" "diffuse" "float g" 0.5',
        "plain": '"string method" "randomwalk"',
    }
    images = {}
    for m in args.methods:
        mine = dermis.render(s.scene(m), spp=2, seed=3, threads=1)
        text = TINY_SCENE.replace('"float eta" 1.33', '"float eta" 1.33 ' + written[m.label])
        expected = dermis.render(dermis.load_scene(text), spp=2, seed=3, threads=1)
        assert (mine == expected).all(), m.label
        images[m.label] = mine
    assert not (images["diffuse walk"] == images["plain"]).all()  # the override changed the image


def test_study_report_shows_labels(wall_study, tiny, tmp_path):
    rc = study.main([str(tiny), "--methods", "probe rays=disk,walk=randomwalk:walksampling=mis", "--time", "0.2",
                     "--budgets", "0.2", "--repeats", "2", "--threads", "1",
                     "--reference", str(wall_study / "reference.exr"), "--out", str(tmp_path)])
    assert rc == 0
    data = json.loads((tmp_path / "study.json").read_text())
    assert [(m["name"], m["method"], m["params"]) for m in data["methods"]] == [
        ("probe rays", "disk", {}), ("walk", "randomwalk", {"walksampling": "mis"})]
    assert (tmp_path / "probe_rays.exr").is_file() and (tmp_path / "walk.exr").is_file()
    assert "<b>probe rays</b>" in (tmp_path / "index.html").read_text()


# The tiny scene with independent samples: a render of N samples per pixel has exactly the
# variance of one sample / N (no stratification to make it fall faster).
INDEPENDENT_SCENE = TINY_SCENE.replace('"zsobol"', '"independent"')
STAT_KEYS = ("variance", "variance_se", "bias2", "bias2_se")


@pytest.fixture(scope="module")
def bias_study(tmp_path_factory):
    """The reference's own method (unbiased against it) and the same with a quarter of the
    albedo (reflectance) of the scene (biased), at equal CPU time (the sample count follows
    the budget), with a deliberately short reference (2 x 1 s of wall time: on a loaded
    machine it may get a sixth of that in CPU time, which the bias must stand out of)."""
    path = tmp_path_factory.mktemp("scene") / "tiny-independent.pbrt"
    path.write_text(INDEPENDENT_SCENE)
    out = tmp_path_factory.mktemp("bias-study")
    methods = "same=volumetric,dark=volumetric:reflectance=0.2/0.125/0.075"
    rc = study.main([str(path), "--methods", methods, "--time", "0.4", "--budgets", "0.1", "--repeats", "3",
                     "--cpu-time", "--threads", "1", "--reference-time", "2", "--out", str(out)])
    assert rc == 0
    return out, json.loads((out / "study.json").read_text())


def test_study_writes_variance_and_bias2(bias_study):
    _, data = bias_study
    for m in data["methods"]:
        assert [st["budget"] for st in m["by_budget"]] == [0.1, 0.4]
        for st in m["by_budget"]:
            assert st["repeats"] == 3 and st["bias2_less_reference_variance"] is True
            for key in STAT_KEYS:
                for sfx in ("", "_mask"):
                    assert math.isfinite(st[key + sfx]), (key + sfx, st)
            assert st["variance"] > 0 and st["variance_se"] > 0 and st["bias2_se"] > 0


def test_variance_falls_as_one_over_the_samples(bias_study):
    """variance x spp is the same at both budgets within 4 standard errors (spp: the harmonic
    mean over the repeats, since the repeats' sample variance estimates sigma_1^2 x mean(1 / spp));
    the sample counts follow the budgets (equal CPU time), so the variance falls as 1 / time."""
    _, data = bias_study
    for m in data["methods"]:
        lo, hi = m["by_budget"]
        assert hi["spp"] > 2 * lo["spp"], (lo["spp"], hi["spp"])
        for sfx in ("", "_mask"):
            a = lo["variance" + sfx] * lo["spp_harmonic"], lo["variance_se" + sfx] * lo["spp_harmonic"]
            b = hi["variance" + sfx] * hi["spp_harmonic"], hi["variance_se" + sfx] * hi["spp_harmonic"]
            assert abs(a[0] - b[0]) < 4 * math.hypot(a[1], b[1]), (m["name"], sfx, a, b)


def test_bias2_is_significant_for_a_biased_method_only(bias_study):
    _, data = bias_study
    same, wrong = data["methods"]
    for st in same["by_budget"]:
        for sfx in ("", "_mask"):
            assert abs(st["bias2" + sfx]) < 4 * st["bias2_se" + sfx], (sfx, st)
    for st in wrong["by_budget"]:
        assert st["bias2_mask"] > 4 * st["bias2_se_mask"], st
        assert st["bias2"] > 4 * st["bias2_se"], st


def test_report_states_bias_and_warns_of_a_short_reference(bias_study):
    out, data = bias_study
    text = (out / "index.html").read_text()
    assert "significant" in text and "the method&#x27;s approximation" in text and "not significant" in text
    # 2 x 1 s of wall time for the reference against 0.4 CPU s for the methods: far above 10 %.
    assert data["reference_noise_warning"] and "too noisy" in data["reference_noise_warning"]
    assert text.index("too noisy") < text.index("<table>")


def test_the_default_reference_solves_the_methods_model():
    plain = {"reflectance": (0.8, 0.5, 0.3)}
    walk, disk, vol = study.Method("randomwalk"), study.Method("disk"), study.Method("volumetric")
    dielectric_walk = study.Method("randomwalk:boundary=dielectric")
    assert study.model_of(walk, plain) == ("diffuse", True)
    assert study.model_of(walk, {"boundary": "dielectric"}) == ("dielectric", True)  # the material's
    assert study.model_of(disk, plain) == ("diffuse", False)
    assert study.model_of(dielectric_walk, plain) == study.model_of(vol, plain) == ("dielectric", True)
    assert study.UNBIASED_METHOD["diffuse"] == "randomwalk:boundary=diffuse"
    assert study.UNBIASED_METHOD["dielectric"] == "volumetric"
    # One reference for both (the user's choice): the walk's bias^2 holds the model difference.
    models = study.models_of([walk, vol], study.Method("volumetric"), plain)
    assert [m["same_as_reference"] for m in models["methods"]] == [False, True]
    from dermis import report
    text, differs = report.models_statement({"models": models})
    assert differs and "randomwalk: the walk's diffuse boundary" in text and "another model" in text
    text, differs = report.models_statement({"models": study.models_of([walk, disk], study.Method(
        "randomwalk:boundary=diffuse"), plain)})
    assert not differs and "approximated by a diffusion profile" in text


def test_methods_of_different_models_each_get_their_models_reference(tiny, tmp_path):
    rc = study.main([str(tiny), "--methods", "randomwalk,volumetric", "--time", "0.2", "--budgets", "0.2",
                     "--repeats", "2", "--reference-time", "0.4", "--threads", "2", "--out", str(tmp_path)])
    assert rc == 0
    data = json.loads((tmp_path / "study.json").read_text())
    models = data["models"]
    assert models["per_model"] and [m["model"] for m in models["methods"]] == ["diffuse", "dielectric"]
    assert [m["reference"] for m in models["methods"]] == ["randomwalk:boundary=diffuse", "volumetric"]
    assert "randomwalk:boundary=diffuse" in data["reference"]["label"]
    assert [r["model"] for r in data["other_references"]] == ["dielectric"]
    assert "volumetric" in data["other_references"][0]["label"]
    assert "each is measured against the reference of its own model" in (tmp_path / "index.html").read_text()
