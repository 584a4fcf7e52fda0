#!/usr/bin/env python3
"""Measured multi-day GHI excerpts with pvlib's clear-sky verdicts, for the self-calibration
tests (tests/tests/self_calibration.rs). Run once, by hand, in a throw-away virtual environment
(the tests only read the files it writes; they never run Python):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1
    /tmp/venv/bin/pip download pvlib==0.16.1 --no-binary :all: --no-deps -d /tmp/pvlib-sdist
    tar xzf /tmp/pvlib-sdist/pvlib-0.16.1.tar.gz -C /tmp/pvlib-sdist
    /tmp/venv/bin/python tests/reference/gen_selfcal_fixtures.py \
        /tmp/pvlib-sdist/pvlib-0.16.1/tests/data/bsrn-pay0616.dat.gz \
        <pvanalytics checkout>/pvanalytics/data/irradiance_RMIS_NREL.csv

(the pvanalytics file from github.com/pvlib/pvanalytics, commit 06fd5969).

Writes tests/data/selfcal/<station>.csv: one row per reading with the sun above -10 degrees on
the days kept, columns
  utc            the reading's time (UTC; RMIS's right-aligned MST stamps converted)
  ghi            the measured GHI as delivered, W/m2 (missing readings left out)
  ineichen       pvlib's Ineichen clear sky with its Linke turbidity climatology, W/m2
  reno_hansen    pvlib.clearsky.detect_clearsky(ghi, ineichen, max_iterations=1): the
                 sample verdict of Reno & Hansen's criteria against that clear sky as given
                 (1-minute data: the 2016 defaults; 5-minute data: infer_limits=True, Jordan &
                 Hansen 2023's thresholds)
  clear          pvlib.clearsky.detect_clearsky(ghi, ineichen) with its default rescaling: the
                 clear minutes of the evaluation, independent of the estimator under test
Runs of readings are cut at missing readings (each run is detected on its own), as the
detector under test does.
"""

import pathlib
import sys

import numpy as np
import pandas as pd
import pvlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "tests" / "data" / "selfcal"


def verdicts(ghi, cs, infer):
    """Both verdicts, run by run of evenly spaced readings."""
    step = ghi.index.to_series().diff()
    interval = step.mode().iloc[0]
    run = (step != interval).cumsum()
    rh = pd.Series(False, index=ghi.index)
    clear = pd.Series(False, index=ghi.index)
    for _, idx in ghi.groupby(run).groups.items():
        g, c = ghi[idx], cs[idx]
        if len(g) < 60:
            continue
        g = g.asfreq(interval)
        c = c.asfreq(interval)
        rh[idx] = pvlib.clearsky.detect_clearsky(g, c, infer_limits=infer, max_iterations=1).values
        clear[idx] = pvlib.clearsky.detect_clearsky(g, c, infer_limits=infer).values
    return rh, clear


def write(name, ghi, loc, days, infer, header):
    ghi = ghi[np.isin(ghi.index.strftime("%Y-%m-%d"), days)].dropna()
    sp = loc.get_solarposition(ghi.index)
    cs = loc.get_clearsky(ghi.index, model="ineichen", solar_position=sp)["ghi"]
    keep = sp["apparent_elevation"] > -10  # the sun up, or less than 10 degrees down
    ghi, cs = ghi[keep], cs[keep]
    rh, clear = verdicts(ghi, cs, infer)
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / f"{name}.csv", "w") as f:
        f.write(header)
        f.write("utc,ghi,ineichen,reno_hansen,clear\n")
        for t, g, c, a, b in zip(ghi.index, ghi.values, cs.values, rh.values, clear.values):
            f.write(f"{t.strftime('%Y-%m-%dT%H:%M:%SZ')},{g:g},{c:.1f},{int(a)},{int(b)}\n")


def main():
    bsrn, rmis = sys.argv[1], sys.argv[2]
    d, meta = pvlib.iotools.read_bsrn(bsrn)
    loc = pvlib.location.Location(meta["latitude"], meta["longitude"], altitude=meta["altitude"])
    days = [f"2016-06-{d:02d}" for d in list(range(5, 11)) + list(range(21, 30))]
    write("bsrn-payerne-201606", d["ghi"], loc, days, False,
          "# BSRN Payerne (PAY), 46.815 N, 6.944 E, 491 m; 1-minute GHI, June 2016, days "
          "5-10 and 21-29; from pvlib 0.16.1's tests/data/bsrn-pay0616.dat.gz\n")
    r = pd.read_csv(rmis, index_col=0)
    r.index = pd.to_datetime(r.index, format="%m/%d/%Y %H:%M").tz_localize("Etc/GMT+7")
    r.index = r.index.tz_convert("UTC")
    loc = pvlib.location.Location(39.7407, -105.1686, altitude=1829)
    days = sorted(set(r.index.strftime("%Y-%m-%d")))
    write("nrel-rmis-golden-201902", r["irradiance_ghi__7981"], loc, days, True,
          "# NREL RMIS, Golden, Colorado, 39.7407 N, 105.1686 W, 1,829 m; 5-minute GHI, "
          "1-6 February 2019 (MST stamps, end of interval); from pvanalytics' "
          "pvanalytics/data/irradiance_RMIS_NREL.csv\n")


if __name__ == "__main__":
    main()
