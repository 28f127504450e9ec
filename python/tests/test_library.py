"""The species library, growth, queries, pruning and phenology from Python."""

import json
import pathlib
import re
import subprocess

import pytest

import plantarch
from conftest import cli


LISTING = '''
from plantarch import Context, PlantArchitecture, vec3

# Define the Helios Context (main model database)
context = Context()

# Define an instance of the plant architecture model
plantarchitecture= PlantArchitecture(context)

# Load an existing set of shoot parameters from the library
# Alternatively, we could manually define a fresh set ourselves
plantarchitecture.loadPlantModelFromLibrary("bean")

# Add the plant with its base at the origin
plantID = plantarchitecture.addPlantInstance(base_position=vec3(0,0,0), current_age=15)
'''


def test_the_specifications_listing_runs_and_builds_a_plant():
    scope = {}
    exec(LISTING, scope)
    arch, plant = scope["plantarchitecture"], scope["plantID"]
    assert arch.getAllPlantIDs() == [plant]
    assert arch.getPlantAge(plant) == 15
    # The listing's plant has no shoots yet; the library builds the same species on.
    shoot = arch.addBaseStemShoot(plant, 3, shoot_type_label="trifoliate")
    assert shoot == 0 and arch.getShootNodeCount(plant, 0) == 3
    arch.advanceTime(10.0, plant)
    assert arch.getPlantLeafCount(plant) > 0


def test_library_plant_queries(arch):
    assert "bean" in arch.getAvailablePlantModels()
    assert arch.getCurrentPlantModel() == "bean"
    p = arch.buildPlantInstanceFromLibrary(plantarch.vec3(1, 2, 0), age=40)
    assert arch.getPlantBasePosition(p) == plantarch.vec3(1, 2, 0)
    assert 0.2 < arch.getPlantHeight(p) < 1.5
    assert arch.getPlantLeafArea(p) > 0.05
    shoots = arch.getShootCount(p)
    assert shoots > 1
    tree = arch.getPlant(p).shoot_tree()
    assert len(tree) == shoots
    for s in tree[1:]:
        assert s["parent"] >= 0
        assert s["id"] in arch.getShootChildren(p, s["parent"])
        assert arch.getShootPathToRoot(p, s["id"])[-1] == 0
    leaves = arch.getPlantObjectIDs(p, plantarch.OrganKind.leaf)
    ctx = arch.getContext()
    assert leaves and all(ctx.getObjectData(o, "organ") == "leaf" for o in leaves)
    assert all(ctx.getObjectData(o, "plantID") == p for o in leaves)
    stats = arch.getPlant(p).statistics()
    assert stats["triangles"] == ctx.getTriangleCount()


def test_plant_summary_is_the_clis_stats(arch, tmp):
    arch.setSeed(5)
    p = arch.buildPlantInstanceFromLibrary(plantarch.vec3(0, 0, 0), age=40)
    s = arch.summarizePlant(p)
    printed = json.loads(subprocess.run(
        [cli(), "--seed", "5", "build", "bean", "--age", "40", "--stats"],
        capture_output=True, text=True, check=True).stdout)
    assert s.leaves == printed["leaves"] == arch.getPlantLeafCount(p)
    assert s.height == pytest.approx(printed["height"], abs=1e-4)
    assert s.widthLong == pytest.approx(printed["width_long"], abs=1e-4)
    assert s.widthShort == pytest.approx(printed["width_short"], abs=1e-4)
    assert list(s.shootsByRank) == printed["shoots_by_rank"]
    assert list(s.phytomersByRank) == printed["phytomers_by_rank"]
    assert sum(s.leafInclination) == pytest.approx(1.0, abs=1e-5)
    assert s.leafInclination == pytest.approx(printed["leaf_inclination"], abs=1e-4)
    with pytest.raises(plantarch.Error, match="no such plant"):
        arch.summarizePlant(p + 1)


def test_canopy_builds_and_same_seed_gives_same_plants():
    def canopy(seed):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.setSeed(seed)
        a.loadPlantModelFromLibrary("bean")
        ids = a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.4), (3, 2), 20)
        return a, ids

    a, ids = canopy(7)
    assert len(ids) == 6
    xs = sorted({round(a.getPlantBasePosition(i).x, 3) for i in ids})
    assert xs == [-0.3, 0.0, 0.3]
    b, _ = canopy(7)
    c, _ = canopy(8)
    strings = lambda arch: [arch.getPlantString(i) for i in arch.getAllPlantIDs()]
    assert strings(a) == strings(b)
    assert strings(a) != strings(c)


