#!/usr/bin/env python3
"""MuJoCo against `impact`'s `mujoco` law: a free sphere launched at a plane, no gravity, no friction.

The case of google-deepmind/mujoco discussion #3404: a 0.5 kg ball meant to bounce with e = 0.75 on k = 1e4 N/m.
The linear spring-dashpot's damping for 0.75 is c = 2 zeta sqrt(k m) (zeta = -ln e / sqrt(pi^2 + ln^2 e)), and
  - "typed physical":  solref = "-k -c"          (what the user typed; MuJoCo reads it per unit mass),
  - "per unit mass":   solref = "-k/m -c/m"      (what means the intended spring-dashpot),
each at MuJoCo's Euler step (semi-implicit: v += dt a, then q += dt v) for several dt, beside `impact run` on the
same contact with `law = "mujoco"`, `[solver] method = "symplectic-euler"`, `dt`. The last case is the shipped
scene models/mujoco-typed-physical.toml itself (read from the file: 10 m/s, radius 1 m).

The ball starts 1e-12 m above the plane (MuJoCo makes a contact at distance <= margin = 0), so that the touch falls
on a step boundary, as in impact's fixed-step run (touch phase 0). e = qvel_z after / v0 once the contact is gone.
"""

import math
import os
import re
import sys
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

# ---------------------------------------------------------------------------------------------------------------
# The parameters (every number the comparison uses)
# ---------------------------------------------------------------------------------------------------------------
MASS = 0.5  # kg
RADIUS = 0.05  # m (a sphere-plane contact's force does not depend on it)
SPEED = 1.0  # m/s, towards the plane
K = 1.0e4  # N/m, the stiffness the user wanted
E_TARGET = 0.75  # the e the user wanted
LN_E = math.log(E_TARGET)
ZETA = -LN_E / math.sqrt(math.pi**2 + LN_E**2)  # 0.091190: the linear spring-dashpot's damping ratio for E_TARGET
C = 2.0 * ZETA * math.sqrt(K * MASS)  # N s/m, 12.8963
SOLIMP = [0.9, 0.95, 0.001, 0.5, 2.0]  # MuJoCo's default, written out
DTS = [2e-4, 1e-4, 5e-5, 2e-5]  # s; 2e-4 is the discussion's step (MuJoCo's default is 2e-3)
MODEL = os.path.join(common.ROOT, "models", "mujoco-typed-physical.toml")

CASES = [  # (name, mass, radius, speed, solref)
    ("typed physical [-k, -c]", MASS, RADIUS, SPEED, [-K, -C]),
    ("per unit mass [-k/m, -c/m]", MASS, RADIUS, SPEED, [-K / MASS, -C / MASS]),
    # ten times faster (a radius of 1 m: the penetration reaches ~10 cm): the impedance's width of 1 mm then matters
    # less, and e comes nearer the 0.7626 of a penetration far beyond the width
    ("per unit mass [-k/m, -c/m]", MASS, 1.0, 10 * SPEED, [-K / MASS, -C / MASS]),
]


def model_case():
    """models/mujoco-typed-physical.toml's own ball, speed and solref."""
    with open(MODEL, "rb") as f:
        scene = tomllib.load(f)
    ball = scene["bodies"][0]
    speed = math.sqrt(sum(v * v for v in ball["velocity"]))
    solimp = scene["contact"].get("solimp", SOLIMP)
    assert solimp == SOLIMP, "the model's solimp is not the one this driver gives MuJoCo"
    return ("models/mujoco-typed-physical.toml", ball["mass"], ball["radius"], speed, scene["contact"]["solref"])


def fmt(values):
    return " ".join(repr(float(v)) for v in values)


def mjcf(mass, radius, solref, dt):
    """The MuJoCo model. Both geoms get the same solref/solimp (a contact mixes the two geoms' values with solmix;
    equal values make the mix irrelevant); condim 1: a frictionless normal contact; Euler is MuJoCo's default
    integrator, spelled out."""
    return f"""<mujoco model="impact-peer">
  <option timestep="{dt!r}" gravity="0 0 0" integrator="Euler" cone="pyramidal"/>
  <default>
    <geom condim="1" solref="{fmt(solref)}" solimp="{fmt(SOLIMP)}" margin="0" gap="0"/>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="10 10 0.1"/>
    <body name="ball" pos="0 0 {radius + 1e-12!r}">
      <freejoint/>
      <geom name="ball" type="sphere" size="{radius!r}" mass="{mass!r}"/>
    </body>
  </worldbody>
</mujoco>
"""


def mujoco_e(mujoco, mass, radius, speed, solref, dt):
    model = mujoco.MjModel.from_xml_string(mjcf(mass, radius, solref, dt))
    data = mujoco.MjData(model)
    data.qvel[2] = -speed
    touched = False
    for _ in range(10_000_000):
        mujoco.mj_step(model, data)
        touched = touched or data.ncon > 0
        if touched and data.ncon == 0 and data.qvel[2] > 0:
            return data.qvel[2] / speed
    raise RuntimeError("the ball did not leave the plane")


def scene(name, mass, radius, speed, solref, dt):
    if name == model_case()[0]:
        with open(MODEL) as f:
            return f.read() + f'\n[solver]\nmethod = "symplectic-euler"\ndt = {dt!r}\n'
    return common.scene_text(
        f"MuJoCo peer: {name}",
        [{"name": "ball", "mass": mass, "radius": radius, "velocity": [0.0, 0.0, -speed]},
         {"name": "floor", "mass": float("inf"), "radius": float("inf"), "velocity": [0.0, 0.0, 0.0]}],
        {"law": "mujoco", "normal": [0.0, 0.0, -1.0], "solref": solref, "solimp": SOLIMP},
        {"method": "symplectic-euler", "dt": dt})


