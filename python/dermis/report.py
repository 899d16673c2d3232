"""The study's report: one self-contained HTML page (report.write_report).

Everything is inlined: images as base64 PNG, plots as base64 SVG, the style sheet and
script of report_page.py. The page loads nothing from anywhere, so it can be mailed,
archived or opened offline. Input is the plain dictionary that study.py builds (see
`write_report`), so the page can be produced from synthetic data in tests.
"""

import base64
import html
import io
import math

import numpy as np
from PIL import Image

from . import plots, repeats, report_page


# ---------------------------------------------------------------------------- images

def tonemap(img, exposure=0.0):
    """Linear RGB float (H, W, 3) -> sRGB-encoded uint8, clamped (as `dermis render`'s PNGs)."""
    x = np.nan_to_num(np.asarray(img, dtype=np.float64) * 2.0**exposure, nan=0.0, posinf=1.0, neginf=0.0)
    x = np.clip(x, 0.0, 1.0)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (x * 255 + 0.5).astype(np.uint8)


def mask_view(reference, mask):
    """The reference where the mask is set, a dark grey elsewhere (uint8 sRGB)."""
    out = tonemap(reference)
    out[~mask] = (out[~mask] * 0.15 + 40).astype(np.uint8)
    return out


def png_uri(rgb8):
    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgb8), "RGB").save(buf, format="PNG", optimize=True)
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def svg_uri(svg):
    return "data:image/svg+xml;base64," + base64.b64encode(svg).decode("ascii")


# ---------------------------------------------------------------------------- pieces

def esc(x):
    return html.escape(str(x))


def _runs_at(method, budget):
    return [r for r in method["runs"] if r["budget"] == budget]


def _spp_text(runs, pixels):
    spp = sum(r["samples"] for r in runs) / len(runs) / pixels
    lo, hi = min(r["min_spp"] for r in runs), max(r["max_spp"] for r in runs)
    return f"{spp:.0f}" if lo == hi else f"{spp:.0f} ({lo}..{hi})"


def _ms(runs, key, digits=4):
    return repeats.format_mean_stderr(*repeats.summarize(runs, key), digits=digits)


class _Panels:
    """Figures whose images share one zoom/pan view (class .zoom, all of one size)."""

    def __init__(self, width, height):
        scale = min(4.0, 330.0 / max(width, height))  # display size: about 330 px
        self.w, self.h = round(width * scale), round(height * scale)

    def _box(self, inner, extra_class="", attrs=""):
        return (f'<div class="zoom {extra_class}" {attrs} style="width:{self.w}px;height:{self.h}px">'
                f"{inner}</div>")

    def _img(self, uri, cls, alt):
        return f'<img class="{cls}" src="{uri}" width="{self.w}" height="{self.h}" alt="{esc(alt)}">'

    def image(self, uri, caption, alt, tonemapped=True):
        box = self._box(self._img(uri, "tm" if tonemapped else "", alt))
        return f"<figure>{box}<figcaption>{caption}</figcaption></figure>"

    def flip(self, uri, ref_uri, name, caption):
        inner = (self._img(uri, "tm", name) + self._img(ref_uri, "tm ref", "reference") +
                 f'<span class="tag">{esc(name)}</span>')
        box = self._box(inner, "flip", f'data-method="{esc(name)}" title="click or press F: flip to the reference"')
        return f"<figure>{box}<figcaption>{caption}</figcaption></figure>"


def _stats_at(method, budget):
    """The method's variance and bias^2 at `budget` (study.budget_stats), or None."""
    for st in method.get("by_budget", []):
        if st["budget"] == budget and st.get("variance") is not None:
            return st
    return None


def has_noise_stats(study):
    """Whether every method has a variance and bias^2 at every budget (K >= 2)."""
    return bool(study["methods"]) and all(_stats_at(m, b) for m in study["methods"] for b in study["budgets"]
                                          if _runs_at(m, b))


