#!/usr/bin/env bash
# A graph of 100 000 nodes (issue 20): validated, not a crash (a recursive cycle check overflowed
# the stack) nor a wait (a quadratic scheduling order never finished in 60 s); and a zero-delay
# cycle through all of them refused (exit 2) with a message of bounded length. How long it takes
# is bench_validation's (docs/performance.md), not this test's.
set -u
by=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
python3 - "$out" <<'PY'
import json, sys
n = 100000
def chain(ring):
    if ring:  # transforms in a ring, each stepping on its input: a zero-delay cycle of them all
        nodes = {f"t{i}": {"plugin": "testing.transform"} for i in range(n)}
        return {"nodes": nodes, "wires": [{"from": f"t{i}.out", "to": f"t{(i + 1) % n}.in"} for i in range(n)]}
    nodes = {"src": {"plugin": "testing.scripted_source"}, "check": {"plugin": "testing.assert_sink"}}
    wires = []
    prev = "src"
    for i in range(n - 2):
        nodes[f"t{i}"] = {"plugin": "testing.transform"}
        wires.append({"from": f"{prev}.out", "to": f"t{i}.in"})
        prev = f"t{i}"
    wires.append({"from": f"{prev}.out", "to": "check.in"})
    return {"nodes": nodes, "wires": wires}
json.dump(chain(False), open(sys.argv[1] + "/chain.json", "w"))
json.dump(chain(True), open(sys.argv[1] + "/cycle.json", "w"))
PY
"$by" validate "$out/chain.json" > "$out/chain.log" 2>&1; rc=$?
cat "$out/chain.log"
[ $rc -eq 0 ] && grep -q "valid — 100000 nodes" "$out/chain.log" || { echo "FAIL: the chain of 100 000 nodes: exit $rc"; exit 1; }
"$by" validate "$out/cycle.json" > "$out/cycle.log" 2>&1; rc=$?
head -c 600 "$out/cycle.log"; echo
[ $rc -eq 2 ] || { echo "FAIL: the cycle: exit $rc, expected 2"; exit 1; }
[ "$(wc -c < "$out/cycle.log")" -lt 4000 ] || { echo "FAIL: the cycle's message is $(wc -c < "$out/cycle.log") bytes"; exit 1; }
echo "big_graph: ok"
