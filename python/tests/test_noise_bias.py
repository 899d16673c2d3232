"""The study's split of the error into noise and bias (repeats.noise_and_bias) on synthetic
repeats with a known truth, and how the report states it. No rendering: see test_study.py
for the same on rendered studies."""

import math
import re

import numpy as np
import pytest

from dermis import plots, repeats, report
from synthetic_study import make_synthetic_study

H, W, K = 36, 48, 3
SIGMA, SIGMA_REF = 0.05, 0.02  # noise of one test render, of the reference (the mean of two halves)


def _scene(rng):
    """(truth, a bias image, the object mask): the bias is 0.03 on a block of the object."""
    truth = rng.uniform(0.2, 1.0, (H, W, 3))
    y, x = np.mgrid[0:H, 0:W]
    mask = (x - W / 2) ** 2 + (y - H / 2) ** 2 < (H / 3) ** 2
    bias = np.zeros((H, W, 3))
    bias[mask] = 0.03
    return truth, bias, mask


def _reference(rng, truth):
    """The reference as study.py renders it: the mean of two independent halves, and its
    per-pixel variance (h1 - h2)^2 / 4."""
    halves = truth + rng.normal(0, SIGMA_REF * math.sqrt(2), (2, H, W, 3))
    return halves.mean(axis=0), (halves[0] - halves[1]) ** 2 / 4


def _repeats(rng, truth, bias, sigma=SIGMA, k=K):
    return truth + bias + rng.normal(0, sigma, (k, H, W, 3))


def test_variance_and_bias2_match_the_known_truth():
    rng = np.random.default_rng(11)
    truth, bias, mask = _scene(rng)
    ref, ref_var = _reference(rng, truth)
    st = repeats.noise_and_bias(_repeats(rng, truth, bias), ref, ref_var, mask)
    true_bias2 = (bias ** 2).mean()
    assert abs(st["variance"] - SIGMA ** 2) < 4 * st["variance_se"], st
    assert abs(st["variance_mask"] - SIGMA ** 2) < 4 * st["variance_se_mask"], st
    assert abs(st["bias2"] - true_bias2) < 4 * st["bias2_se"], st
    assert abs(st["bias2_mask"] - 0.03 ** 2) < 4 * st["bias2_se_mask"], st
    assert repeats.significant(st["bias2"], st["bias2_se"])  # 0.03^2 on the object: about 8 SE
    # Unbiased: bias^2 within 4 SE of zero, though (mean X - R)^2 alone is far from it (noise of both).
    st = repeats.noise_and_bias(_repeats(rng, truth, 0 * bias), ref, ref_var, mask)
    assert not repeats.significant(st["bias2"], st["bias2_se"]), st
    assert not repeats.significant(st["bias2_mask"], st["bias2_se_mask"]), st
    raw = ((_repeats(rng, truth, 0 * bias).mean(axis=0) - ref) ** 2).mean()
    assert raw > 20 * st["bias2_se"]


def test_standard_errors_are_calibrated():
    """Over many independent trials the estimators' errors divided by their standard errors
    have mean ~0 and spread ~1 (the standard errors are neither too small nor too large)."""
    rng = np.random.default_rng(5)
    truth, bias, mask = _scene(rng)
    z = {"variance": [], "bias2": [], "null": []}
    for _ in range(100):
        ref, ref_var = _reference(rng, truth)
        st = repeats.noise_and_bias(_repeats(rng, truth, bias), ref, ref_var)
        z["variance"].append((st["variance"] - SIGMA ** 2) / st["variance_se"])
        z["bias2"].append((st["bias2"] - (bias ** 2).mean()) / st["bias2_se"])
        st = repeats.noise_and_bias(_repeats(rng, truth, 0 * bias), ref, ref_var)
        z["null"].append(st["bias2"] / st["bias2_se"])
    for key, values in z.items():
        v = np.array(values)
        # 100 trials: the mean of z has SE 0.1, its std ~0.07.
        assert abs(v.mean()) < 0.4 and 0.7 < v.std() < 1.3, (key, v.mean(), v.std())


