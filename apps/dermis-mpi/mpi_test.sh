#!/bin/bash
# The tests of dermis-mpi (registered by apps/dermis-mpi/CMakeLists.txt):
#   mpi_test.sh CHECK DERMIS DERMIS_MPI MPIEXEC
# walk, pointcloud: `mpirun -n 2` renders the image of `dermis render`, bit for bit;
# adaptive: the same with --noise-threshold;
# timelimit: both ranks stop and rank 0 writes; badscene: one message, exit status 2;
# rankfails: a rank that fails alone while preparing ends the job (MPI_Abort), status 2.
set -u
check=$1 dermis=$2 dermis_mpi=$3 mpiexec=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# As root in a container: allow it; no shared-memory single-copy (no CMA/ptrace there).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
fail() { echo "FAIL: $*"; exit 1; }
mpi() { "$mpiexec" -n 2 --oversubscribe "$dermis_mpi" "$@"; }
# Bit-identical pixels: every difference is exactly zero.
same_image() {
  local d
  d=$("$dermis" compare "$1" "$2" | grep '^max |A-B|') || fail "cannot compare $1 $2"
  [ "$(echo "$d" | awk '{print $3 $4 $5 $6}')" = "0000" ] || fail "images differ: $d"
}

header='LookAt 0 0.3 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 35
Film "rgb" "integer xresolution" 48 "integer yresolution" 40
WorldBegin
LightSource "infinite" "rgb L" [0.4 0.4 0.4]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [6 6 6]
  Translate 2 3 -2
  Shape "sphere" "float radius" 0.5
AttributeEnd
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-4 -1 -4  4 -1 -4  4 -1 4  -4 -1 4] "integer indices" [0 1 2 0 2 3]'

case $check in
  walk)
    # The random walk. dermis: its albedo table from the user's cache (built there
    # once); dermis-mpi: built in shares (an empty cache), then broadcast from the cache.
    cat > "$dir/s.pbrt" <<SCENE
$header
Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.3 0.2 0.1] "string method" "randomwalk"
Shape "sphere" "float radius" 0.9
SCENE
    "$dermis" render "$dir/s.pbrt" -q --no-png --seed 7 --spp 6 -o "$dir/one.exr" || fail "dermis render"
    XDG_CACHE_HOME=$dir/cache mpi render "$dir/s.pbrt" -q --no-png --seed 7 --spp 6 -o "$dir/two.exr" || fail "dermis-mpi render"
    same_image "$dir/two.exr" "$dir/one.exr"
    mpi render "$dir/s.pbrt" -q --no-png --seed 7 --spp 6 -o "$dir/three.exr" --tiles blocks || fail "dermis-mpi render (cache)"
    same_image "$dir/three.exr" "$dir/one.exr"
    ;;
  pointcloud)
    cat > "$dir/s.pbrt" <<SCENE
$header
Material "subsurface" "rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [0.2 0.2 0.2] "string method" "pointcloud"
Shape "sphere" "float radius" 0.9
SCENE
    "$dermis" render "$dir/s.pbrt" -q --no-png --seed 3 --spp 4 --points 2000 -o "$dir/one.exr" || fail "dermis render"
    mpi render "$dir/s.pbrt" --no-png --seed 3 --spp 4 --points 2000 -o "$dir/two.exr" > "$dir/log" 2>&1 || { cat "$dir/log"; fail "dermis-mpi render"; }
    same_image "$dir/two.exr" "$dir/one.exr"
    # One summary, by rank 0, with every rank's samples.
    [ "$(grep -c '^dermis: wrote' "$dir/log")" = 1 ] || { cat "$dir/log"; fail "not one summary line"; }
    grep -q "$((48 * 40 * 4)) samples" "$dir/log" || { cat "$dir/log"; fail "samples of all ranks not summed"; }
    ;;
  adaptive)
    # Adaptive sampling: the passes' decisions use the whole image's error map, exchanged
    # between the ranks; the image (and so every pixel's count) is the single process's.
    cat > "$dir/s.pbrt" <<SCENE
