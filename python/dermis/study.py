"""Equal-time comparison of subsurface methods on one scene, written as an HTML report.

    /usr/bin/python3 -m dermis.study SCENE --methods disk,randomwalk --time 10 [options]
    dermis study SCENE ...                       (the same, from the command line)

For every method, every `subsurface` material of the scene is switched to it and the
scene is rendered for the same time at each budget, K times with different seeds; each
render is compared with a converged reference. DIR/index.html shows the images, error
maps, tables (mean ± standard error over the K repeats) and convergence plots
(report.py); DIR/study.json holds every number, DIR/*.exr the images. See docs/study.md.

Method specs: a `"string method"` value (docs/materials.md), optionally followed by
parameters of the material, `name:key=value:key=value`, e.g.
`randomwalk:walksampling=mis:boundary=dielectric`. A value is a bool (true/false), a
number, three numbers a/b/c (rgb), else a string. The parameters override the scene's
for that method only (each method starts from the scene as written). A spec may start
with `LABEL=`, the name the report shows it under (default: the spec itself), e.g.
`mis + backward=randomwalk:walksampling=mis:backwardguiding=true`.

Cost: equal wall time (default): render(time_limit=T) with an unbounded sample count.
Equal CPU time (--cpu-time): the budget is CPU seconds of the process (all threads);
each render gets the sample count T / (CPU seconds per pixel sample), the cost per
sample measured for that method so far (first by a short pilot render), so a loaded or
shared machine does not change what a method is given. Either way the tables and plots
use the time each render actually took.
"""

import argparse
import datetime
import json
import os
import platform
import re
import shlex
import subprocess
import sys
import time

import numpy as np

import dermis

from . import repeats, report

UNBOUNDED_SPP = 1_000_000  # the sample count of time-limited renders (the time limit stops them)
REFERENCE_SEEDS = (1_000_001, 1_000_002)


# ---------------------------------------------------------------------------- arguments

class Method:
    """A method spec: `[LABEL=]name[:key=value...]`; `label` is the name shown (the spec
    itself unless LABEL is given)."""

    def __init__(self, spec):
        self.label = spec.strip()
        parts = spec.split(":")
        label, eq, name = parts[0].rpartition("=")
        if eq:  # "LABEL=name": the method's name holds no "=", the parameters come after ":"
            self.label = label.strip()
            if not self.label:
                raise ValueError(f"method '{spec}': empty label before '='")
        self.method = name.strip()
        if not self.method:
            raise ValueError(f"method '{spec}': empty method name")
        self.params = {}
        for p in parts[1:]:
            key, eq, value = p.partition("=")
            if not eq or not key:
                raise ValueError(f"method '{spec}': '{p}' is not key=value")
            self.params[key.strip()] = _value(value.strip())

    def apply(self, scene):
        """Sets every subsurface material of `scene` to this method."""
        for i in scene.subsurface_materials:
            scene.set_material(i, method=self.method, **self.params)


def _value(text):
    if text in ("true", "false"):
        return text == "true"
    parts = text.split("/")
    try:
        numbers = [float(x) for x in parts]
    except ValueError:
        return text
    if len(numbers) == 3:
        return tuple(numbers)
    if len(numbers) == 1:
        return numbers[0]
    return text


def _seconds_list(text):
    values = [float(x) for x in text.split(",") if x.strip()]
    if not values or min(values) <= 0:
        raise argparse.ArgumentTypeError(f"'{text}': expected positive seconds, comma-separated")
    return values


def _resolution(text):
    m = re.fullmatch(r"(\d+)x(\d+)", text)
    if not m:
        raise argparse.ArgumentTypeError(f"'{text}': expected WIDTHxHEIGHT, e.g. 200x150")
    return int(m.group(1)), int(m.group(2))


