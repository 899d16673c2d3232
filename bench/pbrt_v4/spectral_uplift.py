#!/usr/bin/python3
"""What pbrt-v4's RGB -> spectrum uplift does to a product of colours, against Dermis' RGB.

pbrt-v4 turns every RGB parameter into a smooth spectrum (Jakob & Hanika 2019: a sigmoid of
a quadratic polynomial in wavelength whose colour under the colour space's illuminant, D65
for sRGB, is the RGB given; reflectances as RGBAlbedoSpectrum, lights as
RGBIlluminantSpectrum = scale x sigmoid x D65 with scale = 2 max(rgb), coefficients such as
sigma_a as RGBUnboundedSpectrum = scale x sigmoid) and multiplies spectra per wavelength;
the film then records the colour of the product. Dermis multiplies the RGB triples. The
colour of a product of spectra is not the product of their colours, so light that has met a
coloured surface or medium differs by a little, and more after each bounce. This script
fits the sigmoid spectra itself (an exact solve of colour(sigmoid) = rgb with the tables
Dermis uses, src/dermis/spectral/named_spectra_data.cpp; pbrt-v4 interpolates a precomputed
table of such fits, so its spectra differ slightly from these) and prints, for the colours
of bench/pbrt_v4/scenes, Dermis' RGB / pbrt-v4's - 1 per channel.

  /usr/bin/python3 -m bench.pbrt_v4.spectral_uplift
"""
import numpy as np
from scipy.optimize import least_squares

from bench.pbrt_v4.spectral_fresnel import XYZ_TO_SRGB, tables

cie, arrays = tables()
LAM = np.arange(360.0, 831.0)
XB, YB, ZB = (np.interp(LAM, cie[:, 0], cie[:, i]) for i in (1, 2, 3))
D65 = np.interp(LAM, arrays["kIllumD65"][0::2], arrays["kIllumD65"][1::2])
K = 1 / np.sum(D65 * YB)
X = (LAM - 360) / (830 - 360)


def colour(f):
    """Colour (linear sRGB) of a reflectance-like spectrum f under D65."""
    return XYZ_TO_SRGB @ (K * np.array([np.sum(D65 * f * XB), np.sum(D65 * f * YB),
                                        np.sum(D65 * f * ZB)]))


def sigmoid_spectrum(rgb):
    """A sigmoid(quadratic) spectrum in [0, 1] whose colour under D65 is rgb (in [0, 1])."""
    rgb = np.asarray(rgb, float)
    if np.allclose(rgb, rgb[0]):  # grey: a constant, as pbrt's table gives
        return np.full_like(LAM, rgb[0])

    def spec(c):
        z = c[0] * X * X + c[1] * X + c[2]
        return 0.5 + z / (2 * np.sqrt(1 + z * z))  # pbrt's RGBSigmoidPolynomial::s

    sol = least_squares(lambda c: colour(spec(c)) - rgb, x0=[0.0, 0.0, 0.0], xtol=1e-14,
                        ftol=1e-14, gtol=1e-14, max_nfev=20000)
    err = np.max(np.abs(colour(spec(sol.x)) - rgb))
    if err > 1e-4:
        print(f"  (note: the sigmoid fit of {rgb} misses by {err:.1e})")
    return spec(sol.x)


def albedo(rgb):
    return sigmoid_spectrum(rgb)


def unbounded(rgb):
    """pbrt's RGBUnboundedSpectrum and RGBIlluminantSpectrum (without its D65 factor)."""
    m = 2 * max(rgb)
    return m * sigmoid_spectrum(np.asarray(rgb) / m) if m > 0 else np.zeros_like(LAM)


def compare(title, spectra, rgbs):
    """Colour of the product of spectra (pbrt) against the product of the RGBs (Dermis)."""
    p = colour(np.prod(spectra, axis=0))
    d = np.prod(rgbs, axis=0)
    print(f"{title:66s} pbrt {np.array2string(p, precision=4):26s} Dermis "
          f"{np.array2string(d, precision=4):26s} {np.array2string(100 * (d / p - 1), precision=2, sign='+')} %")


def main():
    sky_d = np.array([0.8, 0.85, 1.0])
    sky_s = np.array([0.35, 0.38, 0.45])
    key = np.array([6, 5.6, 5])
    print("Light that met each colour once (and twice), Dermis / pbrt-v4 - 1 per channel:")
    for name, L in (("diffuse: sky [0.8 0.85 1]", sky_d), ("other scenes: sky [0.35 0.38 0.45]", sky_s),
                    ("other scenes: key light [6 5.6 5]", key)):
        Ls = unbounded(L)
        compare(f"{name}, light itself", [Ls], [L])
        for refl in ([0.7, 0.45, 0.3], [0.6, 0.22, 0.18], [0.5, 0.5, 0.5]):
            a = albedo(refl)
            compare(f"{name} x reflectance {refl}", [Ls, a], [L, np.array(refl)])
        a = albedo([0.7, 0.45, 0.3])
        refl = np.array([0.7, 0.45, 0.3])
        compare(f"{name} x [0.7 0.45 0.3] twice", [Ls, a, a], [L, refl, refl])
    # coateddiffuse: light that enters the smooth coat reaches the base, and the coat
    # returns the fraction F_i (its internal diffuse reflectance) to the base, again and
    # again: the base's albedo rho becomes rho / (1 - F_i rho), a convex function of rho.
    eta = 1.5
    mu = (np.arange(4096) + 0.5) / 4096  # cos theta inside
    sin_t = eta * np.sqrt(1 - mu * mu)
    with np.errstate(invalid="ignore"):
        cos_t = np.sqrt(np.maximum(0, 1 - sin_t ** 2))
        rs = ((eta * mu - cos_t) / (eta * mu + cos_t)) ** 2
        rp = ((mu - eta * cos_t) / (mu + eta * cos_t)) ** 2
    fr = np.where(sin_t >= 1, 1.0, 0.5 * (rs + rp))
    f_i = float(np.sum(fr * 2 * mu) / len(mu))
    print(f"\ncoateddiffuse base [0.6 0.22 0.18] under the smooth coat (eta 1.5, internal diffuse "
          f"reflectance F_i = {f_i:.3f}): rho / (1 - F_i rho), Dermis / pbrt-v4 - 1:")
    base = np.array([0.6, 0.22, 0.18])
    bs = albedo(base)
    for name, L in (("sky [0.35 0.38 0.45]", sky_s), ("key light [6 5.6 5]", key)):
        Ls = unbounded(L)
        compare(f"  {name}", [Ls, bs / (1 - f_i * bs)], [L, base / (1 - f_i * base)])
    print("\nTransmittance exp(-sigma_a d) of medium-dielectric's sigma_a [0.15 0.4 0.9] "
          "(absorption alone), Dermis / pbrt-v4 - 1:")
    sa = np.array([0.15, 0.4, 0.9])
    ss = unbounded(sa)
    for d in (0.5, 1.0, 1.4, 3.0):
        compare(f"  d = {d}", [np.exp(-ss * d)], [np.exp(-sa * d)])


if __name__ == "__main__":
    main()
