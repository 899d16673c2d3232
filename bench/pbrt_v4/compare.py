#!/usr/bin/python3
"""Same pbrt-v4 file, same picture? Renders .pbrt scenes with pbrt-v4 and with Dermis at
equal samples per pixel and measures the difference in standard errors (issue 37).

  /usr/bin/python3 -m bench.pbrt_v4.compare --pbrt /path/to/pbrt --quick     # smoke run
  /usr/bin/python3 -m bench.pbrt_v4.compare --pbrt /path/to/pbrt             # all scenes
  PBRT_V4=/path/to/pbrt /usr/bin/python3 -m bench.pbrt_v4.compare bench/pbrt_v4/scenes/conductor.pbrt

pbrt-v4 is not part of Dermis: give the path of a pbrt-v4 binary you have (`--pbrt PATH`
or the environment variable PBRT_V4). Use EXR output and the zsobol or independent
sampler (the scenes here use zsobol), as this script does.

Per scene, each renderer renders `--seeds` K images at `--spp` N (seeds 1..K: pbrt
`--seed`, dermis `--seed`) and one reference at `--reference-spp` (seed 1000). From the K
images:
  * the image mean (over pixels and the three channels) of each renderer, its standard
    error from the spread of the K per-seed means, and the difference Dermis - pbrt
    relative to pbrt and in standard errors (sqrt(se_pbrt^2 + se_dermis^2 + (floor x
    pbrt)^2), `--floor` 0.001: pbrt writes half floats and its RGB -> spectrum -> RGB
    round trip of a light is off by 0.03-0.06%, which noise-free regions such as a
    uniform sky would otherwise count as tens of standard errors); the same per channel
    (the worst channel is reported), whose standard errors pool the per-pixel variance over
    the K seeds (pooled_mean_se: three seeds' spread alone made false 7-sigma blocks);
  * the same over 16x16-pixel blocks, per channel: the worst block in standard errors
    (and its relative difference) and how many blocks exceed 5 standard errors in any
    channel (a block is counted once);
  * the same per channel over a rectangle on the object, where the scene names one in a
    comment `# compare.py region: x0 y0 x1 y1` (pixels, x1 and y1 excluded);
  * each renderer's MSE against its OWN reference (the reference's noise, estimated as
    the per-pixel variance over the K seeds x N / reference spp, is subtracted), its mean
    render time, the median over the K renders (pbrt: the renderTimeSeconds its EXR
    records, the time its progress bar prints; Dermis: `dermis: wrote X in T s`; both the
    render stage only, wall clock), efficiency = 1 / (MSE x time), and the ratio
    Dermis / pbrt; the same ratio with the median CPU time of the whole process
    (parsing, scene build and start-up included), which other load on the machine does
    not inflate;
  * for scenes with a `subsurface` material (pbrt-v4: its tabulated photon-beam-diffusion
    BSSRDF; Dermis: its default random walk), a third render: Dermis' `volumetric` method
    (the medium inside the boundary, by the volumetric path tracer) at the reference spp
    with maxdepth 100000, and both renderers' means on the object against it
    (--no-exact-subsurface skips it).
Writes, under --out (default out/vs-pbrt-v4, which git ignores): the renders (kept and
reused when the scene file, the binary and the settings are unchanged; --rerun renders
again), <scene>.png (pbrt | Dermis | difference of the references relative to the image
mean | 16x16 blocks in standard errors, false colour), results.json and results.md (the
markdown tables, also printed). Every render runs under `nice -n 19`.

Options: --pbrt, --dermis (default build/dermis), --spp (64), --seeds (8),
--reference-spp (1024), --threads (1, for the timed renders), --reference-threads (2),
--floor (0.001), --out, --rerun, --no-exact-subsurface, --spectral (Dermis with --spectral), --quick (16 spp, 3 seeds,
128-spp references), scenes (default: every bench/pbrt_v4/scenes/*.pbrt).
"""

import argparse
import hashlib
import io
import json
import math
import os
import re
import shutil
import time

import numpy as np

from bench.harness import pictures, render as dermis_render
from bench.harness.exr import read_exr
from bench.harness.paths import DERMIS, ROOT
from bench.harness.progress import log

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "scenes")

# The order of the table; scenes not listed follow in alphabetical order.
ORDER = ["diffuse", "arealights", "envmap", "blackbody", "coateddiffuse", "coateddiffuse-grey", "conductor",
         "conductor-grey", "coatedconductor", "coatedconductor-grey", "dielectric", "roughdielectric", "medium-interface",
         "medium-dielectric", "sss-named", "sss-mfp", "sss-mfp-grey", "sss-mfp-scale", "sss-sigma", "sss-rough"]
