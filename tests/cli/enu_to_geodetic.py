#!/usr/bin/env python3
"""ENU positions (m, about a datum) to WGS84 latitude, longitude and height, for a test's ROS 2 bag
(tests/cli/ros2_bag_play.sh): a conversion written from the textbook formulas, independent of the
GeographicLib that bag play uses the other way, so their agreement checks both.
usage: enu_to_geodetic.py LAT0 LON0 H0 FIXES.jsonl OUT.json
FIXES.jsonl: mcap_dump.cjs lines of GnssFix; OUT.json: [[topic, seq, lat, lon, h, status], ...]."""
import json, math, sys

A = 6378137.0
F = 1 / 298.257223563
E2 = F * (2 - F)


def ecef(lat, lon, h):
    p, l = math.radians(lat), math.radians(lon)
    n = A / math.sqrt(1 - E2 * math.sin(p) ** 2)
    return ((n + h) * math.cos(p) * math.cos(l), (n + h) * math.cos(p) * math.sin(l), (n * (1 - E2) + h) * math.sin(p))


def geodetic(x, y, z):
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1 - E2))
    for _ in range(20):  # fixed point on the latitude: converges to 1e-15 rad in a handful
        n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
        h = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1 - E2 * n / (n + h)))
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return math.degrees(lat), math.degrees(lon), p / math.cos(lat) - n


def main():
    lat0, lon0, h0 = map(float, sys.argv[1:4])
    x0, y0, z0 = ecef(lat0, lon0, h0)
    p, l = math.radians(lat0), math.radians(lon0)
    east = (-math.sin(l), math.cos(l), 0.0)
    north = (-math.sin(p) * math.cos(l), -math.sin(p) * math.sin(l), math.cos(p))
    up = (math.cos(p) * math.cos(l), math.cos(p) * math.sin(l), math.sin(p))
    out = []
    for line in open(sys.argv[4]):
        if not line.strip():
            continue
        r = json.loads(line)
        m = r["msg"]
        e, n_, u = m["x"], m["y"], m["z"]
        X = [c0 + e * ce + n_ * cn + u * cu for c0, ce, cn, cu in zip((x0, y0, z0), east, north, up)]
        status = -1 if not m["valid"] or m["fix_type"] == 0 else (2 if m["fix_type"] == 3 else 0)
        out.append([r["topic"], m["header"]["seq"], *geodetic(*X), status])
    json.dump(out, open(sys.argv[5], "w"))


main()
