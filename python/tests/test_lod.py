"""Levels of detail (MSFT_lod) and EXT_meshopt_compression from Python's writeGLTF, and a mesh
detail of 0.1 drawing a tenth of the triangles or fewer."""

import pytest

import plantarch
from conftest import glb_json



def test_levels_and_meshopt(arch, tmp_path):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 40)
    plain, lod, packed = tmp_path / "plain.glb", tmp_path / "lod.glb", tmp_path / "packed.glb"
    plantarch.writeGLTF(arch.getContext(), str(plain), architecture=arch)
    plantarch.writeGLTF(arch.getContext(), str(lod), architecture=arch, lod="reduced,cards")
    plantarch.writeGLTF(arch.getContext(), str(packed), architecture=arch, meshopt=True)
    doc = glb_json(lod)
    assert "MSFT_lod" in doc["extensionsUsed"]
    plant = next(n for n in doc["nodes"] if "extensions" in n)
    assert len(plant["extensions"]["MSFT_lod"]["ids"]) == 2
    assert len(plant["extras"]["MSFT_screencoverage"]) == 3
    assert glb_json(packed)["extensionsRequired"] == ["EXT_meshopt_compression"]
    assert packed.stat().st_size * 2 < plain.stat().st_size
    for bad in ("reduced:0", "bogus", "cards@2"):
        with pytest.raises(plantarch.Error, match="lod"):
            plantarch.writeGLTF(arch.getContext(), str(tmp_path / "bad.glb"), lod=bad)
    assert not (tmp_path / "bad.glb").exists()


def test_lowest_mesh_detail(arch):
    arch.buildPlantInstanceFromLibrary((0, 0, 0), 40)
    full = arch.getContext().triangleCount()
    arch.setMeshDetail(0.1)
    assert arch.getContext().triangleCount() * 10 <= full
