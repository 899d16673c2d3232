#!/usr/bin/python3
"""The held-out configurations' random-walk scene files (scenes.HELDOUT_CONFIGS: eight
configurations that are not in the family, on its geometries), for checking that a change
to the random walk generalises beyond the family it was measured on (issue 40): compare
builds or settings on them with bench/compare_efficiency.py. Against Cycles, with the
disk twins too: run.py --set heldout.

  /usr/bin/python3 -m bench.vs_cycles.heldout --out DIR     # writes DIR/h01-....pbrt ...
"""
import argparse
import os

from bench.vs_cycles import pbrt_writer
from bench.vs_cycles import scenes as S

HELDOUT_MATERIALS = S.HELDOUT_MATERIALS
HELDOUT_CONFIGS = S.HELDOUT_CONFIGS


def heldout_scenes():
    """name -> scene text of the walk variant (the default method), h01 ... h08."""
    label = "randomwalk (default)"
    return {name: pbrt_writer.scene_text(sc, label, sc["dermis"][label])
            for name, sc in S.HELDOUT.items() if name.endswith("-walk")}


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
