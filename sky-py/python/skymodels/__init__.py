"""Daylight, the sun and published sky models from Rust's sky-core, numpy in and out.

* ``daylight(latitude, longitude, times, aod=None)``: the clear-sky daylight at a place over
  an array of times: global, diffuse and direct horizontal illuminance (lx), chromaticity,
  CCT and Duv, melanopic EDI (lx).
* ``daylight_at_sun(sun_zenith, aod=None)``: the same for given sun zenith angles.
* ``sun_position(latitude, longitude, times)``: the sun's zenith, elevation and azimuth.
* ``controller_step(latitude, longitude, times, lux=None, ...)``: a daylight-following
  luminaire's step (illuminance, colour, CCT, melanopic EDI, LED levels), optionally driven by
  an outdoor lux sensor or pyranometer.
* ``Sky``: every sky model's radiance at view directions, and equirectangular images.
* ``PhysicalAtmosphere`` (where ``HAS_PHYSICAL``): the physical atmosphere's spectra.

Times are UTC: numpy ``datetime64`` arrays (any unit), pandas ``DatetimeIndex`` or ``Series``
(time-zone aware ones are converted to UTC), ``datetime.datetime`` objects (naive ones are
taken as UTC, aware ones converted), ISO 8601 strings, or sequences of these. A scalar time
gives scalar results; an array of times gives arrays of its shape.

Every value is sky-core's own, computed in f32 as it computes it (in firmware and in the
browser too); time series are float64 arrays holding those values exactly. A parameter out
of its range raises ``ValueError`` naming the parameter and its valid range.
"""

from __future__ import annotations

import datetime as _datetime

import numpy as _np

from . import _skymodels
from ._skymodels import (
    DEFAULT_AOD,
    GROUND_ALBEDO,
    HAS_PHYSICAL,
    MAX_AOD,
    MIN_AOD,
    OZONE_DU,
    Sky,
    equirect_directions,
)

if HAS_PHYSICAL:
    from ._skymodels import PhysicalAtmosphere

__all__ = [
    "DEFAULT_AOD",
    "GROUND_ALBEDO",
    "HAS_PHYSICAL",
    "MAX_AOD",
    "MIN_AOD",
    "OZONE_DU",
    "Sky",
    "controller_step",
    "daylight",
    "daylight_at_sun",
    "direction",
    "equirect_directions",
    "sun_position",
]
if HAS_PHYSICAL:
    __all__.append("PhysicalAtmosphere")

__version__ = "0.1.0"

_EPOCH = _np.datetime64(0, "us")


def _to_utc(value):
    """One time (datetime, pandas Timestamp, numpy datetime64, ISO string) as datetime64[us]."""
    if isinstance(value, _datetime.datetime) and value.tzinfo is not None:
        value = value.astimezone(_datetime.timezone.utc).replace(tzinfo=None)
    return _np.datetime64(value, "us")


def _times(times):
    """``times`` as int64 microseconds since 1970 UTC (flat), their shape, and whether scalar."""
    if hasattr(times, "tz_convert") and getattr(times, "tz", None) is not None:
        times = times.tz_convert("UTC").tz_localize(None)  # a tz-aware pandas DatetimeIndex
    elif hasattr(times, "dt") and getattr(times.dt, "tz", None) is not None:
        times = times.dt.tz_convert("UTC").dt.tz_localize(None)  # a tz-aware pandas Series
    if isinstance(times, _datetime.datetime):
        times = _to_utc(times)
    array = _np.asarray(times)
    if array.dtype.kind == "O":
        array = _np.array([_to_utc(t) for t in array.ravel()], dtype="datetime64[us]").reshape(
            array.shape
        )
    elif array.dtype.kind in "US":
        array = array.astype("datetime64[us]")
    if array.dtype.kind != "M":
        raise TypeError(
            f"times: expected UTC times (numpy datetime64, pandas timestamps, datetime objects "
            f"or ISO 8601 strings), not an array of {array.dtype}"
        )
    micros = _np.ascontiguousarray(array.astype("datetime64[us]").view(_np.int64).ravel())
    return micros, array.shape, array.ndim == 0


