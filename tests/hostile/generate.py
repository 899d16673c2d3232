#!/usr/bin/python3
"""Writes the hostile corpus: malformed scenes, meshes, images and command lines for
`dermis render` (docs/robustness.md). Each case is a directory CASES/<name>/ with its input
files and case.json: the arguments (after `dermis`), the exit status expected (0: renders;
2: refused with a message) and the kind of refusal ("scene": the message must carry
file:line:col: error:, "cli": any message). tests/hostile/run.py runs them.

Usage: generate.py CASES_DIR   (the directory is emptied first)."""
import gzip
import json
import os
import pathlib
import random
import shutil
import struct
import sys
import zlib

RENDER = ["render", "scene.pbrt", "--spp", "1", "--res", "8x8", "-q", "-o", "out/image.exr"]

# A cheap scene that renders: every directive kind the cases below break.
BASE = """LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
Sampler "independent" "integer pixelsamples" 1
WorldBegin
LightSource "point" "point3 from" [0 0 4] "rgb I" [10 10 10]
AttributeBegin
  Material "subsurface" "string method" "randomwalk" "rgb reflectance" [0.8 0.6 0.5] "rgb mfp" [0.5 0.5 0.5]
  Shape "sphere" "float radius" 1
AttributeEnd
AttributeBegin
  Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
  Shape "trianglemesh" "point3 P" [-5 -1 -5 5 -1 -5 5 -1 5 -5 -1 5] "integer indices" [0 1 2 0 2 3]
AttributeEnd
"""
HEAD = BASE.split("WorldBegin")[0] + "WorldBegin\n"
LIGHT = 'LightSource "point" "point3 from" [0 0 4] "rgb I" [10 10 10]\n'

cases = []


def case(name, files, expect, kind="scene", args=None, note=""):
    """files: {relative path: str | bytes | None (a FIFO) }."""
    assert expect in (0, 2)
    cases.append(dict(name=name, files=files, expect=expect, kind=kind if expect == 2 else "ok",
                      args=args or RENDER, note=note))


def world(body, name, expect, **kw):
    case(name, {"scene.pbrt": HEAD + LIGHT + body}, expect, **kw)


# ------------------------------------------------------------------ truncated scenes
def truncations(text, tag, whole_lines=True, every=1):
    """Cuts that leave a directive unfinished (expected 2): inside a quoted string, inside
    [...], right after a parameter's type-and-name string; and cuts after whole lines once
    the world has begun (expected 0)."""
    lines = text.splitlines(keepends=True)
    offset, world_at = 0, text.index("WorldBegin") + len("WorldBegin\n")
    for i, line in enumerate(lines):
        start = offset
        offset += len(line)
        if i % every:
            continue
        q = line.find('"')
        if q >= 0:
            case(f"trunc_{tag}_l{i}_in_string", {"scene.pbrt": text[:start + q + 2]}, 2)
        b = line.find("[")
        if b >= 0:
            case(f"trunc_{tag}_l{i}_after_bracket", {"scene.pbrt": text[:start + b + 1]}, 2)
            sp = line.find(" ", b + 2)
            if 0 <= sp < line.find("]"):
                case(f"trunc_{tag}_l{i}_in_list", {"scene.pbrt": text[:start + sp]}, 2)
        # after a "type name" string that has a value following it
        parts = line.split('"')
        if len(parts) >= 5 and " " in parts[3]:
            cut = start + len('"'.join(parts[:4])) + 1
            case(f"trunc_{tag}_l{i}_param_without_value", {"scene.pbrt": text[:cut]}, 2)
        if whole_lines and start >= world_at:
            # Cut inside an AttributeBegin block: an error, as in pbrt-v4 (the block is left open).
            kept = [l.split("#")[0].split() for l in lines[:i + 1]]
            open_blocks = sum(1 for w in kept if w[:1] == ["AttributeBegin"]) - sum(1 for w in kept if w[:1] == ["AttributeEnd"])
            case(f"trunc_{tag}_l{i}_whole_lines", {"scene.pbrt": text[:offset]}, 2 if open_blocks else 0)


truncations(BASE, "base")
# a real scene of the project (inline geometry, area and infinite lights, a random walk)
SLAB = (pathlib.Path(__file__).resolve().parents[2] / "scenes/bench/slab-walk-mis.pbrt").read_text()
truncations(SLAB, "slab", whole_lines=False, every=3)

