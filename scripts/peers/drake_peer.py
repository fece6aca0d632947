#!/usr/bin/env python3
"""Drake (pydrake, point contact) against `impact`'s `hunt-crossley` law: a free sphere launched at a half space, no
gravity, no friction.

Drake's compliant point contact is Hunt & Crossley's with a linear spring: F = k x (1 + d x'), x the penetration,
k the two geometries' `point_stiffness` in series (k1 k2 / (k1 + k2)), d their `hunt_crossley_dissipation` (s/m)
combined (equal values: d itself). Its e depends on d v0 alone (x (1 + e) = ln((1 + x)/(1 - e x)), x = d v0).
impact's scene: `law = "hunt-crossley"`, `stiffness = k`, `exponent = 1`, `damping = d`.

  - continuous plant (time_step = 0, Drake's error-controlled RK3 at ACCURACY): against impact's continuous e;
  - discrete plant (time_step = dt, Drake's default discrete contact approximation, printed): impact has no
    scheme for Drake's implicit discrete contact solvers, so the row shows the continuous e only.
"""

import os
import sys
import warnings

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: the machine is shared
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

# ---------------------------------------------------------------------------------------------------------------
# The parameters (every number the comparison uses)
# ---------------------------------------------------------------------------------------------------------------
MASS = 0.5  # kg
RADIUS = 0.05  # m
SPEED = 1.0  # m/s, towards the half space
STIFFNESS = 2.0e5  # N/m, each geometry's point_stiffness (in series: STIFFNESS / 2)
DISSIPATION = 0.5  # s/m, each geometry's hunt_crossley_dissipation (x = d v0 = 0.5)
ACCURACY = 1e-10  # the continuous plant's integrator target accuracy
DISCRETE_STEPS = [1e-3, 1e-4]  # s


def drake_e(drake, time_step):
    builder = drake.DiagramBuilder()
    plant, _ = drake.AddMultibodyPlantSceneGraph(builder, time_step=time_step)
    plant.set_contact_model(drake.ContactModel.kPoint)
    ball = plant.AddRigidBody("ball", drake.SpatialInertia.SolidSphereWithMass(MASS, RADIUS))
    for owner, pose, shape, name in [
            (ball, drake.RigidTransform(), drake.Sphere(RADIUS), "ball"),
            (plant.world_body(), drake.HalfSpace.MakePose([0, 0, 1], [0, 0, 0]), drake.HalfSpace(), "ground")]:
        properties = drake.ProximityProperties()
        drake.AddContactMaterial(dissipation=DISSIPATION, point_stiffness=STIFFNESS,
                                 friction=drake.CoulombFriction(0.0, 0.0), properties=properties)
        plant.RegisterCollisionGeometry(owner, pose, shape, name, properties)
    plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, 0.0])
    plant.Finalize()
    approximation = plant.get_discrete_contact_approximation().name if time_step > 0 else "continuous"
    simulator = drake.Simulator(builder.Build())
    context = plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    plant.SetFreeBodyPose(context, ball, drake.RigidTransform([0.0, 0.0, RADIUS]))  # touching
    plant.SetFreeBodySpatialVelocity(context, ball, drake.SpatialVelocity(w=[0.0, 0.0, 0.0], v=[0.0, 0.0, -SPEED]))
    if time_step == 0:
        simulator.get_mutable_integrator().set_target_accuracy(ACCURACY)
    t = 0.0
    while t < 10.0:
        t += 0.01
        simulator.AdvanceTo(t)
        z = plant.EvalBodyPoseInWorld(context, ball).translation()[2]
        v = plant.EvalBodySpatialVelocityInWorld(context, ball).translational()[2]
        if z > RADIUS and v > 0:
            return v / SPEED, approximation
    raise RuntimeError("the ball did not leave the half space")