def _per_time(name, value, shape, default=None):
    """A float parameter given once or per time, as float32 (one value, or one per time)."""
    if value is None:
        value = default
    array = _np.asarray(value, dtype=_np.float64)
    if array.ndim != 0 and array.shape != tuple(shape):
        raise ValueError(
            f"{name}: shape {array.shape} differs from the times' {tuple(shape)}: "
            f"give one value, or one per time"
        )
    return _float32(array).ravel()


def _float32(array):
    """float64 values as float32, rounded to nearest; beyond float32's range they become
    infinite, which sky-core then refuses with the parameter's range (no overflow warning)."""
    with _np.errstate(over="ignore"):
        return _np.ascontiguousarray(array, dtype=_np.float32)


def _shaped(columns, shape, scalar):
    """Each column of ``columns`` in the times' shape (a float for a scalar time)."""
    out = {}
    for name, column in columns.items():
        if scalar:
            out[name] = column[0] if column.ndim == 1 else column[0].copy()
        else:
            out[name] = column.reshape(tuple(shape) + column.shape[1:])
    return out


def daylight(
    latitude, longitude, times, aod=None, *, elevation=0.0, ozone_du=None, algorithm="fast"
):
    """The clear-sky daylight at a place at each of ``times``: the light a sensor there sees
    under a clear sky, and the light ``controller_step`` follows without a measurement.

    Parameters
    ----------
    latitude, longitude : float
        Degrees, north and east positive: [-90, 90] and [-180, 180].
    times : UTC times (module docs); an array gives arrays of its shape.
    aod : float or array, optional
        Aerosol optical depth at 550 nm, ``MIN_AOD`` to ``MAX_AOD`` (0.05 to 0.8), one value or
        one per time. None: ``DEFAULT_AOD`` (0.38, the default atmosphere of sky-core's tables).
        (A later release will take None as the site's monthly climatology; pass a number to
        keep today's behaviour.)
    elevation : float, keyword
        The site's height above sea level, metres, -500 to 5000: its surface pressure (US
        Standard Atmosphere 1976), which thins the air's share of the light and the
        refraction of the sun's beam, and the sun's parallax.
    ozone_du : float, optional, keyword
        The total ozone column, Dobson units, 200 to 500 (it matters in twilight); None:
        ``OZONE_DU``. ``sky-train site`` prints a site's month.
    algorithm : {"fast", "spa"}, keyword
        The sun's position: "fast" (Grena 2012, the years 2000-2110, within 0.003 degrees of
        SPA) or "spa" (NREL SPA, the years 1-2999).

    Returns
    -------
    dict of float64 arrays (floats for a scalar time), on each time's Earth-Sun distance
    (x 1.035 in early January to x 0.967 in early July of the values at 1 AU), with the sun's
    beam from its refracted position (its air mass and its angle on the plane: at 5 degrees
    and 2,317 m the direct light 5 % above the geometric sun's) and the sky's light the
    geometric sun's (sky-core's ``Daylight::refracted``):
        ``global_illuminance``, ``diffuse_illuminance``, ``direct_illuminance`` (on the
        horizontal plane) and ``direct_normal_illuminance`` (on a plane facing the sun): lx.
        ``x``, ``y``: CIE 1931 chromaticity of the global light (0, 0 with no light).
        ``cct``: correlated colour temperature, K; ``duv``: distance from the Planckian locus
        (ANSI C78.377 sign); both NaN where |Duv| > 0.05 (nautical twilight's blue).
        ``melanopic_edi``: melanopic equivalent daylight illuminance of the global light, lx
        (CIE S 026:2018).

    The sun is from -18 degrees (the end of astronomical twilight; lower suns keep its values)
    to 90 degrees; the model is distilled from sky-train's spectral, multiple-scattering
    physical atmosphere: illuminance within 2 % of it from 0 to 90 degrees and 5 % from -12 to
    0 degrees, chromaticity within 0.002, melanopic EDI within 2 % (docs/daylight.md).

    Raises ``ValueError`` naming the parameter (the element of ``times`` or ``aod``) and its
    valid range; ``TypeError`` for times that are not times.
    """
    micros, shape, scalar = _times(times)
    aod = _per_time("aod", aod, shape, DEFAULT_AOD)
    columns = _skymodels.daylight_series(
        float(latitude),
        float(longitude),
        micros,
        aod,
        float(elevation),
        None if ozone_du is None else float(ozone_du),
        algorithm,
        scalar,
    )
    return _shaped(columns, shape, scalar)


