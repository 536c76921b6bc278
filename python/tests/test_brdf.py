"""hilite.brdf equals `hilite brdf ... --json`, and meets closed forms that share nothing with it."""

import math

import numpy as np
import pytest

from conftest import cli_rows


def test_fresnel_equals_cli(hilite):
    t = np.arange(0.0, 91.0, 5.0)
    got = hilite.brdf.fresnel(t, material="gold")
    rows = cli_rows("brdf", "fresnel", "--material", "gold", "--incidence", "0:90:5")
    np.testing.assert_array_equal(got, np.array([r["rgb"] for r in rows]))
    spectral = hilite.brdf.fresnel(t, material="copper", spectral=True)
    rows = cli_rows("brdf", "fresnel", "--material", "copper", "--spectral", "--incidence", "0:90:5")
    np.testing.assert_array_equal(spectral, np.array([r["rgb"] for r in rows]))


def test_fresnel_closed_form(hilite):
    # Schlick: F0 + (1 - F0)(1 - cos)^5, exact at 0 and 90 degrees
    f = hilite.brdf.fresnel([0.0, 60.0, 90.0], fresnel="schlick", f0=0.04)
    np.testing.assert_allclose(f[:, 0], [0.04, 0.04 + 0.96 * 0.5 ** 5, 1.0], rtol=1e-12)
    assert hilite.brdf.fresnel(30.0, fresnel="schlick", f0=0.04).shape == (3,)


def test_albedo_equals_cli(hilite):
    t = np.arange(0.0, 86.0, 17.0)
    got = hilite.brdf.albedo(t, model="ggx", roughness=0.3, geometry="smith")
    rows = cli_rows("brdf", "albedo", "--model", "ggx", "--roughness", "0.3", "--geometry", "smith",
                    "--incidence", "0:85:17")
    np.testing.assert_array_equal(got, np.array([r["albedo"] for r in rows]))
    hh = hilite.brdf.bihemispherical_albedo(model="ggx", roughness=0.3, geometry="smith")
    np.testing.assert_array_equal(hh, rows[0]["bihemispherical_albedo"])


def test_lambert_albedo_is_rho(hilite):
    a = hilite.brdf.albedo([0.0, 45.0], model="none", diffuse="lambert", albedo=0.7)
    np.testing.assert_allclose(a, 0.7, rtol=1e-9)


def test_normalization(hilite):
    v = hilite.brdf.normalization(model="beckmann", roughness=[0.02, 0.1, 1.0])
    rows = cli_rows("brdf", "normalization", "--model", "beckmann", "--roughness", "0.02,0.1,1")
    np.testing.assert_array_equal(v, [r["integral"] for r in rows])
    np.testing.assert_allclose(v, 1.0, atol=1e-6)
    with pytest.raises(hilite.InputError, match="normalization needs an NDF"):
        hilite.brdf.normalization(model="phong")


def test_eval_lambert_and_reciprocity(hilite):
    rng = np.random.default_rng(1)

    def directions(n):
        z = rng.uniform(0.05, 1, n)
        phi = rng.uniform(0, 2 * math.pi, n)
        s = np.sqrt(1 - z * z)
        return np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=-1)

    wi, wo = directions(500), directions(500)
    f = hilite.brdf.eval(wi, wo, model="none", diffuse="lambert", albedo=0.5)
    np.testing.assert_allclose(f, 0.5 / math.pi, rtol=1e-12)
    g1 = hilite.brdf.eval(wi, wo, model="ggx", roughness=0.3, geometry="smith", fresnel="schlick", f0=0.04)
    g2 = hilite.brdf.eval(wo, wi, model="ggx", roughness=0.3, geometry="smith", fresnel="schlick", f0=0.04)
    np.testing.assert_allclose(g1, g2, rtol=1e-12)
    # GGX at normal incidence and exitance, implicit geometry (G = cos_i cos_o), no Fresnel:
    # f = D(n) / 4 with D(n) = 1 / (pi alpha^2) (Walter et al. 2007, eq. 33)
    n = np.array([0.0, 0.0, 1.0])
    d = hilite.brdf.eval(n, n, model="ggx", roughness=0.2, fresnel="none")
    np.testing.assert_allclose(d, 1 / (4 * math.pi * 0.2 ** 2), rtol=1e-12)
    # broadcasting (..., 3) against (3,)
    assert hilite.brdf.eval(wi.reshape(25, 20, 3), n, model="ggx").shape == (25, 20, 3)
    below = hilite.brdf.eval([0, 0, 1], [0.6, 0, -0.8], model="ggx")
    assert np.all(below == 0)


def test_bounces_equal_cli(hilite):
    # The same settings and seeds: the CLI's rows field for field, times aside.
    settings = dict(paths=4000, batches=4, texels=256, bumps_per_tile=16)
    got = hilite.brdf.bounces([0.0, 60.0], roughness=0.6, material="gold", **settings)
    rows = cli_rows("brdf", "bounces", "--json", "--paths", "4000", "--batches", "4", "--texels", "256",
                    "--bumps-per-tile", "16", "--roughness", "0.6", "--material", "gold", "--incidence", "0,60")
    assert len(rows) == 2 and list(got["theta_deg"]) == [0.0, 60.0]
    for key in rows[0]:
        if key.endswith("time_ms"):
            continue
        want = [r[key] for r in rows]
        if isinstance(want[0], str):
            assert list(got[key]) == want, key
        else:
            np.testing.assert_array_equal(got[key], np.array(want, dtype=float), err_msg=key)
    # F = 1 and Smith's walk loses nothing: its first order and the rest add to 1.
    np.testing.assert_allclose(got["smith_e1"] + got["smith_multiple"], 1.0, atol=1e-12)


def test_bounces_refusals(hilite):
    with pytest.raises(hilite.InputError, match="model"):
        hilite.brdf.bounces(0.0, model="ggx", roughness=0.5, paths=100)
    with pytest.raises(hilite.InputError, match="paths"):
        hilite.brdf.bounces(0.0, roughness=0.5, paths=0)
    with pytest.raises(hilite.InputError, match="surface"):
        hilite.brdf.bounces(0.0, roughness=0.5, paths=100, surface="smooth")
    with pytest.raises(TypeError, match="batches"):
        hilite.brdf.bounces(0.0, roughness=0.5, batches=2.5)
