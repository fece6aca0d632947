#!/bin/sh
# The peers side by side with `impact bench`, in one run, one core each: the same Hunt–Crossley impact
# (m* = K = v0 = 1, n = 3/2, x = alpha v0), solved
#   - by scipy's solve_ivp with events (DOP853 at rtol 1e-6 and 1e-10, x = 0.5),
#   - by velocity Verlet at 100 steps per contact jitted with numba, over a sweep of x in [0.01, 2]
#     (NUMBA_NUM_THREADS=1: one core),
#   - by `impact bench` on the cases x = 0.01, 0.5, 2 (every method and setting of the study),
#   - by `impact sweep` over the numba peer's sweep, writing e alone as the peers compute it: 1,000,000 impacts at
#     tolerance 1e-6 on one core (pinned with taskset, the CSV writer included), and 1,000,000 at the default
#     tolerance on all cores (the GPU peer's sweep), CSV written, each timed end to end,
# and prints one table: method, error in e, time per impact. The GPU peer (JAX + diffrax) needs a GPU; where there
# is none it is not run and its published figures are shown.
#
#   scripts/peers.sh PEERS_DIR [OUT_DIR]     # PEERS_DIR holds scipy_peer.py, numba_peer.py, diffrax_peer.py
#
# Installs scipy and numba with pip if they are missing (into the Python that PYTHON names, python3 by default).
set -eu
if [ $# -lt 1 ] || [ ! -f "$1/scipy_peer.py" ] || [ ! -f "$1/numba_peer.py" ]; then
    echo "usage: scripts/peers.sh PEERS_DIR [OUT_DIR]  (PEERS_DIR: the folder of scipy_peer.py and numba_peer.py)" >&2
    exit 2
fi
peers=$(cd "$1" && pwd)
out=${2:-out/peers}
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$(dirname "$0")/.."   # the repository's root, wherever the script is called from
python=${PYTHON:-python3}

python3_has() { "$python" -c "import $1" 2>/dev/null; }
for module in scipy numba; do
    if ! python3_has "$module"; then
        echo "installing $module with pip ..." >&2
        "$python" -m pip install --quiet "$module"
    fi
done

cargo build --release --quiet
impact=target/release/impact
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg)" >&2

