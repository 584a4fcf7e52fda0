#!/usr/bin/env python3
"""The split of measured GHI against measured DHI on many days: docs/weather.md's check of the
separation models on days no model was fitted to (issue 24 item 5).

The station is DTU's solar station at Lyngby, Denmark (55.7906 N, 12.5251 E, 50 m; GHI,
shadow-ball DHI and DNI, 1-minute, UTC), whose monthly files are freely available from
https://weatherdata.construct.dtu.dk/ and github.com/AssessingSolar/dtu_solar_station
(`data/dtu_YYYY_MM.csv`); they carry no licence, so they are not in this repository. Give
their paths:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1
    cargo build -p sky-train
    /tmp/venv/bin/python tests/reference/separation_check.py [--every N] target/debug/sky-train \
        dtu_2015_06.csv dtu_2016_03.csv ...

With `--every N` only every N-th minute is kept, as a controller stepping every N minutes sees
the readings (DIRINT's stability index is then between readings N minutes apart).

Other stations: `--site LAT,LON,ELEVATION` (degrees north, east, metres) and files in the
same CSV form (`Time(utc),GHI,DNI,DHI`) or BSRN station-to-archive files (`*.dat.gz`, read by
pvlib's `read_bsrn`), e.g. BSRN Payerne June 2016 (46.815 N, 6.944 E, 491 m), the
`pvlib/data/bsrn-pay0616.dat.gz` of the pvlib 0.10.5 wheel:

    /tmp/venv/bin/pip download pvlib==0.10.5 --no-deps -d /tmp/pvlib-0.10.5
    unzip -j /tmp/pvlib-0.10.5/pvlib-0.10.5-py3-none-any.whl pvlib/data/bsrn-pay0616.dat.gz
    /tmp/venv/bin/python tests/reference/separation_check.py --site 46.815,6.944,491 \
        target/debug/sky-train bsrn-pay0616.dat.gz

For each month, the GHI column goes to `sky-train schedule --measurements` (the project's
split, each row against the row before) once per `--decomposition`; the output's `dhi_wm2` is
compared with the measured DHI on each day's daylight minutes with GHI above 50 W/m² that pass
a BSRN-style closure check (GHI within 8 % of DHI + DNI cos Z below 75 deg zenith, 15 % above).
The CLI's clear sky (DIRINDEX, Engerer2) is the site's month's (only --lat, --lon and
--elevation are given). The same models are run again here with pvlib's Ineichen-Perez clear
sky (Linke-turbidity climatology): pvlib's `irradiance.dirindex` with the stability index from
the minute before (as the controller does), and Engerer2 written out from Engerer 2015 eq. 33
and Bright & Engerer 2019's coefficients; and DIRINT as published (its bins, pvlib's
`irradiance.dirint` terms with the stability index from the minute before, the beam cut to the
global): "dirint, binned (pvlib)".

A day is clear when its global over the Ineichen clear sky's (sun above 5 deg) is above 0.85
and pvlib's `detect_clearsky` finds 85 % of its minutes clear; overcast below 0.45; else
broken. Prints one line per day and a summary per sky: the share of days within the issue's
bounds (clear: |bias| <= 15 % and RMS <= 35 %; overcast: RMS <= 25 %; broken: RMS <= 35 %,
for reference only) and the median bias / RMS, both relative to the day's mean measured DHI.
"""

import subprocess
import sys
import tempfile
import warnings

import numpy as np
import pandas as pd
import pvlib

warnings.filterwarnings("ignore")

LAT, LON, ELEV = 55.7906, 12.5251, 50.0
MODELS = ["dirint", "dirindex", "erbs", "engerer2", "engerer2-global"]
ENGERER2 = {
    "engerer2": [4.2336e-2, -3.7912, 7.5479, -1.0036e-2, 3.1480e-3, -5.3146, 1.7073],
    "engerer2-global": [1.0562e-1, -4.1332, 8.2578, 1.0087e-2, 8.8801e-4, -4.9302,
                        4.4378e-1],
}


