#!/usr/bin/python3
"""Writes the seed corpus of the fuzz targets, fuzz/corpus/<target>/, from scenes/ and
small files made here (the big meshes of scenes/meshes are not copied). Run it again after
adding scenes; the corpus is committed, so fuzzing and the replay test need no Python.
Keep the whole corpus under about 2 MB."""
import gzip
import pathlib
import shutil
import struct
import subprocess

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"
MAX_SEED = 128 * 1024  # bytes; larger files are left out


def put(target, name, data):
    d = CORPUS / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def scenes():
    for p in sorted(ROOT.glob("scenes/**/*.pbrt")):
        if p.stat().st_size <= MAX_SEED:
            put("scene_parser", str(p.relative_to(ROOT / "scenes")).replace("/", "_"), p.read_bytes())
    # Directives the bundled scenes do not use.
    put("scene_parser", "extra_directives.pbrt", """
Option "bool disablepixeljitter" true
ColorSpace "srgb"
Camera "perspective" "float fov" 45
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
AttributeBegin
  CoordinateSystem "a"
  TransformBegin Translate 1 2 3 TransformEnd
  CoordSysTransform "a"
  ReverseOrientation
  Texture "c" "spectrum" "checkerboard" "float uscale" 4 "rgb tex1" [1 0 0] "rgb tex2" [0 0 1]
  MakeNamedMaterial "m" "string type" "diffuse" "texture reflectance" "c"
  NamedMaterial "m"
  ObjectBegin "o"
    Shape "sphere" "float radius" 1
    Shape "disk" "float radius" 2
    Shape "bilinearmesh" "point3 P" [0 0 0 1 0 0 0 1 0 1 1 0]
  ObjectEnd
  ObjectInstance "o"
  MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [1 1 1] "rgb sigma_s" [1 1 1]
  MakeNamedMedium "smoke" "string type" "uniformgrid" "integer nx" 2 "integer ny" 1 "integer nz" 2
    "float density" [0 1 2 3] "float Lescale" [1 0 1 0] "rgb Le" [1 0.5 0] "point3 p0" [-1 -1 -1] "point3 p1" [1 1 1]
  MakeNamedMedium "fire" "string type" "uniformgrid" "float density" [1] "float temperature" [2000]
    "float temperaturecutoff" 100 "float temperaturescale" 2
  MakeNamedMedium "tint" "string type" "rgbgrid" "integer nx" 2 "rgb sigma_a" [1 2 3 4 5 6] "rgb Le" [1 1 1 0 0 0]
  MakeNamedMedium "sky" "string type" "cloud" "float wispiness" 0.5 "float frequency" 3
  MediumInterface "fog" ""
  AreaLightSource "diffuse" "rgb L" [1 1 1]
  Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
AttributeEnd
LightSource "point" "rgb I" [1 1 1]
LightSource "distant" "point3 from" [0 0 1] "point3 to" [0 0 0]
LightSource "infinite" "rgb L" [0.1 0.1 0.1]
Material "subsurface" "string method" "randomwalk" "rgb mfp" [1 2 3]
Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
""")


TRI_HEAD = ("ply\nformat {fmt} 1.0\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float u\n"
            "property float v\nelement {elem} {n}\nproperty list uchar int vertex_indices\nend_header\n")
VERTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


def ply_binary(endian, elem, lists):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    out = TRI_HEAD.format(fmt=fmt, elem=elem, n=len(lists)).encode()
    for i, (x, y, z) in enumerate(VERTS):
        out += struct.pack(endian + "8f", x, y, z, 0, 0, 1, x, y)
    for lst in lists:
        out += struct.pack(endian + "B", len(lst)) + struct.pack(endian + "%di" % len(lst), *lst)
    return out