BLOCK = 16
SIGMA_LIMIT = 5.0
MEAN_LIMIT = 0.02
REFERENCE_SEED = 1000
EXACT_MAXDEPTH = 100000  # the volumetric reference's maxdepth: it counts every scattering

ANSI_RE = re.compile(r"\x1b\[[0-9;]*m")
PBRT_PROGRESS_RE = re.compile(r"\(([0-9.]+)s\)\s*$")


# ---------------------------------------------------------------- rendering

def file_digest(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        h.update(f.read())
    return h.hexdigest()[:16]


def binary_stamp(path):
    st = os.stat(path)
    return f"{os.path.realpath(path)}:{st.st_size}:{int(st.st_mtime)}"


def scene_stamp(scene):
    """Digest of the scene file and the files beside it that it names (env maps)."""
    h = hashlib.sha256(open(scene, "rb").read())
    d = os.path.dirname(scene)
    for name in sorted(set(re.findall(r'"([^"]+\.(?:exr|pfm|png|ply|pbrt|spd))"',
                                      open(scene).read()))):
        p = os.path.join(d, name)
        if os.path.isfile(p):
            h.update(name.encode())
            h.update(open(p, "rb").read())
    return h.hexdigest()[:16]


def warnings_of(text, renderer):
    out = []
    for line in ANSI_RE.sub("", text).splitlines():
        line = line.strip()
        low = line.lower()
        if renderer == "pbrt":
            if low.startswith("warning") and "output filename supplied" not in low:
                out.append(line)
            elif low.startswith("error"):
                out.append(line)
        elif "warning:" in low or "error:" in low:
            out.append(line)
    return out


class Renderer:
    def __init__(self, name, binary, outdir, rerun, extra=(), label=None):
        self.name, self.binary, self.outdir, self.rerun = name, binary, outdir, rerun
        self.extra, self.label = list(extra), label or name  # Dermis: --subsurface TEXT
        self.stamp = binary_stamp(binary)

    def command(self, scene, spp, seed, threads, exr):
        if self.name == "pbrt":
            return [self.binary, "--nthreads", str(threads), "--spp", str(spp), "--seed",
                    str(seed), "--outfile", exr, scene]
        return dermis_render.command(self.binary, scene, exr, spp=spp, seed=seed, threads=threads,
                                     extra=self.extra)

    def render(self, scene, sstamp, spp, seed, threads, label=None, outname=None):
        """Renders (or reuses) one image: (image, render time in s, info dict)."""
        base = outname or os.path.splitext(os.path.basename(scene))[0]
        d = os.path.join(self.outdir, base)
        os.makedirs(d, exist_ok=True)
        stem = os.path.join(d, f"{label or self.label}-spp{spp}-seed{seed}")
        exr, meta = stem + ".exr", stem + ".json"
        key = {"scene": sstamp, "binary": self.stamp, "spp": spp, "seed": seed,
               "threads": threads}
        if not self.rerun and os.path.isfile(exr) and os.path.isfile(meta):
            info = json.load(open(meta))
            if info.get("key") == key:
                return read_exr(exr).rgb, info["time"], info
        cmd = ["nice", "-n", "19"] + self.command(scene, spp, seed, threads, exr)
        p = dermis_render.run(cmd, cwd=d, check=False, merge_output=True)  # p.cpu: the whole process
        with open(stem + ".log", "w") as f:
            f.write(" ".join(cmd) + "\n" + p.log)
        if p.returncode != 0 or not os.path.isfile(exr):
            tail = "\n".join(ANSI_RE.sub("", p.log).splitlines()[-15:])
            raise RuntimeError(f"{self.name} failed on {scene} (exit {p.returncode}):\n{tail}")
        img, _, attrs = read_exr(exr)
        t, source = None, None
        if self.name == "pbrt":
            if "renderTimeSeconds" in attrs:
                t, source = float(attrs["renderTimeSeconds"]), "EXR renderTimeSeconds"
            else:
                for line in reversed(ANSI_RE.sub("", p.log).replace("\r", "\n").splitlines()):
                    m = PBRT_PROGRESS_RE.search(line)
                    if m:
                        t, source = float(m.group(1)), "progress bar"
                        break
        else:
            stats = dermis_render.render_stats(p.log)
            if stats:
                t, source = stats.seconds, "dermis: wrote ... in T s"
        if t is None:
            t, source = p.wall, "wall clock (process)"
        info = {"key": key, "time": t, "time_source": source, "wall": p.wall, "cpu": p.cpu,
                "command": " ".join(cmd), "warnings": warnings_of(p.log, self.name)}
        json.dump(info, open(meta, "w"), indent=1)
        return img, t, info


# ---------------------------------------------------------------- statistics

def zscore(dm, pm, dse, pse, floor=0.0):
    """(Dermis - pbrt) in standard errors; `floor` x |pbrt| is added in quadrature to the
    standard error (the precision of the comparison itself, see --floor)."""
    se = np.sqrt(dse ** 2 + pse ** 2 + (floor * pm) ** 2)
    diff = dm - pm
    tiny = 1e-9 * np.maximum(np.abs(pm), 1e-9)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, diff / np.where(se > 0, se, 1),
                     np.where(np.abs(diff) <= tiny, 0.0, np.sign(diff) * np.inf))
    return z


