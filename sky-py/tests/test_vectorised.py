"""Vectorised calls equal per-element calls; shapes are kept; every form of time is the same
instant."""

from __future__ import annotations

import datetime
import zoneinfo

import numpy as np
import pytest
from conftest import FAST_YEARS, as_times, micros_between

import skymodels

VIENNA = (48.21, 16.37)


def same(a, b):
    return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)


@pytest.fixture(scope="module")
def micros():
    return micros_between(np.random.default_rng(11), FAST_YEARS, 150)


def test_daylight_over_an_array_equals_one_call_per_time(micros):
    aod = np.random.default_rng(1).uniform(0.05, 0.8, len(micros))
    whole = skymodels.daylight(*VIENNA, as_times(micros), aod, elevation=190.0)
    for i, t in enumerate(micros):
        one = skymodels.daylight(*VIENNA, as_times(t), aod[i], elevation=190.0)
        for key, column in whole.items():
            assert isinstance(one[key], float), key
            assert same(column[i], one[key]), (key, i)


def test_sun_position_and_daylight_at_sun_equal_their_elements(micros):
    whole = skymodels.sun_position(*VIENNA, as_times(micros), algorithm="spa")
    zenith = whole["sun_zenith"]
    at_sun = skymodels.daylight_at_sun(zenith, 0.3)
    for i, t in enumerate(micros[:40]):
        one = skymodels.sun_position(*VIENNA, as_times(t), algorithm="spa")
        assert all(same(whole[k][i], one[k]) for k in whole)
        single = skymodels.daylight_at_sun(float(zenith[i]), 0.3)
        assert all(same(at_sun[k][i], single[k]) for k in at_sun)


def test_controller_step_over_an_array_equals_one_call_per_time(micros):
    # Up to 10 klx: what sky-core takes with any sun (it refuses a reading above 1.5 times the
    # extraterrestrial irradiance at cos Z >= 0.065: about 129 W/m2 or 13 klx at night).
    lux = np.random.default_rng(2).uniform(0.0, 10_000.0, len(micros))
    whole = skymodels.controller_step(*VIENNA, as_times(micros), lux=lux, full_scale_lux=5000)
    assert whole["levels"].shape == (len(micros), 4)
    for i, t in enumerate(micros[:60]):
        one = skymodels.controller_step(*VIENNA, as_times(t), lux=lux[i], full_scale_lux=5000)
        for key, column in whole.items():
            assert same(column[i], one[key]), (key, i)


def test_shapes_are_kept(micros):
    grid = as_times(micros[:12]).reshape(3, 4)
    d = skymodels.daylight(*VIENNA, grid)
    flat = skymodels.daylight(*VIENNA, grid.ravel())
    assert d["cct"].shape == (3, 4)
    assert all(same(d[k].ravel(), flat[k]) for k in d)
    s = skymodels.controller_step(*VIENNA, grid)
    assert s["levels"].shape == (3, 4, 4)
    assert skymodels.daylight(*VIENNA, grid[:0])["cct"].shape == (0, 4)


def test_sky_arrays_equal_one_direction_at_a_time():
    rng = np.random.default_rng(4)
    dirs = rng.normal(size=(4, 5, 3))
    for sky in [
        skymodels.Sky.preetham(0.9, 1.0, 3.0),
        skymodels.Sky.neural(0.9, 1.0, 3.0),
        skymodels.Sky.daylight(1.66, 4.0),
        skymodels.Sky.cie(12, 0.9, 1.0, zenith_luminance=5000.0),
        skymodels.Sky.perez(0.9, 1.0, 3.0, 0.2, 20_000.0),
        skymodels.Sky.aoas("coral"),
        skymodels.Sky.sh(0.9, 1.0, 3.0),
    ]:
        rgb = sky.rgb(dirs)
        assert rgb.shape == (4, 5, 3) and rgb.dtype == np.float32
        assert same(rgb.reshape(-1, 3), sky.rgb(dirs.reshape(-1, 3)))
        for k, d in enumerate(dirs.reshape(-1, 3)):
            assert same(rgb.reshape(-1, 3)[k], sky.rgb(d)), sky
            assert same(rgb.reshape(-1, 3)[k], sky.rgb(d.tolist())), sky
        if sky.model not in ("aoas", "sh"):
            xyz, lum = sky.xyz(dirs), sky.luminance(dirs)
            assert lum.shape == (4, 5)
            assert same(xyz[..., 1], lum)
            assert same(sky.luminance(dirs[1, 2]), lum[1, 2])


