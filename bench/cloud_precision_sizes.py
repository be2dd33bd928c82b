#!/usr/bin/env python3
"""What compact clouds save (docs/recording.md, --record-cloud-precision): one recorded LiDAR topic
(SQLite, .db3) compressed by the zstd tool at level 3 as float32 (what a recording holds today),
as whole millimetres, and differenced point to point at 1, 2, 5 and 10 mm, as int32 and as
QuantizedPointCloud holds them (zigzag-coded, in byte planes), intensity in 256 steps.
usage: build/bin/brickyard run configs/ims_race.json --duration 20 --record /tmp/c20.db3 --record-only lidar_front.cloud
       /usr/bin/python3 bench/cloud_precision_sizes.py /tmp/c20.db3   (needs numpy and the zstd tool)"""
import os
import sqlite3
import struct
import subprocess
import sys
import tempfile

import numpy as np


def parse(b):  # a PointCloud's CDR (little endian, after its 4-byte encapsulation)
    o = 4 + 12
    o += 4 + struct.unpack_from("<I", b, o)[0]
    o += 1
    o = 4 + (((o - 4) + 7) & ~7) + 48
    arrs = []
    for _ in range(4):
        o = 4 + (((o - 4) + 3) & ~3)
        n = struct.unpack_from("<I", b, o)[0]
        o += 4
        arrs.append(np.frombuffer(b, dtype="<f4", count=n, offset=o))
        o += 4 * n
    return arrs


def zsize(data):
    with tempfile.TemporaryDirectory() as d:
        raw, z = os.path.join(d, "x.bin"), os.path.join(d, "x.zst")
        open(raw, "wb").write(data)
        subprocess.run(["zstd", "-q", "-f", "-3", raw, "-o", z], check=True)
        return os.path.getsize(z)


blobs = [r[0] for r in sqlite3.connect(sys.argv[1]).execute("SELECT data FROM messages ORDER BY id")]
clouds = [parse(b) for b in blobs]
print(f"{len(clouds)} frames, median {int(np.median([len(c[0]) for c in clouds]))} points")
exact = zsize(b"".join(blobs))
print(f"float32 (as recorded)      {exact / 1e6:7.1f} MB  1.00")


def intensity(i):
    top = max(float(np.max(i)), 0.0) if len(i) else 0.0
    return (np.round(np.clip(i / top, 0, 1) * 255) if top > 0 else np.zeros(len(i))).astype("u1").tobytes()


mm = b"".join(b"".join(np.round(c[k] / 0.001).astype("<i4").tobytes() for k in range(3)) + intensity(c[3]) for c in clouds)
size = zsize(mm)
print(f"whole mm, int32            {size / 1e6:7.1f} MB  {size / exact:.2f}")
def planes(d):  # zigzag, then every point's low byte, then every point's next byte, ...
    zig = ((d.astype("<i4") << 1) ^ (d.astype("<i4") >> 31)).astype("<u4")
    return zig.view("u1").reshape(-1, 4).T.tobytes()


for q in (0.001, 0.002, 0.005, 0.01):
    steps = [[np.diff(np.round(c[k] / q).astype("<i8"), prepend=0).astype("<i4") for k in range(3)] for c in clouds]
    size = zsize(b"".join(b"".join(d.tobytes() for d in s) + intensity(c[3]) for s, c in zip(steps, clouds)))
    packed = zsize(b"".join(b"".join(planes(d) for d in s) + intensity(c[3]) for s, c in zip(steps, clouds)))
    print(f"differenced, {q * 1000:4.0f} mm, int32  {size / 1e6:7.1f} MB  {size / exact:.2f}   "
          f"zigzag byte planes {packed / 1e6:7.1f} MB  {packed / exact:.2f}")
