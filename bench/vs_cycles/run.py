#!/usr/bin/python3
"""Dermis vs Blender Cycles at equal error (issues 15 and 40).

Every scene of bench/vs_cycles/scenes.py is written once as a pbrt-v4 file for Dermis and
built by bench/vs_cycles/blender_scene.py in Blender; both renderers render a converged
reference (two independent time-limited halves) and a sweep of sample counts; each sweep
image is measured against its own renderer's reference over the object's pixels (and,
for the family, over the whole image too).

  /usr/bin/python3 -m bench.vs_cycles.run --quick                 # the family, smoke test, ~3 min
  /usr/bin/python3 -m bench.vs_cycles.run                         # the family (issue 40), ~22 min on 2 cores
  /usr/bin/python3 -m bench.vs_cycles.run --set classic           # the seven scenes of issue 15, ~18 min
  /usr/bin/python3 -m bench.vs_cycles.run --set heldout           # eight held-out configurations, ~11 min
  /usr/bin/python3 -m bench.vs_cycles.run --set textured          # six with a checkerboard reflectance, ~9 min
  /usr/bin/python3 -m bench.vs_cycles.run --set closeup           # the family's twelve framed close, ~25 min
  /usr/bin/python3 -m bench.vs_cycles.run --set lighting          # HDR environments and area lights (issue 66), 45 scenes
  /usr/bin/python3 -m bench.vs_cycles.run --scenes medium-matched,calibration --spp 16,64

Measurement (as bench/sss_methods.py): E[(A - R)^2] = Var A + bias^2 + Var R, and the
reference's own per-pixel variance is estimated from its two halves h1, h2 as
(h1 - h2)^2 / 4 and subtracted. Each sample count is rendered with several seeds in both
renderers and its MSE is their mean (the expected MSE; one heavy-tailed image reads low). Efficiency = 1 / (MSE x render time) (higher is better;
for unbiased estimators it does not depend on the sample count).
"""

import argparse
import datetime
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time

import numpy as np

from bench.harness import docs_page, progress, provenance, render
from bench.harness.exr import read_exr
from bench.harness.paths import DERMIS, IMAGES as DOCS_IMAGES, RESULTS, ROOT
from bench.harness.pictures import strip, write_png
from bench.vs_cycles import cycles_log, environments, grid_twin, pbrt_writer
from bench.vs_cycles import scenes as S

HERE = os.path.dirname(os.path.abspath(__file__))
HUGE_SPP = 1000000
# The family's report, the held-out configurations' and the classic seven scenes' (issue 15)
# beside it.
DOC = {"family": os.path.join(RESULTS, "results-vs-cycles.md"),
       "heldout": os.path.join(RESULTS, "results-vs-cycles-heldout.md"),
       "textured": os.path.join(RESULTS, "results-vs-cycles-textured.md"),
       "closeup": os.path.join(RESULTS, "results-vs-cycles-closeup.md"),
       "lighting": os.path.join(RESULTS, "results-vs-cycles-lighting.md"),
       "classic": os.path.join(RESULTS, "results-vs-cycles-classic.md")}
IMAGES = {"family": os.path.join(DOCS_IMAGES, "vs-cycles"),
          "heldout": os.path.join(DOCS_IMAGES, "vs-cycles-heldout"),
          "textured": os.path.join(DOCS_IMAGES, "vs-cycles-textured"),
          "closeup": os.path.join(DOCS_IMAGES, "vs-cycles-closeup"),
          "lighting": os.path.join(DOCS_IMAGES, "vs-cycles-lighting"),
          "classic": os.path.join(DOCS_IMAGES, "vs-cycles")}


def log(msg):
    progress.log(msg, sys.stdout)


# ------------------------------------------------------------------ images

def parse_clock(s):
    """Blender's "MM:SS.ss" or "HH:MM:SS.ss" -> seconds."""
    secs = 0.0
    for part in s.split(":"):
        secs = secs * 60 + float(part)
    return secs


# ------------------------------------------------------------------ Dermis

class Run:
    """One render: image, seconds (render stage only), samples per pixel, extra info."""

    def __init__(self, exr, seconds, spp, wall, **info):
        self.exr, self.seconds, self.spp, self.wall, self.info = exr, seconds, spp, wall, info
        self.img = None

    def load(self):
        if self.img is None:
            self.img, _, self.attrs = read_exr(self.exr)
        return self.img


def dermis_command(args, scene_file, out, spp=None, seconds=None, seed=1):
    extra = ["--sampler", args.dermis_sampler] if args.dermis_sampler else []
    if seconds:
        extra += ["--time-limit", f"{seconds:g}"]
    return render.command(args.dermis, scene_file, out, spp=spp if spp else HUGE_SPP, seed=seed, threads=args.threads,
                          extra=extra)


def dermis_result(args, done, out, scene_file, res):
    """The Run of a finished `dermis render` (a render.Finished: its exit status, log and wall time)."""
    if done.returncode != 0:
        raise render.DermisError(done)
    cmd, stderr, wall = done.cmd, done.log, done.wall
    stats = render.render_stats(stderr)
    reported, mrays, samples = stats.seconds, stats.mrays, stats.samples
    limit = render.time_limit_range(stderr)
    npx = res[0] * res[1]
    warnings = [l for l in stderr.splitlines() if "warning" in l]
    # `dermis render` prints the render-stage time in milliseconds. Builds before 2026-12-03
    # printed it with 0.1 s resolution: for those, below 2 s, use the process's wall time
    # minus that of loading the same scene (a 1 x 1 pixel, 1 spp render), rough
    # and noisy: the difference of two wall times (bust-walk, 16 spp: 0.73 s in one run, 0.44 s rendering).
    secs, approx = reported, False
    if len(stats.printed.partition(".")[2]) < 3 and reported < 2.0:
        secs, approx = max(wall - dermis_load_wall(args, scene_file), 1e-3), True
    log(f"    dermis {os.path.basename(out)}: render {reported:.3f} s{f' (~{secs:.2f} s)' if approx else ''} "
        f"(process {wall:.1f} s), {samples / npx:.1f} spp"
        + (f" [{limit[0]}..{limit[1]}]" if limit else "") + (f"  {'; '.join(warnings)}" if warnings else ""))
    return Run(out, secs, samples / npx, wall, cmd=" ".join(cmd), warnings=warnings, approx=approx, reported=reported,
               rays_per_sample=mrays * 1e6 * reported / max(samples, 1))


def dermis_render(args, scene_file, out, spp=None, seconds=None, seed=1, res=None):
    done = render.run(dermis_command(args, scene_file, out, spp, seconds, seed), check=False)
    return dermis_result(args, done, out, scene_file, res)