def parse_args(argv):
    prog = os.environ.get("DERMIS_STUDY_PROG", "python3 -m dermis.study")
    ap = argparse.ArgumentParser(prog=prog, description=__doc__.split("\n\n")[0],
                                 epilog="See docs/study.md for what the report shows and how errors are computed.")
    ap.add_argument("scene", help="the .pbrt scene (with at least one subsurface material)")
    ap.add_argument("--methods", required=True,
                    help="comma-separated method specs: disk,sphere-lines,randomwalk:walksampling=mis,...")
    ap.add_argument("--time", type=float, required=True, metavar="T",
                    help="the equal-time budget (seconds) whose images and table the report shows")
    ap.add_argument("--budgets", type=_seconds_list, metavar="T1,T2,...",
                    help="the budgets of the convergence plots (T is added); default T/4,T/2,T")
    ap.add_argument("--repeats", type=int, default=3, metavar="K",
                    help="independent renders (seeds) per method and budget, for standard errors (default 3)")
    ref = ap.add_mutually_exclusive_group()
    ref.add_argument("--reference", metavar="IMAGE", help="a converged reference image (EXR) at the study's resolution")
    ref.add_argument("--reference-method", metavar="SPEC",
                     help="the (unbiased) method the reference is rendered with (default: for each model the compared "
                          "methods solve, its unbiased method: volumetric for a dielectric boundary, "
                          "randomwalk:boundary=diffuse for the diffuse one; each method against its own model's)")
    ap.add_argument("--reference-time", type=float, metavar="SEC",
                    help="wall seconds of the rendered reference, in two independent halves (default 10 x the "
                         "largest budget)")
    ap.add_argument("--cpu-time", action="store_true",
                    help="equal CPU time (all threads, user + system) instead of equal wall time")
    ap.add_argument("--threads", type=int, default=0, help="render threads (default 0: all cores)")
    ap.add_argument("--res", type=_resolution, metavar="WxH", help="film resolution (default: the scene's)")
    ap.add_argument("--seed", type=int, default=1, help="first seed of the test renders (default 1)")
    ap.add_argument("-o", "--out", metavar="DIR", help="output folder (default study-<scene name>)")
    args = ap.parse_args(argv)
    try:
        args.methods = [Method(s) for s in args.methods.split(",") if s.strip()]
        if args.reference_method is not None:
            args.reference_method = Method(args.reference_method)
    except ValueError as e:
        ap.error(str(e))
    if not args.methods:
        ap.error("--methods: no method given")
    if len({m.label for m in args.methods}) != len(args.methods):
        ap.error("--methods: a method is named twice")
    if args.time <= 0 or args.repeats < 1 or args.threads < 0:
        ap.error("--time must be positive, --repeats at least 1, --threads at least 0")
    budgets = args.budgets or [args.time / 4, args.time / 2]
    args.budgets = sorted(set(budgets) | {args.time})
    if args.reference_time is None:
        args.reference_time = 10 * max(args.budgets)
    if args.out is None:
        args.out = "study-" + os.path.splitext(os.path.basename(args.scene))[0]
    args.command = prog + " " + shlex.join(argv)
    return args


# ---------------------------------------------------------------------------- models

# What each method solves, named by the boundary light crosses (docs/materials.md): the
# random walk's `boundary`, the volumetric path tracer's dielectric, and the diffusion
# profiles, which stand in for the diffuse boundary's walk (an approximation by design).
MODEL_WORDS = {
    "dielectric": "the medium behind a dielectric boundary (Fresnel at every crossing)",
    "diffuse": "the walk's diffuse boundary (Fresnel in, out through the exit lobe at the first crossing)",
    "matched": "the medium behind an index-matched boundary",
}
# The unbiased method of each model: the reference a study of that model needs.
UNBIASED_METHOD = {"dielectric": "volumetric", "diffuse": "randomwalk:boundary=diffuse",
                   "matched": "randomwalk:boundary=matched"}


