"""impact.sweep against `impact sweep` on the same grid: the columns cell for cell, to_csv byte for byte, shards,
laws, chosen columns, threads, and the errors of bad arguments."""

import csv
import math
import os

import numpy as np
import pytest

import impact

from conftest import MODELS

DEMO = MODELS / "demo.toml"


def _read(path):
    with open(path, newline="") as file:
        rows = list(csv.reader(file))
    return rows[0], rows[1:]


def _same_cells(sweep, header, rows):
    assert list(sweep.columns) == header
    assert len(sweep) == len(rows)
    for k, name in enumerate(header):
        cells = [row[k] for row in rows]
        column = sweep.columns[name]
        if column.dtype == object:
            assert list(column) == cells, name
        else:
            assert column.dtype == np.float64, name
            for cell, value in zip(cells, column):
                assert (cell == "" and math.isnan(value)) or float(cell) == value, (name, cell, value)


@pytest.mark.parametrize(
    "vary, laws, columns",
    [
        ({"contact.restitution": "0.05:1:7"}, ["hunt-crossley", "lankarani-nikravesh", "flores", "kelvin-voigt"], None),
        ({"contact.damping": "0.01:100:5:log"}, None, None),
        ({"contact.restitution": [0.2, 0.5, 0.9], "bodies.0.velocity.0": "0.5,1,2"}, None,
         ["restitution_velocity_ratio", "approach_speed", "steps"]),
        ({"contact.restitution": "0.5,0.8"}, None, ["restitution_velocity_ratio", "first_failure", "elastic_ratio"]),
    ],
)
def test_the_columns_and_the_csv_are_the_commands(command, tmp_path, vary, laws, columns):
    out = tmp_path / "sweep.csv"
    args = ["sweep", DEMO, "--out", out]
    for key, values in vary.items():
        spec = values if isinstance(values, str) else ",".join(repr(float(v)) for v in values)
        args += ["--vary", f"{key}={spec}"]
    if laws:
        args += ["--law", ",".join(laws)]
    if columns:
        args += ["--columns", ",".join(columns)]
    command(*args)
    sweep = impact.sweep(DEMO, vary, laws=laws, columns=columns, progress=False)
    header, rows = _read(out)
    _same_cells(sweep, header, rows)
    mine = tmp_path / "mine.csv"
    sweep.to_csv(mine)
    assert mine.read_bytes() == out.read_bytes()


def test_a_point_a_law_cannot_take_is_an_error_row_and_empty_cells(command, tmp_path):
    # hertz is elastic (e = 1 only): its rows say why they could not run, their results empty (NaN); Hunt–Crossley
    # runs both points (its map has a floor: nominal e = 0 gives a positive e).
    vary = {"contact.restitution": "0,0.5"}
    sweep = impact.sweep(DEMO, vary, laws="hertz,hunt-crossley", progress=False)
    status = list(sweep.columns["status"])
    assert [s.startswith("error: contact.restitution: `hertz`") for s in status] == [True, False, True, False]
    assert status[1] == status[3] == "ok"
    e = sweep.columns["restitution_velocity_ratio"]
    assert np.isnan(e[[0, 2]]).all() and 0 < e[1] < e[3] < 1
    assert list(sweep.columns["law"]) == ["hertz", "hunt-crossley"] * 2
    out = tmp_path / "s.csv"
    command("sweep", DEMO, "--vary", "contact.restitution=0,0.5", "--law", "hertz,hunt-crossley", "--out", out)
    assert sweep.csv().encode() == out.read_bytes()


def test_the_restitution_follows_the_exact_map():
    # carvalho-martins (the demo's law) takes alpha from the exact inverse of Hunt–Crossley's e(x), so the simulated
    # e is the nominal one (docs/laws.md).
    nominal = np.linspace(0.1, 0.95, 12)
    sweep = impact.sweep(DEMO, {"contact.restitution": nominal}, columns="restitution_velocity_ratio", progress=False)
    assert np.allclose(sweep.columns["restitution_velocity_ratio"], nominal, rtol=1e-9, atol=0)
    assert np.array_equal(sweep.columns["contact.restitution"], nominal)


def test_shards_are_the_commands_and_merge_into_the_whole(command, tmp_path):
    vary = {"contact.damping": "0.01:100:9:log"}
    whole = impact.sweep(DEMO, vary, progress=False)
    for i in (1, 2, 3):
        out = tmp_path / f"s{i}.csv"
        command("sweep", DEMO, "--vary", "contact.damping=0.01:100:9:log", "--shard", f"{i}/3", "--out", out)
        part = impact.sweep(DEMO, vary, shard=f"{i}/3", progress=False)
        assert part.csv().encode() == out.read_bytes()
        assert list(part.columns["index"]) == list(range(i - 1, 9, 3))
    assert len(whole) == 9


def test_the_table_does_not_depend_on_the_threads():
    vary = {"contact.restitution": "0.1:0.9:40"}
    one = impact.sweep(DEMO, vary, threads=1, progress=False)
    two = impact.sweep(DEMO, vary, threads=2, progress=False)
    assert one.csv() == two.csv()


def test_the_columns_are_read_only_numpy_arrays():
    sweep = impact.sweep(DEMO, {"contact.restitution": "0.5,0.8"}, progress=False)
    e = sweep.columns["restitution_velocity_ratio"]
    assert isinstance(e, np.ndarray) and e.dtype == np.float64
    with pytest.raises(ValueError):
        e[0] = 0.0
    assert sweep.columns["status"].dtype == object