def test_advance_time_all_one_and_subset(arch):
    p = [arch.buildPlantInstanceFromLibrary((x, 0, 0), 10) for x in range(3)]
    arch.advanceTime(5)
    assert [arch.getPlantAge(i) for i in p] == [15, 15, 15]
    arch.advanceTime(5.0, p[0])
    arch.advanceTime(2, plantIDs=[p[1], p[2]])
    assert [arch.getPlantAge(i) for i in p] == [20, 17, 17]
    arch.advanceTime(plantIDs=p[2], time_step_days=1)
    arch.advanceTime(dt=1, plant_id=p[1])  # the reference package's keywords
    assert [arch.getPlantAge(i) for i in p] == [20, 18, 18]


@pytest.mark.parametrize("call, says", [
    (lambda a, p: a.advanceTime(3, 2), r"advanceTime\(3, 2\) reads two ways: write "
     r"advanceTime\(3, plantIDs=2\) to grow plant 2 by 3 days, or advanceTime\(2, plantIDs=3\)"),
    (lambda a, p: a.advanceTime(p, 2.5), r"takes the days first in Python: write "
     r"advanceTime\(2.5, plantIDs=0\)"),
    (lambda a, p: a.advanceTime([p], 2.5), r"takes the days first in Python: write "
     r"advanceTime\(2.5, plantIDs=\[0\]\)"),
    (lambda a, p: a.advanceTime("5"), "the days must be a number"),
    (lambda a, p: a.advanceTime(True), "the days must be a number"),
    (lambda a, p: a.advanceTime(), "needs the days"),
    (lambda a, p: a.advanceTime(1.0, 0, 1), "3 positional arguments"),
    (lambda a, p: a.advanceTime(1.0, days=2), "no argument 'days'"),
    (lambda a, p: a.advanceTime(1.0, dt=2), "dt given twice"),
    (lambda a, p: a.advanceTime(1.0, p, plantIDs=p), "plantIDs given twice"),
    (lambda a, p: a.advanceTime(1.0, "0"), "plantIDs = '0': not an ID or a list of IDs"),
    (lambda a, p: a.advanceTime(1.0, [0.5]), "plantIDs = 0.5: not an ID"),
    (lambda a, p: a.advanceTime(1.0, -1), "plantIDs = -1: not an ID"),
])
def test_advance_time_refuses_a_call_that_reads_two_ways(arch, call, says):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 10)
    before = arch.getPlantString(p)
    with pytest.raises(plantarch.Error, match=says):
        call(arch, p)
    assert arch.getPlantString(p) == before  # nothing grew


def test_step_size_does_not_change_the_plant():
    def grown(steps):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.loadPlantModelFromLibrary("bean")
        p = a.buildPlantInstanceFromLibrary((0, 0, 0), 0)
        for days in steps:
            a.advanceTime(days, plantIDs=p)
        return a.getPlantString(p, 0)

    assert grown([30]) == grown([1] * 30) == grown([10.5, 19.5])


def test_pruning_and_harvest(arch):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 60)
    stem = max(range(arch.getShootCount(p)), key=lambda s: arch.getShootNodeCount(p, s))
    before = arch.getShootNodeCount(p, stem)
    assert before > 4
    shoots = arch.getShootCount(p)
    arch.pruneBranch(p, stem, 2)
    assert arch.getShootNodeCount(p, stem) == 2
    assert arch.getShootCount(p) <= shoots
    arch.removeShootApex(p, stem)
    arch.advanceTime(10.0, p)
    assert arch.getShootNodeCount(p, stem) == 2
    fruit = len(arch.getPlantObjectIDs(p, plantarch.OrganKind.fruit))
    harvested = arch.harvestPlant(p)
    assert harvested >= fruit
    assert arch.getPlantObjectIDs(p, plantarch.OrganKind.fruit) == []
    arch.removePlantLeaves(p)
    assert arch.getPlantLeafCount(p) == 0


def test_phenology_max_age_and_dormancy(arch):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 10)
    arch.setPlantMaximumAge(p, 20)
    arch.advanceTime(30.0, p)
    structure = lambda: arch.getPlantString(p).split(")", 1)[1]  # without the age header
    frozen = structure()
    arch.advanceTime(30.0, p)
    assert structure() == frozen  # stopped developing at 20 days
    assert arch.getPlantPhenologicalThresholds(p).max_age == 20
    q = arch.buildPlantInstanceFromLibrary((1, 0, 0), 0)
    arch.setPlantPhenologicalThresholds(q, time_to_dormancy_break=5, time_to_flower_initiation=-1,
                                        time_to_flower_opening=-1, time_to_fruit_set=-1,
                                        time_to_fruit_maturity=-1, time_to_senescence=-1)
    t = arch.getPlantPhenologicalThresholds(q)
    assert t.time_to_dormancy_break == 5 and t.time_to_flower_opening == -1
    with pytest.raises(plantarch.Error, match="max_age"):
        arch.setPlantMaximumAge(q, -3)
    assert arch.getPhenologyStage(q) in list(plantarch.PhenologyStage.__members__.values())


