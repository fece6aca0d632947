#!/usr/bin/env python3
"""Kratos DEM (`DEM_D_Hertz_viscous_Coulomb`) against `impact`: an alumina sphere on a rigid wall, no gravity, no
friction (the sphere and speed of Chung & Ooi's test 3, and of Kratos' own restitution test).

Kratos' Hertz law with a viscous damper, for a sphere on a wall (m* = m, R* = r):
    F = (2/3) kn d + c d',  kn = 2 E* sqrt(R* d),  c = 2 gamma sqrt(m* kn),  cut at zero (the force never pulls),
i.e. F = K d^(3/2) + a sqrt(m* K) d^(1/4) d' with K = (4/3) E* sqrt(R*) and a = 2 sqrt(3/2) gamma = sqrt(6) gamma,
where Kratos' DEM strategy computes gamma from the nominal COEFFICIENT_OF_RESTITUTION with Thornton's fit
(sphere_strategy.py, GammaForHertzThornton). impact's scene: `law = "tsuji"`, `damping = sqrt(6) gamma`,
`separation = "force"` (the cut force ends the contact), `[solver] method = "symplectic-euler"` (Kratos' default
scheme, Symplectic_Euler: v += dt F/m, then x += dt v) with `dt`. The sphere starts touching the wall (the touch on a
step boundary). e = -v_z after / v_z before, read once the sphere has left the wall.
"""

import json
import math
import os
import sys
import tempfile

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: the machine is shared
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

# ---------------------------------------------------------------------------------------------------------------
# The parameters (every number the comparison uses)
# ---------------------------------------------------------------------------------------------------------------
RADIUS = 0.0025  # m
DENSITY = 4000.0  # kg/m^3
YOUNG = 3.8e11  # Pa
POISSON = 0.23
WALL_YOUNG = 1.0e20  # Pa: Kratos' walls need a modulus; this one is rigid to 1e-9 (impact: young = inf)
SPEED = 3.9  # m/s, towards the wall
E_NOMINAL = 0.98  # COEFFICIENT_OF_RESTITUTION
STEPS_PER_CONTACT = [200, 50, 20]  # dt = tc / N
SCHEME = "Symplectic_Euler"  # Kratos' TranslationalIntegrationScheme

MASS = 4.0 / 3.0 * math.pi * RADIUS**3 * DENSITY
E_STAR = YOUNG / (1.0 - POISSON**2)  # against a rigid wall
K = 4.0 / 3.0 * E_STAR * math.sqrt(RADIUS)
TC = 3.2180654597 * (MASS**2 / (K**2 * SPEED)) ** 0.2  # s, the elastic contact's duration


def thornton_gamma(e):
    """Kratos' GammaForHertzThornton (DEMApplication/sphere_strategy.py), read from the installed package when it
    has it, so that the prediction uses the very gamma the run uses."""
    from KratosMultiphysics.DEMApplication.sphere_strategy import ExplicitStrategy
    return ExplicitStrategy.GammaForHertzThornton(None, e)


