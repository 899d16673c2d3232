"""The pbrt-v4 parity harness without pbrt-v4: its scenes render in Dermis, and its statistics
find an offset where there is one and none where there is none (synthetic renders, fixed seed)."""
import glob
import os

import numpy as np
import pytest

from bench.harness import paths, render
from bench.harness.exr import read_exr
from bench.pbrt_v4 import compare

DERMIS = os.environ.get("DERMIS", paths.DERMIS)


@pytest.mark.parametrize("scene", sorted(glob.glob(os.path.join(compare.SCENES, "*.pbrt"))),
                         ids=lambda p: os.path.basename(p))
def test_every_scene_renders_in_dermis(scene, tmp_path):
    render.render(DERMIS, scene, str(tmp_path / "o.exr"), spp=1, res="16x16")
    assert (tmp_path / "o.exr").exists()


def synthetic(rng, k, scale):
    """K renders of a 64x64 picture (a gradient) with independent noise of 5 %."""
    truth = np.linspace(0.2, 0.8, 64)[None, :, None] * np.ones((64, 64, 3))
    return scale * truth[None] * (1 + 0.05 * rng.standard_normal((k, 64, 64, 3)))


def analyse(P, D):
    t = np.ones(len(P))
    return compare.analyse(P, D, P.mean(axis=0), D.mean(axis=0), t, t, 64, 64 * 8, 0.0)


def test_statistics_see_an_offset_and_only_an_offset():
    rng = np.random.default_rng(5)
    same = analyse(synthetic(rng, 8, 1.0), synthetic(rng, 8, 1.0))
    # 16 blocks x 3 channels of differences, each a t-statistic over 8 seeds: none beyond 5.
    assert abs(same["z"]) < 4 and same["blocks"]["over"] == 0
    off = analyse(synthetic(rng, 8, 1.0), synthetic(rng, 8, 1.02))
    assert off["rel"] == pytest.approx(0.02, abs=0.002)
    assert off["z"] > 5 and off["blocks"]["over"] > 8


def test_three_seeds_make_no_block_outside_targets_where_nothing_differs():
    """The blocks' and channels' standard errors pool the pixels' variance: with the --quick
    run's three seeds, 16 blocks x 3 channels of equal pictures stay within 5 sigma in each of
    20 trials (from the three block means' spread alone, 4 % of them went beyond)."""
    rng = np.random.default_rng(11)
    for _ in range(20):
        same = analyse(synthetic(rng, 3, 1.0), synthetic(rng, 3, 1.0))
        assert same["blocks"]["over"] == 0
        assert max(abs(c["z"]) for c in same["channels"]) < 5
    off = analyse(synthetic(rng, 3, 1.0), synthetic(rng, 3, 1.02))
    assert off["blocks"]["over"] > 8


def test_variants_keep_the_scene_and_change_one_thing(tmp_path):
    """--res and samplers.py write copies that render in Dermis at the size or with the
    sampler asked for, with file names (the environment map) made absolute."""
    from bench.pbrt_v4 import samplers
    scene = os.path.join(compare.SCENES, "envmap.pbrt")
    if not os.path.isfile(os.path.join(compare.SCENES, "envmap.exr")):
        from bench.pbrt_v4 import make_envmap
        make_envmap.make(os.path.join(compare.SCENES, "envmap.exr"))
    sized = tmp_path / "sized.pbrt"
    compare.resolution_variant(scene, str(sized), (20, 12))
    render.render(DERMIS, str(sized), str(tmp_path / "a.exr"), spp=1)
    assert read_exr(str(tmp_path / "a.exr")).rgb.shape[:2] == (12, 20)
    halton = tmp_path / "halton.pbrt"
    samplers.sampler_variant(scene, str(halton), "halton")
    assert 'Sampler "halton"' in halton.read_text()
    r = render.render(DERMIS, str(halton), str(tmp_path / "b.exr"), spp=1, res="8x8")
    assert "halton" in r.log  # Dermis says what it renders it with
    # A bracketed file name loses its brackets whole (pbrt-v4 refuses a lone "]").
    assert compare.absolute_filenames('"string filename" [ "a.exr" ]', "/d") == '"string filename" "/d/a.exr"'


def test_gain_and_its_standard_error():
    """The gain's standard error (delta method) covers the truth about as often as it should:
    independent per-seed MSEs with a true ratio of 2, 400 trials, |error| < 2 se in 90-99 %."""
    from bench.pbrt_v4 import samplers
    rng = np.random.default_rng(11)
    hits = 0
    for _ in range(400):
        base = 2.0 * (1 + 0.2 * rng.standard_normal(8))
        other = 1.0 * (1 + 0.2 * rng.standard_normal(8))
        g, se = samplers.gain(base, other)
        hits += abs(g - 2.0) < 2 * se
    assert 0.90 * 400 <= hits <= 0.99 * 400


@pytest.mark.parametrize("integrator,expected", [
    ('Integrator "volpath" "integer maxdepth" 8\n', 1),  # raised
    ('Integrator "volpath"\n', 1),  # given
    ("", 1),  # none: pbrt-v4's default volpath (maxdepth 5) would cut the walk's scattering
])
def test_the_exact_variant_never_cuts_the_scattering(tmp_path, integrator, expected):
    scene = tmp_path / "s.pbrt"
    scene.write_text('Film "rgb"\n' + integrator + 'WorldBegin\nMaterial "subsurface" "string name" "Skin1"\n'
                     'Shape "sphere"\n')
    out = tmp_path / "exact.pbrt"
    assert compare.exact_variant(str(scene), str(out)) == 1
    text = out.read_text()
    assert text.count(f'"integer maxdepth" {compare.EXACT_MAXDEPTH}') == expected
    assert '"string method" "volumetric"' in text
    assert text.index("Integrator") < text.index("WorldBegin")
