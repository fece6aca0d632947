"""``impact.Report``: a read-only view of one run's report, key for key what ``impact run --json`` prints."""

import html
import json
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, Dict, Iterator, Optional

import numpy as np

__all__ = ["Report"]


def _frozen(value: Any) -> Any:
    """The JSON value with its objects read-only mappings and its arrays tuples."""
    if isinstance(value, dict):
        return MappingProxyType({k: _frozen(v) for k, v in value.items()})
    if isinstance(value, list):
        return tuple(_frozen(v) for v in value)
    return value


class Report(Mapping):
    """The report of one run (an impact or a world): ``report["contact"]["restitution_velocity_ratio"]``.

    ``json()`` is the command's JSON text; ``to_dict()`` a fresh plain copy; ``history`` the recorded history's
    columns (``run(..., history=True)`` or ``samples=N``); ``figures()`` the run's figures as SVG text; in Jupyter it
    shows its readable table and its force–time figure.
    """

    __slots__ = ("_run", "_data", "_history")

    def __init__(self, run: Any) -> None:
        self._run = run
        self._data = _frozen(json.loads(run.json()))
        self._history: Optional[Dict[str, np.ndarray]] = None

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        kind = "world" if self._run.is_world() else "impact"
        return f"<impact.Report ({kind}) {self._data.get('title', '')!r}>"

    def json(self) -> str:
        """The JSON report, the text ``impact run --json`` prints for the same scene."""
        return self._run.json()

    def to_dict(self) -> Dict[str, Any]:
        """A plain, mutable copy of the report (dicts and lists)."""
        return json.loads(self._run.json())

    def table(self) -> str:
        """The readable report, as ``impact run`` prints it."""
        return self._run.table()

    @property
    def history(self) -> Optional[Dict[str, np.ndarray]]:
        """The history's columns by name (the CSV of ``impact run --csv``; a world: its series), or None when the run
        recorded none (give ``history=True`` or ``samples=N``)."""
        if self._history is None:
            columns = self._run.history()
            if columns is None:
                return None
            for _, array in columns:
                array.flags.writeable = False
            self._history = dict(columns)
        return dict(self._history)

    def figures(self) -> Dict[str, str]:
        """The run's figures as SVG text by name (those of ``impact run --plot``)."""
        return dict(self._run.figures())

    def _repr_html_(self) -> str:
        figures = self.figures()
        name = "force_time" if "force_time" in figures else "contact_forces"
        figure = figures.get(name, "")
        table = html.escape(self.table())
        return (
            f'<div class="impact-report"><pre style="font-size: 12px; line-height: 1.25">{table}</pre>'
            f'<div style="max-width: 900px">{figure}</div></div>'
        )
