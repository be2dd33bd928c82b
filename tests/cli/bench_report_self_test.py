#!/usr/bin/env python3
"""scripts/bench-report on a planted benchmark: its rounds merged into the document's block (a
number the same in every round as printed, one that differs as median [range]), the text around
the block untouched; a benchmark that fails leaves its block as it was and the report exits 1; a
benchmark without a block, or not a benchmark, exits 2 before anything runs.
usage: bench_report_self_test.py SOURCE_DIR WORK_DIR"""
import os
import stat
import subprocess
import sys

src, work = sys.argv[1], sys.argv[2]
os.makedirs(os.path.join(work, "bin"), exist_ok=True)
fake = os.path.join(work, "bin", "bench_fusion")  # a name bench/ has; the planted program stands in for it
counter = os.path.join(work, "round")
doc = os.path.join(work, "performance.md")
failures = []
if os.path.exists(counter):
    os.remove(counter)


def plant(body):
    with open(fake, "w") as f:
        f.write("#!/usr/bin/env bash\n" + body)
    os.chmod(fake, os.stat(fake).st_mode | stat.S_IXUSR)


def report(*args):
    env = dict(os.environ, BUILD_DIR=work)
    return subprocess.run([os.path.join(src, "scripts", "bench-report"), "--doc", doc, *args], env=env, capture_output=True, text=True)


def expect(what, ok):
    if not ok:
        failures.append(what)


# Rounds print 10.0, 12.0, 11.0 ms and the same table row every time.
plant(f'n=$(cat {counter} 2>/dev/null || echo 0); echo $((n + 1)) > {counter}\n'
      'v=(10.0 12.0 11.0); echo "ours ${v[$n]} ms over 64 B"\necho "| row | 5 |"\n')
with open(doc, "w") as f:
    f.write("before\n<!-- bench-report bench_fusion -->\nold\n<!-- /bench-report bench_fusion -->\nafter\n")
r = report("--rounds", "3", "bench_fusion")
text = open(doc).read()
expect(f"the report exits 0 (exit {r.returncode}: {r.stderr})", r.returncode == 0)
expect("the rounds merged: ours 11.0 [10.0–12.0] ms over 64 B", "ours 11.0 [10.0–12.0] ms over 64 B" in text)
expect("the same row kept as printed, as a table", "\n| row | 5 |\n" in text)
expect("the command named", "`scripts/bench-report --rounds 3 bench_fusion`" in text)
expect("the old block replaced, the rest kept", "old" not in text and text.startswith("before\n") and text.endswith("after\n"))

plant('echo "ours 1.0 ms"; exit 1\n')
r = report("--rounds", "1", "bench_fusion")
expect(f"a failing benchmark makes the report exit 1 (exit {r.returncode})", r.returncode == 1)
expect("a failing benchmark leaves its block as it was", open(doc).read() == text)

r = report("bench_nothing")
expect(f"not a benchmark: exit 2 naming it (exit {r.returncode}: {r.stderr})", r.returncode == 2 and "bench_nothing" in r.stderr)
r = report("bench_sim")
expect(f"no block: exit 2 naming the document and the benchmark (exit {r.returncode}: {r.stderr})",
       r.returncode == 2 and "bench_sim" in r.stderr and doc in r.stderr)
r = report("--rounds", "0", "bench_fusion")
expect(f"--rounds 0: exit 2 naming the flag (exit {r.returncode}: {r.stderr})", r.returncode == 2 and "--rounds" in r.stderr)

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
