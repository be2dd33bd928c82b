#!/usr/bin/env python3
"""udp_receive.py PORT_FILE OUT: receives UDP datagrams on 127.0.0.1 (a port the kernel picks,
written to PORT_FILE once it listens) until, after the first, none has come for 1 s (at most
30 s in all). OUT.bin: their payloads, concatenated; OUT.json: each one's size and
arrival time (the monotonic clock, s). For tests/cli/capture_play.sh."""
import json
import os
import socket
import sys
import time

port_file, out = sys.argv[1], sys.argv[2]
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 8 << 20)  # the kernel caps it at rmem_max
s.bind(("127.0.0.1", 0))
with open(port_file + ".tmp", "w") as f:
    f.write(str(s.getsockname()[1]))
os.replace(port_file + ".tmp", port_file)  # whole, so a reader never sees half a number
sizes, times, payloads = [], [], []
deadline = time.monotonic() + 30
while time.monotonic() < deadline:
    s.settimeout(1 if times else max(0.1, deadline - time.monotonic()))
    try:
        data = s.recv(65536)
    except socket.timeout:
        break
    times.append(time.monotonic())
    sizes.append(len(data))
    payloads.append(data)
open(out + ".bin", "wb").write(b"".join(payloads))
json.dump({"sizes": sizes, "times": times}, open(out + ".json", "w"))
