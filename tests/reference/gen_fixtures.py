#!/usr/bin/env python3
"""Reference fixtures for the lighting-controller outputs, from published implementations.

Run once, by hand, in a throw-away virtual environment (the tests only read the files it
writes; they never run Python):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1 colour-science==0.4.7
    /tmp/venv/bin/python tests/reference/gen_fixtures.py

Pinned versions: pvlib 0.16.1 (its NREL SPA, Reda & Andreas 2004, numpy implementation),
colour-science 0.4.7 (Ohno 2013 CCT/Duv; the CIE 1931 2-degree colour-matching functions),
numpy 2.4.6, pandas 3.1.1.

Writes
  tests/fixtures/spa.csv   sun positions by pvlib's SPA (geometric and refracted zenith,
                           azimuth from north clockwise) at sites from polar to tropical,
                           both hemispheres, dates 1950-2100
  tests/fixtures/spa_schedule.csv  the same for whole days at fixed steps, the rows of
                           three `sky-train schedule` runs
  tests/fixtures/cct.csv   CCT and Duv by colour-science's Ohno 2013 for chromaticities along
                           and off the Planckian locus, 1,700-25,000 K
  sky-core/src/cct/cmf.rs  the CIE 1931 2-degree colour-matching functions, 360-830 nm in
                           5 nm steps (the standard's tabulated data, CIE 018:2019 / ISO 11664-1)
"""

import csv
import pathlib

import numpy as np
import pandas as pd
import pvlib
import colour
from colour.temperature import CCT_to_uv_Ohno2013, uv_to_CCT_Ohno2013

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "tests" / "fixtures"

# (name, latitude, longitude, elevation m): polar, tropical, mid-latitude, both hemispheres.
SITES = [
    ("longyearbyen", 78.2232, 15.6267, 10.0),
    ("mcmurdo", -77.8419, 166.6863, 24.0),
    ("south-pole", -89.99, 0.0, 2835.0),
    ("tromso", 69.6492, 18.9553, 0.0),
    ("singapore", 1.3521, 103.8198, 15.0),
    ("quito", -0.1807, -78.4678, 2850.0),
    ("honolulu", 21.3069, -157.8583, 5.0),
    ("jakarta", -6.2088, 106.8456, 8.0),
    ("vienna", 48.21, 16.37, 190.0),
    ("sydney", -33.8688, 151.2093, 58.0),
    ("new-york", 40.7128, -74.006, 10.0),
    ("buenos-aires", -34.6037, -58.3816, 25.0),
    ("date-line", -15.0, 179.9, 0.0),
    ("greenwich", 51.4779, -0.0015, 45.0),
]


def spa_fixture(rng):
    rows = []
    for name, lat, lon, elev in SITES:
        # 30 instants per site, uniform over 1950-2100, to the second.
        seconds = rng.integers(
            int(pd.Timestamp("1950-01-01", tz="UTC").timestamp()),
            int(pd.Timestamp("2100-12-31 23:59:59", tz="UTC").timestamp()),
            size=30,
        )
        times = pd.DatetimeIndex(pd.to_datetime(np.sort(seconds), unit="s", utc=True))
        delta_t = pvlib.spa.calculate_deltat(times.year, times.month)
        pos = pvlib.solarposition.spa_python(
            times, lat, lon, altitude=elev, pressure=101325.0, temperature=15.0,
            delta_t=np.asarray(delta_t), how="numpy",
        )
        for t, (_, p) in zip(times, pos.iterrows()):
            rows.append([
                name, t.strftime("%Y-%m-%dT%H:%M:%SZ"), lat, lon, elev,
                f"{p['zenith']:.6f}", f"{p['apparent_zenith']:.6f}", f"{p['azimuth']:.6f}",
            ])
    with open(FIXTURES / "spa.csv", "w", newline="") as f:
        f.write("# pvlib 0.16.1 spa_python (how=numpy), pressure 1013.25 hPa, 15 C, "
                "delta T from pvlib.spa.calculate_deltat; written by tests/reference/gen_fixtures.py\n")
        w = csv.writer(f)
        w.writerow(["site", "utc", "latitude_deg", "longitude_deg", "elevation_m",
                    "zenith_deg", "apparent_zenith_deg", "azimuth_deg"])
        w.writerows(rows)