class Level:
    """The renders of one sweep sample count, one per seed (1, 2, ...): its time is the
    median of theirs (all of them listed: the run-to-run spread of a shared machine), its
    MSE the mean of theirs. One image's MSE is a poor estimate of the expected MSE where
    the error is heavy-tailed (rare bright paths): most single images miss the fireflies
    that the mean contains, so one seed reads low, and more so for the renderer with the
    heavier tail (bust-burley at 16 spp: Cycles' MSE over seeds 2-9 averaged 1.5x its
    seed-1 figure, Dermis' 1.01x; twentieth session)."""

    def __init__(self, runs):
        self.runs = runs
        self.times = sorted(r.seconds for r in runs)
        self.seconds = float(np.median(self.times))
        # The whole process (Dermis: `dermis render` from start to exit; Cycles: the
        # render operator, sync + render + EXR write, in an already started Blender).
        self.process = float(np.median([r.wall for r in runs]))
        rays = [r.info["rays_per_sample"] for r in runs if "rays_per_sample" in r.info]
        self.rays_per_sample = float(np.median(rays)) if rays else None
        self.spp = runs[0].spp
        self.first = runs[0]  # seed 1: the image of the contact sheet


_load_wall = {}


def dermis_load_wall(args, scene_file):
    """Wall seconds to start Dermis, load and prepare a scene and write a tiny image: the
    best of three 1 x 1 pixel, 1 spp renders."""
    if scene_file not in _load_wall:
        out = scene_file + ".load.exr"
        best = min(render.render(args.dermis, scene_file, out, spp=1, res="1x1", threads=args.threads).wall
                   for _ in range(3))
        os.remove(out)
        _load_wall[scene_file] = best
    return _load_wall[scene_file]


# ------------------------------------------------------------------ Cycles

def cycles_renders(args, sc, renders, work):
    """All Cycles renders of a scene in one Blender process (the scene is built once;
    every render re-syncs it, and only Cycles' render_time is used as the cost). A render's
    `dermis_before` commands are run by that process just before it (interleaved timing);
    their exit status, stderr and wall time come back as the fourth value."""
    job = dict(scene=sc, threads=args.threads, root=ROOT, renders=renders,
               result=os.path.join(work, "cycles-result.json"))
    jpath = os.path.join(work, "cycles-job.json")
    with open(jpath, "w") as f:
        json.dump(job, f, indent=1)
    cmd = [args.blender, "-b", "--factory-startup", *cycles_log.BLENDER_FLAGS, "--python",
           os.path.join(HERE, "blender_scene.py"), "--", jpath]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    with open(os.path.join(work, "cycles-log.txt"), "w") as f:
        f.write(p.stdout + p.stderr)
    if p.returncode != 0 or not os.path.exists(job["result"]):
        sys.exit(f"blender failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout[-3000:]}\n{p.stderr[-3000:]}")
    res = json.load(open(job["result"]))
    # Samples reached: the last "Sample N/M" line before each "vs_cycles: rendered" marker.
    segments = re.split(r"vs_cycles: rendered .*\n", p.stdout)
    # Cycles' render and total times from its log (the EXR stamp truncates them to 10 ms:
    # cycles_log.py), each checked against its render's stamp.
    logged = cycles_log.render_times(p.stderr)
    if len(logged) != len(res["renders"]):
        sys.exit(f"Cycles logged {len(logged)} render times for {len(res['renders'])} renders "
                 f"(Blender run with {' '.join(cycles_log.BLENDER_FLAGS)}); see {work}/cycles-log.txt")
    runs = []
    for r, seg, (rt, total) in zip(res["renders"], segments, logged):
        reached = [int(n) for n in re.findall(r"Sample (\d+)/\d+", seg)]
        img, _, attrs = read_exr(r["out"])
        stamp = parse_clock(attrs["cycles.ViewLayer.render_time"])
        if not cycles_log.agrees_with_stamp(rt, stamp):
            sys.exit(f"Cycles' logged render time {rt} s does not match {r['out']}'s stamp {stamp} s")
        spp = max(reached) if reached else r["spp"]
        run = Run(r["out"], rt, spp, r["wall"], sync=total - rt, total=total, stamp=stamp)
        run.img, run.attrs = img, attrs
        log(f"    cycles {os.path.basename(r['out'])}: render {rt:.4f} s (stamp {stamp:.2f}; sync {total - rt:.3f} s, "
            f"operator {r['wall']:.2f} s), "
            f"{spp} spp")
        runs.append(run)
    log(f"    (blender process {wall:.1f} s)")
    # Dermis' renders that the Blender process ran before its own (dermis_before), in order.
    dermis_runs = [d for r in res["renders"] for d in r.get("dermis", [])]
    return runs, res["info"], " ".join(cmd), dermis_runs


# ------------------------------------------------------------------ measurement

class Family:
    """One renderer (variant) of one scene: a two-half reference and a sweep."""

    def __init__(self, label, halves, sweep, mask, highlights=None):
        self.label, self.halves, self.sweep, self.mask = label, halves, sweep, mask
        a, b = halves[0].load(), halves[1].load()
        self.ref = 0.5 * (a + b)
        self.ref_var = (a - b) ** 2 / 4  # per-pixel variance of the averaged reference
        # Two conventions: MSE over the object's pixels with the render stage's time (the
        # primary one), and MSE over the whole image (silhouettes included) with the time
        # of the whole process.
        self.rows = [self.measure(level, mask) for level in sweep]
        whole = np.ones_like(mask)
        self.rows_image = []
        for level in sweep:
            r = self.measure(level, whole)
            r.update(seconds=level.process, eff=1.0 / (r["mse_corr"] * max(level.process, 1e-3)))
            self.rows_image.append(r)
        # A third: the object's pixels less those showing a light's mirror image (make_highlights),
        # render-stage time: the subsurface's own noise, without the highlights' pixel-area noise.
        sub = mask & ~highlights if highlights is not None else mask
        self.rows_sub = [self.measure(level, sub) for level in sweep] if sub.any() else self.rows

    def measure(self, level, m):
        """The level's MSE over the pixels of mask m: the mean over its seeds' images of the
        MSE less the reference's variance; ± from the spread over the seeds (one seed: from
        the spread of the per-pixel squared errors, pixels taken as independent)."""
        var_ref = float(np.mean(self.ref_var[m]))
        per_seed, pixel_se = [], 0.0
        for r in level.runs:
            err2 = (r.load() - self.ref)[m] ** 2
            per_seed.append(float(np.mean(err2)) - var_ref)
            d = np.mean(err2 - self.ref_var[m], axis=-1)
            pixel_se = float(np.std(d) / math.sqrt(d.size))
        k = len(per_seed)
        corr = max(float(np.mean(per_seed)), 1e-30)
        se = float(np.std(per_seed, ddof=1) / math.sqrt(k)) if k > 1 else pixel_se
        return dict(run=level.first, spp=level.spp, seconds=level.seconds, mse=corr + var_ref, var_ref=var_ref,
                    mse_corr=corr, rse=se / corr, seeds=k, per_seed=per_seed,
                    eff=1.0 / (corr * max(level.seconds, 1e-3)), tmin=level.times[0], tmax=level.times[-1],
                    times=level.times, process=level.process, rays_per_sample=level.rays_per_sample)

    @property
    def ref_spp(self):
        return sum(h.spp for h in self.halves)

    @property
    def ref_seconds(self):
        return sum(h.seconds for h in self.halves)