def cli_split(binary, times, ghi, model):
    with tempfile.NamedTemporaryFile("w", suffix=".csv") as f:
        f.write("utc,ghi_wm2\n")
        for t, g in zip(times, ghi):
            f.write(f"{t.strftime('%Y-%m-%dT%H:%M:%SZ')},{g}\n")
        f.flush()
        out = subprocess.run(
            [binary, "schedule", "--lat", str(LAT), "--lon", str(LON), "--elevation",
             str(ELEV), "--measurements", f.name, "--decomposition", model],
            check=True, capture_output=True, text=True).stdout
    lines = out.splitlines()
    at = lines[0].split(",").index("dhi_wm2")
    return np.array([float(l.split(",")[at]) for l in lines[1:]])


def engerer2(ghi, ghi_cs, zen, times, k):
    i0 = pvlib.irradiance.get_extra_radiation(times, solar_constant=1367.0, method="spencer")
    cz = np.maximum(np.cos(np.radians(zen)), 0.065)
    kt = np.minimum(ghi / (i0 * cz), 1)
    ktc = ghi_cs / (i0 * cz)
    kde = np.where(ghi > ghi_cs, 1 - ghi_cs / np.maximum(ghi, 1e-9), 0)
    eot = pvlib.solarposition.equation_of_time_spencer71(times.dayofyear)
    ast = (times.hour + times.minute / 60 + LON / 15 + eot / 60) % 24
    c, b0, b1, b2, b3, b4, b5 = k
    kd = np.clip(c + (1 - c) / (1 + np.exp(b0 + b1 * kt + b2 * ast + b3 * zen
                                           + b4 * (ktc - kt))) + b5 * kde, 0, 1)
    return np.where(zen > 87, ghi, kd * ghi)


def dirint_prev(g, zen, times, pressure):
    """pvlib's DIRINT (binned, as published) with delta-kt' from the minute before only (Perez
    eq. 3), the dew point unknown."""
    disc = pvlib.irradiance.disc(g, zen, times, pressure=pressure)
    ktp = pvlib.irradiance.clearness_index_zenith_independent(
        disc["kt"], disc["airmass"], max_clearness_index=1)
    delta = (ktp - ktp.shift(1)).abs()
    gap = pd.Series(times).diff().dt.total_seconds().values > 90 * 60
    gap[0] = True
    delta[gap] = np.nan
    delta = delta.fillna(-1)
    coeffs = pvlib.irradiance._dirint_coeffs(
        times, ktp, zen, pd.Series(-1, index=times), delta)
    return disc["dni"] * coeffs


def cut(dni, ghi, zen):
    """The diffuse of a direct normal irradiance, the beam cut to the global, none above 87 deg."""
    dni = np.nan_to_num(np.maximum(np.asarray(dni, dtype=float), 0))
    beam = np.minimum(dni * np.cos(np.radians(zen)), ghi)
    return np.where(zen > 87, ghi, ghi - beam)


def dirint_binned(ghi, zen, times, pressure):
    return cut(dirint_prev(pd.Series(ghi, index=times), zen, times, pressure), ghi, zen)


def dirindex_causal(ghi, cs, zen, times, pressure):
    """pvlib's DIRINDEX with delta-kt' from the minute before only (Perez eq. 3)."""
    g = pd.Series(ghi, index=times)
    dni = (cs["dni"] * dirint_prev(g, zen, times, pressure)
           / dirint_prev(cs["ghi"], zen, times, pressure))
    return cut(dni.values, ghi, zen)


def read(path):
    """A month of 1-minute GHI, DNI, DHI: the DTU CSV, or a BSRN station-to-archive file."""
    if path.endswith(".dat.gz") or path.endswith(".dat"):
        data, _ = pvlib.iotools.read_bsrn(path)
        raw = data[["ghi", "dni", "dhi"]].rename(columns=str.upper)
        raw.index = raw.index.tz_localize(None)
        return raw
    return pd.read_csv(path, index_col=0, parse_dates=True)


