"""impact: impacts of bodies with compliant contact laws, from Python.

The same core as the ``impact`` command (a compiled module, ``impact._impact``); every function returns what the
command's ``--json`` prints for the same scene. See docs/python.md.

>>> import impact
>>> report = impact.run("models/steel-pair-hertz.toml")
>>> report["contact"]["restitution_velocity_ratio"]
"""

import json
from typing import Any, Dict, List, Optional

from . import _impact
from ._report import Report
from ._scene import kind_of
from ._sweep import Sweep, sweep
from .errors import SceneError, SimulationError

__all__ = [
    "run",
    "sweep",
    "translate",
    "calibrate",
    "validate",
    "laws",
    "Report",
    "Sweep",
    "SceneError",
    "SimulationError",
    "__version__",
]

__version__: str = _impact.__version__


def run(scene: Any, *, history: bool = False, samples: Optional[int] = None) -> Report:
    """Simulates a scene — one impact of two bodies or a world — and returns its report.

    ``scene``: a path (str or os.PathLike), TOML text (a str with a newline, starting with ``[`` or with a ``key =``
    line) or a dict shaped like the TOML. ``history=True`` records the contact history (the integrator's steps and
    the located events; a world: its series); ``samples=N`` records N instants evenly spaced over the contact instead.
    Raises SceneError for a scene the command refuses, SimulationError for a run that cannot finish (where the
    command writes its report and exits 1: the integration gave up, a world's step budget was spent; the report, up
    to where the run stopped, is the error's ``report``).
    """
    kind, value = kind_of(scene)
    if not isinstance(history, bool):
        raise TypeError(f"history: expected a bool, got {type(history).__name__}")
    if samples is not None and (not isinstance(samples, int) or isinstance(samples, bool)):
        raise TypeError(f"samples: expected an int, got {type(samples).__name__}")
    report = Report(_impact.run(kind, value, history, samples))
    unfinished = _unfinished(report)
    if unfinished is not None:
        raise SimulationError(unfinished, report=report)
    return report


def _unfinished(report: Report) -> Optional[str]:
    """Why the run did not finish what the scene asked (where the command writes the report and exits 1), or None."""
    solver = report.get("solver")
    if solver is not None and solver.get("gave_up") is not None:
        return (
            f"the integration gave up before the bodies separated ({solver['gave_up']}): "
            "the report (error.report) stops there"
        )
    world = report.get("world")
    if world is not None and world.get("end_reason") == "step_budget":
        return (
            f"the world run stopped before its end at t = {world['end_time']:.6g} s (world.end_reason = "
            '"step_budget"): its report\'s notes say why; the report (error.report) stops there'
        )
    return None


def translate(scene: Any, to: str, *, dt: Optional[float] = None) -> Dict[str, Any]:
    """The scene's contact in another program's terms (``impact translate SCENE --to PEER [--dt S] --json``):
    ``to`` one of lammps, liggghts, mujoco, drake, kratos, adams."""
    kind, value = kind_of(scene)
    if not isinstance(to, str):
        raise TypeError(f"to: expected a program's name (str), got {type(to).__name__}")
    return json.loads(_impact.translate(kind, value, to, None if dt is None else float(dt)))


def calibrate(
    scene: Any = None,
    *,
    law: Optional[str] = None,
    restitution: float,
    approach_speed: Optional[float] = None,
    separation: Optional[str] = None,
) -> Dict[str, Any]:
    """The damping for which the simulated e equals ``restitution`` (``impact calibrate ... --json``)."""
    kind, value = (None, None) if scene is None else kind_of(scene)
    return json.loads(
        _impact.calibrate(
            kind,
            value,
            law,
            float(restitution),
            None if approach_speed is None else float(approach_speed),
            separation,
        )
    )


def validate(case: Optional[str] = None) -> List[Dict[str, Any]]:
    """The validation suite's rows (``impact validate --json [--case NAME]``), each with its ``pass``."""
    return json.loads(_impact.validate(case))


def laws() -> List[Dict[str, Any]]:
    """The contact laws ``impact models`` lists: name, formula, map from e, damping units, source."""
    return json.loads(_impact.laws())
