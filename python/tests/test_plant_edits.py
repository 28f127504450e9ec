"""Plant IDs unique in a Context whichever PlantArchitecture made the plant, and the model
specification's calls for copies, water sprouts, seasons, ground clipping and organ lists."""

from typing import Any

import pytest

import plantarch


def bean(age):
    """A PlantArchitecture with one library bean of that age."""
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantInstanceFromLibrary((0, 0, 0), age)
    return a


def test_two_architectures_on_one_context_never_share_a_plant_id():
    context = plantarch.Context()
    beans = plantarch.PlantArchitecture(context)
    maize = plantarch.PlantArchitecture(context)
    beans.loadPlantModelFromLibrary("bean")
    maize.loadPlantModelFromLibrary("maize")
    bean = beans.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    corn = maize.buildPlantInstanceFromLibrary((1, 0, 0), 20)
    assert bean != corn
    labels = {context.getObjectData(o, "plantID") for o in context.getAllObjectIDs()}
    assert labels == {bean, corn}
    beans.deletePlantInstance(bean)
    again = beans.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    assert again not in (bean, corn)


def test_duplicate_move_and_name():
    context = plantarch.Context()
    a = plantarch.PlantArchitecture(context)
    a.loadPlantModelFromLibrary("bean")
    plant = a.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    copy = a.duplicatePlantInstance(plant, (1, 0, 0), plantarch.AxisRotation(0, 90, 0), 30)
    assert a.getPlantName(copy) == "bean"
    assert a.getPlantLeafArea(copy) == pytest.approx(a.getPlantLeafArea(plant), rel=1e-5)
    assert a.sumPlantLeafArea([plant, copy]) == pytest.approx(
        2 * a.getPlantLeafArea(plant), rel=1e-5)
    a.setPlantBasePosition(copy, (2, 0, 0))
    assert tuple(a.getPlantBasePosition(copy)) == (2, 0, 0)
    with pytest.raises(plantarch.Error, match="age"):
        a.duplicatePlantInstance(plant, (0, 0, 0), age=-1)


def test_organ_lists_seasons_clipping_and_sprouts():
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    plant = a.buildPlantInstanceFromLibrary((0, 0, 0), 45)
    assert a.getPlantLeafObjectIDs(plant) == a.getPlantObjectIDs(plant, plantarch.OrganKind.leaf)
    assert a.getPlantInternodeObjectIDs(plant)
    flowers = a.getPlantFlowerObjectIDs(plant)
    assert sorted(flowers) == sorted(
        a.getPlantObjectIDs(plant, plantarch.OrganKind.flower_closed)
        + a.getPlantObjectIDs(plant, plantarch.OrganKind.flower_open))

    a.setOrganGeometry(plantarch.OrganKind.internode, False)
    assert a.getPlantInternodeObjectIDs(plant) == []
    assert a.getOrganGeometry(plantarch.OrganKind.internode) is False

    a.enableEpicormicChildShoots(plant, "trifoliate", 5.0)
    shoots = a.getShootCount(plant)
    a.advanceTime(10, plantIDs=plant)
    assert a.getShootCount(plant) > shoots

    a.enableGroundClipping(0.1)
    assert a.getGroundClipping() == pytest.approx(0.1)
    a.disableGroundClipping()
    assert a.getGroundClipping() is None

    a.makePlantDormant(plant)
    assert a.isPlantDormant(plant)
    a.breakPlantDormancy(plant)
    assert not a.isPlantDormant(plant)


def test_out_of_range_plant_ids_are_plantarch_errors():
    a = plantarch.PlantArchitecture(plantarch.Context())
    for bad in (-1, 2**40):
        with pytest.raises(plantarch.Error):
            a.getPlantHeight(bad)


def test_a_shoot_spec_builds_the_same_shoots_as_the_keyword_calls():
    def build(with_spec):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.loadPlantModelFromLibrary("bean")
        plant = a.addPlantInstance((0, 0, 0), 0)
        kwargs: dict[str, Any] = dict(current_node_number=4, internode_radius=0.002,
                      internode_length_max=0.03, shoot_type_label="trifoliate")
        if with_spec:
            spec = plantarch.ShootSpec(**kwargs)
            a.addBaseStemShoot(plant, spec)
            spec.phytomers = 2
            a.addChildShoot(plant, 0, 1, spec)
            a.addEpicormicShoot(plant, 0, 0.5, spec)
        else:
            a.addBaseStemShoot(plant, **kwargs)
            kwargs["current_node_number"] = 2
            a.addChildShoot(plant, 0, 1, **kwargs)
            a.addEpicormicShoot(plant, 0, 0.5, **kwargs)
        return a.getPlantString(plant)

    assert build(True) == build(False)
    spec = plantarch.ShootSpec(shoot_type_label="x", internode_radius=0.004)
    assert spec.size.internodeRadius == pytest.approx(0.004)
    with pytest.raises(TypeError):
        plantarch.ShootSpec("x")  # pyright: ignore  (keywords only)


