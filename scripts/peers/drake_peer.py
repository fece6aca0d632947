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


if __name__ == "__main__":
    main()
