"""Bad input raises a Python exception naming the parameter (and, for a number, its valid
range); hostile values never crash the interpreter."""

from __future__ import annotations

import numpy as np
import pytest

import skymodels

VIENNA = (48.21, 16.37)
NOON = "2026-06-21T11:00"
NAN, INF = float("nan"), float("inf")


def raises(call, *fragments, error=ValueError):
    with pytest.raises(error) as e:
        call()
    for fragment in fragments:
        assert fragment in str(e.value), (fragment, str(e.value))


@pytest.mark.parametrize("function", [skymodels.daylight, skymodels.sun_position,
                                      skymodels.controller_step])
def test_sites_and_times(function):
    raises(lambda: function(91.0, 16.37, NOON), "latitude [deg] = 91", "[-90, 90]")
    raises(lambda: function(NAN, 16.37, NOON), "latitude [deg] = NaN", "[-90, 90]")
    raises(lambda: function(48.0, -181.0, NOON), "longitude [deg] = -181", "[-180, 180]")
    raises(lambda: function(*VIENNA, NOON, elevation=1e5), "elevation [m] = 100000",
           "[-500, 10000]")
    raises(lambda: function(*VIENNA, NOON, algorithm="nrel"), "algorithm", '"fast"', '"spa"')
    times = np.array(["2026-01-01", "1999-12-31T23:59", "2026-01-02"], dtype="datetime64[m]")
    raises(lambda: function(*VIENNA, times), "times[1] = 1999-12-31T23:59:00.000000Z",
           "[2000, 2110]", 'algorithm="spa"')
    raises(lambda: function(*VIENNA, times[1]), "times = 1999-12-31", "[2000, 2110]")
    raises(lambda: function(*VIENNA, "3000-01-01", algorithm="spa"), "year = 3000",
           "[1, 2999]")
    raises(lambda: function(*VIENNA, np.array(["NaT"], dtype="datetime64[s]")), "times[0]",
           "NaT")
    raises(lambda: function(*VIENNA, [1.5, 2.5]), "times", error=TypeError)
    raises(lambda: function(*VIENNA, "yesterday"), error=ValueError)


def test_site_atmosphere():
    """The daylight's and the controller's clear atmosphere: the site's elevation (its
    pressure) and the ozone column, each named with its range."""
    for function in [skymodels.daylight, skymodels.controller_step]:
        raises(lambda: function(*VIENNA, NOON, elevation=6000.0),
               "site elevation [m] = 6000", "[-500, 5000]")
        raises(lambda: function(*VIENNA, NOON, ozone_du=100.0), "ozone_du",
               "ozone column [DU] = 100", "[200, 500]")
    # The sun alone has no atmosphere: a site up to 10 km.
    assert skymodels.sun_position(*VIENNA, NOON, elevation=6000.0)["elevation"] > 0


def test_aerosol_optical_depth():
    raises(lambda: skymodels.daylight(*VIENNA, NOON, 0.9), "aod: aerosol optical depth = 0.9",
           "[0.05, 0.8]")
    times = np.array([NOON] * 3, dtype="datetime64[m]")
    raises(lambda: skymodels.daylight(*VIENNA, times, [0.1, 0.2, NAN]), "aod[2]", "NaN")
    raises(lambda: skymodels.daylight(*VIENNA, times, [0.1, 0.2]), "aod", "one per time")
    raises(lambda: skymodels.daylight_at_sun([0.1, 4.0]), "sun_zenith[1]", "[0, 3.1415927]")
    raises(lambda: skymodels.daylight_at_sun(0.5, -1.0), "aod", "[0.05, 0.8]")
    raises(lambda: skymodels.controller_step(*VIENNA, times, aod=[0.1, 0.2, INF]), "aod[2]",
           "[0.05, 0.8]")