def efficiency_error(st):
    """(error, stderr, basis) of a method at one budget for the efficiency: its variance
    if bias^2 is not significant (an unbiased method's MSE is its variance), else its MSE
    against the exact image, variance + bias^2."""
    if repeats.significant(st["bias2"], st["bias2_se"]) and st["bias2"] > 0:
        se = None if st["variance_se"] is None or st["bias2_se"] is None else math.hypot(st["variance_se"],
                                                                                          st["bias2_se"])
        return st["variance"] + st["bias2"], se, "MSE"
    return st["variance"], st["variance_se"], "var."


def main_rows(study, has_mask=True):
    """The main table as text: (header, rows), the methods at the main budget with samples,
    times, errors (mean ± stderr), variance, bias^2 and efficiency. Also used for Markdown
    (bench/sss_methods.py)."""
    T, pixels = study["main_budget"], study["resolution"][0] * study["resolution"][1]
    cost_key = "cpu_seconds" if study["cost"] == "cpu" else "seconds"
    stats = has_noise_stats(study)
    head = ["method", "spp: mean (min..max)", "wall (s)", "CPU (s)", "RMSE", "relMSE"]
    if has_mask:
        head += ["object RMSE", "object relMSE"]
    if stats:
        head += ["variance", "bias²"] + (["object variance", "object bias²"] if has_mask else [])
    base, rows = None, []
    for m in study["methods"]:
        runs = _runs_at(m, T)
        if not runs:
            continue
        cost = repeats.summarize(runs, cost_key)[0]
        if stats:  # variance (unbiased) or variance + bias^2 (biased) x time
            err, err_se, basis = efficiency_error(_stats_at(m, T))
        else:  # relMSE x time: lower is better, time-independent if unbiased
            (err, err_se), basis = repeats.summarize(runs, "relmse"), "relMSE"
        work = err * cost
        rse = (err_se / err) if (err_se is not None and err > 0) else None
        first = base is None
        if first:
            base = (m["name"], work, rse)
        speedup = base[1] / work if work > 0 else float("nan")
        sp_err = None if (first or rse is None or base[2] is None) else speedup * (base[2] ** 2 + rse ** 2) ** 0.5
        cells = [m["name"], _spp_text(runs, pixels), _ms(runs, "seconds", 3), _ms(runs, "cpu_seconds", 3),
                 _ms(runs, "rmse"), _ms(runs, "relmse")]
        if has_mask:
            cells += [_ms(runs, "mask_rmse"), _ms(runs, "mask_relmse")]
        if stats:
            st = _stats_at(m, T)
            for sfx in ("", "_mask") if has_mask else ("",):
                cells += [repeats.format_mean_stderr(st["variance" + sfx], st["variance_se" + sfx], 3),
                          repeats.format_bias2(st["bias2" + sfx], st["bias2_se" + sfx])]
        cells.append(repeats.format_mean_stderr(speedup, sp_err, 3) + "×" + (f" ({basis})" if stats else ""))
        rows.append(cells)
    head.append(f"efficiency vs {base[0] if base else ''}")
    return head, rows


def models_statement(study):
    """What each method solves against the reference's model (study["models"], set by the
    study; empty for an older study): sentences for the report, and whether any differs."""
    models = study.get("models")
    if not models:
        return "", False
    parts, differs = [], False
    if models.get("per_model"):
        parts.append("The methods solve different models: each is measured against the reference of its own model "
                     "(the images show the first).")
    elif models["reference"]:
        parts.append(f"Reference: {models['reference_words']}.")
    for m in models["methods"]:
        text = f"{m['name']}: {m['words']}" + ("" if m["exact"] else ", approximated by a diffusion profile")
        if models.get("per_model") and m.get("reference"):
            text += f", against its model's reference ({m['reference']})"
        if not m["same_as_reference"]:
            differs = True
            text += (" — another model than the reference's: its bias² includes the difference between the models, "
                     "not only the method's error")
        parts.append(text + ".")
    return " ".join(parts), differs


