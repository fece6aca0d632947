"""``impact.sweep`` and ``impact.Sweep``: a scene run over a grid of values (and laws) by the core's sweep, held in
memory by column; on an executor, cut into shards that run there and are joined as ``impact merge`` joins them."""

import math
import os
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _impact, _progress
from ._scene import kind_of

__all__ = ["Sweep", "sweep"]

Values = Union[str, Sequence[float], np.ndarray]


def _specs(vary: Mapping[str, Values]) -> List[str]:
    """The command's ``--vary`` specs: ``KEY=SPEC`` for a spec string, ``KEY=V1,V2,...`` for numbers (written with
    all their digits, so each reads back to the same float)."""
    if not isinstance(vary, Mapping):
        raise TypeError(f"vary: expected a dict from dotted key to values, got {type(vary).__name__}")
    if not vary:
        raise ValueError("vary: give at least one key, e.g. {'contact.restitution': '0.1:0.9:9'}")
    specs = []
    for key, values in vary.items():
        if not isinstance(key, str):
            raise TypeError(f"vary: a key must be a dotted scene key (str), got {type(key).__name__}")
        if isinstance(values, str):
            specs.append(f"{key}={values}")
            continue
        array = np.asarray(values)
        if array.ndim != 1:
            raise ValueError(f"vary[{key!r}]: expected a spec string or a 1-D sequence of numbers, got {array.ndim}-D")
        if array.size == 0:
            raise ValueError(f"vary[{key!r}]: no values")
        if array.dtype.kind not in "iuf":
            raise TypeError(f"vary[{key!r}]: expected numbers, got {array.dtype}")
        specs.append(f"{key}=" + ",".join(repr(float(v)) for v in array))
    return specs


def _names(values: Optional[Union[str, Iterable[str]]], what: str) -> List[str]:
    if values is None:
        return []
    if isinstance(values, str):
        return [v for v in values.split(",")]
    names = list(values)
    for name in names:
        if not isinstance(name, str):
            raise TypeError(f"{what}: expected names (str), got {type(name).__name__}")
    return names


