#!/usr/bin/env python3
"""capture_info.py BRICKYARD DATA OUT: `brickyard capture info --json` on every shipped capture
(docs/drivers.md, "Captures: info and play"), held against the captures read here on their own
(records, datagrams per destination port, time span: capture_check.read_pcap; BESTPOSA logs
counted by their lines) and against the numbers the drivers' unit tests state for the decoders
(plugins/drivers/tests/test_ouster.cpp and test_drivers.cpp)."""
import json
import os
import subprocess
import sys

from capture_check import read_pcap

by, data, out = sys.argv[1:4]
failures = []

# pcap: (metadata, lidar packets, complete frames, incomplete frames, missing columns), test_ouster.cpp's kCaptures.
OUSTER = {
    "OS-0-32-U1_v2.2.0_1024x10.pcap": ("OS-0-32-U1_v2.2.0_1024x10.json", 64, 1, 0, 0),
    "OS-1-32-G_v2.1.1_1024x10.pcap": ("OS-1-32-G_v2.1.1_1024x10.json", 64, 1, 0, 0),
    "OS-2-128-U1_v2.3.0_1024x10.pcap": ("OS-2-128-U1_v2.3.0_1024x10.json", 64, 1, 0, 0),
    "OS-1-128_v2.3.0_1024x10_lb_n3.pcap": ("OS-1-128_v2.3.0_1024x10.json", 192, 3, 0, 0),
    "crc_test.pcap": ("crc_test.json", 34, 1, 1, 480),
}


def info(*args):
    r = subprocess.run([by, "capture", "info", *args, "--json"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: capture info {' '.join(args)}: exit {r.returncode}: {r.stderr}")
    return json.loads(r.stdout)


def close(got, want):
    """Equal, numbers to a microsecond (the times: doubles of seconds)."""
    if isinstance(want, float):
        return isinstance(got, (int, float)) and abs(got - want) < 1e-6
    if isinstance(want, list):
        return isinstance(got, list) and len(got) == len(want) and all(map(close, got, want))
    return got == want


def expect(what, got, want):
    ok = close(got, want)
    print(f"{'ok  ' if ok else 'FAIL'} {what}: {got}" + ("" if ok else f", expected {want}"))
    if not ok:
        failures.append(what)


def check_pcap(name, meta, lidar, complete, incomplete, missing):
    path = os.path.join(data, "lidar_packets", name)
    datagrams = read_pcap(path)
    j = info(path, "--metadata", os.path.join(data, "lidar_packets", meta))
    expect(f"{name} records", j["counters"]["records"], len(datagrams))  # every record is a datagram here
    expect(f"{name} datagrams", j["udp"]["datagrams"], len(datagrams))
    expect(f"{name} refused", j["counters"]["refused"], 0)
    ports = {}
    for _, port, payload in datagrams:
        ports.setdefault(port, [0, 0])
        ports[port][0] += 1
        ports[port][1] += len(payload)
    expect(f"{name} ports", {p["port"]: [p["datagrams"], p["bytes"]] for p in j["ports"]}, ports)
    times = [d[0] for d in datagrams]
    expect(f"{name} first", j["udp"]["first_s"], min(times))
    expect(f"{name} span", j["udp"]["span_s"], max(times) - min(times))
    c = j["ouster"]["counters"]
    expect(f"{name} lidar packets decoded", [c["packets"], c["decoded"], c["refused"]], [lidar, lidar, 0])
    expect(f"{name} frames", [c["frames_complete"], c["frames_incomplete"], c["missing_columns"]], [complete, incomplete, missing])
    expect(f"{name} frames listed", len(j["ouster"]["frames"]), complete + incomplete)


def check_gnss():
    path = os.path.join(data, "gnss", "novatel_BESTPOS.GPS")
    j = info(path)
    lines = sum(1 for line in open(path) if line.startswith("#BESTPOSA,"))
    expect("BESTPOS protocol", j["protocol"], "novatel_oem7")
    expect("BESTPOS messages", j["messages"], {"BESTPOSA": lines})
    expect("BESTPOS refused", j["counters"]["refused"], 0)
    expect("BESTPOS time", [j["first_gps_week"], j["first_gps_seconds_of_week"], j["span_s"]], [1984, 450849.5, 0.0])
    # The vendor's hostile logs: each refused once, as oversized, by the decoder of its framing.
    j = info(os.path.join(data, "gnss", "novatel_ascii_sync_error.ASC"))
    expect("ASC sync error", [j["protocol"], j["counters"]["oversized"], j["counters"]["refused"], j["counters"]["skipped_bytes"]],
           ["novatel_oem7", 1, 1, 120865])
    j = info(os.path.join(data, "gnss", "nmea_sync_error.txt"))
    expect("NMEA sync error", [j["protocol"], j["counters"]["oversized"], j["counters"]["refused"], j["counters"]["skipped_bytes"]],
           ["nmea0183", 1, 1, 307])
    # Logs whose times move (capture_logs.py): 20 logs 50 ms apart; ten GGA across midnight.
    j = info(os.path.join(out, "oem7_20hz.GPS"))
    expect("OEM7 20 Hz", [j["messages"], j["timed"], j["span_s"]], [{"BESTPOSA": 20}, 20, 0.95])
    j = info(os.path.join(out, "nmea_midnight.txt"))
    expect("NMEA over midnight", [j["protocol"], j["messages"], j["first_s"], j["span_s"]],
           ["nmea0183", {"GPGGA": 10}, 86395.0, 9.0])


for name, numbers in OUSTER.items():
    check_pcap(name, *numbers)
check_gnss()
sys.exit(f"FAIL: {', '.join(failures)}" if failures else 0)
