"""docs/python.md's examples run as written, in order, from the repository's folder (those that need a cluster
apart), and print what the page says they print where it says so."""

import contextlib
import io
import os
import re

import pytest

from conftest import ROOT

PAGE = ROOT / "docs" / "python.md"


def _blocks():
    return re.findall(r"```python\n(.*?)```", PAGE.read_text(), flags=re.S)


def test_the_page_has_examples_of_every_function():
    code = "\n".join(_blocks())
    for name in ["impact.run(", "impact.sweep(", "impact.translate(", "impact.calibrate(", "impact.validate(",
                 "impact.laws(", "impact.__version__", ".history", ".figures()", ".to_csv(", ".to_pandas(",
                 "executor=", "impact.SceneError"]:
        assert name in code, name


def test_the_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)
    printed = io.StringIO()
    for block in _blocks():
        if block.startswith("# needs a cluster"):
            continue
        with contextlib.redirect_stdout(printed):
            exec(compile(block, str(PAGE), "exec"), {"__name__": "__docs__"})
    text = printed.getvalue()
    assert "<text>" in text
    assert "bodies.0.mass None None" in text
    assert "['body', 'contact']" in text
    assert "True" in text  # the executor's sweep equals the local one
    assert (ROOT / "out" / "speed.csv").exists()
