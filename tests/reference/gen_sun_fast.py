#!/usr/bin/env python3
"""Reference sun positions for the controller's fast sun (`sky_core::solar::grena`), from
pvlib's NREL SPA: `tests/fixtures/sun_fast_spa.csv`, read by `tests/tests/sun_fast.rs`.

Run once, by hand, in a throw-away virtual environment (the tests only read the file):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1
    /tmp/venv/bin/python tests/reference/gen_sun_fast.py

pvlib 0.16.1's spa_python (Reda & Andreas 2004, its numpy implementation), pressure
1013.25 hPa, 15 C, delta T from pvlib.spa.calculate_deltat (the Espenak & Meeus polynomials).

Rows: every latitude from -80 to 80 degrees in steps of 5 (33 sites, each at its own longitude
spread over -180 to 180 and an elevation 0-3000 m), 60 instants each, uniform over
2000-01-01 to 2100-12-31 to the millisecond (a fixed seed), and the two ends of that range at
every site.
"""

import csv
import pathlib

import numpy as np
import pandas as pd
import pvlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "tests" / "fixtures" / "sun_fast_spa.csv"


def main():
    rng = np.random.default_rng(20122027)
    start = pd.Timestamp("2000-01-01 00:00:00", tz="UTC")
    end = pd.Timestamp("2100-12-31 23:59:59.999", tz="UTC")
    span_ms = int((end - start) / pd.Timedelta(milliseconds=1))
    rows = []
    latitudes = np.arange(-80.0, 80.0 + 1e-9, 5.0)
    for k, lat in enumerate(latitudes):
        lon = round(-180.0 + (k * 137.508) % 360.0, 4)  # golden-angle spread of longitudes
        elev = float((k * 373) % 3000)
        ms = np.sort(rng.integers(0, span_ms + 1, size=60))
        times = pd.DatetimeIndex([start + pd.Timedelta(milliseconds=int(m)) for m in ms]
                                 + [start, end])
        delta_t = pvlib.spa.calculate_deltat(times.year, times.month)
        pos = pvlib.solarposition.spa_python(
            times, lat, lon, altitude=elev, pressure=101325.0, temperature=15.0,
            delta_t=np.asarray(delta_t), how="numpy",
        )
        for t, (_, p) in zip(times, pos.iterrows()):
            rows.append([
                t.strftime("%Y-%m-%dT%H:%M:%S.") + f"{t.microsecond // 1000:03d}Z",
                f"{lat:.1f}", f"{lon:.4f}", f"{elev:.1f}",
                f"{p['zenith']:.7f}", f"{p['apparent_zenith']:.7f}", f"{p['azimuth']:.7f}",
            ])
    with open(OUT, "w", newline="") as f:
        f.write("# pvlib 0.16.1 spa_python (how=numpy), pressure 1013.25 hPa, 15 C, "
                "delta T from pvlib.spa.calculate_deltat; written by tests/reference/gen_sun_fast.py\n")
        w = csv.writer(f)
        w.writerow(["utc", "latitude_deg", "longitude_deg", "elevation_m",
                    "zenith_deg", "apparent_zenith_deg", "azimuth_deg"])
        w.writerows(rows)
    print(f"{OUT}: {len(rows)} rows")


if __name__ == "__main__":
    main()
