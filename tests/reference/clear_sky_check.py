#!/usr/bin/env python3
"""What the measured clear days say about the site's clear sky (docs/daylight.md, "The site's
clear sky"): the figures behind the clear-sky index of `tests/tests/clear_sky_index.rs`.

Run by hand, in a throw-away virtual environment (the tests never run Python):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1
    /tmp/venv/bin/pip download --no-deps -d /tmp/pvold pvlib==0.10.5   # BSRN Payerne's month
    (cd /tmp/pvold && unzip -o pvlib-0.10.5-py3-none-any.whl 'pvlib/data/bsrn-pay0616.dat.gz')
    cargo build -p sky-train
    /tmp/venv/bin/python tests/reference/clear_sky_check.py target/debug/sky-train \
        [--lyngby dtu_2016_04.csv dtu_2017_06.csv ...]

For SURFRAD Alamosa, MIDC UAT Tucson and BSRN Payerne (the stations with a pyrheliometer and
a shaded pyranometer), on the clear minutes of `tests/fixtures/clear_minutes.csv`:

* the ground albedo the station measured (SURFRAD's upward over downward pyranometer);
* per clear day, the aerosol optical depth at 550 nm at which SPCTRL2 (Bird & Riordan 1986,
  pvlib's `spectrum.spectrl2`; Angstrom exponent 1.3, the site's month's water vapour, ozone
  and pressure from `sky-train site`) gives the measured direct normal irradiance (median over
  the day's clear minutes with the sun above 20 deg), against the climatology's; "below 0" where
  even an aerosol-free SPCTRL2 beam is below the measured one;
* by band of sun elevation, the clear-sky index of `sky-train schedule` (climatology alone),
  the luminous efficacy it converts the reading with (Perez 1990's global efficacy:
  `global_lux / ghi_wm2`) and SPCTRL2's own global efficacy for the site's clear atmosphere
  (683 lm/W times the CIE 1931 y-bar of sky-core's table, over SPCTRL2's broadband global);
* by band, the clear-sky index in the morning and in the afternoon, with the station's own
  closure (its global over its direct normal times cos Z plus its diffuse) in each.

With `--lyngby`, DTU's solar station at Lyngby, Denmark (55.7906 N, 12.5251 E, 50 m; monthly
1-minute files of github.com/AssessingSolar/dtu_solar_station, freely available but without a
licence, so not in this repository), held out from every choice: each month's GHI column
through `schedule --measurements` with and without the self-calibration (the calibrated figures
on the days after the first one it reports `calibrated`), on pvlib's clear minutes (sun above
5 deg), as `gen_station_fixtures.py` picks them; and the self-calibration's factor at the
month's end in each band of sun elevation, with the rows it flagged `sensor-suspect`.
"""

import io
import pathlib
import re
import subprocess
import sys
import warnings

import numpy as np
import pandas as pd
import pvlib
from pvlib import atmosphere, spectrum
from scipy.optimize import brentq

warnings.filterwarnings("ignore")
ROOT = pathlib.Path(__file__).resolve().parents[2]
STATIONS = ROOT / "tests" / "data" / "stations"
BSRN = pathlib.Path("/tmp/pvold/pvlib/data/bsrn-pay0616.dat.gz")
BANDS = [(5, 10), (10, 20), (20, 35), (35, 55), (55, 90)]

_rows = re.findall(r"\[([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\]",
                   (ROOT / "sky-core" / "src" / "cct" / "cmf.rs").read_text())
YBAR = np.array([float(r[1]) for r in _rows])
YBAR_NM = 360.0 + 5.0 * np.arange(len(YBAR))


