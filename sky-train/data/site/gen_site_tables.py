#!/usr/bin/env python3
"""The site climatology's compact tables (sky-train/src/site.rs), from pvlib-python's data files.

Run by hand, in a throw-away virtual environment (sky-train only reads the files it writes):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pvlib==0.16.1 h5py
    /tmp/venv/bin/python sky-train/data/site/gen_site_tables.py

Reads pvlib 0.16.1's `pvlib/data/LinkeTurbidities.h5` (2160 x 4320 x 12 uint8, 20 x the monthly
Linke turbidity TL(AM2) on a 5' grid, rows from 90 N, columns from 180 W) and
`pvlib/data/Altitude.h5` (2160 x 4320 uint8, 28 m steps from -450 m, 255 no data), and writes
beside this script

  linke_turbidity_1deg.bin  180 x 360 x 12 bytes: 20 x the mean TL of each 1 deg cell (12 x 12
                            source cells), rows from 89.5 N down, columns from 179.5 W east,
                            months January..December innermost;
  elevation_1deg.bin        180 x 360 little-endian int16: the cell's mean elevation in metres
                            (no-data cells count as 0 m; negative means below sea level);

and prints the downsampling error (the 1 deg table interpolated bilinearly, as sky-train reads
it, against the 5' source at random points, area-weighted, latitudes -60 to 75).
"""

import pathlib

import h5py
import numpy as np
import pvlib

HERE = pathlib.Path(__file__).resolve().parent
DATA = pathlib.Path(pvlib.__file__).resolve().parent / "data"
K = 12  # 5' cells per 1 deg


def block_mean(a, k):
    n0, n1 = a.shape[0] // k, a.shape[1] // k
    return a.reshape(n0, k, n1, k, *a.shape[2:]).mean(axis=(1, 3))


def bilinear(g, lat, lon, step):
    """g's cell centres at 90 - (i + 0.5) step, -180 + (j + 0.5) step; longitude wraps."""
    fi = (90.0 - lat) / step - 0.5
    fj = (lon + 180.0) / step - 0.5
    i0 = np.clip(np.floor(fi).astype(int), 0, g.shape[0] - 2)
    wi = np.clip(fi - i0, 0.0, 1.0)
    j0 = np.floor(fj).astype(int)
    wj = fj - j0
    a, b = j0 % g.shape[1], (j0 + 1) % g.shape[1]
    return (g[i0, a] * (1 - wi) * (1 - wj) + g[i0 + 1, a] * wi * (1 - wj)
            + g[i0, b] * (1 - wi) * wj + g[i0 + 1, b] * wi * wj)


def main():
    with h5py.File(DATA / "LinkeTurbidities.h5") as h:
        tl20 = h["LinkeTurbidity"][:].astype(np.float64)
    with h5py.File(DATA / "Altitude.h5") as h:
        alt = h["Altitude"][:].astype(np.float64)
    alt = np.where(alt == 255, 16.0, alt) * 28.0 - 450.0  # no data: about 0 m

    tl_1 = np.clip(np.rint(block_mean(tl20, K)), 0, 255).astype(np.uint8)
    (HERE / "linke_turbidity_1deg.bin").write_bytes(tl_1.tobytes(order="C"))
    el_1 = np.rint(block_mean(alt, K)).astype("<i2")
    (HERE / "elevation_1deg.bin").write_bytes(el_1.tobytes(order="C"))

    rng = np.random.default_rng(24)
    n = 200_000
    lat = np.clip(np.degrees(np.arcsin(rng.uniform(-1, 1, n))), -60, 75)
    lon = rng.uniform(-180, 180, n)
    month = rng.integers(0, 12, n)
    ii = np.clip(((90 - lat) * K).astype(int), 0, 2159)
    jj = np.clip(((lon + 180) * K).astype(int), 0, 4319)
    err = np.empty(n)
    g = tl_1.astype(np.float64) / 20.0
    for m in range(12):
        s = month == m
        err[s] = bilinear(g[:, :, m], lat[s], lon[s], 1.0) - tl20[ii[s], jj[s], m] / 20.0
    a = np.abs(err)
    print(f"TL, 1 deg bilinear against the 5' source: median |error| {np.median(a):.3f}, "
          f"95th percentile {np.percentile(a, 95):.3f}, largest {a.max():.2f} (TL units)")
    e = np.abs(bilinear(el_1.astype(np.float64), lat, lon, 1.0) - alt[ii, jj])
    print(f"elevation, 1 deg bilinear against the 5' source: median |error| {np.median(e):.0f} m, "
          f"95th percentile {np.percentile(e, 95):.0f} m, largest {e.max():.0f} m")


if __name__ == "__main__":
    main()