def reference_noise_warning(study, limit=0.1):
    """A warning (text) when a rendered reference's own variance is above `limit` x the
    smallest variance measured against it (whole image or object), else None. Each method
    is measured against its own reference (its model's; `reference_noise_rmse` in its
    entry), else the study's."""
    ref = study["reference"]
    worst = None
    for sfx in ("", "_mask"):
        for m in study["methods"]:
            own = "reference_noise_rmse" in m  # the method's own reference (else the study's)
            if (m["reference_noise_rmse"] if own else ref.get("noise_rmse")) is None:
                continue  # a given reference: its noise is unknown
            noise = m.get("reference_noise" + sfx + "_rmse") if own else ref.get("noise" + sfx + "_rmse")
            if noise is None or not noise == noise:
                continue
            for st in m.get("by_budget", []):
                var = st.get("variance" + sfx)
                if var is None or var <= 0:
                    continue
                ratio = noise ** 2 / var  # reference variance / the method's variance
                if ratio > limit and (worst is None or ratio > worst[0]):
                    worst = (ratio, noise ** 2, (var, m["name"], st["budget"]), "the object" if sfx else
                             "the whole image")
    if worst is None:
        return None
    ratio, ref_var, (var, name, budget), where = worst
    return (f"The reference is too noisy: its own variance ({ref_var:.3g}, over {where}) is {100 * ratio:.0f} % of "
            f"the smallest variance in the study ({var:.3g}, {name} at {budget:g} s), above the {100 * limit:.0f} % "
            f"this study trusts. bias² subtracts it, but its standard error grows with it and the MSE columns are "
            f"dominated by it: render the reference about {ratio / limit:.0f}× longer (--reference-time).")


def _efficiency_note(study, cost_word):
    if not has_noise_stats(study):
        return (f"Efficiency = (relMSE × {cost_word} time) of the first method / that of this method: higher is "
                "better, 2× means the same relMSE in half the time (for a biased method it holds at this budget "
                "only; with one repeat there is no variance to use instead).")
    return (f"Efficiency = (error × {cost_word} time) of the first method / that of this method, where the error is "
            "the <b>variance</b> of one render (whole image) for a method whose bias² is not significant (var.: "
            "for an unbiased method the MSE is the variance, and variance × time does not depend on the budget), "
            "and its MSE against the exact image, variance + bias², for a method with a significant bias² (MSE: it "
            "holds at this budget only, since the bias does not fall with time). Higher is better: 2× means the "
            "same error in half the time.")


def _noise_bias_note(study):
    subtracted = all(st.get("bias2_less_reference_variance") for m in study["methods"]
                     for st in m.get("by_budget", []))
    return ("Variance = mean over the pixels of the per-pixel variance of the repeats, s² = Σ (X_k − X̄)² / (K − 1) "
            "(the variance of one render). bias² = mean over the pixels of (X̄ − R)² − s² / K" +
            (" − Var R" if subtracted else "") + ", an unbiased estimate of the squared bias of the method's "
            "expectation against the reference's, since E (X̄ − R)² = bias² + Var X / K + Var R" +
            (" (Var R: the reference's own per-pixel variance, from its two halves)." if subtracted else
             "; the reference's own variance Var R is unknown (a given reference), so bias² here includes it.") +
            " Each ± is one standard error from the spread of the per-pixel terms over the pixels (std / √pixels; "
            "conservative: it includes how the true values vary from pixel to pixel). A bias² of at least "
            f"{repeats.SIGNIFICANCE:g} standard errors is significant: the method's approximation (its expectation "
            "differs from the reference method's); below that it is not significant.")


def _main_table(study):
    head, rows = main_rows(study, bool(study["mask"].any()))
    return ("<table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in head) + "</tr>" +
            "".join("<tr>" + f"<td><b>{esc(r[0])}</b></td>" + "".join(f"<td>{esc(c)}</td>" for c in r[1:]) + "</tr>"
                    for r in rows) + "</table>")


