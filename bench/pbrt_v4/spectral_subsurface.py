#!/usr/bin/python3
"""How much of the difference between pbrt-v4 and Dermis' `--subsurface pbrt-v4` on a coloured
subsurface material is pbrt-v4's spectral rendering (docs/results/results-vs-pbrt-v4.md).

pbrt-v4 uplifts sigma_a and sigma_s to smooth spectra (RGBUnboundedSpectrum, Jakob & Hanika
2019) and evaluates the BSSRDF per wavelength: the single-scattering albedo rho(lambda) =
sigma_s / (sigma_a + sigma_s) varies across each channel's band, and the effective albedo
rho_eff(rho) is far from linear near rho = 1, so the colour of rho_eff(rho(lambda)) is not
rho_eff of the RGB albedo Dermis uses. For an object many mean free paths thick, the
picture is about rho_eff, so the ratio of the two predicts the difference on the object.
rho_eff here is the classical dipole's total diffuse reflectance (Jensen et al. 2001,
eq. 5-6 with Jensen & Buehler 2002, eq. 3): a stand-in of the same shape as the
photon-beam table's, good for the sign and size only.

  /usr/bin/python3 -m bench.pbrt_v4.spectral_subsurface
"""
import numpy as np

from bench.pbrt_v4 import spectral_uplift as su

ETA = 1.33
# The scenes of bench/pbrt_v4/scenes given by coefficients (scale does not change rho).
MEDIA = {
    "sss-named (Skin1)": ((0.032, 0.17, 0.48), (0.74, 0.88, 1.01)),
    "sss-sigma": ((0.02, 0.06, 0.15), (1.2, 1.3, 1.4)),
}


def total_reflectance(alpha, eta=ETA):
    """The dipole's R_d(alpha') (Jensen & Buehler 2002, eq. 3), F_dr by Jensen et al.'s fit."""
    f_dr = -1.440 / eta ** 2 + 0.710 / eta + 0.668 + 0.0636 * eta
    a = (1 + f_dr) / (1 - f_dr)
    s = np.sqrt(3 * (1 - alpha))
    return alpha / 2 * (1 + np.exp(-4 / 3 * a * s)) * np.exp(-s)


def main():
    print("Predicted Dermis (RGB) / pbrt-v4 (spectral) - 1 on a thick object, per channel (%):")
    for name, (sa, ss) in MEDIA.items():
        rho_lambda = su.unbounded(ss) / (su.unbounded(sa) + su.unbounded(ss))
        spectral = su.colour(total_reflectance(rho_lambda))
        rgb = total_reflectance(np.array(ss) / (np.array(sa) + np.array(ss)))
        print(f"  {name:20s} " + " ".join(f"{100 * (d / p - 1):+5.1f}" for d, p in zip(rgb, spectral)))


if __name__ == "__main__":
    main()