def test_plant_structure_xml_and_strings_round_trip(arch, tmp):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    path = tmp / "plant.xml"
    arch.writePlantStructureXML(p, str(path))
    other = plantarch.PlantArchitecture(plantarch.Context())
    warnings = []
    (q,) = other.readPlantStructureXML(str(path), warnings=warnings)
    assert warnings == []
    assert other.getPlantString(q) == arch.getPlantString(p)
    s = arch.getPlantString(p, significant_digits=4)
    r = arch.generatePlantFromString(s)
    assert arch.getPlantString(r, significant_digits=4) == s


def test_helios_files_are_written_and_read_back(arch, tmp):
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 45)
    path = tmp / "plant.helios.xml"
    arch.writeHeliosPlantStructureXML(p, str(path))
    text = path.read_text()
    assert "<helios>" in text and "<internode_phyllotactic_angle>" in text
    assert arch.getHeliosPlantStructureXML([p]) == text
    other = plantarch.PlantArchitecture(plantarch.Context())
    other.loadPlantModelFromLibrary("bean")
    warnings = []
    (q,) = other.readPlantStructureXML(str(path), warnings=warnings)
    assert len(warnings) == 1
    assert other.getShootCount(q) == arch.getShootCount(p)
    assert other.getHeliosPlantStructureXML([q]).count("<leaf>") == text.count("<leaf>")


def test_collision_avoidance_and_attraction_points(arch):
    arch.enableSoftCollisionAvoidance(cone_half_angle=60, rays=64)
    arch.enableAttractionPoints([(0, 0, 1.0), (0.1, 0, 1.0)], view_half_angle_deg=70)
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    stats = arch.getCollisionStats()
    assert stats["softCones"] > 0 and stats["attractionQueries"] > 0
    got = arch.getAttractionPoints(p)
    assert [tuple(round(c, 6) for c in v) for v in got] == [(0, 0, 1), (0.1, 0, 1)]
    assert all(isinstance(v, plantarch.vec3) for v in got)
    arch.disableAttractionPoints()
    arch.disableSoftCollisionAvoidance()
    with pytest.raises(plantarch.Error, match="half"):
        arch.enableSoftCollisionAvoidance(cone_half_angle=500)


def test_ply_from_python_is_the_bytes_the_cli_writes(tmp):
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.setSeed(3)
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    plantarch.writePLY(a.getContext(), str(tmp / "py.ply"))
    subprocess.run([cli(), "--seed", "3", "build", "bean", "--age", "30", "-o",
                    str(tmp / "cli.ply")], check=True, capture_output=True)
    assert (tmp / "py.ply").read_bytes() == (tmp / "cli.ply").read_bytes()


def test_ply_colours_and_labels_from_python_match_the_cli(tmp):
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.setSeed(3)
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    plantarch.writePLY(a.getContext(), str(tmp / "py.ply"), ascii=True, color="organ")
    subprocess.run([cli(), "--seed", "3", "build", "bean", "--age", "20", "--ply-color", "organ",
                    "--ply-format", "ascii", "-o", str(tmp / "cli.ply")],
                   check=True, capture_output=True)
    data = (tmp / "py.ply").read_bytes()
    assert data == (tmp / "cli.ply").read_bytes()
    header = data[:data.index(b"end_header")].decode()
    assert "property uchar red" in header and "property int node" in header
    with pytest.raises(plantarch.Error, match="none, organ, plant, material"):
        plantarch.writePLY(a.getContext(), str(tmp / "bad.ply"), color="leafy")
    assert not (tmp / "bad.ply").exists()


def test_with_blocks_as_the_reference_package_writes_them():
    with plantarch.Context() as context:
        with plantarch.PlantArchitecture(context) as arch:
            arch.loadPlantModelFromLibrary("bean")
            plant = arch.buildPlantInstanceFromLibrary((0, 0, 0), 10)
            arch.advanceTime(5.0)
    assert isinstance(context, plantarch.Context) and isinstance(arch, plantarch.PlantArchitecture)
    assert arch.getPlantAge(plant) == 15  # still usable after the block
    with pytest.raises(KeyError):  # the block's exception goes through
        with plantarch.Context():
            raise KeyError("from the block")


