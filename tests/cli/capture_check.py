#!/usr/bin/env python3
"""capture_check.py pcap PCAP RECEIVED PLAY_LOG RATE | log LOG RECEIVED PLAY_LOG RATE SPAN_S
DATAGRAMS: what udp_receive.py got from `brickyard capture play` (tests/cli/capture_play.sh),
held against the capture read here on its own. pcap: the payloads of the UDP datagrams to port
7502, in order, byte for byte, one datagram each; log: the file's bytes, whole, in DATAGRAMS
datagrams. The pace: the recorded span (the pcap's record times; the log's SPAN_S) over RATE is
what the player's summary says the pass took (no less: nothing goes before it is due; a little
more: its last wake-up's lateness), and, on the receiver's own clock, at least half of it."""
import json
import re
import struct
import sys


def read_pcap(path):
    """Each UDP datagram of a classic little-endian pcap of Ethernet frames of unfragmented
    UDP/IPv4 (the shipped captures: asserted) as (time s, destination port, payload)."""
    b = open(path, "rb").read()
    assert struct.unpack_from("<I", b, 0)[0] == 0xA1B2C3D4 and struct.unpack_from("<I", b, 20)[0] == 1
    at, out = 24, []
    while at + 16 <= len(b):
        sec, usec, captured, _ = struct.unpack_from("<IIII", b, at)
        frame = b[at + 16:at + 16 + captured]
        at += 16 + captured
        ip = frame[14:]
        assert struct.unpack_from(">H", frame, 12)[0] == 0x0800 and ip[9] == 17
        assert struct.unpack_from(">H", ip, 6)[0] & 0x3FFF == 0, "a fragment: not read here"
        udp = ip[(ip[0] & 15) * 4:]
        out.append((sec + usec * 1e-6, struct.unpack_from(">H", udp, 2)[0], udp[8:struct.unpack_from(">H", udp, 4)[0]]))
    return out


def pcap_payloads(path, port):
    datagrams = [d for d in read_pcap(path) if d[1] == port]
    return [d[2] for d in datagrams], datagrams[-1][0] - datagrams[0][0]


def check_pace(arrivals, play_log, recorded_span, rate):
    want = recorded_span / rate
    took = float(re.search(r"whole pass(?:es)? in ([0-9.]+) s", open(play_log).read()).group(1))
    got = arrivals[-1] - arrivals[0]
    print(f"recorded {recorded_span:.3f} s at rate {rate}: {want:.3f} s; the player took {took:.3f} s, arrivals spanned {got:.3f} s")
    if not want - 1e-3 <= took <= want + max(0.1, want / 2):
        sys.exit("FAIL: the player did not keep the recorded pace")
    if not 0.5 * want <= got <= took + 1.0:
        sys.exit("FAIL: the datagrams did not arrive at the recorded pace")


def main():
    kind, capture, received, play_log, rate = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5])
    got = json.load(open(received + ".json"))
    data = open(received + ".bin", "rb").read()
    if kind == "pcap":
        payloads, span = pcap_payloads(capture, 7502)
        print(f"{len(got['sizes'])} datagrams received, {len(payloads)} in the capture to 7502")
        if got["sizes"] != [len(p) for p in payloads] or data != b"".join(payloads):
            sys.exit("FAIL: the datagrams received are not the capture's")
    else:
        span, datagrams = float(sys.argv[6]), int(sys.argv[7])
        print(f"{len(got['sizes'])} datagrams received, {len(data)} bytes")
        if data != open(capture, "rb").read() or len(got["sizes"]) != datagrams:
            sys.exit(f"FAIL: not the log's bytes in {datagrams} datagrams")
    check_pace(got["times"], play_log, span, rate)


if __name__ == "__main__":
    main()
