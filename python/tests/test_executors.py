"""A sweep cut into shards on an executor — a Dask cluster of two worker processes, a process pool — and joined as
`impact merge` joins them: the same table, value for value, as the local sweep and the command's file."""

import concurrent.futures

import numpy as np
import pytest

import impact

from conftest import MODELS

DEMO = MODELS / "demo.toml"
VARY = {"contact.damping": "0.01:100:37:log", "bodies.0.velocity.0": [0.5, 1.0, 2.0]}
LAWS = ["hunt-crossley", "flores"]


def _same(a, b):
    assert list(a.columns) == list(b.columns)
    for name in a.columns:
        x, y = a.columns[name], b.columns[name]
        if x.dtype == object:
            assert list(x) == list(y), name
        else:
            assert np.array_equal(x, y, equal_nan=True), name
    assert a.csv() == b.csv()


@pytest.fixture(scope="module")
def local():
    return impact.sweep(DEMO, VARY, laws=LAWS, progress=False)


def test_a_dask_cluster_of_two_processes_gives_the_local_sweep(local, command, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            spread = impact.sweep(DEMO, VARY, laws=LAWS, executor=client, progress=False)
            assert len(client.scheduler_info()["workers"]) == 2
    _same(spread, local)
    # And the command's file, byte for byte.
    out = tmp_path / "s.csv"
    command("sweep", DEMO, "--vary", "contact.damping=0.01:100:37:log", "--vary", "bodies.0.velocity.0=0.5,1,2",
            "--law", ",".join(LAWS), "--out", out)
    spread.to_csv(tmp_path / "mine.csv")
    assert (tmp_path / "mine.csv").read_bytes() == out.read_bytes()


def test_a_process_pool_gives_the_local_sweep(local):
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as pool:
        spread = impact.sweep(DEMO, VARY, laws=LAWS, executor=pool, shards=5, progress=False)
    _same(spread, local)


def test_more_shards_than_rows_and_a_thread_pool():
    vary = {"contact.restitution": "0.5,0.8"}
    with concurrent.futures.ThreadPoolExecutor(max_workers=3) as pool:
        spread = impact.sweep(DEMO, vary, executor=pool, shards=10, progress=False)
    _same(spread, impact.sweep(DEMO, vary, progress=False))


def test_a_bad_scene_is_refused_before_anything_is_sent(tmp_path):
    class Refusing:
        def submit(self, *args):
            raise AssertionError("nothing should be sent")

    bad = tmp_path / "bad.toml"
    bad.write_text(DEMO.read_text().replace("[contact]", "[contact]\nnonsense = 1"))
    with pytest.raises(impact.SceneError) as caught:
        impact.sweep(bad, {"contact.restitution": "0.5"}, executor=Refusing(), progress=False)
    assert caught.value.path == str(bad)
    with pytest.raises(ValueError, match="executor"):
        impact.sweep(DEMO, {"contact.restitution": "0.5"}, executor=Refusing(), shard="1/2")
    with pytest.raises(TypeError, match="submit"):
        impact.sweep(DEMO, {"contact.restitution": "0.5"}, executor=object())
