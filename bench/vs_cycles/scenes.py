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
    light=quad_light([-100.0, 30.0, 80.0], [0.0, 0.0, 0.0], 30.0, KEY),
)
BUST_GEOM = dict(
    shape=dict(kind="obj", path=NEFERTITI),
    camera=dict(eye=[-850.0, -1000.0, 150.0], target=[0.0, 0.0, 10.0], up=[0.0, 0.0, 1.0], fov=28.0),
    light=quad_light([-800.0, -500.0, 600.0], [0.0, 0.0, 0.0], 300.0, KEY),
)


def scene(name, geom, material, checks, dermis, ref_factor=1.0):
    """ref_factor multiplies the reference time of the run (run.py --reference-time)."""
    return dict(name=name, res=list(RES), sky=SKY, max_depth=MAX_DEPTH, material=material, checks=checks,
                dermis=dermis, ref_factor=ref_factor, **geom)


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

DEFAULT_SCENES = ["sphere-walk", "sphere-burley", "bust-walk", "bust-burley", "medium-matched", "medium-glass",
                  "calibration"]


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
    """The Principled Subsurface Radius that reproduces Dermis' parameters (see module doc)."""
    a, l, eta, g = material["reflectance"], material["mfp"], material["eta"], material["g"]
    if material["method"] == "randomwalk":
        return [li / ((1.0 - g) * math.sqrt(3.0 * (1.0 - _cycles_dipole_alpha_prime(ai, eta)))) for ai, li in zip(a, l)]
    if material["method"] == "burley":
        return [4.0 * math.pi * li / burley_s_volume(ai) for ai, li in zip(a, l)]
    raise ValueError(material["method"])
