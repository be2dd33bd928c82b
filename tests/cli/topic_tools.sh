#!/usr/bin/env bash
# `brickyard topic list | echo | hz` against a running graph, over DDS from another process
# (docs/live.md): the graph's wires listed with their types; a wire's samples as JSON lines,
# decoded by its IDL, each what the graph computed; its rate. A topic nobody writes, a domain
# nobody is on: exit 1 with the reason. A verb or topic that is not one: exit 2.
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
# The real-clock chain at 50 Hz: src counts, double doubles it.
"$by" run "$graphs/real_clock.json" --domain "$domain" --quiet --progress 0 --duration 10 --set check.min_count=1 > "$out/run.log" 2>&1 &
pid=$!
"$by" topic list --domain "$domain" --duration 2 > "$out/list.txt" 2> "$out/list.err" || { cat "$out/list.err"; echo "FAIL: topic list"; exit 1; }
cat "$out/list.txt"
grep -q "^src.out  *brickyard::msgs::" "$out/list.txt" && grep -q "^double.out  *brickyard::msgs::" "$out/list.txt" \
  || { echo "FAIL: topic list lacks the graph's wires"; exit 1; }
"$by" topic echo double.out --domain "$domain" --count 5 > "$out/echo.jsonl" 2> "$out/echo.err" || { cat "$out/echo.err"; echo "FAIL: topic echo"; exit 1; }
"$by" topic hz src.out --domain "$domain" --duration 3 > "$out/hz.txt" 2> "$out/hz.err" || { cat "$out/hz.err"; echo "FAIL: topic hz"; exit 1; }
wait $pid || { cat "$out/run.log"; echo "FAIL: the graph"; exit 1; }
python3 - "$out/echo.jsonl" "$out/hz.txt" <<'PY' || exit 1
import json, re, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
seqs = [l["header"]["seq"] for l in lines]
print(f"topic echo double.out: {len(lines)} samples, seq {seqs}, first {json.dumps(lines[0])}")
hz = open(sys.argv[2]).read().strip().splitlines()
# The source's rate by the median interval: samples written while the reader was still being
# matched arrive together once it is (a CI run read 150 samples over 2.66 s, 56 Hz by count and
# span, with a median interval of 0.0200 s).
rate = 1.0 / float(re.search(r"median ([0-9.]+) s", hz[-1]).group(1))
print(f"topic hz src.out: {hz[-1]}")
ok = len(lines) == 5 and seqs == sorted(seqs) and len(set(seqs)) == 5
ok = ok and all(l["value"] == 2 * l["header"]["seq"] for l in lines)  # src counts; double doubles
ok = ok and 45 <= rate <= 55
sys.exit(0 if ok else 1)
PY
expect() {  # code, pattern, then the command
  code=$1; pat=$2; shift 2
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq "$code" ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected $code: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
expect 1 "no writer heard on domain $domain within 1.0 s" "$by" topic list --domain "$domain" --duration 1
expect 1 "no writer of nobody.out on domain $domain within 5.0 s" "$by" topic echo nobody.out --domain "$domain"
expect 2 "topic echo: expected a topic NODE.PORT, not 'nodot'" "$by" topic echo nodot --domain "$domain"
expect 2 "topic frob: unknown" "$by" topic frob --domain "$domain"
expect 2 "--count 0: expected a whole number of samples" "$by" topic echo a.b --count 0
echo "topic_tools: ok"
