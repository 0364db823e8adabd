"""Writes stars.csv from d3-celestial's data/stars.8.json (npm package d3-celestial 0.7.35:
`npm pack d3-celestial@0.7.35 && tar xzf d3-celestial-0.7.35.tgz`, then
`python3 extract.py package/data/stars.8.json > stars.csv`): every star of visual magnitude
6.5 or brighter, brightest first (ties by Hipparcos number), right ascension from the GeoJSON
longitude (degrees in [-180, 180]) wrapped into [0, 360)."""

import json
import sys

HEADER = """# The stars of visual magnitude 6.5 and brighter ({n}) from d3-celestial 0.7.35 (npm, BSD-3-Clause,
# (c) 2015 Olaf Frohn; see LICENSE-d3-celestial), its data/stars.8.json, which holds XHIP
# (Anderson and Francis 2012, VizieR V/137D): J2000 right ascension and declination (degrees),
# Johnson V, B-V (empty where the source has none), Hipparcos number. Written by
# `python3 crates/astro/data/extract.py package/data/stars.8.json`.
ra_deg,dec_deg,vmag,bv,hip"""


def main():
    features = json.load(open(sys.argv[1]))["features"]
    rows = []
    for x in features:
        mag = x["properties"]["mag"]
        if mag > 6.5:
            continue
        lon, lat = x["geometry"]["coordinates"]
        bv = x["properties"].get("bv")
        bv = "" if bv in (None, "", "-") else "%.3f" % float(bv)
        rows.append((mag, x["id"], "%.4f" % (lon % 360.0), "%.4f" % lat, "%.2f" % mag, bv))
    rows.sort(key=lambda r: (r[0], r[1]))
    print(HEADER.format(n=len(rows)))
    for r in rows:
        print(f"{r[2]},{r[3]},{r[4]},{r[5]},{r[1]}")


if __name__ == "__main__":
    main()