def main():
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import pydrake.all as drake
        import logging
        logging.getLogger("drake").setLevel(logging.ERROR)  # its note on half spaces and deformable contact
    except ImportError as error:
        common.skip("Drake", f"pydrake does not import ({error}); pip install drake (wheels for the Pythons Drake "
                             f"supports; this is Python {sys.version.split()[0]})")
    from importlib.metadata import version
    scene = common.scene_text(
        "Drake peer: a sphere on a half space, point contact (Hunt-Crossley, linear spring)",
        [{"name": "ball", "mass": MASS, "radius": RADIUS, "velocity": [0.0, 0.0, -SPEED]},
         {"name": "ground", "mass": float("inf"), "radius": float("inf"), "velocity": [0.0, 0.0, 0.0]}],
        {"law": "hunt-crossley", "stiffness": STIFFNESS / 2, "exponent": 1.0, "damping": DISSIPATION,
         "normal": [0.0, 0.0, -1.0]})
    _, e_cont = common.impact_e(scene, "drake")
    table = common.Table("Drake")
    e, _ = drake_e(drake, 0.0)
    table.add(f"point contact, d v0 = {DISSIPATION * SPEED:g}, RK3 accuracy {ACCURACY:g}", None, e, e_cont, e_cont)
    for dt in DISCRETE_STEPS:
        e, approximation = drake_e(drake, dt)
        table.add(f"point contact, d v0 = {DISSIPATION * SPEED:g}, discrete {approximation}", dt, e, None, e_cont)
    print(f"Drake {version('drake')}: sphere on a half space, no gravity, no friction")
    table.print()
    translated(drake)


# ---------------------------------------------------------------------------------------------------------------
# `impact translate --to drake`: the snippet's properties and plant config
# ---------------------------------------------------------------------------------------------------------------
HC_STIFFNESS = 1.0e5  # N/m, the hunt-crossley scene's contact stiffness (exponent 1)
HC_E = 0.8  # its restitution
KV_STIFFNESS = 1.0e4  # N/m, the kelvin-voigt scene's (the MuJoCo case: m = 0.5 kg, 1 m/s)
KV_E = 0.75
SAP_STEPS = [1e-3, 1e-4, 1e-5, 1e-6]  # s: --dt of the kelvin-voigt translation (Drake's SAP step)


def ball_scene(title, contact):
    return common.scene_text(
        title,
        [{"name": "ball", "mass": MASS, "radius": RADIUS, "velocity": [0.0, 0.0, -SPEED]},
         {"name": "ground", "mass": float("inf"), "radius": float("inf"), "velocity": [0.0, 0.0, 0.0]}],
        dict(contact, normal=[0.0, 0.0, -1.0]))


def run_snippet(snippet):
    """Executes the translation's snippet: (its `props` and `config`, the error of the snippet as it stands or
    None). When Drake rejects the snippet's AddContactMaterial keywords, the same values are given the way Drake
    1.51 takes them (dissipation=..., and relaxation_time as the ("material", "relaxation_time") property) and the
    snippet's own error is returned beside."""
    names = {}
    try:
        exec(snippet, names)
        return names["props"], names["config"], None
    except TypeError as error:
        lines = str(error).splitlines()
        invoked = [line for line in lines if line.startswith("Invoked with")]
        first = lines[0] + (" " + __import__("re").sub(r"=<[^>]*>", "=...", invoked[0]) if invoked else "")
        fixed = snippet.replace("hunt_crossley_dissipation=", "dissipation=")
        match = __import__("re").search(r"relaxation_time=([^,)]+), ", fixed)
        if match:
            fixed = fixed.replace(match.group(0), "")
            fixed = fixed.replace("config = ", f'props.AddProperty("material", "relaxation_time", {match.group(1)})\n'
                                               "config = ", 1)
        names = {}
        exec(fixed, names)
        return names["props"], names["config"], first