def test_variance_falls_as_one_over_samples():
    """A render of N samples has variance sigma_1^2 / N: variance x N is the same at every
    budget within 4 standard errors."""
    rng = np.random.default_rng(3)
    truth, _, mask = _scene(rng)
    ref, ref_var = _reference(rng, truth)
    per_n = []
    for n in (4, 16, 64):
        st = repeats.noise_and_bias(_repeats(rng, truth, 0, sigma=0.2 / math.sqrt(n)), ref, ref_var, mask)
        per_n.append((st["variance"] * n, st["variance_se"] * n))
    for (a, sa), (b, sb) in zip(per_n, per_n[1:]):
        assert abs(a - b) < 4 * math.hypot(sa, sb), per_n


def test_one_repeat_has_no_variance():
    rng = np.random.default_rng(1)
    truth, bias, mask = _scene(rng)
    st = repeats.noise_and_bias(_repeats(rng, truth, bias, k=1), truth, None, mask)
    assert all(v is None for v in st.values())


def test_unknown_reference_variance_is_left_in_bias2():
    """Without the reference's variance, bias^2 is bias^2 + Var R (an upper bound)."""
    rng = np.random.default_rng(2)
    truth, _, _ = _scene(rng)
    ref, _ = _reference(rng, truth)
    st = repeats.noise_and_bias(_repeats(rng, truth, 0), ref, None)
    assert abs(st["bias2"] - SIGMA_REF ** 2) < 4 * st["bias2_se"]


def test_bias2_text_states_its_significance():
    assert repeats.format_bias2(3.1e-5, 0.4e-5) == "3.1e-05 ± 4e-06: significant (7.8 SE), the method's approximation"
    assert repeats.format_bias2(1e-6, 2e-6).endswith("not significant (< 4 SE)")
    assert "negative" in repeats.format_bias2(-1e-4, 1e-5)
    assert repeats.format_bias2(None, None) == "–"


def test_report_states_noise_and_bias():
    data = make_synthetic_study(noise_stats=True, biased=("disk",))
    text = report.build_html(data)
    assert text.count("image/svg+xml") == 4  # MSE, relMSE, MSE - ref. var, variance + bias^2
    assert "Noise and bias against time" in text and "Warning" not in text
    head, rows = report.main_rows(data, True)
    assert head[-5:] == ["variance", "bias²", "object variance", "object bias²", "efficiency vs disk"]
    disk, walk = rows
    assert "significant (10.0 SE), the method's approximation" in disk[-4]
    assert "not significant" in walk[-4]
    # Efficiency: the biased disk by its MSE (variance + bias^2), the unbiased walk by its variance.
    assert disk[-1].endswith("(MSE)") and walk[-1].endswith("(var.)")
    v_disk = (0.05 ** 2 / 3 + 3e-4) * 0.3 * 1.01
    v_walk = 0.1 ** 2 / 3 * 0.3 * 1.01
    assert float(walk[-1].split()[0]) == pytest.approx(v_disk / v_walk, rel=2e-3)


def test_report_warns_of_a_noisy_reference():
    data = make_synthetic_study(noise_stats=True, reference_noise=0.02)
    warning = report.reference_noise_warning(data)
    # The worst of the whole image (0.02^2 against disk's 0.05^2 / 3 at 0.3 s: 48 %) and the object
    # (0.04^2 against 2 x 0.05^2 / 3: 96 %).
    assert warning and "96 %" in warning and "over the object" in warning and "disk at 0.3 s" in warning
    text = report.build_html(data)
    assert text.index("Warning") < text.index("<table>")  # above the table
    assert report.reference_noise_warning(make_synthetic_study(noise_stats=True)) is None
    # Each method against its own model's reference: a noisy one warns, naming its method.
    quiet = make_synthetic_study(noise_stats=True)
    second = quiet["methods"][1]
    second["reference_noise_rmse"], second["reference_noise_mask_rmse"] = 0.2, None
    own = report.reference_noise_warning(quiet)
    assert own and f"{second['name']} at" in own and "over the whole image" in own
    # A given reference (noise unknown): no warning.
    data["reference"]["noise_rmse"] = None
    assert report.reference_noise_warning(data) is None


def test_noise_bias_plot():
    svg = plots.noise_bias_svg(make_synthetic_study(noise_stats=True)).decode()
    assert "<svg" in svg and "variance ∝ 1/time" in svg
    assert len(re.findall("bias² \\(± 1 SE\\)", svg)) == 2  # whole image, object