def default_walk_boundary(params):
    """The walk's boundary when none is given (scene/subsurface_params.h,
    default_walk_boundary): `dielectric` for a medium given by its coefficients (or a named
    medium, or none), `diffuse` for reflectance + mfp; "entry" "lambertian" keeps `diffuse`.
    (A scene with point, spot or distant lights keeps `diffuse` for coefficients too: give the
    method's boundary explicitly to study such a scene.)"""
    if "reflectance" in params or str(params.get("entry", "")) == "lambertian":
        return "diffuse"
    return "dielectric"


def model_of(method, material_params):
    """(model, exact) of `method` on a material written with `material_params` (its
    parameters as the scene writes them): exact is False for a diffusion approximation."""
    if method.method == "volumetric":
        return "dielectric", True
    if method.method == "randomwalk":
        given = method.params.get("boundary") or material_params.get("boundary")
        return str(given or default_walk_boundary({**material_params, **method.params})), True
    return "diffuse", False


def models_of(methods, reference_method, material_params, per_model=None):
    """Each method's model and whether its reference solves it: the report's statement.
    per_model: {model: reference Method} when each method has its own model's reference."""
    ref_model = model_of(reference_method, material_params)[0] if reference_method else None
    out = []
    for m in methods:
        model, exact = model_of(m, material_params)
        own = per_model.get(model) if per_model else None
        out.append(dict(name=m.label, model=model, words=MODEL_WORDS.get(model, model), exact=exact,
                        reference=own.label if own else None,
                        same_as_reference=own is not None or ref_model is None or model == ref_model))
    return dict(reference=ref_model, reference_words=MODEL_WORDS.get(ref_model, ref_model), methods=out,
                per_model=bool(per_model) and len(set(per_model)) > 1)


# ---------------------------------------------------------------------------- rendering