def mean_se(x):
    """Mean over axis 0 and its standard error from the spread over axis 0."""
    k = x.shape[0]
    return x.mean(axis=0), (x.std(axis=0, ddof=1) / math.sqrt(k) if k > 1 else np.zeros_like(x[0]))


def pooled_mean_se(x):
    """x: (K, H, W, 3) renders of a region. Its mean per channel, and the standard error of
    that mean from the per-pixel variance over the K renders, pooled over the region's pixels
    (K - 1 degrees of freedom per pixel, (K - 1) x pixels in all): the pixels of a render are
    independent, or negatively correlated (zsobol), so this errs on the large side. From the
    spread of K region means alone, three seeds give a t-statistic of 2 degrees of freedom,
    beyond 5 in 4 % of the region-channels where nothing differs: the "blue offset" of
    docs/results/results-vs-pbrt-v4.md was that."""
    k = x.shape[0]
    n = x.shape[1] * x.shape[2]
    mean = x.mean(axis=(0, 1, 2))
    if k < 2:
        return mean, np.zeros_like(mean)
    var = x.var(axis=0, ddof=1).mean(axis=(0, 1))
    return mean, np.sqrt(var / (n * k))


def block_pooled(imgs, b=BLOCK):
    """(K, H, W, 3) -> means and pooled standard errors (pooled_mean_se) of b x b blocks,
    (nby, nbx, 3) each (partial edge blocks kept)."""
    k, h, w, c = imgs.shape
    ys, xs = list(range(0, h, b)), list(range(0, w, b))
    mean, se = np.empty((len(ys), len(xs), c)), np.empty((len(ys), len(xs), c))
    for i, y in enumerate(ys):
        for j, x in enumerate(xs):
            mean[i, j], se[i, j] = pooled_mean_se(imgs[:, y:y + b, x:x + b])
    return mean, se


def mse_against(imgs, ref, spp, ref_spp):
    """MSE of one render against the renderer's own reference, less the reference's noise."""
    raw = float(np.mean([(im - ref) ** 2 for im in imgs]))
    var = float(np.mean(imgs.var(axis=0, ddof=1))) if len(imgs) > 1 else 0.0
    ref_noise = var * spp / ref_spp
    mse = raw - ref_noise
    if mse <= 0:  # the reference is no better than the renders: fall back on the variance
        mse = var
    return {"mse": mse, "mse_raw": raw, "variance": var, "ref_noise": ref_noise}


