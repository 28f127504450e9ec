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
from conftest import REPO

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
    doc = REPO / "docs" / "datasets.md"
    blocks = [b for b in re.findall(r"```python\n(.*?)```", doc.read_text(), re.S)
              if "plantarch.dataset.generate(" in b]
    assert len(blocks) == 1
    (tmp_path / "examples").symlink_to(REPO / "examples")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        exec(compile(blocks[0], str(doc), "exec"), {"__name__": "__main__"})
    finally:
        os.chdir(cwd)
    assert capsys.readouterr().out.startswith("4 samples, ")
    assert (tmp_path / "out" / "tiny-dask" / "dataset.json").is_file()
