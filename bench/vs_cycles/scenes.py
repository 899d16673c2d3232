"""The twin scenes of the Dermis-vs-Cycles harness, each described once.

A scene is a plain dict (JSON-serialisable, so that the Blender script can read the very
same description): geometry, camera, lights, material or medium, resolution. The pbrt
writer (pbrt_writer.py) and the Blender script (blender_scene.py) turn it into a Dermis
scene and a Cycles scene. Units: millimetres in both renderers (1 Blender unit = 1 mm);
radiance in W/(m^2 sr) (Dermis `L`, Cycles Background/Emission strength 1 x colour).

Parameter mapping (both renderers' conventions, from their documentation/source):
- Dermis `subsurface` (reflectance A, mfp l): l = 1/sigma_t, A the surface albedo.
- Cycles 3.4 Principled, subsurface method RANDOM_WALK: radius r is scaled by
  sqrt(3 (1 - alpha')) with alpha' the dipole inversion of A at the Subsurface IOR
  (intern/cycles/kernel/closure/bssrdf.h, bssrdf_setup_radius), then
  sigma_t = 1 / (r_scaled (1 - g)) (subsurface_random_walk.h). We give Cycles the radius
  that yields Dermis' sigma_t = 1/l: r = l / ((1 - g) sqrt(3 (1 - alpha'))) (same extinction; the
  single-scattering albedo still comes from each renderer's own inversion of A).
- Cycles 3.4's Random Walk enters along a cosine lobe about -N (sample_cos_hemisphere in
  subsurface_random_walk.h: a diffuse transmission, Chiang, Kutz & Burley 2016) where
  Dermis' default refracts; its Dermis twin has `"string entry" "lambertian"`
  (pbrt_writer.py). Thick objects do not tell them apart; thin or translucent ones
  do (mfp/size 1 and a backlight, f06: the refracted entry is 2.5-4.6x brighter).
- Cycles 3.4 Christensen-Burley: the profile's d is radius / (4 pi) (bssrdf_setup_radius;
  subsurface_disk.h uses it directly). Dermis' `burley` profile has d = l / s(A) with the
  volume-mfp fit s = 1.85 - A + 7 |A - 0.8|^3 (docs/materials.md). We give Cycles
  r = 4 pi l / s(A): the same profile.
- Fresnel: Principled's specular layer takes F0 = 0.08 * Specular (not the IOR), so
  Specular = F0(eta) / 0.08 with F0 = ((eta - 1)/(eta + 1))^2.
"""

import math

# ---------------------------------------------------------------- shared pieces

SKY = [0.06, 0.075, 0.10]  # uniform environment radiance (as scenes/demo.pbrt)
KEY = [40.0, 34.0, 26.0]  # key light radiance (as scenes/demo.pbrt), one-sided
MAX_DEPTH = 1024  # Dermis `maxdepth` = Cycles max_bounces and every per-type bounce limit
RES = (160, 160)

NEFERTITI = "scenes/meshes/nefertiti.obj"  # relative to the repository root; millimetres

# Skin-like subsurface material (surface albedo, mean free path in mm), eta 1.4, isotropic.
SKIN = dict(reflectance=[0.85, 0.55, 0.40], mfp=[8.0, 4.0, 2.0], eta=1.4, g=0.0)
# Homogeneous medium of the medium scenes (per mm): about 8, 6.4 and 4.8 mfp across.
MEDIUM = dict(sigma_a=[0.004, 0.010, 0.025], sigma_s=[0.20, 0.16, 0.12], g=0.3)


