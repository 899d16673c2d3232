"""A synthetic study (made-up images and numbers, no rendering), for the report's tests."""

import numpy as np


def _false_colour(d):
    """A blue -> red ramp of d in [0, 1] (stands in for dermis.error_map)."""
    d = np.clip(d, 0, 1)[..., None]
    return (d * np.array([1.0, 0.2, 0.0]) + (1 - d) * np.array([0.0, 0.1, 0.6])).astype(np.float32)


def make_synthetic_study(width=48, height=36, methods=("disk", "randomwalk"), budgets=(0.1, 0.3), k=2):
    """The dictionary study.py builds, from made-up images and numbers."""
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
    return dict(title="Dermis study: synthetic", scene="synthetic.pbrt", cost="wall", budgets=list(budgets),
                main_budget=budgets[-1], repeats=k, resolution=(width, height), threads=2, mask=mask,
                reference=dict(label="volumetric, 2 x 1 s", image=ref, details="made up", noise_rmse=0.001,
                               noise_mask_rmse=0.002),
                methods=out, command="dermis study synthetic.pbrt --methods disk,randomwalk --time 0.3",
                settings="synthetic", version="0.1.0", commit="abc1234",
                machine={"CPU": "test", "cores": "2", "OS": "Debian"}, date="2026-01-01 00:00",
                total_seconds=1.0, notes=["a note"])
