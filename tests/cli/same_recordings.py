#!/usr/bin/env python3
# Two recordings hold the same samples: the same topics, times and bytes, in the same order.
# usage: same_recordings.py A B (exit 0 when they do and are not empty). SQLite (.db3) is read
# here; MCAP by Foxglove's @mcap/core (tests/clients/mcap_check.cjs), which digests each topic
# and the whole file's order (the files' bytes differ: chunks close on the wall clock too).
import hashlib, json, os, sqlite3, subprocess, sys
def digest(f):
    if f.endswith(".mcap"):
        check = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "clients", "mcap_check.cjs")
        j = json.loads(subprocess.run(["node", check, f], check=True, capture_output=True, text=True).stdout)
        return j["messages"], hashlib.sha256(json.dumps([j["order_sha256"], j["topics"]], sort_keys=True).encode()).hexdigest()
    h, n = hashlib.sha256(), 0
    for row in sqlite3.connect(f).execute("SELECT topic_id, timestamp, data FROM messages ORDER BY id"):
        h.update(repr(row[:2]).encode()); h.update(row[2]); n += 1
    return n, h.hexdigest()
a, b = digest(sys.argv[1]), digest(sys.argv[2])
print(f"recordings: {a[0]} samples each, sha256 {a[1][:16]}" if a == b else f"recordings differ: {a} {b}")
sys.exit(0 if a == b and a[0] > 0 else 1)
