"""Shared fixtures of the Python tests (run by CTest: `ctest --preset release -L python`).

CTest sets PYTHONPATH to the build's module and STIFFSOFT_PROGRAM to the build's `stiffsoft`.
"""
import os
import pathlib
import shutil

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def repo():
    """The repository root (scenes/, studies/, examples/)."""
    return REPO


@pytest.fixture
def program():
    """The `stiffsoft` program of this build."""
    path = os.environ.get("STIFFSOFT_PROGRAM") or shutil.which("stiffsoft")
    if not path:
        pytest.skip("no stiffsoft program: set STIFFSOFT_PROGRAM")
    return path


@pytest.fixture(autouse=True)
def mesh_cache(tmp_path_factory, monkeypatch):
    """A mesh cache per test session, so tests never touch the user's."""
    monkeypatch.setenv("STIFFSOFT_MESH_CACHE", str(tmp_path_factory.getbasetemp() / "mesh_cache"))
