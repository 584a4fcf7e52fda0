#!/usr/bin/env python3
"""Clear minutes of measured station days, picked independently of this project (issue 24 item 1).

Run once, by hand, in a throw-away virtual environment (the tests only read what it writes;
they never run Python):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1
    /tmp/venv/bin/pip download --no-deps -d /tmp/pvold pvlib==0.10.5   # BSRN Payerne's file
    (cd /tmp/pvold && unzip -o pvlib-0.10.5-py3-none-any.whl 'pvlib/data/bsrn-pay0616.dat.gz')
    /tmp/venv/bin/python tests/reference/gen_station_fixtures.py

The clear minutes are pvlib's `detect_clearsky` (Reno & Hansen 2016's five criteria over
10-minute windows), with pvlib's Ineichen-Perez clear sky and its Linke turbidity climatology as
the shape to compare with, and the sun more than 5 degrees above the horizon (pvlib's NREL SPA,
apparent elevation). Nothing of sky-core or sky-train is used.

Writes
  tests/fixtures/clear_minutes.csv  station,utc: every clear minute of every station day
  tests/data/stations/bsrn-pay-201606-clear.csv
      BSRN Payerne (June 2016): the GHI and DHI of the clear minutes of the month, in the
      project's CSV (utc,ghi_wm2,dhi_wm2), values as the file gives them (pvlib's read_bsrn
      for the station-to-archive format; no cleaning)
  tests/data/stations/midc-bms-ghi-20220120.csv
      NREL MIDC BMS Golden (2022-01-20): the GHI column of pvanalytics' copy, every minute of
      the day, in the project's CSV (utc,ghi_wm2), as given
The SURFRAD and MIDC UAT days are the raw files already in tests/data/stations.
"""

import io
import pathlib
import subprocess

import numpy as np
import pandas as pd
import pvlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
STATIONS = ROOT / "tests" / "data" / "stations"
FIXTURES = ROOT / "tests" / "fixtures"
BSRN = pathlib.Path("/tmp/pvold/pvlib/data/bsrn-pay0616.dat.gz")
PVANALYTICS = pathlib.Path("/work/.mirror/pvlib+pvanalytics/repo")


def surfrad():
    data, meta = pvlib.iotools.read_surfrad(STATIONS / "surfrad-slv16001-day.dat")
    # SURFRAD's header gives the longitude as degrees west (105.92 is 105.92 W).
    return data["ghi"].where(data["ghi_flag"] == 0), (meta["latitude"], -meta["longitude"], meta["elevation"])


def midc_uat():
    # MIDC raw file: Year, DOY, MST (HHMM); GHI "Global Horiz (tracker)".
    raw = pd.read_csv(STATIONS / "midc-uat-raw-20181018-day.txt")
    hhmm = raw["MST"].astype(int)
    t = (pd.to_datetime(raw["Year"].astype(str) + raw["DOY"].astype(str).str.zfill(3), format="%Y%j")
         + pd.to_timedelta(hhmm // 100, unit="h") + pd.to_timedelta(hhmm % 100, unit="min")
         + pd.Timedelta(hours=7))
    ghi = pd.Series(raw["Global Horiz (tracker) [W/m^2]"].to_numpy(), index=t.dt.tz_localize("UTC"))
    return ghi.where(ghi > -7999), (32.22969, -110.95534, 786.0)


def payerne():
    data, meta = pvlib.iotools.read_bsrn(BSRN)
    return data, (meta["latitude"], meta["longitude"], float(meta["altitude"]))


def bms():
    # pvanalytics' copy (a bare git snapshot of github.com/pvlib/pvanalytics).
    text = subprocess.run(["git", "-C", str(PVANALYTICS), "show", "HEAD:pvanalytics/data/midc_bms_ghi_20220120.csv"],
                          check=True, capture_output=True, text=True).stdout
    raw = pd.read_csv(io.StringIO(text), index_col=0)
    idx = pd.to_datetime(raw.index, utc=True)
    return pd.Series(raw.iloc[:, 0].to_numpy(), index=idx), (39.742, -105.18, 1828.8)


def clear_minutes(ghi, site):
    lat, lon, elev = site
    ghi = ghi.sort_index()
    ghi = ghi[~ghi.index.duplicated()]
    full = pd.date_range(ghi.index[0], ghi.index[-1], freq="1min")
    ghi = ghi.reindex(full)
    loc = pvlib.location.Location(lat, lon, altitude=elev)
    sp = loc.get_solarposition(full)
    cs = loc.get_clearsky(full, model="ineichen", solar_position=sp)
    clear = pvlib.clearsky.detect_clearsky(ghi.fillna(0.0), cs["ghi"], window_length=10)
    keep = clear & (sp["apparent_elevation"] > 5.0) & ghi.notna()
    return full[keep.to_numpy()]


def utc(t):
    return t.strftime("%Y-%m-%dT%H:%M:%SZ")


def main():
    rows = []
    ghi, site = surfrad()
    rows += [("alamosa", utc(t)) for t in clear_minutes(ghi, site)]
    ghi, site = midc_uat()
    rows += [("tucson", utc(t)) for t in clear_minutes(ghi, site)]

    data, site = payerne()
    minutes = clear_minutes(data["ghi"], site)
    rows += [("payerne", utc(t)) for t in minutes]
    sel = data.loc[minutes]
    with open(STATIONS / "bsrn-pay-201606-clear.csv", "w") as f:
        f.write("utc,ghi_wm2,dhi_wm2\n")
        for t, r in sel.iterrows():
            dhi = "" if np.isnan(r["dhi"]) else f"{r['dhi']:g}"
            f.write(f"{utc(t)},{r['ghi']:g},{dhi}\n")

    ghi, site = bms()
    rows += [("golden", utc(t)) for t in clear_minutes(ghi, site)]
    with open(STATIONS / "midc-bms-ghi-20220120.csv", "w") as f:
        f.write("utc,ghi_wm2\n")
        for t, v in ghi.items():
            f.write(f"{utc(t)},{v:g}\n")

    with open(FIXTURES / "clear_minutes.csv", "w") as f:
        f.write("station,utc\n")
        for s, t in rows:
            f.write(f"{s},{t}\n")
    for s in ["alamosa", "tucson", "payerne", "golden"]:
        print(s, sum(1 for r in rows if r[0] == s), "clear minutes")


if __name__ == "__main__":
    main()