def analyse(P, D, Pref, Dref, tp, td, spp, ref_spp, floor):
    pm_k, dm_k = P.mean(axis=(1, 2, 3)), D.mean(axis=(1, 2, 3))
    pm, pse = mean_se(pm_k)
    dm, dse = mean_se(dm_k)
    r = {"mean_pbrt": float(pm), "mean_dermis": float(dm), "se_pbrt": float(pse),
         "se_dermis": float(dse), "rel": float((dm - pm) / pm) if pm else float("nan"),
         "z": float(zscore(dm, pm, dse, pse, floor))}
    pc, pcse = pooled_mean_se(P)
    dc, dcse = pooled_mean_se(D)
    zc = zscore(dc, pc, dcse, pcse, floor)
    r["channels"] = [{"pbrt": float(pc[c]), "dermis": float(dc[c]),
                      "rel": float((dc[c] - pc[c]) / pc[c]) if pc[c] else float("nan"),
                      "z": float(zc[c])} for c in range(3)]
    wc = int(np.nanargmax(np.abs(zc)))
    r["worst_channel"] = {"channel": "RGB"[wc], **r["channels"][wc]}
    pb, pbse = block_pooled(P)
    db, dbse = block_pooled(D)
    zb = zscore(db, pb, dbse, pbse, floor)  # (nby, nbx, 3)
    absz = np.abs(zb)
    i, j, c = np.unravel_index(int(np.nanargmax(absz)), absz.shape)
    r["blocks"] = {"count": int(absz.shape[0] * absz.shape[1]),
                   "over": int(np.sum(np.any(absz > SIGMA_LIMIT, axis=-1))),
                   "worst_z": float(zb[i, j, c]), "worst_at": [int(i), int(j), "RGB"[c]],
                   "worst_rel": float((db[i, j, c] - pb[i, j, c]) / pb[i, j, c])
                   if pb[i, j, c] else float("nan"),
                   "z_map": np.max(absz, axis=-1).tolist(),
                   "signed_z": np.take_along_axis(zb, np.argmax(absz, axis=-1)[..., None],
                                                  axis=-1)[..., 0].tolist()}
    mp = mse_against(P, Pref, spp, ref_spp)
    md = mse_against(D, Dref, spp, ref_spp)
    # The median: on a shared machine a render now and then waits for the CPU.
    r["pbrt"] = {**mp, "time": float(np.median(tp)), "times": [float(t) for t in tp]}
    r["dermis"] = {**md, "time": float(np.median(td)), "times": [float(t) for t in td]}
    ep = 1 / (mp["mse"] * r["pbrt"]["time"])
    ed = 1 / (md["mse"] * r["dermis"]["time"])
    r["pbrt"]["efficiency"], r["dermis"]["efficiency"] = ep, ed
    r["efficiency_ratio"] = ed / ep
    r["mse_ratio"] = mp["mse"] / md["mse"]
    r["time_ratio"] = r["pbrt"]["time"] / r["dermis"]["time"]
    return r


# ---------------------------------------------------------------- pictures

def nice_range(x):
    """The smallest 1-2-5 step at or above x (at least 0.01)."""
    x = max(x, 0.01)
    e = 10 ** math.floor(math.log10(x))
    for m in (1, 2, 5, 10):
        if m * e >= x * (1 - 1e-9):
            return m * e
    return 10 * e


def sheet(path, name, Pref, Dref, r):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    h, w = Pref.shape[:2]
    diff = (Dref - Pref).mean(axis=-1) / max(Pref.mean(), 1e-12)
    rng = nice_range(float(np.percentile(np.abs(diff), 99)))
    scale = 2.0  # each panel at twice the render's size
    fw, fh = 4 * w * scale / 100 + 0.9, h * scale / 100 + 0.55
    fig, ax = plt.subplots(1, 4, figsize=(fw, fh), dpi=100,
                           gridspec_kw={"wspace": 0.32, "left": 0.01, "right": 0.96,
                                        "top": 0.86, "bottom": 0.02})
    ax[0].imshow(pictures.srgb8(Pref), interpolation="nearest")
    ax[0].set_title("pbrt-v4", fontsize=8)
    ax[1].imshow(pictures.srgb8(Dref), interpolation="nearest")
    ax[1].set_title("Dermis", fontsize=8)
    im = ax[2].imshow(diff, cmap="RdBu_r", vmin=-rng, vmax=rng, interpolation="nearest")
    ax[2].set_title("Dermis − pbrt (÷ mean)", fontsize=8)
    cb = fig.colorbar(im, ax=ax[2], fraction=0.046, pad=0.03, ticks=[-rng, 0, rng])
    cb.ax.tick_params(labelsize=6)
    zs = np.array(r["blocks"]["signed_z"])
    im2 = ax[3].imshow(np.clip(zs, -10, 10), cmap="RdBu_r", vmin=-10, vmax=10,
                       interpolation="nearest", extent=(0, w, h, 0))
    ax[3].set_title(f"{BLOCK}×{BLOCK} blocks (σ)", fontsize=8)
    cb2 = fig.colorbar(im2, ax=ax[3], fraction=0.046, pad=0.03, ticks=[-10, -5, 0, 5, 10])
    cb2.ax.tick_params(labelsize=6)
    for y in range(zs.shape[0]):
        for x in range(zs.shape[1]):
            if abs(zs[y, x]) > SIGMA_LIMIT:
                ax[3].add_patch(plt.Rectangle((x * BLOCK, y * BLOCK), BLOCK, BLOCK,
                                              fill=False, ec="k", lw=0.8))
    for a in ax:
        a.set_xticks([])
        a.set_yticks([])
    fig.suptitle(f"{name}: mean {100 * r['rel']:+.2f}% ({r['z']:+.1f}σ), worst block "
                 f"{r['blocks']['worst_z']:+.1f}σ, {r['blocks']['over']} > {SIGMA_LIMIT:g}σ",
                 fontsize=8)
    bio = io.BytesIO()
    fig.savefig(bio, format="png")
    plt.close(fig)
    try:  # a palette PNG: about a third of the size
        from PIL import Image
        bio.seek(0)
        Image.open(bio).convert("RGB").quantize(256, dither=Image.Dither.NONE).save(
            path, optimize=True)
    except ImportError:
        open(path, "wb").write(bio.getvalue())


