"""Convergence plots of a study (matplotlib, SVG): error against time, log-log.

One figure per error measure (MSE, relMSE), with a panel for the whole image and one for
the object mask. Each method is a line through its budgets: x the mean time its repeats
took (wall or CPU seconds, the study's cost), y the mean error over the repeats with one
standard error as the error bar. The dashed line has slope -1: an unbiased estimator's
MSE falls as 1/time, so a method parallel to it converges; one that flattens is biased
(or limited by the reference's own noise).

A further figure (noise_bias_svg) splits the error: the variance of one render against
time, with the same slope -1 guide, and bias^2 against time in its own panel.
"""

import io
import math

import matplotlib

matplotlib.use("Agg")  # no display; must precede any pyplot import elsewhere
from matplotlib.figure import Figure  # noqa: E402

from . import repeats  # noqa: E402

# (run key, axis label) per measure; MSE is the square of the RMSE of each repeat.
MEASURES = {
    "mse": ("MSE", lambda r, mask: (r["mask_rmse"] if mask else r["rmse"]) ** 2),
    "relmse": ("relMSE", lambda r, mask: r["mask_relmse"] if mask else r["relmse"]),
    # MSE less the rendered reference's own variance (an unbiased estimate of the method's
    # MSE against the exact image): needs a rendered reference; points <= 0 are not drawn.
    "mse_corr": ("MSE − ref. variance", lambda r, mask: r["mask_mse_corr"] if mask else r["mse_corr"]),
}


def _series(study, method, measure, mask):
    """x (mean cost), y (mean error), yerr (stderr) over the budgets of one method."""
    cost = "cpu_seconds" if study["cost"] == "cpu" else "seconds"
    _, value = MEASURES[measure]
    xs, ys, es = [], [], []
    for budget in study["budgets"]:
        runs = [r for r in method["runs"] if r["budget"] == budget]
        if not runs:
            continue
        xs.append(repeats.summarize(runs, cost)[0])
        y, e = repeats.summarize(runs, lambda r: value(r, mask))
        if not y > 0:  # log axes (a noise-corrected MSE can be negative)
            xs.pop()
            continue
        ys.append(y)
        es.append(e or 0.0)
    return xs, ys, es


def _slope_line(ax, points, label="slope −1 (MSE ∝ 1/time)"):
    """A slope -1 guide through the geometric mean of all plotted points."""
    pts = [(x, y) for x, y in points if x > 0 and y > 0]
    if not pts:
        return
    lx = sum(math.log(x) for x, _ in pts) / len(pts)
    ly = sum(math.log(y) for _, y in pts) / len(pts)
    x0 = min(x for x, _ in pts) / 1.5
    x1 = max(x for x, _ in pts) * 1.5
    ax.plot([x0, x1], [math.exp(ly + lx) / x0, math.exp(ly + lx) / x1], "--", color="0.55", lw=1, label=label)


def convergence_svg(study, measure):
    """SVG bytes of the convergence figure of one measure ('mse', 'relmse' or 'mse_corr')."""
    label, _ = MEASURES[measure]
    panels = [(False, "whole image")]
    if study["mask"].any():
        panels.append((True, "object mask"))
    fig = Figure(figsize=(5.2 * len(panels), 3.9), layout="constrained")
    cost = "CPU time (s)" if study["cost"] == "cpu" else "wall time (s)"
    for i, (mask, title) in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), i + 1)
        points = []
        for method in study["methods"]:
            xs, ys, es = _series(study, method, measure, mask)
            ax.errorbar(xs, ys, yerr=es, marker="o", ms=4, capsize=3, lw=1.4, label=method["name"])
            points += list(zip(xs, ys))
        _slope_line(ax, points)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(cost)
        ax.set_ylabel(f"{label} vs reference")
        ax.set_title(f"{label}, {title}", fontsize=11)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=8)
    buf = io.BytesIO()
    fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()


def _stats_series(study, method, key):
    """x (mean cost), y, yerr of by_budget[key] over the budgets of one method."""
    cost = "cpu_seconds" if study["cost"] == "cpu" else "seconds"
    xs, ys, es = [], [], []
    for st in method.get("by_budget", []):
        if st.get(key) is None:
            continue
        xs.append(st[cost])
        ys.append(st[key])
        es.append(st.get(key.replace("variance", "variance_se").replace("bias2", "bias2_se")) or 0.0)
    return xs, ys, es


def noise_bias_svg(study):
    """SVG bytes of the noise / bias figure: the variance of one render against time (log-log,
    slope -1 guide) on top, bias^2 against time (linear, zero line) below; a column for the
    whole image and one for the object mask."""
    cols = [("", "whole image")]
    if study["mask"].any():
        cols.append(("_mask", "object mask"))
    fig = Figure(figsize=(5.2 * len(cols), 7.2), layout="constrained")
    cost = "CPU time (s)" if study["cost"] == "cpu" else "wall time (s)"
    for i, (sfx, title) in enumerate(cols):
        ax = fig.add_subplot(2, len(cols), i + 1)
        points = []
        for method in study["methods"]:
            xs, ys, es = _stats_series(study, method, "variance" + sfx)
            keep = [j for j, y in enumerate(ys) if y > 0]
            xs, ys, es = [xs[j] for j in keep], [ys[j] for j in keep], [es[j] for j in keep]
            ax.errorbar(xs, ys, yerr=es, marker="o", ms=4, capsize=3, lw=1.4, label=method["name"])
            points += list(zip(xs, ys))
        _slope_line(ax, points, "slope −1 (variance ∝ 1/time)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(cost)
        ax.set_ylabel("variance of one render")
        ax.set_title(f"variance, {title}", fontsize=11)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=8)
        ax = fig.add_subplot(2, len(cols), len(cols) + i + 1)
        for method in study["methods"]:
            xs, ys, es = _stats_series(study, method, "bias2" + sfx)
            ax.errorbar(xs, ys, yerr=es, marker="o", ms=4, capsize=3, lw=1.4, label=method["name"])
        ax.axhline(0.0, ls="--", color="0.55", lw=1)
        ax.set_xscale("log")
        ax.set_xlabel(cost)
        ax.set_ylabel("bias² vs reference")
        ax.set_title(f"bias² (± 1 SE), {title}", fontsize=11)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=8)
    buf = io.BytesIO()
    fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()