def plys():
    for p in [ROOT / "scenes/pbrt-v4/head/geometry/head.ply", ROOT / "scenes/pbrt-v4/sssdragon/geometry/dragon.ply.gz"]:
        if p.exists() and p.stat().st_size <= MAX_SEED:
            put("ply_reader", p.name, p.read_bytes())
    ascii_body = "".join("%g %g %g 0 0 1 %g %g\n" % (x, y, z, x, y) for x, y, z in VERTS)
    put("ply_reader", "quad_ascii.ply", TRI_HEAD.format(fmt="ascii", elem="face", n=1) + ascii_body + "4 0 1 2 3\n")
    put("ply_reader", "tris_le.ply", ply_binary("<", "face", [[0, 1, 2], [0, 2, 3]]))
    put("ply_reader", "tris_be.ply", ply_binary(">", "face", [[0, 1, 2], [0, 2, 3]]))
    put("ply_reader", "strip_le.ply", ply_binary("<", "tristrips", [[0, 1, 3, 2, -1, 0, 1, 2]]))
    put("ply_reader", "tris_le.ply.gz", gzip.compress(ply_binary("<", "face", [[0, 1, 2]]), mtime=0))
    put("ply_reader", "extra_element.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
        "element material 1\nproperty uchar red\nproperty list ushort short names\n"
        "element face 1\nproperty list uint8 uint32 vertex_index\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
        "255 2 7 8\n3 0 1 2\n")


def objs():
    put("obj_assimp", "cube.obj", """# a cube with normals, uvs, groups and quads
o cube
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
g bottom
f 1/1/1 4/4/1 3/3/1 2/2/1
g top
f 5/1/2 6/2/2 7/3/2 8/4/2
g sides
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
""")
    put("obj_assimp", "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    put("obj_assimp", "negative_indices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf -4 -3 -2\nf -3 -1 -2\nl 1 2\np 3\n")
    # the head of the bust (vertices and faces that only use them are not guaranteed: a
    # prefix still exercises the parser)
    big = ROOT / "scenes/meshes/nefertiti.obj"
    if big.exists():
        with open(big, "rb") as f:
            put("obj_assimp", "nefertiti_prefix.obj", f.read(16 * 1024))


def images():
    for p in sorted(ROOT.glob("scenes/**/textures/*")):
        if p.suffix in (".png", ".exr", ".hdr") and p.stat().st_size <= MAX_SEED:
            put("image_texture", p.parent.parent.name + "_" + p.name, p.read_bytes())
    d = CORPUS / "image_texture"
    for args, name in [(["--pattern", "checker:width=2:height=2", "4x4", "3"], "checker_rgb8.png"),
                       (["--pattern", "constant:color=0.5", "3x2", "1"], "gray.png"),
                       (["--pattern", "fill:top=0,0,0,1:bottom=1,1,1,0", "4x4", "4"], "gradient_rgba16.png"),
                       (["--pattern", "checker:width=2:height=2", "4x4", "3"], "checker.hdr"),
                       (["--pattern", "fill:top=0,0,0:bottom=1,2,3", "4x4", "3"], "gradient_half.exr")]:
        extra = ["-d", "uint16"] if "16" in name else ["-d", "half"] if name.endswith(".exr") else []
        subprocess.run(["oiiotool"] + args + extra + ["-o", str(d / name)], check=True)


def point_clouds():
    def cloud(points):
        out = b"DRMSPCLD" + struct.pack("<IIQ", 1, 44, len(points))
        for (p, n, area, tri, e) in points:
            out += struct.pack("<3f3ffI3f", *p, *n, area, tri, *e)
        return out
    put("point_cloud", "empty.pcl", cloud([]))
    put("point_cloud", "three.pcl", cloud([((0, 0, 0), (0, 0, 1), 0.1, 0, (1, 1, 1)),
                                           ((1, 0, 0), (0, 1, 0), 0.2, 1, (0.5, 0, 2)),
                                           ((0, 1, 0), (1, 0, 0), 0.0, 7, (0, 0, 0))]))


if __name__ == "__main__":
    for t in ["scene_parser", "ply_reader", "obj_assimp", "image_texture", "point_cloud"]:
        shutil.rmtree(CORPUS / t, ignore_errors=True)
    scenes()
    plys()
    objs()
    images()
    point_clouds()
    total = sum(p.stat().st_size for p in CORPUS.rglob("*") if p.is_file())
    print("fuzz corpus: %d files, %d bytes" % (sum(1 for p in CORPUS.rglob("*") if p.is_file()), total))
