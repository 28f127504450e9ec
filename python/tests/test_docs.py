"""Runs every Python code block of docs/python.md, in order, in one namespace."""

import os
import pathlib
import re
import subprocess

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"


def test_every_python_block_of_the_guide_runs(tmp_path, capsys):
    text = DOC.read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 6
    scope = {}
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        for block in blocks:
            exec(compile(block, str(DOC), "exec"), scope)
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out
    assert "internode.pitch = 400: out of range (valid: -180 to 180)" in out
    assert sorted(p.name for p in (tmp_path / "frames").iterdir()) == [
        "bean_10.png", "bean_20.png", "bean_30.png", "bean_40.png"]


def test_the_install_check_of_the_guide_runs_from_another_directory(tmp_path):
    text = DOC.read_text()
    command = re.findall(r"```sh\n(.*?)```", text, re.S)[0].strip()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    if "PLANTARCH_TEST_PYTHONPATH" in os.environ:  # sanitized builds: not installed
        env["PYTHONPATH"] = os.environ["PLANTARCH_TEST_PYTHONPATH"]
    out = subprocess.run(command, shell=True, cwd=tmp_path, env=env, capture_output=True,
                         text=True, check=True).stdout
    assert out.strip()


def test_the_readme_python_example_runs():
    readme = DOC.parents[1] / "README.md"
    block = re.findall(r"## From Python.*?```python\n(.*?)```", readme.read_text(), re.S)[0]
    exec(compile(block, str(readme), "exec"), {})


def test_the_formats_guide_python_block_runs(tmp_path):
    doc = DOC.parent / "formats.md"
    text = doc.read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    # The block reads the files the guide's canopy command writes: run that command first.
    cli = os.environ.get("PLANTARCH_CLI", str(DOC.parents[1] / "build" / "plantarch"))
    command = re.findall(r"^build/plantarch (canopy bean --count 2x1 .*)$", text, re.M)[0]
    subprocess.run([cli] + command.split(), cwd=tmp_path, check=True)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    scope = {}
    try:
        for block in blocks:
            exec(compile(block, str(doc), "exec"), scope)
    finally:
        os.chdir(cwd)
    faces = scope["f"]
    assert sorted(set(faces["plant_id"].tolist())) == [0, 1]
    assert set(faces["organ"].tolist()) >= {1, 3}  # internodes and leaves


def test_the_pyhelios_guide_blocks_run():
    doc = DOC.parent / "pyhelios.md"
    blocks = re.findall(r"```python\n(.*?)```", doc.read_text(), re.S)
    assert blocks
    scope = {}
    for block in blocks:
        exec(compile(block, str(doc), "exec"), scope)
    assert scope["arch"].getCurrentShootParameters("tall_trifoliate").max_nodes == 20


# A script as users of the reference package write it (context managers, keyword names,
# days first), and the same plants written in plantarch's own style.
REFERENCE_STYLE = """
from plantarch import Context, PlantArchitecture, vec3

with Context() as context:
    with PlantArchitecture(context) as plantarch:
        plantarch.loadPlantModelFromLibrary("bean")
        first = plantarch.buildPlantInstanceFromLibrary(base_position=vec3(0, 0, 0), age=20)
        second = plantarch.buildPlantInstanceFromLibrary(base_position=vec3(0.5, 0, 0), age=20)
        plantarch.advanceTime(10.0)
        plantarch.advanceTime(5.0, second)
        plantarch.advanceTime(dt=2.5, plant_id=first)
        strings = [plantarch.getPlantString(p) for p in plantarch.getAllPlantIDs()]
"""

PLANTARCH_STYLE = """
import plantarch

arch = plantarch.PlantArchitecture(plantarch.Context())
arch.loadPlantModelFromLibrary("bean")
a = arch.buildPlantInstanceFromLibrary((0, 0, 0), 20)
b = arch.buildPlantInstanceFromLibrary((0.5, 0, 0), 20)
arch.advanceTime(10)
arch.advanceTime(5, plantIDs=[b])
arch.advanceTime(2.5, plantIDs=a)
strings = [arch.getPlantString(p) for p in (a, b)]
"""


def test_a_reference_style_script_grows_the_same_plants():
    reference, ours = {}, {}
    exec(REFERENCE_STYLE, reference)
    exec(PLANTARCH_STYLE, ours)
    assert reference["strings"] == ours["strings"]
    heads = [re.match(r"@\w+\(([^)]*)\)", s) for s in ours["strings"]]
    ages = [float(h.group(1).split(",")[3]) for h in heads if h]
    assert ages == [32.5, 35.0], ours["strings"][0][:80]