def test_controller_settings_and_measurements():
    step = skymodels.controller_step
    raises(lambda: step(*VIENNA, NOON, full_scale_lux=0.0), "full_scale_lux")
    raises(lambda: step(*VIENNA, NOON, light="window"), "light", '"global"', '"sky"')
    raises(lambda: step(*VIENNA, NOON, decomposition="by-hand"), "decomposition", '"erbs"')
    raises(lambda: step(*VIENNA, NOON, lux=100.0, ghi=10.0), "lux", "not both")
    raises(lambda: step(*VIENNA, NOON, dhi=10.0), "dhi", "ghi")
    raises(lambda: step(*VIENNA, NOON, lux=-5000.0), "lux:", "global illuminance")
    raises(lambda: step(*VIENNA, NOON, lux=NAN), "lux")
    times = np.array([NOON] * 2, dtype="datetime64[m]")
    raises(lambda: step(*VIENNA, times, ghi=[500.0, 600.0], dhi=[100.0, 900.0]),
           "ghi[1], dhi[1]", "diffuse")
    bad = [(0.7, 0.3, 300.0), (0.17, 0.7, 600.0), (0.13, 0.06, -1.0), (0.44, 0.4, 900.0)]
    raises(lambda: step(*VIENNA, NOON, luminaire=bad), "luminaire")
    raises(lambda: step(*VIENNA, NOON, luminaire=bad[:3]), error=(TypeError, ValueError))


def test_sky_parameters():
    Sky = skymodels.Sky
    raises(lambda: Sky.preetham(2.0, 0.0, 3.0), "below the horizon")
    raises(lambda: Sky.preetham(0.5, 0.0, 7.0), "turbidity = 7", "[2, 6]")
    raises(lambda: Sky.preetham(NAN, 0.0, 3.0), "sun zenith [rad] = NaN", "[0, 3.1415927]")
    raises(lambda: Sky.preetham(0.5, INF, 3.0), "sun azimuth [rad]", "finite")
    raises(lambda: Sky.neural(0.5, 0.0, 3.0, weights="perez"), "weights", '"preetham"')
    raises(lambda: Sky.neural(0.5, 0.0, 3.0, weights=b"\x00" * 100), "weights")
    raises(lambda: Sky.neural(0.5, 0.0, 11.0, weights="hosek"), "turbidity", "[1, 10]")
    raises(lambda: Sky.daylight(0.5, 0.0, aod=0.01), "aod", "[0.05, 0.8]")
    raises(lambda: Sky.cie(16, 0.5, 0.0, zenith_luminance=1.0), "CIE sky type = 16", "[1, 15]")
    raises(lambda: Sky.cie(300, 0.5, 0.0, zenith_luminance=1.0), "CIE sky type = 300")
    raises(lambda: Sky.cie(-1, 0.5, 0.0, zenith_luminance=1.0), "CIE sky type = -1")
    raises(lambda: Sky.cie(2**70, 0.5, 0.0, zenith_luminance=1.0),
           "CIE sky type = 1180591620717411303424", "[1, 15]")
    raises(lambda: Sky.cie(3.0, 0.5, 0.0, zenith_luminance=1.0), error=TypeError)
    raises(lambda: Sky.cie(3, 0.5, 0.0), "exactly one")
    raises(lambda: Sky.cie(3, 0.5, 0.0, zenith_luminance=1.0, diffuse_illuminance=1.0),
           "exactly one")
    raises(lambda: Sky.cie(3, 0.5, 0.0, zenith_luminance=-1.0), "zenith luminance", "[0, ")
    raises(lambda: Sky.cie(3, 0.5, 0.0, zenith_luminance=1.0, chromaticity=(0.3, 0.0)),
           "chromaticity")
    raises(lambda: Sky.perez(0.5, 0.0, 0.9, 0.1, 1000.0), "sky clearness = 0.9")
    raises(lambda: Sky.perez(0.5, 0.0, 2.0, 0.1, -1.0), "diffuse illuminance [lx] = -1")
    raises(lambda: Sky.perez_from_irradiance(0.5, 0.0, 400.0, 900.0, 100), "ghi, dhi",
           "diffuse")
    raises(lambda: Sky.perez_from_irradiance(0.5, 0.0, 400.0, 100.0, 400), "day of the year",
           "[1, 366]")
    raises(lambda: Sky.aoas("twilight"), "preset", "coral")
    raises(lambda: Sky.sh(0.5, 0.0, 3.0, bands=8), "SH bands = 8", "[1, 7]")
    raises(lambda: Sky.sh(0.5, 0.0, 3.0, bands=-3), "SH bands = -3")
    raises(lambda: Sky.sh(0.5, 0.0, 3.0, bands=-(2**64)), "SH bands = -18446744073709551616")
    raises(lambda: Sky.perez_from_irradiance(0.5, 0.0, 400.0, 100.0, 2**63), "day of the year")
    raises(lambda: Sky.preetham("high", 0.0, 3.0), error=TypeError)


