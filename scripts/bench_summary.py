#!/usr/bin/env python3
"""OUT_DIR/summary.md of scripts/bench-all.sh, built from the CSV and JSON files its runs wrote (no number typed here).

    scripts/bench_summary.py OUT_DIR                                  # the markdown on standard output
    scripts/bench_summary.py --chain-scene BEADS END_TIME TOLERANCE  # the bead chain of `impact bench --worlds`

One table per study; every row gives the case, the program and its setting, the error against the study's reference,
the time (per impact, or per run for a world), and the ratio of its time to impact's row named beside it. A study
whose files are missing (a skipped peer, a failed step) is said to be missing, with the reason steps.tsv gives.
Standard library only.
"""

import argparse
import csv
import json
import math
import os
import statistics
import sys


# ---------------------------------------------------------------------------------------------------------------
# Small helpers
# ---------------------------------------------------------------------------------------------------------------
def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def sci(x, digits=1):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a"
    if x == 0:
        return "0"
    return "%.*e" % (digits, x)


def us(seconds):
    """Microseconds, three significant digits."""
    v = 1e6 * seconds
    return "%.3g" % v if v < 1000 else "%.0f" % v


def secs(seconds):
    return "%.3g s" % seconds


def ratio(a, b):
    if not b:
        return "n/a"
    r = a / b
    return "%.3g" % r


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        lines.append("| " + " | ".join(str(c) for c in row) + " |")
    return "\n".join(lines)


def exact_hunt_crossley_e(x):
    """e of the Hunt-Crossley impact at x = alpha v0: the root in (0, 1) of x (1 + e) = ln((1 + x) / (1 - e x))."""
    if x <= 0:
        return 1.0
    lo, hi = 0.0, min(1.0, (1 - 1e-16) / x)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if x * (1 + mid) - math.log1p(x) + math.log1p(-mid * x) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


class Steps:
    """steps.tsv: each step's exit status and duration, or why it was skipped."""

    def __init__(self, path):
        self.rows = {}
        if os.path.exists(path):
            with open(path) as f:
                for line in f:
                    parts = line.rstrip("\n").split("\t")
                    if len(parts) == 3:
                        self.rows[parts[0]] = (parts[1], parts[2])

    def why_missing(self, *names):
        for name in names:
            if name in self.rows:
                status, detail = self.rows[name]
                if status == "skipped":
                    return "skipped: " + detail
                if status != "0":
                    return "failed (exit %s after %s s; see logs/%s.log)" % (status, detail, name)
        return "not run"


# ---------------------------------------------------------------------------------------------------------------
# The studies
# ---------------------------------------------------------------------------------------------------------------
METHOD_ORDER = ["taylor", "taylor-motion", "first-integral", "dop853", "dopri5", "rk4", "verlet"]
METHOD_NAMES = {
    "taylor": "fast path (`taylor`)",
    "taylor-motion": "fast path, the motion alone (`taylor-motion`: e, dmax, V0, Jr)",
    "first-integral": "first integral (`first-integral`: e, dmax, Fmax, V0, Jr)",
    "dop853": "Dop853, the general path",
    "dopri5": "Dopri5",
    "rk4": "RK4, fixed steps, events located",
    "verlet": "velocity Verlet (the DEM practice)",
}


def setting_of(row):
    if row["tolerance"]:
        return "tolerance %s" % row["tolerance"]
    return "%s steps a contact" % row["steps"]