# ---------------------------------------------------------------- report

def is_subsurface(scene):
    text = re.sub(r"#[^\n]*", "", open(scene).read())
    return re.search(r'"subsurface"', text) is not None


def feature_of(scene):
    """The scene's first comment line after 'name.pbrt:'."""
    for line in open(scene):
        m = re.match(r"#\s*\S+\.pbrt:\s*(.*)", line)
        if m:
            return m.group(1).strip()
    return ""


def region_of(scene):
    """The optional `# compare.py region: x0 y0 x1 y1` comment: a pixel rectangle on the object."""
    for line in open(scene):
        m = re.match(r"#\s*compare\.py region:\s*(\d+)\s+(\d+)\s+(\d+)\s+(\d+)", line)
        if m:
            return [int(v) for v in m.groups()]
    return None


def region_stats(P, D, region, floor, exact=None):
    x0, y0, x1, y1 = region
    pc, pse = pooled_mean_se(P[:, y0:y1, x0:x1])
    dc, dse = pooled_mean_se(D[:, y0:y1, x0:x1])
    z = zscore(dc, pc, dse, pse, floor)
    out = {"region": region, "pbrt": pc.tolist(), "dermis": dc.tolist(),
           "rel": ((dc - pc) / pc).tolist(), "z": z.tolist()}
    if exact is not None:
        ec = exact[y0:y1, x0:x1].mean(axis=(0, 1))
        out["exact"] = ec.tolist()
        out["pbrt_vs_exact"] = (pc / ec - 1).tolist()
        out["dermis_vs_exact"] = (dc / ec - 1).tolist()
    return out


def absolute_filenames(text, d):
    """Relative file names keep working in a variant written elsewhere: named by absolute path."""
    return re.sub(r'"string filename"\s+(\[\s*)?"([^"/][^"]*)"(?(1)\s*\])',
                  lambda mm: f'"string filename" "{os.path.join(d, mm.group(2))}"', text)


def resolution_variant(scene, path, res):
    """The scene at another film resolution (both renderers read the variant): for the large
    scenes of pbrt-v4's repository (head, sssdragon), whose films are 1366 x 1024 and more."""
    w, h = res
    text = open(scene).read()
    for axis, v in (("xresolution", w), ("yresolution", h)):
        text, n = re.subn(rf'("integer\s+{axis}"\s+)(?:\[\s*)?\d+(?:\s*\])?', rf"\g<1>{v}", text)
        if n == 0:
            text = re.sub(r'(Film\s+"\w+")', rf'\1 "integer {axis}" {v}', text)
    text = absolute_filenames(text, os.path.dirname(os.path.abspath(scene)))
    with open(path, "w") as f:
        f.write(f"# Generated by bench/pbrt_v4/compare.py from {scene} at {w}x{h}\n{text}")


def exact_variant(scene, path):
    """The scene with Dermis' `volumetric` method on every subsurface material (the medium in
    a smooth dielectric, rendered by the volumetric path tracer: the exact solution for the
    coefficients Dermis derives) and maxdepth raised so that no scattering is cut off."""
    text = open(scene).read()
    text, n = re.subn(r'(Material\s+"subsurface")', r'\1 "string method" "volumetric"', text)
    text, m = re.subn(r'("string\s+type"\s+(?:\[\s*)?"subsurface"(?:\s*\])?)',
                      r'\1 "string method" "volumetric"', text)
    text = re.sub(r'"string method"\s+(?:\[\s*)?"(?!volumetric)[^"]*"(?:\s*\])?', "", text)
    text, k = re.subn(r'("integer\s+maxdepth"\s+)(?:\[\s*)?\d+(?:\s*\])?',
                      rf"\g<1>{EXACT_MAXDEPTH}", text)
    if k == 0:
        text, i = re.subn(r'(Integrator\s+"\w+")', rf'\1 "integer maxdepth" {EXACT_MAXDEPTH}', text)
        if i == 0:  # no Integrator: pbrt-v4's default volpath, whose maxdepth 5 would cut the walk's scattering
            text = re.sub(r'^(\s*WorldBegin)', rf'Integrator "volpath" "integer maxdepth" {EXACT_MAXDEPTH}\n\1', text,
                          count=1, flags=re.M)
    text = absolute_filenames(text, os.path.dirname(scene))
    with open(path, "w") as f:
        f.write(f"# Generated by bench/pbrt_v4/compare.py from {scene}: Dermis' volumetric "
                f"reference of its subsurface material(s)\n{text}")
    return n + m