def _budget_table(study):
    """Every method at every budget (the numbers behind the convergence plots)."""
    pixels = study["resolution"][0] * study["resolution"][1]
    has_mask = bool(study["mask"].any())
    head = ["method", "budget (s)", "repeats", "spp", "wall (s)", "CPU (s)", "MSE", "relMSE"]
    if has_mask:
        head += ["object MSE", "object relMSE"]
    corrected = all("mse_corr" in r for m in study["methods"] for r in m["runs"])
    if corrected:
        head += ["MSE − ref. var."] + (["object MSE − ref. var."] if has_mask else [])
    stats = has_noise_stats(study)
    if stats:
        head += ["variance", "bias²"] + (["object variance", "object bias²"] if has_mask else [])
    rows = []
    for m in study["methods"]:
        for b in study["budgets"]:
            runs = _runs_at(m, b)
            if not runs:
                continue
            cells = [esc(m["name"]), f"{b:g}", str(len(runs)), _spp_text(runs, pixels), _ms(runs, "seconds", 3),
                     _ms(runs, "cpu_seconds", 3), _ms(runs, lambda r: r["rmse"] ** 2), _ms(runs, "relmse")]
            if has_mask:
                cells += [_ms(runs, lambda r: r["mask_rmse"] ** 2), _ms(runs, "mask_relmse")]
            if corrected:
                cells += [_ms(runs, "mse_corr")] + ([_ms(runs, "mask_mse_corr")] if has_mask else [])
            if stats:
                st = _stats_at(m, b)
                for sfx in ("", "_mask") if has_mask else ("",):
                    cells += [repeats.format_mean_stderr(st["variance" + sfx], st["variance_se" + sfx]),
                              esc(repeats.format_bias2(st["bias2" + sfx], st["bias2_se" + sfx]))]
            rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    return ("<table><tr>" + "".join(f"<th>{h}</th>" for h in head) + "</tr>" + "".join(rows) + "</table>")


def _runs_table(study):
    """One row per render: what reproduces any single number."""
    head = ["method", "budget (s)", "repeat", "seed", "samples", "spp min..max", "wall (s)", "CPU (s)",
            "RMSE", "relMSE", "object RMSE", "object relMSE"]
    rows = []
    for m in study["methods"]:
        for r in m["runs"]:
            cells = [esc(m["name"]), f"{r['budget']:g}", r["repeat"], r["seed"], r["samples"],
                     f"{r['min_spp']}..{r['max_spp']}", f"{r['seconds']:.3f}", f"{r['cpu_seconds']:.3f}",
                     f"{r['rmse']:.5g}", f"{r['relmse']:.5g}", f"{r['mask_rmse']:.5g}", f"{r['mask_relmse']:.5g}"]
            rows.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    return ("<table><tr>" + "".join(f"<th>{h}</th>" for h in head) + "</tr>" + "".join(rows) + "</table>")


# ---------------------------------------------------------------------------- page

