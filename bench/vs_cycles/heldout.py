#!/usr/bin/python3
"""Held-out configurations for checking that a change to the random walk generalises
beyond the scene family it was measured on (issue 40): eight configurations that are not
in scenes.FAMILY_CONFIGS, written after the subsurface pilot was built and before it was
measured on them: other albedos (marble, ketchup, apple, grey), scales and light
balances on the family's geometries. Dermis only (compare builds or settings with
bench/compare_efficiency.py); no Cycles twin.

  /usr/bin/python3 bench/vs_cycles/heldout.py --out DIR     # writes DIR/h01-....pbrt ...
"""
import argparse
import os

import pbrt_writer
import scenes as S

HELDOUT_MATERIALS = {
    "marble": dict(reflectance=[0.92, 0.90, 0.86], ratio=[1.3, 1.0, 0.8]),
    "ketchup": dict(reflectance=[0.70, 0.15, 0.08], ratio=[6.0, 1.5, 1.0]),
    "apple": dict(reflectance=[0.80, 0.75, 0.45], ratio=[2.0, 1.5, 0.7]),
    "grey": dict(reflectance=[0.60, 0.60, 0.60], ratio=[1.0, 1.0, 1.0]),
}
# (geometry, light balance, mfp / size, material)
HELDOUT_CONFIGS = [
    ("sphere", "key", 0.03, "marble"),
    ("sphere", "sky", 0.3, "ketchup"),
    ("sphere", "back", 0.3, "apple"),
    ("bust", "sky", 0.1, "marble"),
    ("bust", "both", 0.03, "ketchup"),
    ("fin", "sky", 0.3, "apple"),
    ("fin", "back", 1.0, "grey"),
    ("sphere", "both", 0.3, "grey"),
]


def heldout_scenes():
    """name -> scene text of the walk variant (the default method), h01 ... h08."""
    materials, configs = dict(S.FAMILY_MATERIALS), list(S.FAMILY_CONFIGS)
    try:
        S.FAMILY_MATERIALS.update(HELDOUT_MATERIALS)
        S.FAMILY_CONFIGS[:] = HELDOUT_CONFIGS
        family = S._family_scenes()
    finally:
        S.FAMILY_MATERIALS.clear()
        S.FAMILY_MATERIALS.update(materials)
        S.FAMILY_CONFIGS[:] = configs
    out = {}
    label = "randomwalk (default)"
    for name, sc in family.items():
        if name.endswith("-walk"):
            out["h" + name[1:]] = pbrt_writer.scene_text(sc, label, sc["dermis"][label])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="folder for the scene files")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for name, text in heldout_scenes().items():
        path = os.path.join(args.out, name + ".pbrt")
        with open(path, "w") as f:
            f.write(text)
        print(path)


if __name__ == "__main__":
    main()