# ------------------------------------------------------------------ wrong types / counts
DIRECTIVES = {  # directive: (a valid use, uses that must be refused)
    "Translate": ("Translate 1 2 3", ["Translate", "Translate 1 2", 'Translate "1" 2 3', "Translate [1 2 3"]),
    "Scale": ("Scale 1 2 3", ["Scale 1", "Scale a b c", "Scale 0 0 0"]),
    "Rotate": ("Rotate 30 0 0 1", ["Rotate 30", "Rotate 30 0 0 0", 'Rotate "30" 0 0 1']),
    "LookAt": ("LookAt 0 0 1 0 0 0 0 1 0", ["LookAt 0 0 1", "LookAt 0 0 0 0 0 0 0 1 0", "LookAt 0 0 1 0 0 0 0 0 1 x"]),
    "Transform": ("Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
                  ["Transform [1 0 0]", "Transform [0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0]", "Transform 1"]),
    "ConcatTransform": ("ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
                        ["ConcatTransform", "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 7]"]),
    "CoordinateSystem": ('CoordinateSystem "c"', ["CoordinateSystem", "CoordinateSystem 4"]),
    "CoordSysTransform": ('CoordinateSystem "c" CoordSysTransform "c"', ["CoordSysTransform", "CoordSysTransform 1"]),
    "AttributeBegin": ("AttributeBegin AttributeEnd", ["AttributeEnd", "AttributeBegin AttributeEnd AttributeEnd"]),
    "TransformBegin": ("TransformBegin TransformEnd", ["TransformEnd"]),
    "Material": ('Material "diffuse"', ["Material", "Material 3", 'Material "plastic-ish"', 'Material "difuse"',
                                        ('Material "hair"', 0),
                                        'Material "diffuse" "rgb reflectance" [1 2]',
                                        'Material "diffuse" "rgb reflectance" "red"',
                                        'Material "subsurface" "string method" "psychic"',
                                        'Material "subsurface" "rgb mfp" [-1 -1 -1]',
                                        'Material "subsurface" "float eta" "x"',
                                        # a heterogeneous interior (docs/materials.md): the name, the method
                                        ('MakeNamedMedium "g" "string type" "uniformgrid" "float density" [1 0.5] '
                                         '"integer nx" 2 Material "subsurface" "string interior" "g"', 0),
                                        'Material "subsurface" "string interior" "nowhere"',
                                        'Material "subsurface" "string interior" 3',
                                        'MakeNamedMedium "g" "string type" "uniformgrid" "float density" [1] '
                                        'Material "subsurface" "string interior" "g" "string method" "disk"',
                                        'MakeNamedMedium "g" "string type" "homogeneous" '
                                        'Material "subsurface" "string interior" "g" "float scale" 2']),
    "MakeNamedMaterial": ('MakeNamedMaterial "m" "string type" "diffuse"',
                          ["MakeNamedMaterial", 'MakeNamedMaterial "m"', 'MakeNamedMaterial "m" "string type" 5']),
    "NamedMaterial": ('MakeNamedMaterial "m" "string type" "diffuse" NamedMaterial "m"',
                      ["NamedMaterial", 'NamedMaterial "nope"', "NamedMaterial 1"]),
    "Texture": ('Texture "t" "spectrum" "checkerboard"',
                ["Texture", 'Texture "t"', 'Texture "t" "spectrum"', 'Texture "t" "colour" "checkerboard"',
                 'Texture "t" "spectrum" "imagemap"', 'Texture "t" "spectrum" "imagemap" "string filename" "none.png"']),
    "Shape": ('Shape "sphere"', ["Shape", "Shape 1", 'Shape "sphere" "float radius" -1',
                                 'Shape "sphere" "float radius" "one"', 'Shape "sphere" "float radius" [1',
                                 'Shape "trianglemesh" "point3 P" [0 0 0 1 0 0] "integer indices" [0 1 2]',
                                 'Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 5]',
                                 'Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1]',
                                 'Shape "plymesh"', 'Shape "plymesh" "string filename" "none.ply"',
                                 'Shape "objmesh" "string filename" "none.obj"',
                                 'Shape "disk" "float radius" 0', 'Shape "sphere" "blob radius" 1']),
    "ObjectBegin": ('ObjectBegin "o" Shape "sphere" ObjectEnd ObjectInstance "o"',
                    ["ObjectBegin", 'ObjectBegin "o"', "ObjectEnd", 'ObjectInstance "missing"', "ObjectInstance"]),
    "LightSource": ('LightSource "point"', ["LightSource", "LightSource 2", 'LightSource "laser"', ('LightSource "goniometric"', 0),
                                           'LightSource "point" "rgb I" [-1 -1 -1]',
                                           'LightSource "point" "rgb I" [1e39 1 1]',
                                           'LightSource "infinite" "string filename" "none.exr"',
                                           'LightSource "distant" "point3 from" [0 0 0] "point3 to" [0 0 0]']),
    "AreaLightSource": ('AreaLightSource "diffuse" "rgb L" [1 1 1]',
                        ["AreaLightSource", 'AreaLightSource "diffuse" "rgb L" [-1 0 0]']),
    "MakeNamedMedium": ('MakeNamedMedium "f" "string type" "homogeneous"',
                        ["MakeNamedMedium", 'MakeNamedMedium "f"', 'MakeNamedMedium "f" "string type" "plasma"',
                        'MakeNamedMedium "f" "string type" "nanovdb"',
                        'MakeNamedMedium "f" "string type" "nanovdb" "string filename" "none.nvdb"',
                        # grid media (docs/scene-format.md): the count, the values, the box
                        ('MakeNamedMedium "f" "string type" "uniformgrid" "float density" [1]', 0),
                        ('MakeNamedMedium "f" "string type" "cloud"', 0),
                        ('MakeNamedMedium "f" "string type" "rgbgrid" "rgb sigma_s" [1 2 3]', 0),
                        'MakeNamedMedium "f" "string type" "uniformgrid"',
                        'MakeNamedMedium "f" "string type" "uniformgrid" "integer nx" 2 "float density" [1 2 3]',
                        'MakeNamedMedium "f" "string type" "uniformgrid" "integer nx" 2 "float density" [1 -1]',
                        'MakeNamedMedium "f" "string type" "uniformgrid" "integer nz" -4 "float density" [1]',
                        'MakeNamedMedium "f" "string type" "uniformgrid" "float density" [1] '
                        '"point3 p0" [0 0 0] "point3 p1" [0 1 1]',
                        'MakeNamedMedium "f" "string type" "uniformgrid" "float density" [nan]',
                        'MakeNamedMedium "f" "string type" "rgbgrid"',
                        'MakeNamedMedium "f" "string type" "rgbgrid" "integer ny" 2 "rgb sigma_a" [1 2 3]',
                        'MakeNamedMedium "f" "string type" "cloud" "point3 p0" [1 1 1] "point3 p1" [1 2 2]']),
    "MediumInterface": ('MakeNamedMedium "f" "string type" "homogeneous" MediumInterface "f" ""',
                        # an unknown name is an error once something uses it (pbrt-v4 resolves at use)
                        ["MediumInterface", 'MediumInterface "nowhere" "" Shape "sphere"', "MediumInterface 1 2"]),
    "ReverseOrientation": ("ReverseOrientation", ["ReverseOrientation 1"]),
    "Attribute": ('Attribute "shape" "float radius" 2', ["Attribute", ('Attribute "nothing" "float x" 1', 0)]),
    "Unknown": ('', ["Shpe \"sphere\"", "Frobnicate", "worldbegin", "]", "[ 1 2 ]", '"lonely string"', "42"]),
}
for d, (good, bads) in DIRECTIVES.items():
    if good:
        world(good + "\n", f"directive_{d}_valid", 0)
    for i, bad in enumerate(bads):
        # (text, 0): ignored or approximated with a warning (docs/scene-format.md), not refused
        text, ex = bad if isinstance(bad, tuple) else (bad, 2)
        world(text + "\n", f"directive_{d}_bad{i}", ex)

