#!/usr/bin/env bash
# DDS security from the graph (issue 20, docs/security.md): `brickyard security init` makes the
# folder; the split graph (tests/graphs/multiprocess/two_process.json) runs with it, its processes
# a and b authenticated, b's input from a signed. Meanwhile, as attackers would on this machine:
# a forger with no identity, a reader with none, a forger with b's stolen certificate and key
# writing a's topic, the same with permissions it signed itself. b accepts writers the graph does
# not name (transport.foreign_writers accept), so only security stands between them and its sink:
# no forged sample may reach it (its largest value stays below 2000, the forger's 1000 doubled), nobody without
# an identity may read. The observer identity reads. Bad security files: exit 2, named.
# Without BY_PROTECT, security init's default, which must encrypt (issue 44: a control value never
# readable on the wire); BY_PROTECT=sign: the same with every message signed, not encrypted.
set -u
protect=${BY_PROTECT:-}
by=$(realpath "$1"); graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
python3 - "$graph" "$out" <<'PY'
import json, sys
g = json.load(open(sys.argv[1]))
json.dump(g, open(sys.argv[2] + "/plain.json", "w"), indent=1)
g["transport"] = {"security": "keys", "foreign_writers": "accept"}
json.dump(g, open(sys.argv[2] + "/secure.json", "w"), indent=1)
PY
"$by" security init "$out/secure.json" --out "$out/keys" ${protect:+--protect "$protect"} > "$out/init.log" 2>&1 || { cat "$out/init.log"; fail "security init"; }
cat "$out/init.log"
kind=$( [ "$protect" = sign ] && echo SIGN || echo ENCRYPT )
grep -q "<rtps_protection_kind>$kind</rtps_protection_kind>" "$out/keys/governance.xml" \
  || fail "the governance does not protect every message with $kind (--protect ${protect:-not given})"
for id in a b observer; do
  for f in cert.pem key.pem permissions.p7s permissions.xml; do [ -s "$out/keys/$id/$f" ] || fail "keys/$id/$f missing"; done
  [ "$(stat -c %a "$out/keys/$id/key.pem")" = 600 ] || fail "keys/$id/key.pem is not 0600"
  openssl smime -verify -in "$out/keys/$id/permissions.p7s" -CAfile "$out/keys/permissions_ca.pem" -text > /dev/null 2>&1 \
    || fail "openssl does not verify keys/$id/permissions.p7s"
done
[ "$(stat -c %a "$out/keys/ca_key.pem")" = 600 ] || fail "ca_key.pem is not 0600"
# a reads no wire: only b's end record (how b's run ended, exec/peer_ends.hpp).
grep -q "<topic>brickyard/src/out</topic>" "$out/keys/a/permissions.xml" \
  && [ "$(grep -A3 "<subscribe>" "$out/keys/a/permissions.xml" | grep -o "<topic>[^<]*</topic>" | tr '\n' ' ')" = "<topic>brickyard_end/b</topic> " ] \
  || fail "a's permissions: publish src.out, subscribe to b's end record alone"
grep -A3 "<subscribe>" "$out/keys/b/permissions.xml" | grep -q "brickyard/src/out" || fail "b's permissions lack subscribing src.out"

# The forger's samples: src.out ramping from 1000, recorded from the graph run without security.
"$by" run "$out/plain.json" --one-process --domain "$domain" --quiet --progress 0 --duration 4 --set src.start=1000 \
  --set check.min_count=0 --record "$out/forged.mcap" --record-only src.out > "$out/rec.log" 2>&1 || { cat "$out/rec.log"; fail "recording the forger's samples"; }

# The attacker's own CA, signing permissions that let b's stolen identity write a's topic.
mkdir -p "$out/stolen/b"
cp "$out/keys/identity_ca.pem" "$out/stolen/"
cp "$out/keys/b/cert.pem" "$out/keys/b/key.pem" "$out/stolen/b/"
openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -keyout "$out/stolen/ca_key.pem" -out "$out/stolen/permissions_ca.pem" \
  -days 30 -subj "/CN=attacker" > /dev/null 2>&1 || fail "openssl: the attacker's CA"
