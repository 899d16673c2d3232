#!/usr/bin/env bash
# Issue 5's comparison, after Langlands & Mertens' table (seed 001): a sparse point
# cloud with the local disk integral against a cloud 12x denser without it, both
# against a converged probe-ray (disk) render of the same dipole profile. The demo's
# key light is made 3x wider and 9x dimmer (same power) so that its specular
# reflection, found by chance, does not dominate every image's error.
#   bash bench/pointcloud_comparison.sh [SPARSE_POINTS] [SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
SPARSE=${1:-5000}
SPP=${2:-16}
DENSE=$((SPARSE * 12))
OUT=${OUT:-out/pointcloud}
mkdir -p "$OUT"
BIN=./build/dermis
scene() {  # $1 = method line
  sed -e "s|\"string method\" \"randomwalk\" \"string boundary\" \"diffuse\" \"string walksampling\" \"mis\"|$1|" \
      -e 's|"string name" "Skin1" "float scale" 0.1|"rgb reflectance" [0.8 0.55 0.4] "rgb mfp" [12 6 3]|' \
      -e 's|"meshes/nefertiti.obj"|"../meshes/nefertiti.obj"|' \
      -e 's|"rgb L" \[ 40 34 26 \]|"rgb L" [ 4.4 3.8 2.9 ]|' \
      -e 's|-150 0 -150   150 0 -150   -150 0 150   150 0 150|-450 0 -450   450 0 -450   -450 0 450   450 0 450|' \
      scenes/demo.pbrt
}
scene '"string method" "disk" "string profile" "dipole"' > scenes/bench/bust-pc-reference.pbrt
scene '"string method" "pointcloud" "string profile" "dipole" "bool localdisk" true' > scenes/bench/bust-pc-localdisk.pbrt
scene '"string method" "pointcloud" "string profile" "dipole" "bool localdisk" false' > scenes/bench/bust-pc-plain.pbrt
RES=200x200
echo "reference: disk, dipole, $((SPP * 32)) spp"
$BIN render scenes/bench/bust-pc-reference.pbrt --res $RES --spp $((SPP * 32)) --seed 1 -o "$OUT/reference.exr" -q
run() {  # $1 name, $2 scene, $3 points
  echo "== $1 ($3 points, $SPP spp)"
  $BIN render "$2" --res $RES --spp "$SPP" --seed 2 --points "$3" --save-pointcloud "$OUT/$1.cloud" \
       -o "$OUT/$1.exr" 2>&1 | grep -E "point clouds|wrote"
  $BIN compare "$OUT/$1.exr" "$OUT/reference.exr" | grep -E "RMSE|relMSE|rel"
}
run sparse-localdisk scenes/bench/bust-pc-localdisk.pbrt "$SPARSE"
run sparse-plain scenes/bench/bust-pc-plain.pbrt "$SPARSE"
run dense-plain scenes/bench/bust-pc-plain.pbrt "$DENSE"
run dense-localdisk scenes/bench/bust-pc-localdisk.pbrt "$DENSE"
