"""The install paths docs/python.md gives: a wheel from `pip wheel . --no-build-isolation`
installed with `--no-index` into a fresh venv (no system site packages) imports from another
folder with nothing of the source tree on its path, finds the species library inside itself,
holds the Blender add-on and writes the PLY bytes the command-line tool writes for the same
seed."""

import os
import pathlib
import subprocess
import sys
import zipfile

import pytest

from conftest import REPO, cli

SANITIZED = "libasan" in os.environ.get("LD_PRELOAD", "")


def plain_build_dir():
    return pathlib.Path(cli()).resolve().parent


def clean_env():
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PLANTARCH_SPECIES_DIR", "LD_PRELOAD", "PYTHONHOME")}
    env["PIP_NO_INDEX"] = "1"
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    return env


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    if SANITIZED:
        pytest.skip("a wheel is built from the plain build (the plain run covers it)")
    out = tmp_path_factory.mktemp("wheels")
    run = subprocess.run(
        ["/usr/bin/python3", "-m", "pip", "wheel", str(REPO), "--no-build-isolation",
         "--no-deps", "-w", str(out), "--config-settings", f"build-dir={plain_build_dir()}"],
        capture_output=True, text=True, env=clean_env())
    assert run.returncode == 0, run.stdout + run.stderr
    wheels = list(out.glob("plantarch-*.whl"))
    assert len(wheels) == 1, wheels
    return wheels[0]


def test_the_wheel_holds_the_package_stubs_and_species(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    assert "plantarch/__init__.py" in names
    assert "plantarch/py.typed" in names
    assert any(n.startswith("plantarch/_plantarch") and n.endswith(".so") for n in names)
    assert any(n.startswith("plantarch/_plantarch") and n.endswith(".pyi") for n in names)
    assert "plantarch/species/bean.xml" in names
    assert "plantarch/blender/plantarch_import.py" in names
    species = {n for n in names if n.startswith("plantarch/species/")}
    assert len(species) == len(list((REPO / "species").glob("*.xml")))
    record = [n for n in names if n.endswith(".dist-info/RECORD")]
    assert len(record) == 1
    listed = zipfile.ZipFile(wheel).read(record[0]).decode().splitlines()
    assert len(listed) == len(names)  # every file has its hash line, RECORD its own


def installed(wheel, folder):
    """A fresh venv (no system site packages) in `folder` with the wheel installed offline;
    returns (its python, the venv)."""
    venv = folder / "venv"
    subprocess.run(["/usr/bin/python3", "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    run = subprocess.run([str(python), "-m", "pip", "install", "--no-index", "--no-deps",
                          str(wheel)], capture_output=True, text=True, env=clean_env())
    assert run.returncode == 0, run.stdout + run.stderr
    return python, venv


def test_a_fresh_venv_imports_the_wheel_and_writes_the_clis_bytes_without_numpy(wheel, tmp_path):
    python, venv = installed(wheel, tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    script = (
        "import sys, plantarch\n"
        "print(plantarch.__file__)\n"
        "print(plantarch.speciesLibraryDirectory())\n"
        "a = plantarch.PlantArchitecture(plantarch.Context())\n"
        "a.setSeed(3)\n"
        "a.loadPlantModelFromLibrary('bean')\n"
        "a.buildPlantInstanceFromLibrary((0, 0, 0), 30)\n"
        "plantarch.writePLY(a.getContext(), 'py.ply')\n"
        "print(any('numpy' in p for p in sys.modules))\n"
        "try:\n"
        "    a.getMeshArrays(0)\n"
        "except ImportError as e:\n"
        "    print(e)\n"
    )
    run = subprocess.run([str(python), "-c", script], cwd=elsewhere, capture_output=True,
                         text=True, env=clean_env())
    assert run.returncode == 0, run.stderr
    module_file, species, numpy_loaded, array_error = run.stdout.splitlines()
    site = venv / "lib"
    assert pathlib.Path(module_file).resolve().is_relative_to(site.resolve())
    assert pathlib.Path(species).resolve() == (pathlib.Path(module_file).parent / "species").resolve()
    # The Blender add-on, installed beside the package, as in the source tree.
    addon = pathlib.Path(module_file).parent / "blender" / "plantarch_import.py"
    assert addon.read_bytes() == (REPO / "blender" / "plantarch_import.py").read_bytes()
    assert numpy_loaded == "False"  # the venv has no numpy, and building needs none
    assert "numpy" in array_error  # a call returning arrays names what it needs
    subprocess.run([cli(), "--seed", "3", "build", "bean", "--age", "30", "-o",
                    str(tmp_path / "cli.ply")], check=True, capture_output=True)
    assert (elsewhere / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()


def test_cmake_install_puts_the_module_under_the_prefix(tmp_path):
    if SANITIZED:
        pytest.skip("the sanitizer build installs no Python module")
    prefix = tmp_path / "prefix"
    run = subprocess.run(["cmake", "--install", str(plain_build_dir()), "--prefix", str(prefix)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    inits = list(prefix.glob("lib/python3*/*-packages/plantarch/__init__.py"))
    assert len(inits) == 1, inits
    env = clean_env()
    env["PYTHONPATH"] = str(inits[0].parents[1])
    run = subprocess.run(
        [sys.executable, "-c", "import plantarch; print(plantarch.__file__); "
         "print(plantarch.speciesLibraryDirectory()); print(plantarch.listSpecies()[:1])"],
        cwd=tmp_path, capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    module_file, species, first = run.stdout.splitlines()
    assert pathlib.Path(module_file).resolve() == inits[0].resolve()
    assert pathlib.Path(species).resolve() == (prefix / "share" / "plantarch" / "species").resolve()
    assert first == "['almond']"
