"""Shared paths for the Python package's tests. They run against the installed wheel
(scripts/test-python.sh installs it into a fresh virtual environment), never against
the source tree."""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """../shared/data (or $ORIENT_SHARED_DATA); the BROAD tests need it and fail without it."""
    path = Path(os.environ.get("ORIENT_SHARED_DATA", ROOT.parent / "shared" / "data"))
    assert (path / "broad").is_dir(), f"BROAD recordings not found in {path} (set ORIENT_SHARED_DATA)"
    return path


@pytest.fixture(scope="session")
def replay_tool() -> Path:
    """The replay tool ($ORIENT_REPLAY, built by scripts/test-python.sh)."""
    path = Path(os.environ.get("ORIENT_REPLAY", ROOT / "target" / "debug" / "replay"))
    assert path.is_file(), f"replay tool not built: {path} (cargo build -p orient-tools --bin replay)"
    return path
