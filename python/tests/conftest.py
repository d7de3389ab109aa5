"""What the tests need: the built package on sys.path (PYTHONPATH=<build>/python, which
CTest sets), the tessera program to compare with (TESSERA_EXE) and the project's scenes."""

import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("TESSERA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SCENES = SOURCE_DIR / "scenes"


def scene_path(relative):
    return str(SCENES / relative)


@pytest.fixture
def tessera_exe():
    exe = os.environ.get("TESSERA_EXE")
    if not exe:
        pytest.skip("TESSERA_EXE (the tessera program) is not set")
    return exe


@pytest.fixture
def run_cli(tessera_exe):
    """Runs `tessera ARGS...` and returns the completed process (stdout and stderr as text)."""

    def run(*args):
        return subprocess.run([tessera_exe, *map(str, args)], capture_output=True, text=True, timeout=120)

    return run