def daylight_at_sun(sun_zenith, aod=None):
    """The clear-sky daylight for sun zenith angles ``sun_zenith`` (radians, [0, pi]; a float
    or an array) and aerosol optical depth ``aod`` (as ``daylight``'s).

    For a sun position from elsewhere (pvlib's ``get_solarposition``: ``np.radians`` of its
    ``zenith`` column, the geometric one). Returns ``daylight``'s dict, in the shape of
    ``sun_zenith``, at the mean Earth-Sun distance (1 AU: no date is given), at sea level and
    with the beam from the geometric sun (sky-core's ``Daylight::new``, the reference's sky;
    ``daylight`` refracts the beam, which raises the direct light near the horizon).
    """
    zenith = _np.asarray(sun_zenith, dtype=_np.float64)
    shape, scalar = zenith.shape, zenith.ndim == 0
    flat = _float32(zenith).ravel()
    aod = _per_time("aod", aod, shape, DEFAULT_AOD)
    return _shaped(_skymodels.daylight_at_sun(flat, aod, scalar), shape, scalar)


def sun_position(latitude, longitude, times, *, elevation=0.0, algorithm="fast"):
    """The sun's position seen from a place at each of ``times``.

    Parameters as ``daylight``'s. Returns a dict of float64 arrays (floats for a scalar time):

    ``zenith``: the topocentric geometric zenith angle, degrees [0, 180].
    ``apparent_zenith``: refracted for a standard atmosphere (1013.25 hPa, 15 C), degrees.
    ``elevation``: 90 - zenith, degrees.
    ``azimuth``: compass azimuth, degrees from north, clockwise (east 90), [0, 360) -- pvlib's.
    ``sun_zenith``, ``sun_azimuth``: the same sun in the sky models' frame, radians: the
    geometric zenith angle, and the azimuth from +x (east) towards +y (north), 90 degrees
    minus the compass azimuth. ``Sky``'s constructors take these.
    """
    micros, shape, scalar = _times(times)
    columns = _skymodels.sun_position_series(
        float(latitude), float(longitude), micros, float(elevation), algorithm, scalar
    )
    return _shaped(columns, shape, scalar)