class Study:
    """The renders of one study and their errors against the reference."""

    def __init__(self, args):
        self.args = args
        self.threads = args.threads or len(os.sched_getaffinity(0))
        self.pixels = None

    def scene(self, method):
        """A freshly loaded scene set to `method` (fresh: set_material keeps parameters a
        previous method set, which must not leak into the next)."""
        scene = dermis.load_scene(self.args.scene)
        if self.args.res:
            scene.resolution = self.args.res
        if not scene.subsurface_materials:
            raise dermis.SceneError(f"{self.args.scene}: the scene has no subsurface material to compare methods on")
        method.apply(scene)
        return scene

    def render(self, scene, seed, time_limit=0.0, spp=None):
        img, st = dermis.render(scene, spp=spp or UNBOUNDED_SPP, seed=seed, threads=self.args.threads,
                                time_limit=time_limit, stats=True)
        return img, st

    def warm_up(self, scene):
        """A 1-spp render: builds what the method prepares once (tables, point clouds),
        so that it is not counted in the timed renders. Returns its wall seconds."""
        t0 = time.perf_counter()
        self.render(scene, seed=0, spp=1)
        return time.perf_counter() - t0

    def reference(self, log, method=None):
        """The reference image, its label, details and own noise (when rendered with
        `method`, default --reference-method)."""
        a = self.args
        method = method or a.reference_method
        if a.reference:
            img = dermis.read_image(a.reference)
            return dict(image=img, label=a.reference, details=f"read from {a.reference}", noise_rmse=None,
                        noise_mask_rmse=None)
        scene = self.scene(method)
        self.warm_up(scene)
        halves, stats = [], []
        for seed in REFERENCE_SEEDS:
            img, st = self.render(scene, seed, time_limit=a.reference_time / 2)
            halves.append(img)
            stats.append(st)
            log(f"reference half (seed {seed}): {st['samples'] / img.shape[0] / img.shape[1]:.0f} spp, "
                f"{st['seconds']:.1f} s")
        ref = 0.5 * (halves[0] + halves[1])
        # The halves are independent: E (h1 - h2)^2 = 2 var(h), var(mean of 2) = var(h) / 2.
        ref_var = (halves[0] - halves[1]) ** 2 / 4
        spp = sum(s["samples"] for s in stats) / (ref.shape[0] * ref.shape[1])
        details = (f"{method.label}, two independent halves (seeds {REFERENCE_SEEDS[0]}, "
                   f"{REFERENCE_SEEDS[1]}) of {a.reference_time / 2:g} s wall each: {spp:.0f} spp in all, "
                   f"{sum(s['seconds'] for s in stats):.1f} s wall, {sum(s['cpu_seconds'] for s in stats):.1f} s CPU")
        return dict(image=ref.astype(np.float32), var=ref_var, label=f"{method.label}, {spp:.0f} spp",
                    details=details, stats=stats)

    def errors(self, img, ref, mask):
        """RMSE and relMSE over the image and over the mask (dermis.compare)."""
        whole = dermis.compare(img, ref)
        e = dict(rmse=whole["rmse"], relmse=whole["relmse"], mask_rmse=float("nan"), mask_relmse=float("nan"))
        if mask.any():
            obj = dermis.compare(img[mask][None], ref[mask][None])  # the masked pixels as a 1 x N image
            e.update(mask_rmse=obj["rmse"], mask_relmse=obj["relmse"])
        return e

    def run_method(self, method, ref, mask, log):
        """Every budget and repeat of one method; its first repeat at the main budget kept."""
        a = self.args
        scene = self.scene(method)
        warmup = self.warm_up(scene)
        cost = None  # CPU seconds per pixel sample (equal CPU time)
        if a.cpu_time:
            _, st = self.render(scene, seed=0, time_limit=max(0.05, min(a.budgets) / 4))
            cost = [st["cpu_seconds"], st["samples"]]
        runs, shown, by_budget = [], None, []
        for bi, budget in enumerate(a.budgets):
            images = []  # the K repeats at this budget, for the variance and bias^2 (then dropped)
            for k in range(a.repeats):
                seed = a.seed + 1000 * bi + k
                if a.cpu_time:
                    spp = max(1, round(budget / (cost[0] / max(cost[1], 1)) / self.pixels))
                    img, st = self.render(scene, seed, spp=spp)
                    cost[0] += st["cpu_seconds"]
                    cost[1] += st["samples"]
                else:
                    img, st = self.render(scene, seed, time_limit=budget)
                run = dict(budget=budget, repeat=k, seed=seed, **{key: st[key] for key in (
                    "seconds", "cpu_seconds", "samples", "min_spp", "max_spp", "nonfinite", "truncated")})
                run.update(self.errors(img, ref["image"], mask))
                if ref.get("noise_rmse") is not None:  # E (A - R)^2 = Var A + bias^2 + Var R: remove Var R
                    run["mse_corr"] = run["rmse"] ** 2 - ref["noise_rmse"] ** 2
                    run["mask_mse_corr"] = run["mask_rmse"] ** 2 - ref["noise_mask_rmse"] ** 2
                runs.append(run)
                images.append(img)
                if budget == a.time and k == 0:
                    shown = img
                log(f"{method.label:>20}  {budget:g} s  #{k + 1}: {st['samples'] / self.pixels:.0f} spp, "
                    f"{st['seconds']:.2f} s wall, {st['cpu_seconds']:.2f} s CPU, RMSE {run['rmse']:.4g}, "
                    f"relMSE {run['relmse']:.4g}")
            by_budget.append(budget_stats(budget, runs[-a.repeats:], images, ref, mask))
            log(f"{method.label:>20}  {budget:g} s: variance {_g(by_budget[-1]['variance'])}, "
                f"bias² {repeats.format_bias2(by_budget[-1]['bias2'], by_budget[-1]['bias2_se'])}")
        emap, scale = dermis.error_map(shown, ref["image"])
        return dict(name=method.label, method=method.method, params=method.params, image=shown, error_map=emap,
                    error_scale=scale, runs=runs, by_budget=by_budget, warmup_seconds=warmup,
                    reference_noise_rmse=ref.get("noise_rmse"), reference_noise_mask_rmse=ref.get("noise_mask_rmse"))

    def run(self, log):
        a = self.args
        t0 = time.time()
        base = self.scene(a.methods[0])
        W, H = base.resolution
        # The material's parameters as written (its boundary), before any method is applied.
        original = dermis.load_scene(a.scene)
        material_params = original.materials[original.subsurface_materials[0]]["parameters"]
        # Each method against the reference of its own model: one reference per model the
        # methods solve unless the user chose one (--reference, --reference-method).
        models = list(dict.fromkeys(model_of(m, material_params)[0] for m in a.methods))
        per_model = not a.reference and a.reference_method is None
        if per_model:
            reference_methods = {k: Method(UNBIASED_METHOD.get(k, "volumetric")) for k in models}
            a.reference_method = reference_methods[models[0]]
            log("reference method(s): " + ", ".join(f"{r.label} ({k})" for k, r in reference_methods.items()))
        self.pixels = W * H
        mask = np.asarray(dermis.subsurface_mask(base), dtype=bool)
        n = len(a.methods) * a.repeats * sum(a.budgets) / (self.threads if a.cpu_time else 1)
        ref_t = 0 if a.reference else a.reference_time * (len(models) if per_model else 1)
        log(f"{W}x{H} pixels, {len(a.methods)} methods x {a.repeats} repeats x budgets "
            f"{','.join(f'{b:g}' for b in a.budgets)} s ({'CPU' if a.cpu_time else 'wall'}): about "
            f"{n + ref_t:.0f} s of rendering (wall)")
        refs = {k: self.reference(log, reference_methods[k]) for k in models} if per_model else {}
        ref = refs[models[0]] if per_model else self.reference(log)
        for r in list(refs.values()) + [ref]:
            if r["image"].shape[:2] != (H, W):
                raise ValueError(f"the reference is {r['image'].shape[1]}x{r['image'].shape[0]} pixels, the study "
                                 f"renders {W}x{H}: give --res {r['image'].shape[1]}x{r['image'].shape[0]}")
            if "var" in r:  # the reference's own noise (RMSE of the averaged halves)
                r["noise_rmse"] = float(np.sqrt(r["var"].mean()))
                r["noise_mask_rmse"] = float(np.sqrt(r["var"][mask].mean())) if mask.any() else float("nan")
        methods = [self.run_method(m, refs.get(model_of(m, material_params)[0], ref), mask, log)
                   for m in a.methods]
        notes = [f"{m['name']}: {sum(r['nonfinite'] for r in m['runs'])} non-finite samples (dropped)"
                 for m in methods if any(r["nonfinite"] for r in m["runs"])]
        notes += [f"{m['name']}: {sum(r['truncated'] for r in m['runs'])} paths cut short (truncated)"
                  for m in methods if any(r["truncated"] for r in m["runs"])]
        how = ("equal CPU time: each render took T / (the method's measured CPU seconds per sample) samples"
               if a.cpu_time else f"equal wall time: render(time_limit=T, spp={UNBOUNDED_SPP})")
        settings = (f"Every subsurface material set to the method (a freshly loaded scene per method, a 1-spp warm-up "
                    f"render first so that preparation is not timed); {how}; threads={a.threads or 'all'} "
                    f"({self.threads}); seeds {a.seed} + 1000 × budget index + repeat.")
        return dict(title=f"Dermis study: {os.path.basename(a.scene)}", scene=a.scene,
                    cost="cpu" if a.cpu_time else "wall", budgets=a.budgets, main_budget=a.time, repeats=a.repeats,
                    resolution=(W, H), threads=self.threads, mask=mask, reference=ref, methods=methods,
                    models=models_of(a.methods, None if a.reference else a.reference_method, material_params,
                                     reference_methods if per_model else None),
                    other_references=[dict(model=k, label=refs[k]["label"], details=refs[k]["details"],
                                           noise_rmse=refs[k].get("noise_rmse")) for k in models[1:]] if per_model else [],
                    command=a.command, settings=settings, version=dermis.__version__, commit=_git_commit(),
                    machine=machine(self.threads), date=datetime.datetime.now().astimezone().strftime(
                        "%Y-%m-%d %H:%M %Z"), total_seconds=time.time() - t0, notes=notes)