def single_impact(out):
    rows = read_csv(os.path.join(out, "bench", "bench.csv"))
    groups = {}
    for r in rows:
        groups.setdefault((r["method"], r["tolerance"], r["steps"]), []).append(r)
    cases = sorted({r["case"] for r in rows})

    def key(item):
        (method, tol, steps), _ = item
        order = METHOD_ORDER.index(method) if method in METHOD_ORDER else len(METHOD_ORDER)
        return (order, -float(tol) if tol else 0.0, float(steps) if steps else 0.0)

    default = groups.get(("taylor", "1e-10", ""))
    default_median = statistics.median(float(r["seconds_per_impact"]) for r in default) if default else None
    body = []
    for (method, tol, steps), rs in sorted(groups.items(), key=key):
        times = [float(r["seconds_per_impact"]) for r in rs]
        median = statistics.median(times)
        body.append(["%d of %d" % (len(rs), len(cases)), "impact, %s, %s" % (METHOD_NAMES.get(method, method),
                                                                         setting_of(rs[0])),
                     sci(max(float(r["error"]) for r in rs)), sci(max(float(r["error_e"]) for r in rs)),
                     "%s (%s)" % (us(median), us(max(times))),
                     ratio(median, default_median) if default_median else "n/a"])
    text = ("### One impact: the work-precision study (`impact bench`)\n\n"
            "%d reference impacts with exact answers; the error is the largest relative error over every quantity "
            "(and over e alone) and over the cases; the time is the median over the cases of each case's median time "
            "of one impact on one thread, with the slowest case; the ratio is that median over the fast path's at "
            "its default tolerance 1e-10.\n\n" % len(cases))
    return text + table(["cases", "program and setting", "error, every quantity", "error in e",
                         "µs an impact: median (slowest)", "ratio to impact at 1e-10"], body)


def peers(out):
    folder = os.path.join(out, "peers")
    bench = read_csv(os.path.join(folder, "bench.csv"))
    taylor = [r for r in bench if r["method"] == "taylor"]
    body = []

    def fastest(method, bound, case=None, column="error"):
        """impact's fastest setting of `method` whose `column` is within `bound` (on `case`, or on every case: by its
        slowest)."""
        groups = {}
        for r in bench:
            if r["method"] == method and (case is None or r["case"] == case):
                groups.setdefault(r["tolerance"], []).append(r)
        ncases = len({r["case"] for r in bench}) if case is None else 1
        good = [rs for rs in groups.values() if len(rs) == ncases and max(float(r[column]) for r in rs) <= bound]
        if not good:
            return None
        return min(good, key=lambda rs: max(float(r["seconds_per_impact"]) for r in rs))

    for name in ("scipy-1e-10", "scipy-1e-6"):
        path = os.path.join(folder, name + ".json")
        if not os.path.exists(path):
            continue
        peer = read_json(path)
        best = fastest("taylor", peer["relative_error"], "hunt-crossley x=0.5 n=1.5", "error_e")
        body.append(["x = 0.5", "scipy `solve_ivp` %s with events, rtol %g (peer)" % (peer["method"], peer["rtol"]),
                     sci(peer["relative_error"]), us(peer["seconds_per_impact"]),
                     ratio(peer["seconds_per_impact"], float(best[0]["seconds_per_impact"])) if best else "n/a"])
        if best:
            r = best[0]
            body.append(["x = 0.5", "impact, fast path at tolerance %s (its fastest within scipy's error in e; "
                         "every quantity within %s)" % (r["tolerance"], sci(float(r["error"]))),
                         sci(float(r["error_e"])), us(float(r["seconds_per_impact"])), "1"])
    path = os.path.join(folder, "numba.json")
    if os.path.exists(path):
        numba = read_json(path)
        best = fastest("taylor-motion", numba["worst_e_error"])
        slowest = max(float(r["seconds_per_impact"]) for r in best) if best else None
        body.append(["x in [0.01, 2]", "%s, 1 thread, %d impacts, nothing written (peer)"
                     % (numba["method"], numba["count"]), sci(numba["worst_e_error"]),
                     us(numba["seconds_per_impact"]), ratio(numba["seconds_per_impact"], slowest)])
        if best:
            body.append(["x = 0.01, 0.5, 2", "impact, `taylor-motion` at tolerance %s (its fastest within numba's "
                         "error in e, on e, dmax, V0 and Jr of every case; the slowest case's time)"
                         % best[0]["tolerance"],
                         sci(max(float(r["error"]) for r in best)), us(slowest), "1"])
        for name, label in (("sweep-one-core", "`impact sweep`, e alone, tolerance 1e-6, 1 core (taskset), CSV "
                             "written"), ("sweep-all-cores", "`impact sweep`, e alone, default tolerance, all "
                                          "cores, CSV written")):
            timing_path, rows_path = os.path.join(folder, name + ".json"), os.path.join(folder, name + ".csv")
            if not (os.path.exists(timing_path) and os.path.exists(rows_path)):
                continue
            timing = read_json(timing_path)
            rows = read_csv(rows_path)
            picks = [round(i * (len(rows) - 1) / 49) for i in range(50)]
            worst = max(abs(float(rows[i]["restitution_velocity_ratio"])
                            / exact_hunt_crossley_e(float(rows[i]["contact.damping"])) - 1) for i in picks)
            per = timing["wall_s"] / len(rows)
            body.append(["x in [0.01, 2]", "%s: %d impacts in %.2f s" % (label, len(rows), timing["wall_s"]),
                         sci(worst), us(per), "numba / this: %s" % ratio(numba["seconds_per_impact"], per)])
    text = ("### The Hunt-Crossley impact beside scipy and numba (`scripts/peers.sh`)\n\n"
            "m* = K = v0 = 1, n = 3/2 (`scripts/peer-hunt-crossley.toml`); the error is in e against the exact "
            "relation (the worst of 50 impacts spread over a sweep); the ratio is the peer's time over the impact "
            "row below it (impact's fastest setting at least as accurate).\n\n")
    return text + table(["case", "program and setting", "error in e", "µs an impact", "ratio to impact"], body)


