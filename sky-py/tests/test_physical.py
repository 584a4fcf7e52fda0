"""The physical atmosphere (the wheel built with sky-py's `physical` feature:
`scripts/python.sh test --physical`) against sky-train's own values, bit for bit; without the
feature, its absence."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

import skymodels

physical_only = pytest.mark.skipif(
    not skymodels.HAS_PHYSICAL, reason="the wheel was built without the physical feature"
)


def test_the_wheel_is_the_variant_built():
    variant = os.environ.get("SKY_PY_VARIANT", "default")
    assert skymodels.HAS_PHYSICAL == (variant == "physical")
    assert hasattr(skymodels, "PhysicalAtmosphere") == skymodels.HAS_PHYSICAL


ATMOSPHERES = [
    {},
    {"aod": 0.1, "ozone_du": 250.0, "albedo": 0.3, "angstrom": 1.1},
    {"aod": 0.05, "elevation": 2317.0},
]


def atmosphere(params):
    return skymodels.PhysicalAtmosphere(**params, resolution="coarse", cache_dir=False)


@physical_only
@pytest.mark.parametrize("params", ATMOSPHERES)
def test_spectra_and_daylight_equal_sky_train(native, params):
    atm = atmosphere(params)
    assert atm.wavelengths.shape == (47,) and atm.wavelengths[0] == 365.0
    zenith = [0.0, 0.7, math.radians(89.5), math.radians(96.0), math.radians(108.0)]
    cases = [{"kind": "physical_irradiance", "sun_zenith": z, "sun_azimuth": 0.0, **params}
             for z in zenith]
    got = atm.irradiance(zenith)
    for k, want in enumerate(native(cases)):
        for key in ["global", "diffuse", "direct_horizontal", "direct_normal"]:
            assert got[key].shape == (len(zenith), 47)
            assert np.array_equal(got[key][k].view(np.uint64), np.array(want[key], np.uint64))
    daylight = atm.daylight(np.reshape(zenith, (5, 1)))
    cases = [{**c, "kind": "physical_daylight"} for c in cases]
    for k, want in enumerate(native(cases)):
        for key, bits in want.items():
            assert daylight[key].shape == (5, 1)
            assert daylight[key][k, 0].view(np.uint64) == np.uint64(bits), key
    rng = np.random.default_rng(2)
    dirs = rng.normal(size=(30, 3))
    want = native([{"kind": "physical_radiance", "sun_zenith": 0.9, "sun_azimuth": 2.0,
                    "dirs": dirs.tolist(), **params}])[0]
    got = atm.spectral_radiance(0.9, 2.0, dirs.reshape(5, 6, 3))
    assert got.shape == (5, 6, 47)
    assert np.array_equal(got.reshape(30, 47).view(np.uint64), np.array(want["values"], np.uint64))


@physical_only
def test_bad_atmospheres_and_suns_raise():
    with pytest.raises(ValueError, match=r"aod = 6 is outside the valid range \[0, 5\]"):
        atmosphere({"aod": 6.0})
    with pytest.raises(ValueError, match="ozone_du = -1"):
        atmosphere({"ozone_du": -1.0})
    with pytest.raises(ValueError, match=r"elevation = 7000 is outside the valid range \[-500, 6000\]"):
        atmosphere({"elevation": 7000.0})
    with pytest.raises(ValueError, match="resolution"):
        skymodels.PhysicalAtmosphere(resolution="fine")
    atm = atmosphere({})
    with pytest.raises(ValueError, match="sun_zenith"):
        atm.irradiance([0.5, math.radians(109.0)])
    with pytest.raises(ValueError, match="dirs"):
        atm.spectral_radiance(0.5, 0.0, np.zeros((3, 2)))