def config_e(drake, props, config):
    """A ball on a half space, both geometries with `props`, the plant from `config`: e."""
    builder = drake.DiagramBuilder()
    plant, _ = drake.AddMultibodyPlant(config, builder)
    ball = plant.AddRigidBody("ball", drake.SpatialInertia.SolidSphereWithMass(MASS, RADIUS))
    for owner, pose, shape, name in [
            (ball, drake.RigidTransform(), drake.Sphere(RADIUS), "ball"),
            (plant.world_body(), drake.HalfSpace.MakePose([0, 0, 1], [0, 0, 0]), drake.HalfSpace(), "ground")]:
        plant.RegisterCollisionGeometry(owner, pose, shape, name, drake.ProximityProperties(props))
    plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, 0.0])
    plant.Finalize()
    simulator = drake.Simulator(builder.Build())
    context = plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    plant.SetFreeBodyPose(context, ball, drake.RigidTransform([0.0, 0.0, RADIUS]))  # touching
    plant.SetFreeBodySpatialVelocity(context, ball, drake.SpatialVelocity(w=[0.0, 0.0, 0.0], v=[0.0, 0.0, -SPEED]))
    if config.time_step == 0:
        simulator.get_mutable_integrator().set_target_accuracy(ACCURACY)
    t = 0.0
    while t < 10.0:
        t += 0.01
        simulator.AdvanceTo(t)
        z = plant.EvalBodyPoseInWorld(context, ball).translation()[2]
        v = plant.EvalBodySpatialVelocityInWorld(context, ball).translational()[2]
        if z > RADIUS and v > 0:
            return v / SPEED
    raise RuntimeError("the ball did not leave the half space")


def translated(drake):
    hc = common.write_scene(ball_scene(
        f"Hunt-Crossley ball, k = {HC_STIFFNESS:g} N/m, exponent 1, e = {HC_E}",
        {"law": "hunt-crossley", "stiffness": HC_STIFFNESS, "exponent": 1.0, "restitution": HC_E}), "drake-hc")
    kv = common.write_scene(ball_scene(
        f"Kelvin-Voigt ball, k = {KV_STIFFNESS:g} N/m, e = {KV_E}",
        {"law": "kelvin-voigt", "stiffness": KV_STIFFNESS, "restitution": KV_E}), "drake-kv")
    table = common.Table("Drake", "translation")
    errors = {}
    for case, path, dt in ([(f"hunt-crossley e = {HC_E}, continuous", hc, None)]
                           + [(f"kelvin-voigt e = {KV_E}, SAP", kv, dt) for dt in SAP_STEPS]):
        t = common.translate(path, "drake", dt)
        props, config, error = run_snippet(t["snippet"])
        if error:
            errors.setdefault(error, t["snippet"])
        e = config_e(drake, props, config)
        values = ", ".join(f"{k} {v:.6g}" for k, v in t["parameters"].items())
        # (continuous: the translation's continuous e is the prediction; SAP: the translation gives no e at dt)
        at_dt = t["restitution_continuous"] if dt is None else t["restitution_at_dt"]
        table.add(f"{case}: {values}", dt, e, at_dt, t["restitution_continuous"])
    print("\nimpact translate --to drake [--dt DT] --json: Drake run with the snippet's properties on both geometries "
          "and its MultibodyPlantConfig")
    table.print()
    for name, path in [("hunt-crossley", hc), ("kelvin-voigt", kv)]:
        with open(path) as f:
            own, _ = common.impact_e(f.read(), "drake-own")
        print(f"the {name} scene's own e (impact run, its restitution read by its law's map): {own:.6f}")
    for error, snippet in errors.items():
        print(f"the snippet as it stands fails: {error}")
    if errors:
        print("  (run with dissipation= for hunt_crossley_dissipation= and props.AddProperty(\"material\", "
              "\"relaxation_time\", tau) for relaxation_time=); the last snippet:")
        print("".join("    " + line + "\n" for line in snippet.splitlines()), end="")


if __name__ == "__main__":
    main()