# nanovdb media reading files that are not .nvdb volumes (tests/hostile/: no NanoVDB writer
# here; valid files are made by the C++ tests)
NVDB = 'MakeNamedMedium "f" "string type" "nanovdb" "string filename" "v.nvdb"\nMediumInterface "f" ""\nShape "sphere"\n'
for i, data in enumerate([b"", b"NanoVDB0" + b"\0" * 8, b"\x4e\x61\x6e\x6f\x56\x44\x42\x30" * 40, bytes(range(256)) * 8]):
    case(f"nanovdb_file_bad{i}", {"scene.pbrt": HEAD + LIGHT + NVDB, "v.nvdb": data}, 2)
case("nanovdb_file_directory", {"scene.pbrt": HEAD + LIGHT + NVDB.replace("v.nvdb", "d"), "d/x": "x"}, 2)

# Options before WorldBegin
OPTIONS = ['Camera', 'Camera 1', 'Camera "fisheye"', ('Camera "orthographic"', 0), 'Film "film"',
           'PixelFilter "gauss"', ('PixelFilter "mitchell"', 0), 'Film', 'Film "rgb" "integer xresolution" 0',
           'Film "rgb" "integer xresolution" -8', 'Film "rgb" "integer xresolution" 2.5',
           'Film "rgb" "integer yresolution" "tall"', 'Sampler "independent" "integer pixelsamples" 0',
           'Sampler "independent" "integer pixelsamples" -3', 'Integrator "volpath" "integer maxdepth" -1',
           'Camera "perspective" "float fov" 0', 'Camera "perspective" "float fov" 200',
           'Camera "perspective" "float lensradius" -1', ('PixelFilter "gaussian" "float radius" -1', 0),
           'WorldBegin WorldBegin']
for i, o in enumerate(OPTIONS):
    text, ex = o if isinstance(o, tuple) else (o, 2)
    case(f"options_bad{i}", {"scene.pbrt": BASE.split("WorldBegin")[0] + text + "\nWorldBegin\n" + LIGHT}, ex)

# ------------------------------------------------------------------ numbers
# strtod's forms (hex, a leading '+') are numbers; beyond float range, or 1e20 away (scene_extent.h), is refused.
NUMBERS = [("1e39", 2), ("-1e39", 2), ("1e400", 2), ("-0", 0), ("nan", 2), ("inf", 2), ("0x10", 0), ("1.2.3", 2),
           ("1e-400", 0), ("--1", 2), ("+.5", 0), (".", 2), ("1e", 2), ("99999999999999999999", 2)]
