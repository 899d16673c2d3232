#!/usr/bin/python3
"""Equal-time comparison of backward guiding for the random walk (issue 6).

The random walk rendered for the same time with classical sampling, the seed's MIS
(guiding toward the entry plane), MIS with backward guiding, and Dwivedi-only with
backward guiding. With the `dielectric` boundary the reference is the brute-force
volumetric path tracer, with the `diffuse` boundary (the production default) the
classical walk itself; 20x the time, two halves. The measurement is
bench/sss_methods.py's (CPU time, reference noise removed); this script only adds the
geometries and the rows.

  /usr/bin/python3 bench/walk_backward.py              # ~20 min on 2 cores
  /usr/bin/python3 bench/walk_backward.py --scale 0.2  # smoke test

Writes docs/results-backward.md (tables; hand-written findings below the marker are kept)
and docs/images/results-backward-*.png.
"""

import argparse
import datetime
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sss_methods as sm  # noqa: E402



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
EQUAL_TIME = dict(bust=6, fin=4, sphere=4, slab=4, thickslab=4)
REF_TIME = {g: 20 * t for g, t in EQUAL_TIME.items()}
ROWS = [  # label, walksampling, backward guiding
    ("classical", "classical", False),
    ("mis", "mis", False),
    ("mis + backward", "mis", True),
    ("dwivedi + backward", "dwivedi", True),
]
MARKER = "<!-- findings: written by hand below this line; kept when the script rewrites the tables -->"


def scene(g, boundary, label, sampling, backward):
    if sampling is None:
        mat, name = f'{sm.WALK_MATERIAL} "string method" "volumetric"', f"{g}-volumetric"
    else:
        mat = (f'{sm.WALK_MATERIAL} "string method" "randomwalk" "string boundary" "{boundary}" '
               f'"string walksampling" "{sampling}" "bool backwardguiding" {"true" if backward else "false"}')
        name = f"{g}-walk-{boundary}-" + label.replace(" + ", "-").replace(" ", "-")
    text = sm.scene_text(g, mat, name)
    if g in BACKLIT:
        text = text.replace(sm.LIGHTS, BACKLIGHT)
    return sm.write_scene(name, text)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scale", type=float, default=1.0, help="multiply every render time (default 1)")
    ap.add_argument("--work", default="/tmp/dermis-walk-backward", help="scratch folder for EXR files")
    ap.add_argument("--geometries", default="slab,thickslab,fin,sphere,bust", help="comma-separated subset")
    ap.add_argument("--boundaries", default="dielectric,diffuse", help="comma-separated subset")
    ap.add_argument("--no-docs", action="store_true", help="do not write docs/results-backward.md")
    args = ap.parse_args()
    os.makedirs(sm.SCENES, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    sm.WORK = args.work
    S = args.scale
    t0 = time.time()
    fams = {}
    masks = {g: sm.make_mask(g, args.work) for g in args.geometries.split(",")}
    for b in args.boundaries.split(","):
        for g in args.geometries.split(","):
            print(f"[{b} {g}]", flush=True)
            fam = sm.Family(f"{g}-{b}-backward", g, args.work, masks[g])
            if b == "dielectric":
                fam.reference(scene(g, b, None, None, None), REF_TIME[g] * S,
                              f"`volumetric` on `scenes/bench/{g}-volumetric.pbrt`")
            else:
                fam.reference(scene(g, b, "classical", "classical", False), REF_TIME[g] * S,
                              f"`randomwalk` {b} classical on `scenes/bench/{g}-walk-{b}-classical.pbrt`")
            for label, sampling, backward in ROWS:
                out = os.path.join(args.work, f"{g}-{b}-{label.replace(' + ', '-')}.exr")
                fam.measure(label, sm.render(scene(g, b, label, sampling, backward), out, seconds=EQUAL_TIME[g] * S,
                                             seed=1))
            fams[(b, g)] = fam
    total = time.time() - t0
    print(f"total wall time {total:.0f} s", flush=True)
    for (b, g), fam in fams.items():
        print(f"\n{b} {g}\n" + sm.fmt_table(fam, "mis"))
    if not args.no_docs:
        write_docs(fams, total, S)


def write_docs(fams, total, S):
    os.makedirs(sm.IMAGES, exist_ok=True)
    for (b, g), fam in fams.items():
        pngs = [fam.ref_png] + [os.path.join(fam.work, f"{g}-{b}-{label.replace(' + ', '-')}.png")
                                for label, _, _ in ROWS]
        sm.strip(pngs, os.path.join(sm.IMAGES, f"results-backward-{b}-{g}.png"), ["reference"] + [r[0] for r in ROWS])
    path = os.path.join(sm.DOCS, "results-backward.md")
    kept = ""
    if os.path.exists(path):
        text = open(path).read()
        if MARKER in text:
            kept = text[text.index(MARKER) + len(MARKER):]
    commit = subprocess.run(["git", "-C", sm.ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    cmd = "/usr/bin/python3 bench/walk_backward.py" + (f" --scale {S:g}" if S != 1 else "")
    out = ["# Results: backward guiding for the random walk, at equal time\n",
           f"Produced by `{cmd}` on {datetime.date.today().isoformat()} (code at commit {commit}; 2 threads on a shared "
           f"2-core machine; the script took {total:.0f} s). Measurement as in [results.md](results.md): CPU time, object "
           "pixels, the reference's own noise removed; efficiency = MSE·CPU of `mis` (the seed's guiding, the default "
           "before backward guiding) over MSE·CPU of the row.\n",
           f"Material: `subsurface` {sm.WALK_MATERIAL} (mean free path 13 / 9.5 / 6.7 mm in R / G / B), "
           '`"string method" "randomwalk"`, the section\'s `boundary`, and the rows\' `walksampling` and '
           "`backwardguiding`. Reference, 20× the time: for `dielectric` the `volumetric` method (the same medium "
           "inside a smooth dielectric), for `diffuse` the classical walk (all rows are unbiased estimators of the same "
           "image: tested).\n"]
    titles = dict(slab="100 × 100 × 8 mm slab lit from behind (0.6–1.2 mfp thick)",
                  thickslab="100 × 100 × 30 mm slab lit from behind (2.3–4.5 mfp thick)",
                  fin="block with a 4 mm fin (0.3–0.6 mfp), front-lit", sphere="sphere of radius 20 mm (3–6 mfp across)",
                  bust="Nefertiti bust (≈ 40 mfp across)")
    for (b, g), fam in fams.items():
        out.append(f"## `{b}` boundary: {titles[g]}, {EQUAL_TIME[g] * S:g} s each\n")
        out.append(sm.fmt_table(fam, "mis") + "\n")
        out.append(sm.ref_line(fam) + "\n")
        out.append("Mean over the object (R, G, B): reference " + sm.means(fam.rows[0]["mean_obj_ref"]) + "; " +
                   "; ".join(f"{row['label']} {sm.means(row['mean_obj'])}" for row in fam.rows) + ".\n")
        out.append(f"![{b} {g}](images/results-backward-{b}-{g}.png)\n")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n" + MARKER + (kept if kept else "\n"))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
