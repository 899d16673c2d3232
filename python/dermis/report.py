"""The study's report: one self-contained HTML page (report.write_report).

Everything is inlined: images as base64 PNG, plots as base64 SVG, the style sheet and
script of report_page.py. The page loads nothing from anywhere, so it can be mailed,
archived or opened offline. Input is the plain dictionary that study.py builds (see
`write_report`), so the page can be produced from synthetic data in tests.
"""

import base64
import html
import io

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


def main_rows(study, has_mask=True):
    """The main table as text: (header, rows), the methods at the main budget with samples,
    times, errors (mean ± stderr) and efficiency. Also used for Markdown (bench/sss_methods.py)."""
    T, pixels = study["main_budget"], study["resolution"][0] * study["resolution"][1]
    cost_key = "cpu_seconds" if study["cost"] == "cpu" else "seconds"
    head = ["method", "spp: mean (min..max)", "wall (s)", "CPU (s)", "RMSE", "relMSE"]
    if has_mask:
        head += ["object RMSE", "object relMSE"]
    base, rows = None, []
    for m in study["methods"]:
        runs = _runs_at(m, T)
        if not runs:
            continue
        cost = repeats.summarize(runs, cost_key)[0]
        rel, rel_se = repeats.summarize(runs, "relmse")
        work = rel * cost  # relMSE x time: lower is better, time-independent if unbiased
        rse = (rel_se / rel) if (rel_se is not None and rel > 0) else None
        first = base is None
        if first:
            base = (m["name"], work, rse)
        speedup = base[1] / work if work > 0 else float("nan")
        sp_err = None if (first or rse is None or base[2] is None) else speedup * (base[2] ** 2 + rse ** 2) ** 0.5
        cells = [m["name"], _spp_text(runs, pixels), _ms(runs, "seconds", 3), _ms(runs, "cpu_seconds", 3),
                 _ms(runs, "rmse"), _ms(runs, "relmse")]
        if has_mask:
            cells += [_ms(runs, "mask_rmse"), _ms(runs, "mask_relmse")]
        cells.append(repeats.format_mean_stderr(speedup, sp_err, 3) + "×")
        rows.append(cells)
    head.append(f"efficiency vs {base[0] if base else ''}")
    return head, rows


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
    relmse, mask_rmse, mask_relmse}]}], command, settings, version, commit, machine
    {name: value}, date, total_seconds, notes [str]."""
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
    w(_main_table(study))
    noise = ""
    if ref.get("noise_rmse") is not None:
        noise = (f" The reference's own noise (RMSE of the reference, from the difference of its two independent "
                 f"halves): {ref['noise_rmse']:.4g} whole image, {ref['noise_mask_rmse']:.4g} on the object; "
                 "errors near it are limited by the reference, not by the method.")
    w(f'<p class="note">Mean ± one standard error over the {study["repeats"]} independent repeats '
      "(standard deviation of the repeats / √K). RMSE and relMSE are over all pixels and channels against the "
      "reference (relMSE = mean of (A − B)² / (B² + 0.01)); <i>object</i> columns are over the pixels of the "
      f"subsurface objects only (mask below). Efficiency = (relMSE × {cost_word} time) of the first method / "
      "that of this method: higher is better, 2× means the same relMSE in half the time (for a biased method it "
      f"holds at this budget only). spp: samples per pixel reached, mean over the repeats (min..max of pixels).{noise}"
      f"</p><p class=\"note\">Reference details: {esc(ref.get('details', ''))}</p>")
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
