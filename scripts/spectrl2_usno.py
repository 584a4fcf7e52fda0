"""Two independent clear-sky models against the USNO clear-sky record (docs/daylight.md).

Global horizontal illuminance of SPCTRL2 (Bird & Riordan 1986, NREL/TP-215-2436) as pvlib 0.13
implements it (`pvlib.spectrum.spectrl2`, its default aerosol: single-scattering albedo 0.945 at
400 nm, Angstrom alpha 1.14, asymmetry 0.65; ozone 0.30 atm-cm, precipitable water 1.42 cm,
1013.25 hPa, ground albedo 0.2, 1 AU) for aerosol optical depths at 500 nm, over USNO Circular
171's curve (the coefficients of sky_train::physical::record::usno_illuminance). Photopic
weighting: Wyman, Sloan & Shirley 2013 (JCGT 2(2)), the multi-lobe fit of the CIE 1931 y-bar
(within about 1 % of the table where it matters), 683 lm/W.

And the IES clear-sky daylight model (IESNA Lighting Handbook, 9th ed., 2000, ch. 8, after
RP-21): direct normal 127.5 klx exp(-0.21 / sin h), sky 0.8 + 15.5 sqrt(sin h) klx.

    python3 -m venv venv && venv/bin/pip install 'pvlib==0.13.*'
    venv/bin/python scripts/spectrl2_usno.py
"""

import math

import numpy as np
from pvlib import atmosphere, spectrum


def usno_lux(h):
    if h > 20:
        c = (3.74, 3.97, -4.07, 1.47)
    elif h > 5:
        c = (3.05, 13.28, -45.98, 64.33)
    elif h > -0.8:
        c = (2.88, 22.26, -207.64, 1034.30)
    else:
        raise ValueError("daytime only")
    x = h / 90.0
    return 10 ** (c[0] + c[1] * x + c[2] * x * x + c[3] * x**3)


def ybar(nm):
    """Wyman, Sloan & Shirley 2013, eq. 2 (the piecewise Gaussian fit of y-bar)."""

    def g(x, mu, s1, s2):
        t = (x - mu) / np.where(x < mu, s1, s2)
        return np.exp(-0.5 * t * t)

    return 0.821 * g(nm, 568.8, 46.9, 40.5) + 0.286 * g(nm, 530.9, 16.3, 31.1)


DAY = 94  # early April, about 1 AU


def global_lux(elevation, tau500):
    zenith = 90.0 - elevation
    out = spectrum.spectrl2(
        apparent_zenith=zenith,
        aoi=zenith,
        surface_tilt=0.0,
        ground_albedo=0.2,
        surface_pressure=101325.0,
        relative_airmass=atmosphere.get_relative_airmass(zenith, model="kasten1966"),
        precipitable_water=1.42,
        ozone=0.30,
        aerosol_turbidity_500nm=tau500,
        dayofyear=DAY,
    )
    # Back to 1 AU (Spencer 1971, as pvlib's spectrl2 applies it).
    b = 2 * math.pi * (DAY - 1) / 365
    r2 = 1.00011 + 0.034221 * math.cos(b) + 0.00128 * math.sin(b) + 0.000719 * math.cos(2 * b) + 0.000077 * math.sin(2 * b)
    nm = np.asarray(out["wavelength"], dtype=float)
    e = np.asarray(out["poa_global"], dtype=float).ravel()
    keep = (nm >= 360) & (nm <= 830)
    return 683.0 * np.trapezoid(ybar(nm[keep]) * e[keep], nm[keep]) / r2


def ies_lux(h):
    s = math.sin(math.radians(h))
    return 127.5e3 * math.exp(-0.21 / s) * s + (0.8 + 15.5 * math.sqrt(s)) * 1e3


if __name__ == "__main__":
    print("model,elevation_deg,lux,usno_lux,ratio")
    elevations = (90.0, 62.0, 40.0, 20.0, 10.0)
    for tau in (0.1, 0.27, 0.49):
        for h in elevations:
            lux = global_lux(h, tau)
            print(f"spctrl2 tau500 {tau},{h:.0f},{lux:.0f},{usno_lux(h):.0f},{lux / usno_lux(h):.3f}")
    for h in elevations:
        print(f"ies clear,{h:.0f},{ies_lux(h):.0f},{usno_lux(h):.0f},{ies_lux(h) / usno_lux(h):.3f}")
