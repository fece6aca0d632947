"""What a scene argument is: a path, TOML text or a dict (the contract's rule), as the compiled module takes it."""

import os
import re
from typing import Any, Dict, Tuple, Union

Scene = Union[str, "os.PathLike[str]", Dict[str, Any]]

# A line such as `title = "x"` or `bodies.0.mass = 1`: a TOML key, then `=`.
_KEY_LINE = re.compile(r"^\s*[A-Za-z0-9_\-\"'.]+\s*=", re.MULTILINE)


def kind_of(scene: Any) -> Tuple[str, Any]:
    """``("path", str)``, ``("text", str)`` or ``("dict", dict)``; TypeError for anything else.

    A ``str`` is TOML text when it holds a newline, starts with ``[`` or has a ``key =`` line; otherwise a path.
    """
    if isinstance(scene, dict):
        return "dict", scene
    if isinstance(scene, os.PathLike):
        path = os.fspath(scene)
        if isinstance(path, bytes):
            path = os.fsdecode(path)
        return "path", path
    if isinstance(scene, str):
        if "\n" in scene or scene.lstrip().startswith("[") or _KEY_LINE.search(scene):
            return "text", scene
        return "path", scene
    raise TypeError(
        "scene: expected a path (str or os.PathLike), TOML text or a dict shaped like the TOML, "
        f"got {type(scene).__name__}"
    )