def cross_check(dref, cref, mask, block=8):
    """Dermis vs Cycles references over the object: per-channel means, relative RMSE, the
    correlation of the two images, and block means (block x block pixels fully inside)."""
    m = mask
    dm, cm = dref[m].mean(axis=0), cref[m].mean(axis=0)
    rrmse = math.sqrt(float(np.mean((dref - cref)[m] ** 2))) / float(cref[m].mean())
    dl, cl = dref[m].mean(axis=-1), cref[m].mean(axis=-1)
    corr = float(np.corrcoef(dl, cl)[0, 1])
    h, w = m.shape
    rel = []
    for y in range(0, h - block + 1, block):
        for x in range(0, w - block + 1, block):
            if m[y:y + block, x:x + block].all():
                a = dref[y:y + block, x:x + block].mean()
                b = cref[y:y + block, x:x + block].mean()
                rel.append((a - b) / b)
    rel = np.array(rel) if rel else np.zeros(1)
    # The mirror image: if the twins were mirrored, this correlation would be the higher one.
    corr_mirror = float(np.corrcoef(dref[m].mean(axis=-1), cref[:, ::-1][m].mean(axis=-1))[0, 1])
    return dict(mean_d=dm, mean_c=cm, ratio=dm / cm, rrmse=rrmse, corr=corr, corr_mirror=corr_mirror,
                blocks=len(rel), block_med=float(np.median(np.abs(rel))), block_max=float(np.max(np.abs(rel))),
                block_mean=float(np.mean(rel)))


def make_mask(args, sc, work):
    path = os.path.join(work, "mask.pbrt")
    with open(path, "w") as f:
        f.write(pbrt_writer.mask_text(sc))
    out = os.path.join(work, "mask.exr")
    render.render(args.dermis, path, out, spp=16, threads=args.threads)
    cov = read_exr(out).rgb[..., 0]
    return cov > 0.999  # fully covered pixels only


def make_highlights(args, sc, work, mask):
    """The pixels of `mask` that show a light's mirror image in the object (the object as a
    smooth mirror with its boundary's Fresnel reflectance, lit by the quad lights alone,
    pbrt_writer.highlight_text; 1024 spp), widened by one pixel. Such a pixel's noise is the
    share of its area the mirror image covers, whatever the subsurface method: in the
    twenty-second family run, the 17 highlight pixels of the key-lit spheres (of 3710) held
    12-53 % of Dermis' squared error over the object at 64 spp and 58-91 % of Cycles', and 3
    of the fin's 2310 held 96 % of Dermis' on f12's disk (docs/results/results-vs-cycles.md, the
    findings of the thirty-ninth session). None where the object shows no light's image.
    """
    text = pbrt_writer.highlight_text(sc, 1024)
    if text is None:
        return None
    path = os.path.join(work, "highlights.pbrt")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(work, "highlights.exr")
    render.render(args.dermis, path, out, threads=args.threads)
    seen = read_exr(out).rgb.max(axis=-1) > 0
    wide = seen.copy()
    wide[1:] |= seen[:-1]
    wide[:-1] |= seen[1:]
    wide[:, 1:] |= seen[:, :-1]
    wide[:, :-1] |= seen[:, 1:]
    return wide & mask


# ------------------------------------------------------------------ per scene

def run_scene(args, name):
    sc = json.loads(json.dumps(S.SCENES[name]))  # a copy
    if sc.get("environment"):  # its two maps, written into the run's folder once
        environments.attach(sc["environment"], os.path.join(args.out, "environments"))
    if sc["material"]["kind"] == "grid":  # its .vdb for Blender (grid_twin.py)
        grid_twin.attach(sc["material"], os.path.join(args.out, "grids"))
    if args.res:
        sc["res"] = list(args.res)
    if sc["material"]["kind"] == "subsurface":
        sc["material"]["cycles_radius"] = S.cycles_radius(sc["material"])
        if "checker" in sc["material"]:
            c = sc["material"]["checker"]
            c["cycles_radius"] = S.cycles_radius(dict(sc["material"], reflectance=c["reflectance"]))
    work = os.path.join(args.out, name)
    os.makedirs(work, exist_ok=True)
    log(f"[{name}] {sc['res'][0]}x{sc['res'][1]}")
    mask = make_mask(args, sc, work)
    highlights = make_highlights(args, sc, work, mask)
    log(f"  mask: {int(mask.sum())} pixels, {0 if highlights is None else int(highlights.sum())} of them highlights")
    half = args.reference_time * sc["ref_factor"] / 2 if args.reference_time else None
    rspp = int(args.reference_spp * sc["ref_factor"]) // 2 if args.reference_spp else None

    dermis, prepared = {}, {}  # prepared: each variant's references and scene file, before its sweep
    for i, (label, extra) in enumerate(sc["dermis"].items()):
        scene_file = os.path.join(work, f"dermis-{i}.pbrt")
        with open(scene_file, "w") as f:
            f.write(pbrt_writer.scene_text(sc, label, extra))
        log(f"  dermis '{label}': {scene_file}")
        halves = [dermis_render(args, scene_file, os.path.join(work, f"dermis-{i}-ref{k}.exr"), spp=rspp, seconds=half,
                                seed=1000 + k, res=sc["res"]) for k in (1, 2)]
        prepared[label] = (halves, scene_file)

    # The sweeps of both renderers interleaved: each Cycles render of (spp, seed) is run
    # right after Dermis' renders of the same (spp, seed), by the Blender process
    # (blender_scene.py runs them), so that a slow spell of the shared machine falls on
    # both renderers' times rather than on one's (the fifteenth family run: for unchanged
    # estimators, one renderer's times moved 0.7-1.4x between runs, timed half a minute
    # apart). The references, whose times are not compared, are rendered before.
    log("  cycles, the sweeps of both renderers interleaved")
    renders = [dict(out=os.path.join(work, f"cycles-ref{k}.exr"), spp=rspp or HUGE_SPP, seed=1000 + k,
                    time_limit=half or 0.0) for k in (1, 2)]
    for n, k in zip(args.spp, args.seeds):
        for seed in range(1, k + 1):
            before = []
            for i, (label, (_, scene_file)) in enumerate(prepared.items()):
                out = os.path.join(work, f"dermis-{i}-{n}spp-s{seed}.exr")
                before.append(dict(label=label, out=out, cmd=dermis_command(args, scene_file, out, spp=n, seed=seed)))
            renders.append(dict(out=os.path.join(work, f"cycles-{n}spp-s{seed}.exr"), spp=n, seed=seed,
                                dermis_before=before))
    runs, info, cmd, dermis_runs = cycles_renders(args, sc, renders, work)
    levels, at = [], 2
    for k in args.seeds:
        levels.append(Level(runs[at:at + k]))
        at += k
    cycles = Family("Cycles", runs[:2], levels, mask, highlights)
    cycles.cmd = cmd
    for label, (halves, scene_file) in prepared.items():
        sweep, at = [], 0
        mine = [r for r in dermis_runs if r["label"] == label]
        for k in args.seeds:
            sweep.append(Level([dermis_result(args, render.Finished(r["cmd"], r["returncode"], r["stderr"], r["wall"]),
                                              r["out"], scene_file, sc["res"]) for r in mine[at:at + k]]))
            at += k
        dermis[label] = Family(label, halves, sweep, mask, highlights)
        dermis[label].scene_file = scene_file

    first = next(iter(dermis.values()))
    xc = cross_check(first.ref, cycles.ref, mask)
    xcs = {label: cross_check(f.ref, cycles.ref, mask) for label, f in dermis.items()}
    if len(dermis) > 1:  # Dermis variants against each other (same physics)
        labels = list(dermis)
        xcs[f"{labels[1]} vs {labels[0]}"] = cross_check(dermis[labels[1]].ref, dermis[labels[0]].ref, mask)
    log(f"  cross-check (Dermis '{first.label}' vs Cycles references): mean ratio "
        + ", ".join(f"{v:.3f}" for v in xc["ratio"]) + f"; rel. RMSE {xc['rrmse']:.3f}; correlation {xc['corr']:.3f} "
        f"(mirrored {xc['corr_mirror']:.3f}); 8x8 blocks |rel diff| median {xc['block_med']:.3f} max {xc['block_max']:.3f}")
    for label, f in dermis.items():
        for rd, rc in zip(f.rows, cycles.rows):
            log(f"  {rd['spp']:.0f} spp: Dermis '{label}' {rd['seconds']:.2f} s MSE {rd['mse_corr']:.3g} "
                f"({rd['rays_per_sample'] or 0:.1f} rays/sample)  |  Cycles "
                f"{rc['seconds']:.2f} s MSE {rc['mse_corr']:.3g}  ->  efficiency ratio {rd['eff'] / rc['eff']:.2f}")
    return dict(name=name, sc=sc, mask=mask, dermis=dermis, cycles=cycles, info=info, xcs=xcs, work=work,
                highlights=0 if highlights is None else int(highlights.sum()))