def build_html(study):
    """The page as a string. `study` (built by study.py):
    title, scene, cost ('wall' | 'cpu'), budgets (seconds), main_budget, repeats,
    resolution (W, H), threads, mask (bool H x W), reference {label, image, details,
    noise_rmse (or None), noise_mask_rmse}, methods [{name, image, error_map, error_scale,
    runs [{budget, repeat, seed, seconds, cpu_seconds, samples, min_spp, max_spp, rmse,
    relmse, mask_rmse, mask_relmse}], by_budget (optional) [{budget, seconds, cpu_seconds,
    variance, variance_se, bias2, bias2_se, the same with _mask, bias2_less_reference_variance}]}],
    command, settings, version, commit, machine {name: value}, date, total_seconds, notes [str]."""
    W, H = study["resolution"]
    T = study["main_budget"]
    pixels = W * H
    cost_word = "CPU" if study["cost"] == "cpu" else "wall"
    mask = study["mask"]
    ref = study["reference"]
    ref_uri = png_uri(tonemap(ref["image"]))
    panels = _Panels(W, H)
    out = []
    w = out.append

    w("<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">")
    w(f"<title>{esc(study['title'])}</title><style>{report_page.CSS}</style></head><body>")
    w(f"<h1>{esc(study['title'])}</h1>")
    names = ", ".join(m["name"] for m in study["methods"])
    w(f'<p class="summary">Scene <code>{esc(study["scene"])}</code>, {W}×{H} pixels. Methods: {esc(names)}, '
      f"each at equal {cost_word} time: {', '.join(f'{b:g}' for b in study['budgets'])} s, "
      f"{study['repeats']} independent repeats (seeds) at each. Reference: {esc(ref['label'])}.</p>")
    w('<div class="toolbar"><label>exposure <input id="exposure" type="range" min="-6" max="6" step="0.25" '
      'value="0"> <span id="exposure-value">0.0 EV</span></label>'
      '<button id="flip-all">flip methods ↔ reference (F)</button><button id="reset-zoom">reset zoom (0)</button>'
      '<span class="note">wheel: zoom · drag: pan (all images together) · click an image: flip it · '
      "double click: reset</span></div>")

    # Images at the main budget (first repeat) beside the reference and the mask.
    w(f"<h2>Images at {T:g} s ({cost_word} time), first repeat</h2><div class=\"grid\">")
    w(panels.image(ref_uri, f"<b>reference</b><br>{esc(ref['label'])}", "reference"))
    for m in study["methods"]:
        runs = _runs_at(m, T)
        cap = (f"<b>{esc(m['name'])}</b><br>spp {_spp_text(runs[:1], pixels)}, {runs[0]['seconds']:.2f} s wall, "
               f"{runs[0]['cpu_seconds']:.2f} s CPU<br>relMSE {runs[0]['relmse']:.4g}") if runs else esc(m["name"])
        w(panels.flip(png_uri(tonemap(m["image"])), ref_uri, m["name"], cap))
    w("</div>")

    # Error maps.
    w("<h2>Error maps</h2><p class=\"note\">Luminance of |method − reference| in false colour (dermis.error_map), "
      "each scaled to its own 99th percentile: the top of the colour ramp is the value given under it. "
      "They share the zoom of the images above.</p><div class=\"grid\">")
    for m in study["methods"]:
        w(panels.image(png_uri(tonemap(m["error_map"])), f"<b>|{esc(m['name'])} − reference|</b><br>"
                       f"top of the ramp = {m['error_scale']:.4g}", f"error map {m['name']}", tonemapped=False))
    w("</div>")

    # Tables.
    w(f"<h2>Errors at {T:g} s</h2>")
    warning = reference_noise_warning(study)
    if warning:
        w(f'<p class="warning"><b>Warning:</b> {esc(warning)}</p>')
    models, differs = models_statement(study)
    if models:
        w(f'<p class="{"warning" if differs else "summary"}"><b>Models.</b> {esc(models)}</p>')
    w(_main_table(study))
    noise = ""
    if ref.get("noise_rmse") is not None:
        noise = (f" The reference's own noise (RMSE of the reference, from the difference of its two independent "
                 f"halves): {ref['noise_rmse']:.4g} whole image, {ref['noise_mask_rmse']:.4g} on the object; "
                 "errors near it are limited by the reference, not by the method.")
    w(f'<p class="note">Mean ± one standard error over the {study["repeats"]} independent repeats '
      "(standard deviation of the repeats / √K). RMSE and relMSE are over all pixels and channels against the "
      "reference (relMSE = mean of (A − B)² / (B² + 0.01)); <i>object</i> columns are over the pixels of the "
      f"subsurface objects only (mask below). {_efficiency_note(study, cost_word)} "
      f"spp: samples per pixel reached, mean over the repeats (min..max of pixels).{noise}</p>")
    if has_noise_stats(study):
        w(f'<p class="note">{esc(_noise_bias_note(study))}</p>')
    w(f"<p class=\"note\">Reference details: {esc(ref.get('details', ''))}</p>")
    for note in study.get("notes", []):
        w(f'<p class="note"><b>Note:</b> {esc(note)}</p>')

    # Convergence.
    w("<h2>Convergence: error against time</h2>")
    corrected = all("mse_corr" in r for m in study["methods"] for r in m["runs"])
    for measure in ("mse", "relmse") + (("mse_corr",) if corrected else ()):
        w(f'<p><img class="plot" src="{svg_uri(plots.convergence_svg(study, measure))}" '
          f'alt="convergence plot {measure}"></p>')
    w('<p class="note">Log-log; every point is the mean over the repeats at one budget (x: the mean '
      f"{cost_word} time the renders took), error bars one standard error. Dashed: slope −1, the rate of an "
      "unbiased estimator (MSE ∝ 1/time); a curve that flattens is biased or has reached the reference's "
      "noise." + (" <i>MSE − ref. variance</i>: each render's MSE less the rendered reference's own variance "
                  "(estimated from its two halves), since E(A − R)² = Var A + bias² + Var R: the method's own "
                  "error against the exact image, free of the reference's noise (non-positive means are not "
                  "drawn)." if corrected else "") + "</p>")
    if has_noise_stats(study):
        w("<h2>Noise and bias against time</h2>")
        w(f'<p><img class="plot" src="{svg_uri(plots.noise_bias_svg(study))}" alt="variance and bias² plot"></p>')
        w('<p class="note">Top: the variance of one render (mean over the pixels of the per-pixel variance over '
          "the repeats) against the mean time, log-log, error bars one standard error; dashed: slope −1 "
          "(variance ∝ 1/time), which an unbiased or biased Monte Carlo method alike should follow. Bottom: bias² "
          "of the method's expectation against the reference (linear scale, zero dashed): a method whose bias² "
          f"stays within {repeats.SIGNIFICANCE:g} standard errors of zero is unbiased as far as the study can tell; "
          "a bias² that does not fall with time is the method's approximation.</p>")
    w(f"<details><summary>All budgets</summary>{_budget_table(study)}</details>")

    # Object mask.
    n_mask = int(mask.sum())
    w(f"<h2>Object mask</h2><p class=\"note\">Pixels whose centre's camera ray first hits a subsurface object "
      f"(dermis.subsurface_mask): {n_mask} of {pixels} pixels ({100 * n_mask / pixels:.1f} %). "
      "The <i>object</i> errors above are restricted to them.</p><div class=\"grid\">")
    w(panels.image(png_uri(mask_view(ref["image"], mask)), "<b>mask</b> (reference inside, grey outside)",
                   "object mask"))
    w("</div>")

    # Reproduction.
    w("<h2>How this was made</h2>")
    w(f"<pre>{esc(study['command'])}</pre>")
    w(f"<p class=\"note\">{esc(study.get('settings', ''))}</p>")
    items = [("Dermis", f"{study.get('version', '?')} (commit {study.get('commit', '?')})"),
             ("date", study.get("date", "?")), ("whole study", f"{study.get('total_seconds', 0):.0f} s wall")]
    items += list(study.get("machine", {}).items())
    w("<table>" + "".join(f"<tr><th>{esc(k)}</th><td>{esc(v)}</td></tr>" for k, v in items) + "</table>")
    w(f"<details><summary>Every render</summary>{_runs_table(study)}</details>")
    w('<p id="status">images not decoded yet (JavaScript off?)</p>')
    w(f"<script>{report_page.JS}</script></body></html>")
    return "\n".join(out)


def write_report(path, study):
    """Writes the page to `path` (its folder must exist)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(build_html(study))
