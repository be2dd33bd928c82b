#!/usr/bin/env bash
# The run report: `brickyard run --out` records the run and writes report.html with its figures;
# headless Chromium renders it to a PNG that must not be blank. A folder that is not a run gets
# exit 2 naming what is missing. (Chromium runs inside the test's private network namespace.)
set -u
by=$1; graph=$2; domain=$3; out=$4; here=$(dirname "$0")
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --domain "$domain" --quiet --out "$out/run" > "$out/run.log" 2>&1 || { cat "$out/run.log"; echo "FAIL: run"; exit 1; }
html="$out/run/report.html"
[ -s "$html" ] || { cat "$out/run.log"; echo "FAIL: no report.html"; exit 1; }
n=$(grep -c '<figure id=' "$html")
for f in map error delta status steering speed; do
  grep -q "<figure id=\"$f\">" "$html" || { echo "FAIL: no $f figure"; exit 1; }
done
echo "report: $n figures"
browser=$(command -v chromium || command -v chromium-browser || true)
[ -n "$browser" ] || { echo "FAIL: chromium not installed (scripts/setup installs it)"; exit 1; }
HOME="$out/home" timeout 120 "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$out/chrome" \
  --window-size=1100,3000 --screenshot="$out/report.png" "file://$(realpath "$html")" > "$out/chrome.log" 2>&1
[ -s "$out/report.png" ] || { tail -5 "$out/chrome.log"; echo "FAIL: no screenshot"; exit 1; }
python3 "$here/png_not_blank.py" "$out/report.png" || { echo "FAIL: the rendered report is blank"; exit 1; }
"$by" report "$out/nothing" > "$out/bad.log" 2>&1; rc=$?
[ $rc -eq 2 ] && grep -q "nothing/summary.json: not found" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: report of a non-run: exit $rc"; exit 1; }
# A recording is anyone's file: a topic name that carries a gnuplot command (a newline, then
# `!` runs a shell) must stay a name.
# (Recorded as SQLite, whose topic names a test can rewrite in place.)
"$by" run "$graph" --domain "$domain" --quiet --duration 2 --no-report --out "$out/crafted" --record "$out/crafted.db3" > /dev/null 2>&1
python3 - "$out/crafted.db3" "$out/PWNED" <<'PY'
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
c.execute("UPDATE topics SET name = ? WHERE name = 'manager.command'", ("x\n!touch " + sys.argv[2] + "\n#",))
c.commit()
PY
"$by" report "$out/crafted" > "$out/crafted.log" 2>&1
[ ! -e "$out/PWNED" ] || { echo "FAIL: a topic name ran a command through gnuplot"; exit 1; }
# A folder whose run kept no recording (--no-report) has no report to draw: exit 2, not an old one.
"$by" run "$graph" --domain "$domain" --quiet --duration 1 --no-report --out "$out/run" > /dev/null 2>&1
[ ! -e "$out/run/recording.mcap" ] && [ ! -e "$out/run/report.html" ] || { echo "FAIL: --no-report left the last run's recording or report"; exit 1; }
"$by" report "$out/run" > "$out/bad.log" 2>&1; rc=$?
[ $rc -eq 2 ] && grep -q "the run kept no recording" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: report of a run without recording: exit $rc"; exit 1; }
# --out never removes a recording it did not write.
mkdir -p "$out/mine"
"$by" run "$graph" --domain "$domain" --quiet --duration 1 --record "$out/mine/recording.mcap" > /dev/null 2>&1
"$by" run "$graph" --domain "$domain" --quiet --duration 1 --out "$out/mine" > "$out/bad.log" 2>&1; rc=$?
[ $rc -eq 2 ] && [ -s "$out/mine/recording.mcap" ] && grep -q "was not written by --out" "$out/bad.log" \
  || { cat "$out/bad.log"; echo "FAIL: --out and a --record file in its folder: exit $rc"; exit 1; }
echo "report: ok"