# ------------------------------------------------------------------ images

def lum(x):
    return x @ np.array([0.2126, 0.7152, 0.0722])


def contact_sheet(res, spp, out):
    """Dermis ref | Cycles ref | |Dermis - its ref| | |Cycles - its ref| at `spp` (the two
    error maps on one common scale: the 99th percentile of both over the object)."""
    from PIL import Image
    w = res["work"]
    d = next(iter(res["dermis"].values()))
    c = res["cycles"]
    i = [r["spp"] for r in d.rows].index(spp) if spp in [r["spp"] for r in d.rows] else len(d.rows) // 2
    ed = np.abs(lum(d.rows[i]["run"].load() - d.ref))
    ec = np.abs(lum(c.rows[i]["run"].load() - c.ref))
    m = res["mask"]
    scale = max(np.percentile(np.concatenate([ed[m], ec[m]]), 99), 1e-12)
    pngs = []
    for k, img in enumerate([d.ref, c.ref]):
        p = os.path.join(w, f"sheet-{k}.png")
        write_png(img, p)
        pngs.append(p)
    for k, e in enumerate([ed, ec]):
        p = os.path.join(w, f"sheet-err{k}.png")
        g = (np.clip(e / scale, 0, 1) ** (1 / 2.2) * 255 + 0.5).astype(np.uint8)
        Image.fromarray(np.stack([g] * 3, axis=-1), "RGB").save(p)
        pngs.append(p)
    n = int(d.rows[i]["spp"])
    strip([Image.open(p).convert("RGB") for p in pngs], out,
          ["Dermis ref", "Cycles ref", f"|Dermis-ref| {n}spp", f"|Cycles-ref| {n}spp"])
    return n, scale


# ------------------------------------------------------------------ report

def v3(v, f="{:.4f}"):
    return "(" + ", ".join(f.format(x) for x in v) + ")"


def gmean(v):
    return math.exp(sum(math.log(max(x, 1e-30)) for x in v) / len(v))


def variant_kind(label):
    """walk, disk, lines (the sphere lines) or volumetric: the method family of a Dermis
    variant's label."""
    if label.startswith("volpath") or label == "volumetric":
        return "volumetric"
    if label.startswith("sphere-lines"):
        return "lines"
    return "walk" if label.startswith("randomwalk") else "disk"


def family_entries(results):
    """One entry per (family configuration, Dermis variant): the efficiency ratios in both
    conventions (geometric mean over the sweep and its lowest sample count), the cost and
    the MSE per sample against Cycles, and Dermis' rays per sample."""
    out = []
    for r in results:
        fam = r["sc"].get("family")
        if not fam:
            continue
        c = r["cycles"]
        for i, (label, f) in enumerate(r["dermis"].items()):
            obj = [d["eff"] / k["eff"] for d, k in zip(f.rows, c.rows)]
            img = [d["eff"] / k["eff"] for d, k in zip(f.rows_image, c.rows_image)]
            sub = [d["eff"] / k["eff"] for d, k in zip(f.rows_sub, c.rows_sub)]
            t = lambda x: max(x, 1e-3)  # noqa: E731  (as in the efficiency)
            cost = [(t(d["seconds"]) / d["spp"]) / (t(k["seconds"]) / k["spp"]) for d, k in zip(f.rows, c.rows)]
            mse = [(d["mse_corr"] * d["spp"]) / (k["mse_corr"] * k["spp"]) for d, k in zip(f.rows, c.rows)]
            rays = [d["rays_per_sample"] for d in f.rows if d.get("rays_per_sample")]
            out.append(dict(fam, scene=r["name"], label=label, kind=variant_kind(label),
                            default=(i == 0 and variant_kind(label) != "disk"),  # the walk; a medium's first
                            obj=gmean(obj), obj_min=min(obj), img=gmean(img), img_min=min(img),
                            sub=gmean(sub), highlights=r.get("highlights", 0),
                            cost=gmean(cost), mse=gmean(mse), rays=float(np.median(rays)) if rays else float("nan")))
    return out


def family_targets(entries, convention="obj"):
    """Issue 40's targets, evaluated on the run (object convention, the primary one; or `sub`,
    the object less its highlights)."""
    d = [e[convention] for e in entries if e["default"]]
    disk = [e[convention] for e in entries if e["kind"] == "disk"]
    vol = [e[convention] for e in entries if e["kind"] == "volumetric"]
    t = []
    if d:
        t.append(("default method: geometric mean >= 3", gmean(d), gmean(d) >= 3))
        t.append(("default method: every configuration >= 2", min(d), min(d) >= 2))
    if disk:
        t.append(("disk: geometric mean >= 1.5 (its Cycles counterpart, Christensen-Burley)", gmean(disk),
                  gmean(disk) >= 1.5))
    if vol:
        t.append(("volumetric: every medium >= 2", min(vol), min(vol) >= 2))
    return t