def _g(x):
    return "–" if x is None else f"{x:.4g}"


def budget_stats(budget, runs, images, ref, mask):
    """One method at one budget (its K repeats `runs` and their `images`): mean spp and
    times, and the variance and bias^2 over the image and the mask (repeats.noise_and_bias;
    the reference's own variance is subtracted from bias^2 when it is known)."""
    spp = [r["samples"] / images[0].shape[0] / images[0].shape[1] for r in runs]
    st = dict(budget=budget, repeats=len(runs), spp=sum(spp) / len(spp),
              spp_harmonic=len(spp) / sum(1 / max(x, 1e-9) for x in spp),  # E s^2 = sigma_1^2 x mean(1 / spp)
              seconds=sum(r["seconds"] for r in runs) / len(runs),
              cpu_seconds=sum(r["cpu_seconds"] for r in runs) / len(runs),
              bias2_less_reference_variance=ref.get("var") is not None)
    st.update(repeats.noise_and_bias(images, ref["image"], ref.get("var"), mask))
    return st


# ---------------------------------------------------------------------------- provenance

def _git_commit():
    here = os.path.dirname(os.path.realpath(__file__))
    try:
        p = subprocess.run(["git", "-C", here, "describe", "--always", "--dirty"], capture_output=True, text=True,
                           timeout=10)
        return p.stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def _first_line(path, prefix, sep):
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(prefix):
                    return line.split(sep, 1)[1].strip().strip('"')
    except OSError:
        pass
    return "unknown"