def test_attraction_weight_means_what_the_reference_means():
    def grown(weight=None):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.loadPlantModelFromLibrary("bean")
        if weight is not None:
            wire = [(0.08, 0.0, 0.02 * k) for k in range(1, 30)]
            a.enableAttractionPoints(wire, look_ahead_distance=0.5, attraction_weight=weight)
        plant = a.buildPlantInstanceFromLibrary((0, 0, 0), 25)
        return a.getPlantString(plant)

    free = grown()
    assert grown(0.0) == free  # no attraction at all
    assert grown(1.0) != free
    with pytest.raises(plantarch.Error, match="attraction_weight"):
        grown(1.5)


def test_a_growth_recorder_keeps_frames_between_steps_of_ones_own(tmp_path):
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    plant = a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    recorder = plantarch.GrowthRecorder()
    recorder.record(a)  # at the plant's age
    a.removePlantLeaves(plant)
    recorder.record(a, 20.5)
    a.advanceTime(5)
    recorder.record(a)
    assert recorder.frameCount() == 3
    assert recorder.days() == [20, 20.5, 25]
    with pytest.raises(plantarch.Error, match="after the last frame"):
        recorder.record(a, 25)
    recorder.write([str(tmp_path / "growth.glb"), str(tmp_path / "growth.usda")], frame_rate=2)
    assert (tmp_path / "growth.glb").read_bytes()[:4] == b"glTF"
    assert '        double[] days = [20, 20.5, 25]\n' in (tmp_path / "growth.usda").read_text()
    with pytest.raises(plantarch.Error, match="animation"):
        recorder.write(str(tmp_path / "growth.obj"))
    assert not (tmp_path / "growth.obj").exists()
    recorder.clear()
    assert recorder.frameCount() == 0


def test_a_ply_written_reads_back_as_its_objects(tmp_path):
    a = bean(20)
    context = a.getContext()
    plantarch.writePLY(context, str(tmp_path / "bean.ply"))
    back = plantarch.Context()
    ids = plantarch.readPLY(back, str(tmp_path / "bean.ply"))
    assert len(ids) == len(context.getAllObjectIDs())
    organs = sorted(str(context.getObjectData(o, "organ")) for o in context.getAllObjectIDs())
    assert sorted(str(back.getObjectData(o, "organ")) for o in ids) == organs
    wall = plantarch.readObstacleMesh(back, str(tmp_path / "bean.ply"))
    assert {back.getObjectData(o, "organ") for o in wall} == {"obstacle"}
    (tmp_path / "bad.ply").write_text("ply\nformat ascii 1.0\nelement vertex 1\nend_header\n")
    with pytest.raises(plantarch.Error, match="bad.ply"):
        plantarch.readPLY(back, str(tmp_path / "bad.ply"))


def test_a_glb_written_reads_back_as_its_objects(tmp_path):
    a = bean(20)
    context = a.getContext()
    plantarch.writeGLTF(context, str(tmp_path / "bean.glb"), architecture=a)
    back = plantarch.Context()
    ids = plantarch.readGLTF(back, str(tmp_path / "bean.glb"))
    assert len(ids) == len(context.getAllObjectIDs())
    assert back.getTriangleCount() == context.getTriangleCount()
    (tmp_path / "bad.glb").write_bytes(b"glTF\x01\x00\x00\x00")
    with pytest.raises(plantarch.Error, match="bad.glb"):
        plantarch.readGLTF(back, str(tmp_path / "bad.glb"))


def test_obj_options_as_a_keyword_class_write_what_the_keywords_write(tmp_path):
    a = bean(15)
    context = a.getContext()
    plantarch.writeOBJ(context, str(tmp_path / "k.obj"), normals=False, materials=False)
    options = plantarch.ObjOptions(normals=False, materials=False)
    assert options.uvs and not options.normals
    plantarch.writeOBJ(context, str(tmp_path / "o.obj"), options)
    assert (tmp_path / "k.obj").read_bytes() == (tmp_path / "o.obj").read_bytes()
    assert not (tmp_path / "o.mtl").exists()