for i, (n, ex) in enumerate(NUMBERS):
    world(f'Shape "sphere" "float radius" {n}\n', f"number_radius_{i}", 2 if ex == 2 or n in ("-0", "1e-400") else 0)
    world(f"Translate {n} 0 0\nShape \"sphere\"\n", f"number_translate_{i}", ex)
for i, n in enumerate(["1e10", "-1", "2147483648", "1.5", "99999999999999999999"]):
    world(f'Material "subsurface" "integer irradiancesamples" {n}\nShape "sphere"\n', f"number_integer_{i}", 2)
for i, n in enumerate(["1e20", "-1e20", "1e30"]):  # beyond what Embree can trace, even out of view
    world(f"Translate {n} 0 0\nShape \"sphere\"\n", f"number_far_{i}", 2)
for i, n in enumerate(["1e19", "1e30"]):  # the camera far away, looking at a sphere there
    case(f"number_far_camera_{i}", {"scene.pbrt": BASE.replace("LookAt 0 0 5  0 0 0", f"LookAt {n} 0 5  {n} 0 0")
                                    + f'Translate {n} 0 0\nShape "sphere"\n'}, 2)
world('Scale 1e-30 1e-30 1e-30\nShape "sphere"\n', "number_tiny_scale", 0)

# ------------------------------------------------------------------ resolutions
for i, (x, y) in enumerate([(100000000, 100), (100000, 100000), (2147483647, 2147483647), (65536, 65536)]):
    case(f"film_huge_{i}", {"scene.pbrt": BASE.replace('"integer xresolution" 8 "integer yresolution" 8',
                                                      f'"integer xresolution" {x} "integer yresolution" {y}')},
         2, args=["render", "scene.pbrt", "--spp", "1", "-q", "-o", "out/image.exr"])
for i, n in enumerate(["1e10", "4294967297"]):
    case(f"film_overflow_{i}", {"scene.pbrt": BASE.replace('"integer xresolution" 8', f'"integer xresolution" {n}')},
         2, args=["render", "scene.pbrt", "--spp", "1", "-q", "-o", "out/image.exr"])

# ------------------------------------------------------------------ includes
world('Include "scene.pbrt"\n', "include_self", 2)
case("include_cycle", {"scene.pbrt": HEAD + 'Include "a.pbrt"\n', "a.pbrt": 'Include "b.pbrt"\n',
                       "b.pbrt": 'Include "a.pbrt"\n'}, 2)
for depth, ex in [(10, 0), (60, 0), (70, 2), (300, 2), (5000, 2)]:
    files = {"scene.pbrt": HEAD + LIGHT + 'Include "inc/0.pbrt"\n'}
    for k in range(depth):
        files[f"inc/{k}.pbrt"] = f'Include "{k + 1}.pbrt"\n' if k + 1 < depth else 'Shape "sphere"\n'
    case(f"include_depth_{depth}", files, ex)
world('Include "missing.pbrt"\n', "include_missing", 2)
world('Include "dir"\n', "include_directory", 2)
cases[-1]["files"]["dir/keep"] = ""
world('Include "fifo"\n', "include_fifo", 2)
cases[-1]["files"]["fifo"] = None
world('Include "/dev/zero"\n', "include_dev_zero", 2)
world('Include "/dev/null"\n', "include_dev_null", 2)
world('Include "/etc/passwd"\n', "include_etc_passwd", 2)
world('Include ""\n', "include_empty_name", 2)
world('Include\n', "include_no_name", 2)
world('Include "empty.pbrt"\n', "include_empty_file", 0)
cases[-1]["files"]["empty.pbrt"] = ""
world('Include "broken.pbrt"\n', "include_broken", 2)
cases[-1]["files"]["broken.pbrt"] = 'Shape "sphere" "float radius" [1\n'
world('Import "missing.pbrt"\n', "import_missing", 2)
world('Include "garbage.pbrt.gz"\n', "include_bad_gzip", 2)
cases[-1]["files"]["garbage.pbrt.gz"] = b"\x1f\x8b\x08\x00" + bytes(range(256)) * 4
world('Include "ok.pbrt.gz"\n', "include_gzip", 0)
cases[-1]["files"]["ok.pbrt.gz"] = gzip.compress(b'Shape "sphere"\n', mtime=0)
world('Include "trunc.pbrt.gz"\n', "include_truncated_gzip", 2)
cases[-1]["files"]["trunc.pbrt.gz"] = gzip.compress(b'Shape "sphere"\n' * 100, mtime=0)[:30]

# --confine: only files inside the scene's directory (docs/robustness.md, "File access")
# Spectra (issue 65): a reflectance outside [0, 1] at some wavelength, a non-monotone
# spectrum file, and --spectral with checkpoints (refused) or a subsurface scene (warned).
world('Material "diffuse" "spectrum reflectance" [400 -0.5 700 0.5]\nShape "sphere"\n', "reflectance_negative", 2)
world('Material "diffuse" "spectrum reflectance" "r.spd"\nShape "sphere"\n', "spectrum_file_not_monotone", 2)
cases[-1]["files"]["r.spd"] = "400 0.5 500 0.4\n450 0.3\n"
NO_SSS = BASE.replace('Material "subsurface" "string method" "randomwalk" "rgb reflectance" [0.8 0.6 0.5] "rgb mfp" '
                      '[0.5 0.5 0.5]', 'Material "diffuse"')
