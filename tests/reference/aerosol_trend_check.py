#!/usr/bin/env python3
"""Can a pyranometer's own clear days tell their aerosol? The figures behind docs/weather.md's
"A lead for the clear days' aerosol" (issue 24): not a test, a check of an idea before it is
built.

Run by hand, in a throw-away virtual environment (the tests never run Python), with the same
set-up as `clear_sky_check.py` (its docstring: pvlib 0.16.1, and pvlib 0.10.5's BSRN Payerne
month in /tmp/pvold):

    cargo build -p sky-train
    /tmp/venv/bin/python tests/reference/aerosol_trend_check.py target/debug/sky-train \
        [--lyngby dtu_2016_06.csv ...]

On the clear minutes of `tests/fixtures/clear_minutes.csv` (sun zenith below 80 deg) of BSRN
Payerne, SURFRAD Alamosa and MIDC UAT Tucson, per clear day (at least 60 such minutes):

* the aerosol optical depth at 550 nm of the measured beam (SPCTRL2's direct normal irradiance
  equal to the measured one, median over the minutes with the sun above 20 deg; "below 0" where
  even an aerosol-free beam is below it), as `clear_sky_check.py` finds it;
* the aerosol from the global alone: the optical depth at which the logarithm of the measured
  global over SPCTRL2's has no trend with the relative air mass (Kasten 1966). An aerosol
  excess in the clear sky dims it most where the path is longest, so the measured-to-model
  ratio rises with the air mass; the level of the ratio (the sensor's calibration, the
  efficacy) does not enter, only its trend. SPCTRL2 (Bird & Riordan 1986, pvlib's
  `spectrum.spectrl2`) is in W/m², so Perez's luminous efficacy is not part of it;
* the split of the day's global against the measured diffuse (GHI above 50 W/m², bias / RMS
  relative to the mean measured diffuse): pvlib's DIRINDEX with SPCTRL2's clear sky at the
  day's own aerosol from the global, at the previous clear day's (what a controller would have
  learned), at the site's climatology's (`sky-train site`, at least 0.05), and pvlib's DIRINT.
"""

import pathlib
import sys
import warnings

import numpy as np
import pandas as pd
import pvlib
from scipy.optimize import brentq

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import clear_sky_check as check  # noqa: E402  (the stations' readers and SPCTRL2's set-up)

warnings.filterwarnings("ignore")


def split_score(g, pressure, ghi_clear=None, dni_clear=None):
    """Bias and RMS of a split's diffuse against the measured one, relative to its mean."""
    if ghi_clear is None:
        dni = pvlib.irradiance.dirint(g.ghi, g.zenith, g.index, pressure=pressure)
    else:
        dni = pvlib.irradiance.dirindex(g.ghi, pd.Series(ghi_clear, index=g.index),
                                        pd.Series(dni_clear, index=g.index), g.zenith, g.index,
                                        pressure=pressure)
    diffuse = (g.ghi - dni.fillna(0.0) * np.cos(np.radians(g.zenith))).clip(lower=0.0)
    sel = g.ghi > 50.0
    error = diffuse[sel] - g.dhi[sel]
    mean = g.dhi[sel].mean()
    return f"{100 * error.mean() / mean:+6.1f} % / {100 * np.sqrt((error ** 2).mean()) / mean:5.1f} %"


def station(exe, data, minutes=True):
    """Each clear day of `data` (the readings, and the station's name, latitude, longitude and
    elevation); with `minutes`, on the fixture's clear minutes of the station."""
    d, (name, lat, lon, elevation, _file, _fmt) = data
    if minutes:
        clear = pd.read_csv(check.ROOT / "tests" / "fixtures" / "clear_minutes.csv")
        d = d.loc[d.index.intersection(pd.to_datetime(clear[clear.station == name].utc, utc=True))]
    d = d.copy()
    sun = pvlib.location.Location(lat, lon, altitude=elevation).get_solarposition(d.index)
    d["apparent_zenith"], d["zenith"] = sun.apparent_zenith, sun.zenith
    d = d[d.apparent_zenith < 80.0]
    s = check.site(exe, lat, lon, elevation, int(d.index.month[0]))
    climatology = max(s["aod_550"], 0.05)
    pressure = pvlib.atmosphere.alt2pres(elevation)
    before = None
    for day, g in d.groupby(d.index.date):
        if len(g) < 60:
            continue
        z, n = g.apparent_zenith.to_numpy(), g.index.dayofyear.to_numpy()
        air_mass = pvlib.atmosphere.get_relative_airmass(z, "kasten1966")
        trend = lambda t: np.polyfit(air_mass, np.log(g.ghi.to_numpy() / check.spctrl2(z, n, s, t)[2]), 1)[0]
        try:
            own = brentq(trend, 1e-3, 1.0)
        except ValueError:
            own = 1e-3  # no trend even without aerosol: as clean as SPCTRL2 goes
        high = z < 70.0
        excess = lambda t: np.median(check.spctrl2(z[high], n[high], s, t)[0] / g.dni.to_numpy()[high]) - 1.0
        beam = f"{brentq(excess, 1e-4, 1.5):.3f}" if high.sum() > 20 and excess(1e-4) > 0 else "below 0"
        splits = []
        for label, tau in (("own", own), ("day before", before if before is not None else own),
                           ("climatology", climatology)):
            dni_c, _, ghi_c, _ = check.spctrl2(z, n, s, tau)
            splits.append(f"{label} {split_score(g, pressure, ghi_c, dni_c)}")
        print(f"{name} {day}: {len(g):4d} minutes; aod_550 of the beam {beam}, of the global's trend {own:.3f} "
              f"(climatology {climatology:.3f}); DIRINDEX at: {', '.join(splits)}; DIRINT {split_score(g, pressure)}")
        before = own


def lyngby(exe, files):
    """DTU Lyngby's months (`clear_sky_check.py --lyngby` says where they are): each day with
    at least 60 of pvlib's clear minutes (sun zenith below 80 deg) that pass a BSRN-style
    closure (GHI within 8 % of DHI + DNI cos Z), through `station`."""
    lat, lon, elevation = 55.7906, 12.5251, 50.0
    location = pvlib.location.Location(lat, lon, altitude=elevation)
    for f in files:
        raw = pd.read_csv(f)
        d = pd.DataFrame({"ghi": raw["GHI"].to_numpy(), "dni": raw["DNI"].to_numpy(), "dhi": raw["DHI"].to_numpy()},
                         index=pd.to_datetime(raw["Time(utc)"], utc=True))
        d = d[~d.index.duplicated()].dropna()
        full = pd.date_range(d.index[0], d.index[-1], freq="1min")
        g = d.reindex(full)
        sun = location.get_solarposition(full)
        cs = location.get_clearsky(full, model="ineichen", solar_position=sun)
        clear = pvlib.clearsky.detect_clearsky(g.ghi.fillna(0.0), cs["ghi"], window_length=10) & g.ghi.notna()
        closure = (g.ghi - (g.dhi + g.dni * np.cos(np.radians(sun.zenith)))).abs() <= 0.08 * g.ghi
        g = g[(clear & closure).to_numpy()]
        station(exe, (g, ("lyngby", lat, lon, elevation, None, None)), minutes=False)


def main():
    exe = sys.argv[1]
    if sys.argv[2:3] == ["--lyngby"]:
        lyngby(exe, sys.argv[3:])
        return
    for data in (check.payerne(), check.surfrad(), check.midc_uat()):
        station(exe, data)


if __name__ == "__main__":
    main()