def month(binary, path, every):
    raw = read(path)
    raw = raw.dropna(subset=["GHI", "DHI", "DNI"])
    raw = raw[raw.GHI > -20]
    location = pvlib.location.Location(LAT, LON, altitude=ELEV)
    # Each day's sky from every minute.
    times = pd.DatetimeIndex(raw.index).tz_localize("UTC")
    sp = pvlib.solarposition.get_solarposition(times, LAT, LON, ELEV)
    cs = location.get_clearsky(times, model="ineichen", solar_position=sp)
    zen, ghi = sp.zenith.values, raw.GHI.values
    skies = {}
    for d in sorted(set(times.date)):
        sel = times.date == d
        day = sel & (zen < 85)
        if day.sum() < 60:
            continue
        csi = ghi[day].sum() / cs.ghi.values[day].sum()
        try:
            clear = pvlib.clearsky.detect_clearsky(
                pd.Series(ghi[sel], index=times[sel]),
                pd.Series(cs.ghi.values[sel], index=times[sel]), infer_limits=False)
            cf = clear.values[zen[sel] < 85].mean()
        except NotImplementedError:  # a gap in the day's minutes
            cf = np.nan
        skies[d] = "clear" if (csi > 0.85 and cf > 0.85) else (
            "overcast" if csi < 0.45 else "broken")
    # The readings the splits see: every `every`-th minute.
    raw = raw[raw.index.minute % every == 0]
    times = pd.DatetimeIndex(raw.index).tz_localize("UTC")
    ghi, dhi, dni = raw.GHI.values, raw.DHI.values, raw.DNI.values
    sp = pvlib.solarposition.get_solarposition(times, LAT, LON, ELEV)
    zen = sp.zenith.values
    cs = location.get_clearsky(times, model="ineichen", solar_position=sp)
    pressure = pvlib.atmosphere.alt2pres(ELEV)
    split = {m: cli_split(binary, times, ghi, m) for m in MODELS}
    g0 = np.maximum(ghi, 0)
    split["dirint, binned (pvlib)"] = dirint_binned(g0, zen, times, pressure)
    split["dirindex, Ineichen"] = dirindex_causal(g0, cs, zen, times, pressure)
    for m, k in ENGERER2.items():
        split[f"{m}, Ineichen"] = engerer2(g0, cs.ghi.values, zen, times, k)
    ratio = ghi / np.maximum(dhi + dni * np.cos(np.radians(zen)), 1e-3)
    qc = np.abs(ratio - 1) <= np.where(zen < 75, 0.08, 0.15)
    rows = []
    for d, sky in skies.items():
        m = (times.date == d) & (zen < 90) & (ghi > 50) & qc
        if m.sum() < 40 // every:
            continue
        mean = dhi[m].mean()
        row = dict(day=str(d), sky=sky, minutes=int(m.sum()), kd=dhi[m].mean() / ghi[m].mean())
        for name, v in split.items():
            e = v[m] - dhi[m]
            row[name] = (100 * e.mean() / mean, 100 * np.sqrt((e ** 2).mean()) / mean)
        rows.append(row)
    return rows


def main():
    global LAT, LON, ELEV
    args = sys.argv[1:]
    every = 1
    while args[0].startswith("--"):
        if args[0] == "--every":
            every, args = int(args[1]), args[2:]
        elif args[0] == "--site":
            LAT, LON, ELEV = (float(v) for v in args[1].split(","))
            args = args[2:]
        else:
            sys.exit(f"unknown option {args[0]}")
    binary, paths = args[0], args[1:]
    rows = []
    for p in paths:
        rows += month(binary, p, every)
    res = pd.DataFrame(rows)
    names = [c for c in res.columns if isinstance(res[c].iloc[0], tuple)]
    for _, r in res.iterrows():
        print(f"{r['day']} {r['sky']:8} {r['minutes']:4} kd {r['kd']:.2f} " +
              " ".join(f"{n} {r[n][0]:+4.0f}/{r[n][1]:3.0f}" for n in names))
    print()
    for sky in ["clear", "overcast", "broken"]:
        sub = res[res.sky == sky]
        if not len(sub):
            continue
        print(f"{sky}: {len(sub)} days")
        for n in names:
            b = np.array([v[0] for v in sub[n]])
            rms = np.array([v[1] for v in sub[n]])
            ok = ((np.abs(b) <= 15) & (rms <= 35)) if sky == "clear" else (
                rms <= 25 if sky == "overcast" else rms <= 35)
            print(f"  {n:24} within the bounds {100 * ok.mean():3.0f} %   "
                  f"median bias {np.median(b):+4.0f} %   median RMS {np.median(rms):3.0f} %")


if __name__ == "__main__":
    main()