def materials(snippet=None):
    """MaterialsDEM.json: the driver's own, or, with a translation's `snippet`, the snippet's materials and relation
    (over the driver's values for the keys the snippet leaves out) with the sphere's PARTICLE_DENSITY added."""
    if snippet is not None:
        return snippet_materials(snippet)
    return {
        "materials": [
            {"material_name": "sphere", "material_id": 1,
             "Variables": {"PARTICLE_DENSITY": DENSITY, "YOUNG_MODULUS": YOUNG, "POISSON_RATIO": POISSON}},
            {"material_name": "wall", "material_id": 2,
             "Variables": {"YOUNG_MODULUS": WALL_YOUNG, "POISSON_RATIO": POISSON, "COMPUTE_WEAR": False}}],
        "material_relations": [
            {"material_names_list": ["sphere", "wall"], "material_ids_list": [1, 2],
             "Variables": {"COEFFICIENT_OF_RESTITUTION": E_NOMINAL, "STATIC_FRICTION": 0.0,
                           "DYNAMIC_FRICTION": 0.0, "FRICTION_DECAY": 500.0, "ROLLING_FRICTION": 0.0,
                           "ROLLING_FRICTION_WITH_WALLS": 0.0, "SEVERITY_OF_WEAR": 0.001,
                           "IMPACT_WEAR_SEVERITY": 0.001, "BRINELL_HARDNESS": 200.0,
                           "DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME": "DEM_D_Hertz_viscous_Coulomb",
                           "DEM_CONTINUUM_CONSTITUTIVE_LAW_NAME": "DEM_KDEM",
                           "CONTACT_INTERNAL_FRICC": 0.4, "CONTACT_TAU_ZERO": 300000.0,
                           "ROTATIONAL_MOMENT_COEFFICIENT": 0.0}}],
        "material_assignation_table": [["SpheresPart", "sphere"], ["RigidFacePart", "wall"]],
    }


def snippet_parts(snippet):
    """The snippet's two parts: MaterialsDEM.json (a whole JSON object) and ProjectParameters.json's settings (read
    as the members of one object)."""
    materials_text, _, project_text = snippet.partition("// ProjectParameters.json")
    strip = lambda text: "\n".join(line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("//"))
    try:
        materials_part = json.loads(strip(materials_text))
    except json.JSONDecodeError as error:
        raise RuntimeError(f"the snippet's MaterialsDEM.json does not read as JSON ({error}):\n{materials_text}")
    project_lines = project_text.splitlines()[1:]  # (the rest of the comment line)
    return materials_part, json.loads("{" + strip("\n".join(project_lines)) + "}")


def snippet_materials(snippet):
    given, _ = snippet_parts(snippet)
    base = materials()
    sphere, wall = given["materials"]
    sphere["Variables"].setdefault("PARTICLE_DENSITY", DENSITY)
    relation = given["material_relations"][0]
    relation["Variables"] = dict(base["material_relations"][0]["Variables"], **relation["Variables"])
    return {"materials": [sphere, wall], "material_relations": [relation],
            "material_assignation_table": given["material_assignation_table"]}


def project(dt, snippet=None):
    settings = project_own(dt)
    if snippet is not None:
        settings.update(snippet_parts(snippet)[1])
    return settings


def project_own(dt):
    return {
        "Dimension": 3, "BoundingBoxOption": False, "dem_inlet_option": False,
        "GravityX": 0.0, "GravityY": 0.0, "GravityZ": 0.0,
        "EnergyCalculationOption": False, "VelocityTrapOption": False, "RotationOption": True,
        "CleanIndentationsOption": False, "RemoveBallsInEmbeddedOption": False,
        "solver_settings": {"strategy": "sphere_strategy", "RemoveBallsInitiallyTouchingWalls": False,
                            "material_import_settings": {"materials_filename": "MaterialsDEM.json"}},
        "DeltaOption": "Absolute", "SearchTolerance": 0.0, "CoordinationNumber": 10, "ModelDataInfo": False,
        "VirtualMassCoefficient": 1.0, "RollingFrictionOption": False, "DontSearchUntilFailure": False,
        "ContactMeshOption": False, "OutputFileType": "Binary", "Multifile": "multiple_files",
        "TranslationalIntegrationScheme": SCHEME, "RotationalIntegrationScheme": "Direct_Integration",
        "AutomaticTimestep": False, "DeltaTimeSafetyFactor": 1.0, "MaxTimeStep": dt,
        "FinalTime": 3.0 * TC, "ControlTime": 100, "NeighbourSearchFrequency": 1, "PeriodicDomainOption": False,
        "ElementType": "SphericPartDEMElement3D", "GraphExportFreq": 1.0, "VelTrapGraphExportFreq": 1.0,
        "OutputTimeStep": 1.0, "do_print_results_option": False, "post_vtk_option": False,
        "problem_name": "impact_peer",
    }


