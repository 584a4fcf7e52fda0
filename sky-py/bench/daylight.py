"""skymodels.daylight over a million times, against a pure-Python loop calling it once per
time and against pvlib's solar position and clear sky over the same times, in one run.

Run by `scripts/python.sh bench` (a virtual environment with the wheel, pvlib and pandas).
Each timing is the wall time and the CPU time of this process (all its threads) of the run
with the least wall time of REPEATS runs (the loop: one run of the million calls); the ratios
are each peer's time over the vectorised call's, in wall time (what a caller waits; the
vectorised call splits long arrays over the cores) and in CPU time (the work done, which other
jobs on a shared machine disturb less). Prints `bench` lines (docs/python.md).
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
    """(wall, cpu) seconds of the run with the least wall time."""
    runs = []
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        call()
        runs.append((time.perf_counter() - wall, time.process_time() - cpu))
    return min(runs)


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
        f"{platform.python_version()}, load average {' '.join(load)} (after the runs)"
    )
    print(
        f"bench daylight, {N:,} times at one site, vectorised (one call): {vectorised[0]:.3f} s "
        f"wall ({vectorised[0] / N * 1e9:.0f} ns a time), {vectorised[1]:.3f} s CPU"
    )

    def ratios(peer):
        return (
            f"the vectorised call is {peer[0] / vectorised[0]:.1f}x as fast in wall time, "
            f"{peer[1] / vectorised[1]:.1f}x in CPU time"
        )

    print(
        f"bench daylight, a pure-Python loop of {N:,} calls, one time each: {looped[0]:.1f} s "
        f"wall ({looped[0] / N * 1e6:.1f} us a call), {looped[1]:.1f} s CPU: {ratios(looped)} "
        f"(goal: at least 20x)"
    )
    print(
        f"bench pvlib {pvlib.__version__} Location.get_solarposition + get_clearsky "
        f"(Ineichen-Perez, Linke turbidity lookup) over the same {N:,} times: {peer[0]:.3f} s "
        f"wall, {peer[1]:.3f} s CPU: {ratios(peer)} (goal: at least 1x)"
    )


if __name__ == "__main__":
    main()
