"""Measured plants from Python: shoots on measured points, skeletons read from node tables,
JSON and MTG text, rebuilt and written back; bad input raises plantarch.Error; the skeleton
picture script draws a check of a reconstruction."""

import subprocess
import sys

import pytest

import plantarch
from conftest import REPO

SCRIPT = REPO / "scripts" / "plot_skeleton.py"
PEPPER = REPO / "examples" / "skeletons" / "pepper_digitised.csv"


def architecture(species="bean"):
    ctx = plantarch.Context()
    arch = plantarch.PlantArchitecture(ctx)
    arch.loadPlantModelFromLibrary(species)
    return ctx, arch


def test_a_shoot_runs_through_measured_points_and_keeps_them_as_it_grows():
    _, arch = architecture()
    plant = arch.addPlantInstance((0, 0, 0), 15)
    points = [(0, 0, 0), (0.0, 0.01, 0.05), (0.01, 0.01, 0.1), (0.02, 0.0, 0.14)]
    shoot = arch.addShootFromNodePositions(plant, -1, 0, points, [0.004, 0.004, 0.003, 0.002],
                                           arch.getBaseStemShootType())
    for k, p in enumerate(points[1:]):
        node = arch.getNodePosition(plant, shoot, k)
        assert node.x == pytest.approx(p[0], abs=1e-6) and node.z == pytest.approx(p[2], abs=1e-6)
    arch.advanceTime(20)
    assert arch.getNodePosition(plant, shoot, 2).z == pytest.approx(0.14, abs=1e-6)
    measured = arch.plant(plant).shoots[0].phytomers[0].measured
    assert measured is not None and measured.radius == pytest.approx(0.004)
    with pytest.raises(plantarch.Error, match="node_positions\\[1\\]"):
        arch.addShootFromNodePositions(plant, 0, 1, [points[2], (float("nan"), 0, 0)], [],
                                       arch.getBaseStemShootType())


def test_skeletons_round_trip_through_node_tables_and_mtg():
    _, arch = architecture("tomato")
    plant = arch.buildPlantInstanceFromLibrary((0, 0, 0), age=35)
    table = plantarch.skeletonCSV(plantarch.plantSkeleton(arch, [plant]))
    mtg = plantarch.plantsMTG(arch, [plant])
    nodes = sum(arch.getShootNodeCount(plant, s) for s in range(arch.getShootCount(plant)))
    for text, form in ((table, "csv"), (mtg, "mtg")):
        skeleton = plantarch.readSkeletonString(text, form, "plant." + form)
        assert len(skeleton.nodes) == nodes + 1  # the base, then every node
        _, back = architecture("tomato")
        rebuilt = plantarch.reconstructPlants(back, skeleton)
        assert back.getShootCount(rebuilt[0]) == arch.getShootCount(plant)
        top = max(n.position.z for n in skeleton.nodes)
        assert back.getPlantStemHeight(rebuilt[0]) <= top + 1e-6


def test_nodes_built_in_python_and_bad_ones_refused():
    skeleton = plantarch.Skeleton()
    skeleton.nodes = [plantarch.SkeletonNode(0, -1, (0, 0, 0)),
                      plantarch.SkeletonNode(1, 0, (0, 0, 4), radius=0.3),
                      plantarch.SkeletonNode(2, 1, (0, 0, 8), radius=0.25),
                      plantarch.SkeletonNode(3, 1, (3, 0, 6), radius=0.1,
                                             link=plantarch.SkeletonLink.branch)]
    _, arch = architecture()
    options = plantarch.ReconstructOptions()
    options.unit = 0.01
    plant = plantarch.reconstructPlants(arch, skeleton, options)[0]
    assert arch.getShootCount(plant) == 2
    skeleton.nodes[3].parent = 9
    with pytest.raises(plantarch.Error, match="parent not in the skeleton"):
        plantarch.reconstructPlants(arch, skeleton, options)
    assert arch.getAllPlantIDs() == [plant]  # a refused skeleton adds nothing
    with pytest.raises(plantarch.Error, match=r"bad\.json:1"):
        plantarch.readSkeletonString('{"nodes": [], "extra": 1}', "json", "bad.json")
    with pytest.raises(plantarch.Error, match="unknown skeleton format"):
        plantarch.readSkeletonString("", "xyz", "x")


def test_the_check_picture_of_a_reconstruction(tmp_path):
    out = tmp_path / "check.png"
    r = subprocess.run([sys.executable, str(SCRIPT), str(PEPPER), "--species", "capsicum",
                        "--unit", "cm", "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 20000
    assert [p.name for p in tmp_path.iterdir()] == ["check.png"]  # no temporary left
    r = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), "--species", "capsicum",
                        "-o", str(tmp_path / "x.png")], capture_output=True, text=True)
    assert r.returncode != 0 and r.stderr.count("\n") == 1 and "plot_skeleton:" in r.stderr
    assert not (tmp_path / "x.png").exists()


def test_measured_leaves_face_their_normal():
    _, arch = architecture()
    plant = arch.addPlantInstance((0, 0, 0), 15)
    options = plantarch.MeasuredShootOptions()
    options.leaves = [plantarch.MeasuredLeaf(1, normal=(0, 0.5, 1), length=0.07)]
    arch.addShootFromNodePositions(plant, -1, 0, [(0, 0, 0), (0, 0, 0.05), (0, 0, 0.1)], [],
                                   arch.getBaseStemShootType(), options)
    leaves = [leaf for pt in arch.plant(plant).shoots[0].phytomers[1].petioles for leaf in pt.leaves]
    assert leaves and max(leaf.leaf_scale for leaf in leaves) == pytest.approx(0.07)
    expected = 26.565  # degrees from the zenith of (0, 0.5, 1)
    targets = [leaf.angle_target for leaf in leaves]
    assert all(t is not None and t.inclination == pytest.approx(expected, abs=1e-3)
               for t in targets)
    options.leaves = [plantarch.MeasuredLeaf(0, normal=(0, 0, 0))]
    with pytest.raises(plantarch.Error, match=r"leaves\[0\]\.normal"):
        arch.addShootFromNodePositions(plant, 0, 1, [(0, 0, 0.1), (0, 0, 0.2)], [],
                                       arch.getBaseStemShootType(), options)