def oblique(out):
    rows = read_csv(os.path.join(out, "oblique", "bench-oblique.csv"))
    twins = {}
    for r in rows:
        if r["path"] in ("frictionless",):
            twins[(r["case"], r["tolerance"])] = float(r["seconds_per_impact"])
    body = []
    for r in rows:
        if r["tolerance"] not in ("1e-6", "1e-10"):
            continue
        twin = twins.get((r["case"], r["tolerance"]))
        body.append([r["case"], "impact, path `%s` (%s), tolerance %s" % (r["path"], r["method"], r["tolerance"]),
                     sci(float(r["error"])), us(float(r["seconds_per_impact"])),
                     ratio(float(r["seconds_per_impact"]), twin) if twin and r["path"] != "frictionless" else ""])
    text = ("### Frictional oblique impacts (`impact bench --oblique`)\n\n"
            "The error is the largest difference of the velocities and spins after the impact from a run at 1e-13; "
            "the ratio is the time over the same contact's frictionless twin at the same tolerance (tolerances 1e-6 "
            "and the default 1e-10 shown; bench-oblique.csv has every one).\n\n")
    return text + table(["case", "program and setting", "error", "µs an impact", "ratio to frictionless"], body)


def lammps_oblique(out):
    run = read_json(os.path.join(out, "lammps", "oblique.json"))
    angles = run["angles"]
    case = "test 4, %d angles %g°–%g°" % (len(angles), angles[0], angles[-1])
    ours = run["impact"]
    body = [[case, "impact, `impact sweep --threads 1`, default tolerance, friction_cap = \"magnitude\" (time over "
             "%d angles, process included)" % ours["timed_impacts"],
             "%s (median %s)" % (sci(ours["error_max"]), sci(ours["error_median"])), "",
             us(ours["seconds_per_impact"]), "1"]]
    for r in run["lammps"]:
        body.append([case, "LAMMPS %s, velocity Verlet, dt = t_c/%g (%d steps, `run` alone)"
                     % (run["lammps_version"].split(" ")[0], r["steps_per_contact"], r["steps"]),
                     "%s (median %s)" % (sci(r["error_max"]), sci(r["error_median"])), sci(r["normal_e_error_max"]),
                     us(r["seconds_per_impact"]), ratio(r["seconds_per_impact"], ours["seconds_per_impact"])])
    text = ("### Chung & Ooi's test 4 beside LAMMPS (`scripts/lammps_oblique.py`)\n\n"
            "One LAMMPS run holds one sphere per angle (`fix wall/gran`, Hertz, Mindlin's spring on the force, "
            "`coeff_restitution`: impact's Tsuji law at its exact map). The error is the larger of the tangential "
            "velocity's and the spin's (r ω) difference from impact's run at 1e-13 with LAMMPS' friction cap, over "
            "the impact speed: the largest over the angles and the median; the normal e's largest difference beside "
            "it. Times are processor time per impact; the ratio is LAMMPS' over impact's. impact's default friction "
            "cap (no friction while the force pulls) moves the result by %s.\n\n" % sci(run["default_cap_difference"]))
    return text + table(["case", "program and setting", "error (median)", "error in normal e", "µs an impact",
                         "ratio to impact"], body)


