#!/usr/bin/python3
"""Adaptive sampling against uniform sampling at equal time (issue 38).

For each scene: a converged reference (two uniform renders of --reference-spp with other
seeds; their difference gives the reference's own noise, which is taken out of every
MSE), then for each noise threshold and seed an adaptive render (at most --max-spp per
pixel) and a uniform render given the adaptive render's time (--time-limit). Reported:
the MSE of each against the reference at equal time, and the time uniform sampling needs
to reach the adaptive render's MSE (uniform MSE x time is constant: MSE ~ 1/samples).
Also: the time uniform sampling needs for its 99th-percentile pixel error (each render's
own estimate, the .exr's `error` channel) to reach the adaptive render's: what "a clean
picture sooner" means. Times are the render stage's (`dermis: wrote ... in X s`).

The scenes and settings are fixed here, before anything is measured (never per scene):
  demo      scenes/demo.pbrt (the bust, the random walk, sky + key light) at 128x128
  sphere    family configuration f01 of bench/vs_cycles (skin sphere, walk, sky + small key)
  medium    family configuration f13 (the index-matched medium, the volumetric path tracer)
thresholds 0.02 and 0.01 (Cycles' default), at most 1024 samples per pixel, the default minimum (32).

    /usr/bin/python3 -m bench.adaptive.run --out /tmp/adaptive [--quick]
"""
import argparse
import os
import sys
import time

import numpy as np

from bench.harness import render as dermis_render
from bench.harness.exr import read_exr
from bench.harness.paths import DERMIS, ROOT
from bench.harness.progress import log
from bench.vs_cycles import pbrt_writer
from bench.vs_cycles import scenes as vsc


def render(args, scene, out, seed, spp, threshold=None, seconds=None, reference=False):
    extra = []
    if threshold:
        extra += ["--noise-threshold", str(threshold)]
    if seconds:
        extra += ["--time-limit", f"{seconds:.3f}"]
    if not threshold:
        extra += ["--error-map"]
    if args.sampler and not reference:
        extra += ["--sampler", args.sampler]
    r = dermis_render.render(args.dermis, scene, out, spp=spp, res=args.res.get(scene) or None, seed=seed,
                             threads=args.threads, extra=extra)
    stats = dermis_render.render_stats(r.log)
    if not stats:
        sys.exit(f"no render time in the output of {' '.join(r.cmd)}:\n{r.log}")
    image = read_exr(out)
    return image.rgb, image.extra, stats.seconds


def mse(img, ref, ref_noise):
    """Mean over pixels and channels of the squared error, less the reference's own."""
    return float(np.mean((img - ref) ** 2)) - ref_noise


def rel_mse(img, ref):
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 1e-2)))


def scene_files(work, quick):
    demo = os.path.join(ROOT, "scenes", "demo.pbrt")
    out = {"demo": (demo, "128x128" if not quick else "64x64")}
    for name, key in (("sphere", "f01-sphere-both-0.1-skin-walk"), ("medium", "f13-medium-matched")):
        sc = vsc.SCENES[key]
        label, extra = next(iter(sc["dermis"].items()))
        path = os.path.join(work, f"{name}.pbrt")
        with open(path, "w") as f:
            f.write(pbrt_writer.scene_text(sc, label, extra))
        res = f"{sc['res'][0]}x{sc['res'][1]}" if not quick else f"{sc['res'][0] // 2}x{sc['res'][1] // 2}"
        out[name] = (path, res)
    return out


