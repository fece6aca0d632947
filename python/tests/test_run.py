"""impact.run against `impact run` on the same scenes: the report key for key, the JSON text, the history's columns,
the figures, the scene as a path, as TOML text and as a dict."""

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

import impact

from conftest import MODELS, ROOT, without_wall_time

ONE_IMPACT = ["steel-pair-hertz.toml", "demo.toml", "lecture-oblique.toml", "rubber-ball-kelvin-voigt.toml",
              "hung-rod.toml", "yielding-steel-ball.toml", "dem-verlet-alumina.toml"]
WORLDS = ["newtons-cradle-3.toml", "ball-stack.toml"]


@pytest.mark.parametrize("model", ONE_IMPACT + WORLDS)
def test_the_report_is_the_commands_key_for_key(model, command):
    scene = MODELS / model
    expected = json.loads(command("run", scene, "--json").stdout)
    report = impact.run(scene)
    assert without_wall_time(report.to_dict()) == without_wall_time(expected)
    # The Mapping reads the same values, and the JSON text is the command's format (wall time apart).
    assert report["title"] == expected["title"]
    assert set(report) == set(expected)
    assert without_wall_time(json.loads(report.json())) == without_wall_time(expected)


def test_the_json_text_is_the_commands_but_for_the_measured_wall_time(command):
    scene = MODELS / "steel-pair-hertz.toml"
    text = command("run", scene, "--json").stdout
    mine = impact.run(scene).json()
    strip = lambda t: [line for line in t.splitlines() if "wall_time_s" not in line]
    assert strip(mine) == strip(text)


def test_the_report_is_read_only():
    report = impact.run(MODELS / "steel-pair-hertz.toml")
    with pytest.raises(TypeError):
        report["title"] = "x"
    with pytest.raises(TypeError):
        report["contact"]["max_force"] = 0.0
    assert isinstance(report["bodies"], tuple)


def test_the_two_steel_balls_touch_as_hertz_says():
    # Hertz's closed form for two equal steel spheres (R = 10 mm, 7850 kg/m^3, E = 210 GPa, nu = 0.3) closing at
    # v0 = 1 m/s: E* = E / (2 (1 - nu^2)), R* = R/2, m* = m/2, K = 4/3 E* sqrt(R*); the energy balance
    # m* v0^2 / 2 = (2/5) K dmax^(5/2) gives dmax = (5 m* v0^2 / (4 K))^(2/5) (Johnson, Contact Mechanics, 11.1).
    report = impact.run(MODELS / "steel-pair-hertz.toml")
    m_star = 7850 * 4 / 3 * math.pi * 0.01**3 / 2
    e_star = 2.1e11 / (2 * (1 - 0.3**2))
    k = 4 / 3 * e_star * math.sqrt(0.01 / 2)
    dmax = (5 * m_star * 1.0**2 / (4 * k)) ** 0.4
    assert report["effective_mass"] == pytest.approx(m_star, rel=1e-12)
    assert report["contact"]["max_penetration"] == pytest.approx(dmax, rel=1e-9)
    assert report["contact"]["restitution_velocity_ratio"] == pytest.approx(1.0, abs=1e-9)


def _command_csv(command, tmp_path, scene, *extra):
    out = tmp_path / "history.csv"
    command("run", scene, "--csv", out, *extra)
    with open(out, newline="") as file:
        rows = list(csv.reader(file))
    return rows[0], rows[1:]


@pytest.mark.parametrize("extra", [(), ("--samples", "50")])
def test_the_history_is_the_commands_csv_by_column(command, tmp_path, extra):
    scene = MODELS / "demo.toml"
    header, rows = _command_csv(command, tmp_path, scene, *extra)
    samples = int(extra[1]) if extra else None
    history = impact.run(scene, history=samples is None, samples=samples).history
    assert list(history) == header
    for k, name in enumerate(header):
        cells = [row[k] for row in rows]
        if name == "phase":
            assert list(history[name]) == cells
        else:
            assert history[name].dtype == np.float64
            assert np.array_equal(history[name], np.array([float(c) for c in cells]))


def test_a_world_history_is_its_series(command, tmp_path):
    scene = MODELS / "newtons-cradle-3.toml"
    header, rows = _command_csv(command, tmp_path, scene)
    history = impact.run(scene, history=True).history
    assert list(history) == header
    assert len(history["time_s"]) == len(rows)
    assert list(history["kind"]) == [row[1] for row in rows]
    force = history["force_N"]
    cells = [row[header.index("force_N")] for row in rows]
    assert all((c == "" and math.isnan(x)) or float(c) == x for c, x in zip(cells, force))


def test_no_history_unless_asked():
    assert impact.run(MODELS / "demo.toml").history is None


def test_the_figures_are_the_commands_svg(command, tmp_path):
    scene = MODELS / "demo.toml"
    command("run", scene, "--plot", tmp_path / "figs")
    figures = impact.run(scene).figures()
    assert list(figures) == ["force_time", "force_penetration", "velocities"]
    for name, svg in figures.items():
        assert svg == (tmp_path / "figs" / f"{name}.svg").read_text()


def test_a_world_draws_its_figures(command, tmp_path):
    scene = MODELS / "bouncing-ball.toml"
    command("run", scene, "--plot", tmp_path / "figs")
    figures = impact.run(scene).figures()
    assert set(figures) == {"contact_forces", "velocities", "heights"}
    for name, svg in figures.items():
        assert svg == (tmp_path / "figs" / f"{name}.svg").read_text()


def test_jupyter_shows_the_table_and_the_force_time_figure(command):
    scene = MODELS / "demo.toml"
    page = impact.run(scene)._repr_html_()
    table = command("run", scene).stdout
    assert "<svg" in page and "</svg>" in page
    first_line = table.splitlines()[0]
    assert first_line.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;") in page


def test_text_and_dict_give_the_files_report():
    path = MODELS / "demo.toml"
    text = path.read_text()
    from_file = impact.run(path).to_dict()
    from_text = impact.run(text).to_dict()
    tomllib = pytest.importorskip("tomllib")  # Python 3.11+

    from_dict = impact.run(tomllib.loads(text)).to_dict()
    for report in (from_text, from_dict):
        assert without_wall_time(report) == without_wall_time(from_file)


def test_a_str_path_and_a_pathlike_are_the_same_scene():
    a = impact.run(str(MODELS / "demo.toml"))
    b = impact.run(MODELS / "demo.toml")
    assert without_wall_time(a.to_dict()) == without_wall_time(b.to_dict())


def test_a_dict_built_in_python_runs():
    scene = {
        "title": "a dict",
        "bodies": [
            {"radius": 0.01, "mass": 0.03, "velocity": np.array([1.0, 0.0, 0.0])},
            {"radius": float("inf"), "mass": float("inf"), "velocity": (0, 0, 0)},
        ],
        "contact": {"law": "hertz", "stiffness": 1e9},
    }
    report = impact.run(scene)
    assert report["title"] == "a dict"
    # Hertz is elastic: e = 1 (within the integration's accuracy).
    assert report["contact"]["restitution_velocity_ratio"] == pytest.approx(1.0, abs=1e-9)


def test_the_version_is_the_crates():
    cargo = (ROOT / "Cargo.toml").read_text()
    version = next(line.split('"')[1] for line in cargo.splitlines() if line.startswith("version = "))
    assert impact.__version__ == version