echo "scipy DOP853 ..." >&2
"$python" "$peers/scipy_peer.py" --method DOP853 --rtol 1e-6 --count 200 > "$out/scipy-1e-6.json"
"$python" "$peers/scipy_peer.py" --method DOP853 --rtol 1e-10 --count 200 > "$out/scipy-1e-10.json"
echo "numba velocity Verlet, 1 thread ..." >&2
NUMBA_NUM_THREADS=1 "$python" "$peers/numba_peer.py" --steps 100 --count 1000000 > "$out/numba.json"
# timed OUT.json COMMAND...: runs COMMAND; writes its wall time and peak memory (the largest child's) to OUT.json.
timed() {
    "$python" -c 'import json, resource, subprocess, sys, time
start = time.perf_counter()
subprocess.run(sys.argv[2:], check=True)
wall = time.perf_counter() - start
json.dump({"wall_s": wall, "peak_kb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss}, open(sys.argv[1], "w"))
' "$@"
}
scene=scripts/peer-hunt-crossley.toml
sweep="contact.damping=0.01:2:1000000"
echo "impact sweep, e alone, tolerance 1e-6, one core ..." >&2
timed "$out/sweep-one-core.json" taskset -c 0 "$impact" sweep "$scene" --vary solver.rtol=1e-6 --vary "$sweep" \
    --columns restitution_velocity_ratio --threads 1 --out "$out/sweep-one-core.csv"
echo "impact sweep, e alone, default tolerance, all cores ..." >&2
timed "$out/sweep-all-cores.json" "$impact" sweep "$scene" --vary "$sweep" --columns restitution_velocity_ratio \
    --out "$out/sweep-all-cores.csv"
echo "impact bench ..." >&2
"$impact" bench --case "hunt-crossley x=0.01 n=1.5" --case "hunt-crossley x=0.5 n=1.5" \
    --case "hunt-crossley x=2 n=1.5" --out "$out" > "$out/bench.txt"
if "$python" -c "import jax; import sys; sys.exit(0 if any(d.platform == 'gpu' for d in jax.devices()) else 1)" 2>/dev/null; then
    echo "diffrax on the GPU ..." >&2
    "$python" "$peers/diffrax_peer.py" --count 1000000 > "$out/diffrax.json"
fi
echo "load average at the end $(cut -d' ' -f1-3 /proc/loadavg)" >&2

"$python" - "$out" "$peers" <<'PYTHON'
import csv, json, os, sys

out = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from scipy_peer import exact_e  # the peers' own exact e (bisection on the Hunt–Crossley relation)
rows = list(csv.DictReader(open(os.path.join(out, "bench.csv"))))
table = []  # (method, error in e, seconds per impact, note)
for name in ("scipy-1e-6", "scipy-1e-10"):
    r = json.load(open(os.path.join(out, name + ".json")))
    table.append((f"scipy solve_ivp {r['method']} rtol {r['rtol']:g} (peer)", r["relative_error"],
                  r["seconds_per_impact"], "x = 0.5"))
numba = json.load(open(os.path.join(out, "numba.json")))
table.append((numba["method"] + ", 1 thread (peer)", numba["worst_e_error"], numba["seconds_per_impact"],
              f"x in [0.01, 2], worst of 50; {numba['count']} impacts in {numba['wall_s']:.2f} s"))
path = os.path.join(out, "diffrax.json")
if os.path.exists(path):
    r = json.load(open(path))
    table.append((r["method"] + " (peer)", r["worst_e_error"], r["seconds_per_impact"],
                  f"x in [0.01, 2]; {r['count']} impacts in {r['wall_s']:.2f} s"))
else:
    table.append(("diffrax dopri8 rtol 1e-10, vmap on a GPU (peer)", float("nan"), 0.19e-6,
                  "not run: no GPU here; published: 1,000,000 impacts in 3.2 s, 0.19 µs an impact"))

def ours(method, setting, case="hunt-crossley x=0.5 n=1.5"):
    for r in rows:
        if r["method"] == method and r["case"] == case and setting in (r["tolerance"], r["steps"]):
            return r
    return None

def label(r):
    what = f"tol {float(r['tolerance']):.0e}" if r["tolerance"] else f"N = {r['steps']}"
    return f"impact {r['method']} {what}"

for method, settings in (("taylor", ["1e-4", "1e-6", "1e-8", "1e-10", "1e-13", "1e-16"]),
                         ("taylor-motion", ["1e-5", "1e-6", "1e-10"]), ("first-integral", ["1e-10"]),
                         ("dop853", ["1e-6", "1e-10"]), ("dopri5", ["1e-6", "1e-10"]),
                         ("rk4", ["100", "1000"]), ("verlet", ["100", "1000"])):
    for setting in settings:
        r = ours(method, setting)
        if r:
            over = {"taylor-motion": "e, dmax, V0, Jr", "first-integral": "e, dmax, Fmax, V0, Jr"}.get(method, "all quantities")
            note = f"x = 0.5; largest error over {over} {float(r['error']):.1e}"
            table.append((label(r), float(r["error_e"]), float(r["seconds_per_impact"]), note))

def sweep_row(name, label):
    """A timed `impact sweep` writing e: its time per impact, and its worst e error over 50 rows spread as the
    numba peer spreads its check (np.linspace(0, count - 1, 50))."""
    timing = json.load(open(os.path.join(out, name + ".json")))
    rows = list(csv.DictReader(open(os.path.join(out, name + ".csv"))))
    count = len(rows)
    picks = [round(i * (count - 1) / 49) for i in range(50)]
    worst = max(abs(float(rows[i]["restitution_velocity_ratio"]) / exact_e(float(rows[i]["contact.damping"])) - 1)
                for i in picks)
    note = (f"x in [0.01, 2], worst of 50; {count} impacts in {timing['wall_s']:.2f} s, CSV written, "
            f"{timing['peak_kb'] / 1024:.0f} MB peak")
    return (label, worst, timing["wall_s"] / count, note)

table.append(sweep_row("sweep-one-core", "impact sweep, e alone, tolerance 1e-6, 1 core (taskset)"))
table.append(sweep_row("sweep-all-cores", f"impact sweep, e alone, tolerance 1e-10, {os.cpu_count()} cores"))

print(f"{'method':<58} {'error in e':>10} {'µs/impact':>11}  note")
for method, error, seconds, note in table:
    shown = "n/a" if error != error else f"{error:.1e}"
    print(f"{method:<58} {shown:>10} {seconds * 1e6:>11.3f}  {note}")

# The comparisons with the peers, on this run's numbers.
taylor = [r for r in rows if r["method"] == "taylor" and r["case"] == "hunt-crossley x=0.5 n=1.5"]
print()
for name in ("scipy-1e-10", "scipy-1e-6"):
    peer = json.load(open(os.path.join(out, name + ".json")))
    good = [r for r in taylor if float(r["error_e"]) <= peer["relative_error"]]
    if good:
        best = min(good, key=lambda r: float(r["seconds_per_impact"]))
        ratio = peer["seconds_per_impact"] / float(best["seconds_per_impact"])
        print(f"vs scipy DOP853 rtol {peer['rtol']:g} (e error {peer['relative_error']:.1e}, "
              f"{peer['seconds_per_impact'] * 1e6:.0f} µs): {label(best)} reaches {float(best['error_e']):.1e} in "
              f"{float(best['seconds_per_impact']) * 1e6:.2f} µs, {ratio:.0f} times faster")
cases = {r["case"] for r in rows}
by_setting, by_motion = {}, {}
for r in rows:
    if r["method"] == "taylor":
        by_setting.setdefault(r["tolerance"], []).append(r)
    if r["method"] == "taylor-motion":
        by_motion.setdefault(r["tolerance"], []).append(r)
def fastest_within(groups, bound):
    """The setting whose every case is within `bound`, fastest by its slowest case: (tolerance, slowest s, worst)."""
    good = [(t, rs) for t, rs in groups.items() if len(rs) == len(cases) and max(float(r["error"]) for r in rs) <= bound]
    if not good:
        return None
    t, rs = min(good, key=lambda item: max(float(r["seconds_per_impact"]) for r in item[1]))
    return float(t), max(float(r["seconds_per_impact"]) for r in rs), max(float(r["error"]) for r in rs)

every_quantity, motion = fastest_within(by_setting, 1e-6), fastest_within(by_motion, 1e-6)
if every_quantity:
    t, slowest, worst = every_quantity
    print(f"vs numba Verlet (worst e error {numba['worst_e_error']:.1e}, {numba['seconds_per_impact'] * 1e6:.2f} µs, "
          f"1 thread): impact taylor tol {t:.0e} reaches {worst:.1e} on every quantity of x = 0.01, 0.5, 2 "
          f"in {slowest * 1e6:.2f} µs (slowest case), {numba['seconds_per_impact'] / slowest:.2f} times the speed")
if motion:
    t, slowest, worst = motion
    print(f"vs numba Verlet, computing what it computes: impact taylor-motion tol {t:.0e} reaches {worst:.1e} "
          f"on e, dmax, V0 and Jr of x = 0.01, 0.5, 2 in {slowest * 1e6:.2f} µs (slowest case), "
          f"{numba['seconds_per_impact'] / slowest:.2f} times the speed")
one = next(t for t in table if t[0].startswith("impact sweep, e alone, tolerance 1e-6"))
every = next(t for t in table if t[0].startswith("impact sweep, e alone, tolerance 1e-10"))
print(f"vs numba Verlet on its own sweep, e alone, one core: impact sweep reaches {one[1]:.1e} (numba "
      f"{numba['worst_e_error']:.1e}) in {one[2] * 1e6:.2f} µs an impact, CSV written (numba "
      f"{numba['seconds_per_impact'] * 1e6:.2f} µs, nothing written): {numba['seconds_per_impact'] / one[2]:.2f} times "
      f"the speed")
wall = json.load(open(os.path.join(out, "sweep-all-cores.json")))["wall_s"]
print(f"vs the GPU peer's 1,000,000 impacts in 3.2 s (e error 2e-10, nothing written): impact sweep on "
      f"{os.cpu_count()} cores reaches {every[1]:.1e} in {wall:.2f} s, CSV written")
PYTHON
