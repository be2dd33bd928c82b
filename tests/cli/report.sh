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
echo "report: ok"