def probe_cost_targets(entries):
    """Item 2 of issue 40: each probe method's cost per camera sample at or below Cycles'
    Christensen-Burley (render stage), on every configuration: the highest ratio."""
    t = []
    for kind, name in (("disk", "disk"), ("lines", "sphere lines")):
        cost = [e["cost"] for e in entries if e["kind"] == kind]
        if cost:
            t.append((f"{name}: cost per sample <= Cycles' on every configuration (highest; lowest {min(cost):.3g})",
                      max(cost), max(cost) <= 1))
    return t


def config_set(entries):
    """Which set the entries are: the held-out configurations (h01 ...), the textured ones
    (t01 ...) or the family's."""
    for prefix, name in (("h", "heldout"), ("t", "textured"), ("c", "closeup"), ("l", "lighting")):
        if all(e["config"].startswith(prefix) for e in entries):
            return name
    return "family"


SET_TITLES = {"family": "scene family", "heldout": "held-out configurations", "textured": "textured configurations",
              "closeup": "close-ups", "lighting": "lighting axis"}


def family_chart(entries, path):
    """Efficiency ratio per configuration and method, both conventions (log scale)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = [f"{e['config']} {e['geometry']} {e['balance']} {'' if e['scale'] is None else format(e['scale'], 'g')} "
             f"{e['albedo']} — {e['kind']}" for e in entries]
    y = np.arange(len(entries))[::-1]
    fig, ax = plt.subplots(figsize=(8.5, 0.28 * len(entries) + 1.4))
    colors = {"walk": "#3b7dd8", "disk": "#e08a2e", "lines": "#b05cc4", "volumetric": "#4aa35a"}
    ax.barh(y + 0.2, [e["obj"] for e in entries], height=0.38, color=[colors[e["kind"]] for e in entries],
            label="object pixels, render-stage time")
    ax.barh(y - 0.2, [e["img"] for e in entries], height=0.38, color=[colors[e["kind"]] for e in entries],
            alpha=0.45, hatch="//", label="whole image, whole-process time")
    ax.scatter([e["sub"] for e in entries], y + 0.2, marker="|", s=60, color="k", zorder=3,
               label="object less its highlights, render-stage time")
    for x, style in ((1, "-"), (2, ":"), (3, "--")):
        ax.axvline(x, color="k", lw=0.8, ls=style)
    ax.set_xscale("log")
    ax.set_yticks(y)
    ax.set_yticklabels(names, fontsize=7)
    ax.set_xlabel("efficiency Dermis ÷ Cycles, 1 / (MSE × time), geometric mean over the sweep")
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title(f"Dermis vs Cycles on the {SET_TITLES[config_set(entries)]} "
                 "(solid: walk blue, disk orange, sphere lines purple, volumetric green)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_family_section(w, entries, image_dir, rel_images):
    if config_set(entries) == "heldout":
        w("## The held-out configurations: efficiency Dermis ÷ Cycles per configuration\n")
        w("Configurations that are not in the family and were never used to tune Dermis (`bench/vs_cycles/scenes.py`, "
          "HELDOUT_CONFIGS: other albedos, scales and light balances on the family's geometries and lights).\n")
    elif config_set(entries) == "textured":
        w("## The textured configurations: efficiency Dermis ÷ Cycles per configuration\n")
        w("The reflectance a 3D checkerboard of the material's and 0.6 × it, the mfp constant, on the family's "
          "geometries and lights (`bench/vs_cycles/scenes.py`, TEXTURED_CONFIGS; Cycles' Subsurface Radius follows "
          "each square's reflectance through a second checker). Never used to tune Dermis.\n")
    elif config_set(entries) == "lighting":
        w("## The lighting axis: efficiency Dermis ÷ Cycles per configuration\n")
        w("Two HDR environments and an area light of three sizes, each alone, on one family configuration per "
          "geometry and on three media (`bench/vs_cycles/scenes.py`, LIGHTINGS, LIGHTING_CONFIGS, LIGHTING_MEDIA; "
          "issue 66), chosen before any tuning for them. Per lighting below: a table and a chart.\n")
    elif config_set(entries) == "closeup":
        w("## The close-ups: efficiency Dermis ÷ Cycles per configuration\n")
        w("The family's twelve configurations, each camera's field of view narrowed until the object covers about "
          "three quarters of the frame (`bench/vs_cycles/scenes.py`, CLOSEUP_FOV): the object's samples are most of "
          "the time, where in the family most pixels see the sky alone. Never used to tune Dermis.\n")
    else:
        w("## The scene family: efficiency Dermis ÷ Cycles per configuration\n")
    w("Configurations chosen before any tuning (`bench/vs_cycles/scenes.py`, FAMILY_CONFIGS or HELDOUT_CONFIGS), "
      "the same renderer settings everywhere. **obj**: MSE over the object's pixels, render-stage time (the primary convention); "
      "**img**: MSE over the whole image (silhouettes included), time of the whole process (`dermis render` from "
      "start to exit; Cycles' render operator: sync + render + EXR write); **sub**: MSE over the object's pixels "
      "less those that show a light's mirror image (the highlights: the object rendered as a smooth mirror with its "
      "boundary's Fresnel reflectance under the quad lights alone, non-zero pixels widened by one; `hl` of them), "
      "render-stage time: the subsurface's own noise, where a highlight's pixel-area noise, the same whatever the "
      "subsurface method, can hold most of the object's MSE. Each: geometric mean over the sample "
      "counts, and the lowest of them in brackets. **cost/sample** and **MSE×spp**: Dermis ÷ Cycles (render stage, "
      "object), geometric mean over the sample counts. **rays/sample**: Dermis' rays traced per camera sample "
      "(median over the sweep; Cycles 3.4 does not report its ray count).\n")
    w("| config | geometry | light | mfp/size | albedo | method | obj | img | sub (hl) | cost/sample | MSE×spp "
      "| rays/sample |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for e in entries:
        sc = "—" if e["scale"] is None else f"{e['scale']:g}"
        w(f"| {e['config']} | {e['geometry']} | {e['balance']} | {sc} | {e['albedo']} | {e['kind']}"
          f"{' (default)' if e['default'] else ''} | **{e['obj']:.3g}** [{e['obj_min']:.3g}] | {e['img']:.3g} "
          f"[{e['img_min']:.3g}] | {e['sub']:.3g} ({e['highlights']}) | {e['cost']:.3g} | {e['mse']:.3g} "
          f"| {e['rays']:.1f} |")
    w("")
    w("Targets of issue 40 (object convention):\n")
    for name, value, ok in family_targets(entries):
        w(f"- {name}: **{value:.3g}** — {'met' if ok else 'not met'}")
    for name, value, ok in probe_cost_targets(entries):
        w(f"- {name}: **{value:.3g}** — {'met' if ok else 'not met'}")
    img = [e["img"] for e in entries if e["default"]]
    if img:
        w(f"- (whole-image convention: default method geometric mean {gmean(img):.3g}, lowest {min(img):.3g})")
    w("")
    w("The same, object less its highlights (**sub**; not the issue's convention, shown so that what a highlight's "
      "pixel-area noise decides is visible):\n")
    for name, value, ok in family_targets(entries, "sub"):
        w(f"- {name}: {value:.3g} — {'would be met' if ok else 'would not be met'}")
    w("")
    os.makedirs(image_dir, exist_ok=True)
    family_chart(entries, os.path.join(image_dir, "family-efficiency.png"))
    w(f"![efficiency ratio per configuration]({rel_images}/family-efficiency.png)\n")
    if config_set(entries) == "lighting":
        write_per_lighting(w, entries, image_dir, rel_images)


def write_per_lighting(w, entries, image_dir, rel_images):
    """Issue 66, item 4: per lighting, every method's efficiency against Cycles (a table and a
    chart), and for the walk its MSE per sample and cost per sample against Cycles'."""
    w("## Per lighting\n")
    w("| lighting | walk (default): geometric mean [lowest] | walk: MSE × spp ÷ Cycles' | walk: cost per sample "
      "÷ Cycles' | disk | volumetric path tracer |")
    w("|---|---|---|---|---|---|")
    lightings = [b for b in S.LIGHTINGS if any(e["balance"] == b for e in entries)]

    def summary(xs):
        return f"{gmean(xs):.3g} [{min(xs):.3g}]" if xs else "—"
    for b in lightings:
        es = [e for e in entries if e["balance"] == b]
        walk = [e for e in es if e["kind"] == "walk"]
        w(f"| {b} | {summary([e['obj'] for e in walk])} | {summary([e['mse'] for e in walk])} | "
          f"{summary([e['cost'] for e in walk])} | {summary([e['obj'] for e in es if e['kind'] == 'disk'])} | "
          f"{summary([e['obj'] for e in es if e['kind'] == 'volumetric'])} |")
    w("")
    for b in lightings:
        es = [e for e in entries if e["balance"] == b]
        w(f"### {b}\n")
        w("| config | geometry | albedo | method | obj | img | cost/sample | MSE×spp |")
        w("|---|---|---|---|---|---|---|---|")
        for e in es:
            w(f"| {e['config']} | {e['geometry']} | {e['albedo']} | {e['kind']}{' (default)' if e['default'] else ''} "
              f"| **{e['obj']:.3g}** [{e['obj_min']:.3g}] | {e['img']:.3g} [{e['img_min']:.3g}] | {e['cost']:.3g} "
              f"| {e['mse']:.3g} |")
        w("")
        family_chart(es, os.path.join(image_dir, f"lighting-{b}.png"))
        w(f"![efficiency ratio under {b}]({rel_images}/lighting-{b}.png)\n")


