"""translate, calibrate, validate and laws: each the JSON the command's --json prints (or, for laws, what
`impact models` lists) for the same arguments."""

import json

import pytest

import impact

from conftest import MODELS


@pytest.mark.parametrize(
    "model, to, dt",
    [
        ("tsuji-dem-alumina.toml", "lammps", 1.3e-7),
        ("mujoco-typed-physical.toml", "mujoco", 2e-4),
        ("linear-hunt-crossley.toml", "drake", None),
        ("dem-hertz-0.98.toml", "kratos", 2e-8),
        ("hysteresis-lankarani-nikravesh.toml", "adams", None),
    ],
)
def test_translate_is_the_commands_json(command, model, to, dt):
    args = ["translate", MODELS / model, "--to", to, "--json"] + (["--dt", repr(dt)] if dt else [])
    assert impact.translate(MODELS / model, to, dt=dt) == json.loads(command(*args).stdout)


@pytest.mark.parametrize(
    "scene, kwargs, flags",
    [
        (None, {"law": "lankarani-nikravesh", "restitution": 0.5, "approach_speed": 2.0},
         ["--law", "lankarani-nikravesh", "--restitution", "0.5", "--approach-speed", "2"]),
        ("rubber-ball-kelvin-voigt.toml", {"restitution": 0.6, "separation": "force"},
         ["--restitution", "0.6", "--separation", "force"]),
        ("viscoelastic-spheres.toml", {"restitution": 0.7}, ["--restitution", "0.7"]),
    ],
)
def test_calibrate_is_the_commands_json(command, scene, kwargs, flags):
    path = None if scene is None else MODELS / scene
    expected = json.loads(command("calibrate", *([path] if path else []), *flags, "--json").stdout)
    assert impact.calibrate(path, **kwargs) == expected


def test_calibration_for_the_exact_map():
    # Hunt–Crossley's exact relation (docs/references.md): e is the nominal one when alpha = chi(e)/v0, so the
    # calibrated damping, simulated, gives e back.
    found = impact.calibrate(law="hunt-crossley", restitution=0.8, approach_speed=1.0)
    assert found["restitution_simulated"] == pytest.approx(0.8, abs=1e-9)


def test_validate_is_the_commands_json(command):
    rows = impact.validate("cradle-3")
    assert rows == json.loads(command("validate", "--json", "--case", "cradle-3").stdout)
    # Herrmann & Schmälzle's cradle (1981): the third ball leaves at 0.9945 v0.
    third = [r for r in rows if r["quantity"].startswith("ball 3")][0]
    assert third["reference"] == pytest.approx(0.9945)
    assert all(r["pass"] for r in rows)


def test_the_whole_validation_suite_passes():
    rows = impact.validate()
    assert len(rows) > 50 and all(r["pass"] for r in rows)


def test_laws_are_what_impact_models_lists(command):
    listed = command("models").stdout
    laws = impact.laws()
    assert len(laws) == 18
    for law in laws:
        assert set(law) == {"name", "formula", "map", "damping_units", "source"}
        block = listed.split(f"\n{law['name']}\n", 1)[1] if not listed.startswith(law["name"]) else listed
        assert f"force     F = {law['formula']}" in block
        assert f"source    {law['source']}" in block
    assert [law["name"] for law in laws][:2] == ["hertz", "kelvin-voigt"]