def machine(threads):
    """The machine, for the report: CPU, cores, memory, OS, load."""
    mem = _first_line("/proc/meminfo", "MemTotal", ":")  # "24683584 kB"
    if mem.endswith(" kB"):
        mem = f"{int(mem.split()[0]) / 2**20:.1f} GiB"
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    return {"CPU": _first_line("/proc/cpuinfo", "model name", ":"),
            "cores": f"{os.cpu_count()} logical, {len(os.sched_getaffinity(0))} available, {threads} render threads",
            "memory": mem, "OS": f"{_first_line('/etc/os-release', 'PRETTY_NAME', '=')}, {platform.system()} "
                                 f"{platform.release()}",
            "Python": f"{platform.python_version()} ({sys.executable}), NumPy {np.__version__}",
            "load average (1, 5, 15 min) at the end": load}


# ---------------------------------------------------------------------------- output

def _filename(label):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", label)


def save(study, out):
    """DIR/index.html, DIR/study.json (every number), DIR/reference.exr and DIR/<method>.exr."""
    os.makedirs(out, exist_ok=True)
    report.write_report(os.path.join(out, "index.html"), study)
    dermis.write_image(os.path.join(out, "reference.exr"), study["reference"]["image"])
    for m in study["methods"]:
        dermis.write_image(os.path.join(out, _filename(m["name"]) + ".exr"), m["image"])
    skip = {"image", "error_map", "mask", "var", "stats"}

    def plain(x):
        if isinstance(x, dict):
            return {k: plain(v) for k, v in x.items() if k not in skip}
        if isinstance(x, (list, tuple)):
            return [plain(v) for v in x]
        if isinstance(x, (np.floating, np.integer)):
            return x.item()
        return x

    data = plain(study)
    data["mask_pixels"] = int(study["mask"].sum())
    data["reference_noise_warning"] = report.reference_noise_warning(study)  # None: the reference is quiet enough
    with open(os.path.join(out, "study.json"), "w") as f:
        json.dump(data, f, indent=1)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)

    def log(text):
        print(text, flush=True)

    try:
        study = Study(args).run(log)
    except dermis.SceneError as e:
        print(e, file=sys.stderr)
        return 2
    except (ValueError, OSError, RuntimeError) as e:
        print(f"{args.command.split()[0]}: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted: no report written", file=sys.stderr)
        return 130
    save(study, args.out)
    log(f"wrote {os.path.join(args.out, 'index.html')} ({study['total_seconds']:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
