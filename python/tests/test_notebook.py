"""Pictures for notebooks, images as arrays, and the type stubs."""

import ast
import inspect
import re
import pathlib

import numpy as np

import plantarch


def test_plants_and_scenes_show_a_picture(arch):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    png = arch.getPlant(p)._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert arch._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    assert arch.getContext()._repr_png_()[:4] == b"\x89PNG"


def test_render_returns_an_image_array(arch, tmp_path):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    image = plantarch.render(arch, width=160, height=120)
    assert image.shape == (120, 160, 3) and image.dtype == np.uint8
    assert image.std() > 5  # a picture, not a blank
    organs = plantarch.render(arch, width=160, height=120, mode="organ")
    leaf_green = (60, 180, 75)
    assert (organs.reshape(-1, 3) == leaf_green).all(axis=1).sum() > 100
    plantarch.writePNG(image, str(tmp_path / "x.png"))
    assert (plantarch.readImage(str(tmp_path / "x.png")) == image).all()


def test_type_stubs_ship_with_the_module_and_cover_it():
    stub = pathlib.Path(plantarch.__file__).with_name("_plantarch.pyi")
    tree = ast.parse(stub.read_text())
    names = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    for expected in ("PlantArchitecture", "Context", "ShootParameters", "uniform", "render",
                     "writePLY", "Error"):
        assert expected in names
    arch = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "PlantArchitecture")
    methods = {n.name for n in arch.body if isinstance(n, ast.FunctionDef)}
    for m in ("buildPlantInstanceFromLibrary", "advanceTime", "getMeshArrays", "pruneBranch",
              "registerPhytomerCreationFunction"):
        assert m in methods
    assert (stub.parent / "py.typed").exists()


def test_every_public_function_method_and_attribute_has_help_text():
    module = plantarch._plantarch
    missing = []
    for name, obj in vars(module).items():
        if name.startswith("_"):
            continue
        members = vars(obj).items() if inspect.isclass(obj) else [(name, obj)]
        for attr, value in members:
            if attr.startswith("_") or not (callable(value) or isinstance(value, property)):
                continue
            if inspect.isclass(obj) and hasattr(obj, "__members__") and attr in ("name", "value"):
                continue  # enum basics
            signature = re.compile(r"^(\d+\. )?" + attr + r"\(")
            doc = getattr(value, "__doc__", None) or ""
            text = [l for l in doc.splitlines() if l.strip() and not signature.match(l.strip())
                    and l.strip() != "Overloaded function."]
            if not text:
                missing.append(f"{name}.{attr}" if inspect.isclass(obj) else name)
    assert missing == []