def write_report(args, results, info, total, path, image_dir, argv):
    os.makedirs(image_dir, exist_ok=True)
    commit = args.dermis_commit or provenance.git_commit()
    dermis_version = provenance.dermis_version(args.dermis)
    cpu = provenance.cpu_model()
    rel_images = os.path.relpath(image_dir, os.path.dirname(path))
    o = []
    w = o.append
    w("# Dermis vs Blender Cycles at equal error\n")
    w(f"Produced by `/usr/bin/python3 -m bench.vs_cycles.run {shlex.join(argv)}` on {datetime.date.today().isoformat()} "
      f"in {total / 60:.1f} min. Dermis: `{args.dermis}` ({dermis_version}), code at commit `{commit}`. "
      f"Blender {info['blender']} (Debian package), Cycles on the CPU. Machine: {cpu}, {os.cpu_count()} cores, "
      f"{args.threads} render threads in both renderers.\n")
    if args.note:
        w(f"**Note.** {args.note}\n")
    w("## How it is measured\n")
    w("- Each scene is described once (`bench/vs_cycles/scenes.py`) and written as a pbrt-v4 file for Dermis "
      "(`pbrt_writer.py`) and built in Blender by `blender_scene.py` (one Blender process per scene).")
    w("- **Reference** per renderer: two independent halves (seeds 1001, 1002) "
      + (f"of {args.reference_time / 2:g} s each × the scene's factor (1; `calibration` 0.25) "
         "(`dermis render --time-limit`, Cycles `time_limit`)"
         if args.reference_time else f"of {args.reference_spp // 2} spp each")
      + "; their difference estimates the reference's own variance, which is subtracted from every MSE "
        "(E(A−R)² = Var A + bias² + Var R; the method of `bench/sss_methods.py`).")
    w(f"- **Sweep**: {', '.join(f'{n} samples per pixel with seeds 1–{k}' if k > 1 else f'{n} with seed 1' for n, k in zip(args.spp, args.seeds))}, "
      "the same seeds in both renderers, interleaved: each Cycles render of a sample count and seed runs right "
      "after Dermis' renders of the same (the Blender process runs them), so that a slow spell of the shared machine "
      "falls on both renderers' times (since the thirty-third session; before, Dermis' whole sweep ran first). "
      "**MSE** over the pixels fully "
      "covered by the object (a Dermis render of the object as a unit emitter; coverage > 0.999), mean over R, G, B, "
      "against the renderer's OWN reference: it measures noise, not the differences between the renderers' models. "
      "A sample count's MSE is the mean of its seeds' MSEs: an estimate of the expected MSE. One image's MSE reads low "
      "where the error is heavy-tailed (most images miss the rare bright paths that the mean contains), and more so "
      "for the renderer with the heavier tail, so a single seed is not a fair comparison.")
    w("- **Time**: Dermis — the time `dermis render` reports for the render stage (`render_image`: tiles, "
      "all samples; excludes parsing, scene/BVH build and the albedo-inversion table, image writing; printed "
      "in milliseconds; ≈ marks an older build's 0.1 s figure replaced by wall time minus load time). Cycles — its render time as Cycles logs it (`--debug-cycles --verbose 2`: "
      "\"Render time (without synchronization)\", path tracing only; excludes scene export, BVH, shader compilation), "
      "to the microsecond; the EXR stamp `cycles.ViewLayer.render_time` holds the same time truncated to 10 ms "
      "(checked against it for every render), which read Cycles up to 10 ms faster than it was (bench/vs_cycles/cycles_log.py). The wall time of "
      "`bpy.ops.render.render()` (sync + render + EXR write) is listed too.")
    w("- **Time** of a sample count: the median of its seeds' render times, with the fastest and slowest in "
      "brackets. A shared machine's run-to-run spread is as large as "
      "some of the differences measured here, so it is shown rather than hidden.")
    w("- **Efficiency** = 1 / (MSE × time); the ratio Dermis ÷ Cycles is the speed-up of Dermis at equal error "
      "(> 1: Dermis reaches the same noise in less time). ± is one standard error from the spread of the seeds' "
      "MSEs (both renderers' in quadrature; with one seed, from the spread of the per-pixel squared errors, pixels "
      "taken as independent); [lo–hi] is the ratio at the least and the most favourable "
      "pairing of the two renderers' fastest and slowest render times.\n")

    w("## Summary: efficiency Dermis ÷ Cycles\n")
    w("| scene | Dermis variant | " + " | ".join(f"{n} spp" for n in args.spp) + " | geometric mean |")
    w("|---|---|" + "---|" * (len(args.spp) + 1))
    for r in results:
        for label, f in r["dermis"].items():
            ratios = [rd["eff"] / rc["eff"] for rd, rc in zip(f.rows, r["cycles"].rows)]
            errs = [q * math.hypot(rd["rse"], rc["rse"]) for q, rd, rc in zip(ratios, f.rows, r["cycles"].rows)]
            # The ratio at the least and the most favourable pairing of the seeds' times.
            t = lambda x: max(x, 1e-3)  # as in the efficiency
            pairs = list(zip(ratios, f.rows, r["cycles"].rows))
            lo = [q * t(rd["seconds"]) / t(rd["tmax"]) * t(rc["tmin"]) / t(rc["seconds"]) for q, rd, rc in pairs]
            hi = [q * t(rd["seconds"]) / t(rd["tmin"]) * t(rc["tmax"]) / t(rc["seconds"]) for q, rd, rc in pairs]
            gmean = lambda v: math.exp(sum(math.log(x) for x in v) / len(v))
            gm = gmean(ratios)
            w(f"| {r['name']} | {label} | " + " | ".join(f"{q:.3g} ± {e:.2g} [{a:.3g}–{b:.3g}]"
                                                         for q, e, a, b in zip(ratios, errs, lo, hi))
              + f" | **{gm:.3g}** [{gmean(lo):.3g}–{gmean(hi):.3g}] |")
    w("")

    entries = family_entries(results)
    if entries:
        write_family_section(w, entries, image_dir, rel_images)

    w("## Per scene\n")
    for r in results:
        sc = r["sc"]
        m = sc["material"]
        w(f"### {r['name']}\n")
        w(sc["checks"] + "\n")
        if m["kind"] == "subsurface":
            w(f"Dermis: `subsurface` reflectance {v3(m['reflectance'], '{:g}')}, mfp {v3(m['mfp'], '{:g}')} mm, "
              f"eta {m['eta']:g}, g {m['g']:g}{', entry lambertian' if m['method'] == 'randomwalk' else ''}. "
              f"Cycles: Principled `{'RANDOM_WALK' if m['method'] == 'randomwalk' else 'BURLEY'}`, "
              f"Base/Subsurface Color = reflectance, Subsurface 1, Subsurface Radius "
              f"{v3(m['cycles_radius'], '{:.3f}')} (converted, see scenes.py), Subsurface IOR {m['eta']:g}, "
              f"Anisotropy {m['g']:g}, Specular {S.principled_specular(m['eta']):.3f} (F0 of eta {m['eta']:g}), "
              "Roughness 0."
              + (f" Checkerboard squares of reflectance {v3(m['checker']['reflectance'], '{:g}')}: Cycles' Checker "
                 f"texture (object space, scale 1/{m['checker']['cell']:g} mm) gives their colour and Subsurface Radius "
                 f"{v3(m['checker']['cycles_radius'], '{:.3f}')}; Dermis' `checkerboard` (dimension 3, cells "
                 f"{m['checker']['cell']:g} mm)." if "checker" in m else "") + "\n")
        elif m["kind"] == "medium":
            w(f"Medium: sigma_a {v3(m['sigma_a'], '{:g}')}, sigma_s {v3(m['sigma_s'], '{:g}')} per mm, HG g {m['g']:g}; "
              + ("index-matched boundary." if m["boundary"] == "matched" else f"smooth dielectric, IOR {m['eta']:g}.") + "\n")
        elif m["kind"] == "grid":
            w(f"Grid medium: {m['n']}^3 densities (grid_twin.py, seed {m['seed']}) over the box "
              f"[{m['box'][0]:g}, {m['box'][1]:g}]^3 mm, sigma_a {v3(m['sigma_a'], '{:g}')}, sigma_s "
              f"{v3(m['sigma_s'], '{:g}')} per mm per unit density, HG g {m['g']:g}; index-matched.\n")
        w("| renderer | spp | seeds | time (s) | other time (s) | MSE (ref. noise removed) | lowest–highest seed | ref. variance removed | efficiency |")
        w("|---|---|---|---|---|---|---|---|---|")
        fams = list(r["dermis"].items()) + [("Cycles", r["cycles"])]
        for label, f in fams:
            for row in f.rows:
                run = row["run"]
                other = (f"process {run.wall:.1f}" if label != "Cycles"
                         else f"stamp {run.info['stamp']:.2f}, sync {run.info['sync']:.3f}, operator {run.wall:.2f}")
                approx = "≈" if run.info.get("approx") else ""
                spread = f" ({row['tmin']:.3f}–{row['tmax']:.3f})" if len(row["times"]) > 1 else ""
                w(f"| {'Dermis ' + label if label != 'Cycles' else 'Cycles'} | {row['spp']:.0f} | {row['seeds']} | {approx}{row['seconds']:.3f}{spread} | "
                  f"{other} | {row['mse_corr']:.4g} ± {row['mse_corr'] * row['rse']:.2g} | "
                  f"{min(row['per_seed']):.3g}–{max(row['per_seed']):.3g} | {row['var_ref']:.3g} | "
                  f"{row['eff']:.4g} |")
        refs = "; ".join(f"{'Dermis ' + label if label != 'Cycles' else 'Cycles'} {f.ref_spp:.0f} spp in {f.ref_seconds:.1f} s"
                         for label, f in fams)
        w(f"\nReferences (two halves together): {refs}.\n")
        w("Cross-check of the references over the object (mean R, G, B; relative RMSE = RMS difference / mean; "
          "correlation of the luminance images, and of one with the other mirrored; |relative difference| of 8×8-pixel "
          "block means):\n")
        for label, x in r["xcs"].items():
            name = label if " vs " in label else f"Dermis {label} vs Cycles"
            w(f"- {name}: means {v3(x['mean_d'])} vs {v3(x['mean_c'])}, ratio {v3(x['ratio'], '{:.3f}')}; "
              f"relative RMSE {x['rrmse']:.3f}; correlation {x['corr']:.4f} (mirrored {x['corr_mirror']:.4f}); "
              f"blocks ({x['blocks']}): median {x['block_med']:.3f}, max {x['block_max']:.3f}, mean signed "
              f"{x['block_mean']:+.3f}.")
        n, scale = contact_sheet(r, args.sheet_spp, os.path.join(image_dir, f"{r['name']}.png"))
        w(f"\n![{r['name']}]({rel_images}/{r['name']}.png)\n")
        w(f"Error maps: luminance of |image − own reference| at {n} spp, both on one scale (white = {scale:.3g}, "
          "gamma 2.2).\n")

    w("## Commands\n")
    r0 = results[0]
    f0 = next(iter(r0["dermis"].values()))
    w("Dermis (per render; references with `--spp 1000000 --time-limit T/2 --seed 1001|1002`):\n")
    w(f"```\n{f0.rows[0]['run'].info['cmd']}\n```\n")
    w(f"Cycles (per scene; the job file lists the renders):\n\n```\n{r0['cycles'].cmd}\n```\n")
    w("## Cycles settings (read back from Blender)\n")
    w("| setting | value |\n|---|---|")
    for k, v in info.items():
        w(f"| {k} | {v} |")
    w("\nAlso: world Background colour = sky radiance with strength 1; the key light is a mesh quad with an "
      "Emission shader of strength 1 × radiance on its front face (Geometry › Backfacing mixes in a black "
      "emission: one-sided, as Dermis' `twosided false`), material Multiple Importance on; colour management "
      "Standard / None / exposure 0 / gamma 1, EXR 32-bit float (scene-linear, checked by the `calibration` "
      "scene); volume materials `homogeneous_volume` on, volume sampling Multiple Importance; Glass BSDF "
      "distribution Sharp.\n")
    docs_page.write_page(path, "\n".join(o), FINDINGS_MARKER)  # the hand-written discussion below is kept
    log(f"wrote {path}")


