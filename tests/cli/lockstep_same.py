#!/usr/bin/env python3
# A split run on the sim clock (its processes in lockstep) is the run in one process: the same
# verdict and sim time in every process's summary, and the processes' nodes together the one
# process's nodes, every step count, metric (digests of every sample a sink took), input's
# received/dropped/max gap and output's published the same; their recordings together the one
# recording, topic for topic (count and a SHA-256 over times and bytes, by @mcap/core).
# usage: lockstep_same.py ONE_DIR SPLIT_DIR (SPLIT_DIR/PROCESS/summary.json for each process)
import json, os, subprocess, sys

one_dir, split_dir = sys.argv[1], sys.argv[2]
fail = []
one = json.load(open(os.path.join(one_dir, "summary.json")))
procs = sorted(p for p in os.listdir(split_dir) if os.path.isfile(os.path.join(split_dir, p, "summary.json")))
if len(procs) < 2: sys.exit(f"FAIL: {split_dir} holds {len(procs)} process summaries")
nodes, stale = {}, []
for p in procs:
    s = json.load(open(os.path.join(split_dir, p, "summary.json")))
    for k in ("result", "reason", "sim_time_s", "seed"):
        if s.get(k) != one.get(k): fail.append(f"process {p}: {k} {s.get(k)!r}, one process {one.get(k)!r}")
    for n, v in s["nodes"].items():
        if n in nodes: fail.append(f"node {n} in two processes")
        nodes[n] = v
    stale += s.get("stale_inputs", [])
if set(nodes) != set(one["nodes"]): fail.append(f"nodes {sorted(nodes)} against {sorted(one['nodes'])}")
for n, v in one["nodes"].items():
    if n in nodes and nodes[n] != v: fail.append(f"node {n}: {json.dumps(nodes[n], sort_keys=True)} against one process's {json.dumps(v, sort_keys=True)}")
if sorted(json.dumps(x, sort_keys=True) for x in stale) != sorted(json.dumps(x, sort_keys=True) for x in one.get("stale_inputs", [])):
    fail.append("stale inputs differ")

check = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "clients", "mcap_check.cjs")
def topics(f):
    # The wires. The scene (/tf, /scene/*, Foxglove's schemas) is each process's drawing of the
    # wires it has: split, the truth's transform in one recording and the estimate's in another.
    t = json.loads(subprocess.run(["node", check, f], check=True, capture_output=True, text=True).stdout)["topics"]
    return {k: v for k, v in t.items() if not v["schema"].startswith("foxglove.")}
rec = os.path.join(one_dir, "recording.mcap")
samples = 0
if os.path.exists(rec):
    want, got = topics(rec), {}
    for p in procs:
        for t, v in topics(os.path.join(split_dir, p, "recording.mcap")).items():
            if t in got: fail.append(f"topic {t} recorded by two processes")
            got[t] = v
    if got != want:
        for t in sorted(set(want) | set(got)):
            if want.get(t) != got.get(t): fail.append(f"recording: topic {t}: {got.get(t)} against one process's {want.get(t)}")
    samples = sum(v["count"] for v in want.values())
for f in fail: print("FAIL:", f)
if fail: sys.exit(1)
print(f"the same run in {len(procs)} processes as in one: {len(nodes)} nodes, result {one['result']}, sim {one['sim_time_s']} s, {samples} recorded samples")