$header
Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.3 0.2 0.1] "string method" "randomwalk"
Shape "sphere" "float radius" 0.9
SCENE
    "$dermis" render "$dir/s.pbrt" -q --no-png --seed 5 --spp 128 --noise-threshold 0.05 -o "$dir/one.exr" || fail "dermis render"
    mpi render "$dir/s.pbrt" --no-png --seed 5 --spp 128 --noise-threshold 0.05 -o "$dir/two.exr" > "$dir/log" 2>&1 || { cat "$dir/log"; fail "dermis-mpi render"; }
    same_image "$dir/two.exr" "$dir/one.exr"
    grep -q 'adaptive sampling: .* converged' "$dir/log" || { cat "$dir/log"; fail "no adaptive summary"; }
    ;;
  timelimit)
    cat > "$dir/s.pbrt" <<SCENE
$header
Material "subsurface" "rgb sigma_a" [0.5 1 2] "rgb sigma_s" [20 20 20] "string method" "randomwalk"
Shape "sphere" "float radius" 0.9
SCENE
    mpi render "$dir/s.pbrt" --no-png --spp 1000000 --time-limit 1 -o "$dir/t.exr" > "$dir/log" 2>&1
    rc=$?
    [ $rc = 0 ] || { cat "$dir/log"; fail "exit status $rc"; }
    grep -q 'time limit reached' "$dir/log" || { cat "$dir/log"; fail "no time-limit message"; }
    [ -f "$dir/t.exr" ] || fail "no image"
    ;;
  badscene)
    printf 'WorldBegin\nShape "sphere" "float radius" "oops"\n' > "$dir/bad.pbrt"
    mpi render "$dir/bad.pbrt" -o "$dir/b.exr" > "$dir/log" 2>&1
    rc=$?
    [ $rc = 2 ] || { cat "$dir/log"; fail "exit status $rc, not 2"; }
    [ "$(grep -c 'dermis-mpi render:' "$dir/log")" = 1 ] || { cat "$dir/log"; fail "not one message"; }
    [ ! -e "$dir/b.exr" ] || fail "an image was written"
    ;;
  rankfails)
    # One rank fails while preparing (its --load-pointcloud file is missing, as on a node
    # without the shared disk) while the other goes on: the job ends, with that rank's
    # message and exit status 2, no image, and no wait (ctest's timeout would catch one).
    cat > "$dir/s.pbrt" <<SCENE
$header
Material "subsurface" "rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [0.2 0.2 0.2] "string method" "pointcloud"
Shape "sphere" "float radius" 0.9
SCENE
    "$dermis" render "$dir/s.pbrt" -q --no-png --spp 1 --points 2000 --save-pointcloud "$dir/pc.bin" -o "$dir/one.exr" \
      || fail "dermis render --save-pointcloud"
    common=(render "$dir/s.pbrt" -q --no-png --spp 1 -o "$dir/two.exr")
    timeout 60 "$mpiexec" --oversubscribe -n 1 "$dermis_mpi" "${common[@]}" --load-pointcloud "$dir/pc.bin" \
      : -n 1 "$dermis_mpi" "${common[@]}" --load-pointcloud "$dir/missing.bin" > "$dir/log" 2>&1
    rc=$?
    [ $rc = 2 ] || { cat "$dir/log"; fail "exit status $rc, not 2"; }
    grep -q "dermis-mpi render: point cloud '$dir/missing.bin': cannot open the file (rank 1); aborting the job" \
      "$dir/log" || { cat "$dir/log"; fail "no message naming the file and the rank"; }
    [ ! -e "$dir/two.exr" ] || fail "an image was written"
    ;;
  *) fail "unknown check $check" ;;
esac
echo "ok: $check"