# ---------------------------------------------------------------------------------------------------------------
# `impact translate --to mujoco`: the snippet's attributes, used literally
# ---------------------------------------------------------------------------------------------------------------
TRANSLATE_DTS = [2e-4, 1e-4]  # s


def kelvin_voigt_scene():
    """The discussion's intent as a scene: a linear spring-dashpot, k = K, e = E_TARGET, the ball at SPEED."""
    return common.scene_text(
        f"Kelvin-Voigt ball, k = {K:g} N/m, m = {MASS} kg, e = {E_TARGET}",
        [{"name": "ball", "mass": MASS, "radius": RADIUS, "velocity": [0.0, 0.0, -SPEED]},
         {"name": "floor", "mass": float("inf"), "radius": float("inf"), "velocity": [0.0, 0.0, 0.0]}],
        {"law": "kelvin-voigt", "stiffness": K, "restitution": E_TARGET, "normal": [0.0, 0.0, -1.0]})


def snippet_model(snippet, mass, radius):
    """A MuJoCo model built from the translation's snippet as it stands: its <option .../> (gravity off added) and
    its <geom .../> attributes as the default of both geoms (the snippet asks for them on both)."""
    option = re.search(r"<option\b([^>]*?)/>", snippet)
    geom = re.search(r"<geom\b([^>]*?)/>", snippet)
    if not option or not geom:
        raise RuntimeError(f"the snippet has no <option/> or <geom/> element:\n{snippet}")
    return f"""<mujoco model="impact-translate">
  <option{option.group(1)} gravity="0 0 0"/>
  <default>
    <geom{geom.group(1)}/>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="10 10 0.1"/>
    <body name="ball" pos="0 0 {radius + 1e-12!r}">
      <freejoint/>
      <geom name="ball" type="sphere" size="{radius!r}" mass="{mass!r}"/>
    </body>
  </worldbody>
</mujoco>
"""


def snippet_e(mujoco, xml, speed):
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    data.qvel[2] = -speed
    touched = False
    for _ in range(10_000_000):
        mujoco.mj_step(model, data)
        touched = touched or data.ncon > 0
        if touched and data.ncon == 0 and data.qvel[2] > 0:
            return data.qvel[2] / speed, model.opt.timestep
    raise RuntimeError("the ball did not leave the plane")


def translated(mujoco):
    """models/mujoco-typed-physical.toml and the Kelvin-Voigt scene, each translated at each dt and run in MuJoCo
    from the snippet; the table sets MuJoCo's e beside the translation's restitution_at_dt and continuous e."""
    _, mass, radius, speed, _ = model_case()
    kv = common.write_scene(kelvin_voigt_scene(), "mujoco-kelvin-voigt")
    table = common.Table("MuJoCo", "translation")
    snippets = []
    for name, path, mass, radius, speed in [
            ("models/mujoco-typed-physical.toml", MODEL, mass, radius, speed),
            (f"kelvin-voigt e = {E_TARGET}, k = {K:g}", kv, MASS, RADIUS, SPEED)]:
        for dt in TRANSLATE_DTS:
            t = common.translate(path, "mujoco", dt)
            xml = snippet_model(t["snippet"], mass, radius)
            e, step = snippet_e(mujoco, xml, speed)
            if step != dt:
                raise RuntimeError(f"the snippet's timestep reads as {step}, not {dt}")
            solref = " ".join(f"{v:.6g}" for v in t["parameters"]["solref"])
            table.add(f"{name} {speed:g} m/s, solref {solref}", dt, e, t["restitution_at_dt"],
                      t["restitution_continuous"])
            snippets.append((name, dt, t["snippet"]))
    print(f"\nimpact translate --to mujoco --dt DT --json: MuJoCo {mujoco.__version__} run with the snippet's <option> "
          "and <geom> attributes (on both geoms), no gravity")
    table.print()
    name, dt, snippet = snippets[-1]
    print(f"the snippet ({name}, dt = {dt:g}), used as it stands:")
    print("".join("  " + line + "\n" for line in snippet.splitlines()), end="")


def main():
    try:
        import mujoco
    except ImportError as error:
        common.skip("MuJoCo", f"the Python package is not installed ({error}); pip install mujoco")
    print(f"MuJoCo {mujoco.__version__}: sphere on a plane, no gravity, condim 1, Euler, default solimp")
    print(f"  k = {K:g} N/m, m = {MASS} kg, e wanted {E_TARGET}: zeta = {ZETA:.6f}, c = {C:.6f} N s/m")
    table = common.Table("MuJoCo")
    for name, mass, radius, speed, solref in CASES + [model_case()]:
        for dt in DTS:
            e = mujoco_e(mujoco, mass, radius, speed, solref, dt)
            e_dt, e_cont = common.impact_e(scene(name, mass, radius, speed, solref, dt), "mujoco")
            table.add(f"{name} {speed:g} m/s", dt, e, e_dt, e_cont)
    table.print()
    print('MuJoCo geom attributes used: condim="1" solref="-K -C" solimp="0.9 0.95 0.001 0.5 2" (on both geoms),')
    print('  <option gravity="0 0 0" integrator="Euler" cone="pyramidal" timestep="DT"/>')
    translated(mujoco)


if __name__ == "__main__":
    main()
