"""Expected star and galactic-centre positions from astropy, for stratus-astro's tests.

Written by `cargo xtask ephemeris-check` (after ephemeris_check.py, in the same virtual
environment); the output, crates/astro/tests/data/stars.json, is committed and read by
crates/astro/tests/stars.rs. Usage: python stars_check.py CATALOGUE.csv OUT.json N CASES

For CASES random instants (uniform over 1950-2100, whole seconds) and places (uniform over the
sphere, at sea level on WGS 84) from a fixed seed, plus the night of the README's Milky Way
(2026-08-12T22:00:00Z at 46 N, 8 E): the topocentric elevation and azimuth of the N brightest
stars of the catalogue (their J2000 positions as the catalogue gives them, without proper
motion, as stratus-astro places them) and of the galactic centre (l = 0, b = 0), AltAz with
pressure 0 (no refraction). astropy's transformation carries what stratus-astro leaves out
(annual aberration, the full IAU 2006/2000A precession-nutation, the frame bias): the
difference is the error of its placement.
"""

import json
import sys
import warnings

import numpy as np
import astropy
import astropy.units as u
from astropy.coordinates import AltAz, EarthLocation, SkyCoord
from astropy.time import Time
from astropy.utils import iers

iers.conf.auto_download = False
iers.conf.iers_degraded_accuracy = "warn"
iers.conf.auto_max_age = None
warnings.simplefilter("ignore")

SEED = 4401


def read_catalogue(path):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#") or line.startswith("ra_deg"):
                continue
            ra, dec, vmag = (float(x) for x in line.split(",")[:3])
            rows.append((ra, dec, vmag))
    return rows


def main():
    catalogue, out, n, count = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    stars = read_catalogue(catalogue)
    order = sorted(range(len(stars)), key=lambda i: stars[i][2])[:n]
    ra = np.array([stars[i][0] for i in order])
    dec = np.array([stars[i][1] for i in order])
    rng = np.random.default_rng(SEED)
    start = Time("1950-01-01T00:00:00", scale="utc").jd
    end = Time("2100-12-31T00:00:00", scale="utc").jd
    jd = np.round(rng.uniform(start, end, count) * 86400.0) / 86400.0
    lat = np.round(np.degrees(np.arcsin(rng.uniform(-1.0, 1.0, count))), 4)
    lon = np.round(rng.uniform(-180.0, 180.0, count), 4)
    dates = []
    for j in jd:
        t = Time(j, format="jd", scale="utc")
        t.precision = 0
        dates.append(t.isot + "Z")
    dates.append("2026-08-12T22:00:00Z")
    lat = np.append(lat, 46.0)
    lon = np.append(lon, 8.0)

    coords = SkyCoord(ra=ra * u.deg, dec=dec * u.deg, frame="icrs")
    centre = SkyCoord(l=0.0 * u.deg, b=0.0 * u.deg, frame="galactic")
    cases = []
    for date, la, lo in zip(dates, lat, lon):
        t = Time(date[:-1], format="isot", scale="utc")
        loc = EarthLocation.from_geodetic(lo * u.deg, la * u.deg, 0 * u.m)
        frame = AltAz(obstime=t, location=loc, pressure=0 * u.hPa)
        s = coords.transform_to(frame)
        c = centre.transform_to(frame)
        cases.append(
            {
                "date_utc": date,
                "latitude_deg": float(la),
                "longitude_deg": float(lo),
                "stars": [
                    {
                        "index": int(i),
                        "ra_deg": float(stars[i][0]),
                        "dec_deg": float(stars[i][1]),
                        "elevation_deg": float(s.alt.deg[k]),
                        "azimuth_deg": float(s.az.deg[k]),
                    }
                    for k, i in enumerate(order)
                ],
                "galactic_centre": {
                    "elevation_deg": float(c.alt.deg),
                    "azimuth_deg": float(c.az.deg),
                },
            }
        )
    doc = {
        "about": "expected values for crates/astro/tests/stars.rs, from `cargo xtask ephemeris-check`",
        "generator": f"astropy {astropy.__version__}, numpy {np.__version__}, seed {SEED}",
        "method": "SkyCoord (ICRS, the catalogue's J2000 positions, no proper motion) and the galactic centre (l = b = 0) to AltAz with pressure 0 (no refraction); WGS 84 sea level",
        "cases": cases,
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"wrote {len(cases)} cases of {n} stars to {out}")


if __name__ == "__main__":
    main()
