"""Bad input raises a Python exception, never a crash: SceneError for every scene the command refuses (the project's
hostile corpus, run through impact.run as files and as text), with the command's message, path, line and key; a
dict's errors name its dotted path; TypeError and ValueError for bad arguments."""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

import impact

from conftest import MODELS, ROOT

CORPUS = ROOT / "target" / "hostile-corpus"


def _corpus():
    manifest = CORPUS / "manifest.json"
    if not manifest.exists():
        subprocess.run(["cargo", "test", "--locked", "--test", "hostile_corpus", "the_corpus_is_written"], cwd=ROOT,
                       check=True, capture_output=True)
    return json.loads(manifest.read_text())


CASES = _corpus()


def test_the_corpus_is_the_projects():
    assert len(CASES) >= 60


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_every_hostile_scene_is_a_scene_error_as_the_command_says(case, command):
    path = CORPUS / case["file"]
    with pytest.raises(impact.SceneError) as caught:
        impact.run(path)
    error = caught.value
    assert isinstance(error, ValueError)
    assert error.path == str(path)
    if case["key"] is not None:
        # (The corpus asserts the key the message names; a key inside a table is named with its table's path.)
        assert error.key == case["key"] or error.key.endswith("." + case["key"])
    if case["line"] is not None:
        assert error.line == case["line"]
    # str() is the command's message, which it prints after "impact: " (exit status 2).
    done = command("run", path, check=False)
    assert done.returncode == 2
    assert done.stderr.strip() == f"impact: {error}"


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_every_hostile_text_is_a_scene_error_too(case):
    data = (CORPUS / case["file"]).read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        pytest.skip("not UTF-8: a str cannot hold it (the file case covers it)")
    if "\n" not in text:
        text += "\n"  # so that the str is TOML text, not a path
    with pytest.raises(impact.SceneError) as caught:
        impact.run(text)
    assert caught.value.path is None
    if case["line"] is not None:
        assert caught.value.line == case["line"]


BASE = {
    "bodies": [
        {"radius": 0.01, "mass": 0.03, "velocity": [1.0, 0.0, 0.0]},
        {"radius": float("inf"), "mass": float("inf"), "velocity": [0.0, 0.0, 0.0]},
    ],
    "contact": {"law": "hunt-crossley", "restitution": 0.8, "stiffness": 1e9},
}


def _with(path, value):
    scene = json.loads(json.dumps(BASE), parse_constant=float)
    scene["bodies"][1]["radius"] = scene["bodies"][1]["mass"] = float("inf")
    at = scene
    *parents, last = path
    for part in parents:
        at = at[part]
    at[last] = value
    return scene


@pytest.mark.parametrize(
    "path, value, key",
    [
        (("bodies", 0, "mass"), float("nan"), "bodies.0.mass"),
        (("bodies", 0, "mass"), "heavy", "bodies.0.mass"),
        (("bodies", 0, "velocity"), [1.0, 0.0], "bodies.0.velocity"),
        (("bodies", 1, "velocity"), [0.0, float("-inf"), 0.0], "bodies.1.velocity"),
        (("contact", "colour"), "red", "contact.colour"),
        (("contact", "law"), "no-such-law", "contact.law"),
        (("contact", "restitution"), 1.5, "contact.restitution"),
        (("contact", "restitution"), None, "contact.restitution"),
        (("contact", "restitution"), object(), "contact.restitution"),
        (("bodies", 0, "velocity"), [1.0, None, 0.0], "bodies.0.velocity.1"),
        (("contact", "stiffness"), 2**70, "contact.stiffness"),
        (("bodies",), "two", "bodies"),
    ],
)
def test_a_dicts_errors_name_its_dotted_path_and_no_line(path, value, key):
    with pytest.raises(impact.SceneError) as caught:
        impact.run(_with(path, value))
    error = caught.value
    assert error.key == key
    assert error.line is None and error.path is None
    assert error.message and error.message in str(error)


def test_the_base_dict_is_valid():
    assert impact.run(_with(("title",), "valid"))["title"] == "valid"


def test_text_errors_give_the_line():
    text = (MODELS / "demo.toml").read_text().replace("[contact]", "[contact]\nnonsense = 1")
    line = text.splitlines().index("nonsense = 1") + 1
    with pytest.raises(impact.SceneError) as caught:
        impact.run(text)
    assert (caught.value.key, caught.value.line, caught.value.path) == ("contact.nonsense", line, None)


def test_scene_errors_survive_pickling():
    import pickle

    with pytest.raises(impact.SceneError) as caught:
        impact.run(_with(("contact", "colour"), "red"))
    again = pickle.loads(pickle.dumps(caught.value))
    assert (again.key, again.line, again.path, str(again)) == (
        caught.value.key, caught.value.line, caught.value.path, str(caught.value))


@pytest.mark.parametrize("scene", [42, b"models/demo.toml", None, [1, 2]])
def test_a_scene_of_another_type_is_a_type_error(scene):
    with pytest.raises(TypeError, match="scene"):
        impact.run(scene)


@pytest.mark.parametrize("samples, error", [(1, ValueError), (10**7, ValueError), (2.5, TypeError)])
def test_bad_samples(samples, error):
    with pytest.raises(error, match="samples"):
        impact.run(MODELS / "demo.toml", samples=samples)


def test_samples_are_one_impacts_only():
    with pytest.raises(ValueError, match="samples"):
        impact.run(MODELS / "newtons-cradle-3.toml", samples=100)