def kratos_e(Kratos, DEM, stage_class, dt, folder, snippet=None):
    with open(os.path.join(folder, "MaterialsDEM.json"), "w") as f:
        json.dump(materials(snippet), f)

    class Stage(stage_class):
        def GetMainPath(self):
            return folder

        def ReadModelParts(self, max_node_id=0, max_elem_id=0, max_cond_id=0):
            properties = Kratos.Properties(0)
            walls = Kratos.Properties(0)
            self.spheres_model_part.AddProperties(properties)
            self.rigid_face_model_part.AddProperties(walls)
            scheme = getattr(DEM, SCHEME.replace("_", "") + "Scheme")()
            scheme.SetTranslationalIntegrationSchemeInProperties(properties, True)
            DEM.ForwardEulerScheme().SetRotationalIntegrationSchemeInProperties(properties, True)
            DEM.PropertiesProxiesManager().CreatePropertiesProxies(self.spheres_model_part)
            centre = Kratos.Array3()
            centre[0], centre[1], centre[2] = 0.0, 0.0, RADIUS  # touching the wall z = 0
            self.creator_destructor.CreateSphericParticle(self.spheres_model_part, centre, properties, RADIUS,
                                                          "SphericParticle3D")
            for node in self.spheres_model_part.Nodes:
                node.SetSolutionStepValue(Kratos.VELOCITY_Z, -SPEED)
            h = 10 * RADIUS
            for i, (x, y) in enumerate([(-h, h), (h, h), (-h, -h), (h, -h)]):
                self.rigid_face_model_part.CreateNewNode(3 + i, x, y, 0.0)
            props = self.rigid_face_model_part.GetProperties()[0]
            self.rigid_face_model_part.CreateNewCondition("RigidFace3D3N", 7, [5, 6, 3], props)
            self.rigid_face_model_part.CreateNewCondition("RigidFace3D3N", 8, [3, 6, 4], props)

        def Finalize(self):
            self.final_velocity = [n.GetSolutionStepValue(Kratos.VELOCITY_Z) for n in self.spheres_model_part.Nodes]
            self.final_z = [n.Z for n in self.spheres_model_part.Nodes]
            super().Finalize()

    settings = project(dt, snippet)
    if settings["MaxTimeStep"] != dt:
        raise RuntimeError(f"the snippet's MaxTimeStep is {settings['MaxTimeStep']}, not {dt}")
    stage = Stage(Kratos.Model(), Kratos.Parameters(json.dumps(settings)))
    stage.Run()
    if stage.final_z[0] <= RADIUS:
        raise RuntimeError("the sphere has not left the wall at the end time")
    return stage.final_velocity[0] / SPEED