def test_collision_stats_hold_every_field_of_the_struct(arch):
    header = (pathlib.Path(__file__).resolve().parents[2] / "include" / "plantarch" /
              "Collision.h").read_text()
    found = re.search(r"struct CollisionStats \{(.*?)\n\};", header, re.S)
    assert found
    body = found.group(1)
    fields = re.findall(r"^\s+(?:std::uint64_t|double|unsigned|float|int)\s+(\w+)\s*=", body, re.M)
    assert len(fields) >= 15
    stats = arch.getCollisionStats()
    assert list(stats) == fields


@pytest.mark.parametrize("write, name, says", [
    (lambda a, f: plantarch.writeOBJ(a.getContext(), f), "x.glb",
     r"'\.glb': writeOBJ writes a Wavefront OBJ mesh \(valid: \.obj\)"),
    (lambda a, f: plantarch.writePLY(a.getContext(), f), "x.obj",
     r"'\.obj': writePLY writes a PLY mesh \(valid: \.ply\)"),
    (lambda a, f: plantarch.writeGLTF(a.getContext(), f), "x.usda",
     r"writeGLTF writes glTF, binary or text \(valid: \.glb, \.gltf\)"),
    (lambda a, f: plantarch.writeUSDA(a.getContext(), f), "x.usd", r"\(valid: \.usda, \.usdz\)"),
    (lambda a, f: plantarch.writePointCloudPLY(a.getContext(), f, points=10), "x.npz",
     r"\(valid: \.ply\)"),
    (lambda a, f: plantarch.writeQSM(a, f), "x.txt", r"writeQSM writes cylinders as CSV"),
    (lambda a, f: plantarch.writePNG(plantarch.render(a, width=8, height=8), f), "x.jpg",
     r"'\.jpg': writePNG writes a PNG picture \(valid: \.png\)"),
    (lambda a, f: a.writePlantStructureXML(0, f), "x.helios.xml",
     r"'\.helios\.xml': writePlantStructureXML writes a plant structure file \(valid: \.xml\)"),
    (lambda a, f: a.writeHeliosPlantStructureXML(0, f), "x.txt",
     r"\(valid: \.xml, \.helios\.xml\)"),
    (lambda a, f: plantarch.writeOBJ(a.getContext(), f), "noextension",
     r"the name has no extension \(valid: \.obj\)"),
])
def test_a_writer_refuses_a_name_of_another_format(arch, tmp, write, name, says):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 5)
    with pytest.raises(plantarch.Error, match=says):
        write(arch, str(tmp / name))
    assert list(tmp.iterdir()) == []  # nothing written


def test_errors_name_what_to_write_instead():
    a = plantarch.PlantArchitecture(plantarch.Context())
    with pytest.raises(AttributeError, match="did you mean 'getPlantHeight'"):
        a.getPlantHieght(0)  # pyright: ignore[reportAttributeAccessIssue]
    with pytest.raises(AttributeError, match="did you mean 'getObjectCount'"):
        a.getContext().getObjectCuont()  # pyright: ignore[reportAttributeAccessIssue]
    assert not hasattr(a, "noSuchThing")
    with pytest.raises(plantarch.Error, match="none defined yet: load a species"):
        a.getCurrentShootParameters("trifoliate")
    a.loadPlantModelFromLibrary("bean")
    with pytest.raises(plantarch.Error, match=r"unknown shoot type \(valid: one of: trifoliate, "
                                              r"unifoliate\)"):
        a.getCurrentShootParameters("trifoliat")
    with pytest.raises(plantarch.Error, match="not an ID"):
        a.getPlantHeight(-1)
    a.buildPlantInstanceFromLibrary((0, 0, 0), 5)
    a.getContext().clear()  # no argument needed
    assert a.getContext().getObjectCount() == 0


def test_state_enum_members_are_the_names_files_and_object_data_hold(arch):
    # The members come from the C++ name tables (plantarch/PlantState.h): in enumerator order,
    # each with its doc, named as plant files write the value and as the "organ" data labels.
    for enum in (plantarch.BudState, plantarch.FloralStage, plantarch.OrganKind,
                 plantarch.PhenologyStage):
        members = list(enum.__members__.items())
        assert [int(v) for _, v in members] == list(range(len(members))), enum
        for name, _ in members:
            assert f"{name} :" in (enum.__doc__ or ""), (enum, name)  # each member's doc
    p = arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    stage = arch.getPhenologyStage(p)
    assert f"<phenology_stage>{stage.name}</phenology_stage>" in arch.getPlantStructureXML([p])
    kinds = 0
    for kind in plantarch.OrganKind.__members__.values():
        for obj in arch.getPlantObjectIDs(p, kind)[:1]:
            assert arch.getContext().getObjectData(obj, "organ") == kind.name
            kinds += 1
    assert kinds >= 3
