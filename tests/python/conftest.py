import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def exe():
    return os.environ.get("UAVPLAN_EXE", str(ROOT / "build" / "uavplan"))
