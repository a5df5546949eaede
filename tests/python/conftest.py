"""Shared fixtures of the Python tests (run by ctest with /usr/bin/python3 -m pytest).

The environment names what the build made: SURFCOMP_PROGRAM (the surfcomp program),
SURFCOMP_PYTHON_DIR (the folder holding the built `surfcomp` package) and SURFCOMP_SOURCE_DIR.
Reference data: datasets/cache (datasets/fetch.sh) and ../shared/datasets
($SURFCOMP_SHARED_DATASETS); a test whose data is absent skips, saying so, or fails when
SURFCOMP_REQUIRE_DATA=1 (as CI sets it).
"""
import os
import pathlib
import subprocess
import sys

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("SURFCOMP_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
if os.environ.get("SURFCOMP_PYTHON_DIR"):
    sys.path.insert(0, os.environ["SURFCOMP_PYTHON_DIR"])
    # Programs the tests start (python3 -m surfcomp, the example) import it too.
    os.environ["PYTHONPATH"] = os.pathsep.join(
        p for p in (os.environ["SURFCOMP_PYTHON_DIR"], os.environ.get("PYTHONPATH")) if p)


def _shared_dir():
    configured = os.environ.get("SURFCOMP_SHARED_DATASETS")
    return pathlib.Path(configured) if configured else SOURCE_DIR.parent / "shared" / "datasets"


def absent(reason):
    """Ends a test whose data is absent: a skip, or a failure under SURFCOMP_REQUIRE_DATA=1."""
    if os.environ.get("SURFCOMP_REQUIRE_DATA") == "1":
        pytest.fail(f"{reason} (SURFCOMP_REQUIRE_DATA=1 requires it)")
    pytest.skip(reason)


@pytest.fixture(scope="session")
def program():
    path = os.environ.get("SURFCOMP_PROGRAM")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("SURFCOMP_PROGRAM does not name the built surfcomp program")
    return path


@pytest.fixture(scope="session")
def cache():
    """datasets/cache, fetched from Debian packages by datasets/fetch.sh."""
    path = SOURCE_DIR / "datasets" / "cache"
    if not (path / "rdkit-data" / "4i23_1C9.pdb").exists():
        absent(f"{path} is not fetched (datasets/fetch.sh)")
    return path


@pytest.fixture(scope="session")
def shared():
    """../shared/datasets, or skip."""
    path = _shared_dir()
    if not (path / "thermolysin").is_dir():
        absent(f"{path} is absent: the reference data sets are not beside the repository")
    return path


def run(command, **kwargs):
    """Runs a command (a list of strings), returning the CompletedProcess with text output."""
    return subprocess.run([str(c) for c in command], capture_output=True, text=True,
                          timeout=kwargs.pop("timeout", 600), **kwargs)
