#!/usr/bin/env python3
"""race_attacked.sh's verdicts. The eavesdropper: the commands an observer read (PREFIX.commands,
JSON lines) as the 8 bytes each double is sent as (CDR little-endian), searched for at every
4-aligned place of what was captured (PREFIX.wire, PREFIX.shm; the captures then removed). The
forger: how many writers fed the car's commands (PREFIX/sim/summary.json's remote_inputs): a
second is the forger's, its samples taken (counted by writer, so that commands lost under load or
a run ended early by the forged ones cannot hide it); the commands the car received against those
the stack's manager sent are printed beside. Doubles with more than four zero bytes (0, 1, round numbers)
are left out: they could be anything's. SECURED must show none, OFF some."""
import json
import os
import struct
from array import array
import sys


def windows_holding(blob, ns):
    """Which of the needles (as integers) sit 4-aligned in blob: where a double of a CDR sample
    can start in a payload or a shared-memory page (race_attacked.sh found them there in
    plaintext); the two 8-byte strides read as integers and looked up in C."""
    found = set()
    for off in (0, 4):
        words = array("Q")
        words.frombytes(blob[off:off + (len(blob) - off) // 8 * 8])
        found |= ns.intersection(words)
    return len(found)


def needles(prefix):
    found = set()
    for line in open(prefix + ".commands"):
        line = line.strip()
        if not line.startswith("{"):
            continue
        c = json.loads(line)
        for k in ("steer", "throttle", "brake", "target_speed"):
            b = struct.pack("<d", float(c[k]))
            if b.count(0) <= 4:
                found.add(struct.unpack("<Q", b)[0])
    return found


def hits(prefix, ns):
    wire, shm = open(prefix + ".wire", "rb").read(), open(prefix + ".shm", "rb").read()
    os.remove(prefix + ".wire"), os.remove(prefix + ".shm")  # hundreds of MB over UDP
    return windows_holding(wire, ns), windows_holding(shm, ns), len(wire), len(shm)


def command_writers(prefix):
    """The writers that fed the car's commands, and the commands it received past those the
    stack's manager sent."""
    sim = json.load(open(prefix + "/sim/summary.json"))
    manager = json.load(open(prefix + "/stack/summary.json"))["nodes"]["manager"]["outputs"]["command"]
    writers = sim["remote_inputs"]["car.command"]["writers_heard"]
    return writers, sim["nodes"]["car"]["inputs"]["command"]["received"] - manager["published"]


ok = True
for prefix, secured in ((sys.argv[1], True), (sys.argv[2], False)):
    writers, beyond = command_writers(prefix)
    ns = needles(prefix)
    on_wire, in_shm, wire_bytes, shm_bytes = hits(prefix, ns)
    name = ("secured by default" if secured else "security off") + (", UDP only" if prefix.endswith("false") else ", shared memory")
    print(f"{name}: {len(ns)} distinctive command values read by the observer; found {on_wire} in {wire_bytes} bytes on the wire, "
          f"{in_shm} in {shm_bytes} bytes of shared memory")
    print(f"{name}: {writers} writer(s) fed the car's commands; it received {beyond:+d} beyond those the stack sent "
          f"(the forger played 6 s of them)")
    if secured and writers != 1:
        print(f"FAIL: {name}: forged commands reached the car")
        ok = False
    elif not secured and writers < 2:
        print(f"FAIL: {name}: the forger's commands were not taken: this check cannot see them")
        ok = False
    if len(ns) < 100:
        print(f"FAIL: {name}: the observer read too few commands to search for")
        ok = False
    elif secured and on_wire + in_shm > 0:
        print(f"FAIL: {name}: command values readable by anyone on this machine")
        ok = False
    elif not secured and on_wire + in_shm == 0:
        print(f"FAIL: {name}: no plaintext command found: this search cannot see one")
        ok = False
sys.exit(0 if ok else 1)
