"""Progress of a sweep: a bar in a terminal or a notebook, nothing in a script's log (standard error not a terminal,
no notebook kernel). tqdm draws it where it is installed (``tqdm.auto``: a widget in Jupyter); otherwise a plain line
on standard error, redrawn in place."""

import sys
import time
from typing import Callable, Optional

__all__ = ["shown", "bar", "Lazy"]


def _in_notebook() -> bool:
    shell = sys.modules.get("IPython")
    if shell is None:
        return False
    try:
        ip = shell.get_ipython()
    except Exception:
        return False
    return ip is not None and type(ip).__name__ == "ZMQInteractiveShell"


def shown(progress: Optional[bool]) -> bool:
    """Whether a bar is drawn: ``progress`` if given, else in a notebook or when standard error is a terminal."""
    if progress is not None:
        return bool(progress)
    if _in_notebook():
        return True
    try:
        return sys.stderr is not None and sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


class _Plain:
    """A bar of text on standard error, redrawn at most ten times a second."""

    def __init__(self, total: int, unit: str) -> None:
        self.total, self.unit, self.start, self.drawn = total, unit, time.monotonic(), 0.0

    def update_to(self, done: int) -> None:
        now = time.monotonic()
        if now - self.drawn < 0.1 and done < self.total:
            return
        self.drawn = now
        width = 30
        filled = width * done // max(self.total, 1)
        elapsed = now - self.start
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{self.total} {self.unit}s, {elapsed:.1f} s")
        sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\r" + " " * 72 + "\r")
        sys.stderr.flush()


class _Tqdm:
    def __init__(self, total: int, unit: str) -> None:
        from tqdm.auto import tqdm

        self.bar = tqdm(total=total, unit=unit, leave=False, dynamic_ncols=True)

    def update_to(self, done: int) -> None:
        if done > self.bar.n:
            self.bar.update(done - self.bar.n)

    def close(self) -> None:
        self.bar.close()


def bar(progress: Optional[bool], total: int, unit: str = "row"):
    """A bar with ``update_to(done)`` and ``close()``, or None where none is shown."""
    if not shown(progress) or total <= 0:
        return None
    try:
        return _Tqdm(total, unit)
    except ImportError:
        return _Plain(total, unit)


class Lazy:
    """The ``progress(done, total)`` the core calls: draws a bar from its first call on (when the total is known),
    if one is to be shown; ``close()`` removes it."""

    def __init__(self, progress: Optional[bool], unit: str = "row") -> None:
        self.wanted, self.unit, self.drawn = shown(progress), unit, None

    def __call__(self, done: int, total: int) -> None:
        if self.drawn is None and self.wanted:
            self.drawn = bar(True, total, self.unit)
            self.wanted = False
        if self.drawn is not None:
            self.drawn.update_to(done)

    def close(self) -> None:
        if self.drawn is not None:
            self.drawn.close()
            self.drawn = None
