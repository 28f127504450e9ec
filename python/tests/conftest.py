import json
import os
import pathlib
import re
import struct

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


@pytest.fixture(scope="module")
def bean():
    """A bean built at 25 days (seed 3), shared by a module's tests."""
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.setSeed(3)
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantInstanceFromLibrary((0, 0, 0), age=25)
    return a


def glb_json(path):
    """The JSON chunk of a .glb file."""
    data = pathlib.Path(path).read_bytes()
    (length,) = struct.unpack_from("<I", data, 12)
    return json.loads(data[20:20 + length])


@pytest.fixture
def tmp(tmp_path):
    return tmp_path


def cli():
    path = os.environ.get("PLANTARCH_CLI", str(CLI))
    if not os.path.exists(path):
        pytest.skip("the plantarch command is not built")  # pragma: no cover
    return path


def run_guide_example(page: str, marker: str, folder: pathlib.Path) -> None:
    """Runs the one ```python block of docs/PAGE that holds `marker`, as a script
    (__name__ "__main__") from `folder`, where examples/ is the repository's."""
    doc = REPO / "docs" / page
    blocks = [b for b in re.findall(r"```python\n(.*?)```", doc.read_text(), re.S)
              if marker in b]
    assert len(blocks) == 1, f"{page}: {len(blocks)} python blocks hold {marker!r}"
    (folder / "examples").symlink_to(REPO / "examples")
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        exec(compile(blocks[0], str(doc), "exec"), {"__name__": "__main__"})
    finally:
        os.chdir(cwd)