def _sub(a, b):
    return [x - y for x, y in zip(a, b)]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _norm(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def quad_light(center, target, size, radiance):
    """A square one-sided emitter at `center` facing `target`. Corners are listed
    counter-clockwise seen from the lit side, so that both pbrt's triangle normal
    (cross(p0 - p2, p1 - p2)) and Blender's polygon normal point toward `target`."""
    n = _norm(_sub(target, center))
    helper = [0.0, 0.0, 1.0] if abs(n[2]) < 0.9 else [1.0, 0.0, 0.0]
    u = _norm(_cross(helper, n))
    v = _cross(n, u)  # (u, v, n) right-handed: u -> v is counter-clockwise seen from +n
    h = size / 2
    corners = [[c + h * (su * uu + sv * vv) for c, uu, vv in zip(center, u, v)]
               for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    assert sum(x * y for x, y in zip(_cross(_sub(corners[1], corners[0]), _sub(corners[2], corners[0])), n)) > 0
    return dict(corners=corners, radiance=radiance)


# ---------------------------------------------------------------- geometry presets

SPHERE_GEOM = dict(
    shape=dict(kind="sphere", center=[0.0, 0.0, 0.0], radius=20.0),
    camera=dict(eye=[-110.0, -130.0, 40.0], target=[0.0, 0.0, 0.0], up=[0.0, 0.0, 1.0], fov=22.0),
    lights=[quad_light([-100.0, 30.0, 80.0], [0.0, 0.0, 0.0], 30.0, KEY)],
)
BUST_GEOM = dict(
    shape=dict(kind="obj", path=NEFERTITI),
    camera=dict(eye=[-850.0, -1000.0, 150.0], target=[0.0, 0.0, 10.0], up=[0.0, 0.0, 1.0], fov=28.0),
    lights=[quad_light([-800.0, -500.0, 600.0], [0.0, 0.0, 0.0], 300.0, KEY)],
)


def scene(name, geom, material, checks, dermis, ref_factor=1.0, sky=SKY, res=RES, environment=None):
    """ref_factor multiplies the reference time of the run (run.py --reference-time); sky
    None: no uniform environment light (a black background); environment: the name of an HDR
    environment (environments.py) lighting the scene."""
    sc = dict(name=name, res=list(res), sky=sky, max_depth=MAX_DEPTH, material=material, checks=checks,
              dermis=dermis, ref_factor=ref_factor, **geom)
    if environment:
        sc["environment"] = dict(name=environment)
    return sc


# `dermis`: the Dermis variants rendered for the scene, label -> extra material parameters
# (pbrt syntax); the first is the one compared with Cycles in the summary table.
SCENES = {
    "sphere-walk": scene(
        "sphere-walk", SPHERE_GEOM, dict(kind="subsurface", method="randomwalk", **SKIN),
        "Random-walk subsurface scattering on a smooth sphere: Dermis' default walk (boundary `diffuse`, "
        "MIS guiding, exact albedo inversion) vs Cycles Principled `RANDOM_WALK` (radius converted to the same "
        "extinction).",
        {"randomwalk (default)": ""}),
    "sphere-burley": scene(
        "sphere-burley", SPHERE_GEOM, dict(kind="subsurface", method="burley", **SKIN),
        "Christensen-Burley profile on the sphere: Dermis `disk` probe rays (three axes, channel/lobe MIS) vs "
        "Cycles Principled `BURLEY` (disk sampling, radius converted to the same profile).",
        {"disk burley": '"string method" "disk" "string profile" "burley"'}),
    "bust-walk": scene(
        "bust-walk", BUST_GEOM, dict(kind="subsurface", method="randomwalk", **SKIN),
        "The random walk on a detailed mesh (Nefertiti, ~100k triangles, flat shaded in both).",
        {"randomwalk (default)": ""}),
    "bust-burley": scene(
        "bust-burley", BUST_GEOM, dict(kind="subsurface", method="burley", **SKIN),
        "The Christensen-Burley profile on the bust.",
        {"disk burley": '"string method" "disk" "string profile" "burley"'}),
    "medium-matched": scene(
        "medium-matched", SPHERE_GEOM, dict(kind="medium", boundary="matched", **MEDIUM),
        "Identical physics: a homogeneous medium (sigma_a, sigma_s, HG g) in an index-matched sphere; Dermis "
        "`interface` material + MediumInterface (volumetric path tracer) vs Cycles Volume Scatter + Volume "
        "Absorption under a Transparent BSDF. The two references must agree.",
        {"volpath interface": ""}),
    "medium-glass": scene(
        "medium-glass", SPHERE_GEOM, dict(kind="medium", boundary="glass", eta=1.33, **MEDIUM),
        "Identical physics: the same medium behind a smooth dielectric of IOR 1.33; Dermis `subsurface` "
        "random walk with `boundary` `dielectric` and, second, the `volumetric` method (medium inside a "
        "dielectric, volumetric path tracer) vs Cycles volume inside a sharp Glass BSDF.",
        {"randomwalk dielectric": '"string method" "randomwalk" "string boundary" "dielectric"',
         "volumetric": '"string method" "volumetric"'}),
    # Not a comparison: units and orientation check (white diffuse sphere, same lights).
    "calibration": scene(
        "calibration", SPHERE_GEOM, dict(kind="diffuse", reflectance=[0.8, 0.8, 0.8]),
        "Units/handedness check: a Lambertian sphere (reflectance 0.8) under the same sky and key light; "
        "the two references must agree.",
        {"diffuse": ""}, ref_factor=0.25),
}

# The grid medium's twin (issue 67, item 4): a 32^3 density grid (grid_twin.py: a noisy puff,
# empty on its two outer layers) in a 48 mm box at the sphere's place, sigma_a and sigma_s
# per unit density, under the sky and the key light; Dermis enters it through an
# index-matched box, Cycles renders it as a Volume object read from its .vdb.
GRID_MEDIUM = dict(kind="grid", boundary="matched", n=32, seed=67, box=[-24.0, 24.0], sigma_a=[0.02, 0.05, 0.10],
                   sigma_s=[0.40, 0.32, 0.24], g=0.3)
SCENES["medium-grid"] = scene(
    "medium-grid", dict(SPHERE_GEOM, shape=dict(kind="box", min=[-24.0] * 3, max=[24.0] * 3)), GRID_MEDIUM,
    "A heterogeneous medium: a 32^3 density grid; Dermis `uniformgrid` inside an index-matched box (volumetric "
    "path tracer: delta and ratio tracking) vs Cycles Volume Scatter + Volume Absorption on a Volume object of the "
    "same densities (OpenVDB, trilinear). The two references must agree.",
    {"volpath interface": ""})

DEFAULT_SCENES = ["sphere-walk", "sphere-burley", "bust-walk", "bust-burley", "medium-matched", "medium-glass",
                  "calibration"]


# ---------------------------------------------------------------- the scene family (issue 40)
#
# Chosen before any tuning (and never tuned per scene): every configuration uses the same
# renderer settings; only geometry, light balance, scale and material change. The span:
#   light balance  sky only | one small key light only | both | a backlight through the object
#                  (hidden behind it from the camera) with the sky;
#   scale          mean mfp / the object's smallest extent (sphere diameter 40 mm, the bust's
#                  depth 240 mm, the fin's thickness 6 mm) about 0.01, 0.1 and 1;
#   geometry       the sphere, the Nefertiti bust, a thin ear-like fin (a flat ellipsoid);
#   albedo         0.3 (dark) to 0.95 (milk);
#   plus the index-matched and the in-glass homogeneous medium under the sky and the small key.
# Each subsurface configuration is rendered twice: Dermis' default method (the random walk)
# against Cycles' Random Walk, and Dermis' `disk` probes (Christensen-Burley) against
# Cycles' Christensen-Burley.

FAMILY_RES = (128, 96)
SMALL_KEY = [9.0 * x for x in KEY]  # a third of the key's side, the same power

# Surface albedo A and the ratio of the channels' mfp (scaled to the configuration's mean).
FAMILY_MATERIALS = {
    "skin": dict(reflectance=[0.85, 0.55, 0.40], ratio=[8.0, 4.0, 2.0]),
    "milk": dict(reflectance=[0.95, 0.93, 0.88], ratio=[1.2, 1.0, 0.8]),
    "wax": dict(reflectance=[0.90, 0.75, 0.50], ratio=[1.5, 1.0, 0.6]),
    "jade": dict(reflectance=[0.35, 0.60, 0.45], ratio=[1.0, 1.3, 1.0]),
    "dark": dict(reflectance=[0.30, 0.28, 0.32], ratio=[1.0, 1.0, 1.0]),
}

FIN_SEMI_AXES = [25.0, 3.0, 18.0]  # mm: 50 wide, 36 high, 6 thick (along y, facing the camera)

# Per geometry: shape, camera, the object's size for the scale (its smallest extent, mm),
# the small key light and the backlight (behind the object on the camera's line of sight,
# smaller than the object's silhouette: hidden from the camera).
FAMILY_GEOMETRY = {
    "sphere": dict(
        shape=SPHERE_GEOM["shape"], camera=dict(SPHERE_GEOM["camera"], fov=18.0), size=40.0, checker_cell=10.0,
        key=quad_light([-100.0, 30.0, 80.0], [0.0, 0.0, 0.0], 10.0, SMALL_KEY),
        back=quad_light([55.0, 65.0, -20.0], [0.0, 0.0, 0.0], 10.0, SMALL_KEY)),
    "bust": dict(
        shape=BUST_GEOM["shape"], camera=dict(BUST_GEOM["camera"], fov=36.0), size=240.0, checker_cell=40.0,
        key=quad_light([-800.0, -500.0, 600.0], [0.0, 0.0, 0.0], 100.0, SMALL_KEY),
        back=None),
    "fin": dict(
        shape=dict(kind="ellipsoid", center=[0.0, 0.0, 0.0], semi_axes=FIN_SEMI_AXES, segments=96, rings=48),
        camera=dict(eye=[-40.0, -150.0, 20.0], target=[0.0, 0.0, 0.0], up=[0.0, 0.0, 1.0], fov=26.0), size=6.0,
        checker_cell=10.0,
        key=quad_light([-90.0, -80.0, 70.0], [0.0, 0.0, 0.0], 10.0, SMALL_KEY),
        back=quad_light([10.0, 60.0, 5.0], [0.0, 0.0, 0.0], 8.0, SMALL_KEY)),
}

# (geometry, light balance, scale, material): twelve subsurface configurations.
FAMILY_CONFIGS = [
    ("sphere", "both", 0.1, "skin"),
    ("sphere", "sky", 0.1, "milk"),
    ("sphere", "key", 0.1, "jade"),
    ("sphere", "both", 0.01, "wax"),
    ("sphere", "both", 1.0, "milk"),
    ("sphere", "back", 1.0, "skin"),
    ("bust", "both", 0.01, "skin"),
    ("bust", "sky", 0.01, "dark"),
    ("bust", "key", 0.1, "wax"),
    ("fin", "back", 0.1, "skin"),
    ("fin", "both", 1.0, "milk"),
    ("fin", "key", 0.01, "dark"),
]
# The two media (sphere, sky + small key), each with the variants of its classic scene: the
# volumetric path tracer in the index-matched sphere; the walk with a dielectric boundary
# and the `volumetric` method in glass.
FAMILY_MEDIA = ["matched", "glass"]


def ellipsoid_mesh(center, semi_axes, segments, rings):
    """A UV-tessellated ellipsoid: vertices and counter-clockwise (outward) triangles."""
    verts = [[center[0], center[1], center[2] - semi_axes[2]]]
    for i in range(1, rings):
        th = math.pi * i / rings
        for j in range(segments):
            ph = 2.0 * math.pi * j / segments
            d = [math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), -math.cos(th)]
            verts.append([c + a * x for c, a, x in zip(center, semi_axes, d)])
    verts.append([center[0], center[1], center[2] + semi_axes[2]])
    top = len(verts) - 1
    ring = lambda i, j: 1 + (i - 1) * segments + j % segments  # noqa: E731
    faces = [[0, ring(1, j + 1), ring(1, j)] for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
            faces += [[a, b, c], [a, c, d]]
    faces += [[ring(rings - 1, j), ring(rings - 1, j + 1), top] for j in range(segments)]
    return verts, faces


# ---------------------------------------------------------------- the lighting axis (issue 66)
#
# The lights artists use, chosen and committed before any change made against them (never
# tuned per scene): two HDR environments made by the harness (environments.py: an outdoor
# sky with a sun of 2 degrees' radius, a studio with three soft boxes), and a square area
# light alone, no environment, subtending about 0.005, 0.05 and 0.2 sr at the object (from
# the family's key direction and distance; its radiance such that the irradiance it gives,
# L times its solid angle, is the same for the three, the sun's). Applied to one
# configuration per geometry (both methods) and to the media: the family's index-matched and
# in-glass media and a dense, strongly scattering, chromatic one (mfp 2-4 % of the sphere's
# diameter, albedo 0.94-0.98, the channels' extinction 2x apart) in an index-matched sphere.

HDR_LIGHTINGS = {"hdr-outdoor": "outdoor", "hdr-studio": "studio"}
AREA_LIGHTINGS = {"area-0.005": 0.005, "area-0.05": 0.05, "area-0.2": 0.2}  # solid angle at the object, sr
AREA_IRRADIANCE = 1.2  # L x solid angle, as the outdoor sun's (environments.py)
AREA_COLOUR = [1.0, 0.85, 0.65]  # the key's colour (KEY), its largest channel 1
LIGHTINGS = list(HDR_LIGHTINGS) + list(AREA_LIGHTINGS)
# (geometry, mfp / size, material): one family configuration per geometry (f01, f09, f11).
LIGHTING_CONFIGS = [("sphere", 0.1, "skin"), ("bust", 0.1, "wax"), ("fin", 1.0, "milk")]
# Dense medium (per mm): sigma_t 0.6, 0.9, 1.2 (mfp 1.7-0.8 mm in the 40 mm sphere), albedo
# 0.98, 0.96, 0.94.
DENSE_MEDIUM = dict(sigma_a=[0.012, 0.036, 0.072], sigma_s=[0.588, 0.864, 1.128], g=0.3)
LIGHTING_MEDIA = ["matched", "glass", "dense"]


def square_side(solid_angle, distance):
    """The side of a square, facing a point on its axis at `distance`, that subtends
    `solid_angle` there: Omega = 4 asin(s^2 / (s^2 + 4 d^2))."""
    q = math.sin(solid_angle / 4)
    return 2 * distance * math.sqrt(q / (1 - q))


def area_light(g, solid_angle):
    """The area light of a geometry subtending `solid_angle` at the object's centre, where its
    key light is (FAMILY_GEOMETRY), facing it."""
    corners = g["key"]["corners"]
    center = [sum(c[i] for c in corners) / 4 for i in range(3)]
    distance = math.sqrt(sum(x * x for x in center))
    L = AREA_IRRADIANCE / solid_angle
    return quad_light(center, [0.0, 0.0, 0.0], square_side(solid_angle, distance), [L * c for c in AREA_COLOUR])


def _family_lights(g, balance):
    """The uniform sky (or None), the quad lights and the HDR environment (or None) of a light
    balance: the family's four, or the lighting axis' (LIGHTINGS)."""
    if balance in HDR_LIGHTINGS:
        return None, [], HDR_LIGHTINGS[balance]
    if balance in AREA_LIGHTINGS:
        return None, [area_light(g, AREA_LIGHTINGS[balance])], None
    sky = SKY if balance in ("sky", "both", "back") else None
    lights = {"sky": [], "key": [g["key"]], "both": [g["key"]], "back": [g["back"]]}[balance]
    assert all(lights), f"no {balance} light for this geometry"
    return sky, lights, None


def _family_scenes(configs=None, materials=None, prefix="f", kind="Family", media=True, checker=None, fov=None,
                   lines=False):
    """The family's scenes (walk and disk twin of each configuration, then the media), or
    another set of configurations on the same geometries and lights (the held-out set).
    checker: the reflectance a checkerboard alternates with (textured_material).
    fov: per geometry, a field of view instead of its camera's (the close-up set).
    lines: the disk twin also renders Dermis' other probe method, the sphere lines, with
    the same profile against the same Cycles renders (issue 40, item 2 names both)."""
    configs = FAMILY_CONFIGS if configs is None else configs
    materials = FAMILY_MATERIALS if materials is None else materials
    out = {}
    for k, (geo, balance, scale, mat) in enumerate(configs, 1):
        g, m = FAMILY_GEOMETRY[geo], materials[mat]
        sky, lights, environment = _family_lights(g, balance)
        mean = sum(m["ratio"]) / 3.0
        mfp = [scale * g["size"] * r / mean for r in m["ratio"]]
        base = f"{prefix}{k:02d}-{geo}-{balance}-{scale:g}-{mat}"
        camera = dict(g["camera"], fov=fov[geo]) if fov else g["camera"]
        geom = dict(shape=g["shape"], camera=camera, lights=lights)
        info = dict(config=f"{prefix}{k:02d}", geometry=geo, balance=balance, scale=scale, albedo=mat)
        for method, label, cycles, extra in (
                ("randomwalk", "randomwalk (default)", "Random Walk", ""),
                ("burley", "disk burley", "Christensen-Burley", '"string method" "disk" "string profile" "burley"')):
            name = f"{base}-{'walk' if method == 'randomwalk' else 'disk'}"
            material = dict(kind="subsurface", method=method, reflectance=m["reflectance"], mfp=mfp, eta=1.4, g=0.0)
            if checker:
                material["checker"] = dict(cell=g["checker_cell"],
                                           reflectance=[checker * a for a in m["reflectance"]])
            variants = {label: extra}
            if lines and method == "burley":
                variants[LINES_LABEL] = LINES_EXTRA
            sc = scene(name, geom, material,
                       f"{kind} configuration {info['config']}: {geo}, light {balance}, mfp/size {scale:g} "
                       f"(mfp {', '.join(f'{x:.3g}' for x in mfp)} mm), albedo {mat}"
                       + (f" in a 3D checkerboard with {checker:g} x it (cells {g['checker_cell']:g} mm)" if checker else "")
                       + f"; Dermis `{' and `'.join(v + '`' for v in variants)} vs Cycles {cycles}.", variants,
                       sky=sky, res=FAMILY_RES, environment=environment)
            sc["family"] = dict(info, method="walk" if method == "randomwalk" else "disk")
            out[name] = sc
    if not media:
        return out
    g = FAMILY_GEOMETRY["sphere"]
    sky, lights, _ = _family_lights(g, "both")
    geom = dict(shape=g["shape"], camera=g["camera"], lights=lights)
    for k, boundary in enumerate(FAMILY_MEDIA, len(FAMILY_CONFIGS) + 1):
        name = f"f{k:02d}-medium-{boundary}"
        src = SCENES[f"medium-{boundary}"]
        sc = scene(name, geom, src["material"], f"Family configuration f{k:02d}: " + src["checks"] +
                   " Under the sky and the small key light.", src["dermis"], sky=sky, res=FAMILY_RES)
        sc["family"] = dict(config=f"f{k:02d}", geometry="sphere", balance="both", scale=None,
                            albedo=f"medium ({boundary})", method="volumetric" if boundary == "matched" else "walk")
        out[name] = sc
    return out


# The sphere lines (random lines through a sphere, the Cycles design) with the disk's
# profile: a second Dermis variant of the family's disk twins (since the forty-second
# session), against the same Cycles Christensen-Burley renders.
LINES_LABEL = "sphere-lines burley"
LINES_EXTRA = '"string method" "sphere-lines" "string profile" "burley"'

FAMILY = _family_scenes(lines=True)
SCENES.update(FAMILY)

# Held-out configurations, for checking that what was measured on the family generalises:
# other albedos (marble, ketchup, apple, grey), scales and light balances on the family's
# geometries and lights, none of them a family configuration. Written after the subsurface
# pilot was built and before it was measured on them; used since to check changes to the
# random walk (heldout.py) and against Cycles (run.py --set heldout), never to tune one.
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
HELDOUT = _family_scenes(HELDOUT_CONFIGS, HELDOUT_MATERIALS, prefix="h", kind="Held-out", media=False)
SCENES.update(HELDOUT)

# Textured configurations: the reflectance a 3D checkerboard of the material's and 0.6 x
# it (cells of FAMILY_GEOMETRY's checker_cell: a few across the object), the mfp constant,
# as a user's texture map varies the colour. Both renderers take the medium at the entry
# point for the whole walk (Cycles' closure there; Dermis: render/subsurface/walk_method.h)
# and the profile of the entry for the probes. Cycles gets the Subsurface Radius of each
# square's reflectance from a second checker (the conversion depends on A). Chosen when
# the textured walk was made faster (2026-12-05), before it was measured against Cycles;
# never used to tune.
TEXTURED_CHECKER = 0.6
TEXTURED_CONFIGS = [
    ("sphere", "both", 0.03, "skin"),
    ("bust", "sky", 0.03, "marble"),
    ("fin", "back", 0.3, "skin"),
    ("bust", "both", 0.01, "apple"),
    ("sphere", "key", 0.3, "jade"),
    ("fin", "sky", 0.1, "ketchup"),
]
TEXTURED = _family_scenes(TEXTURED_CONFIGS, {**FAMILY_MATERIALS, **HELDOUT_MATERIALS}, prefix="t", kind="Textured",
                          media=False, checker=TEXTURED_CHECKER)
SCENES.update(TEXTURED)

# Close-ups: the family's twelve configurations, each camera's field of view narrowed until
# the object covers about three quarters of the frame (fully covered pixels: sphere 0.77,
# bust 0.70, fin 0.78; the family's frames: 0.30, 0.09, 0.19), as a portrait fills it. In
# the family most pixels see the sky alone, which Dermis renders faster than Cycles, so
# their ratios of time mix the object's cost per sample with the background's; here the
# object's samples are most of the time. Chosen (2026-12-05) after one measurement of the
# bust's close-up times (f08, both methods) and before any change made against them;
# never used to tune.
CLOSEUP_FOV = {"sphere": 11.0, "bust": 8.0, "fin": 13.0}
CLOSEUP = _family_scenes(FAMILY_CONFIGS, FAMILY_MATERIALS, prefix="c", kind="Close-up", media=False,
                         fov=CLOSEUP_FOV, lines=True)
SCENES.update(CLOSEUP)

def _lighting_scenes():
    """The lighting axis: each lighting (LIGHTINGS) on LIGHTING_CONFIGS (walk and disk twins)
    and on LIGHTING_MEDIA; configurations l01, l02 ... (lighting-major)."""
    out = {}
    configs = [(geo, lighting, scale, mat) for lighting in LIGHTINGS for geo, scale, mat in LIGHTING_CONFIGS]
    out.update(_family_scenes(configs, prefix="l", kind="Lighting", media=False))
    g = FAMILY_GEOMETRY["sphere"]
    k = len(configs)
    for lighting in LIGHTINGS:
        sky, lights, environment = _family_lights(g, lighting)
        geom = dict(shape=g["shape"], camera=g["camera"], lights=lights)
        for medium in LIGHTING_MEDIA:
            k += 1
            name = f"l{k:02d}-medium-{medium}-{lighting}"
            src = SCENES[f"medium-{'matched' if medium == 'dense' else medium}"]
            material = dict(src["material"], **DENSE_MEDIUM) if medium == "dense" else src["material"]
            checks = (f"Lighting configuration l{k:02d}, {lighting}: " +
                      ("the dense chromatic medium (sigma_t 0.6, 0.9, 1.2 per mm, albedo 0.98-0.94) in the "
                       "index-matched sphere; " if medium == "dense" else "") + src["checks"])
            sc = scene(name, geom, material, checks, src["dermis"], sky=sky, res=FAMILY_RES, environment=environment)
            sc["family"] = dict(config=f"l{k:02d}", geometry="sphere", balance=lighting, scale=None,
                                albedo=f"medium ({medium})", method="walk" if medium == "glass" else "volumetric")
            out[name] = sc
    return out


LIGHTING = _lighting_scenes()
SCENES.update(LIGHTING)

# ---------------------------------------------------------------- parameter conversions

def fresnel_f0(eta):
    return ((eta - 1.0) / (eta + 1.0)) ** 2


def principled_specular(eta):
    """Principled (Blender 3.x) Specular input giving the normal-incidence reflectance of eta."""
    return fresnel_f0(eta) / 0.08


def _cycles_dipole_alpha_prime(rd, eta):
    """Cycles 3.4 bssrdf_dipole_compute_alpha_prime (bisection, 12 steps), in Python."""
    inv_eta = 1.0 / eta
    f_dr = inv_eta * (-1.440 * inv_eta + 0.710) + 0.668 + 0.0636 * eta
    fourthird_a = (4.0 / 3.0) * (1.0 + f_dr) / (1.0 - f_dr)
    if rd < 1e-4:
        return 0.0
    if rd >= 0.995:
        return 0.999999
    x0, x1 = 0.0, 1.0
    for _ in range(12):
        xm = 0.5 * (x0 + x1)
        s = math.sqrt(3.0 * (1.0 - xm))
        f = 0.5 * xm * (1.0 + math.exp(-fourthird_a * s)) * math.exp(-s)
        if f < rd:
            x0 = xm
        else:
            x1 = xm
    return xm


def burley_s_volume(a):
    """Dermis `burley` profile: the volume-mfp fit (docs/materials.md)."""
    return 1.85 - a + 7.0 * abs(a - 0.8) ** 3


def cycles_radius(material):
    """The Principled Subsurface Radius that reproduces Dermis' parameters (see module doc);
    of a checkerboard's other squares: cycles_radius(dict(material, reflectance=...))."""
    a, l, eta, g = material["reflectance"], material["mfp"], material["eta"], material["g"]
    if material["method"] == "randomwalk":
        return [li / ((1.0 - g) * math.sqrt(3.0 * (1.0 - _cycles_dipole_alpha_prime(ai, eta)))) for ai, li in zip(a, l)]
    if material["method"] == "burley":
        return [4.0 * math.pi * li / burley_s_volume(ai) for ai, li in zip(a, l)]
    raise ValueError(material["method"])
