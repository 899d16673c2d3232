#!/bin/bash
# Whether two dermis builds render the same images, bit for bit: each scene rendered by both at
# a fixed seed (3), one thread, and the pixels compared exactly. For changes meant to leave the
# pictures alone (a refactor, formatting); a change that moves the noise but not the mean is
# compared with compare_efficiency.py instead.
#   bench/same_images.sh OLD_DERMIS NEW_DERMIS OUT_DIR SCENE.pbrt...   (RES=64x48 SPP=16 by default)
set -u
old=$1 new=$2 out=$3
shift 3
mkdir -p "$out/old" "$out/new" "$out/cache"
export XDG_CACHE_HOME=$out/cache  # a cache of their own, shared by both
for f in "$@"; do
  n=$(basename "$f" .pbrt)
  for side in old new; do
    bin=$old
    [ "$side" = new ] && bin=$new
    "$bin" render "$f" --res "${RES:-64x48}" --spp "${SPP:-16}" --seed 3 --threads 1 -q --no-png \
      -o "$out/$side/$n.exr" 2>"$out/$side/$n.err" || echo "FAILED: $side $n"
  done
done
/usr/bin/python3 - "$out" <<'PY'
import glob, os, sys
import numpy as np
import OpenImageIO as oiio
out = sys.argv[1]
same = differ = 0
for p in sorted(glob.glob(os.path.join(out, "old", "*.exr"))):
    a = oiio.ImageBuf(p).get_pixels(oiio.FLOAT)
    b = oiio.ImageBuf(p.replace("/old/", "/new/")).get_pixels(oiio.FLOAT)
    if a.shape == b.shape and np.array_equal(a, b):
        same += 1
    else:
        differ += 1
        print("differs:", os.path.basename(p), float(np.abs(a - b).max()) if a.shape == b.shape else "size")
print(f"{same} identical, {differ} different")
PY
