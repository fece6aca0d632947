"""What the peer drivers share: running `impact` on a scene and printing the table.

Each driver (mujoco_peer.py, lammps_peer.py, ...) runs one real program on a contact, writes the same contact as an
`impact` scene (in a temporary folder, from the parameters at the top of the driver) and prints

    case, dt, e (program), e (impact predicted), difference

where the prediction is `impact run SCENE --json` with `[solver] method = "<the program's scheme>"` and `dt` (the
e the program should give at its step) and, in the same row, the continuous e (the accurate path's).
"""

import atexit
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
IMPACT = os.environ.get("IMPACT", os.path.join(ROOT, "target", "release", "impact"))
SKIP = 3  # the exit status of a driver whose program is not installed (peer-simulators.sh reports it and goes on)

_tmp = tempfile.mkdtemp(prefix="impact-peers-")  # the generated scenes and the programs' files; removed at exit
_keep = []  # unless a program failed: its output is kept for reading


def folder():
    """The run's temporary folder."""
    return _tmp


atexit.register(lambda: None if _keep else shutil.rmtree(_tmp, ignore_errors=True))


def skip(program, why):
    print(f"{program}: skipped: {why}")
    sys.exit(SKIP)


class quiet:
    """Send what a program's C++ side writes to stdout (banners, logs) to a file, so that the table stays
    readable; the file's path is printed to stderr when the block fails."""

    def __enter__(self):
        sys.stdout.flush()
        self.path = os.path.join(_tmp, "program-output.log")
        self.log = open(self.path, "a")
        self.saved = os.dup(1)
        os.dup2(self.log.fileno(), 1)
        return self

    def __exit__(self, kind, value, traceback):
        sys.stdout.flush()
        os.dup2(self.saved, 1)
        os.close(self.saved)
        self.log.close()
        if kind is not None and not issubclass(kind, ImportError):  # (an ImportError: the program is missing)
            _keep.append(self.path)
            print(f"(the program's output: {self.path}; {kind.__name__}: {value})", file=sys.stderr)
        return False


def toml_value(v):
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, float) and v == float("inf"):
        return "inf"
    return repr(v)


def scene_text(title, bodies, contact, solver=None):
    """An impact scene (TOML) from plain dicts."""
    lines = [f"title = {toml_value(title)}", ""]
    for body in bodies:
        lines.append("[[bodies]]")
        lines += [f"{k} = {toml_value(v)}" for k, v in body.items()]
        lines.append("")
    lines.append("[contact]")
    lines += [f"{k} = {toml_value(v)}" for k, v in contact.items()]
    if solver:
        lines += ["", "[solver]"] + [f"{k} = {toml_value(v)}" for k, v in solver.items()]
    return "\n".join(lines) + "\n"


def impact_report(text, name="scene"):
    """`impact run --json` on a scene given as text: the parsed report."""
    path = os.path.join(_tmp, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    run = subprocess.run([IMPACT, "run", path, "--json"], capture_output=True, text=True)
    if run.returncode != 0:
        _keep.append(path)
        raise RuntimeError(f"impact run {path} failed ({run.returncode}):\n{run.stderr}")
    return json.loads(run.stdout)


def impact_e(text, name="scene"):
    """(e, e continuous) of a scene: e at the scene's fixed step (or the accurate e when it has none) and the
    accurate path's e (the same when no fixed step is asked)."""
    report = impact_report(text, name)
    e = report["contact"]["restitution_velocity_ratio"]
    continuous = report.get("solver", {}).get("restitution_continuous")
    return e, e if continuous is None else continuous


def write_scene(text, name):
    """A scene given as text written into the run's folder: its path."""
    path = os.path.join(_tmp, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def translate(scene, peer, dt=None):
    """`impact translate SCENE --to PEER [--dt DT] --json`, parsed: SCENE a path, or a scene's text (written into the
    run's folder first)."""
    path = scene if os.path.exists(scene) else write_scene(scene, f"translate-{peer}")
    command = [IMPACT, "translate", path, "--to", peer, "--json"] + ([] if dt is None else ["--dt", repr(dt)])
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        _keep.append(path)
        raise RuntimeError(f"{' '.join(command)} failed ({run.returncode}):\n{run.stderr}")
    return json.loads(run.stdout)


class Table:
    """case, dt, e (program), e (impact at dt), difference, e (impact continuous). `against` names the prediction
    ("impact": `impact run` on the same contact; "translation": `impact translate`'s restitution_at_dt and
    restitution_continuous)."""

    def __init__(self, program, against="impact"):
        self.program = program
        self.against = against
        self.rows = []

    def add(self, case, dt, e_program, e_impact_dt, e_impact_continuous):
        """dt None: the program ran in continuous time (pass impact's continuous e as e_impact_dt too);
        e_impact_dt None: impact has no scheme for the program's step (no difference is shown)."""
        self.rows.append((case, dt, e_program, e_impact_dt, e_impact_continuous))

    def print(self):
        width = max([len("case")] + [len(r[0]) for r in self.rows])
        a = self.against
        print(f"{'case':<{width}}  {'dt (s)':>10}  {'e (' + self.program + ')':>16}  {'e (' + a + ', dt)':>{len(a) + 8}}  "
              f"{'difference':>11}  {'e (' + a + ', dt -> 0)':>{len(a) + 13}}")
        for case, dt, e, e_dt, e_cont in self.rows:
            step = "continuous" if dt is None else f"{dt:.3g}"
            at_dt = ("no scheme" if self.against == "impact" else "not given") if e_dt is None else f"{e_dt:.6f}"
            difference = "n/a" if e_dt is None else f"{e - e_dt:.2e}"
            print(f"{case:<{width}}  {step:>10}  {e:>16.6f}  {at_dt:>{len(a) + 8}}  {difference:>11}  "
                  f"{e_cont:>{len(a) + 13}.6f}")
