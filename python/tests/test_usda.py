"""USD text files read back by a parser: structure, counts and labels."""

import subprocess

import plantarch
import usda
from conftest import cli


def test_usda_of_a_canopy_has_a_prim_per_plant_and_organ_with_its_labels(tmp_path):
    path = tmp_path / "field.usda"
    glb = tmp_path / "field.ply"
    subprocess.run([cli(), "--seed", "2", "canopy", "bean", "--count", "2x2", "--age", "30",
                    "-o", str(path), "-o", str(glb)], check=True, capture_output=True)
    layer, prims = usda.read(path)
    assert layer["upAxis"] == "Z" and layer["metersPerUnit"] == 1
    assert layer["defaultPrim"] == "plantarch"
    (root,) = prims
    plants = [c for c in root.children if c.metadata.get("customData", {}).get("species") == "bean"]
    assert len(plants) == 4
    header = glb.read_bytes()[:4096].decode("latin-1")
    faces_in_ply = int(header.split("element face ")[1].split()[0])
    faces = 0
    for plant in plants:
        data = plant.metadata["customData"]
        assert data["age"] == 30 and data["seed"] == 2
        base = plant.attributes["xformOp:translate"]["value"]
        assert len(base) == 3
        assert {m.name for m in plant.children} >= {"internode", "petiole", "leaf"}
        for mesh in plant.children:
            a = mesh.attributes
            counts = a["faceVertexCounts"]["value"]
            indices = a["faceVertexIndices"]["value"]
            points = a["points"]["value"]
            assert set(counts) == {3} and len(indices) == 3 * len(counts)
            assert max(indices) < len(points)
            assert len(a["primvars:normals"]["value"]) == len(points)
            assert a["primvars:normals"]["metadata"]["interpolation"] == "vertex"
            for label in ("organ", "plantID", "objectID", "leafID", "shootID", "rank", "node",
                          "age", "displayColor"):
                primvar = a["primvars:" + label]
                assert primvar["metadata"]["interpolation"] == "uniform"
                assert len(primvar["value"]) == len(counts)
            organ = plantarch.ORGAN_LABELS[a["primvars:organ"]["value"][0]]
            assert set(a["primvars:organ"]["value"]) == {plantarch.ORGAN_LABELS.index(mesh.name)}
            assert organ == mesh.name
            assert a["semantics:labels:class"]["value"] == [mesh.name]
            assert mesh.metadata["apiSchemas"] == ["SemanticsLabelsAPI:class"]
            assert set(a["primvars:plantID"]["value"]) == {data["plantID"]}
            leaf_ids = set(a["primvars:leafID"]["value"])
            assert (min(leaf_ids) >= 0) == (mesh.name == "leaf"), mesh.name
            assert min(a["primvars:rank"]["value"]) >= 0
            assert 0 <= min(a["primvars:age"]["value"]) <= max(a["primvars:age"]["value"]) <= 30
            faces += len(counts)
    assert faces == faces_in_ply


def test_usda_from_python_places_the_plant(arch, tmp_path):
    p = arch.buildPlantInstanceFromLibrary((1, 2, 0), 20)
    path = tmp_path / "one.usda"
    plantarch.writeUSDA(arch.getContext(), str(path), architecture=arch)
    _, (root,) = usda.read(path)
    (plant,) = root.children
    assert plant.name == f"bean_{p}"
    assert plant.attributes["xformOp:translate"]["value"] == (1, 2, 0)
    leaf = plant.child("leaf")
    # Points are relative to the plant's base: adding it back gives the Context's vertices.
    ctx = arch.getContext()
    first = ctx.getMeshArrays(arch.getPlantObjectIDs(p, plantarch.OrganKind.leaf))["vertices"][0]
    x, y, z = leaf.attributes["points"]["value"][0]
    assert abs(x + 1 - first[0]) < 1e-6 and abs(y + 2 - first[1]) < 1e-6 and abs(z - first[2]) < 1e-6


def test_growth_animation_shows_one_frame_per_time_code(arch, tmp_path):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 0)
    path = tmp_path / "growth.usda"
    arch.writeGrowthAnimation([p], 0, 20, 10, [str(path)], frame_rate=12)
    assert arch.getPlantAge(p) == 20  # left at the last frame
    layer, (root,) = usda.read(path)
    assert layer["startTimeCode"] == 0 and layer["endTimeCode"] == 2
    assert layer["timeCodesPerSecond"] == 12 and layer["upAxis"] == "Z"
    assert [f.name for f in root.children] == ["day_0", "day_10", "day_20"]
    for i, frame in enumerate(root.children):
        assert frame.metadata["customData"]["day"] == 10 * i
        samples = frame.attributes["visibility.timeSamples"]["value"]
        # USD holds a token from its sample on, and the first sample before it.
        def shown(code):
            held = [t for t in sorted(samples) if t <= code] or [min(samples)]
            return samples[held[-1]] == "inherited"
        assert [shown(c) for c in (0, 1, 2)] == [c == i for c in (0, 1, 2)]
        (plant,) = frame.children
        assert plant.metadata["customData"]["age"] == 10 * i
        triangles = sum(len(m.attributes["faceVertexCounts"]["value"]) for m in plant.children)
        # Each frame is the plant as built at that age in a scene of its own.
        other = plantarch.PlantArchitecture(plantarch.Context())
        other.setSeed(arch.seed())
        other.loadPlantModelFromLibrary("bean")
        other.buildPlantInstanceFromLibrary((0, 0, 0), 10 * i)
        assert triangles == other.getContext().getTriangleCount()
