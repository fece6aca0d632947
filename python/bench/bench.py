"""The Python package against the command, in one run (docs/python.md#speed): a sweep of e alone over a million
damping values on two threads, from Python (`impact.sweep(..., columns="restitution_velocity_ratio", threads=2)`)
and by `impact sweep --columns restitution_velocity_ratio --threads 2 --out FILE`, alternating, each repeated; the
Python process's peak memory against the arrays' own size (each measurement in a fresh process); `import impact`.

    python python/bench/bench.py [--impact target/release/impact] [--rows 1000000] [--repeat 5]

Not a test: it prints the figures, it judges nothing.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "models" / "demo.toml"

ONE_SWEEP = r"""
import json, resource, sys, time
import impact
rows = int(sys.argv[1])
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
sweep = impact.sweep(sys.argv[2], {"contact.damping": f"0.01:100:{rows}:log"},
                     columns="restitution_velocity_ratio", threads=2, progress=False)
seconds = time.perf_counter() - start
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
arrays = sum(a.nbytes for a in sweep.columns.values())
print(json.dumps({"seconds": seconds, "rows": len(sweep), "arrays_bytes": arrays,
                  "rss_before_kb": before, "rss_peak_kb": peak}))
"""


def python_sweep(rows):
    done = subprocess.run([sys.executable, "-c", ONE_SWEEP, str(rows), str(SCENE)], capture_output=True, text=True,
                          check=True)
    return json.loads(done.stdout)


def command_sweep(binary, rows, out):
    start = time.perf_counter()
    subprocess.run([binary, "sweep", str(SCENE), "--vary", f"contact.damping=0.01:100:{rows}:log", "--columns",
                    "restitution_velocity_ratio", "--threads", "2", "--out", str(out)], check=True,
                   capture_output=True)
    return time.perf_counter() - start


def import_time(repeat):
    def once(code):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        return time.perf_counter() - start

    bare = [once("pass") for _ in range(repeat)]
    with_impact = [once("import impact") for _ in range(repeat)]
    return statistics.median(with_impact) - statistics.median(bare), statistics.median(with_impact)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--impact", default=str(ROOT / "target" / "release" / "impact"))
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    python_runs, command_runs = [], []
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "sweep.csv"
        for _ in range(args.repeat):
            command_runs.append(command_sweep(args.impact, args.rows, out))
            python_runs.append(python_sweep(args.rows))
    py_seconds = [r["seconds"] for r in python_runs]
    ratios = [p / c for p, c in zip(py_seconds, command_runs)]
    peak = max(r["rss_peak_kb"] - r["rss_before_kb"] for r in python_runs) * 1024
    arrays = python_runs[0]["arrays_bytes"]
    extra, total = import_time(args.repeat)
    print(f"rows: {args.rows}, two threads, {args.repeat} runs each, alternating (cpus: {os.cpu_count()})")
    print(f"impact sweep --columns (CSV written): median {statistics.median(command_runs):.3f} s "
          f"(min {min(command_runs):.3f}, max {max(command_runs):.3f})")
    print(f"impact.sweep from Python (columns in memory): median {statistics.median(py_seconds):.3f} s "
          f"(min {min(py_seconds):.3f}, max {max(py_seconds):.3f})")
    print(f"Python / command, run by run: {', '.join(f'{r:.2f}' for r in ratios)}; median {statistics.median(ratios):.2f}")
    print(f"arrays: {arrays / 1e6:.1f} MB ({len(python_runs[0]) and arrays / args.rows:.0f} bytes a row); "
          f"peak memory of the sweep above the imported interpreter: {peak / 1e6:.1f} MB "
          f"({peak / arrays:.2f} times the arrays)")
    print(f"import impact: {extra * 1000:.0f} ms beyond a bare interpreter's start ({total * 1000:.0f} ms in all)")


if __name__ == "__main__":
    main()