def controller_step(
    latitude,
    longitude,
    times,
    *,
    lux=None,
    ghi=None,
    dhi=None,
    aod=None,
    elevation=0.0,
    ozone_du=None,
    precipitable_water=None,
    algorithm="fast",
    light="global",
    full_scale_lux=10_000.0,
    decomposition=None,
    luminaire=None,
    history=False,
):
    """A daylight-following luminaire's step at each of ``times``: sky-core's
    ``controller::step``, as the firmware and ``sky-train schedule`` run it.

    Without a measurement, the light is the clear-sky daylight (``daylight``). With one -- an
    outdoor lux sensor (``lux``, lx), a pyranometer (``ghi``, W/m2) or a pyranometer pair
    (``ghi`` and the diffuse ``dhi``, W/m2); one value, or one per time -- the illuminance is
    the measured one and its colour that of daylight under cloud, from the clear-sky index.

    Parameters
    ----------
    latitude, longitude, times, aod, elevation, algorithm
        As ``daylight``'s.
    ozone_du : float, optional
        The clear atmosphere's total ozone column, Dobson units, 200 to 500 (it matters in
        twilight); None: sky-core's default (``controller::Settings``). ``sky-train site``
        prints a site's month.
    precipitable_water : float, optional
        The site's precipitable water, cm, 0 to 10, at which a measured irradiance becomes lux
        (Perez's efficacies: a dry site's clear light has more lumens per watt); None: sky-core's
        default, 2 cm.
    lux, ghi, dhi : float or array, keyword
        The measurement, if any: ``lux`` alone, or ``ghi`` with or without ``dhi``.
    light : {"global", "sky"}
        The light followed: sun and sky on a horizontal plane, or the sky alone (a
        north-facing window).
    full_scale_lux : float
        The illuminance, lx, at which the luminaire gives its full output (levels clip above
        it, keeping the colour).
    decomposition : {"dirint", "dirindex", "erbs", "engerer2", "engerer2-global"}, optional
        The separation model that splits a global reading without a diffuse one; None:
        sky-core's default (``controller::Settings``'s: DIRINT, Perez et al. 1992, continuous
        across its bins). Each time is a step alone unless ``history``.
    history : bool
        The times are one sensor's readings in time order (strictly increasing, in the order
        of the flattened array): each step takes the reading before it, as ``sky-train schedule
        --measurements`` does (sky-core's ``controller::step_with_history``), which DIRINT's
        stability index needs: on docs/weather.md's clear station days its diffuse is then
        +26 % and +4 % of the measured one instead of +57 % and +33 % alone. Readings more
        than 90 minutes apart, or a step without a measurement or with the sun down, start
        afresh. False (the default): every time is a step alone, computed over the cores.
    luminaire : four (x, y, lumens) tuples, optional
        Red, green, blue and white channels: CIE 1931 chromaticity and luminous flux at full
        drive. None: sky-core's example RGBW luminaire.

    Returns
    -------
    dict of float64 arrays (floats for a scalar time):
        ``illuminance``: the followed light's horizontal illuminance, lx. ``x``, ``y``: its
        chromaticity. ``cct`` (K) and ``duv``, NaN off the locus (|Duv| > 0.05).
        ``melanopic_edi``: lx. ``levels``: shape (..., 4), the R, G, B, W drive levels in
        [0, 1]. ``luminance_clipped``: bool, brighter than full scale.
        With a measurement also: ``sky_type`` (Perez's sky-clearness bin, 1 overcast to 8
        clear; 0 with the sun down), ``clear_sky_index`` (the measured global illuminance
        over the clear sky's; NaN with the clear sky below 100 lx), ``overcast_fraction`` (0
        clear to 1 overcast), ``global_irradiance``, ``diffuse_irradiance``,
        ``direct_normal_irradiance`` (W/m2, measured or split), ``clear_sky_illuminance`` and
        ``diffuse_illuminance`` (lx).
    """
    micros, shape, scalar = _times(times)

    def reading(name, value):
        return None if value is None else _per_time(name, value, shape)

    if luminaire is not None:
        luminaire = [tuple(float(v) for v in channel) for channel in luminaire]
    columns = _skymodels.controller_series(
        float(latitude),
        float(longitude),
        micros,
        _per_time("aod", aod, shape, DEFAULT_AOD),
        float(elevation),
        None if ozone_du is None else float(ozone_du),
        None if precipitable_water is None else float(precipitable_water),
        algorithm,
        light,
        float(full_scale_lux),
        decomposition,
        reading("lux", lux),
        reading("ghi", ghi),
        reading("dhi", dhi),
        luminaire,
        bool(history),
        scalar,
    )
    return _shaped(columns, shape, scalar)


def direction(zenith, azimuth):
    """Unit view directions (x east, y north, z up) of zenith angles ``zenith`` and azimuths
    ``azimuth`` (radians; the azimuth from +x, east, towards +y, north), broadcast together:
    float32 of their shape + (3,). sky-core's ``geom::direction``."""
    zenith, azimuth = _np.broadcast_arrays(
        _np.asarray(zenith, dtype=_np.float32), _np.asarray(azimuth, dtype=_np.float32)
    )
    return _skymodels.direction(zenith, azimuth)
