#!/usr/bin/env bash
# Two hosts (issue 20): two network namespaces joined by a veth pair, 10.77.0.1 (host A) and
# 10.77.0.2 (host B), nothing else but each one's loopback. The main job split over them
# (tests/graphs/multiprocess/ims_race_split.json: the simulator's process on A, the car stack's
# on B) with DDS security on, over UDP on the veth only (transport.interfaces and peers name
# those two addresses; shared memory off: /dev/shm would join them behind the network's back).
# The car must finish its lap with no contact; each process's traffic must have gone out on its
# veth and nowhere else: no packet on either loopback, no packet without a route.
# Run in a fresh network namespace (tests/CMakeLists.txt: unshare -n); exit 77 (skipped) where
# the platform allows no veth.
set -u
by=$(realpath "$1"); graph=$(realpath "$2"); domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
ip link set lo up || exit 77
# Only in a namespace of our own (scripts/netns-run), never on the machine's own network.
[ "$(ip -o link | wc -l)" -eq 1 ] || { echo "SKIP: not in a private network namespace"; exit 77; }
ip link add by_a type veth peer name by_b 2> "$out/veth.err" || { cat "$out/veth.err"; echo "SKIP: no veth here"; exit 77; }
# The identities first: host B starts as soon as its address is up.
"$by" security init "$graph" --out "$out/keys" > "$out/init.log" 2>&1 || { cat "$out/init.log"; fail "security init"; }
# Host B: a child in a network namespace of its own, started once its veth end is configured.
unshare -n bash -c '
  ip link set lo up
  while ! ip -4 addr show by_b 2>/dev/null | grep -q 10.77.0.2; do sleep 0.05; done
  cat /proc/net/dev > "$0/b_dev_before.txt"
  "$1" run "$2" --process stack --domain "$3" --progress 0 --quiet --duration 200 \
    --arg shared_memory=false --arg security="$0/keys" --arg "interfaces=[\"10.77.0.2\"]" --arg "peers=[\"10.77.0.1\"]" \
    --out "$0/stack" > "$0/stack.log" 2>&1
  echo $? > "$0/stack.rc"
  cat /proc/net/dev > "$0/b_dev_after.txt"; cat /proc/net/snmp > "$0/b_snmp.txt"' "$out" "$by" "$graph" "$domain" &
host_b=$!
sleep 0.3
ip link set by_b netns "$host_b" || fail "moving by_b into host B's namespace"
ip addr add 10.77.0.1/24 dev by_a && ip link set by_a up || fail "configuring by_a"
nsenter -t "$host_b" -n sh -c 'ip addr add 10.77.0.2/24 dev by_b && ip link set by_b up' || fail "configuring by_b"
cat /proc/net/dev > "$out/a_dev_before.txt"
"$by" run "$graph" --process sim --domain "$domain" --progress 0 --quiet --set referee.laps=1 --duration 200 \
  --arg shared_memory=false --arg security="$out/keys" --arg 'interfaces=["10.77.0.1"]' --arg 'peers=["10.77.0.2"]' \
  --out "$out/sim" > "$out/sim.log" 2>&1
rc=$?
cat /proc/net/dev > "$out/a_dev_after.txt"; cat /proc/net/snmp > "$out/a_snmp.txt"
kill -INT "$(pgrep -f -- "--process stack --domain $domain" | head -1)" 2> /dev/null
wait "$host_b"
tail -2 "$out/sim.log"
[ $rc -eq 0 ] || { tail -5 "$out/stack.log"; fail "host A's run exited $rc"; }
python3 - "$out" <<'PY' || exit 1
import json, sys
d = sys.argv[1]
def dev(f):
    out = {}
    for line in open(f).read().splitlines()[2:]:
        name, rest = line.split(":", 1)
        v = rest.split()
        out[name.strip()] = (int(v[1]), int(v[9]))  # packets received, sent
    return out
def no_route(f):
    lines = [l.split() for l in open(f) if l.startswith("Ip:")]
    return int(lines[1][lines[0].index("OutNoRoutes")])
sim = json.load(open(d + "/sim/summary.json"))
ref, car = sim["nodes"]["referee"]["metrics"], sim["nodes"]["car"]["metrics"]
ok = sim["result"] == "success" and ref.get("laps_completed", 0) >= 1 and ref.get("wall_contacts", 0) == 0 and ref.get("obstacles_hit", 0) == 0
print(f"host A: {sim['result']}: {sim.get('reason')}; laps {ref.get('laps_completed')}, wall contacts {ref.get('wall_contacts')}, "
      f"pylons hit {ref.get('obstacles_hit')}, "
      f"longest command gap {car['longest_command_gap_s']:.3f} s")
for host, nic in (("a", "by_a"), ("b", "by_b")):
    before, after = dev(f"{d}/{host}_dev_before.txt"), dev(f"{d}/{host}_dev_after.txt")
    sent = {n: after[n][1] - before.get(n, (0, 0))[1] for n in after}
    nr = no_route(f"{d}/{host}_snmp.txt")
    print(f"host {host.upper()}: packets sent {sent}, without a route {nr}")
    ok = ok and sent.get(nic, 0) > 1000 and sent.get("lo", 0) == 0 and nr == 0 and set(sent) <= {"lo", nic}
sys.exit(0 if ok else 1)
PY
echo "two_hosts: ok"
