"""Driving a `dermis study` (docs/study.md) from a script, and its results in a docs page."""
import json
import os
import sys

from bench.harness import dermis_module, pictures
from bench.harness.paths import ROOT


def run_study(scene, options, out, label=None):
    """`dermis study SCENE OPTIONS --out OUT`, in this process and from the repository root
    (the report names the scene relative to it); its study.json. label: the prefix of its
    lines ("[label] dermis study ...")."""
    study = dermis_module.load("study")
    prefix = f"[{label}] " if label else ""
    argv = [os.path.relpath(scene, ROOT), *options, "--out", out]
    print(f"{prefix}dermis study {' '.join(argv)}", flush=True)
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        rc = study.main(argv)
    finally:
        os.chdir(cwd)
    if rc != 0:
        sys.exit(f"{prefix}the study failed ({rc})")
    with open(os.path.join(out, "study.json")) as f:
        return json.load(f)


def reference_image(folder):
    """The study's reference (linear float32, as dermis.read_image gives it)."""
    return dermis_module.load().read_image(os.path.join(folder, "reference.exr"))


def method_image(folder, name):
    """The image of the study's method `name` (its main budget's first repeat)."""
    filename = dermis_module.load("study")._filename(name)
    return dermis_module.load().read_image(os.path.join(folder, filename + ".exr"))


def strip(images, labels, path):
    """Side-by-side panels of linear images, tone-mapped as the study's report does, labelled."""
    from PIL import Image
    tonemap = dermis_module.load("report").tonemap
    pictures.strip([Image.fromarray(tonemap(img)) for img in images], path, labels)


def table(data):
    """The study's main table (study.json) in Markdown, method names as code."""
    report = dermis_module.load("report")
    head, rows = report.main_rows(data, data["mask_pixels"] > 0)
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(f"`{r[0]}`" if i == 0 else c for i, c in enumerate(r)) + " |" for r in rows]
    return "\n".join(lines)


def reference_line(data):
    """A sentence on the study's reference: how it was rendered and its own noise."""
    r = data["reference"]
    return (f"Reference: {r['details']}; its own noise (RMSE of the reference, from its halves' difference): "
            f"{r['noise_rmse']:.3g} whole image, {r['noise_mask_rmse']:.3g} on the object "
            f"({data['mask_pixels']} pixels).")
