"""The exceptions of impact: a bad scene (what the command refuses with exit status 2) and a run that cannot finish
(exit status 1). Bad arguments are ValueError, values of the wrong type TypeError, as everywhere in Python."""

from typing import Any, Optional

__all__ = ["SceneError", "SimulationError"]


class SceneError(ValueError):
    """A scene the command refuses: ``str(error)`` is the command's message.

    ``path``: the scene file (None for TOML text or a dict); ``line``: 1-based, where known (None for a dict);
    ``key``: the dotted key (0-based indices, ``bodies.1.velocity``; a dict's own dotted path), where one key is at
    fault; ``message``: what is wrong and what was expected, without the place.
    """

    def __init__(
        self,
        text: str,
        *,
        path: Optional[str] = None,
        line: Optional[int] = None,
        key: Optional[str] = None,
        message: Optional[str] = None,
    ) -> None:
        super().__init__(text)
        self.path = path
        self.line = line
        self.key = key
        self.message = text if message is None else message

    def __reduce__(self):  # keeps the attributes across pickling (a Dask worker's error reaches the caller)
        return (_scene_error, (self.args[0], self.path, self.line, self.key, self.message))


def _scene_error(text, path, line, key, message):
    return SceneError(text, path=path, line=line, key=key, message=message)


class SimulationError(RuntimeError):
    """A run that cannot finish (the integrator's step budget spent, a world ended by its budget, ...): the command
    exits with status 1 for these.

    ``report``: where the run did produce a report up to where it stopped (the command writes it before exiting 1),
    that ``impact.Report``; otherwise None.
    """

    def __init__(self, text: str, *, report: Optional[Any] = None) -> None:
        super().__init__(text)
        self.report = report

    def __reduce__(self):  # a Dask worker's error reaches the caller as it was raised (its report is not sent)
        return (SimulationError, (self.args[0],))
