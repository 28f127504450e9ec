"""Geometry as numpy arrays that view the C++ buffer."""

import resource
import subprocess

import numpy as np
import pytest

import plantarch
from conftest import cli


def test_arrays_view_one_buffer_and_agree_with_the_context(arch):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 40)
    m = arch.getMeshArrays(p)
    ctx = arch.getContext()
    assert m["vertices"].dtype == np.float32 and m["vertices"].shape[1] == 3
    assert m["triangles"].dtype == np.uint32 and m["triangles"].shape == (ctx.getTriangleCount(), 3)
    for name in ("vertices", "triangles", "plant_id", "object_id", "organ", "normals"):
        a = m[name]
        assert not a.flags.owndata, name
        assert isinstance(a.base, type(m["vertices"].base)), name  # the capsule owning the buffer
    assert m["triangles"].max() < len(m["vertices"])
    assert set(np.unique(m["plant_id"])) == {p}
    # Organ codes name the organ of each triangle's object.
    for oid in np.unique(m["object_id"])[:50]:
        organ = ctx.getObjectData(int(oid), "organ")
        codes = np.unique(m["organ"][m["object_id"] == oid])
        assert [plantarch.ORGAN_LABELS[c] for c in codes] == [organ]
    # Leaf area from the arrays equals the plant's leaf area.
    leaf = m["organ"] == plantarch.ORGAN_LABELS.index("leaf")
    v = m["vertices"].astype(np.float64)[m["triangles"][leaf]]
    area = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1).sum()
    assert abs(area - arch.getPlantLeafArea(p)) < 1e-4 * area
    normals = np.linalg.norm(m["normals"], axis=1)
    assert np.allclose(normals, 1, atol=1e-4)


def test_arrays_outlive_the_architecture():
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    m = a.getMeshArrays()
    total = float(m["vertices"].sum())
    del a
    import gc
    gc.collect()
    assert float(m["vertices"].sum()) == total


def test_subsets_of_plants_and_objects(arch):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    q = arch.buildPlantInstanceFromLibrary((1, 0, 0), 20)
    both = arch.getMeshArrays([p, q], normals=False)
    one = arch.getMeshArrays(q, normals=False)
    assert both["normals"] is None
    assert len(both["triangles"]) == len(one["triangles"]) + len(arch.getMeshArrays(p)["triangles"])
    ctx = arch.getContext()
    leaves = arch.getPlantObjectIDs(q, plantarch.OrganKind.leaf)
    sub = ctx.getMeshArrays(leaves)
    assert set(np.unique(sub["object_id"])) == set(leaves)


