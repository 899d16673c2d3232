"""The subsurface libraries through the module, against independent references."""
import numpy as np
import pytest


def test_burley_profile_integrates_to_its_albedo_and_samples_its_pdf(dermis_module):
    p = dermis_module.Profile.burley(0.6, 1.0)
    r = np.linspace(1e-6, p.r_max(), 200001)
    dr = r[1] - r[0]
    energy = np.sum(p.eval(r) * 2 * np.pi * r) * dr
    assert energy == pytest.approx(p.albedo() * 0.999, rel=2e-3)  # kept fraction 0.999 inside r_max
    assert np.sum(p.pdf(r)) * dr == pytest.approx(1.0, rel=2e-3)
    # Samples against the pdf: the fraction in each of 8 bins within 4 standard errors.
    rng = np.random.default_rng(3)
    n = 200000
    samples = p.sample(rng.random(n))
    edges = np.linspace(0, p.r_max(), 9)
    counts, _ = np.histogram(samples, edges)
    for k in range(8):
        inside = (r >= edges[k]) & (r < edges[k + 1])
        expected = np.sum(p.pdf(r[inside])) * dr
        sigma = np.sqrt(expected * (1 - expected) / n)
        assert abs(counts[k] / n - expected) < 4 * sigma + 1e-4, k


def test_halfspace_simulation_matches_chandrasekhar(dermis_module):
    # Index-matched isotropic half-space under diffuse light: the exact albedo is
    # Chandrasekhar's; the simulation must agree within 4 standard errors.
    alpha = 0.9
    exact = dermis_module.chandrasekhar_albedo(alpha)
    sim = dermis_module.simulate_halfspace(albedo=alpha, incidence="diffuse", paths=40000, seed=2)
    assert abs(sim["albedo"] - exact) < 4 * sim["albedo_stderr"]
    assert sim["R"].shape == (64,)


def test_albedo_inversion_inverts(dermis_module):
    inv = dermis_module.AlbedoInversion(eta=1.0, size=8, paths_per_node=2000)
    a = inv.surface_albedo(np.array([0.3, 0.9]))
    assert np.allclose(inv.single_scattering_albedo(a), [0.3, 0.9], atol=1e-6)
    assert a[0] < a[1]


def test_bad_profile_parameters_are_value_errors(dermis_module):
    with pytest.raises(ValueError, match="albedo"):
        dermis_module.Profile.burley(1.5, 1.0)
    with pytest.raises(ValueError, match="incidence|normal"):
        dermis_module.simulate_halfspace(incidence="sideways")