FINDINGS_MARKER = "<!-- findings: written by hand below this line; kept when run.py rewrites the report -->"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--set", choices=["family", "heldout", "textured", "closeup", "lighting", "classic"],
                    default="family",
                    help="family (default): the scene family of issue 40, chosen before tuning (scenes.FAMILY); "
                         "heldout: eight other configurations on the family's geometries, never used for tuning "
                         "(scenes.HELDOUT; the family's settings, report docs/results/results-vs-cycles-heldout.md); "
                         "textured: six configurations whose reflectance is a checkerboard (scenes.TEXTURED; the "
                         "family's settings, report docs/results/results-vs-cycles-textured.md); "
                         "closeup: the family's twelve configurations framed close, the object about three quarters "
                         "of the frame (scenes.CLOSEUP; report docs/results/results-vs-cycles-closeup.md); "
                         "lighting: the lighting axis of issue 66, two HDR environments and an area light of three "
                         "sizes on one configuration per geometry and on three media (scenes.LIGHTING; report "
                         "docs/results/results-vs-cycles-lighting.md); "
                         "classic: the seven scenes of issue 15")
    ap.add_argument("--scenes", default="", help=f"comma-separated scene names instead of --set, from "
                    f"{', '.join(S.SCENES)}")
    ap.add_argument("--spp", default="", help="sweep sample counts (default: family 16,64; classic 16,64,256)")
    ap.add_argument("--seeds", default="",
                    help="seeds per sweep sample count (one number, or one per --spp; default: family 6,4; classic "
                         "8,8,4): the MSE is the mean over the seeds, the time the median")
    ap.add_argument("--reference-time", type=float, default=0.0,
                    help="seconds per reference per renderer (two halves; default: family 16, classic 40)")
    ap.add_argument("--reference-spp", type=int, default=0, help="instead of --reference-time: spp per reference")
    ap.add_argument("--dermis", default=DERMIS)
    ap.add_argument("--dermis-sampler", default="",
                    help="pass `--sampler NAME` to dermis render (binaries from ffd318d on: sobol, independent); "
                    "default: the scene files' Sampler \"zsobol\" (Owen-scrambled Sobol' from ffd318d on; "
                    "older binaries have only independent random numbers)")
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default="/tmp/dermis-vs-cycles", help="scratch folder (scenes, EXRs, logs)")
    ap.add_argument("--res", type=lambda s: tuple(int(x) for x in s.lower().split("x")), help="override WxH")
    ap.add_argument("--sheet-spp", type=int, default=64, help="spp of the error maps in the contact sheets")
    ap.add_argument("--quick", action="store_true",
                    help="smoke test: 48x36 (classic: 64x64), spp 4,16, 2 seeds, 2 s references (classic: 4 s), "
                         "report in --out (not docs/)")
    ap.add_argument("--no-docs", action="store_true", help="write the report into --out instead of docs/")
    ap.add_argument("--dermis-commit", default="", help="the commit the Dermis binary was built from "
                    "(default: git rev-parse --short HEAD)")
    ap.add_argument("--note", default="", help="a sentence for the report (e.g. the state of the machine)")
    args = ap.parse_args()
    argv = sys.argv[1:]
    family = args.set in ("family", "heldout", "textured", "closeup", "lighting") and not args.scenes
    if not args.spp:
        args.spp = "4,16" if args.quick else "16,64" if family else "16,64,256"
    if not args.seeds:
        args.seeds = "2" if args.quick else "6,4" if family else "8,8,4"
    if not args.reference_time and not args.reference_spp:
        args.reference_time = (2.0 if family else 4.0) if args.quick else 16.0 if family else 40.0
    if args.quick:
        args.res = args.res or ((48, 36) if family else (64, 64))
        args.no_docs = True
        args.sheet_spp = 16
    args.spp = [int(x) for x in args.spp.split(",")]
    args.seeds = [int(x) for x in args.seeds.split(",")]
    if len(args.seeds) == 1:
        args.seeds *= len(args.spp)
    if len(args.seeds) != len(args.spp) or min(args.seeds) < 1:
        ap.error("--seeds: one number >= 1, or one per --spp")
    if args.reference_spp:
        args.reference_time = 0
    args.dermis = os.path.abspath(args.dermis)
    for _ in range(6):  # build/dermis may be being rebuilt by someone else: wait a little
        if os.path.exists(args.dermis):
            break
        log(f"{args.dermis} not found; waiting 30 s")
        time.sleep(30)
    else:
        sys.exit(f"{args.dermis} not found: build first (make build)")
    names = [n for n in args.scenes.split(",") if n] or list(
        {"family": S.FAMILY, "heldout": S.HELDOUT, "textured": S.TEXTURED, "closeup": S.CLOSEUP,
         "lighting": S.LIGHTING, "classic": S.DEFAULT_SCENES}[args.set])
    for n in names:
        if n not in S.SCENES:
            sys.exit(f"unknown scene {n}; known: {', '.join(S.SCENES)}")
    os.makedirs(args.out, exist_ok=True)
    nvar = sum(len(S.SCENES[n]["dermis"]) for n in names)
    if args.reference_time:
        ref_total = sum((len(S.SCENES[n]["dermis"]) + 1) * S.SCENES[n]["ref_factor"] * args.reference_time for n in names)
        log(f"planned: references {ref_total / 60:.1f} min "
            f"({nvar} Dermis variants + {len(names)} Cycles scenes x {args.reference_time:g} s x the scene's factor), plus the sweeps "
            f"({', '.join(map(str, args.spp))} spp each), masks and Blender start-up/sync")
    t0 = time.time()
    results, info = [], None
    for n in names:
        r = run_scene(args, n)
        results.append(r)
        info = r["info"]
        log(f"  elapsed {(time.time() - t0) / 60:.1f} min")
    total = time.time() - t0
    log(f"total wall time {total:.0f} s")
    if args.no_docs:
        write_report(args, results, info, total, os.path.join(args.out, "results-vs-cycles.md"),
                     os.path.join(args.out, "images"), argv)
    else:
        doc = "family" if args.scenes else args.set
        write_report(args, results, info, total, DOC[doc], IMAGES[doc], argv)


if __name__ == "__main__":
    main()