def sample_map_png(counts, rgb, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.2))
    img = np.clip(rgb, 0, 1) ** (1 / 2.2)
    axes[0].imshow(img)
    axes[0].set_title("adaptive render")
    im = axes[1].imshow(counts, cmap="magma")
    axes[1].set_title("samples per pixel")
    fig.colorbar(im, ax=axes[1], fraction=0.046)
    for a in axes:
        a.axis("off")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dermis", default=DERMIS)
    ap.add_argument("--out", required=True, help="work folder (renders, the report, the sample map)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--thresholds", default="0.02,0.01")
    ap.add_argument("--max-spp", type=int, default=1024)
    ap.add_argument("--reference-spp", type=int, default=4096, help="per reference half (two halves)")
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--scenes", default="demo,sphere,medium")
    ap.add_argument("--reuse-references", action="store_true", help="keep references already in --out")
    ap.add_argument("--sampler", help="sobol or independent for the compared renders (default: the scene's)")
    ap.add_argument("--quick", action="store_true", help="a smoke run: small images, 256 reference samples")
    args = ap.parse_args()
    if args.quick:
        args.reference_spp, args.max_spp, args.seeds, args.thresholds = 256, 128, 1, "0.1"
    os.makedirs(args.out, exist_ok=True)
    files = scene_files(args.out, args.quick)
    args.res = {path: res for path, res in files.values()}
    thresholds = [float(t) for t in args.thresholds.split(",")]
    started = time.time()
    rows = []
    for name in args.scenes.split(","):
        scene, res = files[name]
        log(f"{name}: {scene} at {res}", clock=True)
        halves = []
        for k in (1, 2):
            path = os.path.join(args.out, f"{name}-ref{k}-{args.reference_spp}.exr")
            if args.reuse_references and os.path.exists(path):
                halves.append(read_exr(path).rgb)
            else:
                halves.append(render(args, scene, path, 1000 + k, args.reference_spp, reference=True)[0])
        ref = (halves[0] + halves[1]) / 2
        # Each half's error variance is E|h1 - h2|^2 / 2; their mean's is a quarter of E|h1 - h2|^2.
        ref_noise = float(np.mean((halves[0] - halves[1]) ** 2)) / 4
        log(f"  reference: {2 * args.reference_spp} spp, its own MSE {ref_noise:.3e}", clock=True)
        for threshold in thresholds:
            a_mse, a_rel, a_t, a_spp, a_q, u_mse, u_rel, u_t, u_q = ([] for _ in range(9))
            for seed in range(1, args.seeds + 1):
                out = os.path.join(args.out, f"{name}-adaptive-{threshold:g}-s{seed}.exr")
                rgb, extra, t = render(args, scene, out, seed, args.max_spp, threshold=threshold)
                a_mse.append(mse(rgb, ref, ref_noise))
                a_rel.append(rel_mse(rgb, ref))
                a_t.append(t)
                a_spp.append(float(extra["samples"].mean()))
                a_q.append(float(np.percentile(extra["error"], 99)))
                if seed == 1 and name == "demo":
                    sample_map_png(extra["samples"], rgb, os.path.join(args.out, f"demo-samples-{threshold:g}.png"),
                                   f"demo, noise threshold {threshold:g}, at most {args.max_spp} spp: "
                                   f"{a_spp[-1]:.0f} on average")
                out = os.path.join(args.out, f"{name}-uniform-{threshold:g}-s{seed}.exr")
                rgb, extra, tu = render(args, scene, out, seed, 1 << 20, seconds=t)
                u_q.append(float(np.percentile(extra["error"], 99)))
                u_mse.append(mse(rgb, ref, ref_noise))
                u_rel.append(rel_mse(rgb, ref))
                u_t.append(tu)
                log(f"  threshold {threshold:g} seed {seed}: adaptive {t:.2f} s MSE {a_mse[-1]:.3e} "
                    f"({a_spp[-1]:.0f} spp on average); uniform {tu:.2f} s MSE {u_mse[-1]:.3e}", clock=True)
            A, U = np.mean(a_mse), np.mean(u_mse)
            TA, TU = np.mean(a_t), np.mean(u_t)
            # Uniform's MSE x time is its constant: the time it needs to reach the adaptive MSE.
            t_uniform = U * TU / A
            # The clean picture: the time uniform sampling needs for its 99th-percentile pixel error
            # (each render's own estimate, the .exr's error channel; ~ 1/sqrt(time)) to reach the
            # adaptive render's.
            t_clean = TU * (np.mean(u_q) / np.mean(a_q)) ** 2
            rows.append(dict(scene=name, res=res, threshold=threshold, mean_spp=np.mean(a_spp), t_adaptive=TA,
                             mse_adaptive=A, t_uniform=TU, mse_uniform=U, mse_ratio=U / A, t_uniform_same=t_uniform,
                             speedup=t_uniform / TA, rel_ratio=np.mean(u_rel) / np.mean(a_rel),
                             q99_adaptive=np.mean(a_q), q99_uniform=np.mean(u_q), clean_speedup=t_clean / TA))
    report = os.path.join(args.out, "report.md")
    with open(report, "w") as f:
        f.write(f"Command: `/usr/bin/python3 -m bench.adaptive.run {' '.join(sys.argv[1:])}` "
                f"({(time.time() - started) / 60:.1f} min; {args.seeds} seed(s) each, at most {args.max_spp} spp, "
                f"references 2 x {args.reference_spp} spp, {args.threads} threads)\n\n")
        f.write("| scene | threshold | adaptive: mean spp | time (s) | MSE | uniform at that time: MSE | "
                "MSE ratio uniform/adaptive | uniform's time to the adaptive MSE (s) | time saved at equal MSE (x) | "
                "relative-MSE ratio | 99th-percentile pixel error: adaptive, uniform | time saved at equal "
                "99th-percentile error (x) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['scene']} ({r['res']}) | {r['threshold']:g} | {r['mean_spp']:.0f} | {r['t_adaptive']:.2f} | "
                    f"{r['mse_adaptive']:.3e} | {r['mse_uniform']:.3e} | {r['mse_ratio']:.2f} | "
                    f"{r['t_uniform_same']:.2f} | **{r['speedup']:.2f}** | {r['rel_ratio']:.2f} | "
                    f"{r['q99_adaptive']:.4f}, {r['q99_uniform']:.4f} | **{r['clean_speedup']:.2f}** |\n")
    print(open(report).read())


if __name__ == "__main__":
    main()
