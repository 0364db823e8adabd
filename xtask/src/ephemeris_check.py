"""Expected sun and moon positions from astropy, for stratus-astro's tests.

Written by `cargo xtask ephemeris-check` (which installs astropy in a virtual environment under
target/ and runs this); the output, crates/astro/tests/data/ephemeris.json, is committed and
read by crates/astro/tests/ephemeris.rs. Usage: python ephemeris_check.py OUT.json N EVENTS

N random instants (uniform over 1950-2100, whole seconds) and places (uniform over the sphere,
at sea level on WGS 84), from a fixed seed. For each: the sun's and moon's topocentric
elevation and azimuth (AltAz with pressure 0: geometric, no refraction; astropy's built-in
ephemeris: ERFA's epv00 for the Earth and sun, the full ELP-2000/82 series of Meeus ch. 47
for the moon), the moon's illuminated fraction from the geocentric elongation and distances,
and for the first EVENTS cases the sunrise and sunset of the local solar day (UTC + lon/15 h)
holding the instant: the sun's geometric elevation crossing -0.833 degrees, bisected to 0.1 s.
"""

import json
import sys
import warnings

import numpy as np
import astropy
import astropy.units as u
from astropy.coordinates import AltAz, EarthLocation, get_body
from astropy.time import Time
from astropy.utils import iers

# No network: the bundled IERS-B table, and UT1 = UTC (within 0.9 s) outside it.
iers.conf.auto_download = False
iers.conf.iers_degraded_accuracy = "warn"
iers.conf.auto_max_age = None
warnings.simplefilter("ignore")

SUNRISE_ELEVATION = -0.833
SEED = 2026


def sun_elevation(jd, lon, lat):
    t = Time(jd, format="jd", scale="utc")
    loc = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, 0 * u.m)
    frame = AltAz(obstime=t, location=loc)
    return get_body("sun", t, loc).transform_to(frame).alt.deg


def iso(jd):
    t = Time(jd, format="jd", scale="utc")
    t.precision = 0
    return [s + "Z" for s in np.atleast_1d(t.isot)]


def main():
    out, n, events = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    rng = np.random.default_rng(SEED)
    start = Time("1950-01-01T00:00:00", scale="utc").jd
    end = Time("2100-12-31T00:00:00", scale="utc").jd
    jd = np.round(rng.uniform(start, end, n) * 86400.0) / 86400.0
    dates = iso(jd)
    # The instant exactly as the Rust side reads it: from the printed date.
    t = Time([d[:-1] for d in dates], format="isot", scale="utc")
    lat = np.round(np.degrees(np.arcsin(rng.uniform(-1.0, 1.0, n))), 4)
    lon = np.round(rng.uniform(-180.0, 180.0, n), 4)
    loc = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, 0 * u.m)
    frame = AltAz(obstime=t, location=loc)
    sun = get_body("sun", t, loc).transform_to(frame)
    moon = get_body("moon", t, loc).transform_to(frame)
    sun_g, moon_g = get_body("sun", t), get_body("moon", t)
    elong = sun_g.separation(moon_g).rad
    rs, rm = sun_g.distance.to(u.km).value, moon_g.distance.to(u.km).value
    phase_angle = np.arctan2(rs * np.sin(elong), rm - rs * np.cos(elong))
    phase = (1.0 + np.cos(phase_angle)) / 2.0

    cases = []
    for k in range(n):
        cases.append(
            {
                "date_utc": dates[k],
                "latitude_deg": float(lat[k]),
                "longitude_deg": float(lon[k]),
                "sun": {"elevation_deg": float(sun.alt.deg[k]), "azimuth_deg": float(sun.az.deg[k])},
                "moon": {
                    "elevation_deg": float(moon.alt.deg[k]),
                    "azimuth_deg": float(moon.az.deg[k]),
                    "phase": float(phase[k]),
                },
            }
        )

    # Sunrise and sunset: sample the local day every 10 minutes, bisect each crossing.
    m = min(events, n)
    jd_t = t.jd[:m]
    offset = ((lon[:m] + 180.0) % 360.0 - 180.0) / 15.0 / 24.0
    day_start = np.floor(jd_t + offset - 0.5) + 0.5 - offset
    steps = np.arange(145) * 600.0 / 86400.0
    grid = day_start[:, None] + steps[None, :]
    h = sun_elevation(grid.ravel(), np.repeat(lon[:m], 145), np.repeat(lat[:m], 145))
    h = h.reshape(m, 145) - SUNRISE_ELEVATION
    found = {k: {"sunrise_utc": None, "sunset_utc": None} for k in range(m)}
    ks, a, b, rising = [], [], [], []
    for k in range(m):
        for j in range(144):
            if (h[k, j] < 0) != (h[k, j + 1] < 0):
                ks.append(k)
                a.append(grid[k, j])
                b.append(grid[k, j + 1])
                rising.append(h[k, j + 1] >= 0)
    ks, a, b, rising = np.array(ks), np.array(a), np.array(b), np.array(rising)
    while len(ks) and np.max(b - a) * 86400.0 > 0.1:
        mid = 0.5 * (a + b)
        up = sun_elevation(mid, lon[ks], lat[ks]) - SUNRISE_ELEVATION >= 0
        toward_b = up == rising
        b = np.where(toward_b, mid, b)
        a = np.where(toward_b, a, mid)
    for k, when, r in zip(ks, iso(0.5 * (a + b)) if len(ks) else [], rising):
        key = "sunrise_utc" if r else "sunset_utc"
        if found[k][key] is None:
            found[k][key] = when
    for k in range(m):
        cases[k]["events"] = found[k]

    doc = {
        "about": "expected values for crates/astro/tests/ephemeris.rs, from `cargo xtask ephemeris-check`",
        "generator": f"astropy {astropy.__version__}, numpy {np.__version__}, seed {SEED}",
        "ephemeris": "astropy built-in (ERFA epv00 for the sun, Meeus ch. 47 ELP-2000/82 for the moon); AltAz with pressure 0 (no refraction); WGS 84 sea level",
        "sunrise_elevation_deg": SUNRISE_ELEVATION,
        "cases": cases,
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"wrote {n} cases ({m} with sunrise and sunset) to {out}")


if __name__ == "__main__":
    main()