sed 's#<publish>#<publish><topics><topic>*</topic></topics></publish><publish>#' "$out/keys/b/permissions.xml" > "$out/stolen/b/permissions.xml"
for doc in governance b/permissions; do
  src="$out/keys/$doc.xml"; [ "$doc" = b/permissions ] && src="$out/stolen/b/permissions.xml"
  openssl smime -sign -in "$src" -text -out "$out/stolen/$doc.p7s" -signer "$out/stolen/permissions_ca.pem" -inkey "$out/stolen/ca_key.pem" \
    || fail "openssl: signing $doc"
done

cd "$out"
"$by" run secure.json --process b --domain "$domain" --progress 0 --duration 40 --set check.finish_after=900 \
  --set check.max_value=1999 --out "$out/b" > "$out/b.log" 2>&1 &
pid_b=$!
"$by" run secure.json --process a --domain "$domain" --quiet --progress 0 --duration 45 > "$out/a.log" 2>&1 &
pid_a=$!
sleep 3
"$by" bag play forged.mcap --domain "$domain" > "$out/play_none.log" 2>&1
echo "forger without identity: bag play exit $?"
"$by" topic echo double.out --domain "$domain" --duration 3 > "$out/echo_none.log" 2>&1 && fail "a reader without identity read double.out: $(head -2 "$out/echo_none.log")"
echo "reader without identity: $(tail -1 "$out/echo_none.log")"
"$by" topic echo double.out --domain "$domain" --count 3 --security keys > "$out/echo_observer.log" 2>&1 || { cat "$out/echo_observer.log"; fail "the observer identity could not read double.out"; }
echo "observer: $(head -1 "$out/echo_observer.log")"
"$by" bag play forged.mcap --domain "$domain" --security keys --identity b > "$out/play_b.log" 2>&1 && fail "bag play as b wrote a's topic"
echo "b's identity, its own permissions: $(grep -o 'cannot create a writer[^)]*)' "$out/play_b.log" | head -1)"
grep -q "cannot create a writer on brickyard/src/out" "$out/play_b.log" || { cat "$out/play_b.log"; fail "bag play as b: not refused by its permissions"; }
"$by" bag play forged.mcap --domain "$domain" --security stolen --identity b > "$out/play_stolen.log" 2>&1
echo "b's identity, permissions signed by another CA: bag play exit $?"
wait $pid_b; rc=$?
kill -INT $pid_a 2>/dev/null; wait $pid_a
[ $rc -eq 0 ] || { tail -5 "$out/b.log"; fail "b exited $rc (a forged sample reached its sink?)"; }
python3 - "$out/b/summary.json" <<'PY' || exit 1
import json, sys
m = json.load(open(sys.argv[1]))["nodes"]["check"]["metrics"]
print(f"b's sink: {m['count']:.0f} samples from a, largest {m['max']:.0f} (a forged one is 2000 or more)")
sys.exit(0 if m["max"] < 2000 and m["count"] >= 900 else 1)
PY

# Bad security files: exit 2 naming the file and why, before anything runs.
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; fail "exit $rc, expected 2: $*"; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; fail "message lacks '$pat'"; }
  echo "refused: $(grep -m1 -- "$pat" "$out/bad.log")"
}
expect2 "a run of processes a, b in one participant" "$by" run secure.json --one-process --domain "$domain" --duration 1
cp -r keys keys_good
rm keys/a/key.pem
expect2 "keys/a/key.pem: does not exist" "$by" run secure.json --process a --domain "$domain" --duration 1
cp keys_good/b/key.pem keys/a/key.pem
expect2 "key.pem is not the key of cert.pem" "$by" validate secure.json
cp keys_good/a/key.pem keys/a/key.pem
sed -i 's#brickyard/double/out#brickyard/src/out#' keys/b/permissions.p7s
expect2 "keys/b/permissions.p7s: its signature does not verify" "$by" run secure.json --process b --domain "$domain" --duration 1
cp keys_good/b/permissions.p7s keys/b/
rm -r keys
expect2 "is not a folder: make it with \`brickyard security init" "$by" run secure.json --process a --domain "$domain" --duration 1
echo "security: ok"