def test_translate_calibrate_validate_refuse_bad_arguments():
    with pytest.raises(ValueError, match="--to"):
        impact.translate(MODELS / "demo.toml", "no-such-program")
    with pytest.raises(ValueError, match="--dt"):
        impact.translate(MODELS / "tsuji-dem-alumina.toml", "lammps", dt=-1.0)
    with pytest.raises(impact.SceneError):
        impact.translate(MODELS / "newtons-cradle-3.toml", "mujoco")
    with pytest.raises(ValueError, match="restitution"):
        impact.calibrate(law="hunt-crossley", restitution=1.5)
    with pytest.raises(ValueError, match="--law"):
        impact.calibrate(restitution=0.5)
    with pytest.raises(ValueError, match="no validation case"):
        impact.validate("no-such-case")


def test_a_dict_nested_without_end_is_a_scene_error_not_a_crash():
    deep = [1.0]
    for _ in range(100_000):
        deep = [deep]
    with pytest.raises(impact.SceneError, match="nested"):
        impact.run(_with(("bodies", 0, "velocity"), deep))
    selfish = _with(("title",), "x")
    selfish["contact"]["itself"] = selfish["contact"]
    with pytest.raises(impact.SceneError, match="nested"):
        impact.run(selfish)


def test_a_panic_never_escapes_as_a_panic_exception():
    # The corpus' biggest inputs and deepest nesting, as text: whatever the core does, Python sees SceneError.
    deep = "[contact]\nlaw = " + "[" * 10000 + "]" * 10000 + "\n"
    with pytest.raises(impact.SceneError):
        impact.run(deep)
    huge = {"bodies": [{"radius": 1e308, "mass": 1e-308, "velocity": [1e308, 0, 0]}] * 2,
            "contact": {"law": "hertz", "stiffness": 1e-308}}
    with pytest.raises((impact.SceneError, impact.SimulationError)):
        impact.run(huge)


def test_what_exits_1_is_a_simulation_error(command, tmp_path):
    # LAMMPS' velocity Verlet at a step of 1 µs (a fifth of this contact) cannot give e = 0.9999 with any nominal e:
    # the command exits 1, Python raises SimulationError with its message.
    scene = tmp_path / "near-elastic.toml"
    text = (MODELS / "tsuji-dem-alumina.toml").read_text()
    scene.write_text("\n".join("restitution = 0.9999" if l.startswith("restitution =") else l
                               for l in text.splitlines()) + "\n")
    done = command("translate", scene, "--to", "lammps", "--dt", "1e-6", "--json", check=False)
    assert done.returncode == 1
    with pytest.raises(impact.SimulationError) as caught:
        impact.translate(scene, "lammps", dt=1e-6)
    assert isinstance(caught.value, RuntimeError)
    assert done.stderr.strip() == f"impact: {caught.value}"


CREEPING = (
    "[[bodies]]\nradius = 1.0\nmass = 1.0\nvelocity = [1.0, 0.0, 0.0]\n\n[[bodies]]\nradius = inf\nmass = inf\n"
    "velocity = [0.0, 0.0, 0.0]\n\n[contact]\nlaw = \"kelvin-voigt\"\ndamping = 1e6\nstiffness = 1e6\n\n"
    "[solver]\nmethod = \"dop853\"\n"
)


def test_an_impact_whose_integration_gave_up_is_a_simulation_error_holding_its_report(command, tmp_path):
    # A Kelvin–Voigt contact damped so heavily (c = 1e6 N s/m for k = 1e6 N/m) that the ball creeps into the wall: the
    # command writes the report and exits 1; Python raises SimulationError whose report is the command's.
    path = tmp_path / "creeping.toml"
    path.write_text(CREEPING)
    done = command("run", path, "--json", check=False)
    assert done.returncode == 1, done.stderr
    with pytest.raises(impact.SimulationError) as caught:
        impact.run(path)
    error = caught.value
    assert "gave up" in str(error)
    assert error.report is not None
    assert error.report["contact"]["separated"] is False
    assert error.report["solver"]["gave_up"] == json.loads(done.stdout)["solver"]["gave_up"]


def test_a_world_its_step_budget_stopped_is_a_simulation_error_holding_its_report(command, tmp_path):
    # The ball stack falls onto the floor, which takes more than 40 steps: the command exits 1 with the report.
    stack = (MODELS / "ball-stack.toml").read_text().replace("max_contacts = 2", "max_contacts = 2\nmax_steps = 40")
    path = tmp_path / "stack.toml"
    path.write_text(stack)
    done = command("run", path, "--json", check=False)
    assert done.returncode == 1, done.stderr
    with pytest.raises(impact.SimulationError) as caught:
        impact.run(path)
    report = caught.value.report
    assert report["world"]["end_reason"] == "step_budget"
    assert report["world"]["end_time"] == json.loads(done.stdout)["world"]["end_time"]
    assert "step budget" in str(caught.value) or "step_budget" in str(caught.value)


def test_a_settled_impact_is_no_error():
    # A critically damped Kelvin–Voigt contact dies out at d = 0 without separating: it ends on its own terms.
    settled = CREEPING.replace(
        'law = "kelvin-voigt"\ndamping = 1e6\nstiffness = 1e6',
        'law = "kelvin-voigt"\nrestitution = 0.0\nstiffness = 1e6\nexponent = 1.0\nseparation = "penetration"',
    )
    report = impact.run(settled)
    assert report["contact"]["separated"] is False
    assert report["solver"]["gave_up"] is None