def verdict(r):
    if r["subsurface"] and not r.get("same_subsurface_model"):
        return "methods differ (PBD vs Dermis' walk)"
    ok = abs(r["rel"]) <= MEAN_LIMIT and r["blocks"]["over"] == 0
    return "meets targets" if ok else "**outside targets**"


def table(results, args):
    lines = [
        f"| scene | mean pbrt | mean Dermis | Δ mean | Δ/σ | worst channel | worst block "
        f"(of {results[0]['blocks']['count'] if results else 0}) | blocks > {SIGMA_LIMIT:g}σ "
        f"| time pbrt / Dermis | MSE pbrt / Dermis | efficiency Dermis ÷ pbrt "
        f"| same, process CPU time | verdict |",
        "|---|---:|---:|---:|---:|---|---|---:|---|---:|---:|---:|---|"]
    for r in results:
        wc = r["worst_channel"]
        b = r["blocks"]
        lines.append(
            f"| {r['name']} | {r['mean_pbrt']:.4f} | {r['mean_dermis']:.4f} "
            f"| {100 * r['rel']:+.2f}% | {r['z']:+.1f} "
            f"| {wc['channel']} {100 * wc['rel']:+.2f}% ({wc['z']:+.1f}σ) "
            f"| {b['worst_z']:+.1f}σ ({100 * b['worst_rel']:+.1f}%) | {b['over']} "
            f"| {r['pbrt']['time']:.2f} / {r['dermis']['time']:.2f} s "
            f"| {r['mse_ratio']:.2f} | {r['efficiency_ratio']:.1f}× "
            f"| {r.get('efficiency_ratio_cpu', float('nan')):.1f}× | {verdict(r)} |")
    return "\n".join(lines)


def pct3(v):
    return " ".join(f"{100 * x:+.1f}" for x in v)


