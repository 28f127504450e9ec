"""Synthetic datasets from Python (plantarch.dataset.generate): the samples made on a Dask
LocalCluster of 2 worker processes are the serial run's byte for byte, and both are what
`plantarch dataset` writes; errors arrive as plantarch.Error with one line."""

import json
import os
import pathlib
import re
import subprocess
from typing import Any, cast

import pytest

import plantarch
import plantarch.dataset
from conftest import REPO, run_guide_example

TINY = REPO / "examples" / "datasets" / "tiny.json"


def tree(folder: pathlib.Path):
    """Every file under folder (relative path -> bytes)."""
    return {str(p.relative_to(folder)): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_samples_on_two_dask_workers_are_the_serial_run_and_the_cli_run(tmp_path):
    distributed = pytest.importorskip("distributed")
    seen = []
    serial = plantarch.dataset.generate(TINY, tmp_path / "serial",
                                        progress=lambda done, total: seen.append((done, total)))
    assert serial["samples"] == 4 and serial["made"] == 4 and serial["kept"] == 0
    assert seen == [(1, 4), (2, 4), (3, 4), (4, 4)]
    assert sum(serial["splits"].values()) == 4 and serial["plants"] >= 4
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        mapped = plantarch.dataset.generate(TINY, tmp_path / "dask", client=client)
        workers = {w for w in client.run(lambda: os.getpid()).values()}
    assert len(workers) == 2
    assert mapped["made"] == 4
    for key in ("bytes", "plants", "triangles", "annotations", "splits"):
        assert mapped[key] == serial[key], key
    cli = os.environ.get("PLANTARCH_CLI")
    if cli:
        subprocess.run([cli, "dataset", str(TINY), "--out", str(tmp_path / "cli")], check=True,
                       capture_output=True)
    a, b = tree(tmp_path / "serial"), tree(tmp_path / "dask")
    assert "samples/000003/rgb.png" in a and "dataset.json" in a
    assert sorted(a) == sorted(b)
    for name in a:
        assert a[name] == b[name], name
    if cli:
        c = tree(tmp_path / "cli")
        assert sorted(c) == sorted(a)
        for name in a:
            assert a[name] == c[name], name
    index = json.loads((tmp_path / "dask" / "dataset.json").read_text())
    assert [e["sample"] for e in index["entries"]] == [0, 1, 2, 3]


def test_resume_keeps_samples_and_errors_are_one_line(tmp_path):
    out = tmp_path / "out"
    first = plantarch.dataset.generate(TINY, out, samples=2)
    assert first["made"] == 2
    before = (out / "samples" / "000001" / "rgb.png").read_bytes()
    with pytest.raises(plantarch.Error, match="--resume") as e:
        plantarch.dataset.generate(TINY, out, samples=2)
    assert "\n" not in str(e.value)
    again = plantarch.dataset.generate(TINY, out, samples=3, resume=True)
    assert again["made"] == 1 and again["kept"] == 2
    assert (out / "samples" / "000001" / "rgb.png").read_bytes() == before

    bad = tmp_path / "bad.json"
    spec = json.loads(TINY.read_text())
    spec["camera"]["width"] = -3
    bad.write_text(json.dumps(spec))
    with pytest.raises(plantarch.Error, match="camera/width") as e:
        plantarch.dataset.generate(bad, tmp_path / "never")
    assert "\n" not in str(e.value)
    assert not (tmp_path / "never").exists()
    for count in (0, -1, 10**9, 2.5, True, "4"):
        with pytest.raises(plantarch.Error, match="samples = "):
            plantarch.dataset.generate(TINY, tmp_path / "none", samples=cast(Any, count))
    assert not (tmp_path / "none").exists()
    with pytest.raises(plantarch.Error, match="index"):
        plantarch.writeDatasetSample(str(TINY), 10**7, str(tmp_path / "none"))
    with pytest.raises(plantarch.Error):
        plantarch.checkDatasetSpec(str(tmp_path))


def test_a_sample_from_python_has_its_labelled_files(tmp_path):
    r = plantarch.writeDatasetSample(str(TINY), 2, str(tmp_path))
    assert r["sample"] == 2 and not r["skipped"] and r["plants"] >= 1
    folder = tmp_path / "samples" / "000002"
    np = pytest.importorskip("numpy")
    depth = np.load(folder / "depth.npy")
    normals = np.load(folder / "normals.npy")
    assert depth.shape == (120, 160) and depth.dtype == np.float32
    assert normals.shape == (120, 160, 3)
    seen = depth > 0
    lengths = np.linalg.norm(normals[seen], axis=1)
    assert np.allclose(lengths, 1.0, atol=1e-3)
    coco = json.loads((folder / "coco.json").read_text())
    assert coco["images"][0]["file_name"] == "rgb.png"
    assert coco["info"]["sample"] == 2
    names = [c["name"] for c in coco["categories"]]
    assert "leaf" in names and "plant" in names


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_the_dask_example_of_the_datasets_guide_runs(tmp_path, capsys):
    pytest.importorskip("distributed")
    run_guide_example("datasets.md", "plantarch.dataset.generate(", tmp_path)
    assert capsys.readouterr().out.startswith("4 samples, ")
    assert (tmp_path / "out" / "tiny-dask" / "dataset.json").is_file()


def _ply_points(path: pathlib.Path):
    """Positions, plant IDs and organ labels of a binary point cloud PLY plantarch wrote."""
    np = pytest.importorskip("numpy")
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    names, types = [], {"float": "<f4", "int": "<i4", "uint": "<u4", "uchar": "u1",
                        "ushort": "<u2"}
    dtype = []
    for line in header.splitlines():
        parts = line.split()
        if parts[:1] == ["property"]:
            dtype.append((parts[2], types[parts[1]]))
            names.append(parts[2])
    rows = np.frombuffer(data[end:], dtype=np.dtype(dtype))
    xyz = np.stack([rows["x"], rows["y"], rows["z"]], axis=1).astype(np.float64)
    return xyz, rows["plant_id"], rows["organ"]


def test_a_twenty_sample_dataset_agrees_with_itself(tmp_path):
    """Every sample of a 20-sample dataset: COCO loads and has one annotation per object seen
    above the minimum area, its box and area those of the mask; the masks agree with the
    point cloud's labels; each instance's object is in its plant's structure; each leaf tip
    projects onto its keypoint through camera.json."""
    np = pytest.importorskip("numpy")
    png = pytest.importorskip("PIL.Image")
    spec = json.loads(TINY.read_text())
    spec["samples"] = 20
    spec["points"] = {"count": 20000}
    (tmp_path / "spec.json").write_text(json.dumps(spec))
    result = plantarch.dataset.generate(tmp_path / "spec.json", tmp_path / "out")
    assert result["made"] == 20
    min_area = 20
    checked_points = agreeing_points = 0
    for i in range(20):
        folder = tmp_path / "out" / "samples" / f"{i:06d}"
        coco = json.loads((folder / "coco.json").read_text())
        meta = json.loads((folder / "metadata.json").read_text())
        camera = json.loads((folder / "camera.json").read_text())
        organ = np.array(png.open(folder / "organ_instances.png")).astype(np.int64)
        plant = np.array(png.open(folder / "plant_instances.png")).astype(np.int64)
        semantic = np.array(png.open(folder / "semantic.png")).astype(np.int64)
        depth = np.load(folder / "depth.npy")
        h, w = organ.shape

        # COCO: one annotation per organ instance and per plant of at least min_area pixels.
        def regions(mask):
            out = {}
            for v in np.unique(mask[mask > 0]):
                ys, xs = np.nonzero(mask == v)
                out[int(v)] = (len(xs), [int(xs.min()), int(ys.min()),
                                         int(xs.max() - xs.min() + 1),
                                         int(ys.max() - ys.min() + 1)])
            return out
        organs, plants = regions(organ), regions(plant)
        plant_category = next(c["id"] for c in coco["categories"] if c["name"] == "plant")
        noted_organs = {a["instance"]: a for a in coco["annotations"]
                        if a["category_id"] != plant_category}
        noted_plants = {a["plant_instance"]: a for a in coco["annotations"]
                        if a["category_id"] == plant_category}
        assert sorted(noted_organs) == sorted(k for k, (n, _) in organs.items() if n >= min_area)
        assert sorted(noted_plants) == sorted(k for k, (n, _) in plants.items() if n >= min_area)
        for table, notes in ((organs, noted_organs), (plants, noted_plants)):
            for k, a in notes.items():
                assert a["area"] == table[k][0] and a["bbox"] == table[k][1], (i, k)

        # Instance -> its object in its plant's part of plants.xml.
        xml = (folder / "plants.xml").read_text()
        parts = xml.split("<plant_instance")[1:]
        assert len(parts) == len(meta["plants"])
        for inst in meta["instances"]:
            if inst["plant_instance"]:
                part = parts[inst["plant_instance"] - 1]
                assert re.search(rf"(?<![0-9]){inst['object_id']}(?![0-9])", part), (i, inst)
            assert (semantic[organ == inst["instance"]]
                    == [c["id"] for c in meta["categories"]
                        if c["name"] == inst["category"]][0]).all()

        # Camera matrices project each leaf's tip onto its keypoint.
        K = np.array(camera["K"])
        E = np.array(camera["world_to_camera"])

        def project(p):
            c = E @ np.append(np.asarray(p, dtype=np.float64), 1.0)
            uvw = K @ c[:3]
            return uvw[:2] / uvw[2], c[2]
        for leaf in json.loads((folder / "keypoints.json").read_text())["leaves"]:
            for name in ("base", "tip"):
                uv, z = project(leaf[name]["world"])
                if z > 0:
                    assert np.abs(uv - leaf[name]["pixel"]).max() < 1e-3

        # Points seen (the depth there is theirs) inside one object carry the masks' labels.
        xyz, plant_id, organ_label = _ply_points(folder / "points.ply")
        instance_of = {p["plant_id"]: p["plant_instance"] for p in meta["plants"]}
        cam = (E @ np.c_[xyz, np.ones(len(xyz))].T).T
        front = cam[:, 2] > 0
        uvw = (K @ cam[front, :3].T).T
        u = np.rint(uvw[:, 0] / uvw[:, 2]).astype(int)
        v = np.rint(uvw[:, 1] / uvw[:, 2]).astype(int)
        z = cam[front, 2]
        inside = (u >= 1) & (v >= 1) & (u < w - 1) & (v < h - 1)
        for k in np.nonzero(inside)[0]:
            x, y = u[k], v[k]
            if organ[y, x] == 0 or abs(depth[y, x] - z[k]) > 0.002 + 0.002 * z[k]:
                continue
            if not (organ[y - 1:y + 2, x - 1:x + 2] == organ[y, x]).all():
                continue
            j = np.nonzero(front)[0][k]
            checked_points += 1
            agreeing_points += (semantic[y, x] == organ_label[j]
                                and plant[y, x] == instance_of.get(int(plant_id[j]), -1))
    assert checked_points > 2000
    assert agreeing_points >= 0.99 * checked_points, (agreeing_points, checked_points)


def test_threads_making_the_same_samples_at_once_leave_each_whole(tmp_path):
    """Four threads make samples 0..3 of one folder at once, each thread every sample (the
    GIL is released while a sample is made): each sample is made once, whole, as the serial
    run makes it; the others find it made (resume) or are told another run wrote it."""
    import threading

    serial = tmp_path / "serial"
    plantarch.dataset.generate(TINY, serial)
    out = tmp_path / "threads"
    errors = []

    def work():
        for i in range(4):
            try:
                plantarch.writeDatasetSample(str(TINY), i, str(out), True)
            except plantarch.Error as e:  # pragma: no cover - reported below
                errors.append(str(e))
    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    a, b = tree(serial / "samples"), tree(out / "samples")
    assert sorted(a) == sorted(b)
    for name in a:
        assert a[name] == b[name], name
    assert not (out / ".partial").exists() or not any((out / ".partial").iterdir())
