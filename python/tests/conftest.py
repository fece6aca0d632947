"""What the tests share: the repository, the `impact` command built from it (the command's own output is the reference
for every function of the package), and a scratch folder."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"


def _binary() -> Path:
    given = os.environ.get("IMPACT_BIN")
    if given:
        return Path(given)
    path = ROOT / "target" / "release" / "impact"
    if not path.exists():
        subprocess.run(["cargo", "build", "--release", "--locked", "--bin", "impact"], cwd=ROOT, check=True)
    return path


@pytest.fixture(scope="session")
def command():
    """Runs the `impact` command: `command(*args, cwd=None)` -> CompletedProcess (text)."""
    binary = _binary()

    def call(*args, cwd=None, check=True):
        done = subprocess.run([str(binary), *map(str, args)], cwd=cwd, capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"impact {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
        return done

    return call


def without_wall_time(report: dict) -> dict:
    """The report with the one measured (not computed) value left out: the solver's wall time."""
    report = json.loads(json.dumps(report))
    report["solver"].pop("wall_time_s", None)
    return report


@pytest.fixture
def python():
    """The interpreter running the tests (for subprocesses that import impact)."""
    return sys.executable
