#!/usr/bin/python3
"""How far a conductor's Fresnel reflectance computed on RGB-reduced eta and k (Dermis)
is from the same reflectance computed per wavelength and then reduced to RGB (pbrt-v4).

Dermis reduces every spectrum to linear sRGB before rendering: a metal's `eta` and `k`
become their colour under D65 (docs/scene-format.md, Spectra) and the Fresnel equations
run on the three channels. pbrt-v4 evaluates the Fresnel equations at each sampled
wavelength; under a white light (D65, what `"rgb L" [1 1 1]` is in pbrt-v4) the film
records the colour under D65 of the reflectance spectrum R(lambda). The two differ because
R is not linear in eta and k. This script evaluates both with the tables Dermis itself
uses (src/dermis/spectral/named_spectra_data.cpp: CIE 1931 observer, D65, Palik's metals) at
a few angles of incidence and as the hemispherical (cosine-weighted) albedo.

  /usr/bin/python3 -m bench.pbrt_v4.spectral_fresnel [metal ...]   (default: Au Cu Ag Al CuZn)
"""
import os
import re
import sys

import numpy as np

from bench.harness.paths import ROOT

DATA = os.path.join(ROOT, "src", "dermis", "spectral", "named_spectra_data.cpp")

XYZ_TO_SRGB = np.array([[3.2404542, -1.5371385, -0.4985314],
                        [-0.9692660, 1.8760108, 0.0415560],
                        [0.0556434, -0.2040259, 1.0572252]])


def tables():
    src = open(DATA).read()
    cie = np.array([[float(v) for v in m.groups()] for m in re.finditer(
        r"\{\s*([0-9.]+),\s*([0-9.eE+-]+),\s*([0-9.eE+-]+),\s*([0-9.eE+-]+)\s*\}",
        src.split("kCie1931[] = {")[1].split("};")[0])])
    arrays = {}
    for m in re.finditer(r"constexpr double (k\w+)\[\] = \{(.*?)\};", src, re.S):
        arrays[m.group(1)] = np.array([float(x) for x in re.findall(r"[-+0-9.eE]+", m.group(2))])
    return cie, arrays


def main():
    cie, arrays = tables()
    lam = np.arange(360.0, 831.0)
    xb, yb, zb = (np.interp(lam, cie[:, 0], cie[:, i]) for i in (1, 2, 3))
    d65 = arrays["kIllumD65"]
    s = np.interp(lam, d65[0::2], d65[1::2])
    k = 1 / np.sum(s * yb)

    def colour(f):  # colour under D65 of the spectrum f(lam) (Dermis' rule for non-lights)
        xyz = k * np.array([np.sum(s * f * xb), np.sum(s * f * yb), np.sum(s * f * zb)])
        return XYZ_TO_SRGB @ xyz

    def fresnel(cos_i, n, kk):  # unpolarised reflectance of a conductor, eta = n + i k
        eta = n + 1j * kk
        sin2 = 1 - cos_i ** 2
        t = np.sqrt(eta ** 2 - sin2)
        r_perp = (cos_i - t) / (cos_i + t)
        r_par = (eta ** 2 * cos_i - t) / (eta ** 2 * cos_i + t)
        return 0.5 * (np.abs(r_perp) ** 2 + np.abs(r_par) ** 2)

    metals = sys.argv[1:] or ["Au", "Cu", "Ag", "Al", "CuZn"]
    mu = (np.arange(64) + 0.5) / 64  # midpoint rule in cos theta for the albedo 2 int R mu dmu
    print("metal  angle   pbrt-v4 (spectral)        Dermis (RGB eta, k)       Dermis / pbrt - 1")
    for metal in metals:
        e, kk = arrays[f"k{metal}Eta"], arrays[f"k{metal}K"]
        # pbrt extends a piecewise-linear spectrum with its end values (np.interp does too)
        n_l, k_l = np.interp(lam, e[0::2], e[1::2]), np.interp(lam, kk[0::2], kk[1::2])
        n_rgb, k_rgb = colour(n_l), colour(k_l)
        rows = []
        for name, cosines, weights in (("0 deg", [1.0], [1.0]), ("45 deg", [np.cos(np.pi / 4)], [1.0]),
                                       ("75 deg", [np.cos(np.radians(75))], [1.0]),
                                       ("albedo", mu, 2 * mu / len(mu))):
            sp = sum(w * colour(fresnel(c, n_l, k_l)) for c, w in zip(cosines, weights))
            rg = sum(w * fresnel(c, n_rgb, k_rgb) for c, w in zip(cosines, weights))
            rows.append((name, sp, rg))
        print(f"{metal:5s}  eta_rgb {np.round(n_rgb, 3)}  k_rgb {np.round(k_rgb, 3)}")
        for name, sp, rg in rows:
            print(f"       {name:7s} {np.array2string(sp, precision=4):24s}  "
                  f"{np.array2string(rg, precision=4):24s}  "
                  f"{np.array2string(100 * (rg / sp - 1), precision=2, sign='+')} %")


if __name__ == "__main__":
    main()