assert NO_SSS != BASE
case("spectral_checkpoint", {"scene.pbrt": NO_SSS}, 2, kind="cli",
     args=RENDER + ["--spectral", "--checkpoint", "out/ck.bin"])
case("spectral_subsurface_warns", {"scene.pbrt": BASE}, 0, args=RENDER + ["--spectral"])
CONFINED = RENDER + ["--confine"]
world('Include "../outside.pbrt"\n', "confine_dotdot", 2, args=CONFINED)
world('Include "/etc/passwd"\n', "confine_absolute", 2, args=CONFINED)
world('Include "inc/../inc/ok.pbrt"\n', "confine_inside", 0, args=CONFINED)
cases[-1]["files"]["inc/ok.pbrt"] = 'Shape "sphere"\n'
world('Shape "plymesh" "string filename" "../../mesh.ply"\n', "confine_mesh_dotdot", 2, args=CONFINED)
world('Material "diffuse" "spectrum reflectance" "/usr/share/x.spd"\nShape "sphere"\n', "confine_spd_absolute", 2,
      args=CONFINED)
case("confine_film_filename", {"scene.pbrt": BASE.replace('Film "rgb"', 'Film "rgb" "string filename" "../x.exr"')}, 2,
     args=["render", "scene.pbrt", "--spp", "1", "-q", "--confine"])


# ------------------------------------------------------------------ PLY
def ply(fmt, nverts, nfaces, extra_header="", vprops="property float x\nproperty float y\nproperty float z\n",
        face_prop="property list uchar int vertex_indices\n"):
    return (f"ply\nformat {fmt} 1.0\nelement vertex {nverts}\n{vprops}{extra_header}"
            f"element face {nfaces}\n{face_prop}end_header\n").encode()


def tri_binary(endian, count_bytes=b"\x03", indices=(0, 1, 2), coords=(0, 0, 0, 1, 0, 0, 0, 1, 0)):
    return struct.pack(endian + "9f", *coords) + count_bytes + struct.pack(endian + "3i", *indices)