class Sweep:
    """A sweep's table: ``columns`` by name (float64 arrays with NaN where the CSV cell is empty; ``status``, ``law``
    and the verdicts as arrays of str), one row per point and law in the command's order."""

    def __init__(self, table: Any, inputs: Sequence[str] = ()) -> None:
        self._table = table
        self._inputs = list(inputs)  # the scene file it read: to_csv never replaces it
        self.columns: Dict[str, np.ndarray] = {
            name: table.column(k) for k, name in enumerate(table.names())
        }
        for array in self.columns.values():
            array.flags.writeable = False

    def __len__(self) -> int:
        return len(self._table)

    def __repr__(self) -> str:
        return f"<impact.Sweep {len(self)} rows, columns {', '.join(self.columns)}>"

    def to_csv(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the CSV ``impact sweep --out`` writes for the same sweep, byte for byte: completely or not at all
        (``-`` is standard output). Ctrl-C stops it and leaves no file."""
        self._table.write_csv(os.fspath(path), self._inputs)

    def csv(self) -> str:
        """The CSV text ``to_csv`` writes."""
        return self._table.csv()

    def to_pandas(self):
        """The table as a pandas DataFrame (pandas must be installed)."""
        import pandas

        return pandas.DataFrame(self.columns)

    def to_polars(self):
        """The table as a polars DataFrame (polars must be installed)."""
        import polars

        return polars.DataFrame({name: np.asarray(array) for name, array in self.columns.items()})


def _run_shard(kind: str, scene: Any, specs: List[str], laws: List[str], columns: List[str],
               threads: Optional[int], shard: str) -> str:
    """One shard's CSV text, as ``impact sweep --shard I/N --out`` writes it (run on an executor's worker)."""
    table = _impact.sweep(kind, scene, specs, False, laws, columns, threads, shard, None)
    return table.csv()


def _workers(executor: Any) -> int:
    """How many workers an executor has, where it says (a Dask client, a concurrent.futures pool); else 4."""
    try:
        info = executor.scheduler_info()
        return max(1, sum(w.get("nthreads", 1) for w in info.get("workers", {}).values()))
    except Exception:
        pass
    count = getattr(executor, "_max_workers", None)
    return count if isinstance(count, int) and count > 0 else 4


def _on_executor(executor: Any, kind: str, scene: Any, specs: List[str], laws: List[str], columns: List[str],
                 threads: Optional[int], progress: Optional[bool], shards: Optional[int]) -> Sweep:
    # Checked here, before anything is sent: a bad scene or argument is the caller's error, with its file and line.
    rows, world = _impact.sweep_rows(kind, scene, specs, False, laws, columns)
    if world:
        raise ValueError("executor: a sweep of a world scene is not cut into shards (yet); run it here")
    inputs = [scene] if kind == "path" else []
    if kind == "path":
        # Workers need not see the caller's files: the scene goes as its text.
        with open(scene, encoding="utf-8") as file:
            kind, scene = "text", file.read()
    if shards is None:
        shards = 4 * _workers(executor)
    if not isinstance(shards, int) or isinstance(shards, bool) or shards < 1:
        raise ValueError(f"shards must be a whole number >= 1, got {shards!r}")
    count = max(1, min(shards, rows))
    futures = [
        executor.submit(_run_shard, kind, scene, specs, laws, columns, threads, f"{i}/{count}")
        for i in range(1, count + 1)
    ]
    drawn = _progress.bar(progress, count, unit="shard")
    texts = []
    try:
        for k, future in enumerate(futures):
            texts.append(future.result())
            if drawn is not None:
                drawn.update_to(k + 1)
    except BaseException:
        for future in futures:
            future.cancel()
        raise
    finally:
        if drawn is not None:
            drawn.close()
    names = [f"shard {i}/{count}" for i in range(1, count + 1)]
    return Sweep(_impact.merge(texts, names), inputs)


def sweep(
    scene: Any,
    vary: Mapping[str, Values],
    *,
    laws: Optional[Union[str, Sequence[str]]] = None,
    columns: Optional[Union[str, Sequence[str]]] = None,
    threads: Optional[int] = None,
    shard: Optional[str] = None,
    progress: Optional[bool] = None,
    executor: Any = None,
    shards: Optional[int] = None,
) -> Sweep:
    """Runs ``scene`` over the grid of ``vary`` (the first key slowest), under each of ``laws``; see docs/python.md.

    ``vary``: dotted key -> a spec string as on the command line (``"0.01:100:41:log"``, ``"0.1,0.2"``) or numbers.
    ``columns``: the result columns to compute and keep (default: the 41 of the command). ``threads``: worker threads
    (default: one per core). ``shard``: ``"I/N"``, only that shard's rows. ``progress``: a bar (None: in a terminal or
    a notebook, not in a script's log). ``executor``: anything with ``submit(fn, *args)`` (a concurrent.futures
    executor, a Dask client): the sweep is cut into ``shards`` shards (default four per worker) run there and joined
    as ``impact merge`` joins them — the same table as the local sweep.
    """
    kind, value = kind_of(scene)
    specs = _specs(vary)
    law_names = _names(laws, "laws")
    column_names = _names(columns, "columns")
    if threads is not None and (not isinstance(threads, int) or isinstance(threads, bool)):
        raise TypeError(f"threads: expected an int, got {type(threads).__name__}")
    if shard is not None and not isinstance(shard, str):
        raise TypeError(f"shard: expected 'I/N' (str), got {type(shard).__name__}")
    if executor is not None:
        if shard is not None:
            raise ValueError("shard and executor: an executor runs every shard; give one of them")
        if not callable(getattr(executor, "submit", None)):
            raise TypeError("executor: expected an object with submit(fn, *args) (a concurrent.futures executor, "
                            "a Dask distributed.Client)")
        return _on_executor(executor, kind, value, specs, law_names, column_names, threads, progress, shards)
    if shards is not None:
        raise ValueError("shards applies to an executor's sweep: give executor= too (or shard='I/N' for one shard)")
    watcher = _progress.Lazy(progress)
    try:
        table = _impact.sweep(kind, value, specs, False, law_names, column_names, threads, shard,
                              watcher if watcher.wanted else None)
    finally:
        watcher.close()
    return Sweep(table, [value] if kind == "path" else [])