def worlds(out, steps):
    rows = read_csv(os.path.join(out, "worlds", "bench-worlds.csv"))
    body = []
    for r in rows:
        body.append([r["case"], "impact, tolerance %s" % r["tolerance"], sci(float(r["error"])),
                     secs(float(r["seconds"])), r["steps"], r["contacts"], ""])
    folder = os.path.join(out, "lammps")
    chain_runs = sorted((f for f in os.listdir(folder) if f.startswith("chain-") and "-s" in f and f.endswith(".json")),
                        key=lambda f: float(f.rsplit("-s", 1)[1][:-5])) if os.path.isdir(folder) else []
    references = [f for f in os.listdir(folder) if f.endswith("-reference.json")] if os.path.isdir(folder) else []
    notes = []
    if chain_runs and references:
        reference = read_json(os.path.join(folder, references[0]))
        v_ref = [b["velocity_after"][0] for b in reference["bodies"]]
        v0 = max(abs(b["velocity_before"][0]) for b in reference["bodies"])
        for name in chain_runs:
            run = read_json(os.path.join(folder, name))
            case = "chain-%d" % run["beads"]
            if abs(run["end_time"] - reference["world"]["end_time"]) > 1e-9 * run["end_time"]:
                notes.append("%s: end time %g s, impact's reference %g s: not compared"
                             % (name, run["end_time"], reference["world"]["end_time"]))
                continue
            error = max(abs(a - b) for a, b in zip(run["velocities"], v_ref)) / v0
            ours = [r for r in rows if r["case"] == case]
            good = [r for r in ours if float(r["error"]) <= error]
            if good:
                match = min(good, key=lambda r: float(r["seconds"]))
                against = "impact at %s" % match["tolerance"]
            elif ours:
                match = min(ours, key=lambda r: float(r["error"]))
                against = "impact at %s (LAMMPS is more accurate than every impact row)" % match["tolerance"]
            else:
                match, against = None, "no impact row"
            body.append([case, "LAMMPS %s, dt = t_c/%g (%d steps; `run` alone, processor time %s)"
                         % (run["lammps_version"].split(" ")[0], run["tau"] / run["dt"], run["steps"],
                            secs(run["cpu_s_run"])), sci(error), secs(run["wall_s_run"]), run["steps"], "",
                         "%s (%s)" % (ratio(run["wall_s_run"], float(match["seconds"])), against) if match else "n/a"])
    piles = sorted((f for f in os.listdir(folder) if f.startswith("pile-") and f.endswith(".json")),
                   key=lambda f: -float(f[5:-5])) if os.path.isdir(folder) else []
    for name in piles:
        run = read_json(os.path.join(folder, name))
        ours = [r for r in rows if r["case"] == "settling-pile"]
        match = next((r for r in ours if float(r["tolerance"]) == 1e-10), ours[-1] if ours else None)
        s = run["statistics"]
        body.append(["settling-pile", "LAMMPS, dt = %.3g µs (`run` alone, processor time %s)"
                     % (1e6 * run["dt"], secs(run["cpu_s_run"])),
                     "chaotic: KE + PE left %.2g J, %d of %d balls on the floor" % (s["mechanical"], s["on_floor"],
                                                                                   s["balls"]),
                     secs(run["wall_s_run"]), run["steps"], "",
                     "%s (impact at %s)" % (ratio(run["wall_s_run"], float(match["seconds"])), match["tolerance"])
                     if match else "n/a"])
    text = ("### World runs (`impact bench --worlds`, LAMMPS by `scripts/lammps_chain.py` and `scripts/lammps_pile.py`)"
            "\n\nThe error is the largest difference of a body's final velocity from impact's run at 1e-13, over the "
            "largest initial speed (for LAMMPS' chain: from impact's run of the same chain at 1e-13), except the "
            "settling pile's: impact's energy balance's residual over the energy supplied (a chaotic pile's runs "
            "part ways; LAMMPS keeps no such books, so its row gives the energy left and the balls on the floor). "
            "The times are wall-clock times of the run alone, on one thread: impact's report's `solver.wall_time_s` "
            "(the median of up to 5 runs; the pile's, of one), LAMMPS' `run` command (its processor time beside it; "
            "in a loaded hour the wall time exceeds it, for both programs). The ratio is LAMMPS' wall time over that "
            "of impact's row named: its cheapest tolerance at least as accurate (chain), its run at 1e-10 "
            "(pile).\n\n")
    text += table(["case", "program and setting", "error", "time", "steps", "contacts", "ratio to impact"], body)
    if not chain_runs and not piles:
        notes.append("LAMMPS: %s" % steps.why_missing("lammps", "lammps-chain-50", "lammps-pile-1e-6"))
    if notes:
        text += "\n\n" + "\n".join("- " + n for n in notes)
    return text