PLY_SHAPE = 'Shape "plymesh" "string filename" "mesh.ply"\n'
ASCII_TRI = b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
plys = [
    ("valid_ascii", ply("ascii", 3, 1) + ASCII_TRI, 0),
    ("valid_le", ply("binary_little_endian", 3, 1) + tri_binary("<"), 0),
    ("valid_be", ply("binary_big_endian", 3, 1) + tri_binary(">"), 0),
    ("valid_gz", gzip.compress(ply("ascii", 3, 1) + ASCII_TRI, mtime=0), 0),
    ("count_200M_ascii", ply("ascii", 200000000, 1) + ASCII_TRI, 2),
    ("count_200M_le", ply("binary_little_endian", 200000000, 1) + tri_binary("<"), 2),
    ("count_200M_be", ply("binary_big_endian", 200000000, 1) + tri_binary(">"), 2),
    ("faces_2e9_le", ply("binary_little_endian", 3, 2000000000) + tri_binary("<"), 2),
    ("count_2p63_no_props", ply("ascii", 3, 1, extra_header="element junk 9223372036854775807\n") + ASCII_TRI, 0),
    ("faces_2p63_no_props", ply("ascii", 3, 9223372036854775807, face_prop="") + b"0 0 0\n1 0 0\n0 1 0\n", 2),
    ("vertex_2p63_no_props", ply("ascii", 9223372036854775807, 1, vprops="") + ASCII_TRI, 2),
    ("count_2p64", ply("ascii", 18446744073709551616, 1) + ASCII_TRI, 2),
    ("count_negative", ply("ascii", -3, 1) + ASCII_TRI, 2),
    ("count_word", ply("ascii", "three", 1) + ASCII_TRI, 2),
    ("bad_prop_type", ply("ascii", 3, 1, vprops="property quad x\nproperty float y\nproperty float z\n") + ASCII_TRI, 2),
    ("bad_list_type", ply("ascii", 3, 1, face_prop="property list float128 int vertex_indices\n") + ASCII_TRI, 2),
    ("list_count_float", ply("ascii", 3, 1, face_prop="property list float int vertex_indices\n")
     + b"0 0 0\n1 0 0\n0 1 0\n2.5 0 1 2\n", 2),
    ("list_count_negative_le", ply("binary_little_endian", 3, 1, face_prop="property list char int vertex_indices\n")
     + tri_binary("<", count_bytes=b"\xff"), 2),
    ("list_count_huge_be", ply("binary_big_endian", 3, 1, face_prop="property list uint int vertex_indices\n")
     + tri_binary(">", count_bytes=struct.pack(">I", 4000000000)), 2),
    ("no_xyz", ply("ascii", 3, 1, vprops="property float a\nproperty float b\nproperty float c\n") + ASCII_TRI, 2),
    ("no_end_header", b"ply\nformat ascii 1.0\nelement vertex 3\n", 2),
    ("no_format", b"ply\nelement vertex 0\nend_header\n", 2),
    ("bad_format", b"ply\nformat binary_middle_endian 1.0\nend_header\n", 2),
    ("not_ply", b"PLY?" + bytes(100), 2),
    ("index_out_of_range", ply("ascii", 3, 1) + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", 2),
    ("index_negative", ply("ascii", 3, 1) + b"0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 2),
    ("coord_nan", ply("ascii", 3, 1) + b"nan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 2),
    ("coord_inf_le", ply("binary_little_endian", 3, 1) + tri_binary("<", coords=(float("inf"),) + (0,) * 8), 2),
    ("coord_huge", ply("ascii", 3, 1) + b"1e300 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 2),
    ("two_vertex_elements", ply("ascii", 3, 1, extra_header="element vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\n") + ASCII_TRI, 2),
    ("face_before_vertex", b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
     b"element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n", 2),
    ("face_two_vertices", ply("ascii", 3, 1) + b"0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 2),
    ("no_faces", ply("ascii", 3, 0) + b"0 0 0\n1 0 0\n0 1 0\n", 2),
    ("empty", b"", 2),
    ("garbage_gz", b"\x1f\x8b" + bytes(range(200)), 2),
    ("ascii_junk_value", ply("ascii", 3, 1) + b"0 0 zero\n1 0 0\n0 1 0\n3 0 1 2\n", 2),
]
body_le = ply("binary_little_endian", 3, 1) + tri_binary("<")
body_be = ply("binary_big_endian", 3, 1) + tri_binary(">")
head_len = len(ply("binary_little_endian", 3, 1))
for cut in [4, 35, 36, 40, 48]:
    plys.append((f"truncated_le_{cut}", body_le[:head_len + cut], 2))
    plys.append((f"truncated_be_{cut}", body_be[:len(ply("binary_big_endian", 3, 1)) + cut], 2))
for cut in [5, 40, 90]:
    plys.append((f"truncated_header_{cut}", body_le[:cut], 2))
for name, data, ex in plys:
    world(PLY_SHAPE, f"ply_{name}", ex)
    cases[-1]["files"]["mesh.ply"] = data

# ------------------------------------------------------------------ OBJ
OBJ_SHAPE = 'Shape "objmesh" "string filename" "mesh.obj"\n'
objs = [("valid", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 0), ("empty", "", 2),
        ("index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", 2), ("no_faces", "v 0 0 0\n", 2),
        ("garbage", bytes(random.Random(7).randrange(256) for _ in range(3000)), 2),
        ("nan_vertex", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 2),
        ("huge_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n", 2)]
for name, data, ex in objs:
    world(OBJ_SHAPE, f"obj_{name}", ex)
    cases[-1]["files"]["mesh.obj"] = data


# ------------------------------------------------------------------ images
def png(width, height, idat=b"", color_type=2, bit_depth=8):
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + (chunk(b"IDAT", idat) if idat else b"") + chunk(b"IEND", b"")


good_png = png(2, 2, zlib.compress(b"\x00" + b"\xff\x00\x00" * 2 + b"\x00" + b"\x00\xff\x00" * 2))
EXR_MAGIC = b"\x76\x2f\x31\x01"
images = [("valid_png", "tex.png", good_png, 0),
          ("lying_png_65535", "tex.png", png(65535, 65535), 2),
          ("lying_png_20000", "tex.png", png(20000, 20000, zlib.compress(bytes(100))), 2),
          ("lying_png_1x1e9", "tex.png", png(1, 1000000000), 2),
          ("png_zero_size", "tex.png", png(0, 0), 2),
          ("png_bad_crc", "tex.png", good_png[:29] + b"\0\0\0\0" + good_png[33:], 2),
          ("png_truncated", "tex.png", good_png[:40], 2),
          ("png_bad_depth", "tex.png", png(2, 2, zlib.compress(bytes(20)), bit_depth=7), 2),
          ("png_empty", "tex.png", b"", 2),
          ("png_garbage", "tex.png", bytes(random.Random(3).randrange(256) for _ in range(500)), 2),
          ("exr_magic_only", "tex.exr", EXR_MAGIC, 2),
          ("exr_lying_header", "tex.exr", EXR_MAGIC + b"\x02\x00\x00\x00" + b"dataWindow\0box2i\0" +
           struct.pack("<I4i", 16, 0, 0, 2000000000, 2000000000) + b"\0", 2),
          # A string attribute claiming 1.8 GB in a 60-byte file (OpenEXR allocated it: fuzz_image_texture).
          ("exr_lying_attribute", "tex.exr", EXR_MAGIC + b"\x02\x00\x00\x00" + b"comments\0string\0" +
           struct.pack("<i", 1800000000) + bytes(30), 2),
          ("exr_garbage", "tex.exr", EXR_MAGIC + bytes(random.Random(5).randrange(256) for _ in range(400)), 2),
          ("hdr_lying", "tex.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1000000 +X 1000000\n" + bytes(16), 2),
          ("hdr_truncated", "tex.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n" + bytes(9), 2),
          ("tex_is_directory", "tex.png", None, 2)]
for name, fname, data, ex in images:
    world(f'Texture "t" "spectrum" "imagemap" "string filename" "{fname}"\n'
          'Material "diffuse" "texture reflectance" "t"\nShape "sphere"\n', f"texture_{name}", ex)
    if data is None:
        cases[-1]["files"][fname + "/keep"] = ""
    else:
        cases[-1]["files"][fname] = data
for name, fname, data, ex in images[:3] + images[10:14]:
    world(f'LightSource "infinite" "string filename" "{fname}"\nShape "sphere"\n', f"envmap_{name}", ex)
    cases[-1]["files"][fname] = data

# ------------------------------------------------------------------ light powers
# A light's power beyond float range (4 pi I for a point light of I >= 2.71e37) is an error
# at its directive (render/light_power_range.h); lights at infinity of any radiance the
# parser accepts render, whatever the scene's radius (their power is used only in double).
QUAD = ('Shape "trianglemesh" "point3 P" [-1e5 -2 -1e5 1e5 -2 -1e5 1e5 -2 1e5 -1e5 -2 1e5] '
        '"integer indices" [0 1 2 0 2 3]\n')
LIGHT_POWERS = [
    ("point_3e37", 'LightSource "point" "point3 from" [0 0 4] "rgb I" [3e37 3e37 3e37]\n', 2),
    ("point_2p7e37", 'LightSource "point" "point3 from" [0 0 4] "rgb I" [2.7e37 2.7e37 2.7e37]\n', 0),
    ("point_3e38_channels", 'LightSource "point" "rgb I" [3e38 3e38 3e38]\n', 2),
    ("point_times_scale", 'LightSource "point" "rgb I" [1e30 1e30 1e30] "float scale" 1e8\n', 2),
    ("spot_hemisphere", 'LightSource "spot" "point3 from" [0 0 4] "point3 to" [0 0 0] "rgb I" [1e38 1e38 1e38] '
                        '"float coneangle" 90 "float conedelta" 0\n', 2),
    ("spot_narrow", 'LightSource "spot" "point3 from" [0 0 4] "point3 to" [0 0 0] "rgb I" [1e38 1e38 1e38] '
                    '"float coneangle" 5\n', 0),
    ("area_quad", 'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [3e27 3e27 3e27]\n' + QUAD + 'AttributeEnd\n', 2),
    ("area_quad_two_sided", 'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [2e27 2e27 2e27] "bool twosided" true\n'
                            + QUAD + 'AttributeEnd\n', 2),
    ("area_quad_in_range", 'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [1e27 1e27 1e27]\n' + QUAD +
                           'AttributeEnd\n', 0),
    ("area_sphere", 'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [1e30 1e30 1e30]\nTranslate 0 0 -1e5\n'
                    'Shape "sphere" "float radius" 1e4\nAttributeEnd\n', 2),
    ("distant_3e38", 'LightSource "distant" "rgb L" [3e38 3e38 3e38]\n', 0),
    ("infinite_3e38", 'LightSource "infinite" "rgb L" [3e38 3e38 3e38]\n', 0),
    ("distant_huge_scene", 'LightSource "distant" "rgb L" [3e38 3e38 3e38]\nTranslate 0 0 -1e16\n'
                           'Shape "sphere" "float radius" 1e15\n', 0),
    ("infinite_image_scale", 'LightSource "infinite" "string filename" "sky.png" "float scale" 1e38\n', 2),
    ("infinite_image_scale_in_range", 'LightSource "infinite" "string filename" "sky.png" "float scale" 1e36\n', 0),
]
for name, text, ex in LIGHT_POWERS:
    world(text + 'Shape "sphere"\n', f"light_power_{name}", ex)
    if "sky.png" in text:
        cases[-1]["files"]["sky.png"] = good_png

# ------------------------------------------------------------------ garbage, empty files, huge tokens
rng = random.Random(12)
for i in range(12):
    n = rng.choice([1, 7, 64, 1000, 20000])
    data = bytes(rng.randrange(256) for _ in range(n))
    if data.lstrip().startswith(b"#") or not data.strip():
        data = b"\x01" + data
    case(f"garbage_{i}", {"scene.pbrt": data}, 2)
for i in range(6):  # scene text with random bytes flipped in its middle
    b = bytearray(BASE.encode())
    for _ in range(5):
        b[rng.randrange(len(b) // 3, len(b))] = rng.choice(b'[]"\x00\xff{}')
    case(f"mutated_{i}", {"scene.pbrt": bytes(b)}, 2)
case("nul_bytes", {"scene.pbrt": HEAD.encode() + b"\0" * 100}, 2)
case("utf8_bom", {"scene.pbrt": b"\xef\xbb\xbf" + BASE.encode()}, 2)
case("empty_scene", {"scene.pbrt": ""}, 2, note="no WorldBegin: an error, as in pbrt-v4")
case("only_comments", {"scene.pbrt": "# nothing\n" * 10}, 2)
case("only_world", {"scene.pbrt": "WorldBegin\n"}, 0)
TEN_MB = 10 * 1024 * 1024
world("A" * TEN_MB + "\n", "token_10mb_identifier", 2)
world('Shape "' + "s" * TEN_MB + '"\n', "token_10mb_string", 2, note="an unknown shape type, quoted in part")
world('Shape "sphere" "float radius" ' + "1" * TEN_MB + "\n", "token_10mb_number", 2)
world('Shape "sphere" "float radius" [' + " 1" * 1000000 + " ]\n", "token_1m_values", 2)
world('Shape "sphere" "float radius" "' + "1" * TEN_MB + "\n", "token_10mb_unterminated", 2)
world("#" + "c" * TEN_MB + '\nShape "sphere"\n', "token_10mb_comment", 0)
world('"' * 100000 + "\n", "token_many_quotes", 2)
world("[" * 100000 + "\n", "token_many_brackets", 2)

# ------------------------------------------------------------------ command lines
OK = {"scene.pbrt": BASE}
CLI_CASES = [
    ("spp_zero", ["--spp", "0"]), ("spp_negative", ["--spp", "-1"]), ("spp_word", ["--spp", "many"]),
    ("spp_huge", ["--spp", "1e99"]), ("spp_overflow", ["--spp", "99999999999999999999"]),
    ("res_junk", ["--res", "32x32junk"]), ("res_zero", ["--res", "0x0"]), ("res_x", ["--res", "x"]),
    ("res_negative", ["--res", "-8x8"]), ("res_huge", ["--res", "65536x65536"]),
    ("res_overflow", ["--res", "99999999999x8"]), ("res_float", ["--res", "8.5x8"]),
    ("threads_negative", ["--threads", "-5"]), ("threads_word", ["--threads", "all"]),
    ("seed_word", ["--seed", "abc"]), ("seed_negative", ["--seed", "-1"]),
    ("time_limit_negative", ["--time-limit", "-1"]), ("time_limit_nan", ["--time-limit", "nan"]),
    ("sampler_unknown", ["--sampler", "halton"]), ("unknown_option", ["--frobnicate"]),
    ("output_unknown_ext", ["-o", "out/image.xyz"]), ("output_no_dir", ["-o", "out/missing/image.exr"]),
    ("output_unwritable", ["-o", "/proc/image.exr"]), ("output_is_dir", ["-o", "out"]),
    ("output_png_is_dir", ["-o", "out/busy.exr"]), ("points_zero", ["--points", "0"]),
]
for name, extra in CLI_CASES:
    args = ["render", "scene.pbrt", "--spp", "1", "--res", "8x8", "-q", "-o", "out/image.exr"]
    for k in range(0, len(extra), 2):
        if extra[k] in args and k + 1 < len(extra):
            args[args.index(extra[k]) + 1] = extra[k + 1]
        else:
            args += extra[k:k + 2]
    files = dict(OK)
    if name == "output_png_is_dir":
        files["out/busy.png/keep"] = ""
    case(f"cli_{name}", files, 2, kind="cli", args=args)
case("cli_missing_scene", {}, 2, kind="cli", args=RENDER)
case("cli_scene_is_dir", {"scene.pbrt/keep": ""}, 2, kind="cli", args=RENDER)
case("cli_scene_fifo", {"scene.pbrt": None}, 2, kind="cli", args=RENDER)
case("cli_no_args", {}, 2, kind="cli", args=["render"])
case("cli_unknown_command", {}, 2, kind="cli", args=["paint"])
case("cli_valid", OK, 0, args=RENDER)
case("cli_load_pointcloud_unused", OK, 0, args=RENDER + ["--load-pointcloud", "none.pcl"],
     note="no material uses the pointcloud method: the option is ignored (a warning would be better)")


def shard(index, count):
    """The names of shard `index` of `count`: every count-th case, so that each shard gets
    some of every family (the slow ones too)."""
    return {c["name"] for i, c in enumerate(cases) if i % count == index}


def write(root, only=None):
    """Writes every case (or those named in `only`) under root; returns how many."""
    root = pathlib.Path(root)
    shutil.rmtree(root, ignore_errors=True)
    names = set()
    for c in cases:
        assert c["name"] not in names, c["name"]
        names.add(c["name"])
        if only is not None and c["name"] not in only:
            continue
        d = root / c["name"]
        (d / "out").mkdir(parents=True)
        for rel, data in c["files"].items():
            p = d / rel
            p.parent.mkdir(parents=True, exist_ok=True)
            if data is None:
                os.mkfifo(p)
            else:
                p.write_bytes(data if isinstance(data, bytes) else data.encode())
        meta = {k: c[k] for k in ("args", "expect", "kind", "note")}
        (d / "case.json").write_text(json.dumps(meta, indent=1))
    return len(cases) if only is None else len(only)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    print(f"generate.py: {write(sys.argv[1])} cases in {sys.argv[1]}")
