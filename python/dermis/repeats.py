"""Statistics over independent repeats of a render (different seeds, same settings).

A study renders each method K times at each budget; each repeat gives one value of an
error measure (RMSE, relMSE, ...). Its estimate is the mean over the repeats, and its
uncertainty the standard error of that mean, s / sqrt(K) with s the sample standard
deviation (ddof = 1). With one repeat there is no standard error (None).
"""

import math


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
