"""Statistics over independent repeats of a render (different seeds, same settings).

A study renders each method K times at each budget; each repeat gives one value of an
error measure (RMSE, relMSE, ...). Its estimate is the mean over the repeats, and its
uncertainty the standard error of that mean, s / sqrt(K) with s the sample standard
deviation (ddof = 1). With one repeat there is no standard error (None).

The repeats' images also split a method's error into noise and bias (noise_and_bias):
the variance of one render and the bias^2 of its expectation against the reference, each
with a standard error over the pixels; see docs/study.md.
"""

import math

import numpy as np


def mean_stderr(values):
    """(mean, standard error of the mean) of a list of numbers; stderr is None when K < 2."""
    k = len(values)
    if k == 0:
        return math.nan, None
    mean = sum(values) / k
    if k < 2:
        return mean, None
    var = sum((v - mean) ** 2 for v in values) / (k - 1)
    return mean, math.sqrt(var / k)


def summarize(runs, key):
    """mean_stderr of run[key] (runs: dicts) or of a function of a run (key callable)."""
    get = key if callable(key) else (lambda r: r[key])
    return mean_stderr([get(r) for r in runs])


def format_mean_stderr(mean, stderr, digits=4):
    """'0.01234 ± 0.00056' (or just the mean when there is no standard error)."""
    if mean is None or (isinstance(mean, float) and math.isnan(mean)):
        return "–"
    text = f"{mean:.{digits}g}"
    if stderr is not None:
        text += f" ± {stderr:.2g}"
    return text


# ---------------------------------------------------------------------------- noise and bias

# The per-pixel estimators below take K repeats X_k (K x H x W x 3) of one method at one
# budget, the reference R and its own per-pixel variance v_R (the variance of R as an
# estimate of the exact image; None when unknown). A pixel's term is the mean over its 3
# channels; the value is the mean of the terms over the pixels (of the mask), and its
# standard error the terms' spread over the pixels, std / sqrt(P): pixels are independent
# renders (their channels are not). The spread also holds the pixel-to-pixel variation of
# the true values, so the standard error is conservative (too large, never too small).

SIGNIFICANCE = 4.0  # |bias^2| >= 4 standard errors: significant


def pixel_mean_se(terms):
    """(mean, standard error) of per-pixel terms (P,): mean, std(ddof=1) / sqrt(P)."""
    terms = np.asarray(terms, dtype=np.float64)
    if terms.size == 0:
        return None, None
    se = float(terms.std(ddof=1) / math.sqrt(terms.size)) if terms.size > 1 else None
    return float(terms.mean()), se


def pixel_variance(images):
    """Per-pixel sample variance of the repeats, channels averaged (H, W):
    s^2 = sum_k (X_k - mean X)^2 / (K - 1)."""
    x = np.asarray(images, dtype=np.float64)
    return x.var(axis=0, ddof=1).mean(axis=-1)


def pixel_bias2(images, ref, ref_var=None):
    """Per-pixel unbiased bias^2 of the repeats' mean, channels averaged (H, W):
    b^2 = (mean X - R)^2 - s^2 / K - v_R, since E (mean X - R)^2 = bias^2 + Var X / K + Var R."""
    x = np.asarray(images, dtype=np.float64)
    k = x.shape[0]
    d2 = (x.mean(axis=0) - np.asarray(ref, dtype=np.float64)) ** 2 - x.var(axis=0, ddof=1) / k
    if ref_var is not None:
        d2 = d2 - ref_var
    return d2.mean(axis=-1)


def noise_and_bias(images, ref, ref_var=None, mask=None):
    """variance, variance_se, bias2, bias2_se (and the same with the suffix _mask over
    `mask`) of K >= 2 repeats; every value None when K < 2 (no variance to estimate)."""
    keys = ("variance", "variance_se", "bias2", "bias2_se")
    out = {k + s: None for s in ("", "_mask") for k in keys}
    if len(images) < 2:
        return out
    var = pixel_variance(images)
    b2 = pixel_bias2(images, ref, ref_var)
    regions = [("", np.ones(var.shape, dtype=bool))]
    if mask is not None and np.any(mask):
        regions.append(("_mask", np.asarray(mask, dtype=bool)))
    for suffix, where in regions:
        out["variance" + suffix], out["variance_se" + suffix] = pixel_mean_se(var[where])
        out["bias2" + suffix], out["bias2_se" + suffix] = pixel_mean_se(b2[where])
    return out


def significant(value, stderr, sigmas=SIGNIFICANCE):
    """|value| >= sigmas x stderr (a value with no standard error is not significant)."""
    return value is not None and stderr is not None and stderr >= 0 and abs(value) >= sigmas * stderr


def format_bias2(value, stderr):
    """'3.1e-05 ± 4e-06: significant (7.8 SE), the method's approximation' or '... : not significant'."""
    if value is None:
        return "–"
    text = f"{value:.2g}" + (f" ± {stderr:.1g}" if stderr is not None else "")
    if stderr is None:
        return text
    if significant(value, stderr):
        z = abs(value) / stderr if stderr > 0 else math.inf
        if value < 0:  # cannot be a bias: the noise estimates (the reference's, most likely) are off
            return f"{text}: significantly negative ({z:.1f} SE), the noise estimates are off"
        return f"{text}: significant ({z:.1f} SE), the method's approximation"
    return f"{text}: not significant (< {SIGNIFICANCE:g} SE)"