# (latitude, longitude, elevation m, UTC date, step minutes) of `sky-train schedule` runs.
SCHEDULES = [
    (78.2232, 15.6267, 0.0, "2026-06-21", 60),   # polar day
    (-33.8688, 151.2093, 0.0, "2031-12-01", 30),
    (1.3521, 103.8198, 0.0, "1987-03-03", 45),
]


def schedule_fixture():
    rows = []
    for lat, lon, elev, date, step in SCHEDULES:
        times = pd.date_range(f"{date} 00:00", periods=24 * 60 // step, freq=f"{step}min", tz="UTC")
        delta_t = pvlib.spa.calculate_deltat(times.year, times.month)
        pos = pvlib.solarposition.spa_python(
            times, lat, lon, altitude=elev, pressure=101325.0, temperature=15.0,
            delta_t=np.asarray(delta_t), how="numpy",
        )
        for t, (_, p) in zip(times, pos.iterrows()):
            rows.append([lat, lon, date, step, t.strftime("%Y-%m-%dT%H:%M:%SZ"),
                         f"{p['zenith']:.6f}", f"{p['azimuth']:.6f}"])
    with open(FIXTURES / "spa_schedule.csv", "w", newline="") as f:
        f.write("# pvlib 0.16.1 spa_python for `sky-train schedule` runs; "
                "written by tests/reference/gen_fixtures.py\n")
        w = csv.writer(f)
        w.writerow(["latitude_deg", "longitude_deg", "date", "step_min", "utc",
                    "zenith_deg", "azimuth_deg"])
        w.writerows(rows)


def cct_fixture():
    rows = []
    temperatures = np.geomspace(1700.0, 25000.0, 41)
    for duv in [-0.03, -0.02, -0.01, -0.005, -0.002, 0.0, 0.002, 0.005, 0.01, 0.02, 0.03]:
        for t in temperatures:
            uv = CCT_to_uv_Ohno2013(np.array([t, duv]))
            xy = colour.UCS_uv_to_xy(uv)
            # The reference is colour-science's answer for this chromaticity (not the
            # temperature it was generated from).
            cct, d = uv_to_CCT_Ohno2013(colour.xy_to_UCS_uv(xy))
            rows.append([f"{xy[0]:.10f}", f"{xy[1]:.10f}", f"{cct:.4f}", f"{d:.8f}"])
    with open(FIXTURES / "cct.csv", "w", newline="") as f:
        f.write("# colour-science 0.4.7 uv_to_CCT_Ohno2013 (default CIE 1931 2-degree CMFs); "
                "written by tests/reference/gen_fixtures.py\n")
        w = csv.writer(f)
        w.writerow(["x", "y", "cct_k", "duv"])
        w.writerows(rows)


def rust_float(v):
    # The standard tabulates at most 7 significant digits.
    text = f"{float(v):.7g}"
    return text if ("." in text or "e" in text) else text + ".0"


def cmf_source():
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    wl = np.arange(360, 831, 5)
    values = cmfs[wl]
    lines = [
        "//! The CIE 1931 2° standard observer's colour-matching functions x̄, ȳ, z̄, 360-830 nm in",
        "//! 5 nm steps: the standard's tabulated values (CIE 018:2019, ISO/CIE 11664-1).",
        "//!",
        "//! Generated by tests/reference/gen_fixtures.py from colour-science 0.4.7's copy of the",
        "//! table; do not edit.",
        "",
        "/// The first wavelength of [`CMF`], in nm.",
        "pub const FIRST_NM: f64 = 360.0;",
        "/// The step between rows of [`CMF`], in nm.",
        "pub const STEP_NM: f64 = 5.0;",
        "",
        "/// x̄, ȳ, z̄ per wavelength.",
        f"pub const CMF: [[f64; 3]; {len(wl)}] = [",
    ]
    for row in values:
        lines.append("    [" + ", ".join(rust_float(v) for v in row) + "],")
    lines.append("];")
    (ROOT / "sky-core" / "src" / "cct" / "cmf.rs").write_text("\n".join(lines) + "\n")


def main():
    FIXTURES.mkdir(exist_ok=True)
    (ROOT / "sky-core" / "src" / "cct").mkdir(exist_ok=True)
    spa_fixture(np.random.default_rng(8))
    schedule_fixture()
    cct_fixture()
    cmf_source()


if __name__ == "__main__":
    main()
