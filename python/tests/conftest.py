import os
import pathlib

import pytest

import plantarch

REPO = pathlib.Path(__file__).resolve().parents[2]
CLI = REPO / "build" / "plantarch"


@pytest.fixture
def arch():
    """A PlantArchitecture with its own Context and the bean loaded."""
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    return a


@pytest.fixture
def tmp(tmp_path):
    return tmp_path


def cli():
    path = os.environ.get("PLANTARCH_CLI", str(CLI))
    if not os.path.exists(path):
        pytest.skip("the plantarch command is not built")  # pragma: no cover
    return path
