#!/usr/bin/python3
"""Equal-time comparison of backward guiding for the random walk (issue 6), by `dermis study`.

The random walk rendered for the same CPU time with classical sampling, the seed's MIS
(guiding toward the entry plane), MIS with backward guiding, and Dwivedi-only with
backward guiding: one study (python/dermis/study.py, docs/study.md) per geometry and
boundary, its rows the four settings as labelled method specs. With the `dielectric`
boundary the reference is the brute-force volumetric path tracer, with the `diffuse`
boundary (the production default) the classical walk itself. Geometries: slabs lit from
behind (8 and 30 mm), and the fin, sphere and bust of bench/sss_methods.py, front-lit.

  /usr/bin/python3 -m bench.walk_backward                 # the full run
  /usr/bin/python3 -m bench.walk_backward --scale 0.1     # every time x0.1, a smoke test

Writes docs/results/results-backward.md (tables; hand-written findings below the marker are kept)
and docs/images/results-backward-*.png; the studies' HTML reports stay in --work.
"""

import argparse
import datetime
import os
import sys
import time

from bench import sss_methods as sm  # the scenes
from bench.harness import docs_page, progress, provenance, study
from bench.harness.paths import IMAGES, RESULTS

WORK = "/tmp/dermis-walk-backward"


def slab(thickness):
    """A 100 x 100 mm slab standing on the floor, `thickness` mm thick along y."""
    h = thickness / 2
    p = f"-50 {-h} 0  50 {-h} 0  50 {h} 0  -50 {h} 0  -50 {-h} 100  50 {-h} 100  50 {h} 100  -50 {h} 100"
    return (f'Shape "trianglemesh" "point3 P" [ {p} ]\n'
            '      "integer indices" [ 0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7 ]')


# Slabs lit from behind (BACKLIGHT) and seen from the front: the light the camera sees has crossed them.
BACKLIGHT = """
# Soft blue-grey sky and a warm 120 x 120 mm light behind the slab, to the left, out of
# the camera's view and out of its line of sight through the slab.
LightSource "infinite" "rgb L" [ 0.06 0.075 0.10 ]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 100 85 65 ] "bool twosided" true
  Translate -350 200 60
  Rotate 60 0 0 1
  Shape "bilinearmesh"
      "point3 P" [ -60 0 -60   60 0 -60   -60 0 60   60 0 60 ]
AttributeEnd
"""
sm.GEOMETRY["slab"] = ("-120 -300 80   0 0 50   0 0 1", -0.3, slab(8))
sm.GEOMETRY["thickslab"] = ("-120 -300 80   0 0 50   0 0 1", -0.3, slab(30))
BACKLIT = ("slab", "thickslab")
TITLES = dict(slab="100 × 100 × 8 mm slab lit from behind (0.6–1.2 mfp thick)",
              thickslab="100 × 100 × 30 mm slab lit from behind (2.3–4.5 mfp thick)",
              fin="block with a 4 mm fin (0.3–0.6 mfp), front-lit", sphere="sphere of radius 20 mm (3–6 mfp across)",
              bust="Nefertiti bust (≈ 40 mfp across)")
EQUAL_TIME = 4  # CPU seconds per render (x --scale)
REF_TIME = 60   # wall seconds of each reference, two halves (x --scale)
REPEATS = 3
THREADS = 2
# The rows: label, walksampling, backward guiding. `mis` (the seed's guiding, the default
# before backward guiding) first: the efficiency column is relative to the first row.
ROWS = [("mis", "mis", False), ("classical", "classical", False), ("mis + backward", "mis", True),
        ("dwivedi + backward", "dwivedi", True)]
MARKER = "<!-- findings: written by hand below this line; kept when the script rewrites the tables -->"


def walk_spec(boundary, sampling, backward):
    return (f"randomwalk:boundary={boundary}:walksampling={sampling}:"
            f"backwardguiding={'true' if backward else 'false'}")


def scene(g):
    """The geometry with the walk material (the study sets the method of each row)."""
    name = f"{g}-walk-backward"
    text = sm.scene_text(g, f'{sm.WALK_MATERIAL} "string method" "randomwalk"', name)
    if g in BACKLIT:
        text = text.replace(sm.LIGHTS, BACKLIGHT)
    return sm.write_scene(name, text)


