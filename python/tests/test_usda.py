"""USD text files read back by a parser: structure, counts and labels."""

import subprocess

import numpy
import pytest

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


def _held(samples, code):
    """The value a time-sampled token or number holds at a time code: its sample at or
    before it (the first one before every sample)."""
    times = sorted(samples)
    held = [c for c in times if c <= code] or [times[0]]
    return samples[held[-1]]


def _attr(prim, name, code):
    """An attribute's value at a time code, whether it is sampled or not (None if absent)."""
    if name + ".timeSamples" in prim.attributes:
        return _held(prim.attributes[name + ".timeSamples"]["value"], code)
    a = prim.attributes.get(name)
    return None if a is None else a["value"]


def _rotate(q, v):
    """v turned by the unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    u = numpy.array([x, y, z])
    v = numpy.asarray(v, dtype=float)
    return v + 2.0 * numpy.cross(u, numpy.cross(u, v) + w * v)


def _ordinal(name):
    last = name.rsplit("_", 1)[-1]
    return int(last) - 1 if last.isdigit() else 0


def _shown_organs(root, code, by_plant=False):
    """Each organ's points as shown at a time code: (organ, shoot, node, leaf, ordinal) ->
    n x 3 array, the prims' placements, references and visibility resolved, a
    PointInstancer's instances by their positions, orientations and scales (keys prefixed
    by the plant prim's name with `by_plant`)."""
    paths = {}

    def index(prim, path):
        paths[path] = prim
        for c in prim.children:
            index(c, path + "/" + c.name)
    index(root, "/" + root.name)

    def points(prim):
        if "points" in prim.attributes:
            return numpy.array(prim.attributes["points"]["value"], dtype=float)
        return points(paths[prim.metadata["references"].strip("<>")])

    def visible(prim):
        v = _attr(prim, "visibility", code)
        if v is None and "references" in prim.metadata:
            v = _attr(paths[prim.metadata["references"].strip("<>")], "visibility", code)
        return v != "invisible"

    def resolved(prim, name):
        if name in prim.attributes:
            return prim.attributes[name]["value"]
        return resolved(paths[prim.metadata["references"].strip("<>")], name)

    def instances(instancer, base, prefix, out):
        a = instancer.attributes
        protos = [paths[p.strip("<>")] for p in a["prototypes"]["value"]]
        names = instancer.metadata["customData"]["instanceNames"]
        labels = [a["primvars:" + n]["value"] for n in ("shootID", "node", "leafID")]
        for i, k in enumerate(a["protoIndices"]["value"]):
            q = a["orientationsf"]["value"][i]
            assert numpy.abs(numpy.subtract(a["orientations"]["value"][i], q)).max() < 1e-6
            organ = resolved(protos[k], "semantics:labels:class")[0]
            key = prefix + (organ,) + tuple(v[i] for v in labels) + (_ordinal(names[i]),)
            t = numpy.array(a["positions"]["value"][i], dtype=float)
            s = a["scales"]["value"][i][0]
            assert key not in out, key
            out[key] = numpy.array([base + t + s * _rotate(q, p) for p in points(protos[k])])

    out = {}
    for plant in root.children:
        if plant.specifier != "def":
            continue
        prefix = (plant.name,) if by_plant else ()
        base = numpy.array(_attr(plant, "xformOp:translate", code) or (0, 0, 0), dtype=float)
        organs = [o for s in plant.children for o in (s.children if s.name.startswith("shoot_")
                                                       else [s])]
        for organ in organs:
            if organ.kind == "PointInstancer":
                instances(organ, base, prefix, out)
                continue
            if not visible(organ):
                continue
            d = organ.metadata["customData"]
            key = prefix + (d["organ"], d["shootID"], d["node"], d["leafID"], _ordinal(organ.name))
            meshes = [organ] if organ.kind == "Mesh" else \
                [v for v in organ.children if visible(v)]
            assert len(meshes) == 1, organ.name
            t = numpy.array(_attr(organ, "xformOp:translate", code), dtype=float)
            q = _attr(organ, "xformOp:orient", code)
            scale = _attr(organ, "xformOp:scale", code)
            assert q is not None and scale is not None, organ.name
            s = scale[0]
            out[key] = numpy.array([base + t + s * _rotate(q, p) for p in points(meshes[0])])
    return out


def _built_organs(seed, age):
    """Each organ's vertices in a bean built directly at `age`, keyed as _shown_organs."""
    arch = plantarch.PlantArchitecture(plantarch.Context())
    arch.setSeed(seed)
    arch.loadPlantModelFromLibrary("bean")
    arch.buildPlantInstanceFromLibrary((0, 0, 0), age)
    ctx = arch.getContext()
    out, ordinals = {}, {}
    for i in ctx.getAllObjectIDs():
        def label(name):
            value = ctx.getObjectData(i, name)
            return -1 if value is None else value
        key = (ctx.getObjectData(i, "organ"), label("shootID"), label("node"), label("leafID"))
        ordinals[key] = ordinals.get(key, -1) + 1
        out[key + (ordinals[key],)] = ctx.getObjectMesh(i).positions
    return out


def test_growth_animation_places_every_organ_as_built_at_each_day(arch, tmp_path):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 0)
    path = tmp_path / "growth.usda"
    arch.writeGrowthAnimation([p], 0, 20, 10, [str(path)], frame_rate=12)
    assert arch.getPlantAge(p) == 20  # left at the last frame
    layer, (root,) = usda.read(path)
    assert layer["startTimeCode"] == 0 and layer["endTimeCode"] == 2
    assert layer["timeCodesPerSecond"] == 12 and layer["upAxis"] == "Z"
    assert root.metadata["customData"]["days"] == [0, 10, 20]
    (plant,) = [c for c in root.children if c.specifier == "def"]
    assert plant.metadata["customData"]["age"] == 20
    for code, day in enumerate((0, 10, 20)):
        shown = _shown_organs(root, code)
        built = _built_organs(arch.seed(), day)
        assert shown.keys() == built.keys(), day
        for key, vertices in built.items():
            extent = float(numpy.ptp(vertices, axis=0).max())
            reach = numpy.abs(vertices).max(axis=1, keepdims=True)
            error = numpy.abs(shown[key] - vertices)
            assert (error <= 1e-5 * extent + 4e-6 * reach + 1e-6).all(), (day, key)



def test_a_prim_per_organ_from_python_with_and_without_instancing(arch, tmp_path):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 40)
    ctx = arch.getContext()
    for instancing in ("shared", "none", "gpu"):
        path = tmp_path / f"organs_{instancing}.usda"
        plantarch.writeUSDA(ctx, str(path), architecture=arch, nodes="organ",
                            instancing=instancing)
        _, (root,) = usda.read(path)
        shapes = [c for c in root.children if c.specifier == "class"]
        # equal leaflets written once, then referenced
        assert bool(shapes) == (instancing != "none")
        shown = _shown_organs(root, 0)
        built = _built_organs(arch.seed(), 40)
        assert shown.keys() == built.keys()
        for key, vertices in built.items():
            assert numpy.abs(shown[key] - vertices).max() <= 1e-5 * numpy.ptp(vertices) + 4e-6
    with pytest.raises(plantarch.Error, match="nodes = leaf: unknown node level"):
        plantarch.writeUSDA(ctx, str(tmp_path / "bad.usda"), nodes="leaf")
    assert not (tmp_path / "bad.usda").exists()