def site(exe, lat, lon, elevation, month):
    out = subprocess.run([exe, "site", "--lat", str(lat), "--lon", str(lon), "--elevation", str(elevation)],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    return dict(zip(out[0].split(","), map(float, out[month].split(","))))


def spctrl2(zenith, day, s, tau550, albedo=0.2):
    """SPCTRL2's broadband direct normal, diffuse and global horizontal (W/m2) and global lux."""
    am = atmosphere.get_relative_airmass(zenith, "kasten1966")
    o = spectrum.spectrl2(apparent_zenith=zenith, aoi=zenith, surface_tilt=0.0, ground_albedo=albedo,
                          surface_pressure=s["pressure_hpa"] * 100.0, relative_airmass=am,
                          precipitable_water=s["water_vapour_cm"], ozone=s["ozone_du"] / 1000.0,
                          aerosol_turbidity_500nm=tau550 * (500.0 / 550.0) ** -1.3, dayofyear=day, alpha=1.3)
    nm = np.asarray(o["wavelength"], float)
    g = np.atleast_2d(np.asarray(o["poa_global"], float).T).T
    band = lambda k: np.trapezoid(np.atleast_2d(np.asarray(o[k], float).T).T, nm, axis=0)
    lux = 683.0 * np.trapezoid(g * np.interp(nm, YBAR_NM, YBAR, left=0, right=0)[:, None], nm, axis=0)
    return band("dni"), band("dhi"), band("poa_global"), lux


def surfrad():
    d, _ = pvlib.iotools.read_surfrad(STATIONS / "surfrad-slv16001-day.dat")
    return d, ("alamosa", 37.70, -105.92, 2317, "surfrad-slv16001-day.dat", "surfrad")


def midc_uat():
    raw = pd.read_csv(STATIONS / "midc-uat-raw-20181018-day.txt")
    hhmm = raw["MST"].astype(int)
    t = (pd.to_datetime(raw["Year"].astype(str) + raw["DOY"].astype(str).str.zfill(3), format="%Y%j")
         + pd.to_timedelta(hhmm // 100, unit="h") + pd.to_timedelta(hhmm % 100, unit="min") + pd.Timedelta(hours=7))
    col = lambda p: raw[[c for c in raw.columns if c.startswith(p)][0]].to_numpy()
    d = pd.DataFrame({"ghi": raw["Global Horiz (tracker) [W/m^2]"].to_numpy(), "dni": col("Direct"),
                      "dhi": col("Diffuse")}, index=t.dt.tz_localize("UTC"))
    return d, ("tucson", 32.22969, -110.95534, 786, "midc-uat-raw-20181018-day.txt", "midc")


def payerne():
    d, _ = pvlib.iotools.read_bsrn(BSRN)
    return d, ("payerne", 46.815, 6.944, 491, "bsrn-pay-201606-clear.csv", "csv")


def schedule(exe, lat, lon, elevation, path, fmt, extra=()):
    out = subprocess.run([exe, "schedule", "--lat", str(lat), "--lon", str(lon), "--elevation", str(elevation),
                          "--measurements", str(path), "--measurements-format", fmt, *extra],
                         capture_output=True, text=True, check=True).stdout
    return pd.read_csv(io.StringIO(out))


def station(exe, data):
    d, (name, lat, lon, elevation, file, fmt) = data
    clear = pd.read_csv(ROOT / "tests" / "fixtures" / "clear_minutes.csv")
    minutes = pd.to_datetime(clear[clear.station == name].utc, utc=True)
    d = d.loc[d.index.intersection(minutes)].copy()
    sp = pvlib.location.Location(lat, lon, altitude=elevation).get_solarposition(d.index)
    d["zenith"] = sp["apparent_zenith"]
    s = site(exe, lat, lon, elevation, int(d.index.month[0]))
    print(f"{name}: {len(d)} clear minutes; climatology aod_550 {s['aod_550']:.3f}, water {s['water_vapour_cm']:.2f} cm, "
          f"ozone {s['ozone_du']:.0f} DU, {s['pressure_hpa']:.0f} hPa")
    if "uw_solar" in d:
        high = d.zenith < 70
        print(f"  measured ground albedo (upward / downward, sun above 20 deg): median "
              f"{np.median(d.uw_solar[high] / d.ghi[high]):.3f}")
    for day, g in d.groupby(d.index.date):
        g = g[g.zenith < 70]
        if len(g) < 30:
            continue
        z, n = g.zenith.to_numpy(), g.index.dayofyear.to_numpy()
        excess = lambda t: np.median(spctrl2(z, n, s, t)[0] / g.dni.to_numpy()) - 1.0
        fit = f"{brentq(excess, 1e-4, 1.5):.3f}" if excess(1e-4) > 0 else "below 0"
        print(f"  {day}: {len(g)} clear minutes above 20 deg, aod_550 of the measured beam {fit}")
    out = schedule(exe, lat, lon, elevation, STATIONS / file, fmt, ["--no-self-calibration"])
    out = out[out.utc.isin(set(clear[clear.station == name].utc))]
    t = pd.to_datetime(out.utc, utc=True)
    _, _, ghi, lux = spctrl2(out.apparent_zenith_deg.to_numpy(), t.dt.day_of_year.to_numpy(), s, max(s["aod_550"], 0.05))
    k_sp = lux / ghi
    k_perez = out.global_lux.to_numpy() / out.ghi_wm2.to_numpy()
    e = out.sun_elevation_deg.to_numpy()
    for lo, hi in BANDS:
        m = (e >= lo) & (e < hi)
        if m.sum() < 10:
            continue
        print(f"  sun {lo:2d}-{hi:2d} deg: {m.sum():5d} minutes, clear-sky index {np.median(out.clear_sky_index.to_numpy()[m]):.3f}, "
              f"efficacy Perez {np.median(k_perez[m]):.1f} lm/W, SPCTRL2 {np.median(k_sp[m]):.1f} lm/W "
              f"(ratio {np.median(k_perez[m] / k_sp[m]):.3f})")
    # Morning against afternoon: the index, and the station's own closure (its global over its
    # direct normal times cos Z plus its diffuse), which an asymmetric instrument breaks.
    measured = d.reindex(t.to_numpy())
    closure = (measured.ghi / (measured.dni * np.cos(np.radians(measured.zenith)) + measured.dhi)).to_numpy()
    morning = out.sun_azimuth_deg.to_numpy() < 180.0
    k = out.clear_sky_index.to_numpy()
    for lo, hi in BANDS:
        m = (e >= lo) & (e < hi)
        am, pm = m & morning, m & ~morning
        if am.sum() < 10 or pm.sum() < 10:
            continue
        print(f"  sun {lo:2d}-{hi:2d} deg, morning / afternoon: {am.sum():4d} / {pm.sum():4d} minutes, clear-sky index "
              f"{np.median(k[am]):.3f} / {np.median(k[pm]):.3f}, closure GHI / (DNI cos Z + DHI) "
              f"{np.nanmedian(closure[am]):.3f} / {np.nanmedian(closure[pm]):.3f}")


def lyngby(exe, files):
    lat, lon, elevation = 55.7906, 12.5251, 50.0
    loc = pvlib.location.Location(lat, lon, altitude=elevation)
    for f in files:
        raw = pd.read_csv(f)
        ghi = pd.Series(raw["GHI"].to_numpy(), index=pd.to_datetime(raw["Time(utc)"], utc=True))
        ghi = ghi[~ghi.index.duplicated()].dropna()
        full = pd.date_range(ghi.index[0], ghi.index[-1], freq="1min")
        g = ghi.reindex(full)
        sp = loc.get_solarposition(full)
        cs = loc.get_clearsky(full, model="ineichen", solar_position=sp)
        keep = pvlib.clearsky.detect_clearsky(g.fillna(0.0), cs["ghi"], window_length=10) & (sp["apparent_elevation"] > 5.0) & g.notna()
        minutes = set(full[keep.to_numpy()].strftime("%Y-%m-%dT%H:%M:%SZ"))
        path = pathlib.Path("/tmp/lyngby-ghi.csv")
        with open(path, "w") as o:
            o.write("utc,ghi_wm2\n")
            for t, v in ghi.items():
                o.write(f"{t.strftime('%Y-%m-%dT%H:%M:%SZ')},{v:g}\n")
        for label, extra in [("climatology alone", ["--no-self-calibration"]), ("self-calibrated", [])]:
            full = schedule(exe, lat, lon, elevation, path, "csv", extra)
            out = full[full.utc.isin(minutes)]
            if label == "self-calibrated":
                first = out[out.calibration_status != "learning"].utc.str[:10].min()
                out = out[out.utc.str[:10] > first] if isinstance(first, str) else out.iloc[:0]
            k = out.clear_sky_index
            print(f"lyngby {pathlib.Path(f).name} {label:17s} {len(k):5d} clear minutes on {out.utc.str[:10].nunique():2d} days: "
                  f"median {k.median():.3f}, 5-95 % {k.quantile(0.05):.3f}-{k.quantile(0.95):.3f}")
        # What the self-calibration learned by the month's end: its factor at the last row
        # with the sun near each band's centre (15, 27.5, 45 deg; 57 deg and above), and the
        # rows it flagged.
        out = full  # the self-calibrated run's every row
        factors = []
        for lo, hi in [(14.5, 15.5), (27.0, 28.0), (44.5, 45.5), (57.0, 90.0)]:
            at = out[(out.sun_elevation_deg > lo) & (out.sun_elevation_deg < hi)]
            factors.append(f"{at.clear_sky_factor.iloc[-1]:.3f}" if len(at) else "-")
        print(f"lyngby {pathlib.Path(f).name} learned factor at 15 / 27.5 / 45 / 57+ deg: {' / '.join(factors)}; "
              f"last status {out.calibration_status.iloc[-1]}, rows flagged sensor-suspect "
              f"{(out.calibration_status == 'sensor-suspect').sum()}")


def main():
    exe = sys.argv[1]
    args = sys.argv[2:]
    if args and args[0] == "--lyngby":
        lyngby(exe, args[1:])
        return
    for data in (surfrad(), midc_uat(), payerne()):
        station(exe, data)


if __name__ == "__main__":
    main()