def test_pandas_sees_the_same_table():
    pandas = pytest.importorskip("pandas")
    sweep = impact.sweep(DEMO, {"contact.restitution": "0.5,0.8"}, progress=False)
    frame = sweep.to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == list(sweep.columns)
    assert frame["restitution_velocity_ratio"].tolist() == sweep.columns["restitution_velocity_ratio"].tolist()


@pytest.mark.parametrize(
    "vary, kwargs, error, words",
    [
        ({"contact.nothing": "0:1:2"}, {}, ValueError, "nothing"),
        ({"contact.restitution": "0:1"}, {}, ValueError, "START:STOP:COUNT"),
        ({"contact.restitution": "0.5"}, {"laws": ["no-such-law"]}, ValueError, "no-such-law"),
        ({"contact.restitution": "0.5"}, {"columns": ["no_such_column"]}, ValueError, "no_such_column"),
        ({"contact.restitution": "0.5"}, {"shard": "3/2"}, ValueError, "--shard"),
        ({"contact.restitution": "0.5"}, {"threads": 0}, ValueError, "threads"),
        ({"contact.restitution": [[0.1, 0.2]]}, {}, ValueError, "1-D"),
        ({"contact.restitution": ["a"]}, {}, TypeError, "numbers"),
        ({}, {}, ValueError, "at least one"),
        ("contact.restitution=0.5", {}, TypeError, "dict"),
    ],
)
def test_bad_arguments_are_python_errors(vary, kwargs, error, words):
    with pytest.raises(error, match=words):
        impact.sweep(DEMO, vary, progress=False, **kwargs)


def test_a_bad_scene_is_a_scene_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(DEMO.read_text().replace("[contact]", "[contact]\nnonsense = 1"))
    with pytest.raises(impact.SceneError) as caught:
        impact.sweep(bad, {"contact.restitution": "0.5"}, progress=False)
    assert caught.value.path == str(bad)
    assert caught.value.key == "contact.nonsense"
    assert caught.value.line is not None


def test_a_world_sweep_is_the_commands(command, tmp_path):
    # The cradle's gap (docs/world.md#sweeps): touching, the last ball leaves at Herrmann & Schmälzle's 0.9945 v0;
    # half a millimetre apart, the contacts are apart and it leaves at the sequential model's 1 m/s.
    scene = MODELS / "newtons-cradle-gaps.toml"
    vary = {"bodies.2.position.0": [0.04001, 0.04002, 0.04003, 0.0405]}
    columns = ["bodies.2.velocity_after.0", "contacts.1.overlapping.0", "world.end_reason"]
    out = tmp_path / "gaps.csv"
    command("sweep", scene, "--vary", "bodies.2.position.0=0.04001,0.04002,0.04003,0.0405", "--columns",
            ",".join(columns), "--out", out)
    sweep = impact.sweep(scene, vary, columns=columns, progress=False)
    header, rows = _read(out)
    _same_cells(sweep, header, rows)
    assert sweep.csv().encode() == out.read_bytes()
    sweep.to_csv(tmp_path / "mine.csv")
    assert (tmp_path / "mine.csv").read_bytes() == out.read_bytes()
    last = sweep.columns["bodies.2.velocity_after.0"]
    assert last[0] == pytest.approx(0.9945, abs=1e-4) and last[3] == pytest.approx(1.0, abs=1e-9)
    assert sweep.columns["world.end_reason"].dtype == object


def test_a_world_sweep_takes_no_laws_shards_or_executor():
    scene = MODELS / "newtons-cradle-gaps.toml"
    vary = {"bodies.2.position.0": "0.04001,0.0405"}
    with pytest.raises(ValueError, match="laws"):
        impact.sweep(scene, vary, laws="hertz", progress=False)
    with pytest.raises(ValueError, match="shard"):
        impact.sweep(scene, vary, shard="1/2", progress=False)

    class Pool:
        def submit(self, *args):
            raise AssertionError("nothing should be sent")

    with pytest.raises(ValueError, match="world"):
        impact.sweep(scene, vary, executor=Pool(), progress=False)


def test_to_csv_never_replaces_the_sweeps_scene(tmp_path):
    # An output never replaces an input: the scene file itself, a symbolic link to it and a hard link to it are
    # refused (as `impact sweep --out` refuses them), and the scene is left as it was; another file is written.
    scene = tmp_path / "scene.toml"
    text = (MODELS / "tsuji-dem-alumina.toml").read_text()
    scene.write_text(text)
    (tmp_path / "link.csv").symlink_to(scene)
    os.link(scene, tmp_path / "hard.csv")
    table = impact.sweep(scene, {"contact.restitution": [0.5, 0.6]})
    for target in (scene, tmp_path / "link.csv", tmp_path / "hard.csv"):
        with pytest.raises(ValueError, match="never replaces an input"):
            table.to_csv(target)
        assert scene.read_text() == text
    table.to_csv(tmp_path / "rows.csv")
    assert (tmp_path / "rows.csv").read_text() == table.csv()


def test_to_csv_refuses_an_empty_path(tmp_path):
    # An empty path names no file: a clear ValueError, not the operating system's error.
    table = impact.sweep(MODELS / "tsuji-dem-alumina.toml", {"contact.restitution": [0.5, 0.6]})
    with pytest.raises(ValueError, match="path is empty"):
        table.to_csv("")