def test_a_render_is_the_sky_at_its_pixel_directions():
    sky = skymodels.Sky.daylight(1.2, 0.5)
    for extent in ["upper", "sphere"]:
        image = sky.render(40, 20, extent=extent)
        dirs = skymodels.equirect_directions(40, 20, extent=extent)
        assert image.shape == (20, 40, 3) and dirs.shape == (20, 40, 3)
        assert same(image, sky.rgb(dirs))
        assert same(sky.render(40, 20, extent=extent, quantity="luminance"), sky.luminance(dirs))
    # Column i has azimuth 2 pi (i + 1/2) / width from +x; row j zenith (pi/2) (j + 1/2) / h,
    # in f32 as sky-core computes them.
    d = skymodels.equirect_directions(8, 4)
    f = np.float32
    zenith, azimuth = f(np.pi / 2) * f(1.5) / f(4), f(2 * np.pi) * f(2.5) / f(8)
    assert same(d[1, 2], skymodels.direction(zenith, azimuth))


def test_every_form_of_a_time_is_the_same_instant():
    at = np.datetime64("2026-03-20T16:05:30.250", "us")
    want = skymodels.daylight(*VIENNA, at)
    vienna = zoneinfo.ZoneInfo("Europe/Vienna")
    forms = [
        np.datetime64("2026-03-20T16:05:30.250000000", "ns"),
        np.datetime64("2026-03-20T16:05:30.250", "ms"),
        "2026-03-20T16:05:30.250",
        datetime.datetime(2026, 3, 20, 16, 5, 30, 250_000),  # naive: UTC
        datetime.datetime(2026, 3, 20, 17, 5, 30, 250_000, tzinfo=vienna),  # CET, UTC+1
        datetime.datetime(
            2026, 3, 20, 11, 5, 30, 250_000, tzinfo=datetime.timezone(datetime.timedelta(hours=-5))
        ),
    ]
    for form in forms:
        got = skymodels.daylight(*VIENNA, form)
        assert all(same(got[k], want[k]) for k in want), form
    # Sequences of them, mixed, give arrays.
    got = skymodels.daylight(*VIENNA, [forms[3], forms[4]])
    assert same(got["cct"], [want["cct"]] * 2)
    seconds = np.array(["2026-03-20T16:05:30"], dtype="datetime64[s]")
    assert skymodels.daylight(*VIENNA, seconds)["cct"].shape == (1,)


def test_long_arrays_split_over_threads_give_the_same_values_and_the_first_error():
    """Arrays of 8192 times or more per core are split over the cores: the values are those of
    short (one-thread) calls, and an error names the first bad element."""
    micros = micros_between(np.random.default_rng(12), FAST_YEARS, 40_000)
    times = as_times(micros)
    lux = np.random.default_rng(13).uniform(0.0, 10_000.0, len(micros))
    calls = [
        lambda t, s: skymodels.daylight(*VIENNA, t),
        lambda t, s: skymodels.sun_position(*VIENNA, t),
        lambda t, s: skymodels.controller_step(*VIENNA, t, lux=lux[s]),
    ]
    for call in calls:
        whole = call(times, slice(None))
        parts = [call(times[k : k + 5000], slice(k, k + 5000)) for k in range(0, len(times), 5000)]
        for key, column in whole.items():
            assert same(column, np.concatenate([p[key] for p in parts])), key
    aod = np.full(len(micros), 0.1)
    aod[[25_000, 33_000]] = 0.9
    with pytest.raises(ValueError, match=r"^aod\[25000\]: aerosol optical depth = 0\.9"):
        skymodels.daylight(*VIENNA, times, aod)
