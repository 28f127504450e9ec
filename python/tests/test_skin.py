"""Skinned plants from Python: writeGLTF and writeUSDA with skin=True give a glTF skin (a joint
per internode, weights on every vertex) and UsdSkel prims; skin without the plants is refused."""


import pytest

import plantarch
from conftest import glb_json




def test_skinned_glb_has_a_joint_per_internode(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeGLTF(ctx, str(tmp_path / "plain.glb"), architecture=bean)
    plantarch.writeGLTF(ctx, str(tmp_path / "skin.glb"), architecture=bean, skin=True)
    assert "skins" not in glb_json(tmp_path / "plain.glb")
    doc = glb_json(tmp_path / "skin.glb")
    (skin,) = doc["skins"]
    plant = bean.getAllPlantIDs()[0]
    internodes = sum(bean.getShootNodeCount(plant, s) for s in range(bean.getShootCount(plant)))
    assert len(skin["joints"]) == internodes + 1  # and the root
    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            assert {"JOINTS_0", "WEIGHTS_0"} <= primitive["attributes"].keys()


def test_skinned_usda_is_a_skelroot(bean, tmp_path):
    path = tmp_path / "skin.usda"
    plantarch.writeUSDA(bean.getContext(), str(path), architecture=bean, skin=True)
    text = path.read_text()
    assert 'def SkelRoot "bean_' in text and 'def Skeleton "skeleton"' in text
    assert "primvars:skel:jointWeights" in text


def test_skin_without_the_plants_is_refused(bean, tmp_path):
    with pytest.raises(plantarch.Error, match="skin"):
        plantarch.writeGLTF(bean.getContext(), str(tmp_path / "x.glb"), skin=True)
    assert not (tmp_path / "x.glb").exists()


def test_wind_adds_a_looping_animation(bean, tmp_path):
    plantarch.writeGLTF(bean.getContext(), str(tmp_path / "wind.glb"), architecture=bean, wind=10.0)
    doc = glb_json(tmp_path / "wind.glb")
    assert doc["skins"] and [a["name"] for a in doc["animations"]] == ["wind"]
    with pytest.raises(plantarch.Error, match="wind"):
        plantarch.writeGLTF(bean.getContext(), str(tmp_path / "bad.glb"), architecture=bean,
                            wind=200.0)
    assert not (tmp_path / "bad.glb").exists()
