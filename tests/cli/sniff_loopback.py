#!/usr/bin/env python3
"""What an eavesdropper on this machine sees of a split run (issue 44): for SECONDS, every UDP
payload on the loopback interface (a raw packet socket: run as root in the test's own network
namespace) and, four times a second, the non-zero pages of every Fast DDS shared-memory file that was
not in /dev/shm before the run (BEFORE: a listing). Written to OUT.wire and OUT.shm (pages kept
once each) for race_attacked.py to search."""
import os
import socket
import struct
import sys
import time

seconds, out, before = float(sys.argv[1]), sys.argv[2], set(open(sys.argv[3]).read().split())
ETH_P_ALL = 0x0003
try:
    sock = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(ETH_P_ALL))
    sock.bind(("lo", 0))
except PermissionError as e:  # no namespace of its own and not root: nothing can be captured here
    print(f"cannot capture on loopback: {e}")
    sys.exit(77)
sock.settimeout(0.05)
wire, pages, seen = bytearray(), bytearray(), set()
packets = 0


def udp_payload(frame):
    # Ethernet (14 bytes, loopback's zero addresses), IPv4, UDP.
    if len(frame) < 42 or frame[12:14] != b"\x08\x00" or frame[23] != 17:
        return None
    ihl = (frame[14] & 0x0F) * 4
    return frame[14 + ihl + 8:]


def snapshot_shm():
    for name in os.listdir("/dev/shm"):
        if not name.startswith("fastrtps_") or name in before:
            continue
        try:
            data = open("/dev/shm/" + name, "rb").read()
        except OSError:
            continue
        for at in range(0, len(data), 4096):
            page = data[at:at + 4096]
            if page.count(0) == len(page) or page in seen:
                continue
            seen.add(page)
            pages.extend(page)


end = time.monotonic() + seconds
next_snapshot = 0.0
while time.monotonic() < end:
    if time.monotonic() >= next_snapshot:
        snapshot_shm()
        next_snapshot = time.monotonic() + 0.25
    try:
        frame = sock.recv(65535)
    except socket.timeout:
        continue
    payload = udp_payload(frame)
    if payload is not None:
        packets += 1
        # Padded to 4 bytes: each payload starts 4-aligned, as its doubles are within it (CDR aligns
        # them to 8 from the serialized payload, which starts 4-aligned in an RTPS message).
        wire.extend(struct.pack("<I", len(payload)) + payload + bytes(-len(payload) % 4))
open(out + ".wire", "wb").write(wire)
open(out + ".shm", "wb").write(pages)
print(f"captured {packets} UDP packets ({len(wire)} bytes) and {len(pages) // 4096} shared-memory pages")
