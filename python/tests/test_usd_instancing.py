"""instancing="gpu" / --instancing gpu: in USD a PointInstancer per plant whose instances sit
where the prims of --instancing shared put the organs, labelled per instance; the refusals; a
GLB from Python with a node per shared shape."""

import subprocess

import numpy
import pytest

import plantarch
import usda
from conftest import cli, glb_json
from test_usda import _shown_organs


def _same(shown, expected):
    assert shown.keys() == expected.keys()
    for key, vertices in expected.items():
        error = numpy.abs(shown[key] - vertices).max()
        assert error <= 1e-5 * numpy.ptp(vertices) + 4e-6 * numpy.abs(vertices).max() + 1e-6, key


def test_a_point_instancer_holds_the_shared_shapes_labelled_per_instance(arch, tmp_path):
    arch.setSeed(4)
    arch.buildPlantInstanceFromLibrary((0.2, -0.1, 0), 40)
    ctx = arch.getContext()
    shared, gpu = tmp_path / "shared.usda", tmp_path / "gpu.usda"
    plantarch.writeUSDA(ctx, str(shared), architecture=arch, nodes="organ")
    plantarch.writeUSDA(ctx, str(gpu), architecture=arch, nodes="organ", instancing="gpu")
    _, (root,) = usda.read(gpu)
    _same(_shown_organs(root, 0), _shown_organs(usda.read(shared)[1][0], 0))
    (plant,) = [c for c in root.children if c.specifier == "def"]
    instancer = plant.child("instances")
    assert instancer.kind == "PointInstancer"
    a = instancer.attributes
    n = len(a["protoIndices"]["value"])
    names = instancer.metadata["customData"]["instanceNames"]
    assert n == len(names) == len(set(names)) > len(a["prototypes"]["value"]) >= 1
    for attribute in ("ids", "positions", "orientations", "orientationsf", "scales"):
        assert len(a[attribute]["value"]) == n, attribute
    assert a["orientations"]["type"] == "quath[]" and a["orientationsf"]["type"] == "quatf[]"
    assert a["ids"]["value"] == a["primvars:objectID"]["value"]
    for label, data in (("objectID", None), ("shootID", "shootID"), ("node", "node"),
                        ("leafID", "leafID"), ("age", "age")):
        primvar = a["primvars:" + label]
        assert primvar["metadata"]["interpolation"] == "vertex"  # one value per instance
        if data:
            for i, obj in enumerate(a["ids"]["value"]):
                value = ctx.getObjectData(obj, data)
                value = -1 if value is None else value
                assert primvar["value"][i] == pytest.approx(value), (label, i)
    prototypes = instancer.child("prototypes")
    for target in a["prototypes"]["value"]:
        assert target.strip("<>").startswith(f"/plantarch/{plant.name}/instances/prototypes/")
    for proto in prototypes.children:
        assert proto.metadata["references"].startswith("</plantarch/shapes/")
    # Organs of a shape of their own stay prims; no organ is both.
    organs = {o.name for s in plant.children if s.name.startswith("shoot_") for o in s.children}
    assert organs and not organs & set(names)
    assert gpu.stat().st_size < shared.stat().st_size


def test_a_canopy_has_an_instancer_per_plant_placing_its_organs(tmp_path):
    paths = {}
    for mode in ("shared", "gpu"):
        paths[mode] = tmp_path / f"{mode}.usda"
        subprocess.run([cli(), "--seed", "2", "canopy", "bean", "--count", "2x2", "--age", "30",
                        "--nodes", "organ", "--instancing", mode, "-o", str(paths[mode])],
                       check=True, capture_output=True)
    shown = {m: _shown_organs(usda.read(p)[1][0], 0, by_plant=True) for m, p in paths.items()}
    _same(shown["gpu"], shown["shared"])
    _, (root,) = usda.read(paths["gpu"])
    plants = [c for c in root.children if c.specifier == "def"]
    assert len(plants) == 4
    assert all(p.child("instances").kind == "PointInstancer" for p in plants)


def test_bad_or_impossible_instancing_is_refused_and_writes_nothing(arch, tmp_path):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    ctx = arch.getContext()
    bad = tmp_path / "bad.usda"
    with pytest.raises(plantarch.Error, match="instancing = maybe: unknown instancing"):
        plantarch.writeUSDA(ctx, str(bad), nodes="organ", instancing="maybe")
    with pytest.raises(plantarch.Error, match="gpu instancing needs a node per organ"):
        plantarch.writeGLTF(ctx, str(tmp_path / "bad.glb"), instancing="gpu")
    with pytest.raises(TypeError):
        plantarch.writeUSDA(ctx, str(bad), nodes="organ", instancing=True)  # type: ignore
    assert not list(tmp_path.iterdir())
    for args, message in (
            (["--age", "20", "--instancing", "maybe"],
             "--instancing = maybe: unknown instancing (valid: none, shared, gpu)"),
            (["--age", "20", "--instancing", "gpu"], "gpu instancing needs a node per organ"),
            (["--nodes", "organ", "--instancing", "gpu", "--frames", "0:20:10"],
             "gpu instances cannot be animated")):
        out = tmp_path / "refused.glb"
        run = subprocess.run([cli(), "build", "bean", *args, "-o", str(out)],
                             capture_output=True, text=True)
        assert run.returncode == 2, run.stderr
        assert message in run.stderr and len(run.stderr.strip().splitlines()) == 1, run.stderr
        assert not out.exists()


def test_gltf_from_python_has_an_instancing_node_per_shared_shape(arch, tmp_path):
    arch.setSeed(4)
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 40)
    ctx = arch.getContext()
    path = tmp_path / "gpu.glb"
    plantarch.writeGLTF(ctx, str(path), architecture=arch, nodes="organ", instancing="gpu")
    doc = glb_json(path)
    assert "EXT_mesh_gpu_instancing" in doc["extensionsRequired"]
    nodes = [n for n in doc["nodes"] if "EXT_mesh_gpu_instancing" in n.get("extensions", {})]
    organs = [n for n in doc["nodes"] if "objectID" in n.get("extras", {})]
    instances = sum(len(n["extras"]["instances"]) for n in nodes)
    assert nodes and all(len(n["extras"]["instances"]) >= 2 for n in nodes)
    assert instances + len(organs) == len(ctx.getAllObjectIDs())
    ids = [i for n in nodes for i in n["extras"]["objectIDs"]] + [n["extras"]["objectID"]
                                                                  for n in organs]
    assert sorted(ids) == sorted(ctx.getAllObjectIDs())
