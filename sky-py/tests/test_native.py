"""The wheel's values against sky-core's own, computed by the reference binary from the same
inputs: bit for bit, since the computation is the same (sky-core's functions, in f32)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import (
    FAST_YEARS,
    SPA_YEARS,
    as_times,
    assert_same32,
    bits32,
    f32_values,
    fields,
    micros_between,
)

import skymodels

# Latitude, longitude, elevation: mid-latitude, polar day and night, the tropics at altitude,
# the southern hemisphere, the date line, the South Pole.
SITES = [
    (48.21, 16.37, 190.0),
    (69.65, 18.96, 10.0),
    (-0.18, -78.47, 2850.0),
    (-33.87, 151.21, 58.0),
    (64.84, -179.99, 0.0),
    (-90.0, 0.0, 2835.0),
]
DAYLIGHT_KEYS = [
    "global_illuminance",
    "diffuse_illuminance",
    "direct_illuminance",
    "direct_normal_illuminance",
    "x",
    "y",
    "cct",
    "duv",
    "melanopic_edi",
]
N = 60  # instants per site and algorithm


def instants(seed, algorithm):
    rng = np.random.default_rng(seed)
    years = FAST_YEARS if algorithm == "fast" else SPA_YEARS
    micros = micros_between(rng, years, N)
    return micros, rng


@pytest.mark.parametrize("algorithm", ["fast", "spa"])
def test_daylight_and_sun_position_equal_sky_core(native, algorithm):
    for k, (lat, lon, elevation) in enumerate(SITES):
        micros, rng = instants(100 * k + len(algorithm), algorithm)
        aod = f32_values(rng, skymodels.MIN_AOD, skymodels.MAX_AOD, N)
        # Every other site its own ozone column; the others the default.
        ozone = None if k % 2 == 0 else 230.0 + 50.0 * k
        site = {"latitude": lat, "longitude": lon, "elevation": elevation, "algorithm": algorithm}
        cases = [
            {"kind": "daylight", "time": fields(t), "aod": a, "ozone_du": ozone, **site}
            for t, a in zip(micros, aod)
        ]
        suns = [{**c, "kind": "sun"} for c in cases]
        want, want_sun = native(cases), native(suns)
        assert not any("error" in r for r in want + want_sun), want[:3]

        got = skymodels.daylight(
            lat,
            lon,
            as_times(micros),
            np.float32(aod),
            elevation=elevation,
            ozone_du=ozone,
            algorithm=algorithm,
        )
        for key in DAYLIGHT_KEYS:
            assert_same32(got[key], want, key)

        sun = skymodels.sun_position(
            lat, lon, as_times(micros), elevation=elevation, algorithm=algorithm
        )
        for key in ["zenith", "apparent_zenith", "elevation", "azimuth"]:
            expected = np.array([r[key] for r in want_sun], dtype=np.uint64)
            assert np.array_equal(sun[key].view(np.uint64), expected), key
        for key in ["sun_zenith", "sun_azimuth"]:
            assert_same32(sun[key], want_sun, key)


def test_daylight_is_the_controllers_clear_sky():
    """Without a measurement the controller follows the clear sky at its site (sky-core's
    controller::step): `daylight` at the same site, time, aerosol and ozone is that light,
    at every site of SITES (up to 2,850 m: the pressure and the refraction differ there)."""
    for k, (lat, lon, elevation) in enumerate(SITES):
        micros, rng = instants(500 + k, "fast")
        aod = f32_values(rng, skymodels.MIN_AOD, skymodels.MAX_AOD, N)
        ozone = 260.0 + 30.0 * k
        times = as_times(micros)
        day = skymodels.daylight(
            lat, lon, times, np.float32(aod), elevation=elevation, ozone_du=ozone
        )
        step = skymodels.controller_step(
            lat, lon, times, aod=np.float32(aod), elevation=elevation, ozone_du=ozone,
            full_scale_lux=1e9,
        )
        assert np.array_equal(day["global_illuminance"], step["illuminance"]), (lat, lon)
        assert np.array_equal(day["melanopic_edi"], step["melanopic_edi"]), (lat, lon)


def test_daylight_at_sun_equals_sky_core(native):
    rng = np.random.default_rng(7)
    zenith = f32_values(rng, 0.0, math.pi, 200)
    zenith += [float(np.float32(math.radians(d))) for d in (90.0, 96.0, 108.0, 120.0)]
    aod = f32_values(rng, skymodels.MIN_AOD, skymodels.MAX_AOD, len(zenith))
    want = native(
        [{"kind": "daylight_at_sun", "sun_zenith": z, "aod": a} for z, a in zip(zenith, aod)]
    )
    got = skymodels.daylight_at_sun(np.float32(zenith), np.float32(aod))
    for key in DAYLIGHT_KEYS:
        assert_same32(got[key], want, key)


def measurements(rng, n):
    """Readings of each kind, within and beyond what sky-core accepts."""
    out = []
    for i in range(n):
        kind = i % 4
        if kind == 0:
            out.append(None)
        elif kind == 1:
            out.append({"lux": float(np.float32(rng.choice([0.0, -300.0, -5e3, 40.0, 5e3, 9e4])))})
        elif kind == 2:
            out.append({"ghi": float(np.float32(rng.uniform(-5.0, 1100.0)))})
        else:
            ghi = float(np.float32(rng.uniform(0.0, 900.0)))
            out.append({"ghi": ghi, "dhi": float(np.float32(ghi * rng.uniform(0.0, 1.02)))})
    return out


def step_case(site, t, measurement, **settings):
    """The reference binary's `step` case at `site` (latitude, longitude, elevation) and time
    `t` (microseconds) with `measurement`: the fast sun, aod 0.2, the global light at 10 klx
    full scale, the default split and luminaire, unless `settings` say otherwise."""
    lat, lon, elevation = site
    case = {
        "kind": "step",
        "latitude": lat,
        "longitude": lon,
        "elevation": elevation,
        "algorithm": "fast",
        "time": fields(t),
        "aod": float(np.float32(0.2)),
        "light": "global",
        "full_scale_lux": 10_000.0,
        "decomposition": None,
        "measurement": measurement,
        "luminaire": None,
    }
    return case | settings


@pytest.mark.parametrize(
    "light, decomposition, luminaire",
    [
        ("global", None, None),
        ("global", "erbs", None),
        ("sky", "dirindex", None),
        ("sky", "engerer2", None),
        (
            "global",
            "engerer2-global",
            [(0.69, 0.30, 250.0), (0.18, 0.69, 500.0), (0.14, 0.05, 120.0), (0.45, 0.41, 800.0)],
        ),
    ],
)
def test_controller_step_equals_sky_core(native, light, decomposition, luminaire):
    rng = np.random.default_rng(len(light) + len(decomposition or ""))
    for lat, lon, elevation in SITES[:4]:
        micros = micros_between(rng, FAST_YEARS, 48)
        readings = measurements(rng, len(micros))
        full_scale = float(np.float32(rng.uniform(500.0, 20_000.0)))
        cases = [
            step_case(
                (lat, lon, elevation),
                t,
                m,
                light=light,
                full_scale_lux=full_scale,
                decomposition=decomposition,
                luminaire=luminaire,
            )
            for t, m in zip(micros, readings)
        ]
        want = native(cases)
        keywords = dict(
            aod=np.float32(0.2),
            elevation=elevation,
            light=light,
            full_scale_lux=full_scale,
            decomposition=decomposition,
            luminaire=luminaire,
        )
        for kind in [None, "lux", "ghi", "ghi+dhi"]:
            rows = [
                i
                for i, m in enumerate(readings)
                if (m is None and kind is None)
                or (m is not None and "+".join(m) == kind)
            ]
            ok = [i for i in rows if "error" not in want[i]]
            refused = [i for i in rows if "error" in want[i]]
            values = {}
            if kind is not None:
                for name in kind.split("+"):
                    values[name] = np.float32([readings[i][name] for i in ok])
            got = skymodels.controller_step(lat, lon, as_times(micros[ok]), **values, **keywords)
            expected = [want[i] for i in ok]
            keys = ["illuminance", "x", "y", "cct", "duv", "melanopic_edi"]
            if kind is not None:
                keys += [
                    "clear_sky_index",
                    "overcast_fraction",
                    "global_irradiance",
                    "diffuse_irradiance",
                    "direct_normal_irradiance",
                    "clear_sky_illuminance",
                    "diffuse_illuminance",
                ]
                assert np.array_equal(got["sky_type"], [r["sky_type"] for r in expected])
            for key in keys:
                assert_same32(got[key], expected, key)
            levels = np.array([r["levels"] for r in expected], dtype=np.uint32).reshape(-1, 4)
            assert np.array_equal(bits32(got["levels"]), levels)
            assert got["luminance_clipped"].tolist() == [r["luminance_clipped"] for r in expected]
            # What sky-core refuses, the wheel refuses with sky-core's message.
            for i in refused:
                one = {name: readings[i][name] for name in kind.split("+")}
                with pytest.raises(ValueError) as e:
                    skymodels.controller_step(lat, lon, as_times(micros[i]), **one, **keywords)
                assert want[i]["error"] in str(e.value)


@pytest.mark.parametrize("decomposition", [None, "dirindex", "erbs"])
def test_controller_step_with_history_equals_sky_core(native, decomposition):
    """history=True steps one series in time order as sky-core's step_with_history does
    (the native reference keeps one history across the series' cases): a pyranometer's morning
    every minute with a passing cloud, a two-hour gap, and a few steps more. Without the
    history, DIRINT's split of the steady minutes differs."""
    rng = np.random.default_rng(7)
    lat, lon, elevation = SITES[0]
    start = int(np.datetime64("2026-06-21T06:00", "us").astype(np.int64))
    minutes = np.concatenate([np.arange(0, 150), np.arange(270, 300)])
    micros = start + minutes * 60_000_000
    hours = 6.0 + minutes / 60.0
    clear = 900.0 * np.sin(np.pi * (hours - 4.0) / 16.0) ** 1.3
    cloud = np.where((minutes > 60) & (minutes < 80), 0.35, 1.0)
    ghi = np.float32(clear * cloud * (1.0 + 0.002 * rng.standard_normal(len(minutes))))
    cases = [
        step_case(
            SITES[0], t, {"ghi": float(g)}, decomposition=decomposition, history="morning"
        )
        for t, g in zip(micros, ghi)
    ]
    want = native(cases)
    assert not any("error" in r for r in want)
    keywords = dict(aod=np.float32(0.2), elevation=elevation, decomposition=decomposition)
    got = skymodels.controller_step(lat, lon, as_times(micros), ghi=ghi, history=True, **keywords)
    for key in [
        "illuminance",
        "x",
        "y",
        "cct",
        "duv",
        "melanopic_edi",
        "clear_sky_index",
        "global_irradiance",
        "diffuse_irradiance",
        "direct_normal_irradiance",
        "diffuse_illuminance",
    ]:
        assert_same32(got[key], want, key)
    alone = skymodels.controller_step(lat, lon, as_times(micros), ghi=ghi, **keywords)
    differ = alone["diffuse_irradiance"] != got["diffuse_irradiance"]
    if decomposition == "erbs":
        assert not differ.any(), "Erbs takes no reading before"
    else:
        assert differ.sum() > len(micros) // 2, "DIRINT's stability index"
    # Not in time order: refused, naming the element.
    backwards = micros.copy()
    backwards[5] = backwards[3]
    with pytest.raises(ValueError, match=r"times\[5\]"):
        skymodels.controller_step(lat, lon, as_times(backwards), ghi=ghi, history=True)


def test_controller_step_site_parameters_equal_sky_core(native):
    """ozone_du and precipitable_water reach sky-core's Settings: the steps equal the native
    ones at a high-latitude site's twilight and day, without a measurement and with each kind,
    and they change what they should (the ozone the clear sky in twilight, the water the lux of
    a measured irradiance). Out of range, each is refused naming its keyword."""
    rng = np.random.default_rng(11)
    lat, lon, elevation = SITES[1]
    micros = micros_between(rng, FAST_YEARS, 240)
    readings = measurements(rng, len(micros))
    for ozone, water in [(230.0, 0.4), (460.0, 4.5)]:
        cases = [
            step_case(SITES[1], t, m, ozone_du=ozone, precipitable_water=water)
            for t, m in zip(micros, readings)
        ]
        want = native(cases)
        keywords = dict(
            aod=np.float32(0.2), elevation=elevation, ozone_du=ozone, precipitable_water=water
        )
        changed = {}
        for kind in [None, "lux", "ghi", "ghi+dhi"]:
            ok = [
                i
                for i, m in enumerate(readings)
                if ((m is None and kind is None) or (m is not None and "+".join(m) == kind))
                and "error" not in want[i]
            ]
            values = {}
            if kind is not None:
                for name in kind.split("+"):
                    values[name] = np.float32([readings[i][name] for i in ok])
            times = as_times(micros[ok])
            got = skymodels.controller_step(lat, lon, times, **values, **keywords)
            expected = [want[i] for i in ok]
            for key in ["illuminance", "x", "y", "cct", "duv", "melanopic_edi"]:
                assert_same32(got[key], expected, key)
            default = skymodels.controller_step(
                lat, lon, times, **values, aod=np.float32(0.2), elevation=elevation
            )
            a, b = got["illuminance"], default["illuminance"]
            changed[kind] = np.max(np.abs(a - b) / np.maximum(b, 1e-6))
        # Without a measurement the ozone moves the twilight's clear sky; with an irradiance
        # the water moves its lux (by per cents); a lux reading is the light itself (its colour
        # under cloud, which the clear sky moves, is scaled back to it: a rounding apart).
        assert min(changed[None], changed["ghi"], changed["ghi+dhi"]) > 1e-3, changed
        assert changed["lux"] < 1e-6, changed
    t = as_times(micros[:1])
    with pytest.raises(ValueError, match=r"ozone_du.*\[200, 500\]"):
        skymodels.controller_step(lat, lon, t, ozone_du=150.0)
    for water in [-0.1, 10.5, float("nan")]:
        with pytest.raises(ValueError, match=r"precipitable_water.*\[0, 10\] cm"):
            skymodels.controller_step(lat, lon, t, ghi=500.0, precipitable_water=water)


def view_directions(rng, n=240):
    """Random view directions of random lengths, above and below the horizon, and the
    awkward ones: the zenith, the horizon, the nadir, zero, huge, tiny, NaN and infinite."""
    d = rng.normal(size=(n, 3)) * rng.uniform(0.01, 100.0, size=(n, 1))
    special = [
        (0, 0, 1),
        (1, 0, 0),
        (0, 1, -1e-7),
        (0, 0, -1),
        (0, 0, 0),
        (0, 0, 2e32),
        (1e-30, 0, 1e-30),
        (float("nan"), 0, 1),
        (0, float("inf"), 1),
    ]
    return np.concatenate([d, special]).astype(np.float32)


def models(rng):
    """One parameter set per model and variant, as the reference binary and Sky take them."""
    z = lambda hi=math.pi / 2: float(np.float32(rng.uniform(0.0, hi)))  # noqa: E731
    a = lambda: float(np.float32(rng.uniform(-7.0, 7.0)))  # noqa: E731
    out = [
        {"model": "preetham", "sun_zenith": z(), "sun_azimuth": a(), "turbidity": 2.0},
        {"model": "preetham", "sun_zenith": 1.5, "sun_azimuth": a(), "turbidity": 5.75},
        {"model": "neural", "sun_zenith": z(), "sun_azimuth": a(), "turbidity": 3.5,
         "weights": "preetham"},
        {"model": "neural", "sun_zenith": z(), "sun_azimuth": a(), "turbidity": 8.0,
         "weights": "hosek"},
        {"model": "daylight", "sun_zenith": z(), "sun_azimuth": a(), "aod": 0.1},
        {"model": "daylight", "sun_zenith": float(np.float32(math.radians(95))),
         "sun_azimuth": a(), "aod": float(np.float32(0.37))},
        {"model": "daylight", "sun_zenith": float(np.float32(math.radians(107))),
         "sun_azimuth": a(), "aod": 0.8},
        {"model": "perez", "sun_zenith": z(), "sun_azimuth": a(), "clearness": 1.0,
         "brightness": 0.1, "diffuse_illuminance": 12_000.0},
        {"model": "perez", "sun_zenith": z(), "sun_azimuth": a(), "clearness": 6.5,
         "brightness": 0.3, "diffuse_illuminance": 15_000.0},
        {"model": "perez_from_irradiance", "sun_zenith": z(1.4), "sun_azimuth": a(),
         "ghi": 420.0, "dhi": 260.0, "day_of_year": 120},
        {"model": "aoas", "sun_zenith": z(), "sun_azimuth": a(), "preset": "coral"},
        {"model": "aoas", "sun_zenith": z(), "sun_azimuth": a(), "preset": "physical"},
        {"model": "sh", "sun_zenith": z(), "sun_azimuth": a(), "turbidity": 4.0, "bands": 3},
        {"model": "sh", "sun_zenith": z(), "sun_azimuth": a(), "turbidity": 2.5, "bands": 7},
    ]
    for sky_type in range(1, 16):
        scale = (
            {"zenith_luminance": 8000.0} if sky_type % 2 else {"diffuse_illuminance": 20_000.0}
        )
        colour = {"chromaticity": [0.31, 0.33]} if sky_type == 7 else {}
        out.append(
            {"model": "cie", "sky_type": sky_type, "sun_zenith": z(), "sun_azimuth": a(),
             **scale, **colour}
        )
    return out


def sky_of(case):
    """The wheel's Sky for a parameter set of `models`."""
    sun = (case["sun_zenith"], case["sun_azimuth"])
    m = case["model"]
    if m == "preetham":
        return skymodels.Sky.preetham(*sun, case["turbidity"])
    if m == "neural":
        return skymodels.Sky.neural(*sun, case["turbidity"], weights=case["weights"])
    if m == "daylight":
        return skymodels.Sky.daylight(*sun, aod=case["aod"])
    if m == "cie":
        keys = ["zenith_luminance", "diffuse_illuminance", "chromaticity"]
        return skymodels.Sky.cie(case["sky_type"], *sun, **{k: case[k] for k in keys if k in case})
    if m == "perez":
        return skymodels.Sky.perez(
            *sun, case["clearness"], case["brightness"], case["diffuse_illuminance"]
        )
    if m == "perez_from_irradiance":
        return skymodels.Sky.perez_from_irradiance(
            *sun, case["ghi"], case["dhi"], case["day_of_year"]
        )
    if m == "aoas":
        return skymodels.Sky.aoas(case["preset"], *sun)
    if m == "sh":
        return skymodels.Sky.sh(*sun, case["turbidity"], bands=case["bands"])
    raise AssertionError(m)


def quantities(case):
    return ["rgb"] if case["model"] in ("aoas", "sh") else ["rgb", "xyz", "luminance"]


def test_every_sky_model_equals_sky_core_at_view_directions(native):
    rng = np.random.default_rng(28)
    dirs = view_directions(rng)
    bits = dirs.view(np.uint32).tolist()
    cases, calls = [], []
    for params in models(rng):
        for q in quantities(params):
            cases.append({"kind": "sky", "quantity": q, "dir_bits": bits, **params})
            calls.append((params, q))
    results = native(cases)
    for (params, q), want in zip(calls, results):
        assert "error" not in want, (params, want)
        got = getattr(sky_of(params), q)(dirs)
        assert got.dtype == np.float32
        expected = np.array(want["values"], dtype=np.uint32)
        assert np.array_equal(got.view(np.uint32), expected), (params["model"], q)


def test_equirectangular_images_equal_sky_core(native):
    rng = np.random.default_rng(5)
    params = models(rng)
    chosen = [params[0], params[2], params[5], params[10], params[13], params[-1]]
    cases, calls = [], []
    for p in chosen:
        for extent, (w, h) in [("upper", (16, 8)), ("sphere", (12, 7))]:
            q = quantities(p)[-1]
            cases.append(
                {"kind": "render", "quantity": q, "extent": extent, "width": w, "height": h, **p}
            )
            calls.append((p, q, extent, w, h))
    for (p, q, extent, w, h), want in zip(calls, native(cases)):
        got = sky_of(p).render(w, h, extent=extent, quantity=q)
        expected = np.array(want["values"], dtype=np.uint32)
        assert got.shape == ((h, w, 3) if q != "luminance" else (h, w))
        assert np.array_equal(got.reshape(expected.shape).view(np.uint32), expected), p["model"]


def test_directions_equal_sky_core(native):
    rng = np.random.default_rng(3)
    zenith = f32_values(rng, -4.0, 4.0, 100)
    azimuth = f32_values(rng, -10.0, 10.0, 100)
    want = native(
        [{"kind": "direction", "zenith": t, "azimuth": p} for t, p in zip(zenith, azimuth)]
    )
    got = skymodels.direction(np.float32(zenith), np.float32(azimuth))
    assert np.array_equal(got.view(np.uint32), np.array(want, dtype=np.uint32))


def test_refusals_carry_sky_core_messages(native):
    """Parameters sky-core refuses raise ValueError with sky-core's own message."""
    base = {"latitude": 48.21, "longitude": 16.37, "elevation": 190.0, "algorithm": "fast",
            "time": [2026, 6, 21, 11, 0, 0.0]}
    refused = [
        ({"kind": "daylight", **base, "aod": 0.9},
         lambda: skymodels.daylight(48.21, 16.37, "2026-06-21T11:00", 0.9, elevation=190.0)),
        ({"kind": "daylight", **base, "latitude": 90.5, "aod": 0.1},
         lambda: skymodels.daylight(90.5, 16.37, "2026-06-21T11:00", elevation=190.0)),
        ({"kind": "daylight", **base, "elevation": -600.0, "aod": 0.1},
         lambda: skymodels.daylight(48.21, 16.37, "2026-06-21T11:00", elevation=-600.0)),
        ({"kind": "daylight", **base, "elevation": 6000.0, "aod": 0.1},
         lambda: skymodels.daylight(48.21, 16.37, "2026-06-21T11:00", 0.1, elevation=6000.0)),
        ({"kind": "daylight", **base, "ozone_du": 600.0, "aod": 0.1},
         lambda: skymodels.daylight(48.21, 16.37, "2026-06-21T11:00", 0.1, ozone_du=600.0)),
        ({"kind": "sun", **base, "time": [2111, 1, 1, 0, 0, 0.0]},
         lambda: skymodels.sun_position(48.21, 16.37, "2111-01-01", elevation=190.0)),
        ({"kind": "sky", "model": "preetham", "sun_zenith": 0.3, "sun_azimuth": 0.0,
          "turbidity": 6.5, "quantity": "rgb", "dir_bits": []},
         lambda: skymodels.Sky.preetham(0.3, 0.0, 6.5)),
        ({"kind": "sky", "model": "cie", "sky_type": 3, "sun_zenith": 1.7, "sun_azimuth": 0.0,
          "zenith_luminance": 1.0, "quantity": "rgb", "dir_bits": []},
         lambda: skymodels.Sky.cie(3, 1.7, 0.0, zenith_luminance=1.0)),
        ({"kind": "sky", "model": "perez", "sun_zenith": 0.3, "sun_azimuth": 0.0,
          "clearness": 0.5, "brightness": 0.1, "diffuse_illuminance": 1.0, "quantity": "rgb",
          "dir_bits": []},
         lambda: skymodels.Sky.perez(0.3, 0.0, 0.5, 0.1, 1.0)),
        ({"kind": "sky", "model": "daylight", "sun_zenith": 3.5, "sun_azimuth": 0.0,
          "aod": 0.1, "quantity": "rgb", "dir_bits": []},
         lambda: skymodels.Sky.daylight(3.5, 0.0)),
    ]
    results = native([case for case, _ in refused])
    for (case, call), want in zip(refused, results):
        assert "error" in want, case
        with pytest.raises(ValueError) as e:
            call()
        assert want["error"] in str(e.value), (str(e.value), want["error"])