def run_study(key, scene_path, boundary, scale, work):
    """One study in this process; returns its study.json as a dict."""
    methods = [f"{label}={walk_spec(boundary, s, b)}" for label, s, b in ROWS]
    reference = "volumetric" if boundary == "dielectric" else walk_spec(boundary, "classical", False)
    options = ["--methods", ",".join(methods), "--time", f"{EQUAL_TIME * scale:g}", "--budgets",
               f"{EQUAL_TIME * scale:g}", "--repeats", str(REPEATS), "--cpu-time", "--threads", str(THREADS),
               "--reference-method", reference, "--reference-time", f"{REF_TIME * scale:g}"]
    return study.run_study(scene_path, options, os.path.join(work, key), label=key)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scale", type=float, default=1.0, help="multiply every time (default 1)")
    ap.add_argument("--work", default=WORK, help="folder of the studies (their reports and images)")
    ap.add_argument("--geometries", default="slab,thickslab,fin,sphere,bust", help="comma-separated subset")
    ap.add_argument("--boundaries", default="dielectric,diffuse", help="comma-separated subset")
    ap.add_argument("--no-docs", action="store_true", help="do not write docs/results/results-backward.md")
    args = ap.parse_args()
    args.work = os.path.abspath(args.work)
    os.makedirs(sm.SCENES, exist_ok=True)
    t0 = time.time()
    load_start = os.getloadavg()
    results = {}
    for b in args.boundaries.split(","):
        for g in args.geometries.split(","):
            key = f"{b}-{g}"
            results[key] = (b, g, run_study(key, scene(g), b, args.scale, args.work))
    total = time.time() - t0
    progress.log(f"total wall time {total:.0f} s", sys.stdout)
    if not args.no_docs:
        write_docs(results, total, args, load_start)


def write_docs(results, total, args, load_start):
    os.makedirs(IMAGES, exist_ok=True)
    for key, (b, g, data) in results.items():
        folder = os.path.join(args.work, key)
        names = [m["name"] for m in data["methods"]]
        study.strip([study.reference_image(folder)] + [study.method_image(folder, n) for n in names],
                    ["reference"] + names, os.path.join(IMAGES, f"results-backward-{key}.png"))
    path = os.path.join(RESULTS, "results-backward.md")
    commit = provenance.git_commit()
    cmd = "/usr/bin/python3 -m bench.walk_backward" + (f" --scale {args.scale:g}" if args.scale != 1 else "")
    if args.geometries != "slab,thickslab,fin,sphere,bust":
        cmd += f" --geometries {args.geometries}"
    if args.boundaries != "dielectric,diffuse":
        cmd += f" --boundaries {args.boundaries}"
    any_data = next(iter(results.values()))[2]
    load_end = os.getloadavg()
    out = ["# Results: backward guiding for the random walk, at equal time\n",
           f"Produced by `{cmd}` on {datetime.date.today().isoformat()} (code at commit {commit}; {THREADS} threads; "
           f"CPU: {any_data['machine']['CPU']}; cores: {any_data['machine']['cores']}; the script took {total:.0f} s). "
           f"Load average (1, 5, 15 min) "
           f"{', '.join(f'{x:.1f}' for x in load_start)} at the start, {', '.join(f'{x:.1f}' for x in load_end)} at "
           f"the end (the studies' own {THREADS} threads count in it); equal **CPU** time keeps the comparison fair "
           "on a loaded machine, but the references (rendered for a wall time) then reach fewer samples: their "
           "sample counts and own noise are under each table.\n",
           "Each section is one `dermis study` ([study.md](../study.md)) whose interactive report the script leaves in "
           f"`{args.work}/<boundary>-<geometry>/index.html`; its rows are labelled method specs "
           "(`mis + backward=randomwalk:boundary=…:walksampling=mis:backwardguiding=true`). How to read the tables: "
           f"as in [results.md](results.md): {REPEATS} independent repeats per row, mean ± standard error; "
           "*efficiency* = (relMSE × CPU time) of `mis` (the first row: the seed's guiding, the default before "
           "backward guiding) / that of the row.\n",
           f"Material: `subsurface` {sm.WALK_MATERIAL} (mean free path 13 / 9.5 / 6.7 mm in R / G / B), "
           '`"string method" "randomwalk"`, the section\'s `boundary`, and the rows\' `walksampling` and '
           "`backwardguiding`. Reference: for `dielectric` the `volumetric` method (the same medium inside a smooth "
           "dielectric), for `diffuse` the classical walk (all rows are unbiased estimators of the same image: "
           "tested).\n"]
    for key, (b, g, data) in results.items():
        out.append(f"## `{b}` boundary: {TITLES[g]}, {data['main_budget']:g} CPU s each\n")
        out.append(study.table(data) + "\n")
        out.append(study.reference_line(data) + "\n")
        out.append(f"![{b} {g}](../images/results-backward-{key}.png)\n")
    docs_page.write_page(path, "\n".join(out), MARKER)  # the findings below the marker are kept
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