def region_table(results):
    rows = [r for r in results if "region" in r]
    if not rows:
        return ""
    lines = ["| scene | on the object (x0 y0 x1 y1) | pbrt R G B | Dermis R G B | Δ R G B (%) | Δ/σ R G B |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        g = r["region"]
        lines.append(f"| {r['name']} | {' '.join(map(str, g['region']))} "
                     f"| {' '.join(f'{x:.4f}' for x in g['pbrt'])} "
                     f"| {' '.join(f'{x:.4f}' for x in g['dermis'])} "
                     f"| {pct3(g['rel'])} | {' '.join(f'{x:+.1f}' for x in g['z'])} |")
    return "\n".join(lines)


def exact_table(results):
    rows = [r for r in results if "region" in r and "exact" in r["region"]]
    if not rows:
        return ""
    lines = ["| scene | exact (Dermis volumetric) R G B | pbrt − exact (%) R G B | Dermis − exact (%) R G B | image mean: pbrt / Dermis − exact |",
             "|---|---|---|---|---|"]
    for r in rows:
        g = r["region"]
        lines.append(f"| {r['name']} | {' '.join(f'{x:.4f}' for x in g['exact'])} "
                     f"| {pct3(g['pbrt_vs_exact'])} | {pct3(g['dermis_vs_exact'])} "
                     f"| {100 * r['exact']['pbrt_vs_exact']:+.1f}% / {100 * r['exact']['dermis_vs_exact']:+.1f}% |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="*", help="pbrt-v4 scene files (default: bench/pbrt_v4/scenes/*.pbrt)")
    ap.add_argument("--pbrt", default=os.environ.get("PBRT_V4"),
                    help="pbrt-v4 binary (default: $PBRT_V4)")
    ap.add_argument("--dermis", default=DERMIS)
    ap.add_argument("--spp", type=int, default=None, help="samples per pixel of the measured renders (64)")
    ap.add_argument("--seeds", type=int, default=None, help="renders per renderer and scene (8)")
    ap.add_argument("--reference-spp", type=int, default=None, help="spp of each renderer's own reference (1024)")
    ap.add_argument("--threads", type=int, default=1, help="threads of the timed renders (1)")
    ap.add_argument("--reference-threads", type=int, default=2, help="threads of the references (2)")
    ap.add_argument("--floor", type=float, default=0.001,
                    help="relative error floor added to every standard error (0.001: pbrt "
                         "writes half floats, 2^-11 = 0.05%% apart, and its RGB -> spectrum -> "
                         "RGB round trip of a light is 0.03-0.06%% off; 0 turns it off)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "vs-pbrt-v4"))
    ap.add_argument("--quick", action="store_true", help="16 spp, 3 seeds, 128-spp references")
    ap.add_argument("--rerun", action="store_true", help="render again even where renders are kept")
    ap.add_argument("--res", default=None,
                    help="WIDTHxHEIGHT: render a copy of each scene at this film resolution "
                         "(for the repository's large scenes)")
    ap.add_argument("--subsurface", default="",
                    help="Dermis renders with `--subsurface TEXT` (e.g. pbrt-v4: pbrt-v4's photon-beam "
                         "profile; the subsurface scenes are then held to the same targets as the others)")
    ap.add_argument("--spectral", action="store_true",
                    help="Dermis renders with --spectral (docs/rendering.md, \"Spectral transport\")")
    ap.add_argument("--no-exact-subsurface", dest="exact_subsurface", action="store_false",
                    help="skip Dermis' volumetric reference of the subsurface scenes")
    args = ap.parse_args()
    defaults = (16, 3, 128) if args.quick else (64, 8, 1024)
    args.spp = args.spp or defaults[0]
    args.seeds = args.seeds or defaults[1]
    args.reference_spp = args.reference_spp or defaults[2]
    if args.seeds < 2:
        ap.error("--seeds must be at least 2 (the standard errors come from their spread)")
    if not args.pbrt:
        ap.error("give the path of a pbrt-v4 binary: --pbrt PATH or PBRT_V4=PATH")
    for what, b in (("pbrt", args.pbrt), ("dermis", args.dermis)):
        if not (os.path.isfile(b) and os.access(b, os.X_OK)):
            ap.error(f"{what} binary not found or not executable: {b}")
    if not shutil.which("nice"):
        ap.error("`nice` not found")

    scenes = args.scenes or [os.path.join(SCENES, f) for f in os.listdir(SCENES)
                             if f.endswith(".pbrt")]
    scenes = [os.path.abspath(s) for s in scenes]
    rank = {n: i for i, n in enumerate(ORDER)}
    scenes.sort(key=lambda s: (rank.get(os.path.splitext(os.path.basename(s))[0], len(ORDER)), s))
    env = os.path.join(SCENES, "envmap.exr")
    if any(os.path.dirname(s) == SCENES for s in scenes) and not os.path.isfile(env):
        from bench.pbrt_v4 import make_envmap
        make_envmap.make(env)
        log(f"made {env}")

    os.makedirs(args.out, exist_ok=True)
    pbrt = Renderer("pbrt", args.pbrt, args.out, args.rerun)
    extra = (["--subsurface", args.subsurface] if args.subsurface else []) + (["--spectral"] if args.spectral else [])
    label = "-".join(["dermis"] + ([re.sub(r"[^A-Za-z0-9]+", "_", args.subsurface).strip("_")] if args.subsurface
                                   else []) + (["spectral"] if args.spectral else []))
    dermis = Renderer("dermis", args.dermis, args.out, args.rerun, extra=extra,
                      label=label if extra else None)
    dermis_plain = Renderer("dermis", args.dermis, args.out, args.rerun)  # the volumetric reference
    results = []
    t_start = time.perf_counter()
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        sstamp = scene_stamp(scene)
        if args.res:
            w, h = (int(v) for v in args.res.lower().split("x"))
            os.makedirs(os.path.join(args.out, name), exist_ok=True)
            vpath = os.path.join(args.out, name, f"{name}-{w}x{h}.pbrt")
            resolution_variant(scene, vpath, (w, h))
            scene, sstamp = vpath, sstamp + f"-{w}x{h}"
        t0 = time.perf_counter()
        P, D, tp, td, infos = [], [], [], [], {"pbrt": [], "dermis": []}
        for seed in range(1, args.seeds + 1):  # interleaved: both see the same machine load
            for rd, imgs, times in ((pbrt, P, tp), (dermis, D, td)):
                img, t, info = rd.render(scene, sstamp, args.spp, seed, args.threads)
                imgs.append(img)
                times.append(t)
                infos[rd.name].append(info)
        Pref, _, pinfo = pbrt.render(scene, sstamp, args.reference_spp, REFERENCE_SEED,
                                     args.reference_threads)
        Dref, _, dinfo = dermis.render(scene, sstamp, args.reference_spp, REFERENCE_SEED,
                                       args.reference_threads)
        P, D = np.array(P), np.array(D)
        if P.shape != D.shape:
            raise SystemExit(f"{name}: pbrt's image is {P.shape[1:3]}, Dermis' {D.shape[1:3]}")
        r = analyse(P, D, Pref, Dref, tp, td, args.spp, args.reference_spp, args.floor)
        # Cross-check of the time: CPU seconds of the whole process (parsing, scene build
        # and start-up included), which another process on the machine does not inflate.
        for rn in ("pbrt", "dermis"):
            cpus = [i.get("cpu") for i in infos[rn]]
            r[rn]["cpu"] = float(np.median(cpus)) if all(c is not None for c in cpus) else None
        if r["pbrt"]["cpu"] and r["dermis"]["cpu"]:
            r["efficiency_ratio_cpu"] = (r["pbrt"]["mse"] * r["pbrt"]["cpu"]) / (
                r["dermis"]["mse"] * r["dermis"]["cpu"])
        r.update({"name": name, "scene": os.path.relpath(scene, ROOT),
                  "feature": feature_of(scene), "subsurface": is_subsurface(scene),
                  "same_subsurface_model": args.subsurface == "pbrt-v4",
                  "warnings": {"pbrt": sorted(set(sum((i["warnings"] for i in infos["pbrt"] + [pinfo]), []))),
                               "dermis": sorted(set(sum((i["warnings"] for i in infos["dermis"] + [dinfo]), [])))},
                  "resolution": list(P.shape[1:3][::-1])})
        exact = None
        if r["subsurface"] and args.exact_subsurface:
            vpath = os.path.join(args.out, name, "exact-volumetric.pbrt")
            if exact_variant(scene, vpath):
                exact, _, _ = dermis_plain.render(vpath, scene_stamp(vpath), args.reference_spp,
                                                REFERENCE_SEED, args.reference_threads,
                                                label="dermis-volumetric", outname=name)
                r["exact"] = {"scene": vpath, "mean": float(exact.mean()),
                              "pbrt_vs_exact": float(r["mean_pbrt"] / exact.mean() - 1),
                              "dermis_vs_exact": float(r["mean_dermis"] / exact.mean() - 1)}
        region = region_of(scene)
        if region:
            r["region"] = region_stats(P, D, region, args.floor, exact)
        r["verdict"] = verdict(r)
        sheet(os.path.join(args.out, f"{name}.png"), name, Pref, Dref, r)
        results.append(r)
        log(f"{name}: mean {100 * r['rel']:+.2f}% ({r['z']:+.1f}σ), worst block "
            f"{r['blocks']['worst_z']:+.1f}σ, {r['blocks']['over']} blocks > {SIGMA_LIMIT:g}σ, "
            f"efficiency Dermis/pbrt {r['efficiency_ratio']:.2f}x "
            f"[{time.perf_counter() - t0:.0f} s]")
        for rn in ("pbrt", "dermis"):
            for w in r["warnings"][rn]:
                log(f"  {rn}: {w}")

    settings = {"spp": args.spp, "seeds": args.seeds, "reference_spp": args.reference_spp,
                "threads": args.threads, "reference_threads": args.reference_threads,
                "pbrt": os.path.realpath(args.pbrt), "dermis": os.path.realpath(args.dermis),
                "wall_s": time.perf_counter() - t_start, "block": BLOCK, "floor": args.floor,
                "subsurface": args.subsurface}
    md = table(results, args)
    rt, et = region_table(results), exact_table(results)
    if rt:
        md += "\n\nOn the object (the rectangle each scene names in a `# compare.py region:` comment):\n\n" + rt
    if et:
        md += ("\n\nSubsurface scenes against Dermis' volumetric reference (the same scene with "
               f"`\"string method\" \"volumetric\"` and maxdepth {EXACT_MAXDEPTH}), on the object:\n\n" + et)
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write(f"{args.spp} spp, {args.seeds} seeds, references at {args.reference_spp} spp; "
                f"timed renders on {args.threads} thread(s)\n\n{md}\n")
    json.dump({"settings": settings, "results": results},
              open(os.path.join(args.out, "results.json"), "w"), indent=1)
    print(md)
    log(f"\n{len(results)} scenes in {settings['wall_s']:.0f} s; pictures, results.md and "
        f"results.json in {args.out}")


if __name__ == "__main__":
    main()