# ---------------------------------------------------------------------------------------------------------------
# The chain's scene
# ---------------------------------------------------------------------------------------------------------------
def chain_scene(beads, end, tolerance):
    """The chain of `impact bench --worlds` (src/bench/worlds.rs) and scripts/lammps_chain.py, as a scene."""
    r = 0.005
    lines = ['title = "Hertzian chain of %d steel beads struck at one end"' % beads, "",
             "[world]", "end_time = %r" % end, "max_contacts = 10000000", ""]
    for k in range(beads):
        lines += ["[[bodies]]", "radius = %r" % r, "density = 7850", "young = 2.1e11", "poisson = 0.3",
                  "position = [%r, 0.0, 0.0]" % (2 * r * k), "velocity = [%s, 0.0, 0.0]" % ("1.0" if k == 0 else "0.0"),
                  ""]
    lines += ["[contact]", 'law = "hertz"', "", "[solver]", "rtol = %r" % tolerance, "atol = %r" % tolerance]
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--chain-scene":
        if len(sys.argv) != 5:
            sys.exit("usage: bench_summary.py --chain-scene BEADS END_TIME TOLERANCE")
        try:
            beads, end, tolerance = int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
        except ValueError:
            sys.exit("bench_summary.py --chain-scene: expected BEADS (an integer), END_TIME and TOLERANCE (numbers)")
        sys.stdout.write(chain_scene(beads, end, tolerance))
        return
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", help="the folder scripts/bench-all.sh wrote (its run.tsv, steps.tsv and files)")
    args = parser.parse_args()
    if not os.path.isdir(args.out):
        sys.exit("bench_summary.py: %s: not a folder" % args.out)
    steps = Steps(os.path.join(args.out, "steps.tsv"))
    run = {}
    try:
        with open(os.path.join(args.out, "run.tsv")) as f:
            run = dict(line.rstrip("\n").split("\t", 1) for line in f if "\t" in line)
    except OSError:
        pass
    print("# Speed: every study beside its peers (`scripts/bench-all.sh%s`)\n"
          % (" --quick" if run.get("quick") == "1" else ""))
    print("- started %s; took %s s" % (run.get("started", "(unknown)"), run.get("duration", "(unknown)")))
    print("- machine: %s" % run.get("machine", "unknown"))
    print("- build: %s (`git describe --always --dirty`)" % run.get("build", "unknown"))
    print("- load average (1, 5, 15 min): %s at the start, %s at the end"
          % (run.get("load_start", "unknown"), run.get("load_end", "unknown")))
    print("- steps: " + "; ".join("%s %s" % (name, ("%s s" % detail) if status == "0" else
                                            ("skipped" if status == "skipped" else "failed (exit %s)" % status))
                                  for name, (status, detail) in steps.rows.items()))
    print()
    studies = [
        (single_impact, ("impact-bench",)),
        (peers, ("peers",)),
        (oblique, ("impact-oblique",)),
        (lammps_oblique, ("lammps", "lammps-oblique")),
        (worlds, ("impact-worlds",)),
    ]
    failed = 0
    for build, names in studies:
        try:
            print(build(args.out, steps) if build is worlds else build(args.out))
        except (OSError, KeyError, ValueError, TypeError, IndexError) as err:
            failed += 1
            title = build.__name__.replace("_", " ")
            why = steps.why_missing(*names)
            if not why.startswith("skipped"):
                why += " (%s: %s)" % (type(err).__name__, err)
            print("### %s\n\nMissing: %s." % (title, why))
        print()
    skipped = [(name, detail) for name, (status, detail) in steps.rows.items() if status == "skipped"]
    if skipped:
        print("Skipped: " + "; ".join("%s (%s)" % item for item in skipped) + ".")


if __name__ == "__main__":
    main()
