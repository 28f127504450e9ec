"""`plantarch canopy --separate`: one file per plant and an index."""

import json
import re
import subprocess
import zipfile

import numpy as np

from conftest import cli, glb_json



def test_separate_files_hold_every_plant_once_with_an_index(tmp_path):
    run = subprocess.run([cli(), "--seed", "4", "canopy", "bean", "--count", "3x2", "--age", "25",
                          "--separate", "-o", str(tmp_path / "field.ply"),
                          "-o", str(tmp_path / "field.glb")], check=True, capture_output=True,
                         text=True)
    found = re.search(r"(\d+) triangles", run.stdout)
    assert found, run.stdout
    total = int(found.group(1))
    index = json.loads((tmp_path / "field_index.json").read_text())
    assert index["species"] == "bean" and index["seed"] == 4 and index["coordinates"] == "scene"
    assert [p["plantID"] for p in index["plants"]] == list(range(6))
    faces = 0
    for p in index["plants"]:
        assert p["files"] == [f"field_{p['plantID']:04d}.ply", f"field_{p['plantID']:04d}.glb"]
        ply = tmp_path / p["files"][0]
        assert ply.name == f"field_{p['plantID']:04d}.ply"
        header = ply.read_bytes()[:4096].decode("latin-1")
        faces += int(header.split("element face ")[1].split()[0])
        doc = glb_json(tmp_path / p["files"][1])
        (node,) = [n for n in doc["nodes"] if "extras" in n]
        assert node["extras"]["plantID"] == p["plantID"]
        assert all(abs(a - b) < 1e-6 for a, b in zip(node["translation"], p["position"]))
    assert faces == total


def test_plant_origin_moves_each_plant_to_the_origin(tmp_path):
    subprocess.run([cli(), "--seed", "4", "canopy", "bean", "--count", "2x1", "--age", "25",
                    "--separate", "--plant-origin", "-o", str(tmp_path / "f.glb")], check=True,
                   capture_output=True)
    index = json.loads((tmp_path / "f_index.json").read_text())
    assert index["coordinates"] == "plant"
    for p in index["plants"]:
        doc = glb_json(tmp_path / p["files"][0])
        (node,) = [n for n in doc["nodes"] if "extras" in n]
        assert "translation" not in node  # the plant stands at the origin
        stem = next(m for m in doc["meshes"] if m["name"] == "internode")
        lo = doc["accessors"][stem["primitives"][0]["attributes"]["POSITION"]]["min"]
        assert abs(lo[0]) < 0.2 and abs(lo[1]) < 0.2  # near the origin, not at +-0.15 m


def test_plant_origin_without_separate_is_an_error(tmp_path):
    r = subprocess.run([cli(), "canopy", "bean", "--count", "1x1", "--age", "5", "--plant-origin",
                        "-o", str(tmp_path / "f.glb")], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.strip() == ("plantarch: --plant-origin: --plant-origin places the plants of "
                                "separate files (valid: with --separate)")
    assert not (tmp_path / "f.glb").exists()


def test_points_option_writes_a_labelled_point_cloud(tmp_path):
    path = tmp_path / "points.ply"
    subprocess.run([cli(), "--seed", "3", "build", "bean", "--age", "30", "--points", "1234",
                    "-o", str(path)], check=True, capture_output=True)
    data = path.read_bytes()
    header = data[:data.index(b"end_header\n")].decode()
    assert "element vertex 1234" in header and "element face" not in header
    body = len(data) - data.index(b"end_header\n") - len(b"end_header\n")
    assert body == 1234 * 49  # 6 floats, plant, object, organ, leaf, shoot, rank, age
    # The same points as numpy arrays in an .npz, labels included.
    npz = tmp_path / "points.npz"
    subprocess.run([cli(), "--seed", "3", "build", "bean", "--age", "30", "--points", "1234",
                    "-o", str(npz)], check=True, capture_output=True)
    assert zipfile.ZipFile(npz).testzip() is None  # every array's CRC-32 holds
    arrays = np.load(npz)
    assert arrays["positions"].shape == (1234, 3)
    leaves = arrays["organ"] == 3
    assert (arrays["leaf_id"][leaves] >= 0).all() and (arrays["leaf_id"][~leaves] == -1).all()
    assert (arrays["rank"] >= 0).all() and (arrays["age"] >= 0).all()
    bad = subprocess.run([cli(), "build", "bean", "--age", "5", "--points", "-4", "-o",
                          str(tmp_path / "x.ply")], capture_output=True, text=True)
    assert bad.returncode == 2 and "--points" in bad.stderr and "\n" == bad.stderr[-1]
    assert bad.stderr.count("\n") == 1