def main():
    try:
        with common.quiet():  # Kratos' banner
            import KratosMultiphysics as Kratos
            from KratosMultiphysics import Logger
            Logger.GetDefaultOutput().SetSeverity(Logger.Severity.WARNING)
            import KratosMultiphysics.DEMApplication as DEM
            from KratosMultiphysics.DEMApplication.DEM_analysis_stage import DEMAnalysisStage
    except ImportError as error:
        common.skip("Kratos", f"not installed ({error}); pip install KratosMultiphysics KratosDEMApplication")
    gamma = thornton_gamma(E_NOMINAL)
    a = math.sqrt(6.0) * gamma
    table = common.Table("Kratos")
    folder = tempfile.mkdtemp(prefix="kratos-", dir=common.folder())
    cwd = os.getcwd()
    try:
        for steps in STEPS_PER_CONTACT:
            dt = TC / steps
            os.chdir(folder)
            with common.quiet():  # Kratos' warnings (defaults it assigns, deprecations) go to stdout
                e = kratos_e(Kratos, DEM, DEMAnalysisStage, dt, folder)
            os.chdir(cwd)
            text = common.scene_text(
                "Kratos peer: alumina sphere on a rigid wall, DEM_D_Hertz_viscous_Coulomb",
                [{"name": "sphere", "radius": RADIUS, "density": DENSITY, "young": YOUNG, "poisson": POISSON,
                  "velocity": [0.0, 0.0, -SPEED]},
                 {"name": "wall", "radius": float("inf"), "mass": float("inf"), "young": float("inf"),
                  "velocity": [0.0, 0.0, 0.0]}],
                {"law": "tsuji", "damping": a, "separation": "force", "normal": [0.0, 0.0, -1.0]},
                {"method": "symplectic-euler", "dt": dt})
            e_dt, e_cont = common.impact_e(text, "kratos")
            table.add(f"Hertz_viscous_Coulomb e = {E_NOMINAL} (tc/{steps})", dt, e, e_dt, e_cont)
    finally:
        os.chdir(cwd)
    from importlib.metadata import version
    print(f"Kratos DEM {version('KratosDEMApplication')} (KratosMultiphysics {version('KratosMultiphysics')}): "
          f"alumina sphere (r = {RADIUS} m) on a rigid wall at {SPEED} m/s, {SCHEME}, tc = {TC:.4g} s")
    print(f"  COEFFICIENT_OF_RESTITUTION {E_NOMINAL} -> DAMPING_GAMMA {gamma:.6f} (Thornton's fit) -> "
          f"impact tsuji damping a = sqrt(6) gamma = {a:.6f}")
    table.print()
    translated(Kratos, DEM, DEMAnalysisStage, folder)


# ---------------------------------------------------------------------------------------------------------------
# `impact translate --to kratos`: the snippet's materials and settings
# ---------------------------------------------------------------------------------------------------------------
E_TRANSLATE = 0.98  # the e the scene asks for (law = "tsuji", separation = "force")


def translate_scene():
    return common.scene_text(
        f"Alumina sphere on a rigid wall, tsuji, e = {E_TRANSLATE}, separation force",
        [{"name": "sphere", "radius": RADIUS, "density": DENSITY, "young": YOUNG, "poisson": POISSON,
          "velocity": [0.0, 0.0, -SPEED]},
         {"name": "wall", "radius": float("inf"), "mass": float("inf"), "young": float("inf"),
          "velocity": [0.0, 0.0, 0.0]}],
        {"law": "tsuji", "restitution": E_TRANSLATE, "separation": "force", "normal": [0.0, 0.0, -1.0]})


def translated(Kratos, DEM, stage_class, folder):
    """The scene translated at each dt and run in Kratos with the snippet's MaterialsDEM.json entries (both
    materials, the wall's too, as the snippet gives them; the sphere's PARTICLE_DENSITY added) and its
    ProjectParameters.json settings."""
    table = common.Table("Kratos", "translation")
    cwd = os.getcwd()
    shown = None
    path = common.write_scene(translate_scene(), "kratos-translate")
    for steps in STEPS_PER_CONTACT:
        dt = TC / steps
        t = common.translate(path, "kratos", dt)
        try:
            os.chdir(folder)
            with common.quiet():
                e = kratos_e(Kratos, DEM, stage_class, dt, folder, t["snippet"])
        finally:
            os.chdir(cwd)
        nominal = t["parameters"]["COEFFICIENT_OF_RESTITUTION"]
        table.add(f"tsuji e = {E_TRANSLATE}, force: COEFFICIENT_OF_RESTITUTION {nominal:.6f} (tc/{steps})", dt, e,
                  t["restitution_at_dt"], t["restitution_continuous"])
        shown = t
    print(f"\nimpact translate --to kratos --dt DT --json: Kratos run with the snippet's materials (YOUNG_MODULUS "
          f"{shown['parameters']['YOUNG_MODULUS'][0]:.6g} Pa, POISSON_RATIO {shown['parameters']['POISSON_RATIO'][0]} on "
          f"the sphere and the wall) and settings")
    table.print()


if __name__ == "__main__":
    main()