def rss_bytes():
    """Resident memory now (not the peak)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()


def test_a_five_million_triangle_canopy_reaches_numpy_without_a_second_copy():
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (15, 10), 45)
    ctx = a.getContext()
    triangles = ctx.getTriangleCount()
    assert triangles >= 5_000_000
    vertices = ctx.getVertexCount()
    # One copy: the buffer the arrays view (positions, normals, UVs, indices, labels).
    one_copy = vertices * (12 + 12 + 8) + triangles * (12 + 4 + 4 + 1)
    before = rss_bytes()
    m = a.getMeshArrays()
    grown = rss_bytes() - before
    assert len(m["triangles"]) == triangles
    assert 0.5 * one_copy < grown < 1.5 * one_copy, (grown, one_copy)
    # The arrays point into that buffer: their data addresses lie inside the capsule's block.
    addr = m["vertices"].__array_interface__["data"][0]
    assert addr == m["vertices"].ctypes.data and not m["vertices"].flags.owndata


def test_context_from_python(tmp_path):
    ctx = plantarch.Context()
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], np.float32)
    tris = np.array([[0, 1, 2], [0, 2, 3]], np.uint32)
    wall = ctx.addObject(square, tris, material=plantarch.Material(color=(0.5, 0.5, 0.5)))
    assert ctx.objectCount() == ctx.getObjectCount() == 1
    assert ctx.triangleCount() == 2 and ctx.objectArea(wall) == 1.0
    ctx.setObjectData(wall, "organ", "obstacle")
    assert ctx.objectData(wall, "organ") == "obstacle" and ctx.objectDataType("organ") == "string"
    first, count = ctx.objectPrimitives(wall)
    assert count == 2 and ctx.primitiveObject(first) == wall
    ctx.transformObject(wall, np.diag([2, 2, 2, 1]).astype(np.float32))
    assert ctx.objectArea(wall) == 4.0
    m = ctx.getMeshArrays()
    assert m["organ"].tolist() == [plantarch.ORGAN_LABELS.index("obstacle")] * 2
    with pytest.raises(plantarch.Error, match="vertex index out of range"):
        ctx.addObject(square, np.array([[0, 1, 7]], np.uint32))
    with pytest.raises(plantarch.Error, match="no such object"):
        ctx.objectArea(99)
    plantarch.writeOBJ(ctx, str(tmp_path / "wall.obj"))
    other = plantarch.Context()
    assert len(plantarch.readOBJ(other, str(tmp_path / "wall.obj"))) == 1


def test_gltf_from_python(arch, tmp_path):
    import json
    import struct

    p = arch.buildPlantInstanceFromLibrary((1, 2, 0), 30)
    path = tmp_path / "bean.glb"
    plantarch.writeGLTF(arch.getContext(), str(path), architecture=arch)
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<III", data)
    assert (magic, version, length) == (0x46546C67, 2, len(data))
    size, kind = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + size])
    plant_nodes = [n for n in doc["nodes"] if "extras" in n]
    assert plant_nodes[0]["extras"] == {"plantID": p, "species": "bean", "age": 30.0,
                                        "seed": arch.getSeed()}
    assert plant_nodes[0]["translation"] == [1.0, 2.0, 0.0]
    assert "EXT_structural_metadata" in doc["extensionsUsed"]
    with pytest.raises(plantarch.Error, match="valid: .glb, .gltf"):
        plantarch.writeGLTF(arch.getContext(), str(tmp_path / "bean.gltx"))


def test_labelled_point_cloud(arch, tmp_path):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    cloud = plantarch.samplePoints(arch.getContext(), points=5000, seed=2)
    assert cloud["positions"].shape == (5000, 3) and cloud["normals"].shape == (5000, 3)
    assert not cloud["positions"].flags.owndata
    organs = set(np.asarray(plantarch.ORGAN_LABELS)[cloud["organ"]])
    assert {"leaf", "internode"} <= organs
    again = plantarch.samplePoints(arch.getContext(), points=5000, seed=2)
    assert (again["positions"] == cloud["positions"]).all()
    np.savez(tmp_path / "cloud.npz", **cloud)
    loaded = np.load(tmp_path / "cloud.npz")
    assert (loaded["object_id"] == cloud["object_id"]).all()
    with pytest.raises(plantarch.Error, match="points"):
        plantarch.samplePoints(plantarch.Context(), points=10)


def test_qsm_cylinders_from_python(arch, tmp_path):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    path = tmp_path / "bean.csv"
    plantarch.writeQSM(arch, str(path))
    rows = [l.split(",") for l in path.read_text().splitlines() if l and not l.startswith("#")]
    assert rows[0][:3] == ["id", "parent", "plant"]
    internodes = sum(arch.getShootNodeCount(p, s) for s in range(arch.getShootCount(p)))
    assert len(rows) - 1 == internodes


def test_depth_image_agrees_with_the_object_mask(arch):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    ctx = arch.getContext()
    depth = plantarch.renderDepth(ctx, width=96, height=72, ground=False)
    mask = plantarch.render(ctx, width=96, height=72, mode="object", ground=False)
    assert depth.shape == (72, 96) and depth.dtype == np.float32
    seen = mask.any(axis=2)
    # The same rays: every pixel that sees an object has a distance, and no other pixel.
    assert ((depth > 0) == seen).all()
    assert seen.sum() > 500
    assert 0.05 < depth[depth > 0].min() < depth.max() < 10


def test_scan_from_python_and_the_command_line_npz(arch, tmp_path):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    ctx = arch.getContext()
    scanners = [(0.8, 0, 0.4), (-0.8, 0.2, 0.4)]
    cloud = plantarch.scan(ctx, scanners, resolution=0.5, noise=0.0)
    n = len(cloud["positions"])
    assert n > 500 and cloud["range"].shape == (n,) and set(cloud["scanner"]) == {0, 1}
    origins = np.array(scanners, dtype=np.float32)[cloud["scanner"]]
    distances = np.linalg.norm(cloud["positions"] - origins, axis=1)
    assert np.allclose(distances, cloud["range"], atol=1e-5)
    assert set(cloud["organ"]) <= set(range(len(plantarch.ORGAN_LABELS)))
    # The command line scans the same plant from its file into an .npz numpy reads.
    xml, npz = tmp_path / "bean.xml", tmp_path / "scan.npz"
    arch.writePlantStructureXML(arch.getAllPlantIDs(), str(xml))
    subprocess.run([cli(), "scan", str(xml), "--scanner", "0.8,0,0.4", "--scanner",
                    "-0.8,0.2,0.4", "--resolution", "0.5", "-o", str(npz)], check=True,
                   capture_output=True)
    saved = np.load(npz)
    assert saved["positions"].shape == (n, 3)
    # The same geometry (object IDs are given anew when a file is read).
    assert np.array_equal(saved["range"], cloud["range"])
    assert np.array_equal(saved["organ"], cloud["organ"])
    assert [s.decode() for s in saved["organ_labels"]] == list(plantarch.ORGAN_LABELS)
    with pytest.raises(ValueError, match="resolution of scanner 0 = 20: out of range"):
        plantarch.scan(ctx, scanners, resolution=20)


def test_ground_clearance_keeps_leaves_above_the_base():
    def lowest_leaf(ground):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.setSeed(1)
        a.setGroundClearance(ground)
        a.loadPlantModelFromLibrary("cowpea")
        p = a.buildPlantInstanceFromLibrary((0, 0, 0), 50)
        assert a.getGroundClearance() == ground and a.getGroundClearance(p) == ground
        m = a.getMeshArrays(p, normals=False)
        leaf = m["organ"] == plantarch.ORGAN_LABELS.index("leaf")
        z = m["vertices"][np.unique(m["triangles"][leaf])][:, 2].min()
        if not ground:  # turned on for this plant alone, at once
            a.setGroundClearance(p, True)
            assert a.getGroundClearance(p) and not a.getGroundClearance()
        return z

    assert lowest_leaf(True) >= -1e-3
    assert lowest_leaf(False) < -0.05
