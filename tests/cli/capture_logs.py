#!/usr/bin/env python3
"""capture_logs.py OUT_DIR: GNSS logs with times that move, for the capture tests (the shipped
BESTPOS logs all carry one instant). oem7_20hz.GPS: the first of NovAtel's real BESTPOSA logs
(data/gnss/novatel_BESTPOS.GPS) 20 times, 50 ms apart, each CRC recomputed by NovAtel's CRC-32,
which is first checked to reproduce the real log's own CRC. nmea_midnight.txt: ten GGA sentences
a second apart across midnight (23:59:55 to 00:00:04 UTC), each with its XOR checksum."""
import os
import sys
import zlib


def novatel_crc(text):
    # OEM7's CRC-32 (reflected 0xEDB88320, start 0, no final inversion) is zlib's with its
    # start and final inversions undone.
    return zlib.crc32(text.encode(), 0xFFFFFFFF) ^ 0xFFFFFFFF


def oem7_logs(real):
    body, crc = real[1:].split("*")
    if novatel_crc(body) != int(crc, 16):
        sys.exit(f"FAIL: the CRC here does not reproduce the real log's ({crc})")
    fields = body.split(",")
    start = float(fields[6])  # the header's GPS seconds of week
    out = []
    for k in range(20):
        fields[6] = f"{start + 0.05 * k:.3f}"
        text = ",".join(fields)
        out.append(f"#{text}*{novatel_crc(text):08x}\r\n")
    return "".join(out)


def nmea_logs():
    out = []
    for k in range(10):
        t = (23 * 3600 + 59 * 60 + 55 + k) % 86400
        hhmmss = f"{t // 3600:02d}{t // 60 % 60:02d}{t % 60:02d}.00"
        text = f"GPGGA,{hhmmss},4404.1306,N,12118.8515,W,2,10,0.98,1127.7,M,-19.6,M,0000,0000"
        checksum = 0
        for c in text.encode():
            checksum ^= c
        out.append(f"${text}*{checksum:02X}\r\n")
    return "".join(out)


def main():
    out_dir = sys.argv[1]
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "gnss")
    real = open(os.path.join(data, "novatel_BESTPOS.GPS")).readline().strip()
    with open(os.path.join(out_dir, "oem7_20hz.GPS"), "w", newline="") as f:
        f.write(oem7_logs(real))
    with open(os.path.join(out_dir, "nmea_midnight.txt"), "w", newline="") as f:
        f.write(nmea_logs())


main()