def test_sky_evaluation_and_images():
    sky = skymodels.Sky.preetham(0.5, 0.0, 3.0)
    raises(lambda: sky.rgb(np.zeros((4, 2))), "dirs", "length 3")
    raises(lambda: sky.rgb(np.zeros(0)), "dirs")
    raises(lambda: sky.rgb([["a", "b", "c"]]), error=(TypeError, ValueError))
    raises(lambda: skymodels.Sky.aoas("coral").xyz([0, 0, 1]), "quantity", "rgb")
    raises(lambda: sky.render(0, 10), "image width [px] = 0", "[1, 65536]")
    raises(lambda: sky.render(10, 70_000), "image height [px] = 70000", "[1, 65536]")
    raises(lambda: sky.render(65_536, 65_536), "65536 × 65536", "33554432")
    raises(lambda: sky.render(8, 4, extent="dome"), "extent", '"upper"')
    raises(lambda: sky.render(8, 4, quantity="radiance"), "quantity", '"rgb"')
    raises(lambda: skymodels.equirect_directions(-8, 4), "image width [px] = -8")
    raises(lambda: sky.render(8, 2**80), "image height [px] = 1208925819614629174706176")
    raises(lambda: skymodels.direction(np.zeros(3), np.zeros(4)), error=ValueError)


def test_hostile_values_give_finite_results_or_errors():
    """NaN, infinities, huge and subnormal values: a result (finite where sky-core promises
    it) or a Python exception, never a crash."""
    hostile = [NAN, INF, -INF, 1e38, 3e38, -1e38, 1e-45, -0.0, 0.0, 1e300]
    dirs = np.array([[a, b, c] for a in hostile[:5] for b in hostile[5:] for c in hostile[::3]])
    dirs = np.concatenate([dirs, np.random.default_rng(9).normal(size=(50, 3))])
    with np.errstate(over="ignore"):
        for sky in [
            skymodels.Sky.preetham(0.5, 1.0, 3.0),
            skymodels.Sky.neural(0.5, 1.0, 3.0),
            skymodels.Sky.daylight(1.6, 1.0),
            skymodels.Sky.cie(8, 0.5, 1.0, diffuse_illuminance=1e4),
            skymodels.Sky.perez(0.5, 1.0, 2.0, 0.2, 1e4),
            skymodels.Sky.sh(0.5, 1.0, 3.0),
        ]:
            assert np.isfinite(sky.rgb(dirs)).all(), sky
    for v in hostile:
        for call in [
            lambda: skymodels.Sky.preetham(v, v, v),
            lambda: skymodels.Sky.daylight(v, v, aod=v),
            lambda: skymodels.daylight_at_sun(v, v),
            lambda: skymodels.daylight(v, v, NOON, v, elevation=v),
            lambda: skymodels.controller_step(*VIENNA, NOON, lux=v, full_scale_lux=v),
        ]:
            try:
                result = call()
            except ValueError:
                continue
            values = result.values() if isinstance(result, dict) else [result.rgb([0, 0, 1])]
            for value in values:
                assert not np.isinf(np.asarray(value, dtype=np.float64)).any()
