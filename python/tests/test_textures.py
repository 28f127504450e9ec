"""Procedural textures from Python: textured glTF, USD (.usda beside its PNGs, .usdz package),
OBJ and pictures, and texture sizes refused with plantarch.Error."""

import math
import struct
import zipfile

import pytest

import plantarch
import usda
from conftest import glb_json




def test_textured_glb_embeds_maps_and_flat_is_the_default(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeGLTF(ctx, str(tmp_path / "flat.glb"), architecture=bean)
    plantarch.writeGLTF(ctx, str(tmp_path / "tex.glb"), architecture=bean,
                        appearance="textured", texture_size=64)
    assert "images" not in glb_json(tmp_path / "flat.glb")
    doc = glb_json(tmp_path / "tex.glb")
    assert doc["images"] and all(i["mimeType"] == "image/png" for i in doc["images"])
    leaf = [m for m in doc["materials"] if m.get("name") == "leaf"
            and "baseColorTexture" in m["pbrMetallicRoughness"]]
    assert leaf and all(m["alphaMode"] == "MASK" and "normalTexture" in m for m in leaf)


def test_usda_and_usdz(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeUSDA(ctx, str(tmp_path / "bean.usda"), appearance="textured", texture_size=32)
    layer, prims = usda.read(tmp_path / "bean.usda")  # the text parses
    (root,) = prims
    looks = [c for c in root.children if c.name == "Looks"]
    assert looks and looks[0].children
    pngs = sorted(p.name for p in tmp_path.glob("bean_*.png"))
    assert "bean_leaf_0_basecolor.png" in pngs and "bean_bark_0_normal.png" in pngs
    plantarch.writeUSDA(ctx, str(tmp_path / "bean.usdz"), appearance="textured", texture_size=32)
    with zipfile.ZipFile(tmp_path / "bean.usdz") as z:
        assert z.testzip() is None
        infos = z.infolist()
        assert infos[0].filename == "bean.usda"
        assert all(i.compress_type == zipfile.ZIP_STORED for i in infos)
        raw = (tmp_path / "bean.usdz").read_bytes()
        for i in infos:
            name_length, extra_length = struct.unpack_from("<HH", raw, i.header_offset + 26)
            assert (i.header_offset + 30 + name_length + extra_length) % 64 == 0, i.filename
        assert "leaf_0_basecolor.png" in z.namelist()
        assert b"@./leaf_0_basecolor.png@" in z.read("bean.usda")


def test_obj_maps_and_textured_render(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeOBJ(ctx, str(tmp_path / "bean.obj"), appearance="textured", texture_size=32)
    mtl = (tmp_path / "bean.mtl").read_text()
    assert "map_Kd bean_leaf_0_basecolor.png" in mtl and "map_d bean_leaf_0_alpha.png" in mtl
    flat = plantarch.render(ctx, width=96, height=72)
    textured = plantarch.render(ctx, width=96, height=72, appearance="textured", texture_size=64)
    assert flat.shape == textured.shape and (flat != textured).any()


@pytest.mark.parametrize("size", [0, -8, 100, 8, 8192, 2**40, 2**70, math.nan, 64.0, "64", True])
def test_bad_texture_sizes_are_plantarch_errors(bean, tmp_path, size):
    with pytest.raises(plantarch.Error, match="texture"):
        plantarch.writeGLTF(bean.getContext(), str(tmp_path / "x.glb"), appearance="textured",
                            texture_size=size)
    assert not list(tmp_path.iterdir())


def test_unknown_appearance_is_a_plantarch_error(bean, tmp_path):
    with pytest.raises(plantarch.Error, match="flat, textured"):
        plantarch.writeUSDA(bean.getContext(), str(tmp_path / "x.usda"), appearance="shiny")
