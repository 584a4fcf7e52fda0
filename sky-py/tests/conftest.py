"""Shared helpers: sky-core's own values (the sky-py-reference binary, built by
scripts/python.sh test from the same checkout), and exact comparisons of float bits."""

from __future__ import annotations

import datetime
import json
import os
import subprocess

import numpy as np
import pytest

EPOCH = datetime.datetime(1970, 1, 1)

# The years each sun algorithm takes, as microseconds since 1970 UTC.
FAST_YEARS = (2000, 2110)
SPA_YEARS = (1, 2999)


@pytest.fixture(scope="session")
def native():
    """A function from a list of cases (dicts) to sky-core's results, computed by the
    reference binary: floats as their bits, or {"error": sky-core's message}."""
    path = os.environ.get("SKY_PY_REFERENCE")
    if not path or not os.access(path, os.X_OK):
        raise RuntimeError(
            "SKY_PY_REFERENCE must name the sky-py-reference binary "
            "(scripts/python.sh test builds it and sets it)"
        )

    def run(cases):
        done = subprocess.run(
            [path], input=json.dumps(cases), capture_output=True, text=True, timeout=300
        )
        assert done.returncode == 0, done.stderr
        results = json.loads(done.stdout)
        assert len(results) == len(cases)
        return results

    return run


def micros_between(rng, years, n):
    """n random instants (microseconds since 1970 UTC) from the first day of years[0] to the
    last of years[1]."""
    lo = int((datetime.datetime(years[0], 1, 1) - EPOCH) / datetime.timedelta(microseconds=1))
    hi = int(
        (datetime.datetime(years[1], 12, 31, 23, 59, 59, 999_999) - EPOCH)
        / datetime.timedelta(microseconds=1)
    )
    return rng.integers(lo, hi, size=n, endpoint=True)


def fields(micros):
    """The calendar fields of an instant by Python's own datetime: year, month, day, hour,
    minute and the second with its fraction (the microseconds of the minute over 1e6)."""
    t = EPOCH + datetime.timedelta(microseconds=int(micros))
    return [t.year, t.month, t.day, t.hour, t.minute, (t.second * 10**6 + t.microsecond) / 1e6]


def f32_values(rng, lo, hi, n):
    """n float32 values uniform in [lo, hi] and both ends, as Python floats (exact)."""
    v = rng.uniform(lo, hi, size=n).astype(np.float32)
    v[:2] = [lo, hi]
    return [float(x) for x in v]


def bits32(values):
    """The float32 bits of float64 or float32 values that must hold float32 values exactly."""
    v = np.asarray(values)
    v32 = v.astype(np.float32)
    same = (v32.astype(np.float64) == v.astype(np.float64)) | np.isnan(v)
    assert same.all(), f"not float32 values: {v[~same][:5]}"
    return v32.view(np.uint32)


def expected32(results, key):
    """A column of native f32 bits; None (no CCT, no clear-sky index) as NaN's bits."""
    nan = int(np.float32(np.nan).view(np.uint32))
    return np.array([nan if r[key] is None else r[key] for r in results], dtype=np.uint32)


def assert_same32(actual, results, key):
    """The wheel's column equals sky-core's bit for bit (NaN where sky-core has none)."""
    got = bits32(actual)
    want = expected32(results, key)
    nan = np.isnan(np.asarray(actual, dtype=np.float64))
    want_nan = np.array([r[key] is None for r in results])
    assert np.array_equal(nan, want_nan), f"{key}: NaN where sky-core has no value"
    differ = (got != want) & ~nan
    assert not differ.any(), (
        f"{key}: {differ.sum()} of {len(results)} differ from sky-core, first at "
        f"{np.argmax(differ)}: {np.asarray(actual).ravel()[np.argmax(differ)]!r} != "
        f"{np.uint32(want[np.argmax(differ)]).view(np.float32)!r}"
    )


def as_times(micros):
    return np.asarray(micros, dtype=np.int64).astype("datetime64[us]")
