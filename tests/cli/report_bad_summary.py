#!/usr/bin/env python3
"""brickyard report on hand-edited summaries (issue 20): each is drawn (exit 0) or refused naming
the file (exit 2) -- never a crash (a signal), never exit 1 without a word.
usage: report_bad_summary.py BRICKYARD GRAPH DOMAIN OUT"""
import copy, json, os, shutil, subprocess, sys

by, graph, domain, out = sys.argv[1:5]
shutil.rmtree(out, ignore_errors=True)
run = subprocess.run([by, "run", graph, "--domain", domain, "--quiet", "--progress", "0", "--out", out + "/run"], capture_output=True, text=True)
if run.returncode != 0:
    sys.exit(f"FAIL: the run: {run.stderr[-500:]}")
base = json.load(open(out + "/run/summary.json"))
node = next(iter(base["nodes"]))
cases = {
    "nodes a list": lambda s: s.update(nodes=[]),
    "a node a number": lambda s: s.update(nodes={"x": 3}),
    "recording a string": lambda s: s.update(recording="x"),
    "recording file a number": lambda s: s.update(recording={"file": 3}),
    "recording /etc/passwd": lambda s: s.update(recording={"file": "/etc/passwd"}),
    "recording up and out": lambda s: s.update(recording={"file": "../../../../etc/passwd"}),
    "sim time a string": lambda s: s.update(sim_time_s="x"),
    "result null": lambda s: s.update(result=None),
    "metrics a list": lambda s: s["nodes"][node].update(metrics=[1, 2]),
    "a metric a string": lambda s: s["nodes"][node].setdefault("metrics", {}).update(lap_times_s="x"),
    "huge and null values": lambda s: s["nodes"][node].setdefault("metrics", {}).update(lap_times_s=[1e308, -1e308, None]),
    "negative wall time": lambda s: s.update(wall_time_s=-1),
    "empty": lambda s: s.clear(),
}
texts = {name: None for name in cases}
texts["truncated"] = '{"nodes": '
texts["not json"] = "\x00\x01\x02"
failed = []
for name in texts:
    d = out + "/case"
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(out + "/run", d)
    with open(d + "/summary.json", "w") as f:
        if name in cases:
            s = copy.deepcopy(base)
            cases[name](s)
            json.dump(s, f)
        else:
            f.write(texts[name])
    r = subprocess.run([by, "report", d], capture_output=True, text=True, timeout=300)
    said = (r.stderr.strip().splitlines() or [""])[-1]
    ok = r.returncode == 0 or (r.returncode == 2 and said.startswith("brickyard-report: "))
    print(f"{name}: exit {r.returncode} {said[:120]}")
    if not ok:
        failed.append(name)
if failed:
    sys.exit("FAIL: " + ", ".join(failed))
print(f"report: {len(texts)} bad summaries, each drawn or refused naming the file")
