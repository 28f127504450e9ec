"""Fields built in tiles from Python (plantarch._field.generate_field): 4 tiles on a Dask
LocalCluster of 2 worker processes give the files of the serial run byte for byte, and the
tiles' plants are the plants of the field built whole."""

import csv
import json
import pathlib

import numpy as np
import pytest

import plantarch
from conftest import REPO, run_guide_example
from plantarch._field import generate_field

PROJECT = {
    "plantarch_project": 1, "name": "tiles", "seed": 4,
    "blocks": [{"name": "beans", "species": "bean", "count": [4, 4], "spacing": [0.3, 0.3],
                "age": 12, "seed": 6}],
}


def files(folder: pathlib.Path):
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_four_tiles_on_two_dask_workers_are_the_serial_run_and_the_whole_field(tmp_path):
    distributed = pytest.importorskip("distributed")
    project = tmp_path / "field.json"
    project.write_text(json.dumps(PROJECT))
    tiles = plantarch.fieldTiles(str(project), 0.6)
    assert [t["name"] for t in tiles] == ["tile_0_0", "tile_1_0", "tile_0_1", "tile_1_1"]

    serial = generate_field(project, tmp_path / "serial", 0.6)
    assert serial["tiles"] == 4 and serial["built"] == 4 and len(serial["plants"]) == 16
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        mapped = generate_field(project, tmp_path / "dask", 0.6, client=client)
    assert mapped["built"] == 4
    a, b = files(tmp_path / "serial"), files(tmp_path / "dask")
    assert sorted(a) == sorted(
        [f"tile_{x}_{y}.{e}" for x in (0, 1) for y in (0, 1) for e in ("glb", "csv")]
        + ["plants.csv", "tileset.json"])
    for name in a:
        assert a[name] == b[name], name

    # The whole field: the block's canopy built alone with its seed (plant IDs from 0).
    arch = plantarch.PlantArchitecture(plantarch.Context())
    arch.setSeed(6)
    arch.loadPlantModelFromLibrary("bean")
    ids = arch.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (4, 4), 12)
    rows = list(csv.DictReader((tmp_path / "dask" / "plants.csv").open()))
    assert sorted(int(r["plant"]) for r in rows) == list(ids)
    for r in rows:
        plant = int(r["plant"])
        mesh = arch.getMeshArrays(plant)
        assert int(r["triangles"]) == len(mesh["triangles"]), plant
        assert np.float32(r["height"]) == np.float32(arch.getPlantHeight(plant)), plant
        assert np.float32(r["leaf_area"]) == np.float32(arch.getPlantLeafArea(plant)), plant

    # resume: nothing left to build; the index is written again, the same.
    again = generate_field(project, tmp_path / "dask", 0.6, resume=True)
    assert again["built"] == 0
    assert files(tmp_path / "dask") == b


def test_bad_tile_size_is_one_line(tmp_path):
    project = tmp_path / "field.json"
    project.write_text(json.dumps(PROJECT))
    for size in (0.0, -1.0, float("nan")):
        with pytest.raises(plantarch.Error) as e:
            generate_field(project, tmp_path / "out", size)
        assert "tile_size" in str(e.value) and "\n" not in str(e.value)
    assert not (tmp_path / "out").exists()


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_the_example_of_the_datasets_guide_runs(tmp_path, capsys):
    pytest.importorskip("distributed")
    run_guide_example("datasets.md", "generate_field", tmp_path)
    assert "6 tiles, 27 plants:" in capsys.readouterr().out
    assert (tmp_path / "out" / "field" / "tileset.json").is_file()
