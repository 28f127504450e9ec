import os
import pathlib
import re

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
