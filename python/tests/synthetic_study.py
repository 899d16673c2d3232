"""A synthetic study (made-up images and numbers, no rendering), for the report's tests."""

import numpy as np


def _false_colour(d):
    """A blue -> red ramp of d in [0, 1] (stands in for dermis.error_map)."""
    d = np.clip(d, 0, 1)[..., None]
    return (d * np.array([1.0, 0.2, 0.0]) + (1 - d) * np.array([0.0, 0.1, 0.6])).astype(np.float32)


def _by_budget(i, budgets, biased):
    """Made-up variance and bias^2 per budget (study.budget_stats): the variance falls as 1/time, a
    biased method's bias^2 stays (3e-4 +- 3e-5), an unbiased one's is noise (1e-6 +- 2e-6)."""
    out = []
    for b in budgets:
        var = (0.05 * (i + 1)) ** 2 * budgets[0] / b
        bias2, bias2_se = (3e-4, 3e-5) if biased else (1e-6, 2e-6)
        out.append(dict(budget=b, repeats=2, spp=1000 * b, spp_harmonic=1000 * b, seconds=b * 1.01,
                        cpu_seconds=b * 1.9, variance=var, variance_se=0.05 * var, bias2=bias2, bias2_se=bias2_se,
                        variance_mask=2 * var, variance_se_mask=0.1 * var, bias2_mask=2 * bias2,
                        bias2_se_mask=2 * bias2_se, bias2_less_reference_variance=True))
    return out


def make_synthetic_study(width=48, height=36, methods=("disk", "randomwalk"), budgets=(0.1, 0.3), k=2,
                         noise_stats=False, biased=("disk",), reference_noise=0.001):
    """The dictionary study.py builds, from made-up images and numbers; with `noise_stats`
    each method also has its variance and bias^2 per budget (`biased`: the biased ones)."""
    rng = np.random.default_rng(7)
    y, x = np.mgrid[0:height, 0:width]
    ref = np.stack([x / width, y / height, 0.5 + 0 * x], axis=-1).astype(np.float32) * 0.8
    mask = (x - width / 2) ** 2 + (y - height / 2) ** 2 < (height / 3) ** 2
    out = []
    for i, name in enumerate(methods):
        img = (ref + rng.normal(0, 0.05 * (i + 1), ref.shape)).astype(np.float32)
        d = np.abs(img - ref).mean(axis=-1)
        scale = float(np.quantile(d, 0.99))
        runs = []
        for b in budgets:
            for r in range(k):
                e = 0.05 * (i + 1) / np.sqrt(b / budgets[0]) * (1 + 0.1 * rng.normal())
                runs.append(dict(budget=b, repeat=r, seed=1 + r, seconds=b * 1.01, cpu_seconds=b * 1.9,
                                 samples=int(1000 * b * width * height / (i + 1)), min_spp=int(900 * b),
                                 max_spp=int(1100 * b), rmse=e, relmse=e * e * 3, mask_rmse=e * 1.5,
                                 mask_relmse=e * e * 4, nonfinite=0, mse_corr=e * e - 1e-6,
                                 mask_mse_corr=2.25 * e * e - 4e-6))
        out.append(dict(name=name, image=img, error_map=_false_colour(d / scale), error_scale=scale, runs=runs))
        if noise_stats:
            out[-1]["by_budget"] = _by_budget(i, budgets, name in biased)
    return dict(title="Dermis study: synthetic", scene="synthetic.pbrt", cost="wall", budgets=list(budgets),
                main_budget=budgets[-1], repeats=k, resolution=(width, height), threads=2, mask=mask,
                reference=dict(label="volumetric, 2 x 1 s", image=ref, details="made up", noise_rmse=reference_noise,
                               noise_mask_rmse=2 * reference_noise),
                methods=out, command="dermis study synthetic.pbrt --methods disk,randomwalk --time 0.3",
                settings="synthetic", version="0.1.0", commit="abc1234",
                machine={"CPU": "test", "cores": "2", "OS": "Debian"}, date="2026-01-01 00:00",
                total_seconds=1.0, notes=["a note"])
