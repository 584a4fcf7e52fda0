#!/usr/bin/env python3
"""Measured daylight spectra under clear, broken and overcast skies, for the colour under cloud
(`tests/tests/overcast_measured.rs`), from P. Balakrishnan's Singapore data set.

Source: github.com/prijibalakrishnan/equatorialskies (commit c21b4fbabb2b0e6d72366b15c1520d1d5367ed44),
P. Balakrishnan, *Measuring and Modelling Equatorial Light*, PhD thesis, Singapore University
of Technology and Design, 2019. Run by hand with a clone of that repository (plain Python 3,
no packages):

    python3 tests/reference/gen_singapore_spectra.py /path/to/equatorialskies

Writes tests/data/daylight/singapore_spectra.csv: one row per daytime measurement whose sky the
author classified (CS clear, IS intermediate, OS overcast, MSOS/MSIS morning overcast or
intermediate; the unclassified twilight rows MS, ES, ESCS are left out), with the metadata as
published (local time UTC+8, sky type, the instrument's CCT and illuminance, the station's
global irradiance where there is one) and the global horizontal spectral irradiance averaged
over 10 nm bins [360, 370), ..., [770, 780) nm (the trapezoidal mean of the 1 nm values on
each bin's 11 points, W m^-2 nm^-1, 4 significant digits). The files of 01Nov16 11:55 and
17Nov16 11:53 are byte-identical (same spectrum, illuminance and irradiance): which date is
true is unknown, so both are left out.
"""

import csv
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "tests" / "data" / "daylight" / "singapore_spectra.csv"
KEPT = {"CS", "IS", "OS", "MSOS", "MSIS"}
AMBIGUOUS = {("01Nov16", "11:55"), ("17Nov16", "11:53")}
MONTHS = {m: i + 1 for i, m in enumerate(
    ["Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"])}


def bins(path):
    spd = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            spd[int(row["wv"])] = float(row["spd"])
    out = []
    for start in range(360, 780, 10):
        points = [spd[w] for w in range(start, start + 11)]
        out.append((0.5 * points[0] + sum(points[1:-1]) + 0.5 * points[-1]) / 10.0)
    return out


def main(repo):
    repo = pathlib.Path(repo)
    files = {p.name.split("-")[0] + "-" + p.name.split("-")[1]: p
             for p in (repo / "datasets").glob("*.csv")}
    rows = []
    with open(repo / "metadata.csv", newline="") as f:
        for m in csv.DictReader(f):
            if m["SkyType"] not in KEPT or (m["MonthYear"], m["Time"]) in AMBIGUOUS:
                continue
            d = m["MonthYear"]
            day, month, year = int(d[:2]), MONTHS[d[2:5]], 2000 + int(d[5:])
            hh, mm = (int(v) for v in m["Time"].split(":"))
            key = f"{d}-{hh}{mm:02d}"
            spectrum = bins(files[key])
            rows.append([f"{year:04d}-{month:02d}-{day:02d}", f"{hh:02d}:{mm:02d}", m["SkyType"],
                         m["CCT"], m["GlobalIllum"], m["GlobalIrrad"]]
                        + [f"{v:.4g}" for v in spectrum])
    rows.sort()
    header = ["date", "local_time", "sky_type", "instrument_cct_k", "instrument_lux", "ghi_wm2"] + [
        f"e{w}" for w in range(360, 780, 10)]
    OUT.parent.mkdir(parents=True, exist_ok=True)
    tmp = OUT.with_suffix(".tmp")
    with open(tmp, "w", newline="") as f:
        f.write("# Global horizontal spectral irradiance, Singapore (P. Balakrishnan 2019, "
                "github.com/prijibalakrishnan/equatorialskies); README.md beside this file.\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    tmp.replace(OUT)
    print(f"{len(rows)} rows -> {OUT}")


if __name__ == "__main__":
    main(sys.argv[1])
