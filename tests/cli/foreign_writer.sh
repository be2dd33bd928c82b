#!/usr/bin/env bash
# A writer the graph does not name (issues 20, 44): process b of a split run (tests/graphs/
# multiprocess/two_process.json) takes double.in from process a's src.out; `brickyard bag play`
# of a recording of src.out ramping from 1000 sends to the same topic from another participant,
# as a forger would.
# 1. The graph as it is: secured by default (keys made for it), the forger has no identity: not
#    one forged sample reaches b (its sink's largest value stays that of a's ramp), and b never
#    even meets its writer.
# 2. With "security": "off" (warned): b drops every forged sample by its writer's participant
#    name, says which writer it was, and lists it in its summary.
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --one-process --domain "$domain" --quiet --progress 0 --duration 4 --set src.start=1000 \
  --set check.min_count=0 --record "$out/forged.mcap" --record-only src.out > "$out/rec.log" 2>&1 \
  || { cat "$out/rec.log"; echo "FAIL: recording the forger's samples"; exit 1; }
python3 -c "import json,sys; g=json.load(open(sys.argv[1])); g['transport']={'security': 'off'}; json.dump(g, open(sys.argv[2],'w'))" \
  "$graph" "$out/off.json" || exit 1

# Runs a and b of GRAPH by hand, the forger playing into them; b's folder is $out/NAME.
attack() {
  local g=$1 name=$2
  "$by" run "$g" --process b --domain "$domain" --progress 0 --duration 20 --set check.finish_after=200 \
    --set check.max_value=999 --out "$out/$name" > "$out/$name.log" 2>&1 &
  local pid_b=$!
  "$by" run "$g" --process a --domain "$domain" --quiet --progress 0 --duration 30 > "$out/$name.a.log" 2>&1 &
  local pid_a=$!
  sleep 1
  "$by" bag play "$out/forged.mcap" --domain "$domain" > "$out/$name.play.log" 2>&1
  wait $pid_b; local rc=$?
  kill -INT $pid_a 2>/dev/null; wait $pid_a
  [ $rc -eq 0 ] || { cat "$out/$name.log" "$out/$name.play.log"; echo "FAIL: $name: b exited $rc (a forged sample reached its sink?)"; exit 1; }
}

attack "$graph" secured
grep -q "authenticated and their traffic encrypted" "$out/secured.log" || { cat "$out/secured.log"; echo "FAIL: the run did not say it is secured"; exit 1; }
attack "$out/off.json" off
grep -q "warning: .*off.json#/transport/security is \"off\"" "$out/off.log" || { cat "$out/off.log"; echo "FAIL: no warning that security is off"; exit 1; }
grep "writer the graph does not name" "$out/off.log" | head -2
python3 - "$out/secured/summary.json" "$out/off/summary.json" <<'PY' || exit 1
import json, sys
ok = True
for f, secured in zip(sys.argv[1:], (True, False)):
    s = json.load(open(f))
    fw = s.get("foreign_writers", [])
    m = s["nodes"]["check"]["metrics"]
    name = "secured by default" if secured else "security off"
    print(f"{name}: forged writers met: {len(fw)} ({fw[0]['participant'] if fw else '-'}); b's sink: {m['count']:.0f} samples, largest {m['max']:.0f}")
    met = not fw if secured else (fw and fw[0]["input"] == "double.in" and not fw[0]["accepted"])
    ok = ok and bool(met) and m["max"] < 1000 and m["count"] >= 200
sys.exit(0 if ok else 1)
PY
echo "foreign_writer: ok"
