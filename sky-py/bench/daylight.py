"""skymodels.daylight over a million times, against a pure-Python loop calling it once per
time and against pvlib's solar position and clear sky over the same times, in one run.

Run by `scripts/python.sh bench` (a virtual environment with the wheel, pvlib and pandas).
Every timing is wall time on this machine, the best of REPEATS runs (the loop: one run); the
ratios are each peer's time over the vectorised call's. Prints `bench` lines (docs/python.md).
"""

from __future__ import annotations

import os
import platform
import time

import numpy as np
import pandas as pd
import pvlib

import skymodels

LAT, LON, ALTITUDE = 48.21, 16.37, 190.0  # Vienna
N = 1_000_000
REPEATS = 3


def best(call, repeats=REPEATS):
    times = []
    for _ in range(repeats):
        began = time.perf_counter()
        call()
        times.append(time.perf_counter() - began)
    return min(times)


def main():
    index = pd.date_range("2026-01-01", periods=N, freq="min", tz="UTC")  # 694 days
    instants = index.tz_localize(None).to_numpy()  # datetime64[ns], UTC

    # The same values whichever form the times take.
    a = skymodels.daylight(LAT, LON, index[:1000], elevation=ALTITUDE)
    b = skymodels.daylight(LAT, LON, instants[:1000], elevation=ALTITUDE)
    assert all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)

    vectorised = best(lambda: skymodels.daylight(LAT, LON, index, elevation=ALTITUDE))

    def loop():
        for t in instants:
            skymodels.daylight(LAT, LON, t, elevation=ALTITUDE)

    looped = best(loop, repeats=1)

    location = pvlib.location.Location(LAT, LON, tz="UTC", altitude=ALTITUDE)

    def with_pvlib():
        position = location.get_solarposition(index)
        location.get_clearsky(index, model="ineichen", solar_position=position)

    peer = best(with_pvlib)

    load = open("/proc/loadavg").read().split()[:3] if os.path.exists("/proc/loadavg") else "?"
    print(
        f"machine: {platform.machine()}, {os.cpu_count()} cores, Python "
        f"{platform.python_version()}, load average {' '.join(load)}"
    )
    print(
        f"bench daylight, {N:,} times at one site (vectorised, one call): {vectorised:.3f} s "
        f"({vectorised / N * 1e9:.0f} ns a time)"
    )
    print(
        f"bench daylight, a pure-Python loop of {N:,} calls, one time each: {looped:.1f} s "
        f"({looped / N * 1e6:.1f} us a call): the vectorised call is {looped / vectorised:.1f}x "
        f"as fast (goal: at least 20x)"
    )
    print(
        f"bench pvlib {pvlib.__version__} Location.get_solarposition + get_clearsky "
        f"(Ineichen-Perez, Linke turbidity lookup) over the same {N:,} times: {peer:.3f} s: "
        f"the vectorised call is {peer / vectorised:.2f}x as fast (goal: at least 1x)"
    )


if __name__ == "__main__":
    main()
